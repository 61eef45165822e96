"""Hold a command at a named point, signal it there, check the signal landed there (tyrelab._hold).

A test that interrupts or kills a process never sleeps a fixed time first: it asks the process to
hold at a point (:class:`Holds`), waits until the process says it is there (:meth:`Holds.wait`),
sends its signal, and checks with :meth:`Holds.passed` that the process never went on past it.
The rule is in docs/testing.md.
"""

from __future__ import annotations

import os
import time
from pathlib import Path

from tyrelab._hold import HOLD_VARIABLE

__all__ = ["Holds", "HANG_GUARD_S"]

#: Longest wait for a process to reach a hold point, s. A guard against a hang, not a measure of
#: speed: the points are reached in a second or two; a test that hits it failed for another reason.
HANG_GUARD_S = 600.0


class Holds:
    """The hold files of one test, in ``folder``; :attr:`env` is the environment that enables them."""

    def __init__(self, folder: str | os.PathLike):
        self.folder = Path(folder)
        self.folder.mkdir(parents=True, exist_ok=True)

    @property
    def env(self) -> dict:
        """``os.environ`` with :data:`tyrelab._hold.HOLD_VARIABLE` pointing at the folder."""
        return {**os.environ, HOLD_VARIABLE: str(self.folder)}

    def hold(self, point: str, occurrence: int = 1) -> None:
        """Ask the process to hold at ``point`` the ``occurrence``-th time it reaches it (0: only count)."""
        (self.folder / point).write_text(str(occurrence))

    def release(self, point: str) -> None:
        (self.folder / point).unlink(missing_ok=True)

    def wait(self, point: str, proc) -> int:
        """Wait until ``proc`` (a :class:`subprocess.Popen`) or one of its workers holds at ``point``;
        return the holder's pid. Fails with the process's stderr if it ended first."""
        reached = self.folder / f"{point}.reached"
        deadline = time.monotonic() + HANG_GUARD_S
        while not reached.exists():
            if proc.poll() is not None:
                err = proc.stderr.read() if proc.stderr else ""
                raise AssertionError(f"the process ended (exit {proc.returncode}) before it reached {point!r}:\n{err}")
            assert time.monotonic() < deadline, f"{point!r} not reached in {HANG_GUARD_S:g} s (a hang)"
            time.sleep(0.01)
        return int(reached.read_text())

    def passed(self, point: str) -> bool:
        """Whether a process went on past ``point`` after it was released."""
        return (self.folder / f"{point}.released").exists()

    def count(self, point: str) -> int:
        """How many times the (last) process reached ``point`` while it was asked to count it."""
        path = self.folder / f"{point}.count"
        return int(path.read_text()) if path.exists() else 0
