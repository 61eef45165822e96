"""Stiffness and damping regressions of thesis chapters 4 and 5 (Tables III–X).

Every fit is a least-squares line from :mod:`statsmodels` and is reported with
estimate, standard error, 95 % confidence interval, r² and n. Where the runs
carry their own standard uncertainties (``results.stiffness_u_N_per_m``,
``damping_u_N_s_per_m``, issue 14) and these differ, the line is weighted
least squares with weights ``1/(u_i² + τ²)``: ``u_i`` the run's measurement
uncertainty and ``τ`` the tyre's own run-to-run scatter (thesis §3.6), which
no single run can see, estimated so that the weighted residuals have their
expected size (Paule–Mandel). Runs whose uncertainty is large next to the
scatter count less; when the scatter dominates, the weights are nearly equal
and the fit is the ordinary one. ``weighting`` and ``between_run_sd`` say
which was used.
Run selection follows :mod:`tyrelab.tyre.conditions` (the one place that says
which runs are "nominal"). Functions return tidy DataFrames in thesis units:
stiffness kN/m, damping kNs/m, pressure bar, speed km/h, amplitude mm p-p.

Tables reproducing a thesis table carry ``thesis_<column>``, ``<column>`` and
``<column>_difference`` (ours − thesis) side by side (:func:`compare_with_thesis`).
Tyres with fewer than two distinct regressor values get a row with ``n`` and
null estimates and a ``reason``.
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
# The two estimators and add_constant from their modules: ``statsmodels.api`` imports much more
# (formulas, patsy, every model family) and costs ~0.4 s more per process.
from statsmodels.regression.linear_model import OLS, WLS
from statsmodels.tools.tools import add_constant

from .. import _validate
from . import conditions as cond

__all__ = ["STIFFNESS", "DAMPING", "FIT_COLUMNS", "fit_line", "fit_mean", "measured_tyres",
    "pressure_regressions", "pressure_regressions_each", "factor_regressions", "factor_regressions_each",
    "surface_effects", "compare_with_thesis", "table_iii",
    "table_vii", "amplitude_table", "surface_table", "SUMMARY_FACTORS", "summary_rates", "RESPONSE_UNCERTAINTY", "WLS_MIN_SPREAD", "between_run_variance"]

STIFFNESS = "stiffness_kN_per_m"
DAMPING = "damping_kN_s_per_m"
_RESPONSE_UNIT = {STIFFNESS: "kN/m", DAMPING: "kNs/m"}

#: Columns of every line fit (:func:`fit_line`).
FIT_COLUMNS = [
    "n", "n_distinct_x", "intercept", "intercept_se", "intercept_ci_low", "intercept_ci_high",
    "slope", "slope_se", "slope_ci_low", "slope_ci_high", "slope_p_value", "r_squared", "reason",
    "weighting", "between_run_sd",
]
#: Runs' standard uncertainties, per response column (N/m and N s/m; the responses are in kN).
RESPONSE_UNCERTAINTY = {STIFFNESS: "stiffness_u_N_per_m", DAMPING: "damping_u_N_s_per_m"}
#: Weights count only when the runs' uncertainties differ by more than this ratio (max/min).
WLS_MIN_SPREAD = 1.5


def between_run_variance(x, y, u) -> float:
    """Paule–Mandel τ²: the extra variance that makes Σ (y − ŷ)²/(u² + τ²) = n − 2 for a line.

    0 when the runs' own uncertainties already explain the residuals.

    See Also
    --------
    fit_line : weighs by ``1/(u² + τ²)`` with it.

    Examples
    --------
    >>> x = np.array([1.0, 2, 3, 4]); y = np.array([1.0, 2.2, 2.8, 4.1])
    >>> round(between_run_variance(x, y, np.full(4, 0.01)), 4) > 0, between_run_variance(x, y, np.full(4, 1.0))
    (True, 0.0)
    """
    x, y = _validate.finite_array("x", x, 3), _validate.finite_array("y", y, 3)
    u = _validate.positive_array("u", u)
    _validate.same_last_axis(x=x, y=y, u=u)
    x, y, u = (np.asarray(v, dtype=float) for v in (x, y, u))
    design = np.column_stack([np.ones_like(x), x])

    u2 = u**2

    def chi2(tau2):
        w = 1.0 / (u2 + tau2)
        sw = np.sqrt(w)
        beta = np.linalg.lstsq(design * sw[:, None], y * sw, rcond=None)[0]
        return float(np.sum(w * (y - design @ beta) ** 2))

    target = len(y) - 2
    if target <= 0 or chi2(0.0) <= target:
        return 0.0
    lo, hi = 0.0, float(np.var(y)) * 10 + 1e-30
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        step = (mid, hi) if chi2(mid) > target else (lo, mid)
        if step == (lo, hi):
            break  # converged to adjacent floats: every further step repeats this one
        lo, hi = step
    return 0.5 * (lo + hi)


def fit_line(x, y, *, alpha: float = 0.05, u=None) -> dict:
    """Least-squares line ``y = intercept + slope x`` with its statistics (statsmodels OLS or WLS).

    r² is the thesis' coefficient of determination Σ(ŷ−ȳ)²/Σ(y−ȳ)² (§4.3.1), unweighted.

    Parameters
    ----------
    x, y : array-like
        Regressor and response; rows where either is NaN are dropped.
    alpha : float
        1 − confidence level of the intervals (0.05 → 95 %).
    u : array-like, optional
        Standard uncertainties of ``y`` (same units). When every point has one and
        they differ by more than :data:`WLS_MIN_SPREAD`, the fit is WLS with weights
        ``1/(u² + τ²)`` (:func:`between_run_variance`); the residual scale is then
        estimated from the data as for OLS.

    Returns
    -------
    dict
        Keys :data:`FIT_COLUMNS`. With fewer than two distinct x the estimates
        are NaN and ``reason`` says why; with two points the standard errors
        and intervals are NaN (no residual degrees of freedom).

    See Also
    --------
    fit_mean : a mean with its interval.
    pressure_regressions : a line per tyre and condition.

    Examples
    --------
    >>> f = fit_line([1.0, 1.4, 1.8], [400.0, 441.0, 479.0])
    >>> round(f["intercept"], 1), round(f["slope"], 1), f["n"], round(f["r_squared"], 4)
    (301.8, 98.8, 3, 0.9995)
    >>> fit_line([1.0, 1.0], [400.0, 410.0])["reason"] is not None
    True
    """
    alpha = _validate.probability("alpha", alpha)
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    uu = np.full(x.shape, np.nan) if u is None else np.asarray(u, dtype=float)
    ok = np.isfinite(x) & np.isfinite(y)
    x, y, uu = x[ok], y[ok], uu[ok]
    out = dict.fromkeys(FIT_COLUMNS, np.nan)
    out["weighting"] = "OLS"
    out["n"] = int(len(x))
    out["n_distinct_x"] = int(len(np.unique(np.round(x, 9))))
    out["reason"] = None
    if out["n_distinct_x"] < 2:
        out["reason"] = f"fewer than 2 distinct regressor values (n={out['n']}, distinct={out['n_distinct_x']})"
        return out
    weighted = (len(uu) > 2 and np.all(np.isfinite(uu)) and np.all(uu > 0)
                and uu.max() / uu.min() > WLS_MIN_SPREAD)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        design = add_constant(x, has_constant="add")
        if weighted:
            tau2 = between_run_variance(x, y, uu)
            res = WLS(y, design, weights=1.0 / (uu**2 + tau2)).fit()
            out["weighting"] = "WLS 1/(u² + τ²)"
            out["between_run_sd"] = float(np.sqrt(tau2))
        else:
            res = OLS(y, design).fit()
        ci = np.asarray(res.conf_int(alpha))
        bse = np.asarray(res.bse)
        p = np.asarray(res.pvalues)
    has_df = res.df_resid > 0
    fitted = design @ np.asarray(res.params)
    out.update(
        intercept=float(res.params[0]),
        slope=float(res.params[1]),
        r_squared=float(np.sum((fitted - y.mean()) ** 2) / np.sum((y - y.mean()) ** 2)) if np.var(y) > 0 else np.nan,
        intercept_se=float(bse[0]) if has_df else np.nan,
        slope_se=float(bse[1]) if has_df else np.nan,
        intercept_ci_low=float(ci[0, 0]) if has_df else np.nan,
        intercept_ci_high=float(ci[0, 1]) if has_df else np.nan,
        slope_ci_low=float(ci[1, 0]) if has_df else np.nan,
        slope_ci_high=float(ci[1, 1]) if has_df else np.nan,
        slope_p_value=float(p[1]) if has_df else np.nan,
    )
    if not has_df:
        out["reason"] = "only 2 points: no standard error"
    return out


def fit_mean(y, *, alpha: float = 0.05) -> dict:
    """Mean of ``y`` with standard error and t-interval (statsmodels OLS on a constant).

    Returns
    -------
    dict
        ``n, mean, se, ci_low, ci_high, sd, reason``.

    See Also
    --------
    fit_line : a line with its statistics.
    surface_effects : the mean change over cells.

    Examples
    --------
    >>> m = fit_mean([1.0, 2.0, 3.0])
    >>> m["n"], m["mean"], m["sd"], round(m["ci_low"], 3), round(m["ci_high"], 3)
    (3, 2.0, 1.0, -0.484, 4.484)
    """
    alpha = _validate.probability("alpha", alpha)
    y = np.asarray(y, dtype=float)
    y = y[np.isfinite(y)]
    out = {"n": int(len(y)), "mean": np.nan, "se": np.nan, "ci_low": np.nan, "ci_high": np.nan,
           "sd": np.nan, "reason": None}
    if len(y) == 0:
        out["reason"] = "no matched observations"
        return out
    out["mean"] = float(y.mean())
    if len(y) < 2:
        out["reason"] = "one matched observation: no standard error"
        return out
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = OLS(y, np.ones((len(y), 1))).fit()
    ci = np.asarray(res.conf_int(alpha))
    out.update(se=float(np.asarray(res.bse)[0]), ci_low=float(ci[0, 0]), ci_high=float(ci[0, 1]),
               sd=float(y.std(ddof=1)))
    return out


def _speed(s: pd.Series) -> pd.Series:
    return pd.to_numeric(s, errors="coerce").astype(float).round(cond.SPEED_DECIMALS)


def measured_tyres(results: pd.DataFrame) -> list[str]:
    """Tyre ids with at least one measurement run, sorted (the tyres "in our data").

    See Also
    --------
    pressure_regressions : reports these tyres by default.

    Examples
    --------
    >>> measured_tyres(pd.DataFrame({"tyre_id": ["T2", "T1", "C"], "kind": ["measurement", "measurement", "calibration"]}))
    ['T1', 'T2']
    """
    _validate.frame("results", results)
    if results.empty or "tyre_id" not in results.columns:
        return []
    kind = results.get("kind", pd.Series("measurement", index=results.index)).fillna("measurement")
    return sorted(results.loc[kind == "measurement", "tyre_id"].dropna().astype(str).unique())


def _floats(runs: pd.DataFrame, column: str | None) -> np.ndarray | None:
    """Column as a float array (non-numbers NaN), or None when absent."""
    if column is None or column not in runs.columns:
        return None
    return pd.to_numeric(runs[column], errors="coerce").to_numpy(dtype=float, na_value=np.nan)


def _fit_groups(runs, keys, grid, response, hold, prefer, design: str = "x") -> pd.DataFrame:
    """Fit ``response ~ x`` per group of ``keys`` (:func:`_fit_rows`) as one DataFrame."""
    return _fit_frame(_fit_rows(runs, keys, grid, response, hold, prefer, design), keys, hold)


def _fit_frame(rows: list[dict], keys, hold) -> pd.DataFrame:
    """The DataFrame of :func:`_fit_rows` (columns in their fixed order)."""
    return pd.DataFrame(rows, columns=list(keys) + FIT_COLUMNS + [f"held_{c}" for c in hold] + ["note"])


def _fit_rows(runs, keys, grid, response, hold, prefer, design: str = "x") -> list[dict]:
    """Fit ``response ~ x`` per group of ``keys``; ``grid`` lists the groups to report (one row each).

    ``design`` is the column of the experiment's set levels (the nominal
    condition): the held level is chosen, and a group counts as an experiment
    on x, by its distinct *design* values, so that the scatter of a measured
    regressor around one set level is never mistaken for a sweep.

    The runs are grouped once (positions per group) and every group is fitted on
    arrays (:func:`conditions.hold_level`, :func:`fit_line`): no per-group DataFrame.
    """
    rows = []
    u_col = RESPONSE_UNCERTAINTY.get(response)
    cols = [c for c in hold if c in runs.columns]
    groups = runs.groupby(keys, sort=True).indices if not runs.empty else {}
    x_all, y_all, d_all = _floats(runs, "x"), _floats(runs, response), _floats(runs, design)
    u_all = _floats(runs, u_col)
    u_all = u_all / 1e3 if u_all is not None else None  # N -> kN, as the responses
    levels_all = cond.hold_levels(runs, cols) if cols and not runs.empty else None
    none_held = {c: None for c in hold}
    empty = np.empty(0, dtype=np.intp)
    for key in grid.itertuples(index=False, name=None):
        pos = groups.get(key if len(keys) > 1 else key[0], empty)
        if len(pos) and y_all is not None:
            pos = pos[~np.isnan(y_all[pos])]
        levels, note = none_held, ""
        if len(pos) and levels_all is not None:
            keep, levels, note = cond.hold_level(d_all[pos], levels_all[pos], cols, hold, prefer)
            pos = pos if keep is None else pos[keep]
        n = len(pos)
        one_level = n > 0 and cond.n_distinct(np.round(d_all[pos], 6)) < 2
        u = u_all[pos] if u_all is not None else None
        fit = fit_line(x_all[pos], y_all[pos], u=u) if n and not one_level else fit_line([], [])
        if n == 0:
            fit["reason"] = "no runs under the selection convention (tyrelab.tyre.conditions)"
        elif one_level:
            fit["n"] = int(n)
            fit["reason"] = f"fewer than 2 distinct set levels of the regressor (n={n}): the runs do not vary it"
        row = dict(zip(keys, key))
        row.update(fit)
        for c in hold:
            row[f"held_{c}"] = levels.get(c)
        row["note"] = note or None
        rows.append(row)
    return rows


def _by_tyre(rows: list[dict], tyre_ids) -> dict[str, list[dict]]:
    """The rows of each tyre of ``tyre_ids`` (in their order; rows of other tyres dropped)."""
    out: dict[str, list[dict]] = {t: [] for t in tyre_ids}
    for row in rows:
        if row["tyre_id"] in out:
            out[row["tyre_id"]].append(row)
    return out


def pressure_regressions(
    results: pd.DataFrame, response: str = STIFFNESS, *, by: str = "condition",
    tyre_ids: list[str] | None = None,
) -> pd.DataFrame:
    """Response vs inflation pressure per tyre × condition or per tyre × speed.

    ``K = K_c + ΔK_p P`` (thesis §4.3.1, Table III; §4.5.3) or ``C = C_c + ΔC P``
    (§5.3.1, Table VII). Nominal runs only (:func:`conditions.nominal`); load held
    constant (:func:`conditions.hold_constant`).

    Parameters
    ----------
    results : DataFrame
        The ``results`` table.
    response : str
        ``"stiffness_kN_per_m"`` or ``"damping_kN_s_per_m"``.
    by : {"condition", "speed"}
        ``"condition"``: Table III stationary / rolling (10–15 km/h pooled);
        ``"speed"``: one fit per nominal speed.
    tyre_ids : list of str, optional
        Tyres to report (default: every tyre with measurement runs); a tyre
        without runs gets a row with ``n = 0`` and a reason.

    Returns
    -------
    DataFrame
        ``tyre_id``, ``condition`` or ``speed_km_h``, then :data:`FIT_COLUMNS`
        (intercept = carcass value, slope = pressure dependence per bar),
        ``held_load_kN``, ``note``.

    See Also
    --------
    pressure_regressions_each : the same per tyre in one pass.
    table_iii : Table III from its stiffness fit by condition.
    table_vii : Table VII from its damping fit by speed.
    tyrelab.tyre.conditions.nominal : the runs it fits.

    Examples
    --------
    >>> from tyrelab.tyre.examples import demo_runs
    >>> runs = demo_runs()                                  # tyre T1: 1.0-1.8 bar, standing and at 12 km/h
    >>> fit = pressure_regressions(runs)
    >>> fit[["condition", "n", "intercept", "slope"]].round(6).to_dict("records")
    [{'condition': 'stationary', 'n': 3, 'intercept': 300.0, 'slope': 100.0}, {'condition': 'rolling', 'n': 3, 'intercept': 280.0, 'slope': 100.0}]
    """
    _validate.frame("results", results)
    _validate.choice("response", response, (STIFFNESS, DAMPING))
    _validate.choice("by", by, ("condition", "speed"))
    runs, keys, grid = _pressure_runs(results, by, tyre_ids)
    return _fit_groups(runs, keys, grid, response, *_PRESSURE_HOLD)


#: Held condition of the pressure regressions and its preferred level.
_PRESSURE_HOLD = (["load_kN"], {"load_kN": 0.0})


def _pressure_runs(results: pd.DataFrame, by: str, tyre_ids) -> tuple[pd.DataFrame, list, pd.DataFrame]:
    """Runs (with regressor ``x``), group keys and grid of :func:`pressure_regressions`."""
    results = cond.with_columns(results)
    tyre_ids = measured_tyres(results) if tyre_ids is None else list(tyre_ids)
    if by == "condition":
        runs = cond.table_iii_runs(results) if not results.empty else results.assign(condition=None)
        key = "condition"
        levels = ["stationary", "rolling"]
        grid = pd.DataFrame([(t, c) for t in tyre_ids for c in levels], columns=["tyre_id", key])
    elif by == "speed":
        runs = results.loc[cond.nominal(results)].copy() if not results.empty else results.copy()
        key = "speed_km_h"
        runs[key] = _speed(runs[key]) if key in runs else np.nan
        grid = runs[["tyre_id", key]].drop_duplicates()
        grid = grid.loc[grid["tyre_id"].astype(str).isin(tyre_ids)]
        missing = sorted(set(tyre_ids) - set(grid["tyre_id"].astype(str)))
        grid = pd.concat([grid, pd.DataFrame({"tyre_id": missing, key: np.nan})], ignore_index=True)
        grid = grid.sort_values(["tyre_id", key]).reset_index(drop=True)
    else:
        raise ValueError(f"by must be 'condition' or 'speed', not {by!r}")
    runs = runs.assign(x=pd.to_numeric(runs.get("pressure_bar"), errors="coerce"), tyre_id=runs["tyre_id"].astype(str)) \
        if not runs.empty else runs.assign(x=np.nan)
    return runs, ["tyre_id", key], grid


def pressure_regressions_each(
    results: pd.DataFrame, responses=(STIFFNESS, DAMPING), *, by: str = "condition", tyre_ids: list[str],
) -> dict[str, dict[str, pd.DataFrame]]:
    """:func:`pressure_regressions` of each tyre on its own, all tyres in one pass.

    ``out[tyre][response]`` equals ``pressure_regressions(<results rows of tyre>, response, by=by,
    tyre_ids=[tyre])``: the runs are selected and grouped once and every fit reads its
    group's runs only.

    See Also
    --------
    pressure_regressions : one tyre's (or every tyre's) fits.

    Examples
    --------
    >>> pressure_regressions_each(pd.DataFrame(), tyre_ids=["T1"])["T1"][STIFFNESS]["n"].tolist()
    [0, 0]
    """
    _validate.frame("results", results)
    for response in responses:
        _validate.choice("responses", response, (STIFFNESS, DAMPING))
    _validate.choice("by", by, ("condition", "speed"))
    tyre_ids = [str(t) for t in tyre_ids]
    runs, keys, grid = _pressure_runs(results, by, tyre_ids)
    out: dict[str, dict[str, pd.DataFrame]] = {t: {} for t in tyre_ids}
    for response in responses:
        for t, rows in _by_tyre(_fit_rows(runs, keys, grid, response, *_PRESSURE_HOLD), tyre_ids).items():
            out[t][response] = _fit_frame(rows, keys, _PRESSURE_HOLD[0])
    return out


def factor_regressions(
    results: pd.DataFrame, factor: str, responses=(STIFFNESS, DAMPING),
) -> pd.DataFrame:
    """Rate of change of stiffness and damping with one condition, per tyre × speed.

    Thesis §4.3.3–4.3.6 and §5.3.3–5.3.6; Tables IV and VIII (amplitude) and the
    rates summarised in Tables VI and X (load, frequency, torque, pressure).
    Runs: :func:`conditions.factor_runs`; pressure and load held constant where
    not regressed (nearest 1.38 bar preferred).

    Parameters
    ----------
    results : DataFrame
    factor : {"amplitude", "frequency", "load", "torque", "pressure"}
    responses : sequence of str

    Returns
    -------
    DataFrame
        ``tyre_id, speed_km_h, response, factor, factor_unit, rate_unit``, the fit
        (slope = rate), ``held_pressure_bar``, ``held_load_kN``, ``note``.

    See Also
    --------
    factor_regressions_each : the same per tyre in one pass.
    amplitude_table : Tables IV and VIII from the amplitude rates.
    summary_rates : Tables VI and X from the rates.
    tyrelab.tyre.conditions.factor_runs : the runs it fits.

    Examples
    --------
    >>> from tyrelab.tyre.examples import demo_runs
    >>> runs = demo_runs("load")                            # tyre T1: 14, 18, 22 kN at 12 km/h
    >>> r = factor_regressions(runs, "load")
    >>> r[["response", "factor_unit", "n", "slope"]].round(6).to_dict("records")
    [{'response': 'stiffness_kN_per_m', 'factor_unit': 'kN', 'n': 3, 'slope': 5.0}, {'response': 'damping_kN_s_per_m', 'factor_unit': 'kN', 'n': 3, 'slope': 0.2}]
    """
    _validate.frame("results", results)
    _validate.choice("factor", factor, tuple(cond.FACTORS))
    for response in responses:
        _validate.choice("responses", response, (STIFFNESS, DAMPING))
    runs, grid, hold = _factor_runs(results, factor)
    rows = {response: _fit_rows(runs, _FACTOR_KEYS, grid, response, hold, _FACTOR_PREFER, design="x_design")
            for response in responses}
    return _factor_frame(rows, factor, hold)


_FACTOR_KEYS = ["tyre_id", "speed_km_h"]
#: Preferred levels of the conditions held constant in the one-factor regressions.
_FACTOR_PREFER = {"pressure_bar": cond.STANDARD_PRESSURE_BAR, "load_kN": 0.0}


def _factor_runs(results: pd.DataFrame, factor: str) -> tuple[pd.DataFrame, pd.DataFrame, list[str]]:
    """Runs (with ``x`` and ``x_design``), grid and held columns of :func:`factor_regressions`."""
    results = cond.with_columns(results)
    runs = cond.factor_runs(results, factor) if not results.empty else results.assign(x=np.nan)
    runs = runs.copy()
    if not runs.empty:
        runs["speed_km_h"] = _speed(runs["speed_km_h"])
        runs["tyre_id"] = runs["tyre_id"].astype(str)
    runs["x_design"] = pd.to_numeric(runs[cond.FACTORS[factor][0]], errors="coerce") if not runs.empty else np.nan
    hold = [c for c in ("pressure_bar", "load_kN") if c != cond.FACTORS[factor][0]]
    grid = runs[_FACTOR_KEYS].drop_duplicates().sort_values(_FACTOR_KEYS) \
        if not runs.empty else pd.DataFrame(columns=_FACTOR_KEYS)
    return runs, grid, hold


def _factor_frame(rows: dict[str, list[dict]], factor: str, hold: list[str]) -> pd.DataFrame:
    """The :func:`factor_regressions` table of the fit rows of each response."""
    unit = cond.FACTORS[factor][2]
    held = [f"held_{c}" for c in hold]
    out = []
    for response, fit_rows in rows.items():
        extra = {"response": response, "factor": factor, "factor_unit": unit,
                 "rate_unit": f"{_RESPONSE_UNIT.get(response, response)} per {unit}"}
        absent = {c: np.nan for c in ("held_pressure_bar", "held_load_kN") if c not in held}
        if fit_rows:  # the constant columns inferred from the rows: the dtypes of inserting them
            f = pd.DataFrame([{**r, **extra, **absent} for r in fit_rows],
                             columns=_FACTOR_KEYS + list(extra) + FIT_COLUMNS + held + ["note"] + list(absent))
        else:  # no rows: inserted columns keep the dtypes an insert gives an empty frame
            f = _fit_frame(fit_rows, _FACTOR_KEYS, hold)
            for i, (c, v) in enumerate(extra.items()):
                f.insert(2 + i, c, v)
            for c, v in absent.items():
                f[c] = v
        out.append(f)
    return pd.concat(out, ignore_index=True) if out else pd.DataFrame()


def factor_regressions_each(
    results: pd.DataFrame, factor: str, responses=(STIFFNESS, DAMPING), *, tyre_ids: list[str],
) -> dict[str, pd.DataFrame]:
    """:func:`factor_regressions` of each tyre on its own, all tyres in one pass.

    ``out[tyre]`` equals ``factor_regressions(<results rows of tyre>, factor, responses)``:
    the runs are selected and grouped once and every fit reads its group's runs only.

    See Also
    --------
    factor_regressions : one tyre's (or every tyre's) rates.

    Examples
    --------
    >>> len(factor_regressions_each(pd.DataFrame(), "load", tyre_ids=["T1"])["T1"])
    0
    """
    if factor not in cond.FACTORS:
        raise ValueError(f"factor must be one of {sorted(cond.FACTORS)}, not {factor!r}")
    tyre_ids = [str(t) for t in tyre_ids]
    runs, grid, hold = _factor_runs(results, factor)
    rows = {response: _by_tyre(_fit_rows(runs, _FACTOR_KEYS, grid, response, hold, _FACTOR_PREFER,
                                         design="x_design"), tyre_ids) for response in responses}
    return {t: _factor_frame({r: rows[r][t] for r in responses}, factor, hold) for t in tyre_ids}


def surface_effects(results: pd.DataFrame, response: str = STIFFNESS) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Percent change of stiffness or damping on each surface relative to concrete.

    Thesis §4.3.7 Table V (stiffness) and §5.3.7 Table IX (damping). Runs are
    nominal except for the surface; each surface mean is matched with the
    concrete mean of the same tyre, speed, pressure and load (a *cell*); the
    change is ``100 (mean_surface / mean_concrete − 1)`` per cell and the
    surface estimate is the mean over cells (:func:`fit_mean`).

    Returns
    -------
    cells : DataFrame
        ``surface, tyre_id, speed_km_h, pressure_bar, load_kN, n_surface, n_concrete,
        surface_mean, concrete_mean, change_percent``.
    summary : DataFrame
        Per non-concrete surface: ``surface, n_cells, change_percent, se, ci_low, ci_high,
        sd, tyres, reason``.

    See Also
    --------
    surface_table : Tables V and IX from the summary.
    fit_mean : the mean over cells.

    Examples
    --------
    >>> from tyrelab.tyre.examples import demo_runs
    >>> runs = demo_runs()                                  # tyre T1: 1.0-1.8 bar, standing and at 12 km/h
    >>> grass = runs.assign(surface="grass", stiffness_kN_per_m=runs["stiffness_kN_per_m"] * 0.9)
    >>> cells, summary = surface_effects(pd.concat([runs, grass], ignore_index=True))
    >>> len(cells), summary[["surface", "n_cells"]].to_dict("records"), round(float(summary["change_percent"].iloc[0]), 6)
    (6, [{'surface': 'grass', 'n_cells': 6}], -10.0)
    """
    _validate.frame("results", results)
    _validate.choice("response", response, (STIFFNESS, DAMPING))
    cell_cols = ["surface", "tyre_id", "speed_km_h", "pressure_bar", "load_kN", "n_surface",
                 "n_concrete", "surface_mean", "concrete_mean", "change_percent"]
    sum_cols = ["surface", "n_cells", "change_percent", "se", "ci_low", "ci_high", "sd", "tyres", "reason"]
    if results.empty:
        return pd.DataFrame(columns=cell_cols), pd.DataFrame(columns=sum_cols)
    runs = results.loc[cond.nominal(results, except_for="surface")].copy()
    runs = runs.loc[runs[response].notna()]
    runs["surface"] = runs["surface"].fillna(cond.REFERENCE_SURFACE).astype(str).str.strip().str.lower()
    runs["tyre_id"] = runs["tyre_id"].astype(str)
    runs["speed_km_h"] = _speed(runs["speed_km_h"])
    runs["pressure_bar"] = pd.to_numeric(runs["pressure_bar"], errors="coerce").round(cond.PRESSURE_DECIMALS)
    runs["load_kN"] = pd.to_numeric(runs.get("load_kN", np.nan), errors="coerce").round(cond.LOAD_DECIMALS)
    keys = ["tyre_id", "speed_km_h", "pressure_bar", "load_kN"]
    agg = runs.groupby(["surface"] + keys, dropna=False)[response].agg(["mean", "size"]).reset_index()
    ref = agg.loc[agg["surface"] == cond.REFERENCE_SURFACE].drop(columns="surface") \
        .rename(columns={"mean": "concrete_mean", "size": "n_concrete"})
    other = agg.loc[agg["surface"] != cond.REFERENCE_SURFACE] \
        .rename(columns={"mean": "surface_mean", "size": "n_surface"})
    cells = other.merge(ref, on=keys, how="left")
    cells["change_percent"] = 100.0 * (cells["surface_mean"] / cells["concrete_mean"] - 1.0)
    cells = cells[cell_cols].sort_values(["surface"] + keys).reset_index(drop=True)
    rows = []
    for surface, sub in cells.groupby("surface", sort=True):
        m = fit_mean(sub["change_percent"])
        matched = sub.loc[sub["change_percent"].notna()]
        rows.append({
            "surface": surface, "n_cells": m["n"], "change_percent": m["mean"], "se": m["se"],
            "ci_low": m["ci_low"], "ci_high": m["ci_high"], "sd": m["sd"],
            "tyres": ",".join(sorted(matched["tyre_id"].unique())) or None,
            "reason": ("no concrete run at the same tyre, speed, pressure and load"
                       if m["n"] == 0 else m["reason"]),
        })
    return cells, pd.DataFrame(rows, columns=sum_cols)


# --------------------------------------------------------------------------- comparisons


def _norm_surface(s: pd.Series) -> pd.Series:
    return s.astype(str).str.strip().str.lower().str.replace(r"[\s\-]+", "_", regex=True)


def compare_with_thesis(
    ours: pd.DataFrame, thesis: pd.DataFrame | None, keys: list[str], values: dict[str, str],
) -> pd.DataFrame:
    """Outer-join our estimates with the thesis' and add differences.

    Parameters
    ----------
    ours : DataFrame
        Our table, with ``keys`` and the columns named in ``values``' keys.
    thesis : DataFrame or None
        Published table (``raw/published/*.csv``) with ``keys`` and the columns named
        in ``values``' values; None or empty gives null thesis columns.
    keys : list of str
        Join keys (e.g. ``["tyre_id", "condition"]``).
    values : dict
        our column -> published column.

    Returns
    -------
    DataFrame
        Keys, then per value ``thesis_<col>``, ``<col>``, ``<col>_difference`` (ours − thesis),
        then the remaining columns of ``ours``; also a boolean ``in_thesis``. Rows
        of either side without a partner are kept (thesis columns null for new tyres).

    See Also
    --------
    table_iii : Table III through it.
    table_vii : Table VII through it.

    Examples
    --------
    >>> ours = pd.DataFrame({"tyre_id": ["T1", "T9"], "k": [310.0, 200.0]})
    >>> thesis = pd.DataFrame({"tyre_id": ["T1"], "k_pub": [300.0]})
    >>> compare_with_thesis(ours, thesis, ["tyre_id"], {"k": "k_pub"})[["tyre_id", "thesis_k", "k", "k_difference", "in_thesis"]].to_dict("records")
    [{'tyre_id': 'T1', 'thesis_k': 300.0, 'k': 310.0, 'k_difference': 10.0, 'in_thesis': True}, {'tyre_id': 'T9', 'thesis_k': nan, 'k': 200.0, 'k_difference': nan, 'in_thesis': False}]
    """
    _validate.frame("ours", ours, [*keys, *values])
    if thesis is not None:
        _validate.frame("thesis", thesis)
    ours = ours.copy()
    th_cols = {pub: f"thesis_{col}" for col, pub in values.items()}
    if thesis is None or thesis.empty:
        th = pd.DataFrame(columns=keys + list(th_cols.values()))
    else:
        th = thesis.copy()
        for c in th_cols:
            if c not in th.columns:
                th[c] = np.nan
        extra = [c for c in th.columns if c not in keys and c not in th_cols and c not in ours.columns]
        th = th[keys + list(th_cols) + extra].rename(columns=th_cols)
        th = th.rename(columns={c: f"thesis_{c}" for c in extra})
    for k in keys:
        if k == "speed_km_h":
            ours[k] = _speed(ours[k])
            th[k] = _speed(th[k])
        elif k == "surface":
            ours[k] = _norm_surface(ours[k])
            th[k] = _norm_surface(th[k])
        else:
            ours[k] = ours[k].astype(str)
            th[k] = th[k].astype(str)
    th["in_thesis"] = True
    merged = ours.merge(th, on=keys, how="outer", sort=True)
    merged["in_thesis"] = merged["in_thesis"].astype("boolean").fillna(False).astype(bool)
    front = list(keys)
    for col in values:
        tcol = f"thesis_{col}"
        merged[tcol] = pd.to_numeric(merged[tcol], errors="coerce")
        merged[col] = pd.to_numeric(merged[col], errors="coerce") if col in merged else np.nan
        merged[f"{col}_difference"] = merged[col] - merged[tcol]
        front += [tcol, col, f"{col}_difference"]
    rest = [c for c in merged.columns if c not in front]
    return merged[front + rest].reset_index(drop=True)


def _fit_renamed(fit: pd.DataFrame, intercept: str | None, slope: str) -> pd.DataFrame:
    ren = {"slope": slope, "slope_se": f"{slope}_se", "slope_ci_low": f"{slope}_ci_low",
           "slope_ci_high": f"{slope}_ci_high"}
    if intercept is not None:
        ren.update({"intercept": intercept, "intercept_se": f"{intercept}_se",
                    "intercept_ci_low": f"{intercept}_ci_low", "intercept_ci_high": f"{intercept}_ci_high"})
    return fit.rename(columns=ren)


def table_iii(fit: pd.DataFrame, published: pd.DataFrame | None) -> pd.DataFrame:
    """Table III side by side: K_c, ΔK_p and r², thesis vs ours (thesis §4.3.1).

    Parameters
    ----------
    fit : DataFrame
        :func:`pressure_regressions` of stiffness by condition.
    published : DataFrame or None
        ``raw/published/table_iii.csv`` (tyre_id, size, condition, carcass_stiffness_kN_per_m,
        pressure_dependence_kN_per_m_bar, r_squared, r_squared_qualifier).

    See Also
    --------
    pressure_regressions : the fit it takes.
    compare_with_thesis : the side-by-side join.

    Examples
    --------
    >>> from tyrelab.tyre.examples import demo_runs
    >>> runs = demo_runs()                                  # tyre T1: 1.0-1.8 bar, standing and at 12 km/h
    >>> t = table_iii(pressure_regressions(runs), None)
    >>> t[["tyre_id", "condition", "carcass_stiffness_kN_per_m", "pressure_dependence_kN_per_m_bar"]].round(6).to_dict("records")[1]
    {'tyre_id': 'T1', 'condition': 'stationary', 'carcass_stiffness_kN_per_m': 300.0, 'pressure_dependence_kN_per_m_bar': 100.0}
    """
    _validate.frame("fit", fit, ["tyre_id", "condition"])
    if published is not None:
        _validate.frame("published", published)
    ours = _fit_renamed(fit, "carcass_stiffness_kN_per_m", "pressure_dependence_kN_per_m_bar")
    pub = None if published is None else published.loc[
        published[["carcass_stiffness_kN_per_m", "pressure_dependence_kN_per_m_bar"]].notna().any(axis=1)]
    return compare_with_thesis(
        ours, pub, ["tyre_id", "condition"],
        {"carcass_stiffness_kN_per_m": "carcass_stiffness_kN_per_m",
         "pressure_dependence_kN_per_m_bar": "pressure_dependence_kN_per_m_bar",
         "r_squared": "r_squared"},
    )


def table_vii(fit: pd.DataFrame, published: pd.DataFrame | None) -> pd.DataFrame:
    """Table VII side by side: carcass damping C_c, ΔC and r² per tyre × speed (thesis §5.3.1).

    ``fit`` is :func:`pressure_regressions` of damping by speed.

    See Also
    --------
    pressure_regressions : the fit it takes (``by="speed"``).
    table_iii : the same for stiffness.

    Examples
    --------
    >>> from tyrelab.tyre.examples import demo_runs
    >>> runs = demo_runs()                                  # tyre T1: 1.0-1.8 bar, standing and at 12 km/h
    >>> t = table_vii(pressure_regressions(runs, DAMPING, by="speed"), None)
    >>> t[["speed_km_h", "carcass_damping_kN_s_per_m", "pressure_dependence_kN_s_per_m_bar"]].round(6).to_dict("records")
    [{'speed_km_h': 0.0, 'carcass_damping_kN_s_per_m': 3.5, 'pressure_dependence_kN_s_per_m_bar': -0.5}, {'speed_km_h': 12.0, 'carcass_damping_kN_s_per_m': 1.75, 'pressure_dependence_kN_s_per_m_bar': -0.25}]
    """
    _validate.frame("fit", fit, ["tyre_id", "speed_km_h"])
    if published is not None:
        _validate.frame("published", published)
    ours = _fit_renamed(fit, "carcass_damping_kN_s_per_m", "pressure_dependence_kN_s_per_m_bar")
    return compare_with_thesis(
        ours, published, ["tyre_id", "speed_km_h"],
        {"carcass_damping_kN_s_per_m": "carcass_damping_kN_s_per_m",
         "pressure_dependence_kN_s_per_m_bar": "pressure_dependence_kN_s_per_m_bar",
         "r_squared": "r_squared"},
    )


def amplitude_table(rates: pd.DataFrame, published: pd.DataFrame | None, response: str) -> pd.DataFrame:
    """Table IV (stiffness) or VIII (damping): rate per mm p-p amplitude per tyre × speed.

    Parameters
    ----------
    rates : DataFrame
        :func:`factor_regressions` for ``factor="amplitude"``.
    published : DataFrame or None
        ``table_iv.csv`` (stiffness_rate_kN_per_m_per_mm) or ``table_viii.csv``
        (damping_rate_kN_s_per_m_per_mm), with tyre_id, speed_km_h, r_squared.
    response : str
        ``"stiffness_kN_per_m"`` (Table IV, thesis §4.3.4) or ``"damping_kN_s_per_m"``
        (Table VIII, §5.3.4).

    See Also
    --------
    factor_regressions : the rates it takes.
    compare_with_thesis : the side-by-side join.

    Examples
    --------
    >>> from tyrelab.tyre.examples import demo_runs
    >>> runs = demo_runs("amplitude")                       # tyre T1: 10, 14, 18 mm at 12 km/h
    >>> t = amplitude_table(factor_regressions(runs, "amplitude"), None, STIFFNESS)
    >>> t[["tyre_id", "speed_km_h", "stiffness_rate_kN_per_m_per_mm"]].round(6).to_dict("records")
    [{'tyre_id': 'T1', 'speed_km_h': 12.0, 'stiffness_rate_kN_per_m_per_mm': -2.5}]
    """
    _validate.frame("rates", rates)
    _validate.choice("response", response, (STIFFNESS, DAMPING))
    col = "stiffness_rate_kN_per_m_per_mm" if response == STIFFNESS else "damping_rate_kN_s_per_m_per_mm"
    sub = rates.loc[(rates["response"] == response) & (rates["factor"] == "amplitude")]
    sub = sub.drop(columns=["response", "factor", "factor_unit", "rate_unit"])
    ours = _fit_renamed(sub, None, col)
    return compare_with_thesis(ours, published, ["tyre_id", "speed_km_h"],
                               {col: col, "r_squared": "r_squared"})


def surface_table(summary: pd.DataFrame, published: pd.DataFrame | None, response: str) -> pd.DataFrame:
    """Table V (stiffness) or IX (damping): percent change per surface vs concrete.

    ``published`` is ``table_v.csv`` (surface, stiffness_change_percent) or ``table_ix.csv``
    (surface, damping_change_percent). Surfaces are matched case- and space-insensitively.

    See Also
    --------
    surface_effects : the summary it takes.
    compare_with_thesis : the side-by-side join.

    Examples
    --------
    >>> summary = pd.DataFrame({"surface": ["grass"], "n_cells": [4], "change_percent": [-10.0], "se": [1.0],
    ...                         "ci_low": [-13.2], "ci_high": [-6.8]})
    >>> published = pd.DataFrame({"surface": ["Grass"], "stiffness_change_percent": ["-12%"]})
    >>> surface_table(summary, published, STIFFNESS)[["surface", "thesis_stiffness_change_percent",
    ...                                               "stiffness_change_percent_difference"]].to_dict("records")
    [{'surface': 'grass', 'thesis_stiffness_change_percent': -12, 'stiffness_change_percent_difference': 2.0}]
    """
    _validate.frame("summary", summary)
    _validate.choice("response", response, (STIFFNESS, DAMPING))
    col = "stiffness_change_percent" if response == STIFFNESS else "damping_change_percent"
    ours = summary.rename(columns={"change_percent": col, "se": f"{col}_se",
                                   "ci_low": f"{col}_ci_low", "ci_high": f"{col}_ci_high"})
    if published is not None and not published.empty:
        published = published.copy()
        published[col] = pd.to_numeric(
            published[col].astype(str).str.replace("%", "").str.replace("+", "").str.strip()
            .replace({"-": np.nan, "": np.nan, "nan": np.nan, "None": np.nan}), errors="coerce")
    return compare_with_thesis(ours, published, ["surface"], {col: col})


# --------------------------------------------------------------------------- Tables VI and X

#: The condition rows of Tables VI and X we compute, with the unit of the rate (per unit
#: of the factor, or the total change over the speed range). The thesis values come from
#: ``raw/published/table_vi.csv`` / ``table_x.csv``.
SUMMARY_FACTORS = (
    ("pressure", "per bar"), ("rolling_speed_0_15", "total, 0-15 km/h"),
    ("rolling_speed_10_15", "total, 10-15 km/h"), ("load", "per kN"), ("amplitude", "per mm"),
    ("torque", "per kNm"), ("frequency", "per Hz"),
)


def summary_rates(
    by_speed: pd.DataFrame, rates: pd.DataFrame, response: str, *,
    pressure_bar: float = cond.STANDARD_PRESSURE_BAR, rolling_min_km_h: float = 1.0,
    published: pd.DataFrame | None = None,
) -> pd.DataFrame:
    """Table VI (stiffness) or X (damping): typical rates of change, ours beside the thesis'.

    Our value per factor is the mean over tyre × speed fits of rolling tyres
    (speed ≥ ``rolling_min_km_h``; the thesis quotes rolling rates) of the
    one-factor slope; the pressure row uses the per-speed pressure fits at
    10–15 km/h; the speed rows are the mean over tyres of K(15) − K(0) and
    K(15) − K(10) from the per-speed pressure fits evaluated at ``pressure_bar``.
    Thesis §4.5 Table VI, §5.4.3 Table X.

    Parameters
    ----------
    by_speed : DataFrame
        :func:`pressure_regressions` with ``by="speed"`` for ``response``.
    rates : DataFrame
        Concatenated :func:`factor_regressions` for amplitude, frequency, load, torque.
    response : str
    published : DataFrame, optional
        ``table_vi.csv`` / ``table_x.csv`` (factor, range_text, range_low, change_text,
        rate_value, rate_kind, ...): the thesis' value ("(none)" → 0), range and text.

    Returns
    -------
    DataFrame
        ``factor, measured_range, unit, thesis_value, thesis_change_text, value,
        value_difference, n, se, ci_low, ci_high, basis, reason``.

    See Also
    --------
    pressure_regressions : the per-speed fits it takes.
    factor_regressions : the rates it takes.

    Examples
    --------
    >>> from tyrelab.tyre.examples import demo_runs
    >>> runs = demo_runs()                                  # tyre T1: 1.0-1.8 bar, standing and at 12 km/h
    >>> rolling = runs.loc[runs["speed_km_h"] > 0]          # K rises 10 kN/m per kN of load here
    >>> rates = factor_regressions(rolling.assign(load_kN=[14.0, 18.0, 22.0], pressure_bar=1.38), "load")
    >>> t = summary_rates(pressure_regressions(runs, by="speed"), rates, STIFFNESS)
    >>> t.set_index("factor").loc[["pressure", "load"], "value"].round(6).tolist()
    [100.0, 10.0]
    """
    _validate.frame("by_speed", by_speed)
    _validate.frame("rates", rates)
    _validate.choice("response", response, (STIFFNESS, DAMPING))
    pressure_bar = _validate.positive("pressure_bar", pressure_bar)
    rolling_min_km_h = _validate.non_negative("rolling_min_km_h", rolling_min_km_h)
    response_unit = _RESPONSE_UNIT.get(response, response)
    rows = []
    bs = by_speed.dropna(subset=["slope"]).copy()
    lo, hi = cond.ROLLING_POOL_KM_H
    for factor, per in SUMMARY_FACTORS:
        unit = f"{response_unit} {per}"
        basis = ""
        if factor == "pressure":
            vals = bs.loc[(bs["speed_km_h"] >= lo) & (bs["speed_km_h"] <= hi), "slope"]
            basis = f"mean pressure dependence of per-speed fits at {lo:g}-{hi:g} km/h"
        elif factor.startswith("rolling_speed"):
            v0 = 0.0 if factor == "rolling_speed_0_15" else lo
            bs["k"] = bs["intercept"] + bs["slope"] * pressure_bar
            piv = bs.pivot_table(index="tyre_id", columns="speed_km_h", values="k")
            vals = (piv[hi] - piv[v0]).dropna() if (hi in piv and v0 in piv) else pd.Series(dtype=float)
            basis = f"mean over tyres of K({hi:g}) - K({v0:g} km/h) at {pressure_bar:g} bar (per-speed fits)"
        else:
            sub = rates.loc[(rates["response"] == response) & (rates["factor"] == factor)
                            & (rates["speed_km_h"] >= rolling_min_km_h)]
            vals = sub["slope"].dropna()
            basis = f"mean {factor} slope over tyre x speed fits at >= {rolling_min_km_h:g} km/h"
        m = fit_mean(vals)
        rows.append({"factor": factor, "measured_range": None, "unit": unit, "thesis_value": np.nan,
                     "value": m["mean"], "value_difference": np.nan,
                     "n": m["n"], "se": m["se"], "ci_low": m["ci_low"], "ci_high": m["ci_high"],
                     "basis": basis, "reason": m["reason"]})
    out = pd.DataFrame(rows)
    out.insert(4, "thesis_change_text", None)
    if published is not None and not published.empty and "factor" in published:
        pub = published.copy()
        pub["key"] = pub["factor"].astype(str).str.strip().str.lower().str.replace(" ", "_")
        low = pd.to_numeric(pub["range_low"], errors="coerce") if "range_low" in pub else pd.Series(np.nan, index=pub.index)
        rs = pub["key"] == "rolling_speed"
        pub.loc[rs, "key"] = np.where(low[rs] == 0, "rolling_speed_0_15", "rolling_speed_10_15")
        pub = pub.drop_duplicates("key").set_index("key")
        for i, f in enumerate(out["factor"]):
            if f not in pub.index:
                continue
            r = pub.loc[f]
            val = pd.to_numeric(pd.Series([r.get("rate_value")]), errors="coerce").iloc[0]
            if not np.isfinite(val) and str(r.get("rate_kind")) == "none":
                val = 0.0
            if np.isfinite(val):
                out.loc[i, "thesis_value"] = val
            out.loc[i, "thesis_change_text"] = r.get("change_text")
            out.loc[i, "measured_range"] = r.get("range_text")
        out["value_difference"] = out["value"] - out["thesis_value"]
    return out
