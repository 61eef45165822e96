"""The scenario's parts as read: small frozen dataclasses, one per TOML table (issue 13, 45).

A :class:`Scenario` is the whole file; :meth:`Scenario.parts` is the one place its kN values become
the model's SI parts. Nothing is read or computed here: :mod:`tyrelab.vehicle.scenario.parse` checks
and builds them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from ..model import Axle, Ballast, Cab, Chassis, Implement, Parts, SeatPoint, SeatSuspension
from ..units import from_kilo

__all__ = ["Scenario", "TractorSpec", "SeatSpec", "TyreSpec", "SurfaceSpec", "ExposureSpec", "SimulationSpec",
           "SweepSpec", "AxleSpec", "CabSpec", "ImplementSpec", "BallastSpec", "ScenarioError"]


class ScenarioError(ValueError):
    """A scenario file is wrong; ``problems`` lists every problem (one line each)."""

    def __init__(self, path: str | Path, problems: list[str]):
        self.path = str(path)
        self.problems = list(problems)
        super().__init__("\n".join(f"{self.path}: {p}" for p in self.problems))


@dataclass(frozen=True)
class TractorSpec:
    """``[tractor]``: SI units as in the key names; longitudinal values per rear tyre."""

    mass_kg: float
    pitch_inertia_kg_m2: float
    front_distance_m: float
    rear_distance_m: float
    cg_height_m: float
    longitudinal_model: str = "none"
    longitudinal_stiffness_kN_per_m: float = 455.0
    longitudinal_damping_kN_s_per_m: float = 3.0
    roll_inertia_kg_m2: float | None = None
    front_track_m: float | None = None
    rear_track_m: float | None = None
    #: Each tyre's lateral element (issues 33, 42): ``rolling`` by default with roll, ``kelvin_voigt``,
    #: ``maxwell``, or ``none`` (the body rolls about its CG); see :func:`parse_scenario`.
    lateral_model: str = "none"
    yaw_inertia_kg_m2: float | None = None
    #: ``longitudinal_model = "rolling"``: ``a`` of the rear tyres' series damper ``c₂ = a / v`` (issue 42);
    #: None: the measured tyre's, the catalogue's or the stand-in (:func:`tyrelab.tyre.directional.rolling_coefficients`).
    longitudinal_series_damping_kN_s_per_m_km_h: float | None = None

    @property
    def three_d(self) -> bool:
        """Roll modelled (``roll_inertia_kg_m2`` given): left and right tyres on their own tracks."""
        return self.roll_inertia_kg_m2 is not None

    @property
    def wheelbase_m(self) -> float:
        """Front distance + rear distance, m."""
        return self.front_distance_m + self.rear_distance_m


@dataclass(frozen=True)
class SeatSpec:
    """``[seat]``: reference point relative to the CG (m) and its suspension."""

    ahead_of_cg_m: float = 0.0
    height_above_cg_m: float = 0.0
    suspension: str = "rigid"
    natural_frequency_Hz: float | None = None
    damping_ratio: float | None = None
    left_of_cg_m: float = 0.0
    gravity_tilt: bool = False

    def part(self) -> SeatPoint:
        """The seat as a model part: its point and its suspension
        (:class:`~tyrelab.vehicle.model.SeatSuspension`, None for a rigid seat)."""
        suspension = (SeatSuspension(self.natural_frequency_Hz, self.damping_ratio) if self.suspension == "linear"
                      else None)
        return SeatPoint(self.ahead_of_cg_m, self.left_of_cg_m, self.height_above_cg_m, suspension)


@dataclass(frozen=True)
class AxleSpec:
    """``[front_axle]`` / ``[rear_axle]``: how the axle is carried (kN, kg, m as the key names)."""

    mount: str = "rigid"
    roll_inertia_kg_m2: float | None = None
    mass_kg: float | None = None
    height_m: float | None = None
    suspension_stiffness_kN_per_m: float | None = None
    suspension_damping_kN_s_per_m: float = 0.0


@dataclass(frozen=True)
class CabSpec:
    """``[cab]``: rigid (part of the body) or suspended on four mounts."""

    mount: str = "rigid"
    mass_kg: float | None = None
    pitch_inertia_kg_m2: float | None = None
    roll_inertia_kg_m2: float | None = None
    ahead_of_cg_m: float = 0.0
    height_above_cg_m: float = 0.0
    front_mount_ahead_of_cg_m: float | None = None
    rear_mount_ahead_of_cg_m: float | None = None
    mount_track_m: float | None = None
    mount_stiffness_kN_per_m: float | None = None
    mount_damping_kN_s_per_m: float = 0.0


@dataclass(frozen=True)
class ImplementSpec:
    """``[implement]``: a mounted implement on the rear hitch."""

    mass_kg: float
    behind_rear_axle_m: float
    height_m: float
    pitch_inertia_kg_m2: float = 0.0
    roll_inertia_kg_m2: float = 0.0
    mount: str = "rigid"
    hitch_behind_rear_axle_m: float = 0.0
    hitch_height_m: float = 0.0
    hitch_stiffness_kN_m_per_rad: float | None = None
    hitch_damping_kN_m_s_per_rad: float = 0.0


#: ``[ballast]``: a front ballast mass. Its keys are the model part's fields in the model's units
#: (kg, m, kg m²), so the scenario holds the part itself (:class:`tyrelab.vehicle.model.Ballast`).
BallastSpec = Ballast


@dataclass(frozen=True)
class TyreSpec:
    """``[tyres.front]`` / ``[tyres.rear]``: one tyre of the axle.

    ``stiffness_kN_per_m`` / ``damping_kN_s_per_m`` are None, a float or a tuple
    (one per scenario speed).
    """

    size: str
    pressure_bar: float
    traction: bool
    stiffness_kN_per_m: float | tuple | None = None
    damping_kN_s_per_m: float | tuple | None = None
    measured_tyre_id: str | None = None
    water_ballast: bool = False
    age_years: float = 1.0
    radius_m: float | None = None
    footprint_m: float | None = None
    formula: str = "thesis"
    lateral_stiffness_kN_per_m: float | None = None
    lateral_damping_kN_s_per_m: float | None = None
    #: ``a`` of the rolling lateral element's series damper ``c₂ = a / v``, kN s/m × km/h (issue 42).
    lateral_series_damping_kN_s_per_m_km_h: float | None = None


@dataclass(frozen=True)
class SurfaceSpec:
    """``[surface]``; ``profile`` is an absolute path once loaded."""

    kind: str
    road_class: str | None = None
    length_m: float = 400.0
    seed: int = 1
    dx_m: float = 0.05
    profile: Path | None = None
    spectrum_g0_m3: float | None = None
    spectrum_waviness: float = 2.0
    spectrum_correlated: bool | None = None
    enveloping: str = "tapered"
    lead_in_m: float = 5.0
    tracks: str = "independent"
    #: ``(distance_m, left_m, right_m)`` of ``profile`` as read (:func:`parse_scenario`'s reader).
    profile_data: tuple | None = field(default=None, compare=False, repr=False)
    #: ``kind = "crg"``: the OpenCRG file (absolute once loaded), the tractor's centre line left of
    #: the road's reference line (m), where the driven part starts (m), NaN filled as OpenCRG does.
    file: Path | None = None
    lateral_offset_m: float = 0.0
    start_m: float = 0.0
    fill_missing: bool = False
    #: The road of ``file`` as read (:class:`tyrelab.vehicle.crg.CrgData`, :func:`parse_scenario`'s reader).
    crg_data: object | None = field(default=None, compare=False, repr=False)

    def wheel_positions(self, tractor: "TractorSpec") -> dict:
        """``kind = "crg"``: ``v`` (m) of each wheel's line on the road (:func:`tyrelab.vehicle.crg.wheel_positions`)."""
        from ..crg import wheel_positions

        three_d = tractor.three_d
        return wheel_positions(self.lateral_offset_m, tractor.front_track_m if three_d else None,
                               tractor.rear_track_m if three_d else None)


@dataclass(frozen=True)
class ExposureSpec:
    """``[exposure]``: speeds (km/h) and daily exposure time (h).

    ``list_speeds_km_h`` are the file's own speeds, which per-speed tyre values
    refer to (they stay when ``speeds_km_h`` is overridden on the command line).
    """

    speeds_km_h: tuple[float, ...]
    hours_per_day: float = 8.0
    list_speeds_km_h: tuple[float, ...] = ()
    #: ``working_speed_km_h`` as given (None: the middle speed; :attr:`working_speed`).
    working_speed_km_h: float | None = None

    def __post_init__(self):
        if not self.list_speeds_km_h:
            object.__setattr__(self, "list_speeds_km_h", tuple(self.speeds_km_h))

    @property
    def working_speed(self) -> float:
        """The speed the tractor works at, km/h: ``working_speed_km_h`` when it is one of the speeds
        run, else the middle one of the sorted speeds (the lower middle for an even count)."""
        speeds = sorted(self.speeds_km_h)
        if self.working_speed_km_h is not None and self.working_speed_km_h in speeds:
            return float(self.working_speed_km_h)
        return float(speeds[(len(speeds) - 1) // 2])

    @property
    def working_speed_source(self) -> str:
        """Why :attr:`working_speed` is what it is (said on the pages)."""
        if self.working_speed_km_h is not None and self.working_speed_km_h in self.speeds_km_h:
            return "[exposure] working_speed_km_h"
        if self.working_speed_km_h is not None:
            return (f"the middle speed ([exposure] working_speed_km_h = {self.working_speed_km_h:g} km/h is not "
                    "among the speeds run)")
        return "the middle speed (no [exposure] working_speed_km_h)"


@dataclass(frozen=True)
class SimulationSpec:
    """``[simulation]``: record-length cap (s), tyre lift-off and how the rows are computed
    (``method``: ``"auto"``, ``"time"`` or ``"spectral"``; :mod:`tyrelab.vehicle.spectral_ride`)."""

    duration_s: float | None = None
    lift_off: bool = True
    method: str = "auto"


@dataclass(frozen=True)
class SweepSpec:
    """``[sweep]``: front and rear pressures (bar) to run every pair of; empty = the tyres' own."""

    front_pressures_bar: tuple[float, ...] = ()
    rear_pressures_bar: tuple[float, ...] = ()
    #: Any numeric scenario key (``"section.key"``) -> the values to run (every combination).
    keys: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Scenario:
    """A whole scenario file.

    Attributes
    ----------
    name : str
    tractor : TractorSpec
    seat : SeatSpec
    front, rear : TyreSpec
    front_axle, rear_axle : AxleSpec
    cab : CabSpec
    implement : ImplementSpec or None
    ballast : BallastSpec or None
    surface : SurfaceSpec
    exposure : ExposureSpec
    simulation : SimulationSpec
    sweep : SweepSpec
    path : Path or None
        The file read (None when built in memory).
    description : str
    """

    name: str
    tractor: TractorSpec
    front: TyreSpec
    rear: TyreSpec
    surface: SurfaceSpec
    exposure: ExposureSpec
    seat: SeatSpec = field(default_factory=SeatSpec)
    simulation: SimulationSpec = field(default_factory=SimulationSpec)
    sweep: SweepSpec = field(default_factory=SweepSpec)
    path: Path | None = None
    description: str = ""
    front_axle: AxleSpec = field(default_factory=AxleSpec)
    rear_axle: AxleSpec = field(default_factory=AxleSpec)
    cab: CabSpec = field(default_factory=CabSpec)
    implement: ImplementSpec | None = None
    ballast: BallastSpec | None = None
    #: The parsed TOML and the folder its paths are relative to (for :func:`with_values`).
    doc: dict = field(default_factory=dict, repr=False, compare=False)
    base_dir: Path | None = field(default=None, repr=False, compare=False)

    def parts(self, tyres: dict[str, dict]) -> Parts:
        """The scenario's tractor as model parts in SI: the one place its kN, kN s and kN m values
        become N, N s and N m (:func:`tyrelab.vehicle.units.from_kilo`).

        ``tyres``: ``front``/``rear`` -> one tyre's ``stiffness_N_per_m``, ``damping_N_s_per_m``,
        ``radius_m`` and, with lateral elements (issue 33), ``lateral_stiffness_N_per_m``,
        ``lateral_damping_N_s_per_m`` (:func:`tyrelab.vehicle.ride.build_parts` gives them at a
        speed). The rear tyres carry the longitudinal element; without
        ``tractor.roll_inertia_kg_m2`` the parts are the pitch-plane tractor's.
        """
        t = self.tractor
        lon = t.longitudinal_model
        kx = from_kilo(t.longitudinal_stiffness_kN_per_m) if lon != "none" else 0.0
        cx = from_kilo(t.longitudinal_damping_kN_s_per_m) if lon != "none" else 0.0
        if lon == "maxwell" and not (kx > 0 and cx > 0):
            lon = "none"  # a Maxwell element without spring or damper carries no force
        lon_c2 = tyres["rear"].get("longitudinal_series_damping_N_s_per_m", math.inf) if lon == "rolling" else math.inf

        def axle(name: str, ahead: float, spec: AxleSpec, track_m, **extra) -> Axle:
            ty = tyres[name]
            kw = {}
            if spec.mount != "rigid":
                kw["roll_inertia_kg_m2"] = spec.roll_inertia_kg_m2 or 0.0
            if ty.get("lateral_stiffness_N_per_m") is not None:  # issue 33: the tyres' lateral elements
                kw.update(lateral_model=t.lateral_model, lateral_stiffness_N_per_m=ty["lateral_stiffness_N_per_m"],
                          lateral_damping_N_s_per_m=ty["lateral_damping_N_s_per_m"],
                          lateral_series_damping_N_s_per_m=ty.get("lateral_series_damping_N_s_per_m", math.inf))
                if spec.mount == "pivot":  # the pivot at the axle centre, a rolling radius above the ground
                    kw["height_m"] = spec.height_m if spec.height_m is not None else ty["radius_m"]
            if spec.mount == "suspended":
                kw.update(mass_kg=spec.mass_kg, height_m=spec.height_m if spec.height_m is not None else ty["radius_m"],
                          suspension_stiffness_N_per_m=from_kilo(spec.suspension_stiffness_kN_per_m),
                          suspension_damping_N_s_per_m=from_kilo(spec.suspension_damping_kN_s_per_m))
            return Axle(name, ahead, ty["stiffness_N_per_m"], ty["damping_N_s_per_m"], track_m=track_m or 0.0,
                        mount=spec.mount, **kw, **extra)

        cab = None
        if self.cab.mount == "suspended":
            c = self.cab
            cab = Cab(c.mass_kg, c.pitch_inertia_kg_m2, c.roll_inertia_kg_m2 or 0.0, c.ahead_of_cg_m,
                      c.height_above_cg_m, c.front_mount_ahead_of_cg_m, c.rear_mount_ahead_of_cg_m, c.mount_track_m,
                      from_kilo(c.mount_stiffness_kN_per_m), from_kilo(c.mount_damping_kN_s_per_m))
        imp = None
        if self.implement is not None:
            m = self.implement
            imp = Implement(m.mass_kg, m.pitch_inertia_kg_m2, m.roll_inertia_kg_m2, m.behind_rear_axle_m, m.height_m,
                            m.mount, m.hitch_behind_rear_axle_m, m.hitch_height_m,
                            from_kilo(m.hitch_stiffness_kN_m_per_rad or 0.0),
                            from_kilo(m.hitch_damping_kN_m_s_per_rad))
        return Parts(
            Chassis(t.mass_kg, t.pitch_inertia_kg_m2, t.cg_height_m, t.roll_inertia_kg_m2, t.yaw_inertia_kg_m2),
            axle("front", t.front_distance_m, self.front_axle, t.front_track_m),
            axle("rear", -t.rear_distance_m, self.rear_axle, t.rear_track_m, longitudinal_model=lon,
                 longitudinal_stiffness_N_per_m=kx, longitudinal_damping_N_s_per_m=cx,
                 longitudinal_series_damping_N_s_per_m=lon_c2),
            self.seat.part(), cab, imp, self.ballast, static_load_moment=True)
