"""Where the per-run work of a stage runs: in-process, a local process pool, or Dask.

Stages hand :func:`map_batches` a module-level function and a list of small,
picklable batches (file paths and manifest values, never loaded signals); the
function reads its inputs, computes, and returns a small result (or writes one
file atomically). Results come back in the order of ``batches`` whichever
executor ran them, so the outputs are byte-identical for ``--executor local``
with any ``--jobs`` and for ``--executor dask``.

``local`` uses a :class:`concurrent.futures.ProcessPoolExecutor` with the
``forkserver`` start method (forking a process whose pyarrow thread pool is
running can deadlock); ``jobs=1`` or a single batch runs in-process.
``dask`` connects a :class:`dask.distributed.Client` to ``ctx.scheduler`` (a
scheduler address such as ``tcp://10.0.0.5:8786``), or, without an address,
starts a local cluster of ``ctx.jobs`` worker processes. Dask is imported
only when used, so ``tyrelab run`` starts quickly.
"""

from __future__ import annotations

import errno
import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor
from typing import Any, Callable, Sequence

from .io import MissingExtra

__all__ = ["EXECUTORS", "BLAS_THREAD_VARIABLES", "WORKER_PRELOAD", "map_batches", "map_alongside", "map_in_background", "Background",
           "single_threaded_blas", "command_gc", "GC_THRESHOLDS", "start_worker_server", "worker_server_state", "worker_pool", "abandon_pool"]

EXECUTORS = ("local", "dask")

#: Environment variables that size the BLAS/OpenMP thread pools of numpy and scipy.
BLAS_THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


def single_threaded_blas() -> None:
    """Default the BLAS/OpenMP thread pools to one thread, unless the user set their size.

    The pipeline's linear algebra is on small matrices (the simulators' 4- to 8-state
    systems, per-run least squares), where OpenBLAS's extra threads only spin: measured on
    the small demo campaign (2 cores), the simulate stage took 16.9 s wall and 22 s CPU with
    the default pool and 14.7 s wall and CPU with one thread; with ``--jobs 2`` 17.5 s
    against 11.8 s, the pools of two workers fighting over two cores. Parallelism comes from
    ``--jobs`` (worker processes) instead. Takes effect for numpy imported after the call,
    in this process and in every worker it starts (they inherit the environment); the
    ``tyrelab`` command calls it first thing.

    Examples
    --------
    >>> import os
    >>> single_threaded_blas()
    >>> all(os.environ[v] for v in BLAS_THREAD_VARIABLES)
    True
    """
    for var in BLAS_THREAD_VARIABLES:
        os.environ.setdefault(var, "1")


#: Thresholds of the cyclic garbage collector in a command's process (:func:`command_gc`).
GC_THRESHOLDS = (10_000, 10, 10)


def command_gc() -> None:
    """Tune the cyclic garbage collector for a short-lived process that imports large libraries.

    Its youngest generation is collected every 10,000 allocations instead of 700
    (:data:`GC_THRESHOLDS`): the full collections that importing pandas, scipy,
    statsmodels and matplotlib triggers took 0.13 s of a 3.4 s ``tyrelab run`` after one
    added run, and none are left. And the objects still alive when the process ends are
    moved out of the collector's sight (:func:`gc.freeze`, from an ``atexit`` handler):
    the interpreter's shutdown otherwise runs full collections over every object of those
    libraries (0.35 s). Memory is still freed by reference counting as before; everything
    a command writes is closed and synced before it returns, and the other ``atexit``
    handlers and the module teardown still run. The ``tyrelab`` command calls it when run
    from the command line (not when a test calls :func:`tyrelab.cli.main` in its process).
    """
    import atexit
    import gc

    gc.set_threshold(*GC_THRESHOLDS)
    atexit.unregister(gc.freeze)
    atexit.register(gc.freeze)


def map_batches(
    fn: Callable[[Any], Any], batches: Sequence[Any], ctx, on_done: Callable[[int], None] | None = None,
    alongside: bool = False,
) -> list[Any]:
    """Apply ``fn`` to every batch; return the results in the order of ``batches``.

    Parameters
    ----------
    fn : callable
        A module-level (picklable) function of one batch. It may write files
        (it is never assumed pure: Dask tasks are submitted with ``pure=False``).
    batches : sequence
        Picklable work items (paths and scalars, not loaded data).
    ctx : tyrelab.stages.base.Context
        Supplies ``executor`` (``"local"`` or ``"dask"``), ``jobs`` and ``scheduler``.
    on_done : callable, optional
        Called with a batch's index as soon as that batch has finished (for progress).
    alongside : bool, optional
        With ``executor="local"``, this process works too, beside ``jobs - 1`` workers asked
        for once the worker server is ready (:func:`map_alongside`): for many small batches
        (run conversions, analysis batches), so that a first run never waits for the
        server's imports. Not for a few long batches (the caller would take one of them
        before the workers start).

    Returns
    -------
    list
        ``[fn(b) for b in batches]``.

    Raises
    ------
    ValueError
        For an unknown executor name.
    """
    batches = list(batches)
    done = on_done or (lambda i: None)
    if not batches:
        return []
    if ctx.executor == "dask":
        return _map_dask(fn, batches, ctx, done)
    if ctx.executor != "local":
        raise ValueError(f"unknown executor {ctx.executor!r} (expected one of {', '.join(EXECUTORS)})")
    jobs = max(1, min(int(ctx.jobs or 1), len(batches)))
    if alongside:
        return map_alongside(fn, batches, jobs, on_done=on_done)
    if jobs == 1:
        return _in_process(fn, batches, done)
    results = []
    pool = worker_pool(jobs)
    try:
        for i, r in enumerate(pool.map(fn, batches, chunksize=1)):
            results.append(r)
            done(i)
    except BaseException:
        abandon_pool(pool)
        raise
    pool.shutdown(wait=True)
    return results


#: Modules of the functions the stages hand to :func:`map_batches` (and so the libraries their
#: workers use). The worker server imports them once, when it starts, and every worker is forked
#: from it with them loaded: without this each worker of each stage imported pandas, pyarrow,
#: scipy or matplotlib itself (0.5-1.5 s of CPU per worker and stage) before its first batch.
#: The last one only tells the parent that the others are imported.
WORKER_PRELOAD = ("tyrelab.stages.ingest", "tyrelab.stages.analyse", "tyrelab.stages.simulate",
                  "tyrelab.vehicle.ride", "tyrelab.report.site", "tyrelab.report.figures", "tyrelab._worker_ready")
#: Environment variable naming the file :mod:`tyrelab._worker_ready` creates in the server.
READY_VARIABLE = "TYRELAB_WORKER_SERVER_READY"
#: Longest wait for the server's imports, s (then the pool starts anyway).
READY_TIMEOUT_S = 300.0


#: Path of the marker file of a worker server started but not yet seen ready, else None.
_ready_marker: str | None = None


def _in_process(fn: Callable[[Any], Any], batches: list[Any], done: Callable[[int], None]) -> list[Any]:
    """``[fn(b) for b in batches]`` in this process, ``done(i)`` after each."""
    results = []
    for i, b in enumerate(batches):
        results.append(fn(b))
        done(i)
    return results


def _server_pid() -> int | None:
    """Pid of this process's forkserver, or None if it has not started one."""
    from multiprocessing import forkserver

    return getattr(getattr(forkserver, "_forkserver", None), "_forkserver_pid", None)


def worker_pool(workers: int) -> ProcessPoolExecutor:
    """A pool of ``workers`` processes forked from the worker server (started and waited for if
    needed, :func:`start_worker_server`), ignoring SIGINT; end it with :func:`abandon_pool` on an
    error or interrupt."""
    return ProcessPoolExecutor(max_workers=workers, mp_context=_worker_context(),
                               initializer=_leave_interrupts_to_the_parent)


def start_worker_server() -> None:
    """Start the worker server now, without waiting for its imports (idempotent).

    Its imports (:data:`WORKER_PRELOAD`) then run on another core while the caller goes on;
    the first pool waits for them. ``tyrelab run`` calls it when the first stage that is
    not up to date runs, with ``--jobs`` above 1, before importing the stage: a first run
    uses worker pools in most stages, and a run after a small change hands the report's
    figures to workers (:func:`map_in_background`) once it is ready. The server is started with SIGINT
    ignored: a terminal's Ctrl-C reaches the whole process group, and the server must not
    print a traceback from the middle of an import.
    """
    global _ready_marker
    from multiprocessing import forkserver, util

    if getattr(forkserver, "_forkserver", None) is None or _server_pid() is not None:
        return  # running (or started by someone else, with their own preload)
    import signal
    import threading

    multiprocessing.get_context("forkserver").set_forkserver_preload(list(WORKER_PRELOAD))
    # in the process's own pymp-* folder, which multiprocessing removes at exit: a server that
    # finishes its imports after an interrupted parent has gone finds no folder to write into
    ready = os.path.join(util.get_temp_dir(), f"worker-server-ready-{os.getpid()}")
    main = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
    os.environ[READY_VARIABLE] = ready
    try:
        forkserver.ensure_running()
    finally:
        del os.environ[READY_VARIABLE]
        if main:
            signal.signal(signal.SIGINT, previous)
    _ready_marker = ready


def _worker_context():
    """The ``forkserver`` context, its server running with :data:`WORKER_PRELOAD` imported.

    Starts the server (:func:`start_worker_server`) if needed and waits until its imports
    are done before asking it for workers: a pool abandoned (Ctrl-C, SIGTERM) while its
    workers were still queued behind the imports left workers that failed to start, each
    printing a traceback. An interrupt during the wait stops the parent before any worker
    was asked for.
    """
    global _ready_marker
    import time

    start_worker_server()
    deadline = time.monotonic() + READY_TIMEOUT_S
    try:  # a server that died is "ready": the pool starts another and says why
        while worker_server_state() == "starting" and time.monotonic() < deadline:
            time.sleep(0.005)
    finally:
        ready, _ready_marker = _ready_marker, None  # waited once: not again after a death or a timeout
        if ready is not None and os.path.exists(ready):
            os.unlink(ready)
    return multiprocessing.get_context("forkserver")


def _exited(pid: int) -> bool:
    """Whether child ``pid`` has ended, without reaping it (multiprocessing reaps its server itself)."""
    try:
        return os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None
    except (ChildProcessError, AttributeError):  # not our child, or no waitid on this system
        return False


def _leave_interrupts_to_the_parent() -> None:
    """Worker initializer: ignore SIGINT.

    Ctrl-C in a terminal signals the whole process group; the parent turns it into one
    line and exit 130 and ends the workers itself (:func:`abandon_pool`), so a worker must
    not print its own ``KeyboardInterrupt`` traceback.
    """
    import signal

    from ._hold import hold

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    from .progress import say_library_warnings_once

    say_library_warnings_once()  # a worker's library warnings in our words, once each, as the parent's
    hold("worker")  # a test's Ctrl-C to the process group lands here: a worker started, SIGINT ignored


def abandon_pool(pool: ProcessPoolExecutor) -> None:
    """End a pool at once after an error or an interrupt in the parent.

    ``shutdown(wait=True)`` (what ``with`` does) would first run every queued batch to the
    end — minutes for a large campaign after Ctrl-C. Queued batches are cancelled and the
    running workers terminated (SIGTERM, default action: they end silently), then joined,
    so no worker outlives the command or finds its parent gone while starting up. The pool's
    manager thread is joined last: it closes the pool's wake-up pipe as it ends, and if the command
    exited first, Python's own exit hook (``concurrent.futures.process._python_exit``, which writes to
    that pipe unlocked) could meet the pipe being closed and print "Exception ignored … OSError: [Errno
    9] Bad file descriptor" under the one "interrupted" line (seen once in a fresh clone's run of
    tests/hostile/test_hostile_cli.py).
    """
    processes = list((getattr(pool, "_processes", None) or {}).values())
    manager = getattr(pool, "_executor_manager_thread", None)  # shutdown(wait=False) drops it
    pool.shutdown(wait=False, cancel_futures=True)
    for proc in processes:
        if proc.is_alive():
            proc.terminate()
    for proc in processes:
        proc.join(timeout=10)
    if manager is not None:
        manager.join(timeout=10)


#: Longest wait for a dask scheduler given with ``--scheduler``, s.
DASK_CONNECT_TIMEOUT_S = 10.0


def _map_dask(fn: Callable[[Any], Any], batches: list[Any], ctx, done: Callable[[int], None]) -> list[Any]:
    """Run the batches on a Dask cluster (``ctx.scheduler``, or a local one)."""
    try:
        from dask.distributed import Client, as_completed
    except ImportError:  # pragma: no cover - depends on the installed extras
        raise MissingExtra("--executor dask needs dask[distributed]: pip install 'tyrelab[dask]'") from None
    import logging

    # distributed logs every worker start, stop and heartbeat at INFO (~270 lines for 24 workers), and
    # tyrelab's command line shows INFO: its scheduler and workers say only warnings and errors.
    for name in ("distributed", "dask"):
        logging.getLogger(name).setLevel(max(logging.WARNING, logging.getLogger(name).getEffectiveLevel()))
    if ctx.scheduler:
        try:
            client = Client(ctx.scheduler, timeout=DASK_CONNECT_TIMEOUT_S)
        except (OSError, TimeoutError, ValueError) as exc:  # refused, unreachable, a malformed address
            raise OSError(errno.ECONNREFUSED, f"cannot reach the dask scheduler ({str(exc).splitlines()[0]})",
                          f"--scheduler {ctx.scheduler}") from None
    else:
        # As the local executor: no more workers than batches (24 workers for 2 variants on 2 cores
        # started 24 processes).
        workers = max(1, min(int(ctx.jobs or 1), len(batches)))
        client = Client(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                        silence_logs=logging.WARNING)
    try:
        futures = client.map(fn, batches, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        for f in as_completed(futures):
            done(index[f.key])
        return client.gather(futures)
    finally:
        if ctx.scheduler:
            client.close()
        else:
            cluster = client.cluster
            client.close()
            cluster.close()


def worker_server_state() -> str:
    """``"none"`` (no worker server in this process), ``"starting"`` (still importing
    :data:`WORKER_PRELOAD`) or ``"ready"``, without waiting (:func:`start_worker_server`)."""
    pid = _server_pid()
    if pid is None:
        return "none"
    ready = _ready_marker
    if ready is None or os.path.exists(ready) or _exited(pid):
        return "ready"  # a dead server: the pool starts another and says why (_worker_context)
    return "starting"


class Background:
    """Batches handed to worker processes by :func:`map_in_background`; :meth:`results` collects them."""

    def __init__(self, pool: ProcessPoolExecutor, futures: list):
        self._pool, self._futures = pool, futures

    def results(self, on_done: Callable[[int], None] | None = None) -> list[Any]:
        """``[fn(b) for b in batches]``, waiting for the workers (``on_done(i)`` as batch ``i``'s
        result is taken, in order); the pool ends either way."""
        try:
            out = []
            for i, f in enumerate(self._futures):
                out.append(f.result())
                if on_done is not None:
                    on_done(i)
        except BaseException:
            self.abandon()
            raise
        self._pool.shutdown(wait=True)
        return out

    def abandon(self) -> None:
        """End the workers now (an error or an interrupt in the caller): see :func:`abandon_pool`."""
        abandon_pool(self._pool)


def map_in_background(fn: Callable[[Any], Any], batches: Sequence[Any], jobs: int) -> Background | None:
    """Hand ``batches`` to ``jobs`` worker processes and return at once, if the worker server is ready.

    The caller goes on with other work (the workers are forked from the server, with the
    stages' modules loaded, in milliseconds) and collects ``[fn(b) for b in batches]`` with
    :meth:`Background.results`, or ends the workers with :meth:`Background.abandon` on an
    error. Returns None — the caller maps the batches itself — when there is nothing to do,
    ``jobs`` is 1, or no worker server of this process is ready (:func:`worker_server_state`):
    waiting for its imports (2-3 s of CPU) would cost more than the batches.

    Parameters
    ----------
    fn : callable
        A module-level (picklable) function of one batch.
    batches : sequence
        Picklable work items, handed out in order.
    jobs : int
        Worker processes (at most one per batch).

    Examples
    --------
    >>> map_in_background(abs, [-1, 2], jobs=1) is None  # one process: the caller maps them
    True
    """
    if int(jobs) < 1:
        raise ValueError(f"jobs must be at least 1, got {jobs!r}")
    batches = list(batches)
    if not batches or int(jobs) < 2 or worker_server_state() != "ready":
        return None
    pool = worker_pool(min(int(jobs), len(batches)))
    try:
        futures = [pool.submit(fn, b) for b in batches]
    except BaseException:
        abandon_pool(pool)
        raise
    return Background(pool, futures)


def map_alongside(fn: Callable[[Any], Any], batches: Sequence[Any], jobs: int, depth: int = 2,
                  on_done: Callable[[int], None] | None = None) -> list[Any]:
    """:func:`map_batches` on ``jobs - 1`` local worker processes with this process working too.

    The calling process takes the next batch itself whenever the workers have ``depth``
    batches each in hand, and the workers are asked for only once the worker server
    (:func:`start_worker_server`) has finished its imports: until then this process works
    alone, so it never waits for them (a server started by this call imports for ~2-3 s of
    CPU on another core; when the batches run out first, no worker is started at all). One
    worker fewer is started than with :func:`map_batches`. Batches are handed out one at a
    time in order, to whoever is free, so the load balances whatever the batches cost. The
    results are ``[fn(b) for b in batches]`` wherever each ran, so ``fn`` must give the same
    result in any process.

    Parameters
    ----------
    fn : callable
        A module-level (picklable) function of one batch.
    batches : sequence
        Picklable work items.
    jobs : int
        Processes working, this one included (``jobs=1``: all in this process).
    depth : int, optional
        Batches queued per worker (so a worker never waits for this process to hand out work).
    on_done : callable, optional
        Called with a batch's index once it has finished (for progress), in this process.

    Returns
    -------
    list
        ``[fn(b) for b in batches]``.

    Examples
    --------
    >>> map_alongside(abs, [-1, 2, -3], jobs=1)
    [1, 2, 3]
    """
    if int(jobs) < 1:
        raise ValueError(f"jobs must be at least 1, got {jobs!r}")
    if int(depth) < 1:
        raise ValueError(f"depth must be at least 1, got {depth!r}")
    batches = list(batches)
    done_ = on_done or (lambda i: None)
    workers = min(int(jobs), len(batches)) - 1
    if workers < 1:
        return _in_process(fn, batches, done_)
    from concurrent.futures import FIRST_COMPLETED, wait

    start_worker_server()
    results: list[Any] = [None] * len(batches)
    pending: dict = {}  # future -> batch index
    nxt = 0
    pool = None
    try:
        while nxt < len(batches) or pending:
            for f in [f for f in pending if f.done()]:
                i = pending.pop(f)
                results[i] = f.result()
                done_(i)
            if pool is None and nxt < len(batches) and worker_server_state() == "ready":
                pool = worker_pool(workers)
            while pool is not None and nxt < len(batches) and len(pending) < workers * depth:
                pending[pool.submit(fn, batches[nxt])] = nxt
                nxt += 1
            if nxt < len(batches):
                results[nxt] = fn(batches[nxt])
                done_(nxt)
                nxt += 1
            elif pending:
                finished, _ = wait(list(pending), return_when=FIRST_COMPLETED)
                for f in finished:
                    i = pending.pop(f)
                    results[i] = f.result()
                    done_(i)
    except BaseException:
        if pool is not None:
            abandon_pool(pool)
        raise
    if pool is not None:
        pool.shutdown(wait=True)
    return results
