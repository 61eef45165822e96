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


# --------------------------------------------------------------------------- issue 42: every coefficient's source
def _build():
    k = _lines([("T1", 0.0, 230.0, 40.0), ("T1", 10.0, 250.0, 40.0)])
    c = _lines([("T1", 0.0, 1.4, 0.05), ("T1", 10.0, 1.2, 0.05)])
    s = pd.DataFrame([{"direction": "lateral", "tyre_id": "T1", "coefficient_kN_s_per_m_times_km_h": 99.0},
                      {"direction": "longitudinal", "tyre_id": "T1", "coefficient_kN_s_per_m_times_km_h": float("nan")}])
    return {"stiffness_lines": k, "damping_lines": c, "series_damping": s}


def test_a_measured_tyre_gives_k_c_and_a_from_the_build_per_speed():
    from tyrelab.tyre.directional import rolling_coefficients

    r = rolling_coefficients("lateral", 1.0, [0.0, 5.0, 20.0], tyre_id="T1", **_build())
    assert r.sources == dict.fromkeys(r.sources, "measured")
    assert r.stiffness_kN_per_m.tolist() == pytest.approx([270.0, 280.0, 290.0])  # interpolated, held
    assert r.damping_kN_s_per_m.tolist() == pytest.approx([1.45, 1.35, 1.25])
    assert r.series_damping_N_s_per_m().tolist() == pytest.approx([math.inf, 99e3 / 5, 99e3 / 20])
    assert all("T1" in t for t in r.source_text.values()) and r.ci95 == {}
    # the same tyre at another speed: the same lines (what a fresh run and --build both read)
    one = rolling_coefficients("lateral", 1.0, [5.0], tyre_id="T1", **_build())
    assert one.stiffness_kN_per_m[0] == r.stiffness_kN_per_m[1]


def test_each_coefficient_falls_back_on_its_own():
    """No longitudinal ``a`` fitted (NaN): that one coefficient is the stand-in; the scenario beats the build; the
    catalogue serves a tyre the build lacks; a build with K but no C lines is used for neither."""
    from tyrelab.tyre import rolling
    from tyrelab.tyre.directional import rolling_coefficients

    b = _build()
    lon = rolling_coefficients("longitudinal", 1.0, [8.0], tyre_id="T1", series_damping=b["series_damping"])
    assert lon.sources == {"stiffness_kN_per_m": "stand-in", "damping_kN_s_per_m": "stand-in",
                           "series_damping_kN_s_per_m_km_h": "stand-in"}  # no longitudinal lines, a NaN
    assert lon.stiffness_kN_per_m.tolist() == [455.0] and lon.series_damping_kN_s_per_m_km_h == 140.0
    lat = rolling_coefficients("lateral", 1.0, [8.0], tyre_id="T1", given={"stiffness_kN_per_m": 300.0}, **b)
    assert lat.sources["stiffness_kN_per_m"] == "scenario" and lat.sources["damping_kN_s_per_m"] == "measured"
    assert lat.stiffness_kN_per_m.tolist() == [300.0]
    row = {"lateral_stiffness_kN_per_m": 260.0, "lateral_damping_kN_s_per_m": 1.1,
           "lateral_series_damping_kN_s_per_m_km_h": float("nan")}
    cat = rolling_coefficients("lateral", 1.0, [8.0], tyre_id="X1", catalogue_row=row, **b)
    assert cat.sources == {"stiffness_kN_per_m": "catalogue", "damping_kN_s_per_m": "catalogue",
                           "series_damping_kN_s_per_m_km_h": "stand-in"}
    assert cat.series_damping_kN_s_per_m_km_h == rolling.SERIES_DAMPING_KN_S_PER_M_KM_H["lateral"]
    assert cat.ci95["series_damping_kN_s_per_m_km_h"] == rolling.SERIES_DAMPING_95["lateral"]
    half = rolling_coefficients("lateral", 1.0, [8.0], tyre_id="T1", vertical_stiffness_kN_per_m=400.0,
                                vertical_damping_kN_s_per_m=1.5, stiffness_lines=b["stiffness_lines"])
    assert half.sources["stiffness_kN_per_m"] == half.sources["damping_kN_s_per_m"] == "stand-in"
    assert half.damping_kN_s_per_m.tolist() == [1.5] and half.ci95["stiffness_kN_per_m"][0][0] < 226.3 < \
        half.ci95["stiffness_kN_per_m"][1][0]


def test_bad_coefficients_are_refused_naming_them():
    from tyrelab.tyre.directional import rolling_coefficients

    with pytest.raises(ValueError, match="lateral_series_damping_kN_s_per_m_km_h"):
        rolling_coefficients("lateral", 1.0, [8.0], given={"series_damping_kN_s_per_m_km_h": -5.0,
                                                          "stiffness_kN_per_m": 200.0, "damping_kN_s_per_m": 1.0})
    with pytest.raises(ValueError, match=r"\(lateral_series_damping_kN_s_per_m_km_h\) has non-finite"):
        rolling_coefficients("lateral", 1.0, [8.0], given={"series_damping_kN_s_per_m_km_h": float("nan")},
                             vertical_stiffness_kN_per_m=400.0, vertical_damping_kN_s_per_m=1.5)
    with pytest.raises(ValueError, match="vertical_stiffness_kN_per_m"):
        rolling_coefficients("lateral", 1.0, [8.0])
    with pytest.raises(ValueError, match="given"):
        rolling_coefficients("lateral", 1.0, [8.0], given={"stiffness": 1.0})
    with pytest.raises(ValueError, match="speeds_km_h"):
        rolling_coefficients("longitudinal", 1.0, [-1.0])
