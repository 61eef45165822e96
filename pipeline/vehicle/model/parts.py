"""The parts of a tractor and their rules (issues 23, 35, 45): :class:`Chassis`, :class:`Axle`,
:class:`Cab`, :class:`Implement`, :class:`Ballast`, the seat (:class:`SeatPoint`,
:class:`SeatSuspension`), :class:`Parts`, and the one home of which fields each part kind needs
(:func:`needs`). Each part declares its coordinates and contributes its bodies, elements and outputs
to the :class:`~tyrelab.vehicle.model.assembly.Builder` :func:`~tyrelab.vehicle.model.assemble`
hands it (:mod:`tyrelab.vehicle.model`: the kinematics and the mass rules).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import signal

from ... import _validate
from ..elements import SpringDamper, Tyre, element
from .linear import LinearModel

__all__ = ["Chassis", "Axle", "Cab", "Implement", "Ballast", "SeatPoint", "SeatSuspension", "Parts", "Part",
           "AXLE_MOUNTS", "AXLE_LONGITUDINAL_MODELS", "LATERAL_MODELS", "CHASSIS_FREEDOMS", "needs", "scenario_key",
           "pivot_problem", "cab_mount_problems"]

#: How an axle is carried (:class:`Axle`).
AXLE_MOUNTS = ("rigid", "pivot", "suspended")
#: Longitudinal element of an axle's tyres: none, Kelvin-Voigt (parallel), Maxwell (series), the
#: rolling tyre (a Kelvin-Voigt unit in series with ``c₂ = a / v``, issue 42).
AXLE_LONGITUDINAL_MODELS = ("none", "kelvin_voigt", "maxwell", "rolling")
#: The name of :data:`AXLE_LONGITUDINAL_MODELS` before issue 45 (the twelve-number tractor's are
#: :data:`tyrelab.vehicle.tractor.TRACTOR_LONGITUDINAL_MODELS`): still importable, not in ``__all__``.
LONGITUDINAL_MODELS = AXLE_LONGITUDINAL_MODELS
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

    See Also
    --------
    scenario_key : the scenario key of each field.

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

    See Also
    --------
    needs : the fields a part needs.

    Examples
    --------
    >>> scenario_key("hitch_stiffness_N_m_per_rad"), scenario_key("mass_kg")
    ('hitch_stiffness_kN_m_per_rad', 'mass_kg')
    """
    if not isinstance(field_name, str) or not field_name:
        raise ValueError(f"field_name must be a part field's name (text), got {field_name!r}")
    return field_name.replace("_N_", "_kN_")


def pivot_problem(section: str) -> str:
    """Why a pivot axle needs the 3-D model (the model and the scenario file say it so).

    See Also
    --------
    cab_mount_problems : the cab's mount check.

    Examples
    --------
    >>> pivot_problem("front_axle")
    'front_axle.mount = "pivot" needs the roll model (tractor.roll_inertia_kg_m2): a pivot axle only differs from a rigid one in roll'
    """
    return (f"{section}.mount = \"pivot\" needs the roll model (tractor.roll_inertia_kg_m2): a pivot axle only "
            "differs from a rigid one in roll")


def cab_mount_problems(front_mount_ahead_of_cg_m: float, rear_mount_ahead_of_cg_m: float) -> list[str]:
    """A suspended cab's front mounts must be ahead of its rear mounts (m ahead of the CG).

    See Also
    --------
    pivot_problem : the pivot axle's check.

    Examples
    --------
    >>> cab_mount_problems(0.4, -1.0)
    []
    >>> cab_mount_problems(-1.0, 0.4)
    ['cab.front_mount_ahead_of_cg_m (-1.0 m) must be ahead of cab.rear_mount_ahead_of_cg_m (0.4 m)']
    """
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
        Fore-aft element of the axle's tyres at the ground contact, :data:`AXLE_LONGITUDINAL_MODELS`.
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
        if ax.longitudinal_model not in AXLE_LONGITUDINAL_MODELS:
            return [f"longitudinal_model {ax.longitudinal_model!r}: expected one of {AXLE_LONGITUDINAL_MODELS}"]
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
