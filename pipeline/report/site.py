"""Build the static report site ``build/reports/`` from the warehouse (the I/O side).

Reads the warehouse read-only (:func:`tyrelab.warehouse.query`) and the run
Parquet files named in ``manifest.run_path``, shapes tables and figures with
the pure functions of :mod:`tyrelab.report.tables` and
:mod:`tyrelab.report.figures`, and writes one HTML file per page:

- ``index.html``: campaign summary, chapter contents, quarantined files, QC-flagged runs;
- ``<chapter>.html``: one page per thesis chapter (:data:`tyrelab.report.chapters.CHAPTERS`);
- ``runs.html`` and ``runs/<run>.html``: drill-down pages for a bounded selection of runs.

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
import json
import re
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import pandas as pd

from .. import io
from ..executor import map_alongside, map_in_background, worker_server_state
from ..stages.state import digest
from ..warehouse import check_read_only, connect_read_only
from . import tables
from .chapters import CHAPTERS, Chapter, FigureSpec, TableSpec
from .render import environment, provenance

__all__ = ["RUNS_PER_TYRE", "MAX_RUN_PAGES", "MAX_PLAIN_ROWS", "POOL_MIN_FIGURES", "Warehouse", "resolve_table",
    "shape_table", "resolve_figure", "chapter_items", "run_page_name", "read_signals", "run_item", "build_site"]

#: Drill-down pages: runs per tyre, and the cap on the total.
RUNS_PER_TYRE = 2
MAX_RUN_PAGES = 60
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


def _missing(stage: str, what: str) -> str:
    return f"{what} not produced yet by stage {stage}."


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
    return {"kind": "table", "spec": spec, **shaped}


def shape_table(spec: TableSpec, ours: pd.DataFrame | None, published: pd.DataFrame) -> dict:
    """The template fields of one table (``mode``, ``note`` and ``shaped`` or ``plain``) from our
    frame (None when ``spec.view`` does not exist) and the published one (may be empty)."""
    item = {"note": spec.note}
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
            item.update(mode="comparison", shaped=tables.shape_comparison(df))
        else:
            item.update(mode="plain", plain=tables.plain_table(df, list(spec.columns) or None, MAX_PLAIN_ROWS))
    elif not published.empty:
        item.update(mode="comparison", shaped=tables.shape_comparison(tables.thesis_only(published, tuple(spec.values.values()))))
        item["note"] = spec.note if spec.is_input else " ".join(
            filter(None, [spec.note, _missing(spec.stage, f"Our {spec.view}")]))
    else:
        item.update(mode="missing")
        item["note"] = _missing(spec.stage, f"Table {spec.view}")
    if item.get("mode") != "missing":
        size = item["shaped"].rows if item["mode"] == "comparison" else item["plain"]["rows"]
        if not size:
            item.update(mode="missing", note=f"Table {spec.view} is empty (stage {spec.stage}).")
    return item


@dataclass
class FigureTask:
    """One figure to draw: ``figures.<function>(*args, **kwargs)``, or a run's drill-down.

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
    from . import figures  # matplotlib: imported only where a figure is drawn

    return getattr(figures, task.function)(*task.args, **task.kwargs)


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

    def draw_all(self) -> None:
        """The figures not in the cache: collected from the workers of :meth:`start`, else drawn in
        parallel by this process and ``jobs - 1`` workers (:func:`tyrelab.executor.map_alongside`;
        by this process alone when fewer than :data:`POOL_MIN_FIGURES` and no worker server is ready)."""
        if not hasattr(self, "_todo"):
            self.start()
        todo, background, self._background = self._todo, self._background, None
        if background is not None:
            svgs = background.results()
        else:
            ready = worker_server_state() == "ready"
            svgs = map_alongside(draw, [self.tasks[k] for k in todo],
                                 self.jobs if len(todo) >= POOL_MIN_FIGURES or ready else 1)
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
    return FigureTask("figure", spec.function, tables_, dict(spec.kwargs), tables_)


def resolve_figure(wh: Warehouse, spec: FigureSpec, figs: FigureSet | None = None) -> dict:
    """One :class:`FigureSpec` as a template item (``svg`` None with a note when no data).

    With ``figs`` the figure must have been requested and drawn there; without, it is drawn now.
    """
    svg = figs[("spec", id(spec))] if figs is not None else draw(figure_task(wh, spec))
    note = "" if svg else _missing(spec.stage, f"The data of Fig. {spec.number} ({spec.inputs[0]}) are")
    return {"kind": "figure", "spec": spec, "svg": svg, "note": note}


def chapter_items(wh: Warehouse, chapter: Chapter, figs: FigureSet | None = None, cache=None,
                  shaped: dict | None = None) -> list[dict]:
    """All tables and figures of one chapter page (tables shaped through ``cache``, see :func:`resolve_table`,
    or taken from ``shaped``, keyed by the ``id`` of their :class:`TableSpec`)."""
    shaped = shaped or {}
    return [(shaped.get(id(it)) or resolve_table(wh, it, cache)) if isinstance(it, TableSpec)
            else resolve_figure(wh, it, figs) for it in chapter.items]


def run_page_name(run_id: str) -> str:
    """File name of a run's drill-down page: safe characters plus a short hash (no collisions)."""
    safe = re.sub(r"[^A-Za-z0-9_.-]", "_", str(run_id))[:60]
    return f"{safe}-{hashlib.sha1(str(run_id).encode()).hexdigest()[:6]}.html"


def read_signals(wh: Warehouse, row: pd.Series) -> pd.DataFrame:
    """One run's signals from its Parquet file (``manifest.run_path``), else from the ``runs`` view."""
    path = row.get("run_path")
    if isinstance(path, str) and Path(path).exists():
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
    path = row.get("run_path")
    source = io.file_sha256(path) if isinstance(path, str) and Path(path).exists() else f"warehouse:{wh.db}:{id(wh)}"
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


def build_site(db: Path, out: Path, raw: Path, cache=None, jobs: int = 1) -> dict:
    """Render every page of the report into ``out``.

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

    Returns
    -------
    dict
        ``pages`` (paths written), ``bytes`` (total size of the site),
        ``tables``, ``comparison_tables``, ``missing`` (notes of what is not produced yet),
        ``figures`` (figures on the site) and ``drawn`` (of them, drawn this time).
    """
    out = Path(out)
    wh = Warehouse(db)
    manifest, results, quarantine = wh.table("manifest"), wh.table("results"), wh.table("quarantine")
    prov = provenance(raw, _dataset(manifest, raw))
    env = environment()
    nav = [{"href": "index.html", "title": "Summary"}] + [
        {"href": f"{c.slug}.html", "title": c.title.split(" — ")[0]} for c in CHAPTERS
    ] + [{"href": "runs.html", "title": "Runs"}]
    pages: list[Path] = []
    missing: list[str] = []
    n_tables = n_comparison = 0

    def write(template: str, path: Path, root: str = "", **kw) -> None:
        html = env.get_template(template).render(prov=prov, nav=nav, root=root, **kw)
        if not path.is_file() or path.read_text(encoding="utf-8") != html:  # unchanged pages keep their mtime
            io.write_text_atomic(html, path)
        pages.append(path)

    selected = tables.select_runs(results, RUNS_PER_TYRE, MAX_RUN_PAGES)
    if not selected.empty:
        extra = [c for c in ("run_id", "sample_rate_Hz", "run_path", "file") if c in manifest.columns]
        selected = selected.merge(manifest[extra], on="run_id", how="left", suffixes=("", "_manifest"))

    figs = FigureSet(cache, jobs)
    for chapter in CHAPTERS:
        for it in chapter.items:
            if isinstance(it, FigureSpec):
                figs.request(("spec", id(it)), figure_task(wh, it))
    for _, row in selected.iterrows():
        figs.request(("run", row["run_id"]), run_task(wh, row))
    figs.start()  # with a worker server ready the figures are drawn while the tables are shaped
    try:
        shaped = {id(it): resolve_table(wh, it, cache) for chapter in CHAPTERS for it in chapter.items
                  if isinstance(it, TableSpec)}
        figs.draw_all()
    except BaseException:
        figs.abandon()
        raise

    contents = []
    for chapter in CHAPTERS:
        items = chapter_items(wh, chapter, figs, cache, shaped)
        for it in items:
            n_tables += it["kind"] == "table"
            n_comparison += it.get("mode") == "comparison"
            if it["note"] and "not produced yet" in it["note"]:
                missing.append(f"{chapter.slug}: {it['note']}")
        contents.append({"chapter": chapter, "items": items})
        write("chapter.html.j2", out / f"{chapter.slug}.html", title=chapter.title, chapter=chapter, items=items)

    run_dir = out / "runs"
    listed = []
    for _, row in selected.iterrows():
        name = run_page_name(row["run_id"])
        write("run.html.j2", run_dir / name, root="../", title=f"Run {row['run_id']}", run=run_item(wh, row, figs))
        listed.append({"href": f"runs/{name}", "run_id": row["run_id"], "tyre_id": row.get("tyre_id"),
                       "qc_ok": row.get("qc_ok"), "qc_reasons": row.get("qc_reasons")})
    keep = {p.name for p in pages if p.parent == run_dir}
    for stale in run_dir.glob("*.html") if run_dir.exists() else []:
        if stale.name not in keep:
            stale.unlink()
    write("runs.html.j2", out / "runs.html", title="Run drill-down", runs=listed, n_results=len(results),
          per_tyre=RUNS_PER_TYRE, cap=MAX_RUN_PAGES)

    flagged = results.loc[~results["qc_ok"].fillna(False).astype(bool)] if "qc_ok" in results else results.head(0)
    write("index.html.j2", out / "index.html", title="tyrelab report",
          summary=tables.campaign_summary(manifest, results, quarantine, wh.table("calibration")),
          contents=contents,
          quarantine=tables.plain_table(quarantine, ["campaign", "file", "run_id", "stage", "reason"], 100),
          flagged=tables.plain_table(flagged, ["run_id", "tyre_id", "speed_km_h", "pressure_bar", "qc_reasons"], 100))
    wh.close()
    size = sum(p.stat().st_size for p in out.rglob("*") if p.is_file())
    return {"pages": pages, "bytes": size, "tables": n_tables, "comparison_tables": n_comparison, "missing": missing,
            "figures": len(figs.tasks), "drawn": figs.drawn}
