"""Stiffness models from tables: the thesis' (published Tables II, III, VI) and a build's (issue 27).

Pure: the caller reads the tables (:func:`tyrelab.published.read_published`, the
warehouse) and passes them in; :class:`~tyrelab.tyre.stiffness.StiffnessModel` is what
:func:`~tyrelab.tyre.stiffness.estimate_stiffness` and every caller of it (natural
frequencies, ride, Table XX) take.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd

from .. import _validate
from . import formula_accuracy as fa
from .formula_fit import EXTENDED_TERMS, TERMS, FormulaFit, fit_formula, front_rule
from .stiffness import FormulaDataRange, StiffnessModel

__all__ = ["THESIS_TABLES", "thesis_points", "thesis_formula_fit", "thesis_stiffness_model", "fit_row",
           "fit_from_row", "build_stiffness_model"]

#: Published tables a thesis model is built from.
THESIS_TABLES = ("table_ii", "table_iii", "table_vi")


def thesis_points(table_ii: pd.DataFrame, table_iii: pd.DataFrame) -> pd.DataFrame:
    """Tyre × pressure points of the published Table III rolling lines (traction tyres, F1 left out).

    :func:`tyrelab.tyre.formula_accuracy.predictions_from_table`: ``K_c + ΔK_p P`` on the
    rear/front pressure grids, sizes and ages from Table II (Berlin tyres new: 0 years).

    See Also
    --------
    thesis_formula_fit : the fit of these points.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> table_ii, table_iii, table_vi = (read_published(t) for t in THESIS_TABLES)
    >>> p = thesis_points(table_ii, table_iii)
    >>> len(p), p["tyre_id"].nunique(), sorted(p["source"].unique())
    (80, 16, ['published'])
    """
    _validate.frame("table_ii", table_ii, ["tyre_id", "size"])
    return fa.predictions_from_table(table_iii, table_ii)


def thesis_formula_fit(table_ii: pd.DataFrame, table_iii: pd.DataFrame) -> FormulaFit:
    """:func:`~tyrelab.tyre.formula_fit.fit_formula` of :func:`thesis_points` (``source = "published"``).

    See Also
    --------
    thesis_points : the points it fits.
    tyrelab.tyre.formula_fit.fit_formula : the fit.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> table_ii, table_iii, table_vi = (read_published(t) for t in THESIS_TABLES)
    >>> f = thesis_formula_fit(table_ii, table_iii)
    >>> f.n_tyres, f.n_points, [round(c, 2) for c in f.coefficients]
    (16, 80, [154.03, -1.05, 5.5, 0.31])
    """
    _validate.frame("table_ii", table_ii, ["tyre_id", "size"])
    return fit_formula(thesis_points(table_ii, table_iii), "published")


def thesis_stiffness_model(table_ii: pd.DataFrame, table_iii: pd.DataFrame, table_vi: pd.DataFrame) -> StiffnessModel:
    """The thesis' model: printed point estimate, the published refit's interval, F1's front rule.

    See Also
    --------
    build_stiffness_model : a build's model.
    thesis_formula_fit : its interval's fit.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> m = thesis_stiffness_model(*(read_published(t) for t in THESIS_TABLES))
    >>> m.formula.n_tyres, m.formula.n_points, m.front.n_tyres
    (16, 80, 16)
    """
    _validate.frame("table_vi", table_vi)
    return StiffnessModel("thesis", thesis_formula_fit(table_ii, table_iii), front_rule(table_iii, table_ii),
                          FormulaDataRange.from_tables(table_ii, table_iii, table_vi), point="printed")


def fit_row(fit: FormulaFit) -> dict:
    """:meth:`FormulaFit.row` plus what :func:`fit_from_row` needs: the covariance
    (``cov_<term>_<term>``, upper triangle), the prediction's jackknife covariances
    (``jk_cov_<term>_<term>`` over :data:`TERMS`, ``ext_cov_<term>_<term>`` over
    :data:`EXTENDED_TERMS`; null where not formed) and the data ranges (``<range>_min``/``_max``).

    See Also
    --------
    fit_from_row : its inverse.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> table_ii, table_iii, table_vi = (read_published(t) for t in THESIS_TABLES)
    >>> row = fit_row(thesis_formula_fit(table_ii, table_iii))
    >>> row["source"], row["n_points"], "cov_intercept_age" in row
    ('published', 80, True)
    """
    _validate.instance("fit", fit, FormulaFit)
    row = fit.row()
    for prefix, terms, cov in (("cov", TERMS, fit.covariance), ("jk_cov", TERMS, fit.leverage_covariance),
                               ("ext_cov", EXTENDED_TERMS, fit.extended_covariance)):
        c = np.full((len(terms), len(terms)), np.nan) if cov is None else np.asarray(cov)
        for i, a in enumerate(terms):
            for j, b in enumerate(terms):
                if j >= i:
                    row[f"{prefix}_{a}_{b}"] = float(c[i, j])
    for name, (lo, hi) in fit.ranges.items():
        row[f"{name}_min"], row[f"{name}_max"] = lo, hi
    return row


def fit_from_row(row) -> FormulaFit:
    """The :class:`FormulaFit` of one ``formula_fit`` row written with :func:`fit_row`.

    Raises
    ------
    ValueError
        If the row lacks a coefficient or covariance column.

    See Also
    --------
    fit_row : the row it reads.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> table_ii, table_iii, table_vi = (read_published(t) for t in THESIS_TABLES)
    >>> fit = thesis_formula_fit(table_ii, table_iii)
    >>> back = fit_from_row(fit_row(fit))
    >>> back.coefficients == fit.coefficients, bool(np.allclose(back.covariance, fit.covariance))
    (True, True)
    """
    get = row.get if isinstance(row, dict) else (lambda k, d=None: row[k] if k in row.index else d)
    try:
        beta = tuple(float(get(t)) for t in TERMS)
        cov = np.zeros((4, 4))
        for i, a in enumerate(TERMS):
            for j, b in enumerate(TERMS):
                if j >= i:
                    cov[i, j] = cov[j, i] = float(get(f"cov_{a}_{b}"))
        s = float(get("relative_residual_sd_percent")) / 100
    except (TypeError, ValueError, KeyError) as exc:
        raise ValueError(f"formula_fit row lacks the coefficients or covariance ({exc})") from None
    if not np.all(np.isfinite(beta)) or not np.all(np.isfinite(cov)):
        raise ValueError("formula_fit row has no fitted coefficients")
    ranges = {}
    for name in ("wr_in2", "rim_diameter_in", "age_years", "pressure_bar"):
        lo, hi = get(f"{name}_min"), get(f"{name}_max")
        if lo is not None and hi is not None and np.isfinite(lo) and np.isfinite(hi):
            ranges[name] = (float(lo), float(hi))
    ids = get("tyre_ids") or ""
    return FormulaFit(str(get("source")), beta, tuple(tuple(float(v) for v in r) for r in cov), s,
                      float(get("residual_sd_kN_per_m")), float(get("r_squared")), int(get("n_tyres")),
                      int(get("n_points")), tuple(str(ids).split()), ranges, str(get("method")),
                      _optional_cov(get, "jk_cov", TERMS), _optional_cov(get, "ext_cov", EXTENDED_TERMS))


def _optional_cov(get, prefix: str, terms) -> tuple | None:
    """A covariance written by :func:`fit_row` under ``prefix``; None if absent (a build from
    before issue 34) or not formed (null)."""
    c = np.zeros((len(terms), len(terms)))
    for i, a in enumerate(terms):
        for j, b in enumerate(terms):
            if j >= i:
                try:
                    v = float(get(f"{prefix}_{a}_{b}"))
                except (TypeError, ValueError):
                    return None
                if not np.isfinite(v):
                    return None
                c[i, j] = c[j, i] = v
    return tuple(tuple(float(v) for v in r) for r in c)


def build_stiffness_model(formula_fit_table: pd.DataFrame, thesis: StiffnessModel, source: str = "ours") -> StiffnessModel:
    """A build's model: the ``formula_fit`` row of ``source`` (a lab's tyres), fitted point and interval.

    The front rule stays the thesis' (F1) unless the lab measured ribbed front tyres (it
    has none of its own yet); the range warnings check the lab's tyres' ranges.

    Raises
    ------
    ValueError
        If the table has no usable row of ``source``.

    See Also
    --------
    thesis_stiffness_model : the thesis' model, whose front rule it keeps.
    fit_from_row : the fit of a ``formula_fit`` row.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> table_ii, table_iii, table_vi = (read_published(t) for t in THESIS_TABLES)
    >>> thesis = thesis_stiffness_model(table_ii, table_iii, table_vi)
    >>> table = pd.DataFrame([fit_row(thesis_formula_fit(table_ii, table_iii))])     # a build's formula_fit
    >>> m = build_stiffness_model(table, thesis, source="published")
    >>> m.formula.n_points, m.front == thesis.front
    (80, True)
    """
    _validate.frame("formula_fit_table", formula_fit_table, ["source"])
    _validate.instance("thesis", thesis, StiffnessModel)
    rows = formula_fit_table.loc[formula_fit_table["source"].astype(str) == source]
    if rows.empty:
        raise ValueError(f"formula_fit has no '{source}' row (fewer than 5 measured traction tyres?)")
    fit = fit_from_row(rows.iloc[0])
    r = thesis.data_range
    if r is not None and {"wr_in2", "rim_diameter_in", "age_years", "pressure_bar"} <= set(fit.ranges):
        r = dataclasses.replace(r, wr_in2=fit.ranges["wr_in2"], rim_diameter_in=fit.ranges["rim_diameter_in"],
                                age_years=fit.ranges["age_years"], pressure_bar=fit.ranges["pressure_bar"],
                                source=f"the build's measured tyres ({fit.n_tyres})")
    return StiffnessModel("build", fit, thesis.front, r, point="fitted")
