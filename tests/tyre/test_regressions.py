import numpy as np
import pandas as pd
import pytest

from tyrelab.tyre import regressions as reg
from tests.tyre.tyre_synthetic import TRUTH, make_results, run

# Thesis Table III rows used as literal published values (thesis §4.3.1).
PUBLISHED_III = pd.DataFrame(
    [
        ("T3", "13.6R38", "stationary", 184.0, 200.0, 0.99, ">"),
        ("T3", "13.6R38", "rolling", 112.0, 177.0, 0.99, ">"),
        ("F1", "7.5-18", "stationary", 96.0, 158.0, 0.96, None),
        ("F1", "7.5-18", "rolling", -3.0, 134.0, 0.99, None),
        ("AS9", "9.5R44", "rolling", 99.0, 141.0, 0.99, ">"),
    ],
    columns=["tyre_id", "size", "condition", "carcass_stiffness_kN_per_m",
             "pressure_dependence_kN_per_m_bar", "r_squared", "r_squared_qualifier"],
)


def test_fit_line_analytic():
    x = np.array([0.8, 1.0, 1.2, 1.4, 1.6])
    y = 150 + 217 * x + np.array([1.0, -1.0, 0.0, 1.0, -1.0])
    f = reg.fit_line(x, y)
    # Closed form: slope = Sxy/Sxx, residual sd from 3 dof
    sxx = ((x - x.mean()) ** 2).sum()
    slope = ((x - x.mean()) * (y - y.mean())).sum() / sxx
    assert f["slope"] == pytest.approx(slope)
    assert f["intercept"] == pytest.approx(y.mean() - slope * x.mean())
    res = y - f["intercept"] - f["slope"] * x
    s = np.sqrt((res**2).sum() / 3)
    assert f["slope_se"] == pytest.approx(s / np.sqrt(sxx))
    from scipy.stats import t
    half = t.ppf(0.975, 3) * s / np.sqrt(sxx)
    assert (f["slope_ci_low"], f["slope_ci_high"]) == pytest.approx((slope - half, slope + half))
    se_b = s * np.sqrt(1 / 5 + x.mean() ** 2 / sxx)  # intercept standard error, closed form
    assert f["intercept_se"] == pytest.approx(se_b)
    assert (f["intercept_ci_low"], f["intercept_ci_high"]) == pytest.approx(
        (f["intercept"] - t.ppf(0.975, 3) * se_b, f["intercept"] + t.ppf(0.975, 3) * se_b))
    assert f["n"] == 5 and f["r_squared"] > 0.99 and f["reason"] is None


def test_fit_mean_t_interval():
    from scipy.stats import t

    y = [1.0, 2.0, 4.0, 7.0]
    m = reg.fit_mean(y)
    sd = float(np.std(y, ddof=1))
    half = t.ppf(0.975, 3) * sd / 2
    assert m["mean"] == 3.5 and m["sd"] == pytest.approx(sd) and m["se"] == pytest.approx(sd / 2)
    assert (m["ci_low"], m["ci_high"]) == pytest.approx((3.5 - half, 3.5 + half))


def test_pooled_runs_say_so_in_the_note():
    # three pressures, each at its own load: no load level varies the pressure, so the runs are pooled
    rows = [run("T9", 10.0, p, 100 + 200 * p, 1.0, load_kN=load) for p, load in ((0.8, 16.0), (1.1, 18.3), (1.4, 22.6))]
    fit = reg.pressure_regressions(pd.DataFrame(rows))
    r = fit.query("tyre_id == 'T9' and condition == 'rolling'").iloc[0]
    assert r.note == "pooled over load_kN (no single level varies the regressor)"
    assert r.slope == pytest.approx(200.0)
    assert fit.query("tyre_id == 'T9' and condition == 'stationary'")["note"].isna().all()


def test_fit_line_degenerate():
    f = reg.fit_line([1.0, 1.0], [2.0, 3.0])
    assert np.isnan(f["slope"]) and f["n"] == 2 and "fewer than 2" in f["reason"]
    f2 = reg.fit_line([1.0, 2.0], [2.0, 4.0])
    assert f2["slope"] == pytest.approx(2.0) and np.isnan(f2["slope_se"]) and f2["r_squared"] == pytest.approx(1)


def test_pressure_regressions_recover_known_lines(results):
    fit = reg.pressure_regressions(results)
    assert len(fit) == 4
    for _, r in fit.iterrows():
        kc, dk = TRUTH[r.tyre_id][r.condition]
        assert r.intercept == pytest.approx(kc, abs=1e-6)
        assert r.slope == pytest.approx(dk, abs=1e-6)
        assert r.n == (4 if r.condition == "stationary" else 8)


def test_pressure_regressions_holds_load_constant():
    df = make_results()
    # an extra run at another load and the same pressure must not enter the fit
    df = pd.concat([df, pd.DataFrame([run("T3", 10.0, 1.38, 999.0, 9.0, load_kN=22.6)])])
    fit = reg.pressure_regressions(df)
    r = fit.query("tyre_id == 'T3' and condition == 'rolling'").iloc[0]
    assert r.slope == pytest.approx(177.0) and r.held_load_kN == pytest.approx(18.3)


def test_tyre_with_one_pressure_gets_row_with_reason():
    df = pd.concat([make_results(), pd.DataFrame([run("NEW1", 10.0, 1.2, 300.0, 1.0),
                                                   run("NEW1", 15.0, 1.2, 301.0, 1.0)])])
    fit = reg.pressure_regressions(df)
    r = fit.query("tyre_id == 'NEW1' and condition == 'rolling'").iloc[0]
    assert r.n == 2 and np.isnan(r.slope) and "distinct" in r.reason
    s = fit.query("tyre_id == 'NEW1' and condition == 'stationary'").iloc[0]
    assert s.n == 0 and isinstance(s.reason, str)


def test_pressure_regressions_by_speed(results):
    fit = reg.pressure_regressions(results, reg.DAMPING, by="speed")
    r = fit.query("tyre_id == 'T3' and speed_km_h == 15").iloc[0]
    assert r.intercept == pytest.approx(0.67 - 0.15) and r.slope == pytest.approx(0.36)


def test_table_iii_side_by_side_includes_new_and_thesis_only_tyres(results):
    df = pd.concat([results, pd.DataFrame([run("NEW1", 10.0, 1.2, 300.0, 1.0)])])
    t = reg.table_iii(reg.pressure_regressions(df), PUBLISHED_III)
    r = t.query("tyre_id == 'T3' and condition == 'rolling'").iloc[0]
    assert r.thesis_carcass_stiffness_kN_per_m == 112 and r.carcass_stiffness_kN_per_m == pytest.approx(112)
    assert r.pressure_dependence_kN_per_m_bar_difference == pytest.approx(0.0, abs=1e-6)
    new = t.query("tyre_id == 'NEW1'")
    assert len(new) == 2 and new.thesis_carcass_stiffness_kN_per_m.isna().all()
    assert not new.in_thesis.any()
    assert t.query("tyre_id == 'AS9'").carcass_stiffness_kN_per_m.isna().all()
    assert "thesis_r_squared_qualifier" in t.columns


def test_factor_regressions_amplitude_rate():
    rows = []
    for speed in (0.0, 10.0):
        rate = -15.5 if speed == 0 else -1.09   # thesis Table IV, tyre F1
        for a in (4.0, 10.0, 20.0, 30.0):
            rows.append(run("F1", speed, 1.38, 200 + rate * a, 1.0 + 0.018 * a, amplitude_mm_pp=a))
            rows.append(run("F1", speed, 1.0, 150 + rate * a, 1.0, amplitude_mm_pp=a if a < 20 else 14.0))
    rates = reg.factor_regressions(pd.DataFrame(rows), "amplitude")
    k = rates.query("response == 'stiffness_kN_per_m'").set_index("speed_km_h")
    assert k.loc[0.0, "slope"] == pytest.approx(-15.5) and k.loc[10.0, "slope"] == pytest.approx(-1.09)
    assert k.loc[0.0, "held_pressure_bar"] == pytest.approx(1.38)
    assert list(rates.columns[:6]) == ["tyre_id", "speed_km_h", "response", "factor", "factor_unit", "rate_unit"]
    c = rates.query("response == 'damping_kN_s_per_m' and speed_km_h == 10").iloc[0]
    assert c.slope == pytest.approx(0.018) and c.rate_unit == "kNs/m per mm"
    t4 = reg.amplitude_table(rates, pd.DataFrame({"tyre_id": ["F1"], "speed_km_h": [10],
                             "stiffness_rate_kN_per_m_per_mm": [-1.09], "r_squared": [0.53]}),
                             reg.STIFFNESS)
    r = t4.query("speed_km_h == 10").iloc[0]
    assert r.stiffness_rate_kN_per_m_per_mm_difference == pytest.approx(0, abs=1e-9)


def test_surface_effects_matched_percent():
    rows = []
    for p in (1.0, 1.38):
        rows.append(run("T5", 10.0, p, 400.0 * p, 2.0))
        rows.append(run("T5", 10.0, p, 0.9 * 400.0 * p, 2.4, surface="Artificial rough track"))
    rows.append(run("T5", 5.0, 1.0, 380.0, 2.0, surface="stubble field"))  # no concrete partner
    cells, summary = reg.surface_effects(pd.DataFrame(rows), reg.STIFFNESS)
    s = summary.set_index("surface")
    assert s.loc["artificial rough track", "change_percent"] == pytest.approx(-10.0)
    assert s.loc["artificial rough track", "n_cells"] == 2
    assert s.loc["stubble field", "n_cells"] == 0 and "no concrete" in s.loc["stubble field", "reason"]
    _, sd = reg.surface_effects(pd.DataFrame(rows), reg.DAMPING)
    t9 = reg.surface_table(sd, pd.DataFrame({"surface": ["Artificial Rough Track", "Stubble Field"],
                                              "damping_change_percent": ["-", "+20%"]}), reg.DAMPING)
    r = t9.set_index("surface")
    assert r.loc["artificial_rough_track", "damping_change_percent"] == pytest.approx(20.0)
    assert np.isnan(r.loc["artificial_rough_track", "thesis_damping_change_percent"])
    assert r.loc["stubble_field", "thesis_damping_change_percent"] == 20.0


def test_summary_rates_against_known_values(results):
    by_speed = reg.pressure_regressions(results, reg.STIFFNESS, by="speed")
    rates = reg.factor_regressions(results, "amplitude")
    from tyrelab.published import read_published

    t6 = reg.summary_rates(by_speed, rates, reg.STIFFNESS, published=read_published("table_vi")).set_index("factor")
    # rolling dKp of T3 177 and F1 134 -> mean 155.5; speed 0->15 change at 1.38 bar
    assert t6.loc["pressure", "value"] == pytest.approx((177 + 134) / 2)
    d0 = np.mean([(112 + 177 * 1.38) - (184 + 200 * 1.38), (-3 + 134 * 1.38) - (96 + 158 * 1.38)])
    assert t6.loc["rolling_speed_0_15", "value"] == pytest.approx(d0)
    assert t6.loc["rolling_speed_10_15", "value"] == pytest.approx(0.0, abs=1e-9)
    assert t6.loc["pressure", "thesis_value"] == 190.0  # from raw/published/table_vi.csv
    assert t6.loc["load", "thesis_value"] == 0.0  # "(none)"
    bare = reg.summary_rates(by_speed, rates, reg.STIFFNESS)
    assert bare["thesis_value"].isna().all()  # no thesis numbers live in the code
    assert list(bare.columns[:7]) == ["factor", "measured_range", "unit", "thesis_value", "thesis_change_text",
                                      "value", "value_difference"]  # the documented layout


def test_measured_scatter_around_one_set_level_is_not_a_sweep():
    # Runs all set to 14 mm p-p: the measured amplitudes scatter by ±0.1 mm, which
    # must not produce an amplitude rate (it did: thousands of kN/m per mm).
    rows = [run("AS1", 10.0, 1.2, 300.0 + d, 1.0) for d in (0.0, 3.0, -2.0)]
    df = pd.DataFrame(rows)
    df["amplitude_measured_mm_pp"] = [13.9, 14.0, 14.1]
    fit = reg.factor_regressions(df, "amplitude")
    r = fit.query("tyre_id == 'AS1' and response == 'stiffness_kN_per_m'").iloc[0]
    assert np.isnan(r.slope) and r.n == 3 and "set levels" in r.reason
