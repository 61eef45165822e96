"""ISO 2631-1:1997 whole-body vibration evaluation of simulated and measured accelerations.

Frequency weightings W_k (vertical) and W_d (horizontal) are built from their analog
definitions (ISO 2631-1 Annex A; constants in ``/work/shared/field-notes.md``):
band limiting (2nd-order Butterworth high-pass f1, low-pass f2), acceleration-velocity
transition ``(1 + s/w3)/(1 + s/(Q4 w4) + s^2/w4^2)`` and, for W_k, the upward step
``(1 + s/(Q5 w5) + s^2/w5^2)/(1 + s/(Q6 w6) + s^2/w6^2) (w5/w6)^2``. They are applied in
the frequency domain (FFT of the record times W(j w), inverse FFT). Exposure limits are
those of EU Directive 2002/44/EC. The thesis (§1.1) motivates the work by these
operator-exposure concerns; it does not compute them itself.

Measured recordings (issue 24) use the same weightings through :class:`ResponseFilter`,
which applies an analog response to a stream of chunks in bounded memory (overlap-save
with the response's impulse response, so an 8 h recording is never held whole), and the
same definitions: running r.m.s. with linear integration over ``tau = 1 s`` and its maximum
MTVV (§6.3.1), VDV (§6.3.2), the crest-factor rule of §6.2.1/§6.3 (:func:`method_check`)
and the vector sum ``a_v`` (§8.2.3 and §7.2.3, :func:`vector_sum`).
"""

from __future__ import annotations

import functools
import inspect
import math

import numpy as np

from ... import _validate
from ..._validate import positive

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
    "AXIS_FACTOR",
    "AXIS_WEIGHTING",
    "RUNNING_RMS_TAU_S",
    "CREST_FACTOR_LIMIT",
    "running_rms",
    "mtvv",
    "vector_sum",
    "method_check",
    "impulse_response",
    "ResponseFilter",
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
#: The frequency weighting of each axis of a seated person (ISO 2631-1 §8.2.3, Table 1; health):
#: W_d horizontal, W_k vertical. The one home (issue 45) the spectral ride, the measured recordings
#: and :func:`evaluate` read.
AXIS_WEIGHTING = {"x": "Wd", "y": "Wd", "z": "Wk"}

#: Integration time of the running r.m.s. (ISO 2631-1 §6.3.1, linear integration), s.
RUNNING_RMS_TAU_S = 1.0
#: Crest factor up to which the basic r.m.s. method is enough (ISO 2631-1 §6.2.1).
CREST_FACTOR_LIMIT = 9.0
#: ISO 2631-1 §6.3.3: the additional methods are needed above these ratios.
MTVV_RATIO_LIMIT = 1.5
VDV_RATIO_LIMIT = 1.75


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

    See Also
    --------
    weighting_ba : a digital filter of it.
    weighted_signal : applies it to a record.

    Examples
    --------
    >>> round(float(abs(weighting_response(1.0, "Wk"))), 3)
    0.482
    """
    _validate.choice("name", name, tuple(WEIGHTINGS))
    _validate.non_negative_array("frequency_Hz", frequency_Hz)
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

    See Also
    --------
    weighting_response : the analog response it approximates.
    weighted_signal : the exact frequency-domain application.

    Examples
    --------
    >>> from scipy import signal
    >>> b, a = weighting_ba("Wk", 100.0)
    >>> _, h = signal.freqz(b, a, worN=[4.0], fs=100.0)
    >>> round(float(abs(h[0])), 3), round(float(abs(weighting_response(4.0, "Wk"))), 3)   # within 0.5 % at 4 Hz
    (0.97, 0.967)
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

    See Also
    --------
    weighting_response : the weighting applied.
    weighted_rms : the r.m.s. of the result.

    Examples
    --------
    >>> fs = 200.0; t = np.arange(0, 60, 1 / fs)
    >>> a = np.sin(2 * np.pi * 4.0 * t)                    # 4 Hz, 1 m/s² peak
    >>> round(float(np.sqrt(np.mean(weighted_signal(a, fs, "Wk") ** 2))), 3)
    0.683
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
    """Frequency-weighted rms acceleration a_w, m/s^2 (ISO 2631-1 §6.4.2).

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Acceleration time history, m/s^2, uniformly sampled.
    fs_Hz : float
        Sampling rate, Hz.
    name : {"Wk", "Wd"}
        The weighting: W_k for vertical (z), W_d for horizontal (x, y) seat vibration.

    Returns
    -------
    float
        a_w, m/s^2 (without the axis factor k).

    See Also
    --------
    weighted_signal : the weighted time history itself.
    vibration_dose_value, crest_factor : the other measures of a weighted signal.
    evaluate : all of them for one record and axis, with A(8).

    Examples
    --------
    A 4 Hz sine of 0.8 m/s^2 peak: a_w = 0.8/√2 × W_k(4 Hz), and ISO 2631-1 Table 3 gives
    W_k(4 Hz) = 0.967 (0.547); a 2 Hz sine of 0.5 m/s^2 under W_d(2 Hz) = 0.890 (0.315):

    >>> t = np.arange(0, 60, 1 / 500)
    >>> round(weighted_rms(0.8 * np.sin(2 * np.pi * 4 * t), 500, "Wk"), 3)
    0.547
    >>> round(weighted_rms(0.5 * np.sin(2 * np.pi * 2 * t), 500, "Wd"), 3)
    0.315
    """
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

    Returns
    -------
    float
        VDV, m/s^1.75.

    See Also
    --------
    weighted_signal : the weighting to apply first.
    crest_factor : whether the r.m.s. alone is enough (ISO 2631-1 §6.3).

    Examples
    --------
    A sine of amplitude A over T seconds: ∫ A⁴ sin⁴ = 3 A⁴ T / 8, so VDV = A (3 T / 8)^(1/4)
    (1.742 m/s^1.75 for 0.8 m/s^2 over 60 s):

    >>> t = np.arange(0, 60, 1 / 500)
    >>> round(vibration_dose_value(0.8 * np.sin(2 * np.pi * 4 * t), 500), 3)
    1.742
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    aw = np.asarray(weighted_m_s2, dtype=float)
    a2 = aw * aw  # aw**4 as (aw²)²: a multiply, not pow() (5x faster); numpy's sum, not BLAS' dot,
    a2 *= a2  # whose rounding changes with the operands' memory alignment
    return float((np.sum(a2) / fs_Hz) ** 0.25)


def crest_factor(weighted_m_s2) -> float:
    """Crest factor: peak |a_w| over rms a_w (ISO 2631-1 §6.2.1; > 9 needs VDV).

    See Also
    --------
    vibration_dose_value : the measure to add when the crest factor is high.

    Examples
    --------
    >>> t = np.arange(0, 10, 1 / 500)
    >>> round(crest_factor(np.sin(2 * np.pi * 4 * t)), 3)  # a sine: √2
    1.414
    """
    _validate.finite_array("weighted_m_s2", weighted_m_s2)
    aw = np.asarray(weighted_m_s2, dtype=float)
    rms = float(np.sqrt(np.mean(aw**2)))
    return float(np.max(np.abs(aw)) / rms) if rms > 0 else math.nan


def daily_exposure_a8(weighted_rms_m_s2: float, exposure_hours: float = 8.0) -> float:
    """Daily exposure A(8) = a_w sqrt(T/8 h), m/s^2 (Directive 2002/44/EC Annex B).

    See Also
    --------
    tyrelab.vehicle.daily_exposure.daily_exposure : a day of several tasks and axes.

    Examples
    --------
    >>> daily_exposure_a8(0.6, 2.0)  # 2 h a day at 0.6 m/s²
    0.3
    """
    _validate.non_negative_array("weighted_rms_m_s2", weighted_rms_m_s2, allow_nan=True)
    exposure_hours = _validate.non_negative("exposure_hours", exposure_hours)
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

    See Also
    --------
    weighted_signal : the weighting applied.
    method_check : whether the r.m.s. method is enough.
    tyrelab.vehicle.daily_exposure.daily_exposure : a day of several tasks.

    Examples
    --------
    >>> fs = 200.0; t = np.arange(0, 60, 1 / fs)
    >>> a = np.sin(2 * np.pi * 4.0 * t)                    # 4 Hz, 1 m/s² peak
    >>> r = evaluate(a, fs, "z")
    >>> round(r["weighted_rms_m_s2"], 3), round(r["a8_m_s2"], 3), r["exceeds_action"]   # 0.7071 × |W_k(4 Hz)| 0.967, less the ends
    (0.683, 0.683, True)
    """
    _validate.choice("axis", axis, tuple(AXIS_FACTOR))
    _validate.non_negative("exposure_hours", exposure_hours)
    name = AXIS_WEIGHTING[axis]
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


def running_rms(weighted_m_s2, fs_Hz: float, tau_s: float = RUNNING_RMS_TAU_S) -> np.ndarray:
    """Running r.m.s. ``a_w(t0) = [1/tau ∫_{t0-tau}^{t0} a_w² dt]^½`` (ISO 2631-1 §6.3.1, Eq. 2).

    Linear integration over the trailing ``tau_s`` (not the exponential form ISO 8041-1 also
    allows); before the record starts the signal counts as zero, as a meter switched on at
    ``t = 0``.

    Parameters
    ----------
    weighted_m_s2 : array_like
        *Weighted* acceleration, m/s².
    fs_Hz : float
        Sampling rate, Hz.
    tau_s : float
        Integration time, s.

    Returns
    -------
    ndarray
        ``a_w(t0)`` at every sample, m/s².

    See Also
    --------
    mtvv : its maximum.

    Examples
    --------
    >>> a = np.ones(400)
    >>> r = running_rms(a, 100.0)
    >>> float(r[49]), float(r[-1])
    (0.7071067811865476, 1.0)
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    tau_s = positive("tau_s", tau_s)
    p = np.asarray(weighted_m_s2, dtype=float) ** 2
    window = max(1, int(round(tau_s * fs_Hz)))
    c = np.concatenate(([0.0], np.cumsum(p)))
    lo = np.maximum(0, np.arange(1, p.size + 1) - window)
    return np.sqrt(np.maximum(c[1:] - c[lo], 0.0) / window)


def mtvv(weighted_m_s2, fs_Hz: float, tau_s: float = RUNNING_RMS_TAU_S) -> float:
    """Maximum transient vibration value, the largest :func:`running_rms`, m/s² (ISO 2631-1 Eq. 3).

    See Also
    --------
    running_rms : the running r.m.s. it maximises.
    method_check : compares it with a_w.

    Examples
    --------
    >>> t = np.arange(6000) / 100.0
    >>> round(mtvv(np.sin(2 * np.pi * 5 * t), 100.0), 6)
    0.707107
    """
    r = running_rms(weighted_m_s2, fs_Hz, tau_s)
    return float(r.max()) if r.size else math.nan


def vector_sum(a_wx_m_s2: float, a_wy_m_s2: float, a_wz_m_s2: float) -> float:
    """ISO 2631-1 vibration total value ``a_v = √((1.4 a_wx)² + (1.4 a_wy)² + a_wz²)``, m/s².

    The seat-point factors k of §8.2.3. This is not the Directive's A(8), which takes the
    highest single axis (:mod:`tyrelab.vehicle.daily_exposure`).

    See Also
    --------
    evaluate : one axis' values.
    tyrelab.vehicle.daily_exposure.daily_exposure : the Directive's A(8), the highest axis.

    Examples
    --------
    >>> round(vector_sum(0.3, 0.2, 0.5), 4)
    0.7105
    """
    for _name, _value in (("a_wx_m_s2", a_wx_m_s2), ("a_wy_m_s2", a_wy_m_s2), ("a_wz_m_s2", a_wz_m_s2)):
        _validate.non_negative_array(_name, _value, allow_nan=True)
    k = AXIS_FACTOR
    return float(math.sqrt((k["x"] * a_wx_m_s2) ** 2 + (k["y"] * a_wy_m_s2) ** 2 + (k["z"] * a_wz_m_s2) ** 2))


def method_check(a_w_m_s2: float, crest: float, mtvv_m_s2: float, vdv_m_s1_75: float, duration_s: float) -> dict:
    """Is the basic r.m.s. method enough? ISO 2631-1 §6.2.1 and §6.3.3.

    The basic method holds up to a crest factor of 9; above it, or when
    ``MTVV / a_w > 1.5`` or ``VDV / (a_w T^¼) > 1.75``, the running r.m.s. (MTVV) and
    the VDV must be reported as well.

    Returns
    -------
    dict
        ``rms_method_sufficient`` (bool), ``mtvv_ratio``, ``vdv_ratio`` and ``reasons``
        (list of str, empty when the basic method is enough).

    See Also
    --------
    evaluate : the values it checks.
    mtvv : the maximum transient vibration value.

    Examples
    --------
    >>> method_check(1.0, 12.0, 1.2, 10.0, 3600.0)["reasons"]
    ['crest factor 12 > 9']
    """
    _validate.non_negative_array("a_w_m_s2", a_w_m_s2, allow_nan=True)
    _validate.non_negative("duration_s", duration_s)
    mtvv_ratio = mtvv_m_s2 / a_w_m_s2 if a_w_m_s2 > 0 else math.nan
    vdv_ratio = vdv_m_s1_75 / (a_w_m_s2 * duration_s**0.25) if a_w_m_s2 > 0 and duration_s > 0 else math.nan
    reasons = []
    if crest > CREST_FACTOR_LIMIT:
        reasons.append(f"crest factor {_validate.compared(crest, '>', CREST_FACTOR_LIMIT)}")
    if mtvv_ratio > MTVV_RATIO_LIMIT:
        reasons.append(f"MTVV/a_w {_validate.compared(mtvv_ratio, '>', MTVV_RATIO_LIMIT)}")
    if vdv_ratio > VDV_RATIO_LIMIT:
        reasons.append(f"VDV/(a_w T^1/4) {_validate.compared(vdv_ratio, '>', VDV_RATIO_LIMIT)}")
    return {"rms_method_sufficient": not reasons, "mtvv_ratio": float(mtvv_ratio), "vdv_ratio": float(vdv_ratio),
            "reasons": reasons}


def impulse_response(response, fs_Hz: float, ring_s: float, lead_s: float = 0.2) -> tuple[np.ndarray, int]:
    """Taps of a linear filter given by its analog frequency response, and their lead.

    The response is sampled on the bins of a real FFT ``ring_s + lead_s`` long (at least 4×
    over), as :func:`weighted_signal` samples it on its record; the inverse FFT is that
    sampled system's impulse response. It keeps the first ``ring_s`` seconds (the causal part,
    by which the response has rung down) and the last ``lead_s`` seconds (the small
    non-causal part that sampling a response that is not band-limited leaves before t = 0).

    Parameters
    ----------
    response : callable
        ``response(frequency_Hz) -> complex ndarray``.
    fs_Hz : float
        Sampling rate, Hz.
    ring_s, lead_s : float
        Kept length after and before t = 0, s.

    Returns
    -------
    taps : ndarray
        ``h[-lead], ..., h[0], ..., h[ring - 1]``.
    lead : int
        Number of taps before t = 0 (the output delay of a plain convolution with ``taps``).

    See Also
    --------
    weighted_signal : applies a weighting on the whole record instead.

    Examples
    --------
    >>> taps, lead = impulse_response(lambda f: np.ones(f.shape, complex), 100.0, ring_s=1.0, lead_s=0.1)
    >>> lead, len(taps), round(float(taps[lead]), 12), round(float(np.abs(np.delete(taps, lead)).max()), 12)
    (10, 110, 1.0, 0.0)
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    n_ring = max(1, int(round(positive("ring_s", ring_s) * fs_Hz)))
    n_lead = int(round(lead_s * fs_Hz))
    nfft = 1 << int(math.ceil(math.log2(4 * (n_ring + n_lead))))
    h = np.fft.irfft(response(np.fft.rfftfreq(nfft, 1.0 / fs_Hz)), nfft)
    return np.concatenate((h[nfft - n_lead:], h[:n_ring])), n_lead


#: numpy >= 2 transforms into a given array (no fresh, page-faulting allocation per block).
_FFT_HAS_OUT = "out" in inspect.signature(np.fft.rfft).parameters


def _aligned_empty(shape, dtype=float) -> np.ndarray:
    """An uninitialised array starting on a 64-byte boundary: the SIMD loops of numpy's
    arithmetic then take the same path (and round the same way) every run."""
    dtype = np.dtype(dtype)
    n = int(np.prod(shape))
    raw = np.empty(n * dtype.itemsize + 64, dtype=np.uint8)
    start = (-raw.ctypes.data) % 64
    return raw[start: start + n * dtype.itemsize].view(dtype).reshape(shape)


def _raise_mmap_threshold(nbytes: int) -> None:
    """Let the C allocator reuse blocks of up to ``nbytes`` (capped at 32 MiB by glibc) instead of
    mapping fresh pages for each: glibc serves a malloc above its mmap threshold (128 KiB at
    first) by a new mapping, and raises the threshold to the size of such a block once one is
    freed (mallopt(3), "dynamic mmap threshold"). The FFTs' scratch (numpy's pocketfft mallocs
    a few MB per 2^18-point transform) otherwise page-faulted anew in every call when nothing
    larger had been freed before: 2 400 faults per block, the filter's transforms 2x slower.
    Elsewhere a no-op (an unused allocation)."""
    block = np.empty(nbytes, dtype=np.uint8)
    del block


def _rfft_into(a: np.ndarray, n: int, out: np.ndarray) -> np.ndarray:
    """``np.fft.rfft(a, n, axis=-1)`` written into ``out``."""
    if _FFT_HAS_OUT:
        return np.fft.rfft(a, n, axis=-1, out=out)
    out[...] = np.fft.rfft(a, n, axis=-1)
    return out


def _irfft_into(a: np.ndarray, n: int, out: np.ndarray) -> np.ndarray:
    """``np.fft.irfft(a, n, axis=-1)`` written into ``out``."""
    if _FFT_HAS_OUT:
        return np.fft.irfft(a, n, axis=-1, out=out)
    out[...] = np.fft.irfft(a, n, axis=-1)
    return out


class ResponseFilter:
    """Streaming linear filtering of one signal by several analog responses (overlap-save).

    Chunks of any length go in; each :meth:`process` returns, per response, the filtered
    samples ready so far, and :meth:`finish` the rest, so the outputs have exactly the
    input's length and equal those of filtering the whole record (zero before and after,
    as :func:`weighted_signal`'s zero padding). :meth:`blocks` and :meth:`final_blocks` hand each
    block's outputs over without copying them (for a caller that consumes them at once). Memory:
    the input block, its spectrum, a product and one output block per response, reused (2^18
    samples or 8× the taps each).

    Parameters
    ----------
    responses : sequence of (taps, lead)
        From :func:`impulse_response`; all with the same ``lead``.

    Examples
    --------
    >>> fs = 200.0
    >>> f = ResponseFilter([impulse_response(lambda f: weighting_response(f, "Wk"), fs, 20.0)])
    >>> x = np.sin(2 * np.pi * 4.0 * np.arange(12000) / fs)
    >>> parts = [f.process(x[:5000])[0], f.process(x[5000:])[0], f.finish()[0]]
    >>> y = np.concatenate(parts)
    >>> y.size, bool(np.allclose(y, weighted_signal(x, fs, "Wk"), atol=1e-4))
    (12000, True)
    """

    def __init__(self, responses):
        leads = {lead for _, lead in responses}
        if len(leads) != 1:
            raise ValueError("responses must share one lead")
        self._lead = leads.pop()
        self._taps = [np.asarray(t, dtype=float) for t, _ in responses]
        n_taps = {t.size for t in self._taps}
        if len(n_taps) != 1:
            raise ValueError("responses must have the same number of taps")
        self._n_taps = n_taps.pop()
        # one power-of-two FFT per block of new samples (at least 2^18 and 8× the taps): a
        # power of two is 1.6× faster than the 5-smooth length next to it, and a block as long
        # as the FFT allows spends the fewest FFTs per sample
        self._nfft = 1 << max(18, int(math.ceil(math.log2(8 * self._n_taps))))
        self._hist = self._n_taps - 1
        self._block = self._nfft - self._hist
        # the input in place: the last n_taps - 1 samples before the block (zeros before the
        # record), then the block as it fills; no concatenation per chunk
        self._buf = _aligned_empty(self._nfft)
        self._buf[: self._hist] = 0.0
        self._fill = self._hist
        self._skip = self._lead  # outputs before t = 0 of the record
        # the transforms' arrays, reused block after block (a fresh 2 MB array costs its page faults,
        # more than the arithmetic on it): the block's spectrum, a product, one output per response
        bins = self._nfft // 2 + 1
        self._spectrum = _aligned_empty(bins, complex)
        self._product = _aligned_empty(bins, complex)
        self._outputs = [_aligned_empty(self._nfft) for _ in self._taps]
        self._spectra: dict[int, list[np.ndarray]] = {}
        _raise_mmap_threshold(32 * self._nfft)

    def _transform(self, n: int, nfft: int) -> list[np.ndarray]:
        """The outputs of the buffer's first ``n`` samples (the history and ``n - hist`` new ones)
        by an ``nfft``-point overlap-save step (views of the filter's arrays when ``nfft`` is the
        block's)."""
        spectra = self._spectra.get(nfft)
        if spectra is None:
            spectra = []
            for t in self._taps:
                s = _aligned_empty(nfft // 2 + 1, complex)
                spectra.append(_rfft_into(t, nfft, s))
            self._spectra[nfft] = spectra
        full = nfft == self._nfft
        bins = nfft // 2 + 1
        b = _rfft_into(self._buf[:n], nfft, self._spectrum if full else _aligned_empty(bins, complex))
        product = self._product if full else _aligned_empty(bins, complex)
        out = []
        for j, s in enumerate(spectra):
            np.multiply(b, s, out=product)
            y = _irfft_into(product, nfft, self._outputs[j] if full else _aligned_empty(nfft))
            out.append(y[self._hist: n])
        if self._skip:
            k = min(self._skip, out[0].size)
            out = [o[k:] for o in out]
            self._skip -= k
        return out

    def _shift(self) -> None:
        if self._hist:
            self._buf[: self._hist] = self._buf[self._fill - self._hist: self._fill]
        self._fill = self._hist

    def blocks(self, chunk):
        """Take the next chunk; yield, per completed block, one array per response (the new
        outputs). The arrays are the filter's: valid until the next block (copy to keep them)."""
        chunk = np.asarray(chunk, dtype=float)
        i = 0
        while i < chunk.size:
            k = min(chunk.size - i, self._nfft - self._fill)
            self._buf[self._fill: self._fill + k] = chunk[i: i + k]
            self._fill += k
            i += k
            if self._fill == self._nfft:
                out = self._transform(self._nfft, self._nfft)
                self._shift()
                yield out

    def final_blocks(self):
        """Yield the remaining outputs (the record continued by zeros for the lead), as :meth:`blocks`."""
        if self._lead:
            yield from self.blocks(np.zeros(self._lead))
            self._lead = 0
        if self._fill > self._hist:
            n = self._fill
            nfft = 1 << int(math.ceil(math.log2(n)))
            out = self._transform(n, nfft)
            self._shift()
            yield out

    def _joined(self, blocks) -> list[np.ndarray]:
        parts = [[o.copy() for o in outputs] for outputs in blocks]
        if not parts:
            return [np.empty(0) for _ in self._taps]
        return [np.concatenate([p[j] for p in parts]) if len(parts) > 1 else parts[0][j] for j in range(len(self._taps))]

    def process(self, chunk) -> list[np.ndarray]:
        """Filter the next chunk; returns one array per response, the outputs ready so far (they lag
        the input by up to a block)."""
        return self._joined(self.blocks(chunk))

    def finish(self) -> list[np.ndarray]:
        """The remaining output samples (the record continued by zeros for the lead)."""
        return self._joined(self.final_blocks())
