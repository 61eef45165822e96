"""Issue 34 through the stages: old and new manifests side by side, bad input quarantined, exit 3."""

import numpy as np
import pandas as pd

from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
from tests.synthetic_methods import broadband_recording, free_decay_recording, load_deflection_recording

from tyrelab.cli import main


def _old_campaign(raw):
    runs = [(manifest_row(f"old{i}", f"old{i}.parquet", pressure_bar=p, speed_km_h=v),
             spring_damper_recording(230e3 + 150e3 * p, 2000.0 + 300 * p, duration_s=12.0, seed=i))
            for i, (p, v) in enumerate([(0.83, 0.0), (1.38, 0.0), (1.93, 10.0)])]
    return write_campaign(raw / "old", runs)


def _new_campaign(raw):
    base = dict(excitation_frequency_Hz="")
    good = [
        (manifest_row("rnd", "rnd.parquet", method="random", band_low_Hz=1.0, band_high_Hz=8.0, speed_km_h=0.0, **base),
         broadband_recording(420e3, 2.6e3, seed=1)),
        (manifest_row("lat", "lat.parquet", method="random", direction="lateral", band_low_Hz=1.0, band_high_Hz=8.0,
                      speed_km_h=5.0, **base), broadband_recording(200e3, 1.5e3, 9e3, seed=2)),
        (manifest_row("swp", "swp.parquet", method="swept_sine", direction="longitudinal", speed_km_h=0.0, **base),
         broadband_recording(250e3, 1.8e3, method="swept_sine", seed=3)),
        (manifest_row("fv", "fv.parquet", method="free_vibration", speed_km_h=0.0, **base),
         free_decay_recording(400e3, 4.5e3, seed=4)),
        (manifest_row("fv_roll", "fv_roll.parquet", method="free_vibration", speed_km_h=5.0, **base),
         free_decay_recording(400e3, 4.5e3, seed=11)),
        (manifest_row("ld", "ld.parquet", method="load_deflection", speed_km_h=0.0, **base),
         load_deflection_recording(330e3, 4e4, seed=5)),
        (manifest_row("step", "step.parquet", direction="vertical", method="stepped_sine"),
         spring_damper_recording(300e3, 2500.0, duration_s=12.0, seed=6)),
    ]
    bad = [
        (manifest_row("rnd_noband", "rnd_noband.parquet", method="random", **base), broadband_recording(4e5, 2e3, seed=7)),
        (manifest_row("fv_never", "fv_never.parquet", method="free_vibration", **base),
         free_decay_recording(400e3, 4.5e3, decays=False, seed=8)),
        (manifest_row("ld_nodefl", "ld_nodefl.parquet", method="load_deflection", **base),
         load_deflection_recording(330e3, 4e4, with_deflection=False, seed=9)),
        (manifest_row("diag", "diag.parquet", direction="diagonal"), spring_damper_recording(duration_s=12.0, seed=10)),
    ]
    return write_campaign(raw / "new", good + bad)


def _stages(raw, build):
    return [main([s, "--raw", str(raw), "--build", str(build), "--jobs", "1"]) for s in ("ingest", "analyse", "calibrate")]


def test_old_manifests_give_the_old_numbers_to_the_bit_beside_new_methods(tmp_path, caplog):
    _old_campaign(tmp_path / "alone")
    assert _stages(tmp_path / "alone", tmp_path / "b_alone") == [0, 0, 0]
    _old_campaign(tmp_path / "mixed")
    _new_campaign(tmp_path / "mixed")
    codes = _stages(tmp_path / "mixed", tmp_path / "b_mixed")
    assert codes[0] == 3 and codes[1] == 3  # bad input quarantined, the rest through
    alone = pd.read_parquet(tmp_path / "b_alone/parquet/results.parquet").set_index("run_id")
    mixed = pd.read_parquet(tmp_path / "b_mixed/parquet/results.parquet").set_index("run_id")
    numbers = [c for c in alone.columns if alone[c].dtype.kind == "f" and c not in ("input_hash",)]
    for run in alone.index:
        for c in numbers:
            a, b = alone.loc[run, c], mixed.loc[run, c]
            assert (np.isnan(a) and np.isnan(b)) or a == b, (run, c, a, b)
    assert set(mixed.loc[alone.index, "method"]) == {"stepped_sine"}
    assert set(mixed.loc[alone.index, "direction"]) == {"vertical"}

    q = pd.read_parquet(tmp_path / "b_mixed/parquet/stages/quarantine_ingest.parquet")
    qa = pd.read_parquet(tmp_path / "b_mixed/parquet/stages/quarantine_analyse.parquet")
    reasons = dict(zip(q["run_id"], q["reason"])) | dict(zip(qa["run_id"], qa["reason"]))
    assert "method random needs its excitation band" in reasons["rnd_noband"]
    assert reasons["fv_never"].startswith("run fv_never: method free_vibration: no free decay")
    assert reasons["ld_nodefl"].startswith("run ld_nodefl: method load_deflection needs channel deflection_m")
    assert "direction" in reasons["diag"] and "diagonal" in reasons["diag"]
    assert all("\n" not in r for r in reasons.values())

    r = mixed
    assert r.loc["rnd", "stiffness_ci95_low_N_per_m"] < 420e3 < r.loc["rnd", "stiffness_ci95_high_N_per_m"]
    assert r.loc["lat", "direction"] == "lateral" and r.loc["lat", "model"] == "maxwell"
    assert r.loc["lat", "series_damping_ci95_low_N_s_per_m"] < 9e3 < r.loc["lat", "series_damping_ci95_high_N_s_per_m"]
    assert r.loc["swp", "stiffness_ci95_low_N_per_m"] < 250e3 < r.loc["swp", "stiffness_ci95_high_N_per_m"]
    assert r.loc["fv", "stiffness_ci95_low_N_per_m"] < 400e3 < r.loc["fv", "stiffness_ci95_high_N_per_m"]
    assert r.loc["ld", "secant_stiffness_N_per_m"] == np.float64(r.loc["ld", "stiffness_N_per_m"])
    assert r.loc[["rnd", "lat", "swp", "fv", "ld", "step"], "qc_ok"].all()
    assert "rolling tyre" in r.loc["fv_roll", "method_note"] and r.loc["fv_roll", "qc_ok"]
    assert any("run fv_roll (free vibration, 5 km/h)" in m and "thesis §3.4" in m for m in caplog.messages)
    frf = pd.read_parquet(tmp_path / "b_mixed/parquet/frf.parquet")
    assert set(frf["run_id"]) == {"rnd", "lat", "swp"} and frf["coherence"].between(0, 1).all()


def test_a_campaign_without_a_stepped_sine_run_goes_through_every_stage(tmp_path):
    """Issue 44: broadband, free-vibration and load-deflection runs only (no stepped sine) once
    crashed analyse (KeyError 'excitation_frequency_measured_Hz'); now every stage runs."""
    base = dict(excitation_frequency_Hz="")
    runs = [
        (manifest_row("rnd", "rnd.parquet", method="random", band_low_Hz=1.0, band_high_Hz=8.0, speed_km_h=0.0, **base),
         broadband_recording(420e3, 2.6e3, seed=1)),
        (manifest_row("lat", "lat.parquet", method="random", direction="lateral", band_low_Hz=1.0, band_high_Hz=8.0,
                      speed_km_h=5.0, **base), broadband_recording(200e3, 1.5e3, 9e3, seed=2)),
        (manifest_row("fv", "fv.parquet", method="free_vibration", speed_km_h=0.0, **base),
         free_decay_recording(400e3, 4.5e3, seed=4)),
        (manifest_row("ld", "ld.parquet", method="load_deflection", speed_km_h=0.0, **base),
         load_deflection_recording(330e3, 4e4, seed=5)),
    ]
    raw, build = tmp_path / "raw", tmp_path / "build"
    write_campaign(raw / "broadband", runs)
    assert main(["run", "--raw", str(raw), "--build", str(build), "--jobs", "1", "-q"]) == 0
    r = pd.read_parquet(build / "parquet/results.parquet").set_index("run_id")
    assert set(r.index) == {"rnd", "lat", "fv", "ld"}
    assert r["excitation_frequency_measured_Hz"].isna().all()  # the stepped sine's column, there and null
    assert r.loc["rnd", "stiffness_ci95_low_N_per_m"] < 420e3 < r.loc["rnd", "stiffness_ci95_high_N_per_m"]
    assert (build / "warehouse.duckdb").is_file() and (build / "reports" / "index.html").is_file()
