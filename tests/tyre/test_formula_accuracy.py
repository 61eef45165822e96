import numpy as np
import pandas as pd
import pytest

from tyrelab.tyre import formula_accuracy as fa
from tyrelab.tyre.stiffness import traction_tyre_stiffness
from tests.tyre.thesis_tables import table_iii, tyres
from tests.tyre.tyre_synthetic import run


def test_normal_probabilities_match_thesis_statements():
    # thesis §4.5.3: N(3, 10) -> "65 %", N(17, 24) -> "25 %"
    assert fa.p_within(3, 10) == pytest.approx(0.66, abs=0.01)
    assert fa.p_within(17, 24) == pytest.approx(0.25, abs=0.01)
    assert fa.p_within(0, 10) == pytest.approx(0.6827, abs=1e-4)


def test_formula_error_is_zero_for_a_tyre_that_follows_the_formula():
    # a 13.6R38 tyre of age 4 whose rolling line is the formula itself
    kc = 172 - 1.77 * 38 + 5.6 * 4
    t = pd.DataFrame({"tyre_id": ["X"], "size": ["13.6R38"], "condition": ["rolling"],
                      "carcass_stiffness_kN_per_m": [kc], "pressure_dependence_kN_per_m_bar": [0.34 * 13.6 * 38]})
    pred = fa.predictions_from_table(t, pd.DataFrame({"tyre_id": ["X"], "age_years": [4], "position": ["rear"]}))
    assert len(pred) == 5 and np.allclose(pred.formula_error_percent, 0.0)
    assert pred.stationary_error_percent.isna().all()


def test_published_table_iii_accuracy():
    pred = fa.predictions_from_table(table_iii(), tyres())
    assert "F1" not in set(pred.tyre_id) and pred.tyre_id.nunique() == 16
    s = fa.accuracy_summary(pred, "published").set_index("method")
    assert s.loc["formula", "n"] == 80
    assert s.loc["stationary", "n_tyres"] == 13
    # measured literal check of one cell: T3 at 1.2 bar
    r = pred.query("tyre_id == 'T3' and pressure_bar == 1.2").iloc[0]
    assert r.measured_kN_per_m == pytest.approx(112 + 177 * 1.2)
    assert r.formula_kN_per_m == pytest.approx(traction_tyre_stiffness("13.6R38", 1.2, 4))
    assert r.stationary_kN_per_m == pytest.approx(184 + 200 * 1.2)
    assert np.isfinite(s.loc["formula", "mean_error_percent"])
    # the printed §4.5.3 figures beside ours, and every difference ours - thesis (non-zero here)
    printed = {"formula": (3.0, 10.0, 0.65, 56), "stationary": (17.0, 24.0, 0.25, None)}
    for method, (mean, sd, p, n) in printed.items():
        row = s.loc[method]
        assert (row.thesis_mean_error_percent, row.thesis_sd_error_percent, row.thesis_p_within_10_percent) == (mean, sd, p)
        assert row.thesis_n == n or (n is None and pd.isna(row.thesis_n))
        assert row.thesis_p_within_10_percent_from_printed_moments == pytest.approx(fa.p_within(mean, sd), rel=1e-12)
        # ours is the normal-theory P (the column the report pairs it with is not found by name)
        assert row.p_within_10_percent_difference == pytest.approx(row.p_within_10_percent_normal - p, abs=1e-12)
        assert abs(row.p_within_10_percent_difference) > 1e-3
    from tests.comparisons import assert_differences_are_ours_minus_thesis

    assert assert_differences_are_ours_minus_thesis(s.reset_index(), "formula accuracy") >= 4


def test_predictions_from_recordings_use_measured_pressures():
    rows = [run("T3", 10.0, p, 112 + 177 * p, 1.0) for p in (0.8, 1.2, 1.6)]
    rows += [run("F1", 10.0, p, 200.0, 1.0) for p in (0.8, 1.2)]
    ours = pd.DataFrame({"tyre_id": ["T3", "T3"], "condition": ["stationary", "rolling"],
                         "carcass_stiffness_kN_per_m": [184.0, 112.0], "pressure_dependence_kN_per_m_bar": [200.0, 177.0]})
    pred = fa.predictions_from_recordings(pd.DataFrame(rows), ours, tyres())
    assert list(pred.pressure_bar) == [0.8, 1.2, 1.6] and set(pred.tyre_id) == {"T3"}
    assert pred.stationary_error_percent.iloc[0] == pytest.approx(100 * ((184 + 160) / (112 + 177 * 0.8) - 1))
    # the formula from the tyres table's size and age of T3 (13.6R38, 4 years, Table II)
    t3 = tyres().set_index("tyre_id").loc["T3"]
    assert (t3["size"], t3["age_years"]) == ("13.6R38", 4)
    np.testing.assert_allclose(pred.formula_kN_per_m, [traction_tyre_stiffness("13.6R38", p, 4) for p in (0.8, 1.2, 1.6)],
                               rtol=1e-12)
    assert not pred.age_assumed.any()


def test_accuracy_of_a_single_prediction_has_a_mean_but_no_sd_and_no_warning():
    import warnings

    import numpy as np
    import pandas as pd

    from tyrelab.tyre import formula_accuracy as fa

    pred = pd.DataFrame({"tyre_id": ["T1"], "formula_error_percent": [4.0], "stationary_error_percent": [np.nan]})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s = fa.accuracy_summary(pred, "test").set_index("method")
    assert s.loc["formula", "mean_error_percent"] == 4.0 and np.isnan(s.loc["formula", "sd_error_percent"])


def test_pressure_grids_and_error_percent():
    # rear tyres on 0.8-1.6 bar, front traction tyres on 1.0-2.0 bar (thesis §4.5.3); error = 100 (f - m) / m
    kc, dk = 172 - 1.77 * 38 + 5.6 * 4, 0.34 * 13.6 * 38
    t = pd.DataFrame({"tyre_id": ["R", "F"], "size": ["13.6R38", "13.6R38"], "condition": ["rolling", "rolling"],
                      "carcass_stiffness_kN_per_m": [1.25 * kc, 1.25 * kc],
                      "pressure_dependence_kN_per_m_bar": [1.25 * dk, 1.25 * dk]})
    tyres_ = pd.DataFrame({"tyre_id": ["R", "F"], "age_years": [4, 4], "position": ["rear", "front"]})
    pred = fa.predictions_from_table(t, tyres_).set_index("tyre_id")
    assert list(pred.loc["R", "pressure_bar"]) == [0.8, 1.0, 1.2, 1.4, 1.6]
    assert list(pred.loc["F", "pressure_bar"]) == [1.0, 1.25, 1.5, 1.75, 2.0]
    np.testing.assert_allclose(pred["formula_error_percent"], 100 * (1 / 1.25 - 1))  # -20 %


def test_formula_error_model_interval_is_the_t_prediction_interval_of_the_errors():
    """mean ± t_{n_tyres-1} sd sqrt(1 + 1/n_tyres), mapped from the error e = 100 (F - M)/M back to M:
    a tyre measured at the interval's low end has the largest error, e_hi, exactly."""
    from scipy.stats import t as student_t

    # three rear 13.6R38 tyres whose rolling lines are the formula over 0.9, 1.0 and 1.25:
    # errors 100 (s - 1) at every grid pressure, 5 points each
    scales = {"A": 0.9, "B": 1.0, "C": 1.25}
    kc, dk = 172 - 1.77 * 38 + 5.6 * 4, 0.34 * 13.6 * 38
    table = pd.DataFrame({"tyre_id": list(scales), "size": "13.6R38", "condition": "rolling",
                          "carcass_stiffness_kN_per_m": [kc / s for s in scales.values()],
                          "pressure_dependence_kN_per_m_bar": [dk / s for s in scales.values()]})
    tyres_ = pd.DataFrame({"tyre_id": list(scales), "age_years": 4, "position": "rear"})
    m = fa.formula_error_model(table, tyres_)
    errors = np.repeat([100 * (s - 1) for s in scales.values()], 5)
    assert (m.n, m.n_tyres) == (15, 3)
    assert m.mean_error_percent == pytest.approx(errors.mean(), abs=1e-9)
    assert m.sd_error_percent == pytest.approx(errors.std(ddof=1), rel=1e-12)
    k = student_t.ppf(0.975, 2)  # 4.303
    assert m.coverage_factor() == pytest.approx(k, rel=1e-12)
    assert m.coverage_factor(0.5) == pytest.approx(student_t.ppf(0.75, 2), rel=1e-12)
    half = k * m.sd_error_percent * np.sqrt(1 + 1 / 3)
    lo, hi = m.interval(300.0)
    assert 100 * (300.0 - lo) / lo == pytest.approx(m.mean_error_percent + half, rel=1e-12)
    assert 100 * (300.0 - hi) / hi == pytest.approx(m.mean_error_percent - half, rel=1e-12)
    assert m.standard_uncertainty(300.0) == pytest.approx((hi - lo) / (2 * k), rel=1e-12)
    for level in (0.0, 1.0):
        with pytest.raises(ValueError, match="level"):
            m.coverage_factor(level)
    with pytest.raises(ValueError, match="too few formula predictions"):
        fa.formula_error_model(table.assign(size="huge"), tyres_)
