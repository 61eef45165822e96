import os
import stat

import pandas as pd

from tyrelab import io
from tyrelab.stages import Context, run_stage
from tyrelab.warehouse import build_warehouse, query
from synthetic import manifest_row, spring_damper_recording, write_campaign


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
