"""Atomic file writes and content hashing.

Every file the pipeline writes is first written to a temporary file in the
same folder and then renamed over the target (``os.replace`` is atomic on
POSIX), so a reader never sees a half-written file and a crash leaves the
previous version in place.
"""

from __future__ import annotations

import contextlib
import hashlib
import logging
import os
import re
import stat
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING, Iterator

if TYPE_CHECKING:  # pandas/pyarrow are imported where used: a no-op run never needs them
    import pandas as pd

__all__ = ["atomic_path", "write_parquet_atomic", "write_text_atomic", "file_sha256", "discover_campaigns",
           "os_error_line"]


def os_error_line(exc: OSError) -> str:
    """One line for an OS error: ``<file>: <what the system said>`` (the command line's and
    ``tyrelab watch``'s error lines).

    Examples
    --------
    >>> os_error_line(PermissionError(13, "Permission denied", "/data/r1.parquet"))
    '/data/r1.parquet: Permission denied'
    """
    what = exc.strerror or (str(exc).splitlines()[0] if str(exc) else type(exc).__name__)
    return f"{exc.filename}: {what}" if getattr(exc, "filename", None) else what


_UMASK = os.umask(0)
os.umask(_UMASK)


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it to ``path`` on success.

    On an exception the temporary file is removed and ``path`` is untouched.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    tmp_path = Path(tmp)
    os.chmod(tmp_path, 0o666 & ~_UMASK)  # mkstemp makes 0600; give outputs the usual permissions
    try:
        yield tmp_path
        os.replace(tmp_path, path)
    finally:
        if tmp_path.exists():
            tmp_path.unlink()


def remove_stale_temporaries(folder: str | os.PathLike) -> int:
    """Delete the temporary files :func:`atomic_path` leaves when its process is killed; return how many.

    Call only while holding the folder's write lock (:class:`tyrelab.buildlock.BuildLock`):
    then no other writer's temporary file can be among them.
    """
    n = 0
    for p in Path(folder).rglob(".*.tmp*") if Path(folder).is_dir() else []:
        if _TEMPORARY.match(p.name) and p.is_file() and not p.is_symlink():
            p.unlink()
            n += 1
    return n


#: Names :func:`atomic_path` gives its temporary files (``mkstemp``'s 8 random characters),
#: and DuckDB's write-ahead log beside one.
_TEMPORARY = re.compile(r"^\..+\.[A-Za-z0-9_]{8}\.tmp(\.wal)?$")


def write_parquet_atomic(df: pd.DataFrame, path: str | os.PathLike) -> Path:
    """Write ``df`` to Parquet at ``path`` atomically; return the path.

    The index is not stored. Output is deterministic for the same frame
    (no creation timestamps are written by pyarrow).
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = pa.Table.from_pandas(df, preserve_index=False)
    with atomic_path(path) as tmp:
        pq.write_table(table, tmp, compression="zstd")
    return Path(path)


def write_text_atomic(text: str, path: str | os.PathLike) -> Path:
    """Write UTF-8 ``text`` to ``path`` atomically; return the path."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def file_sha256(path: str | os.PathLike, chunk: int = 1 << 20) -> str:
    """Return the hex SHA-256 of a file's bytes."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        while block := fh.read(chunk):
            h.update(block)
    return h.hexdigest()


_KINDS = ((stat.S_ISDIR, "folder"), (stat.S_ISFIFO, "named pipe (FIFO)"), (stat.S_ISCHR, "character device"),
          (stat.S_ISBLK, "block device"), (stat.S_ISSOCK, "socket"), (stat.S_ISLNK, "symbolic link"))
_warned: set[str] = set()


def file_kind(mode: int) -> str:
    """What a ``st_mode`` is, in words: ``"regular file"``, ``"folder"``, ``"named pipe (FIFO)"``, ...

    Examples
    --------
    >>> import stat
    >>> file_kind(stat.S_IFIFO | 0o644)
    'named pipe (FIFO)'
    """
    return next((name for test, name in _KINDS if test(mode)), "regular file" if stat.S_ISREG(mode) else "special file")


def regular_files(folder: str | os.PathLike, exclude: str | os.PathLike | None = None,
                  skip_folders_with: str | None = None, prune=None):
    """Regular files below ``folder`` (sorted folders; hidden folders and ``exclude`` skipped).

    Named pipes, devices and sockets are skipped with a warning (once per path and
    process): opening a FIFO would block the pipeline for ever. Dangling symlinks are
    skipped silently. Symlinks are followed (``stat``), as reading them would.
    With ``skip_folders_with`` (a name, e.g. ``"manifest.csv"``), a folder holding an
    entry of that name is skipped with everything below it. ``prune(parts)`` (the folder's
    path below ``folder`` as a tuple of names) returning true skips a folder without
    entering it.
    """
    skip = Path(exclude).resolve() if exclude is not None else None
    for dirpath, dirnames, filenames in os.walk(folder):
        if skip_folders_with is not None and (skip_folders_with in filenames or skip_folders_with in dirnames):
            dirnames[:] = []
            continue
        here = () if prune is None else Path(os.path.relpath(dirpath, folder)).parts
        here = () if here == (".",) else here
        dirnames[:] = sorted(d for d in dirnames
                             if not d.startswith(".") and (skip is None or (Path(dirpath) / d).resolve() != skip)
                             and (prune is None or not prune((*here, d))))
        for f in sorted(filenames):
            p = Path(dirpath) / f
            try:
                mode = os.stat(p).st_mode
            except OSError:
                continue
            if stat.S_ISREG(mode):
                yield p
            elif str(p) not in _warned:
                _warned.add(str(p))
                logging.getLogger("tyrelab").warning("%s: skipped: a %s, not a regular file", p, file_kind(mode))


def discover_campaigns(raw: str | os.PathLike) -> list[Path]:
    """Campaign folders: ``raw`` itself if it holds ``manifest.csv``, else every folder below that does.

    Here (not in the ingest stage) so that the command line can check ``--raw`` without importing
    the stage and its libraries; :func:`tyrelab.stages.ingest.discover_campaigns` is this function.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     (Path(d) / "b").mkdir(); _ = (Path(d) / "b" / "manifest.csv").write_text("run_id")
    ...     [p.name for p in discover_campaigns(d)]
    ['b']
    """
    raw = Path(raw)
    if (raw / "manifest.csv").is_file():
        return [raw]
    return sorted(p.parent for p in raw.rglob("manifest.csv") if p.is_file())
