"""Coverage of the per-run 95 % intervals on the stress campaign (issue 14).

For every run of :func:`tyrelab.rig.stress.stress_plan` (artefacts of real
recordings at instrument noise x1 and x10) the run and its day's force-plate
calibration run are simulated in memory with the cell's rig; the run is
analysed exactly as the pipeline does (:func:`tyrelab.stages.analyse.analyse_batch`:
K, C, QC and the uncertainty with the §3.2.9 limits), then its instrument
budget is replaced by its day's check, as the calibrate stage does
(:func:`tyrelab.measurement.uncertainty.day_budget`). A run's interval
"holds the truth" when ``|K − K_truth| <= k u(K)`` (and the same for C), with
the describing-function truth of :mod:`tyrelab.rig.stress`.

    .venv/bin/python bench/bench_uncertainty.py [--runs-per-cell 50] [--seed 1991] [--jobs 2]
"""

from __future__ import annotations

import argparse
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tyrelab.measurement import calibration as cal  # noqa: E402
from tyrelab.measurement import uncertainty as unc  # noqa: E402
from tyrelab.measurement.apparent_mass import tyre_force  # noqa: E402
from tyrelab.rawformat import ACCEL_CHANNELS, BEAM_CHANNELS  # noqa: E402
from tyrelab.rig.campaigns import campaign_plan, simulate_run  # noqa: E402
from tyrelab.rig.stress import stress_config, stress_plan, simulate_stress_run  # noqa: E402
from tyrelab.measurement.recording import analyse_batch  # noqa: E402
from tyrelab.stages.analyse import wheel_interference_Hz  # noqa: E402
from tyrelab.stages.calibrate import welch_averages  # noqa: E402

_CALIBRATION_ROWS: dict[str, dict] = {}


def _calibration_row(day: str) -> dict:
    if not _CALIBRATION_ROWS:
        plan = campaign_plan("full")
        for r in plan[plan["kind"] == "calibration"].to_dict("records"):
            _CALIBRATION_ROWS[r["recorded_on"]] = r
    return _CALIBRATION_ROWS[day]


def _channels(run: pd.DataFrame):
    accel = run[list(ACCEL_CHANNELS)].to_numpy(float).T[np.newaxis]
    beams = run[list(BEAM_CHANNELS)].to_numpy(float).T[np.newaxis]
    return accel, beams


def evaluate_run(row: dict, seed: int) -> dict:
    """One stress run: estimate, interval (day budget), truth, whether the interval holds it."""
    from tyrelab.rig import truth

    cfg = stress_config(row["artefact"], row["noise_scale"])
    run, info = simulate_stress_run(row, seed)
    accel, beams = _channels(run)
    tyre = truth.tyre_params(row["tyre_id"])
    catalogue = pd.Series({"rolling_circumference_m": tyre.circumference_m,
                           "position": "front_ribbed" if tyre.group == "front_ribbed" else tyre.group, "size": tyre.size})
    out = analyse_batch(accel, beams, np.array([row["axle_mass_kg"]]), cfg.sample_rate_Hz,
                        [wheel_interference_Hz(row["speed_km_h"], catalogue)]).iloc[0]
    # the day's check, recorded with the same rig (noise, hum, drift apply to it too)
    cal_row = _calibration_row(row["recorded_on"])
    cal_run, _ = simulate_run(cal_row, seed, cfg)
    ca, cb = _channels(cal_run)
    derived = tyre_force(ca[0, 0], ca[0, 1], cb[0], cal_row["axle_mass_kg"])
    inertial = cal_row["axle_mass_kg"] * 0.5 * (ca[0, 0] + ca[0, 1])
    tf = cal.calibration_transfer_function(cal_run["force_plate_N"].to_numpy(float), derived, cfg.sample_rate_Hz,
                                           inertial_force_N=inertial)
    passed = cal.check_calibration(tf)["pass"]
    f = float(out["excitation_frequency_measured_Hz"])
    budget = (unc.day_budget(tf, f, welch_averages(len(cal_run), cfg.sample_rate_Hz)) if passed
              else unc.limits_budget(row["axle_mass_kg"]))
    u = unc.combine(out["stiffness_N_per_m"], out["damping_N_s_per_m"], f, out["stiffness_u_stat_N_per_m"],
                    out["damping_u_stat_N_s_per_m"], out["uncertainty_dof_stat"], budget, row["axle_mass_kg"])
    k_lo, k_hi = (float(v) for v in u.stiffness_ci95_N_per_m)
    c_lo, c_hi = (float(v) for v in u.damping_ci95_N_s_per_m)
    kt, ct = info["truth_stiffness_N_per_m"], info["truth_damping_N_s_per_m"]
    return {
        "stress_id": row["stress_id"], "artefact": row["artefact"], "noise_scale": row["noise_scale"],
        "tyre_id": row["tyre_id"], "speed_km_h": row["speed_km_h"], "surface": row["surface"],
        "qc_ok": bool(out["qc_ok"]), "qc_reasons": out["qc_reasons"], "day_check_passed": bool(passed),
        "K_truth": kt, "C_truth": ct, "K_model": info["model_stiffness_N_per_m"], "C_model": info["model_damping_N_s_per_m"],
        "K": float(out["stiffness_N_per_m"]), "C": float(out["damping_N_s_per_m"]),
        "u_K": float(u.stiffness_u_N_per_m), "u_C": float(u.damping_u_N_s_per_m),
        "u_K_stat": float(out["stiffness_u_stat_N_per_m"]), "u_C_stat": float(out["damping_u_stat_N_s_per_m"]),
        "K_in": k_lo <= kt <= k_hi, "C_in": c_lo <= ct <= c_hi,
        "K_width_pct": 100 * (k_hi - k_lo) / kt, "C_width_pct": 100 * (c_hi - c_lo) / ct,
    }


def _evaluate_chunk(args) -> list[dict]:
    rows, seed = args
    return [evaluate_run(r, seed) for r in rows]


def evaluate(runs_per_cell: int, seed: int = 1991, jobs: int = 1) -> pd.DataFrame:
    """Every run of the stress campaign with ``runs_per_cell`` runs per (artefact, noise) cell."""
    rows = stress_plan(runs_per_cell, seed).to_dict("records")
    if jobs <= 1:
        return pd.DataFrame([evaluate_run(r, seed) for r in rows])
    chunks = [(rows[i::jobs], seed) for i in range(jobs)]
    with ProcessPoolExecutor(jobs) as pool:
        out = [r for part in pool.map(_evaluate_chunk, chunks) for r in part]
    return pd.DataFrame(out).set_index("stress_id").loc[[r["stress_id"] for r in rows]].reset_index()


def summarise(df: pd.DataFrame) -> pd.DataFrame:
    """Coverage (%) and median interval width (% of the truth) per artefact, noise level and overall."""
    def cell(g: pd.DataFrame) -> pd.Series:
        return pd.Series({"runs": len(g), "K coverage %": 100 * g["K_in"].mean(), "C coverage %": 100 * g["C_in"].mean(),
                          "median K width %": g["K_width_pct"].median(), "median C width %": g["C_width_pct"].median()})

    parts = [df.groupby(["artefact", "noise_scale"], sort=False).apply(cell, include_groups=False).reset_index()]
    for noise, g in df.groupby("noise_scale"):
        parts.append(cell(g).to_frame().T.assign(artefact="all runs", noise_scale=noise))
    parts.append(cell(df).to_frame().T.assign(artefact="all runs", noise_scale="x1 and x10"))
    parts.append(cell(df[df["qc_ok"]]).to_frame().T.assign(artefact="QC-passed runs", noise_scale="x1 and x10"))
    out = pd.concat(parts, ignore_index=True)
    out["runs"] = out["runs"].astype(int)
    return out[["artefact", "noise_scale", "runs", "K coverage %", "C coverage %", "median K width %", "median C width %"]]


def markdown(df: pd.DataFrame) -> str:
    """A DataFrame as a GitHub markdown table."""
    fmt = lambda v: f"{v:.1f}" if isinstance(v, float) else (f"×{v:g}" if isinstance(v, (int, np.integer)) and False else str(v))  # noqa: E731
    lines = ["| " + " | ".join(df.columns) + " |", "|" + "---|" * len(df.columns)]
    return "\n".join(lines + ["| " + " | ".join(fmt(v) for v in row) + " |" for row in df.itertuples(index=False)])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs-per-cell", type=int, default=50)
    ap.add_argument("--seed", type=int, default=1991)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--csv", help="also write every run's row here")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    df = evaluate(args.runs_per_cell, args.seed, args.jobs)
    print(markdown(summarise(df)))
    missed = df[~(df["K_in"] & df["C_in"])]
    print(f"\n{len(df)} runs in {time.perf_counter() - t0:.0f} s; {len(missed)} with a miss; worst:")
    missed = missed.assign(zK=(missed["K"] - missed["K_truth"]) / missed["u_K"], zC=(missed["C"] - missed["C_truth"]) / missed["u_C"])
    print(markdown(missed.reindex(missed[["zK", "zC"]].abs().max(axis=1).sort_values(ascending=False).index).head(10)[
        ["stress_id", "speed_km_h", "surface", "qc_ok", "zK", "zC", "u_K_stat", "u_C_stat"]]))
    if args.csv:
        df.to_csv(args.csv, index=False)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
