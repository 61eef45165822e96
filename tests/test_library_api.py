"""The library's vehicle entry points (issue 38): ``tyrelab.ride`` and ``tyrelab.exposure``."""

import json
import subprocess
import sys
import tomllib

import numpy as np
import pandas as pd
import pytest

import tyrelab
from tests.scenarios import scenario_text
from tyrelab.vehicle.scenario import ScenarioError

TEXT = scenario_text(speeds="[6, 12]")


def test_ride_takes_a_path_toml_text_or_a_dict_and_gives_the_same_rows(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(TEXT)
    by_path = tyrelab.ride(path)
    by_text = tyrelab.ride(TEXT)
    by_dict = tyrelab.ride(tomllib.loads(TEXT))
    assert list(by_path.speeds["speed_km_h"]) == [6.0, 12.0]
    pd.testing.assert_frame_equal(by_path.speeds, by_text.speeds)
    pd.testing.assert_frame_equal(by_path.speeds, by_dict.speeds)
    assert by_path.speeds["a8_axis"].isin(["x", "y", "z"]).all()
    assert list(by_path.mode_table.columns) == ["mode", "frequency_Hz", "low_Hz", "high_Hz", "nodal_point_m"]
    assert list(by_path.mode_table["mode"][:2]) == ["bounce", "pitch"]
    assert set(by_path.tyres) == {"front", "rear"}
    doc = json.loads(by_path.to_json())
    assert doc == by_path.to_dict() and doc["speeds"][1]["a8_axis"] == by_path.speeds["a8_axis"].iloc[1]
    assert doc["speeds"][0]["speed_km_h"] == 6.0


def test_ride_overrides_and_bad_input():
    r = tyrelab.ride(TEXT, speeds_km_h=[9], rear_pressure_bar=1.0)
    assert list(r.speeds["speed_km_h"]) == [9.0] and r.tyres["rear"].pressure_bar == 1.0
    bad = tomllib.loads(TEXT)
    bad["tractor"]["mass_kg"] = -1
    del bad["exposure"]
    with pytest.raises(ScenarioError) as exc:
        tyrelab.ride(bad)
    assert any("tractor.mass_kg" in p for p in exc.value.problems) and "missing table [exposure]" in exc.value.problems
    with pytest.raises(ValueError, match="scenario must be a path, TOML text, a dict or a Scenario"):
        tyrelab.ride(42)


def _seat_csv(path, amplitude, seconds=30):
    t = np.arange(0, seconds, 1 / 200)
    pd.DataFrame({"time_s": t, "seat_z_m_s2": amplitude * np.sin(2 * np.pi * 4 * t),
                  "seat_x_m_s2": 0.1 * np.sin(2 * np.pi * 2 * t)}).to_csv(path, index=False)
    return path


def test_exposure_of_one_recording_and_of_a_day_of_tasks(tmp_path):
    a, b = _seat_csv(tmp_path / "a.csv", 0.8), _seat_csv(tmp_path / "b.csv", 0.2)
    one = tyrelab.exposure(a, hours=8)
    assert one.a8_axis == "z" and one.verdict == "above action value"
    assert one.a8_m_s2 == pytest.approx(0.8 / np.sqrt(2) * 0.967, rel=5e-3)  # |W_k(4 Hz)|, ISO 2631-1 Table 3
    assert set(one.axes["axis"]) == {"x", "z"} and one.to_dict()["a8_axis"] == "z"
    assert json.loads(one.to_json())["verdict"] == one.verdict
    day = tyrelab.exposure([("ploughing", a, 2), ("road", b, 6)])
    assert [t["name"] for t in day.to_dict()["tasks"]] == ["ploughing", "road"]
    assert day.a8_m_s2 == pytest.approx(np.hypot(one.a8_m_s2 * 0.5, 0.25 * one.a8_m_s2 * np.sqrt(6 / 8)), rel=1e-3)


def test_exposure_refuses_bad_hours_before_reading_anything(tmp_path):
    with pytest.raises(ValueError, match="hours of task 'x'"):
        tyrelab.exposure(tmp_path / "x.csv", hours=0)
    with pytest.raises(ValueError, match="hours of task 'x': 25 h is not in"):
        tyrelab.exposure(tmp_path / "x.csv", hours=25)
    with pytest.raises(ValueError, match="recording must be a path"):
        tyrelab.exposure(3.0)


def test_tyrelab_exposure_is_callable_whether_or_not_its_module_was_imported_first():
    code = ("import tyrelab, tyrelab.exposure as m, tyrelab.cli; "
            "assert tyrelab.exposure is m and callable(tyrelab.exposure) and m.assess; print('ok')")
    assert subprocess.run([sys.executable, "-c", code], capture_output=True, text=True).stdout == "ok\n"
    assert callable(tyrelab.exposure) and tyrelab.analyse_recording is tyrelab.analyze_recording
