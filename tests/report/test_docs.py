"""The documents the report ships (docs/ rendered into the site) and the gaps that link to them."""

from __future__ import annotations

import pytest

from tyrelab.report import docs, pages
from tyrelab.report.chapters import Gap, TableSpec


def _gaps():
    return [(page.slug, spec, g) for page in pages.registered() for spec in page.tables() for g in spec.gaps]


def test_every_gap_is_one_sentence_and_a_section_that_exists():
    gaps = _gaps()
    assert len(gaps) >= 8 and {g.doc for _, _, g in gaps} == {"findings", "simulation"}
    for slug, spec, g in gaps:
        assert isinstance(g, Gap), (slug, spec.view, g)
        assert "docs/" not in g.text and g.text.endswith("."), (slug, spec.view, g.text)  # the link says where
        link = docs.gap_link(g)
        assert link["href"].startswith(f"docs/{g.doc}.html#") and link["label"].startswith(f"docs/{g.doc}.md, “")


def test_a_gap_to_a_section_that_does_not_exist_is_refused():
    with pytest.raises(ValueError, match="section must start exactly one heading of docs/findings.md"):
        docs.gap_link(Gap("Text.", "findings", "Chapter 9"))
    with pytest.raises(ValueError, match="name must be one of"):
        docs.document("README")


def test_the_site_carries_the_documents_and_each_gap_links_to_its_section(small_report):
    site = small_report.build / "reports"
    for name in docs.DOCS:
        html = (site / "docs" / f"{name}.html").read_text(encoding="utf-8")
        assert "<h2 id=" in html and 'href="../index.html"' in html  # headings with ids; the navigation
        assert html.count("<h1>") == 1  # the document's own title is the page's title
    chapter = (site / "ch3-measurement.html").read_text(encoding="utf-8")
    assert '<a href="docs/findings.html#chapter-3">docs/findings.md, “Chapter 3”</a>' in chapter
    assert 'id="chapter-3"' in (site / "docs" / "findings.html").read_text(encoding="utf-8")
    assert '<a href="docs/uncertainty.html">docs/uncertainty.md</a>' in (site / "ch4-stiffness.html").read_text(
        encoding="utf-8")
    index = (site / "index.html").read_text(encoding="utf-8")
    assert '<a href="docs/findings.html">Documents</a>' in index  # in the navigation bar


def test_gaps_are_data_of_the_table_spec():
    spec = TableSpec("", "t", "v", "s", gaps=(Gap("Why.", "simulation", "Table XX findings"),))
    assert docs.gap_link(spec.gaps[0])["href"] == "docs/simulation.html#table-xx-findings-not-tuned"
