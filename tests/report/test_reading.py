"""The pages as a reader takes them (issue 26): what "off" means and why ours differs next to each
table, rows not compared behind a count, one format per quantity, abbreviations spelled out."""

from __future__ import annotations

import re

import numpy as np
import pandas as pd

from tyrelab.report import chapters, docs, render, tables


def _page(ctx, name: str) -> str:
    return (ctx.build / "reports" / name).read_text(encoding="utf-8").replace("<wbr>", "")


def test_every_comparison_table_says_what_off_means(small_report):
    for path in sorted((small_report.build / "reports").glob("ch*.html")):
        html = path.read_text(encoding="utf-8")
        for section in re.findall(r'<section id="table-[^"]+">(.*?)</section>', html, re.S):
            if 'class="comparison"' in section:
                assert "<strong>Off</strong> means ours differs from the printed value" in section, path.name
                assert "not that the difference is statistically significant" in section, path.name


def test_gaps_the_documents_explain_are_on_the_page(small_report):
    specs = [i for c in chapters.CHAPTERS for i in c.items if isinstance(i, chapters.TableSpec) and i.gaps]
    assert {s.number for s in specs} >= {"I", "XIII", "XIV", "XVII", "XX"}
    for chapter in chapters.CHAPTERS:
        html = _page(small_report, f"{chapter.slug}.html")
        for spec in (i for i in chapter.items if isinstance(i, chapters.TableSpec)):
            for gap in spec.gaps:  # one sentence and a link to the section that explains it
                link = docs.gap_link(gap)
                escaped = gap.text.replace("'", "&#39;").replace('"', "&#34;")
                assert (f'<strong>Why ours differs:</strong> {escaped} (<a href="{link["href"]}">'
                        f'{link["label"].replace(chr(34), "&#34;")}</a>)</p>') in html, (chapter.slug, spec.view)


def test_rows_the_campaign_did_not_measure_are_counted_not_listed():
    df = pd.DataFrame({"tyre_id": ["T1", "T2", "T3"], "thesis_k": [1.0, 2.0, 3.0], "k": [1.1, np.nan, np.nan]})
    shaped = tables.shape_comparison(df)
    assert [r["cells"]["tyre_id"] for r in shaped.rows] == ["T1"]
    assert [r["cells"]["tyre_id"] for r in shaped.not_compared] == ["T2", "T3"]
    nothing_yet = tables.shape_comparison(df.assign(k=np.nan))
    assert len(nothing_yet.rows) == 3 and not nothing_yet.not_compared  # thesis only: all shown


def test_one_number_format_per_quantity():
    df = pd.DataFrame({"tyre_id": ["a", "b", "c"], "thesis_k": [134.0, 120.0, 118.0], "k": [124.31, 118.2, 2241.48],
                       "k_ci_low": [96.0, 110.0, 2200.0], "k_ci_high": [152.6, 126.4, 2280.0]})
    shaped = tables.shape_comparison(df)
    assert shaped.pairs[0].decimals == 0
    assert [r["intervals"][0] for r in shaped.rows] == ["[96, 153]", "[110, 126]", "[2200, 2280]"]
    shown = [render.format_number(r["pairs"][0][1], decimals=shaped.pairs[0].decimals) for r in shaped.rows]
    assert shown == ["124", "118", "2241"]
    plain = tables.plain_table(pd.DataFrame({"hours": [424.0, 10.364, 2241.483]}))
    assert [render.format_number(v, decimals=plain["decimals"][0]) for (v,) in plain["rows"]] == ["424", "10", "2241"]


def test_names_as_the_cli_and_json_spell_them(small_report):
    assert render.column_label("a_wz_m_s2") == "a_wz (m/s²)"
    ride = _page(small_report, "ride.html")
    assert "a_wz (m/s²)" in ride and "a wz" not in ride


def test_abbreviations_spelled_out_once_per_page(small_report):
    ch7 = _page(small_report, "ch7-tractor.html")
    line = re.search(r'<p class="abbr">(.*?)</p>', ch7).group(1)
    assert "<strong>SBT</strong>: the artificial standard rough track" in line
    assert "<strong>HH</strong>: the Hussey Highway" in line
    assert ch7.count('<p class="abbr">') == 1
    ch4 = _page(small_report, "ch4-stiffness.html")
    assert "<strong>SBT</strong>" not in ch4  # only what the page uses
