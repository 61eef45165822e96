"""Analysis throughput against a naive per-run baseline and the Parquet read floor (one process).

Usage: ``python bench/bench_analysis.py [--runs 200] [--duration 50]``. Ingests a
closed-form campaign once (not timed), then times, on the same per-run Parquet files:

- *read floor*: reading the six channels of every run with pyarrow, nothing else;
- *tyrelab*: :func:`tyrelab.stages.analyse.analyse_paths` over the stage's batches;
- *naive*: per run ``pandas.read_parquet`` and ``scipy.signal.csd``/``welch`` (H1 at the
  excitation bin), the obvious loop.

Prints one JSON object (runs/s, MB/s, ratios). With ``--steps``, it also holds
``steps_ms_per_run``: the CPU milliseconds per run (``time.process_time``, same process) of each
step of :func:`tyrelab.measurement.recording.analyse_batch` called one by one on the same batches
(read, tyre force, excitation search, demodulation, Welch H1, uncertainty, excitation blocks,
clipping screen) and of the whole ``analyse_paths``; ``other`` is the rest of ``analyse_paths``
(the per-run QC verdicts and the result table).
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
from tyrelab.stages.analyse import _batch_task, analyse_paths, batches, load_signals  # noqa: E402


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


def steps(runs: pd.DataFrame, tyres: dict) -> dict[str, float]:
    """CPU ms per run of each step of the analysis, called one by one (see the module docstring)."""
    from tyrelab.measurement import apparent_mass as am
    from tyrelab.measurement import qc
    from tyrelab.measurement import uncertainty as unc

    spent: dict[str, float] = {}

    def step(name: str, t0: float) -> float:
        now = time.process_time()
        spent[name] = spent.get(name, 0.0) + now - t0
        return now

    for chunk in batches(runs):
        task = _batch_task(chunk, tyres)
        t = time.process_time()
        read_floor(task["paths"])
        t = step("read_floor", t)
        accel, beams = load_signals(task["paths"])
        t = step("read_into_numpy", t)
        mass, fs = np.asarray(task["axle_mass_kg"]), task["sample_rate_Hz"]
        force = am.tyre_force(accel[:, 0], accel[:, 1], beams, mass)
        a = accel.mean(axis=1, dtype=float)
        t = step("tyre_force", t)
        fe = am.excitation_frequency(a, fs)
        t = step("excitation_search", t)
        d = am.apparent_mass_demodulation(force, a, fs, fe)
        t = step("demodulation", t)
        am.apparent_mass_welch(force, a, fs, fe)
        t = step("welch_h1", t)
        unc.run_uncertainty(d, [unc.limits_budget(m) for m in mass], mass)
        t = step("uncertainty", t)
        am.excitation_blocks(d.envelope_m_s2, d.angular_frequency_rad_s, fs)
        t = step("excitation_blocks", t)
        for x in (accel, beams):
            qc.clipped(x.reshape(-1, x.shape[-1]))
        t = step("clipping_screen", t)
        analyse_paths(task)
        step("analyse_paths", t)
    parts = sum(v for k, v in spent.items() if k not in ("read_floor", "analyse_paths"))
    spent["other"] = spent["analyse_paths"] - parts
    return {k: round(1e3 * v / len(runs), 3) for k, v in spent.items()}


def timed(fn, *args) -> float:
    t0 = time.perf_counter()
    fn(*args)
    return time.perf_counter() - t0


def main(argv=None) -> dict:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--runs", type=int, default=200)
    p.add_argument("--duration", type=float, default=50.0)
    p.add_argument("--steps", action="store_true", help="also time each step of the analysis (CPU ms per run)")
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
        breakdown = steps(runs, tyres) if args.steps else None
    n = args.runs
    out = {
        "benchmark": "analysis", "runs": n, "duration_s": args.duration, "parquet_MB": round(mb, 1),
        "read_floor_runs_per_s": round(n / t_read), "tyrelab_runs_per_s": round(n / t_ours),
        "naive_runs_per_s": round(n / t_naive), "tyrelab_MB_per_s": round(mb / t_ours, 1),
        "speedup_vs_naive": round(t_naive / t_ours, 2), "ratio_to_read_floor": round(t_ours / t_read, 2),
    }
    if breakdown is not None:
        out["steps_ms_per_run"] = breakdown
    print(json.dumps(out))
    return out


if __name__ == "__main__":
    main()
