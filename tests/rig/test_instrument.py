"""Virtual instrument: raw-format contract, analysis accuracy, an independent recording."""

import hashlib
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.integrate import solve_ivp

from tyrelab.generate import generate_campaign
from tyrelab.measurement import apparent_mass as am
from tyrelab.rawformat import CHANNELS
from tyrelab.rig import instrument as ins
from tyrelab.rig.campaigns import MANIFEST_COLUMNS, campaign_plan, simulate_run

FS = 256.0


def _analyse(run: pd.DataFrame, axle_mass_kg: float = 600.0):
    l, r = run["accel_left_m_s2"].to_numpy(float), run["accel_right_m_s2"].to_numpy(float)
    beams = np.stack([run[f"load_beam_{i}_N"].to_numpy(float) for i in range(1, 5)])
    f = am.tyre_force(l, r, beams, axle_mass_kg)
    d = am.apparent_mass_demodulation(f, (l + r) / 2, FS)
    return float(d.stiffness_N_per_m), float(d.damping_N_s_per_m)


def test_tyre_force_contract_exact_without_instrument_errors():
    """M_a*mean(acc) - sum(beams) is the tyre ground force -(Kx + Cx') + L (+ n)."""
    cfg = ins.RigConfig(noise_scale=0.0, nonlinear_fraction=0.0)
    K, C = 400e3, 2.0e3
    sig = ins.simulate_axle(K, C, 20.0, np.random.default_rng(1), cfg, speed_km_h=5.0, surface="pasture_grass",
                            lug_height_mm=45, traction=True)
    d = sig.axle_displacement_m - sig.ground_displacement_m
    dd = np.gradient(d, 1 / FS)
    expected = 18.3e3 - K * d - C * dd
    assert np.allclose(sig.tyre_force_N[5:-5], expected[5:-5], atol=0.01 * K * d.std())
    run = ins.record(sig, ins.DayCalibration(), np.random.default_rng(2), cfg)
    assert list(run.columns) == ["time_s", *CHANNELS]
    ft = ins.derived_tyre_force(run, cfg.axle_mass_kg)
    assert np.abs(ft - sig.tyre_force_N).max() < 5.0  # quantisation of 4 beams and 2 accelerometers only
    assert ft.mean() == pytest.approx(18.3e3, rel=1e-3)  # static load on the tyre, upward positive
    # upward positive: while the axle is high the tyre pushes less
    assert np.corrcoef(sig.axle_displacement_m, ft)[0, 1] < -0.8


def test_amplitude_and_frequency_held_within_thesis_tolerances():
    sig = ins.simulate_axle(300e3, 1e3, 50.0, np.random.default_rng(3), frequency_Hz=4.0, amplitude_mm_pp=14.0)
    x = sig.axle_displacement_m
    assert 2 * np.sqrt(2) * x.std() * 1e3 == pytest.approx(14.0, rel=0.1)


#: Tolerances (K, C) of the demodulated run against the truth. On concrete the errors are
#: instrument noise and quantisation: over seeds 7-9, |K| <= 0.12 %, |C| <= 0.75 % (C is the
#: small quadrature part, largest for the lightly damped F1/AS6); allowed 0.5 % and 2 %. On
#: a rough surface the ground under the tyre moves and is not measured: its component at the
#: excitation frequency scatters K by ~1.5 % and C by ~10 % (seeds 7-9: +9, +13, -8 %);
#: allowed 3 % and 20 %.
CONCRETE, ROUGH = (0.005, 0.02), (0.03, 0.20)


@pytest.mark.parametrize("run_id,tol", [("T1_sweep_001", CONCRETE), ("T2_sweep_005", CONCRETE),
                                        ("F1_sweep_009", CONCRETE), ("AS6_sweep_006", CONCRETE),
                                        ("T5_surface_003", ROUGH), ("T1_frequency_001", CONCRETE),
                                        ("F1_amplitude_001", CONCRETE)])
def test_virtual_runs_give_back_the_truth(run_id, tol):
    plan = campaign_plan("small").set_index("run_id")
    row = dict(plan.loc[run_id], run_id=run_id)
    run, info = simulate_run(row, 7)
    K, C = _analyse(run)
    assert K == pytest.approx(info["stiffness_N_per_m"], rel=tol[0])
    assert C == pytest.approx(info["damping_N_s_per_m"], rel=tol[1])


def test_independent_recording_solve_ivp():
    """A spring-damper integrated with solve_ivp, channels written by hand in raw v1, not by our generator."""
    K, C, M_a, M_c, L = 350e3, 2.5e3, 600.0, 1265.0, 18.3e3
    kb, kl = 1.5e7, 40e3
    f0, F0 = 3.8, 2.5e3
    dur = 50.0

    def rhs(t, y):
        xa, va, xc, vc = y
        fb = kb * (xc - xa)
        ft = -K * xa - C * va
        fd = F0 * np.sin(2 * np.pi * f0 * t) * (1 + 0.1 * np.sin(2 * np.pi * 0.05 * t))
        return [va, (ft + fb) / M_a, vc, (-fb - kl * xc + fd) / M_c]

    t = np.arange(int((dur + 10) * FS)) / FS
    sol = solve_ivp(rhs, (0, t[-1]), [0, 0, 0, 0], t_eval=t, method="DOP853", rtol=1e-9, atol=1e-12)
    xa, va, xc, vc = sol.y
    acc = np.gradient(va, t, edge_order=2)
    acc = np.array([rhs(ti, yi)[1] for ti, yi in zip(t, sol.y.T)])
    ft = L - K * xa - C * va
    fb_total = M_a * (acc + 9.80665) - ft
    keep = t >= 10
    rng = np.random.default_rng(0)
    run = pd.DataFrame({"time_s": t[keep] - 10})
    for side in ("left", "right"):
        run[f"accel_{side}_m_s2"] = acc[keep] + 9.80665 + 0.01 * rng.standard_normal(keep.sum())
    for i in range(1, 5):
        run[f"load_beam_{i}_N"] = fb_total[keep] / 4 + 2.0 * rng.standard_normal(keep.sum())
    Kest, Cest = _analyse(run, M_a)
    assert Kest == pytest.approx(K, rel=0.01)
    assert Cest == pytest.approx(C, rel=0.03)


def test_generate_small_is_deterministic_and_in_raw_v1(tmp_path, monkeypatch):
    """Two campaigns of the same seed are the same bytes. On a two-run plan (the small plan's first
    measurement run and first calibration run: every kind of file the generator writes), not the
    whole campaign twice: the runs are simulated one by one from (row, seed), so two runs prove it."""
    from tyrelab import generate as gen

    whole = gen.campaign_plan

    def two_runs(scale, cfg):
        plan = whole(scale, cfg)
        return pd.concat([plan[plan["kind"] == kind].head(1) for kind in ("measurement", "calibration")])

    monkeypatch.setattr(gen, "campaign_plan", two_runs)

    def digest(folder: Path) -> str:
        h = hashlib.sha256()
        for p in sorted(folder.rglob("*")):
            if p.is_file():
                h.update(p.relative_to(folder).as_posix().encode())
                h.update(p.read_bytes())
        return h.hexdigest()

    s1 = generate_campaign(tmp_path / "a", "small", seed=5)
    assert s1["seconds"] >= 0  # reported; how long it takes is measured in bench/, not asserted here
    generate_campaign(tmp_path / "b", "small", seed=5)
    assert digest(tmp_path / "a") == digest(tmp_path / "b")
    m = pd.read_csv(tmp_path / "a" / "manifest.csv")
    assert list(m.columns) == MANIFEST_COLUMNS
    assert set(m["kind"]) == {"measurement", "calibration"}
    assert not (tmp_path / "a" / "tyres.csv").exists()
    run = pd.read_parquet(tmp_path / "a" / m.loc[m["kind"] == "calibration", "file"].iloc[0])
    assert list(run.columns) == ["time_s", *CHANNELS, "force_plate_N"]
    assert s1["runs"] == len(m) and m["run_id"].is_unique
    meta = json.loads((tmp_path / "a" / "generator.json").read_text())
    assert (meta["seed"], meta["scale"], meta["runs"]) == (5, "small", len(m))
