"""Warehouse layouts: tables stored in the file (portable) vs views over Parquet paths.

Usage: ``python bench/bench_warehouse.py [--build build] [--repeat 5]`` after
``make all`` (any build folder with ``parquet/``). Both layouts are built from
the same Parquet into a temporary folder, in this process (``views``: the
first layout, the baseline; ``runs_view``: tables stored, ``runs`` a view relative
to the file's folder, issue 10's layout; ``tables``: tyrelab's, every table and
``runs`` stored, 16 KiB blocks; ``tables_256k``: the same with DuckDB's default
block size); for each it prints
the file size, the build time, and the best-of-``repeat`` time of a fresh
read-only connection answering (1) ``select count(*) from results``, (2) every
table read whole into pandas (what the report does), (3) an aggregate over
``runs``; and the ratios to ``views``. Prints one JSON object.
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import tempfile
import time
from pathlib import Path

from tyrelab.warehouse import build_warehouse, connect_read_only


def published(parquet: Path) -> dict[str, Path]:
    return {f"published_{p.stem}": p for p in sorted((parquet / "published").glob("*.parquet"))}


def best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def queries(db: Path, names: list[str]) -> dict:
    def count():
        con = connect_read_only(db)
        con.execute("SELECT count(*) FROM results").fetchall()
        con.close()

    def whole_tables():
        con = connect_read_only(db)
        for n in names:
            if n != "runs":
                con.execute(f'SELECT * FROM "{n}"').df()
        con.close()

    def runs():
        con = connect_read_only(db)
        con.execute("SELECT run_id, avg(accel_left_m_s2) FROM runs GROUP BY run_id").fetchall()
        con.close()

    return {"count_results_s": count, "read_every_table_s": whole_tables, "runs_aggregate_s": runs}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default="build")
    p.add_argument("--repeat", type=int, default=5)
    args = p.parse_args(argv)
    parquet = Path(args.build) / "parquet"
    if not (parquet / "results.parquet").is_file():
        print(f"bench_warehouse: {parquet}/results.parquet not found; run 'make all' first", file=sys.stderr)
        return 2
    out: dict = {"parquet_MB": round(sum(f.stat().st_size for f in parquet.rglob("*.parquet")) / 1e6, 1),
                 "runs_parquet_MB": round(sum(f.stat().st_size for f in (parquet / "runs").rglob("*.parquet")) / 1e6, 1)}
    with tempfile.TemporaryDirectory() as tmp:
        # One copy of the Parquet beside each layout's file in turn: a read-only connection may read only
        # the database folder's parquet/ (tyrelab.warehouse.connect_read_only), absolute paths too.
        home = Path(tmp) / "build"
        shutil.copytree(parquet, home / "parquet")
        for layout, store, block in (("views", "views", 16384), ("runs_view", "runs_view", 16384),
                                     ("tables", "tables", 16384), ("tables_256k", "tables", 262144)):
            db = home / "warehouse.duckdb"
            t0 = time.perf_counter()
            names = build_warehouse(db, home / "parquet", published(home / "parquet"), store=store, block_size_bytes=block)
            r = {"file_MB": round(db.stat().st_size / 1e6, 2), "build_s": round(time.perf_counter() - t0, 3),
                 "objects": len(names)}
            for key, fn in queries(db, names).items():
                r[key] = round(best(fn, args.repeat), 4)
            out[layout] = r
            db.unlink()
    for layout in ("runs_view", "tables", "tables_256k"):
        out[f"ratio_{layout}_over_views"] = {k: round(out[layout][k] / out["views"][k], 2)
                                             for k in out["views"] if k != "objects"}
    out["ratio_tables_over_runs_view"] = {k: round(out["tables"][k] / out["runs_view"][k], 2)
                                          for k in out["views"] if k != "objects"}
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
