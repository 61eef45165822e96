"""``tyrelab exposure``: the issue's JSON keys, the task form, one-line problems and exit codes."""

import json
import math

import numpy as np
import pandas as pd
import pytest

from tyrelab.cli import main
from tyrelab.vehicle import daily_exposure, measured_ride

FS = 200.0


def _recording(path, seconds=60.0, seed=0, floor=False, offset=0.0, amplitude=1.0):
    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * FS)) / FS
    cols = {"time_s": t}
    for i, ax in enumerate("xyz"):
        cols[f"seat_{ax}_m_s2"] = amplitude * (0.3 + 0.2 * i) * np.sin(2 * np.pi * (2.0 + i) * t) \
            + 0.05 * rng.standard_normal(t.size) + (offset if ax == "z" else 0.0)
        if floor:
            cols[f"floor_{ax}_m_s2"] = cols[f"seat_{ax}_m_s2"] / 0.8
    frame = pd.DataFrame(cols)
    frame.to_parquet(path) if path.suffix == ".parquet" else frame.to_csv(path, index=False)
    return path


def _run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_one_recording_json_keys(tmp_path, capsys):
    f = _recording(tmp_path / "mowing.parquet", floor=True)
    code, out, err = _run(capsys, "exposure", str(f), "--hours", "5")
    assert code == 0, err
    doc = json.loads(out)
    for ax in "xyz":
        assert set(doc["axes"][ax]) >= {"a_w_m_s2", "vdv_m_s1_75", "mtvv_m_s2", "crest_factor", "duration_s"}
        assert doc["axes"][ax]["duration_s"] == pytest.approx(60.0)
    for key in ("a_v_m_s2", "dz_m_s2", "dzd_m_s2", "seat_factor", "tasks", "a8_m_s2", "a8_axis", "vdv_daily_m_s1_75",
                "hours_to_eav", "hours_to_elv", "exposure_points", "verdict"):
        assert key in doc, key
    assert doc["seat_factor"]["z"] == pytest.approx(0.8, rel=1e-9)
    assert set(doc["tasks"][0]["partial_a8_m_s2"]) == {"x", "y", "z"}
    # the same numbers as the library on the same signals
    frame = pd.read_parquet(f)
    a = measured_ride.analyse_signals({c: frame[c].to_numpy() for c in frame if c != "time_s"}, FS)
    day = daily_exposure.daily_exposure([daily_exposure.TaskExposure(
        "mowing", 5.0, {ax: v["a_w_m_s2"] for ax, v in a.axes().items()},
        {ax: v["vdv_m_s1_75"] for ax, v in a.axes().items()}, 60.0, a.dz_m_s2)])
    assert doc["a8_m_s2"] == pytest.approx(day["a8_m_s2"], rel=1e-9)
    assert doc["dzd_m_s2"] == pytest.approx(a.dz_m_s2 * (5 * 3600 / 60.0) ** (1 / 6), rel=1e-9)
    assert doc["exposure_points"] == pytest.approx(400 * doc["a8_m_s2"] ** 2)


def test_tasks_of_a_day_and_table(tmp_path, capsys):
    a = _recording(tmp_path / "a.csv", seed=1)
    b = _recording(tmp_path / "b.parquet", seed=2, amplitude=2.0)
    code, out, err = _run(capsys, "exposure", "--task", "baling", str(a), "3", "--task", "road", str(b), "1.5")
    assert code == 0, err
    doc = json.loads(out)
    assert [t["name"] for t in doc["tasks"]] == ["baling", "road"]
    a8 = {ax: math.sqrt(sum(t["partial_a8_m_s2"][ax] ** 2 for t in doc["tasks"])) for ax in "xyz"}
    assert doc["a8_m_s2"] == pytest.approx(max(a8.values())) and doc["a8_axis"] == max(a8, key=a8.get)
    assert doc["hours_to_eav"] == pytest.approx(4.5 * (0.5 / doc["a8_m_s2"]) ** 2)
    assert "axes" in doc["tasks"][0] and "axes" not in doc
    code, out, _ = _run(capsys, "exposure", "--task", "baling", str(a), "3", "--task", "road", str(b), "1.5",
                        "--format", "table")
    assert code == 0 and "day: A(8)" in out and "task road" in out


def test_bad_recordings_one_line_each_all_at_once(tmp_path, capsys):
    good = _recording(tmp_path / "good.csv")
    t = np.arange(0, 30, 1 / FS)
    pd.DataFrame({"seat_z_m_s2": np.sin(t)}).to_csv(tmp_path / "no_time.csv", index=False)
    pd.DataFrame({"time_s": t, "seat_z_m_s2": np.where(t > 3, np.nan, 0.1)}).to_csv(tmp_path / "nan.csv", index=False)
    pd.DataFrame({"time_s": t, "seat_z_m_s2": 1.0 + 0.02 * np.sin(t)}).to_csv(tmp_path / "g.csv", index=False)
    args = ["exposure", "--task", "a", str(good), "2"]
    for i, name in enumerate(("no_time.csv", "nan.csv", "g.csv")):
        args += ["--task", f"t{i}", str(tmp_path / name), "1"]
    code, out, err = _run(capsys, *args)
    assert code == 3 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 3 and "Traceback" not in err
    assert "no_time.csv: no time base" in lines[0] and "nan.csv: channel seat_z_m_s2 has a NaN" in lines[1]
    assert "g.csv: channel seat_z_m_s2 averages 1.00" in lines[2] and "it looks like g" in lines[2]


def test_usage_problems_exit_2(tmp_path, capsys):
    good = _recording(tmp_path / "good.csv")
    for argv, text in ((["exposure"], "give either FILE"),
                       (["exposure", str(tmp_path / "nope.parquet")], "nope.parquet: file not found"),
                       (["exposure", "--task", "a", str(good), "25"], "HOURS '25': 25 h is not in 0.01 to 24 h"),
                       (["exposure", "--task", "a", str(good), "x"], "HOURS 'x': 'x' is not a number"),
                       (["exposure", "--task", "a", str(good), "20", "--task", "b", str(good), "6"], "more than a day"),
                       (["exposure", str(good), "--task", "a", str(good), "2"], "give either")):
        code, out, err = _run(capsys, *argv)
        assert code == 2 and text in err and "Traceback" not in err, (argv, err)


def test_gravity_offset_warns_and_is_removed(tmp_path, capsys):
    plain = json.loads(_run(capsys, "exposure", str(_recording(tmp_path / "p.csv")))[1])
    code, out, err = _run(capsys, "exposure", str(_recording(tmp_path / "g.csv", offset=9.81)))
    assert code == 0 and "±1 g offset" in err
    doc = json.loads(out)
    assert doc["a8_m_s2"] == pytest.approx(plain["a8_m_s2"], rel=1e-6)
    assert doc["dz_m_s2"] == pytest.approx(plain["dz_m_s2"], rel=1e-6)
