"""The rides stage: rides.csv campaigns -> recordings, exposure days, ride_validation (issue 24)."""

import logging
import shutil

import numpy as np
import pandas as pd
import pytest

from tyrelab.resources import scenarios_dir
from tyrelab.stages import run_stage
from tyrelab.stages.base import Context
from tyrelab.vehicle import ride_validation as rv
from tyrelab.scenario_io import load_scenario

ROWS = "ride_id,file,vehicle,speed_km_h,track,recorded_on,scenario,task,hours_per_day,notes\n"


def _scenario_text() -> str:
    """The shipped MF698T scenario at 15 km/h only, 10 s records (a quick prediction)."""
    text = (scenarios_dir() / "mf698t.toml").read_text(encoding="utf-8")
    text = text.replace("speeds_km_h = [10, 12.5, 15, 17.5, 20]", "speeds_km_h = [15]")
    text = text.replace("duration_s = 30", "duration_s = 10")
    for key in ("damping_kN_s_per_m = [1.47, 1.34, 1.20, 1.00, 0.79]", "stiffness_kN_per_m = [364, 360, 356, 352, 348]",
                "damping_kN_s_per_m = [1.12, 0.96, 0.77, 0.67, 0.57]"):
        assert key in text
    text = text.replace("damping_kN_s_per_m = [1.47, 1.34, 1.20, 1.00, 0.79]", "damping_kN_s_per_m = 1.20")
    text = text.replace("stiffness_kN_per_m = [364, 360, 356, 352, 348]", "stiffness_kN_per_m = 356")
    return text.replace("damping_kN_s_per_m = [1.12, 0.96, 0.77, 0.67, 0.57]", "damping_kN_s_per_m = 0.77")


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    """A campaign of recordings made from the scenario's own prediction (1.2× and 1.0×), and bad rows."""
    raw = tmp_path_factory.mktemp("rides") / "raw"
    c = raw / "farm"
    (c / "rec").mkdir(parents=True)
    (c / "mf698t.toml").write_text(_scenario_text(), encoding="utf-8")
    sc = load_scenario(c / "mf698t.toml")
    sig, fs = rv.predicted_seat(sc, 15.0, rv.track_of("scenario"))
    t = np.arange(sig["seat_z_m_s2"].size) / fs
    for name, scale in (("high", 1.2), ("same", 1.0)):
        pd.DataFrame({"time_s": t, "seat_z_m_s2": scale * sig["seat_z_m_s2"] + 9.80665,
                      "seat_x_m_s2": scale * sig["seat_x_m_s2"]}).to_parquet(c / "rec" / f"{name}.parquet")
    bad = pd.DataFrame({"time_s": t, "seat_z_m_s2": sig["seat_z_m_s2"]})
    bad.loc[100, "seat_z_m_s2"] = np.nan
    bad.to_csv(c / "rec" / "nan.csv", index=False)
    (c / "rides.csv").write_text(
        ROWS
        + "high,rec/high.parquet,MF698T,15,scenario,1991-06-12,mf698t.toml,transport,2,\n"
        + "same,rec/same.parquet,MF698T,15,scenario,1991-06-12,mf698t.toml,ploughing,5,\n"
        + "gone,rec/gone.parquet,MF698T,15,scenario,1991-06-12,,,,\n"
        + "nan,rec/nan.csv,MF698T,15,scenario,1991-06-12,,,,\n"
        + "same,rec/same.parquet,MF698T,15,scenario,1991-06-12,,,,\n"
        + "track,rec/same.parquet,MF698T,15,Z,1991-06-12,mf698t.toml,,,\n"
        + "out,../x.parquet,MF698T,15,scenario,1991-06-12,,,,\n", encoding="utf-8")
    return raw


@pytest.fixture(scope="module")
def built(campaign, tmp_path_factory):
    ctx = Context(raw=campaign, build=tmp_path_factory.mktemp("build"), jobs=1)
    result = run_stage("rides", ctx)
    return ctx, result


def test_good_rows_go_through_bad_rows_are_quarantined_one_line_each(built):
    ctx, result = built
    assert (result.n_in, result.n_ok, result.n_quarantined) == (7, 2, 5)
    q = ctx.read_table("quarantine").set_index("run_id")
    reasons = q.loc[q["stage"] == "rides", "reason"]
    assert "file not found" in reasons["gone"]
    assert "seat_z_m_s2 has a NaN" in reasons["nan"] and "row 100" in reasons["nan"]
    assert "duplicate ride_id" in reasons["same"]
    assert "track 'Z'" in reasons["track"]
    assert "outside the campaign" in reasons["out"]
    assert all("\n" not in r for r in reasons)
    rec = ctx.read_table("recordings").set_index("ride_id")
    assert sorted(rec.index) == ["high", "same"]
    assert "±1 g offset" in rec.loc["high", "warnings"]


def test_scaled_recording_gives_ratio_1_2(built):
    ctx, _ = built
    v = ctx.read_table("ride_validation").set_index(["ride_id", "axis"])
    assert v.loc[("high", "z"), "ratio_a_w"] == pytest.approx(1.2, rel=1e-6)
    assert v.loc[("same", "z"), "ratio_a_w"] == pytest.approx(1.0, rel=1e-6)
    assert v.loc[("high", "z"), "envelope_similarity"] == pytest.approx(1.0, abs=1e-6)
    assert ("high", "x") not in v.index  # the scenario's model has no fore-aft motion at this seat
    st = ctx.read_table("ride_validation_statistics").set_index(["axis", "quantity"])
    r = np.array([1 / 1.2, 1.0])  # ratio errors predicted / measured, the thesis' way
    assert st.loc[("z", "a_w"), "mean"] == pytest.approx(r.mean()) and st.loc[("z", "a_w"), "sd"] == pytest.approx(r.std(ddof=1))


def test_exposure_day_from_the_tasks(built):
    ctx, _ = built
    day = ctx.read_table("exposure_days")
    assert len(day) == 1 and day.loc[0, "tasks"] == 2 and day.loc[0, "hours_per_day"] == 7.0
    axes = ctx.read_table("recording_axes").set_index(["ride_id", "channel"])
    a = {n: axes.loc[(n, "seat_z_m_s2"), "a_w_m_s2"] for n in ("high", "same")}
    assert day.loc[0, "a8_m_s2"] == pytest.approx(np.sqrt((a["high"] ** 2 * 2 + a["same"] ** 2 * 5) / 8))
    assert day.loc[0, "a8_axis"] == "z"
    # issue 47: the daily VDV's verdict beside A(8)'s, as tyrelab exposure's JSON gives it
    assert day.loc[0, "vdv_verdict"] == ("above limit value" if day.loc[0, "vdv_daily_m_s1_75"] > 21.0 else
                                         "above action value" if day.loc[0, "vdv_daily_m_s1_75"] > 9.1 else
                                         "below action value")


def test_incremental_and_recordings_removed(campaign, built, tmp_path):
    ctx0, _ = built
    raw = tmp_path / "raw"
    shutil.copytree(campaign, raw)
    build = tmp_path / "build"
    shutil.copytree(ctx0.build, build)
    ctx = Context(raw=raw, build=build, jobs=1, log=logging.getLogger("test"))
    assert run_stage("rides", ctx).skipped is False  # another raw folder: its digest differs
    f = raw / "farm" / "rec" / "same.parquet"
    d = pd.read_parquet(f)
    d["seat_z_m_s2"] = 9.80665 + 0.9 * (d["seat_z_m_s2"] - 9.80665)
    d.to_parquet(f)
    res = run_stage("rides", ctx)
    assert res.message == "recordings 2 reused, 1 computed, validations 1 reused, 1 computed"  # the NaN one too
    v = ctx.read_table("ride_validation").set_index(["ride_id", "axis"])
    assert v.loc[("same", "z"), "ratio_a_w"] == pytest.approx(0.9, rel=1e-6)
    (raw / "farm" / "rides.csv").unlink()
    res = run_stage("rides", ctx)
    assert res.n_in == 0
    for table in ("recordings", "ride_validation", "exposure_days", "recording_axes"):
        assert ctx.read_table(table).empty, table


def _fits(build, t2_shift_kN_per_m: float = 0.0) -> None:
    """Per-speed pressure fits of tyres T1 and T2 (as regress writes them) in ``build``."""
    (build / "parquet").mkdir(parents=True, exist_ok=True)
    rows = [{"tyre_id": t, "speed_km_h": v, "intercept": k + (t2_shift_kN_per_m if t == "T2" else 0.0), "slope": 140.0}
            for t, k in (("T1", 150.0), ("T2", 170.0)) for v in (0.0, 10.0)]
    pd.DataFrame(rows).to_parquet(build / "parquet" / "stiffness_pressure_by_speed.parquet")
    damping = [{**r, "intercept": 0.6, "slope": 0.4} for r in rows]
    pd.DataFrame(damping).to_parquet(build / "parquet" / "damping_pressure_by_speed.parquet")


def test_a_new_run_of_a_tyre_revalidates_its_recordings_only_reading_no_recording(campaign, tmp_path, monkeypatch):
    """Issue 35: a validation depends on its recording and on the fits of ITS tyres: new fits of
    tyre T2 (a run of it added) re-validate the recording whose scenario names T2, reuse the others,
    and read no recording (the analysis is the recording's item; unchanged files are not hashed again)."""
    from tests.scenarios import scenario_text

    from tyrelab import io
    from tyrelab.rawformat import rides as raw_rides

    raw, build = tmp_path / "raw", tmp_path / "build"
    c = raw / "farm"
    (c / "rec").mkdir(parents=True)
    shutil.copy(campaign / "farm" / "rec" / "high.parquet", c / "rec" / "a.parquet")
    shutil.copy(campaign / "farm" / "rec" / "same.parquet", c / "rec" / "b.parquet")
    shutil.copy(campaign / "farm" / "mf698t.toml", c / "mf698t.toml")
    for tyre in ("T1", "T2"):
        (c / f"{tyre}.toml").write_text(scenario_text(rear=f'measured_tyre_id = "{tyre}"', speeds="[15]",
                                                      name=f"rear {tyre}"), encoding="utf-8")
    # on a track of ISO class C (not a known profile: no envelope similarity, which compares signals)
    (c / "rides.csv").write_text(ROWS + "r1,rec/a.parquet,X,15,ISO 8608 class C,1991-06-12,T1.toml,,,\n"
                                 + "r2,rec/b.parquet,X,15,ISO 8608 class C,1991-06-12,T2.toml,,,\n"
                                 + "r3,rec/a.parquet,X,15,ISO 8608 class C,1991-06-12,mf698t.toml,,,\n", encoding="utf-8")
    _fits(build)
    ctx = Context(raw=raw, build=build, jobs=1, log=logging.getLogger("test"))
    # r1 and r3 are one file: one item
    assert run_stage("rides", ctx).message == "recordings 1 reused, 2 computed, validations 0 reused, 3 computed"
    before = ctx.read_table("ride_validation").set_index(["ride_id", "axis"])

    _fits(build, t2_shift_kN_per_m=25.0)  # a run of T2 added: its fits change, T1's rows stay
    read: list[str] = []
    sha, opened = io.file_sha256, raw_rides.open_recording
    monkeypatch.setattr(io, "file_sha256", lambda path, *a, **k: read.append(str(path)) or sha(path, *a, **k))
    monkeypatch.setattr(raw_rides, "open_recording", lambda path, *a, **k: read.append(str(path)) or opened(path, *a, **k))
    res = run_stage("rides", ctx)
    assert res.message == "recordings 3 reused, 0 computed, validations 2 reused, 1 computed"
    assert not [p for p in read if p.endswith(".parquet") and "/rec/" in p], read  # no recording read
    after = ctx.read_table("ride_validation").set_index(["ride_id", "axis"])
    pd.testing.assert_frame_equal(after.drop(index="r2", level=0), before.drop(index="r2", level=0))
    assert (after.loc["r2", "predicted_a_w_m_s2"] != before.loc["r2", "predicted_a_w_m_s2"]).all()
    assert (after.loc["r2", "measured_a_w_m_s2"] == before.loc["r2", "measured_a_w_m_s2"]).all()


def test_an_edited_track_profile_revalidates_the_recordings_on_it(campaign, tmp_path):
    """A rides.csv row on a profile CSV of the campaign: the prediction reads that file, so an edited
    profile validates the row again (the recording's analysis is reused)."""
    raw, build = tmp_path / "raw", tmp_path / "build"
    c = raw / "farm"
    (c / "rec").mkdir(parents=True)
    shutil.copy(campaign / "farm" / "rec" / "same.parquet", c / "rec" / "a.parquet")
    shutil.copy(campaign / "farm" / "mf698t.toml", c / "mf698t.toml")
    x = np.arange(0, 200.0, 0.05)
    track = pd.DataFrame({"distance_m": x, "height_m": 0.004 * np.sin(2 * np.pi * x / 2.5)})
    track.to_csv(c / "track.csv", index=False)
    (c / "rides.csv").write_text(ROWS + "r1,rec/a.parquet,X,15,track.csv,1991-06-12,mf698t.toml,,,\n", encoding="utf-8")
    ctx = Context(raw=raw, build=build, jobs=1, log=logging.getLogger("test"))
    assert run_stage("rides", ctx).message == "recordings 0 reused, 1 computed, validations 0 reused, 1 computed"
    before = ctx.read_table("ride_validation")
    track.assign(height_m=2 * track["height_m"]).to_csv(c / "track.csv", index=False)
    assert run_stage("rides", ctx).message == "recordings 1 reused, 0 computed, validations 0 reused, 1 computed"
    after = ctx.read_table("ride_validation")
    assert (after["predicted_a_w_m_s2"] != before["predicted_a_w_m_s2"]).all()
