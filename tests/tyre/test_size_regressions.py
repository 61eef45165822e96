import numpy as np
import pytest

from tyrelab.tyre import size_regressions as sr
from tests.tyre.thesis_tables import table_iii, tyres


def test_points_use_table_ii_sizes_and_wr():
    p = sr.tyre_points(table_iii(), tyres())
    as11 = p.loc[p.tyre_id == "AS11"].iloc[0]
    assert as11.size_used == "13.6-38" and as11.size_in_table == "13.6R38"
    assert as11.wr_in2 == pytest.approx(13.6 * 38)


def test_analytic_line_is_recovered():
    import pandas as pd
    t = pd.DataFrame({"tyre_id": ["A", "B", "C"], "condition": "rolling",
                      "size": ["10R20", "10R30", "20R40"], "carcass_stiffness_kN_per_m": [100, 100, 100],
                      "pressure_dependence_kN_per_m_bar": [0.3 * 200 + 5, 0.3 * 300 + 5, 0.3 * 800 + 5]})
    out = sr.size_regressions(t, None, "test").set_index("fit")
    assert out.loc["dkp_vs_wr", "slope"] == pytest.approx(0.3) and out.loc["dkp_vs_wr", "intercept"] == pytest.approx(5)


def test_published_table_iii_reproduces_wr_gradient_and_r2():
    out = sr.size_regressions(table_iii(), tyres(), "published").set_index("fit")
    wr = out.loc["dkp_vs_wr"]
    assert wr.slope == pytest.approx(0.34, abs=0.01)
    assert wr.r_squared == pytest.approx(0.82, abs=0.01)
    assert wr.n == 16 and "F1" not in wr.tyres_used.split(",")
    assert wr.reproduces_printed and "not a slipped 29.7" in wr.finding
    assert wr.intercept == pytest.approx(0.53, abs=0.01)
    assert "AS11 13.6R38 vs 13.6-38" in wr.finding and "no effect" in wr.finding
    # the finding prints the fit's own numbers, the intercept with its interval where one is printed
    assert wr.finding.startswith(
        f"reproduced: slope {wr.slope:.3g} (printed 0.34); r² {wr.r_squared:.3g} (printed 0.82); intercept "
        f"{wr.intercept:.3g} [95 % CI {wr.intercept_ci_low:.3g}, {wr.intercept_ci_high:.3g}] (printed 0.297); n=16. ")
    age = out.loc["kc_vs_age"]
    assert age.finding.startswith(f"NOT reproduced: slope {age.slope:.3g} (printed 5.6); n=5. ")  # no intercept printed
    assert "29.7" not in age.finding and "29.7" not in out.loc["kc_vs_rim", "finding"]  # a ΔK_p argument only
    # with the printed gradient the least-squares intercept is mean(y) - 0.34 mean(x): 29.7 lies that far above
    sub = sr.select(sr.tyre_points(table_iii(), tyres()), sr.THESIS_FITS["dkp_vs_wr"])
    given = sub["pressure_dependence_kN_per_m_bar"].mean() - 0.34 * sub["wr_in2"].mean()
    assert f"intercept is {given:.2g} kN/m/bar; an intercept of 29.7 would put the line {29.7 - given:.0f} kN/m/bar " \
        "above" in wr.finding and abs(given) > 1  # (+/- differ by 2|given|)


def test_published_rim_fit_coefficients_close_but_r2_not():
    out = sr.size_regressions(table_iii(), tyres(), "published").set_index("fit")
    r = out.loc["kc_vs_rim"]
    assert r.intercept == pytest.approx(172, abs=1) and r.slope == pytest.approx(-1.77, abs=0.05)
    assert r.r_squared == pytest.approx(0.63, abs=0.01)          # printed 0.70
    assert not r.reproduces_printed and "NOT reproduced" in r.finding
    # the printed values of §4.5.3 beside ours, differences ours - thesis
    assert (r.thesis_intercept, r.thesis_slope, r.thesis_r_squared) == (172.0, -1.77, 0.70)
    from tests.comparisons import assert_differences_are_ours_minus_thesis

    assert assert_differences_are_ours_minus_thesis(out.reset_index(), "size regressions") >= 5


def test_a_selection_with_one_size_is_not_computable():
    """Two tyres of the same size: n = 2 but one distinct W R and rim, so no line (slope NaN) and a finding
    that says why, not a 'NOT reproduced' with NaN numbers."""
    import pandas as pd

    t = pd.DataFrame({"tyre_id": ["A", "B"], "condition": "rolling", "size": "13.6R38",
                      "carcass_stiffness_kN_per_m": [100.0, 110.0], "pressure_dependence_kN_per_m_bar": [150.0, 160.0]})
    out = sr.size_regressions(t, pd.DataFrame({"tyre_id": ["A", "B"], "age_years": [2, 2]}), "test").set_index("fit")
    assert out.loc["dkp_vs_wr", "n"] == 2 and np.isnan(out.loc["dkp_vs_wr", "slope"])
    for fit in out.index:
        assert out.loc[fit, "finding"].startswith("not computable: fewer than 2 distinct regressor values"), fit


def test_published_age_fit_is_4_6_not_5_6():
    out = sr.size_regressions(table_iii(), tyres(), "published").set_index("fit")
    a = out.loc["kc_vs_age"]
    assert a.n == 5 and a.slope == pytest.approx(4.57, abs=0.01)
    search = sr.selection_search(sr.tyre_points(table_iii(), tyres()), "kc_vs_age", max_excluded=1)
    without_t2 = search.loc[search.change == "also excluding T2"].iloc[0]
    assert without_t2.slope == pytest.approx(6.32, abs=0.01)


def test_empty_table_gives_rows_with_reasons():
    import pandas as pd
    out = sr.size_regressions(pd.DataFrame(columns=table_iii().columns), None, "ours")
    assert len(out) == 3 and out["slope"].isna().all()


def test_findings_name_the_numbers_the_variants_and_the_closest_selection():
    points = sr.tyre_points(table_iii(), tyres())
    out = sr.size_regressions(table_iii(), tyres(), "published").set_index("fit")
    assert "slope 0.334 (printed 0.34)" in out.loc["dkp_vs_wr", "finding"]
    var = sr.variants(points, "kc_vs_rim")
    assert list(var["variant"]) == ["rolling, printed exclusions", "stationary, printed exclusions",
                                    "pooled, printed exclusions", "rolling, through the origin"]
    search = sr.selection_search(points, "kc_vs_rim", max_excluded=3)
    # sorted: reproducing selections first, then by |slope - printed| / |printed| + |r² - printed|
    d = (search["slope"] + 1.77).abs() / 1.77 + (search["r_squared"] - 0.70).abs()
    np.testing.assert_allclose(search["distance"], d)
    rest = search.loc[~search["matches_printed"], "distance"].to_numpy()
    assert np.all(np.diff(rest) >= 0)
    if not search["matches_printed"].any():
        assert f"closest: {search.iloc[0].change} " in out.loc["kc_vs_rim", "finding"]


def test_a_fit_matches_only_within_the_printed_precision():
    spec = sr.THESIS_FITS["dkp_vs_wr"]
    assert sr._matches({"intercept": 0.3, "slope": 0.34, "r_squared": 0.82}, spec)
    assert not sr._matches({"intercept": 0.3, "slope": 0.34, "r_squared": 0.70}, spec)
    assert not sr._matches({"intercept": 0.3, "slope": 0.36, "r_squared": 0.82}, spec)


def test_selection_search_fits_are_the_least_squares_lines():
    """The search's closed-form fits are fit_line's (ordinary least squares) on the same tyres."""
    import pandas as pd

    from tyrelab.tyre.regressions import fit_line

    points = sr.tyre_points(table_iii(), tyres())
    spec = sr.THESIS_FITS["kc_vs_rim"]
    base = sr.select(points, spec)
    search = sr.selection_search(points, "kc_vs_rim", max_excluded=1)
    assert len(search) == base["tyre_id"].nunique() + 1 + len(spec["exclude"])
    every = sr.select(points, spec, exclude=())
    for row in search.itertuples():
        if row.change.startswith("including "):  # an excluded tyre put back
            sub = pd.concat([base, every.loc[every["tyre_id"] == row.change.removeprefix("including ")]])
            assert len(sub) == len(base) + 1, row.change
        else:
            ex = row.change.removeprefix("also excluding ").split(",") if row.change != "as printed" else []
            sub = base.loc[~base["tyre_id"].isin(ex)]
        f = fit_line(sub[spec["x"]], sub[spec["y"]])
        assert (row.intercept, row.slope, row.r_squared) == pytest.approx((f["intercept"], f["slope"], f["r_squared"]),
                                                                         rel=1e-9), row.change
    # the variants: the printed selection under other conditions (fit_line), and through the origin
    var = sr.variants(points, "kc_vs_rim").set_index("variant")
    for cond in ("rolling", "stationary", "pooled"):
        sub = sr.select(points, spec, condition=cond)
        f = fit_line(sub[spec["x"]], sub[spec["y"]])
        assert var.loc[f"{cond}, printed exclusions", "slope"] == pytest.approx(f["slope"], rel=1e-12)
    x, y = base[spec["x"]].to_numpy(float), base[spec["y"]].to_numpy(float)
    origin = var.loc["rolling, through the origin"]
    assert origin.intercept == 0.0 and origin.slope == pytest.approx(x @ y / (x @ x), rel=1e-12)


def test_quick_fit_of_two_points_and_of_degenerate_data():
    """Two points one unit apart give their line; no spread in x gives no line, and constant y gives
    no r², both quietly (no 0/0 warnings)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        f = sr._quick_fit([2.0, 3.0], [10.0, 12.0])
        assert (f["intercept"], f["slope"], f["r_squared"]) == pytest.approx((6.0, 2.0, 1.0), rel=1e-12)
        f = sr._quick_fit([2.0, 2.0, 2.0], [1.0, 2.0, 3.0])
        assert np.isnan(f["slope"]) and np.isnan(f["intercept"]) and np.isnan(f["r_squared"])
        f = sr._quick_fit([1.0, 2.0, 3.0], [5.0, 5.0, 5.0])
        assert f["slope"] == 0.0 and f["intercept"] == 5.0 and np.isnan(f["r_squared"])


def test_selection_search_equals_the_pandas_subset_loop():
    """The masked numpy search gives the rows of excluding each combination with pandas, bit for bit."""
    import itertools

    points = sr.tyre_points(table_iii(), tyres())
    spec = sr.THESIS_FITS["kc_vs_rim"]
    base = sr.select(points, spec)
    ids = sorted(base["tyre_id"].unique())
    expected = []
    for k in range(3):
        for ex in itertools.combinations(ids, k):
            sub = base.loc[~base["tyre_id"].isin(ex)]
            f = sr._quick_fit(sub[spec["x"]], sub[spec["y"]])
            expected.append(("as printed" if not ex else "also excluding " + ",".join(ex), f["n"], f["slope"],
                             f["intercept"], f["r_squared"]))
    got = sr.selection_search(points, "kc_vs_rim", max_excluded=2)
    rows = {r.change: (r.change, r.n, r.slope, r.intercept, r.r_squared) for r in got.itertuples()}
    assert len(expected) > 20
    for e in expected:
        assert rows[e[0]][:2] == e[:2]
        np.testing.assert_array_equal(rows[e[0]][2:], e[2:])
