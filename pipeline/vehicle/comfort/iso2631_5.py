"""ISO 2631-5:2018 vibration containing multiple shocks: the vertical acceleration dose.

The seat's vertical acceleration (mean removed: the transfer function passes 0 Hz)
goes through the seat-to-spine transfer function of clause 5.2, Formula 1,

``H(s) = (1 + 2 ζ₁ s/ω₁ + (s/ω₁)²) / Π_k (1 + 2 ζ_k s/ω_k + (s/ω_k)²)``,

one complex zero and six complex pole pairs with the (ω, ζ) of :data:`SPINE_ZERO` and
:data:`SPINE_POLES` (ω in rad/s; unity at 0 Hz, the first pole pair at 31 rad/s ≈ 4.9 Hz,
the seated body's resonance). The constants are those of the 2018 edition as printed in
the open implementation we check against (phonometry 3.3.0,
``vibration/multiple_shock_vibration.py``); the 2004 edition's neural-network model is
withdrawn and not used. The positive peaks ``A_i`` of the response, one per interval
between zero crossings (its maximum), give the dose (Formula 3)

``D_z = 1.07 (Σ A_i⁶)^(1/6)``  (m/s²),

and the daily dose ``D_zd = D_z (t_d / t_m)^(1/6)`` (Formula 4), or for several
conditions ``D_zd = (Σ_j D_zj⁶ t_dj / t_mj)^(1/6)`` (Formula 5). The 2018 edition is
vertical only.

Examples
--------
>>> round(abs(complex(spine_response(0.0))), 6)
1.0
"""

from __future__ import annotations

import math

import numpy as np

from ... import _validate
from ..._validate import positive

__all__ = [
    "SPINE_ZERO",
    "SPINE_POLES",
    "DOSE_FACTOR",
    "SPINE_RING_S",
    "spine_response",
    "spinal_acceleration",
    "positive_peaks",
    "dose_from_peaks",
    "acceleration_dose",
    "daily_dose",
    "PeakDose",
]

#: Complex zero (ω rad/s, ζ) of the seat-to-spine transfer function (ISO 2631-5:2018 Formula 1).
SPINE_ZERO = (34.0, 0.35)
#: Complex pole pairs (ω rad/s, ζ) of the seat-to-spine transfer function.
SPINE_POLES = ((31.0, 0.21), (230.0, 0.88), (260.0, 0.80), (320.0, 0.40), (380.0, 0.75), (420.0, 0.65))
#: Factor of the dose, Formula 3.
DOSE_FACTOR = 1.07
#: Time by which the spine response has rung down (its slowest pole decays as exp(-ζω t) =
#: exp(-6.5 t): 1e-14 after 5 s), s.
SPINE_RING_S = 5.0


def spine_response(frequency_Hz) -> np.ndarray:
    """Complex seat-to-spine transfer function H(j 2π f) (ISO 2631-5:2018 Formula 1).

    Parameters
    ----------
    frequency_Hz : array_like
        Frequencies, Hz.

    Returns
    -------
    ndarray of complex

    See Also
    --------
    spinal_acceleration : applies it to a record.

    Examples
    --------
    >>> f_peak = 31.0 / (2 * math.pi)
    >>> round(float(abs(spine_response(f_peak))), 2)
    1.56
    """
    _validate.non_negative_array("frequency_Hz", frequency_Hz)
    s = 2j * math.pi * np.asarray(frequency_Hz, dtype=float)
    w, z = SPINE_ZERO
    h = 1.0 + 2.0 * z * s / w + (s / w) ** 2
    for w, z in SPINE_POLES:
        h = h / (1.0 + 2.0 * z * s / w + (s / w) ** 2)
    return h


def spinal_acceleration(seat_z_m_s2, fs_Hz: float) -> np.ndarray:
    """Spinal response A_z(t) of a whole record (Formula 2), mean removed first, m/s².

    Applied as :func:`tyrelab.vehicle.iso2631.weighted_signal` applies a weighting: the
    record zero-padded to twice its length, times H at each FFT bin. Streams use
    :class:`tyrelab.vehicle.iso2631.ResponseFilter` with the same response.

    See Also
    --------
    spine_response : the transfer function applied.
    acceleration_dose : the dose from its peaks.

    Examples
    --------
    >>> fs = 500.0; t = np.arange(0, 10, 1 / fs)
    >>> a = np.sin(31.0 * t)                               # 1 m/s² at the spine model's peak, 4.93 Hz
    >>> round(float(np.abs(spinal_acceleration(a, fs)[1000:-1000]).max()), 2)   # |H| = 1.56 there
    1.56
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    a = np.asarray(seat_z_m_s2, dtype=float)
    a = a - a.mean()
    nfft = 1 << int(math.ceil(math.log2(max(2 * a.size, 2))))
    return np.fft.irfft(np.fft.rfft(a, nfft) * spine_response(np.fft.rfftfreq(nfft, 1.0 / fs_Hz)), nfft)[: a.size]


def positive_peaks(response_m_s2) -> np.ndarray:
    """The maximum of each run of positive samples (the peaks between zero crossings), m/s².

    See Also
    --------
    dose_from_peaks : the dose of these peaks.

    Examples
    --------
    >>> positive_peaks(np.array([0.5, 2.0, -1.0, 3.0, 1.0, 0.0, -2.0, 0.1]))
    array([2. , 3. , 0.1])
    """
    _validate.finite_array("response_m_s2", response_m_s2, min_samples=0)
    a = np.asarray(response_m_s2, dtype=float)
    pos = np.concatenate(([False], a > 0, [False]))
    starts = np.flatnonzero(~pos[:-1] & pos[1:])
    return np.maximum.reduceat(a, starts) if starts.size else np.empty(0)


def dose_from_peaks(peaks_m_s2) -> float:
    """``D_z = 1.07 (Σ A_i⁶)^(1/6)``, m/s² (Formula 3); 0 without peaks.

    See Also
    --------
    positive_peaks : the peaks it takes.
    acceleration_dose : the dose of a record.

    Examples
    --------
    >>> round(dose_from_peaks([1.0, 1.0]), 6)
    1.201034
    """
    _validate.non_negative_array("peaks_m_s2", peaks_m_s2)
    p = np.asarray(peaks_m_s2, dtype=float)
    return float(DOSE_FACTOR * np.sum(p**6) ** (1.0 / 6.0))


def acceleration_dose(seat_z_m_s2, fs_Hz: float) -> float:
    """D_z of a whole record of seat vertical acceleration, m/s².

    See Also
    --------
    spinal_acceleration : the response whose peaks it counts.
    daily_dose : the day's dose from the tasks' doses.

    Examples
    --------
    >>> fs = 500.0; t = np.arange(0, 10, 1 / fs)
    >>> a = np.sin(31.0 * t)                               # 1 m/s² at the spine model's peak, 4.93 Hz
    >>> round(acceleration_dose(a, fs), 2)               # 1.07 × 1.56 × (50 peaks)^(1/6) = 3.20, less the ends
    3.17
    """
    return dose_from_peaks(positive_peaks(spinal_acceleration(seat_z_m_s2, fs_Hz)))


def daily_dose(doses_m_s2, exposure_s, measured_s) -> float:
    """Daily dose ``D_zd = (Σ_j D_zj⁶ t_dj / t_mj)^(1/6)``, m/s² (Formulae 4 and 5).

    Parameters
    ----------
    doses_m_s2 : float or array_like
        D_z of each condition (task), as measured.
    exposure_s : float or array_like
        Daily exposure to each condition, s (any unit, the same as ``measured_s``).
    measured_s : float or array_like
        Duration of each condition's measurement.

    See Also
    --------
    acceleration_dose : each task's dose.

    Examples
    --------
    >>> round(daily_dose(2.0, 8 * 3600, 3600), 6)
    2.828427
    """
    d = np.atleast_1d(np.asarray(doses_m_s2, dtype=float))
    td = np.atleast_1d(np.asarray(exposure_s, dtype=float))
    tm = np.atleast_1d(np.asarray(measured_s, dtype=float))
    if not d.shape == td.shape == tm.shape:
        raise ValueError("doses_m_s2, exposure_s and measured_s must have the same length")
    if not (np.all(np.isfinite(tm)) and np.all(tm > 0) and np.all(np.isfinite(td)) and np.all(td >= 0)):
        raise ValueError("measured_s must be positive and exposure_s non-negative")
    return float(np.sum(d**6 * td / tm) ** (1.0 / 6.0))


class PeakDose:
    """Streaming D_z: feed the spinal response in chunks; a peak spanning chunks counts once.

    Examples
    --------
    >>> p = PeakDose()
    >>> p.process(np.array([0.5, 2.0])); p.process(np.array([1.0, -1.0, 3.0]))
    >>> round(p.finish(), 6) == round(dose_from_peaks([2.0, 3.0]), 6)
    True
    """

    def __init__(self):
        self._sum6 = 0.0
        self._open = 0.0  # maximum of the positive run still open at the end of the last chunk (0: none)
        self.n_peaks = 0

    def process(self, response_m_s2) -> None:
        a = np.asarray(response_m_s2, dtype=float)
        if a.size == 0:
            return
        pos = a > 0
        starts = np.flatnonzero(pos[1:] > pos[:-1]) + 1  # where a positive run begins, after the first sample
        if pos[0]:  # a run at the start: the open one going on, or a new one
            end = int(starts[0]) if starts.size else a.size
            self._open = max(self._open, float(a[:end].max()))
            if starts.size == 0 and pos[-1]:  # it goes on into the next chunk
                return
        self._close()
        if starts.size == 0:
            return
        # each run's maximum: from its start to the next run's (the samples between are not positive)
        peaks = np.maximum.reduceat(a, starts)
        if pos[-1]:  # the last run may go on in the next chunk
            self._open = float(peaks[-1])
            peaks = peaks[:-1]
        self._sum6 += float(np.sum(peaks**6))
        self.n_peaks += int(peaks.size)

    def _close(self) -> None:
        if self._open > 0:
            self._sum6 += self._open**6
            self.n_peaks += 1
            self._open = 0.0

    def finish(self) -> float:
        """D_z of everything fed, m/s²."""
        self._close()
        return float(DOSE_FACTOR * self._sum6 ** (1.0 / 6.0))
