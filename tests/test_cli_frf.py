"""Issue 43: ``tyrelab frf FILE`` and ``tyrelab.vehicle_frf`` on stand recordings of a known system."""

import json

import numpy as np
import pandas as pd
import pytest

import tyrelab
from tests.synthetic_frf import MODES, stand_recording
from tyrelab.cli import main
from tyrelab.rawformat.rides import INPUT_CHANNELS


def _write(path, case, duration_s=600.0):
    x, y, fs = stand_recording(case, duration_s=duration_s)
    d = {"time_s": np.arange(x.shape[1]) / fs, **dict(zip(INPUT_CHANNELS, x)), "floor_z_m_s2": y[0],
         "yaw_rad_s2": y[1]}
    pd.DataFrame(d).to_parquet(path)
    return pd.DataFrame(d)


def test_json_and_table_and_the_library_agree(tmp_path, capsys):
    frame = _write(tmp_path / "stand.parquet", "independent")
    assert main(["frf", str(tmp_path / "stand.parquet")]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["inputs"] == INPUT_CHANNELS and doc["outputs"] == ["floor_z_m_s2", "yaw_rad_s2"]
    modes = [m for m in doc["modes"] if m["output"] == "yaw_rad_s2"]
    assert [round(m["frequency_Hz"] / np.sqrt(1 - m["damping_ratio"] ** 2), 1) for m in modes] == [fn for fn, _ in MODES]
    assert {r["h_unit"] for r in doc["frf"] if r["output"] == "yaw_rad_s2"} == {"(rad/s²)/(m/s²)"}
    lib = tyrelab.vehicle_frf(frame)
    assert lib.mode_rows() == doc["modes"]
    assert main(["frf", str(tmp_path / "stand.parquet"), "--format", "table"]) == 0
    table = capsys.readouterr().out
    assert "modes (damped frequency" in table and "input_rear_right_z_m_s2" in table


def test_road_input_exits_3_with_one_line_and_bad_files_exit_2(tmp_path, capsys):
    _write(tmp_path / "road.parquet", "road")
    assert main(["frf", str(tmp_path / "road.parquet")]) == 3
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "cannot be separated" in err[0]
    pd.DataFrame({"time_s": np.arange(1000) / 50, "floor_z_m_s2": np.sin(np.arange(1000))}).to_csv(
        tmp_path / "no_inputs.csv", index=False)
    assert main(["frf", str(tmp_path / "no_inputs.csv")]) == 2
    assert "no input channel" in capsys.readouterr().err
    assert main(["frf", str(tmp_path / "missing.csv")]) == 2
    assert len(capsys.readouterr().err.strip().splitlines()) == 1


def test_library_arguments_checked():
    with pytest.raises(ValueError, match="speed_km_h"):
        tyrelab.vehicle_frf(pd.DataFrame({"floor_z_m_s2": [0.0]}), speed_km_h=-1)


def test_a_scenario_gives_the_predicted_frfs_and_modes_beside_the_measured(tmp_path, capsys):
    """``--scenario``: the model at the recording's speed beside the measurement (the rides stage's
    ``predicted_h_magnitude`` and ``vehicle_frf_validation``), JSON, table and library alike."""
    from tyrelab import stand
    from tyrelab.generate import write_run

    row = next(r for r in stand.stand_plan().to_dict("records") if r["ride_id"] == "stand_rear_left_still_6kmh")
    sc = stand.stand_scenario()
    write_run(stand.stand_recording(sc, row, 1991), tmp_path / "stand.parquet")
    (tmp_path / "stand.toml").write_text(stand.STAND_SCENARIO_TEXT, encoding="utf-8")
    args = ["frf", str(tmp_path / "stand.parquet"), "--speed", "6", "--scenario", str(tmp_path / "stand.toml")]
    assert main(args) == 0
    doc = json.loads(capsys.readouterr().out)
    z = [f for f in doc["frf"] if f["output"] == "floor_z_m_s2" and 1.0 <= f["frequency_Hz"] <= 2.0]
    assert z and all(abs(f["predicted_h_magnitude"] / f["h_magnitude"] - 1) < 0.1 for f in z)
    assert {"bounce", "pitch"} <= {v["predicted_mode"] for v in doc["validation"]}
    lib = tyrelab.vehicle_frf(tmp_path / "stand.parquet", speed_km_h=6.0, scenario=tmp_path / "stand.toml")
    assert [v["predicted_mode"] for v in lib.validation] == [v["predicted_mode"] for v in doc["validation"]]
    assert main([*args, "--format", "table"]) == 0
    assert "the scenario's model at this speed" in capsys.readouterr().out
    assert main(["frf", str(tmp_path / "stand.parquet")]) == 0
    assert "validation" not in json.loads(capsys.readouterr().out)  # no scenario: no prediction
