"""``tyrelab watch``: one process, runs again after each settled change, same bytes as a clean build."""

from __future__ import annotations

import fcntl
import shutil
from pathlib import Path

import pytest

from tests.synthetic import edit_csv, manifest_row, spring_damper_recording, write_campaign
from tyrelab import cli
from tyrelab.stages import Context, run_pipeline
from tyrelab.warehouse import query
from tyrelab.watch import WatchOptions, watch

STAGES = ["ingest", "analyse", "calibrate", "warehouse"]  # calibrate writes results


class FakeTime:
    """A clock that moves only when ``sleep`` is called; ``actions[i]`` runs at the i-th sleep."""

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


def _outputs(build: Path) -> dict[str, bytes]:
    return {str(p.relative_to(build)): p.read_bytes() for p in sorted((build / "parquet").rglob("*")) if p.is_file()}


def test_a_run_added_while_watching_is_analysed_and_the_build_equals_a_clean_one(tmp_path):
    raw, build = tmp_path / "raw", tmp_path / "build"
    _campaign(raw)
    ctx = Context(raw=raw, build=build, jobs=1)
    other = tmp_path / "other"
    _campaign(other, n=4)  # the same three runs and a fourth

    def add_fourth():
        shutil.copytree(other / "c", raw / "c", dirs_exist_ok=True)

    t = FakeTime({0: add_fourth})
    runs = watch(ctx, WatchOptions(interval_s=1.0, settle_s=2.0, max_runs=2),
                 run=lambda c: run_pipeline(c, STAGES), sleep=t.sleep, clock=t.clock)
    assert [r.error for r in runs] == ["", ""]
    assert runs[1].recomputed[:2] == ["ingest", "analyse"]
    # seen changed after the first sleep, acted on once unchanged for settle_s (2 more sleeps)
    assert t.sleeps == 3
    watched = _outputs(build)
    shutil.rmtree(build)
    run_pipeline(Context(raw=raw, build=build, jobs=1), STAGES)
    clean = _outputs(build)
    assert watched.keys() == clean.keys()
    assert [k for k in clean if watched[k] != clean[k]] == []


def test_a_folder_still_changing_is_not_run_until_it_settles(tmp_path):
    raw = tmp_path / "raw"
    (raw / "c").mkdir(parents=True)
    (raw / "c" / "manifest.csv").write_text("run_id\n")
    started = []

    def touch(i):
        return lambda: (raw / "c" / f"part{i}.bin").write_bytes(b"x" * i)

    # a file arrives at each of the first four sleeps (a copy in progress), then nothing
    t = FakeTime({i: touch(i + 1) for i in range(4)})

    def fake_run(ctx):
        started.append(t.now)
        return []

    runs = watch(Context(raw=raw, build=tmp_path / "build"), WatchOptions(interval_s=0.5, settle_s=1.0, max_runs=2),
                 run=fake_run, sleep=t.sleep, clock=t.clock)
    assert len(runs) == 2
    # first run at once; the last change is seen at t = 2.0 s, so the second run waits until 3.0 s
    assert started == [0.0, 3.0]


def test_an_os_error_is_one_line_and_the_watch_goes_on(tmp_path, caplog):
    raw = tmp_path / "raw"
    (raw / "c").mkdir(parents=True)
    (raw / "c" / "manifest.csv").write_text("run_id\n")
    calls = []

    def flaky(ctx):
        calls.append(1)
        if len(calls) == 1:
            raise PermissionError(13, "Permission denied", str(raw / "c" / "r1.parquet"))
        return []

    t = FakeTime({0: lambda: (raw / "c" / "r2.parquet").write_bytes(b"new")})
    runs = watch(Context(raw=raw, build=tmp_path / "build"), WatchOptions(interval_s=1.0, settle_s=0.0, max_runs=2),
                 run=flaky, sleep=t.sleep, clock=t.clock)
    assert runs[0].error == f"{raw / 'c' / 'r1.parquet'}: Permission denied"
    assert runs[1].error == ""
    assert "waiting for the next change" in caplog.text


def test_force_applies_to_the_first_run_only(tmp_path):
    raw = tmp_path / "raw"
    (raw / "c").mkdir(parents=True)
    (raw / "c" / "manifest.csv").write_text("run_id\n")
    forced = []
    t = FakeTime({0: lambda: (raw / "c" / "x").write_text("1")})
    watch(Context(raw=raw, build=tmp_path / "build", force=True), WatchOptions(settle_s=0.0, max_runs=2),
          run=lambda c: forced.append(c.force) or [], sleep=t.sleep, clock=t.clock)
    assert forced == [True, False]


@pytest.mark.parametrize("args, message", [
    (["--interval", "0"], "--interval must be a finite number > 0, got 0.0"),
    (["--settle", "nan"], "--settle must be a finite number >= 0, got nan"),
    (["--max-runs", "0"], "--max-runs must be a whole number >= 1 or None, got 0"),
])
def test_bad_options_are_one_line(tmp_path, capsys, args, message):
    raw = tmp_path / "raw"
    _campaign(raw, n=1)
    code = cli.main(["-q", "watch", "--raw", str(raw), "--build", str(tmp_path / "b"), *args])
    err = capsys.readouterr().err
    assert code == cli.EXIT_USAGE
    assert err == f"tyrelab watch: {message}\n"


def test_cli_watch_runs_the_pipeline_under_the_build_lock(tmp_path, monkeypatch):
    import tyrelab.stages

    raw = tmp_path / "raw"
    _campaign(raw, n=2)
    build = tmp_path / "b"
    held = []

    def pipeline(ctx):  # the three fast stages (every stage is tested by the end-to-end tests)
        with open(build / ".tyrelab.lock") as fh:  # a second open file: flock conflicts even in-process
            try:
                fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                held.append(True)
            else:
                held.append(False)
        return run_pipeline(ctx, STAGES)

    monkeypatch.setattr(tyrelab.stages, "run_pipeline", pipeline)
    assert cli.main(["-q", "watch", "--raw", str(raw), "--build", str(build), "--jobs", "1", "--max-runs", "1"]) == 0
    assert held == [True]
    assert (build / "warehouse.duckdb").is_file()


# -- issue 25: a vanished raw folder keeps the build; a manifest cut short exits 3 ----------------

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
    assert cli.main(["run", "--raw", str(raw), "--build", str(tmp_path / "build"), "--jobs", "1"]) == 3
    q = query(tmp_path / "build" / "warehouse.duckdb", "SELECT reason FROM quarantine")
    assert list(q["reason"]) == ["file has no row in manifest.csv"] * 3
    # and again when nothing changed: the build still holds them
    assert cli.main(["run", "--raw", str(raw), "--build", str(tmp_path / "build"), "--jobs", "1"]) == 3
