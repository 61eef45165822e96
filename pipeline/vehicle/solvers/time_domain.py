"""The time domain of an assembled model (issue 45: the solver the tractor and the ride scenarios
share): exact while every tyre is on the ground, RK4 across lift-off (:func:`simulate`).

Any tractor assembled from parts (:func:`tyrelab.vehicle.model.assemble`) is simulated here; the
equations are the assembly's (its linear model for the exact path, its force elements for the
nonlinear right-hand side), none are written in this module. Two solution paths, switched within
a run (``method="auto"``):

* while every tyre stays in contact the model is linear: its exact discretisation for
  inputs linear between the ``dt/2`` samples (first-order hold, :mod:`tyrelab.vehicle.solvers.lti`
  on :meth:`tyrelab.vehicle.model.Assembly.linear`);
* across a lift-off (the exact solution's tyre force would pull at a half step) the run goes
  back to its last sample in contact and continues with the nonlinear fixed-step RK4 at
  ``dt`` (the thesis used Runge-Kutta-Nystrom at about 1 ms) until every tyre has stayed on
  the ground for :data:`CALM_STEPS` steps, then exactly again from the RK4 state
  (``method_used`` ``"exact+rk4"``). The RK4 parts of all runs of a batch advance together,
  vectorised, each run at its own sample; the runs may differ in their parts, so a whole study
  is one batch.

The pitch-plane tractor of thesis ch. 7 as twelve numbers is :mod:`tyrelab.vehicle.tractor`.
"""

from __future__ import annotations

import numpy as np

from ... import _validate
from ..model import Assembly, coordinate_output
from . import lti

__all__ = ["simulate", "off_ground", "INTEGRATION_METHODS", "CALM_STEPS", "RECORDED_OUTPUTS", "LIFT_OFF_RTOL"]

#: Solution paths of :func:`simulate` (its ``method``): exact while in contact, switched to RK4
#: across lift-off (``auto``), or RK4 throughout.
INTEGRATION_METHODS = ("auto", "rk4")
#: The name of :data:`INTEGRATION_METHODS` before issue 45 (``[simulation] method`` is
#: :data:`tyrelab.vehicle.scenario.limits.RIDE_METHODS`): still importable, not in ``__all__``.
METHODS = INTEGRATION_METHODS
#: What :func:`simulate` records per sample unless told (the pitch-plane tractor's outputs,
#: :data:`tyrelab.vehicle.tractor.TRACTOR_OUTPUTS`).
RECORDED_OUTPUTS = ("vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2", "z_m", "theta_rad")

#: A tyre is off the ground where its dynamic force reaches minus its static load: to this relative
#: rounding (the nonlinear model clamps the force at exactly that; the linear model's force that
#: would pull is tested the same way). The one lift-off test (issue 45): the exact path's switch to
#: RK4 here and the ride's lift-off fractions (:mod:`tyrelab.vehicle.run.time`) both call
#: :func:`off_ground`.
LIFT_OFF_RTOL = 1e-6


def off_ground(force_N, static_N) -> np.ndarray:
    """Where a tyre is off the ground (or would pull, in the linear model): its dynamic force at or
    below minus its static load (N), to :data:`LIFT_OFF_RTOL`.

    See Also
    --------
    simulate : whose exact path leaves for RK4 where a tyre is off the ground.

    Examples
    --------
    >>> off_ground(np.array([-50.0, -99.99999999, -120.0]), 100.0).tolist()
    [False, True, True]
    """
    return np.asarray(force_N) <= -np.asarray(static_N) * (1 - LIFT_OFF_RTOL)


#: Switched path: steps (of ``dt``) every tyre must stay in contact, at every RK4 stage, before a
#: run returns from RK4 to the exact path (20 ms at 1 ms: a tyre that bounces straight off again
#: stays on RK4; on the ch. 7 batch 10-20 steps cost least, 5 and 50 about 10-30 % more CPU).
CALM_STEPS = 20
#: Switched path: samples of the first exact segment after a return from RK4, doubled for each
#: further segment in contact up to ``EXACT_CHUNK_MAX`` (after the first, whole-record, attempt),
#: so the cost of a return to the exact path follows the length it stays in contact.
EXACT_CHUNK = 256
EXACT_CHUNK_MAX = 4096


# --------------------------------------------------------------------------- the batch RHS
class _Batch:
    """The assemblies of a batch's runs, as arrays with the runs last, on their one state layout
    (:attr:`tyrelab.vehicle.model.Assembly.layout`, shared: :func:`simulate` batches runs of one
    structure only, :func:`_structure`), so a run alone gives the same bits as in any batch
    (:class:`_Kernel`: one matrix product per run, whose sums depend on the matrix only).

    Element slots: the tyres (ground input, floor), then the elements without states of their
    own, then those with (a Maxwell element's extension); each element's rows are its kind's
    (:mod:`tyrelab.vehicle.elements`), the same the linear model is built from."""

    def __init__(self, assemblies: list[Assembly], record: tuple[str, ...], lift_off: bool):
        runs = len(assemblies)
        first = assemblies[0]
        lay = first.layout
        self.coordinates, self.tyres, self.states = first.coordinates, first.tyres, lay.states
        order = _slots(first)
        own = [s for e in order for s in e.states()]
        nq, nt, n, ns, n_el = len(self.coordinates), len(self.tyres), lay.n, len(own), len(order)
        self.nq, self.nt, self.n, self.ns, self.n_el = nq, nt, n, ns, n_el
        self.n_pos = n - nq - ns
        self.seen = [j for j in range(nq) if lay.pos_cols[j] is not None]
        width = n + 2 * nt
        # kernel columns [states, u (per tyre), u' (per tyre)] from the layout's [states, u, u' per tyre]
        cols = np.empty(lay.width, dtype=np.intp)
        cols[:n] = np.arange(n)
        cols[n::2], cols[n + 1::2] = n + np.arange(nt), n + nt + np.arange(nt)
        self.a = np.zeros((n_el + ns, width, runs))
        # own states while their element's tyres are off the ground (Element.free_rows: a rolling
        # tyre's contact point re-seats, issue 42) and the gated slot each own state follows
        self.a_free = np.zeros((ns, width, runs))
        self.own_slot = np.zeros(ns, dtype=np.intp)
        self.g = np.zeros((n_el, nq, runs))
        self.floor, self.static = np.zeros((2, nt, runs))
        self.gate_w = np.zeros((n_el - nt, nt, runs))
        self.gate_on = np.zeros((n_el - nt, runs))
        self.minv = np.zeros((nq, nq, runs))
        self.outputs = tuple(record)
        no = len(record)
        self.r_acc = np.zeros((no, nq, runs))
        self.r_q = np.zeros((no, n, runs))
        self.r_f = np.zeros((no, nt, runs))
        state_rows = {lay.index[s]: i for i, s in enumerate(own)}
        for r, asm in enumerate(assemblies):
            alay = asm.layout
            self.minv[:, :, r] = _inverse(asm.mass)
            for j, e in enumerate(_slots(asm)):
                self.a[j, cols, r] = e.force_row(alay)
                self.g[j, :, r] = e.weight * e.g
                if j < nt:
                    self.static[j, r] = e.floor_N
                    self.floor[j, r] = e.floor_N if lift_off else -np.inf
                else:
                    self.gate_w[j - nt, :, r] = [1.0 / len(e.gate) if t in e.gate else 0.0 for t in self.tyres]
                    self.gate_on[j - nt, r] = 0.0 if e.gate else 1.0
                for s, row in e.derivative_rows(alay).items():
                    self.a[n_el + state_rows[alay.index[s]], cols, r] = row
                for s, row in e.free_rows(alay).items():
                    self.a_free[state_rows[alay.index[s]], cols, r] = row
                    self.own_slot[state_rows[alay.index[s]]] = j - nt
            for o, name in enumerate(record):
                if name in asm.kinematic_outputs:
                    r_acc, r_tilt = asm.kinematic_outputs[name]
                    self.r_acc[o, :, r] = r_acc
                    if r_tilt is not None:
                        self.r_q[o, :, r] = alay.row(asm.gravity_m_s2 * r_tilt, np.zeros(nq))[:n]
                elif name.endswith("_force_N"):
                    tyre = name[:-len("_force_N")]
                    self.r_f[o, :, r] = [1.0 if (t == tyre or (t.startswith(tyre) and tyre in ("front", "rear")))
                                         else 0.0 for t in self.tyres]
                else:
                    match = [c for c in asm.coordinates if coordinate_output(c) == name]
                    if not match or alay.pos_cols[asm.coordinates.index(match[0])] is None:
                        raise ValueError(f"record: unknown output {name!r}")
                    self.r_q[o, alay.pos_cols[asm.coordinates.index(match[0])], r] = 1.0
        self.gated = bool(np.any(self.gate_w))
        # own states whose derivative off the ground differs from that in contact
        self.reseat = bool(ns) and self.gated and not np.array_equal(self.a_free, self.a[n_el:])

    @property
    def size(self) -> int:
        """Length of the state (the assemblies' layout)."""
        return self.n

    def kernel(self, runs: np.ndarray) -> "_Kernel":
        """The right-hand side of the runs ``runs`` (indices into the batch), precomputed."""
        return _Kernel(self, np.asarray(runs, dtype=np.intp))


def _slots(asm: Assembly) -> list:
    """The elements in their kernel order: tyres (the assembly's order), then the elements without
    states of their own, then those with."""
    rest = [e for e in asm.elements if e.input is None]
    return ([e for e in asm.elements if e.input is not None] + [e for e in rest if not e.states()]
            + [e for e in rest if e.states()])


class _Kernel:
    """The nonlinear right-hand side of some runs of a :class:`_Batch`, as a few whole-batch matrix
    products: everything that does not change from step to step is worked out here, once.

    Runs first (``(runs, ...)``, one small matrix per run, :func:`numpy.matmul` over the stack).
    A stage's buffer ``E`` (runs, W + N + S) holds ``[x, u, u']`` (W = states + 2 tyres) and,
    after :meth:`rhs`, the elements' quantities ``F`` (N: tyre and spring-damper forces, Maxwell
    extensions) and their own states' derivatives (S):

    * ``[F, x_own'] = A E[:W]`` — each element's :meth:`~tyrelab.vehicle.elements.Element.force_row`
      and :meth:`~tyrelab.vehicle.elements.Element.derivative_rows` (one product);
    * tyres clamped at their floor (lift-off); gated elements (acting while their tyres touch)
      times ``G [contact, 1]``;
    * ``q'' = P F`` with ``P = -M⁻¹ [weight g]ᵀ``;
    * the recorded outputs ``R [E[:W], F]`` (accelerations ``r_acc P F``, positions, forces).
    """

    def __init__(self, b: _Batch, runs: np.ndarray):
        nq, nt, n_el, ns, n = b.nq, b.nt, b.n_el, b.ns, b.n
        width = n + 2 * nt
        count = runs.size

        def take(x):  # (..., runs) -> (runs, ...)
            return np.moveaxis(x[..., runs], -1, 0)

        a = np.ascontiguousarray(take(b.a))
        p = -np.matmul(take(b.minv), np.swapaxes(take(b.g), 1, 2))  # (runs, nq, N)
        r_acc, r_q, r_f = take(b.r_acc), take(b.r_q), take(b.r_f)
        no = r_acc.shape[1]
        r = np.zeros((count, no, width + n_el + ns))
        r[:, :, :n] = r_q
        r[:, :, width:width + n_el] = np.matmul(r_acc, p)
        r[:, :, width:width + nt] += r_f
        self.a, self.p, self.r = a, p, r
        self.floor = np.ascontiguousarray(take(b.floor))
        self.gated = b.gated
        if b.gated:  # gate factor of every non-tyre element: [gate weights per tyre, gate_on]
            self.gw = np.concatenate([take(b.gate_w), take(b.gate_on)[:, :, None]], axis=2)  # (runs, N - nt, nt + 1)
        self.reseat = b.reseat
        if b.reseat:  # a lifted element's own states: blended by its gate factor with their free rows
            self.a_free = np.ascontiguousarray(take(b.a_free))
            self.own_slot = b.own_slot
        self.seen = None if len(b.seen) == nq else np.array(b.seen, dtype=np.intp)
        self.nq, self.nt, self.ns, self.n_pos, self.size, self.width, self.n_el = nq, nt, ns, b.n_pos, n, width, n_el
        self.count, self.no = count, no

    def buffers(self):
        """A stage's work arrays: ``E`` (runs, W + N + S), the derivative ``K`` (runs, size) and the
        lifted tyres ``L`` (runs, tyres)."""
        return (np.zeros((self.count, self.width + self.n_el + self.ns)), np.zeros((self.count, self.size)),
                np.zeros((self.count, self.nt), dtype=bool))

    def bind(self, e: np.ndarray, k: np.ndarray, lifted: np.ndarray):
        """A function of no arguments that writes ``k`` = the state derivative and ``lifted`` =
        the tyres off the ground from the state and inputs in ``e[:, :W]`` at the call, and the
        element quantities into ``e[:, W:]`` (every view taken once, here)."""
        matmul, maximum, less_equal, greater, multiply, copyto, take_ = (
            np.matmul, np.maximum, np.less_equal, np.greater, np.multiply, np.copyto, np.take)
        nq, nt, w, n_el, n_pos = self.nq, self.nt, self.width, self.n_el, self.n_pos
        a, p, floor = self.a, self.p, self.floor
        e_in, f_all = e[:, :w, None], e[:, w:, None]
        f3 = e[:, w:w + n_el, None]
        f_tyre, f_gated, d_own = e[:, w:w + nt], e[:, w + nt:w + n_el], e[:, w + n_el:]
        k_acc, k_q, k_s = k[:, n_pos:n_pos + nq, None], k[:, :n_pos], k[:, n_pos + nq:]
        velocity = e[:, n_pos:n_pos + nq]
        seen = self.seen
        if seen is not None and np.array_equal(seen, np.arange(seen[0], seen[0] + seen.size)):
            velocity, seen = velocity[:, seen[0]:seen[0] + seen.size], None  # contiguous: a view, no gather
        has_s, gated, count_nonzero = self.ns > 0, self.gated, np.count_nonzero
        reseat = self.reseat
        if reseat:
            a_free, own_slot = self.a_free, self.own_slot
        # with every tyre on the ground the clamp is max(f, floor) = f and every gate factor is
        # exactly 1 (weights 1/len(gate) that sum to 1 in floating point): both may be skipped, to the bit
        contact_is_identity = not gated or bool(np.all(np.matmul(self.gw, np.ones((self.count, nt + 1, 1))) == 1.0))
        if gated:
            gw = self.gw
            contact = np.ones((self.count, nt + 1))
            contact3, tyres_contact = contact[:, :, None], contact[:, :nt]
            factor = np.empty((self.count, n_el - nt))
            factor3 = factor[:, :, None]

        def rhs() -> None:
            matmul(a, e_in, out=f_all)
            less_equal(f_tyre, floor, out=lifted)
            if has_s:
                copyto(k_s, d_own)
            if not contact_is_identity or count_nonzero(lifted):  # else clamp and gates change nothing
                maximum(f_tyre, floor, out=f_tyre)
                if gated:
                    greater(f_tyre, floor, out=tyres_contact)
                    matmul(gw, contact3, out=factor3)
                    multiply(f_gated, factor, out=f_gated)
                    if reseat:  # k_s = g d_own + (1 - g) free, g the gate factor of each own state's element
                        g_own = factor[:, own_slot]
                        free = matmul(a_free, e_in)[:, :, 0]
                        k_s[:] = g_own * d_own + (1.0 - g_own) * free
            matmul(p, f3, out=k_acc)
            if seen is None:
                copyto(k_q, velocity)
            else:
                take_(velocity, seen, axis=1, out=k_q)

        return rhs


def _inverse(mass: np.ndarray) -> np.ndarray:
    """``M⁻¹``; a diagonal ``M`` exactly ``1/m`` on the diagonal."""
    if np.count_nonzero(mass - np.diag(np.diag(mass))) == 0:
        return np.diag(1.0 / np.diag(mass))
    return np.linalg.inv(mass)


# --------------------------------------------------------------------------- exact path
class _Exact:
    """Exact path of one run, resumable: solves from a sample until a tyre would lift off. Its
    states are the RK4's (the assembly's one layout): a switch hands the state over as it is."""

    def __init__(self, asm: Assembly, batch: _Batch, r: int, u: np.ndarray, du: np.ndarray, dt_s: float):
        forces = tuple(f"{t}_force_N" for t in asm.tyres)
        self.record = batch.outputs
        lm = asm.linear(tuple(self.record) + forces)
        self.system = lti.discretise(*lm.abcd, dt_s / 2)
        self.n_rec = len(self.record)
        # inputs [u_t, u_t', ...] at dt/2
        self.inputs = np.empty((2 * len(asm.tyres), u.shape[1]))
        self.inputs[0::2], self.inputs[1::2] = u, du
        self.floors = batch.static[:, r]
        self.n = (u.shape[1] + 1) // 2
        self._rows = [i for i, o in enumerate(self.record) if o.endswith("_rad") or o.endswith("_m")]

    def solve(self, k0: int, y, out: dict, row: int, lift_off: bool, chunk: int | None = None):
        """Fill ``out[.][row, k0:k]`` exactly from the state ``y`` at sample ``k0`` (``None``:
        rest); return ``(k, y_k)`` with ``k`` the last sample before a tyre would lift off (RK4
        takes over there), or ``(n, None)`` when the record ends in contact."""
        x = None if y is None else np.asarray(y, float)
        pos = k0
        nr, nt = self.n_rec, len(self.floors)
        while True:
            stop = self.n - 1 if chunk is None else min(self.n - 1, pos + chunk)
            kept = self.system.modes(self.inputs[:, 2 * pos:2 * stop + 1], x)
            # the tyre forces at every half step (the RK4 judges contact at the half steps too: so
            # does this check), the outputs only at the whole steps up to the first lift-off
            if lift_off:
                forces = self.system.outputs(kept, range(nr, nr + nt))
                hit = np.flatnonzero(np.any(off_ground(forces, -self.floors[:, None]), axis=0))[:1]
            else:
                hit = []
            end = max(pos, pos + (int(hit[0]) - 1) // 2) if len(hit) else stop + (stop == self.n - 1)
            m = end - pos
            y = self.system.outputs(kept, range(nr), 2 * m, 2)
            if x is None and m:
                y[self._rows, 0] = 0.0  # at rest at the first sample exactly (the modal transform leaves ~1e-22)
            for key, r in zip(self.record, range(nr)):
                out[key][row, pos:end] = y[r]
            if len(hit):
                return end, np.array(self.system.state_at(kept, 2 * m), float)
            if end == self.n:
                return self.n, None
            x, pos = self.system.state_at(kept, 2 * (stop - pos)), stop
            chunk = min(2 * chunk, EXACT_CHUNK_MAX) if chunk else None  # in contact for the whole chunk: look further

# --------------------------------------------------------------------------- simulate
def simulate(
    assemblies: list[Assembly],
    u_half,
    du_half,
    dt_s: float = 1e-3,
    lift_off: bool = True,
    gravity_m_s2: float | None = None,
    method: str = "auto",
    record: tuple[str, ...] = RECORDED_OUTPUTS,
) -> dict[str, np.ndarray]:
    """Simulate assembled tractors: exact while every tyre is in contact, RK4 across lift-off.

    ``method="rk4"`` integrates every run with the nonlinear fixed-step RK4 at ``dt``. ``"auto"``
    (default) solves each run exactly in its linear model (on the ``dt/2`` samples); a run whose
    tyre would lift off (``lift_off``; judged at the half steps, as the RK4 does) switches within
    the run: exact up to the last sample before the first lift-off, RK4 from that sample until
    every tyre has stayed in contact at every RK4 stage for :data:`CALM_STEPS` steps, exact again
    from there, and so on. The RK4 parts of all such runs advance together.

    Parameters
    ----------
    assemblies : list of Assembly
        One per run (:func:`tyrelab.vehicle.model.assemble`), all with the same tyres.
    u_half, du_half : array_like, shape (runs, tyres, 2N-1)
        Ground elevation (m) and rate (m/s) under each tyre element (the assembly's ``tyres``
        order) at ``dt/2``.
    dt_s : float
        Step, s.
    lift_off : bool
        Let tyres leave the ground.
    gravity_m_s2 : float, optional
        Each assembly's own (:func:`~tyrelab.vehicle.model.assemble` sets it: the lift-off floors
        and the ``*_tilt`` readings); a value given must be theirs.
    method : str
        One of :data:`INTEGRATION_METHODS`.
    record : tuple of str
        Outputs recorded per sample: kinematic outputs of the assembly, coordinates
        (``z_m``, ``theta_rad``, ...) and tyre or axle forces (``<tyre>_force_N``; in the
        RK4 parts the clamped force, i.e. what the ground carries, minus the static load).

    Returns
    -------
    dict
        Each ``record`` name (runs, N); ``lift_off_fraction_<tyre>`` (runs) the fraction of the
        samples at which the tyre is off the ground; ``method_used`` per run.

    See Also
    --------
    tyrelab.vehicle.model.assemble : the assemblies it takes.
    tyrelab.vehicle.tractor.simulate_tractor : the pitch-plane tractor through it.

    Examples
    --------
    >>> from tyrelab.vehicle.model import Axle, Chassis, Parts, assemble
    >>> asm = assemble(Parts(Chassis(5120.0, 6210.0, 0.838), Axle("front", 1.54, 4.25e5, 1.5e3),
    ...                      Axle("rear", -0.896, 3.3e5, 1e3)))
    >>> u = np.full((1, 2, 6001), 0.01); du = np.zeros_like(u)          # 6 s on ground raised by 10 mm
    >>> r = simulate([asm], u, du, record=("z_m",))
    >>> r["z_m"].shape, list(r["method_used"]), round(float(r["z_m"][0].max()), 4)  # overshoots, tyres in contact
    ((1, 3001), ['exact'], 0.0175)
    >>> u[:, :, 100:] = 0.3                                               # a 300 mm step: the tyres leave the ground
    >>> list(simulate([asm], u - 0.01, du, record=("z_m",))["method_used"])
    ['exact+rk4']
    """
    if method not in INTEGRATION_METHODS:
        raise ValueError(f"method {method!r}: expected one of {INTEGRATION_METHODS}")
    dt_s = _validate.positive("dt_s", dt_s)
    u = np.asarray(u_half, float)
    du = np.asarray(du_half, float)
    runs = len(assemblies)
    if u.ndim != 3 or u.shape != du.shape or u.shape[0] != runs:
        raise ValueError(f"u_half, du_half: expected shape ({runs}, tyres, 2N-1), got {u.shape} and {du.shape}")
    if u.shape[2] % 2 == 0:
        raise ValueError("u_half: inputs must be sampled at dt/2 (odd length)")
    if gravity_m_s2 is not None and any(asm.gravity_m_s2 != gravity_m_s2 for asm in assemblies):
        raise ValueError(f"gravity_m_s2 {gravity_m_s2!r}: the assemblies were assembled under "
                         f"{sorted({asm.gravity_m_s2 for asm in assemblies})} (assemble(parts, gravity_m_s2=...))")
    tyres = tuple(assemblies[0].tyres) if runs else ()
    if any(tuple(asm.tyres) != tyres for asm in assemblies):
        raise ValueError(f"assemblies: every run must have the same tyres (the first has {', '.join(tyres)})")
    n = (u.shape[2] + 1) // 2
    out = {k: np.empty((runs, n)) for k in record}
    off = np.zeros((len(tyres), runs))
    used = np.array(["exact"] * runs, dtype=object)
    groups: dict[tuple, list[int]] = {}
    for i, asm in enumerate(assemblies):
        groups.setdefault(_structure(asm), []).append(i)
    for members in groups.values():  # each run's arithmetic is that of its own structure, alone or in any batch
        rows = np.array(members)
        part = {k: np.empty((rows.size, n)) for k in record}
        part_off = np.zeros_like(off[:, rows])
        used[rows] = _simulate_group([assemblies[i] for i in members], u[rows], du[rows], dt_s, lift_off, method,
                                     tuple(record), part, part_off)
        for k in record:
            out[k][rows] = part[k]
        off[:, rows] = part_off
    out.update({f"lift_off_fraction_{t}": off[j] / n for j, t in enumerate(tyres)})
    out["method_used"] = used
    return out


def _structure(asm: Assembly) -> tuple:
    """What sets the shape of a run's arrays in a batch: its coordinates, tyres, states and element slots.
    Runs of one structure share a :class:`_Batch`, so that no run sums another's zero terms (the
    order of a matrix product's sums depends on its length): a run gives the same bits alone as
    in any batch."""
    return (tuple(asm.coordinates), tuple(asm.tyres), tuple(asm.state_names()),
            tuple((e.name, type(e).__name__, e.states()) for e in asm.elements))


def _simulate_group(assemblies, u, du, dt_s, lift_off, method, record, out, off) -> np.ndarray:
    """:func:`simulate` of runs of one structure (:func:`_structure`) into ``out``/``off``; the
    method used per run."""
    runs, n = len(assemblies), (u.shape[2] + 1) // 2
    batch = _Batch(assemblies, record, lift_off)
    used = np.array(["exact"] * runs, dtype=object)
    switched = []  # (run, exact path or None, sample where RK4 takes over, RK4 state there)
    if method == "rk4":
        switched = [(i, None, 0, np.zeros(batch.size)) for i in range(runs)]
        used[:] = "rk4"
    else:
        for i in range(runs):
            exact = _Exact(assemblies[i], batch, i, u[i], du[i], dt_s)
            k, y = exact.solve(0, None, out, i, lift_off)
            if k < n:
                switched.append((i, exact, k, y))
                used[i] = "exact+rk4"
    if switched:
        _run_switched(batch, u, du, dt_s, lift_off, switched, out, off)
    return used


def _run_switched(batch: _Batch, u, du, dt_s, lift_off, switched, out, off) -> None:
    """RK4 across the lift-off intervals of the ``switched`` runs, the exact path in between.

    All runs advance together, each at its own sample; a run that has ended (or gone back to the
    exact path for good) is still computed, its results go nowhere. Arrays are runs first; the
    right-hand side is :class:`_Kernel`'s (four stage buffers, bound once)."""
    idx = np.array([s[0] for s in switched])
    exact = [s[1] for s in switched]
    returns = np.array([e is not None for e in exact])
    may_return = bool(returns.any())
    count, n = idx.size, (u.shape[2] + 1) // 2
    kern = batch.kernel(idx)
    nt, size, w = batch.nt, kern.size, kern.width
    # inputs of every run at every half step, [u, u'] per row, each padded with its last sample
    # twice (the stages past the last sample read it, as a clamped index would)
    span = 2 * n + 1
    inputs = np.empty((count, span, 2 * nt))
    inputs[:, :2 * n - 1, :nt] = u[idx].transpose(0, 2, 1)
    inputs[:, :2 * n - 1, nt:] = du[idx].transpose(0, 2, 1)
    inputs[:, 2 * n - 1:] = inputs[:, 2 * n - 2: 2 * n - 1]
    flat_in = inputs.reshape(count * span, 2 * nt)
    record = batch.outputs
    res = np.empty((count, n + 1, len(record)))  # the last sample a sink for the runs no longer recording
    for i, key in enumerate(record):
        res[:, :n, i] = out[key][idx]
    views = {key: res[:, :n, i] for i, key in enumerate(record)}
    res_flat = res.reshape(count * (n + 1), len(record))
    rows = np.arange(count)
    res_start, sink = rows * (n + 1), rows * (n + 1) + n
    stages = [kern.buffers() for _ in range(4)]
    rhs = [kern.bind(*b) for b in stages]
    (e1, k1, l1), (e2, k2, l2), (e3, k3, l3), (e4, k4, l4) = stages
    y = e1[:, :size]  # the state lives in the first stage's buffer
    y[...] = np.array([s[3] for s in switched], float)
    state2, state3, state4 = e2[:, :size], e3[:, :size], e4[:, :size]
    in1, in2, in3, in4 = (e[:, size:w] for e in (e1, e2, e3, e4))
    rec3 = np.empty((count, len(record), 1))
    rec = rec3[:, :, 0]
    r_all, e1_all = kern.r, e1[:, :, None]
    k = np.array([s[2] for s in switched], dtype=np.intp)
    calm = np.zeros(count, dtype=int)
    active = np.ones(count, dtype=bool)
    offs = np.zeros((count, nt))
    both = np.empty((count, nt), dtype=bool)
    any_lift = np.empty((count, nt), dtype=bool)
    last = n - 1
    h = dt_s
    half_h, sixth_h, two = np.float64(0.5 * h), np.float64(h / 6.0), np.float64(2.0)
    full_h = np.float64(h)
    t1, t2 = np.empty((2, count, size))
    base = rows * span
    add, multiply, copyto, take = np.add, np.multiply, np.copyto, np.take

    while active.any():
        at = base + 2 * k
        take(flat_in, at, axis=0, out=in1, mode="clip")
        rhs[0]()
        pos = np.where(active, res_start + k, sink)
        np.matmul(r_all, e1_all, out=rec3)
        res_flat[pos] = rec
        np.logical_and(l1, active[:, None], out=both)
        offs += both
        step = (k != last) & active
        multiply(k1, half_h, out=t1)
        add(y, t1, out=state2)
        take(flat_in, at + 1, axis=0, out=in2, mode="clip")
        rhs[1]()
        multiply(k2, half_h, out=t1)
        add(y, t1, out=state3)
        copyto(in3, in2)
        rhs[2]()
        multiply(k3, full_h, out=t1)
        add(y, t1, out=state4)
        take(flat_in, at + 2, axis=0, out=in4, mode="clip")
        rhs[3]()
        # y + h/6 (k1 + 2 k2 + 2 k3 + k4), summed in that order
        multiply(k2, two, out=t1)
        add(k1, t1, out=t1)
        multiply(k3, two, out=t2)
        add(t1, t2, out=t1)
        add(t1, k4, out=t1)
        multiply(t1, sixth_h, out=t1)
        add(y, t1, out=t1)
        copyto(y, t1, where=step[:, None])
        k += step
        active = step
        if may_return:
            np.logical_or(l1, l2, out=any_lift)
            np.logical_or(any_lift, l3, out=any_lift)
            np.logical_or(any_lift, l4, out=any_lift)
            calm += 1
            calm[any_lift.any(axis=1)] = 0
            back = (calm >= CALM_STEPS) & step & returns
            for r in np.flatnonzero(back):  # back in contact for a while: exact again
                kr, yr = exact[r].solve(int(k[r]), y[r].copy(), views, r, lift_off, chunk=EXACT_CHUNK)
                if yr is None:
                    active[r] = False
                else:
                    k[r], y[r], calm[r] = kr, yr, 0
    for key in record:
        out[key][idx] = views[key]
    off[:, idx] = offs.T
