"""Single-wheel carriage rolling over a rough track (thesis ch. 6, Fig. 50).

Model (§6.3): carriage mass ``M`` on a Kelvin-Voigt tyre (stiffness ``K``, damping
``C``) in contact with the (enveloped) ground elevation ``u(t)``, plus parasitic
linkage damping ``C_p`` (1 kNs/m, estimated from free decay, §6.3). With ``z`` the
carriage displacement from static equilibrium (upward)::

    M z'' = K (u - z) + C (u' - z') - C_p z'                         (linear, thesis)

Three solution paths:

* :func:`simulate_linear` - exact discretisation (first-order hold on ``u`` and
  ``u'``, :func:`scipy.signal.cont2discrete`), exact for piecewise-linear input;
* :func:`simulate_nonlinear` - fixed-step 4th-order Runge-Kutta at 1 ms (the thesis
  used Runge-Kutta-Nystrom at about 1 ms) adding what the linear model leaves out:
  tyre lift-off (total tyre force cannot pull) and Coulomb friction in the linkage
  (smoothed sign, ``tanh(v/v_s)``); vectorised over a batch of runs;
* :func:`simulate_ivp` - :func:`scipy.integrate.solve_ivp` on the same equations
  (reference for tests and ``bench/bench_carriage.py``);
* :func:`acceleration_response` / :func:`response_psd` - frequency domain,
  ``S_a(f) = |H(f)|^2 G(n)/v`` with ``n = f/v``.

The profile is interpolated with a cubic spline (§6.3). SI units throughout.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import integrate, interpolate

from ... import _validate
from ..._validate import positive
from ..solvers import lti
from ..terrain.wheel_inputs import ground_input, half_step_input

__all__ = [
    "GRAVITY_M_S2",
    "THESIS_GRAVITY_M_S2",
    "PARASITIC_DAMPING_N_S_PER_M",
    "Carriage",
    "ground_input",
    "half_step_input",
    "carriage_state_space",
    "simulate_linear",
    "simulate_nonlinear",
    "simulate_ivp",
    "acceleration_response",
    "response_psd",
    "damped_natural_frequency",
]

#: Gravity of the thesis' studies, m/s² (chapters 6 and 7 computed with 9.81): the carriage and the
#: ch. 7 tractor study use it to reproduce the printed Tables; everything else uses the standard
#: gravity :data:`tyrelab.vehicle.units.STANDARD_GRAVITY_M_S2`.
THESIS_GRAVITY_M_S2 = 9.81
#: The carriage's gravity (the thesis' 9.81; the name kept for callers of issue 35).
GRAVITY_M_S2 = THESIS_GRAVITY_M_S2
#: Linkage damping estimated by the thesis from free decay on coil springs (§6.3).
PARASITIC_DAMPING_N_S_PER_M = 1000.0


@dataclass(frozen=True)
class Carriage:
    """Parameters of the single-wheel carriage (thesis Fig. 50).

    Any field may be an array (one element per run) for batched nonlinear runs.

    Attributes
    ----------
    mass_kg : float
        Carriage mass M on the tyre, kg.
    stiffness_N_per_m : float
        Tyre vertical stiffness K, N/m.
    damping_N_s_per_m : float
        Tyre vertical damping C, N s/m.
    parasitic_damping_N_s_per_m : float
        Viscous linkage damping C_p, N s/m (thesis: 1000).
    coulomb_friction_N : float
        Dry friction in the linkage, N (nonlinear path only; thesis §6.5.2 suspects it).
    """

    mass_kg: float
    stiffness_N_per_m: float
    damping_N_s_per_m: float
    parasitic_damping_N_s_per_m: float = PARASITIC_DAMPING_N_S_PER_M
    coulomb_friction_N: float = 0.0

    @property
    def natural_frequency_Hz(self) -> float:
        """Undamped natural frequency sqrt(K/M)/2pi, Hz."""
        return math.sqrt(self.stiffness_N_per_m / self.mass_kg) / (2 * math.pi)

    @property
    def damping_ratio(self) -> float:
        """Viscous damping ratio (C + C_p)/(2 sqrt(K M))."""
        return (self.damping_N_s_per_m + self.parasitic_damping_N_s_per_m) / (
            2 * math.sqrt(self.stiffness_N_per_m * self.mass_kg)
        )


def damped_natural_frequency(carriage: Carriage) -> float:
    """Damped natural frequency f_n sqrt(1 - zeta^2), Hz.

    See Also
    --------
    Carriage.natural_frequency_Hz : the undamped one.

    Examples
    --------
    >>> c = Carriage(mass_kg=1000.0, stiffness_N_per_m=250e3, damping_N_s_per_m=2000.0)   # C_p 1000 N s/m
    >>> round(c.natural_frequency_Hz, 3), round(c.damping_ratio, 4), round(damped_natural_frequency(c), 3)
    (2.516, 0.0949, 2.505)
    """
    _validate.instance("carriage", carriage, Carriage)
    z = carriage.damping_ratio
    return carriage.natural_frequency_Hz * math.sqrt(max(1 - z * z, 0.0))


def carriage_state_space(c: Carriage) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Continuous state space of the linear carriage (``state_space`` before issue 45, still
    importable from here under that name; :func:`tyrelab.vehicle.ride.state_space` is the
    pitch-plane tractor's).

    State ``[z, z']``, inputs ``[u, u']``, outputs ``[z, z', z'']``.

    See Also
    --------
    simulate_linear : runs it over a ground input.

    Examples
    --------
    >>> a, b, c, d = carriage_state_space(Carriage(100.0, 1e5, 1e3, parasitic_damping_N_s_per_m=0.0))
    >>> a.tolist(), c.shape, d.shape
    ([[0.0, 1.0], [-1000.0, -10.0]], (3, 2), (3, 2))
    """
    _validate.instance("c", c, Carriage)
    m, k, cc, cp = c.mass_kg, c.stiffness_N_per_m, c.damping_N_s_per_m, c.parasitic_damping_N_s_per_m
    a = np.array([[0.0, 1.0], [-k / m, -(cc + cp) / m]])
    b = np.array([[0.0, 0.0], [k / m, cc / m]])
    out_c = np.vstack([np.eye(2), a[1]])
    out_d = np.vstack([np.zeros((2, 2)), b[1]])
    return a, b, out_c, out_d


#: The name of :func:`carriage_state_space` before issue 45 (not in ``__all__``: the ride's
#: ``state_space`` is the pitch-plane tractor's).
state_space = carriage_state_space


def simulate_linear(
    carriage: Carriage, u_m, u_dot_m_s, dt_s: float, z0_m: float = 0.0, v0_m_s: float = 0.0
) -> dict[str, np.ndarray]:
    """Exact discretisation of the linear carriage (thesis §6.3 model).

    First-order hold on both inputs (:func:`tyrelab.vehicle.lti.discretise`: exact when
    ``u`` and ``u'`` vary linearly over each step; the discrete system diagonalised and
    each mode run with :func:`scipy.signal.lfilter`, a few vectorised passes).

    Parameters
    ----------
    carriage : Carriage
        Scalar parameters.
    u_m, u_dot_m_s : array_like
        Ground elevation (m) and rate (m/s) at ``t = k dt``.
    dt_s : float
        Step, s.
    z0_m, v0_m_s : float
        Initial displacement and velocity of the mass, m and m/s.

    Returns
    -------
    dict
        ``z_m``, ``v_m_s``, ``a_m_s2`` arrays like ``u_m``.

    See Also
    --------
    simulate_nonlinear : with lift-off and friction.

    Examples
    --------
    >>> c = Carriage(mass_kg=1000.0, stiffness_N_per_m=250e3, damping_N_s_per_m=2000.0)   # C_p 1000 N s/m
    >>> n = 5000; r = simulate_linear(c, np.full(n, 0.01), np.zeros(n), 1e-3)     # a 10 mm step
    >>> round(float(r["z_m"][-1]), 4), bool(r["z_m"].max() > 0.01)               # settles, after an overshoot
    (0.01, True)
    """
    dt_s = positive("dt_s", dt_s)
    a, b, c, d = carriage_state_space(carriage)
    w = np.vstack([np.asarray(u_m, float), np.asarray(u_dot_m_s, float)])  # (2, n)
    y = lti.discretise(a, b, c, d, dt_s).run(w, x0=np.array([z0_m, v0_m_s], float))
    return {"z_m": y[0], "v_m_s": y[1], "a_m_s2": y[2]}


def _half_samples(u, u_dot):
    u = np.atleast_2d(np.asarray(u, float))
    ud = np.atleast_2d(np.asarray(u_dot, float))
    if u.shape[-1] % 2 == 0:
        raise ValueError("nonlinear inputs must be sampled at dt/2 (odd length)")
    return u, ud


def simulate_nonlinear(
    carriage: Carriage,
    u_half_m,
    u_dot_half_m_s,
    dt_s: float = 1e-3,
    lift_off: bool = True,
    friction_velocity_m_s: float = 0.005,
    gravity_m_s2: float = THESIS_GRAVITY_M_S2,
    n_steps=None,
) -> dict[str, np.ndarray]:
    """Fixed-step RK4 carriage with tyre lift-off and Coulomb linkage friction.

    ``M z'' = F_t + F_l`` with ``F_t = max(K (u - z) + C (u' - z'), -M g)`` when
    ``lift_off`` (the total tyre force ``M g + F_t`` cannot pull the carriage down)
    and ``F_l = -C_p z' - F_c tanh(z'/v_s)``.

    Parameters
    ----------
    carriage : Carriage
        Scalars or arrays of shape ``(n_runs,)`` (batched).
    u_half_m, u_dot_half_m_s : array_like
        Input sampled at ``dt/2``: shape ``(2 N - 1,)`` or ``(n_runs, 2 N - 1)``.
    dt_s : float
        Integration step, s (1 ms as the thesis).
    lift_off : bool
        Allow the tyre to leave the ground.
    friction_velocity_m_s : float
        Smoothing velocity v_s of the Coulomb friction, m/s.
    n_steps : int or array_like of int, optional
        Per run, how many of the N samples are its own (1 to N): a batch of runs of
        different lengths is padded to the longest, and ``lift_off_fraction`` counts a
        run's own samples only, so that it does not depend on the other runs of the
        batch. Default N for every run.

    Returns
    -------
    dict
        ``z_m``, ``v_m_s``, ``a_m_s2``, ``lift_off_fraction`` (per run: the fraction of
        its ``n_steps`` samples with the tyre off the ground); arrays of shape ``(N,)``
        or ``(n_runs, N)``.

    See Also
    --------
    simulate_linear : the exact linear path.
    simulate_ivp : the same equations by solve_ivp.

    Examples
    --------
    >>> c = Carriage(mass_kg=1000.0, stiffness_N_per_m=250e3, damping_N_s_per_m=2000.0)   # C_p 1000 N s/m
    >>> dt = 1e-3; t = np.arange(20001) * dt / 2                        # 10 s, the input at half steps
    >>> u, ud = 0.01 * np.sin(2 * np.pi * 1.5 * t), 0.01 * 2 * np.pi * 1.5 * np.cos(2 * np.pi * 1.5 * t)
    >>> nl = simulate_nonlinear(c, u, ud, dt, lift_off=False)
    >>> lin = simulate_linear(c, u[::2], ud[::2], dt)
    >>> bool(np.abs(nl["z_m"] - lin["z_m"]).max() < 1e-6), float(nl["lift_off_fraction"])
    (True, 0.0)
    """
    dt_s = positive("dt_s", dt_s)
    u, ud = _half_samples(u_half_m, u_dot_half_m_s)
    squeeze = np.ndim(u_half_m) == 1
    runs = u.shape[0]
    shape = (runs,)
    m = np.broadcast_to(np.asarray(carriage.mass_kg, float), shape)
    k = np.broadcast_to(np.asarray(carriage.stiffness_N_per_m, float), shape)
    c = np.broadcast_to(np.asarray(carriage.damping_N_s_per_m, float), shape)
    cp = np.broadcast_to(np.asarray(carriage.parasitic_damping_N_s_per_m, float), shape)
    fc = np.ascontiguousarray(np.broadcast_to(np.asarray(carriage.coulomb_friction_N, float), shape))
    floor = -m * gravity_m_s2 if lift_off else np.full(shape, -np.inf)
    inv_m = 1.0 / m
    vs = np.full(shape, float(friction_velocity_m_s))  # arrays, not Python floats: a scalar operand costs a numpy call 60 % more
    n = (u.shape[1] + 1) // 2
    own = None
    if n_steps is not None:
        own = np.broadcast_to(np.asarray(n_steps), shape)
        if own.dtype.kind not in "iu" or np.any(own < 1) or np.any(own > n):
            raise ValueError(f"n_steps must be integers from 1 to the {n} samples of the input, got {n_steps!r}")
    # A batch is tens of runs, so the cost is the number of numpy calls per step, not the
    # arithmetic: every state is one (3, runs) array [z, z', z''] (rows 1:3 are the derivative
    # of rows 0:2, so one call advances z and z' together), the inputs [u, u'] of a half step
    # one contiguous (2, runs) array, and every result goes into a preallocated buffer (out=).
    # The floating-point operations, and their order, are those of the textbook loop
    # (tests/vehicle/test_carriage.py::test_nonlinear_matches_textbook_rk4 checks bit-identity).
    w = np.stack([u.T, ud.T], axis=1)  # (2n - 1, 2, runs)
    kc = np.stack([k, c])
    rec = np.empty((n, 3, runs))  # [z, z', z''] at every sample
    rec_s, rec_d, rec_v, rec_a = rec[:, 0:2], rec[:, 1:3], rec[:, 1], rec[:, 2]
    ft_rec = np.empty((n, runs))  # tyre force at every sample (lift-off count)
    stage = np.empty((3, 3, runs))  # the states of RK4 stages 2-4
    stage_s, stage_d, stage_v, stage_a = stage[:, 0:2], stage[:, 1:3], stage[:, 1], stage[:, 2]
    diff, inc, inc2 = np.empty((3, 2, runs))
    diff_u, diff_ud = diff
    t1, t2, ft = np.empty((3, runs))
    # C_p z' is +-0 when C_p = 0: subtracting it changes nothing (for a tyre force ft != -0)
    viscous = bool(np.any(cp != 0.0))
    add, sub, mul, div, tanh, maximum = np.add, np.subtract, np.multiply, np.divide, np.tanh, np.maximum

    def accel(xs, v, a, w_j, ft):
        """a = z'' at the state xs = [z, z'] (v its z' row) and input w_j; ft = tyre force."""
        sub(w_j, xs, diff)
        mul(kc, diff, diff)
        add(diff_u, diff_ud, ft)  # K (u - z) + C (u' - z')
        maximum(ft, floor, out=ft)  # (a positional out is deprecated for maximum, and slow)
        if viscous:
            mul(cp, v, t1)
            sub(ft, t1, t1)
            lhs = t1
        else:
            lhs = ft
        div(v, vs, t2)
        tanh(t2, t2)
        mul(fc, t2, t2)
        sub(lhs, t2, t2)
        mul(t2, inv_m, a)

    h, half_h, sixth_h = (np.full((2, runs), step) for step in (dt_s, 0.5 * dt_s, dt_s / 6.0))
    rec[0, 0:2] = 0.0
    (xb_s, xc_s, xd_s), (xb_d, xc_d, xd_d), (xb_v, xc_v, xd_v), (xb_a, xc_a, xd_a) = stage_s, stage_d, stage_v, stage_a
    for i in range(n):
        j = 2 * i
        xs, xdot = rec_s[i], rec_d[i]
        accel(xs, rec_v[i], rec_a[i], w[j], ft_rec[i])
        if i == n - 1:
            break
        w_mid = w[j + 1]
        mul(half_h, xdot, inc)
        add(xs, inc, xb_s)
        accel(xb_s, xb_v, xb_a, w_mid, ft)
        mul(half_h, xb_d, inc)
        add(xs, inc, xc_s)
        accel(xc_s, xc_v, xc_a, w_mid, ft)
        mul(h, xc_d, inc)
        add(xs, inc, xd_s)
        accel(xd_s, xd_v, xd_a, w[j + 2], ft)
        # x + h/6 (k1 + 2 k2 + 2 k3 + k4), summed left to right
        add(xb_d, xb_d, inc)  # 2 k2 exactly
        add(xdot, inc, inc)
        add(xc_d, xc_d, inc2)
        add(inc, inc2, inc)
        add(inc, xd_d, inc)
        mul(sixth_h, inc, inc)
        add(xs, inc, rec_s[i + 1])
    if own is None:
        fraction = np.count_nonzero(ft_rec <= floor, axis=0).astype(float) / n
    else:
        fraction = np.count_nonzero((ft_rec <= floor) & (np.arange(n)[:, None] < own), axis=0) / own
    out = {"z_m": np.ascontiguousarray(rec[:, 0].T), "v_m_s": np.ascontiguousarray(rec[:, 1].T),
           "a_m_s2": np.ascontiguousarray(rec[:, 2].T), "lift_off_fraction": fraction}
    if squeeze:
        out = {kk: vv[0] for kk, vv in out.items()}
    return out


def simulate_ivp(
    carriage: Carriage,
    x_m,
    elevation_m,
    speed_m_s: float,
    t_end_s: float,
    dt_out_s: float = 1e-3,
    x_start_m: float = 0.0,
    lift_off: bool = False,
    rtol: float = 1e-9,
    atol: float = 1e-12,
    max_step_s: float = 2e-3,
) -> dict[str, np.ndarray]:
    """The carriage integrated by :func:`scipy.integrate.solve_ivp` (DOP853).

    Same equations as :func:`simulate_nonlinear` (without friction smoothing when
    ``coulomb_friction_N`` is 0 the model is the linear one), the spline evaluated
    inside the right-hand side. The ground elevation is taken relative to its value
    at ``x_start_m`` and the carriage starts at rest at static equilibrium.

    Returns
    -------
    dict
        ``t_s``, ``z_m``, ``v_m_s``, ``a_m_s2`` at multiples of ``dt_out_s``.

    See Also
    --------
    simulate_nonlinear : the fixed-step integrator it checks.

    Examples
    --------
    >>> c = Carriage(mass_kg=1000.0, stiffness_N_per_m=250e3, damping_N_s_per_m=2000.0)   # C_p 1000 N s/m
    >>> x = np.linspace(0, 50, 501); h = 0.01 * np.sin(2 * np.pi * x / 5.0)
    >>> r = simulate_ivp(c, x, h, speed_m_s=2.0, t_end_s=5.0, dt_out_s=0.01)
    >>> len(r["t_s"]), bool(np.abs(r["z_m"]).max() < 0.05)
    (501, True)
    """
    _validate.instance("carriage", carriage, Carriage)
    for _name, _value in (("speed_m_s", speed_m_s), ("t_end_s", t_end_s), ("dt_out_s", dt_out_s), ("rtol", rtol),
                          ("atol", atol), ("max_step_s", max_step_s)):
        positive(_name, _value)
    spline = interpolate.CubicSpline(np.asarray(x_m, float), np.asarray(elevation_m, float))
    ds = spline.derivative()
    u0 = float(spline(x_start_m))
    m, k, c = carriage.mass_kg, carriage.stiffness_N_per_m, carriage.damping_N_s_per_m
    cp, fc = carriage.parasitic_damping_N_s_per_m, carriage.coulomb_friction_N
    floor = -m * THESIS_GRAVITY_M_S2 if lift_off else -np.inf

    def accel(t, z, v):
        x = x_start_m + speed_m_s * t
        ft = max(k * (float(spline(x)) - u0 - z) + c * (speed_m_s * float(ds(x)) - v), floor)
        return (ft - cp * v - fc * math.tanh(v / 0.005)) / m

    def rhs(t, y):
        return [y[1], accel(t, y[0], y[1])]

    t_eval = np.arange(int(math.floor(t_end_s / dt_out_s + 1e-9)) + 1) * dt_out_s
    sol = integrate.solve_ivp(
        rhs, (0.0, t_eval[-1]), [0.0, 0.0], method="DOP853", t_eval=t_eval, rtol=rtol, atol=atol, max_step=max_step_s
    )
    acc = np.array([accel(t, z, v) for t, z, v in zip(sol.t, sol.y[0], sol.y[1])])
    return {"t_s": sol.t, "z_m": sol.y[0], "v_m_s": sol.y[1], "a_m_s2": acc}


def acceleration_response(carriage: Carriage, frequency_Hz) -> np.ndarray:
    """Complex acceleration per unit ground displacement, H(f) = z''/u, 1/s^2.

    ``H = -w^2 (K + j w C) / (K - M w^2 + j w (C + C_p))``.

    See Also
    --------
    response_psd : the acceleration PSD through it.
    damped_natural_frequency : where it peaks.

    Examples
    --------
    >>> c = Carriage(mass_kg=1000.0, stiffness_N_per_m=250e3, damping_N_s_per_m=2000.0)   # C_p 1000 N s/m
    >>> h = acceleration_response(c, [0.05, 2.5])
    >>> round(float(abs(h[0]) / (2 * np.pi * 0.05) ** 2), 3), bool(abs(h[1]) > 10 * (2 * np.pi * 0.05) ** 2)
    (1.0, True)
    """
    _validate.instance("carriage", carriage, Carriage)
    _validate.non_negative_array("frequency_Hz", frequency_Hz)
    w = 2 * math.pi * np.asarray(frequency_Hz, dtype=float)
    k, c, m, cp = (
        carriage.stiffness_N_per_m,
        carriage.damping_N_s_per_m,
        carriage.mass_kg,
        carriage.parasitic_damping_N_s_per_m,
    )
    return -(w**2) * (k + 1j * w * c) / (k - m * w**2 + 1j * w * (c + cp))


def response_psd(
    carriage: Carriage, n_cycles_per_m, profile_psd_m3, speed_m_s: float
) -> tuple[np.ndarray, np.ndarray]:
    """Acceleration PSD from a profile spectrum (frequency-domain path).

    ``f = n v``, ``G_u(f) = G(n)/v`` and ``S_a(f) = |H(f)|^2 G_u(f)``.

    Returns
    -------
    f_Hz, psd_m2_s4_per_Hz : ndarray

    See Also
    --------
    acceleration_response : the transfer function it squares.

    Examples
    --------
    >>> c = Carriage(mass_kg=1000.0, stiffness_N_per_m=250e3, damping_N_s_per_m=2000.0)   # C_p 1000 N s/m
    >>> n = np.array([0.1, 0.5]); f, s = response_psd(c, n, np.full(2, 256e-6), 10 / 3.6)
    >>> np.round(f, 3).tolist(), bool(np.allclose(s, np.abs(acceleration_response(c, f)) ** 2 * 256e-6 / (10 / 3.6)))
    ([0.278, 1.389], True)
    """
    _validate.instance("carriage", carriage, Carriage)
    speed_m_s = positive("speed_m_s", speed_m_s)
    n = np.asarray(n_cycles_per_m, dtype=float)
    f = n * speed_m_s
    g = np.asarray(profile_psd_m3, dtype=float) / speed_m_s
    return f, np.abs(acceleration_response(carriage, f)) ** 2 * g
