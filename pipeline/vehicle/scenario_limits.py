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

__all__ = ["LIMITS", "METHODS", "uses_spectral", "MAX_VARIANTS", "MAX_SPECTRAL_VARIANTS", "MAX_SAMPLES", "MIN_VERDICT_DURATION_S",
           "BYTES_PER_SAMPLE", "SECONDS_PER_SAMPLE", "SECONDS_PER_SPECTRAL_ROW", "scenario_problems", "override_problems", "work_estimate", "work_problems"]

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
#: Most variants one scenario may sweep in the time domain (``tyrelab ride --max-variants`` lifts it).
MAX_VARIANTS = 400
#: Most variants of a sweep computed in the frequency domain (``--method auto`` or ``spectral``;
#: ``--max-variants`` lifts it): 100 x 100 pressures and a swept key of two values, about 4 min.
MAX_SPECTRAL_VARIANTS = 20_000
#: Time of one spectral speed row (variant x speed), s: the 10 x 10 x 8 grid of bench/bench_ride.py
#: took about 1.2 ms a row (tyres, assembly, expectation on 4,000 frequencies, modes; issue 36).
SECONDS_PER_SPECTRAL_ROW = 1.5e-3
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


#: How a ride's rows are computed (``[simulation] method``; :mod:`tyrelab.vehicle.spectral_ride`).
METHODS = ("auto", "time", "spectral")


def uses_spectral(scenario, method: str, n_variants: int) -> bool:
    """Whether ``method`` computes spectral rows for a sweep of ``n_variants`` of ``scenario``:
    ``spectral``; ``auto`` for more than one variant on an ISO 8608 surface (a profile or any other
    deterministic road is simulated).

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> s = NS(surface=NS(kind="iso8608"))
    >>> uses_spectral(s, "auto", 1), uses_spectral(s, "auto", 2), uses_spectral(s, "time", 2)
    (False, True, False)
    """
    _validate.choice("method", method, METHODS)
    if method == "auto":
        return n_variants > 1 and scenario.surface.kind == "iso8608"
    return method == "spectral"


def work_estimate(scenario, n_variants: int, speeds_km_h=None, method: str = "time") -> dict:
    """Samples, memory and time of ``n_variants`` variants at every speed (an estimate) under
    ``method`` (:mod:`tyrelab.vehicle.spectral_ride`): ``time`` simulates every variant; spectral
    rows (``spectral``, or ``auto`` for a sweep on an ISO 8608 surface) simulate nothing
    (``spectral_rows``: variant x speed rows, :data:`SECONDS_PER_SPECTRAL_ROW` each), ``auto``
    the nominal variant besides (the speeds that may lift a tyre are bounded when known, by
    ``max_samples``).

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
    spectral = uses_spectral(scenario, method, n_variants)
    speeds = list(speeds_km_h or scenario.exposure.speeds_km_h)
    span_m = scenario.surface.length_m + scenario.surface.lead_in_m + \
        scenario.tractor.front_distance_m + scenario.tractor.rear_distance_m
    samples = 0.0
    for v in speeds:
        seconds = span_m / (v / 3.6)
        if scenario.simulation.duration_s is not None:
            seconds = min(seconds, scenario.simulation.duration_s + span_m - scenario.surface.length_m)
        samples += seconds * 1000.0
    simulated = 0 if method == "spectral" and spectral else 1 if spectral else n_variants
    rows = n_variants * len(speeds) if spectral else 0
    total = samples * simulated
    return {"variants": n_variants, "speeds": len(speeds), "samples": int(round(total)),
            "largest_run_samples": int(round(samples)) if simulated else 0,
            "memory_GB": samples * BYTES_PER_SAMPLE / 1e9 if simulated else 0.0,
            "seconds": total * SECONDS_PER_SAMPLE + rows * SECONDS_PER_SPECTRAL_ROW,
            "spectral_rows": rows, "simulated_variants": simulated}


def work_problems(scenario, n_variants: int, speeds_km_h=None, *, max_variants: int | None = None,
                  max_samples: int = MAX_SAMPLES, method: str = "time") -> list[str]:
    """Refusals, each with the estimate and the option that lifts the bound (empty: go ahead).

    ``max_variants`` default: :data:`MAX_SPECTRAL_VARIANTS` where ``method`` computes spectral rows
    (:func:`work_estimate`), else :data:`MAX_VARIANTS`.

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> s = NS(surface=NS(length_m=400.0, lead_in_m=5.0, kind="iso8608"),
    ...        tractor=NS(front_distance_m=1.5, rear_distance_m=1.0),
    ...        exposure=NS(speeds_km_h=tuple(range(4, 20, 2))), simulation=NS(duration_s=None))
    >>> work_problems(s, 100 * 100, method="spectral"), work_problems(s, 100 * 100, method="auto")
    ([], [])
    >>> print(work_problems(s, 100 * 100, method="time")[0])
    10000 variants (pressure pairs x swept values) is more than 400 in the time domain (about 33539 s of simulation); --max-variants N lifts the bound, --method auto or spectral computes them in the frequency domain (about 120 s)
    """
    e = work_estimate(scenario, n_variants, speeds_km_h, method)
    problems = []
    spectral = e["spectral_rows"] > 0
    limit = max_variants or (MAX_SPECTRAL_VARIANTS if spectral else MAX_VARIANTS)
    if n_variants > limit:
        if spectral:
            problems.append(f"{n_variants} variants (pressure pairs x swept values) is more than {limit} (about {e['seconds']:.0f} s in the frequency "
                            "domain); --max-variants N lifts the bound")
        else:
            rows = n_variants * e["speeds"] * SECONDS_PER_SPECTRAL_ROW
            problems.append(f"{n_variants} variants (pressure pairs x swept values) is more than {limit} in the time domain (about {e['seconds']:.0f} s "
                            "of simulation); --max-variants N lifts the bound"
                            + (f", --method auto or spectral computes them in the frequency domain (about {rows:.0f} s)"
                               if scenario.surface.kind == "iso8608" else ""))
    if e["samples"] > max_samples:
        problems.append(f"{e['simulated_variants']} variant(s) x {e['speeds']} speed(s) simulate {e['samples']:,} samples "
                        f"(about {e['memory_GB']:.1f} GB for the longest run and {e['seconds']:.0f} s), more than "
                        f"{max_samples:,}; --max-samples N lifts the bound (or raise the speed, shorten the track)")
    return problems
