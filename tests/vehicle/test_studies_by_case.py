"""Chapter 6 and 7 studies case by case: cases computed before give the same bytes as a full run,
and a case's inputs are what it reads."""

import numpy as np
import pandas as pd
import pytest

from tyrelab.published import read_published
from tyrelab.vehicle import published_layouts as layouts
from tyrelab.vehicle import studies
from tyrelab.vehicle import study_recordings as sr

TABLES = ("runs", "comparisons", "table_xiii", "table_xiv", "spectra", "acceleration_spectra")
TRACTOR_TABLES = ("runs", "table_xvii", "table_xviii", "reference_xviii", "spectra")


def _changed(before: list[dict], after: list[dict]) -> list[bool]:
    """Which cases' inputs differ (by repr, as the cache key digests them: NaN equals NaN)."""
    assert len(before) == len(after)
    return [repr(a) != repr(b) for a, b in zip(before, after)]


@pytest.fixture(scope="module")
def tables():
    xii = read_published("table_xii")
    rolling = layouts.carriage_rolling(xii)
    # the four rows of 12.5 and 17.5 km/h (12.5 km/h heavy gives the example records): a quick study
    return rolling[rolling["speed_km_h"].isin([12.5, 17.5])].reset_index(drop=True), layouts.carriage_stationary(xii)


@pytest.fixture(scope="module")
def recordings(tables):
    return sr.carriage_recordings(*tables)


@pytest.fixture(scope="module")
def full(tables, recordings):
    return studies.carriage_study(*tables, recordings=recordings)


def test_cached_cases_give_the_full_study_to_the_bit(tables, full, recordings):
    rolling, _ = tables
    assert len(full["cases"]) == len(rolling) == 4
    for recompute in ([0], [1, 3]):
        part = studies.carriage_study(*tables, cases={i: c for i, c in enumerate(full["cases"]) if i not in recompute},
                                      recordings=recordings)
        for name in TABLES:
            assert part[name].equals(full[name]), (recompute, name)
        assert part["records"].keys() == full["records"].keys()
        assert all(np.array_equal(part["records"][k], full["records"][k]) for k in full["records"])
    # every case given: nothing is simulated, the tables are assembled from them
    again = studies.carriage_study(*tables, cases=dict(enumerate(full["cases"])), recordings=recordings)
    assert all(again[name].equals(full[name]) for name in TABLES)


def test_a_case_reads_its_row_its_stationary_row_and_its_conditions_footprint(tables):
    rolling, stationary = tables
    before = studies.carriage_case_inputs(rolling, stationary)
    heavy = (rolling["load_condition"] == "heavy").to_numpy()
    damped = rolling.copy()
    damped.loc[0, "damping_kN_s_per_m"] *= 1.1  # one row's damping: that case only
    after = studies.carriage_case_inputs(damped, stationary)
    assert _changed(before, after) == [True, False, False, False]
    stiffer = rolling.copy()
    stiffer.loc[heavy.argmax(), "stiffness_kN_per_m"] += 20  # a stiffness moves its condition's footprint
    after = studies.carriage_case_inputs(stiffer, stationary)
    assert _changed(before, after) == list(heavy)
    st = stationary.copy()
    st.loc[st["load_condition"] == "light", "damping_kN_s_per_m"] += 0.5  # the light stationary row
    after = studies.carriage_case_inputs(rolling, st)
    assert _changed(before, after) == list(~heavy)


def test_cases_must_be_keyed_by_row_position(tables, full):
    with pytest.raises(ValueError, match="cases must be keyed by row positions 0..3"):
        studies.carriage_study(*tables, cases={4: full["cases"][0]})


@pytest.fixture(scope="module")
def tractor_tables():
    mass = layouts.tractor_mass(read_published("table_xv"))
    tyres = layouts.tractor_tyres(read_published("table_xvi"))
    rolling = tyres[tyres["characteristics"] == "rolling"]
    # three cases (the first holds the Table XVIII sweep; one on the farm track), all stationary rows
    keep = rolling.index[[0, 5, 10]].union(tyres.index[tyres["characteristics"] == "stationary"])
    return mass, tyres.loc[keep].reset_index(drop=True)


@pytest.mark.slow  # 35 s on 2 busy cores; runs in `make test-all`, not in the default run
def test_tractor_cached_cases_give_the_full_study_to_the_bit(tractor_tables):
    full = studies.tractor_study(*tractor_tables)
    assert len(full["cases"]) == 3 and [len(c) for c in full["cases"]] == [2 + 11, 2, 2]  # predictions only
    for recompute in ([0], [1, 2]):
        part = studies.tractor_study(*tractor_tables, cases={i: c for i, c in enumerate(full["cases"]) if i not in recompute})
        for name in TRACTOR_TABLES:
            assert part[name].equals(full[name]), (recompute, name)
    with pytest.raises(ValueError, match="cases must be keyed by rolling-row positions 0..2"):
        studies.tractor_study(*tractor_tables, cases={-1: full["cases"][0]})


def test_a_tractor_case_reads_its_row_and_its_load_conditions_rows(tractor_tables):
    mass, tyres = tractor_tables
    before = studies.tractor_case_inputs(mass, tyres)
    lc = [c["row"]["load_condition"] for c in before]
    assert lc == [1, 1, 2]
    edited = tyres.copy()
    edited.loc[1, "rear_damping_kN_s_per_m"] *= 1.1  # the second rolling row
    assert _changed(before, studies.tractor_case_inputs(mass, edited)) == [False, True, False]
    stat = tyres.copy()
    stat.loc[(stat["characteristics"] == "stationary") & (stat["load_condition"] == 1), "rear_stiffness_kN_per_m"] += 10
    assert _changed(before, studies.tractor_case_inputs(mass, stat)) == [True, True, False]
    heavier = mass.copy()
    heavier.loc[heavier["load_condition"] == 2, "mass_kg"] += 100
    assert _changed(before, studies.tractor_case_inputs(heavier, tyres)) == [False, False, True]


def test_a_recording_with_lift_off_is_the_same_alone_and_in_the_full_batch(tables):
    """The virtual carriage's runs of a batch are padded to its longest (slowest) run; a run's
    record counts its own samples only, so a run recorded alone gives the full batch's bytes,
    lift-off included (and the study reads it the same)."""
    rolling, stationary = tables
    light = rolling.copy()
    light.loc[light["speed_km_h"] == 17.5, "damping_kN_s_per_m"] = 0.05  # the fast runs now lift off
    # one stiffness per load condition: its footprint (from the condition's rows) is then the same alone
    light["stiffness_kN_per_m"] = light.groupby("load_condition")["stiffness_kN_per_m"].transform("mean")
    full = sr.carriage_recordings(light, stationary)
    fast = light[light["speed_km_h"] == 17.5]
    alone = sr.carriage_recordings(fast, stationary)
    assert alone.keys() <= full.keys() and all(np.array_equal(alone[k], full[k]) for k in alone)
    # a body that leaves the ground falls at g: its record dips to -g
    assert all(full[k].min() < -0.99 * 9.80665 for k in alone)


def test_lift_off_counts_a_runs_own_samples():
    from tyrelab.vehicle import carriage as cm

    n = 2000
    t = np.arange(2 * n - 1) * 5e-4
    u = 0.05 * np.sin(2 * np.pi * 4.0 * t)  # 4 Hz, 50 mm: lifts off
    ud = 0.05 * 2 * np.pi * 4.0 * np.cos(2 * np.pi * 4.0 * t)
    u[2 * 1000:], ud[2 * 1000:] = u[2 * 1000], 0.0  # the second run's own samples end at 1000 (then level)
    car = cm.Carriage(2000.0, 300e3, 500.0)
    both = cm.simulate_nonlinear(car, np.stack([u, u]), np.stack([ud, ud]), 1e-3, n_steps=[n, 1000])
    alone = cm.simulate_nonlinear(car, u[: 2 * 1000 - 1], ud[: 2 * 1000 - 1], 1e-3)
    assert both["lift_off_fraction"][1] == alone["lift_off_fraction"] > 0
    assert np.array_equal(both["a_m_s2"][1, :1000], alone["a_m_s2"])
    with pytest.raises(ValueError, match="n_steps must be integers from 1 to the 2000 samples"):
        cm.simulate_nonlinear(car, u, ud, 1e-3, n_steps=n + 1)


def test_tables_that_do_not_fit_together_are_refused_with_every_problem(tables, tractor_tables):
    rolling, stationary = tables
    with pytest.raises(ValueError, match="^stationary has no row for load condition heavy$"):
        studies.carriage_case_inputs(rolling, stationary[stationary["load_condition"] != "heavy"])
    with pytest.raises(ValueError, match="stationary has more than one row for load condition light"):
        studies.carriage_study(rolling, pd.concat([stationary, stationary[stationary["load_condition"] == "light"]]))
    mass, tyres = tractor_tables
    no_stat = tyres[~((tyres["characteristics"] == "stationary") & (tyres["load_condition"] == 2))]
    with pytest.raises(ValueError, match="^table_xv has no row for load condition 1; table_xvi has no stationary row "
                                         "for load condition 2$"):
        studies.tractor_study(mass[mass["load_condition"] != 1], no_stat)


def test_the_sweep_case_reads_table_xviii(tractor_tables):
    """The Table XVIII sweep's longitudinal elements come from the table given (an edited
    <raw>/published one): only the case holding the sweep (the first) reads it."""
    mass, tyres = tractor_tables
    xviii = read_published("table_xviii")
    before = studies.tractor_case_inputs(mass, tyres, table_xviii=xviii)
    assert repr(before) == repr(studies.tractor_case_inputs(mass, tyres))  # the default is the shipped table
    edited = xviii.copy()
    edited.loc[2, "longitudinal_damping_kN_s_per_m"] = 2.0  # 455/1 -> 455/2 kN s/m
    after = studies.tractor_case_inputs(mass, tyres, table_xviii=edited)
    assert _changed(before, after) == [True, False, False]
    assert (455.0, 2.0) in after[0]["longitudinal_grid"]["kelvin_voigt"]


def test_a_carriage_study_of_one_case_has_tables_and_no_warning(tables, full):
    """One case (or one left after the 5 and 7.5 km/h runs are set aside) gave numpy's "Degrees of
    freedom <= 0" warning from the envelope's sd; the sd of one comparison is NaN, said once."""
    import warnings

    one = tables[0].head(1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s = studies.carriage_study(one, tables[1], cases={0: full["cases"][0]})
    for name in ("table_xiii", "table_xiv"):
        t = s[name].set_index(["quantity", "statistic"])
        assert np.isnan(t.loc[("envelope_error", "sd"), "rolling"]) and np.isfinite(t.loc[("envelope_error", "mean"), "rolling"])
    assert len(s["comparisons"]) == len(full["cases"][0]["comparisons"])


def test_the_envelope_sd_of_one_comparison_is_nan_without_a_warning():
    import warnings

    from tyrelab.vehicle.comfort import metrics as mt

    fs = 100.0
    x = np.sin(2 * np.pi * 2.0 * np.arange(0, 30, 1 / fs))
    one = pd.DataFrame([{"characteristics": "rolling", **mt.compare_records(1.1 * x, x, fs)}])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        t = mt.accuracy_table(one).set_index(["quantity", "statistic"])["rolling"]
    assert np.isnan(t[("envelope_correlation", "sd")]) and np.isnan(t[("envelope_error", "sd")])
    two = pd.concat([one, pd.DataFrame([{"characteristics": "rolling", **mt.compare_records(0.9 * x, x, fs)}])])
    t2 = mt.accuracy_table(two).set_index(["quantity", "statistic"])["rolling"]
    assert np.isfinite(t2[("envelope_error", "sd")])
