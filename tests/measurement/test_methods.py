"""Alternative methods of Table I (thesis §3.4) on analytic and virtual experiments."""

import numpy as np
import pytest

from tyrelab.measurement import methods
from tyrelab.rig import experiments as ex
from tyrelab.rig.instrument import RigConfig


def test_free_vibration_analytic_sdof():
    m, k, c = 1865.0, 500e3, 3.0e3
    wn = np.sqrt(k / m)
    z = c / (2 * np.sqrt(k * m))
    wd = wn * np.sqrt(1 - z**2)
    t = np.arange(0, 6, 1 / 256)
    # Peaks refined by a parabola through three samples: the peak times, hence K, are good to
    # ~2e-5 (without the refinement ~1e-3); the decrement reads C 0.26-0.43 % low (the mean
    # removed is the tail's, not exactly zero). Allowed: 1e-4 on K, 1 % on C.
    for phase in (0.0, 0.3):
        x = 0.01 * np.exp(-z * wn * t) * np.cos(wd * t + phase)
        out = methods.free_vibration(t, x, m)
        assert out["stiffness_N_per_m"] == pytest.approx(k, rel=1e-4)
        assert out["damping_N_s_per_m"] == pytest.approx(c, rel=0.01)
        assert out["natural_frequency_Hz"] == pytest.approx(wn / (2 * np.pi), rel=5e-5)  # half K's error
        assert out["damping_ratio"] == pytest.approx(z, rel=0.01)
    # A 20 s record (the tail, whose mean is removed, is at rest) sampled at 64 Hz, ~25 samples a
    # cycle: a peak sampled off its top by up to half a sample reads up to (pi f/fs)^2/2 = 8e-3 low,
    # C then 1e-3 off; the parabola through three samples leaves ~(pi f/fs)^4 ~ 2e-5 on the heights.
    # Measured: C within 7e-6, K within 1e-5: allowed 5e-5 on both.
    t64 = np.arange(0, 20, 1 / 64)
    for phase in (0.0, 0.3):
        out = methods.free_vibration(t64, 0.01 * np.exp(-z * wn * t64) * np.cos(wd * t64 + phase), m)
        assert out["damping_N_s_per_m"] == pytest.approx(c, rel=5e-5)
        assert out["stiffness_N_per_m"] == pytest.approx(k, rel=5e-5)
    with pytest.raises(ValueError, match="too few decay cycles"):
        methods.free_vibration(t[:200], 0.01 * np.exp(-z * wn * t[:200]) * np.cos(wd * t[:200]), m)  # two peaks


def test_half_power_and_load_deflection_without_linkage_or_creep():
    cfg = RigConfig(linkage_stiffness_N_per_m=0.0, linkage_damping_N_s_per_m=0.0, beam_damping_N_s_per_m=0.0)
    K, C = 500e3, 3.0e3
    rf = ex.random_force_response(K, C, cfg=cfg)
    hp = methods.half_power(rf.force_N, rf.acceleration_m_s2, cfg.sample_rate_Hz, ex.suspended_mass_kg(18.3))
    # on the rig (axle on the load beams under the carriage) the method reads the suspended
    # system, not the tyre alone: over seeds 0-4, K -2.0 to -2.7 %, C -1.6 to -5.1 %
    assert hp["stiffness_N_per_m"] == pytest.approx(K, rel=0.035)
    assert hp["damping_N_s_per_m"] == pytest.approx(C, rel=0.06)
    ramp = ex.load_ramp(K, creep_ratio=1e9)
    assert methods.load_deflection_stiffness(ramp.force_N, ramp.displacement_m) == pytest.approx(K, rel=0.01)


def test_table_i_structure():
    from tyrelab.published import read_published

    t = ex.table_i(read_published("table_i")).set_index("method")
    assert set(t["source"]) == {methods.TABLE_I_SOURCE}
    assert t.loc["free_vibration", "thesis_stiffness_kN_per_m"] == 485.0
    am = t.loc["apparent_mass"]
    assert am["stiffness_kN_per_m"] == pytest.approx(am["truth_stiffness_kN_per_m"], rel=0.01)
    assert am["damping_kN_s_per_m"] == pytest.approx(3.0, rel=0.05)  # Table I anchor of the truth model
    from tyrelab.rig import truth

    assert am["truth_stiffness_kN_per_m"] == pytest.approx(truth.stiffness("T1", 1.38, 0.0, 18.25) / 1e3)  # stationary
    # creep: load-deflection far below the dynamic value. The rig's creep spring is *chosen*
    # from Table I (330/450), so this only checks the plumbing; the method itself is checked
    # against the series-spring solution at other creep ratios below. The ratio is to our
    # apparent-mass K (within 1 % of the truth): allowed 1.5 %.
    assert t.loc["load_deflection", "stiffness_ratio"] == pytest.approx(
        330 / 450 * am["truth_stiffness_kN_per_m"] / am["stiffness_kN_per_m"], rel=0.015)
    for m in ("free_vibration", "forced_vibration"):
        assert 1.0 < t.loc[m, "stiffness_ratio"] < 1.1  # linkage stiffness in parallel
        # linkage damping included by response methods, below the 1.2 kNs/m upper bound (§3.4)
        assert 0.3 < t.loc[m, "damping_excess_kN_s_per_m"] < 1.2
    assert np.isnan(t.loc["load_deflection", "damping_kN_s_per_m"])
    # every comparison column is ours - thesis of the columns shown, in kN/m and kN s/m
    for q in ("stiffness_kN_per_m", "damping_kN_s_per_m"):
        diff = f"{q.split('_')[0]}_difference_{q.split('_', 1)[1]}"
        np.testing.assert_allclose(t[diff], t[q] - t[f"thesis_{q}"], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(t["damping_excess_kN_s_per_m"], t["damping_kN_s_per_m"] - am["damping_kN_s_per_m"],
                               rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(t["stiffness_ratio"], t["stiffness_kN_per_m"] / am["stiffness_kN_per_m"], rtol=1e-12)


@pytest.mark.parametrize("creep_ratio", [0.5, 2.0, 8.0])
def test_load_deflection_measures_tyre_and_creep_in_series(creep_ratio):
    """A 120 s ramp with first-order creep (tau 3 s, creep spring ``creep_ratio`` K).

    Past a few tau the deflection is F/K + (F - tau dF/dt)/(creep_ratio K), so the loading
    branch has the slope of the two springs in series, K creep_ratio/(1 + creep_ratio);
    the creep transient is e^-8 at the 20 % point where the fit starts, and the noise
    (20 N, 0.05 mm on ~1700 points) moves the slope by ~0.1 %: allowed 1 %.
    """
    K = 450e3
    ramp = ex.load_ramp(K, creep_ratio=creep_ratio, rng=np.random.default_rng(5))
    expected = K * creep_ratio / (1 + creep_ratio)
    assert methods.load_deflection_stiffness(ramp.force_N, ramp.displacement_m) == pytest.approx(expected, rel=0.01)


def test_half_power_on_a_single_degree_of_freedom():
    """Random force on m, K, C alone (lsim), 20 min at 64 Hz.

    The receptance peaks at w_n sqrt(1 - 2 zeta^2): K reads -2 zeta^2 = -0.48 % low
    (zeta = 0.049); the Welch estimate (0.01 Hz bins, 23 averages) of this noise-free
    response scatters K by ~0.1 % (seed 0: -0.41 %) and C by ~0.5 %: K is checked against
    the receptance peak, K (1 - 2 zeta^2), to 0.25 % (the peak of the mobility |H1|/w,
    at w_n itself, reads +0.48 % from it), C to 1.5 %.
    """
    from scipy import signal

    m, K, C, fs = 1865.0, 500e3, 3.0e3, 64.0
    n = int(1200 * fs)
    force = np.random.default_rng(0).standard_normal(n) * 1e3
    _, accel, _ = signal.lsim(signal.lti([1.0, 0.0, 0.0], [m, C, K]), force, np.arange(n) / fs)
    hp = methods.half_power(force, accel, fs, m)
    zeta = C / (2 * np.sqrt(K * m))
    assert hp["stiffness_N_per_m"] == pytest.approx(K * (1 - 2 * zeta**2), rel=0.0025)
    assert hp["natural_frequency_Hz"] == pytest.approx(np.sqrt(K * (1 - 2 * zeta**2) / m) / (2 * np.pi), rel=0.00125)
    assert hp["damping_N_s_per_m"] == pytest.approx(C, rel=0.015)
    assert hp["damping_ratio"] == pytest.approx(zeta, rel=0.015)
