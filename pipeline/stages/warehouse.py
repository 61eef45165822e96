"""Warehouse: publish the thesis tables and (re)build ``build/warehouse.duckdb``.

Each ``raw/published/<stem>.csv`` is validated against
``schemas/published/<stem>.json`` and converted to
``build/parquet/published/<stem>.parquet``; the warehouse then gets a view
per Parquet table (``results``, ``table_iii`` ...), ``runs`` over the per-run
dataset, and ``published_<stem>`` per thesis table.
"""

from __future__ import annotations

import time
from pathlib import Path

import pandas as pd

from .. import io
from ..schema import SCHEMA_DIR, load_schema, validate_frame
from ..warehouse import build_warehouse, view_name
from .base import Context, StageResult

#: Digitised thesis tables shipped with tyrelab.
PUBLISHED_DIR = Path(__file__).resolve().parents[2] / "raw" / "published"


def published_tables(ctx: Context) -> dict[str, Path]:
    """Validate and convert the published CSVs; return view name -> Parquet path.

    Uses ``<raw>/published`` if it exists, else the tables shipped with tyrelab.
    """
    src_dir = ctx.raw / "published" if (ctx.raw / "published").is_dir() else PUBLISHED_DIR
    out: dict[str, Path] = {}
    for csv in sorted(src_dir.glob("*.csv")):
        df = pd.read_csv(csv, keep_default_na=False, na_values=[""])
        schema_file = SCHEMA_DIR / "published" / f"{csv.stem}.json"
        if schema_file.exists():
            for problem in validate_frame(df, load_schema(f"published/{csv.stem}")):
                ctx.log.error("%s: %s", csv, problem)
        target = ctx.parquet / "published" / f"{csv.stem}.parquet"
        io.write_parquet_atomic(df, target)
        out[f"published_{view_name(csv.stem)}"] = target
    return out


def run(ctx: Context) -> StageResult:
    """Rebuild the warehouse atomically."""
    t0 = time.perf_counter()
    views = build_warehouse(ctx.build / "warehouse.duckdb", ctx.parquet, published_tables(ctx))
    return StageResult("warehouse", n_in=len(views), n_ok=len(views), seconds=time.perf_counter() - t0,
                       message=f"{len(views)} views in {ctx.build / 'warehouse.duckdb'}")
