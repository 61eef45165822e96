"""OS errors and bad arguments as one line, never a traceback (issue 25, classes 2, 4, 7, 8)."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

import tyrelab
from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
from tyrelab import executor, io
from tyrelab.cli import EXIT_BROKEN_PIPE, main

GOOD = spring_damper_recording(duration_s=20.0)
TYRELAB = str(Path(sys.executable).with_name("tyrelab"))
#: ``tyrelab`` with ``run`` restricted to the stages these tests need (the others take minutes).
PY = [sys.executable, "-c", "import sys, tyrelab.stages as s; s.ORDER[:] = ['ingest', 'analyse', 'warehouse']\n"
      "from tyrelab.cli import main; sys.exit(main(sys.argv[1:]))"]
SCENARIO = str(Path(__file__).resolve().parents[2] / "raw" / "scenarios" / "mf698t.toml")


def one_line(err: str) -> bool:
    return err.count("\n") == 1 and "Traceback" not in err


@pytest.mark.parametrize("verb", ["run", "watch", "ingest", "report"])
@pytest.mark.parametrize("jobs", ["-1", "0", "100000", "two"])
def test_jobs_out_of_range_is_refused_before_any_stage(tmp_path, capsys, verb, jobs):
    with pytest.raises(SystemExit) as info:
        main([verb, "--raw", str(tmp_path), "--build", str(tmp_path / "build"), "--jobs", jobs])
    assert info.value.code == 2 and "--jobs" in capsys.readouterr().err
    assert not (tmp_path / "build").exists()


@pytest.mark.slow  # 75 s on 2 busy cores; runs in `make test-all`, not in the default run
def test_a_folder_tree_1100_levels_deep(tmp_path):
    raw = write_campaign(tmp_path / "raw", [(manifest_row("a1", "a1.parquet"), GOOD)])
    here = os.getcwd()
    os.chdir(raw)
    try:  # relative steps: the absolute path is longer than the system takes at once
        for _ in range(1100):
            os.mkdir("d")
            os.chdir("d")
        Path("stray.csv").write_text("a\n1\n")
    finally:
        os.chdir(here)
    try:
        assert io.discover_campaigns(tmp_path / "raw") == [raw]
        assert len(list(io.regular_files(raw))) == 3  # manifest.csv, a1.parquet, stray.csv
        r = subprocess.run([*PY, "run", "--raw", str(raw), "--build", str(tmp_path / "build"), "--jobs", "1"],
                           capture_output=True, text=True)
    finally:  # pytest's own clean-up (shutil.rmtree) recurses too
        os.chdir(raw)
        depth = 0
        while os.path.isdir("d"):
            os.chdir("d")
            depth += 1
        os.unlink("stray.csv")
        for _ in range(depth):
            os.chdir("..")
            os.rmdir("d")
        os.chdir(here)
    assert "Traceback" not in r.stderr and "RecursionError" not in r.stderr, r.stderr[-2000:]
    assert r.returncode in (0, 3), r.stderr[-2000:]


def test_walk_is_os_walk(tmp_path):
    for d in ("a/b/c", "a/e", "f"):
        (tmp_path / d).mkdir(parents=True)
    (tmp_path / "a" / "b" / "x").write_text("")
    (tmp_path / "link").symlink_to(tmp_path / "a")
    ours = [(top, sorted(dirs), sorted(files)) for top, dirs, files in io.walk(tmp_path)]
    theirs = [(top, sorted(dirs), sorted(files)) for top, dirs, files in os.walk(tmp_path)]
    assert sorted(ours) == sorted(theirs)


def test_piped_into_head_ends_quietly(tmp_path):
    """stdout's reader is gone (``| head`` that has quit): exit 141, nothing on stderr."""
    build = tmp_path / "build"
    io.write_parquet_atomic(pd.DataFrame({"k": range(200000)}), build / "parquet" / "t.parquet")
    from tyrelab.warehouse import build_warehouse

    build_warehouse(build / "warehouse.duckdb", build / "parquet")
    for args in (["sql", "--build", str(build), "--format", "csv", "SELECT * FROM t"],
                 ["estimate-stiffness", "--size", "480/70R38", "--pressure", "1.2"]):
        read, write = os.pipe()
        os.close(read)  # the reader has quit before the first line
        try:
            r = subprocess.run([TYRELAB, *args], stdout=write, stderr=subprocess.PIPE, text=True)
        finally:
            os.close(write)
        assert r.returncode == EXIT_BROKEN_PIPE and "Traceback" not in r.stderr and "Broken" not in r.stderr, args


@pytest.mark.parametrize("option", ["--front-distance", "--rear-distance", "--mass", "--pitch-inertia"])
@pytest.mark.parametrize("value", ["1e308", "1e200", "1e-320"])
def test_natural_frequencies_out_of_float_range(capsys, option, value):
    args = {"--mass": "5000", "--pitch-inertia": "8000", "--front-distance": "1.2", "--rear-distance": "1.5"}
    args[option] = value
    rc = main(["natural-frequencies", *[x for kv in args.items() for x in kv], "--front-tyre", "7.50-18",
               "--front-pressure", "2", "--rear-tyre", "13.6R38", "--rear-pressure", "1.2"])
    out, err = capsys.readouterr()
    if rc == 0:
        doc = json.loads(out, parse_constant=lambda c: pytest.fail(f"{c} in the JSON"))
        assert doc
    else:
        assert rc == 2 and out == "" and one_line(err)


def test_analyze_run_without_time_s(tmp_path, capsys):
    path = tmp_path / "run.csv"
    GOOD.drop(columns=["time_s"]).to_csv(path, index=False)
    assert main(["analyze-run", str(path), "--axle-mass", "600"]) == 2
    err = capsys.readouterr().err
    assert one_line(err) and "--sample-rate" in err and "run.csv" in err
    rate = 1 / float(GOOD["time_s"].diff().iloc[1])
    assert main(["analyze-run", str(path), "--axle-mass", "600", "--sample-rate", f"{rate:.6f}"]) == 0
    assert json.loads(capsys.readouterr().out)["stiffness_kN_per_m"] == pytest.approx(250, rel=0.01)


def test_analyze_recording_refuses_what_it_cannot_read():
    twice = pd.concat([GOOD, GOOD[["accel_left_m_s2"]]], axis=1)
    with pytest.raises(ValueError, match="duplicated columns: accel_left_m_s2"):
        tyrelab.analyze_recording(twice, 600.0)
    levels = GOOD.set_axis(pd.MultiIndex.from_product([["rig"], GOOD.columns]), axis=1)
    with pytest.raises(ValueError, match="one level of column names"):
        tyrelab.analyze_recording(levels, 600.0)
    for mass in (True, False):
        with pytest.raises(ValueError, match="axle_mass_kg"):
            tyrelab.analyze_recording(GOOD, mass)
        with pytest.raises(ValueError, match="axle_mass_kg"):
            tyrelab.analyze_recording("run.parquet", mass)


def test_dask_scheduler_unreachable_is_one_line(capsys, monkeypatch):
    pytest.importorskip("dask.distributed")
    monkeypatch.setattr(executor, "DASK_CONNECT_TIMEOUT_S", 1.0)
    rc = main(["ride", SCENARIO, "--executor", "dask", "--scheduler", "127.0.0.1:1", "--set", "tractor.mass_kg=5000,5200"])
    out, err = capsys.readouterr()
    assert rc == 2 and out == "" and one_line(err) and "--scheduler 127.0.0.1:1" in err


def test_dask_workers_capped_like_local(monkeypatch):
    distributed = pytest.importorskip("dask.distributed")
    asked = {}

    class Stop(Exception):
        pass

    def client(*args, **kwargs):
        asked.update(kwargs)
        raise Stop

    monkeypatch.setattr(distributed, "Client", client)
    ctx = type("Ctx", (), {"executor": "dask", "jobs": 24, "scheduler": None})()
    with pytest.raises(Stop):
        executor.map_batches(abs, [-1, -2], ctx)
    assert asked["n_workers"] == 2


def test_ride_out_pair_replaced_together(tmp_path, capsys, monkeypatch):
    out = tmp_path / "out"
    assert main(["ride", SCENARIO, "--out", str(out), "--speeds", "8"]) == 0
    capsys.readouterr()
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    assert sorted(before) == ["ride.html", "ride.json"]
    real_replace = io.os.replace
    calls = []

    def full_disk_on_second(src, dst):
        calls.append(dst)
        if len(calls) == 2:
            raise OSError(28, "No space left on device", str(dst))
        return real_replace(src, dst)

    monkeypatch.setattr(io.os, "replace", full_disk_on_second)
    rc = main(["ride", SCENARIO, "--out", str(out), "--speeds", "12"])
    monkeypatch.undo()
    err = capsys.readouterr().err
    assert rc == 2 and one_line(err) and "No space left" in err
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
