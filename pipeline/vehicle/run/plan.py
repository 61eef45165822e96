"""A variant's plan and its end (issue 45): the variant ready to run, each speed's assembly and
linear model, and the :class:`~tyrelab.vehicle.run.records.RideResult` from its reduced runs (modes,
their intervals, the stand-in lateral stiffness' interval of A(8)).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pandas as pd

from ..units import from_kilo, km_h_to_m_s
from ... import _validate
from ..model import Assembly, assemble
from ..modes import ModeSet, damped_modes, follow_damped, frequency_intervals, mode_set
from ..modes import root_sensitivities as modes_root_sensitivities
from ..scenario import Scenario
from ..tyres import _resolve, build_parts
from .output import RideResult
from .records import RideCache, SpeedRun, VariantPlan
from .rows import exposure
from .spectral import _fd_grid, _seat_tf, enveloping_response, expected_weighted_rms
from .track import DT_S, Track

__all__ = ["LATERAL_INTERVAL_STEPS", "seat_axes", "modes"]

#: The seat output the seat suspension filters (:func:`seat_axes`' ``z``).
SEAT_VERTICAL = "seat_vertical_m_s2"
#: Steps across a stand-in lateral stiffness' interval for :func:`_lateral_interval` (odd: the middle is the stand-in).
LATERAL_INTERVAL_STEPS = 9


def record_window(track: Track, wheelbase_m: float, v: float, duration_s: float | None) -> tuple[int, int]:
    """First and one-past-last sample of the record: the front axle on the track."""
    start = int(math.ceil((track.lead_in_m - wheelbase_m) / (v * DT_S))) if track.lead_in_m > wheelbase_m else 0
    length = track.length_m / v if duration_s is None else min(duration_s, track.length_m / v)
    return start, start + int(round(length / DT_S))


def modes(asm) -> tuple[dict, dict]:
    """Undamped natural frequencies (Hz) of an assembled tractor, each named by the coordinate
    that moves most (:func:`tyrelab.vehicle.modes.mode_set`: kinetic-energy share,
    :data:`~tyrelab.vehicle.modes.MODE_NAMES`, a second mode of the same name ``_2``), and the
    bounce and pitch modes' nodal points ahead of the CG (m).

    The pitch-plane tractor on rigid axles is thesis §8.2's beam on two springs
    (:func:`tyrelab.vehicle.bounce_pitch.mode_shapes`, the same eigenproblem).
    """
    _validate.instance("asm", asm, Assembly)
    m = mode_set(asm)
    return m.frequencies(), m.nodal()


def prepare(scenario: Scenario, tyre_data, cache: RideCache, with_spectra: bool = True,
            with_signals: bool = False, a8_interval: bool = True) -> VariantPlan:
    """A variant ready to run: its tyres (:func:`tyrelab.vehicle.tyres.resolve_tyres`), track, seat
    axes and seat filter; the runs are added by :func:`speed_run`. ``a8_interval``: whether its
    result has the A(8) interval across the stand-in lateral stiffness (:func:`_lateral_interval`)."""
    tyres, asms = _resolve(scenario, tyre_data, cache.tyres)
    track_key, track = cache.track(scenario)
    if asms and asms[0] is None:  # footprints given: the first speed's assembly, built here (speed_run takes it)
        asms[0] = assemble(build_parts(scenario, tyres, 0))
    seat = seat_filter(asms[0]) if asms else None  # the seat part's filter (no feedback on the tractor)
    return VariantPlan(scenario, tyres, track, track_key, seat_axes(scenario),
                       cache.seat_system(seat) if seat is not None else None,
                       seat.linear().abcd if seat is not None else None, asms, with_spectra, with_signals,
                       a8_interval=bool(a8_interval), modes_memo=cache.modes)


def seat_filter(asm: Assembly):
    """The filter the assembly puts on the seat's vertical output (:attr:`Assembly.output_filters`: a
    suspended seat's :class:`~tyrelab.vehicle.model.SeatSuspension`, whose ``linear()`` both paths
    apply), or None for a rigid seat."""
    return asm.output_filters.get(SEAT_VERTICAL)


def speed_run(p: VariantPlan, i: int, v: float, start: int, stop: int) -> None:
    """Speed ``i`` of variant ``p``: its assembly and linear model (seat outputs, then the tyre
    forces), as ``p.runs[i]``."""
    sc, tyres = p.scenario, p.tyres
    asm = p.assemblies[i] if p.assemblies[i] is not None else assemble(build_parts(sc, tyres, i))  # the footprints' assembly
    fp = (float(tyres["front"].footprint_m[i]), float(tyres["rear"].footprint_m[i]))
    lm = asm.linear(tuple(p.axes.values()) + tuple(f"{t}_force_N" for t in asm.tyres))
    p.runs[i] = SpeedRun(asm, v, start, stop, fp, lm)


def finish(p: VariantPlan) -> RideResult:
    """The :class:`RideResult` of variant ``p`` from its reduced runs (in speed order)."""
    sc, tyres, track = p.scenario, p.tyres, p.track
    warnings = [f"tyres.{ax}: {w}" for ax in ("front", "rear") for w in tyres[ax].warnings]
    rows, spectra, trans, signals = [], [], [], {}
    for i, speed in enumerate(p.speeds_km_h):
        r = p.runs[i]
        rows.append(r.row)
        if r.warning is not None:
            warnings.append(r.warning)
        if r.signals is not None:  # the cab floor beneath the seat: before the seat suspension (the model's seat x, y have none)
            signals[float(speed)], r.signals = r.signals, None
        if r.spectra is not None:
            spectra.append(r.spectra)
            trans.append(r.transmissibility)
            r.spectra = r.transmissibility = None
    first = p.runs[0].asm
    shapes = mode_set(first)
    nat, nodal = shapes.frequencies(), shapes.nodal()
    by_speed, zeta_ci = {}, {}
    if any(e.name.endswith("_lateral") for e in first.elements):  # the 3-D lateral system: its damping matters
        by_speed = _damped_by_speed(p, shapes)  # issue 42: the complex roots, per speed
        d0 = next(iter(by_speed.values()))
        nat = {n: d.undamped_Hz for n, d in d0.items() if d is not None}
        nodal = {n: x for n, x in nodal.items() if n in nat}
        nat_ci, zeta_ci, notes = _memo(p, ("intervals", first.parts, first.gravity_m_s2, build_parts(sc, tyres, 0)) + tuple(
            (tyres[ax].stiffness_u_kN_per_m, tuple(sorted((tyres[ax].lateral_sources or {}).items())))
            for ax in ("front", "rear")), lambda: _damped_intervals(p, d0, shapes))
        nat_ci, zeta_ci = _copied(nat_ci), _copied(zeta_ci)
    else:
        nat_ci, notes = frequency_intervals(first, tyres["front"].stiffness_u_kN_per_m, tyres["rear"].stiffness_u_kN_per_m,
                                            modes=shapes)
    warnings += [f"natural frequencies: {n}" for n in notes]

    return RideResult(
        scenario=sc, tyres=tyres, natural_frequencies_Hz=nat, nodal_points_m=nodal,
        speeds=pd.DataFrame([row.as_dict() for row in rows]),
        spectra=pd.concat(spectra, ignore_index=True) if spectra else _NO_FIGURE_DATA.copy(),
        transmissibility=pd.concat(trans, ignore_index=True) if trans else _NO_FIGURE_DATA.copy(),
        track_label=track.profile.label, spectrum_source=track.spectrum_source, track_length_m=track.length_m,
        warnings=warnings, natural_frequency_intervals_Hz=nat_ci, signals=signals, road_classes=track.road_classes,
        a8_lateral_ci95_m_s2=_lateral_interval(p, rows) if p.a8_interval else {},
        modes=shapes, modes_by_speed=by_speed, damping_ratio_intervals=zeta_ci,
    )


#: A result's ``spectra`` and ``transmissibility`` without figure data (each result its own copy).
_NO_FIGURE_DATA = pd.DataFrame(columns=["speed_km_h", "frequency_Hz"])


def _damped_by_speed(p: VariantPlan, shapes: ModeSet) -> dict:
    """Speed (km/h) -> ``{mode: DampedMode}`` (issue 42): each speed's assembly's damped modes (its own
    series dampers), each followed by shape from the undamped modes and named by its own shape
    (:func:`~tyrelab.vehicle.modes.damped_modes`): the names say what moves at that speed, so a mode
    whose character changes with speed (two modes veering as the series dampers soften) changes its
    name. Across a sweep's variants the names are followed at each speed
    (:func:`~tyrelab.vehicle.modes.follow_renamed`, :mod:`~tyrelab.vehicle.run.sweep`)."""
    first = p.runs[0].asm
    out = {}
    for i, speed in enumerate(p.speeds_km_h):
        asm = p.runs[i].asm
        key = ("damped", asm.parts, asm.gravity_m_s2, first.parts, first.gravity_m_s2)
        out[float(speed)] = dict(_memo(p, key, lambda: damped_modes(asm, reference=shapes)))
    return out


def _memo(p: VariantPlan, key: tuple, compute):
    """``compute()``, kept in ``p.modes_memo`` under ``key`` (the model it is of: its parts, gravity and
    what else it reads) for the variants that share that model; computed every time without a memo
    or where the key cannot be hashed."""
    if p.modes_memo is None:
        return compute()
    try:
        hash(key)
    except TypeError:  # a part holding an array: not shared
        return compute()
    if key not in p.modes_memo:
        p.modes_memo[key] = compute()
    return p.modes_memo[key]


def _copied(intervals: dict) -> dict:
    """A shared ``{mode: [lo, hi] or None}``, its lists copied (a caller may rename or change them)."""
    return {n: None if ci is None else list(ci) for n, ci in intervals.items()}


def _damped_intervals(p: VariantPlan, nominal: dict, shapes: ModeSet) -> tuple[dict, dict, list]:
    """95 % intervals of the first speed's damped modes (issue 42): first order in each axle's vertical
    tyre stiffness uncertainty (GUM 5.1.2): the roots' derivatives by first-order perturbation
    (:func:`~tyrelab.vehicle.modes.root_sensitivities`, ``dA/dk`` from the models at ±1 % of ``k``)
    where it holds, else central differences of the ±1 % models' modes solved in full (as
    :func:`~tyrelab.vehicle.modes.frequency_intervals`),
    widened to hold every stand-in's spread: the lateral stiffness, lateral damping and series damper
    ``a`` at both ends of their 95 % intervals (x/÷ 2) where they are stand-ins. Every perturbed model's
    modes are followed from the nominal ones by shape. Returns the frequencies' and the damping ratios'
    intervals and a note per mode that cannot be followed."""
    sc, tyres = p.scenario, p.tyres
    base = build_parts(sc, tyres, 0)
    nat = {n: d for n, d in nominal.items() if d is not None}

    def modes_of(parts):
        return follow_damped(nat, damped_modes(assemble(parts), reference=shapes))

    def scaled(parts, axle, **factors):
        part = getattr(parts, axle)
        return dataclasses.replace(parts, **{axle: dataclasses.replace(part, **{
            k: f * getattr(part, k) for k, f in factors.items()})})

    var_f, var_z, lost = dict.fromkeys(nat, 0.0), dict.fromkeys(nat, 0.0), {}
    first = p.runs[0].asm
    a = None if any(d.overdamped for d in nat.values()) else first.linear(list(first.kinematic_outputs)[:1]).a
    for axle in ("front", "rear"):  # (a: the model whose roots the nominal modes are)
        u = tyres[axle].stiffness_u_kN_per_m
        if not u > 0:
            continue
        k = getattr(base, axle).tyre_stiffness_N_per_m
        up_parts = scaled(base, axle, tyre_stiffness_N_per_m=1.01)
        down_parts = scaled(base, axle, tyre_stiffness_N_per_m=0.99)
        # first order in the roots (modes.root_sensitivities) where it holds, else the perturbed models solved
        slopes = None
        if not any(d.overdamped for d in nat.values()):  # (root_sensitivities' first refusal, before assembling)
            lm_up, lm_down = (assemble(x).linear(list(first.kinematic_outputs)[:1]) for x in (up_parts, down_parts))
            if lm_up.a.shape == a.shape == lm_down.a.shape:
                slopes = modes_root_sensitivities(a, nat, (lm_up.a - lm_down.a) / (0.02 * k), 0.01 * k)
        if slopes is not None:
            for n, (df_dk, dz_dk) in slopes.items():
                var_f[n] += (df_dk * from_kilo(u)) ** 2
                var_z[n] += (dz_dk * from_kilo(u)) ** 2
            continue
        up, down = modes_of(up_parts), modes_of(down_parts)
        for n in nat:
            if up[n] is None or down[n] is None:
                lost[n] = axle
                continue
            var_f[n] += ((up[n].undamped_Hz - down[n].undamped_Hz) / (0.02 * k) * from_kilo(u)) ** 2
            var_z[n] += ((up[n].damping_ratio - down[n].damping_ratio) / (0.02 * k) * from_kilo(u)) ** 2
    f_ci = {n: [d.undamped_Hz - 1.96 * math.sqrt(var_f[n]), d.undamped_Hz + 1.96 * math.sqrt(var_f[n])]
            for n, d in nat.items()}
    z_ci = {n: [d.damping_ratio - 1.96 * math.sqrt(var_z[n]), d.damping_ratio + 1.96 * math.sqrt(var_z[n])]
            for n, d in nat.items()}
    spreads = []
    for axle in ("front", "rear"):
        t = tyres[axle]
        sources = t.lateral_sources or {}
        for key, field_ in (("stiffness_kN_per_m", "lateral_stiffness_N_per_m"),
                            ("damping_kN_s_per_m", "lateral_damping_N_s_per_m"),
                            ("series_damping_kN_s_per_m_km_h", "lateral_series_damping_N_s_per_m")):
            if sources.get(key) == "stand-in" and math.isfinite(getattr(base, axle).__dict__.get(field_, 0.0) or 0.0):
                spreads += [scaled(base, axle, **{field_: f}) for f in (0.5, 2.0)]
    for parts in spreads:
        other = modes_of(parts)
        for n, d in other.items():
            if d is None:
                lost.setdefault(n, "stand-in")
                continue
            f_ci[n] = [min(f_ci[n][0], d.undamped_Hz), max(f_ci[n][1], d.undamped_Hz)]
            z_ci[n] = [min(z_ci[n][0], d.damping_ratio), max(z_ci[n][1], d.damping_ratio)]
    notes = []
    for n, why in lost.items():
        f_ci[n] = z_ci[n] = None
        notes.append(f"{n}: no 95 % interval: the mode cannot be followed by its shape when the "
                     + (f"{why} tyre stiffness changes by 1 %" if why != "stand-in" else
                        "stand-ins move across their 95 % intervals") + " (it trades places with another mode)")
    for n, ci in f_ci.items():
        if ci is not None and ci[0] < 0:
            f_ci[n] = None
            notes.append(f"{n}: no 95 % interval: the first-order interval would reach below 0 Hz")
    z_ci = {n: (None if ci is None else [max(ci[0], 0.0), min(ci[1], 1.0)]) for n, ci in z_ci.items()}
    return f_ci, z_ci, notes


def _lateral_interval(p: VariantPlan, rows: list) -> dict:
    """How far A(8) moves across the stand-in lateral stiffness' 95 % interval (issue 33), per speed:
    the frequency-domain expectation of each seat axis with every stand-in lateral stiffness scaled
    across its interval (:data:`LATERAL_INTERVAL_STEPS` log-spaced factors from ÷ 2 to × 2, the
    stand-in among them: a_wy need not be monotonic in it, a resonance may sit inside), over the
    expectation at the stand-in, scales the simulated a_w of that axis; the lowest and highest A(8)
    of those. Empty unless a tyre's lateral stiffness is the stand-in."""
    sc, tyres, track, axes = p.scenario, p.tyres, p.track, p.axes
    stand_in = [ax for ax in ("front", "rear") if tyres[ax].lateral_ci95_kN_per_m is not None]
    if not stand_in or track.side_spectrum is None:
        return {}
    factors = np.geomspace(0.5, 2.0, LATERAL_INTERVAL_STEPS)
    out = {}
    for i, speed in enumerate(p.speeds_km_h):
        v = km_h_to_m_s(speed)  # km/h -> m/s
        base = build_parts(sc, tyres, i)
        variants = [dataclasses.replace(base, **{ax: dataclasses.replace(getattr(base, ax), lateral_stiffness_N_per_m=f * getattr(
            base, ax).lateral_stiffness_N_per_m) for ax in stand_in}) for f in factors]
        lms = [assemble(v_).linear(tuple(axes.values())) for v_ in variants]
        grid = _fd_grid(sc, track, v)
        fp = (float(tyres["front"].footprint_m[i]), float(tyres["rear"].footprint_m[i]))
        env = {axle: enveloping_response(sc.surface.enveloping, fp[j], track.profile.dx_m, grid["n"])
               for j, axle in enumerate(("front", "rear"))}
        seat_tf = _seat_tf(p.seat_abcd, grid["f"]) if p.seat_abcd is not None else None
        exp = expected_weighted_rms(np.array([m.a for m in lms]), np.array([m.b for m in lms]),
                                    np.array([m.c for m in lms]), np.array([m.d for m in lms]),
                                    assemble(base).tyres, grid, env, seat_tf, list(axes))
        mid = LATERAL_INTERVAL_STEPS // 2  # the stand-in itself (factor 1)
        row = rows[i]
        a8 = []
        for k in range(len(factors)):
            scaled = {ax: getattr(row, f"a_w{ax}_m_s2") * (exp[ax][k] / exp[ax][mid] if exp[ax][mid] > 0 else 1.0) for ax in axes}
            a8.append(exposure(scaled["z"], scaled["x"], sc.exposure.hours_per_day, scaled.get("y", 0.0))["a8_m_s2"])
        out[float(speed)] = [min(a8), max(a8)]
    return out


def seat_axes(scenario: Scenario) -> dict[str, str]:
    """Seat axis (``z``, ``x``, and ``y`` in 3-D) -> the assembly output that gives it: the seat
    point's acceleration in space, or with ``[seat] gravity_tilt`` what a body-fixed
    accelerometer reads (plus ``g θ`` fore-aft and ``g φ`` lateral).

    See Also
    --------
    tyrelab.vehicle.model.assemble : the assembly whose outputs they are.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> seat_axes(s)                        # the pitch plane: no lateral axis
    {'z': 'seat_vertical_m_s2', 'x': 'seat_longitudinal_m_s2'}
    """
    _validate.instance("scenario", scenario, Scenario)
    tilt = "_tilt" if scenario.seat.gravity_tilt else ""
    axes = {"z": SEAT_VERTICAL, "x": f"seat_longitudinal{tilt}_m_s2"}
    if scenario.tractor.three_d:
        axes["y"] = f"seat_lateral{tilt}_m_s2"
    return axes


def axle_flags(asm, flags: dict) -> np.ndarray:
    """Per-sample lift-off flags (front, rear) from per-tyre flags: an axle is off the ground
    where any of its tyres is."""
    return np.vstack([np.logical_or.reduce([flags[t] for t in asm.tyres if t.startswith(axle)]) for axle in ("front", "rear")])
