"""Pipeline stages: thin I/O around the pure computations.

:data:`ORDER` lists the stages ``tyrelab run`` executes, in order; each is a
module of this package with ``run(ctx) -> StageResult``.
"""

from __future__ import annotations

import importlib
import time

from .base import Context, StageResult

ORDER = ["ingest", "analyse", "calibrate", "regress", "simulate", "warehouse", "report"]


def available() -> list[str]:
    """Stages of :data:`ORDER` that are installed."""
    names = []
    for name in ORDER:
        try:
            importlib.import_module(f"{__name__}.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
            continue
        names.append(name)
    return names


def run_stage(name: str, ctx: Context) -> StageResult:
    """Run one stage by name and log its one-line summary."""
    module = importlib.import_module(f"{__name__}.{name}")
    ctx.log.info("%s: starting", name)
    result = module.run(ctx)
    ctx.log.info("%s", result.summary())
    return result


def run_pipeline(ctx: Context, stages: list[str] | None = None) -> list[StageResult]:
    """Run ``stages`` (default: every available stage in order)."""
    t0 = time.perf_counter()
    results = [run_stage(name, ctx) for name in (stages or available())]
    ingest = next((r for r in results if r.name == "ingest"), None)
    analyse = next((r for r in results if r.name == "analyse"), None)
    quarantined = sum(r.n_quarantined for r in results)
    ctx.log.info(
        "summary: %s runs in, %s runs analysed, %d runs quarantined, %.1f s",
        ingest.n_in if ingest else "-",
        analyse.n_ok if analyse else "-",
        quarantined,
        time.perf_counter() - t0,
    )
    return results


__all__ = ["Context", "StageResult", "ORDER", "available", "run_stage", "run_pipeline"]
