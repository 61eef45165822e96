"""The virtual rig's repeatability (thesis §3.6, issue 14): run-to-run and day-to-day tyre scatter."""

import dataclasses

import numpy as np
import pytest

from tyrelab.rig import truth
from tyrelab.rig.campaigns import campaign_plan, day_state, run_scatter, simulate_run
from tyrelab.rig.instrument import NO_SCATTER, RigConfig

QUIET = dataclasses.replace(RigConfig(), **NO_SCATTER)


def test_scatter_factors_have_the_documented_spread():
    plan = campaign_plan("full")
    runs = plan[plan["kind"] == "measurement"]["run_id"]
    fk, fc = np.array([run_scatter(1991, r) for r in runs]).T
    assert fk.std() == pytest.approx(0.02, rel=0.15) and fc.std() == pytest.approx(0.04, rel=0.15)
    assert abs(fk.mean() - 1) < 0.003 and abs(fc.mean() - 1) < 0.006
    days = plan["recorded_on"].unique()
    dk = np.array([day_state(1991, d).ambient_stiffness_factor for d in days])
    assert 0.008 < dk.std() < 0.025  # 1.5 % over ~60 days
    assert run_scatter(1991, runs.iloc[0], QUIET) == (1.0, 1.0)
    assert day_state(1991, days[0], cfg=QUIET).ambient_damping_factor == 1.0


def test_no_scatter_gives_the_truth_model_and_the_same_noise():
    plan = campaign_plan("small").set_index("run_id")
    row = dict(plan.loc["T1_sweep_001"], run_id="T1_sweep_001")
    run_q, info_q = simulate_run(row, 7, QUIET)
    run_s, info_s = simulate_run(row, 7)
    tyre = truth.tyre_params("T1")
    k = truth.stiffness(tyre, pressure_bar=row["pressure_bar"], speed_km_h=row["speed_km_h"], load_kN=row["load_kN"],
                        torque_kNm=row["torque_kNm"], surface=row["surface"], amplitude_mm_pp=row["amplitude_mm_pp"],
                        frequency_Hz=row["excitation_frequency_Hz"])
    assert info_q["stiffness_N_per_m"] == k
    assert info_s["stiffness_N_per_m"] != k
    fk, _ = run_scatter(7, "T1_sweep_001")
    day = day_state(7, row["recorded_on"])
    assert info_s["stiffness_N_per_m"] == pytest.approx(k * fk * day.ambient_stiffness_factor)
    # the accelerometers see the same commanded motion and noise: only the tyre differs
    assert np.allclose(run_q["accel_left_m_s2"], run_s["accel_left_m_s2"], atol=0.05)
