"""`tyrelab sql` is read-only by construction (issue 11, defects 2 and 11)."""

import json

import pytest

from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
from tyrelab.cli import main
from tyrelab.stages import Context, run_stage
from tyrelab.warehouse import WriteRefused, connect_read_only, query, query_all


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    root = tmp_path_factory.mktemp("sql")
    raw = write_campaign(root / "raw", [(manifest_row("a1", "a1.parquet"), spring_damper_recording(duration_s=20))])
    ctx = Context(raw=raw, build=root / "build", jobs=1)
    for s in ("ingest", "analyse", "calibrate", "warehouse"):
        run_stage(s, ctx)
    return ctx.build


def sql(build, text, capsys, fmt="csv"):
    rc = main(["sql", "--build", str(build), "--format", fmt, text])
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_explain_analyze_copy_cannot_write(build, capsys, tmp_path):
    target = build / "parquet" / "results.parquet"
    before = target.read_bytes()
    for text in (f"EXPLAIN ANALYZE COPY (SELECT 1 AS a) TO '{target}' (FORMAT parquet)",
                 f"COPY (SELECT 1 AS a) TO '{tmp_path / 'x.csv'}'",
                 "EXPLAIN SELECT 1", "PRAGMA show_tables", "SET enable_external_access = true",
                 "INSTALL httpfs", "CALL pragma_version()", "CREATE TABLE t AS SELECT 1"):
        rc, out, err = sql(build, text, capsys)
        assert rc == 2 and "refused" in err and out == "", text
    assert target.read_bytes() == before
    assert not (tmp_path / "x.csv").exists()


def test_no_file_outside_the_warehouse_and_no_extension_download(build, tmp_path, monkeypatch):
    home = tmp_path / "home"
    monkeypatch.setenv("HOME", str(home))
    secret = tmp_path / "secret.csv"
    secret.write_text("a\n1\n")
    for text in (f"SELECT * FROM read_csv('{secret}')", "SELECT * FROM read_csv('https://example.invalid/x.csv')",
                 f"SELECT * FROM read_csv('{build}/parquet/../../../{secret.parent.name}/secret.csv')",
                 f"ATTACH '{tmp_path / 'other.duckdb'}'"):
        with pytest.raises(Exception) as info:
            query(build / "warehouse.duckdb", text)
        assert isinstance(info.value, WriteRefused) or "disabled by configuration" in str(info.value), text
    assert not home.exists()  # nothing installed into ~/.duckdb
    assert not (tmp_path / "other.duckdb").exists()


def test_configuration_is_locked(build):
    con = connect_read_only(build / "warehouse.duckdb")
    try:
        rows = dict(con.execute("SELECT name, value FROM duckdb_settings() WHERE name IN ('enable_external_access',"
                                "'autoinstall_known_extensions', 'autoload_known_extensions', 'lock_configuration')"
                                ).fetchall())
        assert rows == {"enable_external_access": "false", "autoinstall_known_extensions": "false",
                        "autoload_known_extensions": "false", "lock_configuration": "true"}
        with pytest.raises(Exception, match="locked"):
            con.execute("SET enable_external_access = true")
    finally:
        con.close()


@pytest.mark.parametrize("text", ["SELECT count(*) AS n FROM results", "WITH x AS (SELECT 1 AS n) SELECT n FROM x",
                                  "DESCRIBE results", "SHOW TABLES", "SUMMARIZE results", "FROM manifest"])
def test_queries_are_allowed(build, text):
    assert len(query(build / "warehouse.duckdb", text)) >= 1


def test_every_statement_is_printed(build, capsys):
    rc, out, _ = sql(build, "SELECT 1 AS a; SELECT 2 AS b", capsys)
    assert rc == 0 and out.split() == ["a", "1", "b", "2"]
    rc, out, _ = sql(build, "SELECT 1 AS a; SELECT 2 AS b;", capsys, fmt="json")
    assert rc == 0 and [json.loads(line) for line in out.splitlines()] == [[{"a": 1}], [{"b": 2}]]
    assert [len(df) for df in query_all(build / "warehouse.duckdb", "SELECT 1; SELECT 2 UNION ALL SELECT 3")] == [1, 2]


def test_a_misspelt_column_or_table_gets_the_closest_names(build, capsys):
    rc, out, err = sql(build, "SELECT run_idd FROM results", capsys)
    assert rc == 2 and out == "" and 'did you mean "run_id"' in err and err.count("\n") == 1
    rc, out, err = sql(build, "SELECT * FROM result", capsys)
    assert rc == 2 and 'did you mean "results"' in err
    rc, out, err = sql(build, "SELECT zzzzqqq FROM results", capsys)  # nothing close: DuckDB's line alone
    assert rc == 2 and "did you mean" not in err and "zzzzqqq" in err
