"""Hand-digitized thesis tables (raw/published/*.csv) and the tyre catalogue (raw/tyres.csv).

Every CSV must have a schema and validate against it; spot checks compare a
handful of cells with the thesis text, and a few cross-table checks catch
digitizing slips (e.g. Table XX frequencies recomputed from Table XIX).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tyrelab.schema import SCHEMA_DIR, load_schema, validate_frame
from tyrelab.tyre.sizes import parse_tyre_size

ROOT = Path(__file__).resolve().parents[1]
PUBLISHED = ROOT / "raw" / "published"
TYRES = ROOT / "raw" / "tyres.csv"
CSVS = sorted(PUBLISHED.glob("*.csv"))
STEMS = [p.stem for p in CSVS]

ROMAN = ["i", "ii", "iii", "iv", "v", "vi", "vii", "viii", "ix", "x", "xi", "xii", "xiii", "xiv", "xv", "xvi",
         "xvii", "xviii", "xix", "xx"]


def read(path: Path) -> pd.DataFrame:
    """Read a CSV as text, blanks as missing (as the ingest stage does)."""
    return pd.read_csv(path, dtype=str, keep_default_na=False, na_values=[""])


def table(stem: str) -> pd.DataFrame:
    """Read a published table with pandas' type inference."""
    return pd.read_csv(PUBLISHED / f"{stem}.csv")


def test_every_thesis_table_is_digitized():
    assert STEMS and set(STEMS) == {f"table_{r}" for r in ROMAN}


@pytest.mark.parametrize("stem", STEMS)
def test_published_csv_has_schema_and_validates(stem):
    schema_path = SCHEMA_DIR / "published" / f"{stem}.json"
    assert schema_path.is_file(), f"no schema for raw/published/{stem}.csv"
    schema = load_schema(f"published/{stem}")
    assert schema.get("additionalFields") is False
    assert schema["description"].startswith("Thesis Table")
    df = read(PUBLISHED / f"{stem}.csv")
    assert "notes" in df.columns
    assert list(df.columns) == [f["name"] for f in schema["fields"]], "column order differs from the schema"
    assert validate_frame(df, schema) == []


def test_every_published_schema_has_a_csv():
    schemas = {p.stem for p in (SCHEMA_DIR / "published").glob("*.json")}
    assert schemas == set(STEMS)


def test_tyre_catalogue_validates_and_sizes_parse():
    df = read(TYRES)
    assert validate_frame(df, load_schema("tyres")) == []
    for row in df.itertuples(index=False):
        size = parse_tyre_size(row.size)
        assert size.construction == row.construction, row.tyre_id


def test_tyre_catalogue_matches_table_ii():
    cat = read(TYRES).set_index("tyre_id")
    t2 = read(PUBLISHED / "table_ii.csv").set_index("tyre_id")
    assert set(cat.index) == set(t2.index)
    assert (cat["size"] == t2.loc[cat.index, "size"]).all()
    assert (cat["ply_rating"] == t2.loc[cat.index, "ply_rating"]).all()
    assert (cat["position"] == t2.loc[cat.index, "group"]).all()
    assert cat.loc["T1", "rolling_circumference_m"] == "4.66"
    assert cat.loc["F1", "rolling_circumference_m"] == "2.63"
    assert cat.loc[["T1", "T2", "T3", "T4", "T5"], "age_years"].tolist() == ["11", "16", "4", "9", "1"]


@pytest.mark.parametrize("stem", ["table_iii", "table_iv", "table_vii", "table_viii"])
def test_tyre_ids_are_in_the_catalogue(stem):
    ids = set(read(TYRES)["tyre_id"])
    assert set(read(PUBLISHED / f"{stem}.csv")["tyre_id"]) <= ids


# ---- spot checks against the thesis text -------------------------------------------------


def test_table_i_spot_values():
    t = table("table_i").set_index("method")
    assert t.loc["apparent_mass", "stiffness_kN_per_m"] == 450
    assert t.loc["apparent_mass", "damping_kN_s_per_m"] == 3.0
    assert np.isnan(t.loc["load_deflection", "damping_kN_s_per_m"])


def test_table_iii_spot_values():
    t = table("table_iii").set_index(["tyre_id", "condition"])
    assert t.loc[("T1", "rolling"), "carcass_stiffness_kN_per_m"] == 141
    assert t.loc[("T1", "rolling"), "pressure_dependence_kN_per_m_bar"] == 175
    assert t.loc[("T1", "rolling"), "r_squared_qualifier"] == ">"
    assert t.loc[("T2", "stationary"), "carcass_stiffness_kN_per_m"] == 393  # printed "39³"
    assert t.loc[("F1", "rolling"), "carcass_stiffness_kN_per_m"] == -3
    for tyre in ("T4", "AS1", "AS4"):
        assert t.loc[(tyre, "stationary")].drop("notes").loc[
            ["carcass_stiffness_kN_per_m", "pressure_dependence_kN_per_m_bar", "r_squared"]
        ].isna().all()
    assert len(t) == 34


def test_table_vii_and_viii_spot_values():
    t7 = table("table_vii").set_index(["tyre_id", "speed_km_h"])
    assert tuple(t7.loc[("T5", 15), ["carcass_damping_kN_s_per_m", "pressure_dependence_kN_s_per_m_bar", "r_squared"]]) == (
        0.32,
        0.37,
        0.94,
    )
    t8 = table("table_viii").set_index(["tyre_id", "speed_km_h"])
    assert t8.loc[("T1", 0), "damping_rate_kN_s_per_m_per_mm"] == -0.010
    assert t8.loc[("T2", 15), "damping_rate_kN_s_per_m_per_mm"] == -0.030
    assert t8.loc[("T3", 10), "damping_rate_kN_s_per_m_per_mm"] == 0.002
    # §5.3.4: all decrease when stationary or at 1 km/h; T2 decreases at every speed
    assert (t8.xs(0, level="speed_km_h")["damping_rate_kN_s_per_m_per_mm"] < 0).all()
    assert (t8.xs(1, level="speed_km_h")["damping_rate_kN_s_per_m_per_mm"] < 0).all()
    assert (t8.loc["T2", "damping_rate_kN_s_per_m_per_mm"] < 0).all()


def test_table_v_and_ix_surfaces():
    t5 = table("table_v")
    assert t5["stiffness_change_percent"].tolist() == [0, -3, -3, -5, -5, -7, -10]
    assert t5.set_index("surface").loc["Artificial Rough Track", "stiffness_change_percent"] == -10
    t9 = table("table_ix").set_index("surface")
    assert t9["damping_change_percent"].iloc[:-1].tolist() == [0, 20, 20, 190, 80, 20]
    assert np.isnan(t9.loc["Artificial Rough Track", "damping_change_percent"])
    assert list(t5["surface"]) == list(t9.index)


def test_table_xii_and_xi():
    t12 = table("table_xii")
    rolling = t12[t12["characteristics"] == "rolling"]
    assert len(rolling) == 12
    # measured speeds within 10 % of nominal
    assert np.allclose(rolling["actual_speed_m_s"], rolling["nominal_speed_km_h"] / 3.6, rtol=0.1)
    stat = t12[t12["characteristics"] == "stationary"].set_index("load_condition")
    assert stat["nominal_speed_km_h"].isna().all()
    assert tuple(stat.loc["light", ["load_kg", "damping_kN_s_per_m", "stiffness_kN_per_m"]]) == (1860, 3.42, 545)
    t11 = table("table_xi")
    assert set(t11.loc[t11["load_condition"] == "heavy", "load_kg"]) == {2230}  # 2300 in Table XII


def test_tables_xiii_xiv_qualifiers():
    t13 = table("table_xiii").set_index(["quantity", "statistic"])
    assert t13.loc[("peak_frequency", "mean_ratio_error"), "stationary"] == 1.21
    assert t13.loc[("peak_frequency", "sd_ratio_error"), "stationary"] == 0.07
    assert t13.loc[("peak_width", "p_within_30pct"), "rolling"] == 0.9999
    assert t13.loc[("peak_width", "p_within_30pct"), "rolling_qualifier"] == ">"
    t14 = table("table_xiv").set_index(["quantity", "statistic"])
    assert t14.loc[("peak_height", "mean_ratio_error"), "rolling"] == 1.01  # printed "1 .01"
    assert t14.loc[("peak_frequency", "p_within_10pct"), "rolling_qualifier"] == ">"


def test_table_xv_axle_loads_match_masses():
    t = table("table_xv").set_index(["parameter", "condition"])["value"].astype(float)
    assert t[("wheelbase_m", "all")] == 2.436
    for case in ("heavy", "light"):
        total = t[("front_axle_load_N", case)] + t[("rear_axle_load_N", case)]
        assert total / 9.81 == pytest.approx(t[("total_mass_kg", case)], rel=0.002)
        # CG distance from the rear axle from the moment balance
        assert t[("wheelbase_m", "all")] * t[("front_axle_load_N", case)] / total == pytest.approx(
            t[("cg_to_rear_axle_m", case)], abs=0.005
        )


def test_table_xvi_spot_values():
    t = table("table_xvi")
    r = t[(t["load_condition"] == 1) & (t["track"] == "SBT") & (t["speed_km_h"] == 10)].iloc[0]
    assert (r.rear_stiffness_kN_per_m, r.front_stiffness_kN_per_m, r.rear_damping_kN_s_per_m, r.front_damping_kN_s_per_m) == (
        328,
        426,
        1.12,
        1.47,
    )
    lc4 = t[t["load_condition"] == 4]
    assert set(lc4["rear_pressure_bar"]) == {1.38} and set(lc4["front_pressure_bar"]) == {2.76}
    assert len(t) == 32
    # the front tyre on SBT is 0.9 x its HH stiffness (§7.3)
    for lc in (1, 2, 3, 4):
        sbt = t[(t.load_condition == lc) & (t.track == "SBT")]["front_stiffness_kN_per_m"].iloc[0]
        hh = t[(t.load_condition == lc) & (t.track == "HH")]["front_stiffness_kN_per_m"].iloc[0]
        assert sbt == pytest.approx(0.9 * hh, abs=1.0)


def test_table_xvii_and_xviii_spot_values():
    t17 = table("table_xvii").set_index(["surface", "quantity", "component", "statistic"])
    assert t17.loc[("SBT", "rms", "vertical", "mean_ratio_error"), "rolling"] == 1.13
    assert t17.loc[("HH", "peak_frequency", "second_peak", "p_within_30pct"), "stationary"] == 0.93
    t18 = table("table_xviii")
    assert len(t18) == 9
    measured = t18[t18["is_measured"]].iloc[0]
    assert (measured.vertical_rms_m_s2, measured.pitch_rms_rad_s2, measured.peak_2_Hz, measured.peak_3_Hz) == (1.79, 1.98, 2.15, 3.09)
    # the low mode exists only with longitudinal stiffness
    model = t18[~t18["is_measured"]]
    assert (model["peak_1_Hz"].notna() == (model["longitudinal_stiffness_kN_per_m"] > 0)).all()


def test_table_xx_spot_values():
    t = table("table_xx").set_index(["tractor", "stiffness_source"])
    assert tuple(t.loc[("Leyland 272", "formula")].drop("notes")) == (306, 247, 2.76, 3.50, 2.4, 3.4)
    assert tuple(t.loc[("County 774", "stationary_free_vibration")].iloc[:4]) == (564, 653, 3.55, 3.68)


def test_table_xx_frequencies_recompute_from_table_xix():
    """Bounce/pitch eigenfrequencies of Fig. 68 from Table XIX data and Table XX stiffnesses (2 tyres per axle)."""
    t19 = table("table_xix").set_index("tractor")
    t20 = table("table_xx")
    assert set(t20["tractor"]) == set(t19.index)
    for row in t20.itertuples(index=False):
        tr = t19.loc[row.tractor]
        kf, kr = 2e3 * row.front_stiffness_kN_per_m, 2e3 * row.rear_stiffness_kN_per_m
        l1, l2 = tr.front_distance_m, tr.rear_distance_m
        k = np.array([[kf + kr, kf * l1 - kr * l2], [kf * l1 - kr * l2, kf * l1**2 + kr * l2**2]])
        m = np.diag([tr.mass_kg, tr.pitch_inertia_kg_m2])
        f = np.sort(np.sqrt(np.linalg.eigvals(np.linalg.solve(m, k)).real)) / (2 * np.pi)
        assert f == pytest.approx([row.predicted_frequency_1_Hz, row.predicted_frequency_2_Hz], abs=0.015), row.tractor


def test_table_xix_sizes_parse():
    t = read(PUBLISHED / "table_xix.csv")
    for col in ("front_size", "rear_size"):
        for s in t[col]:
            parse_tyre_size(s)


# ---- the validator catches broken frames ------------------------------------------------


def test_validate_frame_reports_broken_frames():
    schema = load_schema("published/table_iii")
    good = read(PUBLISHED / "table_iii.csv")
    assert validate_frame(good, schema) == []

    wrong_type = good.copy()
    wrong_type.loc[1, "carcass_stiffness_kN_per_m"] = "39³"
    problems = validate_frame(wrong_type, schema)
    assert any("carcass_stiffness_kN_per_m" in p and "type" in p for p in problems)

    out_of_range = good.copy()
    out_of_range.loc[1, "r_squared"] = "1.5"
    problems = validate_frame(out_of_range, schema)
    assert any("r_squared" in p and "maximum" in p for p in problems)

    bad_enum = good.copy()
    bad_enum.loc[0, "condition"] = "moving"
    assert any("condition" in p for p in validate_frame(bad_enum, schema))

    missing = good.drop(columns=["tyre_id"])
    assert any("missing column 'tyre_id'" in p for p in validate_frame(missing, schema))

    extra = good.assign(spare="x")
    assert any("unexpected column" in p for p in validate_frame(extra, schema))

    blank_required = good.copy()
    blank_required.loc[2, "condition"] = np.nan
    assert any("required" in p for p in validate_frame(blank_required, schema))


def test_validate_frame_reports_broken_tyre_catalogue():
    schema = load_schema("tyres")
    cat = read(TYRES)
    dup = pd.concat([cat, cat.iloc[[0]]], ignore_index=True)
    assert any("duplicate" in p for p in validate_frame(dup, schema))
    neg = cat.copy()
    neg.loc[0, "age_years"] = "-1"
    assert any("age_years" in p and "minimum" in p for p in validate_frame(neg, schema))
