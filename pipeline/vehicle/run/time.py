"""The ride in the time domain (issues 13, 45): every variant simulated at every speed.

The linear model of each speed's assembly runs exactly for the piecewise-linear wheel inputs
(first-order hold, modal decomposition: :func:`tyrelab.vehicle.lti.discretise`); a run whose tyre
force would pull (lift-off) is run again with the nonlinear model
(:func:`tyrelab.vehicle.tractor.simulate`: exact in contact, RK4 across the lift-off intervals), so
the numbers are those of the ch. 7 study. The seat suspension filters the seat point's vertical
acceleration (no feedback on the tractor). Each run is reduced to its
:class:`~tyrelab.vehicle.run.rows.SpeedRow` as soon as it is simulated.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..units import km_h_to_m_s, to_kilo
from ... import _validate
from .. import iso2631
from .. import lti
from .. import metrics as mt
from ..scenario import Scenario
from ..scenario.limits import MIN_VERDICT_DURATION_S
from ..solvers.time_domain import LIFT_OFF_RTOL, off_ground, simulate  # noqa: F401  (LIFT_OFF_RTOL: a name of this module)
from .plan import axle_flags, finish, prepare, record_window, speed_run
from .output import RideResult
from .records import AXIS_WORDS, FIGURE_BAND_HZ, RideCache, VariantPlan
from .rows import SpeedRow, exposure, tyre_columns
from .spectral import AXIS_WEIGHTING, _expected_batch, _transmissibility
from .track import DT_S, FS_HZ, tyre_inputs, wheel_inputs

__all__ = ["ride_variants", "LIFT_OFF_RTOL", "RK4_REAL_STABILITY", "fast_element_problems"]

#: The classical RK4's stability bound on the negative real axis, ``|λ dt|`` (2.785; Hairer & Wanner,
#: Solving ODEs II, §IV.2): an element's own state that relaxes faster than this over the lift-off
#: path's step grows without bound there (its records are not finite).
RK4_REAL_STABILITY = 2.785


def ride_variants(scenarios, tyre_data=None, with_spectra: bool = True, with_signals: bool = False,
                  cache: RideCache | None = None, a8_interval=None) -> list[RideResult]:
    """:func:`~tyrelab.vehicle.ride.ride` for several scenarios (variants) at once, batched: the runs are taken speed by
    speed, so the wheel inputs of a speed are built once for every variant that shares its track,
    footprints and radii, and a run's record is reduced to its numbers as soon as it is simulated.
    Each result is what :func:`~tyrelab.vehicle.ride.ride` gives for that scenario alone (``a8_interval``:
    per scenario whether it has the A(8) interval across the stand-in lateral stiffness, as
    :func:`~tyrelab.vehicle.run.frequency.spectral_variants`; default every one's).

    See Also
    --------
    tyrelab.vehicle.run.frequency.spectral_variants : the same in the frequency domain.
    tyrelab.vehicle.ride.ride_sweep : builds the variants and calls it.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> from tyrelab.vehicle.scenario.variants import with_overrides
    >>> r = ride_variants([with_overrides(s, speeds_km_h=[8.0])], with_spectra=False)
    >>> r[0].speeds[["speed_km_h", "method"]].to_dict("records")
    [{'speed_km_h': 8.0, 'method': 'time'}]
    """
    for k, sc in enumerate(scenarios):
        _validate.instance(f"scenarios[{k}]", sc, Scenario)
    cache = cache or RideCache()
    flags = [True] * len(scenarios) if a8_interval is None else [bool(x) for x in a8_interval]
    if len(flags) != len(scenarios):
        raise ValueError(f"a8_interval: one flag per scenario ({len(scenarios)}), got {len(flags)}")
    preps = [prepare(sc, tyre_data, cache, with_spectra, with_signals, f) for sc, f in zip(scenarios, flags)]
    groups: dict = {}
    for j, p in enumerate(preps):
        for i, speed in enumerate(p.speeds_km_h):
            v = km_h_to_m_s(speed)
            start, stop = record_window(p.track, p.wheelbase_m, v, p.scenario.simulation.duration_s)
            groups.setdefault((p.track_key, v, start, stop), []).append((j, i))
    for (track_key, v, start, stop), members in groups.items():
        for j, i in members:
            speed_run(preps[j], i, v, start, stop)
        _expected_batch([(preps[j], i) for j, i in members], v)
        inputs: dict = {}  # wheel input (full steps) -> (u, du), this speed only
        for j, i in members:
            _linear_run(preps[j], i, track_key, inputs, cache)
        del inputs
    for p in preps:
        _redo_lifting(p)
    return [finish(p) for p in preps]


def _linear_run(p: VariantPlan, i: int, track_key, inputs: dict, cache: RideCache) -> None:
    """Speed ``i`` of variant ``p`` (:func:`~tyrelab.vehicle.run.plan.speed_run`) on the exact linear path; a run whose
    tyres stay on the ground (or without lift-off) is reduced to its numbers now, one that would
    pull is left for :func:`_redo_lifting`."""
    sc, run = p.scenario, p.runs[i]
    asm, lm, start, stop = run.asm, run.lm, run.start, run.stop
    track, kind = p.track.profile, sc.surface.enveloping
    u, du = wheel_inputs(asm.tyres, asm.parts.three_d, track, kind, run.footprints_m, p.radii_m, run.v_m_s,
                         p.wheelbase_m, stop, half_steps=False, memo=inputs,
                         enveloped=lambda side, axle, fp, r: cache.envelope(track_key, track, side, kind, fp, r, axle))
    w = np.empty((2 * len(asm.tyres), stop))  # the exact path's inputs: rows u, u' per tyre
    w[0::2], w[1::2] = u, du
    system = lti.discretise(*lm.abcd, DT_S)
    kept = system.modes(w)
    ns = len(p.axes)
    # the tyre forces on the record only (lift-off before it does not count)
    forces = system.outputs(kept, range(ns, ns + len(asm.tyres)), stop, 1, start)
    static = asm.static_tyre_loads_N()
    off = axle_flags(asm, {t: off_ground(forces[j], static[t]) for j, t in enumerate(asm.tyres)})
    run.lift = tuple(float(o.mean()) for o in off)
    if sc.simulation.lift_off and off.any():
        return  # the nonlinear model, batched per variant (_redo_lifting)
    _reduce(p, i, system.outputs(kept, range(ns)))


def _redo_lifting(p: VariantPlan) -> None:
    """The runs of ``p`` whose tyres would pull: the nonlinear model, batched (exact in contact,
    RK4 across the lift-off intervals, as the ch. 7 study)."""
    sc = p.scenario
    redo = [i for i, r in sorted(p.runs.items()) if r.row is None]
    if not redo:
        return
    seat_outputs = tuple(p.axes.values())
    runs = [p.runs[i] for i in redo]
    # before the RK4 runs: an element state it cannot follow is the scenario keys that set it, not
    # "weighted_m_s2 has non-finite samples" after it
    problems = [line for i, r in zip(redo, runs) for line in fast_element_problems(r.asm, DT_S, p.speeds_km_h[i])]
    if problems:  # one line per set of keys (the left and right tyres of an axle share theirs)
        first: dict = {}
        for line in problems:
            first.setdefault(line.split(": ", 1)[0], line)
        raise ValueError("; ".join(first.values()))
    n_max = max(r.stop for r in runs)
    inputs = [tyre_inputs(r.asm, p.track.profile, sc.surface.enveloping, r.footprints_m, p.radii_m, r.v_m_s, p.wheelbase_m,
                          n_max) for r in runs]
    asms = [r.asm for r in runs]
    forces = tuple(f"{t}_force_N" for t in asms[0].tyres)
    sim = simulate(asms, np.array([x[0] for x in inputs]), np.array([x[1] for x in inputs]), DT_S, lift_off=True,
                   method="auto", record=seat_outputs + forces)
    for row_i, (i, r) in enumerate(zip(redo, runs)):
        static = r.asm.static_tyre_loads_N()
        # off the ground: the tyre force at minus its static load (the clamp), to rounding
        off = axle_flags(r.asm, {t: off_ground(sim[f"{t}_force_N"][row_i, :r.stop], static[t]) for t in r.asm.tyres})
        r.lift = tuple(float(o[r.start:r.stop].mean()) for o in off)
        r.method = "nonlinear (tyre lift-off)"
        _reduce(p, i, np.vstack([sim[o][row_i, :r.stop] for o in seat_outputs]))


def fast_element_problems(asm, dt_s: float, speed_km_h: float) -> list[str]:
    """The elements of the assembly ``asm`` whose own state the lift-off path's RK4 (step ``dt_s``)
    cannot follow, one line each naming the scenario keys that set it: a series (Maxwell) element
    relaxes at ``k / c``, a rolling one at ``k / (c + c₂)`` (:mod:`tyrelab.vehicle.elements`; ``c₂``
    its series damper at ``speed_km_h``); faster than :data:`RK4_REAL_STABILITY` ``/ dt_s`` is
    refused (the linear model, ``simulation.lift_off = false``, is exact at any rate).

    See Also
    --------
    tyrelab.vehicle.tractor.simulate : the lift-off path (exact in contact, RK4 across lift-off).

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> from tyrelab.vehicle.elements import element
    >>> e = element("front_left_lateral", np.array([1.0]), 2.6e5, 10.0, "maxwell")
    >>> print(fast_element_problems(NS(elements=[e]), 1e-3, 20.0)[0].split(": the")[0])
    tyres.front.lateral_stiffness_kN_per_m, tyres.front.lateral_damping_kN_s_per_m
    >>> fast_element_problems(NS(elements=[element("rear_longitudinal", np.array([1.0]), 9.1e5, 6e3, "maxwell")]), 1e-3, 20.0)
    []
    """
    lines = []
    for e in asm.elements:
        model = getattr(e, "model", "")
        if not e.states() or model not in ("maxwell", "rolling"):
            continue
        series = e.series_damping if model == "rolling" else 0.0
        c = e.damping + series
        if not c > 0 or e.stiffness / c * dt_s <= RK4_REAL_STABILITY:
            continue
        if e.name.endswith("_lateral"):
            prefix = f"tyres.{e.name.split('_')[0]}.lateral_"
        elif e.name.endswith("_longitudinal"):
            prefix = "tractor.longitudinal_"
        else:  # pragma: no cover - every element with a state is a tyre's lateral or an axle's longitudinal
            prefix = f"{e.name}."
        keys = [prefix + "stiffness_kN_per_m", prefix + "damping_kN_s_per_m"]
        keys += [prefix + "series_damping_kN_s_per_m_km_h"] if model == "rolling" else []
        c2 = f", c2 = {to_kilo(series):.4g} kN s/m at {speed_km_h:g} km/h" if model == "rolling" else ""
        lines.append(f"{', '.join(keys)}: the {e.name.replace('_', ' ')} element ({model}: k = {to_kilo(e.stiffness):.4g} "
                     f"kN/m, c = {to_kilo(e.damping):.4g} kN s/m{c2}) relaxes at {e.stiffness / c:.4g} /s, faster than "
                     f"the lift-off model's RK4 step of {dt_s:g} s follows ({RK4_REAL_STABILITY / dt_s:.4g} /s; "
                     "its records would not be finite): more damping or less stiffness, or simulation.lift_off = false "
                     "(the linear model, exact at any rate)")
    return lines


def _reduce(p: VariantPlan, i: int, y: np.ndarray) -> None:
    """The numbers of run ``i`` of ``p`` from its seat-point records ``y`` (one row per seat axis)."""
    sc, tyres, r, axes = p.scenario, p.tyres, p.runs[i], p.axes
    hours = sc.exposure.hours_per_day
    speed = p.speeds_km_h[i]
    start, stop, v = r.start, r.stop, r.v_m_s
    series = dict(zip(axes, y))
    floor = {ax: sig[start:stop] for ax, sig in series.items()}
    if p.seat_system is not None:
        series["z"] = p.seat_system.run(series["z"][None, :])[0]
    series = {ax: sig[start:stop] for ax, sig in series.items()}
    weighted = {ax: iso2631.weighted_signal(sig, FS_HZ, AXIS_WEIGHTING[ax]) for ax, sig in series.items()}
    aw = {ax: float(np.sqrt(np.mean(sig**2))) for ax, sig in weighted.items()}
    aw.setdefault("y", 0.0)  # the pitch-plane model has no lateral motion
    vdv = max(iso2631.AXIS_FACTOR[ax] * iso2631.vibration_dose_value(sig, FS_HZ) for ax, sig in weighted.items())
    duration = series["z"].size / FS_HZ
    expected = r.expected  # frequency-domain path (_expected_batch)
    row = SpeedRow(
        float(speed), **tyre_columns(tyres, i), a_wz_m_s2=aw["z"], a_wx_m_s2=aw["x"], a_wy_m_s2=aw["y"],
        expected_a_wz_m_s2=expected["z"], expected_a_wx_m_s2=expected["x"],
        expected_a_wy_m_s2=expected.get("y", 0.0), vdv_m_s1_75=vdv,
        vdv_daily_m_s1_75=float(vdv * (hours * 3600.0 / duration) ** 0.25), evdv_m_s1_75=None,
        evdv_daily_m_s1_75=None, crest_factor=iso2631.crest_factor(weighted["z"]),
        mtvv_m_s2=max(iso2631.AXIS_FACTOR[ax] * iso2631.mtvv(sig, FS_HZ) for ax, sig in weighted.items()),
        lift_off_fraction_front=r.lift[0], lift_off_fraction_rear=r.lift[1], front_tyre_force_sd_N=None,
        rear_tyre_force_sd_N=None, lift_off_probability_front=None, lift_off_probability_rear=None,
        **exposure(aw["z"], aw["x"], hours, aw["y"]), hours_per_day=hours, duration_s=duration, simulation=r.method,
        method="time")
    if duration < MIN_VERDICT_DURATION_S:  # the exposure numbers stay; the verdict is withheld
        row.verdict = f"no verdict: record {duration:.2f} s, shorter than {MIN_VERDICT_DURATION_S:g} s"
        r.warning = (f"{speed:g} km/h: the seat record is {duration:.2f} s, shorter than "
                        f"{MIN_VERDICT_DURATION_S:g} s: too short for a reliable exposure verdict "
                        "(lengthen surface.length_m or simulation.duration_s)")
    r.row = row
    if p.with_signals:
        r.signals = {**{f"seat_{ax}_m_s2": sig for ax, sig in series.items()},
                        **{f"floor_{ax}_m_s2": sig for ax, sig in floor.items()}}
    if p.with_spectra:
        psd = {ax: mt.acceleration_psd(sig, FS_HZ, 0.1) for ax, sig in series.items()}
        fz = psd["z"][0]
        band = (fz >= FIGURE_BAND_HZ[0]) & (fz <= FIGURE_BAND_HZ[1])
        r.spectra = pd.DataFrame({"speed_km_h": float(speed), "frequency_Hz": fz[band],
                                     **{f"seat_{AXIS_WORDS[ax]}_psd_m2_s4_per_Hz": psd[ax][1][band] for ax in axes}})
        r.transmissibility = _transmissibility(r, axes, p.seat_abcd, np.geomspace(*FIGURE_BAND_HZ, 300), v, p.wheelbase_m,
                                       float(speed))
