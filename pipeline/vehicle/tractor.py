"""Pitch-plane tractor model (thesis ch. 7, MF698T of Table XV).

Rigid body with vertical ``z`` (up), pitch ``theta`` (nose up) and longitudinal
``x`` (forward) freedom, small angles. Front axle ``a`` ahead of, rear axle ``b``
behind the centre of gravity (CG) at height ``h``. Each axle carries a Kelvin-Voigt
vertical tyre element (both tyres of the axle together) that may lift off (total
tyre force never pulls). The rear tyres may carry a longitudinal element acting at
the ground contact, ``h`` below the CG, either Kelvin-Voigt (spring and damper in
parallel, as the thesis' ADAMS model, §7.3) or Maxwell (spring and damper in series,
which §7.5 argues describes rolling tyres better)::

    z_f = z + a theta,  z_r = z - b theta,  d = x + h theta     (rear contact, fore-aft)
    F_f = max(K_f (u_f - z_f) + C_f (u_f' - z_f'), -W_f)        (same for the rear)
    Kelvin-Voigt: F_x = -(k_x d + c_x d');  Maxwell: F_x = -k_x (d - s), c_x s' = k_x (d - s)
    M z'' = F_f + F_r;  I theta'' = a F_f - b F_r + h F_x;  M x'' = F_x

The rear wheel sees the front wheel's input delayed by wheelbase/speed. The thesis'
model was a 7-DOF ADAMS model with front-axle roll (§7.3); in the pitch plane the
vertical, longitudinal and pitch motions are independent of roll, lateral and yaw
(Stayner, Collins and Lines 1984), so the pitch-plane model carries the same
information for Tables XVII/XVIII. SI units.

Two solution paths, switched within a run by :func:`simulate_tractor` (``method="auto"``):

* while both axles stay in contact the model is linear (the longitudinal element
  acts only in contact, which then always holds): :func:`linear_response` is its
  exact discretisation for inputs linear between the ``dt/2`` samples (first-order
  hold, :mod:`tyrelab.vehicle.lti` on :func:`tyrelab.vehicle.ride.state_space`, the
  carriage's method);
* across a lift-off (the exact solution's total tyre force would pull at a half step) the
  run goes back to its last sample in contact and continues with the nonlinear fixed-step
  RK4 at ``dt`` (the thesis used Runge-Kutta-Nystrom at about 1 ms) until both tyres have
  stayed on the ground for :data:`CALM_STEPS` steps, then exactly again from the RK4
  state (``method_used`` ``"exact+rk4"``). The RK4 parts of all runs of a batch advance
  together, vectorised, each run at its own sample; the longitudinal model may differ
  per run, so a whole study is one batch.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from .carriage import GRAVITY_M_S2

__all__ = ["Tractor", "simulate_tractor", "linear_response", "LONGITUDINAL_MODELS", "METHODS", "CALM_STEPS", "PARAMETERS"]

#: Solution paths of :func:`simulate_tractor`.
METHODS = ("auto", "rk4")
#: Outputs of one run.
_OUTPUTS = ("vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2", "z_m", "theta_rad")

#: Rear longitudinal element: none, Kelvin-Voigt (parallel) or Maxwell (series).
LONGITUDINAL_MODELS = ("none", "kelvin_voigt", "maxwell")


@dataclass(frozen=True)
class Tractor:
    """Pitch-plane tractor parameters; any field may be an array (one per run).

    Attributes
    ----------
    mass_kg, pitch_inertia_kg_m2 : float
        Mass and pitch moment of inertia about the CG.
    front_distance_m, rear_distance_m : float
        Horizontal CG-to-axle distances a (front) and b (rear), m.
    cg_height_m : float
        CG height above the ground, m (lever arm of the longitudinal force).
    front_stiffness_N_per_m, rear_stiffness_N_per_m : float
        Axle vertical stiffness (two tyres), N/m.
    front_damping_N_s_per_m, rear_damping_N_s_per_m : float
        Axle vertical damping (two tyres), N s/m.
    longitudinal_stiffness_N_per_m, longitudinal_damping_N_s_per_m : float
        Rear axle longitudinal element (two tyres), N/m and N s/m.
    longitudinal_model : str or array of str
        One of :data:`LONGITUDINAL_MODELS`, for the whole batch or one per run.
    """

    mass_kg: float
    pitch_inertia_kg_m2: float
    front_distance_m: float
    rear_distance_m: float
    cg_height_m: float
    front_stiffness_N_per_m: float
    rear_stiffness_N_per_m: float
    front_damping_N_s_per_m: float
    rear_damping_N_s_per_m: float
    longitudinal_stiffness_N_per_m: float = 0.0
    longitudinal_damping_N_s_per_m: float = 0.0
    longitudinal_model: str = "none"

    @property
    def wheelbase_m(self):
        """Wheelbase a + b, m."""
        return np.asarray(self.front_distance_m) + np.asarray(self.rear_distance_m)


#: The numeric parameters of :class:`Tractor`, in field order (all but ``longitudinal_model``).
PARAMETERS = tuple(f.name for f in fields(Tractor) if f.name != "longitudinal_model")

#: Switched path: steps (of ``dt``) both tyres must stay in contact, at every RK4 stage, before a
#: run returns from RK4 to the exact path (20 ms at 1 ms: a tyre that bounces straight off again
#: stays on RK4; on the ch. 7 batch 10-20 steps cost least, 5 and 50 about 10-30 % more CPU).
CALM_STEPS = 20
#: Switched path: samples of the first exact segment after a return from RK4, doubled for each
#: further segment in contact up to ``EXACT_CHUNK_MAX`` (after the first, whole-record, attempt),
#: so the cost of a return to the exact path follows the length it stays in contact.
EXACT_CHUNK = 256
EXACT_CHUNK_MAX = 4096


def _params(tractor: Tractor, runs: int) -> dict[str, np.ndarray]:
    return {k: np.broadcast_to(np.asarray(getattr(tractor, k), float), (runs,)) for k in PARAMETERS}


def _models(tractor: Tractor, runs: int) -> np.ndarray:
    """``longitudinal_model`` per run (a string for all runs, or one per run), checked."""
    models = np.asarray(tractor.longitudinal_model, dtype=object)
    if models.ndim > 1 or (models.ndim == 1 and models.size != runs):
        raise ValueError(f"longitudinal_model: expected one value or {runs} (one per run), got shape {models.shape}")
    bad = sorted({str(m) for m in models.ravel()} - set(LONGITUDINAL_MODELS))
    if bad:
        raise ValueError(f"longitudinal_model {bad[0]!r}: expected one of {LONGITUDINAL_MODELS}")
    return np.broadcast_to(models, (runs,))


def _scalar(p: dict[str, np.ndarray], models: np.ndarray, i: int) -> Tractor:
    return Tractor(**{k: float(v[i]) for k, v in p.items()}, longitudinal_model=str(models[i]))


def _exact_system(tractor: Tractor, dt_s: float):
    """The linear model of one run, discretised: outputs vertical, pitch, longitudinal, front and
    rear dynamic tyre force, ``z`` and ``θ``; and its states' names
    (:func:`tyrelab.vehicle.ride.state_names`)."""
    from . import lti
    from .ride import state_names, state_space  # ride imports this module

    a, b, c, d = state_space(tractor)
    n = a.shape[0]
    c = np.vstack([c[2:7], np.eye(n)[:2]])  # z, θ are states 0 and 1
    d = np.vstack([d[2:7], np.zeros((2, d.shape[1]))])
    return lti.discretise(a, b, c, d, dt_s), state_names(tractor)


def linear_response(tractor: Tractor, inputs: np.ndarray, dt_s: float) -> dict[str, np.ndarray]:
    """Exact response of one run (scalar ``tractor``) in permanent contact, from rest.

    The linear model is :func:`tyrelab.vehicle.ride.state_space` and its exact (first-order
    hold) solution :func:`tyrelab.vehicle.lti.discretise`, with ``z`` and ``θ`` added as
    outputs.

    Parameters
    ----------
    tractor : Tractor
        Scalar parameters of one run.
    inputs : ndarray, shape (4, n)
        ``u_f, u_f', u_r, u_r'`` at the sample times (step ``dt_s``), linear in between.
    dt_s : float
        Sample step, s.

    Returns
    -------
    dict
        The per-sample outputs of :func:`simulate_tractor` plus ``front_force_N`` and
        ``rear_force_N`` (dynamic axle forces, from which lift-off is judged).
    """
    system, _ = _exact_system(tractor, dt_s)
    y = system.run(inputs)
    y[5:7, 0] = 0.0  # at rest at the first sample exactly (the modal transform leaves ~1e-22)
    return dict(zip(_OUTPUTS + ("front_force_N", "rear_force_N"), (y[0], y[1], y[2], y[5], y[6], y[3], y[4])))


def _to_states(y7: np.ndarray, names: list[str], h: float) -> np.ndarray:
    """RK4 state ``z, θ, x, z', θ', x', s`` -> the linear model's states ``names``."""
    z, th, x, vz, vth, vx, s = y7
    values = {"z": z, "th": th, "x": x, "vz": vz, "vth": vth, "vx": vx, "q": x + h * th - s}
    return np.array([values[k] for k in names])


def _from_states(xs: np.ndarray, names: list[str], h: float, y7: np.ndarray) -> np.ndarray:
    """The linear model's states -> RK4 state; what the linear model does not carry (``x`` when it
    exerts no force, ``x'`` without an element) keeps its value in ``y7``."""
    y = np.array(y7, float)
    values = dict(zip(names, xs))
    for i, k in enumerate(("z", "th", "x", "vz", "vth", "vx")):
        if k in values:
            y[i] = values[k]
    if "q" in values:
        y[6] = y[2] + h * y[1] - values["q"]  # q = d - s, d = x + h θ
    return y


class _Exact:
    """Exact path of one run, resumable: solves from a sample until a tyre would lift off."""

    def __init__(self, tractor: Tractor, inputs: np.ndarray, dt_s: float, floors: tuple[float, float]):
        self.system, self.names = _exact_system(tractor, dt_s / 2)
        self.inputs = inputs  # (4, 2n - 1) at dt/2
        self.h = float(tractor.cg_height_m)
        self.floors = floors
        self.n = (inputs.shape[1] + 1) // 2

    def solve(self, k0: int, y7, out: dict, row: int, lift_off: bool, chunk: int | None = None):
        """Fill ``out[.][row, k0:k]`` exactly from the RK4 state ``y7`` at sample ``k0`` (``None``:
        rest); return ``(k, y7_k)`` with ``k`` the last sample before a tyre would lift off (RK4
        takes over there), or ``(n, None)`` when the record ends in contact."""
        x = None if y7 is None else _to_states(y7, self.names, self.h)
        y_prev = np.zeros(7) if y7 is None else y7
        pos = k0
        while True:
            stop = self.n - 1 if chunk is None else min(self.n - 1, pos + chunk)
            kept = self.system.modes(self.inputs[:, 2 * pos:2 * stop + 1], x)
            # the tyre forces at every half step (the RK4 judges contact at the half steps too: so
            # does this check), the outputs only at the whole steps up to the first lift-off
            # (FohSystem.outputs: the same values as computing every output everywhere)
            if lift_off:
                forces = self.system.outputs(kept, (3, 4))
                hit = np.flatnonzero((forces[0] <= self.floors[0]) | (forces[1] <= self.floors[1]))[:1]
            else:
                hit = []
            end = max(pos, pos + (int(hit[0]) - 1) // 2) if len(hit) else stop + (stop == self.n - 1)
            m = end - pos
            y = self.system.outputs(kept, (0, 1, 2, 5, 6), 2 * m, 2)
            if x is None and m:
                y[3:5, 0] = 0.0  # at rest at the first sample exactly (the modal transform leaves ~1e-22)
            for key, r in zip(_OUTPUTS, range(5)):
                out[key][row, pos:end] = y[r]
            if len(hit):
                return end, _from_states(self.system.state_at(kept, 2 * m), self.names, self.h, y_prev)
            if end == self.n:
                return self.n, None
            x, pos = self.system.state_at(kept, 2 * (stop - pos)), stop
            chunk = min(2 * chunk, EXACT_CHUNK_MAX) if chunk else None  # in contact for the whole chunk: look further


#: The RK4 loop's order of the state ``z, θ, x, z', θ', x', s`` (:func:`_to_states`' ``y7``): each
#: displacement beside its rate, so one numpy call takes ``[u - z, u' - z']`` or ``[d, x' + h θ']``
#: (:class:`_Rhs`); and back.
_RK4_ORDER = np.array([0, 3, 1, 4, 2, 5, 6])
_Y7_ORDER = np.argsort(_RK4_ORDER)


class _Rhs:
    """Right-hand side of the nonlinear tractor for a batch of runs, into preallocated buffers.

    A batch is tens of runs, so the cost is the number of numpy calls, not the arithmetic: the
    state is ``[z, z', θ, θ', x, x', s]`` (:data:`_RK4_ORDER`) and the derivative ``[z', z'',
    θ', θ'', x', x'', s']``; the front and rear axles' stiffness and damping terms are one (2, 2,
    runs) array each call (``[a, -b]`` the levers: ``u_r - z + b θ`` is ``u_r - z - (-b) θ``
    exactly); each longitudinal model is worked out on its own contiguous slice of runs (the runs
    must come grouped by model, :func:`_run_switched` sorts them); results go into buffers
    (``out=``); scalars are arrays (a Python float operand costs a numpy call 60 % more). The
    floating-point operations and their order are those of the equations in the module docstring
    written out plainly (tests/vehicle/test_tractor_switching.py checks bit-identity against
    that form).
    """

    def __init__(self, p: dict[str, np.ndarray], models: np.ndarray, lift_off: bool, gravity_m_s2: float):
        runs = models.size
        m, inertia, a, b, h = (np.ascontiguousarray(p[k]) for k in PARAMETERS[:5])
        kf, kr, cf, cr, kx, cx = (np.ascontiguousarray(p[k]) for k in PARAMETERS[5:])
        w = m * gravity_m_s2
        wf = -w * b / (a + b) if lift_off else np.full(runs, -np.inf)
        wr = -w * a / (a + b) if lift_off else np.full(runs, -np.inf)
        self.m, self.inertia, self.h, self.h2 = m, inertia, h, np.stack([h, h])
        self.wr = wr
        self.lever, self.ab = np.stack([a, -b]), np.stack([a, b])
        self.coefficients = np.stack([np.stack([kf, kr]), np.stack([cf, cr])])  # [[K_f, K_r], [C_f, C_r]]
        self.floors = np.stack([wf, wr])
        maxwell_rate = np.divide(kx, cx, out=np.zeros(runs), where=cx > 0)
        maxwell_active = (kx > 0) & (cx > 0)
        models = np.asarray(models)
        self.slices = {}
        for kind in ("kelvin_voigt", "maxwell"):
            at = np.flatnonzero(models == kind)
            if at.size:
                if at[-1] - at[0] + 1 != at.size:
                    raise ValueError("longitudinal_model: the runs of a batch must be grouped by model")
                self.slices[kind] = slice(int(at[0]), int(at[-1]) + 1)
        kv = self.slices.get("kelvin_voigt", slice(0, 0))
        mw = self.slices.get("maxwell", slice(0, 0))
        self.kv = np.stack([kx[kv], cx[kv]])
        # an element without spring or damper exerts no force; times 1 changes nothing, so skipped
        self.mw = (-kx[mw], None if maxwell_active[mw].all() else maxwell_active[mw], maxwell_rate[mw])
        self.e1, self.e2 = np.empty((2, 2, 2, runs))
        self.force, self.dq, self.moments = np.empty((3, 2, runs))
        self.fx, self.t1 = np.empty((2, runs))
        self.fx[:] = 0.0  # no longitudinal element: no force
        self.contact = np.empty(runs, dtype=bool)

    def bind(self, y: np.ndarray, w: np.ndarray, k: np.ndarray, lifted: np.ndarray):
        """A function of no arguments that writes ``k`` = the derivative of the state ``y`` (7, runs,
        order :data:`_RK4_ORDER`) under inputs ``w`` = ``[[u_f, u_r], [u_f', u_r']]`` (2, 2, runs),
        and ``lifted`` = ``[F_f <= -W_f, F_r <= -W_r]`` (front, rear off the ground), from the
        arrays' values at the call (every view taken once, here). ``k[6]`` (Maxwell ``s'``) is
        written for the Maxwell runs only: it must hold 0 elsewhere."""
        add, sub, mul, div, maximum, less_equal, greater, negative, copyto = (
            np.add, np.subtract, np.multiply, np.divide, np.maximum, np.less_equal, np.greater, np.negative, np.copyto)
        e1, e2, force, dq, moments, fx, t1 = self.e1, self.e2, self.force, self.dq, self.moments, self.fx, self.t1
        contact, lever, coefficients, floors, wr = self.contact, self.lever[None], self.coefficients, self.floors, self.wr
        m, inertia, h, h2, ab = self.m, self.inertia, self.h, self.h2, self.ab
        zv, tv, xv, s = y[0:2, None], y[2:4, None], y[4:6], y[6]  # [z, z'], [θ, θ'] (as (2, 1, runs)), [x, x']
        e_stiff, e_damp, force_f, force_r, mom_f, mom_r, d = e1[0], e1[1], force[0], force[1], moments[0], moments[1], dq[0]
        k_vel, y_vel, k_z, k_th, k_x = k[0:6:2], y[1:6:2], k[1], k[3], k[5]
        kv = self.slices.get("kelvin_voigt")
        if kv is not None:
            kv_coef, kv_dq, kv_e, kv_contact, kv_fx = self.kv, dq[:, kv], e2[0, :, kv], contact[kv], fx[kv]
            kv_kd, kv_cq = kv_e
        mw = self.slices.get("maxwell")
        if mw is not None:
            mw_neg_kx, mw_active, mw_rate = self.mw
            mw_f1, mw_f2 = e2[1, :, mw]
            mw_d, mw_s, mw_contact, mw_fx, mw_ds = d[mw], s[mw], contact[mw], fx[mw], k[6, mw]

        def rhs() -> None:
            # [F_f, F_r] = max(K (u - z -+ lever θ) + C (u' - z' -+ lever θ'), floors)
            sub(w, zv, e1)  # [[u_f - z, u_r - z], [u_f' - z', u_r' - z']]
            mul(tv, lever, e2)  # [[a θ, -b θ], [a θ', -b θ']]
            sub(e1, e2, e1)
            mul(coefficients, e1, e1)
            add(e_stiff, e_damp, force)
            maximum(force, floors, out=force)  # (a positional out is deprecated for maximum, and slow)
            less_equal(force, floors, out=lifted)
            greater(force_r, wr, out=contact)
            # [d, x' + h θ'], d = x + h θ the rear contact's fore-aft displacement
            mul(h2, tv[:, 0], dq)
            add(xv, dq, dq)
            if kv is not None:  # F_x = -(k_x d + c_x (x' + h θ')) while in contact
                mul(kv_coef, kv_dq, kv_e)
                add(kv_kd, kv_cq, kv_fx)
                negative(kv_fx, kv_fx)
                mul(kv_fx, kv_contact, kv_fx)
            if mw is not None:  # F_x = -k_x (d - s) while in contact, c_x s' = k_x (d - s)
                sub(mw_d, mw_s, mw_f2)
                mul(mw_neg_kx, mw_f2, mw_f1)
                if mw_active is not None:
                    mul(mw_f1, mw_active, mw_f1)
                mul(mw_f1, mw_contact, mw_fx)
                mul(mw_rate, mw_f2, mw_ds)
            copyto(k_vel, y_vel)
            add(force_f, force_r, k_z)
            div(k_z, m, k_z)  # z'' = (F_f + F_r) / M
            mul(ab, force, moments)
            sub(mom_f, mom_r, k_th)
            mul(h, fx, t1)
            add(k_th, t1, k_th)
            div(k_th, inertia, k_th)  # θ'' = (a F_f - b F_r + h F_x) / I
            div(fx, m, k_x)  # x'' = F_x / M

        return rhs


def simulate_tractor(
    tractor: Tractor,
    front_half,
    front_rate_half,
    rear_half,
    rear_rate_half,
    dt_s: float = 1e-3,
    lift_off: bool = True,
    gravity_m_s2: float = GRAVITY_M_S2,
    method: str = "auto",
) -> dict[str, np.ndarray]:
    """Simulate the pitch-plane tractor: exact while both axles are in contact, RK4 across lift-off.

    ``method="rk4"`` integrates every run with the nonlinear fixed-step RK4 at ``dt``
    (:func:`_simulate_rk4`). ``"auto"`` (default) solves each run exactly in the linear model
    (:func:`linear_response`, on the ``dt/2`` samples); a run whose tyre would lift off
    (``lift_off``; judged at the half steps, as the RK4 does) switches within the run: exact
    up to the last sample before the first lift-off, RK4 from that sample until both tyres
    have stayed in contact at every RK4 stage for :data:`CALM_STEPS` steps, exact again from
    there (from the RK4 state) until the next lift-off, and so on. The RK4 parts of all such
    runs advance together (vectorised, each run at its own sample). ``method_used`` per run:
    ``"exact"``, ``"exact+rk4"`` (switched) or ``"rk4"``.

    Parameters
    ----------
    tractor : Tractor
        Scalars or arrays of shape ``(n_runs,)``; ``longitudinal_model`` one string or one per run.
    front_half, front_rate_half, rear_half, rear_rate_half : array_like
        Ground elevation (m) and rate (m/s) under the front and rear axles sampled at
        ``dt/2``, shape ``(2N-1,)`` or ``(n_runs, 2N-1)``; the rear input is the
        front one delayed by wheelbase/speed (the caller builds it from the profile).
    dt_s : float
        Step, s.
    lift_off : bool
        Let tyres leave the ground.
    method : str
        One of :data:`METHODS`.

    Returns
    -------
    dict
        ``vertical_m_s2`` (CG), ``pitch_rad_s2``, ``longitudinal_m_s2`` (CG), ``z_m``,
        ``theta_rad`` per sample, ``lift_off_fraction_front``/``_rear`` (fraction of the
        samples at which the axle is off the ground) and ``method_used`` per run.

    Examples
    --------
    A 60 mm step under both axles at once lifts the front briefly; the run switches:

    >>> t = Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3)
    >>> u = np.r_[np.zeros(1001), np.full(2000, -0.06)]
    >>> out = simulate_tractor(t, u, 0 * u, u, 0 * u)
    >>> str(out["method_used"]), bool(out["lift_off_fraction_front"] > 0)
    ('exact+rk4', True)
    """
    if method not in METHODS:
        raise ValueError(f"method {method!r}: expected one of {METHODS}")
    if not dt_s > 0:
        raise ValueError(f"dt_s must be positive, got {dt_s}")
    uf, udf, ur, udr = (np.atleast_2d(np.asarray(v, float)) for v in (front_half, front_rate_half, rear_half, rear_rate_half))
    squeeze = np.ndim(front_half) == 1
    if not uf.shape == udf.shape == ur.shape == udr.shape:
        raise ValueError("front_half, front_rate_half, rear_half, rear_rate_half: shapes differ")
    if uf.shape[1] % 2 == 0:
        raise ValueError("inputs must be sampled at dt/2 (odd length)")
    runs, n = uf.shape[0], (uf.shape[1] + 1) // 2
    p, models = _params(tractor, runs), _models(tractor, runs)
    if method == "rk4":
        out = _simulate_rk4(tractor, uf, udf, ur, udr, dt_s, lift_off, gravity_m_s2)
        out["method_used"] = np.array(["rk4"] * runs, dtype=object)
        return {k: v[0] for k, v in out.items()} if squeeze else out
    out = {k: np.empty((runs, n)) for k in _OUTPUTS}
    out["lift_off_fraction_front"] = np.zeros(runs)
    out["lift_off_fraction_rear"] = np.zeros(runs)
    used = np.array(["exact"] * runs, dtype=object)
    w = gravity_m_s2 * p["mass_kg"]
    wb = p["front_distance_m"] + p["rear_distance_m"]
    switched = []  # (run, exact path, sample where RK4 takes over, RK4 state there)
    for i in range(runs):
        floors = (-w[i] * p["rear_distance_m"][i] / wb[i], -w[i] * p["front_distance_m"][i] / wb[i])
        exact = _Exact(_scalar(p, models, i), np.stack([uf[i], udf[i], ur[i], udr[i]]), dt_s, floors)
        k, y7 = exact.solve(0, None, out, i, lift_off)
        if k < n:
            switched.append((i, exact, k, y7))
            used[i] = "exact+rk4"
    if switched:
        _run_switched(p, models, uf, udf, ur, udr, dt_s, lift_off, gravity_m_s2, switched, out)
    out["method_used"] = used
    return {k: v[0] for k, v in out.items()} if squeeze else out


def _run_switched(p, models, uf, udf, ur, udr, dt_s, lift_off, gravity_m_s2, switched, out) -> None:
    """RK4 across the lift-off intervals of the ``switched`` runs, the exact path in between.

    ``switched``: per run (index, exact path, sample where RK4 takes over, RK4 state there); a run
    whose exact path is None stays on RK4 to the end (:func:`_simulate_rk4`). All runs advance
    together, each at its own sample; a run that has ended (or gone back to the exact path for
    good) is still computed, its results go nowhere."""
    models = np.asarray(models)
    order = {m: i for i, m in enumerate(LONGITUDINAL_MODELS)}
    switched = sorted(switched, key=lambda s: order[str(models[s[0]])])  # grouped by model (_Rhs), stable
    idx = np.array([s[0] for s in switched])
    exact = [s[1] for s in switched]
    returns = np.array([e is not None for e in exact])
    count, n = idx.size, (uf.shape[1] + 1) // 2
    rhs = _Rhs({k: v[idx] for k, v in p.items()}, models[idx], lift_off, gravity_m_s2)
    # inputs [u_f, u_r, u_f', u_r'] of every run, each padded with its last sample twice (the
    # stages past the last sample read it, as a clamped index would), flat: one gather a step
    width = 2 * n + 1
    inputs = np.empty((4, count, width))
    for row, v in enumerate((uf, ur, udf, udr)):
        inputs[row, :, : 2 * n - 1] = v[idx]
        inputs[row, :, 2 * n - 1:] = inputs[row, :, 2 * n - 2: 2 * n - 1]
    inputs = inputs.reshape(4, count * width)
    rows = np.arange(count)
    at = np.empty((3, count), dtype=np.intp)  # the three half samples a step reads, flat
    at_flat = at.reshape(-1)
    first = rows * width + np.arange(3)[:, None]
    w = np.empty((4, 3, count))
    w_flat = w.reshape(4, 3 * count)
    w1, w2, w3 = (w.reshape(2, 2, 3, count)[:, :, i] for i in range(3))  # [[u_f, u_r], [u_f', u_r']]
    # results: (5, count, n + 1), the last column a sink for the runs that no longer record
    res = np.empty((5, count, n + 1))
    for i, key in enumerate(_OUTPUTS):
        res[i, :, :n] = out[key][idx]
    views = {key: res[i, :, :n] for i, key in enumerate(_OUTPUTS)}
    res_flat = [res[i].reshape(-1) for i in range(5)]  # one flat view per output: np.put is the fast scatter
    res_start, sink = rows * (n + 1), rows * (n + 1) + n
    pos = np.empty(count, dtype=np.intp)
    y = np.array([s[3] for s in switched], float).T[_RK4_ORDER].copy()  # (7, count)
    k = np.array([s[2] for s in switched], dtype=np.intp)
    calm = np.zeros(count, dtype=int)
    active = np.ones(count, dtype=bool)
    off = np.zeros((2, count))  # samples off the ground, front and rear
    k1, k2, k3, k4, yb, yc, yd, acc, acc2, y_new = np.zeros((10, 7, count))
    recorded = list(zip(res_flat, (k1[1], k1[3], k1[5], y[0], y[2])))  # vertical, pitch, longitudinal, z, θ
    lifted = np.empty((4, 2, count), dtype=bool)
    lifted_any = lifted.reshape(8, count)
    lifted_now = np.empty((2, count), dtype=bool)
    step, idle, back = np.empty((3, count), dtype=bool)
    any_lift = np.empty(count, dtype=bool)
    hstep, half, sixth = (np.full((7, count), v) for v in (dt_s, 0.5 * dt_s, dt_s / 6.0))
    add, mul = np.add, np.multiply
    rhs1, rhs2, rhs3, rhs4 = (rhs.bind(*a) for a in ((y, w1, k1, lifted[0]), (yb, w2, k2, lifted[1]),
                                                    (yc, w2, k3, lifted[2]), (yd, w3, k4, lifted[3])))
    last = n - 1
    while active.any():
        add(k, k, at[0])
        add(first, at[0], at)
        np.take(inputs, at_flat, axis=1, out=w_flat, mode="clip")
        rhs1()
        # record sample k of the runs still recording
        add(res_start, k, pos)
        np.logical_not(active, out=idle)
        np.copyto(pos, sink, where=idle)
        for flat, row in recorded:
            np.put(flat, pos, row)
        np.logical_and(lifted[0], active, out=lifted_now)
        add(off, lifted_now, off)
        np.not_equal(k, last, out=step)
        np.logical_and(step, active, out=step)
        mul(half, k1, acc)
        add(y, acc, yb)
        rhs2()
        mul(half, k2, acc)
        add(y, acc, yc)
        rhs3()
        mul(hstep, k3, acc)
        add(y, acc, yd)
        rhs4()
        # y + h/6 (k1 + 2 k2 + 2 k3 + k4), summed left to right
        add(k2, k2, acc)
        add(k1, acc, acc)
        add(k3, k3, acc2)
        add(acc, acc2, acc)
        add(acc, k4, acc)
        mul(sixth, acc, acc)
        add(y, acc, y_new)
        np.copyto(y, y_new, where=step)
        add(k, step, k)
        np.logical_or.reduce(lifted_any, axis=0, out=any_lift)
        add(calm, 1, calm)
        np.copyto(calm, 0, where=any_lift)
        np.copyto(active, step)
        np.greater_equal(calm, CALM_STEPS, out=back)
        np.logical_and(back, step, out=back)
        np.logical_and(back, returns, out=back)
        if back.any():
            for r in np.flatnonzero(back):  # back in contact for a while: exact again
                kr, y7 = exact[r].solve(int(k[r]), y[_Y7_ORDER, r], views, r, lift_off, chunk=EXACT_CHUNK)
                if y7 is None:
                    active[r] = False
                else:
                    k[r], y[:, r], calm[r] = kr, y7[_RK4_ORDER], 0
    for i, key in enumerate(_OUTPUTS):
        out[key][idx] = views[key]
    out["lift_off_fraction_front"][idx] = off[0] / n
    out["lift_off_fraction_rear"][idx] = off[1] / n


def _simulate_rk4(
    tractor: Tractor,
    front_half,
    front_rate_half,
    rear_half,
    rear_rate_half,
    dt_s: float = 1e-3,
    lift_off: bool = True,
    gravity_m_s2: float = GRAVITY_M_S2,
) -> dict[str, np.ndarray]:
    """Integrate the pitch-plane tractor with fixed-step RK4 (every run, every step).

    Parameters and returns as :func:`simulate_tractor` (without ``method_used``): the RK4
    loop of the switched path (:func:`_run_switched`), every run from rest at the first
    sample and none returning to the exact path.
    """
    uf, udf, ur, udr = (np.atleast_2d(np.asarray(v, float)) for v in (front_half, front_rate_half, rear_half, rear_rate_half))
    squeeze = np.ndim(front_half) == 1
    if uf.shape[1] % 2 == 0:
        raise ValueError("inputs must be sampled at dt/2 (odd length)")
    runs, n = uf.shape[0], (uf.shape[1] + 1) // 2
    out = {k: np.empty((runs, n)) for k in _OUTPUTS}
    out["lift_off_fraction_front"] = np.zeros(runs)
    out["lift_off_fraction_rear"] = np.zeros(runs)
    from_rest = [(i, None, 0, np.zeros(7)) for i in range(runs)]
    _run_switched(_params(tractor, runs), _models(tractor, runs), uf, udf, ur, udr, dt_s, lift_off, gravity_m_s2,
                  from_rest, out)
    return {k: v[0] for k, v in out.items()} if squeeze else out
