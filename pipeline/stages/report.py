"""Report: render ``build/reports/index.html`` from the warehouse (read-only)."""

from __future__ import annotations

import json
import time

import pandas as pd

from .. import io
from ..report.render import environment, provenance
from ..warehouse import query
from .base import Context, StageResult

#: Relative tolerance beyond which an "ours vs thesis" cell is highlighted.
REL_TOL = 0.05
#: Absolute floors of the tolerance by column keyword (thesis' own precision, e.g. K_c ± 8 kN/m).
ABS_TOL = {"stiffness": 8.0, "dependence": 8.0, "r_squared": 0.02}


def comparison_table(df: pd.DataFrame, caption: str, text_columns: tuple[str, ...] = ("tyre_id", "condition", "size")) -> dict:
    """Rows, labelled columns and highlighted cells for a thesis-vs-ours table.

    Every ``thesis_<x>`` column is paired with ``<x>``; a ``<x>`` cell is
    highlighted when it differs from the thesis value by more than
    ``max(REL_TOL * |thesis|, ABS_TOL[keyword])``.
    """
    rows = df.to_dict(orient="records")
    for i, r in enumerate(rows):
        r["_row"] = i
    columns = [(c, c.replace("_", " "), c in text_columns or df[c].dtype == object) for c in df.columns]
    off = set()
    for c in df.columns:
        if c.startswith("thesis_") and c[len("thesis_"):] in df.columns:
            ours = c[len("thesis_"):]
            floor = next((v for k, v in ABS_TOL.items() if k in ours), 0.0)
            for i, r in enumerate(rows):
                t, o = r.get(c), r.get(ours)
                if pd.notna(t) and pd.notna(o) and abs(o - t) > max(REL_TOL * abs(t), floor):
                    off.add((i, ours))
    return {"rows": rows, "columns": columns, "caption": caption, "off": off}


def _campaign_seeds(manifest: pd.DataFrame) -> tuple[list[str], list[str]]:
    campaigns = sorted(manifest["campaign"].unique()) if "campaign" in manifest else []
    seeds = []
    for c in campaigns:
        meta = __import__("pathlib").Path(c) / "generator.json"
        if meta.exists():
            seeds.append(str(json.loads(meta.read_text()).get("seed")))
    return campaigns, seeds


def run(ctx: Context) -> StageResult:
    """Render the report pages."""
    t0 = time.perf_counter()
    db = ctx.build / "warehouse.duckdb"
    tables = set(query(db, "SELECT table_name FROM information_schema.tables")["table_name"])

    def table(name: str) -> pd.DataFrame:
        return query(db, f'SELECT * FROM "{name}"') if name in tables else pd.DataFrame()

    manifest, results, quarantine = table("manifest"), table("results"), table("quarantine")
    campaigns, seeds = _campaign_seeds(manifest)
    summary = {
        "runs": len(manifest),
        "tyres": manifest["tyre_id"].nunique() if len(manifest) else 0,
        "analysed": len(results),
        "flagged": int((~results["qc_ok"]).sum()) if len(results) else 0,
        "quarantined": int(quarantine["run_id"].notna().sum()) if len(quarantine) else 0,
    }
    t3 = table("table_iii")
    env = environment()
    html = env.get_template("index.html.j2").render(
        title="tyrelab report",
        summary=summary,
        quarantine=quarantine.to_dict(orient="records"),
        table_iii=comparison_table(t3, "Table III (kN/m, kN/m per bar)") if len(t3) else None,
        prov=provenance(ctx.raw, campaigns, seeds),
    )
    out = ctx.build / "reports" / "index.html"
    io.write_text_atomic(html, out)
    return StageResult("report", n_in=1, n_ok=1, seconds=time.perf_counter() - t0, message=str(out))
