"""Measures of simulation accuracy used in thesis §6.4 and §7.4.

Each simulated ("predicted") acceleration record is compared with a "measured"
record by: rms level, square root of the PSD peak height, peak (mode) frequency,
half-power width divided by peak frequency, and the envelope (complex
demodulation) compared by the maximum normalised cross-correlation
``R = Rxy_max / sqrt(Rxx_max Ryy_max)`` and the normalised rms envelope error.
Ratio errors (predicted / measured) are summarised by mean, standard deviation and
the probability, under a normal model N(mean, sd), of lying within ±10 % and ±30 %.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pandas as pd
from scipy import signal, stats

from ... import _validate
from ..._validate import positive

__all__ = [
    "rms",
    "acceleration_psd",
    "band_rms",
    "spectral_peak",
    "spectral_peaks",
    "envelope",
    "envelope_similarity",
    "envelope_error",
    "compare_records",
    "ratio_error_statistics",
    "accuracy_table",
]


def rms(x) -> float:
    """Root mean square of the mean-removed record (same unit as ``x``).

    See Also
    --------
    band_rms : the r.m.s. of a band of a PSD.

    Examples
    --------
    >>> round(rms(np.sin(2 * np.pi * np.arange(1000) / 100) + 5.0), 4)     # a sine's 1/√2; the mean removed
    0.7071
    """
    _validate.finite_array("x", x, min_samples=0)
    a = np.asarray(x, dtype=float)
    return float(np.sqrt(np.mean((a - a.mean()) ** 2)))


def acceleration_psd(x, fs_Hz: float, bandwidth_Hz: float = 0.1) -> tuple[np.ndarray, np.ndarray]:
    """One-sided Welch PSD with a given analysis bandwidth (thesis §7.4: 0.1 Hz).

    Hann window, 50 % overlap, segment length ``fs/bandwidth`` samples (shortened to
    the record if the record is shorter).

    Parameters
    ----------
    x : array_like
        Record, e.g. acceleration in m/s^2.
    fs_Hz : float
        Sampling rate, Hz.
    bandwidth_Hz : float
        Frequency resolution, Hz.

    Returns
    -------
    f_Hz, psd : ndarray
        Frequencies (Hz) and PSD (unit^2/Hz).

    See Also
    --------
    band_rms : the r.m.s. of a band of it.
    spectral_peak : its dominant peak.

    Examples
    --------
    >>> fs = 100.0; t = np.arange(0, 60, 1 / fs)
    >>> x = np.sin(2 * np.pi * 2.0 * t)                  # 2 Hz, amplitude 1 m/s²
    >>> f, p = acceleration_psd(x, fs)
    >>> round(float(f[1]), 3), round(float(f[np.argmax(p)]), 2)       # 0.1 Hz resolution, the peak at 2 Hz
    (0.1, 2.0)
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    a = np.asarray(x, dtype=float)
    nperseg = min(a.size, int(round(fs_Hz / bandwidth_Hz)))
    return signal.welch(a, fs=fs_Hz, window="hann", nperseg=nperseg, noverlap=nperseg // 2, detrend="constant")


def band_rms(f_Hz, psd, f_low_Hz: float, f_high_Hz: float) -> float:
    """rms from a PSD between two frequencies (thesis §7.4: 0.5-10 Hz).

    See Also
    --------
    acceleration_psd : the PSD it integrates.
    rms : the r.m.s. of the record.

    Examples
    --------
    >>> fs = 100.0; t = np.arange(0, 60, 1 / fs)
    >>> x = np.sin(2 * np.pi * 2.0 * t)                  # 2 Hz, amplitude 1 m/s²
    >>> round(band_rms(*acceleration_psd(x, fs), 0.5, 10.0), 3)
    0.707
    """
    _validate.band("f_low_Hz", (f_low_Hz, f_high_Hz))
    f = np.asarray(f_Hz)
    p = np.asarray(psd)
    m = (f >= f_low_Hz) & (f <= f_high_Hz)
    if m.sum() < 2:
        return math.nan
    return float(math.sqrt(np.trapezoid(p[m], f[m])))


def spectral_peak(f_Hz, psd, f_low_Hz: float = 0.5, f_high_Hz: float = 10.0) -> dict:
    """Dominant spectral peak: frequency, height and half-power width (thesis §6.4.2).

    The half-power points are where the PSD first falls below half the peak on
    either side (linear interpolation between bins).

    Returns
    -------
    dict
        ``peak_frequency_Hz``, ``peak_height`` (PSD units), ``sqrt_peak_height``,
        ``half_power_width_Hz``, ``width_over_frequency`` (≈ 2 ζ for a lightly damped
        single mode).

    See Also
    --------
    spectral_peaks : several peaks.
    record_metrics : rms and this peak of a record.

    Examples
    --------
    >>> fs = 100.0; t = np.arange(0, 60, 1 / fs)
    >>> x = np.sin(2 * np.pi * 2.0 * t)                  # 2 Hz, amplitude 1 m/s²
    >>> pk = spectral_peak(*acceleration_psd(x, fs))
    >>> round(pk["peak_frequency_Hz"], 2), bool(pk["half_power_width_Hz"] < 0.3)
    (2.0, True)
    """
    _validate.band("f_low_Hz", (f_low_Hz, f_high_Hz))
    f = np.asarray(f_Hz, dtype=float)
    p = np.asarray(psd, dtype=float)
    idx = np.flatnonzero((f >= f_low_Hz) & (f <= f_high_Hz))
    i = int(idx[np.argmax(p[idx])])
    half = p[i] / 2.0
    j = i
    while j > 0 and p[j] > half:
        j -= 1
    lo = f[j] + (half - p[j]) * (f[j + 1] - f[j]) / (p[j + 1] - p[j]) if p[j] <= half else f[j]
    k = i
    while k < p.size - 1 and p[k] > half:
        k += 1
    hi = f[k - 1] + (p[k - 1] - half) * (f[k] - f[k - 1]) / (p[k - 1] - p[k]) if p[k] <= half else f[k]
    # refine the peak frequency by a parabola through the three bins around the maximum
    fp = f[i]
    if 0 < i < p.size - 1:
        y0, y1, y2 = np.log(p[i - 1 : i + 2] + 1e-300)
        den = y0 - 2 * y1 + y2
        if den < 0:
            fp = f[i] + 0.5 * (y0 - y2) / den * (f[1] - f[0])
    width = float(hi - lo)
    return {
        "peak_frequency_Hz": float(fp),
        "peak_height": float(p[i]),
        "sqrt_peak_height": float(math.sqrt(p[i])),
        "half_power_width_Hz": width,
        "width_over_frequency": width / float(fp),
    }


def spectral_peaks(
    f_Hz, psd, n_peaks: int = 2, f_low_Hz: float = 0.8, f_high_Hz: float = 6.0, min_separation_Hz: float = 0.25
) -> list[float]:
    """Frequencies of the ``n_peaks`` highest local maxima, ascending (thesis §7.4.2).

    Parameters
    ----------
    f_Hz, psd : array_like
        Spectrum (e.g. 0.1 Hz bandwidth).
    n_peaks : int
        How many peaks to return (fewer if fewer exist; padded with NaN).
    min_separation_Hz : float
        Minimum distance between reported peaks.

    See Also
    --------
    spectral_peak : the dominant peak with its width.

    Examples
    --------
    >>> fs = 100.0; t = np.arange(0, 60, 1 / fs)
    >>> x = np.sin(2 * np.pi * 1.5 * t) + 0.5 * np.sin(2 * np.pi * 3.0 * t)
    >>> [round(v, 2) for v in spectral_peaks(*acceleration_psd(x, fs))]
    [1.5, 3.0]
    """
    n_peaks = _validate.positive_int("n_peaks", n_peaks)
    _validate.band("f_low_Hz", (f_low_Hz, f_high_Hz))
    min_separation_Hz = _validate.non_negative("min_separation_Hz", min_separation_Hz)
    f = np.asarray(f_Hz, dtype=float)
    p = np.asarray(psd, dtype=float)
    m = (f >= f_low_Hz) & (f <= f_high_Hz)
    df = f[1] - f[0]
    pk, _ = signal.find_peaks(p[m], distance=max(1, int(round(min_separation_Hz / df))))
    order = pk[np.argsort(p[m][pk])[::-1]][:n_peaks]
    out = sorted(float(f[m][k]) for k in order)
    return out + [math.nan] * (n_peaks - len(out))


def envelope(x, fs_Hz: float, centre_Hz: float, cutoff_Hz: float = 0.5) -> np.ndarray:
    """Amplitude envelope by complex demodulation (thesis §6.4.3).

    The record is shifted by ``exp(-j 2 pi f0 t)``, low-pass filtered (4th-order
    Butterworth, zero phase) and the envelope is twice the modulus.

    Parameters
    ----------
    x : array_like
        Record.
    fs_Hz : float
        Sampling rate, Hz.
    centre_Hz : float
        Demodulation frequency f0 (the dominant spectral peak), Hz.
    cutoff_Hz : float
        Low-pass cutoff of the demodulated signal, Hz.

    Returns
    -------
    ndarray
        Envelope, same unit and length as ``x``. A sine of amplitude A gives A.

    See Also
    --------
    envelope_similarity : how alike two envelopes are.
    envelope_error : their rms difference.

    Examples
    --------
    >>> fs = 100.0; t = np.arange(0, 60, 1 / fs)
    >>> x = np.sin(2 * np.pi * 2.0 * t)                  # 2 Hz, amplitude 1 m/s²
    >>> e = envelope(2.0 * x, fs, centre_Hz=2.0)
    >>> round(float(np.median(e)), 3)                   # a sine of amplitude A gives A
    2.0
    """
    cutoff_Hz = positive("cutoff_Hz", cutoff_Hz)
    fs_Hz = positive("fs_Hz", fs_Hz)
    a = np.asarray(x, dtype=float)
    a = a - a.mean()
    t = np.arange(a.size) / fs_Hz
    z = a * np.exp(-2j * math.pi * centre_Hz * t)
    sos = _lowpass_sos(float(cutoff_Hz), float(fs_Hz)).copy()  # (scipy's sosfilt wants a writable array)
    zr = signal.sosfiltfilt(sos, z.real)
    zi = signal.sosfiltfilt(sos, z.imag)
    return 2.0 * np.hypot(zr, zi)


@functools.lru_cache(maxsize=16)
def _lowpass_sos(cutoff_Hz: float, fs_Hz: float) -> np.ndarray:
    """4th-order Butterworth low-pass of :func:`envelope` (second-order sections, read-only; kept:
    designing it cost about as much as filtering a record)."""
    sos = signal.butter(4, cutoff_Hz, fs=fs_Hz, output="sos")
    sos.flags.writeable = False
    return sos


def envelope_similarity(env_x, env_y, fs_Hz: float, max_lag_s: float = 1.0) -> float:
    """Maximum normalised cross-correlation of two envelopes (thesis §6.4.3).

    ``R = Rxy(tau)_max / sqrt(Rxx(tau)_max Ryy(tau)_max)`` over lags
    ``|tau| <= max_lag_s``, envelopes mean-removed (so independent envelopes give ≈ 0
    and identical ones 1, as the thesis describes).

    See Also
    --------
    envelope : the envelopes compared.
    envelope_error : their rms difference.

    Examples
    --------
    >>> fs = 50.0; t = np.arange(0, 20, 1 / fs)
    >>> e = 1 + 0.5 * np.sin(2 * np.pi * 0.2 * t)
    >>> round(envelope_similarity(e, e, fs), 6), round(envelope_similarity(e, np.roll(e, 10), fs), 2)  # a lag of 0.2 s
    (1.0, 1.0)
    >>> round(envelope_similarity(e, 1 + 0.5 * np.sin(2 * np.pi * 0.45 * t), fs), 1) < 0.5      # another envelope
    True
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    x = np.asarray(env_x, dtype=float)
    y = np.asarray(env_y, dtype=float)
    n = min(x.size, y.size)
    x = x[:n] - x[:n].mean()
    y = y[:n] - y[:n].mean()
    c = signal.correlate(y, x, mode="full", method="fft")
    lags = np.arange(-n + 1, n)
    m = np.abs(lags) <= int(round(max_lag_s * fs_Hz))
    den = math.sqrt(float(np.dot(x, x)) * float(np.dot(y, y)))
    return float(c[m].max() / den) if den > 0 else math.nan


def envelope_error(env_predicted, env_measured) -> float:
    """Normalised rms envelope error: rms(pred - meas) / rms(meas) (thesis §6.4.3, Fig. 60).

    See Also
    --------
    envelope : the envelopes compared.
    envelope_similarity : their correlation.

    Examples
    --------
    >>> round(envelope_error([1.1, 2.2, 3.3], [1.0, 2.0, 3.0]), 6)
    0.1
    """
    _validate.finite_array("env_predicted", env_predicted)
    _validate.finite_array("env_measured", env_measured)
    p = np.asarray(env_predicted, dtype=float)
    m = np.asarray(env_measured, dtype=float)
    n = min(p.size, m.size)
    return float(np.sqrt(np.mean((p[:n] - m[:n]) ** 2)) / np.sqrt(np.mean(m[:n] ** 2)))


def record_metrics(x, fs_Hz: float, bandwidth_Hz: float = 0.1, f_low_Hz: float = 0.5, f_high_Hz: float = 10.0) -> dict:
    """rms and dominant-peak measures of one acceleration record (thesis §6.4)."""
    fs_Hz = positive("fs_Hz", fs_Hz)
    f, p = acceleration_psd(x, fs_Hz, bandwidth_Hz)
    return {"rms": rms(x), **spectral_peak(f, p, f_low_Hz, f_high_Hz)}


def compare_records(
    predicted, measured, fs_Hz: float, bandwidth_Hz: float = 0.1, envelope_cutoff_Hz: float = 0.5
) -> dict:
    """All §6.4 accuracy measures of one predicted record against a measured one.

    Returns
    -------
    dict
        ``predicted_*`` and ``measured_*`` rms/peak measures; ratio errors
        ``ratio_rms``, ``ratio_sqrt_peak_height``, ``ratio_peak_frequency``,
        ``ratio_width_over_frequency``; ``envelope_correlation`` and
        ``envelope_error``.

    See Also
    --------
    record_metrics : the measures of one record.
    accuracy_table : the statistics over many runs.

    Examples
    --------
    >>> fs = 100.0; t = np.arange(0, 60, 1 / fs)
    >>> x = np.sin(2 * np.pi * 2.0 * t)                  # 2 Hz, amplitude 1 m/s²
    >>> c = compare_records(0.9 * x, x, fs)
    >>> round(c["ratio_rms"], 6), round(c["ratio_peak_frequency"], 6), round(c["envelope_correlation"], 3)
    (0.9, 1.0, 1.0)
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    bandwidth_Hz = positive("bandwidth_Hz", bandwidth_Hz)
    envelope_cutoff_Hz = positive("envelope_cutoff_Hz", envelope_cutoff_Hz)
    mp = record_metrics(predicted, fs_Hz, bandwidth_Hz)
    mm = record_metrics(measured, fs_Hz, bandwidth_Hz)
    env_p = envelope(predicted, fs_Hz, mp["peak_frequency_Hz"], envelope_cutoff_Hz)
    env_m = envelope(measured, fs_Hz, mm["peak_frequency_Hz"], envelope_cutoff_Hz)
    out = {f"predicted_{k}": v for k, v in mp.items()}
    out.update({f"measured_{k}": v for k, v in mm.items()})
    for q in ("rms", "sqrt_peak_height", "peak_frequency_Hz", "width_over_frequency"):
        out[f"ratio_{q.removesuffix('_Hz')}"] = mp[q] / mm[q]
    out["envelope_correlation"] = envelope_similarity(env_p, env_m, fs_Hz)
    out["envelope_error"] = envelope_error(env_p, env_m)
    return out


def ratio_error_statistics(ratios, tolerances=(0.1, 0.3)) -> dict:
    """Mean, standard deviation and normal-model probabilities of ratio errors.

    The thesis (§6.4.1, §7.4, §8.2) fits N(mean, sd) to the ratio errors
    r = predicted/measured and reads the probability that a prediction lies within
    ±tol: ``P(|r - 1| < tol) = Phi((1 + tol - mean)/sd) - Phi((1 - tol - mean)/sd)``.

    Parameters
    ----------
    ratios : array_like
        Ratio errors (dimensionless); NaN ignored.
    tolerances : tuple of float
        Fractional tolerances, default ±10 % and ±30 %.

    Returns
    -------
    dict
        ``n``, ``mean``, ``sd`` (ddof=1) and ``p_within_<pct>`` per tolerance.

    See Also
    --------
    accuracy_table : these statistics per group of runs.

    Examples
    --------
    >>> s = ratio_error_statistics([0.9, 1.0, 1.1])
    >>> round(s["mean"], 3), round(s["sd"], 3), round(s["p_within_10"], 3)
    (1.0, 0.1, 0.683)
    """
    _validate.positive_array("tolerances", tolerances)
    r = np.asarray(ratios, dtype=float)
    r = r[np.isfinite(r)]
    out: dict = {"n": int(r.size)}
    mean = float(r.mean()) if r.size else math.nan
    sd = float(r.std(ddof=1)) if r.size > 1 else (0.0 if r.size else math.nan)
    out.update(mean=mean, sd=sd)
    for tol in tolerances:
        key = f"p_within_{round(tol * 100)}"
        if not r.size:
            out[key] = math.nan
        elif sd > 0:
            out[key] = float(stats.norm.cdf((1 + tol - mean) / sd) - stats.norm.cdf((1 - tol - mean) / sd))
        else:
            out[key] = float(abs(mean - 1) < tol)
    return out


#: Rows of Tables XIII/XIV: (quantity, statistic, source column, kind).
_XIII_ROWS = [
    ("rms_acceleration", "ratio_rms"),
    ("sqrt_peak_height", "ratio_sqrt_peak_height"),
    ("peak_frequency", "ratio_peak_frequency"),
    ("half_power_width_over_frequency", "ratio_width_over_frequency"),
]


def _sample_sd(values: np.ndarray) -> float:
    """Sample standard deviation (ddof=1); NaN for fewer than two values (undefined; numpy would warn)."""
    return float(np.std(values, ddof=1)) if values.size > 1 else math.nan


def accuracy_table(comparisons: pd.DataFrame, by: str = "characteristics") -> pd.DataFrame:
    """Tables XIII/XIV layout from per-run comparisons (thesis §6.4).

    Parameters
    ----------
    comparisons : DataFrame
        One row per run with a ``by`` column (e.g. ``rolling``/``stationary``) and the
        columns of :func:`compare_records`. Filter the runs (e.g. drop 5 and 7.5 km/h)
        before calling.
    by : str
        Column whose values become the table's columns.

    Returns
    -------
    DataFrame
        Long form: ``quantity, statistic, <value of by>...`` with statistics
        ``mean_ratio_error, sd_ratio_error, p_within_10, p_within_30`` for the four
        ratio quantities, and ``mean, sd`` of ``envelope_correlation`` and
        ``envelope_error`` (the sd, ddof=1, of a group of one comparison is NaN: undefined).

    See Also
    --------
    compare_records : the per-run columns it reads.
    ratio_error_statistics : the statistics of each column.

    Examples
    --------
    >>> fs = 100.0; t = np.arange(0, 60, 1 / fs)
    >>> x = np.sin(2 * np.pi * 2.0 * t)                  # 2 Hz, amplitude 1 m/s²
    >>> rows = [{"characteristics": "rolling", **compare_records(k * x, x, fs)} for k in (0.9, 1.0, 1.1)]
    >>> t = accuracy_table(pd.DataFrame(rows)).set_index(["quantity", "statistic"])
    >>> round(float(t.loc[("rms_acceleration", "mean_ratio_error"), "rolling"]), 6), round(float(t.loc[("rms_acceleration", "sd_ratio_error"), "rolling"]), 6)
    (1.0, 0.1)
    """
    _validate.frame("comparisons", comparisons, [by])
    groups = {k: g for k, g in comparisons.groupby(by, sort=False)}
    rows = []
    for quantity, col in _XIII_ROWS:
        st = {k: ratio_error_statistics(g[col]) for k, g in groups.items()}
        for stat, key in (
            ("mean_ratio_error", "mean"),
            ("sd_ratio_error", "sd"),
            ("p_within_10", "p_within_10"),
            ("p_within_30", "p_within_30"),
        ):
            rows.append({"quantity": quantity, "statistic": stat, **{k: v[key] for k, v in st.items()}})
    for quantity in ("envelope_correlation", "envelope_error"):
        for stat, fn in (("mean", np.mean), ("sd", _sample_sd)):
            rows.append(
                {"quantity": quantity, "statistic": stat, **{k: float(fn(g[quantity].to_numpy(float))) for k, g in groups.items()}}
            )
    return pd.DataFrame(rows)
