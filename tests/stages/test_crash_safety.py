"""Killing `tyrelab run` at any moment leaves the previous warehouse readable; the next run completes."""

import json
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from tests.holds import Holds
from tests.stages.crashkit import STAGES, campaign, start_run
from tyrelab.warehouse import query

pytestmark = pytest.mark.long  # collected first: see tests/conftest.py

QUERY = "SELECT run_id, stiffness_kN_per_m, damping_kN_s_per_m FROM results ORDER BY run_id"


@pytest.fixture(scope="module")
def baseline(tmp_path_factory):
    raw = campaign(tmp_path_factory.mktemp("raw") / "c")
    build = tmp_path_factory.mktemp("build")
    assert start_run(raw, build).wait() == 0
    holds = Holds(tmp_path_factory.mktemp("holds"))
    holds.hold("replace", 0)  # count the files a forced run replaces (it holds at none)
    assert start_run(raw, build, "--force", env=holds.env).wait() == 0
    return raw, build, query(build / "warehouse.duckdb", QUERY), holds.count("replace")


def kill_then_rerun(raw, build, holds, point, occurrence, expected, *extra):
    """SIGKILL ``tyrelab run --force`` held at ``point`` (its ``occurrence``-th time there)."""
    holds.hold(point, occurrence)
    proc = start_run(raw, build, "--force", *extra, env=holds.env)
    holds.wait(point, proc)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert proc.returncode == -signal.SIGKILL and not holds.passed(point)  # killed inside its work
    readable = query(build / "warehouse.duckdb", QUERY)  # the previous warehouse, still readable
    assert len(readable) == len(expected)
    assert start_run(raw, build).wait() == 0
    assert query(build / "warehouse.duckdb", QUERY).equals(expected)


#: Where the run is killed: before a stage's work, or with a file written in full but not yet
#: renamed over its target (the first, the middle and the last of those a forced run replaces).
KILL_POINTS = ["stage-analyse", "stage-warehouse", "replace:first", "replace:middle", "replace:last"]


# The middle rename (as first and last: a table written, not yet renamed) with -m slow: the default run's budget
@pytest.mark.parametrize("where", [pytest.param(w, marks=pytest.mark.slow) if w == "replace:middle" else w
                                   for w in KILL_POINTS])
def test_sigkill_at_any_moment(baseline, tmp_path, where):
    raw, build0, expected, replaces = baseline
    assert replaces > 3
    point, _, which = where.partition(":")
    occurrence = {"": 1, "first": 1, "middle": replaces // 2, "last": replaces}[which]
    build = tmp_path / "build"
    shutil.copytree(build0, build)
    # state and views of the copy name build0's absolute paths: one run re-points them at this folder
    assert start_run(raw, build).wait() == 0
    kill_then_rerun(raw, build, Holds(tmp_path / "holds"), point, occurrence, expected)
    assert not list(build.rglob("*.tmp")) or start_run(raw, build).wait() == 0


def test_state_is_written_after_outputs(baseline, tmp_path):
    raw, build0, expected, _ = baseline
    build = tmp_path / "build"
    shutil.copytree(build0, build)
    assert start_run(raw, build).wait() == 0
    states = {s: json.loads((build / "state" / f"{s}.json").read_text()) for s in STAGES}
    for i, stage in enumerate(STAGES):
        later = {p for s in STAGES[i + 1:] for p in states[s]["outputs"]}  # e.g. quarantine: ingest, then analyse
        outputs = [build / p for p in states[stage]["outputs"] if p not in later]
        written = (build / "state" / f"{stage}.json").stat().st_mtime_ns
        assert outputs and all(p.stat().st_mtime_ns <= written for p in outputs)


@pytest.mark.slow
def test_sigkill_real_tyrelab_run(baseline, tmp_path):
    """The real console script with every installed stage (slow: other stages simulate for minutes),
    killed while it is held at the start of simulate."""
    raw, _, _, _ = baseline
    build = tmp_path / "build"
    beside = Path(sys.executable).parent / "tyrelab"  # the venv's console script
    bin_ = str(beside) if beside.exists() else shutil.which("tyrelab") or pytest.skip("tyrelab console script not installed")
    assert subprocess.run([bin_, "run", "--raw", str(raw), "--build", str(build)], capture_output=True).returncode == 0
    expected = query(build / "warehouse.duckdb", QUERY)
    holds = Holds(tmp_path / "holds")
    holds.hold("stage-simulate")
    proc = subprocess.Popen([bin_, "run", "--force", "--raw", str(raw), "--build", str(build)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=holds.env)
    holds.wait("stage-simulate", proc)
    proc.kill()
    proc.wait()
    assert proc.returncode == -signal.SIGKILL and not holds.passed("stage-simulate")
    assert len(query(build / "warehouse.duckdb", QUERY)) == len(expected)
    assert subprocess.run([bin_, "run", "--raw", str(raw), "--build", str(build)], capture_output=True).returncode == 0
    assert query(build / "warehouse.duckdb", QUERY).equals(expected)
