"""Report: render the static site ``build/reports/`` from the warehouse (read-only).

All the work is in :mod:`tyrelab.report.site`; this stage only times it and
summarises what was written. Figures are kept in ``build/cache/report`` by the
digest of their inputs (:class:`tyrelab.stages.state.ItemCache`), so a new run
redraws only the figures whose data changed; the rest are drawn by this process and
``--jobs`` - 1 worker processes.
"""

from __future__ import annotations

import time

from ..report.site import build_site
from .base import Context, StageResult
from .state import ItemCache

__all__ = ["run"]


def run(ctx: Context) -> StageResult:
    """Render every report page into ``build/reports``."""
    t0 = time.perf_counter()
    out = ctx.path("reports/")
    cache = ItemCache(ctx, "report")
    info = build_site(ctx.path("warehouse.duckdb"), out, ctx.raw, cache=cache, jobs=ctx.jobs)
    cache.prune()
    for note in info["missing"]:
        ctx.log.info("report: %s", note)
    n = len(info["pages"])
    return StageResult(
        "report", n_in=info["tables"], n_ok=n, seconds=time.perf_counter() - t0,
        message=f"{n} pages, {info['comparison_tables']} thesis comparisons, {info['figures']} figures "
                f"({info['drawn']} drawn, the others unchanged), tables {cache.summary('table')}, "
                f"{info['bytes'] / 1e6:.2f} MB in {out}",
    )
