"""An independent generator of noisy broadband rig runs (issue 44), for the estimators' bias and coverage.

Not tyrelab's generator (:mod:`tyrelab.rig.method_runs` solves the rig in the frequency domain over a
periodic record): a time-domain state-space model integrated by ``scipy.signal.lsim`` from rest
(the first seconds dropped), the way an audit would build one:

* the axle (``axle_mass_kg``) on the tyre and on four stiff load beams (``beam_stiffness_N_per_m``,
  25 Hz with the axle); above the beams the carriage, so that axle and carriage make the rig's
  suspended mass ``suspended_mass_kg`` (1866 kg: 18.3 kN / g); the linkage to the tractor
  (``linkage_*``) in parallel with the tyre; the vibrator's force on the carriage;
* the tyre Kelvin–Voigt (``K``, ``C``) or, rolling, a Kelvin–Voigt unit in series with a damper
  ``series_C`` (a massless contact point); the ground under the tyre may move (``road``: a height
  profile of ISO 8608 class A, B or C at the run's speed, ``G_d(n) = G_d(n₀) (n/n₀)⁻²``,
  ``n₀ = 0.1`` cycles/m, ``G_d(n₀)`` the class' geometric mean);
* the drive random (flat over the band, random phases) or a linear sweep over the band;
* the channels as raw format v1 records them: two axle accelerometers and four load beams
  (upward/outward positive; ``M_a a = f_tyre + Σ beams``), each with independent white noise whose
  part inside the band is ``accel_noise`` (or ``beam_noise``) times the in-band r.m.s. of the
  channel's own signal.

The truth is the tyre's K and C (and c₂) passed in.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from scipy import fft as sfft
from scipy import signal

#: ISO 8608:2016 Table 1: geometric mean of the class' displacement PSD at n₀ = 0.1 cycles/m, m³.
ISO8608_GD_N0_M3 = {"A": 16e-6, "B": 64e-6, "C": 256e-6}
SPLIT = np.array([0.27, 0.23, 0.26, 0.24])


def _in_band_rms(x, fs, band):
    X = sfft.rfft(x)
    f = sfft.rfftfreq(x.size, 1 / fs)
    sel = (f >= band[0]) & (f <= band[1])
    return float(np.sqrt(2 * np.sum(np.abs(X[sel]) ** 2)) / x.size)


def _white(rng, n, in_band_rms, fs, band):
    """White noise whose part inside ``band`` has r.m.s. ``in_band_rms``."""
    return rng.standard_normal(n) * in_band_rms * np.sqrt((fs / 2) / (band[1] - band[0]))


def road_profile(rng, n, fs, speed_km_h, road_class):
    """Height under the tyre (m) and its rate (m/s): ISO 8608 class ``road_class`` at ``speed_km_h``,
    temporal PSD ``G_d(f/v)/v`` from 0.5 Hz (random phases)."""
    v = speed_km_h / 3.6
    f = sfft.rfftfreq(n, 1 / fs)
    with np.errstate(divide="ignore"):
        gd = ISO8608_GD_N0_M3[road_class] * (np.where(f > 0, f / v, np.inf) / 0.1) ** -2.0
    psd = np.where(f >= 0.5, gd / v, 0.0)  # one-sided, m²/Hz
    amp = np.sqrt(psd * fs * n / 2)
    spec = amp * np.exp(1j * rng.uniform(0, 2 * np.pi, f.size))
    z = sfft.irfft(spec, n)
    zd = sfft.irfft(1j * 2 * np.pi * f * spec, n)
    return z, zd


def rig_run(K, C, series_C=None, *, method="random", seed=0, accel_noise=0.0, beam_noise=0.0, road=None,
            speed_km_h=0.0, suspended_mass_kg=1866.0, axle_mass_kg=600.0, band_Hz=(1.0, 8.0),
            duration_s=50.0, sample_rate_Hz=256.0, beam_stiffness_N_per_m=600.0 * (2 * np.pi * 25.0) ** 2,
            beam_damping_N_s_per_m=2.0e3, linkage_stiffness_N_per_m=35e3, linkage_damping_N_s_per_m=0.7e3,
            axle_rms_m=6e-3) -> pd.DataFrame:
    """One recorded run (raw format v1 columns), the axle's motion ``axle_rms_m`` r.m.s. (module docstring)."""
    rng = np.random.default_rng(seed)
    fs = sample_rate_Hz
    lead = int(8 * fs)
    n = int(duration_s * fs) + lead
    t = np.arange(n) / fs
    Ma, Mc = axle_mass_kg, suspended_mass_kg - axle_mass_kg
    kb, cb, kl, cl = beam_stiffness_N_per_m, beam_damping_N_s_per_m, linkage_stiffness_N_per_m, linkage_damping_N_s_per_m
    if method == "random":
        f = sfft.rfftfreq(n, 1 / fs)
        drive = sfft.irfft(np.where((f >= band_Hz[0]) & (f <= band_Hz[1]),
                                    np.exp(1j * rng.uniform(0, 2 * np.pi, f.size)), 0), n)
    else:
        tt = np.clip(t - lead / fs, 0, None)
        drive = signal.chirp(tt, band_Hz[0], duration_s, band_Hz[1], method="linear") * (t >= lead / fs)
    z, zd = road_profile(rng, n, fs, speed_km_h, road) if road else (np.zeros(n), np.zeros(n))
    # states: x_a, v_a, x_c, v_c [, y (contact point)]; inputs: drive, z, z'
    if series_C is None:
        A = np.array([[0, 1, 0, 0],
                      [-(K + kb) / Ma, -(C + cb) / Ma, kb / Ma, cb / Ma],
                      [0, 0, 0, 1],
                      [kb / Mc, cb / Mc, -(kb + kl) / Mc, -(cb + cl) / Mc]])
        B = np.array([[0, 0, 0], [0, K / Ma, C / Ma], [0, 0, 0], [1 / Mc, 0, 0]])
        # tyre force on the axle: -(K (x_a - z) + C (v_a - z'))
        Ct = np.array([[-K, -C, 0, 0]])
        Dt = np.array([[0, K, C]])
    else:
        c2 = series_C
        s = C + c2
        # y' = (K (x_a - y) + C v_a + c2 z') / (C + c2); force on the axle -c2 (y' - z')
        A = np.array([[0, 1, 0, 0, 0],
                      [0, -cb / Ma, kb / Ma, cb / Ma, 0],
                      [0, 0, 0, 1, 0],
                      [kb / Mc, cb / Mc, -(kb + kl) / Mc, -(cb + cl) / Mc, 0],
                      [K / s, C / s, 0, 0, -K / s]], dtype=float)
        Ct = -c2 * np.array([[K / s, C / s, 0, 0, -K / s]])
        Dt = -c2 * np.array([[0, 0, c2 / s - 1]])
        A[1, :] += Ct[0] / Ma
        A[1, 0] -= kb / Ma
        B = np.zeros((5, 3))
        B[3, 0] = 1 / Mc
        B[4, 2] = c2 / s
        B[1, :] += Dt[0] / Ma
    nx = A.shape[0]
    out_C = np.vstack([np.eye(nx)[:4], Ct])
    out_D = np.vstack([np.zeros((4, 3)), Dt])
    u = np.column_stack([drive, z, zd])
    _, y, _ = signal.lsim(signal.StateSpace(A, B, out_C, out_D), u, t)
    x_a = y[:, 0]
    scale = axle_rms_m / np.std(x_a[lead:]) if method == "random" or not road else 1.0
    if road and method == "random":
        # the road's part must not scale with the drive: solve the drive alone to find the drive's scale
        _, y0, _ = signal.lsim(signal.StateSpace(A, B, out_C, out_D), u * [1, 0, 0], t)
        scale_d = axle_rms_m / np.std(y0[lead:, 0])
        _, y, _ = signal.lsim(signal.StateSpace(A, B, out_C, out_D), u * [scale_d, 1, 1], t)
        scale = 1.0
    elif method != "random":
        _, y0, _ = signal.lsim(signal.StateSpace(A, B, out_C, out_D), u * [1, 0, 0], t)
        scale_d = axle_rms_m / np.std(y0[lead:, 0])
        _, y, _ = signal.lsim(signal.StateSpace(A, B, out_C, out_D), u * [scale_d, 1, 1], t)
        scale = 1.0
    y = y * scale if scale != 1.0 else y
    x_a, v_a, x_c, v_c, f_t = y[lead:, 0], y[lead:, 1], y[lead:, 2], y[lead:, 3], y[lead:, 4]
    f_b = kb * (x_c - x_a) + cb * (v_c - v_a)
    a = (f_t + f_b) / Ma
    m = a.size
    ua = accel_noise * _in_band_rms(a, fs, band_Hz)
    ub = beam_noise * _in_band_rms(f_b, fs, band_Hz)
    df = pd.DataFrame({"time_s": np.arange(m) / fs})
    df["accel_left_m_s2"] = a + _white(rng, m, ua, fs, band_Hz)
    df["accel_right_m_s2"] = a + _white(rng, m, ua, fs, band_Hz)
    for i, sp in enumerate(SPLIT, start=1):
        df[f"load_beam_{i}_N"] = sp * f_b + _white(rng, m, ub / 2, fs, band_Hz)
    return df


def dwell_decay(K, C, mass_kg=1866.0, *, axle_mass_kg=600.0, dwell_s=5.0, decay_s=8.0, amplitude_m=2e-3,
                sample_rate_Hz=256.0, accel_noise=0.01, beam_noise_N=5.0, seed=0) -> pd.DataFrame:
    """A free-vibration record as a lab makes one: ``dwell_s`` of steady sine drive at the damped
    natural frequency (constant amplitude), then the release and ``decay_s`` of free decay, in closed
    form (the mass ``mass_kg`` on K and C: ``x = e^{−στ}(x_r cos ω_d τ + (v_r + σ x_r)/ω_d sin ω_d τ)``
    from the release's position and velocity). The record is ``dwell_s + decay_s`` long (8 s of decay:
    shorter than the stepped sine's 10 s). Channels as raw format v1, ``M_a a = f_t + Σ beams`` with
    ``f_t = −(K x + C v)``; noise ``accel_noise`` m/s² and ``beam_noise_N`` N r.m.s. per channel."""
    rng = np.random.default_rng(seed)
    fs = sample_rate_Hz
    t = np.arange(int((dwell_s + decay_s) * fs)) / fs
    s = C / (2 * mass_kg)
    wd = np.sqrt(K / mass_kg - s**2)
    ph = rng.uniform(0, 2 * np.pi)
    x = amplitude_m * np.cos(wd * t + ph)
    v = -amplitude_m * wd * np.sin(wd * t + ph)
    xr, vr = amplitude_m * np.cos(wd * dwell_s + ph), -amplitude_m * wd * np.sin(wd * dwell_s + ph)
    tau = t - dwell_s
    after = tau >= 0
    e = np.exp(-s * tau[after])
    b = (vr + s * xr) / wd
    x[after] = e * (xr * np.cos(wd * tau[after]) + b * np.sin(wd * tau[after]))
    v[after] = e * ((-s * xr + wd * b) * np.cos(wd * tau[after]) + (-s * b - wd * xr) * np.sin(wd * tau[after]))
    f_t = -(K * x + C * v)
    a = np.where(after, f_t / mass_kg, -(wd**2) * x)  # the dwell: steady sine, whatever drives it
    beams = axle_mass_kg * a - f_t
    df = pd.DataFrame({"time_s": t})
    df["accel_left_m_s2"] = a + rng.normal(0, accel_noise, t.size)
    df["accel_right_m_s2"] = a + rng.normal(0, accel_noise, t.size)
    for i, sp in enumerate(SPLIT, start=1):
        df[f"load_beam_{i}_N"] = sp * beams + rng.normal(0, beam_noise_N, t.size)
    return df
