"""The DuckDB warehouse: a catalogue of views over the Parquet tables.

DuckDB allows one read-write process *or* many read-only ones on a database
file, never both. So the database holds only views over Parquet written by
the pipeline; it is rebuilt into a new file and renamed over the old one
(readers that already opened the old file keep it), and every query
(``tyrelab sql``, the report) opens it read-only. View paths are absolute,
because DuckDB resolves relative paths against the process' working folder.
"""

from __future__ import annotations

import logging
import re
from pathlib import Path

import duckdb
import pandas as pd
import pyarrow.parquet as pq

from . import io

__all__ = ["READ_ONLY_STATEMENTS", "WriteRefused", "view_name", "build_warehouse", "connect_read_only",
    "check_read_only", "query"]

log = logging.getLogger("tyrelab")

#: Statement types a query may run; anything else is refused.
READ_ONLY_STATEMENTS = {"SELECT", "EXPLAIN", "PRAGMA"}


class WriteRefused(ValueError):
    """Raised for a statement that would write to the warehouse."""


def view_name(stem: str) -> str:
    """A SQL identifier from a file stem (``table_iii`` stays ``table_iii``)."""
    return re.sub(r"\W", "_", stem).lower()


def _quote(path: Path) -> str:
    return "'" + str(path).replace("'", "''") + "'"


def build_warehouse(db_path: Path, parquet_dir: Path, published: dict[str, Path] | None = None) -> list[str]:
    """Create the warehouse at ``db_path`` atomically; return the view names.

    Parameters
    ----------
    db_path : Path
        The ``.duckdb`` file to (re)create.
    parquet_dir : Path
        Folder of ``<table>.parquet`` files and the ``runs/`` hive dataset.
    published : dict, optional
        View name -> Parquet path of the digitised thesis tables.
    """
    parquet_dir = Path(parquet_dir).resolve()
    views: dict[str, str] = {}
    for p in sorted(parquet_dir.glob("*.parquet")):
        if not pq.read_schema(p).names:
            log.warning("warehouse: %s has no columns; no view made", p)
            continue
        views[view_name(p.stem)] = f"SELECT * FROM read_parquet({_quote(p)})"
    runs = parquet_dir / "runs"
    if any(runs.glob("*/*.parquet")):
        # Partition folders are percent-encoded tyre ids (tyrelab.stages.ingest.tyre_partition).
        views["runs"] = (
            "SELECT * REPLACE (url_decode(tyre_id) AS tyre_id) FROM read_parquet("
            f"{_quote(runs / '*' / '*.parquet')}, hive_partitioning = true, "
            "hive_types = {'tyre_id': VARCHAR}, union_by_name = true)"
        )
    for name, path in (published or {}).items():
        views[name] = f"SELECT * FROM read_parquet({_quote(Path(path).resolve())})"
    with io.atomic_path(db_path) as tmp:
        tmp.unlink()  # DuckDB wants to create the file itself
        con = duckdb.connect(str(tmp))
        try:
            for name, sql in views.items():
                con.execute(f'CREATE VIEW "{name}" AS {sql}')
        finally:
            con.close()
        wal = Path(str(tmp) + ".wal")
        if wal.exists():
            wal.unlink()
    return list(views)


def connect_read_only(db_path: Path) -> duckdb.DuckDBPyConnection:
    """Open the warehouse read-only (many readers may do so while the pipeline writes)."""
    db_path = Path(db_path)
    if not db_path.exists():
        raise FileNotFoundError(f"{db_path}: no warehouse yet - run 'tyrelab run' first")
    return duckdb.connect(str(db_path), read_only=True)


def check_read_only(sql: str) -> None:
    """Refuse any statement that is not a query.

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
                f"refused: {kind} statements write to the warehouse; 'tyrelab sql' runs read-only queries (SELECT)"
            )


def query(db_path: Path, sql: str) -> pd.DataFrame:
    """Run a read-only query against the warehouse and return a DataFrame."""
    check_read_only(sql)
    con = connect_read_only(db_path)
    try:
        return con.execute(sql).df()
    finally:
        con.close()
