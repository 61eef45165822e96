"""Four-wheel stand recordings of a known linear system, independent of tyrelab's models (issue 43).

A 4-input, 2-output system whose every FRF is a sum of two single-degree-of-freedom
transmissibilities with the modes 1.6 Hz ζ 0.25 and 2.9 Hz ζ 0.12 (the issue's check), gains
fixed by a seed. The inputs are band-limited (0.5-12 Hz, flat acceleration spectrum: thesis
§2.2) Gaussian noise: independent, partly correlated (a common part), the thesis' own
correlated case (the measured wheel independent, the other three like a track: each rear
wheel its front delayed) or pure road input (every wheel on the road: rear = delayed front).
Outputs are computed exactly in the frequency domain (one FFT of the whole, periodic record),
with white sensor noise of ``noise`` times each output's rms added.
"""

from __future__ import annotations

import numpy as np

#: The system's modes: (natural frequency Hz, damping ratio).
MODES = ((1.6, 0.25), (2.9, 0.12))
CASES = ("independent", "correlated", "thesis", "road")


def true_frf(frequency_Hz, n_outputs: int = 2, n_inputs: int = 4, seed: int = 5) -> np.ndarray:
    """The system's FRFs, shape (F, outputs, inputs): output acceleration per input acceleration."""
    rng = np.random.default_rng(seed)
    g = rng.uniform(0.3, 1.0, (len(MODES), n_outputs, n_inputs)) * rng.choice([-1, 1], (len(MODES), n_outputs, n_inputs))
    s = 2j * np.pi * np.asarray(frequency_Hz, dtype=float)[:, None, None]
    out = np.zeros((s.shape[0], n_outputs, n_inputs), complex)
    for r, (fn, z) in enumerate(MODES):
        wn = 2 * np.pi * fn
        out += g[r][None] * (wn ** 2 + 2 * z * wn * s) / (s ** 2 + 2 * z * wn * s + wn ** 2)
    return out


def _band_noise(rng, n: int, fs: float, lo: float = 0.5, hi: float = 12.0) -> np.ndarray:
    x = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, 1 / fs)
    x[(f < lo) | (f > hi)] = 0
    return np.fft.irfft(x, n)


def stand_recording(case: str, fs_Hz: float = 50.0, duration_s: float = 1200.0, noise: float = 0.05, seed: int = 0,
                    delay_s: float = 0.6):
    """``(inputs (4, n) m/s², outputs (2, n), fs_Hz)`` of one case of :data:`CASES`."""
    rng = np.random.default_rng(seed)
    n = int(duration_s * fs_Hz)
    k = int(round(delay_s * fs_Hz))
    if case == "independent":
        x = np.vstack([_band_noise(rng, n, fs_Hz) for _ in range(4)])
    elif case == "correlated":
        c = _band_noise(rng, n, fs_Hz)
        x = np.vstack([0.8 * c + 0.6 * _band_noise(rng, n, fs_Hz) for _ in range(4)])
    elif case in ("thesis", "road"):
        c = _band_noise(rng, n, fs_Hz)
        left, right = c + 0.5 * _band_noise(rng, n, fs_Hz), c + 0.5 * _band_noise(rng, n, fs_Hz)
        x = np.vstack([left, right, np.roll(left, k), np.roll(right, k)])
        if case == "thesis":  # the front-left wheel excited on its own, the others as on a track
            x[0] = _band_noise(rng, n, fs_Hz)
    else:
        raise ValueError(f"case must be one of {CASES}, got {case!r}")
    f = np.fft.rfftfreq(n, 1 / fs_Hz)
    y = np.fft.irfft(np.einsum("fpq,qf->pf", true_frf(f), np.fft.rfft(x, axis=1)), n, axis=1)
    y += noise * y.std(axis=1, keepdims=True) * rng.standard_normal(y.shape)
    return x, y, fs_Hz


def heights(accelerations, fs_Hz: float) -> np.ndarray:
    """Ground heights (m) whose second derivative is ``accelerations`` (band-limited, periodic)."""
    a = np.atleast_2d(accelerations)
    n = a.shape[1]
    f = np.fft.rfftfreq(n, 1 / fs_Hz)
    spec = np.fft.rfft(a, axis=1)
    w2 = (2 * np.pi * f) ** 2
    spec = np.where(w2 > 0, -spec / np.where(w2 > 0, w2, 1.0), 0.0)
    return np.fft.irfft(spec, n, axis=1)
