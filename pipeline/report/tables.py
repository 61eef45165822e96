"""Shape warehouse tables for the report: pure functions, no I/O.

A *comparison* table puts, per quantity, the thesis value, ours and the
difference side by side. Stages name these columns in several ways, all
recognised by :func:`find_pairs`:

- ``thesis_<x>`` / ``<x>`` / ``<x>_difference`` (regress),
- ``thesis_<x>`` / ``ours_<x>`` / ``difference_<x>`` (simulate),
- ``<x>_thesis`` / ``<x>_ours`` (Table XVIII).

Where a stage wrote only our values, :func:`compare_frames` joins them with
the digitised thesis table; where it wrote nothing yet, :func:`thesis_only`
gives the thesis columns with empty "ours" columns.

A difference is *highlighted* when it exceeds the thesis' own precision,
taken as the largest of half a unit in the last printed digit of the thesis
value, :data:`REL_TOL` of the thesis value, and the quantity's scatter floor
in :data:`ABS_TOL` (e.g. the ±8 kN/m standard error of K_c, thesis §4.3.1).
"""

from __future__ import annotations

import dataclasses
import math
import re
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

__all__ = ["REL_TOL", "ABS_TOL", "NUMERIC_KEYS", "HIDDEN", "EXTRAS", "Pair", "Shaped", "find_pairs",
    "tolerance", "shape_comparison", "compare_frames", "thesis_only", "plain_table", "campaign_summary",
    "select_runs", "interval_text", "pair_decimals", "uncertainty_decimals", "significant_decimals", "natural_order", "Note",
    "LONG_TEXT_CHARS", "MAX_DECIMALS"]

#: Relative tolerance beyond which a difference is highlighted.
REL_TOL = 0.05
#: Absolute floors of the tolerance by column keyword (first match wins).
ABS_TOL = {
    "carcass_stiffness": 8.0,
    "pressure_dependence_kN_per_m": 8.0,
    "stiffness_kN_per_m": 8.0,
    "r_squared": 0.02,
    "_Hz": 0.05,
    "percent": 2.0,
}
#: Numeric columns that identify a row rather than measure something.
NUMERIC_KEYS = {
    "speed_km_h", "nominal_speed_km_h", "pressure_bar", "rear_pressure_bar", "front_pressure_bar",
    "load_kg", "load_kN", "load_condition", "longitudinal_stiffness_kN_per_m",
    "longitudinal_damping_kN_s_per_m", "range_low", "range_high",
}
#: Columns never shown (long free text, bookkeeping); they stay in the warehouse.
HIDDEN = {"notes", "note", "reason", "basis", "printed_text", "uncertain_columns", "in_thesis", "tyres",
          "sign_restored", "surface_assigned", "r_squared_qualifier", "rolling_qualifier",
          "stationary_qualifier", "input_hash", "row_hash", "sha256"}
#: Extra numeric columns worth showing next to the pairs.
EXTRAS = ("n",)


@dataclass(frozen=True)
class Pair:
    """One compared quantity: its label and the thesis, ours and difference columns.

    ``decimals`` is how many decimals ours, its interval and Δ are shown with (the same for every
    row: one format per quantity, :func:`pair_decimals`); None until :func:`shape_comparison` sets it.
    """

    label: str
    thesis: str
    ours: str
    difference: str | None = None
    decimals: int | None = None


@dataclass
class Shaped:
    """A table ready for the ``comparison`` macro.

    Attributes
    ----------
    keys : list of str
        Identifying columns, shown first.
    pairs : list of Pair
        Compared quantities (thesis | ours | Δ each).
    extras : list of str
        Further plain columns.
    rows : list of dict
        Per row: ``cells`` (key/extra column -> value), ``intervals`` (per pair, the
        95 % interval of ours as text, :func:`interval_text`) and ``pairs`` (list of
        (thesis, ours, difference, off) per pair).
    n_off : int
        Number of highlighted differences.
    notes : list of str
        Long texts moved out of their cells (:class:`Note`), note 1 first.
    not_compared : list of dict
        Rows (as ``rows``) with the thesis' values and none of ours, when other rows have ours:
        the thesis' conditions this campaign did not measure, shown behind a count.
    """

    keys: list[str]
    pairs: list[Pair]
    extras: list[str]
    rows: list[dict] = field(default_factory=list)
    n_off: int = 0
    notes: list[str] = field(default_factory=list)
    not_compared: list[dict] = field(default_factory=list)


def find_pairs(columns) -> list[Pair]:
    """Thesis/ours/difference column triples among ``columns`` (module docstring)."""
    cols = list(columns)
    have = set(cols)
    pairs = []
    for c in cols:
        if c.startswith("thesis_"):
            x = c[len("thesis_"):]
            ours = next((o for o in (x, f"ours_{x}") if o in have), None)
        elif c.endswith("_thesis"):
            x = c[: -len("_thesis")]
            ours = f"{x}_ours" if f"{x}_ours" in have else None
        else:
            continue
        if ours is None:
            continue
        diff = next((d for d in (f"difference_{x}", f"{x}_difference") if d in have), None)
        pairs.append(Pair(x, c, ours, diff))
    return pairs


def _decimals(value: float) -> int:
    text = f"{abs(value):.6f}".rstrip("0")
    return len(text.split(".")[1]) if "." in text else 0


def tolerance(thesis_value: float, label: str) -> float:
    """Largest difference from ``thesis_value`` that the thesis' precision allows.

    Parameters
    ----------
    thesis_value : float
        The printed value.
    label : str
        Quantity (column) name, matched against :data:`ABS_TOL` keywords.

    Returns
    -------
    float
        ``max(half unit of the last printed digit, REL_TOL·|value|, ABS_TOL floor)``.
    """
    floor = next((v for k, v in ABS_TOL.items() if k in label), 0.0)
    half_unit = 0.5 * 10.0 ** (-_decimals(thesis_value))
    return max(half_unit, REL_TOL * abs(thesis_value), floor)


def _num(v) -> float:
    try:
        f = float(v)
    except (TypeError, ValueError):
        return math.nan
    return f


def _is_numeric(s: pd.Series) -> bool:
    return pd.api.types.is_numeric_dtype(s) and not pd.api.types.is_bool_dtype(s)


def shape_comparison(df: pd.DataFrame, extras: tuple[str, ...] = EXTRAS, columns: tuple[str, ...] = ()) -> Shaped:
    """Split ``df`` into key columns, compared pairs and extras; flag differences.

    Parameters
    ----------
    df : DataFrame
        A table with comparison columns (see :func:`find_pairs`).
    extras : tuple of str, optional
        Plain columns to keep when present.
    columns : tuple of str, optional
        When given, the only key and extra columns shown (the compared pairs are always shown).

    Returns
    -------
    Shaped
    """
    pairs = [dataclasses.replace(p, decimals=pair_decimals(df, p)) for p in find_pairs(df.columns)]
    used = {c for p in pairs for c in (p.thesis, p.ours, p.difference) if c}
    keys = [
        c for c in df.columns
        if c not in used and c not in HIDDEN and c not in extras and not c.startswith("thesis_")
        and not c.endswith(("_difference", "_se", "_ci_low", "_ci_high", "_thesis", "_ours"))
        and not c.startswith(("difference_", "ours_"))
        and (not _is_numeric(df[c]) or c in NUMERIC_KEYS)
    ]
    extra = [c for c in extras if c in df.columns and c not in used]
    if columns:
        keys = [c for c in keys if c in columns]
        extra = [c for c in extra if c in columns]
    shaped = Shaped(keys=keys, pairs=pairs, extras=extra)
    for rec in df.to_dict(orient="records"):
        cells = {c: _noted(rec[c], shaped.notes) for c in keys + extra}
        row_pairs = []
        for p in pairs:
            t, o = _num(rec[p.thesis]), _num(rec[p.ours])
            d = _num(rec[p.difference]) if p.difference else o - t
            off = bool(np.isfinite(d) and np.isfinite(t) and abs(d) > tolerance(t, p.label))
            shaped.n_off += off
            row_pairs.append((t, o, d, off))
        shaped.rows.append({"cells": cells, "pairs": row_pairs,
                            "intervals": [interval_text(rec, p.ours, p.decimals) for p in pairs]})
    compared = [r for r in shaped.rows if any(np.isfinite(o) for _, o, _, _ in r["pairs"])]
    if compared and len(compared) < len(shaped.rows):
        shaped.not_compared = [r for r in shaped.rows if not any(np.isfinite(o) for _, o, _, _ in r["pairs"])]
        shaped.rows = compared
    return shaped


#: Most decimals a compared quantity is shown with.
MAX_DECIMALS = 4


def pair_decimals(df: pd.DataFrame, pair: Pair) -> int:
    """Decimals of ours and Δ for one compared quantity, the same in every row.

    Where ours carries 95 % intervals, two significant digits of the median half-width (the
    uncertainty decides the digits); else one decimal more than the thesis prints (the largest
    count among its rows), so a difference within the thesis' precision still shows. At most
    :data:`MAX_DECIMALS`.

    Examples
    --------
    >>> df = pd.DataFrame({"thesis_k": [134.0, 120.0], "k": [124.31, 118.2],
    ...                    "k_ci_low": [96.0, 110.0], "k_ci_high": [152.6, 126.4]})
    >>> pair_decimals(df, Pair("k", "thesis_k", "k"))
    0
    >>> pair_decimals(pd.DataFrame({"thesis_f": [2.76, 3.5], "f": [2.7523, 3.488]}), Pair("f", "thesis_f", "f"))
    3
    """
    widths = [(_num(hi) - _num(lo)) / 2 for lo, hi in
              (_interval_columns(rec, pair.ours) for rec in df.to_dict(orient="records"))
              if np.isfinite(_num(lo)) and np.isfinite(_num(hi))] if len(df) else []
    widths = [w for w in widths if w > 0]
    if widths:
        return uncertainty_decimals(widths)
    printed = [_decimals(t) for t in map(_num, df[pair.thesis]) if np.isfinite(t)] if pair.thesis in df else []
    if printed:
        return min(MAX_DECIMALS, max(printed) + 1)
    ours = [abs(v) for v in map(_num, df[pair.ours]) if np.isfinite(v) and v != 0] if pair.ours in df else []
    return significant_decimals(ours)


def uncertainty_decimals(half_widths) -> int:
    """Decimals that show two significant digits of the median of ``half_widths`` (a quantity's 95 %
    interval half-widths, or any uncertainty of it; at most :data:`MAX_DECIMALS`): the uncertainty
    decides the digits, and the value is shown to the same decimal place.

    Examples
    --------
    >>> uncertainty_decimals([48.5]), uncertainty_decimals([0.187, 0.22]), uncertainty_decimals([1e-9])
    (0, 2, 4)
    """
    widths = [float(w) for w in half_widths if w is not None and np.isfinite(float(w)) and float(w) > 0]
    if not widths:
        raise ValueError("half_widths must hold a positive finite value")
    return int(min(MAX_DECIMALS, max(0, 1 - math.floor(math.log10(float(np.median(widths)))))))


def significant_decimals(values, digits: int = 3) -> int:
    """Decimals that show ``digits`` significant digits of the median magnitude of ``values`` (0 for
    whole numbers, at most :data:`MAX_DECIMALS`): one format for a whole column.

    Examples
    --------
    >>> significant_decimals([424.0, 10.364, 2241.483]), significant_decimals([0.0123, 0.02]), significant_decimals([3.0, 4.0])
    (0, 4, 0)
    """
    vals = [abs(float(v)) for v in values if v is not None and np.isfinite(float(v))]
    if not vals or all(float(v).is_integer() for v in vals):
        return 0
    nonzero = [v for v in vals if v > 0]
    if not nonzero:
        return 0
    return int(min(MAX_DECIMALS, max(0, digits - 1 - math.floor(math.log10(float(np.median(nonzero)))))))


def _interval_columns(rec: dict, column: str) -> tuple:
    """The (low, high) values of ``column``'s 95 % interval in ``rec`` (None, None without one)."""
    low, high = f"{column}_ci_low", f"{column}_ci_high"
    if low not in rec:
        parts = column.split("_")
        for i in range(len(parts) - 1, 0, -1):
            stem, unit = "_".join(parts[:i]), "_".join(parts[i:])
            if f"{stem}_ci95_low_{unit}" in rec:
                low, high = f"{stem}_ci95_low_{unit}", f"{stem}_ci95_high_{unit}"
                break
    return rec.get(low), rec.get(high)


def interval_text(rec: dict, column: str, decimals: int | None = None) -> str:
    """The 95 % interval of ``column`` as ``[low, high]``, or ``""`` if the row has none.

    ``decimals`` as the value's (:func:`pair_decimals`); default: three significant digits of the width.

    Read from ``<column>_ci_low``/``_ci_high`` (a fit's interval), or, for a column named
    ``<stem>_<unit>``, from ``<stem>_ci95_low_<unit>``/``<stem>_ci95_high_<unit>`` (a
    prediction's interval, e.g. Table XX's ``ours_frequency_1_ci95_low_Hz``).

    Examples
    --------
    >>> interval_text({"k_ci_low": 140.04, "k_ci_high": 151.2}, "k")
    '[140.0, 151.2]'
    >>> interval_text({"f_1_Hz": 2.75, "f_1_ci95_low_Hz": 2.551, "f_1_ci95_high_Hz": 2.962}, "f_1_Hz")
    '[2.551, 2.962]'
    >>> interval_text({"k": 1.0}, "k")
    ''
    >>> interval_text({"k_ci_low": 140.04, "k_ci_high": 151.2}, "k", decimals=0)
    '[140, 151]'
    """
    lo, hi = map(_num, _interval_columns(rec, column))
    if not (np.isfinite(lo) and np.isfinite(hi)):
        return ""
    digits = decimals if decimals is not None else max(0, 2 - int(np.floor(np.log10(max(abs(hi - lo), 1e-12)))))
    return f"[{lo:.{digits}f}, {hi:.{digits}f}]"


def _key_text(s: pd.Series) -> pd.Series:
    """Join keys compare as text; numbers lose trailing zeros (``10.0`` -> ``10``)."""
    num = pd.to_numeric(s, errors="coerce")
    text = s.astype(str).str.strip().str.lower()
    return text.where(num.isna(), num.map(lambda v: f"{v:g}"))


def compare_frames(ours: pd.DataFrame, thesis: pd.DataFrame, keys: list[str], values: dict[str, str],
                   thesis_rename: dict[str, str] | None = None) -> pd.DataFrame:
    """Outer-join our values with the thesis table as ``thesis_<x>``, ``<x>``, ``<x>_difference``.

    Parameters
    ----------
    ours : DataFrame
        Our table with ``keys`` and the ``values`` keys.
    thesis : DataFrame
        Digitised thesis table with ``keys`` (after ``thesis_rename``) and ``values`` values.
    keys : list of str
        Join columns; compared as text with numbers normalised.
    values : dict
        our column -> thesis column.
    thesis_rename : dict, optional
        Renames applied to the thesis table first (e.g. ``nominal_speed_km_h`` -> ``speed_km_h``).

    Returns
    -------
    DataFrame
        Keys (our spelling where the row has ours, else the thesis'), then per value
        the three comparison columns.
    """
    th = thesis.rename(columns=thesis_rename or {})
    keys = [k for k in keys if k in ours.columns and k in th.columns]
    values = {o: t for o, t in values.items() if o in ours.columns and t in th.columns}
    a = ours[keys + list(values)].drop_duplicates().copy()
    b = th[keys + list(values.values())].rename(columns={t: f"thesis_{o}" for o, t in values.items()}).copy()
    for frame in (a, b):
        for k in keys:
            frame[f"_k_{k}"] = _key_text(frame[k])
    jk = [f"_k_{k}" for k in keys]
    m = b.merge(a, on=jk, how="outer", suffixes=("_th", ""), sort=False)
    out = pd.DataFrame({k: m[k].where(m[k].notna(), m[f"{k}_th"]) if f"{k}_th" in m else m[k] for k in keys})
    for o in values:
        out[f"thesis_{o}"] = pd.to_numeric(m[f"thesis_{o}"], errors="coerce")
        out[o] = pd.to_numeric(m[o], errors="coerce")
        out[f"{o}_difference"] = out[o] - out[f"thesis_{o}"]
    return natural_order(out, keys)


def _sort_text(s: pd.Series) -> pd.Series:
    """Sort key of a column: numbers as numbers, text with its digit runs as numbers (T2 < T10)."""
    num = pd.to_numeric(s, errors="coerce")
    if num.notna().sum() == s.notna().sum():
        return num
    return s.map(lambda v: re.sub(r"\d+", lambda m: m.group().zfill(12), str(v).lower()) if pd.notna(v) else None)


def natural_order(df: pd.DataFrame, keys: list[str]) -> pd.DataFrame:
    """``df`` ordered by ``keys``, numbers as numbers (5 < 7.5 < 10, not "10" < "5") and text
    naturally (T2 < T10); missing keys last; a stable sort, the index renumbered.

    Examples
    --------
    >>> natural_order(pd.DataFrame({"speed": [10, 12.5, 5, 7.5]}), ["speed"])["speed"].tolist()
    [5.0, 7.5, 10.0, 12.5]
    """
    keys = [k for k in keys if k in df.columns]
    if not keys or df.empty:
        return df.reset_index(drop=True)
    order = pd.DataFrame({i: _sort_text(df[k]) for i, k in enumerate(keys)})
    index = order.sort_values(list(range(len(keys))), kind="mergesort", na_position="last").index
    return df.loc[index].reset_index(drop=True)


def thesis_only(thesis: pd.DataFrame, value_columns: tuple[str, ...] = ()) -> pd.DataFrame:
    """The thesis table as ``thesis_<x>`` columns with empty ``<x>`` (ours not produced yet).

    Numeric non-key columns, and ``value_columns`` even if they are usually keys
    (Table XI's load), become pairs; text and key columns stay as they are.
    """
    out = pd.DataFrame(index=thesis.index)
    for c in thesis.columns:
        if c in HIDDEN:
            continue
        if _is_numeric(thesis[c]) and (c not in NUMERIC_KEYS or c in value_columns):
            out[f"thesis_{c}"] = thesis[c]
            out[c] = np.nan
        else:
            out[c] = thesis[c]
    return out.reset_index(drop=True)


def plain_table(df: pd.DataFrame, columns: list[str] | None = None, max_rows: int = 40) -> dict:
    """A non-comparison table: chosen columns (default: all but :data:`HIDDEN`), at most ``max_rows`` rows.

    Returns
    -------
    dict
        ``columns``, ``rows`` (list of lists; a text longer than :data:`LONG_TEXT_CHARS` is a
        :class:`Note`), ``n_total``, ``truncated``, ``notes`` (the long texts, note 1 first) and
        ``decimals`` (per column: decimals of a non-integer numeric column, else None).
    """
    cols = [c for c in columns if c in df.columns] if columns else [c for c in df.columns if c not in HIDDEN]
    shown = df[cols].head(max_rows)
    rows = shown.to_dict(orient="split")["data"]
    notes: list[str] = []
    rows = [[_noted(v, notes) for v in row] for row in rows]
    decimals = {c: significant_decimals(pd.to_numeric(shown[c], errors="coerce").dropna()) for c in cols
                if _is_numeric(shown[c]) and not pd.api.types.is_integer_dtype(shown[c])}
    return {"columns": cols, "rows": rows, "n_total": len(df), "truncated": len(df) > max_rows, "notes": notes,
            "decimals": [decimals.get(c) for c in cols]}


#: Text longer than this (characters) leaves its table cell for a numbered note below the table.
LONG_TEXT_CHARS = 90


def _noted(value, notes: list[str]):
    """``value``, or a :class:`Note` (its text appended to ``notes`` once) when it is a long text."""
    if isinstance(value, str) and len(value) > LONG_TEXT_CHARS:
        if value not in notes:
            notes.append(value)
        return Note(notes.index(value) + 1)
    return value


@dataclass(frozen=True)
class Note:
    """A table cell whose long text is shown below the table as note ``number``."""

    number: int

    def __str__(self) -> str:
        return f"note {self.number}"


def campaign_summary(manifest: pd.DataFrame, results: pd.DataFrame, quarantine: pd.DataFrame,
                     calibration: pd.DataFrame | None = None) -> dict:
    """Counts for the index page: runs, tyres, QC failures, quarantined files, calibration days.

    Parameters
    ----------
    manifest, results, quarantine : DataFrame
        Warehouse tables (may be empty).
    calibration : DataFrame, optional
        ``calibration`` table (one row per day) if the calibrate stage ran.
    """
    kind = manifest["kind"].fillna("measurement") if "kind" in manifest else pd.Series("measurement", index=manifest.index)
    cal = manifest.loc[kind == "calibration"]
    days = cal["recorded_on"].nunique() if "recorded_on" in cal else 0
    if calibration is not None and not calibration.empty:
        day_col = next((c for c in ("recorded_on", "day", "date") if c in calibration), None)
        days = calibration[day_col].nunique() if day_col else len(calibration)
    qc = results["qc_ok"].fillna(False).astype(bool) if "qc_ok" in results else pd.Series(dtype=bool)
    return {
        "campaigns": int(manifest["campaign"].nunique()) if "campaign" in manifest else 0,
        "runs": int(len(manifest)),
        "measurement_runs": int((kind != "calibration").sum()),
        "tyres": int(manifest.loc[kind != "calibration", "tyre_id"].nunique()) if "tyre_id" in manifest else 0,
        "analysed": int(len(results)),
        "qc_failures": int((~qc).sum()),
        "quarantined": int(len(quarantine)),
        "calibration_days": int(days),
    }


def select_runs(results: pd.DataFrame, per_tyre: int = 2, max_runs: int = 80) -> pd.DataFrame:
    """Runs that get a drill-down page: the first ``per_tyre`` runs per tyre plus every QC-flagged run.

    Parameters
    ----------
    results : DataFrame
        ``results`` table (run_id, tyre_id, qc_ok, ...).
    per_tyre : int, optional
        Runs per tyre, in run_id order.
    max_runs : int, optional
        Cap on the total (flagged runs first) so the site stays small.

    Returns
    -------
    DataFrame
        Rows of ``results``, flagged first then by tyre and run_id.
    """
    if results.empty or "run_id" not in results:
        return results.head(0)
    r = results.sort_values(["tyre_id", "run_id"]) if "tyre_id" in results else results.sort_values("run_id")
    flagged = ~r["qc_ok"].fillna(False).astype(bool) if "qc_ok" in r else pd.Series(False, index=r.index)
    first = r.groupby("tyre_id", sort=False).head(per_tyre) if "tyre_id" in r else r.head(per_tyre)
    chosen = pd.concat([r.loc[flagged], first.loc[~flagged.loc[first.index]]])
    return chosen.drop_duplicates("run_id").head(max_runs).reset_index(drop=True)
