"""Empirical rolling-tyre stiffness from size, age and pressure (thesis §4.5.3, §8.2).

All stiffnesses here are per tyre, in kN/m, the thesis' units; pressure in bar,
W and R in inches, age in years.
"""

from __future__ import annotations

from .sizes import TyreSize, parse_tyre_size

#: Coefficients of K = a + b R + c A + d W R P (thesis §4.5.3 and §4.6).
FORMULA_INTERCEPT_kN_per_m = 172.0
FORMULA_RIM_kN_per_m_in = -1.77
FORMULA_AGE_kN_per_m_year = 5.6
FORMULA_WRP_kN_per_m_in2_bar = 0.34

#: Undriven ribbed front tyre: Delta K_p of F1 (134 kN/m/bar) spread over W R = 7.5*18 (§8.2).
FRONT_UNDRIVEN_kN_per_m_in2_bar = 134.0 / (7.5 * 18.0)

#: Water ballast raises tyre stiffness by about 25 % (Siefkes 1989; thesis §1.7.10, §8.2).
WATER_BALLAST_FACTOR = 1.25


def _size(size: str | TyreSize) -> TyreSize:
    return size if isinstance(size, TyreSize) else parse_tyre_size(size)


def traction_tyre_stiffness(size: str | TyreSize, pressure_bar: float, age_years: float = 1.0) -> float:
    """Rolling stiffness of a traction tyre from the empirical formula.

    ``K = 172 - 1.77 R + 5.6 A + 0.34 W R P`` (thesis §4.5.3, §4.6, §9), valid for
    traction tyres rolling above about 10 km/h, not for ribbed undriven tyres.

    Parameters
    ----------
    size : str or TyreSize
        Tyre size designation, e.g. ``"13.6R38"``.
    pressure_bar : float
        Inflation pressure P in bar.
    age_years : float, optional
        Tyre age A in years (default 1, as the thesis assumes in §8.2).

    Returns
    -------
    float
        Stiffness K in kN/m.

    Examples
    --------
    >>> round(traction_tyre_stiffness("13.6-38", 1.1, 1), 1)
    303.6
    """
    s = _size(size)
    if pressure_bar < 0:
        raise ValueError(f"pressure {pressure_bar} bar is negative")
    return (
        FORMULA_INTERCEPT_kN_per_m
        + FORMULA_RIM_kN_per_m_in * s.rim_diameter_in
        + FORMULA_AGE_kN_per_m_year * age_years
        + FORMULA_WRP_kN_per_m_in2_bar * s.section_width_in * s.rim_diameter_in * pressure_bar
    )


def undriven_front_tyre_stiffness(size: str | TyreSize, pressure_bar: float) -> float:
    """Rolling stiffness of an undriven ribbed front tyre, ``K = 134/(7.5*18) W R P``.

    Thesis §8.2: the carcass stiffness of F1 is almost zero when rolling and its
    pressure dependence is 134 kN/m/bar; scaled by W R like traction tyres.

    Returns
    -------
    float
        Stiffness K in kN/m.
    """
    s = _size(size)
    if pressure_bar < 0:
        raise ValueError(f"pressure {pressure_bar} bar is negative")
    return FRONT_UNDRIVEN_kN_per_m_in2_bar * s.section_width_in * s.rim_diameter_in * pressure_bar


def estimate_tyre_stiffness(
    size: str | TyreSize,
    pressure_bar: float,
    age_years: float = 1.0,
    *,
    undriven_front: bool = False,
    water_ballast: bool = False,
) -> float:
    """Estimated rolling tyre stiffness in kN/m (thesis §4.5.3 and §8.2).

    Uses :func:`traction_tyre_stiffness`, or :func:`undriven_front_tyre_stiffness`
    for an undriven ribbed front tyre, times 1.25 for water ballast.
    """
    k = (
        undriven_front_tyre_stiffness(size, pressure_bar)
        if undriven_front
        else traction_tyre_stiffness(size, pressure_bar, age_years)
    )
    return k * (WATER_BALLAST_FACTOR if water_ballast else 1.0)
