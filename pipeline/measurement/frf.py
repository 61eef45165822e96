"""A vehicle's multi-input transfer functions and their modes (thesis ch. 2; issue 43).

The thesis measured the tractor's transfer functions from the ground under each wheel to the
cab floor (§2.2 four-ram stand, §2.3 one wheel on a rough track). With several wheels excited
at once a single-input estimate mixes the wheels; this module gives, from recordings of ``q``
inputs (ground or pad vertical acceleration under each wheel, or ground height) and ``p``
outputs:

* the Welch cross-spectral matrices ``S_xx`` (q × q), ``S_xy`` (q × p) and the outputs'
  auto-spectra, from ``scipy.signal.csd`` and ``scipy.signal.welch`` (Hann, 50 % overlap,
  constant detrend: their defaults), accumulated over blocks of segments so the memory is
  bounded by the segment length, not the recording (:class:`CrossSpectraAccumulator`; the sums
  equal one ``csd`` call over the whole record);
* height inputs (ground height under a wheel, m, as the track method's optical transducer
  measured it, §2.3) turned into accelerations: the second difference in time, whose known
  response ``-4 fs² sin²(πf/fs)`` is then divided out in the frequency domain so the spectra are
  those of the exact second derivative ``-(2πf)² X_h`` (:func:`second_difference_correction`).
  Multiplying the windowed height spectra by ``-(2πf)²`` instead is wrong by terms of the Hann
  window's derivatives, of order ``(1 / (T f))²``: 4 % at 0.5 Hz with 10 s segments. The same
  recording as heights and as accelerations gives the same FRFs;
* the MIMO estimate ``H1 = S_yx S_xx⁻¹`` per output (Bendat & Piersol, *Random Data*, 4th ed.,
  ch. 7), the ordinary, partial (conditioned on the other inputs) and multiple coherence, the
  normalised random error of each ``|H|`` on ``n_d − q`` degrees of freedom (B&P eq. 9.90:
  ``ε = sqrt((1 − γ²_y:x) / (2 (n_d − q) γ²_iy·(q−1)!))``, which for ``q = 1`` is the single-input
  ``sqrt(1 − γ²) / (|γ| sqrt(2 (n_d − 1)))``), and the condition number of ``S_xx`` per bin
  (:func:`mimo_frf`); with one input also ``H2 = S_yy / S_yx``;
* the inputs a bin cannot separate: input ``i`` is flagged (``ill_conditioned``) in a bin where
  the other inputs explain at least :data:`MAX_INPUT_COHERENCE` of it (its multiple coherence
  with them; a variance-inflation factor ``1 / (1 − γ²) ≥ 10``, the usual limit of
  collinearity): its ``H`` there is a guess between correlated inputs and is never fitted. Pure
  road input (rear = delayed front) is flagged; the thesis' own correlated case (§2.2: the measured
  wheel independent, the three others correlated like a track) leaves the measured wheel fitted;
* the bins near each wheel's rotation frequency and its harmonics, half the lug-passing and the
  lug-passing frequency masked (§2.4.5: the coherence drops there; :func:`wheel_excitation_mask`);
* the modes per output: a pole–residue model with shared poles over every usable input's FRF
  (each pole's ``f_d`` and ``ζ`` found by non-linear least squares, the residues, a complex
  constant and a complex lower residual ``1/s²`` per input (a body-fixed accelerometer's gravity
  component has a double pole at 0 Hz) by linear least squares for given poles — variable projection, Golub &
  Pereyra 1973), each bin weighted by its random error; the number of modes by the Bayesian
  information criterion; 95 % intervals from the Jacobian of the projected residual on the
  fit's degrees of freedom (:func:`fit_vehicle_modes`); then each output fitted again together with
  the outputs that show the same modes, poles shared (a poly-reference fit: the heavily damped,
  overlapping lateral–roll and yaw modes of rolling tyres are resolved only by the roll, lateral
  and yaw outputs together), a heavily damped pole tried as two, and its interval holding both
  model orders where the data cannot tell them apart (:func:`fit_shared_modes`); a heavily damped
  pole's intervals from the profile of the fit's cost (:func:`_profile_mode`: the Jacobian's assume a
  cost quadratic in the pole, which an overlapping pole 40–80 % damped is not); each mode marked
  ``determined`` or not (its interval reaching a bound of the fit, wider than its frequency, holding
  another pole, or damped beyond :data:`NO_PEAK_DAMPING`, where a mode has no resonance peak), with
  its undamped natural frequency ``|λ| / 2π`` beside the damped one.

Segments are at least :data:`MIN_SEGMENT_S` long: bins of 0.125 Hz or finer, well under the
half-power bandwidth ``2 ζ f`` of tractor modes damped 20–30 % around 1.3 Hz (0.5 Hz), which a
coarser bin would widen (the damping biased up; for lightly damped modes the intervals hold that bias). All functions are pure; SI units inside.

Examples
--------
A 2-input, 1-output system ``y = 2 x₁ − x₂`` recovered from partly correlated inputs:

>>> import numpy as np
>>> rng = np.random.default_rng(1)
>>> common = rng.standard_normal(20_000)
>>> x = np.vstack([common + rng.standard_normal(20_000), common + rng.standard_normal(20_000)])
>>> y = (2 * x[0] - x[1])[None, :]
>>> est = mimo_frf(cross_spectra(x, y, 50.0, 256))
>>> np.round(np.abs(est.h[10, 0]), 3), bool(est.ill_conditioned[10].any())
(array([2., 1.]), False)
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np
from scipy import ndimage, optimize, signal
from scipy.stats import t as student_t

from .._validate import positive, positive_int
from ..units import km_h_to_m_s

__all__ = ["MIN_SEGMENT_S", "MAX_INPUT_COHERENCE", "FIT_MIN_COHERENCE", "FIT_BAND_Hz", "MAX_MODES",
           "MASK_HARMONICS", "MASK_HALF_WIDTH", "CrossSpectra", "CrossSpectraAccumulator", "cross_spectra",
           "segment_samples", "second_difference_correction", "MimoFrf", "mimo_frf",
           "input_delays", "MIN_WINDOW_OVERLAP", "DELAY_SMOOTH_BINS", "wheel_excitation_mask",
           "VehicleMode", "fit_vehicle_modes", "fit_shared_modes", "HEAVY_DAMPING",
           "DAMPING_BOUNDS", "MIN_MODE_CONTRIBUTION", "MIN_MODE_SNR", "NO_PEAK_DAMPING", "PROFILE_STEPS", "WHEELS", "STORED_MAX_Hz",
           "input_channel_wheel", "frf_unit", "merge_bins", "OWN_FIT_BIN_Hz", "RecordingFrf", "recording_frf", "scenario_wheel_geometry"]

#: Shortest Welch segment, s: bins of 1/8 = 0.125 Hz or finer (the issue's limit for 20–30 %
#: damped modes around 1.3 Hz; a bin is then a quarter of their half-power bandwidth). 16 s
#: (``min_segment_s``, 0.049 Hz bins) takes the stationary virtual stand's bounce (3.0 Hz, ζ 0.019,
#: 0.06 Hz from its yaw) from +0.9 % and ζ +0.011 to +0.0 % and +0.001 (six seeds, still and
#: correlated), at 2.4-2.5 times ``csd`` instead of 1.6 (docs/benchmarks.md): not the default; the
#: damping's resolution bias is held by the intervals instead (:func:`_modes_of`).
MIN_SEGMENT_S = 8.0
#: An input whose multiple coherence with the other inputs reaches this in a bin cannot be
#: separated from them there (variance-inflation factor 1/(1 − 0.9) = 10, the usual
#: collinearity limit): flagged ``ill_conditioned``, never fitted.
MAX_INPUT_COHERENCE = 0.9
#: Least multiple coherence of a bin the modal fit uses (the "coherent band").
FIT_MIN_COHERENCE = 0.5
#: Band of the modal fit, Hz: the stand's random excitation, flat 0.5–12 Hz (thesis §2.2).
FIT_BAND_Hz = (0.5, 12.0)
#: Most modes fitted per output (bounce, pitch, lateral–roll pair: a tractor shows at most
#: three or four in one output's band).
MAX_MODES = 4
#: Harmonics of the wheel rotation frequency masked (§2.4.5: "at the wheel rotation frequencies
#: ... and at harmonics of these").
MASK_HARMONICS = 3
#: Half width of a masked band, relative to its centre frequency (±10 %: §2.4.5, "because of ...
#: small variations in the driving speed, these bands of low coherence were wide"), and at
#: least one bin either side.
MASK_HALF_WIDTH = 0.10


def segment_samples(sample_rate_Hz: float, min_segment_s: float = MIN_SEGMENT_S) -> int:
    """Welch segment length, samples: the power of two at least ``min_segment_s`` long.

    See Also
    --------
    cross_spectra : its default segment length.

    Examples
    --------
    >>> segment_samples(500.0), segment_samples(100.0)
    (4096, 1024)
    """
    fs = positive("sample_rate_Hz", sample_rate_Hz)
    n = positive("min_segment_s", min_segment_s) * fs
    return 1 << max(3, math.ceil(math.log2(n)))


@dataclass
class CrossSpectra:
    """One-sided Welch spectral matrices of ``q`` inputs and ``p`` outputs.

    Attributes
    ----------
    frequency_Hz : ndarray, shape (F,)
    s_xx : ndarray, shape (F, q, q)
        ``s_xx[f, i, j]`` = ``csd(x_i, x_j)`` (``E[X_i* X_j]``), unit² / Hz.
    s_xy : ndarray, shape (F, q, p)
        ``s_xy[f, i, k]`` = ``csd(x_i, y_k)``.
    s_yy : ndarray, shape (F, p)
        Outputs' auto-spectra (``welch``).
    n_segments : int
        Welch segments averaged (50 % overlap).
    n_d : float
        Independent averages for the random error: the record's length in segment lengths
        (B&P's ``n_d`` counts disjoint records; 50 % overlapped Hann segments add little).
    sample_rate_Hz : float
    """

    frequency_Hz: np.ndarray
    s_xx: np.ndarray
    s_xy: np.ndarray
    s_yy: np.ndarray
    n_segments: int
    n_d: float
    sample_rate_Hz: float
    #: Segment length, samples (Hann window: :func:`scipy.signal.csd`'s default); None: ``2 (F - 1)``.
    nperseg: int | None = None


class CrossSpectraAccumulator:
    """Welch spectral matrices accumulated over chunks of a recording, memory bounded by the segment.

    Samples are buffered until :attr:`BLOCK_SEGMENTS` segments are complete; one ``csd`` call
    (inputs against inputs and outputs, broadcast) and one ``welch`` call take them, and their
    sums are kept. The result equals ``csd`` over the whole record.

    Parameters
    ----------
    n_inputs, n_outputs : int
    sample_rate_Hz : float
    nperseg : int
        Segment length, samples (:func:`segment_samples`).
    heights : sequence of bool, optional
        Inputs that are ground heights (m): second-differenced as they stream (every channel then
        loses its first and last sample) and corrected to the exact second derivative in
        :meth:`finish` (:func:`second_difference_correction`), so they enter as m/s².

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> x, y = rng.standard_normal((2, 5000)), rng.standard_normal((1, 5000))
    >>> acc = CrossSpectraAccumulator(2, 1, 100.0, 256)
    >>> for i in range(0, 5000, 777):
    ...     acc.add(x[:, i:i + 777], y[:, i:i + 777])
    >>> s = acc.finish()
    >>> from scipy import signal
    >>> ref = signal.csd(x[0], y[0], fs=100.0, nperseg=256)[1]
    >>> bool(np.allclose(s.s_xy[:, 0, 0], ref)), s.n_segments
    (True, 38)
    """

    #: Segments per ``csd`` call.
    BLOCK_SEGMENTS = 16

    def __init__(self, n_inputs: int, n_outputs: int, sample_rate_Hz: float, nperseg: int, heights=None):
        self.q = positive_int("n_inputs", n_inputs)
        h = np.zeros(self.q, bool) if heights is None else np.asarray(heights, dtype=bool).reshape(-1)
        if h.size != self.q:
            raise ValueError(f"heights must flag each of the {self.q} inputs, got {h.size}")
        self.heights = h
        self._carry = None
        self.p = positive_int("n_outputs", n_outputs, minimum=0)
        self.fs = positive("sample_rate_Hz", sample_rate_Hz)
        self.nperseg = positive_int("nperseg", nperseg, minimum=8)
        self.step = self.nperseg // 2
        self._buf = np.empty((self.q + self.p, 0))
        self._sxz = None
        self._syy = None
        self.n_segments = 0
        self.n_samples = 0

    def add(self, inputs, outputs) -> None:
        """Append samples: ``inputs`` (q, n), ``outputs`` (p, n)."""
        x = np.atleast_2d(np.asarray(inputs, dtype=float))
        y = np.asarray(outputs, dtype=float).reshape(self.p, -1)
        if x.shape[0] != self.q or y.shape[1] != x.shape[1]:
            raise ValueError(f"inputs must be ({self.q}, n) and outputs ({self.p}, n), got {x.shape} and {y.shape}")
        block = self.nperseg + (self.BLOCK_SEGMENTS - 1) * self.step
        for i in range(0, x.shape[1], block):  # a block at a time: no copy of a whole chunk
            self._add(np.vstack([x[:, i:i + block], y[:, i:i + block]]))

    def _add(self, z: np.ndarray) -> None:
        self.n_samples += z.shape[1]
        if self.heights.any():  # second difference of the heights, the other channels one sample late
            z = z if self._carry is None else np.concatenate([self._carry, z], axis=1)
            if z.shape[1] < 3:
                self._carry = z
                return
            self._carry = z[:, -2:]
            mid = z[:, 1:-1].copy()
            hh = z[:self.q][self.heights]
            mid[:self.q][self.heights] = (hh[:, 2:] - 2 * hh[:, 1:-1] + hh[:, :-2]) * self.fs ** 2
            z = mid
        self._buf = np.concatenate([self._buf, z], axis=1)
        block = self.nperseg + (self.BLOCK_SEGMENTS - 1) * self.step
        while self._buf.shape[1] >= block:
            self._take(self._buf[:, :block], self.BLOCK_SEGMENTS)
            self._buf = self._buf[:, self.BLOCK_SEGMENTS * self.step:]

    def _take(self, z: np.ndarray, k: int) -> None:
        kw = dict(fs=self.fs, nperseg=self.nperseg, noverlap=self.nperseg - self.step)
        _, sxz = signal.csd(z[:self.q, None, :], z[None, :, :], **kw)  # (q, q + p, F)
        sxz = sxz * k
        syy = signal.welch(z[self.q:], **kw)[1] * k if self.p else np.zeros((0, sxz.shape[-1]))
        if self._sxz is None:
            self._sxz, self._syy = sxz, syy
        else:
            self._sxz += sxz
            self._syy += syy
        self.n_segments += k

    def finish(self) -> CrossSpectra:
        """The averaged matrices (the whole segments of what is left taken first).

        Raises
        ------
        ValueError
            Fewer samples than one segment.
        """
        rest = self._buf.shape[1]
        if rest >= self.nperseg:
            k = (rest - self.nperseg) // self.step + 1
            self._take(self._buf[:, :self.nperseg + (k - 1) * self.step], k)
        self._buf = np.empty((self.q + self.p, 0))
        if not self.n_segments:
            raise ValueError(f"recording has {self.n_samples} samples, fewer than one segment of {self.nperseg} "
                             f"({self.nperseg / self.fs:.3g} s)")
        f = np.fft.rfftfreq(self.nperseg, 1.0 / self.fs)
        sxz = np.moveaxis(self._sxz / self.n_segments, -1, 0)  # (F, q, q + p)
        s_xx = sxz[:, :, :self.q]
        s_xx = 0.5 * (s_xx + np.conj(np.swapaxes(s_xx, 1, 2)))  # Hermitian to the last bit
        s_xy = sxz[:, :, self.q:]
        if self.heights.any():
            c = np.where(self.heights[None, :], second_difference_correction(f, self.fs)[:, None], 1.0)  # (F, q)
            s_xx = s_xx * c[:, :, None] * c[:, None, :]
            s_xy = s_xy * c[:, :, None]
        return CrossSpectra(f, s_xx, s_xy, (self._syy / self.n_segments).T, self.n_segments,
                            self.n_samples / self.nperseg, self.fs, self.nperseg)


def cross_spectra(inputs, outputs, sample_rate_Hz: float, nperseg: int | None = None, heights=None) -> CrossSpectra:
    """:class:`CrossSpectra` of whole arrays: ``inputs`` (q, n), ``outputs`` (p, n).

    ``nperseg`` defaults to :func:`segment_samples`; ``heights`` as for :class:`CrossSpectraAccumulator`.

    See Also
    --------
    mimo_frf : the FRFs from these spectra.
    segment_samples : the default segment length.

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> x = rng.standard_normal((2, 4096)); y = 2.0 * x[:1] - x[1:]
    >>> s = cross_spectra(x, y, 100.0, 256)
    >>> e = mimo_frf(s)
    >>> np.round(np.abs(e.h[10, 0]), 6).tolist()       # output 0 from inputs 0 and 1
    [2.0, 1.0]
    """
    x = np.atleast_2d(np.asarray(inputs, dtype=float))
    y = np.asarray(outputs, dtype=float)
    y = y.reshape(-1, x.shape[1]) if y.size else np.empty((0, x.shape[1]))
    acc = CrossSpectraAccumulator(x.shape[0], y.shape[0], sample_rate_Hz,
                                  nperseg or segment_samples(sample_rate_Hz), heights)
    acc.add(x, y)
    return acc.finish()


def second_difference_correction(frequency_Hz, sample_rate_Hz: float) -> np.ndarray:
    """Factor turning the spectrum of a second difference ``(h[n+1] - 2 h[n] + h[n-1]) fs²`` into
    that of the second derivative: ``(2πf)² / (4 fs² sin²(πf/fs))`` (1 at 0 Hz).

    See Also
    --------
    recording_frf : corrects a height input's differentiation with it.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(second_difference_correction([0.0, 1.0, 12.0], 50.0), 4)
    array([1.    , 1.0013, 1.2132])
    """
    f = np.asarray(frequency_Hz, dtype=float)
    fs = positive("sample_rate_Hz", sample_rate_Hz)
    with np.errstate(invalid="ignore", divide="ignore"):
        c = (2 * np.pi * f) ** 2 / (4 * fs ** 2 * np.sin(np.pi * f / fs) ** 2)
    return np.where(f > 0, c, 1.0)


@dataclass
class MimoFrf:
    """The multi-input FRF estimate of :func:`mimo_frf`; arrays per bin (F), output (p), input (q).

    Attributes
    ----------
    frequency_Hz : (F,)
    h : (F, p, q) complex
        ``H1 = S_yx S_xx⁻¹``: output unit per input unit.
    h2 : (F, p, q) complex or None
        With one input, ``H2 = S_yy / S_yx``; else None.
    coherence : (F, p, q)
        Ordinary coherence ``|S_xy|² / (S_xx S_yy)``.
    partial_coherence : (F, p, q)
        Coherence of input i and the output conditioned on the other inputs.
    multiple_coherence : (F, p)
    random_error : (F, p, q)
        Normalised random error of ``|H|`` (B&P eq. 9.90, n_d − q dof).
    condition_number : (F,)
        Of the inputs' coherence matrix (``S_xx`` scaled to a unit diagonal: independent of the
        inputs' units and levels).
    input_coherence : (F, q)
        Multiple coherence of each input with the other inputs.
    ill_conditioned : (F, q) bool
        ``input_coherence >= MAX_INPUT_COHERENCE``, or ``delay_coherence >= MAX_INPUT_COHERENCE`` where
        the input is another's delayed (:func:`input_delays`), or a bin without input power.
    n_d : float
    delay_coherence : (F, q)
        Largest coherence of the input with another input once aligned by their delay
        (:func:`input_delays`; NaN with one input).
    input_delay_s : (q,)
        The delay of the input behind (+) or ahead of (-) the input it is delay-related with
        (:func:`input_delays`), NaN where none is.
    """

    frequency_Hz: np.ndarray
    h: np.ndarray
    h2: np.ndarray | None
    coherence: np.ndarray
    partial_coherence: np.ndarray
    multiple_coherence: np.ndarray
    random_error: np.ndarray
    condition_number: np.ndarray
    input_coherence: np.ndarray
    ill_conditioned: np.ndarray
    n_d: float
    delay_coherence: np.ndarray | None = None
    input_delay_s: np.ndarray | None = None


#: Least correlation of the Welch window with itself shifted by an inputs' delay at which the delay is
#: sought (:func:`input_delays`): delays up to about a third of a Hann segment (0.32 N). A delay-related
#: pair's Welch coherence is this squared (0.25) times its aligned coherence; a longer delay leaves the
#: segments' inputs nearly independent (each segment sees the two inputs' different stretches of road).
MIN_WINDOW_OVERLAP = 0.5


#: Bins over which a delay-related pair's aligned coherence is averaged before it is compared with
#: :data:`MAX_INPUT_COHERENCE` (:func:`input_delays`).
DELAY_SMOOTH_BINS = 5


def _window_overlap(nperseg: int, lag: np.ndarray) -> np.ndarray:
    """``Σ w[n] w[n + d] / Σ w²`` of the Hann window of ``csd``/``welch`` at lags ``d`` (samples)."""
    w = signal.get_window("hann", nperseg)
    full = np.correlate(w, w, "full")[nperseg - 1:] / np.dot(w, w)
    d = np.minimum(np.abs(np.asarray(lag, dtype=int)), nperseg - 1)
    return full[d]


def input_delays(spectra: CrossSpectra, band_Hz: tuple[float, float] = FIT_BAND_Hz,
                 min_overlap: float = MIN_WINDOW_OVERLAP) -> tuple[np.ndarray, np.ndarray]:
    """Pairs of inputs of which one is the other delayed (road input: each rear wheel its front's
    signal a wheelbase later), which a Welch estimate does not see as coherent.

    Within a segment of length ``T`` a delay ``τ`` leaves only the window's overlap with itself
    shifted, ``ρ(τ) = Σ w[n] w[n+τ] / Σ w²``, of the two inputs' common stretch: their Welch coherence
    is ``ρ(τ)²`` times their coherence once aligned (B&P §9.1.4, the time-delay bias of spectral
    estimates; 0.77 for a 1.46 s delay in 10.24 s Hann segments), so ``S_xx`` looks well conditioned
    while the inputs cannot be separated. The delay of each pair is the peak of its generalised
    cross-correlation (the inverse transform of the coherency ``S_ij / sqrt(S_ii S_jj)``, Knapp &
    Carter 1976) within the lags where ``ρ ≥ min_overlap``; the aligned coherence is
    ``min(1, γ²_ij / ρ(τ)²)``. A pair is delay-related where the median of its aligned coherence over
    the bins of ``band_Hz`` with input power reaches :data:`MAX_INPUT_COHERENCE`; its aligned coherence
    is then averaged over :data:`DELAY_SMOOTH_BINS` bins (one bin's estimate scatters: 0.81-1 for a pure
    delay of 14 % of a segment).

    Returns
    -------
    delay_coherence : (F, q)
        Each input's largest aligned coherence with a delay-related input, averaged over
        :data:`DELAY_SMOOTH_BINS` bins (0 where none is; NaN with one input).
    delay_s : (q,)
        Its delay behind (+) that input, NaN where none is.

    See Also
    --------
    mimo_frf : flags these inputs ``ill_conditioned``.

    Examples
    --------
    A rear input that is the front one 1.46 s later (6 km/h over a 2.44 m wheelbase), 10.24 s segments:

    >>> import numpy as np
    >>> rng = np.random.default_rng(3)
    >>> x = rng.standard_normal(60_000)
    >>> lag = 73                                              # 1.46 s at 50 Hz
    >>> s = cross_spectra(np.vstack([x[lag:], x[:-lag]]), x[None, lag:], 50.0, 512)
    >>> coh, delay = input_delays(s)
    >>> band = (s.frequency_Hz > 0.5) & (s.frequency_Hz < 12)
    >>> np.round(delay, 2).tolist(), bool(coh[band].min() > 0.9), bool(mimo_frf(s).ill_conditioned[band].all())
    ([-1.46, 1.46], True, True)
    """
    f = spectra.frequency_Hz
    s_xx = spectra.s_xx
    nf, q, _ = s_xx.shape
    delay = np.full(q, np.nan)
    if q < 2:
        return np.full((nf, q), np.nan), delay
    nperseg = int(spectra.nperseg or 2 * (nf - 1))
    fs = float(spectra.sample_rate_Hz)
    dx = np.real(np.einsum("fii->fi", s_xx))
    powered = np.all(dx > 1e-12 * np.max(dx, axis=0, keepdims=True), axis=1) & (dx.min(axis=1) > 0)
    band = powered & (f >= band_Hz[0]) & (f <= band_Hz[1])
    lags = np.arange(nperseg)
    lags = np.where(lags > nperseg // 2, lags - nperseg, lags)
    rho = _window_overlap(nperseg, lags)
    allowed = rho >= min_overlap
    out = np.zeros((nf, q))
    best = np.zeros(q)
    if band.sum() < 3:
        return out, delay
    for i in range(q):
        for j in range(i + 1, q):
            with np.errstate(invalid="ignore", divide="ignore"):
                coherency = np.where(powered, s_xx[:, i, j] / np.sqrt(dx[:, i] * dx[:, j]), 0.0)
            r = np.fft.irfft(coherency, n=nperseg)  # peak at the lag of j behind i (csd: conj(X_i) X_j)
            k = int(np.argmax(np.where(allowed, np.abs(r), -1.0)))
            gamma2 = np.abs(coherency) ** 2
            aligned = np.minimum(gamma2 / rho[k] ** 2, 1.0)
            if lags[k] == 0 or np.median(aligned[band]) < MAX_INPUT_COHERENCE:
                continue  # no delay, or not a delay relation (a zero lag is input_coherence's)
            score = float(np.median(aligned[band]))
            # a bin's estimate scatters (the delayed stretch outside the window is noise to it): the
            # mean over DELAY_SMOOTH_BINS bins, so a delay-related pair is flagged in every bin it holds
            smooth = ndimage.uniform_filter1d(np.where(powered, aligned, 0.0), DELAY_SMOOTH_BINS, mode="nearest")
            for a, sign in ((i, -1.0), (j, 1.0)):
                out[:, a] = np.maximum(out[:, a], np.where(powered, smooth, 0.0))
                if score > best[a]:
                    best[a], delay[a] = score, sign * lags[k] / fs
    return out, delay


def mimo_frf(spectra: CrossSpectra, max_input_coherence: float = MAX_INPUT_COHERENCE) -> MimoFrf:
    """H1 = S_yx S_xx⁻¹ per output with its coherences, random error and conditioning.

    Bins without input power (DC, after a height's differentiation) or whose ``S_xx`` is
    singular give NaN and are flagged.

    See Also
    --------
    cross_spectra : the spectra it takes.
    fit_vehicle_modes : the modes of its FRFs.

    Examples
    --------
    One input: H1 and H2 agree when the output is noise-free.

    >>> import numpy as np
    >>> rng = np.random.default_rng(2)
    >>> x = rng.standard_normal((1, 8192)); y = 3.0 * x
    >>> e = mimo_frf(cross_spectra(x, y, 100.0, 512))
    >>> round(float(abs(e.h[5, 0, 0])), 6), round(float(abs(e.h2[5, 0, 0])), 6), round(float(e.coherence[5, 0, 0]), 6)
    (3.0, 3.0, 1.0)
    """
    s_xx, s_xy, s_yy = spectra.s_xx, spectra.s_xy, spectra.s_yy
    nf, q, _ = s_xx.shape
    p = s_xy.shape[2]
    with np.errstate(invalid="ignore", divide="ignore"):
        dx = np.real(np.einsum("fii->fi", s_xx))  # (F, q)
        ok = np.all(dx > 1e-300 * max(1.0, float(np.nanmax(dx)) if dx.size else 1.0), axis=1) & np.all(s_yy >= 0, axis=1)
        scale = np.where(ok[:, None], 1.0 / np.sqrt(np.where(dx > 0, dx, 1.0)), np.nan)
        r = s_xx * scale[:, :, None] * scale[:, None, :]  # coherence (correlation) matrix, unit diagonal
        eye = np.eye(q)
        r_safe = np.where(ok[:, None, None], r, eye)
        sv = np.linalg.svd(r_safe, compute_uv=False)
        cond = np.where(ok & (sv[:, -1] > 0), sv[:, 0] / np.where(sv[:, -1] > 0, sv[:, -1], 1.0), np.inf)
        finite = ok & (cond < 1e12)
        r_use = np.where(finite[:, None, None], r, eye)
        r_inv = np.linalg.inv(r_use)
        # multiple coherence of input i with the others: 1 - 1 / (R⁻¹)_ii
        vif = np.real(np.einsum("fii->fi", r_inv))
        input_coherence = np.where(finite[:, None], 1.0 - 1.0 / vif, 1.0) if q > 1 else np.zeros((nf, 1))
        # H^T = S_xx⁻¹ S_xy
        s_xx_use = np.where(finite[:, None, None], s_xx, eye)
        ht = np.linalg.solve(s_xx_use, s_xy)  # (F, q, p)
        h = np.where(finite[:, None, None], np.swapaxes(ht, 1, 2), np.nan)
        # ordinary coherence
        coh = np.abs(s_xy) ** 2 / (dx[:, :, None] * s_yy[:, None, :])  # (F, q, p)
        coh = np.swapaxes(np.where(finite[:, None, None], np.clip(coh, 0, 1), np.nan), 1, 2)
        # multiple coherence: S_xy^H S_xx⁻¹ S_xy / S_yy
        explained = np.real(np.einsum("fik,fik->fk", np.conj(s_xy), ht))
        mult = np.where(finite[:, None], np.clip(explained / s_yy, 0, 1), np.nan)
        # partial coherence of (x_i, y_k) given the other inputs, from the inverse of the
        # (q+1)x(q+1) matrix of [x; y_k]: |C_iy|² / (C_ii C_yy)
        partial = np.full((nf, p, q), np.nan)
        if q == 1:
            partial[:, :, 0] = coh[:, :, 0]
        else:
            for k in range(p):
                g = np.empty((nf, q + 1, q + 1), complex)
                g[:, :q, :q] = s_xx_use
                g[:, :q, q] = s_xy[:, :, k]
                g[:, q, :q] = np.conj(s_xy[:, :, k])
                g[:, q, q] = np.where(finite, s_yy[:, k], 1.0)
                g = np.where(finite[:, None, None], g, np.eye(q + 1))
                try:
                    c = np.linalg.inv(g)
                except np.linalg.LinAlgError:
                    c = np.linalg.pinv(g)
                cd = np.real(np.einsum("fii->fi", c))
                pc = np.abs(c[:, :q, q]) ** 2 / (cd[:, :q] * cd[:, q:q + 1])
                partial[:, k, :] = np.where(finite[:, None], np.clip(pc, 0, 1), np.nan)
        dof = spectra.n_d - q
        if dof <= 0:
            raise ValueError(f"n_d = {spectra.n_d:.3g} independent averages for {q} inputs: the random error needs "
                             f"n_d > q (a longer recording)")
        err = np.sqrt((1.0 - mult[:, :, None]) / (2.0 * dof * partial))
        h2 = None
        if q == 1:
            h2 = np.where(finite[:, None, None], (s_yy / np.conj(s_xy[:, 0, :]))[:, :, None], np.nan)
    delay_coherence, delay_s = input_delays(spectra)
    ill = ~finite[:, None] | (input_coherence >= max_input_coherence)
    if q > 1:
        ill |= delay_coherence >= max_input_coherence
    return MimoFrf(spectra.frequency_Hz, h, h2, coh, partial, mult, err, cond, input_coherence, ill, spectra.n_d,
                   delay_coherence, delay_s)


def wheel_excitation_mask(frequency_Hz, speed_km_h: float, wheels, harmonics: int = MASK_HARMONICS,
                          half_width: float = MASK_HALF_WIDTH) -> np.ndarray:
    """Bins near each rolling wheel's rotation frequency (and harmonics) and lug-passing frequencies.

    Parameters
    ----------
    frequency_Hz : array
        The bins.
    speed_km_h : float
        0 (stationary: nothing masked) or the rolling speed.
    wheels : iterable of (circumference_m, lugs_per_side)
        Each wheel's rolling circumference and lugs on one side (0: ribbed, no lug band).
    harmonics : int
        Rotation harmonics masked (1 = the rotation frequency only).
    half_width : float
        Half width of a masked band relative to its centre (at least one bin either side).

    Returns
    -------
    ndarray of bool
        True where masked (§2.4.5).

    See Also
    --------
    scenario_wheel_geometry : a scenario's wheels.
    recording_frf : masks a rolling recording's bins with it.

    Examples
    --------
    >>> import numpy as np
    >>> f = np.arange(0, 20, 0.125)
    >>> m = wheel_excitation_mask(f, 6.0, [(4.66, 23)])  # rotation 0.358 Hz, lugs 4.1 and 8.2 Hz
    >>> bool(m[f == 8.25][0]), bool(m[f == 4.0][0]), bool(m[f == 6.0][0]), bool(m[f == 0.375][0])
    (True, True, False, True)
    """
    f = np.asarray(frequency_Hz, dtype=float)
    mask = np.zeros(f.shape, dtype=bool)
    if speed_km_h is None or not speed_km_h > 0:
        return mask
    v = km_h_to_m_s(float(speed_km_h))
    df = float(np.median(np.diff(f))) if f.size > 1 else 0.0
    centres = []
    for circumference_m, lugs in wheels:
        rot = v / positive("circumference_m", circumference_m)
        centres += [k * rot for k in range(1, int(harmonics) + 1)]
        if lugs:
            centres += [0.5 * lugs * rot, lugs * rot]
    for c in centres:
        mask |= np.abs(f - c) <= max(half_width * c, 1.01 * df)
    return mask


@dataclass
class VehicleMode:
    """One fitted mode: damped frequency, damping ratio and their 95 % intervals.

    ``determined`` is False where the data cannot place the mode (``undetermined_reason`` says why: its
    interval reaches the fit's bounds, is wider than its frequency, or holds another fitted pole, the
    two then not resolved); its numbers are then the fit's, not a measurement. The undamped natural
    frequency ``|λ| / 2π`` (:attr:`natural_frequency_Hz`) with its interval is better determined than
    the damped one for a heavily damped mode (``f_d = f_n sqrt(1 − ζ²)``: at ζ 0.8 an error of 0.01 in
    ζ moves ``f_d`` by 2.2 %)."""

    frequency_Hz: float
    damping_ratio: float
    frequency_low_Hz: float
    frequency_high_Hz: float
    damping_low: float
    damping_high: float
    inputs: tuple = field(default_factory=tuple)
    natural_frequency_low_Hz: float = math.nan
    natural_frequency_high_Hz: float = math.nan
    determined: bool = True
    undetermined_reason: str = ""

    @property
    def natural_frequency_Hz(self) -> float:
        """Undamped natural frequency ``f_d / sqrt(1 − ζ²)``, Hz."""
        return self.frequency_Hz / math.sqrt(max(1.0 - self.damping_ratio ** 2, 1e-12))


def _basis(w: np.ndarray, fd: np.ndarray, zeta: np.ndarray) -> np.ndarray:
    """Complex basis (n, 2R + 4) of the pole-residue model at ``s = jω``: per mode the real and
    imaginary parts of a residue pair, then a complex constant (the upper residual) and a complex
    ``1/s²`` (the lower residual: a body-fixed accelerometer's gravity component ``g φ`` or ``g θ``
    per input acceleration is ``g (Φ/U) / s²``, a double pole at 0 Hz, since the static tilt per
    ground height ``Φ/U`` is finite; without it the poles bend to fit it)."""
    wd = 2 * np.pi * fd
    wn = wd / np.sqrt(1 - zeta ** 2)
    pole = -zeta * wn + 1j * wd
    s = 1j * w[:, None]
    a = 1.0 / (s - pole[None, :])
    b = 1.0 / (s - np.conj(pole)[None, :])
    cols = [a + b, 1j * (a - b)]
    low = 1.0 / s[:, :1] ** 2
    return np.concatenate([*cols, np.ones((w.size, 1)), 1j * np.ones((w.size, 1)), low, 1j * low], axis=1)


def _projected(params: np.ndarray, w, h, wt) -> np.ndarray:
    """Weighted residuals of the best linear residues for the poles ``params`` (fd, ζ pairs), every
    input's least-squares problem solved at once (normal equations of the column-scaled basis)."""
    r = params.size // 2
    phi = _basis(w, params[:r], params[r:])  # (n, k)
    a = phi[None, :, :] * wt.T[:, :, None]  # (m, n, k)
    a = np.concatenate([a.real, a.imag], axis=1)  # (m, 2n, k)
    b = (h * wt).T
    b = np.concatenate([b.real, b.imag], axis=1)[:, :, None]  # (m, 2n, 1)
    norm = np.sqrt((a * a).sum(axis=1))
    norm[norm == 0] = 1.0
    a = a / norm[:, None, :]
    at = np.swapaxes(a, 1, 2)
    coef = np.linalg.solve(at @ a + 1e-12 * np.eye(a.shape[2]), at @ b)
    return (a @ coef - b).reshape(-1)


def fit_vehicle_modes(frequency_Hz, h, sigma, usable=None, max_modes: int = MAX_MODES,
                      band_Hz: tuple[float, float] = FIT_BAND_Hz) -> list[VehicleMode]:
    """Modes (damped frequency, damping ratio, 95 % intervals) of one output's FRFs from several inputs.

    Parameters
    ----------
    frequency_Hz : (F,)
    h : (F, m) complex
        The output's FRF from each of ``m`` inputs.
    sigma : (F, m)
        Standard error of each ``|H|`` (``random_error * |H|``); the fit's weights.
    usable : (F, m) bool, optional
        Bins to fit (unmasked, separable, coherent); the band ``band_Hz`` is applied too.
    max_modes : int
    band_Hz : (low, high)

    Returns
    -------
    list of VehicleMode
        By frequency; empty when too few bins are usable.

    See Also
    --------
    recording_frf : the FRFs and modes of a recording.
    mimo_frf : the FRFs it fits.

    Examples
    --------
    >>> import numpy as np
    >>> f = np.arange(0.5, 12, 0.125); s = 2j * np.pi * f
    >>> wn = 2 * np.pi * 1.6; zeta = 0.25
    >>> h = ((wn ** 2 + 2 * zeta * wn * s) / (s ** 2 + 2 * zeta * wn * s + wn ** 2))[:, None]
    >>> m = fit_vehicle_modes(f, h, np.full(h.shape, 0.01))
    >>> len(m), round(float(m[0].frequency_Hz / np.sqrt(1 - zeta ** 2)), 3), round(m[0].damping_ratio, 3)
    (1, 1.6, 0.25)
    """
    f = np.asarray(frequency_Hz, dtype=float)
    h = np.asarray(h, dtype=complex).reshape(f.size, -1)
    sig = np.asarray(sigma, dtype=float).reshape(h.shape)
    use = np.ones(h.shape, bool) if usable is None else np.asarray(usable, bool).reshape(h.shape)
    lo, hi = band_Hz
    use = use & ((f >= lo) & (f <= hi))[:, None] & np.isfinite(h) & np.isfinite(sig) & (sig > 0)
    cols = [j for j in range(h.shape[1]) if use[:, j].sum() >= 8]
    if not cols:
        return []
    rows = use[:, cols].any(axis=1)
    f, h, sig, use = f[rows], h[rows][:, cols], sig[rows][:, cols], use[rows][:, cols]
    w = 2 * np.pi * f
    floor = 1e-3 * np.nanmax(np.abs(np.where(use, h, 0)))
    wt = np.where(use, 1.0 / np.maximum(sig, floor if floor > 0 else 1e-12), 0.0)
    h0 = np.where(use, h, 0)
    n_obs = 2 * int(use.sum())
    fmin, fmax = max(lo, f.min()), min(hi, f.max())
    df = float(np.median(np.diff(f))) if f.size > 1 else 0.0
    lower, upper = [fmin, DAMPING_BOUNDS[0]], [fmax, DAMPING_BOUNDS[1]]
    best = None  # (bic, params, least-squares result, parameters)
    prev = np.empty(0)
    for r in range(1, max_modes + 1):
        n_par = 2 * r + len(cols) * (2 * r + 4)
        if n_par >= n_obs - 2:
            break
        resid = _projected(prev, w, h0, wt) if prev.size else None
        lb, ub = np.repeat(lower, r), np.repeat(upper, r)
        trial = None
        accepted = False
        # the largest residual peak first; the other candidates only when it gives no acceptable fit
        for fc in _candidates(f, h0, wt, resid, len(cols)):
            x0 = np.clip(np.concatenate([prev[:r - 1], [fc], prev[r - 1:], [0.15]]), lb, ub)
            try:
                res = optimize.least_squares(_projected, x0, args=(w, h0, wt), method="trf", bounds=(lb, ub),
                                             x_scale=np.repeat([1.0, 0.1], r), max_nfev=100, ftol=1e-6, xtol=1e-6)
            except (ValueError, np.linalg.LinAlgError):
                continue
            # a pole at a bound or contributing nothing stands for noise or what lies outside the band
            if not _all_modes(res.x, w, h0, wt, lb, ub):
                continue
            bic = n_obs * math.log(max(2 * res.cost, 1e-300) / n_obs) + n_par * math.log(n_obs)
            if trial is None or res.cost < trial.cost:
                trial, trial_bic = res, bic
            if best is None or bic < best[0]:
                accepted = True
                break
        if not accepted:
            break
        bic = trial_bic
        best = (bic, trial.x.copy(), trial, n_par)
        order = np.argsort(trial.x[:r])
        prev = np.concatenate([trial.x[:r][order], trial.x[r:][order]])
    if best is None:
        return []
    _, x, res, n_par = best
    return _modes_of(x, res, n_obs, n_par, df, [tuple(cols)] * (x.size // 2))


def _modes_of(x, res, n_obs: int, n_par: int, df: float, inputs, sort: bool = True) -> list[VehicleMode]:
    """The modes of a converged fit ``res`` (poles ``x``: fd then ζ), 95 % intervals from its Jacobian;
    by frequency, or with ``sort=False`` in the order of ``x``."""
    r = x.size // 2
    dof = max(n_obs - n_par, 1)
    s2 = 2 * res.cost / dof
    jac = res.jac
    cov = np.linalg.pinv(jac.T @ jac) * s2
    k = float(student_t.ppf(0.975, dof))
    modes = []
    for i in range(r):
        fd, z = float(x[i]), float(x[r + i])
        # the statistical standard errors with the resolution's: the bin width as a rectangular
        # uncertainty of the frequency (df / sqrt(12)), in quadrature; and the damping's bias, one-sided
        # (the estimate is broadened): the Welch estimate is the FRF smoothed by the Hann window's
        # spectral kernel |W|², of variance df² / 3 (∫w'² / ∫w² / (2π)², w the Hann window, df = 1/T),
        # which widens a resonance of half-power half-width ζ f_n by that variance over it: ζ by
        # df² / (3 ζ f_n²) (to second order; Bendat & Piersol eq. 8.141 with the kernel's own variance
        # for their B_e² / 12). The interval's lower end holds it: pitch of the virtual stand, 4.56 Hz,
        # ζ 0.030, 0.049 Hz bins: 0.0013 (fitted +0.001 to +0.002 over six seeds)
        fn0 = fd / math.sqrt(1 - z * z)
        res_f = df ** 2 / 12
        bias_z = min(df ** 2 / (3 * max(z, 1e-6) * fn0 ** 2), z)
        res_z = (bias_z / math.sqrt(3)) ** 2  # for the natural frequency's interval: rectangular on [0, bias]
        uf = math.sqrt(max(cov[i, i], 0.0) + res_f)
        uz = math.sqrt(max(cov[r + i, r + i], 0.0))
        # f_n = f_d / sqrt(1 - ζ²) to first order (the delta method) with the same resolution terms
        c = 1.0 / math.sqrt(1 - z * z)
        g = np.array([c, fd * z * c ** 3])
        sub = cov[np.ix_([i, r + i], [i, r + i])]
        un = math.sqrt(max(float(g @ sub @ g), 0.0) + c * c * res_f + (g[1] ** 2) * res_z)
        fn = fd * c
        modes.append(VehicleMode(fd, z, fd - k * uf, fd + k * uf, max(z - k * uz - bias_z, 0.0), z + k * uz,
                                 inputs[i], fn - k * un, fn + k * un))
    return sorted(modes, key=lambda m: m.frequency_Hz) if sort else modes


#: Damping ratio from which a mode's FRF magnitude has no resonance peak (``1/√2``: a single mode's
#: ``|H|`` peaks only below it): a fitted pole whose 95 % damping interval reaches it is not a mode the
#: recording determines (the rolling tyre's lateral–roll and yaw at 11 km/h, 80 and 76 % damped 0.5 Hz
#: apart, are fitted as one pole 15-18 % above the lateral–roll's damped frequency, its profile interval
#: ±4-6 %: six seeds of the virtual stand, still and correlated).
NO_PEAK_DAMPING = 1 / math.sqrt(2)


#: Steps of a profile of the fit's cost each way from a pole's fitted frequency or damping
#: (:func:`_profile_mode`; each twice the last, the first the Jacobian's standard error): up to 63
#: standard errors.
PROFILE_STEPS = 6


def _profile_mode(md: VehicleMode, i: int, res, w, h, wt, lb, ub, dof: int) -> VehicleMode:
    """``md`` (pole ``i`` of the fit ``res``) with 95 % intervals from the profile of the fit's cost.

    Each of the pole's damped frequency and damping ratio is stepped away from its fitted value, the
    other poles and the pole's other parameter fitted again at each step (the residues by the variable
    projection), until the cost rises by ``t² s² / 2`` (``t`` the 97.5 % point of Student's t on the
    fit's ``dof``, ``s²`` the residual variance: the likelihood-ratio interval, exact where the cost is
    quadratic, honest where it is not). An interval reaching a bound of the fit (the band's edge, a
    damping bound) or :data:`PROFILE_STEPS` steps marks the mode undetermined. The result holds the
    Jacobian's interval too; the natural frequency's interval holds every profiled point within the
    threshold."""
    x = res.x
    r = x.size // 2
    cost0 = float(res.cost)
    thr = 0.5 * (2 * cost0 / max(dof, 1)) * float(student_t.ppf(0.975, max(dof, 1))) ** 2
    k = float(student_t.ppf(0.975, max(dof, 1)))
    scale = np.repeat([1.0, 0.1], r)
    fn_points = [md.natural_frequency_Hz]
    limits = {}
    reason = ""
    for p_idx, se in ((i, (md.frequency_high_Hz - md.frequency_low_Hz) / (2 * k)),
                      (r + i, (md.damping_high - md.damping_low) / (2 * k))):
        free = np.array([n for n in range(2 * r) if n != p_idx])
        flo, fhi = lb[free], ub[free]
        for d in (-1.0, 1.0):
            theta, cur, prev = float(x[p_idx]), x[free].copy(), 0.0
            step = max(se, 1e-3 * (ub[p_idx] - lb[p_idx]))
            limit = None
            for _ in range(PROFILE_STEPS):
                new = float(np.clip(theta + d * step, lb[p_idx], ub[p_idx]))

                def fun(z, new=new):
                    xx = x.copy()
                    xx[free] = z
                    xx[p_idx] = new
                    return _projected(xx, w, h, wt)

                try:
                    fit = optimize.least_squares(fun, np.clip(cur, flo + 1e-9 * (fhi - flo), fhi - 1e-9 * (fhi - flo)),
                                                 method="trf", bounds=(flo, fhi), x_scale=scale[free], max_nfev=60,
                                                 ftol=1e-6, xtol=1e-6)
                except (ValueError, np.linalg.LinAlgError):
                    break
                delta = float(fit.cost) - cost0
                if delta > thr:
                    frac = (thr - prev) / (delta - prev) if delta > prev else 1.0
                    limit = theta + (new - theta) * min(max(frac, 0.0), 1.0)
                    break
                cur, theta, prev = fit.x, new, max(delta, 0.0)
                xx = x.copy()
                xx[free], xx[p_idx] = fit.x, new
                fn_points.append(float(xx[i] / math.sqrt(max(1 - xx[r + i] ** 2, 1e-12))))
                if new <= lb[p_idx] or new >= ub[p_idx]:
                    break
                step *= 2.0
            if limit is None:
                limit = theta
                which = "frequency" if p_idx == i else "damping ratio"
                reason = reason or f"the 95 % interval of its {which} reaches the fit's bound: the data do not place it"
            limits[(p_idx, d)] = limit
    return dataclasses.replace(
        md, frequency_low_Hz=max(min(md.frequency_low_Hz, limits[(i, -1.0)]), 0.0),
        frequency_high_Hz=max(md.frequency_high_Hz, limits[(i, 1.0)]),
        damping_low=max(min(md.damping_low, limits[(r + i, -1.0)]), 0.0),
        damping_high=max(md.damping_high, limits[(r + i, 1.0)]),
        natural_frequency_low_Hz=min(md.natural_frequency_low_Hz, min(fn_points)),
        natural_frequency_high_Hz=max(md.natural_frequency_high_Hz, max(fn_points)),
        determined=md.determined and not reason, undetermined_reason=md.undetermined_reason or reason)


def _flag_undetermined(fitted: list[VehicleMode], shown, band_Hz) -> list[VehicleMode]:
    """``fitted`` with the modes the data cannot place marked (:attr:`VehicleMode.determined`): among the
    poles ``shown``, a frequency interval wider than the mode's frequency, a damping interval reaching
    :data:`NO_PEAK_DAMPING`, or intervals (frequency and damping) holding another shown pole: the two not
    resolved.

    Examples
    --------
    >>> m = VehicleMode(1.15, 0.75, 1.10, 1.21, 0.72, 0.78)
    >>> out = _flag_undetermined([m, VehicleMode(4.2, 0.24, 4.18, 4.23, 0.23, 0.25)], [0, 1], (0.5, 12.0))
    >>> [o.determined for o in out], out[0].undetermined_reason[:23]
    ([False, True], 'damped up to 0.78 of cr')
    """
    out = list(fitted)
    for i in shown:
        md = out[i]
        if not md.determined:
            continue
        reason = ""
        if md.frequency_high_Hz - md.frequency_low_Hz > md.frequency_Hz:
            reason = "its 95 % frequency interval is wider than its frequency"
        elif md.damping_high >= NO_PEAK_DAMPING:
            reason = (f"damped up to {md.damping_high:.2f} of critical (95 % interval), beyond 1/√2 = 0.71 where a "
                      "mode has no resonance peak: a pole this damped stands for whatever overlapping modes lie in "
                      "its band, which the data do not resolve")
        else:
            other = [fitted[j] for j in shown if j != i and md.frequency_low_Hz <= fitted[j].frequency_Hz
                     <= md.frequency_high_Hz and md.damping_low <= fitted[j].damping_ratio <= md.damping_high]
            if other:
                reason = (f"its 95 % intervals hold the mode at {other[0].frequency_Hz:.3g} Hz: the two poles are "
                          "not resolved")
        if reason:
            out[i] = dataclasses.replace(md, determined=False, undetermined_reason=reason)
    return out


def _overlap(a: VehicleMode, b: VehicleMode) -> bool:
    """Whether two fitted modes' 95 % intervals overlap in both frequency and damping (one mode)."""
    return (a.frequency_low_Hz <= b.frequency_high_Hz and b.frequency_low_Hz <= a.frequency_high_Hz
            and a.damping_low <= b.damping_high and b.damping_low <= a.damping_high)


def _contributions(x, w, h, wt, snr: bool = False):
    """(R, m): each pole's peak contribution to each column's FRF, relative to the column's largest ``|H|``;
    with ``snr`` also (R, m) its largest contribution in units of the bin's standard error (``|term| wt``)."""
    r = x.size // 2
    phi = _basis(w, x[:r], x[r:])
    peak = np.zeros((r, h.shape[1]))
    sig = np.zeros((r, h.shape[1]))
    for j in range(h.shape[1]):
        keep = wt[:, j] > 0
        if not keep.any():
            continue
        a = phi[keep] * wt[keep, j:j + 1]
        b = h[keep, j] * wt[keep, j]
        coef = np.linalg.lstsq(np.vstack([a.real, a.imag]), np.concatenate([b.real, b.imag]), rcond=None)[0]
        hmax = np.max(np.abs(h[keep, j]))
        for i in range(r):
            term = np.abs(phi[keep, i] * coef[i] + phi[keep, r + i] * coef[r + i])
            peak[i, j] = float(np.max(term)) / hmax if hmax > 0 else 0.0
            sig[i, j] = float(np.max(term * wt[keep, j]))
    return (peak, sig) if snr else peak


def _shown(x, w, h, wt) -> np.ndarray:
    """(R, m) bool: whether each pole shows in each column's FRF: a peak contribution of at least
    :data:`MIN_MODE_CONTRIBUTION` of the FRF's largest ``|H|``, or of at least a fifth of that and
    :data:`MIN_MODE_SNR` times the bin's standard error (a weak mode measured well: the pitch mode in the
    pitch output of one rear wheel, 3-5 % of the bounce peak, its top in the masked lug band)."""
    peak, snr = _contributions(x, w, h, wt, snr=True)
    return (peak >= MIN_MODE_CONTRIBUTION) | ((peak >= MIN_MODE_CONTRIBUTION / 5) & (snr >= MIN_MODE_SNR))


def fit_shared_modes(frequency_Hz, h, sigma, usable, modes, band_Hz: tuple[float, float] = FIT_BAND_Hz) -> dict:
    """Each output's modes fitted together with the outputs that show the same modes (poles shared).

    A mode is a pole of the whole vehicle: the roll, lateral and yaw outputs show the same
    lateral–roll and yaw poles, each a little. Fitted one output at a time, two heavily damped modes
    that overlap (the rolling tyre's lateral–roll and yaw, 40–80 % damped) are resolved by none of
    them (at 6 km/h on the virtual stand the roll output's lateral–roll frequency has a standard
    error of 4 %, the roll, lateral and yaw outputs together 1.3 %). So, per output ``k`` with its
    own fit ``modes[k]`` (:func:`fit_vehicle_modes`): its partners are the outputs with a mode whose
    95 % intervals (frequency and damping) overlap one of ``k``'s; the FRFs of ``k`` and its partners
    are fitted with shared poles (each FRF its own residues: the poly-reference form of
    :func:`fit_vehicle_modes`' variable projection), started from the union of their modes (one
    start where intervals overlap); poles at a bound, contributing less than
    :data:`MIN_MODE_CONTRIBUTION` to every FRF, or within two bins of a stronger one are dropped and
    the rest fitted again. ``k``'s modes are the shared poles that contribute at least
    :data:`MIN_MODE_CONTRIBUTION` to one of its FRFs, with intervals from the shared fit. An output
    whose own modes no other output shares is fitted again alone the same way (its own fit may be on
    coarser bins: :func:`merge_bins`). Outputs fitted on their own resolve modes
    closer than a bin that they show apart (bounce in the vertical output, yaw in the roll one);
    the partners are chosen by overlapping modes so that those stay apart.

    Parameters
    ----------
    frequency_Hz : (F,)
    h : (F, p, m) complex
        Each output's FRF from each of ``m`` inputs.
    sigma : (F, p, m)
        Standard errors of ``|H|``.
    usable : (F, p, m) bool
    modes : list of list of VehicleMode
        Each output's own fit.
    band_Hz : (low, high)

    Returns
    -------
    dict
        Output index -> list of :class:`VehicleMode`.

    See Also
    --------
    fit_vehicle_modes : one output's fit.

    Examples
    --------
    Two outputs of one system, each showing both of two overlapping heavily damped modes:

    >>> import numpy as np
    >>> f = np.arange(0.5, 12, 0.1); s = 2j * np.pi * f
    >>> def mode(fn, z, a):
    ...     wn = 2 * np.pi * fn
    ...     return a * wn ** 2 / (s ** 2 + 2 * z * wn * s + wn ** 2)
    >>> h = np.stack([mode(1.5, 0.4, 1.0) + mode(2.4, 0.45, 0.5), mode(1.5, 0.4, 0.4) - mode(2.4, 0.45, 1.0)], 1)[:, :, None]
    >>> sig = np.full(h.shape, 1e-3); use = np.ones(h.shape, bool)
    >>> own = [fit_vehicle_modes(f, h[:, k], sig[:, k], use[:, k]) for k in range(2)]
    >>> shared = fit_shared_modes(f, h, sig, use, own)
    >>> [(round(float(m.frequency_Hz / np.sqrt(1 - m.damping_ratio ** 2)), 2), round(m.damping_ratio, 2))
    ...  for m in shared[0]]
    [(1.5, 0.4), (2.4, 0.45)]
    """
    f_all = np.asarray(frequency_Hz, dtype=float)
    h_all = np.asarray(h, dtype=complex)
    sig_all = np.asarray(sigma, dtype=float)
    use_all = np.asarray(usable, dtype=bool) & ((f_all >= band_Hz[0]) & (f_all <= band_Hz[1]))[:, None, None]
    use_all &= np.isfinite(h_all) & np.isfinite(sig_all) & (sig_all > 0)
    p, m = h_all.shape[1], h_all.shape[2]
    out = {k: list(modes[k]) for k in range(p)}
    fits: dict = {}  # group (sorted) -> its shared fit: roll, lateral and yaw outputs share one
    for k in range(p):
        if not modes[k]:
            continue
        partners = [j for j in range(p) if j != k and any(_overlap(a, b) for a in modes[k] for b in modes[j])]
        group = tuple(sorted([k] + partners))  # alone: its own fit again on these bins
        if group not in fits:
            fits[group] = _group_fit(group, f_all, h_all, sig_all, use_all, modes, m)
        g = fits[group]
        if g is None or not any(j == k for j, _ in g["cols"]):
            continue
        x, r, cols, seen, at = g["x"], g["x"].size // 2, g["cols"], g["seen"], g["at"]
        own = [c for c, (j, _) in enumerate(cols) if j == k]
        shown = [i for i in range(r) if seen[i, own].any() and not (at[i] or at[r + i])]
        out[k] = [dataclasses.replace(g["modes"][i], inputs=tuple(cols[c][1] for c in own if seen[i, c]))
                  for i in sorted(shown, key=lambda i: x[i])]
    return out


#: Bin width, Hz, the own fit of each output (:func:`fit_vehicle_modes` in :func:`recording_frf`: the
#: shared fit's starts) is made on (:func:`merge_bins`): the 0.1 Hz of 10.24 s segments; with longer
#: segments (``min_segment_s`` 16: 0.049 Hz) half the cost (the shared fit, every output's result,
#: keeps the estimate's bins).
OWN_FIT_BIN_Hz = 0.1


def merge_bins(frequency_Hz, h, sigma, usable, bin_Hz: float):
    """Adjacent bins merged by ``n = round(bin_Hz / df)`` (n ≥ 2, else unchanged): the mean frequency
    and ``H``, the standard error ``sqrt(Σ σ²) / n`` (independent bins), usable where all ``n`` are.

    See Also
    --------
    recording_frf : each output's own fit on the merged bins.
    fit_vehicle_modes : that fit.

    Examples
    --------
    >>> import numpy as np
    >>> f = np.arange(8) * 0.05; h = np.arange(8.0)[:, None, None]
    >>> fm, hm, sm, um = merge_bins(f, h, np.ones_like(h), np.ones(h.shape, bool), 0.1)
    >>> fm.round(3).tolist(), hm[:, 0, 0].tolist(), round(float(sm[0, 0, 0]), 4)
    ([0.025, 0.125, 0.225, 0.325], [0.5, 2.5, 4.5, 6.5], 0.7071)
    """
    f = np.asarray(frequency_Hz, dtype=float)
    df = float(np.median(np.diff(f))) if f.size > 1 else 0.0
    n = int(round(positive("bin_Hz", bin_Hz) / df)) if df > 0 else 1
    if n < 2:
        return f, h, sigma, usable
    m = f.size // n
    cut = slice(0, m * n)

    def fold(a):
        a = np.asarray(a)[cut]
        return a.reshape((m, n) + a.shape[1:])

    with np.errstate(invalid="ignore"):
        return (fold(f).mean(axis=1), fold(h).mean(axis=1), np.sqrt((fold(sigma) ** 2).sum(axis=1)) / n,
                fold(usable).all(axis=1))


def _group_fit(group, f_all, h_all, sig_all, use_all, modes, m) -> dict | None:
    """The shared-pole fit of the outputs ``group`` (:func:`fit_shared_modes`): ``x`` (poles), ``cols``
    ((output, input) of each FRF), ``seen`` (:func:`_shown`), ``at`` (at a bound) and ``modes`` (one
    :class:`VehicleMode` per pole, in the order of ``x``, with 95 % intervals and
    :attr:`VehicleMode.determined`); None when nothing can be fitted."""
    starts: list[VehicleMode] = []
    for j in group:
        for md in modes[j]:
            if not any(_overlap(md, o) for o in starts):
                starts.append(md)
    cols = [(j, i) for j in group for i in range(m) if use_all[:, j, i].sum() >= 8]
    if not cols:
        return None
    use = np.stack([use_all[:, j, i] for j, i in cols], axis=1)
    rows = use.any(axis=1)
    f = f_all[rows]
    use = use[rows]
    hh = np.stack([h_all[rows, j, i] for j, i in cols], axis=1)
    sg = np.stack([sig_all[rows, j, i] for j, i in cols], axis=1)
    floor = 1e-3 * np.max(np.abs(np.where(use, hh, 0)), axis=0)
    wt = np.where(use, 1.0 / np.maximum(sg, np.where(floor > 0, floor, 1e-12)[None, :]), 0.0)
    h0 = np.where(use, hh, 0)
    w = 2 * np.pi * f
    df = float(np.median(np.diff(f))) if f.size > 1 else 0.0
    n_obs = 2 * int(use.sum())

    def n_par_of(rr: int) -> int:
        return 2 * rr + len(cols) * (2 * rr + 4)

    def bounds(rr: int):
        return np.repeat([f.min(), DAMPING_BOUNDS[0]], rr), np.repeat([f.max(), DAMPING_BOUNDS[1]], rr)

    def solve(poles):
        rr = len(poles)
        lb, ub = bounds(rr)
        x0 = np.clip(np.array([q[0] for q in poles] + [q[1] for q in poles]), lb + 1e-6 * (ub - lb),
                     ub - 1e-6 * (ub - lb))
        return optimize.least_squares(_projected, x0, args=(w, h0, wt), method="trf", bounds=(lb, ub),
                                      x_scale=np.repeat([1.0, 0.1], rr), max_nfev=100, ftol=1e-6, xtol=1e-6)

    def at_bound(x):
        lb, ub = bounds(x.size // 2)
        return (x <= lb + 1e-3 * (ub - lb)) | (x >= ub - 1e-3 * (ub - lb))

    poles = [(md.frequency_Hz, md.damping_ratio) for md in starts]
    res = None
    for _ in range(4):
        r = len(poles)
        if not r or n_par_of(r) >= n_obs - 2:
            return None
        try:
            res = solve(poles)
        except (ValueError, np.linalg.LinAlgError):
            return None
        x = res.x
        at = at_bound(x)
        peak = _contributions(x, w, h0, wt)
        strength = peak.max(axis=1)
        bad = at[:r] | at[r:] | ~_shown(x, w, h0, wt).any(axis=1)
        order = np.argsort(x[:r])
        for a, b in zip(order[:-1], order[1:]):
            # within two bins: one peak split, unless the two show in different FRFs (bounce in the
            # vertical output, yaw in the roll one: apart in shape if not in frequency)
            pa, pb = peak[a], peak[b]
            alike = float(pa @ pb) / max(float(np.linalg.norm(pa) * np.linalg.norm(pb)), 1e-300)
            if abs(x[b] - x[a]) < 2 * df and alike > 0.5:
                bad[a if strength[a] < strength[b] else b] = True
        if not bad.any():
            break
        poles = [(x[i], x[r + i]) for i in range(r) if not bad[i]]
        res = None
    if res is None:
        return None

    def bic_of(fit) -> float:
        return n_obs * math.log(max(2 * fit.cost, 1e-300) / n_obs) + n_par_of(fit.x.size // 2) * math.log(n_obs)

    # a heavily damped pole may stand for two that overlap (the rolling tyre's lateral-roll and yaw at
    # 11 km/h, 80 and 76 % damped, 0.5 Hz apart): split in two (x0.8, x1.25) and kept split where the
    # information criterion says the data hold both. One of the two may then sit at the damping
    # bound (not a mode the data can place): it is not reported, but the fit with it gives the
    # other its honest interval (a one-pole fit of two poles gives a narrow interval on the wrong
    # frequency)
    tried = []  # every split fit: the model-order uncertainty of a heavily damped pole (below)
    for _ in range(2):
        x = res.x
        r = x.size // 2
        split = None
        for i in np.argsort(-x[r:]):
            if x[r + i] < HEAVY_DAMPING:
                break
            trial_poles = [(x[n], x[r + n]) for n in range(r) if n != i] + [(x[i] * 0.8, x[r + i]),
                                                                              (x[i] * 1.25, x[r + i])]
            if n_par_of(r + 1) >= n_obs - 2:
                break
            try:
                trial = solve(trial_poles)
            except (ValueError, np.linalg.LinAlgError):
                continue
            tried.append(trial)
            if bic_of(trial) < bic_of(res) and (split is None or bic_of(trial) < bic_of(split)):
                split = trial
        if split is None:
            break
        res = split
    x = res.x
    r = x.size // 2
    at = at_bound(x)
    fitted = _modes_of(x, res, n_obs, n_par_of(r), df, [()] * r, sort=False)
    # the intervals of heavily damped poles from the profile of the fit's cost (the Jacobian's assume a
    # cost quadratic in the pole, which a pole 40-80 % damped and overlapping another is not)
    lb, ub = bounds(r)
    dof = max(n_obs - n_par_of(r), 1)
    for i in range(r):
        if x[r + i] >= HEAVY_DAMPING and not (at[i] or at[r + i]):
            fitted[i] = _profile_mode(fitted[i], i, res, w, h0, wt, lb, ub, dof)
    # a heavily damped mode's interval holds the other model order's too: the nearest pole of each
    # split fit (not at a bound) with its interval; where the data cannot tell one pole from two,
    # the interval then spans both answers
    alternatives = []
    for trial in tried:
        rr = trial.x.size // 2
        t_at = at_bound(trial.x)
        for n_, md in enumerate(_modes_of(trial.x, trial, n_obs, n_par_of(rr), df, [()] * rr, sort=False)):
            if not (t_at[n_] or t_at[rr + n_]):
                alternatives.append(md)
    for n, md in enumerate(fitted):
        if md.damping_ratio < HEAVY_DAMPING or not alternatives:
            continue
        alt = min(alternatives, key=lambda a: abs(_pole(a) - _pole(md)))
        fitted[n] = dataclasses.replace(
            md, frequency_low_Hz=max(min(md.frequency_low_Hz, alt.frequency_low_Hz), 0.0),
            frequency_high_Hz=max(md.frequency_high_Hz, alt.frequency_high_Hz),
            damping_low=min(md.damping_low, alt.damping_low), damping_high=max(md.damping_high, alt.damping_high))
    seen = _shown(x, w, h0, wt)
    shown = [i for i in range(r) if seen[i].any() and not (at[i] or at[r + i])]
    fitted = _flag_undetermined(fitted, shown, (float(f.min()), float(f.max())))
    return {"x": x, "cols": cols, "seen": seen, "at": at, "modes": fitted}


def _pole(m: VehicleMode) -> complex:
    """The root ``λ / 2π`` (Hz) of a fitted mode."""
    z = min(m.damping_ratio, 0.999999)
    return complex(-z * m.frequency_Hz / math.sqrt(1 - z * z), m.frequency_Hz)


#: Bounds of a fitted damping ratio (a pole at one is not reported as a mode).
DAMPING_BOUNDS = (0.005, 0.95)
#: Damping ratio from which a fitted pole is tried as two overlapping ones (:func:`fit_shared_modes`):
#: a half-power bandwidth ``2 ζ f`` of 60 % of the frequency or more, wider than the spacing of a
#: tractor's lateral modes (a documented choice).
HEAVY_DAMPING = 0.3
#: Least peak contribution of a mode to an FRF, relative to the FRF's largest magnitude: a pole
#: contributing less is noise fitted, not a mode.
MIN_MODE_CONTRIBUTION = 0.05
#: A pole contributing less than :data:`MIN_MODE_CONTRIBUTION` but at least a fifth of it shows where its
#: contribution reaches this many standard errors of a bin (noise fitted reaches 2-3).
MIN_MODE_SNR = 10.0


def _all_modes(x, w, h, wt, lb, ub) -> bool:
    """Whether every pole of ``x`` is off its bounds, apart from the others by two bins and shows in some
    input's FRF (:func:`_shown`)."""
    r = x.size // 2
    at_bound = (x <= lb + 1e-3 * (ub - lb)) | (x >= ub - 1e-3 * (ub - lb))
    if at_bound.any():
        return False
    fd = np.sort(x[:r])
    df = float(np.median(np.diff(w))) / (2 * np.pi) if w.size > 1 else 0.0
    if r > 1 and np.min(np.diff(fd)) < 2 * df:
        return False  # two poles within two bins: one peak split, not two modes the bins can resolve
    return bool(_shown(x, w, h, wt).any(axis=1).all())


def _candidates(f, h, wt, resid, m, n: int = 2) -> list[float]:
    """Starting frequencies for a new pole: the largest peaks of the weighted data (first mode) or
    of the previous fit's residual, and the band's geometric middle."""
    if resid is None:
        mag = np.sum(np.abs(h) * (wt > 0), axis=1)
    else:
        mag = np.abs(resid.reshape(2 * m, -1)).reshape(m, 2, -1).sum(axis=(0, 1))
    if mag.size > 4:
        mag = np.convolve(mag, np.ones(3) / 3, mode="same")
    peaks, _ = signal.find_peaks(mag)
    peaks = sorted(peaks, key=lambda i: -mag[i])[:n]
    out = [float(f[i]) for i in peaks]
    out.append(float(math.sqrt(max(f.min(), 1e-3) * f.max())))
    return out


#: Wheels of a four-wheel vehicle, in the order of the input channels.
WHEELS = ("front_left", "front_right", "rear_left", "rear_right")
#: Upper frequency of the stored FRF bins, Hz (the stand's excitation reaches 12 Hz, §2.2).
STORED_MAX_Hz = 20.0


def input_channel_wheel(channel: str) -> tuple[str, bool] | None:
    """``(wheel, is_height)`` of an input channel name (``input_<wheel>_z_m_s2`` or ``_z_m``), else None.

    See Also
    --------
    recording_frf : reads a recording's inputs by it.

    Examples
    --------
    >>> input_channel_wheel("input_rear_left_z_m"), input_channel_wheel("input_front_right_z_m_s2")
    (('rear_left', True), ('front_right', False))
    >>> input_channel_wheel("floor_z_m_s2") is None
    True
    """
    for w in WHEELS:
        if channel == f"input_{w}_z_m_s2":
            return w, False
        if channel == f"input_{w}_z_m":
            return w, True
    return None


def frf_unit(output: str) -> str:
    """Unit of an FRF to ``output`` per m/s² of input (heights enter differentiated).

    See Also
    --------
    recording_frf : the FRFs it names.

    Examples
    --------
    >>> frf_unit("seat_z_m_s2"), frf_unit("body_roll_rad_s2")
    ('(m/s²)/(m/s²)', '(rad/s²)/(m/s²)')
    """
    return "(rad/s²)/(m/s²)" if output.endswith("rad_s2") else "(m/s²)/(m/s²)"


@dataclass
class RecordingFrf:
    """One recording's FRFs and modes (:func:`recording_frf`).

    Attributes
    ----------
    inputs : tuple of str
        Input channels, in the order of the estimate's last axis.
    wheels : tuple of str
    outputs : tuple of str
    estimate : MimoFrf
    masked : (F,) bool
        Rotation and lug-passing bins (§2.4.5).
    modes : dict
        Output -> list of :class:`VehicleMode`.
    speed_km_h : float
    sample_rate_Hz, duration_s : float
    predicted : (F, p, q) complex or None
        A model's FRFs on the same bins (NaN for an output it does not have), set by the caller
        that has one (:func:`tyrelab.api.vehicle_frf` with a scenario); written beside the measured
        ones (``predicted_h_magnitude``).
    validation : list of dict
        The ``vehicle_frf_validation`` rows of that model (:func:`tyrelab.stand.frf_validation_rows`).
    """

    inputs: tuple
    wheels: tuple
    outputs: tuple
    estimate: MimoFrf
    masked: np.ndarray
    modes: dict
    speed_km_h: float
    sample_rate_Hz: float
    duration_s: float
    predicted: np.ndarray | None = None
    validation: list = field(default_factory=list)

    def usable(self, k: int) -> np.ndarray:
        """(F, q) bins of output ``k`` the fit may use: separable, unmasked, coherent."""
        e = self.estimate
        return (~e.ill_conditioned & ~self.masked[:, None]
                & (e.multiple_coherence[:, k:k + 1] >= FIT_MIN_COHERENCE))

    def frf_rows(self, max_Hz: float = STORED_MAX_Hz, predicted=None) -> list[dict]:
        """One row per input, output and bin in (0, ``max_Hz``] (the ``vehicle_frf`` columns).

        ``predicted``: a model's FRFs on the same bins, (F, p, q) complex (NaN where it has none;
        default :attr:`predicted`), written as ``predicted_h_magnitude`` (the column is left out
        without one)."""
        e = self.estimate
        predicted = self.predicted if predicted is None else predicted
        f = e.frequency_Hz
        keep = np.flatnonzero((f > 0) & (f <= max_Hz))
        if predicted is not None and np.shape(predicted) != e.h.shape:
            raise ValueError(f"predicted must have the estimate's shape {e.h.shape}, got {np.shape(predicted)}")
        rows = []
        q = len(self.inputs)
        delay_coherence = e.delay_coherence if e.delay_coherence is not None else np.full((f.size, q), np.nan)
        delay_s = e.input_delay_s if e.input_delay_s is not None else np.full(q, np.nan)
        for k, out in enumerate(self.outputs):
            for j, (inp, wheel) in enumerate(zip(self.inputs, self.wheels)):
                h = e.h[keep, k, j]
                h2 = e.h2[keep, k, j] if e.h2 is not None else np.full(keep.size, np.nan)
                extra = [{}] * keep.size if predicted is None else \
                    [{"predicted_h_magnitude": _num(abs(v))} for v in np.asarray(predicted)[keep, k, j]]
                for n, i in enumerate(keep):
                    rows.append({**extra[n], 
                        "input": inp, "wheel": wheel, "output": out, "frequency_Hz": float(f[i]),
                        "h_magnitude": _num(abs(h[n])), "h_phase_deg": _num(np.degrees(np.angle(h[n]))),
                        "h_unit": frf_unit(out), "h2_magnitude": _num(abs(h2[n])),
                        "h2_phase_deg": _num(np.degrees(np.angle(h2[n]))),
                        "coherence": _num(e.coherence[i, k, j]), "partial_coherence": _num(e.partial_coherence[i, k, j]),
                        "multiple_coherence": _num(e.multiple_coherence[i, k]),
                        "random_error": _num(e.random_error[i, k, j]),
                        "condition_number": _num(e.condition_number[i]),
                        "input_coherence": _num(e.input_coherence[i, j]),
                        "ill_conditioned": bool(e.ill_conditioned[i, j]), "masked": bool(self.masked[i]),
                        "delay_coherence": _num(delay_coherence[i, j]), "input_delay_s": _num(delay_s[j])})
        return rows

    def mode_rows(self) -> list[dict]:
        """One row per output and mode (the ``vehicle_modes`` columns)."""
        rows = []
        for out in self.outputs:
            for n, m in enumerate(self.modes.get(out, []), start=1):
                rows.append({"output": out, "mode": n, "frequency_Hz": m.frequency_Hz, "damping_ratio": m.damping_ratio,
                             "frequency_ci95_low_Hz": m.frequency_low_Hz, "frequency_ci95_high_Hz": m.frequency_high_Hz,
                             "damping_ci95_low": m.damping_low, "damping_ci95_high": m.damping_high,
                             "inputs": ",".join(self.inputs[j] for j in m.inputs),
                             "natural_frequency_Hz": m.natural_frequency_Hz,
                             "natural_frequency_ci95_low_Hz": _num(m.natural_frequency_low_Hz),
                             "natural_frequency_ci95_high_Hz": _num(m.natural_frequency_high_Hz),
                             "determined": bool(m.determined), "undetermined_reason": m.undetermined_reason})
        return rows

    def to_json(self, max_Hz: float = STORED_MAX_Hz) -> dict:
        """``inputs``, ``outputs``, ``speed_km_h``, ``sample_rate_Hz``, ``duration_s``, ``n_d``,
        ``modes`` (rows) and ``frf`` (rows), NaN as None; with a prediction (:attr:`predicted`) the
        rows' ``predicted_h_magnitude`` and ``validation`` (the ``vehicle_frf_validation`` rows)."""
        doc = {"inputs": list(self.inputs), "wheels": list(self.wheels), "outputs": list(self.outputs),
               "speed_km_h": self.speed_km_h, "sample_rate_Hz": self.sample_rate_Hz, "duration_s": self.duration_s,
               "n_d": self.estimate.n_d, "modes": self.mode_rows(), "frf": self.frf_rows(max_Hz)}
        if self.predicted is not None or self.validation:
            doc["validation"] = [{k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                                  for k, v in row.items()} for row in self.validation]
        return doc


def scenario_wheel_geometry(scenario) -> list[tuple[float, int]]:
    """``(rolling circumference m, lugs per side)`` of a scenario's four wheels (front, front, rear,
    rear), for :func:`wheel_excitation_mask`: the tyre's ``radius_m`` if given, else the
    circumference from its size; no lugs on a tyre without ``traction``
    (:func:`tyrelab.tyre.sizes.lugs_per_side`).

    See Also
    --------
    wheel_excitation_mask : the mask it feeds.

    Examples
    --------
    >>> from types import SimpleNamespace as S
    >>> sc = S(front=S(size="7.50-18", radius_m=None, traction=False), rear=S(size="13.6R38", radius_m=None, traction=True))
    >>> [(round(c, 2), n) for c, n in scenario_wheel_geometry(sc)][1:3]
    [(2.35, 0), (4.66, 23)]
    """
    from ..tyre.sizes import lugs_per_side, parse_tyre_size, rolling_circumference_m

    out = []
    for spec in (scenario.front, scenario.rear):
        circ = 2 * math.pi * spec.radius_m if spec.radius_m else rolling_circumference_m(parse_tyre_size(spec.size))
        out += [(circ, lugs_per_side(circ, ribbed=not spec.traction))] * 2
    return out


def _num(v) -> float | None:
    v = float(v)
    return v if math.isfinite(v) else None


def recording_frf(recording, speed_km_h: float = 0.0, wheels_geometry=None, outputs=None,
                  min_segment_s: float = MIN_SEGMENT_S, max_modes: int = MAX_MODES) -> RecordingFrf:
    """FRFs and modes of an opened recording with input channels (streamed: memory by the segment).

    Parameters
    ----------
    recording
        An opened recording (:func:`tyrelab.rawformat.rides.open_recording`): ``channels``,
        ``sample_rate_Hz``, ``chunks()``.
    speed_km_h : float
        Rolling speed; 0 = stationary (nothing masked).
    wheels_geometry : iterable of (circumference_m, lugs_per_side), optional
        The tyres whose rotation and lug bins are masked (none when not given).
    outputs : sequence of str, optional
        Output channels (default: every channel that is not an input).
    min_segment_s : float
    max_modes : int

    Raises
    ------
    ValueError
        One line: no input channel, an input that is constant (no excitation), a recording
        shorter than the segments the random error needs.

    See Also
    --------
    cross_spectra : the spectra it accumulates.
    fit_vehicle_modes : the modes of each output.
    tyrelab.vehicle_frf : the same from a file path.

    Examples
    --------
    Four wheel inputs of random motion, a seat that follows the front left and rear left wheels by
    0.5 and 0.3 (and noise), recorded to a file:

    >>> import pandas as pd, tempfile
    >>> from pathlib import Path
    >>> from tyrelab.rawformat.rides import open_recording
    >>> fs, n = 100.0, 100 * 120
    >>> x = np.random.default_rng(1).normal(size=(5, n))
    >>> wheels = ["front_left", "front_right", "rear_left", "rear_right"]
    >>> path = Path(tempfile.mkdtemp()) / "stand.csv"
    >>> pd.DataFrame({"time_s": np.arange(n) / fs, **{f"input_{w}_z_m_s2": x[i] for i, w in enumerate(wheels)},
    ...               "seat_z_m_s2": 0.5 * x[0] + 0.3 * x[2] + 0.05 * x[4]}).to_csv(path, index=False)
    >>> r = recording_frf(open_recording(path))
    >>> r.wheels, r.outputs, r.duration_s
    (('front_left', 'front_right', 'rear_left', 'rear_right'), ('seat_z_m_s2',), 120.0)
    """
    names = tuple(recording.channels)
    inputs = [c for c in names if input_channel_wheel(c)]
    if not inputs:
        raise ValueError("no input channel (input_<wheel>_z_m_s2 or input_<wheel>_z_m, wheel one of "
                         f"{', '.join(WHEELS)})")
    wheels = [input_channel_wheel(c)[0] for c in inputs]
    twice = sorted({w for w in wheels if wheels.count(w) > 1})
    if twice:
        raise ValueError(f"wheel {twice[0]} has both a height and an acceleration input: give one")
    outs = [c for c in names if c not in inputs] if outputs is None else list(outputs)
    if not outs:
        raise ValueError("no output channel beside the inputs")
    fs = float(recording.sample_rate_Hz)
    nperseg = segment_samples(fs, min_segment_s)
    acc = CrossSpectraAccumulator(len(inputs), len(outs), fs, nperseg,
                                  heights=[input_channel_wheel(c)[1] for c in inputs])
    lo = np.full(len(inputs), np.inf)
    hi = np.full(len(inputs), -np.inf)
    n = 0
    for chunk in recording.chunks():
        x = np.vstack([chunk.channels[c] for c in inputs])
        lo, hi = np.minimum(lo, x.min(axis=1)), np.maximum(hi, x.max(axis=1))
        acc.add(x, np.vstack([chunk.channels[c] for c in outs]))
        n += x.shape[1]
    flat = [c for c, a, b in zip(inputs, lo, hi) if not b > a]
    if flat:
        raise ValueError(f"input channel {flat[0]} is constant: no excitation to estimate a transfer function from")
    duration = n / fs
    if n < 2 * nperseg:
        raise ValueError(f"recording is {duration:.3g} s: the FRFs need at least two segments of "
                         f"{nperseg / fs:.3g} s (bins of {fs / nperseg:.3g} Hz)")
    spectra = acc.finish()
    if spectra.n_d <= len(inputs) + 1:
        raise ValueError(f"recording is {duration:.3g} s: {len(inputs)} inputs need more than {len(inputs) + 1} "
                         f"segments of {nperseg / fs:.3g} s for the random error (n_d - q degrees of freedom)")
    est = mimo_frf(spectra)
    masked = wheel_excitation_mask(est.frequency_Hz, speed_km_h, wheels_geometry or ())
    result = RecordingFrf(tuple(inputs), tuple(wheels), tuple(outs), est, masked, {}, float(speed_km_h), fs, duration)
    sigma = est.random_error * np.abs(est.h)
    usable = np.stack([result.usable(k) for k in range(len(outs))], axis=1)  # (F, p, q)
    # each output's own fit (the starts and partners of the shared fit) on bins merged to about
    # OWN_FIT_BIN_Hz; the shared fit, every output's result, on the estimate's own bins
    fc, hc, sc, uc = merge_bins(est.frequency_Hz, est.h, sigma, usable, OWN_FIT_BIN_Hz)
    own = [fit_vehicle_modes(fc, hc[:, k, :], sc[:, k, :], uc[:, k, :], max_modes=max_modes)
           for k in range(len(outs))]
    shared = fit_shared_modes(est.frequency_Hz, est.h, sigma, usable, own)
    for k, out in enumerate(outs):
        result.modes[out] = shared[k]
    return result
