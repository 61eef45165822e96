"""The DuckDB warehouse ``build/warehouse.duckdb``: the pipeline's tables, portable.

DuckDB allows one read-write process *or* many read-only ones on a database
file, never both. So the pipeline writes Parquet, and the warehouse is rebuilt
from it into a new file renamed over the old one (readers that already opened
the old file keep it); every query (``tyrelab sql``, the report) opens it
read-only.

Portability: every table (``results``, ``table_iii``, ``published_*`` ... and
``runs``, every run's signals) is *stored in* the database file, so it answers
from any working folder, with the stock ``duckdb`` client or
``duckdb.connect(path, read_only=True)``, and keeps answering after the build
folder is moved or copied. DuckDB resolves a relative path in a view against
the process' working folder (or the session's ``file_search_path``, which a
database cannot persist, and a view's path cannot be computed from the
database's own location: a table function takes no subquery), so no view over
Parquet can be both portable and path-free; the file holds no view and no path.

The price is ``runs``: stored, it costs about 1.7 times its Parquet (DuckDB's
lightweight compression against Parquet's zstd on noisy float32 signals), and
the warehouse is rebuilt whole when a stage changes. ``store="runs_view"``
keeps the former layout (``runs`` a view relative to the database's folder,
which :func:`connect_read_only` resolves wherever the build is, a stock client
only from the build folder or after ``SET file_search_path``), for the
benchmark. Sizes and speeds of the layouts: ``docs/benchmarks.md`` (bench/bench_warehouse.py).

Examples
--------
>>> import tempfile, pandas as pd
>>> from pathlib import Path
>>> from tyrelab import io
>>> tmp = Path(tempfile.mkdtemp())
>>> _ = io.write_parquet_atomic(pd.DataFrame({"k": [1, 2, 3]}), tmp / "build" / "parquet" / "t.parquet")
>>> build_warehouse(tmp / "build" / "warehouse.duckdb", tmp / "build" / "parquet")
['t']
>>> moved = (tmp / "build").rename(tmp / "elsewhere")
>>> int(query(moved / "warehouse.duckdb", "SELECT sum(k) AS s FROM t")["s"].iloc[0])
6
"""

from __future__ import annotations

import contextlib
import errno
import logging
import os
import re
from collections.abc import Callable
from pathlib import Path

import duckdb
import pandas as pd
import pyarrow.parquet as pq

from . import interrupts, io
from ._hold import hold

__all__ = ["READ_ONLY_STATEMENTS", "SANDBOX_SETTINGS", "SPILL_FOLDER", "QueryLimits", "QueryTimeout", "WriteRefused",
    "view_name", "build_warehouse", "warehouse_path", "connect_read_only", "check_read_only", "query", "query_all", "parse_size", "iter_query", "memory_bound", "BATCH_ROWS",
    "did_you_mean", "error_line"]

log = logging.getLogger("tyrelab")

#: How :func:`build_warehouse` can hold the tables: every one stored in the file (portable,
#: the default), stored but ``runs`` a view relative to the file's folder (issue 10's layout:
#: smaller, ``runs`` not portable to a stock client), or views over absolute Parquet paths
#: (the first layout; smallest, not portable). The last two are kept for the benchmark.
STORES = ("tables", "runs_view", "views")
#: Block size of the database file, bytes. DuckDB's default (256 KiB) gives every
#: small table whole blocks: 16 KiB blocks make the file ten times smaller and
#: faster to open (docs/benchmarks.md). Readable by DuckDB >= 1.2.
BLOCK_SIZE_BYTES = 16384

#: Statement types a query may run; anything else is refused. DuckDB parses ``WITH``,
#: ``DESCRIBE``, ``SHOW``, ``SUMMARIZE``, ``FROM …`` and ``VALUES`` as SELECT statements;
#: ``EXPLAIN`` is refused because ``EXPLAIN ANALYZE`` executes the statement it explains
#: (``EXPLAIN ANALYZE COPY … TO`` writes a file).
READ_ONLY_STATEMENTS = {"SELECT"}

#: DuckDB settings of a read-only connection, applied in this order after the warehouse is
#: attached: no extension is installed or loaded behind the user's back (no network traffic
#: from ``read_csv('https://…')``), no file outside the build's ``parquet/`` folder is opened,
#: and the configuration is then locked so that no statement can ``SET`` it back.
SANDBOX_SETTINGS = (
    ("autoinstall_known_extensions", "false"),
    ("autoload_known_extensions", "false"),
    ("enable_external_access", "false"),
    ("lock_configuration", "true"),
)


#: Where in the build DuckDB may spill what does not fit in its memory limit (large sorts,
#: joins, aggregates). Each session spills into a folder of its own, ``<build>/.sql-spill-<pid>-<n>``,
#: which DuckDB creates when it first spills and removes when the session closes; one left by a
#: killed process is removed by the next session that finds its process gone (:func:`_spill_folder`). DuckDB's own default is ``.tmp``
#: in the caller's working folder: a read-only query would write outside the build.
SPILL_FOLDER = ".sql-spill"

_SIZE_UNITS = {"": 1, "b": 1, "kb": 10**3, "mb": 10**6, "gb": 10**9, "tb": 10**12,
               "kib": 2**10, "mib": 2**20, "gib": 2**30, "tib": 2**40}


def parse_size(text: str | int) -> int:
    """Bytes from a size such as ``"512MB"``, ``"2GiB"``, ``"1.5 GB"`` or ``"1000"`` (DuckDB's units: KB = 1000 B).

    Raises
    ------
    ValueError
        Naming the text, for anything else (negative, not finite, unknown unit).

    Examples
    --------
    >>> parse_size("2GiB"), parse_size("512MB"), parse_size(0)
    (2147483648, 512000000, 0)
    """
    if isinstance(text, int) and not isinstance(text, bool):
        number, unit = float(text), ""
    else:
        m = re.fullmatch(r"\s*([0-9]+(?:\.[0-9]*)?)\s*([A-Za-z]*)\s*", str(text))
        if not m or m.group(2).lower() not in _SIZE_UNITS:
            raise ValueError(f"{text!r} is not a size (e.g. 512MB, 2GiB, 0)")
        number, unit = float(m.group(1)), m.group(2).lower()
    value = number * _SIZE_UNITS[unit]
    if not (0 <= value < 2**62):
        raise ValueError(f"{text!r} is not a size from 0 to 4 EiB")
    return int(value)


class QueryLimits:
    """What one read-only query session may use: memory, spill space and time.

    Parameters
    ----------
    memory_limit_bytes : int
        DuckDB's ``memory_limit`` (buffer memory; DuckDB's own default is 80 % of the
        machine's). Default 2 GiB.
    spill_limit_bytes : int
        ``max_temp_directory_size``: what may be spilled into the build's
        :data:`SPILL_FOLDER`; 0 spills nothing (a query that does not fit in memory fails).
        Default 4 GiB.
    timeout_s : float or None
        Each statement is interrupted after this many seconds (raising
        :class:`QueryTimeout`); None: no limit. Default None (the command line's
        ``tyrelab sql`` sets 300 s).

    Examples
    --------
    >>> QueryLimits(memory_limit_bytes=parse_size("512MB")).memory_limit_bytes
    512000000
    >>> QueryLimits(timeout_s=0)
    Traceback (most recent call last):
    ...
    ValueError: timeout_s must be a finite number > 0 or None, got 0
    """

    __slots__ = ("memory_limit_bytes", "spill_limit_bytes", "timeout_s")

    def __init__(self, memory_limit_bytes: int = 2 * 2**30, spill_limit_bytes: int = 4 * 2**30,
                 timeout_s: float | None = None):
        for name, value, low in (("memory_limit_bytes", memory_limit_bytes, 2**20),
                                 ("spill_limit_bytes", spill_limit_bytes, 0)):
            if isinstance(value, bool) or not isinstance(value, int) or not low <= value < 2**62:
                raise ValueError(f"{name} must be an integer from {low} to 2**62 bytes, got {value!r}")
        if timeout_s is not None and (isinstance(timeout_s, bool) or not isinstance(timeout_s, (int, float))
                                      or not 0 < timeout_s < float("inf")):
            raise ValueError(f"timeout_s must be a finite number > 0 or None, got {timeout_s!r}")
        self.memory_limit_bytes, self.spill_limit_bytes, self.timeout_s = memory_limit_bytes, spill_limit_bytes, timeout_s

    def __repr__(self) -> str:
        return (f"QueryLimits(memory_limit_bytes={self.memory_limit_bytes}, spill_limit_bytes={self.spill_limit_bytes}, "
                f"timeout_s={self.timeout_s})")


class WriteRefused(ValueError):
    """Raised for a statement that would write to the warehouse."""


class QueryTimeout(TimeoutError):
    """Raised when a statement ran longer than :attr:`QueryLimits.timeout_s`."""


_sessions = iter(range(1, 1 << 62))


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # e.g. another user's process
        return True
    return True


def _spill_folder(build: Path) -> Path | None:
    """A fresh folder name for one session's spill files in ``build`` (DuckDB creates it when it spills), or None.

    Folders of processes that no longer run (killed before DuckDB could remove them) are
    removed first. None when the build folder cannot take one (not writable): then nothing spills.
    """
    import shutil

    build = Path(build).resolve()
    if not os.access(build, os.W_OK | os.X_OK):
        return None
    for old in build.glob(f"{SPILL_FOLDER}-*"):
        pid = old.name[len(SPILL_FOLDER) + 1:].split("-", 1)[0]
        if pid.isdigit() and int(pid) != os.getpid() and not _pid_alive(int(pid)) and not old.is_symlink():
            shutil.rmtree(old, ignore_errors=True)
    return build / f"{SPILL_FOLDER}-{os.getpid()}-{next(_sessions)}"


def _confine(con: duckdb.DuckDBPyConnection, build: Path, limits: QueryLimits | None) -> None:
    """Spills go below ``build`` (bounded) or nowhere; memory bounded when ``limits`` say so."""
    limits_ = limits or QueryLimits()
    folder = _spill_folder(build) if limits_.spill_limit_bytes else None
    con.execute(f"SET temp_directory = {_sql_path(folder) if folder else chr(39) * 2}")
    con.execute(f"SET max_temp_directory_size = '{limits_.spill_limit_bytes if folder else 0}B'")
    if limits is not None:
        con.execute(f"SET memory_limit = '{limits.memory_limit_bytes}B'")


def view_name(stem: str) -> str:
    """A SQL identifier from a file stem (``table_iii`` stays ``table_iii``)."""
    return re.sub(r"\W", "_", stem).lower()


def _sql_path(path: Path | str) -> str:
    return "'" + str(path).replace("'", "''") + "'"


def _search_path(con: duckdb.DuckDBPyConnection, folder: Path) -> None:
    """Resolve relative file paths of this session against ``folder`` (the database's folder)."""
    con.execute(f"SET file_search_path = {_sql_path(Path(folder).resolve())}")


def build_warehouse(db_path: Path, parquet_dir: Path, published: dict[str, Path] | None = None,
                    store: str = "tables", block_size_bytes: int = BLOCK_SIZE_BYTES,
                    on_table: Callable[[int, int], None] | None = None) -> list[str]:
    """Create the warehouse at ``db_path`` atomically; return its table and view names.

    Parameters
    ----------
    db_path : Path
        The ``.duckdb`` file to (re)create.
    parquet_dir : Path
        Folder of ``<table>.parquet`` files and the ``runs/`` hive dataset.
    published : dict, optional
        Table name -> Parquet path of the digitised thesis tables.
    store : {"tables", "views"}
        ``"tables"``: every table stored in the file, ``runs`` too (portable to
        any client and working folder). ``"runs_view"``: the same but ``runs`` a
        view relative to the file's folder. ``"views"``: views over absolute paths.
    block_size_bytes : int
        Block size of the file: a power of two from 16384 to 262144.
    on_table : callable, optional
        Called as ``on_table(done, total)`` after each table or view is made (for progress).

    Raises
    ------
    ValueError
        If ``store`` is not one of :data:`STORES` or ``block_size_bytes`` is invalid.
    """
    if store not in STORES:
        raise ValueError(f"store must be one of {STORES}, got {store!r}")
    if not (isinstance(block_size_bytes, int) and 16384 <= block_size_bytes <= 262144
            and block_size_bytes & (block_size_bytes - 1) == 0):
        raise ValueError(f"block_size_bytes must be a power of two from 16384 to 262144, got {block_size_bytes!r}")
    db_path = Path(db_path)
    parquet_dir = Path(parquet_dir).resolve()
    home = db_path.parent.resolve()
    sources: dict[str, Path] = {}
    for p in sorted(parquet_dir.glob("*.parquet")):
        if not pq.read_schema(p).names:
            log.debug("warehouse: %s has no columns; no table made", p)  # legitimately empty: said with -v only
            continue
        sources[view_name(p.stem)] = p
    for name, path in (published or {}).items():
        sources[name] = Path(path).resolve()
    kind = "VIEW" if store == "views" else "TABLE"
    statements = [f'CREATE {kind} "{name}" AS SELECT * FROM read_parquet({_sql_path(p)})' for name, p in sources.items()]
    runs = parquet_dir / "runs"
    if any(runs.glob("*/*.parquet")):
        pattern = Path(os.path.relpath(runs, home)) if store == "runs_view" else runs
        # Partition folders are percent-encoded tyre ids (tyrelab.stages.ingest.tyre_partition).
        statements.append(
            f'CREATE {"TABLE" if store == "tables" else "VIEW"} "runs" AS SELECT * REPLACE (url_decode(tyre_id) AS tyre_id) '
            f"FROM read_parquet({_sql_path(pattern / '*' / '*.parquet')}, hive_partitioning = true, "
            "hive_types = {'tyre_id': VARCHAR}, union_by_name = true)"
        )
        sources["runs"] = runs
    with io.atomic_path(db_path) as tmp:
        tmp.unlink()  # DuckDB wants to create the file itself
        con = duckdb.connect()
        try:
            _confine(con, home, None)
            con.execute(f"ATTACH {_sql_path(tmp)} AS warehouse (BLOCK_SIZE {block_size_bytes})")
            con.execute("USE warehouse")
            _search_path(con, home)
            con.execute("BEGIN TRANSACTION")  # one commit (one WAL sync) for every table, not one each
            for i, sql in enumerate(statements, start=1):
                con.execute(sql)
                if on_table is not None:
                    on_table(i, len(statements))
            con.execute("COMMIT")
            con.execute("USE memory")
            con.execute("DETACH warehouse")  # checkpoints: everything is in the file
        except duckdb.Error as exc:  # e.g. a file-size limit or a full disk: never an empty warehouse
            raise OSError(errno.EIO, f"cannot write the warehouse ({str(exc).splitlines()[0]})", str(db_path)) from None
        finally:
            con.close()
        wal = Path(str(tmp) + ".wal")
        if wal.exists():
            wal.unlink()
        check = duckdb.connect()
        try:
            check.execute(f"ATTACH {_sql_path(tmp)} AS warehouse (READ_ONLY)")
            made = check.execute(
                "SELECT (SELECT count(*) FROM duckdb_tables() WHERE database_name = 'warehouse')"
                " + (SELECT count(*) FROM duckdb_views() WHERE database_name = 'warehouse' AND NOT internal)"
            ).fetchone()[0]
        except duckdb.Error as exc:
            raise OSError(errno.EIO, f"the warehouse written is unreadable ({str(exc).splitlines()[0]})",
                          str(db_path)) from None
        finally:
            check.close()
        if made != len(statements):
            raise OSError(errno.EIO, f"the warehouse written holds {made} of {len(statements)} tables", str(db_path))
    return list(sources)


def warehouse_path(path: str | Path) -> Path:
    """The warehouse file: ``path`` itself, or ``path/warehouse.duckdb`` when ``path`` is a build
    folder (as ``tyrelab sql --build`` takes it).

    Examples
    --------
    >>> import tempfile
    >>> build = Path(tempfile.mkdtemp())
    >>> warehouse_path(build) == build / "warehouse.duckdb", warehouse_path(build / "w.duckdb").name
    (True, 'w.duckdb')
    """
    path = Path(path)
    return path / "warehouse.duckdb" if path.is_dir() else path


def connect_read_only(db_path: Path, limits: QueryLimits | None = None) -> duckdb.DuckDBPyConnection:
    """Open the warehouse read-only and sandboxed (many readers may do so while the pipeline writes).

    The file is attached (read-only) to a fresh in-memory session: unlike
    ``duckdb.connect(path)``, which shares one database instance per path
    within a process, this always sees the file as it is now, even while an
    earlier reader in the same process holds the file it replaced. Relative
    paths (the ``runs`` view of the ``runs_view`` layout) resolve against the
    database's folder, whatever the working folder. The session then may read files only below the
    warehouse's ``parquet/`` folder (``allowed_directories`` with
    ``enable_external_access = false``), never installs or autoloads an
    extension, and its configuration is locked (:data:`SANDBOX_SETTINGS`).

    What does not fit in memory spills only into the build's :data:`SPILL_FOLDER`, at most
    ``limits.spill_limit_bytes`` (4 GiB without ``limits``), or nowhere when the build folder
    is read-only; ``limits`` also bounds the memory (DuckDB's default, 80 % of the machine's,
    without). The statement timeout is :func:`query_all`'s.

    See Also
    --------
    query : one query's result as a DataFrame.
    iter_query : results streamed in batches (what ``tyrelab sql`` prints).

    Examples
    --------
    >>> import tempfile, pandas as pd
    >>> from tyrelab import io
    >>> build = Path(tempfile.mkdtemp())
    >>> _ = io.write_parquet_atomic(pd.DataFrame({"k": [1, 2]}), build / "parquet" / "t.parquet")
    >>> _ = build_warehouse(build / "warehouse.duckdb", build / "parquet")
    >>> con = connect_read_only(build)
    >>> con.execute("SELECT count(*) FROM t").fetchone()[0]
    2
    >>> try:
    ...     con.execute("CREATE TABLE x AS SELECT 1")
    ... except duckdb.Error as exc:
    ...     print(type(exc).__name__)
    InvalidInputException
    >>> con.close()
    """
    db_path = warehouse_path(db_path)
    if not db_path.is_file():
        what = "no warehouse yet - run 'tyrelab run' first" if not db_path.exists() else "not a regular file"
        raise FileNotFoundError(f"{db_path}: {what}")
    con = duckdb.connect()
    try:
        con.execute(f"ATTACH {_sql_path(db_path.resolve())} AS warehouse (READ_ONLY)")
        con.execute("USE warehouse")
        _search_path(con, db_path.parent)
        _confine(con, db_path.parent, limits)
        # The build's Parquet folder, absolute and as the ``runs`` view names it (relative to the
        # database's folder, through ``file_search_path``); ``..`` cannot climb out of either.
        allowed = [str(db_path.resolve().parent / "parquet") + "/", "parquet/"]
        con.execute(f"SET allowed_directories = [{', '.join(map(_sql_path, allowed))}]")
        for name, value in SANDBOX_SETTINGS:
            con.execute(f"SET {name} = {value}")
    except BaseException as exc:
        con.close()
        _interrupted(exc)
        raise
    return con


def check_read_only(sql: str) -> list[str]:
    """Refuse anything but queries; return the statements, one string each.

    Allowed: SELECT statements (including ``WITH``, ``DESCRIBE``, ``SHOW``,
    ``SUMMARIZE``, ``FROM …``, ``VALUES``); several are allowed, separated by ``;``.

    Raises
    ------
    WriteRefused
        Naming the first offending statement type.
    """
    try:
        statements = duckdb.extract_statements(sql)
    except duckdb.Error as exc:
        raise WriteRefused(f"cannot parse query: {str(exc).splitlines()[0]}") from None
    if not statements:
        raise WriteRefused("empty query")
    for st in statements:
        kind = st.type.name
        if kind not in READ_ONLY_STATEMENTS:
            raise WriteRefused(
                f"refused: {kind} statement; 'tyrelab sql' runs only queries "
                "(SELECT, WITH, DESCRIBE, SHOW, SUMMARIZE, FROM, VALUES)"
            )
    return [st.query.strip().rstrip(";").strip() for st in statements]


def _interrupted(exc: BaseException) -> None:
    """Raise ``KeyboardInterrupt`` from ``exc`` if Ctrl-C or SIGTERM arrived while DuckDB worked.

    DuckDB's Python module looks for signals during a statement, clears the ``KeyboardInterrupt``
    and raises ``RuntimeError: Query interrupted`` (or an error of its own) in its place: an error
    that comes while an interrupt is recorded (:func:`tyrelab.interrupts.requested`) is that
    interrupt, here for every caller of the warehouse (a query, ``--describe``, the report's reads),
    never a query error printed before "interrupted".
    """
    if not isinstance(exc, KeyboardInterrupt) and interrupts.requested():
        raise KeyboardInterrupt from exc


def _statement(con: duckdb.DuckDBPyConnection, statement: str, timeout_s: float | None) -> pd.DataFrame:
    """One statement's result, run in a helper thread so that this one can stop it.

    DuckDB runs a statement with the GIL released and does not always look for Ctrl-C while
    it does (an aggregate over a large range ran on after SIGINT and SIGTERM): this thread
    waits instead, and on Ctrl-C/SIGTERM (KeyboardInterrupt) or at the time limit interrupts
    the statement (``con.interrupt()``) and waits for it to stop.
    """
    import threading
    import time

    box: dict = {}
    done = threading.Event()  # not Thread.join: one interrupted by Ctrl-C may return early later (Python 3.11)

    def run() -> None:
        try:
            box["df"] = con.execute(statement).df()
        except BaseException as exc:  # noqa: BLE001 - handed to the waiting thread
            box["exc"] = exc
        finally:
            done.set()

    def stop() -> None:
        while True:
            try:
                con.interrupt()
                if done.wait(0.1):
                    return
            except KeyboardInterrupt:  # a second Ctrl-C: the statement is being stopped already
                continue

    deadline = None if timeout_s is None else time.monotonic() + timeout_s
    threading.Thread(target=run, name="tyrelab-sql", daemon=True).start()
    try:
        hold("sql-statement")  # a test's Ctrl-C lands here: the statement handed to DuckDB's thread
        while not done.wait(0.1 if deadline is None else max(0.0, min(0.1, deadline - time.monotonic()))):
            interrupts.check()  # a Ctrl-C that DuckDB swallowed on this thread (tyrelab.interrupts)
            if deadline is not None and time.monotonic() >= deadline:
                stop()
                if "df" not in box:
                    raise QueryTimeout(f"statement stopped after {timeout_s:g} s (the time limit)")
    except KeyboardInterrupt:
        stop()
        raise
    if "exc" in box:
        _interrupted(box["exc"])
        raise box["exc"]
    return box["df"]


#: Rows per batch of a streamed result (:func:`iter_query`).
BATCH_ROWS = 1 << 14


def _pandas(batch) -> pd.DataFrame:
    """A result batch as DuckDB's ``df()`` gives it: integers as pandas' nullable integers (so that
    a batch with a NULL and one without print alike)."""
    import pyarrow as pa

    ints = {t: d for t, d in ((pa.int8(), pd.Int8Dtype()), (pa.int16(), pd.Int16Dtype()), (pa.int32(), pd.Int32Dtype()),
                              (pa.int64(), pd.Int64Dtype()), (pa.uint8(), pd.UInt8Dtype()),
                              (pa.uint16(), pd.UInt16Dtype()), (pa.uint32(), pd.UInt32Dtype()),
                              (pa.uint64(), pd.UInt64Dtype()))}
    names = list(batch.schema.names)
    if len(set(names)) < len(names):  # SELECT 1 AS a, 'x' AS a: pyarrow mixes up columns of one name
        df = pa.Table.from_batches([batch]).rename_columns([f"c{i}" for i in range(len(names))]).to_pandas(
            types_mapper=ints.get)
        df.columns = names
    else:
        df = batch.to_pandas(types_mapper=ints.get)
    for i, field in enumerate(batch.schema):  # text as DuckDB gives it: objects, a NULL as None (not NaN)
        if pa.types.is_string(field.type) or pa.types.is_large_string(field.type):
            col = df.iloc[:, i].astype(object)
            df.isetitem(i, col.where(col.notna(), None))
    return df


def _streamed(con: duckdb.DuckDBPyConnection, statement: str, timeout_s: float | None):
    """The batches of one statement's result (pyarrow RecordBatches, :data:`BATCH_ROWS` rows), fetched in
    a helper thread into a queue of two: the result is never held whole. Ctrl-C and the time limit
    interrupt the statement (as :func:`_statement`); a caller that stops early (its reader went away)
    stops the helper. Yields the schema first."""
    import queue
    import threading
    import time

    box: queue.Queue = queue.Queue(maxsize=2)
    quit_ = threading.Event()

    def put(item) -> bool:
        while not quit_.is_set():
            try:
                box.put(item, timeout=0.1)
                return True
            except queue.Full:
                continue
        return False

    def run() -> None:
        try:
            reader = con.sql(statement).to_arrow_reader(BATCH_ROWS)
            if not put(("schema", reader.schema)):
                return
            for batch in reader:
                if not put(("batch", batch)):
                    return
            put(("end", None))
        except BaseException as exc:  # noqa: BLE001 - handed to the waiting thread
            put(("exc", exc))

    def stop(helper) -> None:
        quit_.set()
        while helper.is_alive():
            try:
                con.interrupt()
                helper.join(0.1)
            except KeyboardInterrupt:  # a second Ctrl-C: the statement is being stopped already
                continue

    deadline = None if timeout_s is None else time.monotonic() + timeout_s
    helper = threading.Thread(target=run, name="tyrelab-sql", daemon=True)
    helper.start()
    finished = False
    try:
        hold("sql-statement")  # a test's Ctrl-C lands here: the statement handed to DuckDB's thread
        while True:
            try:
                kind, item = box.get(timeout=0.1 if deadline is None else max(0.0, min(0.1, deadline - time.monotonic())))
            except queue.Empty:
                interrupts.check()  # a Ctrl-C that DuckDB swallowed on this thread (tyrelab.interrupts)
                if deadline is not None and time.monotonic() >= deadline:
                    raise QueryTimeout(f"statement stopped after {timeout_s:g} s (the time limit)") from None
                continue
            if kind == "exc":
                _interrupted(item)
                raise item
            if kind == "end":
                finished = True
                return
            yield kind, item
    finally:
        if not finished:
            stop(helper)


def iter_query(db_path: Path, sql: str, limits: QueryLimits | None = None):
    """Run one or several read-only statements (``;``-separated) and stream their results: yields,
    per statement, its column names and an iterator of DataFrames (:data:`BATCH_ROWS` rows each,
    read only as the caller asks for them). What ``tyrelab sql`` prints: a result larger than memory
    is written as it comes, never held whole.

    Raises as :func:`query_all` does (while the batches are read).
    """
    statements = check_read_only(sql)
    con = connect_read_only(db_path, limits)
    timeout_s = limits.timeout_s if limits is not None else None
    try:
        for statement in statements:
            stream = _streamed(con, statement, timeout_s)
            try:
                kind, schema = next(stream)
                yield list(schema.names), (_pandas(batch) for kind, batch in stream)
            finally:
                stream.close()
    finally:
        con.close()


@contextlib.contextmanager
def memory_bound(memory_limit_bytes: int, headroom_bytes: int = 512 * 2**20):
    """Bound this process's data memory (``RLIMIT_DATA``) to what it uses now, plus twice
    ``memory_limit_bytes`` and ``headroom_bytes``, while the block runs (then the previous limit).

    DuckDB's ``memory_limit`` bounds its buffers, not every allocation (``repeat('x', 1e9)`` builds
    a 1 GB string outside it, and the command's copy to print it another): under this bound such
    an allocation fails (DuckDB's out-of-memory error, Python's ``MemoryError``) instead of taking
    the machine's memory. A no-op where the limit cannot be read or set.
    """
    import resource

    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            now = next(int(line.split()[1]) * 1024 for line in fh if line.startswith("VmData:"))
        soft, hard = resource.getrlimit(resource.RLIMIT_DATA)
        bound = now + 2 * memory_limit_bytes + headroom_bytes
        if hard != resource.RLIM_INFINITY:
            bound = min(bound, hard)
        if soft != resource.RLIM_INFINITY:
            bound = min(bound, soft)
        resource.setrlimit(resource.RLIMIT_DATA, (bound, hard))
    except (OSError, ValueError, StopIteration):
        yield
        return
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_DATA, (soft, hard))


def query_all(db_path: Path, sql: str, limits: QueryLimits | None = None) -> list[pd.DataFrame]:
    """Run one or several read-only statements (``;``-separated); return one DataFrame each.

    ``db_path`` is the warehouse file or the build folder holding it (:func:`warehouse_path`).

    ``limits`` bounds memory, spill space and the time of each statement (:class:`QueryLimits`).

    Raises
    ------
    QueryTimeout
        A statement ran longer than ``limits.timeout_s``.
    KeyboardInterrupt
        Ctrl-C (or SIGTERM through the command line's handler) during a statement: it is stopped first.
    """
    statements = check_read_only(sql)
    con = connect_read_only(db_path, limits)
    timeout_s = limits.timeout_s if limits is not None else None
    try:
        return [_statement(con, st, timeout_s) for st in statements]
    finally:
        con.close()


def query(db_path: Path, sql: str, limits: QueryLimits | None = None) -> pd.DataFrame:
    """Run a read-only query against the warehouse (the file, or the build folder holding it) and
    return a DataFrame (of the last statement).

    See Also
    --------
    query_all : every statement's result.
    error_line : one line, with the closest names, for a query DuckDB refuses.

    Examples
    --------
    >>> import tempfile, pandas as pd
    >>> from tyrelab import io
    >>> build = Path(tempfile.mkdtemp())
    >>> _ = io.write_parquet_atomic(pd.DataFrame({"tyre_id": ["T1", "T2"], "k": [300.0, 350.0]}),
    ...                             build / "parquet" / "tyres.parquet")
    >>> _ = build_warehouse(build / "warehouse.duckdb", build / "parquet")
    >>> query(build, "SELECT tyre_id, k FROM tyres WHERE k > 320")
      tyre_id      k
    0      T2  350.0
    """
    return query_all(db_path, sql, limits)[-1]


#: DuckDB's messages for a name it does not know: (pattern of the unknown name, what it is).
_UNKNOWN_NAME = (
    (re.compile(r'Referenced column "([^"]+)" not found'), "column"),
    (re.compile(r'does not have a column named "([^"]+)"'), "column"),
    (re.compile(r'Table "[^"]+" does not have a column with name "([^"]+)"'), "column"),
    (re.compile(r'Table with name ([^ ]+) does not exist'), "table"),
)


def did_you_mean(name: str, candidates) -> list[str]:
    """The candidates closest to a misspelt ``name`` (at most three, best first; case ignored).

    Parameters
    ----------
    name : str
        The name as the user wrote it.
    candidates : iterable of str
        The names that exist.

    Returns
    -------
    list of str
        Close candidates by :func:`difflib.get_close_matches` (ratio at least 0.6), ``[]`` if none.

    See Also
    --------
    error_line : the one line ``tyrelab sql`` prints for a query DuckDB refuses.

    Examples
    --------
    >>> did_you_mean("tyre_idd", ["tyre_id", "pressure_bar", "tyre_size"])
    ['tyre_id', 'tyre_size']
    >>> did_you_mean("PRESSURE", ["pressure_bar"])
    ['pressure_bar']
    >>> did_you_mean("zzz", ["tyre_id"])
    []
    """
    import difflib

    names = {str(c).lower(): str(c) for c in candidates}
    return [names[m] for m in difflib.get_close_matches(str(name).lower(), list(names), n=3, cutoff=0.6)]


def error_line(db_path: Path, exc: BaseException) -> str:
    """One line for a query DuckDB refused: the first line of its message and, where it names a
    column or table the warehouse does not have, the closest names that it has ("did you mean").

    DuckDB's own candidate list (a binder error's second line) ranks every column of the query's
    tables; this one ranks the names of the whole warehouse by spelling (:func:`did_you_mean`).

    See Also
    --------
    did_you_mean : the ranking.

    Examples
    --------
    >>> import tempfile, pandas as pd
    >>> from tyrelab import io
    >>> tmp = Path(tempfile.mkdtemp())
    >>> _ = io.write_parquet_atomic(pd.DataFrame({"tyre_id": ["T1"], "pressure_bar": [1.2]}), tmp / "parquet" / "tyres.parquet")
    >>> _ = build_warehouse(tmp / "warehouse.duckdb", tmp / "parquet")
    >>> try:
    ...     query(tmp, "SELECT tyre_idd FROM tyres")
    ... except duckdb.Error as exc:
    ...     print(error_line(tmp, exc))
    Binder Error: Referenced column "tyre_idd" not found in FROM clause; did you mean "tyre_id"?
    >>> try:
    ...     query(tmp, "SELECT * FROM tyre")
    ... except duckdb.Error as exc:
    ...     print(error_line(tmp, exc))
    Catalog Error: Table with name tyre does not exist; did you mean "tyres"?
    """
    text = str(exc)
    first = text.splitlines()[0] if text else type(exc).__name__
    for pattern, kind in _UNKNOWN_NAME:
        m = pattern.search(text)
        if not m:
            continue
        try:
            con = connect_read_only(db_path)
        except (OSError, duckdb.Error):
            return first
        try:
            if kind == "table":
                names = [r[0] for r in con.execute(
                    "SELECT table_name FROM duckdb_tables() WHERE database_name = 'warehouse' UNION "
                    "SELECT view_name FROM duckdb_views() WHERE database_name = 'warehouse' AND NOT internal").fetchall()]
            else:
                names = [r[0] for r in con.execute(
                    "SELECT DISTINCT column_name FROM duckdb_columns() WHERE database_name = 'warehouse'").fetchall()]
                if any(r[0] == "runs" for r in con.execute("SELECT view_name FROM duckdb_views() "
                                                            "WHERE database_name = 'warehouse' AND NOT internal").fetchall()):
                    try:
                        names += [r[0] for r in con.execute("DESCRIBE runs").fetchall()]
                    except duckdb.Error:
                        pass
        except duckdb.Error:
            return first
        finally:
            con.close()
        bindings = re.search(r"Candidate bindings: (.*)", text)  # the columns of the query's own tables
        close = did_you_mean(m.group(1), re.findall(r'"([^"]+)"', bindings.group(1))) if bindings else []
        close = close or did_you_mean(m.group(1), names)
        if close:
            return f"{first.rstrip().rstrip('!')}; did you mean " + " or ".join(f'"{c}"' for c in close) + "?"
        return first
    return first

