"""Warehouse: publish the thesis tables and (re)build ``build/warehouse.duckdb``.

Each ``raw/published/<stem>.csv`` is validated against
``schemas/published/<stem>.json`` and converted to
``build/parquet/published/<stem>.parquet``; the warehouse then stores a table
per Parquet table (``results``, ``table_iii`` ...) and ``published_<stem>`` per
thesis table, and gets the view ``runs`` over the per-run dataset, relative to
the build folder (:mod:`tyrelab.warehouse`: portable).

It also publishes ``quarantine.parquet``: the union of the rows each stage quarantined, which
each stage writes to its own part (:func:`tyrelab.stages.base.quarantine_table`), so every table
has one writer.
"""

from __future__ import annotations

import time
from pathlib import Path

from .. import io, published
from ..warehouse import build_warehouse, view_name
from .base import Context, Progress, StageResult, quarantine_table

__all__ = ["published_tables", "run"]


def published_tables(ctx: Context) -> dict[str, Path]:
    """Convert the published thesis tables to Parquet; return view name -> Parquet path."""
    out: dict[str, Path] = {}
    for stem in published.stems(ctx.raw):
        df = published.read_published(stem, ctx.raw, strict=False)
        target = ctx.path(f"parquet/published/{stem}.parquet")
        io.write_parquet_atomic(df, target)
        out[f"published_{view_name(stem)}"] = target
    return out


def run(ctx: Context) -> StageResult:
    """Rebuild the warehouse atomically."""
    t0 = time.perf_counter()
    ctx.write_table("quarantine", quarantine_table(ctx))
    bar: list[Progress] = []  # made at the first table, when the number of tables is known

    def on_table(done: int, total: int) -> None:
        if not bar:
            bar.append(Progress("warehouse", total, logger=ctx.log, unit="tables"))
        bar[0].step()

    views = build_warehouse(ctx.path("warehouse.duckdb"), ctx.parquet, published_tables(ctx), on_table=on_table)
    for b in bar:
        b.close()
    return StageResult("warehouse", n_in=len(views), n_ok=len(views), seconds=time.perf_counter() - t0,
                       message=f"{len(views)} tables and views in {ctx.build / 'warehouse.duckdb'}")
