import numpy as np
import pytest

from tyrelab.measurement import apparent_mass as am
from tests.synthetic import CHANNELS, spring_damper_recording


def split(df):
    accel = np.array([df[c].to_numpy() for c in CHANNELS[:2]])
    beams = np.array([df[c].to_numpy() for c in CHANNELS[2:]])
    return accel, beams


def test_thesis_worked_example():
    # thesis §3.5: H = -400 - 100j at 3.8 Hz -> K = 228 027 N/m, C = 2 388 N s/m
    k, c = am.stiffness_damping(-400 - 100j, 3.8)
    assert k == pytest.approx(228_027, abs=0.5)
    assert c == pytest.approx(2_388, abs=0.5)


def test_apparent_mass_from_kc_inverts_stiffness_damping():
    h = am.apparent_mass_from_kc(228_027.0, 2_387.6, 3.8)
    k, c = am.stiffness_damping(h, 3.8)
    assert (k, c) == pytest.approx((228_027.0, 2_387.6))


def test_tyre_force_recovers_ground_force():
    df = spring_damper_recording(stiffness_N_per_m=2e5, damping_N_s_per_m=1500, static_load_N=1e4)
    accel, beams = split(df)
    f = am.tyre_force(accel[0], accel[1], beams, 600.0)
    t = df["time_s"].to_numpy()
    w = 2 * np.pi * 4.0
    x = 0.007 * np.sin(w * t)
    v = 0.007 * w * np.cos(w * t)
    np.testing.assert_allclose(f, 1e4 - (2e5 * x + 1500 * v), atol=1e-6)


@pytest.mark.parametrize("freq", [2.0, 3.93, 4.0, 5.17])
@pytest.mark.parametrize("k,c", [(250e3, 2000.0), (120e3, 800.0), (450e3, 3500.0)])
def test_demodulation_recovers_pure_spring_damper(freq, k, c):
    df = spring_damper_recording(k, c, freq)
    accel, beams = split(df)
    f = am.tyre_force(accel[0], accel[1], beams, 600.0)
    d = am.apparent_mass_demodulation(f, accel.mean(axis=0), 256.0)
    assert d.frequency_Hz == pytest.approx(freq, rel=1e-4)
    assert d.stiffness_N_per_m == pytest.approx(k, rel=0.005)
    assert d.damping_N_s_per_m == pytest.approx(c, rel=0.005)
    assert d.displacement_amplitude_m == pytest.approx(0.007, rel=0.005)
    assert d.acceleration_amplitude_m_s2 == pytest.approx(0.007 * (2 * np.pi * freq) ** 2, rel=0.005)


def test_damping_sign_is_positive_for_a_dissipative_tyre():
    # Swapping csd arguments conjugates H and flips the damping sign (field notes).
    df = spring_damper_recording(250e3, 2000.0, 4.0)
    accel, beams = split(df)
    f = am.tyre_force(accel[0], accel[1], beams, 600.0)
    w = am.apparent_mass_welch(f, accel.mean(axis=0), 256.0, 4.0)
    d = am.apparent_mass_demodulation(f, accel.mean(axis=0), 256.0)
    assert w.damping_N_s_per_m > 0 and d.damping_N_s_per_m > 0
    assert w.apparent_mass_kg.real < 0  # thesis convention: H = -(K + jωC)/ω²


def test_welch_on_bin_is_exact_and_off_bin_shows_picket_fence():
    df = spring_damper_recording(250e3, 2000.0, 4.0)
    accel, beams = split(df)
    f = am.tyre_force(accel[0], accel[1], beams, 600.0)
    w = am.apparent_mass_welch(f, accel.mean(axis=0), 256.0, 4.0)
    assert w.stiffness_N_per_m == pytest.approx(250e3, rel=0.005)
    assert w.damping_N_s_per_m == pytest.approx(2000.0, rel=0.005)
    assert w.coherence == pytest.approx(1.0, abs=1e-6)
    df = spring_damper_recording(250e3, 2000.0, 3.93)
    accel, beams = split(df)
    f = am.tyre_force(accel[0], accel[1], beams, 600.0)
    w = am.apparent_mass_welch(f, accel.mean(axis=0), 256.0)
    assert abs(w.stiffness_N_per_m / 250e3 - 1) > 0.01  # the bin is 0.055 Hz away


def test_noisy_recording_within_instrument_accuracy():
    df = spring_damper_recording(250e3, 2000.0, 4.0, force_noise_N=400.0, accel_noise_m_s2=0.2, seed=3)
    accel, beams = split(df)
    f = am.tyre_force(accel[0], accel[1], beams, 600.0)
    d = am.apparent_mass_demodulation(f, accel.mean(axis=0), 256.0)
    assert d.stiffness_N_per_m == pytest.approx(250e3, rel=0.01)
    assert d.damping_N_s_per_m == pytest.approx(2000.0, rel=0.03)


def test_frequency_wander_is_tracked():
    fs, k, c = 256.0, 300e3, 2500.0
    t = np.arange(int(50 * fs)) / fs
    # Vibrator frequency wanders ±0.08 Hz, amplitude ±15 % (thesis §3.5 tolerances).
    phase = 2 * np.pi * (4.0 * t - 0.08 * 31 / (2 * np.pi) * np.cos(2 * np.pi * t / 31))
    omega = 2 * np.pi * (4.0 + 0.08 * np.sin(2 * np.pi * t / 31))
    amp = 0.005 * (1 + 0.15 * np.sin(2 * np.pi * t / 23))
    damp = 0.005 * 0.15 * 2 * np.pi / 23 * np.cos(2 * np.pi * t / 23)
    x = amp * np.sin(phase)
    v = damp * np.sin(phase) + amp * omega * np.cos(phase)
    a = np.gradient(v, 1 / fs)
    f = -(k * x + c * v)
    d = am.apparent_mass_demodulation(f, a, fs)
    assert d.stiffness_N_per_m == pytest.approx(k, rel=0.01)
    assert d.damping_N_s_per_m == pytest.approx(c, rel=0.03)


def test_vectorised_over_runs_matches_one_by_one():
    recs = [spring_damper_recording(k, c, fr, force_noise_N=100, seed=i)
            for i, (k, c, fr) in enumerate([(2e5, 1e3, 3.5), (3e5, 2e3, 4.0), (4e5, 3e3, 4.6)])]
    pairs = [split(df) for df in recs]
    forces = np.array([am.tyre_force(a[0], a[1], b, 600.0) for a, b in pairs])
    accels = np.array([a.mean(axis=0) for a, _ in pairs])
    batch = am.apparent_mass_demodulation(forces, accels, 256.0)
    for i in range(3):
        one = am.apparent_mass_demodulation(forces[i], accels[i], 256.0)
        assert batch.stiffness_N_per_m[i] == pytest.approx(float(one.stiffness_N_per_m), rel=1e-9)
        assert batch.damping_N_s_per_m[i] == pytest.approx(float(one.damping_N_s_per_m), rel=1e-9)


def test_excitation_frequency_between_bins():
    fs = 256.0
    t = np.arange(int(20 * fs)) / fs
    assert am.excitation_frequency(np.sin(2 * np.pi * 3.437 * t), fs) == pytest.approx(3.437, abs=2e-3)
    assert np.isnan(am.excitation_frequency(np.sin(2 * np.pi * 3.0 * t[:4]), fs))


def test_welch_segments_at_bin_match_scipy_csd_welch_coherence():
    from scipy import signal

    df = spring_damper_recording(250e3, 2000.0, 3.93, force_noise_N=500, accel_noise_m_s2=0.3, seed=5)
    accel, beams = split(df)
    f = am.tyre_force(accel[0], accel[1], beams, 600.0)
    a = accel.mean(axis=0)
    fs, nperseg = 256.0, 2048
    freqs, g_af = signal.csd(a, f, fs=fs, nperseg=nperseg)
    _, g_aa = signal.welch(a, fs=fs, nperseg=nperseg)
    _, coh = signal.coherence(a, f, fs=fs, nperseg=nperseg)
    i = int(np.argmin(np.abs(freqs - 3.93)))
    w = am.apparent_mass_welch(f, a, fs, 3.93)
    assert w.frequency_Hz == pytest.approx(freqs[i])
    assert complex(w.apparent_mass_kg) == pytest.approx(-g_af[i] / g_aa[i], rel=1e-9)
    assert float(w.coherence) == pytest.approx(coh[i], rel=1e-9)


def test_analytic_band_of_a_pure_tone():
    fs = 256.0
    t = np.arange(int(30 * fs)) / fs
    z = am.analytic_band(3.0 * np.cos(2 * np.pi * 4.0 * t + 0.3) + 1.5 * np.cos(2 * np.pi * 9.0 * t), fs, 4.0)
    mid = slice(int(3 * fs), -int(3 * fs))  # beyond the band-pass start-up at the ends
    np.testing.assert_allclose(np.abs(z[mid]), 3.0, rtol=0.01)
    np.testing.assert_allclose(np.angle(z[mid] * np.exp(-1j * (2 * np.pi * 4.0 * t[mid] + 0.3))), 0.0, atol=1e-3)
    centre = slice(int(10 * fs), -int(10 * fs))
    np.testing.assert_allclose(np.abs(z[centre]), 3.0, rtol=1e-3)


def test_excitation_blocks_see_amplitude_and_frequency_drift():
    fs = 256.0
    t = np.arange(int(40 * fs)) / fs
    amp = np.where(t < 20, 1.0, 1.3)
    d = am.apparent_mass_demodulation(amp * np.sin(2 * np.pi * 4 * t), amp * np.sin(2 * np.pi * 4 * t), fs, 4.0)
    a_blocks, f_blocks = am.excitation_blocks(d.envelope_m_s2, d.angular_frequency_rad_s, fs)
    assert a_blocks.max() / a_blocks.min() == pytest.approx(1.3, rel=0.02)
    np.testing.assert_allclose(f_blocks, 4.0, atol=0.01)


def test_demodulation_of_a_chirp_with_known_instantaneous_frequency():
    """A quadratic chirp 3.8 -> 4.2 Hz over 60 s: ω(t) is known in closed form.

    x = A sin φ(t), φ' = ω(t) = 2π(3.8 + 0.4 (t/T)²), exact velocity and acceleration,
    f = -(K x + C v). The demodulator divides the acceleration by the *instantaneous*
    ω(t)²; what it neglects is the term ω'/ω² ≈ 1.3e-4 of the acceleration, in
    quadrature, so the expected errors are ~1e-4 on ω(t), ≤ (ω'/ω²)·K/(ωC) ≈ 6e-4 on C
    (observed 2e-4) and second order (~5e-5) on K. Allowed: 1e-3 on ω(t) and C, 3e-4 on K.
    Dividing by the run's mean ω² instead costs 1 % on K and C here (the frequency
    profile is not symmetric about the middle of the Hann taper).
    """
    fs, k, c, T, A = 256.0, 300e3, 2500.0, 60.0, 0.005
    t = np.arange(int(T * fs)) / fs
    u = t / T
    phase = 2 * np.pi * (3.8 * t + 0.4 * T * u**3 / 3)
    omega = 2 * np.pi * (3.8 + 0.4 * u**2)
    omega_dot = 2 * np.pi * 0.8 * u / T
    x = A * np.sin(phase)
    v = A * omega * np.cos(phase)
    a = A * omega_dot * np.cos(phase) - A * omega**2 * np.sin(phase)
    d = am.apparent_mass_demodulation(-(k * x + c * v), a, fs)
    mid = slice(int(5 * fs), -int(5 * fs))  # beyond the band-pass start-up and the 1 s smoothing
    np.testing.assert_allclose(d.angular_frequency_rad_s[mid], omega[mid], rtol=1e-3)
    assert d.stiffness_N_per_m == pytest.approx(k, rel=3e-4)
    assert d.damping_N_s_per_m == pytest.approx(c, rel=1e-3)
    assert d.displacement_amplitude_m == pytest.approx(A, rel=1e-3)


def test_excitation_frequency_ignores_content_outside_the_band_and_handles_its_edges():
    fs = 256.0
    t = np.arange(int(30 * fs)) / fs
    # a wheel-rotation component at 0.5 Hz ten times the excitation's amplitude lies below the 1-8 Hz band
    x = 10 * np.sin(2 * np.pi * 0.5 * t) + np.sin(2 * np.pi * 4.2 * t)
    assert am.excitation_frequency(x, fs) == pytest.approx(4.2, abs=2e-3)
    # a tone just above the band (within the Hann main lobe, ±2/30 Hz): the peak sits on the
    # band's last bin, the parabolic refinement uses the two bins inside and stays in the band
    top = am.excitation_frequency(np.sin(2 * np.pi * 8.03 * t), fs)
    assert 7.95 <= top <= am.EXCITATION_BAND_Hz[1] + 1 / (2 * 2 * 30)
    # a tone on the band's first frequency (a bin: the band is inclusive) reads within half a
    # zero-padded bin of it (the refinement's clip), not a bin and a half up
    low = am.excitation_frequency(np.sin(2 * np.pi * am.EXCITATION_BAND_Hz[0] * t), fs)
    assert am.EXCITATION_BAND_Hz[0] <= low <= am.EXCITATION_BAND_Hz[0] + 1 / (2 * 2 * 30)
    assert np.isnan(am.excitation_frequency(np.zeros_like(t), fs))  # nothing in the band: no excitation


def test_analytic_band_default_half_width_excludes_a_tone_1_hz_away():
    fs = 256.0
    t = np.arange(int(30 * fs)) / fs
    z = am.analytic_band(3.0 * np.cos(2 * np.pi * 4.0 * t) + 2.0 * np.cos(2 * np.pi * 5.0 * t), fs, 4.0)
    centre = slice(int(10 * fs), -int(10 * fs))
    np.testing.assert_allclose(np.abs(z[centre]), 3.0, rtol=1e-3)


def test_excitation_blocks_of_a_record_shorter_than_a_block():
    fs = 256.0
    n = int(9 * fs)  # 9 s: 3 s edges leave 3 s, less than one 5 s block
    omega = np.full(n, 2 * np.pi * 4.0)
    amp, freq = am.excitation_blocks(np.full(n, 2.0), omega, fs)
    assert amp.shape == freq.shape == (1,)
    assert amp[0] == pytest.approx(2.0) and freq[0] == pytest.approx(4.0)
    amp, freq = am.excitation_blocks(np.full(int(23 * fs), 2.0), np.full(int(23 * fs), 2 * np.pi * 4.0), fs)
    assert freq.shape == (3,) and np.allclose(freq, 4.0)  # (23 - 2 x 3) s = three 5 s blocks


def test_welch_vectorised_over_runs_and_results_are_frozen():
    import dataclasses

    recs = [spring_damper_recording(k, 2000.0, 4.0, seed=i) for i, k in enumerate((2e5, 4e5))]
    pairs = [split(df) for df in recs]
    forces = np.array([am.tyre_force(a[0], a[1], b, 600.0) for a, b in pairs])
    accels = np.array([a.mean(axis=0) for a, _ in pairs])
    w = am.apparent_mass_welch(forces, accels, 256.0)
    np.testing.assert_allclose(w.stiffness_N_per_m, [2e5, 4e5], rtol=0.005)
    with pytest.raises(dataclasses.FrozenInstanceError):
        w.stiffness_N_per_m = 0.0

# ---------------------------------------------------------------- argument checks (issue 10)

import pytest  # noqa: E402

from tyrelab.measurement import apparent_mass as _am  # noqa: E402


@pytest.mark.parametrize("call, name", [
    (lambda x: _am.apparent_mass_welch(x, x, 0.0), "sample_rate_Hz"),
    (lambda x: _am.apparent_mass_welch(x, x, float("nan")), "sample_rate_Hz"),
    (lambda x: _am.apparent_mass_welch(x, x, 256.0, resolution_Hz=0.0), "resolution_Hz"),
    (lambda x: _am.apparent_mass_welch(x, x[:-1], 256.0, 4.0), "force_N and accel_m_s2"),
    (lambda x: _am.apparent_mass_demodulation(x, x, -256.0), "sample_rate_Hz"),
    (lambda x: _am.apparent_mass_demodulation(x, x, 256.0, excitation_frequency_Hz=-4.0), "excitation_frequency_Hz"),
    (lambda x: _am.apparent_mass_demodulation(x, x, 256.0, 4.0, half_band_Hz=0.0), "half_band_Hz"),
    (lambda x: _am.excitation_frequency(x, 0.0), "sample_rate_Hz"),
    (lambda x: _am.excitation_frequency(x, 256.0, band_Hz=(8.0, 1.0)), "band_Hz"),
    (lambda x: _am.tyre_force(x, x, np.stack([x] * 4), 0.0), "axle_mass_kg"),
    (lambda x: _am.tyre_force(x, x, np.stack([x] * 4), float("inf")), "axle_mass_kg"),
    (lambda x: _am.tyre_force(x, x, np.stack([x] * 3), 600.0), "load_beams_N"),
    (lambda x: _am.tyre_force(x, x, x, 600.0), "load_beams_N"),  # one-dimensional: no beam axis
    (lambda x: _am.tyre_force(x, x, np.stack([x[:-1]] * 4), 600.0), "load_beams_N"),
    (lambda x: _am.tyre_force(x, x[:-1], np.stack([x] * 4), 600.0), "accel_left_m_s2 and accel_right_m_s2"),
    (lambda x: _am.stiffness_damping(-400 - 100j, 0.0), "frequency_Hz"),
    (lambda x: _am.apparent_mass_from_kc(1e5, 1e3, -1.0), "frequency_Hz"),
    (lambda x: _am.welch_segments_at(x, 256.0, 4.0, 1), "nperseg"),
    (lambda x: _am.h1_spectrum(x, x[:-1], 256.0, 64), "mismatched lengths"),
    (lambda x: _am.h1_spectrum(x, x, 256.0, 10**6), "nperseg"),
    (lambda x: _am.excitation_blocks(x, x, 256.0, block_s=0.0), "block_s"),
])
def test_bad_arguments_raise_value_error_naming_the_parameter(call, name):
    x = np.sin(np.arange(2048) / 10.0)
    with pytest.raises(ValueError, match=name):
        call(x)


def test_nan_frequency_means_unknown_not_an_error():
    k, c = _am.stiffness_damping(np.array([-400 - 100j, -400 - 100j]), np.array([3.8, np.nan]))
    assert round(float(k[0])) == 228027 and np.isnan(k[1]) and np.isnan(c[1])


def test_welch_estimate_is_h1_spectrum_read_at_the_bin():
    """apparent_mass_welch's one-bin evaluation and h1_spectrum are the same estimator."""
    rng = np.random.default_rng(5)
    fs, n = 256.0, 256 * 40
    t = np.arange(n) / fs
    a = np.sin(2 * np.pi * 4.0 * t) + 0.1 * rng.standard_normal(n)
    f = 800.0 * a + 3000.0 * np.cos(2 * np.pi * 4.0 * t) + 50 * rng.standard_normal(n)
    w = _am.apparent_mass_welch(f, a, fs, 4.0)
    nperseg = 2048  # what apparent_mass_welch picks at 0.125 Hz resolution
    s = _am.h1_spectrum(a, f, fs, nperseg)
    k = int(np.argmin(np.abs(s.frequency_Hz - float(w.frequency_Hz))))
    assert complex(w.apparent_mass_kg) == pytest.approx(-complex(s.h1[k]), rel=1e-9)
    assert float(w.coherence) == pytest.approx(float(s.coherence[k]), rel=1e-9)


def test_segment_length_may_be_the_whole_record():
    """nperseg from 2 to n inclusive (h1_spectrum, welch_segments_at): one segment of the whole record is
    a periodogram, and on a tone at a bin it reads the gain exactly."""
    fs, n = 256.0, 1024
    t = np.arange(n) / fs
    x = np.sin(2 * np.pi * 8.0 * t)  # 32 cycles: bin 32 of a 1024-point segment
    h = _am.h1_spectrum(x, 3.0 * x, fs, n)
    k = int(np.argmin(np.abs(h.frequency_Hz - 8.0)))
    assert h.frequency_Hz.size == n // 2 + 1 and h.h1[k] == pytest.approx(3.0, rel=1e-9)
    assert _am.welch_segments_at(x, fs, 8.0, n).shape[-1] == 1
    assert _am.h1_spectrum(x, x, fs, 2).frequency_Hz.size == 2


def test_analytic_band_filters_linearly_not_circularly():
    """The band-pass is applied by FFT on a zero-padded record, so a 21x burst in the record's last 2 s
    must not wrap onto its start: the output over the record is the same as for the record followed by a
    minute of zeros (linear convolution either way). Left over: the band filter's tail beyond the padding
    (8/half_band s), 1e-4 of the burst -> allowed 2.5e-4 (half the padding: 8e-4)."""
    fs = 256.0
    t = np.arange(int(40 * fs)) / fs
    x = np.sin(2 * np.pi * 4.0 * t) * (1 + 20 * (t >= 38))  # whole cycles: zero mean either way
    z = _am.analytic_band(x, fs, 4.0)
    ref = _am.analytic_band(np.concatenate([x, np.zeros(int(60 * fs))]), fs, 4.0)[: x.size]
    assert np.max(np.abs(z - ref)[: int(20 * fs)]) < 2.5e-4 * 21


def test_excitation_blocks_drop_the_start_up_and_average_each_run():
    """Default edge: 3 s dropped at both ends (the band-pass start-up of analytic_band), then whole 5 s
    blocks: 36 s at 100 Hz give six blocks; each run (row) averaged on its own."""
    fs, n = 100.0, 3600
    t = np.arange(n) / fs
    env = np.vstack([1.0 + 0.01 * t, 2.0 + 0 * t])
    omega = 2 * np.pi * np.vstack([4.0 + 0 * t, 3.0 + 0.001 * t])
    amp, freq = am.excitation_blocks(env, omega, fs)
    assert amp.shape == freq.shape == (2, 6)
    starts = 3.0 + 5.0 * np.arange(6)
    np.testing.assert_allclose(amp[0], 1.0 + 0.01 * (starts + 2.495), rtol=1e-12)
    np.testing.assert_allclose(amp[1], 2.0, rtol=1e-12)
    np.testing.assert_allclose(freq[1], 3.0 + 0.001 * (starts + 2.495), rtol=1e-12)


def test_excitation_frequency_of_rows_with_no_room_in_the_band_is_nan_per_row():
    x = np.ones((3, 64))
    f = am.excitation_frequency(x, 256.0, band_Hz=(4.0, 4.5))  # 4 Hz bins: fewer than three in the band
    assert f.shape == (3,) and np.isnan(f).all()


def test_welch_reads_an_excitation_above_nyquist_at_the_nyquist_bin():
    """A frequency above fs/2 cannot be in the record: the estimate is read at the last bin, fs/2."""
    fs, n = 64.0, 4096
    rng = np.random.default_rng(4)
    a = rng.standard_normal(n)
    f = np.convolve(a, [0.5, 0.3, 0.2], mode="same")
    high = am.apparent_mass_welch(f, a, fs, 40.0)
    nyq = am.apparent_mass_welch(f, a, fs, fs / 2)
    assert high.frequency_Hz == nyq.frequency_Hz == fs / 2
    assert high.apparent_mass_kg == nyq.apparent_mass_kg
