"""Stage simulate: writes the chapter 6-8 tables, side by side with the thesis.

The stage's output is the one of the shared build of every stage (``full_report`` in
tests/conftest.py: its raw folder has no published/, so the tables shipped with tyrelab
are read), so the ~1 min of simulations runs once per test session.
"""

import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from tests.comparisons import assert_differences_are_ours_minus_thesis

from tyrelab import published
from tyrelab.stages import simulate
from tyrelab.stages.base import Context
from tyrelab.vehicle import metrics, profiles


@pytest.fixture(scope="module")
def ctx(full_report):
    return full_report


def test_tables_written(ctx):
    for name in ("carriage_runs", "table_xiii", "table_xiv", "tractor_runs", "table_xvii", "table_xviii",
                 "table_xx", "table_xx_statistics", "iso2631", "profile_spectra", "simulate_inputs"):
        assert ctx.has_table(name), name
    inputs = ctx.read_table("simulate_inputs")
    assert list(inputs["table"]) == list(simulate.STEMS)
    assert list(inputs["source"]) == [f"shipped/{s}.csv" for s in simulate.STEMS]  # no path of this machine


def test_reads_published_of_the_raw_folder(tmp_path):
    shutil.copytree(published.SHIPPED_DIR, tmp_path / "published")
    xii = (tmp_path / "published" / "table_xii.csv").read_text().replace("stationary,T4,light,,,1860,3.42,545",
                                                                         "stationary,T4,light,,,1860,3.42,555")
    (tmp_path / "published" / "table_xii.csv").write_text(xii)
    tables, inputs = simulate._read(Context(raw=tmp_path, build=tmp_path / "build"))
    assert set(inputs["source"]) == {f"published/{s}.csv" for s in simulate.STEMS}  # relative to the raw folder
    st = tables["table_xii"].set_index(["characteristics", "load_condition"])
    assert st.loc[("stationary", "light"), "stiffness_kN_per_m"] == 555


def test_side_by_side_keeps_unprinted_rows(ctx):
    t = ctx.read_table("table_xvii")
    assert len(t) == 32 and t[["ours_rolling", "ours_stationary"]].notna().all().all()
    hh = t[(t["track"] == "HH") & (t["quantity"] == "vertical_rms")]
    assert list(hh["statistic"]) == ["mean_ratio_error", "sd_ratio_error", "p_within_10", "p_within_30"]
    assert hh["thesis_rolling"].iloc[0] == 2.08 and hh["thesis_rolling"].iloc[2:].isna().all()
    x = ctx.read_table("table_xviii").set_index("row")
    assert x.loc["measured (ours: recording, load condition 1, SBT, 10 km/h)", "vertical_rms_m_s2_thesis"] == 1.79


def test_table_xiii_rolling_beats_stationary(ctx):
    t = ctx.read_table("table_xiii").set_index(["quantity", "statistic"])
    assert list(t.columns) == ["thesis_rolling", "ours_rolling", "difference_rolling",
                               "thesis_stationary", "ours_stationary", "difference_stationary"]
    for q in ("peak_frequency", "half_power_width_over_frequency"):
        r, s = t.loc[(q, "mean_ratio_error")], t.loc[(q, "mean_ratio_error")]
        assert abs(r["ours_rolling"] - 1) < abs(s["ours_stationary"] - 1)
        assert t.loc[(q, "p_within_10"), "ours_rolling"] > t.loc[(q, "p_within_10"), "ours_stationary"]
    assert t.loc[("peak_frequency", "mean_ratio_error"), "ours_rolling"] == pytest.approx(1.0, abs=0.02)


def test_carriage_runs_exclude_low_speeds_in_statistics(ctx):
    """Every speed is simulated, but Tables XIII/XIV are over 10-17.5 km/h only (thesis §6.4)."""
    runs = ctx.read_table("carriage_runs")
    assert set(runs["speed_km_h"]) == {5.0, 7.5, 10.0, 12.5, 15.0, 17.5}
    assert set(runs["characteristics"]) == {"reference", "rolling", "stationary"}
    comps = ctx.read_table("carriage_comparisons")
    for table, estimate in (("table_xiii", "surveyed"), ("table_xiv", "recorded")):
        t = ctx.read_table(table).set_index(["quantity", "statistic"])
        of = comps[comps["profile_estimate"] == estimate]
        kept = metrics.accuracy_table(of[of["speed_km_h"] >= 10.0], by="characteristics").set_index(["quantity", "statistic"])
        every = metrics.accuracy_table(of, by="characteristics").set_index(["quantity", "statistic"])
        for name in ("rolling", "stationary"):
            np.testing.assert_allclose(t[f"ours_{name}"], kept.loc[t.index, name], rtol=1e-12, err_msg=table)
            assert not np.allclose(t[f"ours_{name}"], every.loc[t.index, name], rtol=1e-6), \
                f"{table}: the low speeds make no difference, the test cannot tell"


def test_table_xx_side_by_side(ctx):
    t = ctx.read_table("table_xx")
    f = t[t["stiffness_source"] == "formula"]
    assert np.all(np.abs(f["frequency_1_from_thesis_stiffness_Hz"] - f["thesis_frequency_1_Hz"]) < 0.0135)
    s = ctx.read_table("table_xx_statistics").set_index(["stiffness_source", "basis"])
    assert s.loc[("formula", "thesis"), "mean"] == pytest.approx(1.00, abs=0.01)


def test_iso_every_run(ctx):
    iso = ctx.read_table("iso2631")
    n = len(ctx.read_table("carriage_runs")) + len(ctx.read_table("tractor_runs"))
    assert len(iso) == n and iso["iso_a8_m_s2"].notna().all()


def test_slatted_track_of_the_stage_is_the_seeded_stand_in(ctx):
    """The stage's slat-top spectrum: the seeded stand-in's, and at the level of its spectrum law.

    The track is a Gaussian process with spectrum G0 (n/n0)^-2 sampled at the slats;
    its Welch estimate (12.8 m segments over 100 m, ~14 averages) scatters by ~0.27 in
    log per bin, so the geometric mean of 17 bins over 0.2-1.5 cycles/m is within
    ~0.07 of the law (the slat-top interpolation lowers it slightly): allowed 0.8-1.25.
    """
    sp = ctx.read_table("profile_spectra")
    tops = sp[sp["profile"] == "slat_tops_left"]
    assert tops["track"].iloc[0].startswith("ISO/TR 5007 slatted track, seeded stand-in")
    track = profiles.slatted_track(seed=simulate.SEED)
    n, g = profiles.profile_spectrum(track.left_m, track.dx_m, 12.8)
    np.testing.assert_allclose(tops["psd_m3"], g, rtol=1e-9)
    np.testing.assert_allclose(tops["n_cycles_per_m"], n)
    band = tops[(tops["n_cycles_per_m"] >= 0.2) & (tops["n_cycles_per_m"] <= 1.5)]
    law = profiles.SLATTED_TRACK_G0_M3 * (band["n_cycles_per_m"] / 0.1) ** -2
    assert 0.8 < np.exp(np.mean(np.log(band["psd_m3"] / law))) < 1.25


def test_comparison_tables_give_ours_minus_thesis(ctx):
    for name in ("table_xiii", "table_xiv", "table_xvii", "table_xx"):
        assert assert_differences_are_ours_minus_thesis(ctx.read_table(name), name) > 0, name


def test_carriage_runs_keep_the_quoted_table_xii_stiffness(ctx):
    runs = ctx.read_table("carriage_runs")
    rolling = runs[(runs["characteristics"] == "rolling") & (runs["speed_km_h"] == 10.0) & (runs["load_condition"] == "heavy")]
    assert set(rolling["quoted_stiffness_kN_per_m"]) == {324.0}  # Table XII, before the 10 % surface reduction
    assert rolling["stiffness_kN_per_m"].iloc[0] == pytest.approx(0.9 * 324.0)


def test_fig56_spectra_written(ctx):
    sp = ctx.read_table("carriage_spectra")
    assert {"reference (true)", "rolling (surveyed)", "stationary (surveyed)"} <= set(sp["series"])
    ref = sp[sp["series"] == "reference (true)"]
    assert ref["frequency_Hz"].max() <= 10.0 and (ref["psd_m2_s4_per_Hz"] >= 0).all()


def test_ride_tables_hold_every_shipped_scenario(ctx):
    from tyrelab.resources import scenarios_dir

    scen = ctx.read_table("ride_scenarios")
    assert sorted(scen["file"]) == sorted(p.name for p in scenarios_dir().glob("*.toml"))  # no machine's path
    res = ctx.read_table("ride_results")
    assert set(res["scenario"]) == set(scen["scenario"])
    assert (res["name"] == res["scenario"]).all()  # the README queries ride_results.name (issue 37)
    assert not any(Path(f).is_absolute() for f in res["file"])
    assert {"a_wz_m_s2", "a_wx_m_s2", "a8_m_s2", "hours_to_elv", "verdict", "expected_a_wz_m_s2"} <= set(res.columns)
    # the report's Ride page: every scenario's seat PSD and transmissibility per axis, of its own pressures
    for name, cols in (("ride_spectra", ("seat_vertical_psd_m2_s4_per_Hz", "seat_longitudinal_psd_m2_s4_per_Hz")),
                       ("ride_transmissibility", ("seat_vertical", "seat_longitudinal_per_m"))):
        t = ctx.read_table(name)
        assert set(t["file"]) == set(scen["file"]) and set(cols) <= set(t.columns), name
        assert (t.groupby("file")[cols[0]].max() > 0).all(), name
        own = scen.set_index("file")[["front_pressure_bar", "rear_pressure_bar"]]
        shown = t.groupby("file")[["front_pressure_bar", "rear_pressure_bar"]].first()
        assert shown.sort_index().equals(own.sort_index()), name


def test_mf698t_scenario_reproduces_the_chapter_7_runs(ctx):
    """The shipped MF698T scenario is the ch. 7 study's rolling HH runs of load condition 1: the same numbers
    but for gravity: the scenario runs on the standard 9.80665 m/s², the study on the thesis' 9.81 (its
    printed tables), which moves the lift-off floors by 0.035 % and a_w, VDV, A(8) by at most 3.6e-4
    (issue 45; the same runs to 1e-9 under one gravity: tests/vehicle/test_spectral_ride.py's rows)."""
    res = ctx.read_table("ride_results")
    mf = res[res["scenario"].str.startswith("MF698T")].set_index("speed_km_h").sort_index()
    runs = ctx.read_table("tractor_runs")
    st = runs[(runs["characteristics"] == "rolling") & (runs["track"] == "HH") & (runs["load_condition"] == 1)
              & ~runs["sweep"].astype(bool)].set_index("speed_km_h").sort_index()
    assert list(mf.index) == list(st.index) == [10.0, 12.5, 15.0, 17.5, 20.0]
    gravity = 5e-4  # the two gravities' effect (above); a different run would be percents apart
    np.testing.assert_allclose(mf["a_wz_m_s2"], st["iso_vertical_weighted_rms_m_s2"], rtol=gravity)
    np.testing.assert_allclose(mf["vdv_m_s1_75"], st["iso_vertical_vdv_m_s1_75"], rtol=gravity)
    np.testing.assert_allclose(mf["crest_factor"], st["iso_vertical_crest_factor"], rtol=gravity)
    np.testing.assert_allclose(mf["a8_m_s2"], st["iso_a8_m_s2"], rtol=gravity)
    np.testing.assert_allclose(mf["rear_stiffness_kN_per_m"], st["rear_stiffness_kN_per_m"])
    # lift-off in the same runs (the study counts over its fixed 31.8 s, the ride over the record)
    assert ((mf["lift_off_fraction_front"] > 0) == (st["lift_off_fraction_front"] > 0)).all()


def test_tractor_runs_record_their_solution_path(ctx):
    """Runs that lift a tyre were switched (exact in contact, RK4 across lift-off); the others exact."""
    runs = ctx.read_table("tractor_runs")
    assert set(runs.loc[runs["source"] == "recording", "method_used"]) == {"recording"}
    runs = runs[runs["source"] == "prediction"]
    lifted = (runs["lift_off_fraction_front"] > 0) | (runs["lift_off_fraction_rear"] > 0)
    assert set(runs.loc[lifted, "method_used"]) == {"exact+rk4"}
    assert set(runs.loc[~lifted, "method_used"]) <= {"exact", "exact+rk4"}
    assert (runs["method_used"] == "exact").any() and lifted.any()


@pytest.mark.slow  # 70 s on 2 busy cores; runs in `make test-all`, not in the default run
def test_studies_started_ahead_give_the_tables_of_the_stage_alone(ctx, tmp_path):
    """``run_pipeline`` starts the chapter 6-7 studies ahead on a first build; the stage takes
    their results: the same bytes as the shared build, which ran them itself (``--jobs 1``)."""
    import logging

    ahead = Context(raw=ctx.raw, build=tmp_path / "build", jobs=2, log=logging.getLogger("tyrelab.test"))
    # the tractor's predictions only: the carriage's cases compare with recordings the rides stage writes
    assert simulate.start_studies_ahead(ahead) == ["tractor"]
    assert simulate.start_studies_ahead(ahead) == []  # once
    for table in ("stiffness_pressure_by_speed", "damping_pressure_by_speed", "recordings"):  # the stage's inputs
        if ctx.has_table(table):
            ahead.parquet.mkdir(parents=True, exist_ok=True)
            shutil.copy(ctx.table(table), ahead.table(table))
    result = simulate.run(ahead)
    assert "studies 0 reused, 2 computed" in result.message and not simulate._AHEAD
    assert "carriage cases 0 reused, 12 computed" in result.message  # the cases computed ahead, stored by the stage
    assert "tractor cases 0 reused, 28 computed" in result.message
    for name in ("carriage_runs", "table_xiii", "table_xiv", "tractor_runs", "table_xvii", "table_xviii", "table_xx"):
        # the same task on the same inputs; the shared build ran it in another process (under
        # pytest-xdist, after other tests), where a last bit may round otherwise (docs/benchmarks.md)
        pd.testing.assert_frame_equal(ahead.read_table(name), ctx.read_table(name), check_exact=False, rtol=1e-12,
                                      atol=0, obj=name)


def test_studies_no_stage_took_are_ended(ctx, tmp_path):
    ahead = Context(raw=ctx.raw, build=tmp_path / "build", jobs=2)
    assert simulate.start_studies_ahead(ahead)
    pools = {id(p): p for p, _ in simulate._AHEAD.values()}.values()
    workers = [w for p in pools for w in (p._processes or {}).values()]
    simulate.abandon_studies_ahead()
    assert not simulate._AHEAD and workers and not any(w.is_alive() for w in workers)


def _edit_first_row(path, column, factor):
    """Multiply ``column`` of the first row of a published CSV by ``factor``; return that row."""
    from tests.synthetic import edit_csv

    first = edit_csv(path, lambda rows: rows[0].update({column: f"{float(rows[0][column]) * factor:.3f}"}))[0]
    assert first["characteristics"] == "rolling"
    return first


def test_edited_rows_resimulate_their_cases_only(ctx, tmp_path):
    """The shared build's simulate cache, a raw folder whose Table XII has one rolling row's damping
    changed and whose Table XVI has one rolling row's rear damping changed: the stage reuses the
    other carriage and tractor cases, simulates those two (and one whose cache entry is torn), and
    the runs tables change in the edited cases' rows only."""
    import logging

    raw, build = tmp_path / "raw", tmp_path / "build"
    shutil.copytree(published.published_dir(), raw / "published")
    if (ctx.raw / "scenarios").is_dir():
        shutil.copytree(ctx.raw / "scenarios", raw / "scenarios")
    shutil.copytree(ctx.build / "cache" / "simulate", build / "cache" / "simulate")
    for folder in ctx.raw.iterdir():  # the recordings' campaigns: the warehouse names them relative to the raw folder
        if folder.is_dir() and not (raw / folder.name).exists():
            (raw / folder.name).symlink_to(folder)
    edited = Context(raw=raw, build=build, jobs=1, log=logging.getLogger("tyrelab.test"))
    for table in ("stiffness_pressure_by_speed", "damping_pressure_by_speed", "recordings"):  # the stage's inputs
        if ctx.has_table(table):
            edited.parquet.mkdir(parents=True, exist_ok=True)
            shutil.copy(ctx.table(table), edited.table(table))
    xii = _edit_first_row(raw / "published" / "table_xii.csv", "damping_kN_s_per_m", 1.5)
    xvi = _edit_first_row(raw / "published" / "table_xvi.csv", "rear_damping_kN_s_per_m", 1.5)

    # and one cached case unreadable (a torn or foreign file): it is computed again and replaced
    case_keys = simulate._study_plan(simulate._read(edited)[0], simulate.ItemCache(edited, "simulate"),
                                     raw / "published", simulate.read_study_recordings(edited)[0])[2]
    torn = build / "cache" / "simulate" / f"{case_keys['carriage'][5]}.pkl"
    torn.write_bytes(torn.read_bytes()[:100])

    result = simulate.run(edited)
    assert "carriage cases 10 reused, 2 computed" in result.message, result.message
    assert "tractor cases 27 reused, 1 computed" in result.message, result.message
    cache = build / "cache" / "simulate"
    assert len(list(cache.glob("carriage-case-*.pkl"))) == 12 and len(list(cache.glob("tractor-case-*.pkl"))) == 28
    assert simulate.ItemCache(edited, "simulate").load(torn.stem)[0]  # replaced by a readable entry
    ours, theirs = edited.read_table("carriage_runs"), ctx.read_table("carriage_runs")
    case = (ours["speed_km_h"] == float(xii["nominal_speed_km_h"])) & (ours["load_condition"] == xii["load_condition"])
    row5 = simulate.layouts.carriage_rolling(simulate._read(edited)[0]["table_xii"]).iloc[5]
    again = (ours["speed_km_h"] == row5["speed_km_h"]) & (ours["load_condition"] == row5["load_condition"])
    assert case.sum() == again.sum() == 5 and not (case & again).any()
    other = ~case & ~again
    pd.testing.assert_frame_equal(ours[other], theirs[other], check_exact=True)  # the other cases: from the cache
    # the torn case, simulated again in this process (the shared build's may come from another, where
    # a last bit can round otherwise: docs/benchmarks.md)
    pd.testing.assert_frame_equal(ours[again], theirs[again], check_exact=False, rtol=1e-12, atol=0)
    rolling = case & (ours["characteristics"].isin(["reference", "rolling"]))
    assert (ours.loc[rolling, "damping_kN_s_per_m"] != theirs.loc[rolling, "damping_kN_s_per_m"]).all()
    ours, theirs = edited.read_table("tractor_runs"), ctx.read_table("tractor_runs")
    case = ((ours["load_condition"] == int(xvi["load_condition"])) & (ours["track"] == xvi["track"])
            & (ours["speed_km_h"] == float(xvi["speed_km_h"])))
    assert case.sum() == 3 + 11  # rolling, stationary, recorded and the Table XVIII sweep (load 1, SBT, 10 km/h)
    pd.testing.assert_frame_equal(ours[~case], theirs[~case], check_exact=True)  # the other cases: from the cache
    rolling = case & (ours["characteristics"] != "stationary")
    assert (ours.loc[rolling, "rear_damping_kN_s_per_m"] != theirs.loc[rolling, "rear_damping_kN_s_per_m"]).all()


def test_tables_xiii_xiv_xvii_come_from_the_recordings(ctx, tmp_path, monkeypatch):
    """Issue 24: the "measured" side of Tables XIII, XIV and XVII is the campaign's recordings
    (rides.csv rows naming a study run). A campaign without them still builds: the thesis'
    columns stay, ours are gaps (no value), nothing is quarantined, and no run is "recorded"."""
    from tyrelab.stages import run_stage

    raw, build = tmp_path / "raw", tmp_path / "build"
    shutil.copytree(ctx.raw, raw)
    shutil.copytree(ctx.build, build)  # its item cache: the tractor's predictions are reused
    tables = ("table_xiii", "table_xiv", "table_xvii")
    before = {t: ctx.read_table(t) for t in tables}
    for t in tables:
        assert before[t][["ours_rolling", "ours_stationary"]].notna().all().all(), t
    assert (ctx.read_table("carriage_runs")["source"] == "recording").sum() == 12
    assert (ctx.read_table("tractor_runs")["source"] == "recording").sum() == 28
    (raw / "rides.csv").unlink()
    monkeypatch.setattr(simulate, "scenario_files", lambda raw: [])  # the ride scenarios are not the point here
    c = Context(raw=raw, build=build, jobs=1)
    run_stage("rides", c)
    result = run_stage("simulate", c)
    assert "recordings of the studies: 0 carriage, 0 tractor" in result.message
    for t in tables:
        after = c.read_table(t)
        assert after[["ours_rolling", "ours_stationary", "difference_rolling", "difference_stationary"]].isna().all().all(), t
        pd.testing.assert_frame_equal(after.filter(like="thesis_"), before[t].filter(like="thesis_"))
    measured = c.read_table("table_xviii").set_index("row").filter(like="_ours").iloc[-1]
    assert measured.isna().all()
    assert not (c.read_table("carriage_runs")["source"] == "recording").any()
    assert c.read_table("stages/quarantine_simulate").empty


def test_the_tractor_sweep_reads_table_xviii_of_the_raw_folder(tmp_path):
    """An edited <raw>/published/table_xviii.csv reaches the ch. 7 study (its inputs and the cache
    keys of the study and of the sweep's case), not the shipped copy."""
    shutil.copytree(published.SHIPPED_DIR, tmp_path / "published")
    path = tmp_path / "published" / "table_xviii.csv"
    table = pd.read_csv(path)
    table.loc[2, "longitudinal_damping_kN_s_per_m"] = 2.0
    table.to_csv(path, index=False)

    class Keys:  # the ItemCache's key, readable
        @staticmethod
        def key(*args):
            return repr(args)

    edited = {s: published.read_published(s, tmp_path) for s in simulate.STEMS}
    shipped = {s: published.read_published(s) for s in simulate.STEMS}
    keys, inputs, cases = simulate._study_plan(edited, Keys(), tmp_path / "published")
    keys0, _, cases0 = simulate._study_plan(shipped, Keys(), published.SHIPPED_DIR)
    assert inputs["tractor"][2] is edited["table_xviii"]
    assert keys["tractor"] != keys0["tractor"] and keys["carriage"] == keys0["carriage"]
    assert [a != b for a, b in zip(cases["tractor"], cases0["tractor"])] == [True] + [False] * (len(cases0["tractor"]) - 1)
