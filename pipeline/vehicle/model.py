"""The tractor as parts, assembled once (issue 23).

A tractor is a list of parts (:class:`Chassis`, two :class:`Axle`, optional :class:`Cab`,
:class:`Implement` and :class:`Ballast`, the seat point :class:`SeatPoint`), in the shape of
Project Chrono's vehicle module (chassis, axles with a suspension and left/right wheels,
tyres, attachments). :func:`assemble` turns them into one :class:`Assembly`: named
generalised coordinates, a mass matrix and a list of linear force elements, each a row
``g`` over the coordinates (its deformation ``δ = g·q + u``, ``u`` a ground input or 0)
with a stiffness and a damping in parallel (Kelvin-Voigt) or in series (Maxwell). Every
solution path reads that list:

* :meth:`Assembly.linear` — ``x' = A x + B w``, ``y = C x + D w`` with named states,
  inputs and outputs (the exact first-order-hold path, the frequency domain);
* :meth:`Assembly.undamped` — stiffness and mass matrices of the undamped eigenproblem
  (the bounce/pitch frequencies of thesis ch. 8, the roll modes);
* :class:`BatchRhs` — the nonlinear right-hand side of a batch of runs (tyres that lift off:
  a tyre force never pulls below minus the tyre's static load; the longitudinal element
  acts only while its axle's tyres are on the ground).

Kinematics (small angles, SI): ``x`` forward, ``y`` left, ``z`` up from the tractor's centre
of gravity (CG); pitch ``θ`` nose up, roll ``φ`` left side up. A point ``(p_x, p_y, p_z)``
of the chassis moves by ``dz = z + p_x θ + p_y φ``, ``dx = x - p_z θ``, ``dy = -p_z φ``.

Coordinates: chassis ``z``, ``th``, ``x`` (with a longitudinal element), ``phi`` (with a
roll inertia: the 3-D model); a pivot axle ``<axle>_axle_roll``; a suspended axle
``<axle>_axle_z`` (and its roll in 3-D); a suspended cab ``cab_z``, ``cab_th`` (``cab_phi``);
an implement on a hitch spring ``implement_th``. States are the positions the springs
see, then all velocities (``v`` + name), then the Maxwell elements' spring extensions
(``q``, ``q_<element>`` for more than one): a coordinate no spring sees carries only its
velocity (the fore-aft ``x`` with a Maxwell element or a damper alone).

Mass: ``Chassis`` mass and inertias are the whole tractor's (rigid cab and axles
included); a suspended axle or cab is taken out of it where it sits (its own mass and
inertia moving on its own coordinates instead), so switching a part from rigid to
suspended keeps the tractor's mass, CG and inertia. An implement and a front ballast are
added to the tractor.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from .. import _validate
from .carriage import GRAVITY_M_S2

__all__ = ["Chassis", "Axle", "Cab", "Implement", "Ballast", "SeatPoint", "Parts", "Element", "Assembly",
           "LinearModel", "assemble", "coordinate_output", "AXLE_MOUNTS", "LONGITUDINAL_MODELS"]

#: How an axle is carried (:class:`Axle`).
AXLE_MOUNTS = ("rigid", "pivot", "suspended")
#: Longitudinal element of an axle's tyres: none, Kelvin-Voigt (parallel), Maxwell (series).
LONGITUDINAL_MODELS = ("none", "kelvin_voigt", "maxwell")


@dataclass(frozen=True)
class Chassis:
    """The tractor body: whole-tractor mass and inertias about its CG (SI).

    ``roll_inertia_kg_m2`` None: the pitch-plane model (no roll; each axle's two tyres one
    element under the axle-mean input, as thesis ch. 7). Given: the 3-D model (roll,
    left and right tyres, per-wheel inputs).
    """

    mass_kg: float
    pitch_inertia_kg_m2: float
    cg_height_m: float
    roll_inertia_kg_m2: float | None = None


@dataclass(frozen=True)
class Axle:
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


@dataclass(frozen=True)
class Cab:
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


@dataclass(frozen=True)
class Implement:
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


@dataclass(frozen=True)
class Ballast:
    """Front ballast: a rigid mass ahead of the front axle (m) at a height above the ground."""

    mass_kg: float
    ahead_of_front_axle_m: float
    height_m: float
    pitch_inertia_kg_m2: float = 0.0
    roll_inertia_kg_m2: float = 0.0


@dataclass(frozen=True)
class SeatPoint:
    """The seat reference point relative to the tractor CG (m): ahead, left, above."""

    ahead_of_cg_m: float = 0.0
    left_of_cg_m: float = 0.0
    height_above_cg_m: float = 0.0


@dataclass(frozen=True)
class Parts:
    """Everything :func:`assemble` reads."""

    chassis: Chassis
    front: Axle
    rear: Axle
    seat: SeatPoint = field(default_factory=SeatPoint)
    cab: Cab | None = None
    implement: Implement | None = None
    ballast: Ballast | None = None

    @property
    def three_d(self) -> bool:
        """Roll (and left/right tyres) modelled."""
        return self.chassis.roll_inertia_kg_m2 is not None


@dataclass(frozen=True)
class Element:
    """A linear force element: deformation ``δ = g·q + u`` (``u`` the ground input ``input``,
    if any), force ``F = k δ + c δ'`` (Kelvin-Voigt) or ``F = k (δ - s)``, ``c s' = k (δ - s)``
    (Maxwell), generalised force ``g F``. A ``tyre`` (``input`` set) may lift off: ``F``
    never below ``-floor_N`` (its static load). ``gate``: the tyres whose contact the element
    needs (the longitudinal element acts while they are on the ground, in proportion)."""

    name: str
    g: np.ndarray
    stiffness: float
    damping: float
    model: str = "kelvin_voigt"
    input: str | None = None
    gate: tuple[str, ...] = ()
    floor_N: float = np.inf


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


class Assembly:
    """The assembled tractor: coordinates, mass matrix, elements, output rows, static tyre loads.

    Built by :func:`assemble`; every solution path reads it (see the module docstring).
    """

    def __init__(self, coordinates, mass, elements, outputs, tyres, parts):
        self.coordinates = tuple(coordinates)
        self.mass = mass
        self.elements = list(elements)
        self.kinematic_outputs = outputs  # name -> (row over q'' , row over q) (acceleration, gravity tilt)
        self.tyres = tuple(tyres)  # tyre element names (inputs in this order)
        self.parts = parts
        self.inputs = tuple(x for t in self.tyres for x in (f"u_{t}", f"du_{t}"))

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
        """``Σ k g gᵀ`` over the Kelvin-Voigt elements (and the Maxwell springs' instantaneous
        stiffness excluded), optionally the vertical tyres and suspension springs only."""
        n = len(self.coordinates)
        k = np.zeros((n, n))
        for e in self.elements:
            if e.model == "kelvin_voigt" and not (tyres_only and e.gate):
                k += e.stiffness * np.outer(e.g, e.g)
        return k

    def _maxwell(self) -> list[Element]:
        return [e for e in self.elements if e.model == "maxwell" and e.stiffness > 0 and e.damping > 0]

    def state_names(self) -> list[str]:
        """Positions a spring sees, every velocity, then the Maxwell spring extensions."""
        k = self.stiffness_matrix()
        seen = np.any(k != 0, axis=0)
        pos = [c for i, c in enumerate(self.coordinates) if seen[i]]
        mw = self._maxwell()
        extra = ["q"] if len(mw) == 1 else [f"q_{e.name}" for e in mw]
        return pos + [f"v{c}" for c in self.coordinates] + extra

    # ----------------------------------------------------------------- statics
    def static_tyre_loads_N(self, gravity_m_s2: float = GRAVITY_M_S2) -> dict[str, float]:
        """Static load of every tyre element (N): ``K q_s = -g Σ m J_z`` (tyres and suspension
        springs), a tyre's load its compression force ``k g·q_s``."""
        k = self.stiffness_matrix(tyres_only=True)
        grav = -gravity_m_s2 * self._weight_row
        keep = np.flatnonzero(np.diag(k) != 0)
        q = np.zeros(len(self.coordinates))
        q[keep] = np.linalg.solve(k[np.ix_(keep, keep)], grav[keep])
        return {e.name: float(e.stiffness * (e.g @ q)) for e in self.elements if e.input is not None}

    # ----------------------------------------------------------------- linear
    def linear(self, outputs=None, gravity_m_s2: float = GRAVITY_M_S2) -> LinearModel:
        """The model in contact as a :class:`LinearModel`.

        Outputs (all by default, else the names given): every kinematic output
        (:func:`assemble`: chassis and seat accelerations, ``*_tilt`` readings), the dynamic
        force of every tyre element (``<tyre>_force_N``) and of each axle
        (``front_force_N``/``rear_force_N``), and every coordinate (``<coordinate>_m`` /
        ``_rad`` as :meth:`coordinate_output`).
        """
        names = self.state_names()
        n, nq = len(names), len(self.coordinates)
        ni = len(self.inputs)
        index = {s: i for i, s in enumerate(names)}
        pos_cols = [index.get(c) for c in self.coordinates]
        vel_cols = [index[f"v{c}"] for c in self.coordinates]

        def to_state(r_q, r_v) -> np.ndarray:
            out = np.zeros(n + ni)
            for j in range(nq):
                if r_q[j] != 0 and pos_cols[j] is not None:
                    out[pos_cols[j]] += r_q[j]
                if r_v[j] != 0:
                    out[vel_cols[j]] += r_v[j]
            return out

        # generalised force of each element as a row over [states, inputs]
        force_rows, q_rows = {}, {}
        mw = self._maxwell()
        mw_names = names[n - len(mw):] if mw else []
        for e in self.elements:
            if e.model == "maxwell":
                if e not in mw:
                    force_rows[e.name] = np.zeros(n + ni)
                    continue
                qn = mw_names[mw.index(e)]
                r = np.zeros(n + ni)
                r[index[qn]] = e.stiffness  # F = k q, q = d - s the spring's extension
                force_rows[e.name] = r
                qr = to_state(np.zeros(nq), e.g)
                qr[index[qn]] = -e.stiffness / e.damping
                q_rows[qn] = qr
                continue
            r = to_state(e.stiffness * e.g, e.damping * e.g)
            if e.input is not None:
                r[n + self.inputs.index(f"u_{e.input}")] += e.stiffness
                r[n + self.inputs.index(f"du_{e.input}")] += e.damping
            force_rows[e.name] = r
        gen = np.zeros((nq, n + ni))
        for e in self.elements:
            gen += np.outer(-e.g, force_rows[e.name])  # generalised force -g F
        acc = _solve_mass(self.mass, gen)  # q'' rows over [states, inputs]
        deriv = {}
        for j, c in enumerate(self.coordinates):
            deriv[f"v{c}"] = acc[j]
            if pos_cols[j] is not None:
                deriv[c] = to_state(np.zeros(nq), np.eye(nq)[j])
        deriv.update(q_rows)
        rows = np.array([deriv[s] for s in names])
        out_rows = {}
        g = gravity_m_s2
        for name, (r_acc, r_tilt) in self.kinematic_outputs.items():
            out_rows[name] = r_acc @ acc + (g * to_state(r_tilt, np.zeros(nq)) if r_tilt is not None else 0.0)
        for t in self.tyres:
            out_rows[f"{t}_force_N"] = force_rows[t]
        for axle in ("front", "rear"):
            mine = [t for t in self.tyres if t.startswith(axle)]
            out_rows[f"{axle}_force_N"] = sum(force_rows[t] for t in mine)
        for j, c in enumerate(self.coordinates):
            if pos_cols[j] is not None:
                out_rows[coordinate_output(c)] = to_state(np.eye(nq)[j], np.zeros(nq))
        wanted = list(out_rows) if outputs is None else list(outputs)
        missing = [o for o in wanted if o not in out_rows]
        if missing:
            raise ValueError(f"outputs: unknown {missing} (known: {', '.join(out_rows)})")
        out = np.array([out_rows[o] for o in wanted]).reshape(len(wanted), n + ni)
        return LinearModel(rows[:, :n], rows[:, n:], out[:, :n], out[:, n:], tuple(names), self.inputs, tuple(wanted))

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
        names = [c for i, c in enumerate(self.coordinates) if k[i, i] != 0] if coordinates is None else list(coordinates)
        idx = [self.coordinates.index(c) for c in names]
        return k[np.ix_(idx, idx)], self.mass[np.ix_(idx, idx)], tuple(names)


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
def assemble(parts: Parts) -> Assembly:
    """Coordinates, mass matrix, force elements and kinematic outputs of ``parts``.

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
    ch, three_d = parts.chassis, parts.three_d
    _validate.positive("chassis.mass_kg", ch.mass_kg)
    _validate.positive("chassis.pitch_inertia_kg_m2", ch.pitch_inertia_kg_m2)
    h = float(ch.cg_height_m)
    if three_d:
        _validate.positive("chassis.roll_inertia_kg_m2", ch.roll_inertia_kg_m2)
    axles = (parts.front, parts.rear)
    for ax in axles:
        if ax.mount not in AXLE_MOUNTS:
            raise ValueError(f"{ax.name}_axle.mount {ax.mount!r}: expected one of {AXLE_MOUNTS}")
        if ax.longitudinal_model not in LONGITUDINAL_MODELS:
            raise ValueError(f"longitudinal_model {ax.longitudinal_model!r}: expected one of {LONGITUDINAL_MODELS}")
        if ax.mount != "rigid" and three_d:
            _validate.positive(f"{ax.name}_axle.roll_inertia_kg_m2", ax.roll_inertia_kg_m2)
        if ax.mount == "pivot" and not three_d:
            raise ValueError(f"{ax.name}_axle.mount = 'pivot' needs the roll model (chassis roll_inertia_kg_m2)")
        if ax.mount == "suspended":
            _validate.positive(f"{ax.name}_axle.mass_kg", ax.mass_kg)
            _validate.positive(f"{ax.name}_axle.suspension_stiffness_N_per_m", ax.suspension_stiffness_N_per_m)
        if three_d:
            _validate.positive(f"{ax.name}_axle.track_m", ax.track_m)
    lon = [ax for ax in axles if ax.longitudinal_model != "none"]
    cab = parts.cab
    imp = parts.implement
    # ---- coordinates
    coords = ["z", "th"] + (["x"] if lon else []) + (["phi"] if three_d else [])
    for ax in axles:
        if ax.mount == "suspended":
            coords.append(f"{ax.name}_axle_z")
        if ax.mount != "rigid" and three_d:
            coords.append(f"{ax.name}_axle_roll")
    if cab is not None:
        coords += ["cab_z", "cab_th"] + (["cab_phi"] if three_d else [])
    if imp is not None and imp.mount == "hitch_spring":
        coords.append("implement_th")
    n = len(coords)

    def row(coef: dict) -> np.ndarray:
        r = np.zeros(n)
        for k, v in coef.items():
            if k in coords:
                r[coords.index(k)] += v
        return r

    def chassis_point(px, py, pz) -> dict:
        """Rows (vertical, fore-aft, lateral) of a chassis point relative to the CG."""
        return {"z": row({"z": 1.0, "th": px, "phi": py}), "x": row({"x": 1.0, "th": -pz}), "y": row({"phi": -pz})}

    mass = np.zeros((n, n))
    weight = np.zeros(n)  # Σ m J_z: the generalised gravity force is -g times this

    def add_body(m, i_roll, i_pitch, rows: dict, roll_row, pitch_row, sign=1.0):
        nonlocal mass, weight
        for key in ("z", "x", "y"):
            mass += sign * m * np.outer(rows[key], rows[key])
        if roll_row is not None and i_roll:
            mass += sign * i_roll * np.outer(roll_row, roll_row)
        mass += sign * i_pitch * np.outer(pitch_row, pitch_row)
        weight += sign * m * rows["z"]

    # chassis (whole tractor); its own rows written out so the diagonal is exactly m, I
    mass[coords.index("z"), coords.index("z")] = ch.mass_kg
    mass[coords.index("th"), coords.index("th")] = ch.pitch_inertia_kg_m2
    if "x" in coords:
        mass[coords.index("x"), coords.index("x")] = ch.mass_kg
    if three_d:
        mass[coords.index("phi"), coords.index("phi")] = ch.roll_inertia_kg_m2
    weight[coords.index("z")] = ch.mass_kg
    roll_row, pitch_row = (row({"phi": 1.0}) if three_d else None), row({"th": 1.0})

    elements: list[Element] = []
    tyres: list[str] = []
    for ax in axles:
        a = float(ax.ahead_of_cg_m)
        sides = (("left", 0.5 * ax.track_m), ("right", -0.5 * ax.track_m)) if three_d else ((None, 0.0),)
        ax_h = float(ax.height_m) - h  # axle centre relative to the CG
        if ax.mount == "suspended":
            zc = f"{ax.name}_axle_z"
            at_body = chassis_point(a, 0.0, ax_h)
            moving = {"z": row({zc: 1.0}), "x": at_body["x"], "y": at_body["y"]}
            aroll = row({f"{ax.name}_axle_roll": 1.0}) if three_d else None
            add_body(ax.mass_kg, ax.roll_inertia_kg_m2, 0.0, moving, aroll, pitch_row)
            add_body(ax.mass_kg, 0.0, 0.0, at_body, None, pitch_row, sign=-1.0)  # taken out of the chassis
            elements.append(Element(f"{ax.name}_suspension", row({zc: 1.0}) - at_body["z"],
                                    float(ax.suspension_stiffness_N_per_m), float(ax.suspension_damping_N_s_per_m)))
        elif ax.mount == "pivot":
            add_body(0.0, ax.roll_inertia_kg_m2, 0.0, {k: np.zeros(n) for k in "zxy"},
                     row({f"{ax.name}_axle_roll": 1.0}), np.zeros(n))
        names = []
        for side, py in sides:
            name = ax.name if side is None else f"{ax.name}_{side}"
            if ax.mount == "rigid":
                jz = chassis_point(a, py, -h)["z"]
            elif ax.mount == "pivot":
                jz = row({"z": 1.0, "th": a, f"{ax.name}_axle_roll": py})
            else:
                jz = row({f"{ax.name}_axle_z": 1.0, f"{ax.name}_axle_roll": py})
            per = 1.0 if three_d else 2.0  # pitch-plane: the axle's two tyres in one element
            elements.append(Element(name, -jz, per * float(ax.tyre_stiffness_N_per_m),
                                    per * float(ax.tyre_damping_N_s_per_m), input=name))
            tyres.append(name)
            names.append(name)
        if ax.longitudinal_model != "none":
            # fore-aft of the axle's ground contact, h below the CG: d = x + h θ
            per = 2.0
            elements.append(Element(f"{ax.name}_longitudinal", chassis_point(a, 0.0, -h)["x"],
                                    per * float(ax.longitudinal_stiffness_N_per_m),
                                    per * float(ax.longitudinal_damping_N_s_per_m), model=ax.longitudinal_model,
                                    gate=tuple(names)))
    # cab
    seat = parts.seat
    if cab is None:
        seat_rows = chassis_point(seat.ahead_of_cg_m, seat.left_of_cg_m, seat.height_above_cg_m)
        seat_tilt = {"x": pitch_row, "y": roll_row}
    else:
        cx, cz = float(cab.ahead_of_cg_m), float(cab.height_above_cg_m)
        cab_roll = row({"cab_phi": 1.0}) if three_d else None

        def cab_point(px, py, pz) -> dict:
            """A cab point relative to the tractor CG: the cab's own vertical, pitch and roll; fore-aft
            and lateral as the chassis at the cab CG (stiff mounts) plus the cab's rotation."""
            at = chassis_point(cx, 0.0, cz)
            return {"z": row({"cab_z": 1.0, "cab_th": px - cx, "cab_phi": py}),
                    "x": at["x"] + row({"cab_th": -(pz - cz)}), "y": at["y"] + row({"cab_phi": -(pz - cz)})}

        add_body(cab.mass_kg, cab.roll_inertia_kg_m2, cab.pitch_inertia_kg_m2, cab_point(cx, 0.0, cz), cab_roll,
                 row({"cab_th": 1.0}))
        add_body(cab.mass_kg, cab.roll_inertia_kg_m2, cab.pitch_inertia_kg_m2, chassis_point(cx, 0.0, cz), roll_row,
                 pitch_row, sign=-1.0)
        mounts = [("front", cab.front_mount_ahead_of_cg_m), ("rear", cab.rear_mount_ahead_of_cg_m)]
        for where, mx in mounts:
            for side, py in ((("left", 0.5 * cab.mount_track_m), ("right", -0.5 * cab.mount_track_m)) if three_d
                             else ((None, 0.0),)):
                per = 1.0 if three_d else 2.0
                g = cab_point(mx, py, cz)["z"] - chassis_point(mx, py, cz)["z"]
                elements.append(Element(f"cab_{where}_mount" + (f"_{side}" if side else ""), g,
                                        per * cab.mount_stiffness_N_per_m, per * cab.mount_damping_N_s_per_m))
        seat_rows = cab_point(seat.ahead_of_cg_m, seat.left_of_cg_m, seat.height_above_cg_m)
        seat_tilt = {"x": row({"cab_th": 1.0}), "y": cab_roll}
    # implement and ballast: rigid attachments, or the implement pitching about the hitch
    rear_x = float(parts.rear.ahead_of_cg_m)
    if imp is not None:
        ix, iz = rear_x - float(imp.behind_rear_axle_m), float(imp.height_m) - h
        if imp.mount == "rigid":
            add_body(imp.mass_kg, imp.roll_inertia_kg_m2, imp.pitch_inertia_kg_m2, chassis_point(ix, 0.0, iz), roll_row,
                     pitch_row)
        else:
            hx, hz = rear_x - float(imp.hitch_behind_rear_axle_m), float(imp.hitch_height_m) - h
            hitch = chassis_point(hx, 0.0, hz)
            ith = row({"implement_th": 1.0})
            rows = {"z": hitch["z"] + (ix - hx) * ith, "x": hitch["x"] - (iz - hz) * ith, "y": chassis_point(ix, 0.0, iz)["y"]}
            add_body(imp.mass_kg, imp.roll_inertia_kg_m2, imp.pitch_inertia_kg_m2, rows, roll_row, ith)
            elements.append(Element("hitch", ith - pitch_row, float(imp.hitch_stiffness_N_m_per_rad),
                                    float(imp.hitch_damping_N_m_s_per_rad)))
    if parts.ballast is not None:
        bl = parts.ballast
        add_body(bl.mass_kg, bl.roll_inertia_kg_m2, bl.pitch_inertia_kg_m2,
                 chassis_point(float(parts.front.ahead_of_cg_m) + float(bl.ahead_of_front_axle_m), 0.0,
                               float(bl.height_m) - h), roll_row, pitch_row)
    # kinematic outputs: (row over q'', tilt row over q (times g) or None)
    zero = np.zeros(n)
    outputs = {
        "vertical_m_s2": (row({"z": 1.0}), None),
        "pitch_rad_s2": (row({"th": 1.0}), None),
        "longitudinal_m_s2": (row({"x": 1.0}) if "x" in coords else zero, None),
        "seat_vertical_m_s2": (seat_rows["z"], None),
        "seat_longitudinal_m_s2": (seat_rows["x"], None),
        "seat_longitudinal_tilt_m_s2": (seat_rows["x"], seat_tilt["x"]),
    }
    if three_d:
        outputs["roll_rad_s2"] = (row({"phi": 1.0}), None)
        outputs["seat_lateral_m_s2"] = (seat_rows["y"], None)
        outputs["seat_lateral_tilt_m_s2"] = (seat_rows["y"], seat_tilt["y"])
    asm = Assembly(coords, mass, elements, outputs, tyres, parts)
    floors = asm_static(asm, weight)
    asm.elements = [Element(e.name, e.g, e.stiffness, e.damping, e.model, e.input, e.gate, floors.get(e.name, np.inf))
                    for e in asm.elements]
    return asm


def asm_static(asm: Assembly, weight: np.ndarray) -> dict:
    """Static tyre loads (N) of ``asm`` under the weight row ``weight`` (``Σ m J_z``)."""
    asm._weight_row = weight
    return asm.static_tyre_loads_N()
