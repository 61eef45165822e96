"""ISO 2631-1:1997 whole-body vibration evaluation of simulated accelerations.

Frequency weightings W_k (vertical) and W_d (horizontal) are built from their analog
definitions (ISO 2631-1 Annex A; constants in ``/work/shared/field-notes.md``):
band limiting (2nd-order Butterworth high-pass f1, low-pass f2), acceleration-velocity
transition ``(1 + s/w3)/(1 + s/(Q4 w4) + s^2/w4^2)`` and, for W_k, the upward step
``(1 + s/(Q5 w5) + s^2/w5^2)/(1 + s/(Q6 w6) + s^2/w6^2) (w5/w6)^2``. They are applied in
the frequency domain (FFT of the record times W(j w), inverse FFT). Exposure limits are
those of EU Directive 2002/44/EC. The thesis (§1.1) motivates the work by these
operator-exposure concerns; it does not compute them itself.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from .._validate import positive

__all__ = [
    "WEIGHTINGS",
    "weighting_response",
    "weighting_ba",
    "weighted_signal",
    "weighted_rms",
    "vibration_dose_value",
    "crest_factor",
    "daily_exposure_a8",
    "evaluate",
    "EU_ACTION_A8_M_S2",
    "EU_LIMIT_A8_M_S2",
    "EU_ACTION_VDV",
    "EU_LIMIT_VDV",
]

#: Analog weighting constants, ISO 2631-1:1997 Table A.2 (frequencies in Hz).
WEIGHTINGS: dict[str, dict[str, float | None]] = {
    "Wk": dict(f1=0.4, f2=100.0, f3=12.5, f4=12.5, Q4=0.63, f5=2.37, Q5=0.91, f6=3.35, Q6=0.91),
    "Wd": dict(f1=0.4, f2=100.0, f3=2.0, f4=2.0, Q4=0.63, f5=None, Q5=None, f6=None, Q6=None),
}

#: EU Directive 2002/44/EC daily exposure values A(8), m/s^2.
EU_ACTION_A8_M_S2 = 0.5
EU_LIMIT_A8_M_S2 = 1.15
#: EU Directive 2002/44/EC vibration dose values, m/s^1.75.
EU_ACTION_VDV = 9.1
EU_LIMIT_VDV = 21.0

#: Multiplying factors k for the seat point (ISO 2631-1 §8.2.3): x, y 1.4; z 1.0.
AXIS_FACTOR = {"x": 1.4, "y": 1.4, "z": 1.0}


def _polys(name: str) -> tuple[np.ndarray, np.ndarray]:
    """Numerator and denominator polynomials in s (highest power first)."""
    c = WEIGHTINGS[name]
    w = {k: 2 * math.pi * v for k, v in c.items() if k.startswith("f") and v is not None}
    q1 = q2 = 1 / math.sqrt(2)
    num = np.array([1.0, 0.0, 0.0])  # high-pass s^2
    den = np.array([1.0, w["f1"] / q1, w["f1"] ** 2])
    num = np.polymul(num, [w["f2"] ** 2])
    den = np.polymul(den, [1.0, w["f2"] / q2, w["f2"] ** 2])
    num = np.polymul(num, [1 / w["f3"], 1.0])
    den = np.polymul(den, [1 / w["f4"] ** 2, 1 / (c["Q4"] * w["f4"]), 1.0])
    if c["f5"] is not None:
        gain = (w["f5"] / w["f6"]) ** 2
        num = np.polymul(num, np.array([1 / w["f5"] ** 2, 1 / (c["Q5"] * w["f5"]), 1.0]) * gain)
        den = np.polymul(den, [1 / w["f6"] ** 2, 1 / (c["Q6"] * w["f6"]), 1.0])
    return num, den


def weighting_response(frequency_Hz, name: str = "Wk") -> np.ndarray:
    """Complex analog frequency response W(j 2 pi f) of an ISO 2631-1 weighting.

    Parameters
    ----------
    frequency_Hz : array_like
        Frequencies in Hz.
    name : {"Wk", "Wd"}
        Weighting: W_k vertical (seated, z), W_d horizontal (x, y).

    Returns
    -------
    ndarray of complex
        Response; ``abs`` gives the weighting factor (ISO 2631-1 Table 3).

    Examples
    --------
    >>> round(float(abs(weighting_response(1.0, "Wk"))), 3)
    0.482
    """
    num, den = _polys(name)
    s = 2j * math.pi * np.asarray(frequency_Hz, dtype=float)
    return np.polyval(num, s) / np.polyval(den, s)


def weighting_ba(name: str, fs_Hz: float) -> tuple[np.ndarray, np.ndarray]:
    """Digital IIR coefficients of a weighting via the bilinear transform.

    Uses :func:`scipy.signal.bilinear` with frequency pre-warping at 4 Hz (the
    band where W_k matters most). For sampling rates much higher than 100 Hz the
    digital filter follows the analog one closely; :func:`weighted_signal` uses the
    exact frequency-domain application instead.

    Returns
    -------
    (b, a) : tuple of ndarray
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    from scipy import signal

    num, den = _polys(name)
    return signal.bilinear(num, den, fs=fs_Hz)


def weighted_signal(acceleration_m_s2, fs_Hz: float, name: str = "Wk") -> np.ndarray:
    """Frequency-weighted acceleration, applying W(j w) in the frequency domain.

    The record is mean-removed, zero-padded to a power of two at least twice its
    length (so the circular convolution does not wrap), multiplied by W at each FFT
    bin and transformed back.

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Acceleration time history, m/s^2, uniformly sampled.
    fs_Hz : float
        Sampling rate, Hz.
    name : {"Wk", "Wd"}

    Returns
    -------
    ndarray
        Weighted acceleration, m/s^2, same length.
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    a = np.asarray(acceleration_m_s2, dtype=float)
    a = a - a.mean()
    n = a.size
    nfft = 1 << int(math.ceil(math.log2(max(2 * n, 2))))
    spec = np.fft.rfft(a, nfft)
    w_re, w_im = _weighting_on_grid(nfft, float(fs_Hz), name)
    # the complex product in real arithmetic: numpy's complex multiply rounds differently with the
    # operands' memory alignment (its SIMD loop), which would make the last bits depend on the
    # allocation history of the process (a worker's earlier tasks); real multiply and add do not
    weighted = np.empty_like(spec)
    weighted.real = spec.real * w_re - spec.imag * w_im
    weighted.imag = spec.real * w_im + spec.imag * w_re
    return np.fft.irfft(weighted, nfft)[:n]


@functools.lru_cache(maxsize=16)
def _weighting_on_grid(nfft: int, fs_Hz: float, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Real and imaginary parts of :func:`weighting_response` at the bins of an ``nfft``-point real
    FFT (read-only; kept, as the records of a study share a few lengths and the polynomial
    evaluation costs more than the FFTs)."""
    w = weighting_response(np.fft.rfftfreq(nfft, 1.0 / fs_Hz), name)
    parts = (np.ascontiguousarray(w.real), np.ascontiguousarray(w.imag))
    for part in parts:
        part.flags.writeable = False
    return parts


def weighted_rms(acceleration_m_s2, fs_Hz: float, name: str = "Wk") -> float:
    """Frequency-weighted rms acceleration a_w, m/s^2 (ISO 2631-1 §6.4.2)."""
    aw = weighted_signal(acceleration_m_s2, fs_Hz, name)
    return float(np.sqrt(np.mean(aw**2)))


def vibration_dose_value(weighted_m_s2, fs_Hz: float) -> float:
    """Fourth-power vibration dose value VDV = (integral a_w^4 dt)^(1/4), m/s^1.75.

    Parameters
    ----------
    weighted_m_s2 : array_like
        *Weighted* acceleration, m/s^2.
    fs_Hz : float
        Sampling rate, Hz.
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    aw = np.asarray(weighted_m_s2, dtype=float)
    return float((np.sum(aw**4) / fs_Hz) ** 0.25)


def crest_factor(weighted_m_s2) -> float:
    """Crest factor: peak |a_w| over rms a_w (ISO 2631-1 §6.2.1; > 9 needs VDV)."""
    aw = np.asarray(weighted_m_s2, dtype=float)
    rms = float(np.sqrt(np.mean(aw**2)))
    return float(np.max(np.abs(aw)) / rms) if rms > 0 else math.nan


def daily_exposure_a8(weighted_rms_m_s2: float, exposure_hours: float = 8.0) -> float:
    """Daily exposure A(8) = a_w sqrt(T/8 h), m/s^2 (Directive 2002/44/EC Annex B)."""
    return float(weighted_rms_m_s2 * math.sqrt(exposure_hours / 8.0))


def evaluate(
    acceleration_m_s2, fs_Hz: float, axis: str = "z", exposure_hours: float = 8.0
) -> dict:
    """ISO 2631-1 summary of one record on one axis.

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Acceleration, m/s^2.
    fs_Hz : float
        Sampling rate, Hz.
    axis : {"z", "x", "y"}
        ``z`` uses W_k with k = 1; ``x``/``y`` use W_d with k = 1.4.
    exposure_hours : float
        Daily exposure duration for A(8) and the VDV extrapolation.

    Returns
    -------
    dict
        ``weighting, axis_factor, unweighted_rms_m_s2, weighted_rms_m_s2`` (k·a_w),
        ``vdv_m_s1_75`` (record), ``vdv_daily_m_s1_75`` (extrapolated to the exposure),
        ``crest_factor, a8_m_s2, exceeds_action, exceeds_limit``.
    """
    name = "Wk" if axis == "z" else "Wd"
    k = AXIS_FACTOR[axis]
    a = np.asarray(acceleration_m_s2, dtype=float)
    aw = k * weighted_signal(a, fs_Hz, name)
    rms_w = float(np.sqrt(np.mean(aw**2)))
    vdv = vibration_dose_value(aw, fs_Hz)
    duration_s = a.size / fs_Hz
    a8 = daily_exposure_a8(rms_w, exposure_hours)
    return {
        "weighting": name,
        "axis_factor": k,
        "unweighted_rms_m_s2": float(np.sqrt(np.mean((a - a.mean()) ** 2))),
        "weighted_rms_m_s2": rms_w,
        "vdv_m_s1_75": vdv,
        "vdv_daily_m_s1_75": float(vdv * (exposure_hours * 3600.0 / duration_s) ** 0.25),
        "crest_factor": crest_factor(aw),
        "a8_m_s2": a8,
        "exceeds_action": bool(a8 > EU_ACTION_A8_M_S2),
        "exceeds_limit": bool(a8 > EU_LIMIT_A8_M_S2),
    }
