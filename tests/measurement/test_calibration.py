"""Force-plate calibration check (thesis §3.2.9)."""

import numpy as np
import pandas as pd
import pytest

from tyrelab.measurement import calibration as cal
from tyrelab.rig.campaigns import campaign_plan, simulate_run
from tyrelab.rig.instrument import derived_tyre_force

FS = 256.0


def _random(n=60 * 256, seed=0):
    x = np.random.default_rng(seed).standard_normal(n)
    return np.convolve(x, np.ones(8) / 8, mode="same") * 1e3


def test_identity_passes_and_sign_of_phase():
    fp = _random()
    tf = cal.calibration_transfer_function(fp, fp, FS)
    assert cal.check_calibration(tf)["pass"]
    # derived force lagging the plate by 2 samples: negative phase, fails the 1 degree limit at 6 Hz
    late = np.roll(fp, 2)
    tf = cal.calibration_transfer_function(fp, late, FS)
    c = cal.check_calibration(tf)
    assert not c["pass"] and c["mean_phase_deg"] < 0
    assert c["max_phase_error_deg"] == pytest.approx(360 * 6.0 * 2 / FS, rel=0.05)


def test_inertial_ratio_and_the_phase_a_gain_mismatch_gives_the_check():
    fp = _random()
    inertial = 1.5 * fp + 0.4 * np.roll(fp, 3)  # M_a a: a ratio with an imaginary part
    tf = cal.calibration_transfer_function(fp, fp, FS, inertial_force_N=inertial)
    r = tf["inertial_ratio_re"].to_numpy() + 1j * tf["inertial_ratio_im"].to_numpy()
    w = 2 * np.pi * tf["frequency_Hz"].to_numpy() / FS
    np.testing.assert_allclose(r, 1.5 + 0.4 * np.exp(-3j * w), atol=5e-3)  # Welch: a delay leaks a little
    # accelerometers 0.3 % high, beams exact: derived = f_t + 0.003 M_a a; phase (da - db) Im R (no force-path phase)
    tf2 = cal.calibration_transfer_function(fp, fp + 0.003 * inertial, FS, inertial_force_N=inertial)
    np.testing.assert_allclose(np.radians(tf2["phase_deg"]), 0.003 * r.imag, rtol=0.02, atol=1e-7)
    assert "inertial_ratio_re" not in cal.calibration_transfer_function(fp, fp, FS)


def test_gain_error_detected():
    fp = _random()
    c = cal.check_calibration(cal.calibration_transfer_function(fp, 1.04 * fp, FS))
    assert not c["pass"] and c["max_gain_error_pct"] == pytest.approx(4.0, abs=0.05)
    assert cal.check_calibration(cal.calibration_transfer_function(fp, 1.02 * fp, FS))["pass"]


def test_limits_are_inclusive():
    """§3.2.9: within 1 ± 3 % and 0 ± 1°, limits included (tolerances chosen so the errors are exact in binary)."""
    tf = pd.DataFrame({"frequency_Hz": [2.0, 4.0, 6.0], "gain": [1.0, 1.5, 1.0], "phase_deg": [0.0, -2.0, 0.0]})
    assert cal.check_calibration(tf, gain_tolerance=0.5, phase_tolerance_deg=2.0)["pass"]
    assert not cal.check_calibration(tf, gain_tolerance=0.25, phase_tolerance_deg=2.0)["pass"]
    assert not cal.check_calibration(tf, gain_tolerance=0.5, phase_tolerance_deg=1.0)["pass"]


def test_virtual_days_good_and_miscalibrated():
    plan = campaign_plan("small")
    rows = plan[plan["kind"] == "calibration"].to_dict("records")
    good = next(r for r in rows if r["plan_beam_gain_error"] == 0 and r["tyre_id"] == "T1")
    bad = next(r for r in rows if r["plan_beam_gain_error"] > 0)
    out = {}
    for r in (good, bad):
        run, _ = simulate_run(r, 1991)
        tf = cal.calibration_transfer_function(run["force_plate_N"].to_numpy(float), derived_tyre_force(run, 600.0), FS)
        out[r["run_id"]] = cal.check_calibration(tf)
    assert out[good["run_id"]]["pass"]
    assert not out[bad["run_id"]]["pass"] and out[bad["run_id"]]["max_gain_error_pct"] > 3


def test_flag_failed_days_idempotent_and_clears():
    results = pd.DataFrame({"run_id": ["a", "b", "c"], "recorded_on": ["1989-05-01", "1989-05-02", "1989-05-02"],
                            "qc_ok": [True, True, False], "qc_reasons": ["", "", "coherence 0.50 < 0.9"]})
    days = pd.DataFrame({"day": ["1989-05-01", "1989-05-02"], "day_pass": [True, False]})
    f1 = cal.flag_failed_days(results, days)
    assert f1["qc_ok"].tolist() == [True, False, False]
    assert f1["qc_reasons"].tolist()[1:] == ["calibration failed on 1989-05-02",
                                             "coherence 0.50 < 0.9; calibration failed on 1989-05-02"]
    assert cal.flag_failed_days(f1, days).equals(f1)
    cleared = cal.flag_failed_days(f1, days.assign(day_pass=True))
    assert cleared["qc_ok"].tolist() == [True, True, False]


def test_correction_by_calibration():
    f = np.linspace(1, 8, 29)
    tf = pd.DataFrame({"frequency_Hz": f, "gain": 1.02, "phase_deg": 0.5})
    w = 2 * np.pi * 4.0
    z = (300e3 + 1j * w * 1.5e3) * 1.02 * np.exp(1j * np.radians(0.5))
    k, c = cal.corrected_stiffness_damping(z.real, z.imag / w, 4.0, tf)
    assert (k, c) == pytest.approx((300e3, 1.5e3), rel=1e-9)


def test_correction_factor_checks_its_arguments():
    import pandas as pd
    import pytest

    from tyrelab.measurement.calibration import correction_factor

    tf = pd.DataFrame({"frequency_Hz": [2.0, 6.0], "gain": [1.0, 1.02], "phase_deg": [0.0, 1.0]})
    assert abs(correction_factor(tf, 4.0)) == pytest.approx(1.01)
    with pytest.raises(ValueError, match="frequency_Hz"):
        correction_factor(tf, 0.0)
    with pytest.raises(ValueError, match="tf is empty"):
        correction_factor(tf.iloc[:0], 4.0)


def test_default_limits_band_and_percent_of_the_check():
    """§3.2.9 defaults: gain 1 ± 3 %, phase 0 ± 1°, judged over 2-6 Hz inclusive; the transfer function is
    returned over the 1-8 Hz excitation band, ends included."""
    f = np.array([1.5, 2.0, 4.0, 6.0, 6.5])

    def check(gain_at, phase_at):
        g, p = np.ones(f.size), np.zeros(f.size)
        g[gain_at[0]], p[phase_at[0]] = gain_at[1], phase_at[1]
        return cal.check_calibration(pd.DataFrame({"frequency_Hz": f, "gain": g, "phase_deg": p}))

    assert check((2, 1.025), (2, 0.9))["pass"]
    assert not check((2, 1.035), (2, 0.0))["pass"] and not check((2, 1.0), (2, 1.1))["pass"]
    assert not check((1, 1.04), (1, 0.0))["pass"] and not check((3, 1.0), (3, -1.5))["pass"]  # the band's ends count
    assert check((0, 1.5), (4, 10.0))["pass"]  # outside 2-6 Hz nothing counts
    c = check((2, 1.04), (2, 0.0))
    assert c["max_gain_error_pct"] == pytest.approx(4.0, rel=1e-9) and c["mean_gain"] == pytest.approx(3.04 / 3, rel=1e-12)  # over 2, 4 and 6 Hz
    tf = cal.calibration_transfer_function(_random(), _random(), FS)
    assert (tf["frequency_Hz"].iloc[0], tf["frequency_Hz"].iloc[-1]) == (1.0, 8.0)
    assert np.allclose(np.diff(tf["frequency_Hz"]), 0.25)
