"""The digitised thesis Tables XII-XX in the studies' layouts (spot checks against the thesis)."""

import math

import pandas as pd
import pytest

from tyrelab.published import read_published
from tyrelab.vehicle import published_layouts as layouts
from tyrelab.vehicle.metrics import accuracy_table


def test_carriage_table_xii():
    xii = read_published("table_xii")
    rolling = layouts.carriage_rolling(xii)
    assert len(rolling) == 12 and set(rolling["speed_km_h"]) == {5.0, 7.5, 10.0, 12.5, 15.0, 17.5}
    r = rolling.set_index(["load_condition", "speed_km_h"])
    assert r.loc[("light", 17.5), "stiffness_kN_per_m"] == 380 and r.loc[("heavy", 5.0), "damping_kN_s_per_m"] == 1.66
    st = layouts.carriage_stationary(xii).set_index("load_condition")
    assert st.loc["light", "stiffness_kN_per_m"] == 545 and st.loc["heavy", "damping_kN_s_per_m"] == 3.80


@pytest.mark.parametrize("stem", ["table_xiii", "table_xiv"])
def test_carriage_accuracy_labels_match_metrics(stem):
    t = layouts.carriage_accuracy(read_published(stem))
    comps = pd.DataFrame({"characteristics": ["rolling", "rolling"], "ratio_rms": [1.0, 1.1],
                          "ratio_sqrt_peak_height": [1.0, 1.1], "ratio_peak_frequency": [1.0, 1.1],
                          "ratio_width_over_frequency": [1.0, 1.1], "envelope_correlation": [0.9, 0.8],
                          "envelope_error": [0.3, 0.4]})
    ours = accuracy_table(comps)
    assert list(zip(t["quantity"], t["statistic"])) == list(zip(ours["quantity"], ours["statistic"]))


def test_carriage_accuracy_values():
    t = layouts.carriage_accuracy(read_published("table_xiv")).set_index(["quantity", "statistic"])
    assert t.loc[("peak_frequency", "mean_ratio_error"), "thesis_stationary"] == 1.21
    assert t.loc[("half_power_width_over_frequency", "sd_ratio_error"), "thesis_stationary"] == 0.38
    assert t.loc[("envelope_error", "mean"), "thesis_rolling"] == 0.38


def test_tractor_mass_table_xv():
    xv = layouts.tractor_mass(read_published("table_xv")).set_index("load_condition")
    assert list(xv.index) == [1, 2, 3, 4]
    assert xv.loc[4, "mass_class"] == "light" and xv.loc[4, "mass_kg"] == 3617
    assert xv.loc[1, "pitch_inertia_kg_m2"] == 6210 and (xv["wheelbase_m"] == 2.436).all()
    assert xv.loc[2, "rear_pressure_bar"] == 2.07


def test_tractor_accuracy_table_xvii():
    t = layouts.tractor_accuracy(read_published("table_xvii")).set_index(["track", "quantity", "statistic"])
    assert t.loc[("SBT", "vertical_rms", "mean_ratio_error"), "thesis_rolling"] == 1.13
    assert t.loc[("HH", "second_peak_frequency", "p_within_30"), "thesis_stationary"] == 0.93
    assert ("HH", "vertical_rms", "p_within_10") not in t.index  # not printed


def test_longitudinal_sweep_table_xviii():
    t = layouts.longitudinal_sweep(read_published("table_xviii"))
    assert (t["row"] == "predicted").sum() == 8
    meas = t[t["row"] == "measured"].iloc[0]
    assert meas["vertical_rms_m_s2"] == 1.79 and meas["pitch_rms_rad_s2"] == 1.98 and math.isnan(meas["peak_1_Hz"])


def test_tractors_booleans():
    t = layouts.tractors(read_published("table_xix")).set_index("tractor")
    assert t.loc["County 774", "front_water_ballast"] and not t.loc["Leyland 272", "four_wheel_drive"]


def test_unknown_label_rejected():
    xvii = read_published("table_xvii").copy()
    xvii.loc[0, "component"] = "roll"
    with pytest.raises(ValueError, match="unknown label"):
        layouts.tractor_accuracy(xvii)
