"""A sweep (issues 13, 36, 37, 45): every variant of a scenario, time or spectral rows as the
method says, the work split into executor tasks; and the frequency-domain expectation alone of a
pressure study (:func:`expected_sweep`).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..units import km_h_to_m_s
from ... import _validate
from .. import spectral_ride as sr
from ..model import assemble
from ..modes import follow_names, follow_renamed
from ..scenario import Scenario, limits, with_overrides
from ..tyres import build_parts, resolve_tyres
from ..units import from_kilo
from .frequency import spectral_variants
from .plan import seat_axes, seat_filter
from .output import RideResult
from .records import RideCache
from .rows import exposure
from .spectral import _fd_grid, _seat_tf, enveloping_response, expected_weighted_rms
from .time import ride_variants

__all__ = ["SWEEP_CHUNK", "expected_sweep"]

#: Variants per executor task of :func:`~tyrelab.vehicle.ride.ride_sweep` (a task shares its wheel inputs between them).
SWEEP_CHUNK = 25


def _ride_batch(item: tuple) -> list[RideResult]:
    """Executor task: a chunk of scenario variants, batched (:func:`~tyrelab.vehicle.run.time.ride_variants`;
    module level, picklable). ``item``: scenarios, tyre data, ``with_spectra`` and optionally the
    ``a8_interval`` flags."""
    scenarios, tyre_data, with_spectra, *flags = item
    return ride_variants(scenarios, tyre_data, with_spectra, a8_interval=flags[0] if flags else None)


def _spectral_batch(item: tuple) -> list[RideResult]:
    """Executor task: a chunk of variants in the frequency domain (module level, picklable)."""
    scenarios, tyre_data, with_spectra, *flags = item
    return spectral_variants(scenarios, tyre_data, with_spectra, a8_interval=flags[0] if flags else None)


def in_chunks(task, scenarios: list, size: int, tyre_data, with_spectra: bool, map_fn,
              a8_interval=None) -> list[RideResult]:
    """``task`` (:func:`_ride_batch`, :func:`_spectral_batch`) over chunks of ``scenarios`` of
    ``size``, through the caller's executor ``map_fn``; results in order. ``a8_interval``: per
    scenario, as :func:`~tyrelab.vehicle.run.frequency.spectral_variants` (default every one's)."""
    flags = [True] * len(scenarios) if a8_interval is None else list(a8_interval)
    chunks = [(scenarios[k:k + size], tyre_data, with_spectra, flags[k:k + size]) for k in range(0, len(scenarios), size)]
    return [r for chunk in map_fn(task, chunks) for r in chunk]


def _sweep_results(scenarios: list, method: str, nominal: int, tyre_data, with_spectra: bool | str, map_fn,
                   max_samples: int | None) -> list[RideResult]:
    """The results of a sweep's variants under ``method`` (:mod:`tyrelab.vehicle.spectral_ride`), in
    order, with figure data as :func:`~tyrelab.vehicle.ride.ride_sweep`'s ``with_spectra`` says. ``auto``'s time-domain
    checks stay within ``max_samples`` (the nominal variant first, then the lifting speeds in order;
    those beyond are left spectral, with a warning). The A(8) interval across the stand-in lateral
    stiffness is computed for the first variant alone, the one :func:`~tyrelab.vehicle.ride.result_json`
    reports (``a8_lateral_ci95_m_s2``; the others' are empty), and not for the time-domain checks (their
    rows alone are taken)."""
    cache = RideCache()  # shared by the runs in this process (tracks, enveloped wheel tracks, tyres, modes)

    def timed(chosen: list, spectra: bool, flags: list) -> list[RideResult]:  # chunks, each batched in its task
        if map_fn is None or len(chosen) <= 1:
            return ride_variants(chosen, tyre_data, spectra, cache=cache, a8_interval=flags) if chosen else []
        return in_chunks(_ride_batch, chosen, max(1, min(SWEEP_CHUNK, -(-len(chosen) // 8))), tyre_data, spectra,
                         map_fn, flags)

    def spectral(chosen: list, spectra: bool, flags: list) -> list[RideResult]:
        if map_fn is None or len(chosen) <= sr.SPECTRAL_CHUNK:
            return spectral_variants(chosen, tyre_data, spectra, cache, a8_interval=flags) if chosen else []
        return in_chunks(_spectral_batch, chosen, sr.SPECTRAL_CHUNK, tyre_data, spectra, map_fn, flags)

    run = spectral if limits.uses_spectral(scenarios[0], method, len(scenarios)) else timed
    reported = [j == 0 for j in range(len(scenarios))]  # the variant whose A(8) interval is reported
    if with_spectra == "nominal":  # the figure data of the nominal variant alone (what a sweep's page draws)
        results = run(scenarios[:nominal] + scenarios[nominal + 1:], False, reported[:nominal] + reported[nominal + 1:])
        results.insert(nominal, run([scenarios[nominal]], True, [reported[nominal]])[0])
    else:
        results = run(scenarios, bool(with_spectra), reported)
    if run is timed or method == "spectral":
        return results
    checks = [(nominal, scenarios[nominal])]  # auto: the nominal variant and the speeds that may lift a tyre
    budget = (max_samples or limits.MAX_SAMPLES) - limits.work_estimate(scenarios[nominal], 1)["samples"]
    skipped = []
    for j, r in enumerate(results):
        lifting = sr.lifting_speeds(r.speeds) if j != nominal else []
        if not lifting:
            continue
        sc = with_overrides(scenarios[j], lifting)
        cost = limits.work_estimate(sc, 1)["samples"]
        if cost > budget:
            skipped.append(j)
            continue
        budget -= cost
        checks.append((j, sc))
    for (j, _), t in zip(checks, timed([sc for _, sc in checks], False, [False] * len(checks))):
        results[j].time_rows = t.speeds
        results[j].warnings = list(dict.fromkeys(results[j].warnings + t.warnings))
    for j in skipped:
        results[j].warnings.append(
            f"{len(skipped)} variant(s) whose lift-off probability exceeds {sr.LIFT_OFF_PROBABILITY_LIMIT:g} were not "
            "simulated in the time domain (the --max-samples budget): their rows are the linear expectation, which "
            "does not hold where tyres lift off")
    return results


def nominal_result(results: list[RideResult]) -> RideResult:
    """The variant at the scenario's own values (:attr:`RideResult.nominal`), else the first."""
    return next((r for r in results if r.nominal), results[0])


def _follow_modes(results: list[RideResult]) -> None:
    """Every variant's modes under the first variant's names, followed by shape
    (:func:`tyrelab.vehicle.modes.follow_names`): a sweep's ``bounce_Hz`` is one mode in every
    variant. A mode of the first variant that a variant does not have (by shape) is NaN there,
    with a warning."""
    ref = results[0].modes
    for r in results[1:]:
        if ref is None or r.modes is None:
            continue
        mapping, notes = follow_names(ref, r.modes)
        back = {new: own for own, new in mapping.items()}
        r.nodal_points_m = {n: r.modes.nodal_points_m[r.modes.names.index(back[n])] if n in back else math.nan
                            for n in ref.nodal()}
        if results[0].modes_by_speed and r.modes_by_speed:  # issue 42: the damped modes, by their own shapes
            notes = _follow_damped_modes(results[0], r)
        else:
            r.natural_frequencies_Hz = {n: r.natural_frequencies_Hz.get(back[n], math.nan) if n in back else math.nan
                                        for n in ref.names}
            r.natural_frequency_intervals_Hz = {n: r.natural_frequency_intervals_Hz.get(back[n]) if n in back else None
                                                for n in ref.names}
        r.warnings += [f"natural frequencies: {n}" for n in notes]


def _follow_damped_modes(first: RideResult, r: RideResult) -> list[str]:
    """``r``'s damped modes under ``first``'s names (issue 42), speed by speed (each speed's from the first
    variant's at that speed, :func:`tyrelab.vehicle.modes.follow_renamed`), and its frequencies and their
    intervals under them: a sweep's ``lateral_roll_Hz`` and its ``modes_damping`` name one mode in every
    variant. A mode of the first variant no mode of ``r`` follows is NaN there, with a note."""
    ref_first = next(iter(first.modes_by_speed.values()))
    renamed_first = None
    for speed, own in list(r.modes_by_speed.items()):
        modes, renamed = follow_renamed(first.modes_by_speed.get(speed, ref_first), own)
        r.modes_by_speed[speed] = modes
        renamed_first = renamed if renamed_first is None else renamed_first
    back = {new: old for old, new in renamed_first.items()}
    d0 = next(iter(r.modes_by_speed.values()))
    names = list(first.natural_frequencies_Hz)
    r.natural_frequencies_Hz = {n: d0[n].undamped_Hz if n in d0 else math.nan for n in names}
    r.natural_frequency_intervals_Hz = {n: r.natural_frequency_intervals_Hz.get(back[n]) if n in back else None
                                        for n in names}
    r.damping_ratio_intervals = {back_n: r.damping_ratio_intervals.get(old)
                                 for old, back_n in renamed_first.items() if old in r.damping_ratio_intervals}
    return [f"{n}: not followed from the first variant by its damped shape: no number"
            for n in names if not math.isfinite(r.natural_frequencies_Hz[n])]


def expected_sweep(scenario: Scenario, front_pressures_bar, rear_pressures_bar, speeds_km_h=None,
                   tyre_data=None, cache: RideCache | None = None) -> pd.DataFrame:
    """The frequency-domain expectation alone (no simulation) for every front × rear pressure
    pair and speed: a large pressure study in seconds.

    The tyres are resolved once per axle and pressure, the linear models of all pairs at a speed
    come from one assembly (:meth:`tyrelab.vehicle.model.Assembly.linear_tyres`) and their
    expected weighted r.m.s. from one batched :func:`expected_weighted_rms`; each number is the
    ``expected_a_w*_m_s2`` :func:`ride` gives for that pair, speed and the scenario's track spectrum.

    Returns
    -------
    DataFrame
        One row per pair and speed: ``front_pressure_bar``, ``rear_pressure_bar``, ``speed_km_h``,
        ``expected_a_wz_m_s2``, ``expected_a_wx_m_s2``, ``expected_a_wy_m_s2``, and the exposure
        of these (``a8_m_s2``, ``hours_to_eav``, ``hours_to_elv``, ``verdict``) at the scenario's
        hours per day.

    See Also
    --------
    tyrelab.vehicle.ride.ride_sweep : simulated as well.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> sc = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> t = expected_sweep(sc, [1.2, 1.6], [1.2], [8.0])
    >>> row = t.iloc[1]
    >>> from tyrelab.vehicle.ride import ride
    >>> r = ride(with_overrides(sc, [8.0], 1.6, 1.2), with_spectra=False).speeds.iloc[0]
    >>> bool(abs(row["expected_a_wz_m_s2"] / r["expected_a_wz_m_s2"] - 1) < 1e-9)
    True
    """
    _validate.instance("scenario", scenario, Scenario)
    cache = cache or RideCache()
    fronts, rears = [float(x) for x in front_pressures_bar], [float(x) for x in rear_pressures_bar]
    if not fronts or not rears:
        raise ValueError("front_pressures_bar, rear_pressures_bar: give at least one pressure each")
    base = with_overrides(scenario, speeds_km_h, fronts[0], rears[0])
    bad = limits.override_problems(speeds_km_h, fronts, rears)
    if bad:
        raise ValueError("; ".join(bad))
    speeds = base.exposure.speeds_km_h
    front = {pf: resolve_tyres(with_overrides(base, None, pf, rears[0]), tyre_data)["front"] for pf in fronts}
    rear = {pr_: resolve_tyres(with_overrides(base, None, fronts[0], pr_), tyre_data)["rear"] for pr_ in rears}
    _, track = cache.track(base)
    axes = seat_axes(base)
    tyres0 = {"front": front[fronts[0]], "rear": rear[rears[0]]}
    seat = seat_filter(assemble(build_parts(base, tyres0, 0)))  # the assembly's filter on the seat output
    seat_ss = seat.linear().abcd if seat is not None else None
    pf_all = np.repeat(fronts, len(rears))
    pr_all = np.tile(rears, len(fronts))
    frames = []
    for i, speed in enumerate(speeds):
        v = km_h_to_m_s(speed)
        asm = assemble(build_parts(base, tyres0, i))
        k = {"front": np.array([from_kilo(front[p].stiffness_kN_per_m[i]) for p in pf_all]),
             "rear": np.array([from_kilo(rear[p].stiffness_kN_per_m[i]) for p in pr_all])}
        c = {"front": np.array([from_kilo(front[p].damping_kN_s_per_m[i]) for p in pf_all]),
             "rear": np.array([from_kilo(rear[p].damping_kN_s_per_m[i]) for p in pr_all])}
        if base.tractor.three_d and base.tractor.lateral_model != "none":
            # the lateral elements follow each pair's tyres (the stand-in scales with k_z; a Maxwell
            # element is not affine in its damping): one assembly per pair
            lms = [assemble(build_parts(base, {"front": front[pf], "rear": rear[pr_]}, i)).linear(tuple(axes.values()))
                   for pf, pr_ in zip(pf_all, pr_all)]
            a, b, cc, d = (np.array([getattr(m, x) for m in lms]) for x in "abcd")
        else:
            a, b, cc, d = asm.linear_tyres(tuple(axes.values()), k, c)
        grid = _fd_grid(base, track, v)
        env_f = {p: enveloping_response(base.surface.enveloping, float(front[p].footprint_m[i]), track.profile.dx_m,
                                        grid["n"]) for p in fronts}
        env_r = {p: enveloping_response(base.surface.enveloping, float(rear[p].footprint_m[i]), track.profile.dx_m,
                                        grid["n"]) for p in rears}
        env = {"front": (np.array([env_f[p] for p in fronts]), np.repeat(np.arange(len(fronts)), len(rears))),
               "rear": (np.array([env_r[p] for p in rears]), np.tile(np.arange(len(rears)), len(fronts)))}
        seat_tf = _seat_tf(seat_ss, grid["f"]) if seat_ss is not None else None
        got = expected_weighted_rms(a, b, cc, d, asm.tyres, grid, env, seat_tf, list(axes))
        frame = pd.DataFrame({"front_pressure_bar": pf_all, "rear_pressure_bar": pr_all, "speed_km_h": float(speed),
                              **{f"expected_a_w{ax}_m_s2": got[ax] for ax in axes}})
        frames.append(frame)
    out = pd.concat(frames, ignore_index=True)
    if "expected_a_wy_m_s2" not in out:
        out["expected_a_wy_m_s2"] = 0.0
    hours = base.exposure.hours_per_day
    ex = [exposure(z, x, hours, y) for z, x, y in
          zip(out["expected_a_wz_m_s2"], out["expected_a_wx_m_s2"], out["expected_a_wy_m_s2"])]
    for key in ("a8_m_s2", "a8_axis", "hours_to_eav", "hours_to_elv", "verdict"):
        out[key] = [e[key] for e in ex]
    return out
