"""The documents of ``docs/`` the report links to, rendered into the site beside the chapters.

A chapter page explains each gap between ours and the thesis in one sentence and links to the
section of ``docs/findings.md`` or ``docs/simulation.md`` that explains it (:class:`Gap`). The
site is read offline and mailed as a zip, so the link cannot point at a repository: the
documents of :data:`DOCS` are shipped with tyrelab (package ``tyrelab.docs``,
:func:`tyrelab.resources.docs_dir`) and rendered by Python-Markdown into ``docs/<name>.html`` of
the site (:class:`tyrelab.report.pages.DocsPage`), each heading with the id Markdown's ``toc``
extension gives it. A gap naming a document or section that does not exist is refused when the
site is built (:func:`gap_link`), never a dead link.

Examples
--------
>>> gap = Gap("Ours is 41 % above the printed value.", "findings", "Chapter 3")
>>> gap_link(gap)["href"]
'docs/findings.html#chapter-3'
>>> gap_link(gap)["label"]
'docs/findings.md, “Chapter 3”'
"""

from __future__ import annotations

import html as html_lib
import re
from dataclasses import dataclass
from functools import cache

from markupsafe import Markup

from .. import resources

__all__ = ["DOCS", "Gap", "Document", "document", "section_id", "gap_link"]

#: The documents of ``docs/`` the site carries (``docs/<name>.html``): the ones its pages link to.
DOCS = ("findings", "simulation", "uncertainty", "rig_methods")


@dataclass(frozen=True)
class Gap:
    """Why ours differs from the thesis: one sentence, and the document section that explains it.

    Attributes
    ----------
    text : str
        The sentence shown under the table.
    doc : str
        A document of :data:`DOCS` (``"findings"`` is ``docs/findings.md``).
    section : str
        The start of the heading of the section that explains it (``"Chapter 3"``).
    """

    text: str
    doc: str
    section: str


@dataclass(frozen=True)
class Document:
    """A rendered document: its title (first heading), body HTML without that heading, and the
    id of every heading by its text."""

    name: str
    title: str
    html: Markup
    sections: dict[str, str]


def _headings(tokens: list[dict]) -> dict[str, str]:
    out: dict[str, str] = {}
    for t in tokens:
        out[html_lib.unescape(t["name"])] = t["id"]
        out.update(_headings(t["children"]))
    return out


@cache
def document(name: str) -> Document:
    """``docs/<name>.md`` rendered (tables, fenced code, heading ids).

    Raises
    ------
    ValueError
        If ``name`` is not one of :data:`DOCS`.
    """
    import markdown

    if name not in DOCS:
        raise ValueError(f"name must be one of {DOCS}, got {name!r}")
    md = markdown.Markdown(extensions=["tables", "fenced_code", "toc"])
    body = md.convert((resources.docs_dir() / f"{name}.md").read_text(encoding="utf-8"))
    sections = _headings(md.toc_tokens)
    title = html_lib.unescape(md.toc_tokens[0]["name"]) if md.toc_tokens else name
    body = re.sub(r"\A\s*<h1\b[^>]*>.*?</h1>\s*", "", body, count=1, flags=re.S)  # the page's own <h1> is the title
    return Document(name, title, Markup(body), sections)


def section_id(name: str, section: str) -> str:
    """The id of the heading of document ``name`` that starts with ``section``.

    Raises
    ------
    ValueError
        If no heading (or more than one) starts with ``section``.
    """
    found = [i for heading, i in document(name).sections.items() if heading.startswith(section)]
    if len(found) != 1:
        raise ValueError(f"section must start exactly one heading of docs/{name}.md, got {section!r} "
                         f"({len(found)} match; headings: {', '.join(document(name).sections)})")
    return found[0]


def gap_link(gap: Gap) -> dict:
    """A gap as the page shows it: ``text``, ``href`` (relative to the site folder) and ``label``."""
    return {"text": gap.text, "href": f"docs/{gap.doc}.html#{section_id(gap.doc, gap.section)}",
            "label": f"docs/{gap.doc}.md, “{gap.section}”"}
