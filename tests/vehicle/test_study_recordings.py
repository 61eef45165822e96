"""Chapters 6-7 from recordings (issue 24): the studies compare their predictions with the
recordings they are given, measure both by the same functions, and without recordings have
gaps, not errors; the virtual vehicles' recordings are seeded and in the raw ride format."""

import numpy as np
import pandas as pd
import pytest

from tyrelab.published import read_published
from tyrelab.rawformat.rides import open_recording
from tyrelab.schema import load_schema, validate_frame
from tyrelab.vehicle import metrics as mt
from tyrelab.vehicle import published_layouts as layouts
from tyrelab.vehicle import studies
from tyrelab.vehicle import study_recordings as sr


@pytest.fixture(scope="module")
def carriage_tables():
    xii = read_published("table_xii")
    rolling = layouts.carriage_rolling(xii)
    return rolling[rolling["speed_km_h"].isin([10.0, 12.5])].reset_index(drop=True), layouts.carriage_stationary(xii)


@pytest.fixture(scope="module")
def tractor_tables():
    tyres = layouts.tractor_tyres(read_published("table_xvi"))
    rolling = tyres[tyres["characteristics"] == "rolling"]
    keep = rolling.index[[1, 6]].union(tyres.index[tyres["characteristics"] == "stationary"])  # SBT and HH, 12.5 km/h
    return layouts.tractor_mass(read_published("table_xv")), tyres.loc[keep].reset_index(drop=True)


def test_the_measured_side_is_the_recording_given(carriage_tables):
    """A 'recording' that is the rolling prediction on the surveyed estimate, scaled by 1.2,
    gives that prediction a ratio of 1/1.2 in r.m.s. and the square root of the peak height,
    the same peak frequency and an envelope correlation of 1: the measured side is the
    recording, measured by the same function as the prediction."""
    rolling, stationary = carriage_tables
    none = studies.carriage_study(rolling, stationary)
    pred = {studies.carriage_key(r): None for r in rolling.to_dict("records")}
    runs = none["runs"]
    assert set(runs["source"]) == {"prediction"} and none["comparisons"].empty
    # the rolling/surveyed prediction's record of each run, from a study that keeps it
    for r in rolling.to_dict("records"):
        one = studies.carriage_study(pd.DataFrame([r]), stationary)
        pred[studies.carriage_key(r)] = None if not one["records"] else one["records"].get(("rolling", "surveyed"))
    heavy = studies.carriage_key({"speed_km_h": 12.5, "load_condition": "heavy"})
    record = pred[heavy]
    assert record is not None  # 12.5 km/h heavy keeps its records (Fig. 56)
    study = studies.carriage_study(rolling, stationary, recordings={heavy: 1.2 * record})
    c = study["comparisons"].set_index(["characteristics", "profile_estimate"]).loc[("rolling", "surveyed")]
    assert c["ratio_rms"] == pytest.approx(1 / 1.2, rel=1e-9)
    assert c["ratio_sqrt_peak_height"] == pytest.approx(1 / 1.2, rel=1e-9)
    assert c["ratio_peak_frequency"] == pytest.approx(1.0) and c["envelope_correlation"] == pytest.approx(1.0)
    rec = study["runs"][study["runs"]["source"] == "recording"].iloc[0]
    assert rec["rms"] == pytest.approx(1.2 * mt.record_metrics(record, studies.FS_HZ)["rms"])
    assert len(study["comparisons"]) == 4  # one recorded run, four predictions of it


def test_without_recordings_the_tables_are_gaps_not_errors(carriage_tables, tractor_tables):
    car = studies.carriage_study(*carriage_tables)
    for name in ("table_xiii", "table_xiv"):
        t = car[name]
        assert len(t) == 20 and t[["rolling", "stationary"]].isna().all().all(), name
    tr = studies.tractor_study(*tractor_tables)
    assert len(tr["table_xvii"]) == 32 and tr["table_xvii"][["ours_rolling", "ours_stationary"]].isna().all().all()
    assert tr["reference_xviii"].empty and (tr["runs"]["source"] == "prediction").all()


def test_virtual_vehicles_recordings_reproduce_the_reference_vehicle(carriage_tables, tractor_tables):
    """The tractor's recordings are measured by run_metrics, the function of the predictions:
    the same record gives the same row whether predicted or recorded."""
    recs = sr.tractor_recordings(*tractor_tables)
    assert sorted(recs) == [(1, "HH", 12.5), (1, "SBT", 12.5)]
    tr = studies.tractor_study(*tractor_tables, recordings=recs)
    ref = tr["runs"][tr["runs"]["source"] == "recording"].set_index(["track"])
    for (lc, track, v), r in recs.items():
        row = studies.run_metrics({"load_condition": lc, "track": track, "speed_km_h": v}, "x",
                                  r["vertical_m_s2"], r["pitch_rad_s2"], r["longitudinal_m_s2"])
        assert ref.loc[track, "vertical_rms_m_s2"] == row["vertical_rms_m_s2"] > 0
        assert ref.loc[track, "pitch_rms_rad_s2"] == row["pitch_rms_rad_s2"] > 0
    x = tr["table_xvii"]
    assert x[x["track"] == "SBT"][["ours_rolling", "ours_stationary"]].notna().any().all()


def test_generated_study_recordings_are_raw_rides_and_seeded(tmp_path, carriage_tables, tractor_tables):
    rolling, _ = carriage_tables
    pub = {"table_xii": read_published("table_xii"), "table_xv": read_published("table_xv"),
           "table_xvi": read_published("table_xvi")}
    # the study's tables, cut to the rows of the fixtures (the generator reads the published layout)
    xvi = pub["table_xvi"]
    rows_xvi = xvi[(xvi["characteristics"] == "stationary") | (xvi["speed_km_h"] == 12.5) & (xvi["load_condition"] == 1)]
    xii = pub["table_xii"]
    pub_small = {**pub, "table_xvi": rows_xvi, "table_xii": xii[(xii["characteristics"] == "stationary")
                                                             | xii["nominal_speed_km_h"].isin([10.0, 12.5])]}
    rows, frames, track = sr.study_recordings(pub_small, seed=7)
    assert validate_frame(rows.astype(str), load_schema("raw_rides")) == []
    assert set(rows["study"]) == {"carriage", "tractor"} and len(rows) == len(rolling) + 2
    again_rows, again, _ = sr.study_recordings(pub_small, seed=7)
    assert again_rows.equals(rows) and all(again[f].equals(frames[f]) for f in frames)
    other = sr.study_recordings(pub_small, seed=8)[1]
    f = rows["file"].iloc[0]
    diff = other[f]["floor_z_m_s2"].to_numpy(float) - frames[f]["floor_z_m_s2"].to_numpy(float)
    assert 0 < np.std(diff) < 2 * np.sqrt(2) * sr.NOISE_M_S2  # another seed: another noise, nothing else
    from tyrelab.generate import write_run

    write_run(frames[f], tmp_path / "r.parquet")
    rec = open_recording(tmp_path / "r.parquet")
    assert rec.channels == ("floor_z_m_s2",) and rec.sample_rate_Hz == pytest.approx(studies.FS_HZ)
    assert list(track.columns) == ["x_m", "left_m", "right_m"]
