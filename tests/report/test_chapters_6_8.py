"""Chapters 6-8 of the report built through every stage hold our simulated values.

The report comes from ``full_report`` (tests/conftest.py): the tiny campaign run through
ingest ... simulate ... report. Each comparison table of chapters 6-8 must show, per row
and per compared quantity, the value the simulate stage wrote (read back from its Parquet
output, not through the report code) in the "ours" cell and ours − thesis in the Δ cell.
"""

from __future__ import annotations

import html as htmllib
import re

import numpy as np
import pandas as pd
import pytest

from tyrelab.report.render import format_number
from tyrelab.report.tables import find_pairs

pytestmark = pytest.mark.long  # collected first: see tests/conftest.py

#: (page, table number, stage output, rows that must have our value for every pair)
TABLES = [
    ("ch6-carriage.html", "xiii", "table_xiii", 16),
    ("ch6-carriage.html", "xiv", "table_xiv", 16),
    ("ch7-tractor.html", "xvii", "table_xvii", 32),
    ("ch7-tractor.html", "xviii", "table_xviii", 5),
    ("ch8-frequencies.html", "xx", "table_xx", 10),
]


def _rendered_rows(page: str, number: str) -> list[list[tuple[str, str, str]]]:
    """Per body row of the table in ``<section id="table-<number>">``: (thesis, ours, Δ) texts."""
    m = re.search(rf'<section id="table-{number}">(.*?)</section>', page, re.S)
    assert m, f"Table {number.upper()} is not on the page"
    # the rows with ours, then those of the thesis alone (tbody.not-compared, behind a count)
    body = "".join(b.split("</tbody>", 1)[0] for b in re.split(r'<tbody(?: class="not-compared")?>', m.group(1))[1:])
    rows = []
    for tr in re.findall(r"<tr>(.*?)</tr>", body, re.S):
        cells = re.findall(r'<td class="([^"]*)">(.*?)</td>', tr, re.S)
        triples = [(htmllib.unescape(cells[i][1]), htmllib.unescape(_CI.sub("", cells[i + 1][1])),
                    htmllib.unescape(cells[i + 2][1]), _interval(cells[i + 1][1]))
                   for i, (cls, _) in enumerate(cells) if "thesis" in cls.split()]
        rows.append(triples)
    return rows


_CI = re.compile(r'<br><small class="ci"[^>]*>(.*?)</small>', re.S)


def _interval(cell: str) -> tuple[float, float] | None:
    """The ``[low, high]`` shown below a value, as numbers, or None."""
    m = _CI.search(cell)
    if not m:
        return None
    low, high = (float(x) for x in m.group(1).strip("[] ").split(","))
    return low, high


def _fmt(v) -> str:
    return format_number(float(v)) if pd.notna(v) else format_number(None)


def _shows(text: str, value) -> bool:
    """Whether ``text`` is ``value`` rounded to the decimals it shows (or "–" for a missing value)."""
    if not (pd.notna(value) and np.isfinite(float(value))):
        return text == "–"
    decimals = len(text.split(".")[1]) if "." in text else 0
    return abs(float(text) - float(value)) <= 0.5 * 10.0 ** -decimals + 1e-12


def _decimals_shown(text: str) -> int | None:
    return None if text == "–" else len(text.split(".")[1]) if "." in text else 0


@pytest.mark.parametrize("page,number,table,min_filled", TABLES, ids=[t[1] for t in TABLES])
def test_chapter_tables_show_our_simulated_values_and_ours_minus_thesis(full_report, page, number, table, min_filled):
    ours_table = pd.read_parquet(full_report.build / "parquet" / f"{table}.parquet")
    pairs = find_pairs(ours_table.columns)
    assert pairs, table
    rendered = _rendered_rows((full_report.build / "reports" / page).read_text(encoding="utf-8"), number)
    assert len(rendered) == len(ours_table), f"{table}: {len(rendered)} rows shown, {len(ours_table)} written"
    filled = 0
    formats: dict[str, set] = {}
    for (_, rec), shown in zip(ours_table.iterrows(), rendered):
        assert len(shown) == len(pairs)
        row_filled = True
        for p, (thesis_txt, ours_txt, diff_txt, _) in zip(pairs, shown):
            ours, thesis = pd.to_numeric(rec[p.ours], errors="coerce"), pd.to_numeric(rec[p.thesis], errors="coerce")
            assert _shows(ours_txt, ours), f"{table}.{p.ours}: shows {ours_txt}, stage wrote {ours}"
            assert thesis_txt == _fmt(thesis), f"{table}.{p.thesis}: shows {thesis_txt}, thesis {thesis}"
            if np.isfinite(ours) and np.isfinite(thesis):
                assert _shows(diff_txt, ours - thesis), f"{table}.{p.label}: Δ {diff_txt} is not ours - thesis"
            formats.setdefault(p.label, set()).update({_decimals_shown(ours_txt), _decimals_shown(diff_txt)} - {None})
            row_filled &= bool(np.isfinite(ours))
        filled += row_filled
    # one number format per quantity: ours and Δ with the same decimals in every row
    assert {label: d for label, d in formats.items() if len(d) > 1} == {}, table
    assert filled >= min_filled, f"{table}: only {filled} rows with our values"


def test_chapter_6_to_8_values_are_the_simulations_not_the_thesis(full_report):
    """Our simulated accuracy statistics are plausible and not copies of the thesis' numbers."""
    xiii = pd.read_parquet(full_report.build / "parquet" / "table_xiii.parquet").set_index(["quantity", "statistic"])
    r = xiii.loc[("peak_frequency", "mean_ratio_error")]
    assert r["ours_rolling"] == pytest.approx(1.0, abs=0.05)  # rolling characteristics predict the peak (§6.5)
    both = xiii[["thesis_rolling", "ours_rolling"]].dropna()
    assert (both["thesis_rolling"] != both["ours_rolling"]).any()
    xx = pd.read_parquet(full_report.build / "parquet" / "table_xx.parquet")
    ours = [c for c in xx.columns if c.startswith("ours_")]
    assert ours and xx[ours].notna().any().all()


def test_table_xx_shows_the_formula_rows_95_percent_intervals(full_report):
    """Issue 14: every formula row of Table XX shows the interval the simulate stage wrote."""
    xx = pd.read_parquet(full_report.build / "parquet" / "table_xx.parquet")
    rendered = _rendered_rows((full_report.build / "reports" / "ch8-frequencies.html").read_text(encoding="utf-8"), "xx")
    pairs = find_pairs(xx.columns)
    shown_any = 0
    for (_, rec), shown in zip(xx.iterrows(), rendered):
        for p, (_, _, _, interval) in zip(pairs, shown):
            stem, unit = p.ours.rsplit("_", 1)
            low, high = rec.get(f"{stem}_ci95_low_{unit}"), rec.get(f"{stem}_ci95_high_{unit}")
            if low is None or not np.isfinite(low):
                assert interval is None, f"{p.ours}: an interval shown where the stage wrote none"
                continue
            assert interval is not None, f"{p.ours}: the stage's interval [{low}, {high}] is not shown"
            assert interval[0] == pytest.approx(low, abs=6e-3) and interval[1] == pytest.approx(high, abs=6e-3)
            assert interval[0] - 6e-3 <= rec[p.ours] <= interval[1] + 6e-3  # as shown, rounded
            shown_any += 1
    assert shown_any >= 2
