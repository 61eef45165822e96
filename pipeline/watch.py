"""``tyrelab watch``: keep the pipeline loaded and rebuild whenever the raw folder changes.

A test lab copies the day's recordings into the raw folder while the rig runs and wants
the tables and the report updated within seconds. A fresh ``tyrelab run`` first spends
about 2.4 s of CPU importing its libraries (pandas, pyarrow, scipy, statsmodels, DuckDB,
matplotlib; see docs/benchmarks.md) before the incremental stages do the work of the new
run. ``watch`` pays those imports once: it polls the raw folder and, when its files have
changed and then stayed unchanged for ``settle_s`` (a copy in progress is not half read),
runs the stages in the same process. What each stage recomputes is decided by the
stages' fingerprints exactly as in ``tyrelab run``, so the outputs are the bytes a
``tyrelab run`` would write.

The raw folder is compared by :func:`tyrelab.stages.state.raw_digest` (path, size and
modification time of every regular file below it, the build folder excluded): cheap enough
to poll every second. Restart ``watch`` after upgrading tyrelab: the running process keeps
the code it loaded.

Times are seconds (``_s``).
"""

from __future__ import annotations

import dataclasses
import logging
import time
from dataclasses import dataclass, field
from typing import Callable

__all__ = ["WatchOptions", "WatchRun", "watch", "preload", "MAX_WAIT_S", "MAX_RUNS"]

log = logging.getLogger("tyrelab")


@dataclass(frozen=True)
class WatchOptions:
    """How :func:`watch` polls.

    Attributes
    ----------
    interval_s : float
        Seconds between two looks at the raw folder (> 0).
    settle_s : float
        A change is acted on once the raw folder has stayed unchanged this long (>= 0).
    max_runs : int or None
        Stop after this many pipeline runs (None: until interrupted).

    Examples
    --------
    >>> WatchOptions(interval_s=0.5).settle_s
    1.0
    >>> WatchOptions(interval_s=0)
    Traceback (most recent call last):
    ...
    ValueError: interval_s must be a finite number > 0, got 0
    """

    interval_s: float = 1.0
    settle_s: float = 1.0
    max_runs: int | None = None

    def __post_init__(self):
        from ._validate import finite, shown

        def number(v) -> bool:  # a finite real number, not a bool (True is no second), not 10**400
            try:
                return isinstance(v, (int, float)) and finite("v", v) is not None
            except ValueError:
                return False

        if not (number(self.interval_s) and self.interval_s > 0):
            raise ValueError(f"interval_s must be a finite number > 0, got {shown(self.interval_s)}")
        if not (number(self.settle_s) and self.settle_s >= 0):
            raise ValueError(f"settle_s must be a finite number >= 0, got {shown(self.settle_s)}")
        for name in ("interval_s", "settle_s"):
            if getattr(self, name) > MAX_WAIT_S:
                raise ValueError(f"{name} must be at most {MAX_WAIT_S:g} s (a day), got {getattr(self, name):g}")
        if self.max_runs is not None and not (isinstance(self.max_runs, int) and not isinstance(self.max_runs, bool)
                                              and self.max_runs >= 1):
            raise ValueError(f"max_runs must be a whole number >= 1 or None, got {shown(self.max_runs)}")
        if self.max_runs is not None and self.max_runs > MAX_RUNS:
            raise ValueError(f"max_runs must be at most {MAX_RUNS}, got {shown(self.max_runs)}")


#: Longest ``interval_s`` or ``settle_s``, s: a day (a documented choice: a rarer look is a cron job's,
#: and ``time.sleep`` refuses what a C timeout cannot hold).
MAX_WAIT_S = 86_400.0
#: Most pipeline runs ``max_runs`` may ask for (a documented choice: a run a second for 30 years).
MAX_RUNS = 10**9


@dataclass
class WatchRun:
    """One pipeline run started by :func:`watch`.

    Attributes
    ----------
    seconds : float
        Wall time of the run, s.
    recomputed : list of str
        Stages that ran (the others were up to date).
    quarantined : bool
        Some runs, a manifest or a catalogue were quarantined or rejected.
    error : str
        One line if the run stopped on an input or OS error (the watch goes on), else "".
    """

    seconds: float
    recomputed: list[str] = field(default_factory=list)
    quarantined: bool = False
    error: str = ""


def watch(ctx, options: WatchOptions | None = None, *, run: Callable | None = None,
          sleep: Callable[[float], None] = time.sleep, clock: Callable[[], float] = time.monotonic) -> list[WatchRun]:
    """Run the pipeline now and again after every settled change of ``ctx.raw``.

    Parameters
    ----------
    ctx : tyrelab.stages.Context
        The raw and build folders and options, as for ``tyrelab run``.
    options : WatchOptions, optional
        Polling interval, settling time, number of runs.
    run : callable, optional
        ``run(ctx) -> list of StageResult`` (default :func:`tyrelab.stages.run_pipeline`).
    sleep, clock : callable, optional
        Waiting and the monotonic clock (tests pass their own).

    Returns
    -------
    list of WatchRun
        The runs made, when ``options.max_runs`` is reached (otherwise the function
        returns only by an exception such as ``KeyboardInterrupt``).
    """
    from .io import raw_problem
    from .published import PublishedTableError
    from .stages import run_pipeline
    from .stages.state import raw_digest

    options = options or WatchOptions()
    run = run or run_pipeline
    runs: list[WatchRun] = []
    done = None  # raw digest the last run started from
    pending, since = None, 0.0  # digest seen changed, and when it was first seen
    log.info("watch: %s -> %s, looking every %g s (Ctrl-C to stop)", ctx.raw, ctx.build, options.interval_s)
    while options.max_runs is None or len(runs) < options.max_runs:
        now = raw_digest(ctx.raw, exclude=ctx.build)
        if now != done:
            if now != pending:
                pending, since = now, clock()
            if done is None or clock() - since >= options.settle_s:
                first, done = done is None, now
                problem = raw_problem(ctx.raw)
                if problem:  # vanished or emptied: keep the build, never replace it with an empty one
                    log.error("tyrelab watch: %s; the build is kept as it is (waiting for the next change)", problem)
                    runs.append(WatchRun(seconds=0.0, error=problem))
                    continue
                if not first:
                    log.info("watch: the raw folder changed; running")
                runs.append(_one_run(ctx, run, PublishedTableError))
                if len(runs) == 1:
                    preload()
                    if ctx.executor == "local" and int(ctx.jobs or 1) > 1:
                        from .executor import start_worker_server

                        start_worker_server()  # later pools (a day of runs at once) fork at once
                if ctx.force:  # --force is for the first run; later runs recompute what changed
                    ctx = dataclasses.replace(ctx, force=False)
                continue  # look again at once: files may have arrived during the run
        sleep(options.interval_s)
    return runs


def preload() -> list[str]:
    """Import every stage module (and so the libraries each uses); return their names.

    :func:`watch` calls it after its first run, which may have been a no-op that
    imported nothing, so that the first change it sees pays no imports.
    """
    import importlib

    from .stages import ORDER

    for name in ORDER:
        importlib.import_module(f"{__package__}.stages.{name}")
    return list(ORDER)


def _one_run(ctx, run, input_errors) -> WatchRun:
    """One pipeline run; an OS or input error is one line and the watch goes on."""
    from .io import os_error_line

    t0 = time.perf_counter()
    try:
        results = run(ctx)
    except OSError as exc:
        line = os_error_line(exc)
    except input_errors as exc:
        line = str(exc).splitlines()[0]
    else:
        return WatchRun(seconds=time.perf_counter() - t0, recomputed=[r.name for r in results if not r.skipped],
                        quarantined=any(r.n_quarantined or r.n_rejected for r in results))
    log.error("tyrelab watch: %s (waiting for the next change)", line)
    return WatchRun(seconds=time.perf_counter() - t0, error=line)
