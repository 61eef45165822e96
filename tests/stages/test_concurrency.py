import pytest
"""`tyrelab sql` works while a pipeline run is rewriting the tables and the warehouse."""

import subprocess
import sys
import time

from tests.stages.crashkit import campaign, start_run
from tyrelab.warehouse import query

pytestmark = pytest.mark.long  # collected first: see tests/conftest.py


def test_queries_while_the_pipeline_writes(tmp_path):
    raw, build = campaign(tmp_path / "raw" / "c", n=16), tmp_path / "build"
    assert start_run(raw, build).wait() == 0
    db = build / "warehouse.duckdb"
    writer = start_run(raw, build, "--force", repeat=3)
    counts, errors, cli_ok = [], [], 0
    while writer.poll() is None:
        try:
            counts.append(int(query(db, "SELECT count(*) AS n FROM results JOIN manifest USING (run_id)")["n"][0]))
        except Exception as exc:  # noqa: BLE001 - any failure is what the test looks for
            errors.append(f"{type(exc).__name__}: {exc}")
        if cli_ok < 2:
            out = subprocess.run([sys.executable, "-m", "tyrelab.cli", "sql", "--build", str(build), "--format", "csv",
                                  "SELECT count(*) AS n FROM results"], capture_output=True, text=True)
            assert out.returncode == 0 and out.stdout.split() == ["n", "16"], out.stderr
            cli_ok += 1
        time.sleep(0.05)  # a reader every 50 ms, not a busy loop taking the writer's core
    assert writer.returncode == 0, writer.stderr.read()
    assert not errors, errors[:3]
    assert len(counts) > 5 and set(counts) == {16}
