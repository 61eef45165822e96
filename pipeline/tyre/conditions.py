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

__all__ = ["REFERENCE_SURFACE", "NOMINAL_FREQUENCY_HZ", "FREQUENCY_TOLERANCE_HZ", "NOMINAL_AMPLITUDE_MM_PP",
    "NOMINAL_TORQUE_KNM", "ROLLING_POOL_KM_H", "STANDARD_PRESSURE_BAR", "SPEED_DECIMALS", "PRESSURE_DECIMALS",
    "LOAD_DECIMALS", "FACTORS", "RESULTS_COLUMNS", "with_columns", "usable", "on_reference_surface",
    "at_nominal_torque", "at_nominal_frequency", "at_nominal_amplitude", "nominal", "speed_condition",
    "table_iii_runs", "regressor", "factor_runs", "hold_constant"]

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


def with_columns(results: pd.DataFrame) -> pd.DataFrame:
    """``results`` with any missing :data:`RESULTS_COLUMNS` added as nulls (e.g. an empty table)."""
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
    """
    kind = _col(results, "kind", "measurement").fillna("measurement").astype(str)
    qc = _col(results, "qc_ok", True).fillna(False).astype(bool)
    return (kind == "measurement") & qc


def on_reference_surface(results: pd.DataFrame) -> pd.Series:
    """Runs on concrete (case-insensitive); missing surface counts as concrete."""
    s = _col(results, "surface", REFERENCE_SURFACE).fillna(REFERENCE_SURFACE).astype(str)
    return s.str.strip().str.lower() == REFERENCE_SURFACE


def at_nominal_torque(results: pd.DataFrame) -> pd.Series:
    """Runs without driving torque (missing torque counts as 0 kNm)."""
    t = pd.to_numeric(_col(results, "torque_kNm", 0.0), errors="coerce").fillna(0.0)
    return (t - NOMINAL_TORQUE_KNM).abs() < 1e-9


def at_nominal_frequency(results: pd.DataFrame) -> pd.Series:
    """Runs at nominal excitation 4 Hz ± 0.5 Hz (nominal, not measured, frequency)."""
    f = pd.to_numeric(_col(results, "excitation_frequency_Hz", np.nan), errors="coerce")
    return (f - NOMINAL_FREQUENCY_HZ).abs() <= FREQUENCY_TOLERANCE_HZ + 1e-9


def at_nominal_amplitude(results: pd.DataFrame) -> pd.Series:
    """Runs at nominal amplitude 10–18 mm peak-to-peak (nominal amplitude)."""
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
    """
    if except_for is not None and except_for not in _NOMINAL_TESTS and except_for not in FACTORS:
        raise ValueError(f"unknown condition {except_for!r}")
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
    """
    v = pd.Series(pd.to_numeric(pd.Series(speed_km_h), errors="coerce").to_numpy(), dtype=float)
    lo, hi = ROLLING_POOL_KM_H
    out = pd.Series([None] * len(v), dtype=object, index=v.index)
    out[v.abs() < 1e-9] = "stationary"
    out[(v >= lo - 1e-9) & (v <= hi + 1e-9)] = "rolling"
    return out


def table_iii_runs(results: pd.DataFrame) -> pd.DataFrame:
    """Nominal runs with a Table III ``condition`` column (stationary / rolling), others dropped.

    Thesis §4.3.1, Table III. Returns a copy of the selected rows.
    """
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
    """
    nominal_col, measured_col, _ = FACTORS[factor]
    x = pd.to_numeric(_col(results, nominal_col, np.nan), errors="coerce").astype(float)
    if measured_col is not None and measured_col in results.columns:
        m = pd.to_numeric(results[measured_col], errors="coerce").astype(float)
        x = m.where(m.notna(), x)
    return x


def factor_runs(results: pd.DataFrame, factor: str) -> pd.DataFrame:
    """Runs for a one-factor regression on ``factor`` (all other convention conditions nominal).

    Adds column ``x`` (the regressor, :func:`regressor`). Thesis §4.3.3–4.3.6, §5.3.3–5.3.6.
    """
    if factor not in FACTORS:
        raise ValueError(f"unknown factor {factor!r}; expected one of {sorted(FACTORS)}")
    free = factor if factor in _NOMINAL_TESTS else None
    sel = results.loc[nominal(results, except_for=free)].copy()
    sel["x"] = regressor(sel, factor).to_numpy()
    return sel.loc[sel["x"].notna()]


def hold_constant(
    runs: pd.DataFrame, x: str, hold: list[str], *, prefer: dict[str, float] | None = None
) -> tuple[pd.DataFrame, dict[str, float | None], str]:
    """Keep the runs of one level of the ``hold`` columns: the one with most distinct ``x``.

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
    """
    prefer = prefer or {}
    cols = [c for c in hold if c in runs.columns]
    if not cols or runs.empty:
        return runs, {c: None for c in hold}, ""
    decimals = {"load_kN": LOAD_DECIMALS, "pressure_bar": PRESSURE_DECIMALS}
    keys = pd.DataFrame(
        {c: pd.to_numeric(runs[c], errors="coerce").round(decimals.get(c, 3)) for c in cols},
        index=runs.index,
    )
    if keys.isna().any(axis=None):
        keys = keys.fillna(-1.0)
    best = None
    for level, sub_keys in keys.groupby(cols, sort=True):
        level = level if isinstance(level, tuple) else (level,)
        idx = sub_keys.index
        sub_x = runs[x].loc[idx]  # only the regressor: taking every column of a wide table is slow
        distinct = sub_x.round(6).nunique()
        distance = sum(abs(v - prefer[c]) for c, v in zip(cols, level) if c in prefer)
        score = (distinct, len(sub_x), -distance, -sum(level))
        if best is None or score > best[0]:
            best = (score, level, idx)
    (distinct, _, _, _), level, idx = best
    if distinct < 2 and runs[x].round(6).nunique() >= 2 and keys.drop_duplicates().shape[0] > 1:
        return runs, {c: None for c in hold}, f"pooled over {', '.join(cols)} (no single level varies the regressor)"
    levels = {c: (float(v) if v != -1.0 else None) for c, v in zip(cols, level)}
    levels.update({c: None for c in hold if c not in cols})
    return runs.loc[idx], levels, ""
