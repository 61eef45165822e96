"""Issue 42, Deliver 2 and the first Checked-by item, end to end: a fresh ``tyrelab run`` over a campaign
whose scenario names a measured tyre (``measured_tyre_id = "T1"``, with T1's lateral rolling runs in the
campaign, so its lateral K, C and the series damper's ``a`` of ``c₂ = a / v`` are measured):

- the rolling element takes the build's lateral coefficients, each named ``measured``;
- the run's ride rows equal ``tyrelab ride --build`` on the finished build (and the library call on it);
- the modes (undamped frequency, damping ratio) and the seat's a_wx, a_wy, a_wz agree with the independent
  reference model (``tests/vehicle/reference_lateral.py``, not the project's assembly) fed the build's
  numbers, worked out here from the warehouse tables by hand.

The campaign is the smallest with lateral rolling runs: of the small virtual campaign only T1's
pressure x speed sweep (its vertical fits) and its lateral random runs (0 and 5 km/h at two pressures),
with the calibration run of each of their days — each run as in the whole campaign. Slow: the fresh run
goes through every stage, the thesis' studies and the report included (~25 s of CPU).
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from tyrelab.cli import main
from tyrelab.generate import generate_campaign
from tyrelab.scenario_io import load_scenario
from tyrelab.stages import simulate
from tyrelab.tyredata import WarehouseTyres
from tyrelab.vehicle import ride

from tests.vehicle.test_reference_rolling_ride import A_SERIES, CY, KY, SPEEDS, _check, _scenario, _subset

pytestmark = pytest.mark.slow

LATERAL = ("stiffness_kN_per_m", "damping_kN_s_per_m", "series_damping_kN_s_per_m_km_h")
REAR_PRESSURE_BAR = 1.2  # test_ride_3d's rear tyre
AMPLITUDE_M = 0.01


def _t1_lateral(plan: pd.DataFrame) -> pd.Series:
    """T1's sweep and lateral runs and the calibration runs of their days."""
    mine = (plan["tyre_id"] == "T1") & (plan["run_id"].str.contains("_sweep_") | (plan["direction"] == "lateral"))
    return mine | ((plan["kind"] == "calibration") & plan["recorded_on"].isin(plan.loc[mine, "recorded_on"]))


@pytest.fixture(scope="module")
def fresh(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("measured_rolling")
    raw, build = tmp / "raw", tmp / "build"
    summary = generate_campaign(raw / "t1", scale="small", seed=1991, runs=_t1_lateral)
    assert summary["measurement_runs"] == 13 and summary["calibration_runs"] == 2
    scenarios = raw / "scenarios"
    scenarios.mkdir()
    # the tractor of test_ride_3d, rolling tyres (the 3-D default), one-sided sinusoids (test_reference_rolling_ride):
    # the front's lateral K, C, a given, the rear tyre the measured T1 (its vertical K, C stay the scenario's)
    _scenario(scenarios, AMPLITUDE_M, 0.0, False, SPEEDS, {
        "lateral_stiffness_kN_per_m": {"front": KY["front"]}, "lateral_damping_kN_s_per_m": {"front": CY["front"]},
        "lateral_series_damping_kN_s_per_m_km_h": {"front": A_SERIES["front"]}, "measured_tyre_id": {"rear": '"T1"'}})
    path = scenarios / "s.toml"
    assert main(["run", "--raw", str(raw), "--build", str(build), "--jobs", "1"]) == 0
    return raw, build, path


def _sql(build, query, capsys) -> pd.DataFrame:
    capsys.readouterr()
    assert main(["sql", "--build", str(build), "--format", "json", query]) == 0
    return pd.DataFrame(json.loads(capsys.readouterr().out))


def test_the_run_equals_tyrelab_ride_on_the_finished_build(fresh, capsys):
    raw, build, path = fresh
    rows = _sql(build, "SELECT * FROM ride_results WHERE file = "
                       f"'{simulate.portable_path(str(path), raw)}' ORDER BY speed_km_h", capsys)
    assert list(rows["speed_km_h"]) == list(map(float, SPEEDS))
    assert main(["ride", str(path), "--build", str(build), "--format", "json", "--jobs", "1"]) == 0
    doc = json.loads(capsys.readouterr().out)
    rear = doc["tyres"]["rear"]
    assert rear["lateral_sources"] == dict.fromkeys(LATERAL, "measured") and "T1" in rear["lateral_source"]
    assert doc["tyres"]["front"]["lateral_sources"] == dict.fromkeys(LATERAL, "scenario")
    cli = pd.DataFrame(doc["speeds"])
    for column in ("a_wz_m_s2", "a_wx_m_s2", "a_wy_m_s2", "a_v_m_s2", "vdv_m_s1_75"):
        # the JSON prints 6 significant digits; the library call below is exact
        assert list(cli[column]) == pytest.approx(list(rows[column]), rel=1e-5, abs=1e-9), column
    # the modes with their damping: the first speed's frequencies, and each speed's as the table's text prints them
    assert {f"{k}_Hz" for k in doc["natural_frequencies_Hz"]} <= set(rows.columns) and "yaw" in doc["natural_frequencies_Hz"]
    for name, f in doc["natural_frequencies_Hz"].items():
        assert rows[f"{name}_Hz"].iloc[0] == pytest.approx(f, rel=1e-5), name
    for speed in doc["modes_by_speed"]:
        text = "; ".join(f"{k} overdamped ({m['natural_frequency_Hz']:.3f} Hz)" if m["overdamped"] else
                         f"{k} {m['natural_frequency_Hz']:.3f} Hz ζ {m['damping_ratio']:.3f}"
                         for k, m in speed["modes"].items() if m is not None)
        assert rows.loc[rows["speed_km_h"] == speed["speed_km_h"], "modes_damping"].tolist() == [text]
    table = ride.results_table(ride.ride_sweep(load_scenario(path), tyre_data=WarehouseTyres(build), with_spectra=True),
                               rows["scenario"].iloc[0])
    shared = [c for c in table.columns if c in rows.columns and c != "file"]
    pd.testing.assert_frame_equal(rows[shared], table[shared], check_exact=False, rtol=1e-12, check_dtype=False)


def _at(lines: pd.DataFrame, pressure_bar: float, speeds) -> np.ndarray:
    """A per-speed pressure fit (intercept + slope P) at ``pressure_bar``, interpolated in speed and held
    outside the measured speeds, kN/m or kN s/m."""
    lines = lines.sort_values("speed_km_h")
    at_p = lines["intercept"].to_numpy(float) + lines["slope"].to_numpy(float) * pressure_bar
    return np.interp(np.asarray(speeds, float), lines["speed_km_h"].to_numpy(float), at_p)


def test_a_measured_tyre_of_a_fresh_build_agrees_with_the_independent_reference(fresh, capsys):
    raw, build, path = fresh
    where = "WHERE tyre_id = 'T1' AND intercept IS NOT NULL AND slope IS NOT NULL"
    k_lines = _sql(build, f"SELECT speed_km_h, intercept, slope FROM lateral_stiffness_pressure_by_speed {where}", capsys)
    c_lines = _sql(build, f"SELECT speed_km_h, intercept, slope FROM lateral_damping_pressure_by_speed {where}", capsys)
    a = _sql(build, "SELECT coefficient_kN_s_per_m_times_km_h AS a FROM series_damping_speed "
                    "WHERE tyre_id = 'T1' AND direction = 'lateral'", capsys)["a"]
    assert sorted(k_lines["speed_km_h"]) == [0.0, 5.0] and len(a) == 1
    # the rig's truth (tyrelab.rig.method_runs): T1's a = 10 kN s/m x 10 km/h; its lateral K about 0.45 of the
    # vertical stationary stiffness; the fits come from noisy recordings, so only roughly
    assert a.iloc[0] == pytest.approx(100.0, rel=0.1)
    ky = _at(k_lines, REAR_PRESSURE_BAR, SPEEDS)
    cy = np.maximum(_at(c_lines, REAR_PRESSURE_BAR, SPEEDS), 0.0)
    assert np.all((ky > 150.0) & (ky < 400.0)) and np.all(cy > 0.0)

    res = ride.ride(load_scenario(path), tyre_data=WarehouseTyres(build), with_spectra=False)
    rear = res.tyres["rear"]
    assert rear.lateral_stiffness_kN_per_m == pytest.approx(ky, rel=1e-9)
    assert rear.lateral_damping_kN_s_per_m == pytest.approx(cy, rel=1e-9)
    assert rear.lateral_series_damping_kN_s_per_m_km_h == pytest.approx(a.iloc[0], rel=1e-9)
    for i, speed in enumerate(SPEEDS):  # one reference tractor per speed (K_y, C_y follow the speed)
        _check(_subset(res, i), False, (speed,), AMPLITUDE_M, 0.0,
               {"front": 1e3 * KY["front"], "rear": 1e3 * ky[i]}, {"front": 1e3 * CY["front"], "rear": 1e3 * cy[i]},
               {"front": 1e3 * A_SERIES["front"], "rear": 1e3 * a.iloc[0]})
