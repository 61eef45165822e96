"""What a ride scenario may ask of the model: each number's range, and the work a sweep may create.

The schema (``schemas/scenario.json``) checks types and signs; the model needs more. A
length of 1 mm, a step of 1 km or a speed of 1e300 km/h divide by zero or leave no sample,
a track of 1e9 m or 0.001 km/h asks for terabytes, a mass of 1e-300 kg or a pressure of
1e6 bar gives infinities in the state matrices. :data:`LIMITS` is the range of every
number the model is built for (documented choices, generous around agricultural
tractors: the thesis' tractors weigh 2.5-8 t, run 2-30 km/h on tracks of 100-400 m), and
:func:`scenario_problems` names each key outside it with its bound, all at once.

The work is bounded before it starts: :func:`work_estimate` counts the simulated samples
(1 kHz, :data:`tyrelab.vehicle.ride.DT_S`) of every speed of every pressure pair, and
:func:`work_problems` refuses more than :data:`MAX_VARIANTS` pairs or
:data:`MAX_SAMPLES` samples with the estimate (memory and time, from the issue-25
measurement: 0.05 km/h on 100 m, 7.2 million samples, took 2.2 GB and 18 s, i.e. about
300 bytes and 2.5 µs per sample) and the option that lifts the bound.

Examples
--------
>>> LIMITS["exposure.speeds_km_h"]
(0.5, 80.0, 'km/h')
"""

from __future__ import annotations

import math

import numpy as np

from .. import _validate

__all__ = ["LIMITS", "MAX_VARIANTS", "MAX_SAMPLES", "MIN_VERDICT_DURATION_S", "BYTES_PER_SAMPLE",
           "SECONDS_PER_SAMPLE", "scenario_problems", "override_problems", "work_estimate", "work_problems"]

#: key -> (lowest, highest, unit) of every number of a scenario the model is built for.
LIMITS: dict[str, tuple[float, float, str]] = {
    "tractor.mass_kg": (200.0, 50_000.0, "kg"),
    "tractor.pitch_inertia_kg_m2": (10.0, 500_000.0, "kg m²"),
    "tractor.front_distance_m": (0.05, 10.0, "m"),
    "tractor.rear_distance_m": (0.05, 10.0, "m"),
    "tractor.cg_height_m": (0.0, 5.0, "m"),
    "tractor.longitudinal_stiffness_kN_per_m": (1.0, 100_000.0, "kN/m"),
    "tractor.longitudinal_damping_kN_s_per_m": (0.01, 1_000.0, "kN s/m"),
    "seat.ahead_of_cg_m": (-10.0, 10.0, "m"),
    "seat.height_above_cg_m": (-10.0, 10.0, "m"),
    "seat.natural_frequency_Hz": (0.3, 30.0, "Hz"),
    "seat.damping_ratio": (0.01, 5.0, ""),
    "pressure_bar": (0.1, 10.0, "bar"),
    "stiffness_kN_per_m": (10.0, 100_000.0, "kN/m"),
    "damping_kN_s_per_m": (0.01, 1_000.0, "kN s/m"),
    "age_years": (0.0, 60.0, "years"),
    "lateral_stiffness_kN_per_m": (1.0, 100_000.0, "kN/m"),
    "lateral_damping_kN_s_per_m": (0.01, 1_000.0, "kN s/m"),
    "tractor.yaw_inertia_kg_m2": (10.0, 500_000.0, "kg m²"),
    "radius_m": (0.1, 2.0, "m"),
    "footprint_m": (0.01, 2.0, "m"),
    "surface.length_m": (10.0, 100_000.0, "m"),
    "surface.dx_m": (0.001, 1.0, "m"),
    "surface.lead_in_m": (0.0, 1_000.0, "m"),
    "surface.spectrum_g0_m3": (1e-9, 1.0, "m³"),
    "surface.start_m": (0.0, 100_000.0, "m"),
    "surface.lateral_offset_m": (-50.0, 50.0, "m"),
    "surface.spectrum_waviness": (0.5, 5.0, ""),
    "exposure.speeds_km_h": (0.5, 80.0, "km/h"),
    "exposure.hours_per_day": (0.01, 24.0, "h"),
    "simulation.duration_s": (1.0, 3_600.0, "s"),
    "profile.height_m": (-2.0, 2.0, "m"),
    "profile.gap_m": (0.0, 10.0, "m"),
}
#: Most pressure pairs one scenario may sweep (``tyrelab ride --max-variants`` lifts it).
MAX_VARIANTS = 400
#: Most samples (1 kHz) one command may simulate over all speeds and pairs (``--max-samples``).
MAX_SAMPLES = 10_000_000
#: Memory and time per simulated sample (measured: 2.2 GB and 18 s for 7.2 million samples).
BYTES_PER_SAMPLE = 300.0
SECONDS_PER_SAMPLE = 2.5e-6
#: Shortest seat record that gets a verdict against the EU limits, s: four periods of 0.4 Hz, the
#: lower band limit of the ISO 2631-1 weightings (a documented choice; shorter records get their
#: exposure numbers, a warning and `verdict` "no verdict: ...").
MIN_VERDICT_DURATION_S = 10.0


def _out(key: str, value: float) -> str | None:
    low, high, unit = LIMITS[key.rsplit(".", 1)[-1] if key.startswith("tyres.") or key.startswith("sweep.") else key]
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or not math.isfinite(value):
        return f"{key}: {value!r} is not a finite number"
    if not low <= value <= high:
        u = f" {unit}" if unit else ""
        return f"{key}: {value:g}{u} is outside {low:g} to {high:g}{u}, what the ride model is built for"
    return None


def scenario_problems(scenario) -> list[str]:
    """Every number of ``scenario`` outside :data:`LIMITS`, one line each naming key and bound.

    Also: a step ``dx_m`` longer than a sixteenth of the track, and a profile CSV whose heights
    or gaps between points are out of range.
    """
    s = scenario
    checks: list[tuple[str, object]] = []
    for name in ("mass_kg", "pitch_inertia_kg_m2", "front_distance_m", "rear_distance_m", "cg_height_m",
                 "longitudinal_stiffness_kN_per_m", "longitudinal_damping_kN_s_per_m"):
        checks.append((f"tractor.{name}", getattr(s.tractor, name)))
    if s.tractor.yaw_inertia_kg_m2 is not None:
        checks.append(("tractor.yaw_inertia_kg_m2", s.tractor.yaw_inertia_kg_m2))
    for name in ("ahead_of_cg_m", "height_above_cg_m", "natural_frequency_Hz", "damping_ratio"):
        if getattr(s.seat, name) is not None:
            checks.append((f"seat.{name}", getattr(s.seat, name)))
    for axle, t in (("front", s.front), ("rear", s.rear)):
        checks.append((f"tyres.{axle}.pressure_bar", t.pressure_bar))
        checks.append((f"tyres.{axle}.age_years", t.age_years))
        for name in ("stiffness_kN_per_m", "damping_kN_s_per_m", "radius_m", "footprint_m",
                     "lateral_stiffness_kN_per_m", "lateral_damping_kN_s_per_m"):
            v = getattr(t, name)
            for x in (v if isinstance(v, tuple) else () if v is None else (v,)):
                checks.append((f"tyres.{axle}.{name}", x))
    surf = s.surface
    for name in ("length_m", "dx_m", "lead_in_m", "spectrum_waviness"):
        checks.append((f"surface.{name}", getattr(surf, name)))
    if surf.spectrum_g0_m3 is not None:
        checks.append(("surface.spectrum_g0_m3", surf.spectrum_g0_m3))
    if surf.kind == "crg":  # issue 33: where on the road the tractor drives
        checks += [("surface.start_m", surf.start_m), ("surface.lateral_offset_m", surf.lateral_offset_m)]
    checks += [("exposure.speeds_km_h", v) for v in s.exposure.speeds_km_h]
    checks.append(("exposure.hours_per_day", s.exposure.hours_per_day))
    if s.simulation.duration_s is not None:
        checks.append(("simulation.duration_s", s.simulation.duration_s))
    checks += [("sweep.front_pressures_bar", v) for v in s.sweep.front_pressures_bar]
    checks += [("sweep.rear_pressures_bar", v) for v in s.sweep.rear_pressures_bar]
    problems = []
    for key, value in checks:
        line = _out(key.replace("_pressures_bar", ".pressure_bar") if key.startswith("sweep.") else key, value)
        if line:
            problems.append(line.replace("sweep.front.pressure_bar", "sweep.front_pressures_bar")
                            .replace("sweep.rear.pressure_bar", "sweep.rear_pressures_bar"))
    if not problems and surf.dx_m > surf.length_m / 16:
        problems.append(f"surface.dx_m: {surf.dx_m:g} m is longer than surface.length_m / 16 "
                        f"({surf.length_m / 16:g} m): the track needs at least 16 points")
    if surf.kind == "profile" and surf.profile_data is not None:
        problems += _profile_problems(*surf.profile_data)
    return problems


def _profile_problems(x, left, right) -> list[str]:
    """What the model cannot take of a profile's data (distance, left and right heights, m)."""
    problems = []
    if not np.isfinite(x).all():
        problems.append("surface.profile: distance_m has values that are not finite")
    else:
        gap = float(np.max(np.diff(x))) if len(x) > 1 else 0.0
        low, high, _ = LIMITS["profile.gap_m"]
        if gap > high:
            problems.append(f"surface.profile: a gap of {gap:g} m between points is above {high:g} m")
        if x[-1] - x[0] > LIMITS["surface.length_m"][1]:
            problems.append(f"surface.profile: {x[-1] - x[0]:g} m long, above {LIMITS['surface.length_m'][1]:g} m")
    low, high, _ = LIMITS["profile.height_m"]
    h = np.concatenate([left, right])
    if not (np.isfinite(h).all() and h.min() >= low and h.max() <= high):
        problems.append(f"surface.profile: heights must be finite and within {low:g} to {high:g} m "
                        f"(found {np.nanmin(h):g} to {np.nanmax(h):g} m)")
    return problems


def override_problems(speeds_km_h=None, front_pressures_bar=None, rear_pressures_bar=None) -> list[str]:
    """Speeds and pressures given beside a scenario (``tyrelab ride --speeds`` ...) outside :data:`LIMITS`.

    Examples
    --------
    >>> override_problems(speeds_km_h=[8, 1e300])
    ['speeds_km_h: 1e+300 km/h is outside 0.5 to 80 km/h, what the ride model is built for']
    """
    problems = []
    for key, limit, values in (("speeds_km_h", "exposure.speeds_km_h", speeds_km_h),
                               ("front_pressures_bar", "pressure_bar", front_pressures_bar),
                               ("rear_pressures_bar", "pressure_bar", rear_pressures_bar)):
        for v in values or ():
            line = _out(limit, v)
            if line:
                problems.append(key + line[len(limit):])
    return problems


def work_estimate(scenario, n_variants: int, speeds_km_h=None) -> dict:
    """Samples, memory and time of ``n_variants`` pressure pairs at every speed (an estimate).

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> s = NS(surface=NS(length_m=100.0, lead_in_m=5.0), tractor=NS(front_distance_m=1.5, rear_distance_m=1.0),
    ...        exposure=NS(speeds_km_h=(0.05,)), simulation=NS(duration_s=None))
    >>> e = work_estimate(s, 1)
    >>> e["samples"], round(e["memory_GB"], 1), round(e["seconds"])
    (7740000, 2.3, 19)
    """
    _validate.positive_int("n_variants", n_variants)
    speeds = list(speeds_km_h or scenario.exposure.speeds_km_h)
    span_m = scenario.surface.length_m + scenario.surface.lead_in_m + \
        scenario.tractor.front_distance_m + scenario.tractor.rear_distance_m
    samples = 0.0
    for v in speeds:
        seconds = span_m / (v / 3.6)
        if scenario.simulation.duration_s is not None:
            seconds = min(seconds, scenario.simulation.duration_s + span_m - scenario.surface.length_m)
        samples += seconds * 1000.0
    total = samples * n_variants
    return {"variants": n_variants, "speeds": len(speeds), "samples": int(round(total)),
            "largest_run_samples": int(round(samples)),
            "memory_GB": samples * BYTES_PER_SAMPLE / 1e9, "seconds": total * SECONDS_PER_SAMPLE}


def work_problems(scenario, n_variants: int, speeds_km_h=None, *, max_variants: int = MAX_VARIANTS,
                  max_samples: int = MAX_SAMPLES) -> list[str]:
    """Refusals, each with the estimate and the option that lifts the bound (empty: go ahead)."""
    e = work_estimate(scenario, n_variants, speeds_km_h)
    problems = []
    if n_variants > max_variants:
        problems.append(f"{n_variants} pressure pairs is more than {max_variants} (about {e['seconds']:.0f} s of "
                        "simulation); --max-variants N lifts the bound")
    if e["samples"] > max_samples:
        problems.append(f"{e['variants']} pair(s) x {e['speeds']} speed(s) simulate {e['samples']:,} samples "
                        f"(about {e['memory_GB']:.1f} GB for the longest run and {e['seconds']:.0f} s), more than "
                        f"{max_samples:,}; --max-samples N lifts the bound (or raise the speed, shorten the track)")
    return problems
