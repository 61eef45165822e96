"""`tyrelab sql` is bounded: spills only inside the build, memory limit, statement timeout, Ctrl-C (issue 25)."""

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from tests.holds import HANG_GUARD_S, Holds
from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
from tyrelab.cli import main
from tyrelab.stages import Context, run_stage
from tyrelab.warehouse import SPILL_FOLDER, QueryLimits, QueryTimeout, connect_read_only, parse_size, query

#: A sort of 2 million 32-character strings: more than an 80 MB memory limit holds, so DuckDB spills.
BIG_SORT = "SELECT count(*) AS n FROM (SELECT md5(i::VARCHAR) AS m FROM range(2000000) t(i) ORDER BY m OFFSET 1)"
SMALL_MEMORY = ["--memory-limit", "80MB"]
#: A statement that runs for minutes.
LONG = "SELECT sum(hash(i)) AS s FROM range(100000000000) t(i)"


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    root = tmp_path_factory.mktemp("sqlres")
    raw = write_campaign(root / "raw", [(manifest_row("a1", "a1.parquet"), spring_damper_recording(duration_s=20))])
    ctx = Context(raw=raw, build=root / "build", jobs=1)
    for s in ("ingest", "analyse", "warehouse"):
        run_stage(s, ctx)
    return ctx.build


@pytest.fixture
def elsewhere(tmp_path, monkeypatch):
    """The caller's working folder: nothing may be written into it."""
    cwd = tmp_path / "cwd"
    cwd.mkdir()
    monkeypatch.chdir(cwd)
    return cwd


def sql(build, capsys, *args):
    rc = main(["sql", "--build", str(build), "--format", "csv", *args])
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_a_large_sort_spills_inside_the_build_only(build, elsewhere, capsys):
    rc, out, err = sql(build, capsys, *SMALL_MEMORY, BIG_SORT)
    assert rc == 0, err
    assert out.split() == ["n", "1999999"]
    assert list(elsewhere.iterdir()) == []  # DuckDB's default spill folder is .tmp here
    assert list(build.glob(SPILL_FOLDER + "*")) == []  # the session's folder is gone with it


def test_spill_is_bounded_and_can_be_off(build, elsewhere, capsys):
    for limit in ("0", "5MB"):
        rc, out, err = sql(build, capsys, *SMALL_MEMORY, "--max-spill", limit, BIG_SORT)
        assert rc == 2 and out == "", limit
        assert err.count("\n") == 1 and "--memory-limit" in err and "Traceback" not in err, err
    assert list(elsewhere.iterdir()) == []


def test_settings_of_a_session(build):
    con = connect_read_only(build / "warehouse.duckdb", QueryLimits(memory_limit_bytes=parse_size("64MiB")))
    try:
        rows = dict(con.execute("SELECT name, value FROM duckdb_settings() WHERE name IN "
                                "('memory_limit', 'temp_directory', 'max_temp_directory_size')").fetchall())
    finally:
        con.close()
    assert rows["memory_limit"] == "64.0 MiB"
    folder = Path(rows["temp_directory"])
    assert folder.parent == build.resolve() and folder.name.startswith(f"{SPILL_FOLDER}-{os.getpid()}-")
    assert rows["max_temp_directory_size"] == "4.0 GiB"


def test_a_killed_session_s_spill_folder_is_removed(build, tmp_path):
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()  # a pid that no longer runs
    stale = build / f"{SPILL_FOLDER}-{child.pid}-1"
    stale.mkdir()
    (stale / "duckdb_temp_storage-0.tmp").write_bytes(b"x" * 1000)
    mine = build / f"{SPILL_FOLDER}-{os.getpid()}-999999"  # a live process's: kept
    mine.mkdir()
    query(build / "warehouse.duckdb", "SELECT 1")
    assert not stale.exists() and mine.exists()
    mine.rmdir()


def test_a_read_only_build_spills_nothing(build, elsewhere, monkeypatch):
    import tyrelab.warehouse

    monkeypatch.setattr(tyrelab.warehouse.os, "access", lambda path, mode: False)  # (root may write anywhere)
    con = connect_read_only(build / "warehouse.duckdb", QueryLimits())
    try:
        assert con.execute("SELECT current_setting('temp_directory')").fetchone()[0] == ""
    finally:
        con.close()
    assert list(elsewhere.iterdir()) == []


def test_statement_timeout(build, capsys):
    with pytest.raises(QueryTimeout):
        query(build / "warehouse.duckdb", LONG, QueryLimits(timeout_s=0.3))
    rc, out, err = sql(build, capsys, "--timeout", "0.3", LONG)
    assert rc == 2 and out == "" and "--timeout" in err and err.count("\n") == 1


@pytest.mark.parametrize("args", [["--memory-limit", "lots"], ["--memory-limit", "0"], ["--timeout", "-1"],
                                  ["--max-spill", "1e999GB"]])
def test_bad_limits_are_usage_errors(build, capsys, args):
    try:
        rc = main(["sql", "--build", str(build), *args, "SELECT 1"])
    except SystemExit as exc:  # refused by the parser
        rc = exc.code
    assert rc == 2
    err = capsys.readouterr().err
    assert args[0] in err and "Traceback" not in err


def test_ctrl_c_exits_130(build, tmp_path):
    tyrelab = Path(sys.executable).with_name("tyrelab")
    holds = Holds(tmp_path / "holds")
    holds.hold("sql-statement")  # the command says when DuckDB runs the statement (it runs for minutes)
    proc = subprocess.Popen([str(tyrelab), "sql", "--build", str(build), LONG], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=holds.env)
    try:
        holds.wait("sql-statement", proc)
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=HANG_GUARD_S)
    finally:
        proc.kill()
    assert proc.returncode == 130, err
    assert not holds.passed("sql-statement")
    assert err.strip().splitlines()[-1] == "tyrelab sql: interrupted" and "Traceback" not in err


# DuckDB's Python module checks for signals while it runs a statement on the main thread: it catches the
# KeyboardInterrupt, clears it and raises "RuntimeError: Query interrupted" (a SET or ATTACH while the
# connection is made) or nothing (the statement finished anyway). Measured: one Ctrl-C in ~100 that landed
# while `tyrelab sql` connected ended as "RuntimeError: Query interrupted", exit 2, and one ran on with the
# statement (minutes). tyrelab.interrupts records the request besides raising.

def test_a_ctrl_c_that_duckdb_swallowed_still_stops_a_running_statement(build):
    import threading

    from tyrelab import interrupts
    from tyrelab.warehouse import iter_query

    previous = interrupts.install()
    try:
        # the handler ran and its KeyboardInterrupt was lost in DuckDB: only the record is left
        timer = threading.Timer(0.5, interrupts._requested.set)
        timer.start()
        with pytest.raises(KeyboardInterrupt):  # not QueryTimeout: the limit is the test's guard against a hang
            for _names, frames in iter_query(build / "warehouse.duckdb", LONG, QueryLimits(timeout_s=HANG_GUARD_S / 4)):
                for _ in frames:
                    pass
        timer.join()
    finally:
        interrupts.restore(previous)
        interrupts._requested.clear()


@pytest.mark.parametrize("describe", [False, True], ids=["query", "describe"])
@pytest.mark.parametrize("kind", ["RuntimeError", "InterruptException"])
def test_a_ctrl_c_that_duckdb_turned_into_query_interrupted_exits_130(build, capsys, monkeypatch, kind, describe):
    import duckdb

    from tyrelab import interrupts, warehouse

    class Connection:  # DuckDB's own connection, whose ATTACH met the Ctrl-C
        def execute(self, *args, **kwargs):
            interrupts._requested.set()  # SIGINT arrived; DuckDB cleared the KeyboardInterrupt and raised its own
            raise RuntimeError("Query interrupted") if kind == "RuntimeError" else duckdb.InterruptException("Interrupted!")

        def close(self):
            pass

    monkeypatch.setattr(warehouse.duckdb, "connect", lambda *args, **kwargs: Connection())
    try:  # the warehouse says "interrupted" for every caller: a query and --describe alike
        rc = main(["sql", "--build", str(build)] + (["--describe", "runs"] if describe else ["SELECT 1"]))
    finally:
        interrupts._requested.clear()
    err = capsys.readouterr().err
    assert rc == 130, err
    assert err.strip().splitlines() == ["tyrelab sql: interrupted"]
