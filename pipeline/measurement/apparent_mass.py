"""Tyre stiffness and damping from the apparent mass (thesis chapter 3).

The dynamic tyre test vehicle measures the axle acceleration and the force the
tyre exerts on the axle; the transfer function between them at the excitation
frequency gives the tyre's stiffness K and damping C (thesis §3.3.1, eqs 1-9,
worked example §3.5).

Sign conventions
----------------
Recordings (raw format v1) use *upward-positive* acceleration ``a`` and
upward-positive ground force ``f_t`` on the axle. A Kelvin-Voigt tyre under an
axle displaced upwards by ``x`` gives ``f_t = -(K x + C x')`` about the static
load, so in the frequency domain ``F/A = (K + jωC)/ω²``.

The thesis' apparent mass ``H`` is defined with deflection-positive
acceleration (its worked example ``H = -400 - 100j`` kg at 3.8 Hz gives
``K = 228 027 N/m`` and ``C = 2 388 N s/m``), i.e. ``H = -F/A``, and

    K = Re(-ω² H),   C = Re(jω H)            (thesis eqs 8 and 9, §3.5).

Every function here returns ``H`` in the thesis convention.

All functions operate along the last axis, so a 2-D array of equal-length
runs (runs x samples) is analysed in one vectorised call.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import fft, ndimage, signal

from .._validate import band, positive, positive_array, same_last_axis

__all__ = [
    "EXCITATION_BAND_Hz", "tyre_force", "stiffness_damping", "apparent_mass_from_kc", "excitation_frequency",
    "DemodulationResult", "analytic_band", "excitation_blocks", "apparent_mass_demodulation", "welch_segments_at",
    "WelchResult", "apparent_mass_welch", "H1Spectrum", "h1_spectrum",
]

#: Band in which the excitation is searched for, Hz (vibrator range 1.5-6 Hz, thesis §3.2.5).
EXCITATION_BAND_Hz = (1.0, 8.0)


def tyre_force(
    accel_left_m_s2: np.ndarray,
    accel_right_m_s2: np.ndarray,
    load_beams_N: np.ndarray,
    axle_mass_kg: float | np.ndarray,
) -> np.ndarray:
    """Ground reaction force on the tyre from axle acceleration and load beams.

    ``f_t = M_a * mean(a_left, a_right) - sum(load beams)`` (thesis §3.2.8,
    Fig. 15; the static ``M_a g`` term has no component at the excitation
    frequency and is left in).

    Parameters
    ----------
    accel_left_m_s2, accel_right_m_s2 : ndarray, shape (..., n)
        Axle-end accelerations, m/s², upward positive.
    load_beams_N : ndarray, shape (..., 4, n)
        Forces exerted by the carriage on the axle through the load beams, N,
        upward positive.
    axle_mass_kg : float or ndarray, shape (...)
        Mass of axle, wheel and tyre M_a, kg (typically about 600 kg).

    Returns
    -------
    ndarray, shape (..., n)
        Tyre force on the axle, N, upward positive.

    Raises
    ------
    ValueError
        If ``axle_mass_kg`` is not finite and positive, or the shapes disagree.

    See Also
    --------
    apparent_mass_demodulation : H from this force and the acceleration.
    tyrelab.measurement.frame_tyre_force : the same from a run's DataFrame.

    Examples
    --------
    An axle of 600 kg accelerating at 1 m/s² upward while the beams carry 100 N:

    >>> tyre_force([1.0], [1.0], [[25.0], [25.0], [25.0], [25.0]], 600.0)
    array([500.])
    """
    mass = positive_array("axle_mass_kg", axle_mass_kg)[..., np.newaxis]
    left, right = np.asarray(accel_left_m_s2, dtype=float), np.asarray(accel_right_m_s2)
    load_beams_N = np.asarray(load_beams_N)
    if left.shape != right.shape:
        raise ValueError(f"accel_left_m_s2 and accel_right_m_s2 differ in shape: {left.shape} vs {right.shape}")
    if load_beams_N.ndim < 2 or load_beams_N.shape[-2] != 4 or load_beams_N.shape[-1] != left.shape[-1]:
        raise ValueError(f"load_beams_N must have shape (..., 4, {left.shape[-1]}), got {load_beams_N.shape}")
    accel = 0.5 * (left + right)
    return mass * accel - np.sum(load_beams_N, axis=-2, dtype=float)


def stiffness_damping(apparent_mass_kg: complex | np.ndarray, frequency_Hz: float | np.ndarray):
    """Stiffness and damping from the apparent mass at one frequency.

    ``K = Re(-ω² H)`` and ``C = Re(jω H)`` with ``ω = 2π f`` (thesis eqs 8-9,
    §3.3.1 and the worked example of §3.5).

    Parameters
    ----------
    apparent_mass_kg : complex or ndarray
        Apparent mass H in the thesis convention (deflection-positive), kg.
    frequency_Hz : float or ndarray
        Frequency at which H was evaluated, Hz.

    Returns
    -------
    stiffness_N_per_m, damping_N_s_per_m : float or ndarray

    See Also
    --------
    apparent_mass_from_kc : its inverse.
    apparent_mass_demodulation : H of a run.

    Examples
    --------
    >>> k, c = stiffness_damping(-400 - 100j, 3.8)
    >>> round(float(k)), round(float(c))
    (228027, 2388)
    """
    omega = 2.0 * np.pi * positive_array("frequency_Hz", frequency_Hz, allow_nan=True)
    h = np.asarray(apparent_mass_kg, dtype=complex)
    return np.real(-(omega**2) * h), np.real(1j * omega * h)


def apparent_mass_from_kc(stiffness_N_per_m, damping_N_s_per_m, frequency_Hz):
    """Apparent mass (thesis convention) of a Kelvin-Voigt tyre: ``H = -(K + jωC)/ω²``.

    The inverse of :func:`stiffness_damping`; used for synthetic cases.

    See Also
    --------
    stiffness_damping : its inverse.

    Examples
    --------
    >>> h = apparent_mass_from_kc(228027.0, 2388.0, 3.8)
    >>> [round(float(v)) for v in stiffness_damping(h, 3.8)]
    [228027, 2388]
    """
    omega = 2.0 * np.pi * positive_array("frequency_Hz", frequency_Hz, allow_nan=True)
    return -(np.asarray(stiffness_N_per_m) + 1j * omega * np.asarray(damping_N_s_per_m)) / omega**2


def excitation_frequency(
    accel_m_s2: np.ndarray, sample_rate_Hz: float, band_Hz: tuple[float, float] = EXCITATION_BAND_Hz
) -> np.ndarray:
    """Frequency of the sinusoidal excitation, from the acceleration spectrum.

    The peak of the Hann-windowed, zero-padded (×2) amplitude spectrum within
    ``band_Hz``, refined by parabolic interpolation of the log magnitude
    around the peak. This is the frequency at which the thesis reads H
    (§3.3.1: "evaluated at the frequency at which the axle was being
    excited"), without picket-fence error.

    Parameters
    ----------
    accel_m_s2 : ndarray, shape (..., n)
        Axle acceleration, m/s².
    sample_rate_Hz : float
        Sampling rate, Hz.
    band_Hz : (float, float)
        Search band, Hz.

    Returns
    -------
    ndarray, shape (...)
        Excitation frequency, Hz (NaN where the band is empty or the signal has no content in it).

    See Also
    --------
    apparent_mass_demodulation : follows the frequency as it wanders.

    Examples
    --------
    >>> t = np.arange(2560) / 256.0
    >>> round(float(excitation_frequency(np.sin(2 * np.pi * 3.7 * t), 256.0)), 2)
    3.7
    """
    sample_rate_Hz = positive("sample_rate_Hz", sample_rate_Hz)
    band_Hz = band("band_Hz", band_Hz)
    x = np.asarray(accel_m_s2, dtype=float)
    n = x.shape[-1]
    nfft = 1 << int(np.ceil(np.log2(2 * n)))
    # single precision is ample to locate a peak, and twice as fast
    windowed = ((x - x.mean(axis=-1, keepdims=True)) * np.hanning(n)).astype(np.float32)
    spec = np.abs(fft.rfft(windowed, nfft, axis=-1))
    freqs = np.fft.rfftfreq(nfft, 1.0 / sample_rate_Hz)
    in_band = np.flatnonzero((freqs >= band_Hz[0]) & (freqs <= band_Hz[1]))
    if in_band.size < 3:
        return np.full(x.shape[:-1], np.nan)
    sub = spec[..., in_band].astype(np.float64)
    k = np.argmax(sub, axis=-1)
    k = np.clip(k, 1, in_band.size - 2)
    take = lambda off: np.take_along_axis(sub, (k + off)[..., np.newaxis], axis=-1)[..., 0]  # noqa: E731
    ym, y0, yp = (np.log(np.maximum(take(o), 1e-300)) for o in (-1, 0, 1))
    denom = ym - 2 * y0 + yp
    delta = np.where(denom != 0, 0.5 * (ym - yp) / np.where(denom != 0, denom, 1), 0.0)
    df = freqs[1] - freqs[0]
    found = sub.max(axis=-1) > 0  # a signal with no content in the band has no excitation
    return np.where(found, freqs[in_band[0]] + (k + np.clip(delta, -0.5, 0.5)) * df, np.nan)


def _signals(force_N, accel_m_s2, sample_rate_Hz, excitation_frequency_Hz):
    """Float arrays of force and acceleration, and the excitation frequency (found if None), checked."""
    positive("sample_rate_Hz", sample_rate_Hz)
    f = np.asarray(force_N, dtype=float)
    a = np.asarray(accel_m_s2, dtype=float)
    if f.shape != a.shape:
        raise ValueError(f"force_N and accel_m_s2 differ in shape: {f.shape} vs {a.shape}")
    if a.ndim == 0 or a.shape[-1] < 2:
        raise ValueError(f"accel_m_s2 needs samples along its last axis, got shape {a.shape}")
    if excitation_frequency_Hz is None:
        excitation_frequency_Hz = excitation_frequency(a, sample_rate_Hz)
    else:
        positive_array("excitation_frequency_Hz", excitation_frequency_Hz)
    return f, a, excitation_frequency_Hz


@dataclass(frozen=True)
class DemodulationResult:
    """Output of :func:`apparent_mass_demodulation` (arrays of shape (...))."""

    apparent_mass_kg: np.ndarray  #: H, thesis convention, kg
    frequency_Hz: np.ndarray  #: amplitude-weighted mean instantaneous excitation frequency, Hz
    stiffness_N_per_m: np.ndarray  #: K, N/m
    damping_N_s_per_m: np.ndarray  #: C, N s/m
    displacement_amplitude_m: np.ndarray  #: mean axle displacement amplitude (peak), m
    acceleration_amplitude_m_s2: np.ndarray  #: mean axle acceleration amplitude (peak), m/s²
    envelope_m_s2: np.ndarray  #: (..., n) instantaneous amplitude of the excitation, m/s²
    angular_frequency_rad_s: np.ndarray  #: (..., n) instantaneous angular frequency (1 s mean), rad/s
    #: (...) the denominator ``D`` of ``K + jωC = N / D`` (Hann-weighted, demodulated ``a/ω²``), m;
    #: input of :mod:`tyrelab.measurement.uncertainty`
    denominator_m: np.ndarray | None = None
    #: (..., n_probes) the force left over by the fitted tyre, demodulated like ``N`` at the
    #: :data:`PROBE_OFFSETS` around the excitation, N: the noise the estimate sits in
    residual_probes_N: np.ndarray | None = None


def _band_weights(freqs: np.ndarray, f0: np.ndarray, half_band_Hz: float) -> np.ndarray:
    """One-sided raised-cosine band-pass weights at ``freqs`` (Hz), shape (..., len(freqs)).

    Flat within ``f0 ± 0.3 half_band`` (the vibrator wanders by ±0.1 Hz, §3.5),
    cos²-tapered to zero at ``f0 ± half_band``; the gentle taper keeps the
    filter's ringing short.
    """
    flat = 0.3
    d = np.abs(freqs - np.asarray(f0, dtype=float)[..., np.newaxis]) / half_band_Hz
    taper = np.cos(0.5 * np.pi * (d - flat) / (1.0 - flat)) ** 2
    return np.where(d <= flat, 1.0, np.where(d < 1.0, taper, 0.0))


def analytic_band(x: np.ndarray, sample_rate_Hz: float, f0, half_band_Hz: float = 0.5,
                  integrate_twice: bool = False) -> np.ndarray:
    """Analytic signal of the band ``f0 ± half_band`` of ``x`` (zero phase).

    One real FFT, the one-sided spectrum weighted by a raised-cosine band and
    doubled, one inverse FFT: the band-pass and the Hilbert transform in a
    single step, vectorised over rows with different ``f0``. Its modulus is
    the band component's amplitude envelope and its angle the phase.

    Parameters
    ----------
    x : ndarray, shape (..., n)
        Signal (mean removed here).
    sample_rate_Hz : float
        Sampling rate, Hz.
    f0 : float or ndarray, shape (...)
        Band centre, Hz.
    half_band_Hz : float
        Half-width of the band, Hz.
    integrate_twice : bool
        Divide each bin by ``-(2πf)²``: the band of the double integral
        (displacement from acceleration), exact however the frequency wanders.

    Returns
    -------
    ndarray of complex, shape (..., n)

    See Also
    --------
    apparent_mass_demodulation : demodulates with its phase.

    Examples
    --------
    >>> fs = 256.0; t = np.arange(0, 20, 1 / fs)
    >>> z = analytic_band(2.0 * np.sin(2 * np.pi * 4.0 * t) + 0.5 * np.sin(2 * np.pi * 9.0 * t), fs, 4.0)
    >>> round(float(np.median(np.abs(z))), 2)              # the 4 Hz component's amplitude alone
    2.0
    """
    sample_rate_Hz = positive("sample_rate_Hz", sample_rate_Hz)
    half_band_Hz = positive("half_band_Hz", half_band_Hz)
    positive_array("f0", f0)
    spectrum, n = _band_spectrum(x, sample_rate_Hz, half_band_Hz)
    return _analytic_from_spectrum(spectrum, n, sample_rate_Hz, f0, half_band_Hz, integrate_twice)


def _band_spectrum(x: np.ndarray, sample_rate_Hz: float, half_band_Hz: float) -> tuple[np.ndarray, int]:
    """The zero-padded real spectrum of ``x`` (mean removed) that :func:`analytic_band` filters, and ``x``'s length.

    Computed once per signal, it serves every band taken from that signal
    (:func:`_analytic_from_spectrum`): the phase reference and the
    displacement band of :func:`apparent_mass_demodulation` share one FFT.
    """
    x = np.asarray(x, dtype=float)
    n = x.shape[-1]
    # Zero-pad by a few impulse-response lengths (~1/half_band) so that the
    # filtering is linear, not circular: the record's ends do not wrap onto
    # each other. The first and last ~3 s then carry the filter's start-up
    # (the Hann weighting of the demodulation makes them count little).
    nfft = _padded_length(n, sample_rate_Hz, half_band_Hz)
    return fft.rfft(x - x.mean(axis=-1, keepdims=True), n=nfft, axis=-1), n


def _padded_length(n: int, sample_rate_Hz: float, half_band_Hz: float) -> int:
    """FFT length of :func:`_band_spectrum` for ``n`` samples: the signal and a few
    impulse-response lengths (~1/half_band) of zeros on either side, rounded up to a fast size."""
    return fft.next_fast_len(n + 2 * int(np.ceil(4.0 * sample_rate_Hz / half_band_Hz)), real=True)


def _analytic_from_spectrum(spectrum: np.ndarray, n: int, sample_rate_Hz: float, f0, half_band_Hz: float,
                            integrate_twice: bool = False) -> np.ndarray:
    """:func:`analytic_band` from the spectrum of :func:`_band_spectrum` (arguments already checked)."""
    nfft = _padded_length(n, sample_rate_Hz, half_band_Hz)
    df = sample_rate_Hz / nfft
    f0 = np.asarray(f0, dtype=float)
    lo = max(int(np.floor((np.min(f0) - half_band_Hz) / df)), 0)
    hi = min(int(np.ceil((np.max(f0) + half_band_Hz) / df)) + 1, spectrum.shape[-1])
    one_sided = np.zeros(spectrum.shape[:-1] + (nfft,), dtype=complex)
    bins = np.arange(lo, hi) * df
    weights = _band_weights(bins, f0, half_band_Hz)
    if integrate_twice:
        weights = weights * np.where(bins > 0, -1.0 / (2 * np.pi * np.where(bins > 0, bins, 1.0)) ** 2, 0.0)
    band = one_sided[..., lo:hi]
    np.multiply(2.0, spectrum[..., lo:hi], out=band)
    band *= weights
    return fft.ifft(one_sided, axis=-1, overwrite_x=True)[..., :n]


def _instantaneous_phase(accel: np.ndarray, sample_rate_Hz: float, f0, half_band_Hz: float, z: np.ndarray | None = None):
    """cos φ, sin φ, angular frequency (smoothed over ~1 s) and envelope of the excitation in ``accel``.

    ``z``, the band's analytic signal (:func:`analytic_band` of ``accel``), when already computed.
    """
    if z is None:
        z = analytic_band(accel, sample_rate_Hz, f0, half_band_Hz)
    envelope = np.abs(z)
    safe = np.where(envelope > 0, envelope, 1.0)
    cos_phi, sin_phi = z.real / safe, z.imag / safe
    # phase step between samples: atan2 of the cross and dot products of successive unit phasors
    # (written into preallocated buffers: the same operations, in the same order, as the expression
    # ``arctan2(c0 s1 - s0 c1, c0 c1 + s0 s1)``, without its six temporaries)
    c0, c1, s0, s1 = cos_phi[..., :-1], cos_phi[..., 1:], sin_phi[..., :-1], sin_phi[..., 1:]
    cross, dot, scratch = (np.empty(c0.shape) for _ in range(3))
    np.multiply(c0, s1, out=cross)
    cross -= np.multiply(s0, c1, out=scratch)
    np.multiply(c0, c1, out=dot)
    dot += np.multiply(s0, s1, out=scratch)
    omega = np.empty(cos_phi.shape)
    np.arctan2(cross, dot, out=omega[..., :-1])
    omega[..., -1] = omega[..., -2]
    omega *= sample_rate_Hz
    omega = ndimage.uniform_filter1d(omega, size=max(int(round(sample_rate_Hz)), 1), axis=-1, mode="nearest")
    return cos_phi, sin_phi, omega, envelope


def _demodulate(x: np.ndarray, cos_phi: np.ndarray, sin_phi: np.ndarray) -> np.ndarray:
    """``Σ x exp(-jφ)`` along the last axis, as two fused real sums (no complex temporaries)."""
    return np.einsum("...n,...n->...", x, cos_phi) - 1j * np.einsum("...n,...n->...", x, sin_phi)


#: Offsets of the noise probes around the excitation, in units of 2/T (T the record length): the
#: Hann taper's main lobe is ±2/T wide, so probes 2/T apart are nearly independent and the nearest
#: (4/T away) sees none of the excitation. 16 probes, within ±0.36 Hz of it for a 50 s run.
PROBE_OFFSETS = tuple(m for m in range(-9, 10) if abs(m) >= 2)


def _tyre_residual(force: np.ndarray, xi: np.ndarray, omega: np.ndarray, w: np.ndarray) -> np.ndarray:
    """The force a Kelvin-Voigt tyre whose K and C follow the vibration amplitude does not explain.

    Least squares (weights ``w``) of ``f`` on ``Re ξ``, ``−ω Im ξ`` and the
    same times ``a(t) = |ξ|²/mean|ξ|² − 1``: within a run the amplitude wanders
    (§3.5: by up to 20 %) and K and C follow it (thesis Tables IV, VIII), which
    is a change of the measurand over the run, not noise around it.
    """
    amp2 = np.abs(xi) ** 2
    a = amp2 / np.sum(w * amp2, axis=-1, keepdims=True) * np.sum(w) - 1.0
    g = np.empty(xi.shape[:-1] + (4, xi.shape[-1]))  # rows Re ξ, −ω Im ξ, and both times a(t)
    g[..., 0, :] = xi.real
    np.multiply(np.negative(omega), xi.imag, out=g[..., 1, :])
    np.multiply(g[..., :2, :], a[..., np.newaxis, :], out=g[..., 2:, :])
    gw = g * w
    gram = np.einsum("...in,...jn->...ij", gw, g)
    rhs = np.einsum("...in,...n->...i", gw, force)
    beta = np.linalg.solve(gram, rhs[..., np.newaxis])[..., 0]
    return force - np.einsum("...i,...in->...n", beta, g)


def _probe_sums(x: np.ndarray, cos_phi: np.ndarray, sin_phi: np.ndarray) -> np.ndarray:
    """``Σ x exp(-j(φ + 2π Δ_m t))`` for the :data:`PROBE_OFFSETS` ``Δ_m`` (multiples of 2/T), shape (..., n_probes).

    With ``T = n/fs`` the offsets are DFT bins of the demodulated signal: one FFT per row.
    """
    n = x.shape[-1]
    z = np.empty(x.shape, dtype=complex)  # x cos φ - j x sin φ, built in place
    np.multiply(x, cos_phi, out=z.real)
    np.multiply(x, sin_phi, out=z.imag)
    np.negative(z.imag, out=z.imag)
    spectrum = fft.fft(z, axis=-1, overwrite_x=True)
    return spectrum[..., (2 * np.asarray(PROBE_OFFSETS)) % n]


def excitation_blocks(
    envelope: np.ndarray, omega: np.ndarray, sample_rate_Hz: float, block_s: float = 5.0, edge_s: float = 3.0
) -> tuple[np.ndarray, np.ndarray]:
    """Excitation amplitude and frequency per block of ``block_s`` seconds.

    From the envelope and instantaneous angular frequency of
    :func:`apparent_mass_demodulation`; ``edge_s`` is dropped at both ends
    (the band-pass' start-up, see :func:`analytic_band`).
    Used by QC for the amplitude (±20 %) and frequency (±0.1 Hz) limits of
    thesis §3.5.

    Returns
    -------
    amplitude, frequency_Hz : ndarray, shape (..., n_blocks)
        Mean amplitude (units of the signal) and mean frequency (Hz) per block.

    See Also
    --------
    apparent_mass_demodulation : the envelope and frequency it takes.
    tyrelab.measurement.qc.qc_reasons : the limits it serves.

    Examples
    --------
    >>> fs = 256.0; t = np.arange(0, 30, 1 / fs); w = 2 * np.pi * 3.8
    >>> x = 0.005 * np.sin(w * t)                              # axle displacement, m
    >>> a = -w**2 * x                                          # its acceleration, m/s²
    >>> f = -(228e3 * x + 2.4e3 * 0.005 * w * np.cos(w * t))  # a Kelvin-Voigt tyre's force, N
    >>> d = apparent_mass_demodulation(f, a, fs)
    >>> amp, freq = excitation_blocks(d.envelope_m_s2, d.angular_frequency_rad_s, fs)
    >>> len(amp), round(float(amp.mean()), 2), round(float(freq.mean()), 3)   # 5 s blocks of 24 s; ω² x₀
    (4, 2.85, 3.8)
    """
    sample_rate_Hz = positive("sample_rate_Hz", sample_rate_Hz)
    block_s = positive("block_s", block_s)
    if not edge_s >= 0:
        raise ValueError(f"edge_s must be >= 0, got {edge_s!r}")
    edge = int(round(edge_s * sample_rate_Hz))
    size = max(int(round(block_s * sample_rate_Hz)), 1)
    env = envelope[..., edge : envelope.shape[-1] - edge]
    om = omega[..., edge : omega.shape[-1] - edge]
    nb = env.shape[-1] // size
    if nb == 0:
        return env.mean(axis=-1, keepdims=True), om.mean(axis=-1, keepdims=True) / (2 * np.pi)
    shape = env.shape[:-1] + (nb, size)
    cut = nb * size
    return (env[..., :cut].reshape(shape).mean(axis=-1),
            om[..., :cut].reshape(shape).mean(axis=-1) / (2 * np.pi))


def apparent_mass_demodulation(
    force_N: np.ndarray,
    accel_m_s2: np.ndarray,
    sample_rate_Hz: float,
    excitation_frequency_Hz: float | np.ndarray | None = None,
    half_band_Hz: float = 0.5,
) -> DemodulationResult:
    """Apparent mass by phase-locked synchronous demodulation over the whole run.

    The excitation's instantaneous phase φ(t) is taken from the band-passed
    acceleration; force and acceleration (mean removed) are both demodulated
    with ``exp(-jφ)`` and averaged over the run with a Hann taper. The
    acceleration is divided by the instantaneous ω(t)² first, so that the
    ratio is the dynamic stiffness ``K + jωC`` even while the vibrator's
    frequency wanders (thesis §3.5 holds it within ±0.1 Hz). Uncorrelated
    force noise, wheel-rotation and lug-passing components average out.
    Unlike reading a Welch estimate at an FFT bin (the thesis' method), there
    is no picket-fence error and every cycle is used.

    Parameters
    ----------
    force_N : ndarray, shape (..., n)
        Tyre force on the axle, N, upward positive (:func:`tyre_force`).
    accel_m_s2 : ndarray, shape (..., n)
        Axle acceleration, m/s², upward positive.
    sample_rate_Hz : float
        Sampling rate, Hz.
    excitation_frequency_Hz : float or ndarray, optional
        Centre of the phase-reference band; found with
        :func:`excitation_frequency` when omitted.
    half_band_Hz : float
        Half-width of the phase-reference band-pass, Hz.

    Returns
    -------
    DemodulationResult

    Raises
    ------
    ValueError
        Naming a non-positive rate, band or frequency, or force and
        acceleration of different lengths.

    See Also
    --------
    apparent_mass_welch : the thesis' estimator, for comparison.
    stiffness_damping : K and C from an apparent mass.

    Examples
    --------
    >>> fs = 256.0; t = np.arange(0, 30, 1 / fs); w = 2 * np.pi * 3.8
    >>> x = 0.005 * np.sin(w * t)                              # axle displacement, m
    >>> a = -w**2 * x                                          # its acceleration, m/s²
    >>> f = -(228e3 * x + 2.4e3 * 0.005 * w * np.cos(w * t))  # a Kelvin-Voigt tyre's force, N
    >>> d = apparent_mass_demodulation(f, a, fs)
    >>> round(float(d.frequency_Hz), 3), round(float(d.stiffness_N_per_m)), round(float(d.damping_N_s_per_m))
    (3.8, 228000, 2400)
    """
    half_band_Hz = positive("half_band_Hz", half_band_Hz)
    f, a, excitation_frequency_Hz = _signals(force_N, accel_m_s2, sample_rate_Hz, excitation_frequency_Hz)
    rows, size = (a.shape[0] if a.ndim == 2 else 1), max(2, BLOCK_SAMPLES // a.shape[-1])
    if a.ndim != 2 or rows <= size:
        return _demodulation_block(f, a, sample_rate_Hz, excitation_frequency_Hz, half_band_Hz)
    # Blocks of rows whose temporaries stay in cache; every block has at least two rows, so that each
    # row's sums take the same path as in one call over the whole batch (same numbers to the bit).
    fe = np.broadcast_to(np.asarray(excitation_frequency_Hz, dtype=float), (rows,))
    parts = [_demodulation_block(f[b], a[b], sample_rate_Hz, fe[b], half_band_Hz)
             for b in np.array_split(np.arange(rows), -(-rows // size))]
    return DemodulationResult(*(np.concatenate([getattr(p, name) for p in parts])
                                for name in DemodulationResult.__dataclass_fields__))


#: Samples (rows x length) :func:`apparent_mass_demodulation` processes at a time: a batch of
#: 32 runs of 50 s at 256 Hz goes in 4 blocks of 8 runs, each temporary ~0.8 MB instead of 3.3 MB.
BLOCK_SAMPLES = 1 << 17


def _demodulation_block(f: np.ndarray, a: np.ndarray, sample_rate_Hz: float, excitation_frequency_Hz,
                        half_band_Hz: float) -> DemodulationResult:
    """:func:`apparent_mass_demodulation` of checked float arrays (one block of rows)."""
    # one FFT of the acceleration serves both bands taken from it: the phase reference and the displacement
    spectrum, n = _band_spectrum(a, sample_rate_Hz, half_band_Hz)
    z = _analytic_from_spectrum(spectrum, n, sample_rate_Hz, excitation_frequency_Hz, half_band_Hz)
    cos_phi, sin_phi, omega, envelope = _instantaneous_phase(a, sample_rate_Hz, excitation_frequency_Hz,
                                                             half_band_Hz, z)
    n = a.shape[-1]
    w = np.hanning(n)
    fc = f - f.mean(axis=-1, keepdims=True)
    wa = w * (a - a.mean(axis=-1, keepdims=True))
    num = _demodulate(w * fc, cos_phi, sin_phi)
    den = _demodulate(wa / omega**2, cos_phi, sin_phi)
    # for the uncertainty: minus the displacement of the excitation band (analytic, by double integration
    # in the frequency domain), the regressor of the tyre model whose residual the probes measure
    xi = _analytic_from_spectrum(spectrum, n, sample_rate_Hz, excitation_frequency_Hz, half_band_Hz, True)
    np.negative(xi, out=xi)
    dynamic_stiffness = num / den  # K + jωC, upward-positive recording convention
    weight = w * envelope
    omega_mean = np.sum(weight * omega, axis=-1) / np.sum(weight, axis=-1)
    freq = omega_mean / (2 * np.pi)
    h = -dynamic_stiffness / omega_mean**2
    k, c = stiffness_damping(h, freq)
    residual = _tyre_residual(fc, xi, omega, w)
    accel_amp = 2.0 * np.abs(_demodulate(wa, cos_phi, sin_phi)) / np.sum(w, axis=-1)
    disp_amp = 2.0 * np.abs(den) / np.sum(w, axis=-1)
    return DemodulationResult(h, freq, k, c, disp_amp, accel_amp, envelope, omega, den,
                              _probe_sums(w * residual, cos_phi, sin_phi))


def welch_segments_at(x: np.ndarray, sample_rate_Hz: float, frequency_Hz, nperseg: int) -> np.ndarray:
    """DFT coefficients of Welch's segments at one bin frequency per row.

    Exactly what :func:`scipy.signal.csd` / :func:`scipy.signal.welch` average
    at that bin (periodic Hann window, 50 % overlap, each segment's mean
    removed), up to the density scaling, which cancels in H1 and the
    coherence. Evaluating one bin by a dot product instead of every bin by an
    FFT makes the thesis estimator cheap.

    Parameters
    ----------
    x : ndarray, shape (..., n)
    sample_rate_Hz : float
    frequency_Hz : float or ndarray, shape (...)
        A bin frequency (multiple of ``sample_rate_Hz / nperseg``), Hz.
    nperseg : int
        Segment length.

    Returns
    -------
    ndarray of complex, shape (..., n_segments)

    See Also
    --------
    apparent_mass_welch : the thesis estimator it makes cheap.

    Examples
    --------
    >>> from scipy import signal
    >>> fs, n = 256.0, 256; x = np.random.default_rng(1).normal(size=2048)
    >>> seg = welch_segments_at(x, fs, 4.0, n)
    >>> f, p = signal.welch(x, fs, nperseg=n)
    >>> k = int(np.argmin(np.abs(f - 4.0)))
    >>> win = signal.get_window("hann", n)                 # Welch's density scaling, one-sided
    >>> bool(np.isclose(2 * np.mean(np.abs(seg) ** 2) / (fs * np.sum(win**2)), p[k])), seg.shape
    (True, (15,))
    """
    positive("sample_rate_Hz", sample_rate_Hz)
    if not (isinstance(nperseg, (int, np.integer)) and 2 <= nperseg <= np.shape(x)[-1]):
        raise ValueError(f"nperseg must be an integer from 2 to the signal length {np.shape(x)[-1]}, got {nperseg!r}")
    segments = np.lib.stride_tricks.sliding_window_view(x, nperseg, axis=-1)[..., :: nperseg // 2, :]
    window = signal.get_window("hann", nperseg)
    k = np.arange(nperseg)
    theta = 2 * np.pi * np.asarray(frequency_Hz, dtype=float)[..., np.newaxis] * k / sample_rate_Hz
    kc, ks = window * np.cos(theta), window * np.sin(theta)  # kernel = kc - j ks
    raw = np.einsum("...sk,...k->...s", segments, kc) - 1j * np.einsum("...sk,...k->...s", segments, ks)
    return raw - segments.mean(axis=-1) * (kc.sum(axis=-1) - 1j * ks.sum(axis=-1))[..., np.newaxis]


@dataclass(frozen=True)
class WelchResult:
    """Output of :func:`apparent_mass_welch` (arrays of shape (...))."""

    apparent_mass_kg: np.ndarray  #: H at the excitation bin, thesis convention, kg
    frequency_Hz: np.ndarray  #: frequency of that bin, Hz
    stiffness_N_per_m: np.ndarray  #: K, N/m
    damping_N_s_per_m: np.ndarray  #: C, N s/m
    coherence: np.ndarray  #: magnitude-squared coherence at that bin


def apparent_mass_welch(
    force_N: np.ndarray,
    accel_m_s2: np.ndarray,
    sample_rate_Hz: float,
    excitation_frequency_Hz: float | np.ndarray | None = None,
    resolution_Hz: float = 0.125,
) -> WelchResult:
    """Apparent mass the thesis' way: H1 from Welch spectra, read at the excitation bin.

    ``H1 = G_af / G_aa`` with ``G_af = csd(a, f)`` (scipy's ``csd(x, y)`` is
    ``conj(X) Y``, so this is the estimator of the system from acceleration to
    force) and ``G_aa = welch(a)``; Hann window, 50 % overlap, segment length
    the power of two giving about ``resolution_Hz`` bins (thesis §3.3.1,
    Fig. 19). H is read at the bin nearest the excitation frequency and K, C
    are computed at that bin's frequency, as the thesis did: this suffers
    picket-fence error when the excitation falls between bins.

    Parameters
    ----------
    force_N, accel_m_s2 : ndarray, shape (..., n)
        Tyre force (N) and axle acceleration (m/s²), upward positive.
    sample_rate_Hz : float
        Sampling rate, Hz.
    excitation_frequency_Hz : float or ndarray, optional
        Excitation frequency, Hz (found with :func:`excitation_frequency` if omitted).
    resolution_Hz : float
        Target bin width, Hz.

    Returns
    -------
    WelchResult

    Raises
    ------
    ValueError
        Naming a non-positive rate, resolution or frequency, or force and
        acceleration of different lengths.

    See Also
    --------
    apparent_mass_demodulation : tyrelab's estimator, without picket-fence error.
    h1_spectrum : the full H1 spectrum.

    Notes
    -----
    The same estimator as :func:`h1_spectrum` (``-H1``, acceleration to
    force), evaluated at one bin by :func:`welch_segments_at` instead of at
    every bin; a test checks they agree.

    Examples
    --------
    >>> apparent_mass_welch(np.ones(64), np.ones(64), 0.0)
    Traceback (most recent call last):
    ...
    ValueError: sample_rate_Hz must be finite and positive, got 0.0
    """
    resolution_Hz = positive("resolution_Hz", resolution_Hz)
    f, a, excitation_frequency_Hz = _signals(force_N, accel_m_s2, sample_rate_Hz, excitation_frequency_Hz)
    n = a.shape[-1]
    nperseg = min(1 << int(round(np.log2(sample_rate_Hz / resolution_Hz))), 1 << int(np.log2(n)))
    df = sample_rate_Hz / nperseg
    fe = np.broadcast_to(np.asarray(excitation_frequency_Hz, dtype=float), a.shape[:-1])
    fbin = np.clip(np.rint(fe / df), 0, nperseg // 2) * df
    seg_a = welch_segments_at(a, sample_rate_Hz, fbin, nperseg)
    seg_f = welch_segments_at(f, sample_rate_Hz, fbin, nperseg)
    gaf = np.mean(np.conj(seg_a) * seg_f, axis=-1)
    gaa = np.mean(np.abs(seg_a) ** 2, axis=-1)
    gff = np.mean(np.abs(seg_f) ** 2, axis=-1)
    h_up = gaf / gaa
    coherence = np.abs(gaf) ** 2 / (gaa * gff)
    h = -h_up
    k, c = stiffness_damping(h, fbin)
    return WelchResult(h, fbin, k, c, coherence)


@dataclass(frozen=True)
class H1Spectrum:
    """Output of :func:`h1_spectrum` (arrays over frequency)."""

    frequency_Hz: np.ndarray  #: bin frequencies, Hz
    h1: np.ndarray  #: H1 = G_xy / G_xx, the system from x to y (units of y per unit of x)
    coherence: np.ndarray  #: magnitude-squared coherence of x and y
    psd_x: np.ndarray  #: G_xx, one-sided PSD of x (units of x squared per Hz)


def h1_spectrum(x: np.ndarray, y: np.ndarray, sample_rate_Hz: float, nperseg: int) -> H1Spectrum:
    """H1 transfer function from ``x`` to ``y`` and their coherence, from Welch spectra.

    ``H1 = G_xy / G_xx`` with ``G_xy = csd(x, y)`` (scipy's ``csd(x, y)`` is
    ``conj(X) Y``, so this is the system from x to y) and ``G_xx = welch(x)``;
    coherence ``|G_xy|² / (G_xx G_yy)``. Hann window, 50 % overlap, each
    segment's mean removed (scipy's defaults; thesis §3.3.1, Fig. 19). The
    one implementation of the full-spectrum H1: the calibration check
    (force plate -> derived force), the half-power method (force ->
    acceleration) and the report's per-run spectra call it.

    Parameters
    ----------
    x, y : ndarray, shape (n,)
        Input and output signals, same length.
    sample_rate_Hz : float
        Sampling rate, Hz.
    nperseg : int
        Segment length, from 2 to ``n``.

    Returns
    -------
    H1Spectrum

    Raises
    ------
    ValueError
        Naming a non-positive rate, a bad ``nperseg`` or signals of different lengths.

    See Also
    --------
    apparent_mass_welch : H1 read at the excitation bin.
    welch_segments_at : one bin of the same segments.

    Examples
    --------
    A pure gain of 2 has H1 = 2 and coherence 1 at every bin:

    >>> rng = np.random.default_rng(0)
    >>> x = rng.standard_normal(4096)
    >>> s = h1_spectrum(x, 2 * x, 256.0, 256)
    >>> bool(np.allclose(s.h1[1:], 2) and np.allclose(s.coherence[1:], 1))
    True
    """
    sample_rate_Hz = positive("sample_rate_Hz", sample_rate_Hz)
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    same_last_axis(x=x, y=y)
    if not (isinstance(nperseg, (int, np.integer)) and 2 <= nperseg <= x.shape[-1]):
        raise ValueError(f"nperseg must be an integer from 2 to the signal length {x.shape[-1]}, got {nperseg!r}")
    f, gxy = signal.csd(x, y, fs=sample_rate_Hz, nperseg=nperseg)
    _, gxx = signal.welch(x, fs=sample_rate_Hz, nperseg=nperseg)
    _, gyy = signal.welch(y, fs=sample_rate_Hz, nperseg=nperseg)
    with np.errstate(divide="ignore", invalid="ignore"):
        h1 = gxy / gxx
        coherence = np.abs(gxy) ** 2 / (gxx * gyy)
    return H1Spectrum(f, h1, coherence, gxx)
