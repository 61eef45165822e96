"""Pure table shaping of the report."""

import numpy as np
import pandas as pd

from tyrelab.report import tables


def test_find_pairs_recognises_every_naming():
    cols = ["tyre_id", "thesis_k", "k", "k_difference", "thesis_rolling", "ours_rolling", "difference_rolling",
            "peak_ours", "peak_thesis", "thesis_notes"]
    pairs = {p.label: p for p in tables.find_pairs(cols)}
    assert set(pairs) == {"k", "rolling", "peak"}
    assert pairs["k"].difference == "k_difference"
    assert pairs["rolling"].ours == "ours_rolling" and pairs["rolling"].difference == "difference_rolling"
    assert pairs["peak"].ours == "peak_ours" and pairs["peak"].difference is None


def test_tolerance_uses_printed_precision_relative_and_floor():
    assert tables.tolerance(0.3, "x") == 0.05  # half a unit of the printed 0.3
    assert tables.tolerance(400.0, "x") == 20.0  # 5 %
    assert tables.tolerance(100.0, "carcass_stiffness_kN_per_m") == 8.0  # quoted scatter


def test_shape_comparison_highlights_only_beyond_tolerance():
    df = pd.DataFrame({"tyre_id": ["T1", "T2", "T3"], "speed_km_h": [10.0, 10.0, 10.0],
                       "thesis_c": [1.63, 1.63, np.nan], "c": [1.64, 2.0, 1.0], "n": [6, 6, 6]})
    s = tables.shape_comparison(df)
    assert s.keys == ["tyre_id", "speed_km_h"] and s.extras == ["n"]
    offs = [row["pairs"][0][3] for row in s.rows]
    assert offs == [False, True, False]
    assert s.n_off == 1
    assert np.isclose(s.rows[1]["pairs"][0][2], 0.37)


def test_compare_frames_joins_on_normalised_keys():
    ours = pd.DataFrame({"load_condition": ["light", "heavy"], "speed_km_h": [5.0, 10.0], "load_kg": [1860.0, 2230.0]})
    thesis = pd.DataFrame({"load_condition": ["light", "heavy", "heavy"], "nominal_speed_km_h": [5, 10, 12.5],
                           "load_kg": [1860, 2230, 2230]})
    out = tables.compare_frames(ours, thesis, ["load_condition", "speed_km_h"], {"load_kg": "load_kg"},
                                {"nominal_speed_km_h": "speed_km_h"})
    assert len(out) == 3
    assert list(out.columns[-3:]) == ["thesis_load_kg", "load_kg", "load_kg_difference"]
    matched = out.loc[out["load_kg"].notna()]
    assert (matched["load_kg_difference"] == 0).all()
    assert out["load_kg"].isna().sum() == 1  # the thesis row we have no run for


def test_thesis_only_gives_empty_ours_columns():
    pub = pd.DataFrame({"tyre_id": ["T1"], "speed_km_h": [10], "r_squared": [0.98], "notes": ["x"]})
    out = tables.thesis_only(pub)
    assert list(out.columns) == ["tyre_id", "speed_km_h", "thesis_r_squared", "r_squared"]
    assert out["r_squared"].isna().all()


def test_select_runs_takes_first_per_tyre_and_all_flagged():
    res = pd.DataFrame({"run_id": [f"r{i}" for i in range(8)], "tyre_id": ["A"] * 4 + ["B"] * 4,
                        "qc_ok": [True, True, True, False, True, True, True, True]})
    sel = tables.select_runs(res, per_tyre=2)
    assert list(sel["run_id"]) == ["r3", "r0", "r1", "r4", "r5"]
    assert len(tables.select_runs(res, per_tyre=2, max_runs=3)) == 3


def test_campaign_summary_counts():
    manifest = pd.DataFrame({"campaign": ["c"] * 4, "tyre_id": ["A", "B", "plate", "plate"],
                             "kind": ["measurement", "measurement", "calibration", "calibration"],
                             "recorded_on": ["d1", "d1", "d1", "d2"]})
    results = pd.DataFrame({"qc_ok": [True, False]})
    quarantine = pd.DataFrame({"run_id": ["x"]})
    s = tables.campaign_summary(manifest, results, quarantine)
    assert (s["runs"], s["tyres"], s["qc_failures"], s["quarantined"], s["calibration_days"]) == (4, 2, 1, 1, 2)
