"""Stage simulate: writes the chapter 6-8 tables, side by side with the thesis."""

import shutil

import numpy as np
import pandas as pd
import pytest

from tyrelab import published
from tyrelab.stages import simulate
from tyrelab.stages.base import Context


@pytest.fixture(scope="module")
def ctx(tmp_path_factory):
    raw = tmp_path_factory.mktemp("raw")  # no published/: the tables shipped with tyrelab
    c = Context(raw=raw, build=tmp_path_factory.mktemp("build"))
    result = simulate.run(c)
    assert result.n_ok == result.n_in > 0
    return c


def test_tables_written(ctx):
    for name in ("carriage_runs", "table_xiii", "table_xiv", "tractor_runs", "table_xvii", "table_xviii",
                 "table_xx", "table_xx_statistics", "iso2631", "profile_spectra", "simulate_inputs"):
        assert ctx.has_table(name), name
    inputs = ctx.read_table("simulate_inputs")
    assert list(inputs["table"]) == list(simulate.STEMS)
    assert list(inputs["source"]) == [str(published.SHIPPED_DIR / f"{s}.csv") for s in simulate.STEMS]


def test_reads_published_of_the_raw_folder(tmp_path):
    shutil.copytree(published.SHIPPED_DIR, tmp_path / "published")
    xii = (tmp_path / "published" / "table_xii.csv").read_text().replace("stationary,T4,light,,,1860,3.42,545",
                                                                         "stationary,T4,light,,,1860,3.42,555")
    (tmp_path / "published" / "table_xii.csv").write_text(xii)
    tables, inputs = simulate._read(Context(raw=tmp_path, build=tmp_path / "build"))
    assert set(inputs["source"]) == {str((tmp_path / "published" / f"{s}.csv").resolve()) for s in simulate.STEMS}
    st = tables["table_xii"].set_index(["characteristics", "load_condition"])
    assert st.loc[("stationary", "light"), "stiffness_kN_per_m"] == 555


def test_side_by_side_keeps_unprinted_rows(ctx):
    t = ctx.read_table("table_xvii")
    assert len(t) == 32 and t[["ours_rolling", "ours_stationary"]].notna().all().all()
    hh = t[(t["track"] == "HH") & (t["quantity"] == "vertical_rms")]
    assert list(hh["statistic"]) == ["mean_ratio_error", "sd_ratio_error", "p_within_10", "p_within_30"]
    assert hh["thesis_rolling"].iloc[0] == 2.08 and hh["thesis_rolling"].iloc[2:].isna().all()
    x = ctx.read_table("table_xviii").set_index("row")
    assert x.loc["measured (ours: reference virtual tractor)", "vertical_rms_m_s2_thesis"] == 1.79


def test_table_xiii_rolling_beats_stationary(ctx):
    t = ctx.read_table("table_xiii").set_index(["quantity", "statistic"])
    assert list(t.columns) == ["thesis_rolling", "ours_rolling", "difference_rolling",
                               "thesis_stationary", "ours_stationary", "difference_stationary"]
    for q in ("peak_frequency", "half_power_width_over_frequency"):
        r, s = t.loc[(q, "mean_ratio_error")], t.loc[(q, "mean_ratio_error")]
        assert abs(r["ours_rolling"] - 1) < abs(s["ours_stationary"] - 1)
        assert t.loc[(q, "p_within_10"), "ours_rolling"] > t.loc[(q, "p_within_10"), "ours_stationary"]
    assert t.loc[("peak_frequency", "mean_ratio_error"), "ours_rolling"] == pytest.approx(1.0, abs=0.02)


def test_carriage_runs_exclude_low_speeds_in_statistics(ctx):
    runs = ctx.read_table("carriage_runs")
    assert set(runs["speed_km_h"]) == {5.0, 7.5, 10.0, 12.5, 15.0, 17.5}
    assert set(runs["characteristics"]) == {"reference", "rolling", "stationary"}


def test_table_xx_side_by_side(ctx):
    t = ctx.read_table("table_xx")
    f = t[t["stiffness_source"] == "formula"]
    assert np.all(np.abs(f["frequency_1_from_thesis_stiffness_Hz"] - f["thesis_frequency_1_Hz"]) < 0.0135)
    s = ctx.read_table("table_xx_statistics").set_index(["stiffness_source", "basis"])
    assert s.loc[("formula", "thesis"), "mean"] == pytest.approx(1.00, abs=0.01)


def test_iso_every_run(ctx):
    iso = ctx.read_table("iso2631")
    n = len(ctx.read_table("carriage_runs")) + len(ctx.read_table("tractor_runs"))
    assert len(iso) == n and iso["iso_a8_m_s2"].notna().all()


def test_deterministic_pieces(ctx):
    from tyrelab.vehicle import profiles

    a = profiles.slatted_track(seed=simulate.SEED)
    b = profiles.slatted_track(seed=simulate.SEED)
    assert np.array_equal(a.left_m, b.left_m)


def test_carriage_runs_keep_the_quoted_table_xii_stiffness(ctx):
    runs = ctx.read_table("carriage_runs")
    rolling = runs[(runs["characteristics"] == "rolling") & (runs["speed_km_h"] == 10.0) & (runs["load_condition"] == "heavy")]
    assert set(rolling["quoted_stiffness_kN_per_m"]) == {324.0}  # Table XII, before the 10 % surface reduction
    assert rolling["stiffness_kN_per_m"].iloc[0] == pytest.approx(0.9 * 324.0)


def test_fig56_spectra_written(ctx):
    sp = ctx.read_table("carriage_spectra")
    assert {"reference (true)", "rolling (surveyed)", "stationary (surveyed)"} <= set(sp["series"])
    ref = sp[sp["series"] == "reference (true)"]
    assert ref["frequency_Hz"].max() <= 10.0 and (ref["psd_m2_s4_per_Hz"] >= 0).all()
