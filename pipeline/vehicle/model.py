"""The tractor as parts that assemble themselves (issues 23, 35).

A tractor is a list of parts (:class:`Chassis`, two :class:`Axle`, optional :class:`Cab`,
:class:`Implement` and :class:`Ballast`, the seat :class:`SeatPoint`), in the shape of
Project Chrono's vehicle module (chassis, axles with a suspension and left/right wheels,
tyres, attachments, each subsystem initialising itself). :func:`assemble` hands every part
a :class:`Builder` twice: :meth:`Part.declare` asks for the coordinates the part moves on,
:meth:`Part.contribute` adds its bodies (mass and inertia on rows of the coordinates), its
force elements (:mod:`tyrelab.vehicle.elements`: each a row ``g`` over the coordinates, its
deformation ``δ = g·q (+ u)``) and its outputs. The result is one :class:`Assembly` with one
state layout (:class:`tyrelab.vehicle.elements.StateLayout`), which every solution path reads:

* :meth:`Assembly.linear` — ``x' = A x + B w``, ``y = C x + D w`` with named states,
  inputs and outputs (the exact first-order-hold path, the frequency domain);
* :meth:`Assembly.undamped` — stiffness and mass matrices of the undamped eigenproblem
  (the bounce/pitch frequencies of thesis ch. 8, the roll modes);
* the nonlinear right-hand side of :mod:`tyrelab.vehicle.tractor` (RK4 across lift-off), on
  the same states, from the same element rows.

How to add a part kind
----------------------
Write one frozen dataclass with ``declare(builder)`` and ``contribute(builder)`` (and
``check(three_d)`` for its rules) and hand it to :func:`assemble` in ``Parts.extra``; no
solver changes. A front-linkage implement on a spring, say::

    @dataclass(frozen=True)
    class FrontWeight(Part):
        mass_kg: float
        ahead_of_cg_m: float
        stiffness_N_per_m: float
        damping_N_s_per_m: float

        def declare(self, b):
            b.coordinate("front_weight_z")

        def contribute(self, b):
            at = b.chassis_point(self.ahead_of_cg_m, 0.0, 0.0)
            own = {"z": b.row({"front_weight_z": 1.0}), "x": at["x"], "y": at["y"]}
            b.body(self.mass_kg, 0.0, 0.0, own, None, b.pitch_row)
            b.element(SpringDamper("front_weight", own["z"] - at["z"], self.stiffness_N_per_m,
                                   self.damping_N_s_per_m))

A new element kind (a lateral tyre element) is a subclass of
:class:`tyrelab.vehicle.elements.Element` (see that module); a new chassis freedom (lateral
``y``, yaw) is a name added to :data:`CHASSIS_FREEDOMS` (after the existing ones, so the
existing models keep their coordinates' order and their numbers to the bit).

Kinematics (small angles, SI): ``x`` forward, ``y`` left, ``z`` up from the tractor's centre
of gravity (CG); pitch ``θ`` nose up, roll ``φ`` left side up. A point ``(p_x, p_y, p_z)``
of the chassis moves by ``dz = z + p_x θ + p_y φ``, ``dx = x - p_z θ``, ``dy = -p_z φ``.

Coordinates: chassis ``z``, ``th``, ``x`` (with a longitudinal element), ``phi`` (with a
roll inertia: the 3-D model); a pivot axle ``<axle>_axle_roll``; a suspended axle
``<axle>_axle_z`` (and its roll in 3-D); a suspended cab ``cab_z``, ``cab_th`` (``cab_phi``);
an implement on a hitch spring ``implement_th``. States are the positions the springs
see, then all velocities (``v`` + name), then the elements' own states (a Maxwell element's
spring extension, ``q``, or ``q_<element>`` for more than one): a coordinate no spring sees
carries only its velocity (the fore-aft ``x`` with a Maxwell element or a damper alone).

Mass: ``Chassis`` mass and inertias are the whole tractor's (rigid cab and axles
included); a suspended axle or cab is taken out of it where it sits (its own mass and
inertia moving on its own coordinates instead), so switching a part from rigid to
suspended keeps the tractor's mass, CG and inertia. An implement and a front ballast are
added to the tractor.

The seat suspension (:class:`SeatSuspension`, on :class:`SeatPoint`) is base-excited with no
feedback on the tractor (thesis ch. 7): a linear filter the seat point's vertical output
passes through, :attr:`Assembly.output_filters`, which the time and frequency domains apply.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np
from scipy import signal

from .. import _validate
from .elements import Element, Maxwell, Rolling, SpringDamper, StateLayout, StaticLoadMoment, Tyre, element
from .units import STANDARD_GRAVITY_M_S2
from .units import STANDARD_GRAVITY_M_S2 as GRAVITY_M_S2  # noqa: F401  (the name of issue 35)

__all__ = ["Chassis", "Axle", "Cab", "Implement", "Ballast", "SeatPoint", "SeatSuspension", "Parts", "Part",
           "Builder", "Element", "Assembly", "LinearModel", "assemble", "coordinate_output", "AXLE_MOUNTS",
           "LONGITUDINAL_MODELS", "LATERAL_MODELS", "CHASSIS_FREEDOMS", "needs", "scenario_key", "pivot_problem",
           "cab_mount_problems"]

#: How an axle is carried (:class:`Axle`).
AXLE_MOUNTS = ("rigid", "pivot", "suspended")
#: Longitudinal element of an axle's tyres: none, Kelvin-Voigt (parallel), Maxwell (series), the
#: rolling tyre (a Kelvin-Voigt unit in series with ``c₂ = a / v``, issue 42).
LONGITUDINAL_MODELS = ("none", "kelvin_voigt", "maxwell", "rolling")
#: Lateral element of a tyre at its contact patch (issue 33): none, Kelvin-Voigt, Maxwell, rolling (issue 42).
LATERAL_MODELS = ("none", "kelvin_voigt", "maxwell", "rolling")
#: The chassis' freedoms, in the order they are coordinates (those some part asks for): lateral
#: ``y`` and yaw ``psi`` (nose left) with lateral tyre elements (issue 33).
CHASSIS_FREEDOMS = ("z", "th", "x", "phi", "y", "psi")


def needs(part: str, mount: str = "rigid", three_d: bool = False) -> tuple[str, ...]:
    """The fields a part kind needs given for its ``mount`` (and the 3-D model or not): the one
    place of these rules (issue 35). The model refuses such a field that is not a finite number,
    or not positive where it is a mass, inertia, stiffness or track (:meth:`Part.check`); a
    scenario file refuses a missing key (:mod:`tyrelab.vehicle.scenario`, its keys
    :func:`scenario_key`).

    Examples
    --------
    >>> needs("axle", "suspended", three_d=True)
    ('roll_inertia_kg_m2', 'mass_kg', 'suspension_stiffness_N_per_m')
    >>> needs("implement", "hitch_spring")
    ('mass_kg', 'behind_rear_axle_m', 'height_m', 'hitch_stiffness_N_m_per_rad')
    """
    kinds = ("axle", "cab", "implement", "ballast")
    if part not in kinds:
        raise ValueError(f"part {part!r}: expected one of {kinds}")
    out: tuple[str, ...] = ()
    if part == "axle":
        if mount in ("pivot", "suspended") and three_d:
            out += ("roll_inertia_kg_m2",)
        if mount == "suspended":
            out += ("mass_kg", "suspension_stiffness_N_per_m")
    elif part == "cab" and mount == "suspended":
        out += ("mass_kg", "pitch_inertia_kg_m2", "front_mount_ahead_of_cg_m", "rear_mount_ahead_of_cg_m",
                "mount_track_m", "mount_stiffness_N_per_m") + (("roll_inertia_kg_m2",) if three_d else ())
    elif part in ("implement", "ballast"):
        out += ("mass_kg", "behind_rear_axle_m" if part == "implement" else "ahead_of_front_axle_m", "height_m")
        if part == "implement" and mount == "hitch_spring":
            out += ("hitch_stiffness_N_m_per_rad",)
    return out


def scenario_key(field_name: str) -> str:
    """A part field's key in a scenario file: stiffness and damping in kN (``_N_`` -> ``_kN_``).

    Examples
    --------
    >>> scenario_key("hitch_stiffness_N_m_per_rad"), scenario_key("mass_kg")
    ('hitch_stiffness_kN_m_per_rad', 'mass_kg')
    """
    if not isinstance(field_name, str) or not field_name:
        raise ValueError(f"field_name must be a part field's name (text), got {field_name!r}")
    return field_name.replace("_N_", "_kN_")


def pivot_problem(section: str) -> str:
    """Why a pivot axle needs the 3-D model (the model and the scenario file say it so)."""
    return (f"{section}.mount = \"pivot\" needs the roll model (tractor.roll_inertia_kg_m2): a pivot axle only "
            "differs from a rigid one in roll")


def cab_mount_problems(front_mount_ahead_of_cg_m: float, rear_mount_ahead_of_cg_m: float) -> list[str]:
    """A suspended cab's front mounts must be ahead of its rear mounts (m ahead of the CG)."""
    if front_mount_ahead_of_cg_m > rear_mount_ahead_of_cg_m:
        return []
    return [f"cab.front_mount_ahead_of_cg_m ({front_mount_ahead_of_cg_m} m) must be ahead of "
            f"cab.rear_mount_ahead_of_cg_m ({rear_mount_ahead_of_cg_m} m)"]


def _needed_problems(section: str, part, kind: str, mount: str, three_d: bool) -> list[str]:
    """:func:`needs` checked on a part's values."""
    out = []
    for name in needs(kind, mount, three_d):
        value = getattr(part, name)
        if name.endswith(("_kg", "_kg_m2", "_N_per_m", "_N_m_per_rad", "track_m")):
            out += _positive(f"{section}.{name}", value)
        elif isinstance(value, bool) or not isinstance(value, (int, float)) or not np.isfinite(value):
            out.append(f"{section}.{name} must be a finite number, got {value!r}")
    return out


class Part:
    """A part of the tractor: it asks for coordinates, then adds its bodies, elements, outputs."""

    def check(self, three_d: bool) -> list[str]:
        """Problems with the part's numbers (one line each; none: fine)."""
        return []

    def declare(self, b: "Builder") -> None:
        """Ask ``b`` for the coordinates this part moves on (:meth:`Builder.freedom`,
        :meth:`Builder.coordinate`)."""

    def contribute(self, b: "Builder") -> None:
        """Add this part's bodies, force elements and outputs to ``b``."""


@dataclass(frozen=True)
class Chassis(Part):
    """The tractor body: whole-tractor mass and inertias about its CG (SI).

    ``roll_inertia_kg_m2`` None: the pitch-plane model (no roll; each axle's two tyres one
    element under the axle-mean input, as thesis ch. 7). Given: the 3-D model (roll,
    left and right tyres, per-wheel inputs).
    """

    mass_kg: float
    pitch_inertia_kg_m2: float
    cg_height_m: float
    roll_inertia_kg_m2: float | None = None
    #: Yaw inertia about the CG, kg m² (with lateral tyre elements; None: the pitch inertia, a
    #: documented stand-in: for a box ``I_yaw - I_pitch = m (W² - H²)/12``, small for a tractor
    #: about as wide as it is high).
    yaw_inertia_kg_m2: float | None = None

    def check(self, three_d: bool) -> list[str]:
        out = _positive("chassis.mass_kg", self.mass_kg) + _positive("chassis.pitch_inertia_kg_m2",
                                                                        self.pitch_inertia_kg_m2)
        if self.yaw_inertia_kg_m2 is not None:
            out += _positive("chassis.yaw_inertia_kg_m2", self.yaw_inertia_kg_m2)
        return out + (_positive("chassis.roll_inertia_kg_m2", self.roll_inertia_kg_m2) if three_d else [])

    def declare(self, b: "Builder") -> None:
        b.freedom("z")
        b.freedom("th")
        if b.three_d:
            b.freedom("phi")

    def contribute(self, b: "Builder") -> None:
        # its own rows written out so the diagonal is exactly m, I
        b.set_diagonal("z", self.mass_kg)
        b.set_diagonal("th", self.pitch_inertia_kg_m2)
        if "x" in b.coordinates:
            b.set_diagonal("x", self.mass_kg)
        if b.three_d:
            b.set_diagonal("phi", self.roll_inertia_kg_m2)
        if "y" in b.coordinates:
            b.set_diagonal("y", self.mass_kg)
            b.set_diagonal("psi", self.yaw_inertia_kg_m2 if self.yaw_inertia_kg_m2 is not None
                           else self.pitch_inertia_kg_m2)
        b.weight[b.coordinates.index("z")] = self.mass_kg
        b.output("vertical_m_s2", b.row({"z": 1.0}))
        b.output("pitch_rad_s2", b.row({"th": 1.0}))
        b.output("longitudinal_m_s2", b.row({"x": 1.0}) if "x" in b.coordinates else np.zeros(b.n))
        if b.three_d:
            b.output("roll_rad_s2", b.row({"phi": 1.0}))
        if "y" in b.coordinates:
            b.output("lateral_m_s2", b.row({"y": 1.0}))
            b.output("yaw_rad_s2", b.row({"psi": 1.0}))
        b.seat_frame = (b.chassis_point, b.pitch_row, b.roll_row)


@dataclass(frozen=True)
class Axle(Part):
    """One axle and its two tyres (per tyre: stiffness N/m, damping N s/m).

    Attributes
    ----------
    name : str
        ``"front"`` or ``"rear"``.
    ahead_of_cg_m : float
        Axle position ahead of the CG, m (negative behind).
    tyre_stiffness_N_per_m, tyre_damping_N_s_per_m : float
        Vertical Kelvin-Voigt element of one tyre.
    track_m : float
        Wheel centre to wheel centre, m (3-D only).
    mount : str
        ``rigid`` (bolted to the chassis), ``pivot`` (follows the chassis vertically and in
        pitch at the axle, rolls freely about a longitudinal pivot: passes no roll moment) or
        ``suspended`` (a pivot axle on a spring/damper to the chassis, with its own mass).
    roll_inertia_kg_m2 : float
        Pivot or suspended axle: roll inertia about the pivot (axle centre), kg m².
    mass_kg, height_m : float
        Suspended axle: its mass (part of the tractor's) and the height of its centre
        above the ground, m.
    suspension_stiffness_N_per_m, suspension_damping_N_s_per_m : float
        Suspended axle: the spring and damper between axle and chassis (both sides together).
    longitudinal_model : str
        Fore-aft element of the axle's tyres at the ground contact, :data:`LONGITUDINAL_MODELS`.
    longitudinal_stiffness_N_per_m, longitudinal_damping_N_s_per_m : float
        Per tyre.
    lateral_model : str
        Lateral element of each tyre at its contact patch (3-D), :data:`LATERAL_MODELS`: acts while
        its tyre is on the ground; on a pivot or suspended axle it acts on the axle, whose centre
        (``height_m`` above the ground) passes it to the chassis.
    lateral_stiffness_N_per_m, lateral_damping_N_s_per_m : float
        Per tyre.
    lateral_series_damping_N_s_per_m, longitudinal_series_damping_N_s_per_m : float
        The rolling element's series damper ``c₂`` per tyre at the speed, N s/m (``inf``: locked, a
        stationary tyre; :class:`~tyrelab.vehicle.elements.Rolling`).
    """

    name: str
    ahead_of_cg_m: float
    tyre_stiffness_N_per_m: float
    tyre_damping_N_s_per_m: float
    track_m: float = 0.0
    mount: str = "rigid"
    roll_inertia_kg_m2: float = 0.0
    mass_kg: float = 0.0
    height_m: float = 0.0
    suspension_stiffness_N_per_m: float = 0.0
    suspension_damping_N_s_per_m: float = 0.0
    longitudinal_model: str = "none"
    longitudinal_stiffness_N_per_m: float = 0.0
    longitudinal_damping_N_s_per_m: float = 0.0
    lateral_model: str = "none"
    lateral_stiffness_N_per_m: float = 0.0
    lateral_damping_N_s_per_m: float = 0.0
    lateral_series_damping_N_s_per_m: float = math.inf
    longitudinal_series_damping_N_s_per_m: float = math.inf

    def check(self, three_d: bool) -> list[str]:
        ax, out = self, []
        if ax.mount not in AXLE_MOUNTS:
            return [f"{ax.name}_axle.mount {ax.mount!r}: expected one of {AXLE_MOUNTS}"]
        if ax.longitudinal_model not in LONGITUDINAL_MODELS:
            return [f"longitudinal_model {ax.longitudinal_model!r}: expected one of {LONGITUDINAL_MODELS}"]
        if ax.lateral_model not in LATERAL_MODELS:
            return [f"lateral_model {ax.lateral_model!r}: expected one of {LATERAL_MODELS}"]
        if ax.lateral_model != "none":
            if not three_d:
                out.append(f"{ax.name}_axle.lateral_model = {ax.lateral_model!r} needs the roll model "
                           "(chassis roll_inertia_kg_m2)")
            out += _positive(f"{ax.name}_axle.lateral_stiffness_N_per_m", ax.lateral_stiffness_N_per_m)
            if ax.lateral_model == "maxwell":
                out += _positive(f"{ax.name}_axle.lateral_damping_N_s_per_m", ax.lateral_damping_N_s_per_m)
            if ax.lateral_model == "rolling":
                out += _series_problems(f"{ax.name}_axle.lateral_series_damping_N_s_per_m",
                                        ax.lateral_series_damping_N_s_per_m)
        if ax.longitudinal_model == "rolling":
            out += _series_problems(f"{ax.name}_axle.longitudinal_series_damping_N_s_per_m",
                                    ax.longitudinal_series_damping_N_s_per_m)
        out += _needed_problems(f"{ax.name}_axle", ax, "axle", ax.mount, three_d)
        if ax.mount == "pivot" and not three_d:
            out.append(pivot_problem(f"{ax.name}_axle"))
        if three_d:
            out += _positive(f"{ax.name}_axle.track_m", ax.track_m)
        return out

    def declare(self, b: "Builder") -> None:
        if self.longitudinal_model != "none":
            b.freedom("x")
        if self.lateral_model != "none" and b.three_d:
            b.freedom("y")
            b.freedom("psi")
        if self.mount == "suspended":
            b.coordinate(f"{self.name}_axle_z")
        if self.mount != "rigid" and b.three_d:
            b.coordinate(f"{self.name}_axle_roll")

    def contribute(self, b: "Builder") -> None:
        ax, n, three_d, h, row = self, b.n, b.three_d, b.cg_height_m, b.row
        a = float(ax.ahead_of_cg_m)
        sides = (("left", 0.5 * ax.track_m), ("right", -0.5 * ax.track_m)) if three_d else ((None, 0.0),)
        ax_h = float(ax.height_m) - h  # axle centre relative to the CG
        if ax.mount == "suspended":
            zc = f"{ax.name}_axle_z"
            at_body = b.chassis_point(a, 0.0, ax_h)
            moving = {"z": row({zc: 1.0}), "x": at_body["x"], "y": at_body["y"]}
            aroll = row({f"{ax.name}_axle_roll": 1.0}) if three_d else None
            b.body(ax.mass_kg, ax.roll_inertia_kg_m2, 0.0, moving, aroll, b.pitch_row)
            b.body(ax.mass_kg, 0.0, 0.0, at_body, None, b.pitch_row, sign=-1.0)  # taken out of the chassis
            b.element(SpringDamper(f"{ax.name}_suspension", row({zc: 1.0}) - at_body["z"],
                                   float(ax.suspension_stiffness_N_per_m), float(ax.suspension_damping_N_s_per_m)))
        elif ax.mount == "pivot":
            b.body(0.0, ax.roll_inertia_kg_m2, 0.0, {k: np.zeros(n) for k in "zxy"},
                   row({f"{ax.name}_axle_roll": 1.0}), np.zeros(n))
        names = []
        for side, py in sides:
            name = ax.name if side is None else f"{ax.name}_{side}"
            if ax.mount == "rigid":
                jz = b.chassis_point(a, py, -h)["z"]
            elif ax.mount == "pivot":
                jz = row({"z": 1.0, "th": a, f"{ax.name}_axle_roll": py})
            else:
                jz = row({f"{ax.name}_axle_z": 1.0, f"{ax.name}_axle_roll": py})
            per = 1.0 if three_d else 2.0  # pitch-plane: the axle's two tyres in one element
            b.element(Tyre(name, -jz, per * float(ax.tyre_stiffness_N_per_m), per * float(ax.tyre_damping_N_s_per_m)))
            names.append(name)
            if ax.lateral_model != "none" and three_d:
                self._lateral(b, name, a, py, ax_h)
        if ax.longitudinal_model != "none":
            # fore-aft of the axle's ground contact, h below the CG: d = x + h θ
            per = 2.0
            b.element(element(f"{ax.name}_longitudinal", b.chassis_point(a, 0.0, -h)["x"],
                              per * float(ax.longitudinal_stiffness_N_per_m),
                              per * float(ax.longitudinal_damping_N_s_per_m), ax.longitudinal_model, tuple(names),
                              series_damping=per * float(ax.longitudinal_series_damping_N_s_per_m)))
            rolling = f"{ax.name}_longitudinal" if ax.longitudinal_model == "rolling" else None
            for name in names:  # the static loads' pitch moment, -F x (issue 33); at the contact point (issue 42)
                b.static_load_moment(name, b.pitch_row, b.row({"x": 1.0}), contact=rolling)

    def _lateral(self, b: "Builder", name: str, a: float, py: float, ax_h: float) -> None:
        """The lateral element of tyre ``name`` at its contact patch and its static load's roll moment.

        Rigid axle: the patch is the chassis point ``(a, py, -h)``, lateral ``y + h φ + a ψ``; the
        static load ``F`` turns the chassis by ``-F y`` (the patch stays on the ground, the CG moves
        by ``y``). Pivot or suspended axle: the patch is ``r = height_m`` below the axle centre,
        lateral ``y_c + r α`` (``y_c`` the centre's, ``α`` the axle's roll); the load turns the axle
        by ``-F y_c`` about its centre and reaches the chassis at the centre: ``F (y_c - y)``.
        """
        ax, row = self, b.row
        if ax.mount == "rigid":
            jy = b.chassis_point(a, py, -b.cg_height_m)["y"]
        else:
            centre = b.chassis_point(a, 0.0, ax_h)["y"]
            jy = centre + float(ax.height_m) * row({f"{ax.name}_axle_roll": 1.0})
        b.element(element(f"{name}_lateral", jy, float(ax.lateral_stiffness_N_per_m),
                          float(ax.lateral_damping_N_s_per_m), ax.lateral_model, (name,),
                          series_damping=float(ax.lateral_series_damping_N_s_per_m)))
        # the rolling tyre's static load acts at its contact point, which moves (issue 42): -F (y - s)
        rolling = f"{name}_lateral" if ax.lateral_model == "rolling" else None
        if ax.mount == "rigid":
            b.static_load_moment(name, b.roll_row, row({"y": 1.0}), contact=rolling)
        else:
            b.static_load_moment(name, row({f"{ax.name}_axle_roll": 1.0}), centre, contact=rolling)
            b.static_load_moment(name, b.roll_row, row({"y": 1.0}) - centre)


@dataclass(frozen=True)
class Cab(Part):
    """A suspended cab (a rigid cab is part of the chassis): mass and inertias about its CG,
    its CG ahead of / above the tractor's CG, and four mounts (front and rear row, each a
    pair ``mount_track_m`` apart; per mount stiffness and damping). SI."""

    mass_kg: float
    pitch_inertia_kg_m2: float
    roll_inertia_kg_m2: float
    ahead_of_cg_m: float
    height_above_cg_m: float
    front_mount_ahead_of_cg_m: float
    rear_mount_ahead_of_cg_m: float
    mount_track_m: float
    mount_stiffness_N_per_m: float
    mount_damping_N_s_per_m: float

    def check(self, three_d: bool) -> list[str]:
        out = _needed_problems("cab", self, "cab", "suspended", three_d)
        return out or cab_mount_problems(self.front_mount_ahead_of_cg_m, self.rear_mount_ahead_of_cg_m)

    def declare(self, b: "Builder") -> None:
        b.coordinate("cab_z")
        b.coordinate("cab_th")
        if b.three_d:
            b.coordinate("cab_phi")

    def contribute(self, b: "Builder") -> None:
        cab, row, three_d = self, b.row, b.three_d
        cx, cz = float(cab.ahead_of_cg_m), float(cab.height_above_cg_m)
        cab_roll = row({"cab_phi": 1.0}) if three_d else None

        def cab_point(px, py, pz) -> dict:
            """A cab point relative to the tractor CG: the cab's own vertical, pitch and roll; fore-aft
            and lateral as the chassis at the cab CG (stiff mounts) plus the cab's rotation."""
            at = b.chassis_point(cx, 0.0, cz)
            return {"z": row({"cab_z": 1.0, "cab_th": px - cx, "cab_phi": py}),
                    "x": at["x"] + row({"cab_th": -(pz - cz)}), "y": at["y"] + row({"cab_phi": -(pz - cz)})}

        b.body(cab.mass_kg, cab.roll_inertia_kg_m2, cab.pitch_inertia_kg_m2, cab_point(cx, 0.0, cz), cab_roll,
               row({"cab_th": 1.0}))
        b.body(cab.mass_kg, cab.roll_inertia_kg_m2, cab.pitch_inertia_kg_m2, b.chassis_point(cx, 0.0, cz), b.roll_row,
               b.pitch_row, sign=-1.0)
        for where, mx in (("front", cab.front_mount_ahead_of_cg_m), ("rear", cab.rear_mount_ahead_of_cg_m)):
            for side, py in ((("left", 0.5 * cab.mount_track_m), ("right", -0.5 * cab.mount_track_m)) if three_d
                             else ((None, 0.0),)):
                per = 1.0 if three_d else 2.0
                g = cab_point(mx, py, cz)["z"] - b.chassis_point(mx, py, cz)["z"]
                b.element(SpringDamper(f"cab_{where}_mount" + (f"_{side}" if side else ""), g,
                                       per * cab.mount_stiffness_N_per_m, per * cab.mount_damping_N_s_per_m))
        b.seat_frame = (cab_point, row({"cab_th": 1.0}), cab_roll)


@dataclass(frozen=True)
class Implement(Part):
    """A mounted implement on the rear hitch: mass, inertias about its CG, CG behind the rear
    axle and above the ground (m). ``mount = "rigid"`` or ``"hitch_spring"`` (pitching about
    the hitch point, ``hitch_behind_rear_axle_m`` behind the rear axle at ``hitch_height_m``,
    on a rotational spring/damper to the chassis: hitch damping)."""

    mass_kg: float
    pitch_inertia_kg_m2: float
    roll_inertia_kg_m2: float
    behind_rear_axle_m: float
    height_m: float
    mount: str = "rigid"
    hitch_behind_rear_axle_m: float = 0.0
    hitch_height_m: float = 0.0
    hitch_stiffness_N_m_per_rad: float = 0.0
    hitch_damping_N_m_s_per_rad: float = 0.0

    def check(self, three_d: bool) -> list[str]:
        if self.mount not in ("rigid", "hitch_spring"):
            return [f"implement.mount {self.mount!r}: expected one of ('rigid', 'hitch_spring')"]
        return _needed_problems("implement", self, "implement", self.mount, three_d)

    def declare(self, b: "Builder") -> None:
        if self.mount == "hitch_spring":
            b.coordinate("implement_th")

    def contribute(self, b: "Builder") -> None:
        imp, row, h = self, b.row, b.cg_height_m
        rear_x = float(b.parts.rear.ahead_of_cg_m)
        ix, iz = rear_x - float(imp.behind_rear_axle_m), float(imp.height_m) - h
        if imp.mount == "rigid":
            b.body(imp.mass_kg, imp.roll_inertia_kg_m2, imp.pitch_inertia_kg_m2, b.chassis_point(ix, 0.0, iz),
                   b.roll_row, b.pitch_row)
            return
        hx, hz = rear_x - float(imp.hitch_behind_rear_axle_m), float(imp.hitch_height_m) - h
        hitch = b.chassis_point(hx, 0.0, hz)
        ith = row({"implement_th": 1.0})
        rows = {"z": hitch["z"] + (ix - hx) * ith, "x": hitch["x"] - (iz - hz) * ith,
                "y": b.chassis_point(ix, 0.0, iz)["y"]}
        b.body(imp.mass_kg, imp.roll_inertia_kg_m2, imp.pitch_inertia_kg_m2, rows, b.roll_row, ith)
        b.element(SpringDamper("hitch", ith - b.pitch_row, float(imp.hitch_stiffness_N_m_per_rad),
                               float(imp.hitch_damping_N_m_s_per_rad)))


@dataclass(frozen=True)
class Ballast(Part):
    """Front ballast: a rigid mass ahead of the front axle (m) at a height above the ground."""

    mass_kg: float
    ahead_of_front_axle_m: float
    height_m: float
    pitch_inertia_kg_m2: float = 0.0
    roll_inertia_kg_m2: float = 0.0

    def check(self, three_d: bool) -> list[str]:
        return _needed_problems("ballast", self, "ballast", "rigid", three_d)

    def contribute(self, b: "Builder") -> None:
        bl = self
        b.body(bl.mass_kg, bl.roll_inertia_kg_m2, bl.pitch_inertia_kg_m2,
               b.chassis_point(float(b.parts.front.ahead_of_cg_m) + float(bl.ahead_of_front_axle_m), 0.0,
                               float(bl.height_m) - b.cg_height_m), b.roll_row, b.pitch_row)


@dataclass(frozen=True)
class SeatSuspension(Part):
    """A linear seat suspension: base-excited single-DOF (spring and damper under the seat and
    its occupant), no feedback on the tractor (thesis ch. 7), so a filter on the seat point's
    vertical acceleration: ``T(s) = (2 ζ ω s + ω²) / (s² + 2 ζ ω s + ω²)``, ``ω = 2π f_n``."""

    natural_frequency_Hz: float
    damping_ratio: float

    def check(self, three_d: bool) -> list[str]:
        z = self.damping_ratio
        bad = not isinstance(z, (int, float)) or isinstance(z, bool) or not (np.isfinite(z) and z >= 0)
        return (_positive("seat.natural_frequency_Hz", self.natural_frequency_Hz)
                + ([f"seat.damping_ratio must be finite and non-negative, got {z!r}"] if bad else []))

    def linear(self) -> "LinearModel":
        """The filter as a :class:`LinearModel` (:func:`scipy.signal.tf2ss` of ``T``): input the
        seat base's vertical acceleration (m/s²), output the seat's (m/s²).

        Examples
        --------
        >>> lm = SeatSuspension(1.0, 0.5).linear()
        >>> lm.inputs, lm.outputs, lm.d.tolist()
        (('seat_base_m_s2',), ('seat_m_s2',), [[0.0]])
        """
        problems = self.check(False)
        if problems:
            raise ValueError("; ".join(problems))
        wn = 2 * np.pi * float(self.natural_frequency_Hz)
        z = float(self.damping_ratio)
        a, b, c, d = signal.tf2ss([2 * z * wn, wn**2], [1.0, 2 * z * wn, wn**2])
        return LinearModel(a, b, c, d, ("seat_s1", "seat_s2"), ("seat_base_m_s2",), ("seat_m_s2",))

    def contribute(self, b: "Builder") -> None:
        b.output_filters["seat_vertical_m_s2"] = self


@dataclass(frozen=True)
class SeatPoint(Part):
    """The seat reference point relative to the tractor CG (m): ahead, left, above; on the cab
    when the cab is suspended, else on the chassis; and its suspension (None: rigid)."""

    ahead_of_cg_m: float = 0.0
    left_of_cg_m: float = 0.0
    height_above_cg_m: float = 0.0
    suspension: SeatSuspension | None = None

    def check(self, three_d: bool) -> list[str]:
        return self.suspension.check(three_d) if self.suspension is not None else []

    def contribute(self, b: "Builder") -> None:
        point, tilt_x, tilt_y = b.seat_frame
        rows = point(self.ahead_of_cg_m, self.left_of_cg_m, self.height_above_cg_m)
        b.output("seat_vertical_m_s2", rows["z"])
        b.output("seat_longitudinal_m_s2", rows["x"])
        b.output("seat_longitudinal_tilt_m_s2", rows["x"], tilt_x)
        if b.three_d:
            b.output("seat_lateral_m_s2", rows["y"])
            b.output("seat_lateral_tilt_m_s2", rows["y"], tilt_y)
        if self.suspension is not None:
            self.suspension.contribute(b)


@dataclass(frozen=True)
class Parts:
    """Everything :func:`assemble` reads: the tractor's parts, then any ``extra`` part kinds
    (each a :class:`Part`, contributed after the seat)."""

    chassis: Chassis
    front: Axle
    rear: Axle
    seat: SeatPoint = field(default_factory=SeatPoint)
    cab: Cab | None = None
    implement: Implement | None = None
    ballast: Ballast | None = None
    extra: tuple = ()
    #: The static tyre loads' moment where tyres have a horizontal element (issue 33): roll with
    #: lateral elements, pitch with longitudinal ones. False for the thesis' studies (ch. 7-8 keep
    #: the thesis' equations); the ride scenarios set it.
    static_load_moment: bool = False

    @property
    def three_d(self) -> bool:
        """Roll (and left/right tyres) modelled."""
        return self.chassis.roll_inertia_kg_m2 is not None

    def members(self) -> list[Part]:
        """The parts in the order they contribute (the coordinates' and elements' order)."""
        return [p for p in (self.chassis, self.front, self.rear, self.cab, self.implement, self.ballast)
                if p is not None] + [self.seat, *self.extra]

    def problems(self) -> list[str]:
        """Every part's problems (:meth:`Part.check`), one line each."""
        return [m for p in self.members() for m in p.check(self.three_d)]


def _series_problems(name: str, value) -> list[str]:
    """A series damper ``c₂``: positive, ``inf`` allowed (locked)."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        return [f"{name} must be a number, got {value!r}"]
    return [] if v == math.inf else _positive(name, v)


def _positive(name: str, value) -> list[str]:
    try:
        _validate.positive(name, value)
    except (ValueError, TypeError) as exc:
        return [str(exc)]
    return []


@dataclass(frozen=True)
class LinearModel:
    """``x' = A x + B w``, ``y = C x + D w`` with named states, inputs and outputs."""

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray
    states: tuple[str, ...]
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]

    def select(self, outputs) -> "LinearModel":
        """The same system with only the outputs ``outputs`` (names), in that order."""
        rows = [self.outputs.index(o) for o in outputs]
        return LinearModel(self.a, self.b, self.c[rows], self.d[rows], self.states, self.inputs, tuple(outputs))

    @property
    def abcd(self):
        """``(A, B, C, D)``."""
        return self.a, self.b, self.c, self.d




class Builder:
    """What the parts are assembled on: :func:`assemble` hands it to each part twice.

    While declaring, :meth:`freedom` and :meth:`coordinate` name the coordinates; then
    (``coordinates``, ``n`` fixed) a part's :meth:`Part.contribute` reads the rows of points
    (:meth:`row`, :meth:`chassis_point`, ``pitch_row``, ``roll_row``, ``seat_frame``) and
    adds :meth:`body`, :meth:`element`, :meth:`output` and ``output_filters``. SI units.
    """

    def __init__(self, parts: Parts):
        self.parts = parts
        self.three_d = parts.three_d
        self.cg_height_m = float(parts.chassis.cg_height_m)
        self._freedoms: set[str] = set()
        self._own: list[str] = []
        self.coordinates: tuple[str, ...] = ()

    # ------------------------------------------------------------------ declaring
    def freedom(self, name: str) -> None:
        """Ask for a chassis freedom (:data:`CHASSIS_FREEDOMS`)."""
        if name not in CHASSIS_FREEDOMS:
            raise ValueError(f"freedom {name!r}: expected one of {CHASSIS_FREEDOMS}")
        self._freedoms.add(name)

    def coordinate(self, name: str) -> None:
        """Ask for a part's own coordinate (after the chassis', in the order asked)."""
        if name in self._own or name in CHASSIS_FREEDOMS:
            raise ValueError(f"coordinate {name!r} asked for twice")
        self._own.append(name)

    def _fix(self) -> None:
        self.coordinates = tuple([f for f in CHASSIS_FREEDOMS if f in self._freedoms] + self._own)
        n = self.n = len(self.coordinates)
        self.mass = np.zeros((n, n))
        self.weight = np.zeros(n)  # Σ m J_z: the generalised gravity force is -g times this
        self.elements: list[Element] = []
        self.outputs: dict = {}
        self.output_filters: dict = {}
        self.pitch_row = self.row({"th": 1.0})
        self.roll_row = self.row({"phi": 1.0}) if self.three_d else None
        self.seat_frame = None
        self.static_moments: list = []  # (tyre, freedom row, displacement row): issue 33

    # ------------------------------------------------------------------ contributing
    def row(self, coef: dict) -> np.ndarray:
        """A row over the coordinates from ``{coordinate: value}`` (unknown coordinates ignored)."""
        r = np.zeros(self.n)
        for k, v in coef.items():
            if k in self.coordinates:
                r[self.coordinates.index(k)] += v
        return r

    def chassis_point(self, px, py, pz) -> dict:
        """Rows (``z`` vertical, ``x`` fore-aft, ``y`` lateral) of a chassis point relative to the CG, m."""
        row = self.row
        return {"z": row({"z": 1.0, "th": px, "phi": py}), "x": row({"x": 1.0, "th": -pz, "psi": -py}),
                "y": row({"y": 1.0, "phi": -pz, "psi": px})}

    def set_diagonal(self, coordinate: str, value: float) -> None:
        """The mass matrix' diagonal entry of ``coordinate`` (the chassis: exactly its m, I)."""
        i = self.coordinates.index(coordinate)
        self.mass[i, i] = value

    def body(self, m, i_roll, i_pitch, rows: dict, roll_row, pitch_row, sign=1.0) -> None:
        """A rigid body of mass ``m`` (kg) and inertias (kg m²) whose CG moves by ``rows``
        (``z``, ``x``, ``y`` over the coordinates) and turns by ``roll_row``, ``pitch_row``;
        ``sign=-1`` takes it out (a part that moves on its own coordinates)."""
        for key in ("z", "x", "y"):
            self.mass += sign * m * np.outer(rows[key], rows[key])
        if roll_row is not None and i_roll:
            self.mass += sign * i_roll * np.outer(roll_row, roll_row)
        self.mass += sign * i_pitch * np.outer(pitch_row, pitch_row)
        self.weight += sign * m * rows["z"]

    def element(self, e: Element) -> None:
        """A force element (:mod:`tyrelab.vehicle.elements`); a :class:`~tyrelab.vehicle.elements.Tyre`
        is also a ground input, in the order added."""
        if any(x.name == e.name for x in self.elements):
            raise ValueError(f"element {e.name!r} added twice")
        self.elements.append(e)

    def static_load_moment(self, tyre: str, freedom_row: np.ndarray, displacement_row: np.ndarray,
                           contact: str | None = None) -> None:
        """The static load of ``tyre`` turns the part of ``freedom_row`` by minus the load times
        ``displacement_row · q`` (:class:`~tyrelab.vehicle.elements.StaticLoadMoment`; added by
        :func:`assemble` once the static loads are known, when ``Parts.static_load_moment``), less
        the contact point's displacement of the rolling element ``contact`` (issue 42)."""
        if self.parts.static_load_moment:
            self.static_moments.append((tyre, np.asarray(freedom_row, float), np.asarray(displacement_row, float),
                                        contact))

    def output(self, name: str, acceleration_row: np.ndarray, tilt_row: np.ndarray | None = None) -> None:
        """A kinematic output: ``acceleration_row · q''`` plus ``g · tilt_row · q`` (what a
        body-fixed accelerometer tilted by ``tilt_row`` reads), m/s² or rad/s²."""
        self.outputs[name] = (acceleration_row, tilt_row)


class Assembly:
    """The assembled tractor: coordinates, mass matrix, elements, output rows, static tyre loads,
    and its one state layout (:attr:`layout`).

    Built by :func:`assemble`; every solution path reads it (see the module docstring).
    """

    def __init__(self, coordinates, mass, elements, outputs, parts, weight, output_filters=None,
                 gravity_m_s2: float = STANDARD_GRAVITY_M_S2):
        self.coordinates = tuple(coordinates)
        #: Gravity the assembly was assembled under, m/s²: its static tyre loads (the lift-off
        #: floors), the ``*_tilt`` readings of :meth:`linear` and of the time-domain solver.
        self.gravity_m_s2 = float(gravity_m_s2)
        self.mass = mass
        self.elements = list(elements)
        self.kinematic_outputs = outputs  # name -> (row over q'' , row over q) (acceleration, gravity tilt)
        self.parts = parts
        self.output_filters = dict(output_filters or {})  # output -> SeatSuspension-like (.linear())
        self._weight_row = weight

    @property
    def tyres(self) -> tuple[str, ...]:
        """The tyre elements' names (their ground inputs in this order)."""
        return tuple(e.name for e in self.elements if e.input is not None)

    @property
    def inputs(self) -> tuple[str, ...]:
        """``u_<tyre>``, ``du_<tyre>`` (m, m/s) per tyre."""
        return tuple(x for t in self.tyres for x in (f"u_{t}", f"du_{t}"))

    @property
    def layout(self) -> StateLayout:
        """The state layout (positions a spring sees, velocities, the elements' own states)."""
        key = tuple((id(e), e.stiffness) for e in self.elements)
        if getattr(self, "_layout_key", None) != key:
            seen = np.any(self.stiffness_matrix() != 0, axis=0)
            for e in self.elements:  # positions a static load's moment reads (issue 33), its contact's (42)
                if isinstance(e, StaticLoadMoment):
                    seen |= np.asarray(e.d) != 0
                    if e.contact is not None and not e.contact.locked:
                        seen |= np.asarray(e.contact.g) != 0
            own = [s for e in self.elements for s in e.states()]
            self._layout, self._layout_key = StateLayout(self.coordinates, seen, own, self.inputs), key
        return self._layout

    # ----------------------------------------------------------------- helpers
    def row(self, coef: dict) -> np.ndarray:
        """A row over the coordinates from ``{coordinate: value}`` (unknown coordinates ignored)."""
        r = np.zeros(len(self.coordinates))
        for k, v in coef.items():
            if k in self.coordinates:
                r[self.coordinates.index(k)] += v
        return r

    def element(self, name: str) -> Element:
        """The element called ``name``."""
        return next(e for e in self.elements if e.name == name)

    def stiffness_matrix(self, tyres_only: bool = False) -> np.ndarray:
        """``Σ k g gᵀ`` over the elements' static stiffness (a Maxwell element has none),
        optionally the vertical tyres and suspension springs only (no gated element)."""
        n = len(self.coordinates)
        k = np.zeros((n, n))
        for e in self.elements:
            if e.model in ("kelvin_voigt", "rolling") and not (tyres_only and e.gate):
                k += e.static_stiffness * np.outer(e.g, e.g)
        return k

    def state_names(self) -> list[str]:
        """Positions a spring sees, every velocity, then the elements' own states."""
        return list(self.layout.states)

    # ----------------------------------------------------------------- statics
    def static_tyre_loads_N(self, gravity_m_s2: float | None = None) -> dict[str, float]:
        """Static load of every tyre element (N): ``K q_s = -g Σ m J_z`` (tyres and suspension
        springs), a tyre's load its compression force ``k g·q_s``; ``g`` the assembly's
        :attr:`gravity_m_s2` unless given."""
        k = self.stiffness_matrix(tyres_only=True)
        grav = -(self.gravity_m_s2 if gravity_m_s2 is None else gravity_m_s2) * self._weight_row
        keep = np.flatnonzero(np.diag(k) != 0)
        q = np.zeros(len(self.coordinates))
        q[keep] = np.linalg.solve(k[np.ix_(keep, keep)], grav[keep])
        return {e.name: float(e.stiffness * (e.g @ q)) for e in self.elements if e.input is not None}

    # ----------------------------------------------------------------- linear
    def linear(self, outputs=None, gravity_m_s2: float | None = None) -> LinearModel:
        """The model in contact as a :class:`LinearModel`, on :attr:`layout`.

        Outputs (all by default, else the names given): every kinematic output
        (:func:`assemble`: chassis and seat accelerations, ``*_tilt`` readings), the dynamic
        force of every tyre element (``<tyre>_force_N``) and of each axle
        (``front_force_N``/``rear_force_N``), and every coordinate a spring sees
        (``<coordinate>_m`` / ``_rad`` as :func:`coordinate_output`). The ``*_tilt`` readings
        take gravity ``gravity_m_s2``, by default the assembly's :attr:`gravity_m_s2`.
        """
        lay = self.layout
        names, n, nq = lay.states, lay.n, len(self.coordinates)
        # the force of each element as a row over [states, inputs] (its kind's form)
        force_rows = {e.name: _weighted(e, e.force_row(lay)) for e in self.elements}
        gen = np.zeros((nq, lay.width))
        for e in self.elements:
            gen += np.outer(-e.g, force_rows[e.name])  # generalised force -g F
        acc = _solve_mass(self.mass, gen)  # q'' rows over [states, inputs]
        rows = np.zeros((n, lay.width))
        eye = np.eye(nq)
        for j in range(nq):
            rows[lay.vel_cols[j]] = acc[j]
            if lay.pos_cols[j] is not None:
                rows[lay.pos_cols[j]] = lay.row(np.zeros(nq), eye[j])
        for e in self.elements:
            for s, r in e.derivative_rows(lay).items():
                rows[lay.index[s]] = r
        out_rows = {}
        g = self.gravity_m_s2 if gravity_m_s2 is None else gravity_m_s2
        for name, (r_acc, r_tilt) in self.kinematic_outputs.items():
            out_rows[name] = r_acc @ acc + (g * lay.row(r_tilt, np.zeros(nq)) if r_tilt is not None else 0.0)
        for t in self.tyres:
            out_rows[f"{t}_force_N"] = force_rows[t]
        for axle in ("front", "rear"):
            mine = [t for t in self.tyres if t.startswith(axle)]
            out_rows[f"{axle}_force_N"] = sum(force_rows[t] for t in mine)
        for j, c in enumerate(self.coordinates):
            if lay.pos_cols[j] is not None:
                out_rows[coordinate_output(c)] = lay.row(eye[j], np.zeros(nq))
        wanted = list(out_rows) if outputs is None else list(outputs)
        missing = [o for o in wanted if o not in out_rows]
        if missing:
            raise ValueError(f"outputs: unknown {missing} (known: {', '.join(out_rows)})")
        out = np.array([out_rows[o] for o in wanted]).reshape(len(wanted), lay.width)
        return LinearModel(rows[:, :n], rows[:, n:], out[:, :n], out[:, n:], tuple(names), lay.inputs, tuple(wanted))

    def linear_tyres(self, outputs, stiffness_N_per_m: dict, damping_N_s_per_m: dict | None = None):
        """:meth:`linear` for many values of the axles' tyre stiffness and damping at once.

        The model in contact is affine in each tyre element's stiffness and damping (they enter
        the force rows linearly, and ``M⁻¹`` and the output rows are fixed), so the model of
        other tyres is this one plus the per-unit change times the difference: two more
        assemblies per axle and quantity, then numpy over the variants (a pressure sweep's
        linear models without assembling each).

        Parameters
        ----------
        outputs : sequence of str
            As :meth:`linear`.
        stiffness_N_per_m, damping_N_s_per_m : dict
            Axle (``front``/``rear``) -> per-tyre values, shape (V,); an axle not given keeps
            its parts' value.

        Returns
        -------
        a, b, c, d : ndarray
            Shapes (V, n, n), (V, n, m), (V, p, n), (V, p, m).

        Examples
        --------
        >>> p = Parts(Chassis(5120.0, 6210.0, 0.838), Axle("front", 1.54, 4.25e5, 1.5e3),
        ...           Axle("rear", -0.896, 3.3e5, 1e3))
        >>> a, b, c, d = assemble(p).linear_tyres(["seat_vertical_m_s2"], {"front": np.array([2e5, 4.25e5])})
        >>> bool(np.allclose(a[1], assemble(p).linear().a, rtol=1e-12, atol=0))
        True
        """
        import copy

        base = self.linear(outputs)
        given = {("tyre_stiffness_N_per_m", k): np.asarray(v, float) for k, v in stiffness_N_per_m.items()}
        given.update({("tyre_damping_N_s_per_m", k): np.asarray(v, float) for k, v in (damping_N_s_per_m or {}).items()})
        n_var = {v.shape for v in given.values()}
        if len(n_var) != 1 or len(next(iter(n_var))) != 1:
            raise ValueError(f"stiffness_N_per_m, damping_N_s_per_m: one 1-D array of the same length each, got {n_var}")
        size = next(iter(n_var))[0]
        out = [np.repeat(m[None], size, axis=0) for m in base.abcd]
        per = 1.0 if self.parts.three_d else 2.0  # the pitch plane: the axle's two tyres in one element
        for (attr, axle), values in given.items():
            if axle not in ("front", "rear"):
                raise ValueError(f"stiffness_N_per_m, damping_N_s_per_m: unknown axle {axle!r}")
            x0 = float(getattr(getattr(self.parts, axle), attr))
            step = abs(x0) if x0 != 0 else 1.0
            other = copy.copy(self)
            field_ = "stiffness" if "stiffness" in attr else "damping"
            other.elements = [dataclasses.replace(e, **{field_: per * (x0 + step)})
                              if e.input is not None and e.name.startswith(axle) else e for e in self.elements]
            moved = other.linear(outputs)
            for m, m0, m1 in zip(out, base.abcd, moved.abcd):
                m += (values - x0)[:, None, None] * ((m1 - m0) / step)[None]
        return tuple(out)

    # ----------------------------------------------------------------- undamped modes
    def undamped(self, coordinates=None) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
        """``(K, M, names)`` of the undamped free vibration over the coordinates a spring
        sees (or ``coordinates``): the tyres' and suspensions' vertical stiffness only
        (the longitudinal elements left out, as thesis §8.2)."""
        k = self.stiffness_matrix(tyres_only=True)
        for e in self.elements:  # issue 33: the lateral tyre springs (a Maxwell one's damper locked) and
            if e.name.endswith("_lateral"):  # the static loads' moment (not symmetric)
                k = k + e.stiffness * np.outer(e.g, e.g)
            elif isinstance(e, StaticLoadMoment) and not np.any(e.g * self.row({"th": 1.0})):  # roll, not pitch
                k = k + e.stiffness * np.outer(e.g, e.d)
        names = [c for i, c in enumerate(self.coordinates) if k[i, i] != 0] if coordinates is None else list(coordinates)
        idx = [self.coordinates.index(c) for c in names]
        return k[np.ix_(idx, idx)], self.mass[np.ix_(idx, idx)], tuple(names)


def _weighted(e: Element, row: np.ndarray) -> np.ndarray:
    """The element's force row: its quantity's row times its weight (1 exactly: the row itself)."""
    w = e.weight
    return row if w == 1.0 else w * row


def coordinate_output(name: str) -> str:
    """Output name of a coordinate: ``z`` -> ``z_m``, ``th`` -> ``theta_rad``, an angle ``_rad``."""
    if not isinstance(name, str) or not name:
        raise ValueError(f"name must be a coordinate name (text), got {name!r}")
    special = {"z": "z_m", "th": "theta_rad", "x": "x_m", "phi": "phi_rad"}
    if name in special:
        return special[name]
    return f"{name}_rad" if name.endswith(("roll", "_th", "_phi")) else f"{name}_m"


def _solve_mass(mass: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """``M⁻¹ rhs``; a diagonal ``M`` divides row by row (as the equations are written out)."""
    if np.count_nonzero(mass - np.diag(np.diag(mass))) == 0:
        return rhs / np.diag(mass)[:, None]
    return np.linalg.solve(mass, rhs)


# --------------------------------------------------------------------------- assembly
def assemble(parts: Parts, gravity_m_s2: float | None = None) -> Assembly:
    """Coordinates, mass matrix, force elements and kinematic outputs of ``parts``: every part
    declares its coordinates, then contributes (:class:`Builder`); the tyres' static loads
    under ``gravity_m_s2`` (m/s²; default the standard gravity
    :data:`~tyrelab.vehicle.units.STANDARD_GRAVITY_M_S2`, a thesis study passes the thesis' 9.81)
    set their lift-off floors.

    Examples
    --------
    The pitch-plane tractor of the ch. 7 study (no longitudinal element) has the states
    and bounce/pitch stiffness of thesis §8.2:

    >>> p = Parts(Chassis(5120.0, 6210.0, 0.838), Axle("front", 1.54, 4.25e5, 1.5e3),
    ...           Axle("rear", -0.896, 3.3e5, 1e3))
    >>> asm = assemble(p)
    >>> asm.state_names()
    ['z', 'th', 'vz', 'vth']
    >>> k, m, names = asm.undamped()
    >>> k.tolist() == [[8.5e5 + 6.6e5, 8.5e5 * 1.54 - 6.6e5 * 0.896],
    ...                [8.5e5 * 1.54 - 6.6e5 * 0.896, 8.5e5 * 1.54**2 + 6.6e5 * 0.896**2]]
    True
    """
    _validate.instance("parts", parts, Parts)
    gravity_m_s2 = STANDARD_GRAVITY_M_S2 if gravity_m_s2 is None else _validate.positive("gravity_m_s2", gravity_m_s2)
    problems = parts.problems()
    if problems:
        raise ValueError("; ".join(problems))
    b = Builder(parts)
    members = parts.members()
    for part in members:
        part.declare(b)
    b._fix()
    for part in members:
        part.contribute(b)
    asm = Assembly(b.coordinates, b.mass, b.elements, b.outputs, parts, b.weight, b.output_filters, gravity_m_s2)
    loads = asm.static_tyre_loads_N()
    asm.elements = [dataclasses.replace(e, floor_N=-loads[e.name]) if e.name in loads else e for e in asm.elements]
    count: dict = {}
    by_name = {e.name: e for e in asm.elements}
    for tyre, g, d, contact in b.static_moments:
        count[tyre] = count.get(tyre, 0) + 1
        asm.elements.append(StaticLoadMoment(f"{tyre}_static_moment_{count[tyre]}", g, loads[tyre], 0.0, (tyre,), d=d,
                                             contact=by_name[contact] if contact else None))
    return asm
