"""Issue 43's page: the verdict (which modes the model gets within the measured intervals), the FRF
panels per recording and output, the modes measured against predicted."""

import duckdb
import numpy as np
import pandas as pd

from tyrelab.report import frf_figures
from tyrelab.report.frf_page import BEST_MODES_SQL, VERDICT_SQL, VEHICLE_FRF

COLUMNS = ("ride_id", "output", "mode", "predicted_mode", "measured_frequency_Hz", "measured_frequency_ci95_low_Hz",
           "measured_frequency_ci95_high_Hz", "predicted_frequency_Hz", "frequency_ratio", "frequency_in_interval",
           "measured_damping_ratio", "predicted_damping_ratio", "damping_ratio_ratio", "damping_in_interval")


def _validation(rows, determined=None):
    con = duckdb.connect()
    frame = pd.DataFrame(rows, columns=COLUMNS)
    frame["measured_determined"] = True if determined is None else determined
    con.register("v", frame)
    con.execute("CREATE TABLE vehicle_frf_validation AS SELECT * FROM v")
    return con


def test_the_verdict_judges_each_mode_where_it_is_best_determined():
    con = _validation([
        # a: bounce in two outputs; the narrow interval (floor_z) is in, the wide one (yaw) out
        ("a", "floor_z_m_s2", 1, "bounce", 2.44, 2.40, 2.48, 2.44, 1.0, True, 0.025, 0.024, 0.96, True),
        ("a", "yaw_rad_s2", 2, "bounce", 2.80, 2.50, 3.10, 2.44, 0.87, False, 0.1, 0.024, 0.24, False),
        ("a", "roll_rad_s2", 1, "lateral_roll", 1.40, 1.30, 1.50, 1.36, 0.97, True, 0.47, 0.41, 0.87, False),
        ("b", "floor_z_m_s2", 1, "bounce", 2.45, 2.41, 2.49, 2.44, 0.996, True, 0.026, 0.024, 0.92, True),
        ("b", "roll_rad_s2", 1, "lateral_roll", 1.35, 1.30, 1.40, 1.36, 1.0, True, 0.42, 0.41, 0.98, True),
        ("b", "roll_rad_s2", 2, None, 7.0, 6.9, 7.1, None, None, None, 0.1, None, None, None),
        ("b", "pitch_rad_s2", None, None, None, None, None, None, None, None, None, None, None, None),
    ])
    best = con.execute(BEST_MODES_SQL + " ORDER BY ride_id, predicted_mode").fetchdf()
    assert list(zip(best["ride_id"], best["predicted_mode"], best["output"])) == [
        ("a", "bounce", "floor_z_m_s2"), ("a", "lateral_roll", "roll_rad_s2"), ("b", "bounce", "floor_z_m_s2"),
        ("b", "lateral_roll", "roll_rad_s2")]
    verdict = con.execute(VERDICT_SQL).fetchdf().set_index("mode")
    assert list(verdict.index) == ["bounce", "lateral_roll"]  # the modes the model gets first
    assert verdict.loc["bounce", "verdict"] == "within the measured intervals in every recording"
    assert verdict.loc["lateral_roll", "verdict"] == "within in 1 of 2 recordings"
    assert (verdict.loc["lateral_roll", "frequency_within"], verdict.loc["lateral_roll", "damping_within"]) == (2, 1)


def test_the_page_leads_with_the_verdict_then_the_frfs_then_the_modes():
    kinds = [(type(i).__name__, getattr(i, "ours_sql", None) == VERDICT_SQL) for i in VEHICLE_FRF.items]
    assert kinds[0] == ("TableSpec", True) and kinds[1][0] == "FigureSpec" and kinds[2][0] == "TableSpec"
    assert VEHICLE_FRF.items[1].function == "frf_panels" and VEHICLE_FRF.items[1].module == "frf_figures"


def _frf(rides=("stand_x", "track_y"), predicted=True):
    f = np.arange(0.1, 20.0, 0.1)
    rows = []
    for ride in rides:
        for inp, coh in (("input_rear_left_z_m_s2", 0.0), ("input_front_left_z_m_s2", 0.6)):
            for out in ("roll_rad_s2", "floor_z_m_s2"):
                h = 1 / np.abs(1 - (f / 2.4) ** 2 + 0.1j * f / 2.4)
                frame = pd.DataFrame({"ride_id": ride, "input": inp, "output": out, "frequency_Hz": f, "h_magnitude": h,
                                      "random_error": 0.02, "multiple_coherence": 0.95, "masked": f > 8,
                                      "ill_conditioned": False, "input_coherence": coh})
                if predicted:
                    frame["predicted_h_magnitude"] = h * 1.02
                rows.append(frame)
    return pd.concat(rows, ignore_index=True)


def test_frf_panels_draw_measured_band_prediction_and_coherence():
    svg = frf_figures.frf_panels(_frf(), pd.DataFrame({"ride_id": ["track_y", "stand_x"],
                                                       "method": ["track", "four_post"]}))
    assert svg.startswith("<svg") and "predicted" in svg and "measured, 95 %" in svg and "coherence" in svg
    assert "input_rear_left_z_m_s2" in svg and "input_front_left_z_m_s2" not in svg  # the wheel excited alone
    assert "predicted" not in frf_figures.frf_panels(_frf(predicted=False))
    assert "no recordings with wheel inputs" in frf_figures.frf_panels(_frf().iloc[:0])
    assert frf_figures.frf_panels(pd.DataFrame({"ride_id": []})) is None  # the rides stage has not run


def test_at_most_max_recordings_stand_and_track_first():
    rides = [f"r{i:02d}" for i in range(frf_figures.MAX_RECORDINGS + 3)]
    methods = pd.DataFrame({"ride_id": rides, "method": ["road"] * 3 + ["four_post"] * (len(rides) - 3)})
    chosen = frf_figures._recordings(pd.DataFrame({"ride_id": rides}), methods)
    assert len(chosen) == frf_figures.MAX_RECORDINGS and chosen[0] == "r03" and "r00" not in chosen


def test_a_mode_no_recording_determines_says_so_and_a_determined_one_is_judged_first():
    rows = [
        # a: lateral-roll in two outputs, the narrower interval undetermined (damped beyond 1/√2)
        ("a", "roll_rad_s2", 1, "lateral_roll", 1.15, 1.10, 1.20, 0.99, 0.86, False, 0.75, 0.80, 1.07, False),
        ("a", "floor_y_m_s2", 1, "lateral_roll", 1.00, 0.80, 1.30, 0.99, 0.99, True, 0.78, 0.80, 1.03, True),
        ("b", "roll_rad_s2", 1, "yaw", 1.50, 1.40, 1.60, 1.46, 0.97, True, 0.70, 0.76, 1.09, True),
    ]
    con = _validation(rows, determined=[False, True, False])
    best = con.execute(BEST_MODES_SQL + " ORDER BY ride_id, predicted_mode").fetchdf()
    assert list(zip(best["predicted_mode"], best["output"])) == [("lateral_roll", "floor_y_m_s2"), ("yaw", "roll_rad_s2")]
    verdict = con.execute(VERDICT_SQL).fetchdf().set_index("mode")
    assert verdict.loc["yaw", "verdict"].startswith("not determined") and verdict.loc["yaw", "undetermined"] == 1
    assert verdict.loc["lateral_roll", "verdict"] == "within the measured intervals in every recording"
