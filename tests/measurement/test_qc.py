"""QC flags (thesis §3.5 tolerances) on analytic signals and on a virtual run."""

import numpy as np
import pytest

from tyrelab.measurement import apparent_mass as am
from tyrelab.measurement.qc import clipped, qc_reasons
from tyrelab.rig.campaigns import campaign_plan, simulate_run

FS = 256.0
T = np.arange(int(50 * FS)) / FS


def _sine(amp=4.0, f=4.0, t=T):
    return amp * np.sin(2 * np.pi * f * t)


def test_clean_sine_has_no_reasons():
    a = _sine()
    assert qc_reasons(T, a, -1e5 * a / 631.0, 4.0, 0.99) == []


def test_excitation_blocks_recover_amplitude_and_frequency():
    a = _sine(3.0, 4.03)
    d = am.apparent_mass_demodulation(a, a, FS, 4.0)
    amp, freq = am.excitation_blocks(d.envelope_m_s2, d.angular_frequency_rad_s, FS)
    assert np.allclose(amp, 3.0, rtol=0.01)
    assert np.allclose(freq, 4.03, atol=0.002)


def test_amplitude_drift_flagged():
    a = (1 + 1.0 * T / T[-1]) * _sine()
    assert any(r.startswith("amplitude drift") for r in qc_reasons(T, a, a, 4.0, 0.99))


def test_frequency_drift_flagged():
    f = np.where(T < 25, 3.9, 4.15)
    a = 4 * np.sin(2 * np.pi * np.cumsum(f) / FS)
    reasons = qc_reasons(T, a, a, 4.0, 0.99)
    assert any(r.startswith("frequency drift") for r in reasons)


def test_low_coherence_and_missing_excitation():
    assert any("coherence" in r for r in qc_reasons(T, _sine(), _sine(), 4.0, 0.5))
    noise = np.random.default_rng(0).standard_normal(T.size)
    assert "excitation not found" in qc_reasons(T, noise, noise, float("nan"), 0.1)
    assert "excitation not found" in qc_reasons(T, noise, noise, 4.0, 0.99)


def test_clipping():
    a = np.clip(_sine(4.0), -3.0, 3.0)
    assert clipped(a)
    assert not clipped(_sine(4.0))
    assert "clipping in accel" in qc_reasons(T, a, _sine(), 4.0, 0.99)
    lsb = 2 * 39.2 / 65536
    assert clipped(np.round(_sine(39.3) / lsb) * lsb, full_scale=39.2)


@pytest.mark.parametrize("run_id", ["T1_sweep_004", "T5_surface_002", "F1_amplitude_002"])
def test_virtual_runs_pass(run_id):
    plan = campaign_plan("small").set_index("run_id")
    row = dict(plan.loc[run_id], run_id=run_id)
    run, _ = simulate_run(row, 1991)
    a = (run["accel_left_m_s2"].to_numpy(float) + run["accel_right_m_s2"].to_numpy(float)) / 2
    beams = np.stack([run[f"load_beam_{i}_N"].to_numpy(float) for i in range(1, 5)])
    f = am.tyre_force(run["accel_left_m_s2"].to_numpy(float), run["accel_right_m_s2"].to_numpy(float), beams, 600.0)
    fe = float(am.excitation_frequency(a, FS))
    coh = float(am.apparent_mass_welch(f, a, FS, fe).coherence)
    chans = {c: run[c].to_numpy(float) for c in run.columns if c != "time_s"}
    assert qc_reasons(run["time_s"].to_numpy(), a, f, fe, coh, channels=chans) == []


def test_wheel_excitation_near_excitation_flagged():
    from tyrelab.measurement.qc import interference_frequencies_Hz

    fi = interference_frequencies_Hz(50.0, 3.44)
    assert fi[0] == pytest.approx(50 / 3.6 / 3.44)
    reasons = qc_reasons(T, _sine(), _sine(), 4.0, 0.99, interference_Hz=fi)
    assert any(r.startswith("wheel excitation") for r in reasons)
    assert qc_reasons(T, _sine(), _sine(), 4.0, 0.99, interference_Hz=interference_frequencies_Hz(10.0, 4.66, 23)) == []
