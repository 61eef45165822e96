import os
import stat

import pandas as pd

from tyrelab import io
from tyrelab.stages import Context, run_stage
from tyrelab.warehouse import build_warehouse, query
from tests.synthetic import manifest_row, spring_damper_recording, write_campaign


def test_runs_view_decodes_tyre_ids(tmp_path):
    raw = write_campaign(tmp_path / "raw", [(manifest_row("x1", "x1.parquet", tyre_id="<b>&1"), spring_damper_recording())])
    pd.DataFrame({"tyre_id": ["<b>&1"], "size": ["13.6R38"]}).to_csv(raw / "tyres.csv", index=False)
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1)
    for s in ("ingest", "analyse", "warehouse"):
        run_stage(s, ctx)
    db = ctx.build / "warehouse.duckdb"
    assert query(db, "SELECT DISTINCT tyre_id FROM runs")["tyre_id"].tolist() == ["<b>&1"]
    joined = query(db, "SELECT count(*) AS n FROM runs JOIN manifest USING (run_id, tyre_id)")
    assert joined["n"].iloc[0] == 12800


def test_all_runs_quarantined_still_builds_a_warehouse(tmp_path):
    raw = write_campaign(tmp_path / "raw", [(manifest_row("s1", "s1.parquet"), spring_damper_recording(duration_s=5))])
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1)
    for s in ("ingest", "analyse", "warehouse"):
        run_stage(s, ctx)
    db = ctx.build / "warehouse.duckdb"
    assert query(db, "SELECT count(*) AS n FROM manifest")["n"].iloc[0] == 0
    assert query(db, "SELECT reason FROM quarantine")["reason"].str.contains("shorter").all()


def test_outputs_have_ordinary_permissions(tmp_path):
    out = io.write_text_atomic("x", tmp_path / "a.txt")
    umask = os.umask(0)
    os.umask(umask)
    assert stat.S_IMODE(out.stat().st_mode) == 0o666 & ~umask


def test_warehouse_is_replaced_atomically_while_a_reader_holds_it(tmp_path):
    pq_dir = tmp_path / "parquet"
    io.write_parquet_atomic(pd.DataFrame({"a": [1, 2]}), pq_dir / "t.parquet")
    db = tmp_path / "w.duckdb"
    build_warehouse(db, pq_dir)
    import duckdb

    reader = duckdb.connect(str(db), read_only=True)
    io.write_parquet_atomic(pd.DataFrame({"a": [1, 2, 3]}), pq_dir / "t.parquet")
    build_warehouse(db, pq_dir)  # no lock error although a reader has the old file open
    assert query(db, "SELECT count(*) AS n FROM t")["n"].iloc[0] == 3
    reader.close()


def test_moved_build_answers_from_another_folder(tmp_path, monkeypatch):
    """The warehouse is portable: move the build, delete nothing else, query it from elsewhere."""
    import shutil

    import duckdb

    raw = write_campaign(tmp_path / "raw", [(manifest_row("m1", "m1.parquet"), spring_damper_recording()),
                                            (manifest_row("m2", "m2.parquet", tyre_id="T2"), spring_damper_recording(seed=2))])
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1)
    for s in ("ingest", "analyse", "calibrate", "warehouse"):  # calibrate writes results
        run_stage(s, ctx)
    before = query(ctx.build / "warehouse.duckdb", "SELECT count(*) AS n FROM results")["n"].iloc[0]
    assert before == 2
    copied = shutil.copytree(ctx.build, tmp_path / "colleague" / "build-copy")
    moved = shutil.move(str(ctx.build), str(tmp_path / "server" / "moved-build"))
    elsewhere = tmp_path / "somewhere" / "else"
    elsewhere.mkdir(parents=True)
    monkeypatch.chdir(elsewhere)
    for build in (copied, moved):
        con = duckdb.connect(str(build / "warehouse.duckdb") if hasattr(build, "joinpath") else f"{build}/warehouse.duckdb",
                             read_only=True)
        try:
            assert con.execute("SELECT count(*) FROM results").fetchone()[0] == before
            assert con.execute("SELECT count(*) FROM published_table_ii").fetchone()[0] > 0
        finally:
            con.close()
    # runs too, through tyrelab and with the stock client from another folder (issue 47: the file
    # holds no view and no path, so nothing resolves against the working folder)
    n_runs = query(f"{moved}/warehouse.duckdb", "SELECT count(DISTINCT run_id) AS n FROM runs")["n"].iloc[0]
    assert n_runs == 2
    for build in (copied, moved):
        con = duckdb.connect(f"{build}/warehouse.duckdb", read_only=True)
        try:
            assert con.execute("SELECT count(*) FROM runs").fetchone()[0] == 2 * 12800
            assert con.execute("SELECT count(*) FROM duckdb_views() WHERE NOT internal").fetchone()[0] == 0
            assert con.execute("SELECT DISTINCT tyre_id FROM runs ORDER BY 1").fetchall() == [("T1",), ("T2",)]
        finally:
            con.close()


def test_store_runs_view_is_the_former_layout(tmp_path, monkeypatch):
    """``store="runs_view"``: ``runs`` a view relative to the file's folder (issue 10's layout, for the
    benchmark): a stock client finds it from the build folder only."""
    import duckdb
    import pytest

    pq_dir = tmp_path / "build" / "parquet"
    io.write_parquet_atomic(pd.DataFrame({"run_id": ["a"], "x": [1.0]}), pq_dir / "runs" / "tyre_id=T1" / "a.parquet")
    build_warehouse(tmp_path / "build" / "warehouse.duckdb", pq_dir, store="runs_view")
    assert query(tmp_path / "build", "SELECT count(*) AS n FROM runs")["n"].iloc[0] == 1
    monkeypatch.chdir(tmp_path)
    con = duckdb.connect("build/warehouse.duckdb", read_only=True)
    try:
        with pytest.raises(duckdb.IOException, match="No files found"):
            con.execute("SELECT count(*) FROM runs")
    finally:
        con.close()


def test_store_views_is_the_absolute_path_layout(tmp_path):
    import pytest

    pq_dir = tmp_path / "parquet"
    io.write_parquet_atomic(pd.DataFrame({"a": [1, 2]}), pq_dir / "t.parquet")
    build_warehouse(tmp_path / "w.duckdb", pq_dir, store="views")
    sql = query(tmp_path / "w.duckdb", "SELECT sql FROM duckdb_views() WHERE view_name = 't'")["sql"].iloc[0]
    assert str(pq_dir.resolve()) in sql
    with pytest.raises(ValueError, match="store"):
        build_warehouse(tmp_path / "w.duckdb", pq_dir, store="copy")
    with pytest.raises(ValueError, match="block_size_bytes"):
        build_warehouse(tmp_path / "w.duckdb", pq_dir, block_size_bytes=20000)


def test_each_table_made_is_counted_for_progress(tmp_path):
    pq_dir = tmp_path / "parquet"
    for name in ("a", "b", "c"):
        io.write_parquet_atomic(pd.DataFrame({"x": [1]}), pq_dir / f"{name}.parquet")
    calls = []
    names = build_warehouse(tmp_path / "w.duckdb", pq_dir, on_table=lambda done, total: calls.append((done, total)))
    assert names == ["a", "b", "c"] and calls == [(1, 3), (2, 3), (3, 3)]
