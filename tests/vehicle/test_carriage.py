"""Carriage simulators (thesis §6.3): exact vs integrated, analytic frequency, frequency domain."""

import math

import numpy as np
import pytest

from tyrelab.vehicle import carriage as cm
from tyrelab.vehicle import enveloping as ev
from tyrelab.vehicle import metrics as mt
from tyrelab.vehicle import profiles as pr

# Table XII, 10 km/h light: 2.728 m/s, 1860 kg, 1.72 kNs/m, 388 kN/m (x0.9 on slats)
CAR = cm.Carriage(1860.0, 0.9 * 388e3, 1720.0)
SPEED = 2.728


@pytest.fixture(scope="module")
def track():
    t = pr.add_lead_in(pr.slatted_track(seed=3, length_m=40.0), 2.0)
    return t.x_m, ev.tapered_moving_average(t.left_m, t.dx_m, 0.5)


def test_exact_matches_solve_ivp(track):
    x, h = track
    _, u, ud = cm.ground_input(x, h, SPEED, 1e-3, 0.0, 30.0)
    lin = cm.simulate_linear(CAR, u - u[0], ud, 1e-3)["a_m_s2"]
    ivp = cm.simulate_ivp(CAR, x, h, SPEED, (u.size - 1) * 1e-3)["a_m_s2"]
    n = min(lin.size, ivp.size)
    err = np.sqrt(np.mean((lin[:n] - ivp[:n]) ** 2)) / np.sqrt(np.mean(ivp[:n] ** 2))
    assert err < 1e-3


def test_rk4_matches_exact_without_nonlinearity(track):
    x, h = track
    _, uh, udh = cm.ground_input(x, h, SPEED, 5e-4, 0.0, 20.0)
    if uh.size % 2 == 0:
        uh, udh = uh[:-1], udh[:-1]
    nl = cm.simulate_nonlinear(CAR, uh - uh[0], udh, 1e-3, lift_off=False)["a_m_s2"]
    lin = cm.simulate_linear(CAR, uh[::2] - uh[0], udh[::2], 1e-3)["a_m_s2"]
    assert np.sqrt(np.mean((nl - lin) ** 2)) / np.sqrt(np.mean(lin**2)) < 1e-3


def test_free_decay_frequency_and_log_decrement_lightly_damped():
    c = cm.Carriage(2000.0, 320e3, 300.0, parasitic_damping_N_s_per_m=200.0)
    n = 20000
    out = cm.simulate_linear(c, np.zeros(n), np.zeros(n), 1e-3, z0_m=0.01)
    z = out["z_m"]
    zc = np.flatnonzero((z[:-1] > 0) & (z[1:] <= 0))
    frac = z[zc] / (z[zc] - z[zc + 1])
    tc = (zc + frac) * 1e-3
    f_sim = (tc.size - 1) / (tc[-1] - tc[0])
    assert abs(f_sim / cm.damped_natural_frequency(c) - 1) < 1e-4
    # free decay: the logarithmic decrement gives the damping ratio of tyre + linkage damping,
    # zeta = (C + C_p) / (2 sqrt(K M)) = 500 / (2 sqrt(320e3 * 2000)) = 0.00988. Successive
    # maxima of a linear free decay are one damped period apart and fall by exp(-delta);
    # reading them at 1 ms samples (2 Hz) errs by ~(2 pi f dt)^2 / 8 = 1e-5 of the peak,
    # so over 30 cycles delta is good to ~1e-6 of itself; allowed 1e-3.
    zeta = 500.0 / (2 * math.sqrt(320e3 * 2000.0))
    assert c.damping_ratio == pytest.approx(zeta, rel=1e-12)
    peaks = np.flatnonzero((z[1:-1] > z[:-2]) & (z[1:-1] >= z[2:])) + 1
    delta = math.log(z[peaks[0]] / z[peaks[30]]) / 30
    assert delta / math.sqrt(4 * math.pi**2 + delta**2) == pytest.approx(zeta, rel=1e-3)
    assert out["a_m_s2"][0] == pytest.approx(-320e3 * 0.01 / 2000)  # released from z0 at rest


def test_spectral_peak_of_random_response_near_damped_frequency():
    c = cm.Carriage(2000.0, 320e3, 200.0, parasitic_damping_N_s_per_m=100.0)
    f = np.linspace(0.5, 10, 100001)
    h = np.abs(cm.acceleration_response(c, f)) ** 2 / (2 * math.pi * f) ** 4  # displacement transmissibility
    fd = cm.damped_natural_frequency(c)
    assert f[np.argmax(h)] == pytest.approx(fd, rel=0.01)


def test_frequency_domain_matches_time_domain_rms():
    t = pr.add_lead_in(pr.slatted_track(seed=4, length_m=100.0), 2.0)
    h = ev.tapered_moving_average(t.left_m, t.dx_m, 0.5)
    _, u, ud = cm.ground_input(t.x_m, h, 3.0, 1e-3, 2.0, 100.0)
    a = cm.simulate_linear(CAR, u - u[0], ud, 1e-3)["a_m_s2"][3000:]
    n, g = pr.profile_spectrum(h, t.dx_m, segment_m=25.6)
    f, s = cm.response_psd(CAR, n, g, 3.0)
    rms_fd = math.sqrt(np.trapezoid(s, f))
    assert rms_fd == pytest.approx(mt.rms(a), rel=0.15)


def test_lift_off_limits_pull_and_friction_damps():
    n = 4001
    t = np.arange(n) * 5e-4
    u = 0.05 * np.sin(2 * np.pi * 2.0 * t)  # large input near resonance
    ud = 0.05 * 2 * np.pi * 2.0 * np.cos(2 * np.pi * 2.0 * t)
    free = cm.simulate_nonlinear(cm.Carriage(1860.0, 350e3, 1500.0), u, ud, 1e-3, lift_off=True)
    assert free["a_m_s2"].min() >= -cm.GRAVITY_M_S2 - 1e-6 - 1000 / 1860 * 2
    assert free["lift_off_fraction"] > 0
    fr = cm.simulate_nonlinear(cm.Carriage(1860.0, 350e3, 1500.0, 0.0, 300.0), u, ud, 1e-3, lift_off=False)
    nf = cm.simulate_nonlinear(cm.Carriage(1860.0, 350e3, 1500.0, 0.0, 0.0), u, ud, 1e-3, lift_off=False)
    assert mt.rms(fr["a_m_s2"]) < mt.rms(nf["a_m_s2"])


def test_batched_equals_single():
    n = 2001
    rng = np.random.default_rng(0)
    u = np.cumsum(rng.standard_normal(n)) * 1e-4
    ud = np.gradient(u, 5e-4)
    cars = cm.Carriage(np.array([1860.0, 2300.0]), np.array([3.4e5, 2.9e5]), np.array([1700.0, 1600.0]), 0.0, 150.0)
    b = cm.simulate_nonlinear(cars, np.vstack([u, u]), np.vstack([ud, ud]), 1e-3)
    s = cm.simulate_nonlinear(cm.Carriage(2300.0, 2.9e5, 1600.0, 0.0, 150.0), u, ud, 1e-3)
    np.testing.assert_allclose(b["a_m_s2"][1], s["a_m_s2"], rtol=1e-12, atol=1e-12)


def test_linear_carriage_starting_in_equilibrium_on_raised_ground_stays_put():
    """z0 = u0 = 10 mm, at rest, ground level: the initial state is the static equilibrium.

    The first-order-hold state is shifted by the input at t = 0; getting that shift's sign
    wrong starts the carriage 2 x 10 mm off and it rings at ~2 Hz.
    """
    n = 4000
    u = np.full(n, 0.01)
    out = cm.simulate_linear(CAR, u, np.zeros(n), 1e-3, z0_m=0.01)
    np.testing.assert_allclose(out["z_m"], 0.01, atol=1e-12)
    np.testing.assert_allclose(out["a_m_s2"], 0.0, atol=1e-9)


def test_lift_off_changes_nothing_while_the_tyre_stays_on_the_ground():
    """A 2 mm ripple at 2 Hz: the dynamic tyre force stays far below the static load M g,
    so allowing lift-off must give the same run bit for bit, and no time off the ground."""
    n = 4001
    t = np.arange(n) * 5e-4
    u = 0.002 * np.sin(2 * np.pi * 2.0 * t)
    ud = 0.002 * 2 * np.pi * 2.0 * np.cos(2 * np.pi * 2.0 * t)
    on = cm.simulate_nonlinear(CAR, u, ud, 1e-3, lift_off=True)
    off = cm.simulate_nonlinear(CAR, u, ud, 1e-3, lift_off=False)
    assert np.max(np.abs(CAR.stiffness_N_per_m * 0.002 * 3)) < CAR.mass_kg * cm.GRAVITY_M_S2  # stays in contact
    np.testing.assert_array_equal(on["a_m_s2"], off["a_m_s2"])
    assert on["lift_off_fraction"] == 0.0


def _textbook_rk4(car, u, ud, h, lift_off, vs=0.005):
    """The RK4 of :func:`cm.simulate_nonlinear` written out plainly (one run, whole-array steps)."""
    m, k, c, cp, fc = (np.asarray(getattr(car, f), float) for f in
                       ("mass_kg", "stiffness_N_per_m", "damping_N_s_per_m", "parasitic_damping_N_s_per_m", "coulomb_friction_N"))
    floor = -m * cm.GRAVITY_M_S2 if lift_off else np.full(m.shape, -np.inf)

    def accel(z, v, uu, uud):
        ft = np.maximum(k * (uu - z) + c * (uud - v), floor)
        return (ft - cp * v - fc * np.tanh(v / vs)) * (1.0 / m), ft

    n = (u.shape[1] + 1) // 2
    z, v, off = np.zeros(m.shape), np.zeros(m.shape), np.zeros(m.shape)
    zs, vs_, acc = [], [], []
    for i in range(n):
        j = 2 * i
        a1, ft = accel(z, v, u[:, j], ud[:, j])
        zs.append(z), vs_.append(v), acc.append(a1)
        off += ft <= floor
        if i == n - 1:
            break
        zb, vb = z + 0.5 * h * v, v + 0.5 * h * a1
        a2, _ = accel(zb, vb, u[:, j + 1], ud[:, j + 1])
        zc, vc = z + 0.5 * h * vb, v + 0.5 * h * a2
        a3, _ = accel(zc, vc, u[:, j + 1], ud[:, j + 1])
        zd, vd = z + h * vc, v + h * a3
        a4, _ = accel(zd, vd, u[:, j + 2], ud[:, j + 2])
        z = z + h / 6.0 * (v + 2 * vb + 2 * vc + vd)
        v = v + h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4)
    return {"z_m": np.array(zs).T, "v_m_s": np.array(vs_).T, "a_m_s2": np.array(acc).T, "lift_off_fraction": off / n}


@pytest.mark.parametrize("parasitic", [0.0, 1000.0])
def test_nonlinear_matches_textbook_rk4(parasitic):
    """The buffered, row-stacked RK4 loop does the textbook RK4's arithmetic bit for bit
    (lift-off, friction, with and without the viscous linkage term, a batch of three)."""
    n = 1201
    t = np.arange(n) * 5e-4
    u = np.vstack([a * np.sin(2 * np.pi * 2.0 * t) for a in (0.002, 0.03, 0.05)])
    ud = np.vstack([a * 2 * np.pi * 2.0 * np.cos(2 * np.pi * 2.0 * t) for a in (0.002, 0.03, 0.05)])
    car = cm.Carriage(np.array([1860.0, 2300.0, 1860.0]), np.array([3.4e5, 2.9e5, 3.5e5]),
                      np.array([1700.0, 1600.0, 1500.0]), parasitic, np.array([150.0, 0.0, 300.0]))
    for lift_off in (True, False):
        got = cm.simulate_nonlinear(car, u, ud, 1e-3, lift_off=lift_off)
        want = _textbook_rk4(car, u, ud, 1e-3, lift_off)
        assert want["lift_off_fraction"][2] > 0 or not lift_off
        for key in want:
            np.testing.assert_array_equal(got[key], want[key], err_msg=key)
