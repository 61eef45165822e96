"""Table schemas for raw and published data.

Schemas live in ``schemas/*.json`` (and ``schemas/published/*.json``) in the
Frictionless *Table Schema* format: a ``fields`` list whose entries have a
``name``, a ``type`` (``string``, ``number``, ``integer``, ``boolean``,
``date``), an optional ``unit`` and ``description`` and optional
``constraints`` (``required``, ``minimum``, ``maximum``, ``enum``,
``unique``). A top-level ``"additionalFields": false`` forbids columns that
are not listed (the default allows them).

:func:`validate_frame` returns a list of one-line problems; an empty list
means the frame conforms.
"""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

import numpy as np
import pandas as pd

from . import resources

__all__ = ["SCHEMA_DIR", "load_schema", "field_names", "row_problems", "validate_frame"]

#: Repository folder holding the schemas (``schemas/`` beside ``pipeline/``).
SCHEMA_DIR = resources.schemas_dir()


@lru_cache(maxsize=None)
def load_schema(name: str) -> dict:
    """Load ``schemas/<name>.json`` (``name`` may contain a sub-folder)."""
    path = SCHEMA_DIR / f"{name}.json"
    with open(path, encoding="utf-8") as fh:
        return json.load(fh)


def field_names(schema: dict, required_only: bool = False) -> list[str]:
    """Names of the schema's fields, optionally only the required ones."""
    return [
        f["name"]
        for f in schema["fields"]
        if not required_only or f.get("constraints", {}).get("required", False)
    ]


def _coerce(series: pd.Series, ftype: str) -> tuple[pd.Series, pd.Series]:
    """Return (coerced values, mask of non-null values that failed to coerce)."""
    if ftype in ("number", "integer", "string") and _is_numeric(series):
        # Already numbers (as ``read_csv`` parses a numeric column): a number is never
        # blank text and always coerces, so the text round trip below is skipped.
        if ftype == "string":  # NaN stays missing: ``where(notna)`` would return the same
            return series, pd.Series(False, index=series.index)
        bad = pd.Series(False, index=series.index)
        if ftype == "integer":
            v = series.to_numpy(dtype=float)
            with np.errstate(invalid="ignore"):
                bad = pd.Series(~np.isnan(v) & (v != np.floor(v)), index=series.index)
        return series, bad
    present = _present(series)
    if ftype in ("number", "integer"):
        values = pd.to_numeric(series, errors="coerce")
        bad = present & values.isna()
        if ftype == "integer":
            frac = values.notna() & (values != np.floor(values))
            bad = bad | frac
        return values, bad
    if ftype == "boolean":
        mapping = {"true": True, "false": False, "1": True, "0": False}
        values = series.astype("string").str.strip().str.lower().map(mapping)
        return values, present & values.isna()
    if ftype == "date":
        values = pd.to_datetime(series, errors="coerce", format="%Y-%m-%d")
        return values, present & values.isna()
    return series.where(present), pd.Series(False, index=series.index)


def _present(series: pd.Series) -> pd.Series:
    """Mask of values that are neither missing nor blank text."""
    if not (series.dtype == object or isinstance(series.dtype, pd.StringDtype)):
        return series.notna() & (series.astype("string").str.strip() != "")
    values = series.to_numpy(dtype=object)
    blank = np.fromiter((isinstance(v, str) and not v.strip() for v in values), dtype=bool, count=len(values))
    return pd.Series(~pd.isna(values) & ~blank, index=series.index)


def _is_numeric(series: pd.Series) -> bool:
    """Float or integer numpy dtype (not boolean, not an extension or object dtype)."""
    return isinstance(series.dtype, np.dtype) and series.dtype.kind in "fiu"


def row_problems(df: pd.DataFrame, schema: dict) -> tuple[list[str], dict[int, list[str]]]:
    """Check ``df`` against a Table Schema, row by row.

    Returns
    -------
    frame_problems : list of str
        Problems of the frame as a whole (missing required or unexpected columns).
    by_row : dict
        Row position (0-based) -> one-line problems of that row.
    """
    frame: list[str] = []
    by_row: dict[int, list[str]] = {}

    def flag(mask: np.ndarray, text) -> None:
        for i in np.flatnonzero(mask):
            by_row.setdefault(int(i), []).append(text(int(i)))

    names = field_names(schema)
    for f in schema["fields"]:
        name, ftype = f["name"], f.get("type", "string")
        cons = f.get("constraints", {})
        if name not in df.columns:
            if cons.get("required", False):
                frame.append(f"missing column '{name}'")
            continue
        raw = df[name]
        values, bad_s = _coerce(raw, ftype)
        # masks as numpy arrays: a handful of pandas operations per column cost more
        # than the checks themselves on the tables' tens to thousands of rows
        bad = bad_s.to_numpy(dtype=bool)
        missing = values.isna().to_numpy(dtype=bool)
        flag(bad, lambda i: f"column '{name}': value {raw.iloc[i]!r} is not of type {ftype}")
        ok = ~missing & ~bad
        if cons.get("required", False):
            flag(missing & ~bad, lambda i: f"column '{name}': required value missing")
        if ftype in ("number", "integer"):
            num = values.to_numpy(dtype=float, na_value=np.nan)
            with np.errstate(invalid="ignore"):
                flag(ok & np.isinf(num), lambda i: f"column '{name}': infinite value")
                if "minimum" in cons:
                    flag(ok & (num < cons["minimum"]), lambda i: f"column '{name}': value {num[i]:g} below minimum {cons['minimum']}")
                if "maximum" in cons:
                    flag(ok & (num > cons["maximum"]), lambda i: f"column '{name}': value {num[i]:g} above maximum {cons['maximum']}")
        if "enum" in cons:
            allowed = set(cons["enum"])
            flag(ok & ~values.isin(allowed).to_numpy(dtype=bool), lambda i: f"column '{name}': value {values.iloc[i]!r} not one of {sorted(allowed)}")
        if cons.get("unique", False):
            flag(ok & values.duplicated(keep="first").to_numpy(dtype=bool), lambda i: f"column '{name}': duplicate value {values.iloc[i]!r}")
    if schema.get("additionalFields", True) is False:
        extra = [c for c in df.columns if c not in names]
        if extra:
            frame.append(f"unexpected column(s) {extra}")
    return frame, by_row


def validate_frame(df: pd.DataFrame, schema: dict) -> list[str]:
    """Check ``df`` against a Table Schema; return a list of problems.

    Each problem is one line naming the column and, for a row problem, the
    first offending row (0-based). An empty list means the frame conforms.
    """
    frame, by_row = row_problems(df, schema)
    problems = list(frame)
    seen: set[str] = set()
    for i in sorted(by_row):
        for text in by_row[i]:
            column = text.split(":", 1)[0]
            if column not in seen:
                seen.add(column)
                problems.append(f"{text} (row {i})")
    return problems
