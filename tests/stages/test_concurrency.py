"""`tyrelab sql` works while a pipeline run is rewriting the tables and the warehouse."""

import subprocess
import sys
import time

import pytest

from tests.holds import HANG_GUARD_S, Holds
from tests.stages.crashkit import campaign, start_run
from tyrelab.warehouse import query

pytestmark = pytest.mark.long  # collected first: see tests/conftest.py

COUNT = "SELECT count(*) AS n FROM results JOIN manifest USING (run_id)"


def _cli_count(build) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "tyrelab.cli", "sql", "--build", str(build), "--format", "csv",
                           "SELECT count(*) AS n FROM results"], capture_output=True, text=True)


# "replace" in the default run; the same readers before the warehouse stage (11 s) with -m slow (the budget)
@pytest.mark.parametrize("point", [pytest.param("stage-warehouse", marks=pytest.mark.slow), "replace"])
def test_queries_while_the_pipeline_writes(tmp_path, point):
    """Readers (the library and the command) while a forced run is held in the middle of its writes
    (before the warehouse stage rewrites the database, or with a table written but not yet renamed
    over the old one), then while it goes on (three forced runs in a row): every read sees the 16 runs."""
    raw, build = campaign(tmp_path / "raw" / "c", n=16), tmp_path / "build"
    assert start_run(raw, build).wait() == 0
    db = build / "warehouse.duckdb"
    holds = Holds(tmp_path / "holds")
    holds.hold(point, 3 if point == "replace" else 1)  # the third file the first forced run replaces
    writer = start_run(raw, build, "--force", repeat=3, env=holds.env)
    holds.wait(point, writer)
    held = [int(query(db, COUNT)["n"][0]) for _ in range(3)]  # while the writer is inside its run, for sure
    out = _cli_count(build)
    assert out.returncode == 0 and out.stdout.split() == ["n", "16"], out.stderr
    assert not holds.passed(point)
    holds.release(point)
    counts, errors = [], []
    while writer.poll() is None:  # and while it goes on, as often as it comes
        try:
            counts.append(int(query(db, COUNT)["n"][0]))
        except Exception as exc:  # noqa: BLE001 - any failure is what the test looks for
            errors.append(f"{type(exc).__name__}: {exc}")
        time.sleep(0.05)  # a reader every 50 ms, not a busy loop taking the writer's core
    assert writer.wait(timeout=HANG_GUARD_S) == 0, writer.stderr.read()
    assert holds.passed(point)
    assert not errors, errors[:3]
    assert held == [16, 16, 16] and set(counts) <= {16}
