"""Atomic file writes and content hashing.

Every file the pipeline writes is first written to a temporary file in the
same folder and then renamed over the target (``os.replace`` is atomic on
POSIX), so a reader never sees a half-written file and a crash leaves the
previous version in place.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import logging
import math
import os
import re
import stat
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING, Iterator

from ._hold import hold

if TYPE_CHECKING:  # pandas/pyarrow are imported where used: a no-op run never needs them
    import pandas as pd

__all__ = ["atomic_path", "write_parquet_atomic", "write_text_atomic", "write_texts_atomic", "file_sha256",
           "discover_campaigns", "os_error_line", "make_folder", "safe_name", "walk", "json_safe",
           "raw_problem", "printable", "MissingExtra", "MAX_HEADER_BYTES", "head_lines", "TEXT_WIDTH", "fit_lines"]

#: Widest line of a command's ``--format table`` by default (``--wide``: no limit), characters.
TEXT_WIDTH = 100

#: Longest header line of a CSV the pipeline reads in pieces (a vehicle recording, a track profile),
#: bytes: it is read first, bounded, so that a file without line ends is refused instead of being read
#: whole as its header (a 2 GB one took 15 GB and a minute).
MAX_HEADER_BYTES = 64 * 1024


def head_lines(path: str | os.PathLike, n: int, what: str) -> list[bytes]:
    """The first ``n`` lines of a text file, each read bounded (:data:`MAX_HEADER_BYTES`).

    Raises
    ------
    ValueError
        ``cannot read (…)`` for a file the system will not open, or for a first line longer than
        the bound (a file without line ends), naming ``what`` the first line should hold.
    """
    try:
        with open(path, "rb") as fh:
            lines = [fh.readline(MAX_HEADER_BYTES + 1) for _ in range(n)]
    except OSError as exc:
        raise ValueError(f"cannot read ({exc.strerror or exc})") from None
    if len(lines[0]) > MAX_HEADER_BYTES:
        raise ValueError(f"the header line is longer than {MAX_HEADER_BYTES // 1024} KiB (a file without line ends?): "
                         f"the first line names the columns ({what})")
    return lines


class MissingExtra(RuntimeError):
    """An optional dependency (an extra of the package) that is not installed; the message says
    what to install. The command line prints it as one line, exit 2."""


#: Control characters (C0, DEL, C1) and the Unicode line and paragraph separators.
_CONTROL = re.compile("[\x00-\x1f\x7f-\x9f\u2028\u2029]")


def printable(text) -> str:
    r"""``text`` with its control characters escaped (``\n``, ``\x1b``, ``\u2028``): what a
    table row or a one-line error prints of a user's name or file name, so that an ESC cannot
    drive the terminal and a newline cannot split the line or forge another.

    Examples
    --------
    >>> print(printable("baling" + chr(27) + "[2J" + chr(10) + "day: fake"))
    baling\x1b[2J\nday: fake
    >>> printable("plain, ünïcode")
    'plain, ünïcode'
    """
    text = str(text)
    if not _CONTROL.search(text):
        return text
    return _CONTROL.sub(lambda m: m.group().encode("unicode_escape").decode("ascii"), text)


def _break_at(text: str, room: int) -> int:
    """Where to break ``text`` so that its first part fits ``room``: after the last ``"; "`` or
    ``", "``, or before the last ``" ("``, that leaves a first part of at least half the room, else
    at the last space; -1 when there is no space to break at within the room."""
    best = -1
    for sep, keep in (("; ", 1), (", ", 1), (" (", 0)):
        i = text.rfind(sep, 0, room - keep + 1)
        if i >= 0 and i + keep >= room // 2:
            best = max(best, i + keep)
    if best < 0:
        best = text.rfind(" ", 0, room + 1)
    return best


def fit_lines(lines, width: int | None = TEXT_WIDTH) -> list[str]:
    """Lines of text no wider than ``width``: a longer line is broken after a ``;`` or ``,`` or
    before a ``(`` where it can (else at a space), its continuation indented four spaces past its
    own indent (a word longer than the room, e.g. a path, stays whole); ``width=None`` leaves every
    line as it is (``--wide``).

    See Also
    --------
    tyrelab.report.ride_page.format_table : a table that splits into blocks of columns instead.

    Examples
    --------
    >>> for line in fit_lines(["  hours to EAV 2.2, to ELV 11.4 (at this mix of tasks); daily VDV 15.03 m/s^1.75"], 60):
    ...     print(line)
      hours to EAV 2.2, to ELV 11.4 (at this mix of tasks);
          daily VDV 15.03 m/s^1.75
    >>> fit_lines(["short"], None), fit_lines(["x" * 50], 10) == ["x" * 50]
    (['short'], True)
    """
    if width is None:
        return list(lines)
    out = []
    for line in lines:
        indent = line[:len(line) - len(line.lstrip(" "))]
        text, lead = line.strip(" "), indent
        while len(lead) + len(text) > width:
            cut = _break_at(text, width - len(lead))
            if cut <= 0:  # a word longer than the room: whole, up to the next space
                cut = text.find(" ", width - len(lead))
                if cut < 0:
                    break
            out.append((lead + text[:cut]).rstrip())
            text, lead = text[cut:].lstrip(" "), indent + "    "
        out.append(lead + text)
    return out


def os_error_line(exc: OSError) -> str:
    """One line for an OS error: ``<file>: <what the system said>`` (the command line's and
    ``tyrelab watch``'s error lines).

    Examples
    --------
    >>> os_error_line(PermissionError(13, "Permission denied", "/data/r1.parquet"))
    '/data/r1.parquet: Permission denied'
    """
    what = exc.strerror or (str(exc).splitlines()[0] if str(exc) else type(exc).__name__)
    return f"{printable(exc.filename)}: {what}" if getattr(exc, "filename", None) else what


_UMASK = os.umask(0)
os.umask(_UMASK)


def make_folder(folder: str | os.PathLike) -> Path:
    """``mkdir -p folder``; a regular file in the way is NotADirectoryError naming it (mkdir says "File exists")."""
    folder = Path(folder)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except FileExistsError as exc:
        raise NotADirectoryError(errno.ENOTDIR, "Not a directory", exc.filename) from None
    return folder


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it to ``path`` on success.

    On an exception the temporary file is removed and ``path`` is untouched.
    """
    path = Path(path)
    make_folder(path.parent)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    tmp_path = Path(tmp)
    os.chmod(tmp_path, 0o666 & ~_UMASK)  # mkstemp makes 0600; give outputs the usual permissions
    try:
        yield tmp_path
        hold("replace")  # a test's kill lands here: the temporary file written, the target still the old one
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


def write_texts_atomic(files: dict[str | os.PathLike, str]) -> list[Path]:
    """Write a set of UTF-8 files that belong together: all are replaced, or none is; return the paths.

    Every file is first written to a temporary file beside its target; only when all
    are written (a full disk, a file-size limit or a missing folder fails here, before
    any target is touched) are they renamed over the targets. Should a rename fail,
    the targets already replaced get their previous contents back (kept as hard links
    until the set is complete), so readers see the old set or the new one.

    Examples
    --------
    >>> import tempfile
    >>> d = Path(tempfile.mkdtemp())
    >>> [p.name for p in write_texts_atomic({d / "a.json": "{}", d / "a.html": "<p>"})]
    ['a.json', 'a.html']
    >>> write_texts_atomic({d / "b.json": "{}", d / "a.json" / "below-a-file.html": ""})
    Traceback (most recent call last):
    ...
    NotADirectoryError: [Errno 20] Not a directory: ...
    >>> sorted(p.name for p in d.iterdir())  # b.json was not written: the set failed
    ['a.html', 'a.json']
    """
    targets = [Path(p) for p in files]
    temporaries: list[Path] = []
    replaced: list[tuple[Path, Path | None]] = []  # targets replaced so far, with their previous contents
    try:
        for path, text in zip(targets, files.values()):
            make_folder(path.parent)
            fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
            temporaries.append(Path(tmp))
            with os.fdopen(fd, "w", encoding="utf-8") as fh:
                fh.write(text)
            os.chmod(tmp, 0o666 & ~_UMASK)
        hold("replace")  # every temporary file written, no target replaced yet
        for path, tmp in zip(targets, temporaries):
            backup = None
            if len(targets) > 1 and path.is_file() and not path.is_symlink():
                backup = Path(tempfile.mktemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent))
                os.link(path, backup)
            try:
                os.replace(tmp, path)
            except BaseException:
                if backup is not None:
                    backup.unlink()
                raise
            replaced.append((path, backup))
    except BaseException:
        for path, backup in reversed(replaced):
            if backup is not None:
                os.replace(backup, path)
            else:
                path.unlink(missing_ok=True)
        raise
    finally:
        for tmp in temporaries:
            tmp.unlink(missing_ok=True)
        for _, backup in replaced:
            if backup is not None:
                backup.unlink(missing_ok=True)
    return targets


def json_safe(obj):
    """``obj`` with NaN and infinities as None (JSON has neither: ``json.dumps`` would print
    ``NaN``/``Infinity``), recursively through dicts, lists and tuples; numpy scalars as Python's.

    Examples
    --------
    >>> json_safe({"k": [1.0, float("inf")], "c": float("nan")})
    {'k': [1.0, None], 'c': None}
    """
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [json_safe(v) for v in obj]
    if hasattr(obj, "item") and getattr(obj, "ndim", None) == 0:  # a numpy scalar
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def safe_name(text: str) -> str:
    """A file-name-safe, unique name for ``text`` (a run id, a tyre id): unsafe characters become ``_``
    and, where anything was changed, a digest of the original keeps names apart.

    Examples
    --------
    >>> safe_name("MF-480/70R38 #2")
    'MF-480_70R38__2-e3099418'
    >>> safe_name("r001")
    'r001'
    """
    safe = re.sub(r"[^A-Za-z0-9._-]", "_", text)[:80]
    if safe != text:
        safe += "-" + hashlib.sha1(text.encode()).hexdigest()[:8]
    return safe


def walk(folder: str | os.PathLike):
    """``os.walk(folder)`` (top-down, symlinked folders listed but not entered, unreadable folders
    skipped) without recursion: Python 3.11's ``os.walk`` and ``Path.rglob`` recurse once per
    level and raise RecursionError in a tree ~1,000 folders deep. ``dirnames`` may be pruned in place.
    """
    stack = [os.fspath(folder)]
    while stack:
        top = stack.pop()
        dirs, files = [], []
        try:
            with os.scandir(top) as entries:
                for entry in entries:
                    try:
                        is_dir = entry.is_dir()
                    except OSError:
                        is_dir = False
                    (dirs if is_dir else files).append(entry.name)
        except OSError:
            continue
        yield top, dirs, files
        stack.extend(os.path.join(top, d) for d in reversed(dirs) if not os.path.islink(os.path.join(top, d)))


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
    for dirpath, dirnames, filenames in walk(folder):
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
    return sorted(Path(top) for top, _, files in walk(raw) if "manifest.csv" in files
                  and (Path(top) / "manifest.csv").is_file())


def raw_problem(raw: str | os.PathLike) -> str | None:
    """Why ``raw`` cannot be built from (one line naming it), or None: not a folder, or no campaign in it.

    ``tyrelab run`` refuses such a ``--raw`` before any stage, and ``tyrelab watch`` before each
    run: a raw folder that vanished (an unmounted share, a folder renamed) must not replace a
    build with an empty one.

    Examples
    --------
    >>> raw_problem("/no/such/folder")
    '--raw /no/such/folder: no such folder'
    """
    raw = Path(raw)
    if not raw.is_dir():
        return f"--raw {raw}: no such folder"
    if not discover_campaigns(raw):
        return f"--raw {raw}: no campaign (no manifest.csv in it or below it)"
    return None
