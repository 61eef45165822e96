"""A variant's plan and its end (issue 45): the variant ready to run, each speed's assembly and
linear model, and the :class:`~tyrelab.vehicle.run.records.RideResult` from its reduced runs (modes,
their intervals, the stand-in lateral stiffness' interval of A(8)).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pandas as pd

from ..units import km_h_to_m_s
from ... import _validate
from ..model import Assembly, assemble
from ..modes import frequency_intervals, mode_set
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
            with_signals: bool = False) -> VariantPlan:
    """A variant ready to run: its tyres (:func:`tyrelab.vehicle.tyres.resolve_tyres`), track, seat
    axes and seat filter; the runs are added by :func:`speed_run`."""
    tyres, asms = _resolve(scenario, tyre_data, cache.tyres)
    track_key, track = cache.track(scenario)
    if asms and asms[0] is None:  # footprints given: the first speed's assembly, built here (speed_run takes it)
        asms[0] = assemble(build_parts(scenario, tyres, 0))
    seat = seat_filter(asms[0]) if asms else None  # the seat part's filter (no feedback on the tractor)
    return VariantPlan(scenario, tyres, track, track_key, seat_axes(scenario),
                       cache.seat_system(seat) if seat is not None else None,
                       seat.linear().abcd if seat is not None else None, asms, with_spectra, with_signals)


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
    nat_ci, notes = frequency_intervals(first, tyres["front"].stiffness_u_kN_per_m, tyres["rear"].stiffness_u_kN_per_m)
    warnings += [f"natural frequencies: {n}" for n in notes]
    cols = ["speed_km_h", "frequency_Hz"]
    return RideResult(
        scenario=sc, tyres=tyres, natural_frequencies_Hz=nat, nodal_points_m=nodal,
        speeds=pd.DataFrame([row.as_dict() for row in rows]),
        spectra=pd.concat(spectra, ignore_index=True) if spectra else pd.DataFrame(columns=cols),
        transmissibility=pd.concat(trans, ignore_index=True) if trans else pd.DataFrame(columns=cols),
        track_label=track.profile.label, spectrum_source=track.spectrum_source, track_length_m=track.length_m,
        warnings=warnings, natural_frequency_intervals_Hz=nat_ci, signals=signals, road_classes=track.road_classes,
        a8_lateral_ci95_m_s2=_lateral_interval(p, rows),
        modes=shapes,
    )


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
    accelerometer reads (plus ``g θ`` fore-aft and ``g φ`` lateral)."""
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
