"""Force-element kinds of the assembled vehicle: each kind's linear form, once (issue 35).

How to add an element kind
--------------------------
Subclass :class:`Element` (a frozen dataclass) and give it, over the assembly's one state
layout (:class:`StateLayout`: positions a spring sees, every velocity, then the elements' own
states), three things; both solution paths read them and nothing else:

* :meth:`Element.force_row` — the element's quantity ``f`` as a row over ``[states, inputs]``
  (a spring-damper's force; a Maxwell element's spring extension);
* :attr:`Element.weight` — the force is ``weight · f`` (1, or a Maxwell spring's stiffness);
  the generalised force on the coordinates is ``-g · weight · f``;
* :meth:`Element.states` and :meth:`Element.derivative_rows` — the element's own states and
  their time derivatives as rows (a Maxwell damper's extension ``e' = g·q' - (k/c) e``).

The nonlinear parts are two fields every kind has: ``floor_N`` (``f`` never below it: a tyre
that lifts off) and ``gate`` (the tyres whose contact the element needs: it acts in
proportion to them being on the ground). The linear model in contact
(:meth:`tyrelab.vehicle.model.Assembly.linear`) and the vectorised RK4 right-hand side
(:class:`tyrelab.vehicle.tractor` ``_Kernel``) are built from these rows, so a new kind
(a lateral tyre element, a front-linkage damper) touches no solver::

    @dataclass(frozen=True)
    class Bushing(Element):            # a spring only, say
        def force_row(self, layout):
            return layout.row(self.stiffness * self.g, 0 * self.g)

Kinematics are the parts' (:mod:`tyrelab.vehicle.model`): ``g`` is the element's deformation
``δ = g·q (+ u)`` over the coordinates. SI units throughout (N, m, s).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Element", "SpringDamper", "Tyre", "Maxwell", "Rolling", "StaticLoadMoment", "StateLayout", "element",
           "RESEAT_S"]


class StateLayout:
    """The one state layout of an assembly: the positions a spring sees (coordinate order),
    every velocity (``v`` + coordinate), then the elements' own states; inputs after them.

    Rows over ``[states, inputs]`` are built with :meth:`row` (from rows over the coordinates'
    positions and velocities) and :meth:`at` (one state or input)."""

    def __init__(self, coordinates, seen: np.ndarray, own_states, inputs):
        self.coordinates = tuple(coordinates)
        own = list(own_states)
        # one Maxwell state is called ``q`` (its element's name as an alias), as before issue 35
        shown = ["q"] if len(own) == 1 and own[0].startswith("q_") else own
        pos = [c for i, c in enumerate(self.coordinates) if seen[i]]
        self.states = tuple(pos + [f"v{c}" for c in self.coordinates] + shown)
        self.inputs = tuple(inputs)
        self.n, self.ni, self.nq = len(self.states), len(self.inputs), len(self.coordinates)
        self.index = {s: i for i, s in enumerate(self.states)}
        self.index.update({o: self.n - len(own) + i for i, o in enumerate(own)})
        self.index.update({w: self.n + i for i, w in enumerate(self.inputs)})
        self.pos_cols = [self.index.get(c) for c in self.coordinates]
        self.vel_cols = [self.index[f"v{c}"] for c in self.coordinates]

    @property
    def width(self) -> int:
        """States plus inputs."""
        return self.n + self.ni

    def row(self, r_q, r_v) -> np.ndarray:
        """A row over ``[states, inputs]`` from rows over the positions ``r_q`` and velocities
        ``r_v`` (a position no spring sees is not a state: its coefficient is dropped)."""
        out = np.zeros(self.width)
        for j in range(self.nq):
            if r_q[j] != 0 and self.pos_cols[j] is not None:
                out[self.pos_cols[j]] += r_q[j]
            if r_v[j] != 0:
                out[self.vel_cols[j]] += r_v[j]
        return out

    def at(self, name: str, value: float = 1.0) -> np.ndarray:
        """A row with ``value`` at the state or input ``name``."""
        out = np.zeros(self.width)
        out[self.index[name]] = value
        return out


@dataclass(frozen=True)
class Element:
    """A linear force element: deformation ``δ = g·q``, stiffness (N/m or N m/rad) and damping
    (N s/m or N m s/rad) in parallel (Kelvin-Voigt, :class:`SpringDamper`) unless a kind says
    otherwise. ``gate``: the tyres whose contact the element needs; ``floor_N``: the least the
    element's force may be (a tyre's static load, negated; -inf: no limit)."""

    name: str
    g: np.ndarray
    stiffness: float
    damping: float
    gate: tuple[str, ...] = ()
    floor_N: float = -np.inf

    #: The ground input this element reads (``u_<input>``, ``du_<input>``), if any.
    input = None
    #: Kelvin-Voigt (``"kelvin_voigt"``) or series (``"maxwell"``): how the element is named in
    #: the parts (a tractor's ``longitudinal_model``).
    model = "kelvin_voigt"

    # ------------------------------------------------------------------ linear form
    @property
    def weight(self) -> float:
        """Force = ``weight · f`` (``f`` :meth:`force_row`)."""
        return 1.0

    @property
    def static_stiffness(self) -> float:
        """Stiffness the element adds to ``K`` of the statics and undamped modes (0: none)."""
        return self.stiffness

    def states(self) -> tuple[str, ...]:
        """The element's own states (none)."""
        return ()

    def force_row(self, layout: StateLayout) -> np.ndarray:
        """``f = k g·q + c g·q'`` as a row over ``[states, inputs]``."""
        return layout.row(self.stiffness * self.g, self.damping * self.g)

    def derivative_rows(self, layout: StateLayout) -> dict[str, np.ndarray]:
        """Time derivatives of :meth:`states` as rows over ``[states, inputs]``."""
        return {}

    def free_rows(self, layout: StateLayout) -> dict[str, np.ndarray]:
        """Time derivatives of :meth:`states` while the element's tyres are off the ground (its gate
        closed): by default the same as in contact (:meth:`derivative_rows`)."""
        return self.derivative_rows(layout)


@dataclass(frozen=True)
class SpringDamper(Element):
    """Kelvin-Voigt: ``F = k δ + c δ'`` (suspensions, cab mounts, hitch, a longitudinal tyre
    element in parallel)."""


@dataclass(frozen=True)
class Tyre(Element):
    """A tyre's vertical Kelvin-Voigt element on the ground input ``u`` under it:
    ``δ = g·q + u``, ``F = k δ + c δ'``, never below ``floor_N`` (minus its static load: it
    lifts off rather than pull)."""

    @property
    def input(self) -> str:  # the tyre's own ground input
        return self.name

    def force_row(self, layout: StateLayout) -> np.ndarray:
        r = layout.row(self.stiffness * self.g, self.damping * self.g)
        r[layout.index[f"u_{self.name}"]] += self.stiffness
        r[layout.index[f"du_{self.name}"]] += self.damping
        return r


@dataclass(frozen=True)
class Maxwell(Element):
    """Spring and damper in series: ``F = k e``, ``e = δ - s`` the spring's extension, ``s``
    the damper's (``c s' = k e``), so ``e' = g·q' - (k/c) e``. Without spring or damper it
    carries no force and has no state."""

    model = "maxwell"

    @property
    def active(self) -> bool:
        """Both spring and damper present."""
        return self.stiffness > 0 and self.damping > 0

    @property
    def weight(self) -> float:
        return self.stiffness if self.active else 0.0

    @property
    def static_stiffness(self) -> float:
        return 0.0  # the damper in series passes no static force

    def states(self) -> tuple[str, ...]:
        return (f"q_{self.name}",) if self.active else ()

    def force_row(self, layout: StateLayout) -> np.ndarray:
        if not self.active:
            return np.zeros(layout.width)
        return layout.at(f"q_{self.name}")

    def derivative_rows(self, layout: StateLayout) -> dict[str, np.ndarray]:
        if not self.active:
            return {}
        q = f"q_{self.name}"
        r = layout.row(np.zeros(layout.nq), self.g)
        r[layout.index[q]] = -self.stiffness / self.damping
        return {q: r}


#: The shortest time a lifted rolling element takes to re-seat, s: its unit's own ``c/k`` where longer
#: (a few ms for a tractor tyre); a floor so that the time-domain solver's step (0.5 ms, RK4 stable below
#: ``2.8/dt``) follows it.
RESEAT_S = 5e-3


@dataclass(frozen=True)
class Rolling(Element):
    """A rolling tyre's horizontal element (issue 42, thesis §2.5): a Kelvin-Voigt unit (``k``,
    ``c``) from the patch point to the contact point, in series with a damper ``c₂`` from the
    contact point to the ground (``c₂ = a / v``: the contact point's velocity over the ground,
    the single-point slip model). Its state is the unit's deflection ``e = δ - s`` (``s`` the
    contact point's displacement; massless: ``c₂ s' = F``), so

        F = k e + c e',   e' = (c₂ δ' - k e) / (c + c₂)
          = k c₂/(c + c₂) e + c c₂/(c + c₂) g·q'.

    ``series_damping = inf`` (a stationary tyre) locks the contact point: the Kelvin-Voigt
    element, no state. ``c = 0``: the Maxwell element. :meth:`contact_row` is the contact
    point's displacement ``s = g·q - e`` as a row (the static load acts there)."""

    series_damping: float = np.inf
    model = "rolling"

    @property
    def locked(self) -> bool:
        """The series damper is rigid (``inf``): the unit alone."""
        return not np.isfinite(self.series_damping)

    @property
    def active(self) -> bool:
        """The element carries force: a unit (spring or damper) and a series damper that is not free."""
        return (self.stiffness > 0 or self.damping > 0) and self.series_damping > 0

    @property
    def static_stiffness(self) -> float:
        return self.stiffness if self.locked else 0.0  # a series damper passes no static force

    def states(self) -> tuple[str, ...]:
        return (f"q_{self.name}",) if self.active and not self.locked else ()

    def _series(self) -> tuple[float, float]:
        """``(c₂/(c + c₂), 1/(c + c₂))``."""
        total = self.damping + self.series_damping
        return self.series_damping / total, 1.0 / total

    def force_row(self, layout: StateLayout) -> np.ndarray:
        if self.locked:
            return layout.row(self.stiffness * self.g, self.damping * self.g)
        if not self.states():
            return np.zeros(layout.width)
        share, _ = self._series()
        r = layout.row(np.zeros(layout.nq), self.damping * share * self.g)
        r[layout.index[f"q_{self.name}"]] += self.stiffness * share
        return r

    def derivative_rows(self, layout: StateLayout) -> dict[str, np.ndarray]:
        if not self.states():
            return {}
        q = f"q_{self.name}"
        share, inv = self._series()
        r = layout.row(np.zeros(layout.nq), share * self.g)
        r[layout.index[q]] = -self.stiffness * inv
        return {q: r}

    def free_rows(self, layout: StateLayout) -> dict[str, np.ndarray]:
        """Off the ground the contact point is free (no ground to hold it, ``c₂ = 0``): the unit relaxes,
        ``e' = -e / τ`` with ``τ = max(c / k, RESEAT_S)``, and the tyre touches down with its contact
        point under the patch again (it re-seats; issue 42)."""
        if not self.states():
            return {}
        q = f"q_{self.name}"
        tau = max(self.damping / self.stiffness if self.stiffness > 0 else RESEAT_S, RESEAT_S)
        return {q: layout.at(q, -1.0 / tau)}

    def contact_row(self, layout: StateLayout) -> np.ndarray:
        """The contact point's displacement over the ground ``s = g·q - e`` over ``[states, inputs]``:
        0 where the series damper is locked (the patch holds), ``g·q`` where it is free (``c₂ = 0``)."""
        if self.locked:
            return np.zeros(layout.width)
        r = layout.row(self.g, np.zeros(layout.nq))
        if self.states():
            r[layout.index[f"q_{self.name}"]] -= 1.0
        return r


@dataclass(frozen=True)
class StaticLoadMoment(Element):
    """The moment of a tyre's static load about the part that carries the tyre (issue 33).

    The static load ``F`` (N, :attr:`stiffness`) acts at the tyre's contact patch, which a
    horizontal tyre element (lateral, longitudinal) holds on the ground; when the part moves by
    ``d·q`` (m) relative to the patch the load turns it by ``-F d·q`` about its freedom ``g``
    (roll or pitch): ``f = F d·q``, generalised force ``-g f``. With laterally stiff tyres
    (``y ≈ -h φ``) this is the familiar destabilising ``m g h φ``. Not a spring (no static
    stiffness, no damping); gated by its tyre (a tyre off the ground carries no load)."""

    d: np.ndarray | None = None
    #: A rolling element whose contact point the load acts at (issue 42): ``f = F (d·q - s)``,
    #: ``s`` its contact point's displacement (:meth:`Rolling.contact_row`); None: the patch is
    #: ground-fixed.
    contact: "Rolling | None" = None
    model = "static_load"

    @property
    def static_stiffness(self) -> float:
        return 0.0

    def force_row(self, layout: StateLayout) -> np.ndarray:
        r = layout.row(self.stiffness * np.asarray(self.d, float), np.zeros(layout.nq))
        if self.contact is not None:
            r -= self.stiffness * self.contact.contact_row(layout)
        return r


_KINDS = {"kelvin_voigt": SpringDamper, "maxwell": Maxwell, "rolling": Rolling}


def element(name: str, g, stiffness: float, damping: float, model: str = "kelvin_voigt", gate=(),
            series_damping: float = np.inf) -> Element:
    """An element of the horizontal ``model`` (``"kelvin_voigt"``, ``"maxwell"`` or ``"rolling"``
    with its ``series_damping`` in N s/m, ``inf``: locked).

    See Also
    --------
    tyrelab.vehicle.tyres.build_parts : the tyre elements of a tractor.

    Examples
    --------
    >>> e = element("rear_longitudinal", np.array([1.0, 0.8]), 9.1e5, 6e3, "maxwell")
    >>> type(e).__name__, e.states()
    ('Maxwell', ('q_rear_longitudinal',))
    """
    if model not in _KINDS:
        raise ValueError(f"model {model!r}: expected one of {tuple(_KINDS)}")
    if model == "rolling":
        return Rolling(name, np.asarray(g, float), float(stiffness), float(damping), tuple(gate),
                       series_damping=float(series_damping))
    return _KINDS[model](name, np.asarray(g, float), float(stiffness), float(damping), tuple(gate))
