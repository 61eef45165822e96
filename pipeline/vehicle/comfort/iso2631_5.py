"""ISO 2631-5:2018 vibration containing multiple shocks: the regime and the vertical acceleration dose.

**Regime** (clause 4). The 2018 edition splits exposures to multiple shocks in two: *severe*
ones, where the occupant may lose contact with the seat (free fall), assessed by the clause 5
model below and its Annex C; and *less severe* ones, where the occupant stays seated throughout
(tractors, forestry and earth-moving machines on rough ground), which the edition assigns to
its Annex A model — a finite-element model of the spine that ISO distributes as software and
that cannot be rebuilt from the standard's text. The edition's delineation is 1 g
(9.81 m/s²) of band-limited vertical seat acceleration. tyrelab decides it from the signal as
the physics behind that threshold says (:func:`contact_regime`): the occupant, held on the
cushion only by gravity, leaves it when the seat moves *downward* faster than free fall, i.e.
when the band-limited, offset-free seat acceleration goes below ``−g``
(:data:`LOSS_OF_CONTACT_M_S2` = 9.80665 m/s², the standard gravity). Such a recording's regime is
``"loss_of_contact"`` (clause 5 applies: :data:`REGIME_MODEL`); otherwise ``"seated"``, whose
model (Annex A) tyrelab does not have: D_z is still computed by clause 5 and reported, marked as
not the standard's assessment of that recording (``dz_applies`` false).

**Band and offsets.** The seat acceleration's offset is removed (the transfer function passes
0 Hz, so an offset would pass into every peak), and the band :data:`BAND_HZ` = 0.01–80 Hz is
applied with the spinal response (linear systems: the order does not matter) as the
band-limiting filters of the form ISO 2631-1 and ISO 8041-1 use — a second-order Butterworth
high-pass at 0.01 Hz and low-pass at 80 Hz (:func:`band_response`): the low-pass exactly, as
its analog response at each frequency with the transfer function (:func:`spine_and_lowpass`;
a bilinear one would be the analog one only well below Nyquist: its phase at 4 Hz is off by a
third at 256 Hz), the high-pass as its bilinear digital filter (:func:`highpass_sos`, the analog
one to within 1e-6 above 0.1 Hz), run from rest. The high-pass is what keeps a residual offset (one the first chunk's mean did not remove, a drift
of the accelerometer) out of the peaks: it decays within a minute (time constant 1/(ζω) =
23 s) instead of raising every peak after it. The band's edges are the edition's as this
project's issue 44 cites them (0.01–80 Hz); the filter form is our documented choice.

**Dose** (clause 5). The seat's vertical acceleration goes through the seat-to-spine transfer
function of clause 5.2, Formula 1,

``H(s) = (1 + 2 ζ₁ s/ω₁ + (s/ω₁)²) / Π_k (1 + 2 ζ_k s/ω_k + (s/ω_k)²)``,

one complex zero and six complex pole pairs with the (ω, ζ) of :data:`SPINE_ZERO` and
:data:`SPINE_POLES` (ω in rad/s; unity at 0 Hz, the first pole pair at 31 rad/s ≈ 4.9 Hz,
the seated body's resonance). The positive peaks ``A_i`` of the response, one per interval
between zero crossings (its maximum), give the dose (Formula 3)

``D_z = 1.07 (Σ A_i⁶)^(1/6)``  (m/s²),

and the daily dose ``D_zd = D_z (t_d / t_m)^(1/6)`` (Formula 4), or for several
conditions ``D_zd = (Σ_j D_zj⁶ t_dj / t_mj)^(1/6)`` (Formula 5). The 2018 edition is
vertical only.

**Sources of the constants.** Formula 1's zero and poles, Formula 3's 1.07 and exponent 6 and
Formulae 4/5 are ISO 2631-5:2018 clause 5 as printed in the open implementation we check against
(phonometry 3.3.0, ``vibration/multiple_shock_vibration.py``, whose documentation also gives
clause 4's regimes, the 1 g delineation and Annex A's finite-element model; the project's
``field-notes.md``); the band's edges are issue 44's citation of the edition; g is the standard
gravity (ISO 80000-3). The 2004 edition's neural-network model is withdrawn and not used.
``tests/vehicle/test_iso2631_5.py`` checks the dose and the regime against closed forms worked by
hand from these formulae (a sinusoid: ``D_z = 1.07 A |H(f)| n^(1/6)``; the time below ``−g``).

Examples
--------
>>> round(abs(complex(spine_response(0.0))), 6)
1.0
>>> fs = 256.0
>>> t = np.arange(int(60 * fs)) / fs
>>> contact_regime(12.0 * np.sin(2 * np.pi * 4.0 * t), fs).regime, contact_regime(np.sin(2 * np.pi * 4.0 * t), fs).regime
('loss_of_contact', 'seated')
"""

from __future__ import annotations

import math

from dataclasses import dataclass

import numpy as np

from ... import _validate
from ..._validate import positive
from ..units import STANDARD_GRAVITY_M_S2

__all__ = [
    "SPINE_ZERO",
    "SPINE_POLES",
    "DOSE_FACTOR",
    "SPINE_RING_S",
    "BAND_HZ",
    "LOSS_OF_CONTACT_M_S2",
    "REGIMES",
    "REGIME_MODEL",
    "lowpass_response",
    "band_response",
    "highpass_sos",
    "regime_band_sos",
    "HighPass",
    "band_limited",
    "spine_and_lowpass",
    "ContactRegime",
    "contact_regime",
    "ContactWatch",
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
#: The band applied, Hz: (high-pass, low-pass) edges of second-order Butterworth band-limiting.
BAND_HZ = (0.01, 80.0)
#: Downward seat acceleration beyond which the occupant leaves the seat (free fall: the standard
#: gravity g), m/s²; the 2018 edition's 1 g delineation of its regimes.
LOSS_OF_CONTACT_M_S2 = STANDARD_GRAVITY_M_S2
#: A recording's regime: the occupant lost contact with the seat at some time, or stayed seated.
REGIMES = ("loss_of_contact", "seated")
#: Regime -> the model ISO 2631-5:2018 assigns to it (tyrelab computes clause 5's only).
REGIME_MODEL = {"loss_of_contact": "clause 5", "seated": "Annex A"}


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
    """Spinal response A_z(t) of a whole record (Formula 2), mean removed first and the band
    :data:`BAND_HZ` applied, m/s².

    The transfer function and the band's low-pass are applied as
    :func:`tyrelab.vehicle.iso2631.weighted_signal` applies a weighting (the record zero-padded to
    twice its length, times the response at each FFT bin), then the band's high-pass
    (:class:`HighPass`, from rest). Streams use :class:`tyrelab.vehicle.iso2631.ResponseFilter`
    with the same response (:func:`spine_and_lowpass`), then the same high-pass.

    See Also
    --------
    acceleration_dose : D_z from it.
    spine_and_lowpass : the response applied.

    Examples
    --------
    >>> fs = 256.0
    >>> t = np.arange(int(100 * fs)) / fs
    >>> a = np.sin(2 * np.pi * 4.0 * t)
    >>> steady = spinal_acceleration(a, fs)[-int(10 * fs):]
    >>> round(float(steady.max()), 3) == round(float(abs(spine_response(4.0))), 3)
    True
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    _validate.finite_array("seat_z_m_s2", seat_z_m_s2, min_samples=1)
    a = np.asarray(seat_z_m_s2, dtype=float)
    return HighPass(fs_Hz).filter(_through(a - a.mean(), fs_Hz, spine_and_lowpass))


def lowpass_response(frequency_Hz) -> np.ndarray:
    """The band's upper edge: a second-order Butterworth low-pass at ``BAND_HZ[1]`` (80 Hz), its
    analog response (applied exactly, as the transfer function is, at any sampling rate).

    See Also
    --------
    band_response : with the 0.01 Hz high-pass.
    spine_and_lowpass : times the transfer function.

    Examples
    --------
    >>> round(float(abs(lowpass_response(80.0))), 4), round(float(abs(lowpass_response(4.0))), 6)
    (0.7071, 0.999997)
    """
    _validate.non_negative_array("frequency_Hz", frequency_Hz)
    s = 1j * np.asarray(frequency_Hz, dtype=float) / BAND_HZ[1]
    return 1.0 / (1.0 + math.sqrt(2.0) * s + s**2)


def band_response(frequency_Hz) -> np.ndarray:
    """The band :data:`BAND_HZ` as analog second-order Butterworth high- and low-pass (the
    reference :func:`highpass_sos` realises below the low-pass).

    See Also
    --------
    lowpass_response : the upper edge alone.
    highpass_sos : the lower edge as a digital filter.

    Examples
    --------
    >>> [round(float(abs(band_response(f))), 4) for f in (0.01, 4.0, 80.0)]
    [0.7071, 1.0, 0.7071]
    """
    _validate.non_negative_array("frequency_Hz", frequency_Hz)
    s = 1j * np.asarray(frequency_Hz, dtype=float) / BAND_HZ[0]
    return s**2 / (1.0 + math.sqrt(2.0) * s + s**2) * lowpass_response(frequency_Hz)


def highpass_sos(fs_Hz: float) -> np.ndarray:
    """Second-order sections of the band's 0.01 Hz high-pass at ``fs_Hz`` (Butterworth, bilinear:
    at 0.01 Hz, 1/1600 of the lowest accepted rate's Nyquist frequency, the digital filter is the
    analog one to within 1e-4 above 0.1 Hz).

    See Also
    --------
    HighPass : runs it, chunk after chunk.
    regime_band_sos : with a digital 80 Hz low-pass.

    Examples
    --------
    >>> highpass_sos(500.0).shape
    (1, 6)
    """
    from scipy import signal

    fs_Hz = positive("fs_Hz", fs_Hz)
    return signal.butter(2, BAND_HZ[0], "highpass", fs=fs_Hz, output="sos")


def regime_band_sos(fs_Hz: float) -> np.ndarray:
    """Second-order sections of the band as the regime decision applies it (:func:`contact_regime`):
    the 0.01 Hz high-pass and, where 80 Hz is below the Nyquist frequency, the 80 Hz low-pass, both
    bilinear Butterworth (a threshold decision; a recursive filter streams exactly, where the analog
    low-pass's impulse response, not small at Nyquist, would have to be cut).

    See Also
    --------
    contact_regime : the decision it serves.

    Examples
    --------
    >>> regime_band_sos(500.0).shape, regime_band_sos(100.0).shape
    ((2, 6), (1, 6))
    """
    from scipy import signal

    fs_Hz = positive("fs_Hz", fs_Hz)
    sos = [highpass_sos(fs_Hz)]
    if BAND_HZ[1] < 0.5 * fs_Hz:
        sos.append(signal.butter(2, BAND_HZ[1], "lowpass", fs=fs_Hz, output="sos"))
    return np.concatenate(sos)


class HighPass:
    """The band's high-pass streamed (or, ``regime=True``, the band of :func:`regime_band_sos`):
    :meth:`filter` chunk after chunk, from rest.

    Examples
    --------
    >>> fs = 100.0
    >>> x = np.random.default_rng(1).standard_normal(5000)
    >>> h = HighPass(fs)
    >>> y = np.concatenate([h.filter(x[:1234]), h.filter(x[1234:])])
    >>> bool(np.allclose(y, HighPass(fs).filter(x)))
    True
    """

    def __init__(self, fs_Hz: float, regime: bool = False):
        self.sos = regime_band_sos(fs_Hz) if regime else highpass_sos(fs_Hz)
        self._zi = np.zeros((self.sos.shape[0], 2))

    def filter(self, samples) -> np.ndarray:
        from scipy import signal

        y, self._zi = signal.sosfilt(self.sos, np.asarray(samples, dtype=float), zi=self._zi)
        return y


def _through(a: np.ndarray, fs_Hz: float, response) -> np.ndarray:
    """``a`` through an analog ``response``: zero-padded to twice its length, times the response at
    each FFT bin (as :func:`tyrelab.vehicle.iso2631.weighted_signal`)."""
    nfft = 1 << int(math.ceil(math.log2(max(2 * a.size, 2))))
    return np.fft.irfft(np.fft.rfft(a, nfft) * response(np.fft.rfftfreq(nfft, 1.0 / fs_Hz)), nfft)[: a.size]


def band_limited(seat_z_m_s2, fs_Hz: float) -> np.ndarray:
    """The seat acceleration with its mean removed and the band applied as the regime decision
    applies it (:func:`regime_band_sos`), m/s².

    See Also
    --------
    contact_regime : the regime decided from it.

    Examples
    --------
    >>> fs = 256.0
    >>> t = np.arange(int(200 * fs)) / fs
    >>> y = band_limited(0.2 + np.sin(2 * np.pi * 4.0 * t), fs)
    >>> round(float(np.abs(y[-int(fs):]).max()), 2)
    1.0
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    _validate.finite_array("seat_z_m_s2", seat_z_m_s2, min_samples=1)
    a = np.asarray(seat_z_m_s2, dtype=float)
    return HighPass(fs_Hz, regime=True).filter(a - a.mean())


def spine_and_lowpass(frequency_Hz) -> np.ndarray:
    """The transfer function times the band's low-pass (:func:`spine_response` × :func:`lowpass_response`).

    See Also
    --------
    spinal_acceleration : applies it, then the high-pass.

    Examples
    --------
    >>> round(float(abs(spine_and_lowpass(0.0))), 6)
    1.0
    """
    return spine_response(frequency_Hz) * lowpass_response(frequency_Hz)


@dataclass(frozen=True)
class ContactRegime:
    """A recording's ISO 2631-5 regime, decided from its seat's vertical acceleration.

    Attributes
    ----------
    regime : str
        ``"loss_of_contact"`` where the band-limited seat acceleration went below
        ``−`` :data:`LOSS_OF_CONTACT_M_S2` at some time, else ``"seated"``.
    down_peak_m_s2 : float
        Largest downward band-limited seat acceleration (a magnitude; 0 if it never went below
        zero), m/s².
    loss_of_contact_s : float
        Time the seat went down faster than free fall, s.
    """

    regime: str
    down_peak_m_s2: float
    loss_of_contact_s: float

    @property
    def model(self) -> str:
        """The model ISO 2631-5:2018 assigns to the regime (:data:`REGIME_MODEL`)."""
        return REGIME_MODEL[self.regime]

    @property
    def dz_applies(self) -> bool:
        """Whether clause 5's D_z is the standard's assessment of the recording."""
        return self.regime == "loss_of_contact"


class ContactWatch:
    """The regime streamed: feed the band-limited seat acceleration in chunks, then :meth:`finish`.

    Examples
    --------
    >>> w = ContactWatch(100.0)
    >>> w.process(np.array([-3.0, -10.0, -11.0, 2.0])); w.process(np.array([-9.0]))
    >>> r = w.finish()
    >>> r.regime, r.down_peak_m_s2, r.loss_of_contact_s
    ('loss_of_contact', 11.0, 0.02)
    """

    def __init__(self, fs_Hz: float):
        self.fs = positive("fs_Hz", fs_Hz)
        self._low = 0.0
        self._below = 0

    def process(self, band_limited_m_s2) -> None:
        a = np.asarray(band_limited_m_s2, dtype=float)
        if a.size:
            self._low = min(self._low, float(a.min()))
            self._below += int(np.count_nonzero(a < -LOSS_OF_CONTACT_M_S2))

    def finish(self) -> ContactRegime:
        return ContactRegime(REGIMES[0] if self._below else REGIMES[1], -self._low, self._below / self.fs)


def contact_regime(seat_z_m_s2, fs_Hz: float) -> ContactRegime:
    """The ISO 2631-5 regime of a whole record of seat vertical acceleration (module docstring).

    Parameters
    ----------
    seat_z_m_s2 : array_like
        Seat vertical acceleration, upward positive, m/s² (an offset such as a DC-coupled
        accelerometer's 1 g is removed).
    fs_Hz : float
        Sampling rate, Hz.

    Returns
    -------
    ContactRegime

    See Also
    --------
    ContactWatch : the same, streamed.

    Examples
    --------
    >>> fs = 256.0
    >>> t = np.arange(int(60 * fs)) / fs
    >>> r = contact_regime(9.81 + 12.0 * np.sin(2 * np.pi * 4.0 * t), fs)
    >>> r.regime, r.model, round(r.down_peak_m_s2, 1)
    ('loss_of_contact', 'clause 5', 12.0)
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    w = ContactWatch(fs_Hz)
    w.process(band_limited(seat_z_m_s2, fs_Hz))
    return w.finish()


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
    """D_z of a whole record of seat vertical acceleration (clause 5), m/s².

    Whether it is the standard's assessment of the record is its regime's question
    (:func:`contact_regime`).

    See Also
    --------
    contact_regime : whether D_z applies.
    daily_dose : the day from the doses.

    Examples
    --------
    >>> fs = 256.0
    >>> t = np.arange(int(100 * fs)) / fs
    >>> dz = acceleration_dose(2.0 * np.sin(2 * np.pi * 4.0 * t), fs)
    >>> bool(abs(dz / (1.07 * 2.0 * abs(spine_response(4.0)) * 400 ** (1 / 6)) - 1) < 0.01)
    True
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
