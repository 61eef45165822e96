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

Two solution paths, chosen per run by :func:`simulate_tractor` (``method="auto"``):

* while both axles stay in contact the model is linear (the longitudinal element
  acts only in contact, which then always holds): :func:`linear_response` is its
  exact discretisation for inputs linear between the ``dt/2`` samples (first-order
  hold, :func:`tyrelab.vehicle.ride.simulate_state_space` on
  :func:`tyrelab.vehicle.ride.state_space`, the carriage's method);
* a run whose linear solution lifts a tyre off (total tyre force would pull) is
  integrated again by the nonlinear fixed-step RK4 at ``dt`` (the thesis used
  Runge-Kutta-Nystrom at about 1 ms), vectorised over those runs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .carriage import GRAVITY_M_S2

__all__ = ["Tractor", "simulate_tractor", "linear_response", "LONGITUDINAL_MODELS", "METHODS"]

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
    longitudinal_model : str
        One of :data:`LONGITUDINAL_MODELS` (scalar for the whole batch).
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


def _params(tractor: Tractor, runs: int) -> dict[str, np.ndarray]:
    return {k: np.broadcast_to(np.asarray(getattr(tractor, k), float), (runs,)) for k in (
        "mass_kg", "pitch_inertia_kg_m2", "front_distance_m", "rear_distance_m", "cg_height_m",
        "front_stiffness_N_per_m", "rear_stiffness_N_per_m", "front_damping_N_s_per_m", "rear_damping_N_s_per_m",
        "longitudinal_stiffness_N_per_m", "longitudinal_damping_N_s_per_m")}  # fmt: skip


def linear_response(tractor: Tractor, inputs: np.ndarray, dt_s: float) -> dict[str, np.ndarray]:
    """Exact response of one run (scalar ``tractor``) in permanent contact, from rest.

    The linear model is :func:`tyrelab.vehicle.ride.state_space` and its exact (first-order
    hold) solution :func:`tyrelab.vehicle.ride.simulate_state_space`, with ``z`` and ``θ``
    added as outputs.

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
    from .ride import simulate_state_space, state_space  # ride imports this module

    a, b, c, d = state_space(tractor)
    n = a.shape[0]
    c = np.vstack([c[2:5], np.eye(n)[:2], c[5:7]])  # vertical, pitch, longitudinal, z, θ (states 0, 1), forces
    d = np.vstack([d[2:5], np.zeros((2, d.shape[1])), d[5:7]])
    y = simulate_state_space(a, b, c, d, inputs, dt_s)
    y[3:5, 0] = 0.0  # at rest at the first sample exactly (the modal transform leaves ~1e-22)
    return dict(zip(_OUTPUTS + ("front_force_N", "rear_force_N"), y))


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
    """Simulate the pitch-plane tractor: exact where the model is linear, RK4 where a tyre lifts off.

    Parameters and returns as :func:`_simulate_rk4`; ``method="rk4"`` integrates every run
    with RK4, ``"auto"`` (default) solves each run exactly in the linear model
    (:func:`linear_response`, on the ``dt/2`` samples) and integrates only the runs
    where a tyre would lift off (``lift_off``) with RK4. ``method_used`` says which per run.
    """
    if method not in METHODS:
        raise ValueError(f"method {method!r}: expected one of {METHODS}")
    if tractor.longitudinal_model not in LONGITUDINAL_MODELS:
        raise ValueError(f"longitudinal_model {tractor.longitudinal_model!r}: expected {LONGITUDINAL_MODELS}")
    uf, udf, ur, udr = (np.atleast_2d(np.asarray(v, float)) for v in (front_half, front_rate_half, rear_half, rear_rate_half))
    squeeze = np.ndim(front_half) == 1
    if uf.shape[1] % 2 == 0:
        raise ValueError("inputs must be sampled at dt/2 (odd length)")
    runs, n = uf.shape[0], (uf.shape[1] + 1) // 2
    out = {k: np.empty((runs, n)) for k in _OUTPUTS}
    out["lift_off_fraction_front"] = np.zeros(runs)
    out["lift_off_fraction_rear"] = np.zeros(runs)
    used = np.array(["rk4"] * runs, dtype=object)
    todo = list(range(runs))
    if method == "auto":
        p = _params(tractor, runs)
        w = gravity_m_s2 * p["mass_kg"]
        wb = p["front_distance_m"] + p["rear_distance_m"]
        todo = []
        for i in range(runs):
            one = Tractor(**{k: float(v[i]) for k, v in p.items()}, longitudinal_model=tractor.longitudinal_model)
            lin = linear_response(one, np.stack([uf[i], udf[i], ur[i], udr[i]]), dt_s / 2)
            floor_f, floor_r = -w[i] * p["rear_distance_m"][i] / wb[i], -w[i] * p["front_distance_m"][i] / wb[i]
            # the RK4 judges contact at the half steps too: so does this check
            if lift_off and (lin["front_force_N"].min() <= floor_f or lin["rear_force_N"].min() <= floor_r):
                todo.append(i)
                continue
            for k in _OUTPUTS:
                out[k][i] = lin[k][::2]
            used[i] = "exact"
    if todo:
        sub = Tractor(**{k: v[todo] for k, v in _params(tractor, runs).items()},
                      longitudinal_model=tractor.longitudinal_model)
        nl = _simulate_rk4(sub, uf[todo], udf[todo], ur[todo], udr[todo], dt_s, lift_off, gravity_m_s2)
        for k, v in nl.items():
            out[k][todo] = v
    out["method_used"] = used
    if squeeze:
        out = {k: v[0] for k, v in out.items()}
    return out


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
    """Integrate the pitch-plane tractor with fixed-step RK4.

    Parameters
    ----------
    tractor : Tractor
        Scalars or arrays of shape ``(n_runs,)``.
    front_half, front_rate_half, rear_half, rear_rate_half : array_like
        Ground elevation (m) and rate (m/s) under the front and rear axles sampled at
        ``dt/2``, shape ``(2N-1,)`` or ``(n_runs, 2N-1)``; the rear input is the
        front one delayed by wheelbase/speed (the caller builds it from the profile).
    dt_s : float
        Step, s.
    lift_off : bool
        Let tyres leave the ground.

    Returns
    -------
    dict
        ``vertical_m_s2`` (CG), ``pitch_rad_s2``, ``longitudinal_m_s2`` (CG),
        ``z_m``, ``theta_rad`` and ``lift_off_fraction`` (front, rear) per run.
    """
    if tractor.longitudinal_model not in LONGITUDINAL_MODELS:
        raise ValueError(f"longitudinal_model {tractor.longitudinal_model!r}: expected {LONGITUDINAL_MODELS}")
    uf, udf, ur, udr = (np.atleast_2d(np.asarray(v, float)) for v in (front_half, front_rate_half, rear_half, rear_rate_half))
    squeeze = np.ndim(front_half) == 1
    if uf.shape[1] % 2 == 0:
        raise ValueError("inputs must be sampled at dt/2 (odd length)")
    runs = uf.shape[0]
    p = _params(tractor, runs)
    m, inertia, a, b, h = (p[k] for k in ("mass_kg", "pitch_inertia_kg_m2", "front_distance_m", "rear_distance_m", "cg_height_m"))
    kf, kr, cf, cr = (p[k] for k in ("front_stiffness_N_per_m", "rear_stiffness_N_per_m", "front_damping_N_s_per_m", "rear_damping_N_s_per_m"))
    kx, cx = p["longitudinal_stiffness_N_per_m"], p["longitudinal_damping_N_s_per_m"]
    model = tractor.longitudinal_model
    w = m * gravity_m_s2
    wf = -w * b / (a + b) if lift_off else np.full(runs, -np.inf)
    wr = -w * a / (a + b) if lift_off else np.full(runs, -np.inf)
    maxwell_rate = np.divide(kx, cx, out=np.zeros(runs), where=cx > 0)
    maxwell_active = (kx > 0) & (cx > 0)

    def deriv(y, j):
        z, th, x, vz, vth, vx, s = y
        ff = np.maximum(kf * (uf[:, j] - z - a * th) + cf * (udf[:, j] - vz - a * vth), wf)
        fr = np.maximum(kr * (ur[:, j] - z + b * th) + cr * (udr[:, j] - vz + b * vth), wr)
        d = x + h * th
        contact = fr > wr
        if model == "kelvin_voigt":
            fx = -(kx * d + cx * (vx + h * vth)) * contact
            ds = np.zeros(runs)
        elif model == "maxwell":
            fx = -kx * (d - s) * maxwell_active * contact
            ds = maxwell_rate * (d - s)
        else:
            fx = np.zeros(runs)
            ds = np.zeros(runs)
        az = (ff + fr) / m
        ath = (a * ff - b * fr + h * fx) / inertia
        ax = fx / m
        return np.array([vz, vth, vx, az, ath, ax, ds]), ff <= wf, fr <= wr

    n = (uf.shape[1] + 1) // 2
    y = np.zeros((7, runs))
    out = {k: np.empty((runs, n)) for k in ("vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2", "z_m", "theta_rad")}
    off_f = np.zeros(runs)
    off_r = np.zeros(runs)
    hstep = dt_s
    for i in range(n):
        j = 2 * i
        k1, lf, lr = deriv(y, j)
        out["vertical_m_s2"][:, i] = k1[3]
        out["pitch_rad_s2"][:, i] = k1[4]
        out["longitudinal_m_s2"][:, i] = k1[5]
        out["z_m"][:, i] = y[0]
        out["theta_rad"][:, i] = y[1]
        off_f += lf
        off_r += lr
        if i == n - 1:
            break
        k2, _, _ = deriv(y + 0.5 * hstep * k1, j + 1)
        k3, _, _ = deriv(y + 0.5 * hstep * k2, j + 1)
        k4, _, _ = deriv(y + hstep * k3, j + 2)
        y = y + hstep / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    out["lift_off_fraction_front"] = off_f / n
    out["lift_off_fraction_rear"] = off_r / n
    if squeeze:
        out = {k: v[0] for k, v in out.items()}
    return out
