"""Issue 34: every rig method and direction, recovered from recordings with known K and C.

The recordings come from tests/synthetic_methods.py (exactly solved single-mass systems,
independent of tyrelab's virtual rig); each method must put the truth inside its stated 95 %
interval in at least 93 % of runs, and refuse with a reason what it cannot measure.
"""

import numpy as np
import pandas as pd
import pytest

from tests.synthetic_methods import broadband_recording, free_decay_recording, load_deflection_recording

from tyrelab.measurement import broadband as bb
from tyrelab.measurement import rig_methods as rm
from tyrelab.measurement.recording import recording_arrays


def _analyse(method, frame, *, direction="vertical", rolling=False, band=(1.0, 8.0)):
    accel, beams = recording_arrays(frame)
    d = frame["deflection_m"].to_numpy() if "deflection_m" in frame else None
    row, frf = rm.analyse_method_run(method, direction, frame["time_s"].to_numpy(), accel, beams, 600.0,
                                     band_Hz=band, rolling=rolling, deflection_m=d, run_id="R")
    return row, frf


def _covered(rows, name, unit, truth):
    return np.mean([r[f"{name}_ci95_low_{unit}"] < truth < r[f"{name}_ci95_high_{unit}"] for r in rows])


@pytest.mark.parametrize("method, series_C, direction", [
    ("random", None, "vertical"), ("swept_sine", None, "lateral"), ("random", 9e3, "longitudinal")])
def test_broadband_recovers_known_k_and_c_within_its_intervals(method, series_C, direction):
    K, C = 420e3, 2.6e3
    rows = []
    for seed in range(15):
        frame = broadband_recording(K, C, series_C, method=method, seed=seed)
        row, frf = _analyse(method, frame, direction=direction, rolling=series_C is not None)
        assert row["direction"] == direction and row["method"] == method and not row["reasons"]
        rows.append(row)
    assert {r["model"] for r in rows} == {"maxwell" if series_C else "kelvin_voigt"}
    assert _covered(rows, "stiffness", "N_per_m", K) >= 0.93
    assert _covered(rows, "damping", "N_s_per_m", C) >= 0.93
    if series_C:
        assert _covered(rows, "series_damping", "N_s_per_m", series_C) >= 0.93
    k = np.mean([r["stiffness_N_per_m"] for r in rows])
    assert k == pytest.approx(K, rel=0.02)
    # the FRF: one row per bin of the band, K(f) and C(f) near the truth where coherent
    assert list(frf.columns) == rm.FRF_COLUMNS and frf["frequency_Hz"].between(1.0, 8.0).all()
    fit = frf.loc[frf["in_fit"]]
    assert (fit["coherence"] >= bb.MIN_COHERENCE).all() and len(fit) >= 10
    if series_C is None:
        assert np.median(fit["stiffness_N_per_m"]) == pytest.approx(K, rel=0.03)


def test_h1_of_a_pure_mass_is_the_mass_and_the_model_fit_is_exact():
    f = np.linspace(1.5, 7.5, 13)
    z = bb.maxwell_impedance(2 * np.pi * f, 4e5, 1.5e3, 8e3)
    m = bb.fit_model(f, z, np.full(f.size, 1e3), "maxwell")
    assert (m.stiffness_N_per_m, m.damping_N_s_per_m, m.series_damping_N_s_per_m) == pytest.approx((4e5, 1.5e3, 8e3))
    kv = bb.fit_model(f, bb.kelvin_voigt_impedance(2 * np.pi * f, 3e5, 2e3), np.full(f.size, 1e3))
    assert (kv.stiffness_N_per_m, kv.damping_N_s_per_m) == pytest.approx((3e5, 2e3))


def test_the_residual_decides_the_model_of_a_rolling_tyre():
    kv, _ = _analyse("random", broadband_recording(420e3, 2.6e3, None, seed=3), rolling=True)
    mw, _ = _analyse("random", broadband_recording(420e3, 2.6e3, 6e3, seed=3), rolling=True)
    assert mw["model"] == "maxwell" and mw["maxwell_reduced_chi2"] < mw["kelvin_voigt_reduced_chi2"]
    # a stationary tyre is fitted as Kelvin-Voigt only
    st, _ = _analyse("random", broadband_recording(420e3, 2.6e3, None, seed=3))
    assert st["model"] == "kelvin_voigt" and np.isnan(st["maxwell_reduced_chi2"] if "maxwell_reduced_chi2" in st
                                                      else np.nan)
    assert kv["stiffness_ci95_low_N_per_m"] < 420e3 < kv["stiffness_ci95_high_N_per_m"]


def test_low_coherence_is_refused_with_its_reason():
    frame = broadband_recording(420e3, 2.6e3, force_rms_N=50.0, force_noise_N=4e3, seed=1)
    row, frf = _analyse("random", frame)
    assert row["reasons"] and "coherence below 0.9" in row["reasons"][0] and "not reported" in row["reasons"][0]
    assert np.isnan(row.get("stiffness_N_per_m", np.nan)) and len(frf)  # the FRF is still there to look at


def test_free_vibration_recovers_known_k_and_c():
    K, C, m = 400e3, 4.5e3, 1800.0
    rows = [_analyse("free_vibration", free_decay_recording(K, C, m, seed=s))[0] for s in range(20)]
    assert all(not r["reasons"] for r in rows)
    assert _covered(rows, "stiffness", "N_per_m", K) >= 0.93
    assert _covered(rows, "damping", "N_s_per_m", C) >= 0.93
    assert np.mean([r["moving_mass_kg"] for r in rows]) == pytest.approx(m, rel=0.01)
    wn = np.sqrt(K / m)
    assert rows[0]["natural_frequency_Hz"] == pytest.approx(wn / 2 / np.pi, rel=0.01)
    assert rows[0]["damping_ratio"] == pytest.approx(C / (2 * m * wn), rel=0.05)


def test_free_vibration_that_never_decays_is_refused_and_rolling_gets_the_caveat():
    row, _ = _analyse("free_vibration", free_decay_recording(400e3, 4.5e3, decays=False))
    assert row["reasons"] and row["reasons"][0].startswith("no free decay")
    row, _ = _analyse("free_vibration", free_decay_recording(400e3, 4.5e3), rolling=True)
    assert not row["reasons"] and "thesis §3.4" in row["method_note"] and "rolling" in row["method_note"]


def test_load_deflection_secant_tangent_and_the_loop_as_creep_not_damping():
    """Issue 44: the slow loop's equivalent viscous coefficient is creep, its own column; the run's
    damping is null, so it never enters a damping average."""
    K, C = 330e3, 40e3
    rows = [_analyse("load_deflection", load_deflection_recording(K, C, seed=s))[0] for s in range(15)]
    assert _covered(rows, "stiffness", "N_per_m", K) >= 0.93
    creep = np.array([r["creep_coefficient_N_s_per_m"] for r in rows])
    u = np.array([r["creep_coefficient_u_N_s_per_m"] * r["coverage_factor"] for r in rows])
    assert np.mean(np.abs(creep - C) <= u) >= 0.93
    assert all(np.isnan(r["damping_N_s_per_m"]) and np.isnan(r["damping_ci95_low_N_s_per_m"]) for r in rows)
    r = rows[0]
    assert r["secant_stiffness_N_per_m"] == pytest.approx(K, rel=0.02)
    assert r["tangent_stiffness_N_per_m"] == pytest.approx(K, rel=0.05)
    assert r["hysteresis_energy_J"] > 0


def test_channels_that_do_not_fit_the_method_are_named_in_one_line():
    frame = load_deflection_recording(330e3, 4e4, with_deflection=False)
    msg = rm.channel_problem("LD7", "load_deflection", frame.columns)
    assert msg.startswith("run LD7: method load_deflection needs channel deflection_m") and "\n" not in msg
    assert rm.channel_problem("LD7", "random", frame.columns) is None
    with pytest.raises(ValueError, match="direction"):
        _analyse("random", broadband_recording(4e5, 2e3), direction="diagonal")
    with pytest.raises(ValueError, match="band_Hz"):
        rm.analyse_method_run("random", "vertical", np.arange(10.0), np.zeros((2, 10)), np.zeros((4, 10)), 600.0)
