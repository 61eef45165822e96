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

import dataclasses
import math

import numpy as np

from ..terrain.profiles import ROAD_HEIGHT_BOUNDS_M
from ..units import km_h_to_m_s
from ... import _validate
from ..comfort.daily_exposure import MAX_HOURS_PER_DAY, MIN_HOURS_PER_DAY, MIN_RECORD_S

__all__ = ["LIMITS", "RIDE_METHODS", "uses_spectral", "MAX_VARIANTS", "MAX_SPECTRAL_VARIANTS", "MAX_SAMPLES", "MIN_VERDICT_DURATION_S",
           "BYTES_PER_SAMPLE", "SECONDS_PER_SAMPLE", "SECONDS_PER_SPECTRAL_ROW", "SECONDS_PER_SPECTRAL_VARIANT", "SECONDS_PER_SPECTRAL_ROW_3D",
           "SECONDS_PER_SPECTRAL_VARIANT_3D", "SECONDS_PER_SPECTRAL_FIGURE_ROW", "MAX_SPECTRAL_SECONDS", "MAX_TRACK_POINTS", "BOUND_CEILINGS", "scenario_problems",
           "profile_problems", "override_problems", "track_length_m", "long_integer_problems", "work_estimate", "work_problems",
           "bound_argument"]

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
    "lateral_series_damping_kN_s_per_m_km_h": (1.0, 10_000.0, "kN s/m km/h"),
    "tractor.longitudinal_series_damping_kN_s_per_m_km_h": (1.0, 10_000.0, "kN s/m km/h"),
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
    "exposure.hours_per_day": (MIN_HOURS_PER_DAY, MAX_HOURS_PER_DAY, "h"),  # a task's hours (comfort/daily_exposure.py)
    "exposure.working_speed_km_h": (0.5, 80.0, "km/h"),  # one of the speeds (checked when parsed)
    "simulation.duration_s": (1.0, 3_600.0, "s"),
    "profile.height_m": (*ROAD_HEIGHT_BOUNDS_M, "m"),  # one home: every road's heights (terrain.profiles)
    "profile.gap_m": (0.0, 10.0, "m"),
    # the 3-D model and the tractor's parts (issue 23; bounds issue 37): roll inertias as the pitch
    # inertias' scale, tracks and offsets within a tractor's width, parts' masses below the
    # heaviest tractor's, stiffnesses as the tyres'
    "tractor.roll_inertia_kg_m2": (10.0, 500_000.0, "kg m²"),
    "tractor.front_track_m": (0.5, 5.0, "m"),
    "tractor.rear_track_m": (0.5, 5.0, "m"),
    "seat.left_of_cg_m": (-2.5, 2.5, "m"),
    "axle.roll_inertia_kg_m2": (1.0, 20_000.0, "kg m²"),
    "axle.mass_kg": (10.0, 10_000.0, "kg"),
    "axle.height_m": (0.0, 3.0, "m"),
    "axle.suspension_stiffness_kN_per_m": (1.0, 100_000.0, "kN/m"),
    "axle.suspension_damping_kN_s_per_m": (0.0, 1_000.0, "kN s/m"),
    "cab.mass_kg": (10.0, 10_000.0, "kg"),
    "cab.pitch_inertia_kg_m2": (1.0, 100_000.0, "kg m²"),
    "cab.roll_inertia_kg_m2": (1.0, 100_000.0, "kg m²"),
    "cab.ahead_of_cg_m": (-10.0, 10.0, "m"),
    "cab.height_above_cg_m": (-10.0, 10.0, "m"),
    "cab.front_mount_ahead_of_cg_m": (-10.0, 10.0, "m"),
    "cab.rear_mount_ahead_of_cg_m": (-10.0, 10.0, "m"),
    "cab.mount_track_m": (0.1, 5.0, "m"),
    "cab.mount_stiffness_kN_per_m": (1.0, 100_000.0, "kN/m"),
    "cab.mount_damping_kN_s_per_m": (0.0, 1_000.0, "kN s/m"),
    "implement.mass_kg": (1.0, 20_000.0, "kg"),
    "implement.pitch_inertia_kg_m2": (0.0, 200_000.0, "kg m²"),
    "implement.roll_inertia_kg_m2": (0.0, 200_000.0, "kg m²"),
    "implement.behind_rear_axle_m": (0.0, 10.0, "m"),
    "implement.height_m": (0.0, 5.0, "m"),
    "implement.hitch_behind_rear_axle_m": (0.0, 10.0, "m"),
    "implement.hitch_height_m": (0.0, 5.0, "m"),
    "implement.hitch_stiffness_kN_m_per_rad": (1.0, 1_000_000.0, "kN m/rad"),
    "implement.hitch_damping_kN_m_s_per_rad": (0.0, 100_000.0, "kN m s/rad"),
    "ballast.mass_kg": (1.0, 10_000.0, "kg"),
    "ballast.ahead_of_front_axle_m": (0.0, 5.0, "m"),
    "ballast.height_m": (0.0, 5.0, "m"),
    "ballast.pitch_inertia_kg_m2": (0.0, 100_000.0, "kg m²"),
    "ballast.roll_inertia_kg_m2": (0.0, 100_000.0, "kg m²"),
}
#: Most variants one scenario may sweep in the time domain (``tyrelab ride --max-variants`` lifts it).
MAX_VARIANTS = 400
#: Most variants of a sweep computed in the frequency domain (``--method auto`` or ``spectral``;
#: ``--max-variants`` lifts it): 100 x 100 pressures and a swept key of two values. Their rows
#: (variant x speed) are bounded besides, by :data:`MAX_SPECTRAL_SECONDS`.
MAX_SPECTRAL_VARIANTS = 20_000
#: CPU time of one spectral row (a variant at a speed) of the pitch-plane model, s: tyres, assembly,
#: the expectation on 4,000 frequencies. Measured by ``bench/bench_spectral_rows.py`` (issue 46;
#: docs/benchmarks.md, "Spectral rows") on the shipped ``modern_tractor.toml``: 2.6-4.1 ms a row at
#: load 9-18 (issue 36's 1.2 ms was the 10 x 10 x 8 grid before the damped modes of issue 42).
SECONDS_PER_SPECTRAL_ROW = 3e-3
#: What a pitch-plane variant costs besides its rows, whatever its speeds (modes, their intervals), s:
#: the bench's one variant at 200 speeds and 100 variants at one speed, solved for both: 2.8-3.3 ms.
SECONDS_PER_SPECTRAL_VARIANT = 3e-3
#: The same of the 3-D model (roll inertia given; the rolling tyre's damped modes per speed) on
#: ``modern_3d_tractor.toml``: 63 ms a row since issue 42's cuts (78-82 ms before),
SECONDS_PER_SPECTRAL_ROW_3D = 70e-3
#: and 0.24 s a variant (the damped modes' intervals; 0.21-0.58 s before the cuts, the range the
#: shared machine's load, 10 and 18).
SECONDS_PER_SPECTRAL_VARIANT_3D = 0.3
#: What a row's figure data (the expected seat PSD and transmissibility per axis) add to it, s:
#: 3-14 ms (pitch plane, 3-D). Every row of the simulate stage has them, the page's variant of
#: ``tyrelab ride --out``.
SECONDS_PER_SPECTRAL_FIGURE_ROW = 6e-3
#: Most estimated seconds of spectral rows one command computes (:func:`work_estimate`): the bound on
#: rows (variants x speeds) before any work, ``--max-rows N`` sets another. 5 min: the 100 x 100
#: pressure grid at 8 speeds of the pitch plane (80,000 rows, about 270 s) goes through; of the 3-D
#: model about 4,200 rows of few variants, 350 variants at 8 speeds.
MAX_SPECTRAL_SECONDS = 300.0
#: Most samples (1 kHz) one command may simulate over all speeds and pairs (``--max-samples``).
MAX_SAMPLES = 10_000_000
#: Highest value each bound may be set to (``--max-variants``, ``--max-samples``, ``--max-rows``; the
#: library's ``max_variants``, ``max_samples``, ``max_rows``): a bound stays a bound, an integer of
#: 400 digits is refused naming its argument, not taken for "none".
BOUND_CEILINGS = {"max_variants": 1_000_000, "max_samples": 10**12, "max_rows": 10**9}
#: Most points of a profile's uniform grid (its median step from its first distance to its last),
#: checked before the grid is built: what ``tyrelab road`` and a ride resample a profile CSV onto
#: (a 108 kB file of 30 km at 1 mm asked for 30 million points, 1.8 GB). The samples' bound.
MAX_TRACK_POINTS = MAX_SAMPLES
#: Memory and time per simulated sample (measured: 2.2 GB and 18 s for 7.2 million samples).
BYTES_PER_SAMPLE = 300.0
SECONDS_PER_SAMPLE = 2.5e-6
#: Shortest seat record that gets a verdict against the EU limits, s: four periods of 0.4 Hz, the
#: lower band limit of the ISO 2631-1 weightings (a documented choice; shorter records get their
#: exposure numbers, a warning and `verdict` "no verdict: ..."). The daily exposure's
#: :data:`~tyrelab.vehicle.comfort.daily_exposure.MIN_RECORD_S`, one number (issue 45).
MIN_VERDICT_DURATION_S = MIN_RECORD_S


def _limit(key: str) -> tuple[float, float, str]:
    """The :data:`LIMITS` entry of a scenario key (a tyre's by its name, an axle's as ``axle.``)."""
    if key.startswith(("tyres.", "sweep.")):
        return LIMITS[key.rsplit(".", 1)[-1]]
    if key.startswith(("front_axle.", "rear_axle.")):
        return LIMITS["axle." + key.split(".", 1)[1]]
    return LIMITS[key]


def _known(key: str) -> bool:
    try:
        _limit(key)
    except KeyError:
        return False
    return True


def _finite(value) -> bool:
    """``math.isfinite`` where an integer too large for a float is not finite (no OverflowError)."""
    try:
        return math.isfinite(value)
    except OverflowError:
        return False


def _out(key: str, value: float) -> str | None:
    """The line of ``key``'s ``value`` outside :data:`LIMITS` (None: inside); a bool, a non-finite
    value or an integer too large for a float is no number here.

    Examples
    --------
    >>> _out("tractor.mass_kg", 10**400)
    'tractor.mass_kg: 1000000000…0000000000 (401 digits) is not a finite number'
    >>> _out("tractor.mass_kg", 5120) is None
    True
    """
    low, high, unit = _limit(key)
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or not _finite(value):
        return f"{key}: {_validate.shown(value)} is not a finite number"
    if not low <= value <= high:
        u = f" {unit}" if unit else ""
        return f"{key}: {value:g}{u} is outside {low:g} to {high:g}{u}, what the ride model is built for"
    return None


def scenario_problems(scenario) -> list[str]:
    """Every number of ``scenario`` outside :data:`LIMITS`, one line each naming key and bound.

    Also: a step ``dx_m`` longer than a sixteenth of the track, and a profile CSV whose heights
    or gaps between points are out of range.

    See Also
    --------
    override_problems : numbers given beside a scenario.
    work_problems : the work a sweep asks for.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> scenario_problems(load_scenario(scenarios_dir() / "modern_tractor.toml"))
    []
    """
    s = scenario
    checks: list[tuple[str, object]] = []
    for name in ("mass_kg", "pitch_inertia_kg_m2", "front_distance_m", "rear_distance_m", "cg_height_m",
                 "longitudinal_stiffness_kN_per_m", "longitudinal_damping_kN_s_per_m"):
        checks.append((f"tractor.{name}", getattr(s.tractor, name)))
    for name in ("yaw_inertia_kg_m2", "longitudinal_series_damping_kN_s_per_m_km_h"):
        if getattr(s.tractor, name) is not None:
            checks.append((f"tractor.{name}", getattr(s.tractor, name)))
    for name in ("ahead_of_cg_m", "height_above_cg_m", "natural_frequency_Hz", "damping_ratio"):
        if getattr(s.seat, name) is not None:
            checks.append((f"seat.{name}", getattr(s.seat, name)))
    checks += [(f"tractor.{name}", getattr(s.tractor, name)) for name in ("roll_inertia_kg_m2", "front_track_m",
                                                                         "rear_track_m")
               if getattr(s.tractor, name) is not None] + [("seat.left_of_cg_m", s.seat.left_of_cg_m)]
    for section in ("front_axle", "rear_axle", "cab", "implement", "ballast"):  # the tractor's parts
        part = getattr(s, section, None)
        if part is not None:
            checks += [(f"{section}.{f.name}", getattr(part, f.name)) for f in dataclasses.fields(part)
                       if _known(f"{section}.{f.name}")
                       if getattr(part, f.name) is not None and not isinstance(getattr(part, f.name), str)]
    for axle, t in (("front", s.front), ("rear", s.rear)):
        checks.append((f"tyres.{axle}.pressure_bar", t.pressure_bar))
        checks.append((f"tyres.{axle}.age_years", t.age_years))
        for name in ("stiffness_kN_per_m", "damping_kN_s_per_m", "radius_m", "footprint_m",
                     "lateral_stiffness_kN_per_m", "lateral_damping_kN_s_per_m",
                     "lateral_series_damping_kN_s_per_m_km_h"):
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
    if s.exposure.working_speed_km_h is not None:
        checks.append(("exposure.working_speed_km_h", s.exposure.working_speed_km_h))
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
    problems = _validate.grouped_problems(problems)
    if not problems and surf.dx_m > surf.length_m / 16:
        problems.append(f"surface.dx_m: {surf.dx_m:g} m is longer than surface.length_m / 16 "
                        f"({surf.length_m / 16:g} m): the track needs at least 16 points")
    if surf.kind == "profile" and surf.profile_data is not None:
        problems += profile_problems(*surf.profile_data, surf.profile)
    if isinstance(surf.seed, int) and surf.seed < 0:
        problems.append(f"surface.seed: {surf.seed} is negative (a seed is a whole number from 0)")
    if not problems:
        problems += _held_parts_problems(s)
    return problems


def _held_parts_problems(scenario) -> list[str]:
    """A suspended cab and suspended axles are part of ``tractor.mass_kg`` and its inertias and are
    taken out of the body (:func:`tyrelab.vehicle.model.assemble`): what is left of the body (mass,
    pitch and roll inertia about the tractor's CG, with the parts' offsets) must be positive
    definite. An implement on a hitch spring must have an inertia about its hitch."""
    t = scenario.tractor
    three_d = t.roll_inertia_kg_m2 is not None
    n = 3 if three_d else 2
    left = np.diag([t.mass_kg, t.pitch_inertia_kg_m2, t.roll_inertia_kg_m2 or 0.0][:n])
    held = []

    def take(mass, pitch_inertia, roll_inertia, ahead_m, above_m):
        z = np.array([1.0, ahead_m, 0.0][:n])
        x = np.array([0.0, -above_m, 0.0][:n])
        y = np.array([0.0, 0.0, -above_m][:n])
        left[...] -= mass * (np.outer(z, z) + np.outer(x, x) + np.outer(y, y))
        left[1, 1] -= pitch_inertia
        if three_d:
            left[2, 2] -= roll_inertia

    cab = scenario.cab
    if cab.mount == "suspended" and cab.mass_kg is not None:
        take(cab.mass_kg, cab.pitch_inertia_kg_m2 or 0.0, cab.roll_inertia_kg_m2 or 0.0, cab.ahead_of_cg_m,
             cab.height_above_cg_m)
        held.append("cab.mass_kg, its inertias and place")
    for axle, ahead in (("front", t.front_distance_m), ("rear", -t.rear_distance_m)):
        spec = getattr(scenario, f"{axle}_axle")
        if spec.mount == "suspended" and spec.mass_kg is not None:
            height = spec.height_m if spec.height_m is not None else _tyre_radius_m(getattr(scenario, axle))
            take(spec.mass_kg, 0.0, 0.0, ahead, height - t.cg_height_m)
            held.append(f"{axle}_axle.mass_kg")
    problems = []
    if held and np.linalg.eigvalsh(left).min() <= 0:
        keys = "tractor.mass_kg, tractor.pitch_inertia_kg_m2" + (", tractor.roll_inertia_kg_m2" if three_d else "")
        problems.append(f"{keys}: the whole tractor's mass and inertias hold {' and '.join(held)}, and are smaller "
                        f"than those parts' own about the tractor's CG (nothing, or less than nothing, is left of the "
                        f"body: mass {left[0, 0]:.4g} kg)")
    imp = scenario.implement
    if imp is not None and imp.mount == "hitch_spring" and imp.pitch_inertia_kg_m2 + imp.mass_kg * (
            (imp.behind_rear_axle_m - imp.hitch_behind_rear_axle_m) ** 2 + (imp.height_m - imp.hitch_height_m) ** 2) <= 0:
        problems.append("implement.pitch_inertia_kg_m2, behind_rear_axle_m, height_m, hitch_behind_rear_axle_m, "
                        "hitch_height_m: the implement has no inertia about its hitch (its CG at the hitch and no "
                        "pitch inertia)")
    return problems


def _tyre_radius_m(tyre) -> float:
    """A tyre's rolling radius, m: given, or from its size (as :func:`tyrelab.vehicle.ride.resolve_tyres`)."""
    from ...tyre.sizes import parse_tyre_size, rolling_circumference_m

    return tyre.radius_m or rolling_circumference_m(parse_tyre_size(tyre.size)) / (2 * math.pi)


def profile_problems(x, left, right, path=None) -> list[str]:
    """What the model cannot take of a profile's data (distance, left and right heights, m; read
    from ``path``, named in each line): not finite, gaps or a length out of range, a step (the
    median spacing, the track's grid) finer than ``surface.dx_m``'s bound (it sets the samples
    the track is resampled to, before any is allocated), heights out of range.

    See Also
    --------
    scenario_problems : the same for a whole scenario (its profile's data among them).

    Examples
    --------
    >>> x = np.arange(0.0, 10.0, 0.05)
    >>> profile_problems(x, np.zeros_like(x), np.zeros_like(x))
    []
    >>> profile_problems(x, np.full_like(x, 5.0), np.zeros_like(x), "road.csv")[0][:60]
    "surface.profile 'road.csv': heights must be finite and withi"
    """
    where = f"surface.profile {str(path)!r}" if path is not None else "surface.profile"
    problems = []
    if not np.isfinite(x).all():
        problems.append(f"{where}: distance_m has values that are not finite")
    elif len(x) > 1:
        gap = float(np.max(np.diff(x)))
        low, high, _ = LIMITS["profile.gap_m"]
        if gap > high:
            problems.append(f"{where}: a gap of {gap:g} m between points is above {high:g} m")
        if x[-1] - x[0] > LIMITS["surface.length_m"][1]:
            problems.append(f"{where}: {x[-1] - x[0]:g} m long, above {LIMITS['surface.length_m'][1]:g} m")
        step = float(np.median(np.diff(x)))
        low = LIMITS["surface.dx_m"][0]
        points = (float(x[-1]) - float(x[0])) / step + 1 if step > 0 else math.inf
        if step < low:
            problems.append(f"{where}: a step of {step:g} m between points (the median) is below {low:g} m: "
                            f"the track would hold {(x[-1] - x[0]) / step:.3g} points")
        elif points > MAX_TRACK_POINTS:
            problems.append(f"{where}: its median step of {step:g} m over {float(x[-1]) - float(x[0]):g} m makes "
                            f"{points:,.0f} points, more than the {MAX_TRACK_POINTS:,} a track is resampled to (a "
                            "coarser profile, or a part of it)")
    low, high, _ = LIMITS["profile.height_m"]
    h = np.concatenate([left, right])
    if not (np.isfinite(h).all() and h.min() >= low and h.max() <= high):
        finite = h[np.isfinite(h)]
        found = f"{finite.min():g} to {finite.max():g} m" if finite.size else "no finite value"
        bad = int((~np.isfinite(h)).sum())
        problems.append(f"{where}: heights must be finite and within {low:g} to {high:g} m (found {found}"
                        + (f", and {bad} values that are not finite" if bad else "") + ")")
    return problems


#: The old (private) name of :func:`profile_problems`.
_profile_problems = profile_problems


def override_problems(speeds_km_h=None, front_pressures_bar=None, rear_pressures_bar=None) -> list[str]:
    """Speeds and pressures given beside a scenario (``tyrelab ride --speeds`` ...) outside :data:`LIMITS`.

    See Also
    --------
    scenario_problems : the scenario's own numbers.

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
    return _validate.grouped_problems(problems)


#: How a ride's rows are computed (``[simulation] method``; :mod:`tyrelab.vehicle.spectral_ride`).
RIDE_METHODS = ("auto", "time", "spectral")
#: The name of :data:`RIDE_METHODS` before issue 45 (the time domain's own are
#: :data:`tyrelab.vehicle.solvers.time_domain.INTEGRATION_METHODS`): still importable, not in ``__all__``.
METHODS = RIDE_METHODS


def uses_spectral(scenario, method: str, n_variants: int) -> bool:
    """Whether ``method`` computes spectral rows for a sweep of ``n_variants`` of ``scenario``:
    ``spectral``; ``auto`` for more than one variant on an ISO 8608 surface (a profile or any other
    deterministic road is simulated).

    See Also
    --------
    work_estimate : the work under each method.

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> s = NS(surface=NS(kind="iso8608"))
    >>> uses_spectral(s, "auto", 1), uses_spectral(s, "auto", 2), uses_spectral(s, "time", 2)
    (False, True, False)
    """
    _validate.choice("method", method, RIDE_METHODS)
    if method == "auto":
        return n_variants > 1 and scenario.surface.kind == "iso8608"
    return method == "spectral"


def track_length_m(scenario) -> float:
    """The length of road a scenario's tractor drives, m: a profile CSV's own (its first distance to
    its last, as read; ``surface.length_m`` does not apply to it), else ``surface.length_m`` (a CRG
    road's window: the rest of the file unless given). What the work of a ride is estimated on.

    See Also
    --------
    work_estimate : the samples, memory and time of a ride on it.

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> track_length_m(NS(surface=NS(kind="profile", length_m=400.0, profile_data=(np.array([5.0, 20005.0]),) * 3)))
    20000.0
    >>> track_length_m(NS(surface=NS(kind="iso8608", length_m=200.0)))
    200.0
    """
    s = scenario.surface
    data = getattr(s, "profile_data", None)
    if getattr(s, "kind", None) == "profile" and data is not None and len(data[0]) > 1:
        return float(data[0][-1]) - float(data[0][0])
    return float(s.length_m)


def _spectral_costs(scenario) -> tuple[str, float, float]:
    """The model of ``scenario`` (``pitch-plane`` or ``3-D``: roll inertia given) and what its
    spectral rows cost, s: a row, and a variant whatever its speeds (:data:`SECONDS_PER_SPECTRAL_ROW`,
    :data:`SECONDS_PER_SPECTRAL_VARIANT`, and their ``_3D``)."""
    if getattr(getattr(scenario, "tractor", None), "roll_inertia_kg_m2", None) is not None:
        return "3-D", SECONDS_PER_SPECTRAL_ROW_3D, SECONDS_PER_SPECTRAL_VARIANT_3D
    return "pitch-plane", SECONDS_PER_SPECTRAL_ROW, SECONDS_PER_SPECTRAL_VARIANT


def work_estimate(scenario, n_variants: int, speeds_km_h=None, method: str = "time",
                  with_spectra: bool | str = False) -> dict:
    """Samples, memory and time of ``n_variants`` variants at every speed (an estimate) under
    ``method`` (:mod:`tyrelab.vehicle.spectral_ride`): ``time`` simulates every variant; spectral
    rows (``spectral``, or ``auto`` for a sweep on an ISO 8608 surface) simulate nothing
    (``spectral_rows``: variant x speed rows, :data:`SECONDS_PER_SPECTRAL_ROW` each, or
    :data:`SECONDS_PER_SPECTRAL_ROW_3D` of the 3-D model, and a variant's own cost,
    :data:`SECONDS_PER_SPECTRAL_VARIANT` or :data:`SECONDS_PER_SPECTRAL_VARIANT_3D`; and
    :data:`SECONDS_PER_SPECTRAL_FIGURE_ROW` more for each row with figure data: every row with
    ``with_spectra`` True, the nominal variant's with ``"nominal"``: ``spectral_figure_rows``;
    ``spectral_seconds``),
    ``auto`` the nominal variant besides (the speeds that may lift a tyre are bounded when known, by
    ``max_samples``).

    See Also
    --------
    work_problems : the refusals from it.

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> s = NS(surface=NS(length_m=100.0, lead_in_m=5.0), tractor=NS(front_distance_m=1.5, rear_distance_m=1.0),
    ...        exposure=NS(speeds_km_h=(0.05,)), simulation=NS(duration_s=None))
    >>> e = work_estimate(s, 1)
    >>> e["samples"], round(e["memory_GB"], 1), round(e["seconds"])
    (7740000, 2.3, 19)
    >>> s.surface.kind = "iso8608"
    >>> e = work_estimate(s, 10, [4, 8, 12], method="spectral", with_spectra="nominal")
    >>> e["spectral_rows"], e["samples"], round(e["spectral_seconds"], 3)   # 30 rows, 3 with figure data
    (30, 0, 0.138)
    """
    _validate.positive_int("n_variants", n_variants)
    if with_spectra not in (True, False, "nominal"):
        raise ValueError(f"with_spectra must be True, False or 'nominal', got {_validate.shown(with_spectra)}")
    spectral = uses_spectral(scenario, method, n_variants)
    speeds = list(speeds_km_h or scenario.exposure.speeds_km_h)
    length_m = track_length_m(scenario)  # a profile CSV's own length, not surface.length_m
    span_m = length_m + scenario.surface.lead_in_m + scenario.tractor.front_distance_m + scenario.tractor.rear_distance_m
    samples = 0.0
    for v in speeds:
        seconds = span_m / km_h_to_m_s(v)
        if scenario.simulation.duration_s is not None:
            seconds = min(seconds, scenario.simulation.duration_s + span_m - length_m)
        samples += seconds * 1000.0
    simulated = 0 if method == "spectral" and spectral else 1 if spectral else n_variants
    rows = n_variants * len(speeds) if spectral else 0
    figure_rows = 0 if not spectral or not with_spectra else rows if with_spectra is True else len(speeds)
    _, row_s, variant_s = _spectral_costs(scenario)
    spectral_seconds = (rows * row_s + (n_variants * variant_s if spectral else 0.0)
                        + figure_rows * SECONDS_PER_SPECTRAL_FIGURE_ROW)
    total = samples * simulated
    return {"variants": n_variants, "speeds": len(speeds), "samples": int(round(total)),
            "largest_run_samples": int(round(samples)) if simulated else 0,
            "memory_GB": samples * BYTES_PER_SAMPLE / 1e9 if simulated else 0.0,
            "seconds": total * SECONDS_PER_SAMPLE + spectral_seconds,
            "spectral_rows": rows, "spectral_figure_rows": figure_rows, "spectral_seconds": spectral_seconds,
            "simulated_variants": simulated}


def work_problems(scenario, n_variants: int, speeds_km_h=None, *, max_variants: int | None = None,
                  max_samples: int = MAX_SAMPLES, method: str = "time", max_rows: int | None = None,
                  with_spectra: bool | str = False) -> list[str]:
    """Refusals, each with the estimate and the option that lifts the bound (empty: go ahead).

    ``max_variants`` default: :data:`MAX_SPECTRAL_VARIANTS` where ``method`` computes spectral rows
    (:func:`work_estimate`), else :data:`MAX_VARIANTS`. Spectral rows (variant x speed): at most
    ``max_rows``, by default as many as :data:`MAX_SPECTRAL_SECONDS` of the estimate allow (the line
    names the speeds' key: ``speeds_km_h`` when given, else ``exposure.speeds_km_h``; and the estimate).

    See Also
    --------
    work_estimate : the estimate it checks.

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> s = NS(surface=NS(length_m=400.0, lead_in_m=5.0, kind="iso8608"),
    ...        tractor=NS(front_distance_m=1.5, rear_distance_m=1.0),
    ...        exposure=NS(speeds_km_h=tuple(range(4, 20, 2))), simulation=NS(duration_s=None))
    >>> work_problems(s, 100 * 100, method="spectral"), work_problems(s, 100 * 100, method="auto")
    ([], [])
    >>> print(work_problems(s, 100 * 100, method="time")[0])
    10000 variants (pressure pairs x swept values) is more than 400 in the time domain (about 33539 s of simulation); --max-variants N lifts the bound, --method auto or spectral computes them in the frequency domain (about 270 s)
    >>> print(work_problems(s, 1, [0.5 + i / 1000 for i in range(200_000)], method="spectral")[0])
    speeds_km_h: 1 variant(s) x 200000 speed(s) make 200,000 spectral rows, about 600 s of the pitch-plane model (0.003 s a row, 0.003 s a variant), more than the 300 s a command's spectral rows may take; --max-rows N lifts the bound
    """
    e = work_estimate(scenario, n_variants, speeds_km_h, method, with_spectra)
    problems = []
    spectral = e["spectral_rows"] > 0
    limit = max_variants or (MAX_SPECTRAL_VARIANTS if spectral else MAX_VARIANTS)
    if n_variants > limit:
        if spectral:
            problems.append(f"{n_variants} variants (pressure pairs x swept values) is more than {limit} (about {e['seconds']:.0f} s in the frequency "
                            "domain); --max-variants N lifts the bound")
        else:
            _, row_s, variant_s = _spectral_costs(scenario)
            rows = n_variants * (e["speeds"] * row_s + variant_s)
            problems.append(f"{n_variants} variants (pressure pairs x swept values) is more than {limit} in the time domain (about {e['seconds']:.0f} s "
                            "of simulation); --max-variants N lifts the bound"
                            + (f", --method auto or spectral computes them in the frequency domain (about {rows:.0f} s)"
                               if scenario.surface.kind == "iso8608" else ""))
    rows = e["spectral_rows"]
    if rows and (rows > max_rows if max_rows is not None else e["spectral_seconds"] > MAX_SPECTRAL_SECONDS):
        key = "speeds_km_h" if speeds_km_h is not None else "exposure.speeds_km_h"
        model, row_s, variant_s = _spectral_costs(scenario)
        costs = f"{row_s:.3f} s a row, {variant_s:.3f} s a variant"
        figures = e["spectral_figure_rows"] > 0
        bound = (f"the {max_rows:,} rows allowed" if max_rows is not None
                 else f"the {MAX_SPECTRAL_SECONDS:.0f} s a command's spectral rows may take")
        problems.append(f"{key}: {n_variants} variant(s) x {e['speeds']} speed(s) make {rows:,} spectral rows, about "
                        f"{e['spectral_seconds']:.0f} s of the {model} model ({costs}"
                        f"{', figure data besides' if figures else ''}), more than {bound}; --max-rows N lifts the bound")
    if e["samples"] > max_samples:
        problems.append(f"{e['simulated_variants']} variant(s) x {e['speeds']} speed(s) simulate {e['samples']:,} samples "
                        f"(about {e['memory_GB']:.1f} GB for the longest run and {e['seconds']:.0f} s), more than "
                        f"{max_samples:,}; --max-samples N lifts the bound (or raise the speed, shorten the track)")
    return problems


def bound_argument(name: str, value) -> int:
    """A bound given to the work (``max_variants``, ``max_samples``, ``max_rows``) as an int;
    ValueError naming ``name`` unless it is an integer from 1 to its :data:`BOUND_CEILINGS` entry
    (an integer of any length, a bool, a float are refused, never an OverflowError).

    See Also
    --------
    work_problems : the refusals of the work those bounds set.

    Examples
    --------
    >>> bound_argument("max_rows", 5000)
    5000
    >>> bound_argument("max_rows", 10**400)
    Traceback (most recent call last):
    ...
    ValueError: max_rows must be an integer from 1 to 1000000000, got 1000000000…0000000000 (401 digits)
    """
    high = BOUND_CEILINGS[name]
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) or not 1 <= value <= high:
        raise ValueError(f"{name} must be an integer from 1 to {high}, got {_validate.shown(value)}")
    return int(value)


def long_integer_problems(text: str) -> list[str]:
    """Every integer of a scenario's TOML text too long for Python to read (more digits than
    ``sys.get_int_max_str_digits()``, 4300: :mod:`tomllib` refuses the whole text with a ValueError
    naming no key), one line each naming its key (``[table]`` and ``key =`` on its line; else the
    line); the digits are counted, never converted.

    See Also
    --------
    tyrelab.scenario_io.huge_number_problems : integers TOML reads that are too large for a float.

    Examples
    --------
    >>> long_integer_problems("[tractor]\\nmass_kg = 1" + "0" * 5000 + "\\n")
    ['tractor.mass_kg: an integer of 5001 digits is not a finite number']
    """
    import re
    import sys

    limit = sys.get_int_max_str_digits() or 4300
    table, problems = "", []
    for number, line in enumerate(text.splitlines(), 1):
        header = re.match(r"\s*\[\[?\s*([^\]]*?)\s*\]\]?\s*(#.*)?$", line)
        if header:
            table = header.group(1).replace('"', "").replace("'", "").replace(" ", "")
            continue
        for run in re.finditer(r"(?<![\w.])[+-]?[0-9][0-9_]*", line):
            digits = sum(c.isdigit() for c in run.group())
            if digits <= limit:
                continue
            key = re.match(r"\s*([\w.\"' -]+?)\s*=", line)
            name = key.group(1).replace('"', "").replace("'", "").replace(" ", "") if key else None
            where = f"{table}.{name}" if table and name else name or f"line {number}"
            problems.append(f"{where}: an integer of {digits} digits is not a finite number")
    return problems
