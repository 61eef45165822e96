"""The report's page registry: pages are objects, a new page is one registration."""

from __future__ import annotations

import pytest

from tyrelab.report import pages, site
from tyrelab.report.chapters import Chapter, FigureSpec, TableSpec


def test_registry_lists_index_chapters_ride_runs_and_docs_in_order():
    slugs = [p.slug for p in pages.registered()]
    assert slugs[0] == "index" and slugs[-2:] == ["runs", "docs"]
    # issue 24's page after the chapters, issue 43's vehicle FRFs, then issue 34's rig methods (registered by
    # tyrelab.report.methods_page)
    assert slugs[1:-2] == [c.slug for c in pages.CHAPTERS] + ["measured-ride", "vehicle-frf", "rig-methods"]
    with pytest.raises(ValueError, match="'runs' is already registered"):
        pages.register(pages.RunsPage())


def test_a_page_without_render_cannot_be_made():
    """``Page.render`` is abstract: a page class that forgets it fails when made, not when the
    report is half written."""
    class Forgetful(pages.Page):
        slug, title, order = "forgetful", "Forgetful", 50

    with pytest.raises(TypeError, match="render"):
        Forgetful()


@pytest.mark.slow  # 51 s on 2 busy cores; runs in `make test-all`, not in the default run
def test_a_new_page_is_one_registration(small_report, tmp_path):
    """A page registered beside the built-in ones gets its file, a navigation link and an index
    entry, and its table and figure come from the warehouse like a chapter's."""
    extra = pages.ChapterPage(Chapter(
        "measured-example", "Measured example — one table and one figure", "Intro of the example page.",
        (TableSpec("", "Ride results again", "ride_results", "simulate", columns=("scenario", "speed_km_h")),
         FigureSpec("", "Seat a_w against speed", "ride_aw_speed", ("ride_results",), "simulate",
                    module="ride_figures"))), order=95)
    registry = list(pages.registered())
    pages.register(extra, registry)
    info = site.build_site(small_report.build / "warehouse.duckdb", tmp_path, small_report.raw,
                           pages=pages.registered(registry))
    html = (tmp_path / "measured-example.html").read_text(encoding="utf-8")
    assert "Intro of the example page." in html and "<svg" in html and "ride_results" in html
    assert 'href="measured-example.html" class="here">Measured example</a>' in html
    index = (tmp_path / "index.html").read_text(encoding="utf-8")
    assert '<a href="measured-example.html">Measured example — one table and one figure</a>' in index
    assert index.index("ride.html") < index.index("measured-example.html") < index.index('href="runs.html">Run')
    assert tmp_path / "measured-example.html" in info["pages"] and info["missing"] == []


def test_missing_data_is_a_typed_signal_not_a_phrase(small_report, tmp_path):
    """A table and a figure whose data are not in the warehouse carry ``Missing``; the stage's
    "not produced yet" list is built from it (whatever the note says)."""
    wh = site.Warehouse(small_report.build / "warehouse.duckdb")
    wh.names -= {"ride_results"}
    table = site.resolve_table(wh, TableSpec("", "Gone", "ride_results", "simulate", note="Explained elsewhere."))
    assert table["missing"] == site.Missing("simulate", "Table ride_results") and table["mode"] == "missing"
    figure = site.resolve_figure(wh, FigureSpec("", "Gone", "ride_aw_speed", ("ride_results",), "simulate",
                                                module="ride_figures"))
    assert figure["missing"].stage == "simulate" and figure["svg"] is None
    present = site.resolve_table(wh, TableSpec("", "There", "results", "analyse"))
    assert present["missing"] is None

    class Hidden(site.Warehouse):  # the site's own warehouse, without the ride tables
        @property
        def names(self):
            return super().names - {"ride_results"}

    ride = next(p for p in pages.registered() if p.slug == "ride")
    real = site.Warehouse
    site.Warehouse = Hidden
    try:
        info = site.build_site(small_report.build / "warehouse.duckdb", tmp_path, small_report.raw,
                               pages=[pages.IndexPage(), ride])
    finally:
        site.Warehouse = real
    assert info["missing"] and all(m.startswith("ride: ") and "stage simulate" in m for m in info["missing"])
    html = (tmp_path / "ride.html").read_text(encoding="utf-8")
    assert '<p class="missing">Table ride_results not produced yet by stage simulate.</p>' in html


def test_the_thesis_note_only_on_pages_with_thesis_tables(small_report):
    root = small_report.build / "reports"
    note = "Each thesis table shows the thesis value"
    assert note not in (root / "ride.html").read_text(encoding="utf-8")
    assert note in (root / "ch4-stiffness.html").read_text(encoding="utf-8")
