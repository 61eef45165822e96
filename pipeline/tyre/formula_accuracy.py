"""How well rolling stiffness is predicted: the empirical formula vs the stationary tyre (§4.5.3).

Thesis §4.5.3 (Fig. 32): over all traction tyres of Table II except F1 "at all
the inflation pressures measured (56 combinations)" the formula
``K = 172 − 1.77 R + 5.6 A + 0.34 W R P`` predicts the rolling stiffness with a
mean error of 3 % and a standard deviation of 10 %, "therefore 65 %" within
±10 %; the stationary tyre predicts it with mean 17 %, sd 24 %, "only a 25 %
probability" within ±10 %. The probabilities are those of a normal
distribution N(mean, sd): P(|e| < 10 %) = Φ((10 − m)/s) − Φ((−10 − m)/s), which
gives 0.66 and 0.25 from the printed moments.

Error convention: ``e = 100 (predicted − measured) / measured`` in percent.

Pressure grid for the published Table III (the thesis does not list the
pressures): rear tyres :data:`REAR_GRID_BAR` (0.8–1.6 bar in 0.2 bar steps),
front traction tyres :data:`FRONT_GRID_BAR` (1.0–2.0 bar in 0.25 bar steps;
front tyres run at higher pressure, and Table VI quotes 0.7–2 bar overall).
A tyre is "front" if the ``tyres`` table's ``position`` says so, else if its
rim is ≤ 30 in. Ages come from ``tyres.age_years``; a missing age is taken as
0 (the Berlin tyres were "all new", Table II) and flagged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.stats import norm
from scipy.stats import t as student_t

from .. import _validate
from . import conditions as cond
from .sizes import TyreSizeError, parse_tyre_size
from .stiffness import traction_tyre_stiffness

__all__ = ["REAR_GRID_BAR", "FRONT_GRID_BAR", "NOT_TRACTION", "THESIS_ACCURACY", "PRED_COLUMNS", "p_within",
    "predictions_from_table", "predictions_from_recordings", "accuracy_summary", "FormulaErrorModel", "formula_error_model"]

REAR_GRID_BAR = (0.8, 1.0, 1.2, 1.4, 1.6)
FRONT_GRID_BAR = (1.0, 1.25, 1.5, 1.75, 2.0)
#: Tyres the formula does not apply to (undriven ribbed front tyre, §4.5.3).
NOT_TRACTION = ("F1",)
#: Printed accuracy (thesis §4.5.3): method -> (mean %, sd %, within ±10 %, n).
THESIS_ACCURACY = {"formula": (3.0, 10.0, 0.65, 56), "stationary": (17.0, 24.0, 0.25, None)}

PRED_COLUMNS = ["source", "tyre_id", "size", "position", "age_years", "age_assumed", "pressure_bar",
                "measured_kN_per_m", "formula_kN_per_m", "stationary_kN_per_m",
                "formula_error_percent", "stationary_error_percent"]


def p_within(mean: float, sd: float, limit: float = 10.0) -> float:
    """P(|e| < limit) for e ~ N(mean, sd) (thesis §4.5.3, §6.4), via ``scipy.stats.norm``; NaN for a
    non-finite moment or sd <= 0 (too few errors to have one).

    See Also
    --------
    accuracy_summary : uses it per method.

    Examples
    --------
    >>> round(p_within(0.0, 10.0), 4), round(p_within(4.6, 8.0), 3)     # ±1 sd; the formula's errors
    (0.6827, 0.716)
    """
    limit = _validate.positive("limit", limit)
    if not (np.isfinite(mean) and np.isfinite(sd)) or sd <= 0:
        return float("nan")
    return float(norm.cdf((limit - mean) / sd) - norm.cdf((-limit - mean) / sd))


def _tyre_info(tyres: pd.DataFrame | None) -> pd.DataFrame:
    cols = ["tyre_id", "size", "position", "age_years"]
    if tyres is None or tyres.empty:
        return pd.DataFrame(columns=cols)
    t = tyres.copy()
    for c in cols:
        if c not in t:
            t[c] = None
    t["tyre_id"] = t["tyre_id"].astype(str)
    return t[cols]


def _is_front(position, size) -> bool:
    if isinstance(position, str) and position.strip():
        return "front" in position.lower()
    try:
        return parse_tyre_size(size).rim_diameter_in <= 30
    except (TyreSizeError, TypeError):
        return False


def _is_traction(tyre_id, position) -> bool:
    text = position.lower() if isinstance(position, str) else ""
    return tyre_id not in NOT_TRACTION and "undriven" not in text and "ribbed" not in text


def _formula(size, p, age):
    try:
        return traction_tyre_stiffness(size, p, age)
    except (TyreSizeError, ValueError, TypeError):
        return np.nan


#: Columns of a Table III-like table the predictions read.
_LINE_COLUMNS = ("tyre_id", "condition", "carcass_stiffness_kN_per_m", "pressure_dependence_kN_per_m_bar")


def _lines(table: pd.DataFrame) -> dict:
    out = {}
    for r in table.itertuples(index=False):
        kc = getattr(r, "carcass_stiffness_kN_per_m")
        dk = getattr(r, "pressure_dependence_kN_per_m_bar")
        if np.isfinite(kc) and np.isfinite(dk):
            out[(str(r.tyre_id), r.condition)] = (kc, dk)
    return out


def _prediction_rows(source, tyre_id, size, position, age, pressures, measured, lines):
    assumed = not np.isfinite(age) if age is not None else True
    a = 0.0 if assumed else float(age)
    rows = []
    stat = lines.get((tyre_id, "stationary"))
    for p, m in zip(pressures, measured):
        f = _formula(size, p, a)
        s = stat[0] + stat[1] * p if stat else np.nan
        rows.append(dict(source=source, tyre_id=tyre_id, size=size, position=position, age_years=a,
                         age_assumed=assumed, pressure_bar=p, measured_kN_per_m=m, formula_kN_per_m=f,
                         stationary_kN_per_m=s, formula_error_percent=100 * (f - m) / m,
                         stationary_error_percent=100 * (s - m) / m))
    return rows


def predictions_from_table(table: pd.DataFrame, tyres: pd.DataFrame | None,
                           *, rear_grid=REAR_GRID_BAR, front_grid=FRONT_GRID_BAR,
                           source: str = "published") -> pd.DataFrame:
    """Formula and stationary predictions vs Table III rolling lines on a pressure grid.

    "Measured" rolling stiffness is ``K_c + ΔK_p P`` of the rolling row;
    the stationary-method prediction is the stationary row's line at the same P.

    Parameters
    ----------
    table : DataFrame
        Table III-like (tyre_id, condition, carcass_stiffness_kN_per_m,
        pressure_dependence_kN_per_m_bar, optional size).
    tyres : DataFrame or None
        ``tyres`` table (size, position, age_years).

    Returns
    -------
    DataFrame
        :data:`PRED_COLUMNS`, one row per traction tyre × grid pressure.

    See Also
    --------
    predictions_from_recordings : the same from our runs.
    accuracy_summary : their errors summarised.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> table_ii, table_iii = read_published("table_ii"), read_published("table_iii")
    >>> p = predictions_from_table(table_iii, table_ii)
    >>> len(p), p["tyre_id"].nunique(), round(float(p["formula_error_percent"].mean()), 2)
    (80, 16, 4.62)
    """
    _validate.frame("table", table, _LINE_COLUMNS)
    if tyres is not None:
        _validate.frame("tyres", tyres, ["tyre_id"])
    _validate.positive_array("rear_grid", rear_grid)
    _validate.positive_array("front_grid", front_grid)
    info = _tyre_info(tyres).set_index("tyre_id")
    lines = _lines(table)
    own_size = dict(zip(table["tyre_id"].astype(str), table["size"])) if "size" in table else {}
    rows = []
    for tid in sorted({t for t, c in lines if c == "rolling"}):
        size = info["size"].get(tid) if tid in info.index and isinstance(info["size"].get(tid), str) else own_size.get(tid)
        pos = info["position"].get(tid) if tid in info.index else None
        age = pd.to_numeric(pd.Series([info["age_years"].get(tid) if tid in info.index else np.nan])).iloc[0]
        if not _is_traction(tid, pos):
            continue
        grid = np.asarray(front_grid if _is_front(pos, size) else rear_grid, dtype=float)
        kc, dk = lines[(tid, "rolling")]
        rows += _prediction_rows(source, tid, size, pos, age, grid, kc + dk * grid, lines)
    return pd.DataFrame(rows, columns=PRED_COLUMNS)


def predictions_from_recordings(results: pd.DataFrame, our_table_iii: pd.DataFrame,
                                tyres: pd.DataFrame | None) -> pd.DataFrame:
    """Formula and stationary predictions vs our measured rolling stiffness.

    Measured = mean stiffness of the Table III rolling runs
    (:func:`conditions.table_iii_runs`) per tyre and measured pressure; the
    stationary prediction is our stationary Table III line at that pressure.

    See Also
    --------
    predictions_from_table : the same from published lines.
    accuracy_summary : summarises either.

    Examples
    --------
    >>> from tyrelab.tyre.regressions import DAMPING, pressure_regressions, table_iii
    >>> from tyrelab.tyre.examples import demo_runs
    >>> runs = demo_runs()                                  # tyre T1: 1.0-1.8 bar, standing and at 12 km/h
    >>> p = predictions_from_recordings(runs, table_iii(pressure_regressions(runs), None),
    ...                                 pd.DataFrame({"tyre_id": ["T1"], "size": ["13.6R38"]}))
    >>> p[["pressure_bar", "measured_kN_per_m", "stationary_kN_per_m", "stationary_error_percent"]].round(2).to_dict("records")[0]
    {'pressure_bar': 1.0, 'measured_kN_per_m': 380.0, 'stationary_kN_per_m': 400.0, 'stationary_error_percent': 5.26}
    """
    _validate.frame("results", results)
    _validate.frame("our_table_iii", our_table_iii, _LINE_COLUMNS)
    if tyres is not None:
        _validate.frame("tyres", tyres, ["tyre_id"])
    info = _tyre_info(tyres).set_index("tyre_id")
    if results.empty:
        return pd.DataFrame(columns=PRED_COLUMNS)
    runs = cond.table_iii_runs(results)
    runs = runs.loc[(runs["condition"] == "rolling") & runs["stiffness_kN_per_m"].notna()].copy()
    runs["tyre_id"] = runs["tyre_id"].astype(str)
    runs["p"] = pd.to_numeric(runs["pressure_bar"], errors="coerce").round(cond.PRESSURE_DECIMALS)
    lines = _lines(our_table_iii)
    rows = []
    for tid, sub in runs.groupby("tyre_id", sort=True):
        size = info["size"].get(tid) if tid in info.index else None
        pos = info["position"].get(tid) if tid in info.index else None
        age = pd.to_numeric(pd.Series([info["age_years"].get(tid) if tid in info.index else np.nan])).iloc[0]
        if not _is_traction(tid, pos):
            continue
        m = sub.groupby("p")["stiffness_kN_per_m"].mean()
        rows += _prediction_rows("ours", tid, size, pos, age, m.index.to_numpy(float), m.to_numpy(float), lines)
    return pd.DataFrame(rows, columns=PRED_COLUMNS)


def accuracy_summary(pred: pd.DataFrame, source: str) -> pd.DataFrame:
    """Mean, sd, share within ±10 % and normal-theory P(|e| < 10 %) per method.

    Returns
    -------
    DataFrame
        ``source, method, n_tyres, n, mean_error_percent, sd_error_percent,
        within_10_percent_fraction, p_within_10_percent_normal`` and the printed
        ``thesis_*`` values with differences (thesis §4.5.3).

    See Also
    --------
    predictions_from_table : the predictions it summarises.
    p_within : the normal-theory share.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> table_ii, table_iii = read_published("table_ii"), read_published("table_iii")
    >>> s = accuracy_summary(predictions_from_table(table_iii, table_ii), "published")
    >>> s[["method", "n_tyres", "n", "mean_error_percent", "sd_error_percent"]].round(2).to_dict("records")
    [{'method': 'formula', 'n_tyres': 16, 'n': 80, 'mean_error_percent': 4.62, 'sd_error_percent': 7.96}, {'method': 'stationary', 'n_tyres': 13, 'n': 65, 'mean_error_percent': 15.16, 'sd_error_percent': 25.27}]
    """
    _validate.frame("pred", pred)
    if len(pred):
        _validate.frame("pred", pred, ["formula_error_percent", "stationary_error_percent"])
    rows = []
    for method in ("formula", "stationary"):
        e = pred[f"{method}_error_percent"].to_numpy(float) if len(pred) else np.array([])
        ok = np.isfinite(e)
        e = e[ok]
        mean = float(e.mean()) if len(e) else np.nan
        sd = float(e.std(ddof=1)) if len(e) > 1 else np.nan
        tm, ts, tw, tn = THESIS_ACCURACY[method]
        p = p_within(mean, sd)
        rows.append(dict(
            source=source, method=method,
            n_tyres=int(pred.loc[ok, "tyre_id"].nunique()) if len(pred) else 0, n=int(len(e)),
            thesis_n=tn, mean_error_percent=mean, thesis_mean_error_percent=tm,
            mean_error_percent_difference=mean - tm, sd_error_percent=sd, thesis_sd_error_percent=ts,
            sd_error_percent_difference=sd - ts,
            within_10_percent_fraction=float(np.mean(np.abs(e) < 10)) if len(e) else np.nan,
            p_within_10_percent_normal=p, thesis_p_within_10_percent=tw,
            p_within_10_percent_difference=p - tw,
            thesis_p_within_10_percent_from_printed_moments=p_within(tm, ts),
        ))
    return pd.DataFrame(rows)


@dataclass(frozen=True)
class FormulaErrorModel:
    """How far the empirical formula misses a measured rolling stiffness (prediction intervals).

    From the formula's errors ``e = 100 (F − M)/M`` (%) on the published Table III
    rolling lines (:func:`predictions_from_table`, the thesis' own data, §4.5.3):
    their mean and standard deviation over ``n`` tyre × pressure points of
    ``n_tyres`` tyres. A new tyre's measured stiffness ``M`` lies, with
    probability ``level``, where its error is within
    ``mean ± t_{n_tyres−1} sd √(1 + 1/n_tyres)`` (a normal prediction interval; the
    points of one tyre are not independent, so the tyres count for the degrees of
    freedom): ``M ∈ [F/(1 + e_hi/100), F/(1 + e_lo/100)]``.
    """

    mean_error_percent: float
    sd_error_percent: float
    n: int
    n_tyres: int
    source: str = "thesis Table III rolling lines, Table II sizes and ages (formula_accuracy.predictions_from_table)"

    def coverage_factor(self, level: float = 0.95) -> float:
        """Student t factor for ``level`` with ``n_tyres − 1`` degrees of freedom."""
        if not 0 < level < 1:
            raise ValueError(f"level must be in (0, 1), got {level!r}")
        return float(student_t.ppf(0.5 + level / 2, max(self.n_tyres - 1, 1)))

    def interval(self, predicted_kN_per_m: float, level: float = 0.95) -> tuple[float, float]:
        """Prediction interval (kN/m) of the measured stiffness of a tyre the formula gives ``predicted_kN_per_m``.

        Examples
        --------
        >>> m = FormulaErrorModel(3.0, 10.0, 56, 14)
        >>> lo, hi = m.interval(300.0)
        >>> round(lo), round(hi)
        (239, 372)
        """
        if not predicted_kN_per_m > 0:
            raise ValueError(f"predicted_kN_per_m must be positive, got {predicted_kN_per_m!r}")
        half = self.coverage_factor(level) * self.sd_error_percent * math.sqrt(1 + 1 / self.n_tyres)
        e_lo, e_hi = self.mean_error_percent - half, self.mean_error_percent + half
        return predicted_kN_per_m / (1 + e_hi / 100), predicted_kN_per_m / (1 + e_lo / 100)

    def standard_uncertainty(self, predicted_kN_per_m: float) -> float:
        """Standard uncertainty (kN/m) of the stiffness: the 95 % interval's half-width over its t factor."""
        lo, hi = self.interval(predicted_kN_per_m)
        return (hi - lo) / (2 * self.coverage_factor())


def formula_error_model(table: pd.DataFrame, tyres: pd.DataFrame | None) -> FormulaErrorModel:
    """:class:`FormulaErrorModel` from a Table III-like table and a tyres table.

    See Also
    --------
    predictions_from_table : the errors it models.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> table_ii, table_iii = read_published("table_ii"), read_published("table_iii")
    >>> m = formula_error_model(table_iii, table_ii)
    >>> round(m.mean_error_percent, 2), round(m.sd_error_percent, 2), m.n, m.n_tyres
    (4.62, 7.96, 80, 16)
    """
    _validate.frame("table", table, _LINE_COLUMNS)
    pred = predictions_from_table(table, tyres)
    e = pred["formula_error_percent"].to_numpy(float)
    ok = np.isfinite(e)
    if ok.sum() < 3:
        raise ValueError("table: too few formula predictions to estimate its error")
    return FormulaErrorModel(float(e[ok].mean()), float(e[ok].std(ddof=1)), int(ok.sum()),
                             int(pred.loc[ok, "tyre_id"].nunique()))
