"""A typed record of a ride run (issue 45): the plan of a variant, one speed's run, the result.

:class:`VariantPlan` is one variant (a scenario) ready to run: its tyres, track, seat axes, seat
filter and the assembly of each speed; :class:`SpeedRun` one of its speeds, filled in as the run
goes (the assembly and linear model, the record window, then the expected and simulated numbers
and the :class:`~tyrelab.vehicle.run.rows.SpeedRow`); what a caller gets is a
:class:`~tyrelab.vehicle.run.output.RideResult`.
:class:`RideCache` is what the runs of several variants share in one process.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .. import lti
from .. import profiles as pr
from ..model import SeatSuspension
from ..scenario import Scenario
from .rows import SpeedRow
from .track import DT_S, FS_HZ, Track, build_profile, envelope_side, track_width_m

__all__ = ["DT_S", "FS_HZ", "FIGURE_BAND_HZ", "AXIS_WORDS", "VariantPlan", "SpeedRun", "RideCache"]

#: Frequency range of the seat PSD and transmissibility figures, Hz.
FIGURE_BAND_HZ = (0.2, 20.0)
#: Seat axes and their words in column names.
AXIS_WORDS = {"z": "vertical", "x": "longitudinal", "y": "lateral"}


@dataclass
class SpeedRun:
    """One speed of a variant: set up by :func:`tyrelab.vehicle.run.plan.speed_run`, then filled in.

    Attributes
    ----------
    asm : Assembly
        The tractor at this speed's tyre numbers.
    v_m_s : float
        Speed, m/s.
    start, stop : int
        The record: first and one-past-last sample (the front axle on the track).
    footprints_m : tuple of float
        Front and rear tyre footprint at this speed, m.
    lm : LinearModel
        Seat-axis outputs, then each tyre element's dynamic force.
    method : str
        ``linear`` or ``nonlinear (tyre lift-off)`` (the time path that gave the numbers).
    lift : tuple of float
        Fraction of the record each axle is off the ground.
    expected : dict
        Seat axis -> expected weighted r.m.s. (frequency domain), m/s².
    force_sd_N : dict
        Tyre element -> r.m.s. of its dynamic force (spectral rows), N.
    row : SpeedRow
        The numbers; None until the run is reduced.
    """

    asm: object
    v_m_s: float
    start: int
    stop: int
    footprints_m: tuple
    lm: object
    method: str = "linear"
    lift: tuple | None = None
    expected: dict | None = None
    force_sd_N: dict | None = None
    row: SpeedRow | None = None
    warning: str | None = None
    signals: dict | None = None
    spectra: pd.DataFrame | None = None
    transmissibility: pd.DataFrame | None = None


@dataclass
class VariantPlan:
    """One variant ready to run (:func:`tyrelab.vehicle.run.plan.prepare`) and its runs by speed index."""

    scenario: Scenario
    tyres: dict
    track: Track
    track_key: tuple
    #: Seat axis (``z``, ``x``, ``y``) -> the assembly output that gives it (:func:`~tyrelab.vehicle.run.plan.seat_axes`).
    axes: dict
    #: The seat suspension discretised at :data:`DT_S` and its ``(A, B, C, D)`` (None: a rigid seat).
    seat_system: lti.FohSystem | None
    seat_abcd: tuple | None
    #: The assembly of each speed that gave the tyres' footprints (None where none was built).
    assemblies: list
    with_spectra: bool = True
    with_signals: bool = False
    runs: dict = field(default_factory=dict)
    #: Static tyre loads by the tyres' stiffness pair (spectral rows).
    static_loads: dict = field(default_factory=dict)
    #: Whether :func:`~tyrelab.vehicle.run.plan.finish` computes the A(8) interval across the stand-in
    #: lateral stiffness (``a8_lateral_ci95_m_s2``): a sweep reports its first variant's only.
    a8_interval: bool = True
    #: The modes of the models this variant shares with others (:attr:`RideCache.modes`), by model.
    modes_memo: dict | None = None

    @property
    def wheelbase_m(self) -> float:
        return self.scenario.tractor.wheelbase_m

    @property
    def speeds_km_h(self) -> tuple:
        return self.scenario.exposure.speeds_km_h

    @property
    def radii_m(self) -> tuple[float, float]:
        return (self.tyres["front"].radius_m, self.tyres["rear"].radius_m)


class RideCache:
    """What the runs of several variants share in one process: the tracks (by surface), each wheel
    track enveloped (by footprint or radius), the seat filter's discretisation and the damped modes
    of each model (:attr:`modes`).
    :func:`~tyrelab.vehicle.ride.ride_sweep` passes one to all its variants; a caller running
    variants one by one may pass its own."""

    def __init__(self):
        self.tracks: dict = {}
        self.enveloped: dict = {}
        self.seat: dict = {}
        #: :func:`~tyrelab.vehicle.tyres.resolve_tyres`' memo
        self.tyres: dict = {}
        #: The damped modes and their intervals by the model they are of (its parts and gravity): a
        #: variant that shares a model with another (a swept key the model does not read, the nominal
        #: variant simulated beside its spectral rows) takes them from here.
        self.modes: dict = {}

    def track(self, scenario: Scenario) -> tuple[tuple, Track]:
        """(key, :class:`~tyrelab.vehicle.run.track.Track`) of ``scenario``'s surface (built once per surface)."""
        t = scenario.tractor
        key = (scenario.surface, t.wheelbase_m, t.three_d, track_width_m(scenario))
        if key not in self.tracks:
            self.tracks[key] = build_profile(scenario)
        return key, self.tracks[key]

    def envelope(self, key: tuple, track: pr.Profile, side: str, kind: str, footprint_m: float,
                 radius_m: float, axle: str = "front") -> np.ndarray:
        """One wheel track (``left``, ``right`` or the axle ``mean`` of the two enveloped) under
        ``axle``'s wheels, enveloped (:func:`~tyrelab.vehicle.run.track.envelope_side`)."""
        what = footprint_m if kind in ("tapered", "fixed") else radius_m if kind == "rigid_band" else None
        rear = axle == "rear" and track.rear_left_m is not None  # the rear wheels' own tracks
        k = (key, side, kind, what, rear)
        if k not in self.enveloped:
            if side == "mean":
                self.enveloped[k] = 0.5 * (self.envelope(key, track, "left", kind, footprint_m, radius_m, axle)
                                           + self.envelope(key, track, "right", kind, footprint_m, radius_m, axle))
            else:
                self.enveloped[k] = envelope_side(track, side, kind, footprint_m, radius_m, axle)
        return self.enveloped[k]

    def seat_system(self, seat) -> lti.FohSystem | None:
        """The seat's suspension (a scenario's ``[seat]`` or a :class:`~tyrelab.vehicle.model.SeatSuspension`
        part) discretised at :data:`DT_S` (None for a rigid seat)."""
        part = seat if isinstance(seat, SeatSuspension) else seat.part().suspension
        if part is None:
            return None
        if part not in self.seat:
            self.seat[part] = lti.discretise(*part.linear().abcd, DT_S)
        return self.seat[part]
