"""Recordings of the other rig methods in raw format v1, independent of tyrelab's generator (issue 34).

Each is a closed-form or exactly solved single-mass system with a known tyre, so the K and C
(and series damping) the analysis must recover are known:

* :func:`broadband_recording` — the axle (mass ``M``) on the tyre, driven through the load
  beams by band-limited random force or a linear sweep; the tyre Kelvin–Voigt or Kelvin–Voigt
  in series with a damper; solved in the frequency domain over a periodic record;
* :func:`free_decay_recording` — a mass ``m`` held displaced, then released: ``m x'' = -(K x + C x')``;
* :func:`load_deflection_recording` — one slow cosine load cycle, ``F = K d + C d'``.

The channels: accelerations (upward positive, AC-coupled) and four load beams with
``M a = f_t + Σ beams``, plus noise; ``deflection_m`` for load deflection.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from scipy import fft as sfft
from scipy import signal

SPLIT = np.array([0.26, 0.24, 0.27, 0.23])


def _frame(t, a, beams_total, rng, accel_noise, force_noise, **extra) -> pd.DataFrame:
    df = pd.DataFrame({"time_s": t})
    df["accel_left_m_s2"] = a + rng.normal(0, accel_noise, t.size)
    df["accel_right_m_s2"] = a + rng.normal(0, accel_noise, t.size)
    for i, s in enumerate(SPLIT, start=1):
        df[f"load_beam_{i}_N"] = s * beams_total + rng.normal(0, force_noise / 2, t.size)
    for k, v in extra.items():
        df[k] = v
    return df


def tyre_impedance(omega, K, C, series_C=None):
    """K + jωC, or that in series with a damper ``series_C``."""
    kv = K + 1j * omega * C
    if series_C is None:
        return kv
    d = 1j * omega * series_C
    return kv * d / (kv + d)


def broadband_recording(K: float, C: float, series_C: float | None = None, *, method: str = "random",
                        axle_mass_kg: float = 600.0, sample_rate_Hz: float = 256.0, duration_s: float = 50.0,
                        band_Hz=(1.0, 8.0), force_rms_N: float = 3e3, force_noise_N: float = 30.0,
                        accel_noise_m_s2: float = 0.02, seed: int = 0) -> pd.DataFrame:
    """Axle on the tyre driven through the beams by random force or a linear sweep over ``band_Hz``."""
    rng = np.random.default_rng(seed)
    n = int(duration_s * sample_rate_Hz)
    t = np.arange(n) / sample_rate_Hz
    f = sfft.rfftfreq(n, 1 / sample_rate_Hz)
    w = 2 * np.pi * f
    if method == "random":
        spec = np.where((f >= band_Hz[0]) & (f <= band_Hz[1]), np.exp(1j * rng.uniform(0, 2 * np.pi, f.size)), 0)
        drive = sfft.irfft(spec, n)
    else:
        drive = signal.chirp(t, band_Hz[0], duration_s, band_Hz[1], method="linear")
    drive *= force_rms_N / drive.std()
    S = sfft.rfft(drive)
    Z = tyre_impedance(w, K, C, series_C)
    with np.errstate(divide="ignore", invalid="ignore"):
        X = np.where(w > 0, S / (Z - axle_mass_kg * w**2), 0)
    a = sfft.irfft(-(w**2) * X, n)
    return _frame(t, a, drive, rng, accel_noise_m_s2, force_noise_N)


def free_decay_recording(K: float, C: float, mass_kg: float = 1800.0, *, axle_mass_kg: float = 600.0,
                         x0_m: float = 0.01, hold_s: float = 2.0, duration_s: float = 14.0,
                         sample_rate_Hz: float = 256.0, force_noise_N: float = 20.0,
                         accel_noise_m_s2: float = 0.01, seed: int = 0, decays: bool = True) -> pd.DataFrame:
    """A mass on the tyre held ``x0_m`` up for ``hold_s``, then released (no drive after it).
    ``decays=False``: a drive at the natural frequency keeps going to the end (it never decays)."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(duration_s * sample_rate_Hz)) / sample_rate_Hz
    s = C / (2 * mass_kg)
    wd = np.sqrt(K / mass_kg - s**2)
    tau = np.clip(t - hold_s, 0, None)
    x = x0_m * np.exp(-s * tau) * (np.cos(wd * tau) + s / wd * np.sin(wd * tau))
    if not decays:
        x = x0_m * np.cos(wd * t)
    v = np.gradient(x, t)
    a = np.where(t < hold_s, 0.0, np.gradient(v, t)) if decays else -(wd**2) * x
    f_t = -(K * x + C * v)
    beams = axle_mass_kg * a - f_t
    return _frame(t, a, beams, rng, accel_noise_m_s2, force_noise_N)


def load_deflection_recording(K: float, C: float, *, axle_mass_kg: float = 600.0, deflection_m: float = 0.03,
                              period_s: float = 60.0, sample_rate_Hz: float = 64.0, force_noise_N: float = 30.0,
                              deflection_noise_m: float = 2e-5, seed: int = 0, with_deflection: bool = True
                              ) -> pd.DataFrame:
    """One cosine load cycle of a Kelvin–Voigt tyre: compression ``d`` from 0 to ``deflection_m`` and back."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(period_s * sample_rate_Hz)) / sample_rate_Hz
    w = 2 * np.pi / period_s
    d = deflection_m / 2 * (1 - np.cos(w * t))
    F = K * d + C * deflection_m / 2 * w * np.sin(w * t)  # compression force = tyre force on the axle, upward
    extra = {"deflection_m": d + rng.normal(0, deflection_noise_m, t.size)} if with_deflection else {}
    return _frame(t, np.zeros(t.size), -F, rng, 0.005, force_noise_N, **extra)
