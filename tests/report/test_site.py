"""The generated site: thesis tables present, markup escaped, offline, relative links."""

import re
from pathlib import Path

import pytest

from tests.report.small_campaign import EVIL_TYRE

THESIS_TABLES = ["III", "IV", "V", "VI", "VII", "VIII", "IX", "X", "XI", "XII", "XIII", "XIV", "XV", "XVI",
                 "XVII", "XVIII", "XIX", "XX"]


def _pages(ctx) -> dict[Path, str]:
    root = ctx.build / "reports"
    # <wbr>: where a long cell text may wrap (after "_", "/", ","); not part of the text
    return {p: p.read_text(encoding="utf-8").replace("<wbr>", "") for p in sorted(root.rglob("*.html"))}


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
        for href, anchor in re.findall(r'href="([^"#]*)#([^"]+)"', html):  # a section: its id is there
            target = (path.parent / href) if href else path
            assert f'id="{anchor}"' in target.read_text(encoding="utf-8"), (path, href, anchor)


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


def test_a_figure_whose_stage_ran_but_drew_nothing_is_not_not_produced_yet(small_report, monkeypatch):
    """Issue 47: a user's campaign without Fig. 21's runs read "not produced yet by stage analyse"
    although analyse ran. Its table exists: the note says the stage ran, and the build does not list it."""
    import pandas as pd

    from tyrelab.report import chapters, site

    wh = site.Warehouse(small_report.build / "warehouse.duckdb")
    spec = next(f for c in chapters.CHAPTERS for f in c.items
                if isinstance(f, chapters.FigureSpec) and f.inputs and f.inputs[0] == "results")
    real = wh.table
    monkeypatch.setattr(wh, "table", lambda name: real(name).iloc[0:0] if name == "results" else real(name))
    item = site.resolve_figure(wh, spec)
    assert item["svg"] is None and "not produced yet" not in item["note"]
    assert f"stage {spec.stage} ran" in item["note"] and item["missing"].empty
    wh.names -= {"results"}  # the stage has not run: that is "not produced yet"
    assert "not produced yet by stage" in site.resolve_figure(wh, spec)["note"]


def _server_ready():
    import time

    from tyrelab.executor import start_worker_server, worker_server_state

    start_worker_server()
    deadline = time.monotonic() + 300
    while worker_server_state() != "ready" and time.monotonic() < deadline:
        time.sleep(0.05)
    return worker_server_state() == "ready"


@pytest.mark.slow  # 81 s on 2 busy cores; runs in `make test-all`, not in the default run
def test_figures_drawn_in_the_background_give_the_same_pages(small_report, tmp_path, monkeypatch):
    """Every figure drawn by workers forked from the worker server (while the tables are shaped)
    gives the bytes of the same site drawn in this process.

    Both sites are built here with the footer's "generated" time fixed (``SOURCE_DATE_EPOCH``):
    the shared report was built minutes earlier, and its footer names that minute.
    """
    from tyrelab.report import site

    assert _server_ready()
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "631152000")
    db = small_report.build / "warehouse.duckdb"
    handed = []
    real = site.map_in_background
    monkeypatch.setattr(site, "map_in_background", lambda *a: handed.append(real(*a)) or handed[-1])
    info = site.build_site(db, tmp_path / "workers", small_report.raw, jobs=2)
    assert info["drawn"] == info["figures"] > 0 and handed and handed[0] is not None  # drawn by workers
    handed.clear()
    assert site.build_site(db, tmp_path / "here", small_report.raw, jobs=1)["drawn"] == info["figures"]
    assert handed == [None]  # jobs=1: no background workers, drawn in this process
    ours, theirs = ({p.relative_to(tmp_path / name): p.read_text(encoding="utf-8")
                     for p in sorted((tmp_path / name).rglob("*.html"))} for name in ("workers", "here"))
    assert ours.keys() == theirs.keys() and len(ours) > 5
    assert [p for p in ours if ours[p] != theirs[p]] == []


def test_an_error_while_figures_are_drawn_ends_their_workers(small_report, tmp_path, monkeypatch):
    """An error (or Ctrl-C) in this process while workers draw: the workers are ended, not left running."""
    import pytest

    from tyrelab import executor
    from tyrelab.report import site

    assert _server_ready()
    ended = []
    real = executor.abandon_pool

    def abandon(pool):
        procs = list(pool._processes.values())
        real(pool)
        ended.append([p.is_alive() for p in procs])

    monkeypatch.setattr(executor, "abandon_pool", abandon)

    def broken(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(site, "resolve_table", broken)
    with pytest.raises(KeyboardInterrupt):
        site.build_site(small_report.build / "warehouse.duckdb", tmp_path / "reports", small_report.raw, jobs=2)
    assert ended and ended[0] and not any(ended[0])  # the pool's workers existed and are gone


def test_every_query_of_ours_has_a_row_order(small_report):
    """A chapter table's own query (``TableSpec.ours_sql``) orders its rows: its result keys the
    report's cache of shaped tables, and DuckDB returns DISTINCT/GROUP BY rows in any order (the
    random-kill test found a second cache entry for the same table)."""
    from tyrelab.report import chapters, site

    specs = [i for c in chapters.CHAPTERS for i in c.items if isinstance(i, chapters.TableSpec) and i.ours_sql]
    assert len(specs) >= 4
    wh = site.Warehouse(small_report.build / "warehouse.duckdb")
    for spec in specs:
        assert " ORDER BY " in spec.ours_sql, spec.ours_sql
        assert len(wh.sql(spec.ours_sql)), spec.ours_sql  # and it runs on the warehouse
