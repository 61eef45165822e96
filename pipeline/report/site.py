"""Build the static report site ``build/reports/`` from the warehouse (the I/O side).

Reads the warehouse read-only (:func:`tyrelab.warehouse.query`) and the run
Parquet files named in ``manifest.run_path``, shapes tables and figures with
the pure functions of :mod:`tyrelab.report.tables` and
:mod:`tyrelab.report.figures`, and writes one HTML file per page:

the pages registered in :mod:`tyrelab.report.pages` (:data:`~tyrelab.report.pages.PAGES`: the
index, one page per thesis chapter and the Ride page, the run drill-downs, the documents the
chapters link to). :func:`build_site`
knows no page by name: it asks each registered page for its tables and figures, then for its
files (a new page is one :func:`~tyrelab.report.pages.register` call).

Everything is inline (CSS, SVG); links are relative, so the folder opens from
the file system and can be mailed as a zip.

Figures are the expensive part. :func:`build_site` first lists every figure of
the site as a :class:`FigureTask` (the drawing function and exactly the data it
draws: its warehouse tables, or a run's row and the content digest of its
signal file), then reuses the ones a cache already holds under the digest of
that task and draws the others in parallel (:func:`tyrelab.executor.map_alongside`: this
process and ``jobs - 1`` workers),
and only then renders the pages. A figure is therefore redrawn only when its own
inputs (or the code) changed, and the site is the same bytes either way.
"""

from __future__ import annotations

import dataclasses
import hashlib
import importlib
import json
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import pandas as pd

from .. import io
from ..executor import map_alongside, map_in_background, worker_server_state
from ..itemcache import digest
from ..progress import Progress
from ..warehouse import check_read_only, connect_read_only
from . import tables
from markupsafe import escape

from .chapters import ABBREVIATIONS, Chapter, FigureSpec, TableSpec
from .docs import gap_link
from .pages import ChapterPage, Page, registered, run_page_name
from . import methods_page  # noqa: F401  (registers itself: the rig-methods page, issue 34)
from .render import abbreviations_used, environment, provenance

__all__ = ["MAX_PLAIN_ROWS", "POOL_MIN_FIGURES", "Missing", "Warehouse", "resolve_table", "table_queries",
    "shape_table", "resolve_figure", "chapter_items", "run_page_name", "read_signals", "run_item", "SiteBuild",
    "build_site"]

#: Rows shown of a plain (non-comparison) table.
MAX_PLAIN_ROWS = 40
#: Without a worker server ready, fewer figures to draw than this are drawn in this process, more
#: by this process and ``jobs - 1`` workers (:func:`tyrelab.executor.map_alongside`: this process
#: draws from the start and asks for workers once the worker server has imported the stages'
#: modules, ~2-3 s of CPU on another core). A figure takes ~0.1-0.3 s where matplotlib is loaded
#: (measured on the small demo campaign's one-run change, 7 figures: report 8.4 s wall with 2 fresh
#: workers, 4.0 s in the process; docs/benchmarks.md). With the server ready (``tyrelab run``
#: starts it when its first stage runs, so after one added run it is by the report) every figure
#: goes to ``jobs`` workers forked from it while this process shapes the tables
#: (:meth:`FigureSet.start`): report 1.76 -> 0.9 s, and this process never imports matplotlib.
POOL_MIN_FIGURES = 16


class Warehouse:
    """Read-only access to the warehouse with a per-build cache of whole tables (one connection)."""

    def __init__(self, db: Path):
        self.db = Path(db)
        self._con = None
        self._names: set[str] | None = None
        self._cache: dict[str, pd.DataFrame] = {}

    @property
    def names(self) -> set[str]:
        """Names of the tables and views (listed on first use: a drill-down worker reading
        its run's file never connects)."""
        if self._names is None:
            self._names = set(self.sql("SELECT table_name FROM information_schema.tables")["table_name"])
        return self._names

    @names.setter
    def names(self, value) -> None:
        self._names = set(value)

    def __contains__(self, name: str) -> bool:
        return name in self.names

    def __getstate__(self):  # picklable: reconnects in the other process
        return {**self.__dict__, "_con": None}

    def table(self, name: str) -> pd.DataFrame:
        """Table ``name`` as a DataFrame (empty when it does not exist)."""
        if name not in self._cache:
            self._cache[name] = self.sql(f'SELECT * FROM "{name}"') if name in self.names else pd.DataFrame()
        return self._cache[name]

    def sql(self, text: str) -> pd.DataFrame:
        """Run a read-only query (:func:`tyrelab.warehouse.query`'s checks, on one open connection)."""
        check_read_only(text)
        if self._con is None:
            self._con = connect_read_only(self.db)
        return self._con.execute(text).df()

    def close(self) -> None:
        """Close the connection."""
        if self._con is not None:
            self._con.close()
            self._con = None


@dataclass(frozen=True)
class Missing:
    """What a page item lacks, as a typed signal (``item["missing"]``; ``str()`` is the note shown).

    Attributes
    ----------
    stage : str
        The stage that writes it.
    subject : str
        What is missing, as the start of a sentence (``"Our table_xiii"``).
    empty : bool
        The table exists but has no rows (else it was not produced yet).
    nothing_to_draw : bool
        A figure whose input table exists (its stage ran) but holds none of what it draws.

    Examples
    --------
    >>> str(Missing("simulate", "Table table_xiii"))
    'Table table_xiii not produced yet by stage simulate.'
    >>> str(Missing("analyse", "Fig. 21 (results)", empty=True, nothing_to_draw=True))
    'Fig. 21 (results): stage analyse ran, but its table holds nothing this figure draws.'
    """

    stage: str
    subject: str
    empty: bool = False
    nothing_to_draw: bool = False

    def __str__(self) -> str:
        if self.nothing_to_draw:
            return f"{self.subject}: stage {self.stage} ran, but its table holds nothing this figure draws."
        if self.empty:
            return f"{self.subject} is empty (stage {self.stage})."
        return f"{self.subject} not produced yet by stage {self.stage}."


def resolve_table(wh: Warehouse, spec: TableSpec, cache=None) -> dict:
    """Fetch and shape one :class:`TableSpec` into a template item.

    With ``cache`` (:class:`tyrelab.stages.state.ItemCache`) the shaping is kept under the
    digest of the spec and of exactly the frames it shapes (our table or query result and the
    published table), so an unchanged table is fetched but not shaped again.
    """
    published = wh.table(spec.published) if spec.published and spec.published in wh else pd.DataFrame()
    ours = None
    if spec.view in wh:
        ours = wh.sql(spec.ours_sql) if spec.ours_sql else wh.table(spec.view)
    if cache is None:
        shaped = shape_table(spec, ours, published)
    else:
        key = cache.key("table", dataclasses.asdict(spec), ours, published)
        shaped = cache.get_or_compute(key, lambda: shape_table(spec, ours, published))
    return {"kind": "table", "spec": spec, **shaped, "queries": table_queries(wh, spec),
            "gaps": [gap_link(g) for g in spec.gaps]}


def table_queries(wh: Warehouse, spec: TableSpec) -> list[str]:
    """The queries a page shows under a table: those that run in ``tyrelab sql`` on this warehouse
    (our values: ``spec.ours_sql`` or the whole view; the digitised thesis table)."""
    queries = []
    if spec.view in wh:
        queries.append(spec.ours_sql or f"SELECT * FROM {spec.view}")
    if spec.published and spec.published in wh:
        queries.append(f"SELECT * FROM {spec.published}")
    return queries


def shape_table(spec: TableSpec, ours: pd.DataFrame | None, published: pd.DataFrame) -> dict:
    """The template fields of one table (``mode``, ``note``, ``missing`` and ``shaped`` or ``plain``)
    from our frame (None when ``spec.view`` does not exist) and the published one (may be empty).

    ``missing`` is a :class:`Missing` when our table is not produced yet or empty (an input table,
    ``spec.is_input``, shown with the thesis' values alone is not missing), else None.
    """
    item = {"note": spec.note, "missing": None}
    if ours is not None:
        if spec.ours_sql and not published.empty:
            df = tables.compare_frames(ours, published, list(spec.keys), spec.values, spec.thesis_rename)
        elif tables.find_pairs(ours.columns) or published.empty:
            df = ours
        else:
            common = [c for c in ours.columns if c in published.columns and c not in tables.HIDDEN]
            keys = [c for c in common if not tables._is_numeric(ours[c]) or c in tables.NUMERIC_KEYS]
            df = tables.compare_frames(ours, published, keys, {c: c for c in common if c not in keys})
        if tables.find_pairs(df.columns):
            item.update(mode="comparison", shaped=tables.shape_comparison(df, columns=spec.columns))
        else:
            item.update(mode="plain", plain=tables.plain_table(df, list(spec.columns) or None, MAX_PLAIN_ROWS))
    elif not published.empty:
        item.update(mode="comparison", shaped=tables.shape_comparison(tables.thesis_only(published, tuple(spec.values.values()))))
        if not spec.is_input:
            item["missing"] = Missing(spec.stage, f"Our {spec.view}")
            item["note"] = " ".join(filter(None, [spec.note, str(item["missing"])]))
    else:
        item.update(mode="missing", missing=Missing(spec.stage, f"Table {spec.view}"))
        item["note"] = str(item["missing"])
    if item.get("mode") != "missing":
        size = item["shaped"].rows if item["mode"] == "comparison" else item["plain"]["rows"]
        if not size:
            item.update(mode="missing", missing=Missing(spec.stage, f"Table {spec.view}", empty=True))
            item["note"] = str(item["missing"])
    return item


@dataclass
class FigureTask:
    """One figure to draw: ``<module>.<function>(*args, **kwargs)`` of this package (``function``
    is ``"figures.stiffness_vs_pressure"``), or a run's drill-down.

    ``kind`` is ``"figure"`` (``args`` are the warehouse tables) or ``"run"``
    (``args`` is ``(row, db)``: the run's result row and the warehouse, the
    signals are read by the worker). ``inputs`` is what the figure depends on,
    hashed into :attr:`key` (for a run: the row and the SHA-256 of its signal
    file instead of the signals themselves).
    """

    kind: str
    function: str
    args: tuple
    kwargs: dict = field(default_factory=dict)
    inputs: tuple = ()

    @cached_property
    def key(self) -> str:
        """Digest of the drawing function and everything it draws."""
        return digest([self.kind, self.function, self.kwargs, list(self.inputs)])


def draw(task: FigureTask) -> str | None:
    """Draw one :class:`FigureTask`; the SVG markup or None (runs in a worker process)."""
    if task.kind == "run":
        row, db = task.args
        wh = Warehouse(db) if Path(db).exists() else None
        try:
            return run_figure(wh, row)
        finally:
            if wh is not None:
                wh.close()
    module, name = task.function.rsplit(".", 1)  # matplotlib: imported only where a figure is drawn
    return getattr(importlib.import_module(f"{__package__}.{module}"), name)(*task.args, **task.kwargs)


class FigureSet:
    """The figures of a site: requested first, drawn together (reused from ``cache``), then looked up.

    Parameters
    ----------
    cache : tyrelab.stages.state.ItemCache, optional
        Where drawn figures are kept by :attr:`FigureTask.key`; None draws every figure.
    jobs : int
        Processes drawing the figures, this one included (when there are at least
        :data:`POOL_MIN_FIGURES` of them; fewer are drawn in this process alone).
    """

    def __init__(self, cache=None, jobs: int = 1):
        self.cache, self.jobs = cache, jobs
        self.tasks: dict[str, FigureTask] = {}
        self.names: dict = {}
        self.svgs: dict[str, str | None] = {}
        self.drawn = 0

    def request(self, name, task: FigureTask) -> str:
        """Register ``task`` under ``name`` (a spec or a run id); return its key."""
        self.tasks.setdefault(task.key, task)
        self.names[name] = task.key
        return task.key

    def start(self) -> None:
        """Take what the cache holds; when the worker server is ready, hand the rest to ``jobs``
        worker processes (:func:`tyrelab.executor.map_in_background`), which draw while this
        process shapes the tables; :meth:`draw_all` collects them (or draws them, without a server)."""
        self._todo = []
        for key, task in self.tasks.items():
            hit, svg = self.cache.get(self.cache.key("figure", key)) if self.cache else (False, None)
            if hit:
                self.svgs[key] = svg
            else:
                self._todo.append(key)
        # Drill-downs (the dearest) first, so that the last figures handed out are cheap ones.
        self._todo.sort(key=lambda k: self.tasks[k].kind != "run")
        self._background = map_in_background(draw, [self.tasks[k] for k in self._todo], self.jobs)

    def abandon(self) -> None:
        """End the workers of :meth:`start` (an error or an interrupt before :meth:`draw_all`)."""
        background, self._background = getattr(self, "_background", None), None
        if background is not None:
            background.abandon()

    @property
    def to_draw(self) -> int:
        """Figures :meth:`draw_all` will draw (not in the cache), once :meth:`start` ran."""
        return len(getattr(self, "_todo", ()))

    def draw_all(self, on_done=None) -> None:
        """The figures not in the cache: collected from the workers of :meth:`start`, else drawn in
        parallel by this process and ``jobs - 1`` workers (:func:`tyrelab.executor.map_alongside`;
        by this process alone when fewer than :data:`POOL_MIN_FIGURES` and no worker server is ready);
        ``on_done(i)`` after each."""
        if not hasattr(self, "_todo"):
            self.start()
        todo, background, self._background = self._todo, self._background, None
        if background is not None:
            svgs = background.results(on_done)
        else:
            ready = worker_server_state() == "ready"
            svgs = map_alongside(draw, [self.tasks[k] for k in todo],
                                 self.jobs if len(todo) >= POOL_MIN_FIGURES or ready else 1, on_done=on_done)
        for key, svg in zip(todo, svgs):
            self.svgs[key] = svg
            if self.cache:
                self.cache.put(self.cache.key("figure", key), svg)
        self.drawn = len(todo)

    def __getitem__(self, name) -> str | None:
        """The SVG of the figure requested under ``name``."""
        return self.svgs[self.names[name]]


def figure_task(wh: Warehouse, spec: FigureSpec) -> FigureTask:
    """The :class:`FigureTask` of a chapter figure: its function, kwargs and input tables."""
    tables_ = tuple(wh.table(n) for n in spec.inputs)
    return FigureTask("figure", f"{spec.module}.{spec.function}", tables_, dict(spec.kwargs), tables_)


def resolve_figure(wh: Warehouse, spec: FigureSpec, figs: FigureSet | None = None) -> dict:
    """One :class:`FigureSpec` as a template item (``svg`` None with a note when no data).

    With ``figs`` the figure must have been requested and drawn there; without, it is drawn now.
    """
    svg = figs[("spec", id(spec))] if figs is not None else draw(figure_task(wh, spec))
    label = f"Fig. {spec.number}" if spec.number else "the figure"
    if svg:
        missing = None
    elif all(name in wh for name in spec.inputs):  # the stage ran: nothing of what the figure draws
        missing = Missing(spec.stage, f"{label[:1].upper()}{label[1:]} ({spec.inputs[0]})", empty=True,
                          nothing_to_draw=True)
    else:
        missing = Missing(spec.stage, f"The data of {label} ({spec.inputs[0]}) are")
    return {"kind": "figure", "spec": spec, "svg": svg, "note": str(missing or ""), "missing": missing}


def chapter_items(wh: Warehouse, chapter: Chapter, figs: FigureSet | None = None, cache=None,
                  shaped: dict | None = None) -> list[dict]:
    """All tables and figures of one chapter page (tables shaped through ``cache``, see :func:`resolve_table`,
    or taken from ``shaped``, keyed by the ``id`` of their :class:`TableSpec`)."""
    shaped = shaped or {}
    return [(shaped.get(id(it)) or resolve_table(wh, it, cache)) if isinstance(it, TableSpec)
            else resolve_figure(wh, it, figs) for it in chapter.items]


def _run_file(wh: Warehouse | None, row: pd.Series) -> Path | None:
    """The converted file of a run (``manifest.run_path``: relative to the build, the warehouse's
    folder; an absolute one of an older build as it is), or None where there is none."""
    path = row.get("run_path")
    if not isinstance(path, str) or not path:
        return None
    p = Path(path)
    if not p.is_absolute() and wh is not None and getattr(wh, "db", None):
        p = Path(wh.db).parent / p
    return p if p.exists() else None


def read_signals(wh: Warehouse, row: pd.Series) -> pd.DataFrame:
    """One run's signals from its Parquet file (``manifest.run_path``), else from the ``runs`` view."""
    path = _run_file(wh, row)
    if path is not None:
        return pd.read_parquet(path)
    if wh is not None and "runs" in wh:
        rid = str(row["run_id"]).replace("'", "''")
        return wh.sql(f"SELECT * FROM runs WHERE run_id = '{rid}' ORDER BY time_s")
    return pd.DataFrame()


def run_figure(wh: Warehouse | None, row: pd.Series) -> str | None:
    """The drill-down figure of one run (signals read from its file, else from the warehouse)."""
    from . import figures

    signals = read_signals(wh, row)
    fs = row.get("sample_rate_Hz")
    if (fs is None or pd.isna(fs)) and "time_s" in signals and len(signals) > 1:
        fs = 1.0 / float(signals["time_s"].diff().median())
    f_exc = row.get("excitation_frequency_Hz")
    f_exc = float(f_exc) if f_exc is not None and pd.notna(f_exc) else None
    spectra = figures.run_spectra(signals, float(row["axle_mass_kg"]), float(fs)) if len(signals) > 64 else pd.DataFrame()
    k = row.get("stiffness_kN_per_m")
    return figures.run_drilldown(signals, spectra, f_exc, float(k) if k is not None and pd.notna(k) else None)


def run_task(wh: Warehouse, row: pd.Series) -> FigureTask:
    """The :class:`FigureTask` of a run's drill-down: its row and the digest of its signal file."""
    path = _run_file(wh, row)
    source = io.file_sha256(path) if path is not None else f"warehouse:{wh.db}:{id(wh)}"
    return FigureTask("run", "run_drilldown", (row, wh.db), {}, (row.to_dict(), source))


def run_item(wh: Warehouse, row: pd.Series, figs: FigureSet | None = None) -> dict:
    """Figures and facts for one run's drill-down page."""
    facts = [(c, row.get(c)) for c in (
        "tyre_id", "kind", "speed_km_h", "pressure_bar", "load_kN", "excitation_frequency_Hz",
        "excitation_frequency_measured_Hz", "amplitude_mm_pp", "amplitude_measured_mm_pp", "surface",
        "recorded_on", "stiffness_kN_per_m", "damping_kN_s_per_m", "welch_stiffness_kN_per_m",
        "welch_damping_kN_s_per_m", "coherence", "qc_ok") if c in row.index]
    for name, unit in (("stiffness", "N_per_m"), ("damping", "N_s_per_m")):
        lo, hi = row.get(f"{name}_ci95_low_{unit}"), row.get(f"{name}_ci95_high_{unit}")
        if lo is not None and hi is not None and pd.notna(lo) and pd.notna(hi):
            k_unit = "kN/m" if name == "stiffness" else "kN s/m"
            facts.append((f"{name} 95 % interval", f"{lo / 1e3:.4g} to {hi / 1e3:.4g} {k_unit} "
                                                   f"({row.get('uncertainty_source', '')})"))
    reasons = [r for r in str(row.get("qc_reasons") or "").split("; ") if r and r != "nan"]
    return {
        "run_id": row["run_id"], "facts": facts, "qc_reasons": reasons,
        "file": row.get("file"), "campaign": row.get("campaign"),
        "figure": figs[("run", row["run_id"])] if figs is not None else run_figure(wh, row),
    }


def _dataset(manifest: pd.DataFrame, raw: Path) -> dict:
    """Data set identity: campaigns, a digest of the run files, generator seeds or the raw source."""
    campaigns = sorted(map(str, manifest["campaign"].unique())) if "campaign" in manifest else []
    seeds = []
    for c in campaigns:
        meta = Path(c) / "generator.json"
        if meta.exists():
            info = json.loads(meta.read_text())
            seeds.append(f"{Path(c).name}: seed {info.get('seed')} ({info.get('scale', '?')})")
    digest = hashlib.sha256("".join(sorted(manifest["sha256"].astype(str))).encode()).hexdigest()[:12] \
        if "sha256" in manifest and len(manifest) else "–"
    return {"campaigns": campaigns, "seeds": seeds, "digest": digest, "raw": str(raw)}


class SiteBuild:
    """One build of the site: what the registered pages read (see :mod:`tyrelab.report.pages`).

    Parameters
    ----------
    wh : Warehouse
    figs : FigureSet
    pages : list of Page
        The pages of this build, in order.
    cache : tyrelab.stages.state.ItemCache, optional
        Shaped tables (and figures, through ``figs``).
    """

    def __init__(self, wh: Warehouse, figs: FigureSet, pages: list[Page], cache=None):
        self.wh, self.figs, self.pages, self.cache = wh, figs, pages, cache
        self.manifest, self.results = wh.table("manifest"), wh.table("results")
        self.shaped: dict[int, dict] = {}
        self._items: dict[str, list[dict]] = {}
        self._memo: dict = {}

    def memo(self, key, compute):
        """``compute()`` once per build under ``key`` (a page's own derived data)."""
        if key not in self._memo:
            self._memo[key] = compute()
        return self._memo[key]

    def figure_task(self, spec: FigureSpec) -> FigureTask:
        """The task of a chapter figure (:func:`figure_task`)."""
        return figure_task(self.wh, spec)

    def function_task(self, function: str, args: tuple = (), kwargs: dict | None = None) -> FigureTask:
        """The task of a figure drawn by ``tyrelab.report.<function>`` (``"ride_figures.seat_psd"``)
        from ``args`` (the data it draws, hashed into its key) and ``kwargs``."""
        return FigureTask("figure", function, tuple(args), dict(kwargs or {}), tuple(args))

    def run_task(self, row: pd.Series) -> FigureTask:
        """The task of a run's drill-down figure (:func:`run_task`)."""
        return run_task(self.wh, row)

    def run_item(self, row: pd.Series) -> dict:
        """Facts and figure of a run's drill-down page (:func:`run_item`)."""
        return run_item(self.wh, row, self.figs)

    def shape_tables(self) -> None:
        """Shape every registered page's tables (through the cache)."""
        for page in self.pages:
            for spec in page.tables():
                if id(spec) not in self.shaped:
                    self.shaped[id(spec)] = resolve_table(self.wh, spec, self.cache)

    def items(self, page: ChapterPage) -> list[dict]:
        """The tables and figures of a chapter page as template items (resolved once per build)."""
        if page.slug not in self._items:
            self._items[page.slug] = chapter_items(self.wh, page.chapter, self.figs, self.cache, self.shaped)
        return self._items[page.slug]

    def missing(self) -> list[str]:
        """``"<page>: <note>"`` for every item of a chapter page whose data were not produced yet."""
        return [f"{page.slug}: {it['note']}" for page in self.pages if isinstance(page, ChapterPage)
                for it in self.items(page) if it.get("missing") and not it["missing"].empty]


def _spell_out(html: str) -> str:
    """The page with its abbreviations (:data:`~tyrelab.report.chapters.ABBREVIATIONS` that appear
    in it) spelled out once, under the title."""
    used = abbreviations_used(html, ABBREVIATIONS)
    if not used or "</h1>\n" not in html:
        return html
    line = "; ".join(f"<strong>{escape(a)}</strong>: {escape(m)}" for a, m in used)
    return html.replace("</h1>\n", f'</h1>\n<p class="abbr">Abbreviations on this page — {line}.</p>\n', 1)


def build_site(db: Path, out: Path, raw: Path, cache=None, jobs: int = 1, pages: list[Page] | None = None) -> dict:
    """Render every registered page of the report into ``out``.

    Parameters
    ----------
    db : Path
        The warehouse (opened read-only).
    out : Path
        Output folder, normally ``build/reports``.
    raw : Path
        Raw data folder, for the provenance footer.
    cache : tyrelab.stages.state.ItemCache, optional
        Figures kept by the digest of their inputs (see the module docstring);
        None draws every figure.
    jobs : int
        Processes drawing the figures not in ``cache``, this one included.
    pages : list of Page, optional
        The pages to build (default: :func:`tyrelab.report.pages.registered`).

    Returns
    -------
    dict
        ``pages`` (paths written), ``bytes`` (total size of the site),
        ``tables``, ``comparison_tables``, ``missing`` (notes of what is not produced yet),
        ``figures`` (figures on the site) and ``drawn`` (of them, drawn this time).
    """
    out = Path(out)
    wh = Warehouse(db)
    pages_ = registered() if pages is None else list(pages)
    prov = provenance(raw, _dataset(wh.table("manifest"), raw))
    env = environment()
    nav = [{"href": p.href, "title": p.nav_title, "slug": p.slug} for p in pages_ if p.nav]
    written: list[Path] = []

    figs = FigureSet(cache, jobs)
    site = SiteBuild(wh, figs, pages_, cache)
    for page in pages_:
        for name, task in page.figures(site):
            figs.request(name, task)
    figs.start()  # with a worker server ready the figures are drawn while the tables are shaped
    progress = Progress("report: figures and pages", figs.to_draw + len(pages_), unit="items")
    try:
        site.shape_tables()
        figs.draw_all(on_done=lambda i: progress.step())
    except BaseException:
        figs.abandon()
        progress.close()
        raise

    for page in pages_:
        outputs = list(page.render(site))
        for o in outputs:
            html = _spell_out(env.get_template(o.template).render(prov=prov, nav=nav, root=o.root, here=page.slug,
                                                                  title=o.title, **o.context))
            path = out / o.path
            if not path.is_file() or path.read_text(encoding="utf-8") != html:  # unchanged pages keep their mtime
                io.write_text_atomic(html, path)
            written.append(path)
        if page.folder and (out / page.folder).is_dir():
            keep = {out / o.path for o in outputs}
            for stale in (out / page.folder).glob("*.html"):
                if stale not in keep:
                    stale.unlink()
        progress.step()

    items = [it for page in pages_ if isinstance(page, ChapterPage) for it in site.items(page)]
    missing = site.missing()
    wh.close()
    size = sum(p.stat().st_size for p in out.rglob("*") if p.is_file())
    return {"pages": written, "bytes": size, "tables": sum(it["kind"] == "table" for it in items),
            "comparison_tables": sum(it.get("mode") == "comparison" for it in items), "missing": missing,
            "figures": len(figs.tasks), "drawn": figs.drawn}
