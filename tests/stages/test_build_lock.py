"""One writer per build (issue 11, defect 9): a lock naming its holder; readers never blocked."""

import json
import os
import signal
import subprocess
import sys

import pytest

from tests.holds import HANG_GUARD_S, Holds
from tests.stages.crashkit import campaign, start_run
from tyrelab.buildlock import LOCK_NAME, BuildLock, BuildLocked
from tyrelab.cli import main
from tyrelab.warehouse import query

pytestmark = pytest.mark.long  # collected first: see tests/conftest.py

QUERY = "SELECT run_id, stiffness_kN_per_m FROM results ORDER BY run_id"


@pytest.fixture(scope="module")
def raw(tmp_path_factory):
    return campaign(tmp_path_factory.mktemp("raw") / "c", n=6)


def test_second_writer_exits_2_naming_the_holder(raw, tmp_path, capsys):
    build = tmp_path / "b"
    with BuildLock(build, "tyrelab run"):
        for verb in (["run"], ["ingest"], ["warehouse"]):
            assert main([*verb, "--raw", str(raw), "--build", str(build)]) == 2
            err = capsys.readouterr().err
            assert f"pid {os.getpid()}" in err and "tyrelab run" in err and "being written" in err
        with pytest.raises(BuildLocked):
            BuildLock(build, "x").acquire()
    assert main(["ingest", "--raw", str(raw), "--build", str(build), "--jobs", "1"]) == 0  # released


def test_stale_lock_of_a_dead_process_is_taken_over(raw, tmp_path, caplog):
    build = tmp_path / "b"
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    build.mkdir()
    (build / LOCK_NAME).write_text(json.dumps({"pid": dead.pid, "command": "tyrelab run", "start_ticks": 1}))
    assert main(["ingest", "--raw", str(raw), "--build", str(build), "--jobs", "1"]) == 0
    assert any("stale lock" in r.message and str(dead.pid) in r.message for r in caplog.records)
    assert (build / LOCK_NAME).read_text() == ""  # released: no holder named


def test_two_writers_the_second_refused_the_first_unaffected(raw, tmp_path):
    build = tmp_path / "b"
    assert start_run(raw, build).wait() == 0
    expected = query(build / "warehouse.duckdb", QUERY)
    holds = Holds(tmp_path / "holds")
    holds.hold("stage-analyse")  # the first writer holds the lock, inside its run, until released
    first = start_run(raw, build, "--force", env=holds.env)
    assert holds.wait("stage-analyse", first) == first.pid
    assert json.loads((build / LOCK_NAME).read_text())["pid"] == first.pid
    assert len(query(build / "warehouse.duckdb", QUERY)) == len(expected)  # a reader is not blocked
    second = start_run(raw, build, "--force")
    out, err = second.communicate(timeout=HANG_GUARD_S)
    assert second.returncode == 2 and f"pid {first.pid}" in err, err
    assert not holds.passed("stage-analyse")  # the second ran while the first was inside its run
    holds.release("stage-analyse")
    assert first.wait(timeout=HANG_GUARD_S) == 0, first.stderr.read()
    assert holds.passed("stage-analyse")
    assert query(build / "warehouse.duckdb", QUERY).equals(expected)


@pytest.mark.parametrize("point", ["stage-analyse", "replace"])
def test_sigint_ends_without_a_traceback(raw, tmp_path, point):
    """Ctrl-C while the run is held at a stage's start, or with a file written but not yet renamed
    over its target: one line, exit 130, the lock released, no temporary file left."""
    build = tmp_path / "b"
    holds = Holds(tmp_path / "holds")
    holds.hold(point)
    proc = start_run(raw, build, "--force", env=holds.env)
    holds.wait(point, proc)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=HANG_GUARD_S)
    assert proc.returncode == 130, err
    assert not holds.passed(point)  # the signal landed inside the run
    assert "Traceback" not in err and "interrupted" in err.splitlines()[-1]
    assert (build / LOCK_NAME).read_text() == ""
    assert not [p for p in build.rglob("*") if p.name.endswith(".tmp")]


def test_build_that_is_a_file_is_one_line(raw, tmp_path, capsys):
    build = tmp_path / "b"
    build.write_text("not a folder")
    assert main(["run", "--raw", str(raw), "--build", str(build)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and str(build) in err and "not a folder" in err
