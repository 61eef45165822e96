"""Hold points: a test stops a process at a named moment, knows it is there, and signals it there.

A test that interrupts or kills a command must not guess when the command is busy (a fixed sleep
races the machine: on a fast or a loaded one the signal lands before or after the work). Instead it
sets the environment variable :data:`HOLD_VARIABLE` to a folder and creates in it a file named after
a hold point; the command, on reaching that point, says so in a file and waits there until the test
removes the hold file. The test waits for that file, sends its signal (the work cannot have
finished: it is held), and checks that the hold was never passed.

Without the variable (every run but a test's) a hold point costs one environment lookup.

For a point ``P`` in folder ``F`` (``TYRELAB_TEST_HOLD=F``):

- ``F/P`` present asks for the hold; its content is the occurrence to hold at (``3``: the third
  time this process reaches ``P``; empty: the first; ``0``: never — only count).
- ``F/P.count``: how many times this process has reached ``P`` (written each time while ``F/P``
  exists; the count is per process).
- ``F/P.reached``: written (the process's pid) when the process holds at ``P``; it then waits until
  ``F/P`` is removed, and writes ``F/P.released`` before it goes on.

The points (their names are the contract of the tests):

``stage-NAME``
    ``tyrelab run``'s process, when stage ``NAME`` must run, before its work starts
    (:func:`tyrelab.stages.run_stage`).
``replace``
    Any process, before a file written in full is renamed over its target (its temporary
    file is complete, the target still the old one: :func:`tyrelab.io.atomic_path`).
``worker``
    A pool worker, once started (SIGINT ignored), before its first batch
    (:func:`tyrelab.executor.worker_pool`).
``ahead``
    A worker of the work a stage started ahead (the chapter 6-7 studies), before it starts.
``sql-statement``
    ``tyrelab sql``, while DuckDB runs a statement (the waiting thread, which stops it on Ctrl-C).
"""

from __future__ import annotations

import os
import time

__all__ = ["HOLD_VARIABLE", "hold"]

#: Environment variable naming the folder of the hold files (set only by tests).
HOLD_VARIABLE = "TYRELAB_TEST_HOLD"

#: Times this process reached each point (while asked to count it).
_counts: dict[str, int] = {}


def _write(path: str, text: str) -> None:
    tmp = f"{path}.{os.getpid()}.tmp"
    with open(tmp, "w", encoding="ascii") as fh:
        fh.write(text)
    os.replace(tmp, path)


def hold(point: str) -> None:
    """Wait at ``point`` while a test holds it there (see the module's text); else return at once.

    Parameters
    ----------
    point : str
        The hold point's name (a file name).

    Examples
    --------
    >>> hold("stage-ingest")  # no test holds anything: returns at once
    """
    folder = os.environ.get(HOLD_VARIABLE)
    if not folder:
        return
    path = os.path.join(folder, point)
    try:
        with open(path, encoding="ascii") as fh:
            text = fh.read().strip()
    except OSError:
        return
    n = _counts[point] = _counts.get(point, 0) + 1
    _write(f"{path}.count", str(n))
    if n != (int(text) if text.isdigit() else 1):
        return
    _write(f"{path}.reached", str(os.getpid()))
    while os.path.exists(path):
        time.sleep(0.01)
    _write(f"{path}.released", str(os.getpid()))
