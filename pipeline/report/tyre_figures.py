"""Figures of the fitted stiffness formula (issue 27): how wide its prediction interval is, and where.

Drawn from the warehouse's ``formula_fit`` table (:func:`tyrelab.tyre.models.fit_from_row`),
so the page shows the fits the build made: the refit on the thesis' Table III and, when the
build measured enough traction tyres, the lab's own.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..tyre.models import fit_from_row
from ..tyre.sizes import parse_tyre_size
from .figures import MARKERS, _figure, to_svg

__all__ = ["WR_GRID_IN2", "interval_width_table", "formula_interval_width"]

#: W·R grid of the figure, in²: from below the smallest thesis tyre to beyond an IF 710/70R42 (1174 in²).
WR_GRID_IN2 = np.arange(150.0, 1401.0, 25.0)


def interval_width_table(formula_fit: pd.DataFrame, *, rim_diameter_in: float = 38.0, pressure_bar: float = 1.2,
                         age_years: float = 1.0, wr_in2=WR_GRID_IN2) -> pd.DataFrame:
    """Half-width of the 95 % prediction interval, % of K, against W·R for each fitted source.

    Returns
    -------
    DataFrame
        ``source, wr_in2, stiffness_kN_per_m, half_width_percent, leverage_percent, inside_data``
        (``inside_data``: W·R within the fit's tyres' range).
    """
    rows = []
    if formula_fit is None or formula_fit.empty or "cov_wrp_wrp" not in formula_fit:
        return pd.DataFrame(columns=["source", "wr_in2", "stiffness_kN_per_m", "half_width_percent",
                                     "leverage_percent", "inside_data"])
    for _, row in formula_fit.loc[formula_fit["cov_wrp_wrp"].notna()].iterrows():
        fit = fit_from_row(row)
        lo, hi = fit.ranges.get("wr_in2", (np.nan, np.nan))
        for wr in np.asarray(wr_in2, float):
            p = fit.predict_terms(rim_diameter_in, wr, pressure_bar, age_years)
            a, b = p.interval_kN_per_m
            rows.append(dict(source=fit.source, wr_in2=wr, stiffness_kN_per_m=p.stiffness_kN_per_m,
                             half_width_percent=100 * (b - a) / 2 / p.stiffness_kN_per_m,
                             leverage_percent=100 * p.mean_se_kN_per_m / p.stiffness_kN_per_m,
                             inside_data=bool(lo <= wr <= hi)))
    return pd.DataFrame(rows)


def formula_interval_width(formula_fit: pd.DataFrame) -> str | None:
    """95 % prediction interval half-width (% of K) against W·R, R = 38 in, 1.2 bar, 1 year; the
    W·R span of each fit's tyres marked (solid inside, dotted outside)."""
    t = interval_width_table(formula_fit)
    if t.empty:
        return None
    fig, ax = _figure(size=(6.4, 3.4))
    for i, (source, g) in enumerate(t.groupby("source", sort=True)):
        line, = ax.plot(g["wr_in2"], g["half_width_percent"], ":", label=f"{source}: outside its tyres")
        inside = g.loc[g["inside_data"]]
        ax.plot(inside["wr_in2"], inside["half_width_percent"], "-" + MARKERS[i % len(MARKERS)], markevery=4,
                color=line.get_color(), label=f"{source}: its tyres' W·R")
        ax.plot(g["wr_in2"], g["leverage_percent"], "--", color=line.get_color(), linewidth=0.8,
                label=f"{source}: fitted-mean part")
    wr_if = parse_tyre_size("IF 710/70R42").width_times_rim_in2
    ax.axvline(wr_if, color="0.6", linewidth=0.6)
    ax.text(wr_if, ax.get_ylim()[1] * 0.97, " IF 710/70R42", fontsize=7, va="top", color="0.4")
    ax.set(xlabel="W·R (in²), R = 38 in, P = 1.2 bar, A = 1 year", ylabel="95 % half-width (% of K)",
           title="Prediction interval of the fitted formula")
    ax.set_ylim(bottom=0)
    ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=7)
    return to_svg(fig)
