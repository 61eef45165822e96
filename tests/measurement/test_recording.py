"""The library entry point: tyrelab.analyze_recording (tyrelab.api), and the pure analyse_frame under it."""

import json
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

import tyrelab
from tyrelab.api import analyze_recording
from tyrelab.measurement.recording import RecordingResult, analyse_frame
from tyrelab.rawformat import RunFileError
from tests.synthetic import spring_damper_recording

#: The JSON keys of ``tyrelab analyze-run`` (a contract: add, never rename).
ANALYZE_RUN_KEYS = {
    "file", "sample_rate_Hz", "duration_s", "axle_mass_kg", "excitation_frequency_Hz", "stiffness_N_per_m",
    "damping_N_s_per_m", "stiffness_kN_per_m", "damping_kN_s_per_m", "apparent_mass_real_kg",
    "apparent_mass_imag_kg", "amplitude_mm_pp", "amplitude_rms_mm", "coherence", "estimator", "welch",
    "qc_ok", "qc_reasons",
    # issue 14: every K and C with its uncertainty
    "stiffness_u_N_per_m", "damping_u_N_s_per_m", "stiffness_ci95_N_per_m", "damping_ci95_N_s_per_m", "uncertainty",
}


def test_frame_recovers_k_c_and_passes_qc():
    r = tyrelab.analyze_recording(spring_damper_recording(300e3, 2500.0, 3.3, force_noise_N=50), axle_mass_kg=600.0)
    assert isinstance(r, RecordingResult)
    assert r.stiffness_kN_per_m == pytest.approx(300.0, rel=0.005)
    assert r.damping_kN_s_per_m == pytest.approx(2.5, rel=0.01)
    assert r.excitation_frequency_Hz == pytest.approx(3.3, abs=0.01)
    assert r.amplitude_mm_pp == pytest.approx(14.0, rel=0.01)
    assert r.welch.stiffness_N_per_m == pytest.approx(300e3, rel=0.05)
    assert r.qc_ok and r.qc_reasons == () and r.coherence > 0.99 and r.file is None
    # K = Re(-ω² H): the apparent mass and K agree (thesis eq. 8)
    w = 2 * np.pi * r.excitation_frequency_Hz
    assert (-(w**2) * r.apparent_mass_kg).real == pytest.approx(r.stiffness_N_per_m, rel=1e-9)


def test_file_and_frame_agree_and_json_keys_are_the_cli_contract(tmp_path, capsys):
    rec = spring_damper_recording(force_noise_N=50, seed=3)
    path = tmp_path / "run.parquet"
    rec.to_parquet(path)
    from_file = analyze_recording(path, 600.0)
    from_frame = analyze_recording(rec, 600.0)
    assert from_file.stiffness_N_per_m == from_frame.stiffness_N_per_m and from_file.file == str(path)
    assert analyse_frame(rec, 600.0) == from_frame and from_frame.file is None
    d = from_file.to_dict()
    assert set(d) == ANALYZE_RUN_KEYS
    json.dumps(d)  # JSON-ready
    from tyrelab.cli import main

    assert main(["analyze-run", str(path), "--axle-mass", "600"]) == 0
    assert json.loads(capsys.readouterr().out) == json.loads(json.dumps(d))


def test_frame_without_time_needs_the_sample_rate():
    rec = spring_damper_recording().drop(columns="time_s")
    with pytest.raises(ValueError, match="sample_rate_Hz"):
        analyze_recording(rec, 600.0)
    r = analyze_recording(rec, 600.0, sample_rate_Hz=256.0)
    assert r.sample_rate_Hz == pytest.approx(256.0) and r.stiffness_kN_per_m == pytest.approx(250.0, rel=0.005)


def test_rolling_run_gets_interference_check():
    # the lug-passing frequency right at the excitation: QC must refuse the run
    r = analyze_recording(spring_damper_recording(), 600.0, interference_Hz=[4.0])
    assert r.qc_reasons == ("wheel excitation at 4.00 Hz within 0.15 Hz of the excitation",) and not r.qc_ok
    assert analyze_recording(spring_damper_recording(), 600.0, interference_Hz=[9.0]).qc_ok


@pytest.mark.parametrize("mass", [0.0, -600.0, float("nan"), float("inf"), "heavy"])
def test_bad_axle_mass_names_the_parameter(mass):
    with pytest.raises(ValueError, match="axle_mass_kg"):
        analyze_recording(spring_damper_recording(duration_s=12.0), mass)


def test_bad_inputs_are_value_or_run_file_errors(tmp_path):
    with pytest.raises(ValueError, match="recording"):
        analyze_recording(42, 600.0)
    with pytest.raises(ValueError, match="frame must be a pandas DataFrame"):
        analyse_frame({"time_s": [0.0]}, 600.0)
    with pytest.raises(ValueError, match="sample_rate_Hz"):
        analyze_recording(spring_damper_recording(duration_s=12.0), 600.0, sample_rate_Hz=0.0)
    with pytest.raises(RunFileError, match="missing channel"):
        analyze_recording(spring_damper_recording(duration_s=12.0).drop(columns="load_beam_3_N"), 600.0)
    with pytest.raises(RunFileError, match="does not match"):
        analyze_recording(spring_damper_recording(duration_s=12.0), 600.0, sample_rate_Hz=512.0)
    with pytest.raises(RunFileError, match="not found"):
        analyze_recording(tmp_path / "nothing.parquet", 600.0)


def test_flat_recording_has_no_excitation_and_fails_qc():
    r = analyze_recording(spring_damper_recording(amplitude_mm_pp=0.0), 600.0)
    assert np.isnan(r.stiffness_N_per_m) and not r.qc_ok
    assert r.to_dict()["stiffness_N_per_m"] is None


def test_import_tyrelab_is_light_and_lazy():
    code = (
        "import sys, tyrelab; heavy = [m for m in ('numpy', 'pandas', 'scipy', 'matplotlib', 'duckdb') "
        "if m in sys.modules]; f = tyrelab.analyze_recording; print(heavy, f.__module__, 'scipy' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["[]", "tyrelab.api", "True"]
    assert set(tyrelab.__all__) >= {"analyze_recording", "RecordingResult", "CHANNELS", "RunFileError", "measurement"}
    with pytest.raises(AttributeError):
        tyrelab.no_such_thing  # noqa: B018


def test_batch_checks_shapes_and_masses():
    from tyrelab.measurement.recording import analyse_batch

    accel, beams = np.zeros((2, 2, 3000)), np.zeros((2, 4, 3000))
    with pytest.raises(ValueError, match="beams must have shape"):
        analyse_batch(accel, beams[:, :3], np.array([600.0, 600.0]), 256.0)
    with pytest.raises(ValueError, match="axle_mass_kg must have shape"):
        analyse_batch(accel, beams, np.array([600.0]), 256.0)
    with pytest.raises(ValueError, match="axle_mass_kg must be finite and positive"):
        analyse_batch(accel, beams, np.array([600.0, np.nan]), 256.0)
    with pytest.raises(ValueError, match="interference_Hz"):
        analyse_batch(accel, beams, np.array([600.0, 600.0]), 256.0, [[1.0]])
