"""tyrelab export-tyre: a measured tyre as MF-Tyre .tir files, read back independently (issue 12)."""

import json
import math
import re

import pandas as pd
import pytest

from tyrelab.cli import main
from tyrelab.tyre.mf_tyre import PressureLine, measured_tyre, property_file, tir_parameters
from tyrelab.warehouse import query


def read_tir(text: str) -> dict[str, dict[str, object]]:
    """A minimal MF-Tyre property file reader, independent of tyrelab's writer.

    ``[SECTION]`` headers; ``KEY = value`` lines, ``$`` starting a comment;
    lines starting with ``!`` or ``$`` are comments; quoted values are text.
    """
    sections: dict[str, dict[str, object]] = {}
    current = None
    for raw in text.splitlines():
        line = raw.strip()
        if not line or line[0] in "!$":
            continue
        if m := re.fullmatch(r"\[(\w+)\]", line):
            current = sections.setdefault(m[1], {})
            continue
        key, _, value = line.split("$", 1)[0].partition("=")
        value = value.strip()
        current[key.strip()] = value.strip("'") if value.startswith("'") else float(value)
    return sections


def mf61_vertical_stiffness(tir: dict, pressure_Pa: float) -> float:
    """MF 6.1: C_z = VERTICAL_STIFFNESS (1 + PFZ1 dp_i), dp_i = (p - NOMPRES) / NOMPRES."""
    p0 = tir["OPERATING_CONDITIONS"]["NOMPRES"]
    return tir["VERTICAL"]["VERTICAL_STIFFNESS"] * (1 + tir["VERTICAL"]["PFZ1"] * (pressure_Pa - p0) / p0)


@pytest.fixture(scope="module")
def t1_fit(small_report):
    db = small_report.build / "warehouse.duckdb"
    row = query(db, "SELECT * FROM table_iii WHERE tyre_id = 'T1' AND condition = 'rolling'").iloc[0]
    return row


def test_tir_gives_back_the_warehouse_fit_at_two_pressures(small_report, t1_fit, tmp_path, capsys):
    out = tmp_path / "t1.tir"
    assert main(["export-tyre", "T1", "--build", str(small_report.build), "--pressure", "1.0", "1.6",
                 "--out", str(out)]) == 0
    printed = capsys.readouterr().out.split()
    files = {p: tmp_path / f"t1_{p}bar.tir" for p in ("1", "1.6")}
    assert set(map(str, files.values())) <= set(printed)
    kc, dkp = t1_fit["carcass_stiffness_kN_per_m"], t1_fit["pressure_dependence_kN_per_m_bar"]
    assert 100 < kc < 250 and 100 < dkp < 200  # the campaign's truth: 170 + 150 P kN/m
    for name, path in files.items():
        tir = read_tir(path.read_text())
        assert tir["OPERATING_CONDITIONS"]["NOMPRES"] == pytest.approx(float(name) * 1e5)
        assert tir["OPERATING_CONDITIONS"]["INFLPRES"] == tir["OPERATING_CONDITIONS"]["NOMPRES"]
        for p_bar in (0.9, 1.7):  # two pressures, neither the file's own
            k = mf61_vertical_stiffness(tir, p_bar * 1e5)
            assert k == pytest.approx((kc + dkp * p_bar) * 1e3, rel=0.005)
        assert tir["INFLATION_PRESSURE_RANGE"]["PRESMIN"] == pytest.approx(0.83e5)
        assert tir["INFLATION_PRESSURE_RANGE"]["PRESMAX"] == pytest.approx(1.93e5)
        assert tir["VERTICAL"]["FNOMIN"] == pytest.approx(t1_fit["held_load_kN"] * 1e3)
        assert tir["VERTICAL"]["VERTICAL_DAMPING"] > 0
        assert tir["DIMENSION"]["RIM_RADIUS"] == pytest.approx(38 * 0.0254 / 2)
        assert tir["DIMENSION"]["WIDTH"] == pytest.approx(13.6 * 0.0254)
        assert tir["MODEL"]["FITTYP"] == 61 and tir["UNITS"]["LENGTH"] == "meter"
    # damping differs between the two files (MF has no pressure term for it)
    c = [read_tir(p.read_text())["VERTICAL"]["VERTICAL_DAMPING"] for p in files.values()]
    assert c[0] != c[1]


def test_tables_per_speed_with_intervals(small_report, tmp_path, capsys):
    out = tmp_path / "t1.tir"
    assert main(["export-tyre", "T1", "--build", str(small_report.build), "--out", str(out)]) == 0
    capsys.readouterr()
    assert out.exists()  # one pressure: the file is the --out path itself
    table = pd.read_csv(tmp_path / "t1.csv")
    assert set(table["speed_km_h"]) == {0.0, 10.0}
    assert {0.83, 1.38, 1.93} <= set(table["pressure_bar"].round(2))
    by_speed = query(small_report.build / "warehouse.duckdb",
                     "SELECT * FROM stiffness_pressure_by_speed WHERE tyre_id = 'T1'")
    for _, fit in by_speed.iterrows():
        rows = table.loc[table["speed_km_h"] == fit["speed_km_h"]]
        assert rows["stiffness_kN_per_m"].to_numpy() == pytest.approx(fit["intercept"] + fit["slope"] * rows["pressure_bar"])
    assert (table["stiffness_ci_low_kN_per_m"] < table["stiffness_kN_per_m"]).all()
    assert (table["stiffness_ci_high_kN_per_m"] > table["stiffness_kN_per_m"]).all()
    assert (table["damping_se_bound_kN_s_per_m"] > 0).all()
    summary = json.loads((tmp_path / "t1.json").read_text())
    assert summary["tyre_id"] == "T1" and summary["size"] == "13.6R38"
    assert len(summary["by_speed"]) == len(table)
    tir = read_tir(out.read_text())
    assert tir["OPERATING_CONDITIONS"]["NOMPRES"] == pytest.approx((0.83 + 1.93) / 2 * 1e5)


def test_unknown_tyre_and_missing_warehouse_are_usage_errors(small_report, tmp_path, capsys):
    assert main(["export-tyre", "T9", "--build", str(small_report.build), "--out", str(tmp_path / "x.tir")]) == 2
    assert "'T9'" in capsys.readouterr().err
    assert main(["export-tyre", "T1", "--build", str(tmp_path / "nowhere")]) == 2
    assert "no warehouse" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


def test_measured_tyre_from_catalogue_coefficients_alone():
    tyres = pd.DataFrame([{
        "tyre_id": "MY1", "size": "480/70R38 145D", "outer_diameter_m": "1.64",
        "carcass_stiffness_kN_per_m": "120", "pressure_dependence_kN_per_m_bar": "230",
        "carcass_damping_kN_s_per_m": "1.1", "pressure_dependence_kN_s_per_m_bar": "0.4",
        "measured_speed_km_h": "12", "tested_load_kN": "25", "measured_pressure_min_bar": "0.8",
        "measured_pressure_max_bar": "1.6",
    }])
    t = measured_tyre("MY1", tyres)
    assert t.stiffness == PressureLine(120.0, 230.0) and t.damping_speed_km_h == 12
    assert t.unloaded_radius_m == pytest.approx(0.82)
    tir = read_tir(property_file(t, 1.2))
    assert tir["VERTICAL"]["VERTICAL_STIFFNESS"] == pytest.approx((120 + 230 * 1.2) * 1e3)
    assert tir["VERTICAL"]["PFZ1"] == pytest.approx(1.2 * 230 / (120 + 230 * 1.2))
    assert tir["VERTICAL"]["VERTICAL_DAMPING"] == pytest.approx((1.1 + 0.4 * 1.2) * 1e3)
    assert tir["VERTICAL"]["FNOMIN"] == 25e3
    assert tir["MODEL"]["LONGVL"] == pytest.approx(12 / 3.6)
    assert tir["DIMENSION"]["ASPECT_RATIO"] == 0.7 and tir["DIMENSION"]["UNLOADED_RADIUS"] == pytest.approx(0.82)
    # every written key says where its value comes from
    for items in tir_parameters(t, 1.2).values():
        for key, _, comment in items:
            assert key in ("LENGTH", "FORCE", "ANGLE", "MASS", "TIME") or re.match(
                r"(measured|placeholder|from the size|inch size|inflation|nominal|Magic)", comment), key
    with pytest.raises(ValueError, match="no rolling stiffness fit") as refused:
        measured_tyre("MY1", tyres.drop(columns=["carcass_stiffness_kN_per_m"]))
    assert "record rolling runs" in str(refused.value) and "stationary only" not in str(refused.value)
    stationary = pd.DataFrame({"tyre_id": ["MY1"], "condition": ["stationary"], "carcass_stiffness_kN_per_m": [300.0],
                               "pressure_dependence_kN_per_m_bar": [100.0]})
    with pytest.raises(ValueError, match="stationary only") as refused:  # issue 47: what to measure or pass
        measured_tyre("MY1", tyres.drop(columns=["carcass_stiffness_kN_per_m"]), stationary)
    assert "speed_km_h > 0" in str(refused.value) and "tyres.csv" in str(refused.value)
    with pytest.raises(ValueError, match="pressure_bar"):
        tir_parameters(t, 0)
    assert math.isnan(t.stiffness.intercept_se)


def test_default_file_name_is_safe_for_any_tyre_id(small_report, tmp_path, monkeypatch, capsys):
    from tests.report.small_campaign import EVIL_TYRE

    monkeypatch.chdir(tmp_path)
    assert main(["export-tyre", EVIL_TYRE, "--build", str(small_report.build)]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert len(names) == 3 and all("<" not in n and "/" not in n for n in names)
    tir = read_tir((tmp_path / [n for n in names if n.endswith(".tir")][0]).read_text())
    assert tir["VERTICAL"]["VERTICAL_STIFFNESS"] > 0
    assert capsys.readouterr().out.count("\n") == 3
