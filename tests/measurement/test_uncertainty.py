"""Per-run uncertainty of K and C (issue 14): type A from the run's blocks, type B from §3.2.9."""

import math

import numpy as np
import pandas as pd
import pytest

from tyrelab.measurement import apparent_mass as am
from tyrelab.measurement import uncertainty as un
from tests.synthetic import spring_damper_recording

FS = 256.0
K_TRUE, C_TRUE = 250e3, 2000.0


def _analyse(df, axle_mass_kg=600.0):
    accel = df[["accel_left_m_s2", "accel_right_m_s2"]].to_numpy(float).T
    beams = df[[f"load_beam_{i}_N" for i in range(1, 5)]].to_numpy(float).T
    f = am.tyre_force(accel[0], accel[1], beams, axle_mass_kg)
    return am.apparent_mass_demodulation(f, accel.mean(axis=0), FS), len(df)


def _type_a(duration_s, seed, noise_N=200.0):
    d, n = _analyse(spring_damper_recording(K_TRUE, C_TRUE, duration_s=duration_s, force_noise_N=noise_N, seed=seed))
    uk, uc, dof = un.residual_uncertainty(d.residual_probes_N, d.denominator_m, d.frequency_Hz)
    return d, float(uk), float(uc), float(dof)


def test_probes_see_the_noise_not_the_excitation():
    """Without noise the residual probes are ~0 (the tyre is fitted, the excitation is out of reach)."""
    clean, *_ = _type_a(50.0, 1, noise_N=0.0)
    noisy, uk, uc, dof = _type_a(50.0, 1, noise_N=2000.0)
    assert clean.residual_probes_N.shape == (len(am.PROBE_OFFSETS),)
    assert np.abs(clean.residual_probes_N).max() < 1e-2 * np.abs(noisy.residual_probes_N).max()
    assert dof > 25


def test_interval_width_scales_as_one_over_root_duration():
    """Pure spring-damper with white force noise: the run's own interval narrows as 1/√T."""
    durations = np.array([50.0, 200.0, 800.0])
    widths_k, widths_c = [], []
    for T in durations:
        runs = [_type_a(T, seed, noise_N=2000.0) for seed in range(10)]
        widths_k.append(np.mean([2 * un.coverage_factor(r[3]) * r[1] for r in runs]))
        widths_c.append(np.mean([2 * un.coverage_factor(r[3]) * r[2] for r in runs]))
    for widths in (widths_k, widths_c):
        slope = np.polyfit(np.log(durations), np.log(widths), 1)[0]
        assert slope == pytest.approx(-0.5, abs=0.1)


def test_type_a_intervals_cover_the_truth_of_a_noisy_spring_damper():
    inside_k = inside_c = 0
    n = 80
    for seed in range(n):
        d, uk, uc, dof = _type_a(20.0, 100 + seed, noise_N=600.0)
        k = float(un.coverage_factor(dof))
        inside_k += abs(float(d.stiffness_N_per_m) - K_TRUE) <= k * uk
        inside_c += abs(float(d.damping_N_s_per_m) - C_TRUE) <= k * uc
    # 95 % nominal; with 80 runs the binomial sd is 2.4 %
    assert 0.88 <= inside_k / n <= 1.0 and 0.88 <= inside_c / n <= 1.0
    assert inside_k + inside_c < 2 * n  # not uselessly wide either (P(no miss in 160) < 0.1 %)


def test_limits_budget_is_the_thesis_limits_as_rectangular_distributions():
    b = un.limits_budget(600.0)
    assert b.force_gain == pytest.approx(0.03 / math.sqrt(3))
    assert math.degrees(b.phase_rad) == pytest.approx(1 / math.sqrt(3))
    with pytest.raises(ValueError, match="axle_mass_kg"):
        un.limits_budget(-1.0)


def test_instrument_sensitivities_match_a_perturbed_dynamic_stiffness():
    """Phase: rotate Z by δφ; axle mass: add ω² δM to K; channel gains: (M_a ω² − Z)(δa − δb)."""
    k, c, f, m = 230e3, 2400.0, 3.8, 600.0
    w = 2 * np.pi * f
    z = k + 1j * w * c
    dphi, dm, dg = 1e-3, 2.0, 1e-3
    uk, uc = un.instrument_terms(k, c, f, un.InstrumentBudget(0.0, dphi), m)
    rotated = z * np.exp(-1j * dphi)
    assert float(uk) == pytest.approx(abs(rotated.real - k), rel=1e-2)
    assert float(uc) == pytest.approx(abs(rotated.imag / w - c), rel=1e-2)
    uk, uc = un.instrument_terms(k, c, f, un.InstrumentBudget(0.0, 0.0, axle_mass_kg=dm), m)
    assert float(uk) == pytest.approx(w**2 * dm) and float(uc) == 0.0
    uk, uc = un.instrument_terms(k, c, f, un.InstrumentBudget(0.0, 0.0, accel_gain=dg), m)
    # derived force M_a(1+δ)a − Σbeams over a(1+δ): exact perturbation of Z
    z_meas = (z + m * w**2 * dg) / (1 + dg)
    assert float(uk) == pytest.approx(abs(z_meas.real - k), rel=1e-2)
    assert float(uc) == pytest.approx(abs(z_meas.imag / w - c), rel=1e-2)


def test_day_budget_reads_the_days_phase_and_its_random_error():
    f = np.arange(1.0, 8.01, 0.25)
    tf = pd.DataFrame({"frequency_Hz": f, "gain": 1.0, "phase_deg": 0.5, "coherence": 0.9999})
    b = un.day_budget(tf, 4.0, 29)
    assert math.degrees(b.phase_rad) == pytest.approx(0.5, rel=0.05)
    corrected = un.day_budget(tf, 4.0, 29, corrected=True)
    assert 0 < corrected.phase_rad < b.phase_rad and corrected.axle_mass_kg == 0.0
    with pytest.raises(ValueError, match="n_averages"):
        un.day_budget(tf, 4.0, 0)


def test_day_budget_does_not_count_a_phase_the_channel_gains_explain():
    # a check phase of 0.02 deg with a negligible random error: resolved when nothing explains it ...
    f = np.arange(1.0, 8.01, 0.25)
    tf = pd.DataFrame({"frequency_Hz": f, "gain": 1.0, "phase_deg": 0.02, "coherence": 1 - 1e-9})
    alone = un.day_budget(tf, 4.0, 29)
    assert math.degrees(alone.phase_rad) == pytest.approx(0.02, rel=0.01)
    # ... but a gain mismatch dA - dB of 0.17 % times Im R = -0.4 moves the check's phase by 0.04 deg (1 sd):
    # that is the channel-gain terms of the budget, not a phase of the force path
    with_r = un.day_budget(tf.assign(inertial_ratio_re=1.5, inertial_ratio_im=-0.4), 4.0, 29)
    assert math.degrees(with_r.phase_rad) < 0.001
    assert with_r.accel_gain == un.ACCEL_GAIN_U and with_r.beam_gain == un.BEAM_GAIN_U
    # a phase well beyond both is a force-path phase and counts with its size
    big = un.day_budget(tf.assign(phase_deg=0.3, inertial_ratio_re=1.5, inertial_ratio_im=-0.4), 4.0, 29)
    assert math.degrees(big.phase_rad) == pytest.approx(0.3, rel=0.01)


def test_day_budget_line_error_counts_the_correlation_of_hann_bins():
    # correlated neighbouring bins carry less information than independent ones: the GLS standard error is
    # larger than the independent-bin one, sqrt(1 + 2 (4/9 + 1/36)) = 1.37 times for the band's mean
    f = np.arange(1.0, 8.01, 0.25)
    tf = pd.DataFrame({"frequency_Hz": f, "gain": 1.0, "phase_deg": 0.0, "coherence": 0.99})
    sd = math.sqrt(0.01) / (math.sqrt(0.99) * math.sqrt(2 * 29))
    n = int(((f >= 2) & (f <= 6)).sum())
    ratio = un.day_budget(tf, 4.0, 29).phase_rad / (sd / math.sqrt(n))
    assert 1.2 < ratio < 1.45


def test_combined_interval_contains_the_estimate_and_uses_student_t():
    r = un.combine(230e3, 2400.0, 4.0, 1000.0, 50.0, 7.0, un.InstrumentBudget(0.0, 0.0))
    assert float(r.stiffness_u_N_per_m) == pytest.approx(1000.0)
    assert float(r.coverage_factor) == pytest.approx(2.365, abs=1e-3)
    lo, hi = r.stiffness_ci95_N_per_m
    assert lo < 230e3 < hi and hi - lo == pytest.approx(2 * 2.365 * 1000.0, rel=1e-3)
