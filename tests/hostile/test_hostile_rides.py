"""The rides stage against hostile rows: one bad row never aborts the stage (issue 37, I/O side)."""

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tyrelab.stages import run_stage
from tyrelab.stages.base import Context
from tests.stages.test_rides import ROWS, _scenario_text

DAY = "1991-06-12"


def _seat(duration_s=20.0, fs=100.0, channel="seat_z_m_s2"):
    t = np.arange(int(duration_s * fs)) / fs
    return pd.DataFrame({"time_s": t, channel: 0.8 * np.sin(2 * np.pi * 4 * t)})


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    raw = tmp_path_factory.mktemp("hostile_rides") / "raw"
    c = raw / "farm"
    (c / "rec").mkdir(parents=True)
    (c / "s.toml").write_text(_scenario_text(), encoding="utf-8")
    _seat().to_csv(c / "rec" / "good.csv", index=False)
    _seat().to_csv(c / "rec" / "sheet.csv", index=False, sep=";", decimal=",")
    huge = _seat()
    huge.loc[10, "seat_z_m_s2"] = 1e200
    huge.loc[11, "seat_z_m_s2"] = -1e200
    huge.to_csv(c / "rec" / "huge.csv", index=False)
    _seat(channel="floor_z_m_s2").to_csv(c / "rec" / "floor.csv", index=False)
    rows = [
        f"good,rec/good.csv,T1,8,C,{DAY},,baling,2,",
        f"sheet,rec/sheet.csv,T2,8,C,{DAY},,,,",
        f"huge,rec/huge.csv,T1,8,C,{DAY},,mowing,1,",
        f"tiny,rec/good.csv,T3,8,C,{DAY},,raking,1e-320,",
        f"floor,rec/floor.csv,T1,8,C,{DAY},,ploughing,6,",
        f"still,rec/good.csv,T4,0,scenario,{DAY},s.toml,,,",
    ]
    asammdf = pytest.importorskip("asammdf")
    t = np.arange(0, 20, 0.002)
    mdf = asammdf.MDF(version="4.10")
    mdf.append([asammdf.Signal(np.sin(2 * np.pi * 4 * t), t, name="AccZ")])
    mdf.save(str(c / "rec" / "seat.mf4"), overwrite=True)
    mdf.close()
    (c / "channel_map.json").write_text(json.dumps({"channels": {"seat_z_m_s2": "AccZ"}}))  # no time_s
    rows.append(f"mdf,rec/seat.mf4,T5,8,C,{DAY},,,,")
    (c / "rides.csv").write_text(ROWS + "\n".join(rows) + "\n", encoding="utf-8")
    ctx = Context(raw=raw, build=tmp_path_factory.mktemp("build"), jobs=1, log=logging.getLogger("tyrelab.test"))
    return ctx, run_stage("rides", ctx)


def _reasons(ctx):
    q = ctx.read_table("quarantine")
    return q[q["stage"] == "rides"].set_index("run_id")["reason"]


def test_bad_rows_are_quarantined_and_the_good_ones_go_through(built):
    ctx, result = built
    rec = ctx.read_table("recordings").set_index("ride_id")
    assert sorted(rec.index) == ["floor", "good", "mdf", "sheet"]
    reasons = _reasons(ctx)
    assert "seat_z_m_s2 has a sample of 1e+200" in reasons["huge"] and "row 10" in reasons["huge"]
    assert reasons["tiny"].startswith("hours_per_day: ")
    assert all("\n" not in r for r in reasons)


def test_a_row_with_speed_0_and_a_scenario_is_quarantined_not_kept(built):
    ctx, _ = built
    assert "still" not in set(ctx.read_table("recordings")["ride_id"])
    assert "speed_km_h 0" in _reasons(ctx)["still"]


def test_a_spreadsheet_and_an_mf4_without_time_s_in_its_map_are_read(built):
    ctx, _ = built
    rec = ctx.read_table("recordings").set_index("ride_id")
    good = ctx.read_table("recording_axes").set_index("ride_id")
    assert good.loc["sheet", "a_w_m_s2"] == pytest.approx(good.loc["good", "a_w_m_s2"], rel=1e-9)
    assert rec.loc["mdf", "sample_rate_Hz"] == pytest.approx(500.0)


def test_a_seatless_task_stays_in_its_day_without_a_verdict(built):
    ctx, _ = built
    days = ctx.read_table("exposure_days").set_index("vehicle")
    t1 = days.loc["T1"]
    assert t1["hours_per_day"] == pytest.approx(8.0)  # baling 2 h + ploughing 6 h (mowing's row is quarantined)
    assert t1["verdict"].startswith("no verdict") and "ploughing (6 h, floor)" in t1["verdict"]


def test_the_warehouse_holds_no_path_of_this_machine(built):
    ctx, _ = built
    for table, col in (("recordings", "campaign"), ("exposure_days", "campaign"), ("quarantine", "campaign")):
        values = ctx.read_table(table)[col].dropna().astype(str)
        assert len(values) and not any(Path(v).is_absolute() for v in values), (table, set(values))
    assert set(ctx.read_table("recordings")["campaign"]) == {"farm"}
