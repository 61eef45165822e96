"""The axis that governs A(8) (issue 38): one rule for the ride rows, ride.json and ``tyrelab exposure``."""

import math

import pytest

from tests.scenarios import scenario_text, write
from tyrelab.scenario_io import load_scenario
from tyrelab.vehicle import iso2631, ride
from tyrelab.vehicle.daily_exposure import TaskExposure, daily_exposure, governing_axis


def test_the_largest_k_a_w_governs_ties_go_to_x_then_y_then_z_and_nan_is_ignored():
    assert governing_axis({"z": 0.5, "x": 1.4 * 0.4}) == "x"  # 0.56 > 0.5: the lateral/fore-aft factor decides
    assert governing_axis({"z": 0.6, "x": 1.4 * 0.4}) == "z"
    assert governing_axis({"z": 0.3, "y": 0.3, "x": 0.3}) == "x"
    assert governing_axis({"z": 0.3, "y": 0.3}) == "y"
    assert governing_axis({"x": math.nan, "z": 0.1}) == "z"
    assert governing_axis({"x": math.nan}) is None and governing_axis({}) is None


def test_a_speed_row_names_the_axis_of_its_a8():
    e = ride.exposure(0.5, 0.4, 8.0)  # k a_wx = 0.56 beats a_wz = 0.5
    assert e["a8_axis"] == "x" and e["a8_m_s2"] == pytest.approx(0.56, rel=1e-15)
    e = ride.exposure(0.5, 0.1, 8.0, a_wy_m_s2=0.38)
    assert e["a8_axis"] == "y" and e["a8_m_s2"] == pytest.approx(1.4 * 0.38, rel=1e-15)
    assert ride.exposure(0.9, 0.1, 8.0)["a8_axis"] == "z"


def test_ride_rows_and_json_carry_a8_axis_consistent_with_their_a_w(tmp_path):
    res = ride.ride(load_scenario(write(tmp_path, scenario_text(speeds="[6, 14]"))), with_spectra=False)
    doc = ride.result_json([res])
    k = iso2631.AXIS_FACTOR
    for row, js in zip(res.speeds.to_dict(orient="records"), doc["speeds"]):
        weighted = {ax: k[ax] * row[f"a_w{ax}_m_s2"] for ax in ("x", "y", "z")}
        assert row["a8_axis"] == max(weighted, key=weighted.get) == js["a8_axis"]
        assert row["a8_m_s2"] == pytest.approx(weighted[row["a8_axis"]] * math.sqrt(6 / 8), rel=1e-12)


def test_the_day_of_exposure_uses_the_same_rule():
    day = daily_exposure([TaskExposure("a", 4.0, {"x": 0.4, "y": 0.1, "z": 0.5}, {"x": 5.0, "y": 1.0, "z": 6.0}, 600.0)])
    assert day["a8_axis"] == governing_axis({ax: iso2631.AXIS_FACTOR[ax] * v for ax, v in
                                             {"x": 0.4, "y": 0.1, "z": 0.5}.items()}) == "x"
