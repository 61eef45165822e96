"""Accuracy metrics (thesis §6.4) and the pitch-plane tractor (ch. 7)."""

import math

import numpy as np
import pandas as pd
import pytest

from tyrelab.vehicle import bounce_pitch as bp
from tyrelab.vehicle import metrics as mt
from tyrelab.vehicle.tractor import Tractor, simulate_tractor


def test_probabilities_match_thesis_table_xiii():
    # Table XIII rolling rms: mean 0.92, sd 0.12 -> P(±10 %) 0.51, P(±30 %) 0.97 (printed)
    from scipy import stats

    m, s = 0.92, 0.12
    p10 = stats.norm.cdf((1.1 - m) / s) - stats.norm.cdf((0.9 - m) / s)
    p30 = stats.norm.cdf((1.3 - m) / s) - stats.norm.cdf((0.7 - m) / s)
    assert p10 == pytest.approx(0.51, abs=0.02) and p30 == pytest.approx(0.97, abs=0.01)
    r = mt.ratio_error_statistics([0.8, 0.9, 1.0, 1.1, 1.2])
    assert r["mean"] == pytest.approx(1.0) and r["n"] == 5


def test_peak_width_of_single_mode():
    fs, fn, zeta = 100.0, 2.0, 0.05
    f = np.linspace(0, 50, 50001)
    r = f / fn
    p = 1.0 / ((1 - r**2) ** 2 + (2 * zeta * r) ** 2)
    pk = mt.spectral_peak(f, p)
    assert pk["peak_frequency_Hz"] == pytest.approx(fn * math.sqrt(1 - 2 * zeta**2), rel=1e-3)
    assert pk["width_over_frequency"] == pytest.approx(2 * zeta, rel=0.02)


def test_envelope_and_similarity():
    fs = 100.0
    t = np.arange(0, 60, 1 / fs)
    env = 1.0 + 0.5 * np.sin(2 * np.pi * 0.05 * t)
    x = env * np.sin(2 * np.pi * 2.0 * t)
    e = mt.envelope(x, fs, 2.0, 0.5)
    assert np.max(np.abs(e[500:-500] - env[500:-500])) < 0.02
    assert mt.envelope_similarity(e, e, fs) == pytest.approx(1.0)
    rng = np.random.default_rng(1)
    other = mt.envelope(rng.standard_normal(t.size), fs, 2.0, 0.5)
    assert abs(mt.envelope_similarity(e, other, fs)) < 0.5
    assert mt.envelope_error(e, e) == 0.0


def test_accuracy_table_layout():
    rows = []
    for ch, k in (("rolling", 1.0), ("stationary", 1.2)):
        for i in range(4):
            rows.append({"characteristics": ch, "ratio_rms": k + 0.01 * i, "ratio_sqrt_peak_height": k,
                         "ratio_peak_frequency": k, "ratio_width_over_frequency": k,
                         "envelope_correlation": 0.9, "envelope_error": 0.3})
    t = mt.accuracy_table(pd.DataFrame(rows))
    assert len(t) == 20 and list(t.columns) == ["quantity", "statistic", "rolling", "stationary"]


def _free_decay(tr, n=12001, step_m=0.0):
    """Free vibration after the ground under both axles steps up by ``step_m`` at t = 0.

    :func:`simulate_tractor` starts at rest in the static equilibrium, so the step is
    the same as releasing the tractor ``step_m`` below its (new) equilibrium.
    """
    ground, zeros = np.full(2 * n - 1, float(step_m)), np.zeros(2 * n - 1)
    return simulate_tractor(tr, ground, zeros, ground, zeros, 1e-3, lift_off=False)


def test_tractor_modes_match_eigenproblem():
    # MF698T heavy, Table XV; tiny damping; impulse via a short bump under the front axle
    m, i, b, a = 5120.0, 6210.0, 0.896, 2.436 - 0.896
    kf, kr = 2 * 426e3, 2 * 328e3
    tr = Tractor(m, i, a, b, 0.838, kf, kr, 50.0, 50.0)
    n = 40001
    t = np.arange(2 * n - 1) * 5e-4
    bump = np.where(t < 0.02, 0.01 * np.sin(np.pi * t / 0.02) ** 2, 0.0)
    rate = np.gradient(bump, 5e-4)
    out = simulate_tractor(tr, bump, rate, np.zeros_like(bump), np.zeros_like(bump), 1e-3, lift_off=False)
    f, p = mt.acceleration_psd(out["vertical_m_s2"], 1000.0, 0.05)
    fp, pp = mt.acceleration_psd(out["pitch_rad_s2"], 1000.0, 0.05)
    peaks = mt.spectral_peaks(f, p + pp * (p.max() / pp.max()), 2, 1.0, 6.0)
    f1, f2 = bp.natural_frequencies(m, i, a, b, kf, kr)
    assert peaks[0] == pytest.approx(f1, abs=0.06) and peaks[1] == pytest.approx(f2, abs=0.06)


def test_tractor_static_and_longitudinal_models():
    tr = Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3, 9.1e5, 6e3, "maxwell")
    out = _free_decay(tr, 2001)  # in equilibrium, nothing moves
    assert np.allclose(out["vertical_m_s2"], 0.0) and np.allclose(out["pitch_rad_s2"], 0.0)
    with pytest.raises(ValueError):
        _free_decay(Tractor(1, 1, 1, 1, 1, 1, 1, 1, 1, longitudinal_model="spring"))


@pytest.mark.parametrize("model", ["kelvin_voigt", "maxwell"])
def test_tractor_free_decay_from_a_displacement(model):
    """Released 10 mm below equilibrium: the first accelerations are the springs' forces
    over the mass and inertia (no damper force at rest), and the decay settles on the
    raised ground, level. Damping ratio of bounce ~ (3 + 2) kN s/m / (2 sqrt(1.51e6 N/m
    x 5120 kg)) = 0.028 at ~2.7 Hz, so after 12 s the oscillation is down to
    exp(-0.028 x 2 pi x 2.7 x 12) ~ 3e-3 of its start: allowed 1e-2 of the step.
    """
    m, inertia, a, b, h = 5120.0, 6210.0, 1.54, 0.896, 0.838
    kf, kr, step = 8.5e5, 6.6e5, 0.01
    out = _free_decay(Tractor(m, inertia, a, b, h, kf, kr, 3e3, 2e3, 9.1e5, 6e3, model), 12001, step)
    assert out["vertical_m_s2"][0] == pytest.approx((kf + kr) * step / m, rel=1e-12)
    assert out["pitch_rad_s2"][0] == pytest.approx((a * kf - b * kr) * step / inertia, rel=1e-12)
    assert out["z_m"][0] == 0.0 and np.max(out["z_m"]) > 1.5 * step  # overshoots: lightly damped
    assert out["z_m"][-1] == pytest.approx(step, abs=1e-2 * step)
    assert abs(out["theta_rad"][-1]) < 1e-2 * step / (a + b)


def test_tractor_rk4_against_the_exact_linear_response_to_a_bump():
    """Without lift-off or longitudinal compliance the tractor is a linear 4-state system.

    Reference: its state equations written here and integrated by :func:`scipy.signal.lsim`
    (exact for inputs linear between samples) over a 20 mm sin² bump of 0.2 s under the
    front, then the rear axle. Expected difference: lsim's linear interpolation of the
    bump's rate, ~4e-5 of the peak at 1 ms (RK4's own error is O(dt^4)); allowed 2e-4.
    Feeding RK4's midpoint stage the previous input sample instead costs 5e-3.
    """
    from scipy import signal

    m, inertia, a, b, h = 5120.0, 6210.0, 1.54, 0.896, 0.838
    kf, kr, cf, cr = 8.5e5, 6.6e5, 3e3, 2e3
    dt, n = 1e-3, 3001
    th = np.arange(2 * n - 1) * dt / 2

    def bump(t, t0):
        s = np.clip((t - t0) / 0.2, 0, 1)
        rate = np.where((s > 0) & (s < 1), 0.02 * np.sin(2 * np.pi * s) * np.pi / 0.2, 0.0)
        return 0.02 * np.sin(np.pi * s) ** 2, rate

    uf, udf = bump(th, 0.1)
    ur, udr = bump(th, 0.1 + (a + b) / 3.0)  # 3 m/s
    out = simulate_tractor(Tractor(m, inertia, a, b, h, kf, kr, cf, cr, 0.0, 0.0, "none"), uf, udf, ur, udr, dt,
                           lift_off=False)
    A = np.array([[0, 0, 1, 0], [0, 0, 0, 1],
                  [-(kf + kr) / m, (-kf * a + kr * b) / m, -(cf + cr) / m, (-cf * a + cr * b) / m],
                  [(-a * kf + b * kr) / inertia, -(a * a * kf + b * b * kr) / inertia,
                   (-a * cf + b * cr) / inertia, -(a * a * cf + b * b * cr) / inertia]])
    B = np.array([[0, 0, 0, 0], [0, 0, 0, 0], [kf / m, cf / m, kr / m, cr / m],
                  [a * kf / inertia, a * cf / inertia, -b * kr / inertia, -b * cr / inertia]])
    U = np.column_stack([uf[::2], udf[::2], ur[::2], udr[::2]])
    _, y, _ = signal.lsim((A, B, np.eye(4), np.zeros((4, 4))), U, th[::2])
    for got, ref in ((out["z_m"], y[:, 0]), (out["theta_rad"], y[:, 1])):
        assert np.max(np.abs(got - ref)) < 2e-4 * np.max(np.abs(ref))
    np.testing.assert_array_equal(out["longitudinal_m_s2"], 0.0)


def test_default_tractor_has_no_longitudinal_force():
    tr = Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3)
    n = 2001
    t = np.arange(2 * n - 1) * 5e-4
    u = np.where(t < 0.2, 0.01 * np.sin(np.pi * t / 0.2) ** 2, 0.0)
    out = simulate_tractor(tr, u, np.gradient(u, 5e-4), np.zeros_like(u), np.zeros_like(u), 1e-3, lift_off=False)
    assert tr.longitudinal_stiffness_N_per_m == 0.0 and tr.longitudinal_damping_N_s_per_m == 0.0
    np.testing.assert_array_equal(out["longitudinal_m_s2"], 0.0)


def test_tractor_in_free_fall_off_a_ledge():
    """The ground under both axles drops 0.5 m at t = 0: with lift-off both tyres leave it at
    once (their forces floor at minus the static axle loads W b/(a+b) and W a/(a+b)), so the
    body falls at exactly g without pitching until it lands, 0.32 s later."""
    m, inertia, a, b = 5120.0, 6210.0, 1.54, 0.896
    n = 201
    drop, zeros = np.full(2 * n - 1, -0.5), np.zeros(2 * n - 1)
    out = simulate_tractor(Tractor(m, inertia, a, b, 0.838, 8.5e5, 6.6e5, 3e3, 2e3), drop, zeros, drop, zeros, 1e-3)
    from tyrelab.vehicle.tractor import GRAVITY_M_S2

    np.testing.assert_allclose(out["vertical_m_s2"], -GRAVITY_M_S2, rtol=1e-12)
    np.testing.assert_allclose(out["pitch_rad_s2"], 0.0, atol=1e-12)
    assert out["lift_off_fraction_front"] == out["lift_off_fraction_rear"] == 1.0


def test_maxwell_without_a_damper_is_no_longitudinal_element():
    n = 2001
    t = np.arange(2 * n - 1) * 5e-4
    u = np.where(t < 0.2, 0.01 * np.sin(np.pi * t / 0.2) ** 2, 0.0)
    ud = np.gradient(u, 5e-4)
    runs = [simulate_tractor(Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3, kx, cx, model),
                             u, ud, np.zeros_like(u), np.zeros_like(u), 1e-3, lift_off=False)
            for kx, cx, model in ((9.1e5, 0.0, "maxwell"), (0.0, 0.0, "none"))]
    np.testing.assert_array_equal(runs[0]["pitch_rad_s2"], runs[1]["pitch_rad_s2"])
