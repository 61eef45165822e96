"""Fast closed-form campaigns for the benchmarks (a spring-damper tyre per run, as tests/synthetic.py).

Writes a campaign folder in raw format v1 (``manifest.csv`` + ``runs/*.parquet``)
with ``n`` runs whose stiffness, damping, frequency and noise vary with the
run index, at a few thousand runs per second.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from tyrelab.rawformat import CHANNELS  # noqa: F401  (the raw format's one home; used by the benchmarks)

SPLIT = np.array([0.26, 0.24, 0.27, 0.23])


def run_table(i: int, duration_s: float, fs: float, rng: np.random.Generator) -> tuple[pa.Table, dict]:
    """One run: ``x = X sin(ωt)``, ``f_t = W - (K x + C x')``, beams = ``M a - f_t``, plus noise."""
    k, c, f = 150e3 + 50 * (i % 4000), 1500.0 + (i % 7) * 100, 2.0 + 0.5 * (i % 8)
    t = np.arange(int(duration_s * fs)) / fs
    w, amp = 2 * np.pi * f, 0.007
    x, v = amp * np.sin(w * t), amp * w * np.cos(w * t)
    a = -(w**2) * x
    beams = 600.0 * a - (18300.0 - (k * x + c * v))
    cols = {"time_s": t, "accel_left_m_s2": a + rng.normal(0, 0.05, t.size),
            "accel_right_m_s2": a + rng.normal(0, 0.05, t.size)}
    for j, s in enumerate(SPLIT, start=1):
        cols[f"load_beam_{j}_N"] = s * beams + rng.normal(0, 50, t.size)
    return pa.table(cols), {"excitation_frequency_Hz": f, "pressure_bar": round(0.8 + 0.1 * (i % 10), 2)}


def write_campaign(folder: Path, n: int, duration_s: float = 50.0, fs: float = 256.0, seed: int = 0) -> Path:
    """Write ``n`` runs and their manifest; return the folder."""
    folder = Path(folder)
    (folder / "runs").mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    rows = []
    for i in range(n):
        table, cond = run_table(i, duration_s, fs, rng)
        pq.write_table(table, folder / "runs" / f"r{i:05d}.parquet", compression="zstd")
        rows.append(dict(run_id=f"r{i:05d}", file=f"runs/r{i:05d}.parquet", tyre_id="T1", speed_km_h=10.0,
                         load_kN=18.3, amplitude_mm_pp=14.0, torque_kNm=0.0, surface="concrete",
                         axle_mass_kg=600.0, recorded_on="1990-06-01", **cond))
    pd.DataFrame(rows).to_csv(folder / "manifest.csv", index=False)
    return folder
