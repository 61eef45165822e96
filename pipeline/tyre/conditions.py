"""Which runs count for which thesis regression: the one place for the convention.

Thesis chapters 4 and 5 vary one condition at a time around a standard set of
conditions. The thesis never tabulates that standard set, so tyrelab fixes it
here, and every regression in :mod:`tyrelab.tyre.regressions` selects its runs
through these functions.

The convention (used for Table III and Table VII, the pressure regressions)
-------------------------------------------------------------------------
A *nominal* run is

* ``kind == "measurement"`` (not a force-plate calibration run) and ``qc_ok``;
* on ``surface == "concrete"`` (thesis §4.3.7: the reference surface of Table V);
* at driving torque 0 kNm (§4.3.6);
* at nominal excitation frequency 4 Hz ± 0.5 Hz (§3.5, §4.3.5);
* at nominal amplitude 10–18 mm peak-to-peak (§3.5: 5 mm rms ≈ 14 mm p-p).

*Stationary* is speed 0 km/h. The *rolling* column of Table III pools the
nominal runs with 10 ≤ speed ≤ 15 km/h: the thesis finds stiffness "almost
constant" from 10 km/h on (§4.3.2), and Table VII / Fig. 21 show 10 and 15 km/h
as the standard rolling speeds. Per-speed fits (table
``stiffness_pressure_by_speed``) use the individual speeds instead.

Held-constant conditions
------------------------
Load is not part of the brief's convention, but the thesis varied it
(§4.3.3, §5.3.3: damping rises by up to 0.2 kNs/m per kN), so a pressure
regression pooling loads would mix two effects. Regressions therefore hold the
non-regressed free conditions (load, and pressure for the one-factor
regressions) constant at the level that gives the most distinct values of the
regressor (ties: most runs, then the level nearest the thesis' standard 1.38 bar
/ the lowest load). If no single level gives two distinct regressor values but
the pooled runs do, the runs are pooled and the fit says so in ``note``. See
:func:`hold_constant`.

One-factor regressions (Tables IV, VIII and the rates of Tables VI, X)
---------------------------------------------------------------------
For a regression on factor X, every convention condition other than X is held
nominal (:func:`factor_runs`) and the rest is held constant per
:func:`hold_constant`. The regressor is the *measured* value where the results
carry one (``amplitude_measured_mm_pp``, ``excitation_frequency_measured_Hz``)
and the nominal value otherwise (:data:`FACTORS`).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .. import _validate

__all__ = ["REFERENCE_SURFACE", "NOMINAL_FREQUENCY_HZ", "FREQUENCY_TOLERANCE_HZ", "NOMINAL_AMPLITUDE_MM_PP",
    "NOMINAL_TORQUE_KNM", "ROLLING_POOL_KM_H", "STANDARD_PRESSURE_BAR", "SPEED_DECIMALS", "PRESSURE_DECIMALS",
    "LOAD_DECIMALS", "FACTORS", "RESULTS_COLUMNS", "with_columns", "usable", "on_reference_surface",
    "at_nominal_torque", "at_nominal_frequency", "at_nominal_amplitude", "nominal", "speed_condition",
    "table_iii_runs", "regressor", "factor_runs", "hold_levels", "hold_level", "n_distinct", "hold_constant"]

#: Reference surface (thesis §4.3.7, Tables V and IX are relative to it).
REFERENCE_SURFACE = "concrete"
#: Nominal excitation frequency and tolerance, Hz (thesis §3.5).
NOMINAL_FREQUENCY_HZ = 4.0
FREQUENCY_TOLERANCE_HZ = 0.5
#: Nominal peak-to-peak amplitude window, mm (thesis §3.5: 5 mm rms ≈ 14 mm p-p).
NOMINAL_AMPLITUDE_MM_PP = (10.0, 18.0)
#: Nominal driving torque, kNm (§4.3.6: torque up to 4.7 kNm was an experiment variable).
NOMINAL_TORQUE_KNM = 0.0
#: Speeds pooled into the "rolling" column of Table III, km/h (thesis §4.3.2).
ROLLING_POOL_KM_H = (10.0, 15.0)
#: The thesis' standard inflation pressure (Figs 21, 22, 34, 35), bar.
STANDARD_PRESSURE_BAR = 1.38

#: Rounding used to decide that two runs share a condition level.
SPEED_DECIMALS = 2
PRESSURE_DECIMALS = 2
LOAD_DECIMALS = 1

#: One-factor regressors: factor -> (nominal column, preferred measured column or None, unit).
FACTORS: dict[str, tuple[str, str | None, str]] = {
    "pressure": ("pressure_bar", None, "bar"),
    "amplitude": ("amplitude_mm_pp", "amplitude_measured_mm_pp", "mm"),
    "frequency": ("excitation_frequency_Hz", "excitation_frequency_measured_Hz", "Hz"),
    "load": ("load_kN", None, "kN"),
    "torque": ("torque_kNm", None, "kNm"),
}


#: Columns of the ``results`` table the regressions read (architecture.md).
RESULTS_COLUMNS = [
    "tyre_id", "kind", "speed_km_h", "pressure_bar", "load_kN", "excitation_frequency_Hz",
    "amplitude_mm_pp", "torque_kNm", "surface", "excitation_frequency_measured_Hz",
    "stiffness_kN_per_m", "damping_kN_s_per_m", "amplitude_measured_mm_pp", "qc_ok",
]


def _numbers(name: str, values) -> np.ndarray:
    try:
        return np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be numbers, got {values!r}") from None


def with_columns(results: pd.DataFrame) -> pd.DataFrame:
    """``results`` with any missing :data:`RESULTS_COLUMNS` added as nulls (e.g. an empty table).

    See Also
    --------
    RESULTS_COLUMNS : the columns added.
    usable : the first test every selection applies.

    Examples
    --------
    >>> out = with_columns(pd.DataFrame({"tyre_id": ["T1"]}))
    >>> all(c in out.columns for c in RESULTS_COLUMNS), bool(out["qc_ok"].isna().all())
    (True, True)
    """
    _validate.frame("results", results)
    missing = [c for c in RESULTS_COLUMNS if c not in results.columns]
    if not missing:
        return results
    return results.assign(**{c: pd.Series(np.nan, index=results.index, dtype=object if c in
                                          ("tyre_id", "kind", "surface") else float) for c in missing})


def _col(df: pd.DataFrame, name: str, default) -> pd.Series:
    if name in df.columns:
        return df[name]
    return pd.Series(default, index=df.index)


def usable(results: pd.DataFrame) -> pd.Series:
    """Measurement runs that passed QC.

    Parameters
    ----------
    results : DataFrame
        The ``results`` table (one row per run). ``kind`` missing means
        ``"measurement"``, ``qc_ok`` missing means true.

    Returns
    -------
    Series of bool, aligned with ``results``.

    See Also
    --------
    nominal : usable and at every nominal condition.
    with_columns : the columns a selection reads.

    Examples
    --------
    >>> from tyrelab.tyre.examples import demo_runs
    >>> results = demo_runs("mixed")       # passed QC standing and rolling; failed QC; a calibration run
    >>> usable(results).tolist()
    [True, True, False, False]
    """
    _validate.frame("results", results)
    kind = _col(results, "kind", "measurement").fillna("measurement").astype(str)
    qc = _col(results, "qc_ok", True).fillna(False).astype(bool)
    return (kind == "measurement") & qc


def on_reference_surface(results: pd.DataFrame) -> pd.Series:
    """Runs on concrete (case-insensitive); missing surface counts as concrete.

    See Also
    --------
    nominal : every nominal condition together.
    REFERENCE_SURFACE : concrete.

    Examples
    --------
    >>> on_reference_surface(pd.DataFrame({"surface": ["Concrete ", "grass", None]})).tolist()
    [True, False, True]
    """
    _validate.frame("results", results)
    s = _col(results, "surface", REFERENCE_SURFACE).fillna(REFERENCE_SURFACE).astype(str)
    return s.str.strip().str.lower() == REFERENCE_SURFACE


def at_nominal_torque(results: pd.DataFrame) -> pd.Series:
    """Runs without driving torque (missing torque counts as 0 kNm).

    See Also
    --------
    nominal : every nominal condition together.
    NOMINAL_TORQUE_KNM : 0 kNm.

    Examples
    --------
    >>> at_nominal_torque(pd.DataFrame({"torque_kNm": [0.0, 4.7, None]})).tolist()
    [True, False, True]
    """
    _validate.frame("results", results)
    t = pd.to_numeric(_col(results, "torque_kNm", 0.0), errors="coerce").fillna(0.0)
    return (t - NOMINAL_TORQUE_KNM).abs() < 1e-9


def at_nominal_frequency(results: pd.DataFrame) -> pd.Series:
    """Runs at nominal excitation 4 Hz ± 0.5 Hz (nominal, not measured, frequency).

    See Also
    --------
    nominal : every nominal condition together.
    regressor : the frequency as a regressor (measured where present).

    Examples
    --------
    >>> at_nominal_frequency(pd.DataFrame({"excitation_frequency_Hz": [4.0, 4.5, 6.0]})).tolist()
    [True, True, False]
    """
    _validate.frame("results", results)
    f = pd.to_numeric(_col(results, "excitation_frequency_Hz", np.nan), errors="coerce")
    return (f - NOMINAL_FREQUENCY_HZ).abs() <= FREQUENCY_TOLERANCE_HZ + 1e-9


def at_nominal_amplitude(results: pd.DataFrame) -> pd.Series:
    """Runs at nominal amplitude 10–18 mm peak-to-peak (nominal amplitude).

    See Also
    --------
    nominal : every nominal condition together.
    NOMINAL_AMPLITUDE_MM_PP : the window, mm peak-to-peak.

    Examples
    --------
    >>> at_nominal_amplitude(pd.DataFrame({"amplitude_mm_pp": [10.0, 14.0, 30.0]})).tolist()
    [True, True, False]
    """
    _validate.frame("results", results)
    a = pd.to_numeric(_col(results, "amplitude_mm_pp", np.nan), errors="coerce")
    lo, hi = NOMINAL_AMPLITUDE_MM_PP
    return (a >= lo - 1e-9) & (a <= hi + 1e-9)


_NOMINAL_TESTS = {
    "surface": on_reference_surface,
    "torque": at_nominal_torque,
    "frequency": at_nominal_frequency,
    "amplitude": at_nominal_amplitude,
}


def nominal(results: pd.DataFrame, *, except_for: str | None = None) -> pd.Series:
    """Nominal runs of the convention (module docstring), optionally freeing one condition.

    Parameters
    ----------
    results : DataFrame
        The ``results`` table.
    except_for : {"surface", "torque", "frequency", "amplitude"} or None
        Condition left free (e.g. ``"amplitude"`` for Table IV).

    Returns
    -------
    Series of bool.

    See Also
    --------
    usable : the runs that passed QC.
    table_iii_runs : the nominal runs with their Table III condition.
    factor_runs : the nominal runs of a one-factor regression.

    Examples
    --------
    >>> from tyrelab.tyre.examples import demo_runs
    >>> results = demo_runs("mixed")       # passed QC standing and rolling; failed QC; a calibration run
    >>> nominal(results).tolist()
    [True, False, False, False]
    >>> nominal(results, except_for="surface").tolist()
    [True, True, False, False]
    """
    _validate.frame("results", results)
    if except_for is not None and except_for not in _NOMINAL_TESTS and except_for not in FACTORS:
        raise ValueError(f"except_for: unknown condition {except_for!r}")
    mask = usable(results)
    for name, test in _NOMINAL_TESTS.items():
        if name != except_for:
            mask &= test(results)
    return mask


def speed_condition(speed_km_h) -> pd.Series:
    """Table III condition of a speed: ``"stationary"`` (0), ``"rolling"`` (10–15 km/h) or None.

    Parameters
    ----------
    speed_km_h : array-like
        Rolling speed, km/h.

    Returns
    -------
    Series of object (str or None).

    See Also
    --------
    table_iii_runs : the nominal runs with this condition.
    ROLLING_POOL_KM_H : the speeds pooled as rolling.

    Examples
    --------
    >>> speed_condition([0.0, 5.0, 12.0, 15.0]).tolist()
    ['stationary', None, 'rolling', 'rolling']
    """
    _validate.non_negative_array("speed_km_h", pd.to_numeric(pd.Series(speed_km_h, dtype=object), errors="coerce"),
                                allow_nan=True)
    v = pd.Series(pd.to_numeric(pd.Series(speed_km_h), errors="coerce").to_numpy(), dtype=float)
    lo, hi = ROLLING_POOL_KM_H
    out = pd.Series([None] * len(v), dtype=object, index=v.index)
    out[v.abs() < 1e-9] = "stationary"
    out[(v >= lo - 1e-9) & (v <= hi + 1e-9)] = "rolling"
    return out


def table_iii_runs(results: pd.DataFrame) -> pd.DataFrame:
    """Nominal runs with a Table III ``condition`` column (stationary / rolling), others dropped.

    Thesis §4.3.1, Table III. Returns a copy of the selected rows.

    See Also
    --------
    nominal : the runs it keeps.
    speed_condition : the condition of a speed.
    tyrelab.tyre.regressions.table_iii : the pressure regression of these runs.

    Examples
    --------
    >>> from tyrelab.tyre.examples import demo_runs
    >>> results = demo_runs("mixed")       # passed QC standing and rolling; failed QC; a calibration run
    >>> table_iii_runs(results)[["speed_km_h", "condition"]].to_dict("records")
    [{'speed_km_h': 0.0, 'condition': 'stationary'}]
    """
    _validate.frame("results", results, ["speed_km_h"])
    sel = results.loc[nominal(results)].copy()
    sel["condition"] = speed_condition(sel["speed_km_h"]).to_numpy()
    return sel.loc[sel["condition"].notna()]


def regressor(results: pd.DataFrame, factor: str) -> pd.Series:
    """Value of the regressor for ``factor``: measured where present, else nominal.

    Parameters
    ----------
    results : DataFrame
    factor : str
        A key of :data:`FACTORS`.

    Returns
    -------
    Series of float in the factor's unit (:data:`FACTORS`).

    See Also
    --------
    factor_runs : the runs of a one-factor regression, with this as ``x``.
    FACTORS : each factor's nominal and measured column.

    Examples
    --------
    >>> runs = pd.DataFrame({"amplitude_mm_pp": [14.0, 14.0], "amplitude_measured_mm_pp": [13.2, None]})
    >>> regressor(runs, "amplitude").tolist()
    [13.2, 14.0]
    """
    _validate.frame("results", results)
    _validate.choice("factor", factor, tuple(FACTORS))
    nominal_col, measured_col, _ = FACTORS[factor]
    x = pd.to_numeric(_col(results, nominal_col, np.nan), errors="coerce").astype(float)
    if measured_col is not None and measured_col in results.columns:
        m = pd.to_numeric(results[measured_col], errors="coerce").astype(float)
        x = m.where(m.notna(), x)
    return x


def factor_runs(results: pd.DataFrame, factor: str) -> pd.DataFrame:
    """Runs for a one-factor regression on ``factor`` (all other convention conditions nominal).

    Adds column ``x`` (the regressor, :func:`regressor`). Thesis §4.3.3–4.3.6, §5.3.3–5.3.6.

    See Also
    --------
    regressor : the column ``x``.
    nominal : the other conditions held nominal.
    hold_constant : the held level of the free conditions.

    Examples
    --------
    >>> runs = pd.DataFrame({"speed_km_h": [0.0] * 3, "pressure_bar": [1.0, 1.4, 1.8],
    ...                      "excitation_frequency_Hz": [4.0, 4.0, 6.0], "amplitude_mm_pp": [14.0] * 3})
    >>> factor_runs(runs, "pressure")["x"].tolist()
    [1.0, 1.4]
    """
    _validate.frame("results", results)
    if factor not in FACTORS:
        raise ValueError(f"unknown factor {factor!r}; expected one of {sorted(FACTORS)}")
    free = factor if factor in _NOMINAL_TESTS else None
    sel = results.loc[nominal(results, except_for=free)].copy()
    sel["x"] = regressor(sel, factor).to_numpy()
    return sel.loc[sel["x"].notna()]


_HOLD_DECIMALS = {"load_kN": LOAD_DECIMALS, "pressure_bar": PRESSURE_DECIMALS}


def hold_levels(runs: pd.DataFrame, cols: list[str]) -> np.ndarray:
    """Rounded levels of the ``cols`` of ``runs`` as an ``(n, len(cols))`` float array (missing → −1).

    The keys by which :func:`hold_constant` groups runs: load to 0.1 kN, pressure to 0.01 bar,
    any other column to 3 decimals.

    See Also
    --------
    hold_constant : groups runs by these keys.

    Examples
    --------
    >>> hold_levels(pd.DataFrame({"load_kN": [10.04, None]}), ["load_kN"]).ravel().tolist()
    [10.0, -1.0]
    """
    _validate.frame("runs", runs, cols)
    keys = np.empty((len(runs), len(cols)), dtype=float)
    for j, c in enumerate(cols):
        keys[:, j] = np.round(pd.to_numeric(runs[c], errors="coerce").to_numpy(dtype=float, na_value=np.nan),
                              _HOLD_DECIMALS.get(c, 3))
    keys[np.isnan(keys)] = -1.0
    return keys


def n_distinct(values) -> int:
    """Number of distinct non-NaN values of a float array (as ``Series.nunique``).

    See Also
    --------
    hold_level : counts the distinct regressor values of each level with it.

    Examples
    --------
    >>> n_distinct(np.array([1.0, 1.0, np.nan, 2.0]))
    2
    """
    values = _numbers("values", values)
    values = np.asarray(values, dtype=float)
    values = values[~np.isnan(values)]
    return int(len(np.unique(values))) if len(values) else 0


def hold_level(x, keys: np.ndarray, cols: list[str], hold: list[str], prefer: dict[str, float] | None = None):
    """:func:`hold_constant` on arrays: which runs of one group to keep.

    Parameters
    ----------
    x : array-like of float
        Regressor values of the group's runs.
    keys : ndarray
        :func:`hold_levels` of the group's runs (columns ``cols``, those of ``hold`` present).
    cols, hold : list of str
        Held columns present, and all held columns (absent ones get level None).
    prefer : dict, optional
        Tie-break target per column.

    Returns
    -------
    positions : ndarray of int or None
        Positions (ascending) of the kept runs; None when the runs are pooled (all kept).
    levels : dict
        Held level per column of ``hold`` (None where pooled or absent).
    note : str
        Empty, or why the runs were pooled.

    See Also
    --------
    hold_constant : the same on a DataFrame.
    hold_levels : the keys it takes.

    Examples
    --------
    >>> keys = np.array([[1.0], [1.0], [2.0]])
    >>> pos, levels, note = hold_level(np.array([1.0, 2.0, 1.0]), keys, ["load_kN"], ["load_kN"])
    >>> pos.tolist(), levels, note
    ([0, 1], {'load_kN': 1.0}, '')
    """
    prefer = prefer or {}
    x = np.asarray(x, dtype=float)
    keys = np.asarray(keys, dtype=float)
    if keys.shape != (len(x), len(cols)):
        raise ValueError(f"keys must have shape (len(x), len(cols)) = {(len(x), len(cols))}, not {keys.shape}")
    if len(x) == 0 or not cols:
        return None, {c: None for c in hold}, ""
    xr = np.round(x, 6)
    # the levels in lexicographic order (a stable sort keeps each level's runs in their order)
    order = np.lexsort(keys.T[::-1])
    ordered = keys[order]
    starts = np.flatnonzero(np.r_[True, np.any(ordered[1:] != ordered[:-1], axis=1)])
    ends = np.r_[starts[1:], len(order)]
    best = None
    for s, e in zip(starts.tolist(), ends.tolist()):
        level = tuple(ordered[s].tolist())
        pos = order[s:e]
        distinct = n_distinct(xr[pos])
        distance = sum(abs(v - prefer[c]) for c, v in zip(cols, level) if c in prefer)
        score = (distinct, e - s, -distance, -sum(level))
        if best is None or score > best[0]:
            best = (score, level, pos)
    (distinct, _, _, _), level, pos = best
    if distinct < 2 and n_distinct(xr) >= 2 and len(starts) > 1:
        return None, {c: None for c in hold}, f"pooled over {', '.join(cols)} (no single level varies the regressor)"
    levels = {c: (float(v) if v != -1.0 else None) for c, v in zip(cols, level)}
    levels.update({c: None for c in hold if c not in cols})
    return pos, levels, ""


def hold_constant(
    runs: pd.DataFrame, x: str, hold: list[str], *, prefer: dict[str, float] | None = None
) -> tuple[pd.DataFrame, dict[str, float | None], str]:
    """Keep the runs of one level of the ``hold`` columns: the one with most distinct ``x``.

    Levels are ``hold`` values rounded (:func:`hold_levels`); ties of distinct ``x`` go to the
    level with most runs, then the one nearest ``prefer``, then the lowest (:func:`hold_level`,
    the same rule on arrays).

    Parameters
    ----------
    runs : DataFrame
        Runs of one group (e.g. one tyre and speed).
    x : str
        Regressor column.
    hold : list of str
        Columns to hold constant (e.g. ``["load_kN"]``); missing columns are ignored.
    prefer : dict, optional
        Tie-break target per column (e.g. ``{"pressure_bar": 1.38}``): nearest wins.

    Returns
    -------
    runs : DataFrame
        The selected runs.
    levels : dict
        Held level per column (None where pooled).
    note : str
        Empty, or why the runs were pooled.

    See Also
    --------
    hold_level : the same rule on arrays.
    factor_runs : the runs it is applied to.

    Examples
    --------
    >>> runs = pd.DataFrame({"pressure_bar": [1.0, 1.4, 1.8, 1.0], "load_kN": [18.3, 18.3, 18.3, 22.0]})
    >>> kept, levels, note = hold_constant(runs, "pressure_bar", ["load_kN"])
    >>> kept["pressure_bar"].tolist(), levels, note
    ([1.0, 1.4, 1.8], {'load_kN': 18.3}, '')
    """
    _validate.frame("runs", runs)
    cols = [c for c in hold if c in runs.columns]
    if not cols or runs.empty:
        return runs, {c: None for c in hold}, ""
    if x not in runs.columns:
        raise ValueError(f"x: runs has no column {x!r}")
    xs = pd.to_numeric(runs[x], errors="coerce").to_numpy(dtype=float, na_value=np.nan)
    pos, levels, note = hold_level(xs, hold_levels(runs, cols), cols, hold, prefer)
    return (runs if pos is None else runs.loc[runs.index[pos]]), levels, note
