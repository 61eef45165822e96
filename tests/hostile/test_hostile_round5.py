"""The fifth hostile probe (issue 46): numbers a file or an argument can ask for, huge integers,
bools where numbers belong, one bad scenario beside good ones. Each refusal is one line naming
the option, argument or key; the library raises ValueError, never OverflowError."""

import functools
import json
import math

import numpy as np
import pytest

import tyrelab
from tests.scenarios import scenario_text
from tyrelab import _validate
from tyrelab.cli import main
from tyrelab.resources import scenarios_dir
from tyrelab.scenario_io import ScenarioError, huge_number_problems, parse_scenario, scenario_from_dict
from tyrelab.stages import simulate as simulate_stage
from tyrelab.vehicle import ride as ride_module
from tyrelab.watch import WatchOptions

text = functools.partial(scenario_text, name="round5", hours_per_day=None)
HUGE = 10**400
HUGE_TEXT = "1" + "0" * 400
MODERN = scenarios_dir() / "modern_tractor.toml"
NF = ["--pitch-inertia", "5000", "--front-distance", "1.5", "--rear-distance", "1", "--front-tyre", "7.50-18",
      "--front-pressure", "2", "--rear-tyre", "13.6R38", "--rear-pressure", "1.2"]


def lines(err: str) -> list[str]:
    assert "Traceback" not in err and "Warning" not in err
    return err.splitlines()


# ----------------------------------------------------------------------------- the shared checker
@pytest.mark.parametrize("check", [
    lambda v: _validate.positive("x", v), lambda v: _validate.non_negative("x", v),
    lambda v: _validate.probability("x", v), lambda v: _validate.finite("x", v),
    lambda v: _validate.in_range("x", v, 0, 1), lambda v: _validate.positive_array("x", [1.0, v]),
    lambda v: _validate.non_negative_array("x", [v]), lambda v: _validate.finite_array("x", [v]),
    lambda v: _validate.band("x", (0, v)),
])
@pytest.mark.parametrize("value", [HUGE, -HUGE, math.inf, math.nan, True, np.bool_(True)],
                         ids=["huge", "-huge", "inf", "nan", "True", "np.True_"])
def test_every_check_refuses_huge_integers_non_finite_and_bools_with_a_value_error(check, value):
    is_bool = isinstance(value, (bool, np.bool_))
    try:
        check(value)
    except ValueError as exc:
        assert str(exc).startswith("x ") and len(str(exc)) < 200  # a 401-digit number is not printed whole
    else:  # a bool inside a float array is numpy's 1.0: only the scalar checks see it
        assert is_bool and check(1.0) is not None


@pytest.mark.parametrize("value", [True, False, np.bool_(False)])
def test_scalar_checks_refuse_bools(value):
    for check in (_validate.positive, _validate.non_negative, _validate.finite, _validate.probability):
        with pytest.raises(ValueError, match="^x must be a number"):
            check("x", value)


def test_shown_keeps_a_huge_number_short():
    assert _validate.shown(HUGE) == "1000000000…0000000000 (401 digits)"
    assert _validate.shown(-HUGE).startswith("-1000000000…")
    assert len(_validate.shown("x" * 10_000)) < 100


# ----------------------------------------------------------------------------- the library API
@pytest.mark.parametrize("kwargs, name", [
    (dict(speeds_km_h=[HUGE]), "speeds_km_h[0]"),
    (dict(speeds_km_h=[8, -HUGE]), "speeds_km_h[1]"),
    (dict(speeds_km_h=[True]), "speeds_km_h[0]"),
    (dict(speeds_km_h=[math.nan]), "speeds_km_h[0]"),
    (dict(speeds_km_h=[1e300]), "speeds_km_h"),
    (dict(speeds_km_h="8"), "speeds_km_h"),
    (dict(speeds_km_h=8), "speeds_km_h"),
    (dict(speeds_km_h=[]), "speeds_km_h"),
    (dict(front_pressure_bar=HUGE), "front_pressure_bar"),
    (dict(rear_pressure_bar=HUGE), "rear_pressure_bar"),
    (dict(rear_pressure_bar=False), "rear_pressure_bar"),
    (dict(front_pressure_bar=1e6), "front_pressure_bar"),
    (dict(speeds_km_h=[8], with_spectra="yes"), "with_spectra"),
    (dict(speeds_km_h=[8], max_samples=0), "max_samples"),
    (dict(speeds_km_h=[8], max_samples=True), "max_samples"),
])
def test_ride_refuses_bad_arguments_naming_them(kwargs, name):
    with pytest.raises(ValueError) as info:
        tyrelab.ride(MODERN, **kwargs)
    assert not isinstance(info.value, OverflowError) and name in str(info.value)


@pytest.mark.parametrize("n", [1_000, 10_000])
def test_ride_with_many_speeds_is_refused_before_any_work_like_the_cli(n):
    speeds = list(np.linspace(2.0, 30.0, n))
    with pytest.raises(ValueError, match="max_samples=N lifts the bound"):
        tyrelab.ride(MODERN, speeds_km_h=speeds)


def test_ride_max_samples_lifts_or_lowers_the_bound():
    with pytest.raises(ValueError, match="more than 1,000"):
        tyrelab.ride(MODERN, speeds_km_h=[8], max_samples=1000)


def test_ride_scenario_dict_with_a_huge_integer_names_the_key():
    import tomllib

    doc = tomllib.loads(MODERN.read_text())
    doc["tractor"]["mass_kg"] = HUGE
    doc["tractor"]["pitch_inertia_kg_m2"] = -5
    with pytest.raises(ScenarioError) as info:
        tyrelab.ride(doc, speeds_km_h=[8])
    problems = info.value.problems
    assert any(p.startswith("tractor.mass_kg: 1000000000…") for p in problems)
    assert any(p.startswith("tractor.pitch_inertia_kg_m2") for p in problems)  # every problem at once


@pytest.mark.parametrize("hours, words", [
    (True, "True is not a number of hours"), (False, "False is not a number of hours"),
    (np.bool_(True), "is not a number of hours"), (HUGE, "is not a finite number of hours"),
    (-HUGE, "is not a finite number of hours"), (math.inf, "not a finite number"),
])
def test_exposure_refuses_bools_and_huge_hours_before_reading(tmp_path, hours, words):
    missing = tmp_path / "none.parquet"
    with pytest.raises(ValueError) as info:
        tyrelab.exposure(missing, hours=hours)
    assert words in str(info.value) and "hours of task" in str(info.value)
    with pytest.raises(ValueError) as info:
        tyrelab.exposure([("a", missing, hours), ("b", missing, HUGE)])
    assert "task 'b'" in str(info.value)


@pytest.mark.parametrize("kwargs, name", [
    (dict(axle_mass_kg=HUGE), "axle_mass_kg"), (dict(axle_mass_kg=True), "axle_mass_kg"),
    (dict(axle_mass_kg=600.0, sample_rate_Hz=HUGE), "sample_rate_Hz"),
    (dict(axle_mass_kg=600.0, sample_rate_Hz=True), "sample_rate_Hz"),
])
@pytest.mark.parametrize("recording", ["missing.parquet", "frame"])
def test_analyse_recording_refuses_huge_and_bool_arguments_before_reading(kwargs, name, recording):
    import pandas as pd

    rec = pd.DataFrame({"time_s": [0.0, 0.001]}) if recording == "frame" else recording
    with pytest.raises(ValueError) as info:
        tyrelab.analyse_recording(rec, **kwargs)
    assert str(info.value).startswith(name)


def test_export_refuses_pressures_no_tyre_is_built_for():
    from tyrelab.export import TyreTables, tyre_export

    import pandas as pd

    tables = TyreTables(tyres=pd.DataFrame({"tyre_id": ["T1"], "size": ["13.6R38"]}))
    for bad, name in (([1e308], "pressures_bar[0]"), ([1.2, HUGE], "pressures_bar[1]"), ([True], "pressures_bar[0]"),
                      ([], "at least one"), ("1.2", "a list")):
        with pytest.raises(ValueError, match=name.replace("[", r"\[").replace("]", r"\]")):
            tyre_export(tables, "T1", bad)


# ----------------------------------------------------------------------------- the command line
@pytest.mark.parametrize("argv, option", [
    (["natural-frequencies", "--mass", "1e308", *NF], "--mass"),
    (["natural-frequencies", "--mass", HUGE_TEXT, *NF], "--mass"),
    (["natural-frequencies", "--mass", "50", *NF], "--mass"),
    (["natural-frequencies", "--mass", "4000", *NF, "--age", "1e308"], "--age"),
    (["natural-frequencies", "--mass", "4000", *NF, "--front-stiffness", "1e308"], "--front-stiffness"),
    (["natural-frequencies", "--mass", "4000", *NF, "--rear-stiffness-u", "nan"], "--rear-stiffness-u"),
    (["natural-frequencies", "--mass", "4000", *NF, "--front-stiffness-u", "-1"], "--front-stiffness-u"),
    (["natural-frequencies", "--mass", "4000", *NF[:-1], "1e308"], "--rear-pressure"),
    (["estimate-stiffness", "--size", "13.6R38", "--pressure", "1e308"], "--pressure"),
    (["estimate-stiffness", "--size", "13.6R38", "--pressure", "1.7e308", "--format", "json"], "--pressure"),
    (["estimate-stiffness", "--size", "13.6R38", "--pressure", "1.2", "--age", "1e308"], "--age"),
    (["export-tyre", "T1", "--build", "nowhere", "--pressure", "1.2", "1e308"], "--pressure"),
    (["road", "x.csv", "--start-m", "1e308"], "--start-m"),
    (["road", "x.crg", "--length-m", "1e12"], "--length-m"),
    (["road", "x.crg", "--track-width-m", "1e308"], "--track-width-m"),
    (["road", "x.crg", "--lateral-offset-m=-1e308"], "--lateral-offset-m"),
    (["natural-frequencies", "--mass", "inf", *NF], "--mass"),
    (["sql", "SELECT 1", "--timeout", "nan"], "--timeout"),
    (["ride", "x.toml", "--speeds", "8", "1e400"], "--speeds"),
    (["ride", "x.toml", "--max-samples", HUGE_TEXT], "--max-samples"),
    (["exposure", "x.parquet", "--hours", HUGE_TEXT], "--hours"),
    (["analyze-run", "x.parquet", "--axle-mass", "1e308"], "--axle-mass"),
    (["analyze-run", "x.parquet", "--axle-mass", "600", "--sample-rate", "1e300"], "--sample-rate"),
    (["generate", "--out", "nowhere", "--seed", "-1"], "--seed"),
    (["generate", "--out", "nowhere", "--seed", HUGE_TEXT], "--seed"),
])
def test_every_numeric_option_out_of_range_is_one_line_naming_it(tmp_path, monkeypatch, capsys, argv, option):
    monkeypatch.chdir(tmp_path)
    try:
        rc = main(argv)
    except SystemExit as exc:  # argparse's own refusal: the same one line
        rc = exc.code
    out, err = capsys.readouterr()
    assert rc == 2 and out == "" and len(lines(err)) == 1 and option in err and len(err) < 300
    assert not (tmp_path / "nowhere").exists()  # refused before anything is written


def test_all_bad_options_of_a_verb_at_once(capsys):
    rc = main(["natural-frequencies", "--mass", "1e308", "--pitch-inertia", "0.0001", *NF[2:], "--age", "99"])
    err = capsys.readouterr().err
    assert rc == 2 and [ln.split(": ")[1].split()[0] for ln in lines(err)] == ["--mass", "--pitch-inertia", "--age"]


def test_natural_frequencies_in_range_still_answer(capsys):
    assert main(["natural-frequencies", "--mass", "4000", *NF]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert 1.0 < doc["natural_frequencies_Hz"]["bounce"] < 10.0 if "natural_frequencies_Hz" in doc else doc


@pytest.mark.parametrize("args, option", [
    (["--interval", "nan"], "--interval"), (["--interval", "1e308"], "--interval"), (["--interval", "0"], "--interval"),
    (["--settle", "-1"], "--settle"), (["--settle", "inf"], "--settle"),
    (["--max-runs", "0"], "--max-runs"), (["--max-runs", HUGE_TEXT], "--max-runs"),
])
def test_watch_options_are_checked_with_the_raw_folder_all_at_once(tmp_path, capsys, args, option):
    rc = main(["watch", "--raw", str(tmp_path / "none"), "--build", str(tmp_path / "b"), *args])
    err = lines(capsys.readouterr().err)
    assert rc == 2 and len(err) == 2 and any(option in ln for ln in err) and any("--raw" in ln for ln in err)


@pytest.mark.parametrize("kwargs", [dict(interval_s=True), dict(settle_s=HUGE), dict(max_runs=True),
                                    dict(max_runs=2.0), dict(interval_s=86_401)])
def test_watch_options_refuse_bools_and_huge_values(kwargs):
    with pytest.raises(ValueError, match=next(iter(kwargs))):
        WatchOptions(**kwargs)


# ----------------------------------------------------------------------------- huge integers in a scenario
@pytest.mark.parametrize("kwargs, key", [
    (dict(tractor={"mass_kg": HUGE_TEXT}), "tractor.mass_kg"),
    (dict(tractor={"mass_kg": "-" + HUGE_TEXT}), "tractor.mass_kg"),
    (dict(speeds=f"[8, {HUGE_TEXT}]"), "exposure.speeds_km_h[1]"),
    (dict(front=f"pressure_bar_x = {HUGE_TEXT}"), "tyres.front.pressure_bar_x"),
    (dict(extra=f"[simulation]\nduration_s = {HUGE_TEXT}"), "simulation.duration_s"),
    (dict(surface=f'kind = "iso8608"\nclass = "C"\nseed = {HUGE_TEXT}'), "surface.seed"),
])
def test_a_huge_integer_in_a_scenario_names_its_key(kwargs, key):
    with pytest.raises(ScenarioError) as info:
        parse_scenario(text(**kwargs))
    assert any(p.startswith(f"{key}: 1000000000…") or p.startswith(f"{key}: -1000000000…")
               for p in info.value.problems), info.value.problems


def test_huge_number_problems_walks_tables_and_arrays():
    assert huge_number_problems({"a": [1, {"b": HUGE}], "c": True, "d": 1e308}) == [
        "a[1].b: 1000000000…0000000000 (401 digits) is not a finite number"]
    with pytest.raises(ScenarioError):
        scenario_from_dict({"name": "x", "tractor": {"mass_kg": HUGE}})


def test_tyrelab_ride_on_a_scenario_with_a_huge_mass_is_one_line(tmp_path, capsys):
    p = tmp_path / "huge.toml"
    p.write_text(text(tractor={"mass_kg": HUGE_TEXT}))
    assert main(["ride", str(p)]) == 2
    err = lines(capsys.readouterr().err)
    assert len(err) == 1 and "tractor.mass_kg" in err[0]


# ----------------------------------------------------------------------------- one bad scenario, the others through
def test_a_huge_integer_scenario_beside_a_good_one_is_quarantined(tmp_path):
    good, bad = tmp_path / "good.toml", tmp_path / "bad.toml"
    good.write_text(text(name="good"))
    bad.write_text(text(name="bad", tractor={"mass_kg": HUGE_TEXT}))
    scenarios, results, problems = simulate_stage.run_scenarios([(str(good), "raw"), (str(bad), "raw")])
    assert list(scenarios["file"]) == [str(good)] and set(results["file"]) == {str(good)}
    assert [p["file"] for p in problems] == [str(bad)] and "tractor.mass_kg" in problems[0]["reason"]


@pytest.mark.parametrize("error", [TypeError("unexpected"), KeyError("x"), AttributeError("y"), OverflowError("z")])
def test_any_failure_of_one_scenario_is_its_own(tmp_path, monkeypatch, error):
    good, bad = tmp_path / "good.toml", tmp_path / "bad.toml"
    good.write_text(text(name="good"))
    bad.write_text(text(name="bad"))
    real = ride_module.ride_sweep

    def failing(sc, *a, **k):
        if sc.name == "bad":
            raise error
        return real(sc, *a, **k)

    monkeypatch.setattr(ride_module, "ride_sweep", failing)
    scenarios, _, problems = simulate_stage.run_scenarios([(str(good), "raw"), (str(bad), "raw")])
    assert list(scenarios["file"]) == [str(good)]
    assert problems[0]["file"] == str(bad) and type(error).__name__ in problems[0]["reason"]


@pytest.mark.parametrize("error", [OverflowError("int too large"), TypeError("x"), PermissionError(13, "denied")])
def test_the_ride_plan_never_stops_on_one_file(tmp_path, monkeypatch, error):
    from tyrelab.itemcache import ItemCache

    good, bad = tmp_path / "good.toml", tmp_path / "bad.toml"
    good.write_text(text(name="good"))
    bad.write_text(text(name="bad"))
    from tyrelab.stages import ride_scenarios  # the simulate stage's ride scenarios (issue 45)

    real = ride_scenarios.load_scenario

    def loading(path, *a, **k):
        if str(path).endswith("bad.toml"):
            raise error
        return real(path, *a, **k)

    monkeypatch.setattr(ride_scenarios, "load_scenario", loading)
    monkeypatch.setattr(ride_scenarios, "read_fit_tables", lambda ctx: {})
    monkeypatch.setattr(ride_scenarios, "scenario_fits", lambda sc, tables: {})

    class Ctx:
        parquet = tmp_path / "parquet"
        build = tmp_path / "build"

    cache = ItemCache(Ctx(), "simulate", "round5")
    keys, tyres = simulate_stage._ride_plan(Ctx(), [(str(good), "raw"), (str(bad), "raw")], cache)
    assert len(keys) == 2 and len(set(keys)) == 2
