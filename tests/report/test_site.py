"""The generated site: thesis tables present, markup escaped, offline, relative links."""

import re
from pathlib import Path

from small_campaign import EVIL_TYRE

THESIS_TABLES = ["III", "IV", "V", "VI", "VII", "VIII", "IX", "X", "XI", "XII", "XIII", "XIV", "XV", "XVI",
                 "XVII", "XVIII", "XIX", "XX"]


def _pages(ctx) -> dict[Path, str]:
    root = ctx.build / "reports"
    return {p: p.read_text(encoding="utf-8") for p in sorted(root.rglob("*.html"))}


def test_every_thesis_table_has_thesis_and_our_columns(small_report):
    html = "\n".join(_pages(small_report).values())
    for number in THESIS_TABLES:
        m = re.search(rf'<section id="table-{number.lower()}">(.*?)</section>', html, re.S)
        assert m, f"Table {number} missing"
        section = m.group(1)
        assert "<th>thesis</th><th>ours</th><th>Δ</th>" in section, f"Table {number} lacks thesis/ours columns"
        assert "<tbody>" in section and "<td" in section.split("<tbody>")[1], f"Table {number} has no rows"


def test_markup_in_a_tyre_id_renders_as_text(small_report):
    pages = _pages(small_report)
    for path, html in pages.items():
        assert EVIL_TYRE not in html, path
        assert "<script" not in html.lower(), path
    escaped = "&lt;script&gt;alert(1)&lt;/script&gt;"
    assert any(escaped in html for html in pages.values())
    assert escaped in pages[small_report.build / "reports" / "ch4-stiffness.html"]  # Table III row


def test_site_is_offline_with_working_relative_links(small_report):
    allowed = {"http://www.w3.org/2000/svg", "http://www.w3.org/1999/xlink"}
    for path, html in _pages(small_report).items():
        assert not re.search(r"<(script|link|img|iframe)\b", html, re.I), path
        assert set(re.findall(r"https?://[^\"' )<]+", html)) <= allowed, path
        for href in re.findall(r'href="([^"#]+)', html):
            assert not href.startswith(("/", "http:", "https:", "file:")), (path, href)
            assert (path.parent / href).exists(), (path, href)


def test_index_summary_provenance_and_size(small_report):
    pages = _pages(small_report)
    index = pages[small_report.build / "reports" / "index.html"]
    assert "QC failures" in index and "calibration days" in index
    assert "r_missing" in index and "file not found" in index  # quarantined file and reason
    for html in pages.values():
        assert "Provenance." in html and "tyrelab" in html and "Generated" in html
    size = sum(p.stat().st_size for p in (small_report.build / "reports").rglob("*") if p.is_file())
    assert size < 3_000_000
    assert any("runs/" in str(p) for p in pages)  # drill-down pages exist


def test_missing_tables_say_which_stage(small_report):
    """A warehouse without the simulate stage's tables: the chapter says which stage is missing."""
    from tyrelab.report import chapters, site

    wh = site.Warehouse(small_report.build / "warehouse.duckdb")
    wh.names -= {"table_xiii", "table_xiv", "carriage_runs", "carriage_comparisons"}
    ch6 = next(c for c in chapters.CHAPTERS if c.slug == "ch6-carriage")
    notes = [it["note"] for it in site.chapter_items(wh, ch6) if it["kind"] == "table"]
    assert any("not produced yet by stage simulate" in (n or "") for n in notes), notes
    html = _pages(small_report)[small_report.build / "reports" / "ch6-carriage.html"]
    assert "not produced yet" not in html  # the full build has them
