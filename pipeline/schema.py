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

#: Repository folder holding the schemas (``schemas/`` beside ``pipeline/``).
SCHEMA_DIR = Path(__file__).resolve().parent.parent / "schemas"


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
    present = series.notna() & (series.astype("string").str.strip() != "")
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


def validate_frame(df: pd.DataFrame, schema: dict) -> list[str]:
    """Check ``df`` against a Table Schema; return a list of problems.

    Each problem is one line naming the column and, where it applies, the
    first offending row (0-based) and value.
    """
    problems: list[str] = []
    names = field_names(schema)
    for f in schema["fields"]:
        name = f["name"]
        cons = f.get("constraints", {})
        if name not in df.columns:
            if cons.get("required", False):
                problems.append(f"missing column '{name}'")
            continue
        values, bad = _coerce(df[name], f.get("type", "string"))
        if bad.any():
            i = int(np.flatnonzero(bad.to_numpy())[0])
            problems.append(
                f"column '{name}': value {df[name].iloc[i]!r} in row {i} is not of type {f.get('type')}"
            )
            continue
        missing = values.isna()
        if cons.get("required", False) and missing.any():
            i = int(np.flatnonzero(missing.to_numpy())[0])
            problems.append(f"column '{name}': required value missing in row {i}")
        if f.get("type") in ("number", "integer"):
            if np.isinf(values.to_numpy(dtype=float, na_value=np.nan)).any():
                problems.append(f"column '{name}': infinite value")
            for key, op, word in (("minimum", np.less, "below minimum"), ("maximum", np.greater, "above maximum")):
                if key in cons:
                    viol = values.notna() & op(values, cons[key])
                    if viol.any():
                        i = int(np.flatnonzero(viol.to_numpy())[0])
                        problems.append(
                            f"column '{name}': value {values.iloc[i]} in row {i} {word} {cons[key]}"
                        )
        if "enum" in cons:
            allowed = set(cons["enum"])
            viol = values.notna() & ~values.isin(allowed)
            if viol.any():
                i = int(np.flatnonzero(viol.to_numpy())[0])
                problems.append(
                    f"column '{name}': value {values.iloc[i]!r} in row {i} not one of {sorted(allowed)}"
                )
        if cons.get("unique", False):
            dup = values.notna() & values.duplicated(keep="first")
            if dup.any():
                i = int(np.flatnonzero(dup.to_numpy())[0])
                problems.append(f"column '{name}': duplicate value {values.iloc[i]!r} in row {i}")
    if schema.get("additionalFields", True) is False:
        extra = [c for c in df.columns if c not in names]
        if extra:
            problems.append(f"unexpected column(s) {extra}")
    return problems
