"""SIGKILL at random points of `tyrelab run --force` (random ones of the moments it replaces a file, held
there: tests/holds.py), then `tyrelab run`: the build converges to the
bytes of a clean build (issue 11). The default run kills a short pipeline; the slow test every stage."""

import hashlib
import random
import shutil
import signal
import sys
from pathlib import Path

import pytest

from tests.holds import Holds
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


def converges(raw, build, stages, kills, seed, holds: Holds):
    """A clean build, then ``kills`` times: SIGKILL a forced run at a random one of the moments it
    replaces a file (written in full, not yet renamed over its target), run again, compare."""
    assert start_run(raw, build, stages=stages).wait() == 0
    clean = fingerprint(build)
    copy = build.with_name(build.name + "-count")  # count them in a forced run of a copy (no hold)
    shutil.copytree(build, copy)
    holds.hold("replace", 0)
    assert start_run(raw, copy, "--force", stages=stages, env=holds.env).wait() == 0
    replaces = holds.count("replace")
    shutil.rmtree(copy)
    assert replaces > 0
    rng = random.Random(seed)
    for _ in range(kills):
        holds.hold("replace", rng.randint(1, replaces))
        proc = start_run(raw, build, "--force", stages=stages, env=holds.env)
        holds.wait("replace", proc)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        assert proc.returncode == -signal.SIGKILL and not holds.passed("replace")
        holds.release("replace")
        rerun = start_run(raw, build, stages=stages)
        assert rerun.wait() == 0, rerun.stderr.read()
        now = fingerprint(build)
        assert not [p for p in build.rglob("*") if p.name.endswith(".tmp")]
        assert now.keys() == clean.keys() and [k for k in now if now[k] != clean[k]] == []


@pytest.mark.slow  # 57 s on 2 busy cores; runs in `make test-all`, not in the default run
def test_random_kills_converge_to_the_clean_bytes(tmp_path):
    raw = calibrated_campaign(tmp_path / "raw" / "c", per_day=2)
    converges(raw, tmp_path / "build", SHORT, kills=2, seed=11, holds=Holds(tmp_path / "holds"))


@pytest.mark.slow
def test_random_kills_across_every_stage_converge(tmp_path, monkeypatch):
    # The report's footer says when it was generated: fix that time (SOURCE_DATE_EPOCH, as for any
    # reproducible build) so that the pages of the clean build and of the re-run can be compared.
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "631152000")
    raw = calibrated_campaign(tmp_path / "raw" / "c", per_day=4)
    converges(raw, tmp_path / "build", ALL, kills=8, seed=1991, holds=Holds(tmp_path / "holds"))
