"""The warehouse's legend: every column's unit and meaning, in one place (issue 44).

``schemas/warehouse_legend.json`` holds the meanings; this module reads it, with the raw and
published schemas (:mod:`tyrelab.resources`), and answers for any table and column:

* **unit** — from the column's name (:data:`UNIT_SUFFIXES`, the longest suffix that matches:
  ``stiffness_kN_per_m`` is kN/m), else the legend's own ``unit`` for the column, else ``–`` (none);
* **meaning** — the table's own entry in the legend, else the published table's schema (a
  digitised thesis table, or the table of ours that reproduces it), else the legend's meaning of the
  column's name (one column name means one thing in every table unless the table says otherwise),
  else the raw formats' schemas, else a rule of the warehouse's naming (:func:`meaning`:
  ``thesis_<x>``, ``<x>_difference``, ``<x>_ci95_low_<unit>``, ``<x>_u_<unit>``, ``<x>_se``,
  ``cov_<a>_<b>`` …), which builds it from the meaning of ``<x>``.

The docs' warehouse reference (``docs/site/_ext/tyrelab_reference.py``) and ``tyrelab sql
--describe TABLE`` read :func:`describe`; ``tests/test_legend.py`` fails when a declared table has a
column without a meaning (the legend's ``gaps`` list the columns still to be explained: it may only
shrink).

Examples
--------
>>> describe_column("results", "stiffness_ci95_low_N_per_m")[0]
'N/m'
>>> unit_, text = describe_column("results", "stiffness_kN_per_m")
>>> unit_, text.startswith("Vertical, lateral or longitudinal stiffness K")
('kN/m', True)
"""

from __future__ import annotations

import functools
import json
import re
from pathlib import Path

__all__ = ["UNIT_SUFFIXES", "LEGEND_FILE", "legend", "schema_descriptions", "unit", "meaning", "describe_column", "describe",
           "undocumented"]

#: Unit of a column from the end of its name (longest first wins); the warehouse's naming rule.
UNIT_SUFFIXES = {
    "_kN_s_per_m_per_mm": "kN s/m per mm", "_kN_per_m_per_mm": "kN/m per mm", "_kN_per_m_bar": "kN/m per bar",
    "_kN_s_per_m_bar": "kN s/m per bar", "_kN_s_per_m_per_rad": "kN s/m per rad",
    "_N_s_per_m_per_rad": "N s/m per rad", "_kN_s_per_m_times_km_h": "kN s/m × km/h", "_kN_per_rad": "kN/rad",
    "_N_per_rad": "N/rad", "_s_per_m": "s/m", "_kN_per_m": "kN/m", "_kN_s_per_m": "kN s/m", "_N_per_m": "N/m",
    "_N_s_per_m": "N s/m", "_km_h": "km/h", "_bar": "bar", "_kNm": "kN m", "_kN": "kN", "_kg": "kg", "_Hz": "Hz",
    "_mm_pp": "mm p-p", "_m2_s4_per_Hz": "(m/s²)²/Hz", "_m_s2": "m/s²", "_rad_s2": "rad/s²", "_m_s1_75": "m/s^1.75",
    "_m_per_s": "m/s", "_m_s": "m/s", "_percent": "%", "_pct": "%", "_in2": "in²", "_in": "in", "_N": "N",
    "_J": "J", "_deg": "°", "_rad": "rad", "_mm": "mm", "_m3": "m³", "_m2": "m²", "_m": "m", "_s": "s",
    "_years": "years", "_kg_m2": "kg m²", "_per_m": "1/m",
}
#: The legend file (in the package's schemas).
LEGEND_FILE = "warehouse_legend.json"

_CI = re.compile(r"^(?P<x>.+)_ci95_(?P<end>low|high)_(?P<u>.+)$")
_CI_PLAIN = re.compile(r"^(?P<x>.+)_ci(?:95)?_(?P<end>low|high)$")
_U = re.compile(r"^(?P<x>.+?)_u(?:_(?P<part>a|b|stat))?_(?P<u>(?:k?N|Hz|kg|m)\w*)$")
_COV = re.compile(r"^(?P<kind>ext_|jk_)?cov_(?P<a>intercept|age|pressure|speed|rim_diameter|wrp|width)_"
                  r"(?P<b>intercept|age|pressure|speed|rim_diameter|wrp|width)$")


@functools.lru_cache(maxsize=1)
def legend() -> dict:
    """The legend file as a dict: ``columns`` (name -> meaning or {meaning, unit}), ``tables``
    (table -> {description, columns}), ``gaps`` (table -> columns still without a meaning)."""
    from .resources import schemas_dir

    return json.loads((Path(schemas_dir()) / LEGEND_FILE).read_text(encoding="utf-8"))


@functools.lru_cache(maxsize=1)
def schema_descriptions() -> tuple[dict, dict, dict]:
    """The column descriptions of the published tables' and the raw formats' schemas.

    The one reader of those schemas for the legend (:func:`meaning`) and the docs' warehouse
    reference (``docs/site/_ext/tyrelab_reference.py``).

    Returns
    -------
    published : dict
        Published table (``table_iii`` …) -> column -> description.
    raw : dict
        Column -> description, from the raw formats' schemas (``raw_manifest``, ``tyres``,
        ``raw_rides``, ``raw_ride``, ``raw_run``; the first one describing a column wins).
    titles : dict
        Published table -> its schema's title.

    See Also
    --------
    meaning : uses them where the legend itself says nothing.

    Examples
    --------
    >>> published, raw, titles = schema_descriptions()
    >>> "carcass_stiffness_kN_per_m" in published["table_iii"], bool(raw["axle_mass_kg"])
    (True, True)
    """
    from .resources import schemas_dir

    published, raw, titles = {}, {}, {}
    for p in sorted((Path(schemas_dir()) / "published").glob("*.json")):
        doc = json.loads(p.read_text(encoding="utf-8"))
        published[p.stem] = {f["name"]: f.get("description", "") for f in doc.get("fields", [])}
        titles[p.stem] = doc.get("title", "")
    for name in ("raw_manifest", "tyres", "raw_rides", "raw_ride", "raw_run"):
        p = Path(schemas_dir()) / f"{name}.json"
        if p.exists():
            for f in json.loads(p.read_text(encoding="utf-8")).get("fields", []):
                raw.setdefault(f["name"], f.get("description", ""))
    return published, raw, titles


def _entry(table: str, column: str):
    lg = legend()
    own = lg.get("tables", {}).get(table, {}).get("columns", {})
    if column in own:
        return own[column]
    return lg.get("columns", {}).get(column)


def unit(table: str, column: str) -> str:
    """The column's unit (module docstring); ``–`` where it has none."""
    entry = _entry(table, column)
    if isinstance(entry, dict) and entry.get("unit"):
        return entry["unit"]
    for suffix in sorted(UNIT_SUFFIXES, key=len, reverse=True):
        if column.endswith(suffix) and len(column) > len(suffix):
            return UNIT_SUFFIXES[suffix]
    return "–"


def meaning(table: str, column: str) -> str:
    """What the column means (module docstring); ``""`` where nothing explains it."""
    entry = _entry(table, column)
    if entry:
        return entry["meaning"] if isinstance(entry, dict) else entry
    published, raw, _ = schema_descriptions()
    key = table.removeprefix("published_")
    for source in (published.get(key, {}), *published.values()):
        if column in source and source[column]:
            return source[column]
    if column in raw and raw[column]:
        return raw[column]
    return _rule(table, column)


def _rule(table: str, column: str) -> str:
    """A meaning from the warehouse's naming rules, built from the base column's own."""
    base = lambda name: meaning(table, name) if name != column else ""  # noqa: E731
    if column.startswith("thesis_") and base(column[7:]):
        return "The thesis' printed value: " + base(column[7:])
    if column.endswith("_difference"):
        b = column[: -len("_difference")]
        return f"Ours − thesis of {b}" + (f" ({base(b)})" if base(b) else "") + "."
    m = _CI.match(column)
    if m and base(f"{m['x']}_{m['u']}"):
        return f"{'Lower' if m['end'] == 'low' else 'Upper'} end of the 95 % interval of {m['x']}_{m['u']}."
    m = _CI_PLAIN.match(column)
    if m and base(m["x"]):
        return f"{'Lower' if m['end'] == 'low' else 'Upper'} end of the 95 % confidence interval of {m['x']}."
    m = _U.match(column)
    if m and base(f"{m['x']}_{m['u']}"):
        part = {"a": "type A (the method's own scatter) ", "b": "type B (the §3.2.9 instrument limits) ",
                "stat": "statistical (type A) "}.get(m["part"], "")
        return f"Standard uncertainty, {part}of {m['x']}_{m['u']}.".replace(", of", " of")
    if column.endswith("_se") and base(column[:-3]):
        return f"Standard error of {column[:-3]}."
    if column.endswith("_vs_printed_se") and base(column[: -len("_vs_printed_se")]):
        return f"(Ours − printed) {column[: -len('_vs_printed_se')]} in standard errors of ours."
    m = _COV.match(column)
    if m:
        kind = {"ext_": "extended (with the tyre-to-tyre variance) ", "jk_": "jackknife "}.get(m["kind"] or "", "")
        return f"Covariance, {kind}of the fitted coefficients {m['a']} and {m['b']}.".replace(", of", " of")
    for scale, unit_ in (("_kN_per_m", "_N_per_m"), ("_kN_s_per_m", "_N_s_per_m")):
        if column.endswith(scale) and base(column[: -len(scale)] + unit_):
            return f"{column[: -len(scale)] + unit_} in k{unit_[1:].replace('_', ' ')}."
    return ""


def describe_column(table: str, column: str) -> tuple[str, str]:
    """``(unit, meaning)`` of one column."""
    return unit(table, column), meaning(table, column)


def describe(table: str, columns: list[str]) -> list[tuple[str, str, str]]:
    """``(column, unit, meaning)`` for each of a table's ``columns``."""
    return [(c, *describe_column(table, c)) for c in columns]


def undocumented(tables: dict[str, list[str]]) -> dict[str, list[str]]:
    """Of ``tables`` (table -> its columns), the columns without a meaning and not among the known
    gaps (``gaps`` of the legend file)."""
    gaps = legend().get("gaps", {})
    out = {}
    for t, cols in tables.items():
        missing = [c for c in cols if not meaning(t, c) and c not in gaps.get(t, [])]
        if missing:
            out[t] = missing
    return out
