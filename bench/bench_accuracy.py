"""Estimator accuracy on the full virtual campaign (issue 3).

For every measurement run of ``campaign_plan("full")`` the run is simulated in
memory exactly as ``tyrelab generate --scale full`` writes it (same seeds), the
tyre force is derived from the raw channels and K, C are estimated by

* ``demodulation``: :func:`tyrelab.measurement.apparent_mass.apparent_mass_demodulation`
  (used downstream), and
* ``welch_bin``: :func:`tyrelab.measurement.apparent_mass.apparent_mass_welch`
  (the thesis' H1 read at the excitation bin),

and compared with the K, C the truth model gave that run. Runs of the
deliberately miscalibrated day are reported separately (the calibrate stage
flags them). Repeated with the instrument noise x3.

    .venv/bin/python bench/bench_accuracy.py [--seed 1991] [--noise 1 3] [--limit N]
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tyrelab.measurement import apparent_mass as am  # noqa: E402
from tyrelab.measurement.recording import frame_tyre_force, recording_arrays  # noqa: E402
from tyrelab.measurement.qc import interference_frequencies_Hz  # noqa: E402
from tyrelab.rig import truth  # noqa: E402
from tyrelab.rig.campaigns import campaign_plan, simulate_run  # noqa: E402
from tyrelab.rig.instrument import RigConfig  # noqa: E402


def evaluate(seed: int, noise_scale: float, limit: int | None = None) -> pd.DataFrame:
    """One row per measurement run: truth, both estimates, relative errors."""
    cfg = dataclasses.replace(RigConfig(), noise_scale=noise_scale)
    plan = campaign_plan("full", cfg)
    plan = plan[(plan["kind"] == "measurement") & (plan["method"] == "stepped_sine")]
    if limit:
        plan = plan.iloc[:: max(len(plan) // limit, 1)]
    rows = []
    fs = cfg.sample_rate_Hz
    for r in plan.to_dict("records"):
        run, info = simulate_run(r, seed, cfg)
        accel, _ = recording_arrays(run)
        force = frame_tyre_force(run, r["axle_mass_kg"])
        a = accel.mean(axis=0)
        fe = am.excitation_frequency(a, fs)
        d = am.apparent_mass_demodulation(force, a, fs, fe)
        w = am.apparent_mass_welch(force, a, fs, fe)
        K, C = info["stiffness_N_per_m"], info["damping_N_s_per_m"]
        tyre = truth.tyre_params(r["tyre_id"])
        lugs = max(int(round(tyre.circumference_m / 0.2)), 8) if tyre.traction else 0
        near = [fi for fi in interference_frequencies_Hz(r["speed_km_h"], tyre.circumference_m, lugs)
                if abs(fi - float(d.frequency_Hz)) <= 0.15]
        rows.append({
            "run_id": r["run_id"], "set": r["plan_set"], "tyre_id": r["tyre_id"], "speed_km_h": r["speed_km_h"],
            "surface": r["surface"], "miscalibrated": r["plan_beam_gain_error"] != 0, "wheel_interference": bool(near), "K": K, "C": C,
            "demodulation_K_err": float(d.stiffness_N_per_m) / K - 1, "demodulation_C_err": float(d.damping_N_s_per_m) / C - 1,
            "welch_bin_K_err": float(w.stiffness_N_per_m) / K - 1, "welch_bin_C_err": float(w.damping_N_s_per_m) / C - 1,
        })
    return pd.DataFrame(rows)


def markdown(df: pd.DataFrame, fmt: str = "{:.2f}") -> str:
    """A DataFrame as a GitHub markdown table (no tabulate dependency)."""
    cells = [[fmt.format(v) if isinstance(v, float) else str(v) for v in row] for row in df.itertuples(index=False)]
    lines = ["| " + " | ".join(map(str, df.columns)) + " |", "|" + "---|" * len(df.columns)]
    return "\n".join(lines + ["| " + " | ".join(c) + " |" for c in cells])


def summarise(df: pd.DataFrame) -> pd.DataFrame:
    out = []
    for est in ("demodulation", "welch_bin"):
        row = {"estimator": est, "runs": len(df)}
        for q in ("K", "C"):
            e = 100 * df[f"{est}_{q}_err"].abs()
            row[f"median |{q} err| %"] = e.median()
            row[f"p95 |{q} err| %"] = e.quantile(0.95)
            row[f"max |{q} err| %"] = e.max()
        out.append(row)
    return pd.DataFrame(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=1991)
    ap.add_argument("--noise", type=float, nargs="+", default=[1.0, 3.0])
    ap.add_argument("--limit", type=int, default=None, help="evaluate about N runs only")
    args = ap.parse_args(argv)
    for noise in args.noise:
        t0 = time.perf_counter()
        df = evaluate(args.seed, noise, args.limit)
        good = df[~df["miscalibrated"]]
        print(f"\n## noise x{noise:g}: {len(good)} runs (+{int(df['miscalibrated'].sum())} on the miscalibrated day), "
              f"{time.perf_counter() - t0:.0f} s")
        print(markdown(summarise(good)))
        clean = good[~good["wheel_interference"]]
        print(f"\nwithout the {len(good) - len(clean)} runs QC flags for wheel excitation near the excitation frequency:")
        print(markdown(summarise(clean)))
        worst = good.reindex(good["demodulation_C_err"].abs().sort_values(ascending=False).index).head(5)
        print("\nworst demodulation C errors:")
        print(markdown(worst[["run_id", "set", "speed_km_h", "surface", "C", "demodulation_K_err", "demodulation_C_err"]],
                       "{:.4g}"))
        bad = df[df["miscalibrated"]]
        if len(bad):
            print("\nmiscalibrated day (flagged by calibrate):")
            print(markdown(summarise(bad)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
