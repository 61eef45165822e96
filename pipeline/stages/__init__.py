"""Pipeline stages: thin I/O around the pure computations.

What each stage reads and writes is declared in :data:`tyrelab.stages.dag.STAGES`;
:data:`ORDER`, the order ``tyrelab run`` executes them in, follows from those declarations. Each
stage is a module of this package with ``run(ctx) -> StageResult``; :func:`plan` says which
stages would run and why (``tyrelab run --explain``).
"""

from __future__ import annotations

import importlib
import time

from .. import progress
from .._hold import hold
from . import state
from .base import Context, StageResult
from .dag import ORDER, STAGES, upstream


def run_stage(name: str, ctx: Context) -> StageResult:
    """Run one stage by name unless it is up to date; log why it ran and its summary.

    The stage module is imported only when it has to run, so a no-op
    ``tyrelab run`` imports none of the heavy libraries.
    """
    stage = STAGES[name]
    prev = state.load(ctx.build, name)
    cache = state.HashCache(prev.get("hash_cache"))
    state.load_code_index(ctx.build)
    code = state.stage_fingerprint(stage)
    inputs = state.input_digests(ctx, stage, cache)
    reason = state.why_stale(ctx, stage, code, inputs, cache)
    if reason is None:
        state.save_code_index(ctx.build)
        result = StageResult(name, skipped=True, message="inputs unchanged", **prev.get("counts", {}))
        ctx.log.info("%s", result.summary())
        return result
    ctx.log.info("%s: recomputing (%s)", name, reason)
    if ctx.executor == "local" and int(ctx.jobs or 1) > 1:
        from ..executor import start_worker_server

        # Its imports run on the other core while this process works: a first build uses worker
        # pools in most stages; after one added run the report's figures are drawn by workers
        # forked from it (~2-3 s into the run, it is ready by then) while this process shapes tables.
        start_worker_server()
    module = importlib.import_module(f"{__name__}.{name}")
    ctx.stage = name
    try:
        hold(f"stage-{name}")  # a test's signal lands here: the stage must run and has not started
        result = module.run(ctx)
    finally:
        ctx.stage = None
        progress.close_all()  # a bar the stage left (an error, Ctrl-C) leaves the terminal
    counts = {"n_in": result.n_in, "n_ok": result.n_ok, "n_quarantined": result.n_quarantined,
              "n_rejected": result.n_rejected}
    state.record(ctx, stage, code, inputs, cache, counts)
    state.save_code_index(ctx.build)
    ctx.log.info("%s", result.summary())
    return result


def run_pipeline(ctx: Context, stages: list[str] | None = None) -> list[StageResult]:
    """Run ``stages`` (default: every stage of :data:`ORDER`, in order).

    With ``--jobs`` above 1 (the worker server was started when the first stage ran, see
    :func:`run_stage`), a later stage that declares work it can start ahead (``Stage.ahead``: work
    whose inputs are raw-side, there before the stages it runs after) is started on workers (its module's ``start_ahead(ctx)``) once the stages that spread work over
    worker pools (``Stage.pools``) are done and the server is ready, so that it runs while the stages
    between keep one core busy; the stage takes the results, and work no stage took is ended at the
    end (``abandon_ahead()``).
    """
    t0 = time.perf_counter()
    names = list(stages or ORDER)
    results, ahead = [], {}
    try:
        for i, name in enumerate(names):
            # after the stages with worker pools, whose pools would share the cores with the work started
            # ahead (measured: the studies started before analyse, the full campaign's first run took 2 s longer)
            if not STAGES[name].pools and _worker_server_ready():
                for later in names[i:]:
                    if STAGES[later].ahead and later not in ahead:
                        ahead[later] = importlib.import_module(STAGES[later].module)
                        ahead[later].start_ahead(ctx)
            results.append(run_stage(name, ctx))
    finally:
        for module in ahead.values():
            module.abandon_ahead()
    ran = [r.name for r in results if not r.skipped]
    ctx.log.info("recomputed: %s", ", ".join(ran) if ran else "nothing (every stage up to date)")
    ingest = next((r for r in results if r.name == "ingest"), None)
    analyse = next((r for r in results if r.name == "analyse"), None)
    quarantined = sum(r.n_quarantined for r in results)
    analysed = analyse.n_in - analyse.n_quarantined if analyse else None
    ctx.log.info(
        "summary: %s runs in, %s runs analysed (%s passed QC), %d runs quarantined, %.1f s",
        ingest.n_in if ingest else "-",
        analysed if analysed is not None else "-",
        _passed_qc(ctx),
        quarantined,
        time.perf_counter() - t0,
    )
    return results


def plan(ctx: Context, stages: list[str] | None = None) -> list[tuple[str, str | None]]:
    """Which of ``stages`` (default :data:`ORDER`) ``tyrelab run`` would run, and why; runs nothing.

    Returns ``(stage, reason)`` pairs in run order: ``reason`` is None for a stage that is up to date
    and stays so. A stage that is up to date now but reads what an earlier stage of the plan will
    rewrite is listed with the reason "after <stages>, if they change its inputs" (it is decided
    once they ran, as ``make`` does).
    """
    out: list[tuple[str, str | None]] = []
    running: set[str] = set()
    state.load_code_index(ctx.build)
    for name in stages or ORDER:
        stage = STAGES[name]
        cache = state.HashCache(state.load(ctx.build, name).get("hash_cache"))
        reason = state.why_stale(ctx, stage, state.stage_fingerprint(stage), state.input_digests(ctx, stage, cache),
                                 cache)
        before = sorted(upstream(name) & running, key=ORDER.index)
        if reason is None and before:
            reason = f"after {', '.join(before)}, if they change its inputs"
        if reason is not None:
            running.add(name)
        out.append((name, reason))
    return out


def explain(ctx: Context, stages: list[str] | None = None) -> str:
    """:func:`plan` as text, one stage a line, then the stage graph (:func:`tyrelab.stages.dag.graph_text`).

    Under a stage that will run, its items (``Stage.items``: what each is computed again from), and
    what its module's ``item_plan(ctx)`` says of them, if it has one (the ride scenarios and tables of
    ``simulate``: kept or to compute), on its inputs as they are now: when stages it reads from run
    before it, the line says so (they may change those inputs)."""
    from .dag import graph_text

    lines, running = [], set()
    for name, reason in plan(ctx, stages):
        lines.append(f"{name:<10} {'runs: ' + reason if reason else 'up to date: skipped'}")
        if reason is None:
            continue
        lines.extend(f"{'':<10}   item {item}" for item in STAGES[name].items)
        waits = sorted(upstream(name) & running, key=ORDER.index)
        running.add(name)
        module = importlib.import_module(STAGES[name].module) if _has_item_plan(STAGES[name]) else None
        if module is not None:  # on its inputs as they are now (before the stages it reads from run, if any)
            when = f"now, before {', '.join(waits)} run" if waits else "now"
            lines.extend(f"{'':<10}   {when}: {line}" for line in module.item_plan(ctx))
    return "\n".join(["plan:", *lines, "", "stage graph (tyrelab.stages.dag.STAGES):", graph_text()])


def _has_item_plan(stage) -> bool:
    """Whether the stage's module defines ``item_plan`` (read from its source: nothing imported)."""
    import ast

    path = state._module_file(stage.module)
    if path is None:
        return False
    tree = ast.parse(path.read_bytes())
    return any(isinstance(node, ast.FunctionDef) and node.name == "item_plan" for node in tree.body)


def _worker_server_ready() -> bool:
    """Whether this process started a worker server that is ready, without importing anything heavy."""
    import sys

    executor = sys.modules.get(f"{__package__.rsplit('.', 1)[0]}.executor")
    return executor is not None and executor.worker_server_state() == "ready"


def _passed_qc(ctx: Context) -> int | str:
    """Runs with ``qc_ok`` in the final ``results`` (after calibrate's flags).

    The count is kept in ``build/state/passed_qc.json`` with the size, mtime and inode of the
    ``results`` file it was counted from, so a no-op run does not import pyarrow to recount.
    """
    import json

    from .. import io

    path = ctx.table("results")
    try:
        st = path.stat()
    except FileNotFoundError:
        return "-"
    key = [st.st_size, st.st_mtime_ns, st.st_ino]
    memo = ctx.state / "passed_qc.json"
    try:
        kept = json.loads(memo.read_text())
        if kept.get("results") == key:
            return kept["passed_qc"]
    except (OSError, ValueError, AttributeError, KeyError):
        pass
    import pyarrow.parquet as pq

    schema = pq.read_schema(path)
    n = "-" if "qc_ok" not in schema.names else int(
        pq.read_table(path, columns=["qc_ok"]).column("qc_ok").to_numpy(zero_copy_only=False).sum())
    if ctx.state.is_dir():
        io.write_text_atomic(json.dumps({"results": key, "passed_qc": n}), memo)
    return n


__all__ = ["Context", "StageResult", "ORDER", "STAGES", "run_stage", "run_pipeline", "plan", "explain"]
