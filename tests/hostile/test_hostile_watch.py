"""watch keeps a build when --raw vanishes; a run that quarantined anything exits 3 (issue 25, class 6)."""

import shutil
from pathlib import Path

from synthetic import edit_csv, manifest_row, spring_damper_recording, write_campaign
from tyrelab.cli import main
from tyrelab.stages import Context, run_pipeline
from tyrelab.warehouse import query
from tyrelab.watch import WatchOptions, watch

STAGES = ["ingest", "analyse", "warehouse"]


class FakeTime:
    def __init__(self, actions=()):
        self.now, self.sleeps, self.actions = 0.0, 0, dict(actions)

    def clock(self) -> float:
        return self.now

    def sleep(self, seconds: float) -> None:
        self.now += seconds
        action = self.actions.get(self.sleeps)
        self.sleeps += 1
        if action:
            action()


def _campaign(raw: Path, n: int = 3) -> Path:
    return write_campaign(raw / "c", [(manifest_row(f"r{i}", f"r{i}.parquet", pressure_bar=1.0 + 0.1 * i),
                                       spring_damper_recording(duration_s=12.0, seed=i)) for i in range(n)])


def test_raw_vanishing_during_watch_keeps_the_build(tmp_path):
    raw, build = tmp_path / "raw", tmp_path / "build"
    _campaign(raw)
    ctx = Context(raw=raw, build=build, jobs=1)
    moved = tmp_path / "moved"
    t = FakeTime({0: lambda: raw.rename(moved), 4: lambda: moved.rename(raw)})
    ran = []

    def run(c):
        ran.append(c.raw)
        return run_pipeline(c, STAGES)

    runs = watch(ctx, WatchOptions(interval_s=1.0, settle_s=1.0, max_runs=3), run=run, sleep=t.sleep, clock=t.clock)
    assert runs[0].error == "" and "no such folder" in runs[1].error and runs[2].error == ""
    assert len(ran) == 2  # no pipeline run while the folder was gone
    assert len(query(build / "warehouse.duckdb", "SELECT * FROM results")) == 3


def test_raw_emptied_during_watch_keeps_the_build(tmp_path):
    raw, build = tmp_path / "raw", tmp_path / "build"
    _campaign(raw)
    ctx = Context(raw=raw, build=build, jobs=1)
    t = FakeTime({0: lambda: shutil.rmtree(raw / "c")})
    runs = watch(ctx, WatchOptions(interval_s=1.0, settle_s=1.0, max_runs=2),
                 run=lambda c: run_pipeline(c, STAGES), sleep=t.sleep, clock=t.clock)
    assert "no campaign" in runs[1].error
    assert len(query(build / "warehouse.duckdb", "SELECT * FROM results")) == 3


def test_a_manifest_cut_short_exits_3(tmp_path, monkeypatch):
    import tyrelab.stages as stages

    monkeypatch.setattr(stages, "ORDER", STAGES)
    raw = _campaign(tmp_path / "raw", n=4)
    edit_csv(raw / "manifest.csv", lambda rows: rows.__delitem__(slice(1, None)))
    assert main(["run", "--raw", str(raw), "--build", str(tmp_path / "build"), "--jobs", "1"]) == 3
    q = query(tmp_path / "build" / "warehouse.duckdb", "SELECT reason FROM quarantine")
    assert list(q["reason"]) == ["file has no row in manifest.csv"] * 3
    # and again when nothing changed: the build still holds them
    assert main(["run", "--raw", str(raw), "--build", str(tmp_path / "build"), "--jobs", "1"]) == 3
