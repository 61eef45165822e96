"""Tyre enveloping: redefining the ground input of a point-contact tyre (thesis §1.5, §6.3).

Three redefinitions of a profile (each a pure function on a uniformly sampled
elevation array):

* :func:`fixed_footprint` - local average over the contact-patch length
  (rectangular window);
* :func:`tapered_moving_average` - the "simple tapered moving average filter" of
  Nguyen and Lines (1988) used in §6.3: a local average over the contact patch,
  tapered at each end to reduce the side bands of the rectangular window. The
  published coefficients are not reproduced in the thesis; we use a Tukey
  (cosine-tapered) window whose flat part and tapers together span the contact
  length, taper fraction 0.5 by default - an approximation, not their coefficients;
* :func:`rigid_tread_band` - locus of the centre of a rigid wheel rolling over the
  ground (Captain, Boghani and Wormley 1979), minus the radius.

Distances in m.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import signal

from ... import _validate

__all__ = [
    "contact_length",
    "fixed_footprint",
    "tapered_moving_average",
    "tapered_window",
    "window",
    "rigid_tread_band",
    "TAPER_FRACTION",
]

#: Tukey taper fraction of the tapered moving average (§6.3; an approximation of Nguyen and Lines'
#: coefficients, see the module's text): its window spans ``1 + TAPER_FRACTION / 2`` contact lengths.
TAPER_FRACTION = 0.5


def contact_length(radius_m: float, deflection_m: float) -> float:
    """Contact-patch length of a tyre pressed onto flat ground, ``2 sqrt(2 R d - d²)``, m.

    Chord of a circle of radius ``R`` cut at depth ``d`` (``≈ 2 sqrt(2 R d)``
    for small ``d``).

    See Also
    --------
    fixed_footprint, tapered_moving_average : filters of this length.

    Examples
    --------
    >>> round(contact_length(0.742, 0.05), 3)
    0.536
    """
    radius_m = _validate.positive("radius_m", radius_m)
    deflection_m = _validate.non_negative("deflection_m", deflection_m)
    d = max(float(deflection_m), 0.0)
    return 2.0 * math.sqrt(max(2.0 * radius_m * d - d * d, 0.0))


def _fraction(name: str, value) -> float:
    v = _validate.non_negative(name, value)
    if v > 1:
        raise ValueError(f"{name} must be from 0 to 1, got {value!r}")
    return v


def _moving(heights, w: np.ndarray) -> np.ndarray:
    """``heights`` averaged by the centred taps ``w`` (:func:`window`), the ends padded with the end values."""
    h = np.asarray(heights, dtype=float)
    k = w.size // 2
    padded = np.concatenate([np.full(k, h[0]), h, np.full(w.size - 1 - k, h[-1])])
    return signal.fftconvolve(padded, w[::-1], mode="valid") if h.size > 2000 else np.convolve(padded, w[::-1], mode="valid")


def fixed_footprint(heights_m, dx_m: float, footprint_m: float) -> np.ndarray:
    """Fixed-footprint enveloping: centred mean over the contact length (thesis §1.5).

    Parameters
    ----------
    heights_m : array_like
        Profile elevations, m, spacing ``dx_m``.
    dx_m : float
        Spacing, m.
    footprint_m : float
        Contact-patch length, m.

    Returns
    -------
    ndarray
        Enveloped elevations, same length (ends padded with the end values).

    See Also
    --------
    tapered_moving_average : the tapered filter of the same length.
    rigid_tread_band : a rigid disc instead.

    Examples
    --------
    >>> h = np.r_[np.zeros(50), np.full(50, 0.1)]           # a 100 mm step, 1 cm spacing
    >>> e = fixed_footprint(h, 0.01, 0.21)                      # a 21 cm footprint
    >>> round(float(e[50 - 15]), 6), round(float(e[49]), 3), round(float(e[50 + 15]), 6)
    (0.0, 0.048, 0.1)
    """
    return _moving(heights_m, window("fixed", footprint_m, dx_m))


def tapered_window(n_samples: int, taper_fraction: float = 0.5) -> np.ndarray:
    """Normalised Tukey window used as the tapered moving average (sums to 1).

    See Also
    --------
    tapered_moving_average : the filter it weights.

    Examples
    --------
    >>> w = tapered_window(9)
    >>> round(float(w.sum()), 12), bool(w[0] < w[4])
    (1.0, True)
    """
    n_samples = _validate.positive_int("n_samples", n_samples)
    taper_fraction = _fraction("taper_fraction", taper_fraction)
    w = signal.windows.tukey(max(int(n_samples), 1), alpha=taper_fraction, sym=True)
    if w.sum() == 0:  # n = 1
        w = np.ones(1)
    return w / w.sum()


def window(kind: str, footprint_m: float, dx_m: float, taper_fraction: float = TAPER_FRACTION) -> np.ndarray:
    """The taps of a linear enveloping filter, centred (odd length) and summing to 1: the one
    home of the windows :func:`fixed_footprint` and :func:`tapered_moving_average` average with and
    the spectral ride's transfer function of the filter reads (issue 45).

    Parameters
    ----------
    kind : str
        ``fixed`` (rectangular over the contact length) or ``tapered`` (a Tukey window of total
        length ``footprint_m * (1 + taper_fraction / 2)``, :func:`tapered_window`).
    footprint_m : float
        Contact-patch length, m.
    dx_m : float
        Spacing of the profile, m.
    taper_fraction : float
        Tukey alpha of ``tapered``.

    Returns
    -------
    ndarray
        The taps (dimensionless), ``max(1, round(length / dx_m) | 1)`` of them.

    See Also
    --------
    tyrelab.vehicle.run.spectral.enveloping_response : the transfer function of these taps.

    Examples
    --------
    >>> window("fixed", 0.3, 0.1).tolist() == [1 / 3] * 3
    True
    >>> w = window("tapered", 0.4, 0.1)
    >>> w.size, float(round(w.sum(), 12)), bool(w[0] < w[2])
    (5, 1.0, True)
    """
    _validate.choice("kind", kind, ("fixed", "tapered"))
    dx_m = _validate.positive("dx_m", dx_m)
    footprint_m = _validate.non_negative("footprint_m", footprint_m)
    taper_fraction = _fraction("taper_fraction", taper_fraction)
    if kind == "fixed":
        taps = np.ones(max(1, int(round(footprint_m / dx_m)) | 1))  # odd, so it is centred
    else:
        total = footprint_m * (1.0 + taper_fraction / 2.0)
        taps = tapered_window(max(1, int(round(total / dx_m)) | 1), taper_fraction)
    return taps / taps.sum()


def tapered_moving_average(heights_m, dx_m: float, footprint_m: float, taper_fraction: float = TAPER_FRACTION) -> np.ndarray:
    """Tapered moving-average enveloping filter (Nguyen and Lines 1988; thesis §1.5, §6.3).

    A centred Tukey window of total length ``footprint_m * (1 + taper_fraction/2)``:
    its equivalent rectangular length equals the contact length, so the static gain
    and the averaging length match :func:`fixed_footprint` while the side lobes
    are lower.

    Parameters
    ----------
    heights_m : array_like
        Profile elevations, m, spacing ``dx_m``.
    dx_m : float
        Spacing, m.
    footprint_m : float
        Contact-patch length, m.
    taper_fraction : float
        Tukey alpha (0 = rectangular = fixed footprint).

    Returns
    -------
    ndarray
        Enveloped elevations, m.

    See Also
    --------
    tapered_window : its window.
    fixed_footprint : the rectangular filter.

    Examples
    --------
    >>> x = np.arange(2000) * 0.01
    >>> e = tapered_moving_average(np.sin(2 * np.pi * x / 0.2), 0.01, 0.4)   # 20 cm waves, 40 cm footprint
    >>> bool(np.abs(e[200:-200]).max() < 0.1), round(float(tapered_moving_average(np.full(100, 0.03), 0.01, 0.4)[50]), 6)
    (True, 0.03)
    """
    return _moving(heights_m, window("tapered", footprint_m, dx_m, taper_fraction))


def rigid_tread_band(heights_m, dx_m: float, radius_m: float) -> np.ndarray:
    """Rigid tread band: wheel-centre locus of a rigid disc, minus the radius (thesis §1.5).

    ``e(x) = max_{|u| <= R} [h(x + u) + sqrt(R^2 - u^2)] - R``. Always reaches the top
    of the highest obstacle and bridges gaps narrower than the disc.

    Parameters
    ----------
    heights_m : array_like
        Surface elevations, m (may include slat gaps).
    dx_m : float
        Spacing, m.
    radius_m : float
        Wheel radius R, m.

    Returns
    -------
    ndarray
        Enveloped elevations, m.

    See Also
    --------
    fixed_footprint : a flexible footprint instead.

    Examples
    --------
    >>> h = np.zeros(200); h[100:102] = -0.05                   # a 2 cm wide, 5 cm deep gap
    >>> round(float(rigid_tread_band(h, 0.01, 0.75).min()) * 1e3, 3)   # mm: a 0.75 m wheel bridges it
    -0.067
    """
    dx_m = _validate.positive("dx_m", dx_m)
    radius_m = _validate.positive("radius_m", radius_m)
    h = np.asarray(heights_m, dtype=float)
    k = int(math.floor(radius_m / dx_m))
    padded = np.concatenate([np.full(k, h[0]), h, np.full(k, h[-1])])
    out = np.full(h.size, -np.inf)
    for j in range(-k, k + 1):
        u = j * dx_m
        lift = math.sqrt(max(radius_m**2 - u * u, 0.0)) - radius_m
        np.maximum(out, padded[k + j : k + j + h.size] + lift, out=out)
    return out
