"""Methods: thesis Table I, the measurement methods compared (§3.4; issue 34).

When the campaign's ``results`` hold, for one tyre and condition, stepped-sine runs and runs of
another method (swept sine or random, free vibration, load deflection), Table I is computed from
those recordings (:func:`tyrelab.measurement.methods.table_i_from_results`); otherwise from
virtual experiments on the truth-model tyre (:func:`tyrelab.rig.experiments.table_i`), as before.
The ``source`` column says which. The virtual table is kept in ``build/cache/methods`` under the
digest of the published table (:class:`tyrelab.stages.state.ItemCache`).
"""

from __future__ import annotations

import time

from .. import published
from ..measurement.methods import table_i_from_results
from ..rig.experiments import table_i
from .base import Context, StageResult
from .state import ItemCache

__all__ = ["run"]


def run(ctx: Context) -> StageResult:
    """Compute Table I (module docstring) and write ``table_i``."""
    t0 = time.perf_counter()
    cache = ItemCache(ctx, "methods")
    thesis = published.read_published("table_i", ctx.raw)
    results = ctx.read_table("results") if ctx.has_table("results") else None
    table = table_i_from_results(results, thesis) if results is not None else None
    origin = "recordings"
    if table is None:
        table = cache.get_or_compute(cache.key("table_i", thesis), lambda: table_i(thesis))
        origin = "virtual experiments"
    ctx.write_table("table_i", table)
    cache.prune()
    return StageResult("methods", n_in=len(thesis), n_ok=len(table), seconds=time.perf_counter() - t0,
                       message=f"Table I: {len(table)} methods from {origin}, {cache.summary()}")
