import pandas as pd

from tyrelab.tyre import conditions as cond

from tyre_synthetic import make_results, run


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
