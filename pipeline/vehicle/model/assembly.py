"""The assembly of a tractor's parts (issues 23, 35, 45): :func:`assemble` hands every part a
:class:`Builder` twice (declare, then contribute) and returns one :class:`Assembly` with one state
layout, which every solution path reads (:mod:`tyrelab.vehicle.model`).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ... import _validate
from ..elements import Element, StateLayout, StaticLoadMoment
from ..units import STANDARD_GRAVITY_M_S2
from .linear import LinearModel
from .parts import CHASSIS_FREEDOMS, Axle, Chassis, Parts  # noqa: F401  (Axle, Chassis: the Examples)

__all__ = ["Builder", "Assembly", "assemble", "coordinate_output"]


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
        g = self.gravity_m_s2 if gravity_m_s2 is None else gravity_m_s2
        memo = getattr(self, "_static_loads", None)  # (elements, g, loads): kept while the elements are these
        if memo is not None and memo[1] == g and len(memo[0]) == len(self.elements) and all(
                a is b for a, b in zip(memo[0], self.elements)):
            return dict(memo[2])
        k = self.stiffness_matrix(tyres_only=True)
        grav = -g * self._weight_row
        keep = np.flatnonzero(np.diag(k) != 0)
        q = np.zeros(len(self.coordinates))
        q[keep] = np.linalg.solve(k[np.ix_(keep, keep)], grav[keep])
        loads = {e.name: float(e.stiffness * (e.g @ q)) for e in self.elements if e.input is not None}
        self._static_loads = (tuple(self.elements), g, loads)
        return dict(loads)

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
        force_rows, acc, rows = self.state_rows(lay, self.elements)
        eye = np.eye(nq)
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

    def state_rows(self, lay: StateLayout, elements, known: dict | None = None) -> tuple[dict, np.ndarray, np.ndarray]:
        """The rows of the model in contact that :meth:`linear` builds, for ``elements`` (this
        assembly's, or others of the same coordinates and mass) on the layout ``lay``: each
        element's force row (by name; ``known`` gives rows already computed on ``lay``), the
        accelerations ``q''`` over ``[states, inputs]`` and the state derivatives' rows (``A | B``).

        Examples
        --------
        >>> p = Parts(Chassis(5120.0, 6210.0, 0.838), Axle("front", 1.54, 4.25e5, 1.5e3),
        ...           Axle("rear", -0.896, 3.3e5, 1e3))
        >>> asm = assemble(p)
        >>> _, _, rows = asm.state_rows(asm.layout, asm.elements)
        >>> bool(np.array_equal(rows[:, :asm.layout.n], asm.linear().a))
        True
        """
        n, nq = lay.n, len(self.coordinates)
        known = known or {}
        # the force of each element as a row over [states, inputs] (its kind's form)
        force_rows = {e.name: known[e.name] if e.name in known else _weighted(e, e.force_row(lay)) for e in elements}
        gen = np.zeros((nq, lay.width))
        for e in elements:
            gen += np.outer(-e.g, force_rows[e.name])  # generalised force -g F
        acc = _solve_mass(self.mass, gen)  # q'' rows over [states, inputs]
        rows = np.zeros((n, lay.width))
        eye = np.eye(nq)
        for j in range(nq):
            rows[lay.vel_cols[j]] = acc[j]
            if lay.pos_cols[j] is not None:
                rows[lay.pos_cols[j]] = lay.row(np.zeros(nq), eye[j])
        for e in elements:
            for s, r in e.derivative_rows(lay).items():
                rows[lay.index[s]] = r
        return force_rows, acc, rows

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
    """Output name of a coordinate: ``z`` -> ``z_m``, ``th`` -> ``theta_rad``, an angle ``_rad``.

    See Also
    --------
    assemble : the assembly whose coordinates these name.

    Examples
    --------
    >>> [coordinate_output(n) for n in ("z", "th", "front_axle_roll", "cab_z")]
    ['z_m', 'theta_rad', 'front_axle_roll_rad', 'cab_z_m']
    """
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

    See Also
    --------
    tyrelab.vehicle.solvers.time_domain.simulate : simulates assemblies.
    tyrelab.vehicle.solvers.modes.mode_set : their modes.

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
    # the floors and the static moments leave the static loads as they are (neither is a spring):
    # kept for the assembled elements (:meth:`Assembly.static_tyre_loads_N`)
    asm._static_loads = (tuple(asm.elements), asm.gravity_m_s2, loads)
    return asm
