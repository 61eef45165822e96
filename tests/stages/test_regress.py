"""The regress stage: tables written, thesis side by side, new tyres, degenerate inputs."""

import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tests.comparisons import assert_differences_are_ours_minus_thesis

from tyrelab.stages import regress
from tyrelab.stages.base import Context

REPO_RAW = Path(__file__).resolve().parents[2] / "raw"
TABLES = ["table_iii", "table_iv", "table_v", "table_vi", "table_vii", "table_viii", "table_ix", "table_x",
          "size_regressions", "formula_accuracy", "spoke_speed", "spoke_frequency", "spoke_amplitude",
          "spoke_deflection", "spoke_fit", "stiffness_pressure_by_speed"]


def _run(tyre_id, speed, p, k, c, **kw):
    row = dict(campaign="c", run_id=f"{tyre_id}-{speed}-{p}-{kw}", tyre_id=tyre_id, kind="measurement",
               speed_km_h=speed, pressure_bar=p, load_kN=18.3, excitation_frequency_Hz=4.0,
               amplitude_mm_pp=14.0, torque_kNm=0.0, surface="concrete", axle_mass_kg=1200.0,
               recorded_on="1989-06-01", rolling=speed > 0, excitation_frequency_measured_Hz=4.0,
               stiffness_kN_per_m=k, damping_kN_s_per_m=c, welch_stiffness_kN_per_m=k,
               welch_damping_kN_s_per_m=c, amplitude_measured_mm_pp=14.0, coherence=0.99,
               qc_ok=True, qc_reasons="")
    row.update(kw)
    return row


def _results():
    rows = []
    for v in (0.0, 10.0, 15.0):
        for p in (0.8, 1.1, 1.4, 1.6):   # T3 as Table III / VII
            kc, dk = (184, 200) if v == 0 else (112, 177)
            cc, dc = {0.0: (1.2, 0.4), 10.0: (0.67, 0.31), 15.0: (0.67, 0.36)}[v]
            rows.append(_run("T3", v, p, kc + dk * p, cc + dc * p))
        for a in (6.0, 20.0, 28.0):
            rows.append(_run("T3", v, 1.4, 112 + 177 * 1.4 + 0.8 * (a - 14), 1.1, amplitude_mm_pp=a,
                             amplitude_measured_mm_pp=a))
    rows.append(_run("T3", 10.0, 1.4, 0.9 * (112 + 177 * 1.4), 1.3, surface="Artificial Rough Track"))
    rows.append(_run("NEW9", 10.0, 1.2, 310.0, 1.0))       # a tyre not in the thesis, one pressure
    rows.append(_run("NEW9", 12.0, 1.2, 305.0, 0.9))
    return pd.DataFrame(rows)


@pytest.fixture
def ctx(tmp_path):
    raw = tmp_path / "raw"
    (raw / "published").mkdir(parents=True)
    for f in (REPO_RAW / "published").glob("table_*.csv"):
        shutil.copy(f, raw / "published" / f.name)
    if (REPO_RAW / "tyres.csv").exists():
        shutil.copy(REPO_RAW / "tyres.csv", raw / "tyres.csv")
    c = Context(raw=raw, build=tmp_path / "build", jobs=1)
    c.write_table("results", _results())
    return c


def test_writes_every_table(ctx):
    res = regress.run(ctx)
    for t in TABLES:
        assert ctx.has_table(t), t
    assert res.n_in == len(_results())


def test_table_iii_side_by_side(ctx):
    regress.run(ctx)
    t = ctx.read_table("table_iii")
    r = t.query("tyre_id == 'T3' and condition == 'rolling'").iloc[0]
    assert r.carcass_stiffness_kN_per_m == pytest.approx(112) and r.pressure_dependence_kN_per_m_bar == pytest.approx(177)
    if (ctx.raw / "published" / "table_iii.csv").exists():
        assert r.thesis_carcass_stiffness_kN_per_m == 112
        assert r.carcass_stiffness_kN_per_m_difference == pytest.approx(0, abs=1e-6)
        assert t.query("tyre_id == 'AS9'").carcass_stiffness_kN_per_m.isna().all()
    new = t.query("tyre_id == 'NEW9'")
    assert set(new.condition) == {"stationary", "rolling"}
    assert new.thesis_carcass_stiffness_kN_per_m.isna().all() and new.carcass_stiffness_kN_per_m.isna().all()
    assert new.reason.notna().all()
    assert {"carcass_stiffness_kN_per_m_se", "carcass_stiffness_kN_per_m_ci_low", "n"} <= set(t.columns)


def test_other_tables(ctx):
    regress.run(ctx)
    t7 = ctx.read_table("table_vii").query("tyre_id == 'T3' and speed_km_h == 15").iloc[0]
    assert t7.carcass_damping_kN_s_per_m == pytest.approx(0.67) and t7.pressure_dependence_kN_s_per_m_bar == pytest.approx(0.36)
    t4 = ctx.read_table("table_iv").query("tyre_id == 'T3' and speed_km_h == 10").iloc[0]
    assert t4.stiffness_rate_kN_per_m_per_mm == pytest.approx(0.8)
    t5 = ctx.read_table("table_v").set_index("surface")
    assert t5.loc["artificial_rough_track", "stiffness_change_percent"] == pytest.approx(-10)
    fit = ctx.read_table("spoke_fit").set_index("tyre_id")
    assert {"T3", "NEW9"} <= set(fit.index)
    sp = ctx.read_table("spoke_speed").query("model == 'combined' and speed_km_h >= 1")
    assert np.all(np.diff(sp.sort_values("speed_km_h").damping_N_s_per_m) < 0)


@pytest.mark.skipif(not (REPO_RAW / "published" / "table_iii.csv").exists(), reason="published Table III not digitised")
def test_published_wr_regression_reproduces_thesis(ctx):
    regress.run(ctx)
    s = ctx.read_table("size_regressions").set_index(["source", "fit"])
    wr = s.loc[("published", "dkp_vs_wr")]
    assert wr.slope == pytest.approx(0.34, abs=0.01) and wr.r_squared == pytest.approx(0.82, abs=0.01)
    acc = ctx.read_table("formula_accuracy").set_index(["source", "method"])
    assert acc.loc[("published", "formula"), "n_tyres"] == 16


def test_no_results_no_published(tmp_path):
    (tmp_path / "raw" / "published").mkdir(parents=True)  # a raw folder with an empty published/ overrides the shipped tables
    c = Context(raw=tmp_path / "raw", build=tmp_path / "build", jobs=1)
    res = regress.run(c)
    assert c.has_table("table_iii") and c.read_table("table_iii").empty
    assert len(c.read_table("size_regressions")) == 3
    assert res.n_in == 0


def test_shipped_published_tables_used_when_raw_has_none(tmp_path):
    c = Context(raw=tmp_path / "elsewhere", build=tmp_path / "build", jobs=1)
    regress.run(c)
    t3 = c.read_table("table_iii")
    assert t3["thesis_carcass_stiffness_kN_per_m"].notna().sum() >= 30
    assert t3["carcass_stiffness_kN_per_m"].isna().all()


def _shifted_results():
    """T3 as in :func:`_results` but every value off the thesis' by a known amount.

    Table III: rolling K_c 112 + 7, ΔK_p 177 + 10; Table VII: C_c + 0.05 at 10 and 15 km/h.
    Damping rises 0.01 kN s/m per mm of amplitude (Table VIII); on pasture grass damping
    rises 30 % (Table IX: +20 %) and stiffness falls 5 % (Table V: -3 %); the stiffness amplitude rate is 0.8 (the thesis' T3 rates differ).
    """
    rows = []
    for v in (0.0, 10.0, 15.0):
        for p in (0.8, 1.1, 1.4, 1.6):
            kc, dk = (184, 200) if v == 0 else (112 + 7, 177 + 10)
            cc, dc = {0.0: (1.2, 0.4), 10.0: (0.67 + 0.05, 0.31), 15.0: (0.67 + 0.05, 0.36)}[v]
            rows.append(_run("T3", v, p, kc + dk * p, cc + dc * p))
        for a in (6.0, 20.0, 28.0):
            rows.append(_run("T3", v, 1.4, 119 + 187 * 1.4 + 0.8 * (a - 14), 1.1 + 0.01 * (a - 14),
                             amplitude_mm_pp=a, amplitude_measured_mm_pp=a))
    rows.append(_run("T3", 10.0, 1.4, 0.95 * (119 + 187 * 1.4), 1.3 * (0.72 + 0.31 * 1.4), surface="Pasture Grass"))
    return pd.DataFrame(rows)


COMPARISON_TABLES = ["table_iii", "table_iv", "table_v", "table_vi", "table_vii", "table_viii", "table_ix", "table_x",
                     "size_regressions", "formula_accuracy"]


def test_every_comparison_table_gives_ours_minus_thesis_on_non_zero_differences(ctx):
    ctx.write_table("results", _shifted_results())
    regress.run(ctx)
    t3 = ctx.read_table("table_iii").query("tyre_id == 'T3' and condition == 'rolling'").iloc[0]
    assert t3.carcass_stiffness_kN_per_m_difference == pytest.approx(+7.0)
    assert t3.pressure_dependence_kN_per_m_bar_difference == pytest.approx(+10.0)
    t7 = ctx.read_table("table_vii").query("tyre_id == 'T3' and speed_km_h == 15").iloc[0]
    assert t7.carcass_damping_kN_s_per_m_difference == pytest.approx(+0.05)
    t6 = ctx.read_table("table_vi").set_index("factor")
    assert t6.loc["pressure", "value_difference"] == pytest.approx(t6.loc["pressure", "value"] - 190.0)
    assert t6.loc["pressure", "value_difference"] < 0  # ours 187 (rolling T3) vs the thesis' +190 /bar
    t5 = ctx.read_table("table_v").set_index("surface")
    assert t5.loc["pasture_grass", "stiffness_change_percent_difference"] == pytest.approx(-5.0 - (-3.0))
    t9 = ctx.read_table("table_ix").set_index("surface")
    assert t9.loc["pasture_grass", "damping_change_percent_difference"] == pytest.approx(30.0 - 20.0)
    t10 = ctx.read_table("table_x").set_index("factor")
    assert t10.loc["pressure", "value_difference"] == pytest.approx(t10.loc["pressure", "value"] - 0.4)
    for name in COMPARISON_TABLES:
        assert assert_differences_are_ours_minus_thesis(ctx.read_table(name), name) > 0, f"{name}: no non-zero case"


def _mixed_results():
    """:func:`_results` plus tyres that take the other paths of the per-tyre fits: runs with
    their own uncertainties (WLS), two loads none of which varies the pressure (pooled), only
    failed-QC runs, and a tyre missing from the catalogue."""
    rows = _results().to_dict("records")
    rng = np.random.default_rng(3)
    for p in (0.8, 1.1, 1.4, 1.6):
        for v in (0.0, 10.0):
            rows.append(_run("T5", v, p, 300 + 150 * p + rng.normal(0, 3), 1.0 + 0.3 * p + rng.normal(0, 0.02),
                             stiffness_u_N_per_m=float(rng.uniform(500, 5000)),
                             damping_u_N_s_per_m=float(rng.uniform(5, 50))))
    for p, load in ((0.9, 15.0), (1.3, 20.0)):
        rows.append(_run("T7", 10.0, p, 250 + 100 * p, 1.1, load_kN=load))
    rows.append(_run("T8", 10.0, 1.2, 280.0, 1.0, qc_ok=False))
    rows.append(_run("ZZ1", 15.0, 1.2, 260.0, 0.95))
    rows.append(_run("ZZ1", 15.0, 1.6, 290.0, 1.05, amplitude_mm_pp=20.0, amplitude_measured_mm_pp=20.5))
    return pd.DataFrame(rows)


def test_tyre_fits_in_one_pass_equal_one_tyre_at_a_time():
    results = _mixed_results()
    tyres = pd.read_csv(REPO_RAW / "tyres.csv")
    ids = sorted(results["tyre_id"].unique())
    each = regress.tyre_fits_each(results, ids, tyres)
    assert set(each) == set(ids)
    for t in ids:
        alone = regress.tyre_fits(results.loc[results["tyre_id"] == t], [t], tyres.loc[tyres["tyre_id"] == t])
        assert set(each[t]) == set(alone)
        for name, df in alone.items():
            pd.testing.assert_frame_equal(each[t][name], df, check_exact=True, obj=f"{t} {name}")
    k = pd.concat([each[t]["k_speed"] for t in ids])
    assert (k["weighting"] != "OLS").any()  # the WLS path is exercised
    assert each["T7"]["k_speed"]["note"].str.startswith("pooled").any()  # and the pooled one
    assert each["T8"]["k_cond"]["n"].eq(0).all() and each["ZZ1"]["spoke_fit"]["size"].isna().all()


def test_progress_counts_every_tyre_then_each_step_and_passes_change_nothing(monkeypatch):
    """``compute(on_done=...)`` counts one per measured tyre (fitted in at most ``FIT_PASSES``
    passes), then ``ACROSS_TYRE_STEPS``; how the tyres are split into passes changes no table."""
    from tyrelab.itemcache import digest
    from tyrelab.tyre.regressions import measured_tyres

    results, tyres = _mixed_results(), pd.read_csv(REPO_RAW / "tyres.csv")
    published = {name: None for name in regress.PUBLISHED}
    counted = []
    monkeypatch.setattr(regress, "FIT_PASSES", 2)
    two = regress.compute(results, tyres, published, on_done=counted.append)
    n = len(measured_tyres(results))
    assert counted == [-(-n // 2), n - -(-n // 2)] + [1] * regress.ACROSS_TYRE_STEPS
    monkeypatch.setattr(regress, "FIT_PASSES", 1)
    one = regress.compute(results, tyres, published)
    assert {k: digest(v) for k, v in two.items()} == {k: digest(v) for k, v in one.items()}


def test_a_changed_run_refits_our_formula_not_the_published_one(tmp_path):
    """Issue 35: each source's formula fit (and its leave-one-tyre-out refits) is an item keyed by
    its points: a changed run of ours refits our formula; the published Table III's is reused; the
    tables are those of a computation without the cache."""
    from tyrelab import published as pub
    from tyrelab.itemcache import digest
    from tyrelab.stages.state import ItemCache

    results, tyres = _mixed_results(), pd.read_csv(REPO_RAW / "tyres.csv")
    published = {name: pub.read_published(name) for name in regress.PUBLISHED}
    ctx = Context(raw=tmp_path / "raw", build=tmp_path / "build")
    first = ItemCache(ctx, "regress")
    regress.compute(results, tyres, published, first)
    assert first.summary("formula") == "0 reused, 2 computed"
    changed = results.copy()
    t3 = (changed["tyre_id"] == "T3") & (changed["speed_km_h"] == 0.0)
    changed.loc[t3, "stiffness_kN_per_m"] *= 1.05
    again = ItemCache(ctx, "regress")
    tables = regress.compute(changed, tyres, published, again)
    assert again.summary("formula") == "1 reused, 1 computed"
    plain = regress.compute(changed, tyres, published)
    assert {k: digest(v) for k, v in tables.items()} == {k: digest(v) for k, v in plain.items()}
