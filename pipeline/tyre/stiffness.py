"""Empirical rolling-tyre stiffness from size, age and pressure (thesis §4.5.3, §8.2).

All stiffnesses here are per tyre, in kN/m, the thesis' units; pressure in bar,
W and R in inches, age in years. :func:`estimate_stiffness` returns the estimate
with its inputs and warnings where the tyre or pressure lies outside the data the
rule rests on (:class:`FormulaDataRange`, from the digitised Tables II, III, VI).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import pandas as pd

from .. import _validate
from .formula_fit import FormulaFit, FrontRule
from .sizes import TyreSize, parse_tyre_size

__all__ = [
    "FormulaDataRange",
    "StiffnessEstimate",
    "StiffnessModel",
    "estimate_stiffness",
    "estimate_tyre_stiffness",
    "range_warnings",
    "traction_tyre_stiffness",
    "undriven_front_tyre_stiffness",
]

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

    See Also
    --------
    estimate_stiffness : with its prediction interval.

    Examples
    --------
    >>> round(traction_tyre_stiffness("13.6-38", 1.1, 1), 1)
    303.6
    """
    s = _size(size)
    pressure_bar = _validate.non_negative("pressure_bar", pressure_bar)
    age_years = _validate.non_negative("age_years", age_years)
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

    See Also
    --------
    estimate_tyre_stiffness : either rule by the tyre's kind, with water ballast.

    Examples
    --------
    The thesis' F1 itself (7.5-18) at 2 bar: its measured 134 kN/m per bar, times 2:

    >>> round(undriven_front_tyre_stiffness("7.5-18", 2.0), 6)
    268.0
    """
    s = _size(size)
    pressure_bar = _validate.non_negative("pressure_bar", pressure_bar)
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

    Parameters
    ----------
    size : str or TyreSize
        ``13.6-38``, ``480/70R38``, … (:func:`tyrelab.tyre.sizes.parse_tyre_size`).
    pressure_bar, age_years : float
        Inflation pressure, bar; tyre age, years.
    undriven_front, water_ballast : bool
        The ribbed front tyre rule; ×1.25 for water ballast.

    Returns
    -------
    float
        Stiffness K in kN/m (the printed formulas; no interval).

    See Also
    --------
    estimate_stiffness : the same with its prediction interval and range warnings.

    Examples
    --------
    K = 172 − 1.77 R + 5.6 A + 0.34 W R P with W = 13.6 in, R = 38 in, A = 1, P = 1.1 bar:
    172 − 67.26 + 5.6 + 193.28 = 303.62 kN/m (the README's ``estimate-stiffness`` example):

    >>> round(estimate_tyre_stiffness("13.6-38", 1.1, 1.0), 2)
    303.62
    >>> round(estimate_tyre_stiffness("13.6-38", 1.1, 1.0, water_ballast=True) / 303.62, 2)
    1.25
    """
    k = (
        undriven_front_tyre_stiffness(size, pressure_bar)
        if undriven_front
        else traction_tyre_stiffness(size, pressure_bar, age_years)
    )
    return k * (WATER_BALLAST_FACTOR if water_ballast else 1.0)


# --- the formula on any tyre, with what the thesis' data cover (issue 12) --------------------

#: Traction tyres behind the formula: Table III's rolling rows but the ribbed F1, as for the
#: fit of ΔK_p on W·R (thesis §4.5.3, Fig. 30).
_FRONT_RIBBED = "front_ribbed"


_THESIS_SOURCE = "thesis Tables II, III (sizes, ages) and VI (pressure)"


@dataclass(frozen=True)
class FormulaDataRange:
    """Ranges of the thesis' measurements that the stiffness rules rest on.

    Attributes
    ----------
    wr_in2 : tuple of float
        (min, max) W·R of the traction tyres of Table III (sizes as in Table II), in².
    rim_diameter_in : tuple of float
        (min, max) rim diameter R of those tyres, in.
    pressure_bar : tuple of float
        (min, max) inflation pressure, bar: Table VI's "Pressure" range (Tables II-III
        print no pressures; Table VI gives the range the measurements spanned).
    age_years : tuple of float
        (min, max) tyre age, years: Table II (the Berlin tyres, printed without an
        age, were new, §4.2: 0).
    front_wr_in2, front_rim_diameter_in : tuple of float
        The same for the undriven ribbed front tyre rule (§8.2), which rests on F1 alone.
    source : str
        Where the ranges come from.
    """

    wr_in2: tuple[float, float]
    rim_diameter_in: tuple[float, float]
    pressure_bar: tuple[float, float]
    age_years: tuple[float, float]
    front_wr_in2: tuple[float, float]
    front_rim_diameter_in: tuple[float, float]
    source: str = "thesis Tables II, III (sizes, ages) and VI (pressure)"  # = _THESIS_SOURCE

    @classmethod
    def from_tables(
        cls, table_ii: pd.DataFrame, table_iii: pd.DataFrame, table_vi: pd.DataFrame
    ) -> "FormulaDataRange":
        """Ranges from the digitised Tables II, III and VI (:func:`tyrelab.published.read_published`).

        Raises
        ------
        ValueError
            If a table lacks the rows or columns needed.
        """
        ii = table_ii.assign(tyre_id=table_ii["tyre_id"].astype(str)).set_index("tyre_id")
        rolling = table_iii.loc[
            (table_iii["condition"] == "rolling") & table_iii["pressure_dependence_kN_per_m_bar"].notna()
        ]
        ids = [t for t in rolling["tyre_id"].astype(str) if t in ii.index]
        if not ids:
            raise ValueError("table_iii has no rolling rows for tyres of table_ii")
        sizes = {t: parse_tyre_size(str(ii.at[t, "size"])) for t in ids}
        front = [t for t in ids if ii.at[t, "group"] == _FRONT_RIBBED]
        traction = [t for t in ids if t not in front]
        if not traction or not front:
            raise ValueError("table_ii/table_iii give no traction or no ribbed front tyre")

        def span(values):
            values = list(values)
            return (float(min(values)), float(max(values)))

        pressure = table_vi.loc[table_vi["factor"].astype(str).str.strip().str.lower() == "pressure"]
        if pressure.empty or pressure["range_unit"].iloc[0] != "bar":
            raise ValueError("table_vi has no 'Pressure' row in bar")
        ages = pd.to_numeric(ii.loc[traction, "age_years"], errors="coerce").fillna(0.0)  # blank = new (§4.2)
        return cls(
            wr_in2=span(sizes[t].width_times_rim_in2 for t in traction),
            rim_diameter_in=span(sizes[t].rim_diameter_in for t in traction),
            pressure_bar=(float(pressure["range_low"].iloc[0]), float(pressure["range_high"].iloc[0])),
            age_years=span(ages),
            front_wr_in2=span(sizes[t].width_times_rim_in2 for t in front),
            front_rim_diameter_in=span(sizes[t].rim_diameter_in for t in front),
        )


def _outside(name: str, value: float, lo: float, hi: float, unit: str, what: str,
             whose: str = "the thesis' data") -> str | None:
    """One warning if ``value`` lies outside [lo, hi], saying by how much."""
    if lo <= value <= hi:
        return None
    side, by, ref = ("below", lo - value, lo) if value < lo else ("above", value - hi, hi)
    span = f"{lo:g}" if lo == hi else f"{lo:g}-{hi:g}"
    return (
        f"{name} = {value:.4g} {unit} is {side} {whose} ({what}: {span} {unit}) "
        f"by {by:.3g} {unit} ({100 * by / ref:.1f} %)"
    )


def range_warnings(
    size: str | TyreSize,
    pressure_bar: float,
    age_years: float = 1.0,
    *,
    undriven_front: bool = False,
    data_range: FormulaDataRange | None = None,
) -> tuple[str, ...]:
    """Where a tyre and pressure lie outside the data a stiffness rule rests on.

    Parameters
    ----------
    size : str or TyreSize
    pressure_bar, age_years : float
    undriven_front : bool
        Check against the ribbed front tyre rule's data (F1: W·R and R) instead of the
        traction tyres' (W·R, R, age and Table VI's pressure range, which is the rear
        traction tyres'; no published table gives F1's pressures, so none is checked).
    data_range : FormulaDataRange, optional
        The data the rule rests on (:meth:`FormulaDataRange.from_tables` of the published
        Tables II, III, VI, or :attr:`StiffnessModel.data_range`). None: nothing to check
        against, no warnings but the flexion class.

    Returns
    -------
    tuple of str
        One line per quantity outside its range, saying by how much; empty when inside.

    See Also
    --------
    estimate_stiffness : returns these warnings with the estimate.

    Examples
    --------
    >>> r = FormulaDataRange((326.4, 699.2), (24, 44), (0.7, 2.0), (0, 16), (135, 135), (18, 18))
    >>> range_warnings("13.6R38", 1.2, 2, data_range=r)
    ()
    >>> print(range_warnings("13.6R38", 2.4, 2, data_range=r)[0])
    P = 2.4 bar is above the thesis' data (pressure range of Table VI: 0.7-2 bar) by 0.4 bar (20.0 %)
    """
    s = _size(size)
    pressure_bar = _validate.non_negative("pressure_bar", pressure_bar)
    age_years = _validate.non_negative("age_years", age_years)
    r = data_range
    if r is None:
        checks = []
    elif undriven_front:
        checks = [("W·R", s.width_times_rim_in2, r.front_wr_in2, "in²", "the ribbed front tyre F1"),
                  ("R", s.rim_diameter_in, r.front_rim_diameter_in, "in", "the ribbed front tyre F1")]
    elif r.source != _THESIS_SOURCE:  # a build's fit: its own tyres' ranges
        checks = [(n, v, rng, unit, r.source) for n, v, rng, unit in (
            ("W·R", s.width_times_rim_in2, r.wr_in2, "in²"), ("R", s.rim_diameter_in, r.rim_diameter_in, "in"),
            ("A", float(age_years), r.age_years, "years"), ("P", float(pressure_bar), r.pressure_bar, "bar"))]
    else:
        checks = [("W·R", s.width_times_rim_in2, r.wr_in2, "in²", "traction tyres of Tables II-III"),
                  ("R", s.rim_diameter_in, r.rim_diameter_in, "in", "traction tyres of Tables II-III"),
                  ("A", float(age_years), r.age_years, "years", "tyre ages of Table II")]
        checks.append(("P", float(pressure_bar), r.pressure_bar, "bar", "pressure range of Table VI"))
    whose = "the thesis' data" if r is None or r.source == _THESIS_SOURCE or undriven_front else "the data"
    out = [w for name, v, (lo, hi), unit, what in checks if (w := _outside(name, v, lo, hi, unit, what, whose))]
    if s.flexion_class:
        name = {"IF": "improved flexion", "VF": "very high flexion"}[s.flexion_class]
        out.append(f"{s.flexion_class} tyre: the thesis measured no {name} tyres, which carry "
                   f"{s.flexion_load_factor:g} x the load of a standard tyre at the same pressure")
    return tuple(out)


@dataclass(frozen=True)
class StiffnessEstimate:
    """An estimated tyre stiffness with its inputs and range warnings.

    Attributes
    ----------
    size : TyreSize
    pressure_bar, age_years : float
    undriven_front, water_ballast : bool
    rule : str
        The formula used, with its thesis reference.
    stiffness_kN_per_m : float
        Estimated rolling stiffness K per tyre, kN/m.
    warnings : tuple of str
        Where the tyre or pressure lies outside the thesis' data (:func:`range_warnings`).
    prediction_interval_kN_per_m : (float, float) or None
        95 % prediction interval of the tyre's measured rolling stiffness, kN/m, from
        the fitted formula of the :class:`StiffnessModel` (:mod:`tyrelab.tyre.formula_fit`)
        or its front rule; None without a model.
    stiffness_u_kN_per_m : float or None
        Standard uncertainty of the estimate, kN/m (the interval's half-width over its t factor).
    prediction_interval_basis : str
        What the interval rests on, or why there is none.
    model : str
        Name of the :class:`StiffnessModel` used (``"thesis"``, ``"build"``), ``"printed"`` without one.

    Further fields (e.g. an interval) can be added with a default; :meth:`to_dict`
    includes every field.
    """

    size: TyreSize
    pressure_bar: float
    age_years: float
    undriven_front: bool
    water_ballast: bool
    rule: str
    stiffness_kN_per_m: float
    warnings: tuple[str, ...] = ()
    prediction_interval_kN_per_m: tuple[float, float] | None = None
    stiffness_u_kN_per_m: float | None = None
    prediction_interval_basis: str = ""
    model: str = "printed"

    def to_dict(self) -> dict:
        """JSON-ready dict: the inputs, what the size says, K (rounded to 1e-3) and the warnings."""
        s = self.size
        out = {
            "size": s.designation,
            "section_width_in": s.section_width_in,
            "section_width_mm": s.section_width_mm,
            "rim_diameter_in": s.rim_diameter_in,
            "wr_in2": s.width_times_rim_in2,
            "aspect_ratio": s.aspect_ratio,
            "aspect_ratio_stated": s.aspect_ratio_stated,
            "construction": s.construction,
            "flexion_class": s.flexion_class,
            "load_index": s.load_index,
            "load_kg": s.load_kg,
            "speed_symbol": s.speed_symbol,
            "speed_km_h": s.speed_km_h,
        }
        for f in fields(self):
            if f.name == "size":
                continue
            v = getattr(self, f.name)
            if f.name in ("stiffness_kN_per_m", "stiffness_u_kN_per_m") and v is not None:
                v = round(v, 3)
            if f.name == "prediction_interval_kN_per_m" and v is not None:
                v = tuple(round(x, 3) for x in v)
            out[f.name] = list(v) if isinstance(v, tuple) else v
        return out


@dataclass(frozen=True)
class StiffnessModel:
    """What :func:`estimate_stiffness` rests on: a fitted formula, the front rule, the data's ranges.

    Built from tables by :mod:`tyrelab.tyre.models` (pure: the tables are read by the
    caller, :mod:`tyrelab.published` or the warehouse).

    Attributes
    ----------
    name : str
        ``"thesis"`` (fitted to the published Table III) or ``"build"`` (a lab's tyres).
    formula : FormulaFit
        Traction tyres: ``K = a + b R + c A + d W R P`` with its covariance.
    front : FrontRule or None
        Undriven ribbed front tyres (thesis §8.2) with their uncertainty.
    data_range : FormulaDataRange or None
        For :func:`range_warnings`.
    point : str
        ``"printed"``: K from the thesis' printed coefficients (172, −1.77, 5.6, 0.34), as
        Table XX and every published number use, with the fit's prediction interval (which
        is that of the tyre's stiffness whatever point estimate is quoted); ``"fitted"``:
        K from :attr:`formula`'s own coefficients.
    """

    name: str
    formula: FormulaFit
    front: FrontRule | None = None
    data_range: FormulaDataRange | None = None
    point: str = "printed"


def estimate_stiffness(
    size: str | TyreSize,
    pressure_bar: float,
    age_years: float = 1.0,
    *,
    undriven_front: bool = False,
    water_ballast: bool = False,
    data_range: FormulaDataRange | None = None,
    model: StiffnessModel | None = None,
) -> StiffnessEstimate:
    """Estimated rolling tyre stiffness with its prediction interval and range warnings (§4.5.3, §8.2).

    Parameters
    ----------
    size : str or TyreSize
    pressure_bar, age_years : float
        Inflation pressure (bar), tyre age (years).
    undriven_front, water_ballast : bool
        The ribbed front tyre rule; ×1.25 for water ballast.
    data_range : FormulaDataRange, optional
        Overrides ``model.data_range`` for the warnings.
    model : StiffnessModel, optional
        The fitted formula (and front rule) behind K and its interval
        (:func:`tyrelab.tyre.models.thesis_stiffness_model` for the thesis' data). None:
        the printed formulas, no interval and no range warnings.

    Returns
    -------
    StiffnessEstimate
        K per tyre (kN/m), the 95 % prediction interval of the tyre's measured rolling
        stiffness from the fit (leverage included: wider away from the data), its standard
        uncertainty, what they rest on, and the range warnings (the rule is still applied
        outside the data).

    See Also
    --------
    traction_tyre_stiffness : the formula's point value.
    range_warnings : where the estimate leaves its data.

    Examples
    --------
    >>> e = estimate_stiffness("480/70R38", 1.2, 2)
    >>> round(e.stiffness_kN_per_m, 1), e.prediction_interval_kN_per_m
    (408.9, None)
    """
    s = _size(size)
    pressure_bar = _validate.non_negative("pressure_bar", pressure_bar)
    age_years = _validate.non_negative("age_years", age_years)
    k = estimate_tyre_stiffness(s, pressure_bar, age_years, undriven_front=undriven_front, water_ballast=water_ballast)
    rule = (
        "front undriven K = 134/(7.5*18) W R P (thesis §8.2)"
        if undriven_front
        else "K = 172 - 1.77 R + 5.6 A + 0.34 W R P (thesis §4.5.3)"
    )
    interval, u = None, None
    factor = WATER_BALLAST_FACTOR if water_ballast else 1.0
    ballast = "; water ballast scales it by 1.25 (its own uncertainty is not known)" if water_ballast else ""
    if model is None:
        basis = "none: no stiffness model given (tyrelab.tyre.models.thesis_stiffness_model)"
    elif undriven_front:
        if model.front is None:
            basis = f"none: the {model.name} model has no undriven front tyre rule"
        else:
            pred = model.front.predict(s, pressure_bar)
            k = pred.stiffness_kN_per_m * factor
            interval = tuple(v * factor for v in pred.interval_kN_per_m)
            u = pred.standard_uncertainty_kN_per_m * factor
            basis = "95 % prediction interval, " + model.front.basis + ballast
    else:
        f = model.formula
        pred = f.predict(s, pressure_bar, age_years)
        if model.point == "fitted":
            k = pred.stiffness_kN_per_m * factor
            b = f.coefficients
            rule = f"K = {b[0]:.4g} {b[1]:+.4g} R {b[2]:+.4g} A {b[3]:+.4g} W R P (fitted to the {model.name}'s tyres)"
        interval = tuple(v * factor for v in pred.interval_kN_per_m)
        u = pred.standard_uncertainty_kN_per_m * factor
        basis = (f"95 % prediction interval of the formula fitted to {f.n_points} points of {f.n_tyres} tyres "
                 f"({f.source}; {f.method}); relative residual sd {100 * f.relative_residual_sd:.1f} %, "
                 f"leverage {pred.mean_se_kN_per_m:.1f} kN/m" + ballast)
    if data_range is None and model is not None:
        data_range = model.data_range
    return StiffnessEstimate(
        size=s,
        pressure_bar=float(pressure_bar),
        age_years=float(age_years),
        undriven_front=bool(undriven_front),
        water_ballast=bool(water_ballast),
        rule=rule,
        stiffness_kN_per_m=k,
        warnings=range_warnings(s, pressure_bar, age_years, undriven_front=undriven_front, data_range=data_range),
        prediction_interval_kN_per_m=interval,
        stiffness_u_kN_per_m=u,
        prediction_interval_basis=basis,
        model=model.name if model is not None else "printed",
    )
