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

try:  # the ride scenarios of the simulate stage (a module of their own since issue 45)
    from tyrelab.stages import ride_scenarios as ride_stage
except ImportError:  # pragma: no cover - before it
    ride_stage = simulate_stage
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
    (["frf", "x.parquet", "--speed", "1e308"], "--speed"),
    (["frf", "x.parquet", "--max-frequency", "1e300"], "--max-frequency"),
    (["estimate-stiffness", "--size", "13.6R38", "--pressure", "0.01"], "--pressure"),
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
    real = ride_stage.load_scenario

    def loading(path, *a, **k):
        if str(path).endswith("bad.toml"):
            raise error
        return real(path, *a, **k)

    monkeypatch.setattr(ride_stage, "load_scenario", loading)
    monkeypatch.setattr(ride_stage, "read_fit_tables", lambda ctx: {})
    monkeypatch.setattr(ride_stage, "scenario_fits", lambda sc, tables: {})

    class Ctx:
        parquet = tmp_path / "parquet"
        build = tmp_path / "build"

    cache = ItemCache(Ctx(), "simulate", "round5")
    keys, tyres = ride_stage._ride_plan(Ctx(), [(str(good), "raw"), (str(bad), "raw")], cache)
    assert len(keys) == 2 and len(set(keys)) == 2


# ----------------------------------------------------------------------------- quiet and escaped
def test_sql_batches_with_duplicate_column_names_keep_each_column():
    import pyarrow as pa

    from tyrelab.warehouse import _pandas

    batch = pa.record_batch([pa.array([1], pa.int32()), pa.array(["x"]), pa.array([None], pa.int64())],
                            names=["a", "a", "a"])
    df = _pandas(batch)
    assert list(df.columns) == ["a", "a", "a"] and df.iloc[0, 0] == 1 and df.iloc[0, 1] == "x"
    assert df.iloc[0, 2] is pd_na()


def pd_na():
    import pandas as pd

    return pd.NA


@pytest.mark.parametrize("fmt", ["table", "csv", "json"])
def test_sql_answers_duplicate_column_names_in_every_format(capsys, fmt):
    import pandas as pd

    from tyrelab.cli import _print_result

    frame = pd.DataFrame([[1, "x", 2]], columns=["a", "a", "a_2"])
    _print_result(fmt, ["a", "a", "a_2"], [frame], True, 10**6)
    out, err = capsys.readouterr()
    if fmt == "json":
        assert json.loads(out) == [{"a": 1, "a_3": "x", "a_2": 2}] and len(lines(err)) == 1 and "a_3" in err
    else:
        assert out.count("a") >= 3 and "x" in out and err == ""


def test_unique_keys_never_take_a_name_in_use():
    from tyrelab.cli import unique_keys

    assert unique_keys(["a", "a", "a"]) == ["a", "a_2", "a_3"]
    assert unique_keys(["a", "a_2", "a", "a"]) == ["a", "a_2", "a_3", "a_4"]
    assert unique_keys([1, 1]) == ["1", "1_2"]


@pytest.mark.parametrize("fmt", ["table", "json"])
def test_road_escapes_control_characters_of_a_file_name(tmp_path, capsys, fmt):
    p = tmp_path / "evil\x1b[31m\u2028.csv"
    p.write_text("distance_m,height_m\n" + "".join(f"{i},{0.001 * (i % 3)}\n" for i in range(40)))
    assert main(["road", str(p), "--format", fmt]) == 0
    out, err = capsys.readouterr()
    assert "\x1b" not in out and "\u2028" not in out and err == ""
    bad = tmp_path / "bad\x1b[2J.csv"
    bad.write_text("x\n1\n")
    assert main(["road", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "\x1b" not in err and len(lines(err)) == 1 and "\\x1b" in err


@pytest.mark.parametrize("verb", [["estimate-stiffness", "--size", "evil\x1b[2J", "--pressure", "1.2"],
                                  ["export-tyre", "T\x1b]0;x\x07", "--build", "nowhere\x1b[2J"],
                                  ["sql", "SELECT '\x1b[2J' FROM nowhere", "--build", "nowhere\x1b"]])
def test_error_lines_of_every_verb_are_escaped(tmp_path, monkeypatch, capsys, verb):
    monkeypatch.chdir(tmp_path)
    assert main(verb) == 2
    err = capsys.readouterr().err
    assert "\x1b" not in err and "\x07" not in err and len(lines(err)) == 1


def test_an_executor_that_is_not_used_is_said(capsys):
    rc = main(["ride", str(MODERN), "--speeds", "8", "--executor", "dask", "--scheduler", "tcp://127.0.0.1:1",
               "--format", "table"])
    err = capsys.readouterr().err
    assert rc == 0 and "--executor dask --scheduler tcp://127.0.0.1:1 was not used" in err and len(lines(err)) == 1


def test_no_note_when_nothing_was_asked_of_an_executor(capsys):
    assert main(["ride", str(MODERN), "--speeds", "8", "--format", "table"]) == 0
    assert "not used" not in capsys.readouterr().err


def test_library_warnings_are_said_once_in_our_words(caplog):
    import logging
    import warnings

    from tyrelab.progress import in_our_words, say_library_warnings_once

    with warnings.catch_warnings():
        warnings.simplefilter("always")
        previous = say_library_warnings_once(logging.getLogger("tyrelab.round5"))
        try:
            with caplog.at_level(logging.WARNING, logger="tyrelab.round5"):
                for _ in range(3):
                    np.nanmax(np.array([np.nan]))
                    np.var(np.array([1.0]), ddof=1)
        finally:
            warnings.showwarning = previous
    said = [r.getMessage() for r in caplog.records if r.name == "tyrelab.round5"]
    assert len(said) == 3  # All-NaN slice, Degrees of freedom <= 0, its invalid divide: each once
    assert any("all missing (NaN)" in s for s in said) and any("fewer than two values" in s for s in said)
    assert in_our_words("something else\nentirely").startswith("a library warned: something else entirely")


def test_the_command_line_shows_no_library_warning(capsys, monkeypatch):
    import warnings

    import argcomplete

    def noisy(*args, **kwargs):
        with warnings.catch_warnings():
            warnings.simplefilter("always")
            for _ in range(2):
                np.nanmean(np.array([np.nan]))
        return ""

    monkeypatch.setattr(argcomplete, "shellcode", noisy)
    assert main(["completion", "bash"]) == 0
    err = capsys.readouterr().err
    assert "RuntimeWarning" not in err and err.count("mean of no values") == 1


# ----------------------------------------------------------------------------- relative paths, a moved build
def _path_columns(ctx):
    import pandas as pd

    out = {}
    for name in ("manifest", "results", "quarantine"):
        if ctx.table(name).exists() or name == "quarantine":
            df = ctx.read_table(name)
            for col in ("campaign", "run_path", "file"):
                if col in df:
                    out[f"{name}.{col}"] = [v for v in df[col].dropna().astype(str)]
    for part in sorted(ctx.parquet.glob("**/*.parquet")):
        if "runs" in part.parts:
            continue
        df = pd.read_parquet(part)
        for col in df.columns:
            if df[col].dtype == object:
                out[f"{part.name}.{col}"] = [v for v in df[col].dropna() if isinstance(v, str)]
    return out


def test_no_table_holds_an_absolute_path_and_a_moved_raw_and_build_reuse_everything(tmp_path, caplog):
    import logging
    import shutil

    from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
    from tyrelab.stages import Context, run_pipeline

    stages = ["ingest", "analyse", "calibrate", "warehouse"]
    raw = tmp_path / "first" / "raw"
    write_campaign(raw / "c", [(manifest_row(f"r{i}", f"r{i}.parquet", pressure_bar=1.0 + 0.1 * i),
                                spring_damper_recording(duration_s=12.0, seed=i)) for i in range(3)]
                   + [(manifest_row("bad", "bad.parquet"), b"not a parquet file")])
    ctx = Context(raw=raw, build=tmp_path / "first" / "build", jobs=1)
    run_pipeline(ctx, stages)
    columns = _path_columns(ctx)
    assert columns["manifest.campaign"] == ["c"] * 3
    assert all(p.startswith("parquet/runs/") for p in columns["manifest.run_path"])
    assert columns["quarantine.file"] == ["c/bad.parquet"] and columns["quarantine.campaign"] == ["c"]
    for key, values in columns.items():
        assert not any(v.startswith(("/", str(tmp_path))) or str(tmp_path) in v for v in values), key

    shutil.move(str(tmp_path / "first"), str(tmp_path / "moved"))
    moved = Context(raw=tmp_path / "moved" / "raw", build=tmp_path / "moved" / "build", jobs=1,
                    calibration_correct=True)
    caplog.clear()
    with caplog.at_level(logging.INFO, logger="tyrelab"):
        results = {r.name: r for r in run_pipeline(moved, stages)}
    assert results["ingest"].skipped or "0 converted, 3 unchanged" in results["ingest"].message
    assert results["analyse"].skipped or "3 reused, 0 analysed" in results["analyse"].message
    assert _path_columns(moved) == columns  # the same tables, wherever the folders are


def test_context_paths_relative_and_back(tmp_path):
    from tyrelab.stages import Context

    ctx = Context(raw=tmp_path / "raw", build=tmp_path / "b")
    assert ctx.raw_relative(tmp_path / "raw" / "c" / "x.csv") == "c/x.csv"
    assert ctx.raw_relative(tmp_path / "raw") == "."
    assert ctx.raw_relative(tmp_path / "elsewhere" / "x.csv") == "x.csv"  # never a path of this machine
    assert ctx.build_relative(tmp_path / "b" / "parquet" / "runs" / "r.parquet") == "parquet/runs/r.parquet"
    assert ctx.build_file("parquet/runs/r.parquet") == tmp_path / "b" / "parquet" / "runs" / "r.parquet"
    old = "/gone/build/parquet/runs/tyre_id=T1/r.parquet"  # an older table's absolute path of a moved build
    assert ctx.build_file(old) == tmp_path / "b" / "parquet" / "runs" / "tyre_id=T1" / "r.parquet"
    assert ctx.raw_file("c", "r.csv") == tmp_path / "raw" / "c" / "r.csv"
    assert ctx.raw_file(".", "r.csv") == tmp_path / "raw" / "r.csv"


# ----------------------------------------------------------------------------- bounded from the content
def _crg(folder, records=2000, fmt="KRBI"):
    import pyopencrg

    v = np.array([-1.0, 0.0, 1.0])
    pyopencrg.CrgRoad(np.random.default_rng(1).normal(0, 0.01, (records, v.size)), u_inc=0.1, v=v).save(
        folder / "data.crg", fmt=fmt)
    (folder / "ref.crg").write_text("$ROAD_CRG_FILE\ndata.crg\n$\n")
    return folder / "data.crg", folder / "ref.crg"


def test_a_crg_referencing_a_large_data_file_is_refused_at_header_cost(tmp_path, monkeypatch):
    from tyrelab import scenario_io

    data, ref = _crg(tmp_path)
    assert scenario_io.read_crg(ref).u_inc_m == pytest.approx(0.1)  # a reference within the bounds is read
    monkeypatch.setattr(scenario_io, "MAX_CRG_BYTES", data.stat().st_size - 1)
    calls = []
    monkeypatch.setattr("pyopencrg.open", lambda *a, **k: calls.append(a))  # the data are never opened
    with pytest.raises(ValueError, match=r"ref\.crg: its data file data\.crg \(\$ROAD_CRG_FILE\) has \d+ bytes"):
        scenario_io.read_crg(ref)
    assert not calls


@pytest.mark.parametrize("fmt", ["KRBI", "KDBI", "LDFI"])
def test_a_crg_with_more_heights_than_the_bound_is_refused_before_reading(tmp_path, monkeypatch, fmt):
    import tyrelab.vehicle.crg as crg
    from tyrelab import scenario_io

    data, ref = _crg(tmp_path, records=1000, fmt=fmt)
    monkeypatch.setattr(crg, "MAX_GRID_VALUES", 2000)  # 1000 cross sections x 3 heights
    for path in (data, ref):
        with pytest.raises(ValueError, match="heights, above the 2000 a CRG road may have"):
            scenario_io.read_crg(path)


def test_a_sparse_crg_is_refused_before_its_holes_are_read(tmp_path):
    import resource

    from tyrelab import scenario_io

    data, _ = _crg(tmp_path, records=10)
    sparse = tmp_path / "sparse.crg"
    header = data.read_bytes()[: len(data.read_bytes()) - 10 * 3 * 4]
    with open(sparse, "wb") as f:
        f.write(header)
        f.truncate(190_000_000)  # holes: 190 MB on paper, nothing on disk
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    with pytest.raises(ValueError, match="holds about 47499"):
        scenario_io.read_crg(sparse)
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before < 100_000  # kB: nothing of it was read


def test_tyrelab_road_bounds_the_grid_of_a_profile_before_building_it(tmp_path, capsys):
    x = np.concatenate([np.arange(6000) * 0.001, 6.0 + np.arange(1, 3000) * 9.99])  # median step 1 mm over 30 km
    p = tmp_path / "long.csv"
    p.write_text("distance_m,height_m\n" + "".join(f"{v:.3f},0.001\n" for v in x))
    assert main(["road", str(p)]) == 2
    err = capsys.readouterr().err
    assert len(lines(err)) == 1 and "makes 29,966,011 points, more than the 10,000,000" in err


# ----------------------------------------------------------------------------- confined and tracked
def _crg_campaign(tmp_path, reference="data.crg", data_at=None):
    """raw/scenarios/s.toml on ``ref.crg``, whose $ROAD_CRG_FILE names ``reference`` (a 3-D tractor);
    the data file written at ``data_at`` (default: beside it)."""
    import pyopencrg

    from tests.vehicle.test_ride_3d import text as text_3d

    folder = tmp_path / "raw" / "scenarios"
    folder.mkdir(parents=True)
    v = np.round(np.arange(-1.5, 1.5001, 0.1), 10)
    z = np.random.default_rng(3).normal(0, 0.005, (1200, v.size))
    where = data_at or folder / "data.crg"
    where.parent.mkdir(parents=True, exist_ok=True)
    pyopencrg.CrgRoad(z, u_inc=0.05, v=v).save(where, fmt="KDBI")
    (folder / "ref.crg").write_text(f"$ROAD_CRG_FILE\n{reference}\n$\n")
    path = folder / "s.toml"
    path.write_text(text_3d('kind = "crg"\nfile = "ref.crg"\nlength_m = 50'))
    return path, where


def test_a_campaign_crg_reads_a_data_file_inside_its_folder(tmp_path):
    from tyrelab.scenario_io import load_scenario

    path, _ = _crg_campaign(tmp_path)
    assert load_scenario(path).surface.crg_data is not None


@pytest.mark.parametrize("how", ["outside", "symlink", "environment"])
def test_a_campaign_crg_referencing_a_file_outside_its_folder_is_refused(tmp_path, monkeypatch, how):
    from tyrelab.scenario_io import load_scenario

    outside = tmp_path / "elsewhere" / "data.crg"
    if how == "outside":
        path, _ = _crg_campaign(tmp_path, reference="../../elsewhere/data.crg", data_at=outside)
    elif how == "symlink":
        path, _ = _crg_campaign(tmp_path, reference="link.crg", data_at=outside)
        (path.parent / "link.crg").symlink_to(outside)
    else:
        monkeypatch.setenv("I46_UP", "../../elsewhere")  # pyopencrg expands variables in the reference
        path, _ = _crg_campaign(tmp_path, reference="./$I46_UP/data.crg", data_at=outside)
    with pytest.raises(ScenarioError) as info:
        load_scenario(path)
    assert any("outside the campaign's folder" in p for p in info.value.problems), info.value.problems
    assert load_scenario(path, confine=False).surface.crg_data is not None  # tyrelab ride on the user's own file


def test_editing_a_crg_data_file_changes_its_scenarios_cache_key(tmp_path, monkeypatch):
    from tyrelab.itemcache import ItemCache
    from tyrelab.scenario_io import crg_files

    path, data = _crg_campaign(tmp_path)
    assert [p.name for p in crg_files(path.parent / "ref.crg")] == ["ref.crg", "data.crg"]
    monkeypatch.setattr(ride_stage, "read_fit_tables", lambda ctx: {})
    monkeypatch.setattr(ride_stage, "scenario_fits", lambda sc, tables: {})

    class Ctx:
        parquet = tmp_path / "parquet"
        build = tmp_path / "build"

    def key():
        return ride_stage._ride_plan(Ctx(), [(str(path), "raw")], ItemCache(Ctx(), "simulate", "round5"))[0][0]

    before = key()
    assert key() == before
    raw = bytearray(data.read_bytes())
    raw[-8:] = np.float64(0.25).tobytes()[::-1] if raw[-8:] != np.float64(0.25).tobytes()[::-1] else bytes(8)
    data.write_bytes(bytes(raw))
    assert key() != before
