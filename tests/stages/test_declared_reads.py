"""Issue 35, Deliver 4: a stage reads only what it declares, and the ride scenarios read this run's fits.

- A stage that reads a table (or build path) it does not declare is refused while it runs, as an
  undeclared write is.
- A campaign scenario with ``measured_tyre_id`` runs on a fresh build (no warehouse yet: the
  ``warehouse`` stage runs after ``simulate``) from this run's Parquet fits, and its rows equal
  ``tyrelab ride --build`` on the finished build.
- ``formula = "build"`` reads ``formula_fit``/``damping_fit``: a change of them re-runs exactly
  the scenarios that use it.
"""

from __future__ import annotations

import json
import logging
import shutil

import pandas as pd
import pytest

from tyrelab.resources import scenarios_dir
from tests.scenarios import scenario_text, write

from tyrelab.stages import Context, run_stage, simulate
from tyrelab.stages.dag import may_read

log = logging.getLogger("tyrelab.test")


def test_a_stage_reading_an_undeclared_table_is_refused(tmp_path):
    ctx = Context(raw=tmp_path / "raw", build=tmp_path / "build", jobs=1)
    ctx.stage = "rides"
    assert ctx.table("formula_fit").name == "formula_fit.parquet"  # declared read
    assert not ctx.has_table("recordings")  # its own output
    with pytest.raises(RuntimeError, match="stage rides reads table 'results', which it does not declare"):
        ctx.read_table("results")
    with pytest.raises(RuntimeError, match="stage rides reads warehouse.duckdb, which it does not declare"):
        ctx.path("warehouse.duckdb")
    ctx.stage = "simulate"
    for name in ("stiffness_pressure_by_speed", "damping_pressure_by_speed", "formula_fit", "damping_fit"):
        assert may_read("simulate", f"parquet/{name}.parquet")  # what `formula = "build"` reads is declared
    with pytest.raises(RuntimeError, match="warehouse.duckdb"):  # the warehouse is written after it
        ctx.path("warehouse.duckdb")
    ctx.stage = None  # outside a stage (the CLI's own reads): no check
    assert not ctx.has_table("results")


def test_run_stage_refuses_a_stage_that_reads_an_undeclared_table(tmp_path, monkeypatch):
    from tyrelab.stages import methods

    def sneaky(ctx):
        ctx.read_table("tyres")  # the methods stage reads the published tables and results only (issue 34)

    monkeypatch.setattr(methods, "run", sneaky)
    ctx = Context(raw=tmp_path / "raw", build=tmp_path / "build", jobs=1, log=log)
    with pytest.raises(RuntimeError, match="stage methods reads table 'tyres', which it does not declare"):
        run_stage("methods", ctx)
    assert ctx.stage is None


BUILD_FORMULA = 'formula = "build"'  # the rear tyre's stiffness and damping from the build's own fits


def _own_fit(path) -> None:
    """Replace the ``ours`` row of a ``formula_fit``/``damping_fit`` table by its ``published`` row."""
    table = pd.read_parquet(path)
    source = table["source"].astype(str)
    ours = table.loc[source == "published"].assign(source="ours")
    pd.concat([table.loc[source != "ours"], ours], ignore_index=True).to_parquet(path)


@pytest.fixture(scope="module")
def fresh(full_report, tmp_path_factory):
    """The shared build (copied, its item cache too) with three campaign scenarios added and its
    warehouse removed (as on a first build, where simulate runs before the warehouse stage), and
    the simulate stage run on it."""
    tmp = tmp_path_factory.mktemp("declared_reads")
    raw, build = tmp / "raw", tmp / "build"
    shutil.copytree(full_report.raw, raw)
    shutil.copytree(full_report.build, build)
    (build / "warehouse.duckdb").unlink()
    (raw / "scenarios").mkdir(exist_ok=True)
    paths = {
        "measured": write(raw / "scenarios", scenario_text(rear='measured_tyre_id = "T1"', name="measured T1",
                                                           speeds="[5, 8]"), "measured.toml"),
        "build": write(raw / "scenarios", scenario_text(rear=BUILD_FORMULA, name="build formula"), "build.toml"),
        "thesis": write(raw / "scenarios", scenario_text(name="thesis formula"), "thesis.toml"),
    }
    for name in ("formula_fit", "damping_fit"):  # the tiny campaign has too few tyres for its own fits:
        _own_fit(build / "parquet" / f"{name}.parquet")  # the published fit stands in as "ours"
    ctx = Context(raw=raw, build=build, jobs=1, log=log)
    result = run_stage("simulate", ctx)
    return ctx, paths, result


def test_a_measured_tyre_scenario_reads_this_runs_fits_and_equals_tyrelab_ride(fresh, capsys):
    from tyrelab.cli import main

    ctx, paths, result = fresh
    shipped = len(list(scenarios_dir().glob("*.toml")))
    assert f"ride scenarios {shipped} reused, 3 computed" in result.message, result.message  # the shipped were cached
    assert ctx.read_table("stages/quarantine_simulate").empty
    rows = ctx.read_table("ride_results")
    ours = rows[rows["file"] == simulate.portable_path(str(paths["measured"]), ctx.raw)].reset_index(drop=True)
    assert len(ours) == 2 and ours["rear_stiffness_source"].str.contains("measured tyre T1").all()

    run_stage("warehouse", ctx)  # the finished build: `tyrelab ride --build` reads its warehouse
    assert main(["ride", str(paths["measured"]), "--build", str(ctx.build), "--format", "json", "--jobs", "1"]) == 0
    doc = json.loads(capsys.readouterr().out)
    cli = pd.DataFrame(doc["speeds"])
    compared = [c for c in ("a_wz_m_s2", "a_wx_m_s2", "a_v_m_s2", "vdv_m_s1_75") if c in ours and c in cli]
    assert compared
    for column in compared:  # the JSON prints 6 significant digits; the library call below is exact
        assert list(cli[column]) == pytest.approx(list(ours[column]), rel=1e-5, abs=1e-9), column
    from tyrelab.scenario_io import load_scenario
    from tyrelab.stages.tyredata import WarehouseTyres
    from tyrelab.vehicle import ride

    table = ride.results_table(ride.ride_sweep(load_scenario(paths["measured"]), tyre_data=WarehouseTyres(ctx.build),
                                               with_spectra=True), "measured T1")
    shared = [c for c in table.columns if c in ours.columns]
    pd.testing.assert_frame_equal(ours[shared], table[shared], check_exact=True)


def test_an_edited_build_formula_re_runs_exactly_the_scenarios_that_use_it(fresh):
    ctx, paths, _ = fresh
    before = ctx.read_table("ride_results")
    path = ctx.table("formula_fit")
    table = pd.read_parquet(path)
    ours = table["source"].astype(str) == "ours"
    table.loc[ours, "intercept"] = table.loc[ours, "intercept"] * 1.01
    table.to_parquet(path)  # a regress run whose formula fit changed (its inputs edited)

    result = run_stage("simulate", ctx)
    shipped = len(list(scenarios_dir().glob("*.toml")))
    assert f"ride scenarios {shipped + 2} reused, 1 computed" in result.message, result.message
    after = ctx.read_table("ride_results")
    file = simulate.portable_path(str(paths["build"]), ctx.raw)  # as the warehouse holds it: no machine's path
    mine = after["file"] == file
    assert mine.any()
    pd.testing.assert_frame_equal(after[~mine].reset_index(drop=True),
                                  before[before["file"] != file].reset_index(drop=True))


def test_new_fits_of_a_tyre_re_run_only_the_scenarios_naming_it(fresh):
    """Issue 35, Deliver 5: new per-speed fits of a tyre no scenario names (a run of it added) leave
    every item alone: simulate writes the tables it kept, reading no recording; new fits of T1
    re-run the one scenario that names it."""
    ctx, paths, _ = fresh
    run_stage("simulate", ctx)  # settle (the tests above may have left the stage to run)
    before = {name: ctx.read_table(name) for name in ("ride_results", "table_xx", "carriage_runs")}
    path = ctx.table("stiffness_pressure_by_speed")
    table = pd.read_parquet(path)
    other = table["tyre_id"].astype(str) != "T1"
    assert other.any()
    table.loc[other, "intercept"] += 5.0
    table.to_parquet(path)
    result = run_stage("simulate", ctx)
    assert not result.skipped and "no item's inputs changed: the tables of the last run" in result.message, \
        result.message
    for name, frame in before.items():
        pd.testing.assert_frame_equal(ctx.read_table(name), frame, check_exact=True)

    table.loc[~other, "intercept"] += 5.0
    table.to_parquet(path)
    result = run_stage("simulate", ctx)
    shipped = len(list(scenarios_dir().glob("*.toml")))
    assert f"ride scenarios {shipped + 2} reused, 1 computed" in result.message and "Table XX 1 reused, 0 computed" in \
        result.message, result.message
    after = ctx.read_table("ride_results")
    mine = after["file"] == simulate.portable_path(str(paths["measured"]), ctx.raw)
    pd.testing.assert_frame_equal(after[~mine].reset_index(drop=True),
                                  before["ride_results"][~mine].reset_index(drop=True))
    assert (after.loc[mine, "rear_stiffness_kN_per_m"].to_numpy()
            != before["ride_results"].loc[mine, "rear_stiffness_kN_per_m"].to_numpy()).all()


def test_explain_lists_the_items_of_a_stage_that_runs(tmp_path):
    from tyrelab.stages import explain

    text = explain(Context(raw=tmp_path / "raw", build=tmp_path / "build", jobs=1))
    rides = text.split("\nrides ", 1)[1].split("\nsimulate ", 1)[0]
    assert "item validation <- its recording's analysis, its scenario, the fit rows of its tyres" in rides
    simulate_part = text.split("\nsimulate ", 1)[1].split("\nwarehouse ", 1)[0]
    # nothing built yet; on the inputs as they are now, before the stages it reads from run
    shipped = len(list(scenarios_dir().glob("*.toml")))
    assert f"now, before ingest, analyse, calibrate, regress, rides run: ride scenarios: 0 kept, {shipped} to run; " \
        "Table XX: to run" in simulate_part, simulate_part


def test_a_scenarios_profile_csv_is_in_its_key(tmp_path):
    """A raw scenario's surface profile is read with it: an edited profile CSV (the scenario's
    text unchanged) gives the scenario another key, so it is run again."""
    import numpy as np

    from tyrelab.stages.state import ItemCache

    folder = tmp_path / "raw" / "scenarios"
    folder.mkdir(parents=True)
    x = np.arange(0, 200.0, 0.05)
    profile = pd.DataFrame({"distance_m": x, "height_m": 0.004 * np.sin(2 * np.pi * x / 2.5)})
    profile.to_csv(folder / "sine.csv", index=False)
    path = write(folder, scenario_text('kind = "profile"\nprofile = "sine.csv"'), "p.toml")
    ctx = Context(raw=tmp_path / "raw", build=tmp_path / "build", jobs=1)
    keys = simulate._ride_plan(ctx, [(str(path), "raw")], ItemCache(ctx, "simulate"))[0]
    profile.assign(height_m=2 * profile["height_m"]).to_csv(folder / "sine.csv", index=False)
    again = simulate._ride_plan(ctx, [(str(path), "raw")], ItemCache(ctx, "simulate"))[0]
    assert keys != again
