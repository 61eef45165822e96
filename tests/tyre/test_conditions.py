import pandas as pd

from tyrelab.tyre import conditions as cond

from tests.tyre.tyre_synthetic import make_results, run


def test_nominal_excludes_each_non_nominal_condition():
    base = dict(tyre_id="T1", speed=10.0, pressure=1.0, k=300.0, c=1.0)
    rows = [
        run(**base),
        run(**base, surface="Grass"),
        run(**base, torque_kNm=2.0),
        run(**base, excitation_frequency_Hz=2.0),
        run(**base, amplitude_mm_pp=25.0),
        run(**base, kind="calibration"),
        run(**base, qc_ok=False),
        run(**base, excitation_frequency_Hz=4.5, amplitude_mm_pp=10.0, surface=" Concrete "),
    ]
    df = pd.DataFrame(rows)
    assert cond.nominal(df).tolist() == [True, False, False, False, False, False, False, True]
    assert cond.nominal(df, except_for="amplitude").tolist()[4] is True


def test_speed_condition_table_iii_pool():
    got = cond.speed_condition([0.0, 0.1, 1.0, 10.0, 12.0, 15.0, 20.0]).tolist()
    assert got == ["stationary", None, None, "rolling", "rolling", "rolling", None]


def test_table_iii_runs_labels_conditions():
    df = make_results()
    sel = cond.table_iii_runs(df)
    assert set(sel["condition"]) == {"stationary", "rolling"}
    assert len(sel) == len(df)


def test_regressor_prefers_measured_value():
    df = pd.DataFrame([run("T1", 10.0, 1.0, 1, 1, amplitude_measured_mm_pp=12.5),
                       run("T1", 10.0, 1.0, 1, 1)])
    assert cond.regressor(df, "amplitude").tolist() == [12.5, 14.0]


def test_hold_constant_picks_level_with_most_distinct_x():
    df = pd.DataFrame({"x": [1, 2, 3, 1, 1], "load_kN": [18.3, 18.3, 18.3, 22.6, 15.9]})
    sub, levels, note = cond.hold_constant(df, "x", ["load_kN"])
    assert levels == {"load_kN": 18.3} and len(sub) == 3 and note == ""


def test_hold_constant_pools_when_no_level_varies_x():
    df = pd.DataFrame({"x": [1, 2, 3], "load_kN": [16.0, 18.0, 22.0]})
    sub, levels, note = cond.hold_constant(df, "x", ["load_kN"])
    assert len(sub) == 3 and levels == {"load_kN": None} and "pooled" in note


def test_nominal_windows_include_their_edges_and_missing_torque_is_none():
    base = dict(tyre_id="T1", speed=10.0, pressure=1.0, k=300.0, c=1.0)
    amps = [9.9, 10.0, 14.0, 18.0, 18.1]  # §3.5: 10-18 mm peak-to-peak
    df = pd.DataFrame([run(**base, amplitude_mm_pp=a) for a in amps] + [run(**base, torque_kNm=float("nan"))])
    assert cond.nominal(df).tolist() == [False, True, True, True, False, True]


def test_speed_condition_pool_ends_at_15_km_h():
    assert cond.speed_condition([9.9, 10.0, 15.0, 15.5, 16.0]).tolist() == [None, "rolling", "rolling", None, None]


def test_hold_constant_pooling_needs_variation_overall_and_none_within_a_level():
    # a level with two distinct x is an experiment: held, not pooled
    df = pd.DataFrame({"x": [1, 2, 3], "load_kN": [18.3, 18.3, 22.6]})
    sub, levels, note = cond.hold_constant(df, "x", ["load_kN"])
    assert levels == {"load_kN": 18.3} and len(sub) == 2 and note == ""
    # two x, each at its own load: pooled
    sub, levels, note = cond.hold_constant(pd.DataFrame({"x": [1, 2], "load_kN": [16.0, 22.0]}), "x", ["load_kN"])
    assert len(sub) == 2 and levels == {"load_kN": None} and "pooled" in note
    # one x at two loads: nothing varies x, nothing to pool for
    sub, levels, note = cond.hold_constant(pd.DataFrame({"x": [1, 1], "load_kN": [16.0, 22.0]}), "x", ["load_kN"])
    assert len(sub) == 1 and note == ""
