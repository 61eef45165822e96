"""Spectral rows and the choice of method (issue 36): ``[simulation] method``, ``tyrelab ride --method``."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from tests.scenarios import scenario_text, write
from tyrelab.cli import main
from tyrelab.report.ride_page import format_table, render_page
from tyrelab.resources import scenarios_dir
from tyrelab.scenario_io import load_scenario, parse_scenario
from tyrelab.vehicle import ride, spectral_ride
from tyrelab.vehicle import scenario_limits as limits
from tyrelab.vehicle.model import assemble
from tyrelab.vehicle.solvers import lti

#: Both shipped scenarios on main before issue 36 (at 3b91bfc, after issue 33; one variant each: its rows
#: must not change), under the thesis' gravity 9.81 m/s² the model had then (issue 45 made it the
#: standard 9.80665: ``tests/vehicle/test_parts_unchanged.py`` records how far that moves them).
BEFORE = {
    "modern_tractor.toml": {
        "a_wz_m_s2": [0.07299975902082016, 0.5679819366778999, 0.9706889865435399, 0.9557106855462723],
        "a_wx_m_s2": [0.05169685140311933, 0.37323982675972794, 0.6684394697340468, 0.6693073282037546],
        "expected_a_wz_m_s2": [0.07002171419085243, 0.5341979547030931, 0.958054965812363, 0.9526429317293867],
        "vdv_m_s1_75": [0.4251481113302107, 2.7187315566632684, 4.096870739295132, 3.9123808638616095],
        "crest_factor": [4.012604601502517, 3.4935424216942343, 3.169784969794118, 3.487362708128478],
        "hours_to_eav": [375.3074130988937, 6.1995611379252, 2.122607973886933, 2.1896621540883285],
        "lift_off_fraction_front": [0.0, 0.0, 0.0, 0.0],
    },
    "mf698t.toml": {
        "a_wz_m_s2": [1.6247881676860152, 1.9286413193747094, 2.678863266930218, 2.7732278158243586, 2.882469591152072],
        "a_wx_m_s2": [0.0, 0.0, 0.0, 0.0, 0.0],
        "expected_a_wz_m_s2": [1.5776210132168247, 2.1269821719302464,
                               2.2963443842868116, 3.10202332446235, 3.8576020848008534],
        "vdv_m_s1_75": [5.0244590789213515, 5.888651339590329, 8.522376161878247, 8.36190307899481, 8.960275353447672],
        "crest_factor": [3.355377711653201, 3.2095427949000412,
                         3.407701418814293, 3.2249782247201484, 3.100453877617885],
        "hours_to_eav": [0.7575939542213631, 0.5376839364040809,
                         0.2786948229802309, 0.26005122296550703, 0.24071354396411196],
        "lift_off_fraction_front": [0.0009333333333333333, 0.01806666666666667,
                                    0.07133333333333333, 0.11223333333333334, 0.17823333333333333],
    },
}


@pytest.mark.parametrize("name", sorted(BEFORE))
def test_a_single_scenario_keeps_its_time_rows(name, monkeypatch):
    from tests.vehicle.golden_vehicle import use_thesis_gravity

    use_thesis_gravity(monkeypatch)
    sc = load_scenario(scenarios_dir() / name)
    assert sc.simulation.method == "auto"
    auto = ride.results_table(ride.ride_sweep(sc, with_spectra=False))
    assert set(auto["method"]) == {"time"}
    for column, before in BEFORE[name].items():
        assert auto[column].tolist() == pytest.approx(before, rel=1e-9, abs=1e-12), column
    assert auto["mtvv_m_s2"].notna().all()  # a record has an MTVV


def _lifting(tmp_path=None, speeds="[3, 20]"):
    """A light front end (CG 0.5 m ahead of the rear axle) on a rough (class D) track."""
    return parse_scenario(scenario_text(surface='kind = "iso8608"\nclass = "D"\nlength_m = 60', speeds=speeds,
                                        tractor=dict(front_distance_m=2.0, rear_distance_m=0.5)))


def test_a_variant_that_lifts_off_is_simulated_under_auto_and_says_so():
    sc = _lifting()
    results = ride.ride_sweep(sc, [1.0, 1.6], [1.2], with_spectra=False)  # 1.6/1.2 bar: the nominal
    other = results[0]
    assert other.tyres["front"].pressure_bar == 1.0 and set(other.speeds["method"]) == {"spectral"}
    p = other.speeds.set_index("speed_km_h")["lift_off_probability_front"]
    assert p[3.0] < spectral_ride.LIFT_OFF_PROBABILITY_LIMIT < p[20.0]
    # the speed that may lift a tyre is simulated (nonlinear), the other is not
    assert other.time_rows["speed_km_h"].tolist() == [20.0]
    assert other.time_rows["method"].tolist() == ["time"]
    assert other.time_rows["simulation"].tolist() == ["nonlinear (tyre lift-off)"]
    assert other.time_rows["lift_off_fraction_front"].iloc[0] > 0
    assert len(results[1].time_rows) == 2  # the nominal variant: every speed
    doc = ride.result_json(results)
    assert doc["sweep"][0]["time_domain"][0]["simulation"] == "nonlinear (tyre lift-off)"
    table = format_table(doc)
    assert "simulated beside: nonlinear (tyre lift-off)" in table
    assert "whose lift-off probability exceeds 0.001: 2 rows" in " ".join(table.split())
    flat = ride.results_table(results)
    assert flat.groupby("method").size().to_dict() == {"spectral": 4, "time": 3}


def test_spectral_mtvv_and_crest_factor_are_null_in_json_and_dashes_on_the_page():
    sc = parse_scenario(scenario_text(speeds="[8, 12]", extra='[simulation]\nmethod = "spectral"'))
    results = ride.ride_sweep(sc, with_spectra=True)
    doc = ride.result_json(results)
    for row in doc["speeds"]:
        assert row["method"] == "spectral"
        assert row["mtvv_m_s2"] is None and row["crest_factor"] is None and row["vdv_m_s1_75"] is None
        assert row["evdv_m_s1_75"] > 0 and row["a_wz_m_s2"] > 0
    html = render_page(results, doc)
    table = html[html.index("<h2>Seat vibration per speed</h2>"):]
    table = table[:table.index("</table>")]
    header = re.findall(r"<th>(.*?)</th>", table)
    cells = re.findall(r"<tr>(.*?)</tr>", table.split("<tbody>")[1])[0]
    cells = re.findall(r"<td[^>]*>(.*?)</td>", cells)
    by_name = dict(zip(header, cells))
    assert by_name["mtvv (m/s²)"] == "–" and by_name["crest factor"] == "–" and by_name["method"] == "spectral"
    assert "a spectral row has none (–)" in html
    assert "evdv_m_s1_75" in doc["speeds"][0]
    assert "crest" in format_table(doc) and " – " in format_table(doc)


def test_spectral_rows_are_the_expectation_and_evdv_is_iso_2631_1s_estimate():
    sc = parse_scenario(scenario_text(speeds="[6, 10]"))
    time_row = ride.ride(sc, with_spectra=False).speeds
    spec = ride.spectral_variants([sc], with_spectra=False)[0].speeds
    for ax in ("z", "x"):
        assert spec[f"a_w{ax}_m_s2"].tolist() == pytest.approx(time_row[f"expected_a_w{ax}_m_s2"].tolist(), rel=1e-12)
    row = spec.iloc[1]
    highest = max(row["a_wz_m_s2"], 1.4 * row["a_wx_m_s2"])
    assert row["evdv_m_s1_75"] == pytest.approx(1.4 * highest * row["duration_s"] ** 0.25, rel=1e-12)
    assert row["evdv_daily_m_s1_75"] == pytest.approx(1.4 * highest * (6 * 3600.0) ** 0.25, rel=1e-12)
    assert row["duration_s"] == time_row.iloc[1]["duration_s"]
    assert row["a8_m_s2"] == pytest.approx(highest * math.sqrt(6 / 8), rel=1e-12)


def test_tyre_force_standard_deviation_agrees_with_a_long_simulation():
    """The spectral σ of each axle's tyre force against the standard deviation of the simulated
    linear force on a 1.5 km track (the time path's own inputs and model; sampling scatter ~3 %)."""
    sc = parse_scenario(scenario_text(surface='kind = "iso8608"\nclass = "C"\nlength_m = 1500', speeds="[10]"))
    row = ride.spectral_variants([sc], with_spectra=False)[0].speeds.iloc[0]
    tyres = ride.resolve_tyres(sc)
    track = ride.build_profile(sc)
    asm = assemble(ride.build_parts(sc, tyres, 0))
    v = 10 / 3.6
    start, stop = ride._record_window(track, sc.tractor.wheelbase_m, v, None)
    fp = (float(tyres["front"].footprint_m[0]), float(tyres["rear"].footprint_m[0]))
    u, du = ride.tyre_inputs(asm, track.profile, sc.surface.enveloping, fp,
                             (tyres["front"].radius_m, tyres["rear"].radius_m), v, sc.tractor.wheelbase_m, stop)
    w = np.empty((2 * len(asm.tyres), stop))
    w[0::2], w[1::2] = u[:, ::2], du[:, ::2]
    lm = asm.linear(tuple(f"{t}_force_N" for t in asm.tyres))
    forces = lti.discretise(*lm.abcd, ride.DT_S).run(w)[:, start:stop]
    for k, axle in enumerate(asm.tyres):  # pitch plane: an element is the axle's two tyres
        assert row[f"{axle}_tyre_force_sd_N"] == pytest.approx(np.std(forces[k]) / 2, rel=0.08), axle
    static = asm.static_tyre_loads_N()
    assert row["lift_off_probability_front"] == pytest.approx(
        float(spectral_ride.lift_off_probability(static["front"], 2 * row["front_tyre_force_sd_N"])), rel=1e-12)


def test_bounds_know_the_method(tmp_path, capsys, monkeypatch):
    sc = load_scenario(scenarios_dir() / "modern_tractor.toml")
    speeds8 = [4, 6, 8, 10, 12, 14, 16, 18]
    assert limits.work_problems(sc, 100 * 100, speeds8, method="spectral") == []
    assert limits.work_problems(sc, 100 * 100, speeds8, method="auto") == []
    assert limits.work_problems(sc, 100 * 100, speeds8, method="time")
    monkeypatch.setattr(ride, "_sweep_results", lambda *a, **k: pytest.fail("work started"))
    pressures = [f"{1 + i / 100:g}" for i in range(100)]
    args = ["ride", str(scenarios_dir() / "modern_tractor.toml"), "--front-pressure", *pressures,
            "--rear-pressure", *pressures, "--speeds", *map(str, speeds8)]
    assert main([*args, "--method", "time"]) == 2
    err = capsys.readouterr().err
    assert "10000 variants" in err and "in the time domain" in err and "--method auto or spectral" in err
    with pytest.raises(BaseException, match="work started"):  # spectral: allowed, work starts
        main([*args, "--method", "spectral"])


def test_the_method_key_is_checked(tmp_path, capsys):
    path = write(tmp_path, scenario_text(extra='[simulation]\nmethod = "fast"'))
    assert main(["ride", str(path)]) == 2
    assert "simulation.method: 'fast' is not one of auto, time, spectral" in capsys.readouterr().err
    path = write(tmp_path, scenario_text(speeds="[8]", extra='[simulation]\nmethod = "spectral"'))
    assert main(["ride", str(path), "--method", "time", "--format", "table"]) == 0
    assert "Every row was simulated in the time domain" in " ".join(capsys.readouterr().out.split())
    with pytest.raises(ValueError, match="method"):
        ride.ride_sweep(parse_scenario(scenario_text()), method="fast")


def test_a_3d_sweep_gives_each_tyre_its_force_and_lateral_a_w():
    sc = parse_scenario(scenario_text(
        surface='kind = "iso8608"\nclass = "C"\nlength_m = 80\ntracks = "isotropic"', speeds="[10]",
        tractor_extra="roll_inertia_kg_m2 = 2400\nfront_track_m = 1.9\nrear_track_m = 1.8",
        seat="[seat]\nheight_above_cg_m = 1.0\nleft_of_cg_m = 0.35", extra='[front_axle]\nmount = "pivot"\nroll_inertia_kg_m2 = 160'))
    spec = ride.spectral_variants([sc], with_spectra=True)[0]
    row = spec.speeds.iloc[0]
    timed = ride.ride(sc, with_spectra=False).speeds.iloc[0]
    for ax in ("z", "x", "y"):
        assert row[f"a_w{ax}_m_s2"] == pytest.approx(timed[f"expected_a_w{ax}_m_s2"], rel=1e-12)
    assert row["a_wy_m_s2"] > 0 and row["front_tyre_force_sd_N"] > 0 and row["rear_tyre_force_sd_N"] > 0
    assert {"seat_vertical_psd_m2_s4_per_Hz", "seat_lateral_psd_m2_s4_per_Hz"} <= set(spec.spectra.columns)


def test_a_sweep_page_gets_the_figure_data_of_its_nominal_variant_alone():
    sc = parse_scenario(scenario_text(speeds="[8]"))
    results = ride.ride_sweep(sc, [1.2, 1.6], [1.2], with_spectra="nominal")
    assert [len(r.spectra) > 0 for r in results] == [False, True]  # 1.6/1.2 bar: the scenario's own
    # the expected PSD integrates to the unweighted seat acceleration's variance (below 20 Hz, most of it)
    psd = results[1].spectra
    df = float(np.diff(psd["frequency_Hz"]).mean())
    assert float(psd["seat_vertical_psd_m2_s4_per_Hz"].sum()) * df > results[1].speeds["a_wz_m_s2"].iloc[0] ** 2 / 4
    assert "(1.6/1.2 bar)" in " ".join(f["caption"] for f in __import__(
        "tyrelab.report.ride_page", fromlist=["figures"]).figures(results))
