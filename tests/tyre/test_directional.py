"""Issue 34: a tyre's lateral and longitudinal coefficients for the vehicle, from the build or the catalogue."""

import math

import pandas as pd
import pytest

from tyrelab.tyre.directional import CATALOGUE_COLUMNS, directional_tyre


def _lines(rows):
    return pd.DataFrame(rows, columns=["tyre_id", "speed_km_h", "intercept", "slope"])


def test_the_build_s_lines_interpolate_in_speed_and_the_series_damper_falls_with_it():
    k = _lines([("T1", 0.0, 230.0, 40.0), ("T1", 5.0, 240.0, 40.0), ("T9", 0.0, 1.0, 1.0)])
    c = _lines([("T1", 0.0, 1.4, 0.05), ("T1", 5.0, 1.4, 0.05)])
    s = pd.DataFrame([{"direction": "lateral", "tyre_id": "T1", "coefficient_kN_s_per_m_times_km_h": 100.0}])
    t = directional_tyre("T1", "lateral", 1.0, 2.5, stiffness_lines=k, damping_lines=c, series_damping=s)
    assert t.stiffness_N_per_m == pytest.approx(275e3) and t.damping_N_s_per_m == pytest.approx(1450.0)
    assert t.series_damping_N_s_per_m == pytest.approx(40e3) and t.model == "maxwell" and "build" in t.source
    held = directional_tyre("T1", "lateral", 1.0, 20.0, stiffness_lines=k, damping_lines=c, series_damping=s)
    assert held.stiffness_N_per_m == pytest.approx(280e3) and held.series_damping_N_s_per_m == pytest.approx(5e3)
    still = directional_tyre("T1", "lateral", 1.0, 0.0, stiffness_lines=k, damping_lines=c, series_damping=s)
    assert math.isinf(still.series_damping_N_s_per_m) and still.model == "kelvin_voigt"


def test_the_catalogue_serves_a_tyre_measured_elsewhere_and_nothing_is_none():
    row = {"longitudinal_stiffness_kN_per_m": 380.0, "longitudinal_damping_kN_s_per_m": 1.6,
           "longitudinal_series_damping_kN_s_per_m_km_h": float("nan")}
    t = directional_tyre("X1", "longitudinal", 1.6, 8.0, catalogue_row=row)
    assert (t.stiffness_N_per_m, t.damping_N_s_per_m, t.model) == (380e3, 1600.0, "kelvin_voigt")
    assert "catalogue" in t.source
    assert directional_tyre("X1", "lateral", 1.6, 8.0, catalogue_row=row) is None
    assert set(CATALOGUE_COLUMNS) >= set(row)
    with pytest.raises(ValueError, match="direction"):
        directional_tyre("X1", "vertical", 1.6, 8.0)
