"""SIGKILL at random points of `tyrelab run --force`, then `tyrelab run`: the build converges to the
bytes of a clean build (issue 11). The default run kills a short pipeline; the slow test every stage."""

import hashlib
import random
import signal
import sys
import time
from pathlib import Path

import pytest

from tests.stages.crashkit import start_run
from tyrelab.buildlock import LOCK_NAME
from tyrelab.warehouse import query

from tests.hostile.hostilekit import calibrated_campaign  # noqa: E402

pytestmark = pytest.mark.long  # collected first: see tests/conftest.py

SHORT = ["ingest", "analyse", "calibrate", "warehouse"]
ALL = ["ingest", "analyse", "calibrate", "regress", "simulate", "warehouse", "report"]


def fingerprint(build: Path) -> dict:
    """SHA-256 of every file of the build but the bookkeeping, and the rows of every warehouse view
    (the DuckDB file itself is not byte-reproducible)."""
    out = {}
    for p in sorted(build.rglob("*")):
        rel = p.relative_to(build)
        if p.is_file() and rel.parts[0] != "state" and p.name not in (LOCK_NAME, "warehouse.duckdb"):
            out[str(rel)] = hashlib.sha256(p.read_bytes()).hexdigest()
    db = build / "warehouse.duckdb"
    for (view,) in query(db, "SELECT view_name FROM duckdb_views() WHERE NOT internal ORDER BY 1").itertuples(index=False):
        out[f"view:{view}"] = hashlib.sha256(query(db, f'SELECT * FROM "{view}"').to_csv(index=False).encode()).hexdigest()
    return out


def converges(raw, build, stages, kills, seed):
    t0 = time.monotonic()
    assert start_run(raw, build, stages=stages).wait() == 0
    clean, duration = fingerprint(build), time.monotonic() - t0
    rng = random.Random(seed)
    for _ in range(kills):
        proc = start_run(raw, build, "--force", stages=stages)
        time.sleep(rng.uniform(0.05, 1.0) * duration)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        rerun = start_run(raw, build, stages=stages)
        assert rerun.wait() == 0, rerun.stderr.read()
        now = fingerprint(build)
        assert not [p for p in build.rglob("*") if p.name.endswith(".tmp")]
        assert now.keys() == clean.keys() and [k for k in now if now[k] != clean[k]] == []


@pytest.mark.slow  # 57 s on 2 busy cores; runs in `make test-all`, not in the default run
def test_random_kills_converge_to_the_clean_bytes(tmp_path):
    raw = calibrated_campaign(tmp_path / "raw" / "c", per_day=2)
    converges(raw, tmp_path / "build", SHORT, kills=2, seed=11)


@pytest.mark.slow
def test_random_kills_across_every_stage_converge(tmp_path, monkeypatch):
    # The report's footer says when it was generated: fix that time (SOURCE_DATE_EPOCH, as for any
    # reproducible build) so that the pages of the clean build and of the re-run can be compared.
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "631152000")
    raw = calibrated_campaign(tmp_path / "raw" / "c", per_day=4)
    converges(raw, tmp_path / "build", ALL, kills=8, seed=1991)
