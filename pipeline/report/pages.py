"""The report's pages, registered as objects: a new page is one :func:`register` call.

A :class:`Page` says what it shows and how it is written; :func:`tyrelab.report.site.build_site`
knows no page by name. It asks every registered page, in :attr:`Page.order`, for

1. its thesis/own tables (:meth:`Page.tables`) and figures (:meth:`Page.figures`), so that every
   figure of the site is drawn together (reused from the cache, the rest in parallel) and every
   table is shaped once;
2. its files (:meth:`Page.render`): one or more :class:`Output` (template, path, context).

The navigation bar lists the registered pages with ``nav`` set, in order. Pages read the build
through the ``site`` object handed to them (:class:`tyrelab.report.site.SiteBuild`): ``items(page)``
(the page's tables and figures as template items), ``figure_task(spec)``, ``run_task(row)``,
``run_item(row)``, ``memo(key, compute)``, ``manifest``, ``results``, ``pages`` (the registered
pages) and ``wh`` (the warehouse).

Examples
--------
A chapter-like page of tables and figures is a :class:`ChapterPage` around a
:class:`~tyrelab.report.chapters.Chapter`:

>>> from tyrelab.report.chapters import Chapter, TableSpec
>>> page = ChapterPage(Chapter("example", "Example — one table", "Intro.",
...                            (TableSpec("", "Ride results", "ride_results", "simulate"),)), order=95)
>>> page.href, page.nav_title, [t.view for t in page.tables()]
('example.html', 'Example', ['ride_results'])
>>> registered = register(page, registry=[])  # register(page) adds it to the report
"""

from __future__ import annotations

import hashlib
import re
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Any, Iterable

import pandas as pd

from . import tables
from .chapters import CHAPTERS, Chapter, FigureSpec, TableSpec
from .docs import DOCS, document
from .frf_page import VEHICLE_FRF
from .measured_page import MEASURED_RIDE

__all__ = ["Output", "Page", "ChapterPage", "RidePage", "IndexPage", "RunsPage", "DocsPage", "PAGES", "register", "registered",
           "run_page_name"]


@dataclass(frozen=True)
class Output:
    """One HTML file of a page.

    Attributes
    ----------
    path : str
        File path relative to the site folder (``"ch4-stiffness.html"``, ``"runs/x.html"``).
    template : str
        Jinja2 template in ``reports/``.
    title : str
        Page title (``<h1>`` and ``<title>``).
    context : dict
        Template variables besides the common ones (``prov``, ``nav``, ``root``, ``here``, ``title``).
    """

    path: str
    template: str
    title: str
    context: dict = field(default_factory=dict)

    @property
    def root(self) -> str:
        """Relative link prefix back to the site folder (``"../"`` for a file in a subfolder)."""
        return "../" * self.path.count("/")


class Page(ABC):
    """A registered page of the report (subclass, set the attributes and implement :meth:`render`).

    Attributes
    ----------
    slug : str
        File name without ``.html``; unique in the registry.
    title : str
        Title; the navigation bar shows the part before " — ".
    order : float
        Position in the navigation bar and on the index (ascending).
    nav : bool
        Listed in the navigation bar.
    folder : str or None
        Sub-folder this page owns: its ``*.html`` files not written by this build are removed.
    """

    slug: str
    title: str
    order: float
    nav: bool = True
    folder: str | None = None

    @property
    def href(self) -> str:
        """The page's main file, relative to the site folder."""
        return f"{self.slug}.html"

    @property
    def nav_title(self) -> str:
        """Short title for the navigation bar."""
        return self.title.split(" — ")[0]

    def tables(self) -> tuple[TableSpec, ...]:
        """Tables shown on the page (shaped once per build, through the report cache)."""
        return ()

    def figures(self, site) -> Iterable[tuple[Any, Any]]:
        """``(name, FigureTask)`` pairs of the figures the page shows, requested before any is drawn."""
        return ()

    @abstractmethod
    def render(self, site) -> Iterable[Output]:
        """The page's files (every page implements it: a class without it cannot be instantiated)."""


@dataclass(frozen=True)
class ChapterPage(Page):
    """A page of tables and figures (a thesis chapter, the Ride page) from a :class:`Chapter`:
    ``chapter.html.j2``. Its items are resolved once per build (``site.items(page)``)."""

    chapter: Chapter
    order: float
    nav: bool = True

    @property
    def slug(self) -> str:
        return self.chapter.slug

    @property
    def title(self) -> str:
        return self.chapter.title

    def tables(self) -> tuple[TableSpec, ...]:
        return tuple(it for it in self.chapter.items if isinstance(it, TableSpec))

    def figure_specs(self) -> tuple[FigureSpec, ...]:
        """The chapter's figures."""
        return tuple(it for it in self.chapter.items if isinstance(it, FigureSpec))

    def figures(self, site):
        return [(("spec", id(spec)), site.figure_task(spec)) for spec in self.figure_specs()]

    def render(self, site):
        items = site.items(self)
        return [Output(self.href, "chapter.html.j2", self.chapter.title,
                       {"chapter": self.chapter, "items": items,
                        "has_thesis_tables": any(it["kind"] == "table" and it["spec"].published for it in items)})]


@dataclass(frozen=True)
class RidePage(ChapterPage):
    """The Ride page: its chapter's items, and after the first ``lead`` of them one section per ride
    scenario of the build (:func:`tyrelab.report.ride_sections.scenario_sections`: each variant's tyres
    and natural frequencies, per-axis a_w against speed, the hours to the action value over two
    swept keys or why there is none, the seat PSD and transmissibility per axis), drawn by the same
    code as ``tyrelab ride``'s page: ``ride_page.html.j2``."""

    lead: int = 1

    def sections(self, site) -> list[dict]:
        """The scenario sections of this build (once per build)."""
        from .ride_sections import SECTION_TABLES, scenario_sections

        return site.memo((self.slug, "sections"), lambda: scenario_sections(*(site.wh.table(t) for t in SECTION_TABLES)))

    def figures(self, site):
        out = list(super().figures(site))
        for sec in self.sections(site):
            out += [((self.slug, sec["file"], f.name), site.function_task(f"ride_figures.{f.function}", f.args, f.kwargs))
                    for f in sec["figures"] if f.function]
        return out

    def render(self, site):
        items = site.items(self)
        sections = [{**sec, "figures": [{"name": f.name, "caption": f.caption, "note": f.note,
                                         "svg": site.figs[(self.slug, sec["file"], f.name)] if f.function else None}
                                        for f in sec["figures"]]} for sec in self.sections(site)]
        from .ride_sections import AXIS_WORDS

        return [Output(self.href, "ride_page.html.j2", self.chapter.title,
                       {"chapter": self.chapter, "items": items, "lead": self.lead, "sections": sections,
                        "axis_words": AXIS_WORDS})]


def run_page_name(run_id: str) -> str:
    """File name of a run's drill-down page: safe characters plus a short hash (no collisions).

    Examples
    --------
    >>> run_page_name("T2/p1.38 v0")
    'T2_p1.38_v0-1e1559.html'
    """
    safe = re.sub(r"[^A-Za-z0-9_.-]", "_", str(run_id))[:60]
    return f"{safe}-{hashlib.sha1(str(run_id).encode()).hexdigest()[:6]}.html"


@dataclass(frozen=True)
class RunsPage(Page):
    """The drill-down list ``runs.html`` and one page per selected run in ``runs/``
    (every QC-flagged run and the first ``per_tyre`` runs of each tyre, at most ``cap``)."""

    slug: str = "runs"
    title: str = "Run drill-down"
    order: float = 1000
    folder: str | None = "runs"
    per_tyre: int = 2
    cap: int = 60

    @property
    def nav_title(self) -> str:
        return "Runs"

    def selected(self, site) -> pd.DataFrame:
        """The runs that get a page (results rows with their manifest's file and signal path)."""
        def select():
            chosen = tables.select_runs(site.results, self.per_tyre, self.cap)
            manifest = site.manifest
            if not chosen.empty:
                extra = [c for c in ("run_id", "sample_rate_Hz", "run_path", "file") if c in manifest.columns]
                chosen = chosen.merge(manifest[extra], on="run_id", how="left", suffixes=("", "_manifest"))
            return chosen

        return site.memo((self.slug, "selected"), select)

    def figures(self, site):
        return [(("run", row["run_id"]), site.run_task(row)) for _, row in self.selected(site).iterrows()]

    def render(self, site):
        outputs, listed = [], []
        for _, row in self.selected(site).iterrows():
            path = f"{self.folder}/{run_page_name(row['run_id'])}"
            outputs.append(Output(path, "run.html.j2", f"Run {row['run_id']}", {"run": site.run_item(row)}))
            listed.append({"href": path, "run_id": row["run_id"], "tyre_id": row.get("tyre_id"),
                           "qc_ok": row.get("qc_ok"), "qc_reasons": row.get("qc_reasons")})
        outputs.append(Output(self.href, "runs.html.j2", self.title,
                              {"runs": listed, "n_results": len(site.results), "per_tyre": self.per_tyre,
                               "cap": self.cap}))
        return outputs


@dataclass(frozen=True)
class IndexPage(Page):
    """``index.html``: campaign summary, the other pages with their tables, quarantine, QC flags."""

    slug: str = "index"
    title: str = "Summary"
    order: float = 0

    def render(self, site):
        contents = [{"href": p.href, "title": p.title, "items": site.items(p) if isinstance(p, ChapterPage) else []}
                    for p in site.pages if p is not self]
        results, quarantine = site.results, site.wh.table("quarantine")
        flagged = results.loc[~results["qc_ok"].fillna(False).astype(bool)] if "qc_ok" in results else results.head(0)
        return [Output(self.href, "index.html.j2", "tyrelab report", {
            "summary": tables.campaign_summary(site.manifest, results, quarantine, site.wh.table("calibration")),
            "contents": contents,
            "quarantine": tables.plain_table(quarantine, ["campaign", "file", "run_id", "stage", "reason"], 100),
            "flagged": tables.plain_table(flagged, ["run_id", "tyre_id", "speed_km_h", "pressure_bar", "qc_reasons"],
                                          100)})]


@dataclass(frozen=True)
class DocsPage(Page):
    """The documents the chapter pages link to (:data:`tyrelab.report.docs.DOCS`), rendered into
    ``docs/<name>.html``: a gap's "why" (:class:`~tyrelab.report.docs.Gap`) links to its section."""

    slug: str = "docs"
    title: str = "Documents — findings, simulation, uncertainty"
    order: float = 1100
    folder: str | None = "docs"

    @property
    def href(self) -> str:
        return f"{self.folder}/{DOCS[0]}.html"

    def render(self, site):
        documents = [document(name) for name in DOCS]
        return [Output(f"{self.folder}/{d.name}.html", "doc.html.j2", d.title, {"doc": d, "documents": documents})
                for d in documents]


#: The registry: every page of the report (see :func:`register`).
PAGES: list[Page] = []


def register(page: Page, registry: list[Page] | None = None) -> Page:
    """Add ``page`` to the report (``registry`` defaults to :data:`PAGES`); returns it.

    Raises
    ------
    ValueError
        A page with the same ``slug`` is already registered.
    """
    registry = PAGES if registry is None else registry
    if any(p.slug == page.slug for p in registry):
        raise ValueError(f"page: slug {page.slug!r} is already registered")
    registry.append(page)
    return page


def registered(registry: list[Page] | None = None) -> list[Page]:
    """The registered pages in :attr:`Page.order` (ties: registration order)."""
    return sorted(PAGES if registry is None else registry, key=lambda p: p.order)


register(IndexPage())
for _number, _chapter in enumerate(CHAPTERS):
    register((RidePage if _chapter.slug == "ride" else ChapterPage)(_chapter, order=10 * (_number + 1)))
register(RunsPage())
register(ChapterPage(MEASURED_RIDE, order=10 * (len(CHAPTERS) + 1)))
register(ChapterPage(VEHICLE_FRF, order=10 * (len(CHAPTERS) + 1) + 3))  # beside the measured ride
register(DocsPage())
