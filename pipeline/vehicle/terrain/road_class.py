"""The ISO 8608 class of a measured road profile (issue 33): ``tyrelab road`` and the ride page.

ISO 8608 describes a road track by its displacement PSD ``G_d(n) = G_d(n0) (n/n0)^-w``,
``n0`` = 0.1 cycles/m, and classes it by ``G_d(n0)`` with the waviness ``w = 2``: classes A-H,
each a factor 4 wide around its geometric mean (A 16e-6 m³, B 64e-6, ... H 262144e-6; the
field notes; the class boundaries are the geometric means between neighbours, e.g. A/B at
32e-6 m³).

:func:`road_class` fits ``G_d(n0)`` to one track:

1. the one-sided displacement PSD by Welch's method (Hann segments of ``segment_m``, half
   overlapping, linear trend removed per segment; :func:`tyrelab.vehicle.profiles.profile_spectrum`);
2. averaged in third-octave bands of ``n`` over the standard's band 0.011-2.83 cycles/m, as far
   as the track resolves it (above two Welch bins, ``2 / segment_m``, and below 0.8 of the
   Nyquist wavenumber ``0.5 / dx_m``);
3. ``log10 G_d(n0)`` = the mean over the bands of ``log10(G(n_b) (n_b / n0)^w)``, ``w = 2``:
   the least-squares line of slope ``-w`` in log-log co-ordinates, each band weighted equally
   (a documented choice: equal weights per band, not per Welch bin, so the many high-wavenumber
   bins do not decide the fit alone).

Examples
--------
>>> import numpy as np
>>> from tyrelab.vehicle import profiles as pr
>>> t = pr.iso8608_track("C", seed=3, length_m=1000.0)
>>> c = road_class(t.left_m, t.dx_m)
>>> c["class"], 128e-6 < c["g0_m3"] < 512e-6
('C', True)
"""

from __future__ import annotations

import math

import numpy as np

from ... import _validate
from .profiles import ISO8608_CLASS_G0_M3, ISO8608_N0_CYCLES_PER_M, profile_spectrum

__all__ = ["ISO8608_BAND_CYCLES_PER_M", "WAVINESS", "class_of", "road_class"]

#: The spatial-frequency band of ISO 8608's classification, cycles/m.
ISO8608_BAND_CYCLES_PER_M = (0.011, 2.83)
#: The waviness of the classification fit.
WAVINESS = 2.0
#: Longest Welch segment, m: resolves the standard's lowest wavenumber (1 / 0.011 cycles/m = 91 m).
SEGMENT_M = 102.4


def class_of(g0_m3: float) -> str:
    """The ISO 8608 class (A-H) of a level ``G_d(n0)`` (m³): the class whose geometric mean is
    within a factor 2 (below A's range: A; above H's: H).

    See Also
    --------
    road_class : the class of a measured track.

    Examples
    --------
    >>> class_of(256e-6), class_of(511e-6), class_of(513e-6), class_of(1e-9), class_of(1.0)
    ('C', 'C', 'D', 'A', 'H')
    """
    g0 = _validate.positive("g0_m3", g0_m3)
    for c, mean in ISO8608_CLASS_G0_M3.items():
        if g0 < 2.0 * mean:
            return c
    return "H"


def road_class(elevation_m, dx_m: float, segment_m: float | None = None) -> dict:
    """ISO 8608 class of one track: ``G_d(n0)`` fitted with ``w = 2`` (module docstring).

    Parameters
    ----------
    elevation_m : array_like
        Heights along the track, m, uniform spacing ``dx_m`` (at least 16 finite values).
    dx_m : float
        Spacing, m.
    segment_m : float, optional
        Welch segment, m (default: the shorter of 102.4 m and a quarter of the track).

    Returns
    -------
    dict
        ``class`` (A-H), ``g0_m3`` (fitted ``G_d(n0)``), ``rms_m`` (r.m.s. about the mean),
        ``length_m``, ``band_cycles_per_m`` ([low, high] used; None and class None when the track
        is too short or too coarse to resolve two third-octave bands of the standard's band).

    Raises
    ------
    ValueError
        Naming ``elevation_m``, ``dx_m`` or ``segment_m``.
    """
    h = _validate.finite_array("elevation_m", elevation_m, min_samples=16)
    dx_m = _validate.positive("dx_m", dx_m)
    length = (h.size - 1) * dx_m
    if segment_m is None:
        segment_m = min(SEGMENT_M, length / 4)
    segment_m = _validate.positive("segment_m", segment_m)
    out = {"class": None, "g0_m3": None, "rms_m": float(np.std(h)), "length_m": float(length),
           "band_cycles_per_m": None}
    lo = max(ISO8608_BAND_CYCLES_PER_M[0], 2.0 / segment_m)
    hi = min(ISO8608_BAND_CYCLES_PER_M[1], 0.8 * 0.5 / dx_m)
    if not hi > lo:  # before the spectrum: a spacing above segment_m / 2 has no Welch segment
        return out
    n, g = profile_spectrum(h, dx_m, segment_m)
    # third-octave bands between lo and hi (centres n0 2^(k/3), edges a sixth of an octave away)
    k = np.arange(math.ceil(3 * math.log2(lo / ISO8608_N0_CYCLES_PER_M)),
                  math.floor(3 * math.log2(hi / ISO8608_N0_CYCLES_PER_M)) + 1)
    centres = ISO8608_N0_CYCLES_PER_M * 2.0 ** (k / 3.0)
    terms = []
    for nc in centres:
        sel = (n >= nc * 2 ** (-1 / 6)) & (n < nc * 2 ** (1 / 6)) & (g > 0)
        if sel.any():
            terms.append(math.log10(float(np.mean(g[sel]))) + WAVINESS * math.log10(nc / ISO8608_N0_CYCLES_PER_M))
    if len(terms) < 2:
        return out
    g0 = 10.0 ** float(np.mean(terms))
    out.update({"class": class_of(g0), "g0_m3": g0, "band_cycles_per_m": [float(lo), float(hi)]})
    return out
