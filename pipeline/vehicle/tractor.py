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
            y, kept = self.system.run(self.inputs[:, 2 * pos:2 * stop + 1], x, keep_modes=True)
            if x is None:
                y[5:7, 0] = 0.0  # at rest at the first sample exactly (the modal transform leaves ~1e-22)
            # the RK4 judges contact at the half steps too: so does this check
            hit = np.flatnonzero((y[3] <= self.floors[0]) | (y[4] <= self.floors[1]))[:1] if lift_off else []
            end = max(pos, pos + (int(hit[0]) - 1) // 2) if len(hit) else stop + (stop == self.n - 1)
            m = end - pos
            for key, r in zip(_OUTPUTS, (0, 1, 2, 5, 6)):
                out[key][row, pos:end] = y[r, 0:2 * m:2]
            if len(hit):
                return end, _from_states(self.system.state_at(kept, 2 * m), self.names, self.h, y_prev)
            if end == self.n:
                return self.n, None
            x, pos = self.system.state_at(kept, 2 * (stop - pos)), stop
            chunk = min(2 * chunk, EXACT_CHUNK_MAX) if chunk else None  # in contact for the whole chunk: look further


class _Rhs:
    """Right-hand side of the nonlinear tractor, vectorised over runs (per-run longitudinal model)."""

    def __init__(self, p: dict[str, np.ndarray], models: np.ndarray, lift_off: bool, gravity_m_s2: float):
        runs = models.size
        self.m, self.inertia, self.a, self.b, self.h = (p[k] for k in PARAMETERS[:5])
        self.kf, self.kr, self.cf, self.cr, self.kx, self.cx = (p[k] for k in PARAMETERS[5:])
        w = self.m * gravity_m_s2
        self.wf = -w * self.b / (self.a + self.b) if lift_off else np.full(runs, -np.inf)
        self.wr = -w * self.a / (self.a + self.b) if lift_off else np.full(runs, -np.inf)
        self.maxwell_rate = np.divide(self.kx, self.cx, out=np.zeros(runs), where=self.cx > 0)
        self.maxwell_active = (self.kx > 0) & (self.cx > 0)
        kinds = set(models.tolist())
        self.kind = kinds.pop() if len(kinds) == 1 else "mixed"
        self.kv, self.mw = models == "kelvin_voigt", models == "maxwell"
        self.zeros = np.zeros(runs)

    def __call__(self, y, uf, udf, ur, udr):
        z, th, x, vz, vth, vx, s = y
        a, b, h = self.a, self.b, self.h
        ff = np.maximum(self.kf * (uf - z - a * th) + self.cf * (udf - vz - a * vth), self.wf)
        fr = np.maximum(self.kr * (ur - z + b * th) + self.cr * (udr - vz + b * vth), self.wr)
        d = x + h * th
        contact = fr > self.wr
        if self.kind == "kelvin_voigt":
            fx = -(self.kx * d + self.cx * (vx + h * vth)) * contact
            ds = self.zeros
        elif self.kind == "maxwell":
            fx = -self.kx * (d - s) * self.maxwell_active * contact
            ds = self.maxwell_rate * (d - s)
        elif self.kind == "none":
            fx = self.zeros
            ds = self.zeros
        else:
            fx = np.where(self.kv, -(self.kx * d + self.cx * (vx + h * vth)),
                          np.where(self.mw, -self.kx * (d - s) * self.maxwell_active, 0.0)) * contact
            ds = np.where(self.mw, self.maxwell_rate * (d - s), 0.0)
        az = (ff + fr) / self.m
        ath = (a * ff - b * fr + h * fx) / self.inertia
        ax = fx / self.m
        return np.array([vz, vth, vx, az, ath, ax, ds]), ff <= self.wf, fr <= self.wr


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
    whose exact path is None stays on RK4 to the end (:func:`_simulate_rk4`)."""
    idx = np.array([s[0] for s in switched])
    exact = [s[1] for s in switched]
    returns = np.array([e is not None for e in exact])
    rhs = _Rhs({k: v[idx] for k, v in p.items()}, np.asarray(models)[idx], lift_off, gravity_m_s2)
    inputs = np.stack([v[idx] for v in (uf, udf, ur, udr)], axis=-1)  # (runs, 2n - 1, 4): one gather a stage
    count, n = idx.size, (uf.shape[1] + 1) // 2
    rows = np.arange(count)
    y = np.array([s[3] for s in switched]).T  # (7, count)
    k = np.array([s[2] for s in switched])
    calm = np.zeros(count, dtype=int)
    active = np.ones(count, dtype=bool)
    off_f, off_r = np.zeros(count), np.zeros(count)
    res = np.stack([out[key][idx] for key in _OUTPUTS])  # (5, count, n), written back at the end
    views = {key: res[i] for i, key in enumerate(_OUTPUTS)}
    last, hstep = 2 * n - 2, dt_s
    while active.any():
        j = 2 * k
        w0 = inputs[rows, j].T
        w1 = inputs[rows, np.minimum(j + 1, last)].T
        w2 = inputs[rows, np.minimum(j + 2, last)].T
        k1, lf, lr = rhs(y, *w0)
        act = np.flatnonzero(active)
        res[:, act, k[act]] = np.stack([k1[3], k1[4], k1[5], y[0], y[1]])[:, act]
        off_f[act] += lf[act]
        off_r[act] += lr[act]
        end = active & (k == n - 1)
        step = active & ~end
        k2, lf2, lr2 = rhs(y + 0.5 * hstep * k1, *w1)
        k3, lf3, lr3 = rhs(y + 0.5 * hstep * k2, *w1)
        k4, lf4, lr4 = rhs(y + hstep * k3, *w2)
        y = np.where(step, y + hstep / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4), y)
        k = k + step
        calm = np.where(lf | lr | lf2 | lr2 | lf3 | lr3 | lf4 | lr4, 0, calm + 1)
        active &= ~end
        for r in np.flatnonzero(step & (calm >= CALM_STEPS) & returns):  # back in contact for a while: exact again
            kr, y7 = exact[r].solve(int(k[r]), y[:, r], views, r, lift_off, chunk=EXACT_CHUNK)
            if y7 is None:
                active[r] = False
            else:
                k[r], y[:, r], calm[r] = kr, y7, 0
    for i, key in enumerate(_OUTPUTS):
        out[key][idx] = res[i]
    out["lift_off_fraction_front"][idx] = off_f / n
    out["lift_off_fraction_rear"][idx] = off_r / n


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
