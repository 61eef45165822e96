"""Methods: thesis Table I, the measurement methods compared on virtual experiments (§3.4).

Reads only the published Table I (``published``) and writes ``table_i``: the four methods of
:mod:`tyrelab.measurement.methods` applied to virtual experiments on the truth-model tyre
(:func:`tyrelab.rig.experiments.table_i`), beside the thesis. Nothing of the campaign is read,
so a new recording never re-runs it; the result is kept in ``build/cache/methods`` under the
digest of the published table (:class:`tyrelab.stages.state.ItemCache`).
"""

from __future__ import annotations

import time

from .. import published
from ..rig.experiments import table_i
from .base import Context, StageResult
from .state import ItemCache

__all__ = ["run"]


def run(ctx: Context) -> StageResult:
    """Compute Table I (module docstring) and write ``table_i``."""
    t0 = time.perf_counter()
    cache = ItemCache(ctx, "methods")
    thesis = published.read_published("table_i", ctx.raw)
    table = cache.get_or_compute(cache.key("table_i", thesis), lambda: table_i(thesis))
    ctx.write_table("table_i", table)
    cache.prune()
    return StageResult("methods", n_in=len(thesis), n_ok=len(table), seconds=time.perf_counter() - t0,
                       message=f"Table I: {len(table)} methods, {cache.summary()}")
