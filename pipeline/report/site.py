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
"""

from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path

import pandas as pd

from .. import io
from ..warehouse import query
from . import figures, tables
from .chapters import CHAPTERS, Chapter, FigureSpec, TableSpec
from .render import environment, provenance

__all__ = ["RUNS_PER_TYRE", "MAX_RUN_PAGES", "MAX_PLAIN_ROWS", "Warehouse", "resolve_table", "resolve_figure",
    "chapter_items", "run_page_name", "read_signals", "run_item", "build_site"]

#: Drill-down pages: runs per tyre, and the cap on the total.
RUNS_PER_TYRE = 2
MAX_RUN_PAGES = 60
#: Rows shown of a plain (non-comparison) table.
MAX_PLAIN_ROWS = 40


class Warehouse:
    """Read-only access to the warehouse with a per-build cache of whole tables."""

    def __init__(self, db: Path):
        self.db = Path(db)
        self.names = set(query(self.db, "SELECT table_name FROM information_schema.tables")["table_name"])
        self._cache: dict[str, pd.DataFrame] = {}

    def __contains__(self, name: str) -> bool:
        return name in self.names

    def table(self, name: str) -> pd.DataFrame:
        """Table ``name`` as a DataFrame (empty when it does not exist)."""
        if name not in self._cache:
            self._cache[name] = query(self.db, f'SELECT * FROM "{name}"') if name in self.names else pd.DataFrame()
        return self._cache[name]

    def sql(self, text: str) -> pd.DataFrame:
        """Run a read-only query."""
        return query(self.db, text)


def _missing(stage: str, what: str) -> str:
    return f"{what} not produced yet by stage {stage}."


def resolve_table(wh: Warehouse, spec: TableSpec) -> dict:
    """Fetch and shape one :class:`TableSpec` into a template item."""
    item = {"kind": "table", "spec": spec, "note": spec.note}
    published = wh.table(spec.published) if spec.published and spec.published in wh else pd.DataFrame()
    if spec.view in wh:
        ours = wh.sql(spec.ours_sql) if spec.ours_sql else wh.table(spec.view)
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


def resolve_figure(wh: Warehouse, spec: FigureSpec) -> dict:
    """Draw one :class:`FigureSpec` into a template item (``svg`` None with a note when no data)."""
    svg = getattr(figures, spec.function)(*(wh.table(n) for n in spec.inputs), **spec.kwargs)
    note = "" if svg else _missing(spec.stage, f"The data of Fig. {spec.number} ({spec.inputs[0]}) are")
    return {"kind": "figure", "spec": spec, "svg": svg, "note": note}


def chapter_items(wh: Warehouse, chapter: Chapter) -> list[dict]:
    """All tables and figures of one chapter page."""
    return [resolve_table(wh, it) if isinstance(it, TableSpec) else resolve_figure(wh, it) for it in chapter.items]


def run_page_name(run_id: str) -> str:
    """File name of a run's drill-down page: safe characters plus a short hash (no collisions)."""
    safe = re.sub(r"[^A-Za-z0-9_.-]", "_", str(run_id))[:60]
    return f"{safe}-{hashlib.sha1(str(run_id).encode()).hexdigest()[:6]}.html"


def read_signals(wh: Warehouse, row: pd.Series) -> pd.DataFrame:
    """One run's signals from its Parquet file (``manifest.run_path``), else from the ``runs`` view."""
    path = row.get("run_path")
    if isinstance(path, str) and Path(path).exists():
        return pd.read_parquet(path)
    if "runs" in wh:
        rid = str(row["run_id"]).replace("'", "''")
        return wh.sql(f"SELECT * FROM runs WHERE run_id = '{rid}' ORDER BY time_s")
    return pd.DataFrame()


def run_item(wh: Warehouse, row: pd.Series) -> dict:
    """Figures and facts for one run's drill-down page."""
    signals = read_signals(wh, row)
    fs = row.get("sample_rate_Hz")
    if (fs is None or pd.isna(fs)) and "time_s" in signals and len(signals) > 1:
        fs = 1.0 / float(signals["time_s"].diff().median())
    f_exc = row.get("excitation_frequency_Hz")
    f_exc = float(f_exc) if f_exc is not None and pd.notna(f_exc) else None
    spectra = figures.run_spectra(signals, float(row["axle_mass_kg"]), float(fs)) if len(signals) > 64 else pd.DataFrame()
    k = row.get("stiffness_kN_per_m")
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
        "figure": figures.run_drilldown(signals, spectra, f_exc, float(k) if k is not None and pd.notna(k) else None),
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


def build_site(db: Path, out: Path, raw: Path) -> dict:
    """Render every page of the report into ``out``.

    Parameters
    ----------
    db : Path
        The warehouse (opened read-only).
    out : Path
        Output folder, normally ``build/reports``.
    raw : Path
        Raw data folder, for the provenance footer.

    Returns
    -------
    dict
        ``pages`` (paths written), ``bytes`` (total size of the site),
        ``tables``, ``comparison_tables``, ``missing`` (notes of what is not produced yet).
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
        io.write_text_atomic(html, path)
        pages.append(path)

    contents = []
    for chapter in CHAPTERS:
        items = chapter_items(wh, chapter)
        for it in items:
            n_tables += it["kind"] == "table"
            n_comparison += it.get("mode") == "comparison"
            if it["note"] and "not produced yet" in it["note"]:
                missing.append(f"{chapter.slug}: {it['note']}")
        contents.append({"chapter": chapter, "items": items})
        write("chapter.html.j2", out / f"{chapter.slug}.html", title=chapter.title, chapter=chapter, items=items)

    selected = tables.select_runs(results, RUNS_PER_TYRE, MAX_RUN_PAGES)
    if not selected.empty:
        extra = [c for c in ("run_id", "sample_rate_Hz", "run_path", "file") if c in manifest.columns]
        selected = selected.merge(manifest[extra], on="run_id", how="left", suffixes=("", "_manifest"))
    run_dir = out / "runs"
    listed = []
    for _, row in selected.iterrows():
        name = run_page_name(row["run_id"])
        write("run.html.j2", run_dir / name, root="../", title=f"Run {row['run_id']}", run=run_item(wh, row))
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
    size = sum(p.stat().st_size for p in out.rglob("*") if p.is_file())
    return {"pages": pages, "bytes": size, "tables": n_tables, "comparison_tables": n_comparison, "missing": missing}
