"""analyse_batch: the estimators and QC on a batch of runs in raw-format channels."""

import numpy as np

from tyrelab.stages.analyse import analyse_batch, load_signals
from tests.synthetic import CHANNELS, spring_damper_recording


def batch(*recordings):
    accel = np.array([[r[c].to_numpy() for c in CHANNELS[:2]] for r in recordings], dtype=np.float32)
    beams = np.array([[r[c].to_numpy() for c in CHANNELS[2:]] for r in recordings], dtype=np.float32)
    return accel, beams


def test_clipped_channel_is_flagged_and_clean_run_is_not():
    clean = spring_damper_recording(force_noise_N=50, seed=1)
    clipped = spring_damper_recording(force_noise_N=50, seed=2)
    rail = np.quantile(clipped["load_beam_2_N"], 0.97)
    clipped["load_beam_2_N"] = np.minimum(clipped["load_beam_2_N"], rail)  # flat tops at a converter rail
    accel, beams = batch(clean, clipped)
    out = analyse_batch(accel, beams, np.array([600.0, 600.0]), 256.0)
    assert out["qc_ok"].tolist() == [True, False]
    assert "clipping in load_beam_2_N" in out["qc_reasons"].iloc[1]


def test_float32_batch_recovers_k_and_c():
    accel, beams = batch(spring_damper_recording(300e3, 2500.0), spring_damper_recording(150e3, 900.0, 3.3))
    out = analyse_batch(accel, beams, np.array([600.0, 600.0]), 256.0)
    np.testing.assert_allclose(out["stiffness_kN_per_m"], [300.0, 150.0], rtol=0.005)
    np.testing.assert_allclose(out["damping_kN_s_per_m"], [2.5, 0.9], rtol=0.01)


def test_load_signals_keeps_float32(tmp_path):
    spring_damper_recording().to_parquet(tmp_path / "a.parquet")
    spring_damper_recording(seed=3).to_parquet(tmp_path / "b.parquet")
    accel, beams = load_signals([str(tmp_path / "a.parquet"), str(tmp_path / "b.parquet")])
    assert accel.shape == (2, 2, 12800) and beams.shape == (2, 4, 12800) and accel.dtype == np.float32


def test_reversed_acceleration_sign_is_flagged():
    # Deflection-positive accelerations (the thesis' convention) instead of upward-positive:
    # K comes out plausible but wrong, C negative -> QC must not pass the run.
    rec = spring_damper_recording(force_noise_N=50, seed=4)
    for c in ("accel_left_m_s2", "accel_right_m_s2"):
        rec[c] = -rec[c]
    accel, beams = batch(rec)
    out = analyse_batch(accel, beams, np.array([600.0]), 256.0)
    assert not out["qc_ok"].iloc[0]
    assert "non-positive damping" in out["qc_reasons"].iloc[0]


def test_excitation_not_found_quarantine_names_the_file(tmp_path):
    from tyrelab.stages import Context, run_stage
    from tests.synthetic import manifest_row, write_campaign

    flat = spring_damper_recording(amplitude_mm_pp=0.0)
    raw = write_campaign(tmp_path / "raw", [(manifest_row("flat", "flat.parquet"), flat)])
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1)
    run_stage("ingest", ctx)
    r = run_stage("analyse", ctx)
    q = ctx.read_table("quarantine")
    row = q[q["stage"] == "analyse"]
    assert r.n_quarantined == 1 and row["file"].iloc[0].endswith("flat.parquet")


def test_a_run_analysed_alone_gives_the_bytes_it_gives_in_a_batch(tmp_path):
    """An added run is analysed in a batch of its own; a clean build puts it in a batch with others.

    numpy sums a (1, n) batch along another path than a (rows >= 2, n) one: the type A
    uncertainty moved in its last bit (every run of the demo campaign) before a lone run was
    analysed as two copies of itself.
    """
    import pandas as pd

    from tyrelab.stages.analyse import analyse_paths

    paths = []
    for i, (k, c) in enumerate(((300e3, 2500.0), (150e3, 900.0), (220e3, 1600.0))):
        paths.append(str(tmp_path / f"r{i}.parquet"))
        spring_damper_recording(k, c, force_noise_N=80.0, seed=10 + i).to_parquet(paths[-1])

    def task(ps):
        return {"paths": ps, "interference_Hz": [[5.2] for _ in ps], "axle_mass_kg": [600.0] * len(ps),
                "sample_rate_Hz": 256.0}

    together = analyse_paths(task(paths))
    for i, p in enumerate(paths):
        alone = analyse_paths(task([p]))
        assert len(alone) == 1
        pd.testing.assert_frame_equal(alone, together.iloc[[i]].reset_index(drop=True), check_exact=True)
