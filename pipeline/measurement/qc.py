"""Quality control of one measurement run (thesis §3.5, §3.2.8).

The experimenter "checked frequently" that the conditions stayed constant: the
amplitude was "measured and variation limited to about 20 %" and "the
frequency of vibration of the tyre maintained within 0.1 Hz" (§3.5). A run
that breaks these limits, whose excitation cannot be found, whose force and
acceleration are poorly coherent at the excitation frequency, or whose
channels hit the converter rails, should not be used downstream.

:func:`qc_reasons` returns the list of reasons (empty = run OK). The amplitude
and frequency checks use the envelope and instantaneous frequency of the
synchronous demodulation averaged over ~5 s blocks
(:func:`tyrelab.measurement.apparent_mass.excitation_blocks`).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from .. import _validate
from .._validate import positive_int
from ..units import km_h_to_m_s
from . import apparent_mass as am

__all__ = ["MIN_COHERENCE", "MAX_AMPLITUDE_DRIFT", "MAX_FREQUENCY_DRIFT_HZ", "BLOCK_S", "clipped",
    "interference_frequencies_Hz", "qc_reasons", "plausibility_reasons"]

MIN_COHERENCE = 0.9
MAX_AMPLITUDE_DRIFT = 0.20  # §3.5: "variation limited to about 20%"
MAX_FREQUENCY_DRIFT_HZ = 0.1  # §3.5: "maintained within 0.1 Hz"
BLOCK_S = 5.0


def clipped(x: np.ndarray, full_scale=None, min_run: int = 3, min_count: int = 5):
    """Whether a channel (or each row of a stack of channels) shows clipping.

    Either samples within one LSB of ``+-full_scale`` (16-bit converter), or
    the channel's extreme value repeated at least ``min_run`` times in a row
    and ``min_count`` times in all (flat tops at a rail of unknown range).

    Parameters
    ----------
    x : ndarray, shape (n,) or (channels, n)
        Samples.
    full_scale : float or array of float, optional
        Converter full scale (per channel; NaN = unknown).

    Returns
    -------
    bool, or ndarray of bool of shape (channels,)

    See Also
    --------
    qc_reasons : a clipped channel is one of its reasons.

    Examples
    --------
    >>> s = np.sin(np.linspace(0, 20 * np.pi, 2000))
    >>> clipped(s), clipped(np.clip(1.5 * s, -1.0, 1.0)), clipped(s, full_scale=1.0)   # flat tops; the rail
    (False, True, True)
    """
    min_run, min_count = positive_int("min_run", min_run), positive_int("min_count", min_count)
    x = np.asarray(x)
    if not np.issubdtype(x.dtype, np.floating):
        x = x.astype(float)
    rows = np.atleast_2d(x)
    out = np.zeros(rows.shape[0], dtype=bool)
    if rows.shape[-1] == 0:
        return bool(out[0]) if x.ndim == 1 else out
    if full_scale is not None:
        fsc = np.broadcast_to(np.asarray(full_scale, dtype=float), out.shape)
        lsb = 2 * fsc / 65536
        with np.errstate(invalid="ignore"):
            out |= np.any(np.abs(rows) >= (fsc - 1.5 * lsb)[:, np.newaxis], axis=-1)
    for ext in (rows.max(axis=-1), rows.min(axis=-1)):
        at = rows == ext[:, np.newaxis]
        # the run-length test only where the extreme repeats often enough (rare)
        for i in np.flatnonzero((np.count_nonzero(at, axis=-1) >= min_count) & ~out):
            d = np.diff(np.concatenate(([0], at[i].view(np.int8), [0])))
            runs = np.flatnonzero(d == -1) - np.flatnonzero(d == 1)
            out[i] = runs.size > 0 and runs.max() >= min_run
    return bool(out[0]) if x.ndim == 1 else out


def interference_frequencies_Hz(speed_km_h: float, circumference_m: float, lugs_per_side: int = 0,
                                harmonics: int = 3) -> list[float]:
    """Frequencies of the periodic excitation by the rolling wheel (§2.4.5), Hz.

    Wheel rotation ``v/circumference`` and its first ``harmonics`` multiples;
    for traction tyres half the lug passing frequency (``lugs_per_side`` per
    revolution) and the lug passing frequency. Empty for a stationary tyre.

    See Also
    --------
    qc_reasons : refuses an excitation near one of them.
    tyrelab.tyre.sizes.lugs_per_side : a traction tyre's lugs.

    Examples
    --------
    >>> [round(f, 3) for f in interference_frequencies_Hz(10.0, 4.66)]    # 13.6R38 at 10 km/h: rotation x 1, 2, 3
    [0.596, 1.192, 1.788]
    >>> [round(f, 2) for f in interference_frequencies_Hz(10.0, 4.66, lugs_per_side=23)][3:]   # and lug passing
    [13.71, 27.42]
    """
    for name, value in (("speed_km_h", speed_km_h), ("circumference_m", circumference_m)):
        if not np.isfinite(value) or value < 0:
            raise ValueError(f"{name} must be finite and >= 0, got {value!r}")
    if lugs_per_side < 0 or harmonics < 0:
        raise ValueError(f"lugs_per_side and harmonics must be >= 0, got {lugs_per_side!r}, {harmonics!r}")
    if speed_km_h == 0 or circumference_m == 0:
        return []
    f_rot = km_h_to_m_s(speed_km_h) / circumference_m
    out = [k * f_rot for k in range(1, harmonics + 1)]
    if lugs_per_side > 0:
        out += [lugs_per_side * f_rot, 2 * lugs_per_side * f_rot]
    return out


def qc_reasons(
    time_s: np.ndarray,
    accel_m_s2: np.ndarray,
    force_N: np.ndarray,
    excitation_frequency_Hz: float,
    coherence: float,
    *,
    channels: Mapping[str, np.ndarray] | None = None,
    full_scale: Mapping[str, float] | None = None,
    min_coherence: float = MIN_COHERENCE,
    max_amplitude_drift: float = MAX_AMPLITUDE_DRIFT,
    max_frequency_drift_Hz: float = MAX_FREQUENCY_DRIFT_HZ,
    block_s: float = BLOCK_S,
    interference_Hz: list[float] | None = None,
    interference_tolerance_Hz: float = 0.15,
    blocks: tuple[np.ndarray, np.ndarray] | None = None,
    clipped_channels: list[str] | None = None,
) -> list[str]:
    """Reasons a measurement run should not be used (empty list = OK).

    Parameters
    ----------
    time_s : ndarray
        Sample times, s.
    accel_m_s2 : ndarray
        Axle acceleration (mean of the two ends), m/s².
    force_N : ndarray
        Derived tyre force, N.
    excitation_frequency_Hz : float
        Measured excitation frequency, Hz; NaN if none was found.
    coherence : float
        Magnitude-squared coherence of force and acceleration at the excitation bin.
    channels : mapping of str to ndarray, optional
        Raw channels (e.g. the six of raw format v1) to check for clipping;
        default: ``accel`` and ``force``.
    full_scale : mapping of str to float, optional
        Converter full scale per channel name (units of the channel).
    min_coherence, max_amplitude_drift, max_frequency_drift_Hz, block_s :
        Thresholds (§3.5) and demodulation block length (s).
    interference_Hz : list of float, optional
        Known periodic excitation frequencies (:func:`interference_frequencies_Hz`);
        a run whose excitation lies within ``interference_tolerance_Hz`` of one is
        flagged: the wheel's own excitation then adds to the axle motion at the
        measurement frequency and biases K and C (coherence stays high).
    blocks : (ndarray, ndarray), optional
        Per-block excitation amplitude and frequency (Hz) already computed by
        the analysis (:func:`tyrelab.measurement.apparent_mass.excitation_blocks`);
        computed here from the synchronous demodulation when omitted.
    clipped_channels : list of str, optional
        Names of the channels already found clipped (e.g. by :func:`clipped`
        over a whole batch); ``channels`` are checked here when omitted.

    Returns
    -------
    list of str
        e.g. ``["coherence 0.62 < 0.9 at the excitation frequency",
        "amplitude drift 27.0 % > 20 %", "frequency drift 0.140 Hz > 0.1 Hz",
        "clipping in load_beam_2_N", "excitation not found"]``.

    See Also
    --------
    plausibility_reasons : whether K and C can be a tyre's.
    clipped : the clipping check.

    Examples
    --------
    >>> fs = 256.0; t = np.arange(0, 30, 1 / fs); w = 2 * np.pi * 3.8
    >>> x = 0.005 * np.sin(w * t); a = -w**2 * x               # 10 mm p-p at 3.8 Hz
    >>> f = -(228e3 * x + 2.4e3 * 0.005 * w * np.cos(w * t))  # a Kelvin-Voigt tyre's force, N
    >>> qc_reasons(t, a, f, 3.8, 0.99), qc_reasons(t, a, f, 3.8, 0.5)
    ([], ['coherence 0.5 < 0.9 at the excitation frequency'])
    """
    reasons: list[str] = []
    chans = dict(channels) if channels is not None else {"accel": accel_m_s2, "force": force_N}
    fsc = dict(full_scale or {})
    if clipped_channels is None:
        names = list(chans)
        flags = clipped(np.stack([np.asarray(chans[n]) for n in names]), [fsc.get(n, np.nan) for n in names])
        clipped_channels = [n for n, flag in zip(names, flags) if flag]
    reasons.extend(f"clipping in {n}" for n in clipped_channels)
    f0 = float(excitation_frequency_Hz) if excitation_frequency_Hz is not None else float("nan")
    if not np.isfinite(f0) or f0 <= 0:
        reasons.append("excitation not found")
        return reasons
    for fi in interference_Hz or []:
        if abs(fi - f0) <= interference_tolerance_Hz:
            reasons.append(f"wheel excitation at {fi:.2f} Hz within {interference_tolerance_Hz:g} Hz of the excitation")
            break
    if not np.isfinite(coherence) or coherence < min_coherence:
        reasons.append(f"coherence {_validate.compared(coherence, '<', min_coherence, 2)} at the excitation frequency")
    if blocks is None:
        fs = 1.0 / float(np.median(np.diff(time_s)))
        d = am.apparent_mass_demodulation(force_N, accel_m_s2, fs, f0)
        blocks = am.excitation_blocks(d.envelope_m_s2, d.angular_frequency_rad_s, fs, block_s)
    amp, freq = blocks
    if amp.size == 0 or not np.all(np.isfinite(amp)) or np.median(amp) <= 0:
        reasons.append("excitation not found")
        return reasons
    noise = np.std(np.asarray(accel_m_s2, dtype=float))
    if np.median(amp) < 0.2 * np.sqrt(2) * noise:
        reasons.append("excitation not found")
        return reasons
    drift = float(np.max(np.abs(amp / np.median(amp) - 1)))
    if drift > max_amplitude_drift:
        reasons.append(f"amplitude drift {100 * drift:.1f} % > {100 * max_amplitude_drift:g} %")
    fdrift = float(np.max(np.abs(freq - np.median(freq))))
    if fdrift > max_frequency_drift_Hz:
        reasons.append(f"frequency drift {fdrift:.3f} Hz > {max_frequency_drift_Hz:g} Hz")
    return reasons


def plausibility_reasons(stiffness_N_per_m: float, damping_N_s_per_m: float) -> list[str]:
    """Reasons K and C cannot be a tyre's (empty list = plausible).

    A passive tyre has K > 0 and C > 0, i.e. a thesis-convention apparent
    mass in the third quadrant (thesis §3.3.1, eqs 8-9). Negative damping
    is the signature of accelerations recorded deflection-positive (the
    thesis' convention) instead of upward-positive as raw format v1 requires:
    the tyre force ``M_a a - Σ beams`` then changes too and K comes out
    plausible but wrong, while C changes sign.

    See Also
    --------
    qc_reasons : the run's other checks.

    Examples
    --------
    >>> plausibility_reasons(250e3, 2e3)
    []
    >>> plausibility_reasons(250e3, -2e3)
    ['non-positive damping C = -2.00 kN s/m: are the accelerations upward positive (raw format v1)?']
    """
    reasons = []
    if np.isfinite(stiffness_N_per_m) and stiffness_N_per_m <= 0:
        reasons.append(f"non-positive stiffness K = {stiffness_N_per_m / 1e3:.1f} kN/m")
    if np.isfinite(damping_N_s_per_m) and damping_N_s_per_m <= 0:
        reasons.append(
            f"non-positive damping C = {damping_N_s_per_m / 1e3:.2f} kN s/m: are the accelerations "
            "upward positive (raw format v1)?"
        )
    return reasons
