"""One writer per build folder: an advisory lock taken by every command that writes ``build/``.

``tyrelab run`` and the single-stage commands hold :data:`LOCK_NAME` in the build
folder for as long as they write. The lock is an ``flock`` on that file, so the
kernel releases it when the holder exits *or is killed*: a lock can never be left
behind by a dead process. The file keeps the holder's pid, the start time of that
process (from ``/proc``, so a re-used pid is told apart) and the command, so a second
writer can name who holds the build; a file whose lock is free but that still names
a holder is a stale lock of a process that died, and it is taken over (and said so).

Readers (``tyrelab sql``, the report in a browser, ``duckdb -readonly``) never take
the lock: the pipeline replaces every file atomically, so they are never blocked.

Examples
--------
>>> import tempfile
>>> with tempfile.TemporaryDirectory() as d:
...     with BuildLock(d, "doctest"):
...         try:
...             BuildLock(d, "second").acquire()
...         except BuildLocked as exc:
...             print("refused:", "being written by pid" in str(exc))
refused: True
"""

from __future__ import annotations

import datetime as _dt
import errno
import fcntl
import json
import logging
import os
import time
from pathlib import Path

__all__ = ["LOCK_NAME", "BuildLock", "BuildLocked", "process_start_ticks"]

log = logging.getLogger("tyrelab")

#: Name of the lock file inside the build folder (hidden: not a stage output).
LOCK_NAME = ".tyrelab.lock"


class BuildLocked(RuntimeError):
    """Raised when another live process holds the build's lock; the message names it."""


def process_start_ticks(pid: int) -> int | None:
    """Start time of process ``pid`` in clock ticks since boot (``/proc/<pid>/stat`` field 22), or None."""
    try:
        text = Path(f"/proc/{int(pid)}/stat").read_text()
    except (OSError, ValueError):
        return None
    fields = text.rpartition(")")[2].split()  # after the command name, which may hold spaces
    try:
        return int(fields[19])
    except (IndexError, ValueError):
        return None


def _describe(holder: dict) -> str:
    started = holder.get("started_utc", "?")
    alive = process_start_ticks(holder.get("pid", -1))
    note = "" if alive is None or alive == holder.get("start_ticks", alive) else "; pid since re-used"
    return f"pid {holder.get('pid', '?')} ({holder.get('command', '?')}, since {started}{note})"


class BuildLock:
    """The write lock of a build folder (a context manager).

    Parameters
    ----------
    build : path
        The build folder; created if missing.
    command : str
        What the holder is doing (e.g. ``"tyrelab run"``), written into the lock file.

    Raises
    ------
    BuildLocked
        From :meth:`acquire`, when another live process holds the lock.
    NotADirectoryError, PermissionError, OSError
        When the build folder cannot be created or written.
    """

    def __init__(self, build: str | os.PathLike, command: str):
        if not str(command):
            raise ValueError("command: must name what the holder does")
        self.build = Path(build)
        self.path = self.build / LOCK_NAME
        self.command = str(command)
        self._fd: int | None = None

    def acquire(self) -> "BuildLock":
        """Take the lock without waiting; report and take over a stale one."""
        if self.build.exists() and not self.build.is_dir():
            raise NotADirectoryError(errno.ENOTDIR, "--build is not a folder", str(self.build))
        self.build.mkdir(parents=True, exist_ok=True)
        fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = self._read(fd)
            os.close(fd)
            raise BuildLocked(f"{self.build} is being written by {_describe(holder)}; "
                              "wait for it to finish (readers such as 'tyrelab sql' are not blocked)") from None
        except BaseException:
            os.close(fd)
            raise
        stale = self._read(fd)
        if stale.get("pid") is not None:
            log.warning("%s: stale lock of %s, a process that is gone; taking it over", self.path, _describe(stale))
        me = {"pid": os.getpid(), "start_ticks": process_start_ticks(os.getpid()), "command": self.command,
              "started_utc": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
              "acquired_unix_s": round(time.time(), 3)}
        os.ftruncate(fd, 0)
        os.pwrite(fd, (json.dumps(me) + "\n").encode(), 0)
        self._fd = fd
        return self

    def release(self) -> None:
        """Empty the lock file (no holder) and release the lock; the file itself stays."""
        if self._fd is None:
            return
        try:
            os.ftruncate(self._fd, 0)
        finally:
            fcntl.flock(self._fd, fcntl.LOCK_UN)
            os.close(self._fd)
            self._fd = None

    @staticmethod
    def _read(fd: int) -> dict:
        try:
            data = os.pread(fd, 4096, 0)
            return json.loads(data) if data.strip() else {}
        except (OSError, ValueError):
            return {}

    def __enter__(self) -> "BuildLock":
        return self.acquire()

    def __exit__(self, *exc) -> None:
        self.release()
