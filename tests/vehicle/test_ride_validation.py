"""Predictions checked against recordings: a recording made from a scenario's own prediction."""

import math

import numpy as np
import pandas as pd
import pytest

from tyrelab.rawformat.rides import open_recording
from tyrelab.resources import scenarios_dir
from tyrelab.vehicle import measured_ride
from tyrelab.vehicle import ride_validation as rv
from tyrelab.scenario_io import load_scenario


@pytest.fixture(scope="module")
def prediction():
    sc = load_scenario(scenarios_dir() / "mf698t.toml")
    return rv.predicted_seat(sc, 15.0, rv.track_of("scenario"))


def test_scaled_recording_gives_ratio_1_2(tmp_path, prediction):
    """The prediction written as a recording (with a DC-coupled 1 g on z), scaled by 1.2."""
    sig, fs = prediction
    t = np.arange(sig["seat_z_m_s2"].size) / fs
    path = tmp_path / "pass.csv"
    pd.DataFrame({"time_s": t, "seat_z_m_s2": 1.2 * sig["seat_z_m_s2"] + 9.80665,
                  "seat_x_m_s2": 1.2 * sig["seat_x_m_s2"]}).to_csv(path, index=False)
    rec = open_recording(path)
    measured = measured_ride.analyse_recording(rec)
    frame = pd.read_csv(path)
    rows = {r["axis"]: r for r in rv.validation_rows(measured, sig, fs, True,
                                                     {c: frame[c].to_numpy() for c in ("seat_z_m_s2", "seat_x_m_s2")})}
    z = rows["z"]
    assert z["ratio_a_w"] == pytest.approx(1.2, rel=1e-6)
    assert z["measured_peak_frequency_Hz"] == pytest.approx(z["predicted_peak_frequency_Hz"], rel=1e-9)
    assert z["measured_half_power_width_Hz"] == pytest.approx(z["predicted_half_power_width_Hz"], rel=1e-9)
    assert z["envelope_similarity"] == pytest.approx(1.0, abs=1e-9)


def test_an_iso_class_track_compares_spectra_not_envelopes(prediction):
    """An ISO 8608 class names a spectrum, not elevations: no R. Class C has a quarter of class D's
    PSD (ISO 8608: 256 vs 1024 × 10⁻⁶ m³), so the seat's a_w on it is half (a linear ride)."""
    sig, fs = prediction
    sc = load_scenario(scenarios_dir() / "mf698t.toml")
    track = rv.track_of("ISO 8608 class C")
    assert not track.known_profile
    on_c, _ = rv.predicted_seat(sc, 15.0, track)
    measured = measured_ride.analyse_signals(on_c, fs)
    z = {r["axis"]: r for r in rv.validation_rows(measured, sig, fs, track.known_profile, on_c)}["z"]
    assert math.isnan(z["envelope_similarity"])
    assert z["ratio_a_w"] == pytest.approx(0.5, rel=0.02)


def test_statistics_are_the_thesis_ratio_errors():
    rows = pd.DataFrame({"axis": ["z"] * 3, "measured_a_w_m_s2": [1.0, 1.0, 1.0], "predicted_a_w_m_s2": [0.9, 1.0, 1.1],
                         "measured_peak_frequency_Hz": [2.0] * 3, "predicted_peak_frequency_Hz": [2.0] * 3,
                         "measured_half_power_width_Hz": [0.5] * 3, "predicted_half_power_width_Hz": [0.5] * 3,
                         "envelope_similarity": [0.8, 0.9, math.nan]})
    st = rv.validation_statistics(rows).set_index("quantity")
    assert st.loc["a_w", "mean"] == pytest.approx(1.0) and st.loc["a_w", "sd"] == pytest.approx(0.1)
    assert st.loc["a_w", "p_within_10"] == pytest.approx(0.6827, abs=1e-3)
    assert st.loc["envelope_similarity", "n"] == 2 and st.loc["envelope_similarity", "mean"] == pytest.approx(0.85)


@pytest.mark.parametrize("text,problem", [("Z", "expected 'scenario'"), ("../x.csv", "outside the campaign"),
                                          ("nope.csv", "file not found")])
def test_bad_tracks_are_named(tmp_path, text, problem):
    with pytest.raises(ValueError, match=problem):
        rv.track_of(text, tmp_path)
