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


def test_interference_frequencies_and_tolerance():
    from tyrelab.measurement.qc import interference_frequencies_Hz

    f_rot = 10 / 3.6 / 4.66
    got = interference_frequencies_Hz(10.0, 4.66, 23)  # rotation, 2 harmonics, half lug and lug passing
    assert got == pytest.approx([f_rot, 2 * f_rot, 3 * f_rot, 23 * f_rot, 46 * f_rot])
    assert interference_frequencies_Hz(10.0, 0.0) == [] and interference_frequencies_Hz(0.0, 4.66) == []
    # within 0.15 Hz of the excitation flags, 0.2 Hz away does not
    assert qc_reasons(T, _sine(), _sine(), 4.0, 0.99, interference_Hz=[4.2]) == []
    assert any(r.startswith("wheel excitation") for r in qc_reasons(T, _sine(), _sine(), 4.0, 0.99, interference_Hz=[4.1]))


def test_reasons_name_the_limits_and_values_in_their_units():
    from tyrelab.measurement.qc import plausibility_reasons

    a = (1 + 1.0 * T / T[-1]) * _sine()
    drift = [r for r in qc_reasons(T, a, a, 4.0, 0.99) if r.startswith("amplitude drift")][0]
    assert drift.endswith("% > 20 %")  # thesis §3.5: amplitude within ±20 %
    assert plausibility_reasons(250e3, 2000.0) == []
    assert plausibility_reasons(0.5, 2000.0) == []  # 0.5 N/m is tiny but positive
    k, c = plausibility_reasons(-2e3, -1500.0)
    assert k == "non-positive stiffness K = -2.0 kN/m" and c.startswith("non-positive damping C = -1.50 kN s/m")


def test_clipped_of_one_channel_is_a_bool_and_of_several_an_array():
    assert clipped(np.array([])) is False
    flags = clipped(np.vstack([np.clip(_sine(4.0), -3.0, 3.0), _sine(4.0)]))
    assert flags.tolist() == [True, False]

def test_interference_arguments_are_checked():
    import pytest

    from tyrelab.measurement.qc import interference_frequencies_Hz

    assert interference_frequencies_Hz(0.0, 4.66, 20) == []
    assert interference_frequencies_Hz(16.776, 4.66, 0, harmonics=1) == pytest.approx([1.0])
    for args, name in (((-5.0, 4.66), "speed_km_h"), ((5.0, float("nan")), "circumference_m"),
                       ((5.0, 4.66, -1), "lugs_per_side")):
        with pytest.raises(ValueError, match=name):
            interference_frequencies_Hz(*args)

def test_zero_stiffness_is_not_plausible():
    from tyrelab.measurement.qc import plausibility_reasons

    assert plausibility_reasons(0.0, 2000.0) == ["non-positive stiffness K = 0.0 kN/m"]
