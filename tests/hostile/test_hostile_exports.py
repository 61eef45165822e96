"""export-tyre and ride --out: OS errors in one line, a set of files replaced together or not at all,
pressures outside the tested range not labelled measured (issue 25, classes 4 and 7)."""

import json
import resource
import signal
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from tyrelab import io
from tyrelab.cli import main
from tyrelab.export import TyreTables, export_tyre, tyre_export, write_export
from tyrelab.warehouse import build_warehouse

TYRES = pd.DataFrame({"tyre_id": ["MY1"], "size": ["480/70R38"], "carcass_stiffness_kN_per_m": [120.0],
                      "pressure_dependence_kN_per_m_bar": [230.0], "carcass_damping_kN_s_per_m": [1.1],
                      "pressure_dependence_kN_s_per_m_bar": [0.4], "measured_speed_km_h": [12.0],
                      "tested_load_kN": [25.0], "measured_pressure_min_bar": [0.83], "measured_pressure_max_bar": [1.93]})


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    """A warehouse with the tables export-tyre reads: MY1 known from its catalogue coefficients only."""
    build = tmp_path_factory.mktemp("export") / "build"
    parquet = build / "parquet"
    io.write_parquet_atomic(TYRES, parquet / "tyres.parquet")
    io.write_parquet_atomic(pd.DataFrame({"tyre_id": ["X"], "condition": ["rolling"], "carcass_stiffness_kN_per_m": [1.0],
                                          "pressure_dependence_kN_per_m_bar": [1.0]}), parquet / "table_iii.parquet")
    by_speed = pd.DataFrame({"tyre_id": ["MY1"], "speed_km_h": [10.0], "intercept": [120.0], "slope": [230.0],
                             "intercept_se": [5.0], "slope_se": [4.0], "n": [12]})
    io.write_parquet_atomic(by_speed, parquet / "stiffness_pressure_by_speed.parquet")
    io.write_parquet_atomic(by_speed.assign(intercept=1.1, slope=0.4, intercept_se=0.1, slope_se=0.05),
                            parquet / "damping_pressure_by_speed.parquet")
    io.write_parquet_atomic(pd.DataFrame({"tyre_id": ["X"], "kind": ["measurement"], "pressure_bar": [1.0]}),
                            parquet / "results.parquet")
    build_warehouse(build / "warehouse.duckdb", parquet)
    return build


def export(build, capsys, *args):
    rc = main(["export-tyre", "MY1", "--build", str(build), *args])
    out = capsys.readouterr()
    return rc, out.out, out.err


def one_line(err: str) -> bool:
    return err.count("\n") == 1 and "Traceback" not in err


def test_out_onto_a_folder_or_below_a_file(build, tmp_path, capsys):
    (tmp_path / "folder.tir").mkdir()
    rc, out, err = export(build, capsys, "--out", str(tmp_path / "folder.tir"))
    assert rc == 2 and out == "" and one_line(err) and "folder.tir" in err
    (tmp_path / "file").write_text("x")
    rc, out, err = export(build, capsys, "--out", str(tmp_path / "file" / "t.tir"))
    assert rc == 2 and out == "" and one_line(err) and "Not a directory" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file", "folder.tir"]


def test_a_set_is_replaced_together_or_not_at_all(build, tmp_path, capsys, monkeypatch):
    out = tmp_path / "my1.tir"
    assert export(build, capsys, "--out", str(out), "--pressure", "1.2")[0] == 0
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    assert sorted(before) == ["my1.csv", "my1.json", "my1.tir"]
    real_replace = io.os.replace
    calls = []

    def failing_replace(src, dst):  # the disk fills after two of the three renames
        calls.append(dst)
        if len(calls) == 3:
            raise OSError(28, "No space left on device", str(dst))
        return real_replace(src, dst)

    monkeypatch.setattr(io.os, "replace", failing_replace)
    rc, _, err = export(build, capsys, "--out", str(out), "--pressure", "1.5")
    monkeypatch.undo()
    assert rc == 2 and one_line(err) and "No space left" in err
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before  # the old set, whole


def test_file_size_limit_leaves_the_old_set(build, tmp_path):
    out = tmp_path / "my1.tir"
    tyrelab = Path(sys.executable).with_name("tyrelab")
    ok = subprocess.run([str(tyrelab), "export-tyre", "MY1", "--build", str(build), "--out", str(out)],
                        capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}

    def limit():
        resource.setrlimit(resource.RLIMIT_FSIZE, (1000, 1000))  # the .tir fits, the .csv does not

    r = subprocess.run([str(tyrelab), "export-tyre", "MY1", "--build", str(build), "--out", str(out), "--pressure",
                        "1.5"], capture_output=True, text=True, preexec_fn=limit)
    assert r.returncode == 2 and one_line(r.stderr) and "File too large" in r.stderr, r.stderr
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


def test_pressure_outside_the_tested_range_warns_and_is_not_measured(build, tmp_path, capsys):
    rc, out, err = export(build, capsys, "--out", str(tmp_path / "a.tir"), "--pressure", "5")
    assert rc == 0
    assert "warning" in err and "5 bar is outside the tested range 0.83-1.93 bar" in err
    tir = (tmp_path / "a.tir").read_text()
    stiffness = next(line for line in tir.splitlines() if line.startswith("VERTICAL_STIFFNESS"))
    assert "measured" not in stiffness.split("$")[1] and "extrapolated" in stiffness
    doc = json.loads((tmp_path / "a.json").read_text())
    assert doc["extrapolated_pressures_bar"] == [5.0] and doc["warnings"]
    rows = pd.read_csv(tmp_path / "a.csv")
    assert rows.set_index("pressure_bar")["extrapolated"].to_dict() == {5.0: True}  # no runs: asked pressures only
    rc, _, err = export(build, capsys, "--out", str(tmp_path / "b.tir"), "--pressure", "1.2")
    assert rc == 0 and err == ""
    assert "measured:" in next(line for line in (tmp_path / "b.tir").read_text().splitlines()
                               if line.startswith("VERTICAL_STIFFNESS"))


def test_library_export_is_three_steps(build, tmp_path):
    e, paths = export_tyre(build / "warehouse.duckdb", "MY1", [1.0, 1.5], tmp_path / "x")
    assert [p.name for p in paths] == ["x_1bar.tir", "x_1.5bar.tir", "x.csv", "x.json"]
    pure = tyre_export(TyreTables(tyres=TYRES), "MY1", [1.0, 1.5])
    assert pure.tir_texts[0].splitlines()[6:] == e.tir_texts[0].splitlines()[6:]  # the source line differs
    with pytest.raises(ValueError, match="pressures_bar"):
        tyre_export(TyreTables(tyres=TYRES), "MY1", [float("nan")])
    (tmp_path / "d.tir").mkdir()
    with pytest.raises(IsADirectoryError):
        write_export(tyre_export(TyreTables(tyres=TYRES), "MY1", [1.0]), tmp_path / "d.tir")


def test_estimate_stiffness_json_is_json_for_any_pressure(capsys):
    for pressure in ("1e308", "1.7e308"):
        rc = main(["estimate-stiffness", "--size", "480/70R38", "--pressure", pressure, "--format", "json"])
        out, err = capsys.readouterr()
        assert "Traceback" not in err
        if rc == 0:
            json.loads(out, parse_constant=lambda c: pytest.fail(f"{c} is not JSON"))
        else:
            assert rc == 2 and out == "" and one_line(err) and "pressure" in err
