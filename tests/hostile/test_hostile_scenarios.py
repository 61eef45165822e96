"""Scenario values the model cannot take, unbounded sweeps, bad scenarios in the pipeline (issue 25,
classes 1, 2 and 6): each one line naming the key and its bound, refused before any work."""

import functools
import os
from pathlib import Path

import pytest

from tests.scenarios import scenario_text
from tyrelab.cli import main
from tyrelab.stages import simulate as simulate_stage
from tyrelab.vehicle import ride
from tyrelab.scenario_io import ScenarioError, load_scenario, parse_scenario
from tyrelab.vehicle.scenario_limits import LIMITS, work_estimate

#: The ride tests' scenario, named "hostile", without an exposure time (one template: tests.scenarios).
text = functools.partial(scenario_text, name="hostile", hours_per_day=None)


@pytest.mark.parametrize("kwargs, key", [
    (dict(surface='kind = "iso8608"\nclass = "C"\nlength_m = 1e-3'), "surface.length_m"),
    (dict(surface='kind = "iso8608"\nclass = "C"\nlength_m = 1e9'), "surface.length_m"),
    (dict(surface='kind = "iso8608"\nclass = "C"\ndx_m = 1000'), "surface.dx_m"),
    (dict(surface='kind = "iso8608"\nclass = "C"\ndx_m = 1e-9'), "surface.dx_m"),
    (dict(speeds="[1e300]"), "exposure.speeds_km_h"),
    (dict(speeds="[0.001]"), "exposure.speeds_km_h"),
    (dict(extra="[simulation]\nduration_s = 1e-9"), "simulation.duration_s"),
    (dict(front="footprint_m = 1e9"), "tyres.front.footprint_m"),
    (dict(tractor={"rear_distance_m": 1e12}), "tractor.rear_distance_m"),
    (dict(tractor={"mass_kg": 1e-300}), "tractor.mass_kg"),
    (dict(tractor={"mass_kg": 1e300}), "tractor.mass_kg"),
    (dict(front="stiffness_kN_per_m = 1e-300"), "tyres.front.stiffness_kN_per_m"),
    (dict(tractor={"pitch_inertia_kg_m2": 1e300}), "tractor.pitch_inertia_kg_m2"),
])
def test_each_number_is_range_checked_naming_key_and_bound(kwargs, key):
    with pytest.raises(ScenarioError) as info:
        parse_scenario(text(**kwargs))
    if key:
        line = next(p for p in info.value.problems if p.startswith(key))
        low, high, _ = LIMITS[key.rsplit(".", 1)[-1] if key.startswith("tyres.") else key]
        assert f"{low:g} to {high:g}" in line


def test_all_problems_at_once():
    with pytest.raises(ScenarioError) as info:
        parse_scenario(text(speeds="[0.001, 8]", tractor={"mass_kg": 1e-3, "cg_height_m": 99}))
    assert len(info.value.problems) == 3


def test_toml_nesting_bomb_nul_path_and_dev_zero(tmp_path, capsys):
    with pytest.raises(ScenarioError, match="nested too deeply"):
        parse_scenario("x = " + "[" * 100000 + "]" * 100000)
    with pytest.raises(ScenarioError, match="NUL"):
        parse_scenario(text(surface='kind = "profile"\nprofile = "a\\u0000b.csv"'), tmp_path)
    for path in ("/dev/zero", str(tmp_path)):
        assert main(["ride", path]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "not a regular file" in err


def test_profile_with_inf_distance_huge_gap_or_height(tmp_path):
    import numpy as np
    import pandas as pd

    x = np.arange(64) * 0.1
    for name, frame in (("inf", pd.DataFrame({"distance_m": [*x[:-1], np.inf], "height_m": 0.0})),
                        ("gap", pd.DataFrame({"distance_m": [*x[:-1], 1e12], "height_m": 0.0})),
                        ("high", pd.DataFrame({"distance_m": x, "height_m": [1e300] * 64}))):
        frame.to_csv(tmp_path / f"{name}.csv", index=False)
        with pytest.raises(ScenarioError) as info:
            parse_scenario(text(surface=f'kind = "profile"\nprofile = "{name}.csv"'), tmp_path)
        assert any(p.startswith("surface.profile") for p in info.value.problems), name


def test_sweeps_are_bounded_before_any_work(tmp_path, capsys, monkeypatch):
    path = tmp_path / "s.toml"
    path.write_text(text())
    monkeypatch.setattr(ride, "ride", lambda *a, **k: pytest.fail("work started"))
    pressures = [str(1 + i / 1000) for i in range(1000)]
    assert main(["ride", str(path), "--front-pressure", *pressures, "--rear-pressure", *pressures]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "1000000 variants" in err and "--max-variants" in err
    assert main(["ride", str(path), "--speeds", *[str(0.5 + i / 100) for i in range(2000)]]) == 2
    err = capsys.readouterr().err
    assert "samples" in err and "--max-samples" in err and "GB" in err
    assert main(["ride", str(path), "--speeds", "1e300"]) == 2
    assert "0.5 to 80 km/h" in capsys.readouterr().err


def test_work_estimate_of_the_issue_example():
    sc = parse_scenario(text(surface='kind = "iso8608"\nclass = "C"\nlength_m = 100'))
    e = work_estimate(sc, 1, [0.05])
    assert 7e6 < e["samples"] < 8.5e6 and 2 < e["memory_GB"] < 2.6


def test_a_short_record_warns(tmp_path):
    sc = parse_scenario(text(surface='kind = "iso8608"\nclass = "C"\nlength_m = 10', speeds="[20]"))
    res = ride.ride(sc, with_spectra=False)
    assert any("too short for a reliable exposure verdict" in w for w in res.warnings)
    assert res.speeds["verdict"].iloc[0].startswith("no verdict: record 1.")


def test_a_model_failure_is_one_scenario_s_problem(tmp_path, monkeypatch):
    good, bad = tmp_path / "good.toml", tmp_path / "bad.toml"
    good.write_text(text(name="same"))
    bad.write_text(text(name="other"))
    real = ride.ride_sweep

    def failing(sc, *a, **k):
        if sc.name == "other":
            raise ZeroDivisionError("float division by zero")
        return real(sc, *a, **k)

    monkeypatch.setattr(ride, "ride_sweep", failing)
    scenarios, results, problems = simulate_stage.run_scenarios([(str(good), "raw"), (str(bad), "raw")])
    assert list(scenarios["file"]) == [str(good)] and set(results["file"]) == {str(good)}
    assert problems[0]["file"] == str(bad) and "ZeroDivisionError" in problems[0]["reason"]


def test_rows_are_keyed_by_scenario_file(tmp_path):
    a, b = tmp_path / "a.toml", tmp_path / "b.toml"
    a.write_text(text(name="same"))
    b.write_text(text(name="same", speeds="[10]"))
    scenarios, results, problems = simulate_stage.run_scenarios([(str(a), "raw"), (str(b), "raw")])
    assert not problems
    keys = results[["file", "speed_km_h", "front_pressure_bar", "rear_pressure_bar"]]
    assert not keys.duplicated().any() and set(results["file"]) == {str(a), str(b)}
