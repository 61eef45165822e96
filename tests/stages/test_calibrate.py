"""The calibrate stage flags runs of a miscalibrated day (thesis §3.2.9)."""

import numpy as np
import pandas as pd
import pytest

from tyrelab.generate import write_run
from tyrelab.rig.campaigns import campaign_plan, simulate_run
from tyrelab.stages import calibrate
from tyrelab.stages.base import Context
from tyrelab.stages.dag import ANALYSED, STAGES


def _context_with_days(tmp_path, **options):
    """Two calibration days (one good, one miscalibrated) and three analysed runs."""
    plan = campaign_plan("small")
    cal_rows = plan[plan["kind"] == "calibration"]
    good = cal_rows[cal_rows["plan_beam_gain_error"] == 0].iloc[-1].to_dict()
    bad = cal_rows[cal_rows["plan_beam_gain_error"] > 0].iloc[0].to_dict()
    manifest = []
    for r in (good, bad):
        run, _ = simulate_run(r, 1991)
        path = tmp_path / "runs" / f"{r['run_id']}.parquet"
        write_run(run, path)
        manifest.append({**{k: v for k, v in r.items() if not k.startswith("plan_")}, "campaign": "c1",
                         "run_path": str(path)})
    ctx = Context(raw=tmp_path, build=tmp_path / "build", **options)
    ctx.write_table("manifest", pd.DataFrame(manifest))
    results = pd.DataFrame({
        "campaign": "c1", "run_id": ["m_good", "m_bad", "m_other_campaign"],
        "recorded_on": [good["recorded_on"], bad["recorded_on"], bad["recorded_on"]],
        "stiffness_N_per_m": 4e5, "damping_N_s_per_m": 2e3, "excitation_frequency_measured_Hz": 4.0,
        "qc_ok": True, "qc_reasons": "", "axle_mass_kg": 600.0,
        "stiffness_u_stat_N_per_m": 100.0, "damping_u_stat_N_s_per_m": 10.0, "uncertainty_dof_stat": 7.0,
    })
    for name in unc_columns():
        if name not in results:
            results[name] = float("nan")
    results["uncertainty_source"] = "§3.2.9 limits"
    results.loc[2, "campaign"] = "c2"
    ctx.write_table(ANALYSED, results)  # what analyse writes; calibrate completes it into results
    return ctx, good, bad


def test_failed_day_flags_its_runs(tmp_path):
    ctx, good, bad = _context_with_days(tmp_path)
    res = calibrate.run(ctx)
    table = ctx.read_table("calibration")
    assert table.set_index("run_id")["pass"].to_dict() == {good["run_id"]: True, bad["run_id"]: False}
    assert len(ctx.read_table("calibration_tf")) > 20
    out = ctx.read_table("results").set_index("run_id")
    assert out.loc["m_good", "qc_ok"] and out.loc["m_other_campaign", "qc_ok"]
    assert not out.loc["m_bad", "qc_ok"]
    assert out.loc["m_bad", "qc_reasons"] == f"calibration failed on {bad['recorded_on']}"
    assert "1 failed" in res.message


def test_the_warning_of_a_failed_day_gives_its_calibration_runs_notes(tmp_path, caplog):
    ctx, good, bad = _context_with_days(tmp_path)
    calibrate.run(ctx)
    said = [r.getMessage() for r in caplog.records if "calibration failed on" in r.getMessage()]
    assert len(said) == 1 and bad["recorded_on"] in said[0]
    assert bad["notes"] and f"(manifest notes: {bad['notes']})" in said[0]  # the demo's: "deliberately miscalibrated"
    assert "deliberately miscalibrated" in said[0]



def unc_columns():
    from tyrelab.measurement.uncertainty import UNCERTAINTY_COLUMNS

    return UNCERTAINTY_COLUMNS


def test_passing_day_replaces_the_limits_by_its_own_budget(tmp_path):
    """Issue 14: a run of a day whose check passed gets that day's (much smaller) instrument uncertainty."""
    ctx, good, bad = _context_with_days(tmp_path)
    calibrate.run(ctx)
    out = ctx.read_table("results").set_index("run_id")
    assert out.loc["m_good", "uncertainty_source"] == f"calibration {good['recorded_on']}"
    assert out.loc["m_bad", "uncertainty_source"] == "§3.2.9 limits"  # failed day: no budget of its own
    assert out.loc["m_other_campaign", "uncertainty_source"] == "§3.2.9 limits"
    u_good, u_bad = out.loc["m_good", "stiffness_u_N_per_m"], out.loc["m_bad", "stiffness_u_N_per_m"]
    assert 100.0 < u_good < 0.2 * u_bad  # limits: 1.7 % of 400 kN/m; the day: type A + 0.17 % gains
    for run in ("m_good", "m_bad"):
        row = out.loc[run]
        half = row["coverage_factor"] * row["stiffness_u_N_per_m"]
        assert row["stiffness_ci95_low_N_per_m"] == pytest.approx(4e5 - half)
        assert row["stiffness_ci95_high_N_per_m"] == pytest.approx(4e5 + half)
    calibrate.run(ctx)  # idempotent
    pd.testing.assert_frame_equal(out, ctx.read_table("results").set_index("run_id"))


def test_calibration_correction_is_an_option_in_the_fingerprint(tmp_path):
    from tyrelab.stages import state

    ctx, good, bad = _context_with_days(tmp_path, calibration_correct=True)
    calibrate.run(ctx)
    out = ctx.read_table("results").set_index("run_id")
    assert "uncorrected_stiffness_N_per_m" in out.columns  # corrected by the good day's transfer function
    assert out.loc["m_good", "uncorrected_stiffness_N_per_m"] == 4e5
    # K + jωC divided by the good day's transfer function at the run's 4 Hz, a bin of the
    # 0.25 Hz calibration spectrum (no interpolation): exact to rounding.
    tf = ctx.read_table("calibration_tf")
    at4 = tf[(tf["run_id"] == good["run_id"]) & np.isclose(tf["frequency_Hz"], 4.0)].iloc[0]
    g = at4["gain"] * np.exp(1j * np.radians(at4["phase_deg"]))
    assert 1e-6 < abs(g - 1) < 0.03  # a passing day (1 ± 3 %), but not exactly 1: the correction acts
    w = 2 * np.pi * 4.0
    z = (4e5 + 1j * w * 2e3) / g
    assert out.loc["m_good", "stiffness_N_per_m"] == pytest.approx(z.real, rel=1e-9)
    assert out.loc["m_good", "damping_N_s_per_m"] == pytest.approx(z.imag / w, rel=1e-9)
    assert out.loc["m_good", "stiffness_kN_per_m"] == pytest.approx(z.real / 1e3, rel=1e-9)
    # runs of the failed day and of a campaign without calibration are left as they were
    assert out.loc["m_bad", "stiffness_N_per_m"] == 4e5 and out.loc["m_other_campaign", "stiffness_N_per_m"] == 4e5
    cache = state.HashCache()
    on = state.input_digests(ctx, STAGES["calibrate"], cache)
    ctx.calibration_correct = False
    off = state.input_digests(ctx, STAGES["calibrate"], cache)
    assert on != off  # switching the option re-runs the stage


def test_progress_of_the_checks_and_of_the_passing_days(tmp_path, caplog):
    """Without a terminal each step logs its count at the end (a bar on a terminal: tyrelab.progress)."""
    import logging

    ctx, good, bad = _context_with_days(tmp_path)
    days = []
    calibrate.day_uncertainty(ctx.read_table(ANALYSED), pd.DataFrame(), pd.DataFrame(), {}, False,
                              on_day=lambda: days.append(1))
    with caplog.at_level(logging.INFO, logger="tyrelab"):
        calibrate.run(ctx)
    assert days == []  # nothing checked, no day
    assert "calibrate: force-plate checks: 2/2 runs" in caplog.text
    assert "calibrate: uncertainty of passing days: 1/1 days" in caplog.text
    assert len(calibrate.passing_days(ctx.read_table("calibration"))) == 1
