"""Analysis throughput against a naive per-run baseline and the Parquet read floor (one process).

Usage: ``python bench/bench_analysis.py [--runs 200] [--duration 50]``. Ingests a
closed-form campaign once (not timed), then times, on the same per-run Parquet files:

- *read floor*: reading the six channels of every run with pyarrow, nothing else;
- *tyrelab*: :func:`tyrelab.stages.analyse.analyse_paths` over the stage's batches;
- *naive*: per run ``pandas.read_parquet`` and ``scipy.signal.csd``/``welch`` (H1 at the
  excitation bin), the obvious loop.

Prints one JSON object (runs/s, MB/s, ratios).
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
from scipy import signal

sys.path.insert(0, str(Path(__file__).resolve().parent))
from synthetic_runs import CHANNELS, write_campaign  # noqa: E402

from tyrelab.stages import Context, run_stage  # noqa: E402
from tyrelab.stages.analyse import _batch_task, analyse_paths, batches  # noqa: E402


def read_floor(paths: list[str]) -> None:
    for p in paths:
        pq.read_table(p, columns=CHANNELS)


def tyrelab(runs: pd.DataFrame, tyres: dict) -> None:
    for chunk in batches(runs):
        analyse_paths(_batch_task(chunk, tyres))


def naive(runs: pd.DataFrame) -> None:
    for row in runs.itertuples():
        df = pd.read_parquet(row.run_path)
        a = ((df["accel_left_m_s2"] + df["accel_right_m_s2"]) / 2).to_numpy()
        f = row.axle_mass_kg * a - df[CHANNELS[2:]].sum(axis=1).to_numpy()
        fs = row.sample_rate_Hz
        freqs, g_af = signal.csd(a, f, fs=fs, nperseg=2048)
        _, g_aa = signal.welch(a, fs=fs, nperseg=2048)
        i = int(np.argmin(np.abs(freqs - row.excitation_frequency_Hz)))
        h = -g_af[i] / g_aa[i]
        w = 2 * np.pi * freqs[i]
        _k, _c = np.real(-(w**2) * h), np.real(1j * w * h)


def timed(fn, *args) -> float:
    t0 = time.perf_counter()
    fn(*args)
    return time.perf_counter() - t0


def main(argv=None) -> dict:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--runs", type=int, default=200)
    p.add_argument("--duration", type=float, default=50.0)
    args = p.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        raw = write_campaign(Path(tmp) / "raw", args.runs, args.duration)
        ctx = Context(raw=raw, build=Path(tmp) / "build", jobs=1)
        run_stage("ingest", ctx)
        runs = ctx.read_table("manifest")
        tyres = {r["tyre_id"]: r for _, r in ctx.read_table("tyres").iterrows()}
        paths = runs["run_path"].tolist()
        mb = sum(Path(p).stat().st_size for p in paths) / 1e6
        read_floor(paths)  # warm the page cache: every variant reads from memory
        t_read, t_ours, t_naive = timed(read_floor, paths), timed(tyrelab, runs, tyres), timed(naive, runs)
    n = args.runs
    out = {
        "benchmark": "analysis", "runs": n, "duration_s": args.duration, "parquet_MB": round(mb, 1),
        "read_floor_runs_per_s": round(n / t_read), "tyrelab_runs_per_s": round(n / t_ours),
        "naive_runs_per_s": round(n / t_naive), "tyrelab_MB_per_s": round(mb / t_ours, 1),
        "speedup_vs_naive": round(t_naive / t_ours, 2), "ratio_to_read_floor": round(t_ours / t_read, 2),
    }
    print(json.dumps(out))
    return out


if __name__ == "__main__":
    main()
