"""Ground profiles: the slatted rough track stand-in, ISO 8608 farm tracks, spectra.

Thesis §6.2 and §7.2: the carriage and the MF698T were driven over the 100 m
artificial rough track of ISO/TR 5007 (1979) (now ISO 5008), wooden slats 80 mm wide
with 80 mm gaps, two wheel tracks; the tractor also over an unmetalled farm track.

**The slat heights of the standard track are not public.** :func:`slatted_track`
makes a *seeded stand-in*: slat-top heights drawn as a Gaussian random process
with an ISO 8608-type displacement spectrum ``G(n) = G0 (n/n0)^-2`` (the slope of
Fig. 51 below 1.2 cycles/m), one independent realisation per wheel track. It is
labelled as such in every output. The farm track (:func:`iso8608_track`) uses the
ISO 8608 class geometric means (field notes), not the class upper bounds.

Heights in m, distances in m, spatial frequency n in cycles/m, displacement PSD
in m^2/(cycles/m) = m^3.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy import signal

from ... import _validate

__all__ = [
    "Profile",
    "ISO8608_CLASS_G0_M3",
    "ISO8608_N0_CYCLES_PER_M",
    "SLATTED_TRACK_G0_M3",
    "spectral_synthesis",
    "slatted_track",
    "slat_surface",
    "iso8608_track",
    "isotropic_coherence",
    "TRACK_MODELS",
    "profile_spectrum",
    "side_spectra",
    "add_lead_in",
    "uniform_grid",
    "ROAD_HEIGHT_BOUNDS_M",
]

#: Lowest and highest height a road may have under a wheel, m, from every source alike (a profile
#: CSV's heights, a CRG road's under each wheel; ``profile.height_m`` of the scenario limits is
#: this): a plausibility bound far beyond any farm track's (ISO 8608 class H at 10 mm steps stays
#: within a few hundred mm), below a road written in millimetres as metres (a documented choice).
ROAD_HEIGHT_BOUNDS_M = (-2.0, 2.0)

#: ISO 8608 reference spatial frequency n0, cycles/m.
ISO8608_N0_CYCLES_PER_M = 0.1
#: ISO 8608 class geometric means of G_d(n0), m^3 (field notes; not the upper bounds).
ISO8608_CLASS_G0_M3 = {c: g * 1e-6 for c, g in zip("ABCDEFGH", (16, 64, 256, 1024, 4096, 16384, 65536, 262144))}
#: Stand-in spectrum level of the slatted track at n0, m^3: the ISO 8608 class D
#: geometric mean, giving slat-top heights of about 14 mm rms over 0.01-3 cycles/m.
#: Chosen so the simulated MF698T vertical rms at 10 km/h is of the order the thesis
#: reports (1.79 m/s^2 measured, 1.91 predicted, Table XVIII); a stand-in.
SLATTED_TRACK_G0_M3 = 1024e-6
#: Slat width and gap of the ISO/TR 5007 track, m (thesis §6.2).
SLAT_WIDTH_M = 0.08
SLAT_GAP_M = 0.08


@dataclass(frozen=True)
class Profile:
    """A two-track ground profile on a uniform grid.

    Attributes
    ----------
    x_m : ndarray
        Distance along the track, m, uniform spacing.
    left_m, right_m : ndarray
        Elevation of the left and right wheel tracks, m.
    label : str
        What the profile is (e.g. ``"slatted track (seeded stand-in, seed 1)"``).
    meta : dict
        Generation parameters (seed, class, G0, ...).
    rear_left_m, rear_right_m : ndarray or None
        The rear wheels' own tracks where they differ from the front wheels' (a road surface whose
        heights the front and rear wheels of different track widths sample apart: a CRG road);
        None: the rear wheels follow the front ones' tracks.
    """

    x_m: np.ndarray
    left_m: np.ndarray
    right_m: np.ndarray
    label: str
    meta: dict = field(default_factory=dict)
    rear_left_m: np.ndarray | None = None
    rear_right_m: np.ndarray | None = None

    @property
    def dx_m(self) -> float:
        """Sample spacing, m."""
        return float(self.x_m[1] - self.x_m[0])

    def track(self, side: str, axle: str = "front") -> np.ndarray:
        """Elevation of ``"left"``, ``"right"`` or ``"mean"`` (axle centre) under ``axle``'s wheels
        (``"front"``, ``"rear"``: the rear tracks when the profile has its own), m."""
        if axle not in ("front", "rear"):
            raise ValueError(f"axle {axle!r}: expected front or rear")
        rear = axle == "rear" and self.rear_left_m is not None
        left, right = (self.rear_left_m, self.rear_right_m) if rear else (self.left_m, self.right_m)
        if side == "left":
            return left
        if side == "right":
            return right
        if side == "mean":
            return 0.5 * (left + right)
        raise ValueError(f"side {side!r}: expected left, right or mean")

    def replace(self, left_m=None, right_m=None, label=None, **meta) -> "Profile":
        """A copy with other elevations/label and extra metadata."""
        return Profile(
            self.x_m,
            self.left_m if left_m is None else np.asarray(left_m, float),
            self.right_m if right_m is None else np.asarray(right_m, float),
            self.label if label is None else label,
            {**self.meta, **meta},
            self.rear_left_m,
            self.rear_right_m,
        )


def spectral_synthesis(
    n_samples: int,
    dx_m: float,
    g0_m3: float,
    rng: np.random.Generator,
    waviness: float = 2.0,
    n_min_cycles_per_m: float = 0.0,
    n_max_cycles_per_m: float | None = None,
) -> np.ndarray:
    """Gaussian random profile with spectrum ``G(n) = G0 (n/n0)^-w`` (ISO 8608 §C).

    Sum of cosines at the FFT frequencies ``n_k = k/(N dx)`` with amplitudes
    ``sqrt(2 G(n_k) dn)`` and uniform random phases (computed with one inverse FFT).

    Parameters
    ----------
    n_samples : int
        Number of samples N.
    dx_m : float
        Spacing, m.
    g0_m3 : float
        G_d(n0) in m^3, n0 = 0.1 cycles/m.
    rng : numpy.random.Generator
        Source of the phases (seeded by the caller).
    waviness : float
        Exponent w (ISO 8608: 2).
    n_min_cycles_per_m, n_max_cycles_per_m : float
        Band of spatial frequencies included (default: all but the mean).

    Returns
    -------
    ndarray
        Elevations in m, zero mean.

    See Also
    --------
    iso8608_track : two tracks of an ISO 8608 class.
    profile_spectrum : its PSD.

    Examples
    --------
    >>> h = spectral_synthesis(4096, 0.05, 256e-6, np.random.default_rng(1), n_max_cycles_per_m=2.83)
    >>> h.shape, round(float(h.mean()), 12)
    ((4096,), 0.0)
    """
    g0_m3 = _validate.positive("g0_m3", g0_m3)
    dx_m = _validate.positive("dx_m", dx_m)
    if int(n_samples) < 2:
        raise ValueError(f"n_samples must be at least 2, got {n_samples!r}")
    n = np.fft.rfftfreq(n_samples, dx_m)
    dn = n[1]
    g = np.zeros_like(n)
    hi = n_max_cycles_per_m if n_max_cycles_per_m is not None else n[-1]
    band = (n > 0) & (n >= n_min_cycles_per_m) & (n <= hi)
    g[band] = g0_m3 * (n[band] / ISO8608_N0_CYCLES_PER_M) ** (-waviness)
    amp = np.sqrt(2.0 * g * dn)
    phase = rng.uniform(0.0, 2.0 * np.pi, n.size)
    spec = 0.5 * n_samples * amp * np.exp(1j * phase)
    spec[0] = 0.0
    return np.fft.irfft(spec, n_samples)


def slatted_track(
    seed: int = 5007,
    length_m: float = 100.0,
    dx_m: float = 0.01,
    g0_m3: float = SLATTED_TRACK_G0_M3,
) -> Profile:
    """Seeded stand-in for the ISO/TR 5007 slatted rough track (thesis §6.2).

    One slat every 0.16 m (80 mm slat, 80 mm gap). Slat-top heights are samples,
    at the slat centres, of a Gaussian process with spectrum ``G0 (n/n0)^-2``
    (n up to the slat Nyquist 3.125 cycles/m), independent for the left and right
    wheel tracks, shifted so the lowest slat of each track is 10 mm above the base.
    The returned elevations are the slat tops joined by straight lines across the
    gaps, i.e. what a surveyor measuring slat tops records (thesis §6.3 a); the
    gap-resolved surface is :func:`slat_surface`.

    **A stand-in**: the standard's slat heights are not public (field notes).

    Parameters
    ----------
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    length_m : float
        Track length, m (100 m in the thesis).
    dx_m : float
        Output spacing, m.
    g0_m3 : float
        Spectrum level G(n0), m^3.

    Returns
    -------
    Profile
        ``meta`` holds ``slat_x_m``, ``left_slats_m``, ``right_slats_m``.

    See Also
    --------
    slat_surface : its slats and gaps resolved.

    Examples
    --------
    >>> tr = slatted_track(seed=1, length_m=10.0)
    >>> round(float(np.diff(tr.meta["slat_x_m"]).mean()), 2), tr.dx_m     # a slat every 0.16 m
    (0.16, 0.01)
    """
    seed = _validate.positive_int("seed", seed, minimum=0)
    length_m = _validate.positive("length_m", length_m)
    dx_m = _validate.positive("dx_m", dx_m)
    g0_m3 = _validate.positive("g0_m3", g0_m3)
    rng = np.random.default_rng(seed)
    pitch = SLAT_WIDTH_M + SLAT_GAP_M
    n_slats = int(round(length_m / pitch))
    slat_x = (np.arange(n_slats) + 0.5) * pitch
    tops = []
    for _ in ("left", "right"):
        h = spectral_synthesis(n_slats, pitch, g0_m3, rng)
        tops.append(h - h.min() + 0.010)
    x = np.arange(int(round(length_m / dx_m)) + 1) * dx_m
    left = np.interp(x, slat_x, tops[0])
    right = np.interp(x, slat_x, tops[1])
    return Profile(
        x,
        left,
        right,
        f"ISO/TR 5007 slatted track, seeded stand-in (seed {seed})",
        {
            "kind": "slatted_track",
            "seed": seed,
            "g0_m3": g0_m3,
            "stand_in": True,
            "slat_x_m": slat_x,
            "left_slats_m": tops[0],
            "right_slats_m": tops[1],
        },
    )


def slat_surface(track: Profile, side: str = "left") -> np.ndarray:
    """Gap-resolved surface of a slatted track: slat top on slats, base (0 m) in gaps.

    Parameters
    ----------
    track : Profile
        From :func:`slatted_track`.
    side : {"left", "right"}

    Returns
    -------
    ndarray
        Elevation at ``track.x_m``, m.

    See Also
    --------
    slatted_track : the track it resolves.

    Examples
    --------
    >>> tr = slatted_track(seed=1, length_m=2.0)
    >>> s = slat_surface(tr, "left")
    >>> float(s.min()), bool(s.max() >= 0.010)          # the base in the gaps, slats at least 10 mm above it
    (0.0, True)
    """
    _validate.instance("track", track, Profile)
    _validate.choice("side", side, ("left", "right"))
    if "slat_x_m" not in track.meta:
        raise ValueError("track must be a slatted_track (its meta has no slats)")
    slat_x = track.meta["slat_x_m"]
    tops = track.meta[f"{side}_slats_m"]
    pitch = SLAT_WIDTH_M + SLAT_GAP_M
    k = np.clip(np.floor(track.x_m / pitch).astype(int), 0, slat_x.size - 1)
    on_slat = np.abs(track.x_m - slat_x[k]) <= SLAT_WIDTH_M / 2 + 1e-12
    return np.where(on_slat, tops[k], 0.0)


#: Left/right track relations of :func:`iso8608_track`.
TRACK_MODELS = ("independent", "isotropic", "identical")


def isotropic_coherence(n_cycles_per_m, track_width_m: float) -> np.ndarray:
    """Coherence (real, the cross-spectrum over the single-track PSD) of two parallel tracks
    ``b`` apart on an isotropic surface whose track PSD falls as ``n^-2`` (waviness 2).

    ``ρ(n) = κ b K₁(κ b)``, ``κ = 2π n``: the cross-spectrum of an isotropic surface, an
    integral of its two-dimensional spectrum over the lateral wavenumber (Dodds and Robson
    1973, "The description of road surface roughness", J. Sound Vib. 31(2) 175-183), in closed
    form for w = 2 (the 2-D spectrum ∝ |k|⁻³: ``∫ (κ² + k₂²)^(-3/2) cos(k₂ b) dk₂ = 2 b K₁(κ b)/κ``
    against ``2/κ²`` for ``b = 0``). 1 at long wavelengths, falling to 0.5 near ``n ≈ 0.2/b``.

    See Also
    --------
    iso8608_track : two tracks with this coherence.

    Examples
    --------
    >>> np.round(isotropic_coherence([0.0, 0.1, 1.0], 1.8), 3).tolist()
    [1.0, 0.548, 0.0]
    """
    from scipy.special import k1

    n = np.asarray(n_cycles_per_m, float)
    _validate.positive("track_width_m", track_width_m)
    x = 2 * np.pi * n * track_width_m
    with np.errstate(invalid="ignore", divide="ignore"):
        rho = np.where(x > 0, x * k1(np.where(x > 0, x, 1.0)), 1.0)
    return rho


def iso8608_track(
    road_class: str = "D",
    seed: int = 8608,
    length_m: float = 200.0,
    dx_m: float = 0.05,
    n_min_cycles_per_m: float = 0.011,
    n_max_cycles_per_m: float = 2.83,
    tracks: str = "independent",
    track_width_m: float | None = None,
) -> Profile:
    """Seeded two-track random profile of an ISO 8608 class (farm track, thesis §7.2).

    Uses the class geometric mean of G_d(n0) (field notes), w = 2, band 0.011-2.83
    cycles/m (ISO 8608's range). The thesis' farm track was surveyed at 50 mm
    intervals, hence the default spacing. ``tracks`` (:data:`TRACK_MODELS`):
    ``independent`` left and right tracks (the default, as before), ``identical`` (the
    right is the left: no roll input) or ``isotropic`` (the right track's Fourier
    coefficients ``ρ L + sqrt(1 - ρ²) N`` with ``N`` an independent track and ``ρ``
    :func:`isotropic_coherence` at ``track_width_m``: each track keeps the class PSD and
    their cross-spectrum is ``ρ`` times it).

    Parameters
    ----------
    road_class : str
        ISO 8608 class letter A-H.
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    length_m, dx_m : float
        Length and spacing, m.

    Returns
    -------
    Profile

    See Also
    --------
    spectral_synthesis : the random process of each track.
    isotropic_coherence : the coherence of ``tracks="isotropic"``.
    profile_spectrum : the PSD of the result.

    Examples
    --------
    >>> p = iso8608_track("C", seed=1, length_m=400.0)
    >>> n, g = profile_spectrum(p.left_m, p.dx_m)
    >>> band = (n > 0.05) & (n < 0.5)                  # G_d(n) n² is G_d(n0) n0² for waviness 2
    >>> fitted = float(np.exp(np.mean(np.log(g[band] * (n[band] / 0.1) ** 2))))
    >>> bool(0.5 < fitted / ISO8608_CLASS_G0_M3["C"] < 2.0), p.dx_m
    (True, 0.05)
    """
    length_m = _validate.positive("length_m", length_m)
    dx_m = _validate.positive("dx_m", dx_m)
    c = road_class.upper()
    if c not in ISO8608_CLASS_G0_M3:
        raise ValueError(f"ISO 8608 class {road_class!r}: expected one of A-H")
    if tracks not in TRACK_MODELS:
        raise ValueError(f"tracks {tracks!r}: expected one of {TRACK_MODELS}")
    if tracks == "isotropic":
        track_width_m = _validate.positive("track_width_m", track_width_m)
    rng = np.random.default_rng(seed)
    n = int(round(length_m / dx_m))
    g0 = ISO8608_CLASS_G0_M3[c]
    left, right = (
        spectral_synthesis(n, dx_m, g0, rng, 2.0, n_min_cycles_per_m, n_max_cycles_per_m) for _ in range(2)
    )
    if tracks == "identical":
        right = left.copy()
    elif tracks == "isotropic":
        rho = isotropic_coherence(np.fft.rfftfreq(n, dx_m), track_width_m)
        right = np.fft.irfft(rho * np.fft.rfft(left) + np.sqrt(1.0 - rho**2) * np.fft.rfft(right), n)
    return Profile(
        np.arange(n) * dx_m,
        left,
        right,
        f"ISO 8608 class {c} farm track, seeded (seed {seed})",
        {"kind": "iso8608", "road_class": c, "g0_m3": g0, "seed": seed, "tracks": tracks},
    )


def uniform_grid(x_m, *heights_m) -> tuple[np.ndarray, list[np.ndarray]]:
    """A profile file's heights on its own uniform grid: spacing the median step of ``x_m``, from its
    first distance to its last (``(end - start)/dx`` is a whole number up to the rounding of the
    distances written in the file, which must not drop the last sample); heights interpolated.

    See Also
    --------
    tyrelab.scenario_io.read_profile_csv : reads a profile file onto it.

    Examples
    --------
    >>> g, (h,) = uniform_grid([0.0, 0.1, 0.2, 0.35, 0.4], [0.0, 1.0, 2.0, 3.5, 4.0])
    >>> [round(float(v), 3) for v in g], [round(float(v), 3) for v in h]
    ([0.0, 0.1, 0.2, 0.3, 0.4], [0.0, 1.0, 2.0, 3.0, 4.0])
    """
    x = _validate.finite_array("x_m", x_m, min_samples=2)
    dx = float(np.median(np.diff(x)))
    grid = x[0] + np.arange(int(np.floor((x[-1] - x[0]) / dx + 1e-6)) + 1) * dx
    return grid, [np.interp(grid, x, np.asarray(h, float)) for h in heights_m]


def add_lead_in(profile: Profile, lead_in_m: float = 5.0) -> Profile:
    """Prepend a level approach at the first elevation and append a level run-out.

    Lets a simulation start at rest on level ground; ``meta['lead_in_m']`` records
    the offset so analyses can skip it.

    See Also
    --------
    iso8608_track : a profile to lead into.

    Examples
    --------
    >>> p = iso8608_track("C", seed=1, length_m=20.0)
    >>> q = add_lead_in(p, 5.0)
    >>> round(float(q.x_m[-1] - p.x_m[-1]), 2), q.meta["lead_in_m"], float(q.left_m[0]) == float(p.left_m[0])
    (10.0, 5.0, True)
    """
    _validate.instance("profile", profile, Profile)
    lead_in_m = _validate.non_negative("lead_in_m", lead_in_m)
    dx = profile.dx_m
    k = int(round(lead_in_m / dx))
    x = np.arange(profile.x_m.size + 2 * k) * dx
    pad = lambda h: None if h is None else np.concatenate([np.full(k, h[0]), h, np.full(k, h[-1])])  # noqa: E731
    return Profile(x, pad(profile.left_m), pad(profile.right_m), profile.label, {**profile.meta, "lead_in_m": k * dx},
                   pad(profile.rear_left_m), pad(profile.rear_right_m))


def profile_spectrum(elevation_m, dx_m: float, segment_m: float = 12.8,
                     detrend: str = "linear") -> tuple[np.ndarray, np.ndarray]:
    """One-sided displacement PSD of a profile by Welch's method (thesis Fig. 51).

    Parameters
    ----------
    elevation_m : array_like
        Elevations, m, uniform spacing.
    dx_m : float
        Spacing, m.
    segment_m : float
        Welch segment length, m (resolution 1/segment cycles/m), Hann, 50 % overlap.
    detrend : str
        Each segment's trend taken out: ``linear`` (the profiles' spectra, Fig. 51) or ``constant``
        (its mean: the 3-D ride's side spectra, :func:`side_spectra`).

    Returns
    -------
    n_cycles_per_m, psd_m3 : ndarray
        Spatial frequency (cycles/m) and PSD in m^2/(cycles/m).

    See Also
    --------
    spectral_synthesis : a profile of a given spectrum.

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> h = spectral_synthesis(2**14, 0.05, 256e-6, rng, n_min_cycles_per_m=0.011, n_max_cycles_per_m=2.83)
    >>> n, g = profile_spectrum(h, 0.05)
    >>> round(float(n[1]), 4)                           # 1 / 12.8 m
    0.0781
    >>> bool(0.5 < float(np.median(g[(n > 0.08) & (n < 1)] * (n[(n > 0.08) & (n < 1)] / 0.1) ** 2)) / 256e-6 < 2)
    True
    """
    _validate.finite_array("elevation_m", elevation_m, min_samples=2)
    dx_m = _validate.positive("dx_m", dx_m)
    segment_m = _validate.positive("segment_m", segment_m)
    _validate.choice("detrend", detrend, ("linear", "constant"))
    h = np.asarray(elevation_m, dtype=float)
    nper = min(h.size, int(round(segment_m / dx_m)))
    return signal.welch(h, fs=1.0 / dx_m, window="hann", nperseg=nper, noverlap=nper // 2, detrend=detrend)


def side_spectra(left_m, right_m, dx_m: float, segment_m: float,
                 detrend: str = "constant") -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The two wheel tracks' spectra and their cross-spectrum by Welch's method, as
    :func:`profile_spectrum` (Hann, 50 % overlap; each segment's mean taken out by default): the
    side spectra of a 3-D ride over a measured road (issue 45: one Welch for the profiles).

    Parameters
    ----------
    left_m, right_m : array_like
        Elevations of the left and right tracks, m, on the same grid of spacing ``dx_m``.
    dx_m, segment_m : float
        Spacing and Welch segment length, m.
    detrend : str
        As :func:`profile_spectrum`.

    Returns
    -------
    n_cycles_per_m, g_ll, g_rr, g_lr : ndarray
        Spatial frequency (cycles/m), the tracks' PSDs and their cross-spectrum, m^2/(cycles/m).
        ``g_lr`` is ``E[L R*]`` (the model's ``S_LR``: the output spectrum is ``h S hᴴ``);
        :func:`scipy.signal.csd` ``(x, y)`` averages ``conj(X) Y``, hence ``csd(right, left)``.

    See Also
    --------
    profile_spectrum : one track's spectrum, the same Welch.

    Examples
    --------
    Two tracks half a wavelength apart: opposite phase, the cross-spectrum minus the spectrum.

    >>> x = np.arange(4096) * 0.05
    >>> n, g_ll, g_rr, g_lr = side_spectra(np.sin(2 * np.pi * x), -np.sin(2 * np.pi * x), 0.05, 12.8)
    >>> k = int(np.argmax(g_ll))
    >>> float(n[k]), bool(np.isclose(g_lr[k].real, -g_ll[k])), bool(np.isclose(g_rr[k], g_ll[k]))
    (1.015625, True, True)
    """
    n, g_ll = profile_spectrum(left_m, dx_m, segment_m, detrend)
    _, g_rr = profile_spectrum(right_m, dx_m, segment_m, detrend)
    h_l, h_r = np.asarray(left_m, dtype=float), np.asarray(right_m, dtype=float)
    if h_l.shape != h_r.shape:
        raise ValueError(f"right_m: {h_r.size} samples, left_m has {h_l.size}")
    nper = min(h_l.size, int(round(segment_m / dx_m)))
    _, g_lr = signal.csd(h_r, h_l, fs=1.0 / dx_m, window="hann", nperseg=nper, noverlap=nper // 2, detrend=detrend)
    return n, g_ll, g_rr, g_lr


def spectra_table(profiles: dict[str, np.ndarray], dx_m: float, segment_m: float = 12.8) -> pd.DataFrame:
    """Long table of profile spectra: ``profile, n_cycles_per_m, psd_m3``."""
    frames = []
    for name, h in profiles.items():
        n, g = profile_spectrum(h, dx_m, segment_m)
        frames.append(pd.DataFrame({"profile": name, "n_cycles_per_m": n, "psd_m3": g}))
    return pd.concat(frames, ignore_index=True)
