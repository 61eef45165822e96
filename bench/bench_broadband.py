"""Broadband (random-excitation) analysis against the stepped-sine analysis of runs of the same length (issue 34).

Usage: ``python bench/bench_broadband.py [--runs 1000] [--duration 50] [--rolling 0.0]``. Writes, once
and untimed, ``--runs`` stepped-sine runs and as many band-limited random runs of the virtual rig
(:mod:`tyrelab.rig.method_runs`, T1 at 1.38 bar, 256 Hz, ``--duration`` s; a fraction ``--rolling``
of the random runs rolling, which adds the series-damper fit) as the per-run Parquet files ingest
writes, then times in this process (``time.process_time``, CPU seconds):

- *stepped sine*: :func:`tyrelab.stages.analyse.analyse_paths` over the stage's batches of 32
  (read, demodulation, Welch H1 at the excitation, uncertainty, QC);
- *random*: :func:`tyrelab.stages.analyse.analyse_method_path` per run (read, scipy.signal csd and
  welch of 8 blocks, H1/H2/coherence, Kelvin–Voigt fit over the coherent band, batch-means
  uncertainty, the FRF rows; rolling runs also the series-damper fit).

Prints one JSON object: ms per run of each, and ``ratio`` = random / stepped (issue 34: ≤ 3).
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from tyrelab.rig import truth
from tyrelab.rig.instrument import DayCalibration, RigConfig, record, simulate_axle
from tyrelab.rig.method_runs import directional_truth, method_signals
from tyrelab.stages.analyse import analyse_method_path, analyse_paths

FS = 256.0


def _write(frame, path: Path) -> None:
    table = pa.table({c: pa.array(frame[c].to_numpy(np.float64 if c == "time_s" else np.float32))
                      for c in frame.columns})
    pq.write_table(table, path)


def write_runs(folder: Path, n: int, duration_s: float, rolling: float, seed: int = 7):
    """``n`` stepped-sine and ``n`` random runs of T1 (paths, and the random runs' tasks)."""
    rng = np.random.default_rng(seed)
    cfg = RigConfig(sample_rate_Hz=FS)
    k, c, _ = directional_truth("T1", "vertical", 1.38, 0.0, truth.NOMINAL_LOAD_KN)
    stepped, tasks = [], []
    # a handful of distinct recordings, each written under many names (the analysis reads them all)
    base_step = [record(simulate_axle(k, c, duration_s, rng, cfg), DayCalibration(), rng, cfg) for _ in range(4)]
    base_rand = []
    for v in (0.0, 5.0):  # stationary, rolling
        kk, cc, c2 = directional_truth("T1", "lateral", 1.38, v, truth.NOMINAL_LOAD_KN)
        sig, _ = method_signals("random", "lateral", kk, cc, c2, truth.NOMINAL_LOAD_KN, rng, cfg, duration_s=duration_s)
        base_rand.append((record(sig, DayCalibration(), rng, cfg, gravity_m_s2=0.0), v))
    n_rolling = int(round(rolling * n))
    for i in range(n):
        p = folder / f"s{i:05d}.parquet"
        _write(base_step[i % 4], p)
        stepped.append(str(p))
        frame, v = base_rand[1 if i < n_rolling else 0]
        q = folder / f"r{i:05d}.parquet"
        _write(frame, q)
        tasks.append({"path": str(q), "run_id": f"r{i:05d}", "method": "random", "direction": "lateral",
                      "band_Hz": (1.0, 8.0), "axle_mass_kg": 600.0, "rolling": v > 0})
    return stepped, tasks


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=1000)
    ap.add_argument("--duration", type=float, default=50.0)
    ap.add_argument("--rolling", type=float, default=0.0, help="fraction of rolling random runs (series damper)")
    a = ap.parse_args(argv)
    if not 1 <= a.runs <= 20000 or not 10 <= a.duration <= 600 or not 0 <= a.rolling <= 1:
        ap.error("--runs 1-20000, --duration 10-600 s, --rolling 0-1")
    with tempfile.TemporaryDirectory() as tmp:
        stepped, tasks = write_runs(Path(tmp), a.runs, a.duration, a.rolling)
        t0 = time.process_time()
        for i in range(0, len(stepped), 32):
            chunk = stepped[i:i + 32]
            analyse_paths({"paths": chunk, "interference_Hz": [[] for _ in chunk], "axle_mass_kg": [600.0] * len(chunk),
                           "sample_rate_Hz": FS})
        t_step = time.process_time() - t0
        t0 = time.process_time()
        for t in tasks:
            analyse_method_path(t)
        t_rand = time.process_time() - t0
    out = {"runs": a.runs, "duration_s": a.duration, "rolling_fraction": a.rolling,
           "stepped_sine_ms_per_run": round(1e3 * t_step / a.runs, 3),
           "random_ms_per_run": round(1e3 * t_rand / a.runs, 3), "ratio": round(t_rand / t_step, 3),
           "command": "python bench/bench_broadband.py " + " ".join(argv if argv is not None else sys.argv[1:])}
    print(json.dumps(out))
    return out


if __name__ == "__main__":
    main()
