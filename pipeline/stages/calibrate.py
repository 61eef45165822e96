"""Calibrate: daily force-plate check of the tyre force (thesis §3.2.9, §3.6).

For every ``kind == "calibration"`` run of the ``manifest`` table: the
transfer function from the force-plate force to the derived tyre force
(``M_a * mean(acc) - sum(beams)``), pass/fail against 1 +- 3 % and 0 +- 1
degree over 2-6 Hz. A day passes when all its calibration runs pass.

Writes ``calibration`` (one row per calibration run: campaign, day, run_id,
tyre_id, pass, day_pass, max_gain_error_pct, max_phase_error_deg, mean_gain,
mean_phase_deg) and ``calibration_tf`` (run_id, day, frequency_Hz, gain,
phase_deg, coherence), and ``results``: the analyse stage's table
(``stages/analysed``) with runs recorded on a failed day (same campaign and ``recorded_on``) have
``qc_ok`` False and the reason ``calibration failed on <day>``. Days without
a calibration run are left as they are.

Optional correction (§3.6): with ``ctx.calibration_correct`` (``tyrelab run
--calibration-correct``), ``stiffness_N_per_m``/``damping_N_s_per_m`` (and the kN columns) of
runs on *passing* days are corrected by the day's transfer function at the
run's measured frequency; the uncorrected values are kept in
``uncorrected_stiffness_N_per_m`` / ``uncorrected_damping_N_s_per_m``.

Uncertainty (issue 14, docs/uncertainty.md): analyse gives every run the
§3.2.9 limits as its instrument uncertainty; here runs of a day whose check
passed get the day's budget instead (:func:`tyrelab.measurement.uncertainty.day_budget`:
the day's phase at the run's frequency, the channel gains), combined again
with the run's own type A part; ``uncertainty_source`` names the day.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.parquet as pq

from ..measurement import calibration as cal
from ..measurement import uncertainty as unc
from ..measurement.apparent_mass import tyre_force
from ..rawformat import ACCEL_CHANNELS, BEAM_CHANNELS, CHANNELS
from .base import Context, Progress, StageResult
from .dag import ANALYSED
from .state import ItemCache

__all__ = ["CALIBRATION_COLUMNS", "TF_COLUMNS", "check_calibration_run", "correct_results", "passing_days", "day_uncertainty", "run"]

CALIBRATION_COLUMNS = ["campaign", "day", "run_id", "tyre_id", "pass", "day_pass", "max_gain_error_pct",
                       "max_phase_error_deg", "mean_gain", "mean_phase_deg", "reason"]
TF_COLUMNS = ["campaign", "day", "run_id", "frequency_Hz", "gain", "phase_deg", "coherence", "inertial_ratio_re",
              "inertial_ratio_im"]


def check_calibration_run(path: str, axle_mass_kg: float, sample_rate_Hz: float) -> tuple[dict, pd.DataFrame]:
    """Check one force-plate calibration run file; return (check dict, transfer function)."""
    t = pq.read_table(path)
    if "force_plate_N" not in t.column_names:
        return {"pass": False, "reason": "no force_plate_N channel"}, pd.DataFrame()
    col = {c: t.column(c).to_numpy().astype(np.float64) for c in [*CHANNELS, "force_plate_N"]}
    derived = tyre_force(col[ACCEL_CHANNELS[0]], col[ACCEL_CHANNELS[1]], np.stack([col[c] for c in BEAM_CHANNELS]),
                         axle_mass_kg)
    inertial = axle_mass_kg * 0.5 * (col[ACCEL_CHANNELS[0]] + col[ACCEL_CHANNELS[1]])
    tf = cal.calibration_transfer_function(col["force_plate_N"], derived, sample_rate_Hz, inertial_force_N=inertial)
    check = cal.check_calibration(tf)
    check["reason"] = "" if check["pass"] else (
        f"gain error {check['max_gain_error_pct']:.1f} % / phase error {check['max_phase_error_deg']:.2f} deg "
        f"outside 3 % / 1 deg over 2-6 Hz")
    return check, tf


def _sample_rate(row: pd.Series) -> float:
    fs = row.get("sample_rate_Hz")
    if fs is None or not np.isfinite(fs):
        t = pq.read_table(row["run_path"], columns=["time_s"]).column(0).to_numpy()
        fs = 1.0 / float(np.median(np.diff(t)))
    return float(fs)


def undo_correction(results: pd.DataFrame) -> pd.DataFrame:
    """``results`` as analyse wrote them: K and C from ``uncorrected_*`` where a previous
    calibrate run corrected them, without those columns. Makes the stage idempotent: it may
    rerun on its own output (after an interruption, or with ``--calibration-correct`` toggled)
    and gives the same bytes as on analyse's output."""
    cols = {"stiffness_N_per_m": "uncorrected_stiffness_N_per_m", "damping_N_s_per_m": "uncorrected_damping_N_s_per_m"}
    if not set(cols.values()) & set(results.columns):
        return results
    out = results.copy()
    for value, kept in cols.items():
        if kept in out:
            mask = out[kept].notna()
            out.loc[mask, value] = out.loc[mask, kept]
    out["stiffness_kN_per_m"] = out["stiffness_N_per_m"] / 1e3
    out["damping_kN_s_per_m"] = out["damping_N_s_per_m"] / 1e3
    return out.drop(columns=[c for c in cols.values() if c in out])


def correct_results(results: pd.DataFrame, tfs: pd.DataFrame, checks: pd.DataFrame) -> pd.DataFrame:
    """§3.6 option: correct K, C of runs on passing days by that day's transfer function."""
    out = results.copy()
    if out.empty or checks.empty:
        return out
    out["uncorrected_stiffness_N_per_m"] = out["stiffness_N_per_m"]
    out["uncorrected_damping_N_s_per_m"] = out["damping_N_s_per_m"]
    good = checks[checks["pass"]].drop_duplicates(["campaign", "day"])
    for r in good.itertuples(index=False):
        tf = tfs[tfs["run_id"] == r.run_id]
        sel = (out["campaign"].astype(str) == str(r.campaign)) & (out["recorded_on"].astype(str) == str(r.day))
        for i in np.flatnonzero(sel.to_numpy()):
            k, c, f = (out.iloc[i][n] for n in ("stiffness_N_per_m", "damping_N_s_per_m", "excitation_frequency_measured_Hz"))
            if np.isfinite(k) and np.isfinite(f):
                k2, c2 = cal.corrected_stiffness_damping(k, c, f, tf)
                out.iloc[i, out.columns.get_loc("stiffness_N_per_m")] = k2
                out.iloc[i, out.columns.get_loc("damping_N_s_per_m")] = c2
    out["stiffness_kN_per_m"] = out["stiffness_N_per_m"] / 1e3
    out["damping_kN_s_per_m"] = out["damping_N_s_per_m"] / 1e3
    return out


def welch_averages(n_samples: int, sample_rate_Hz: float, resolution_Hz: float = 0.25) -> int:
    """Number of 50 %-overlapping segments :func:`~tyrelab.measurement.calibration.calibration_transfer_function` averages."""
    nperseg = int(round(sample_rate_Hz / resolution_Hz))
    return max((int(n_samples) - nperseg) // (nperseg // 2) + 1, 1)


#: The columns of a run's row that its combined uncertainty depends on (besides its day's budget).
RECOMBINE_INPUTS = ["stiffness_N_per_m", "damping_N_s_per_m", "excitation_frequency_measured_Hz",
                    "stiffness_u_stat_N_per_m", "damping_u_stat_N_s_per_m", "uncertainty_dof_stat", "axle_mass_kg"]


def passing_days(checks: pd.DataFrame) -> pd.DataFrame:
    """The check rows of the days that passed, one per (campaign, day)."""
    if checks.empty:
        return checks
    return checks[checks["pass"].astype(bool) & checks["day_pass"].astype(bool)].drop_duplicates(["campaign", "day"])


def day_uncertainty(results: pd.DataFrame, tfs: pd.DataFrame, checks: pd.DataFrame, averages: dict,
                    corrected: bool, cache: ItemCache | None = None, on_day=None) -> pd.DataFrame:
    """Recombine the uncertainty of runs on passing days with their day's budget (see module docstring).

    With ``cache``, each passing day's recombination is kept under the digest of its runs'
    :data:`RECOMBINE_INPUTS`, its transfer function and options: a run added on one day
    recomputes that day only (a day budget per run is ~0.5 ms: 0.5 s for the full campaign).
    ``on_day()``, if given, is called once per day of :func:`passing_days` when it is done.
    """
    on_day = on_day or (lambda: None)
    out = results.copy()
    needed = {"stiffness_u_stat_N_per_m", "damping_u_stat_N_s_per_m", "uncertainty_dof_stat"}
    if out.empty or not needed <= set(out.columns):
        return out
    ok = (out["excitation_frequency_measured_Hz"].notna() & out["stiffness_u_stat_N_per_m"].notna()).to_numpy()

    def combined(idx, budgets) -> dict:
        rows = out.iloc[idx]
        u = unc.combine(rows["stiffness_N_per_m"].to_numpy(float), rows["damping_N_s_per_m"].to_numpy(float),
                        rows["excitation_frequency_measured_Hz"].to_numpy(float),
                        rows["stiffness_u_stat_N_per_m"].to_numpy(float), rows["damping_u_stat_N_s_per_m"].to_numpy(float),
                        rows["uncertainty_dof_stat"].to_numpy(float), budgets, rows["axle_mass_kg"].to_numpy(float))
        return u.columns()

    # the columns are gathered in arrays and set once (setting rows of a frame column by column per day
    # took ~10 ms a day); a column of another dtype than float or object is set in place, as before
    buf: dict[str, np.ndarray] = {}

    def assign(idx, columns: dict, source: str) -> None:
        for name, values in {**columns, "uncertainty_source": source}.items():
            if name not in buf and out[name].dtype in (np.dtype(float), np.dtype(object)):
                buf[name] = out[name].to_numpy(copy=True)
            if name in buf:
                buf[name][idx] = values
            else:
                out.iloc[idx, out.columns.get_loc(name)] = values

    def gathered() -> pd.DataFrame:
        for name, values in buf.items():
            out[name] = pd.Series(values, index=out.index, dtype=out[name].dtype)
        return out

    # every run first with the §3.2.9 limits (idempotent: a day that no longer passes loses its budget)
    idx = np.flatnonzero(ok)
    if len(idx):
        assign(idx, combined(idx, [unc.limits_budget(m) for m in out.iloc[idx]["axle_mass_kg"].to_numpy(float)]),
               unc.limits_budget().source)
    if checks.empty or tfs.empty:
        return gathered()
    for r in passing_days(checks).itertuples(index=False):
        tf = tfs[tfs["run_id"] == r.run_id]
        sel = (out["campaign"].astype(str) == str(r.campaign)) & (out["recorded_on"].astype(str) == str(r.day))
        idx = np.flatnonzero(sel.to_numpy() & ok)
        if tf.empty or not len(idx):
            on_day()
            continue
        source, n_avg = f"calibration {r.day}", averages.get(r.run_id, 1)

        def compute(idx=idx, tf=tf, source=source, n_avg=n_avg) -> dict:
            f = out.iloc[idx]["excitation_frequency_measured_Hz"].to_numpy(float)
            return combined(idx, [unc.day_budget(tf, fi, n_avg, corrected, source) for fi in f])

        if cache is None:
            assign(idx, compute(), source)
        else:
            key = cache.key("day", out.iloc[idx][RECOMBINE_INPUTS].reset_index(drop=True), tf.reset_index(drop=True),
                            n_avg, bool(corrected), source)
            assign(idx, cache.get_or_compute(key, compute), source)
        on_day()
    return gathered()


def _day_notes(cal_runs: pd.DataFrame, day: str) -> str:
    """`` (manifest notes: …)`` of the calibration runs recorded on ``day`` that have notes, else ``""``
    (the demo campaign's deliberately miscalibrated day says so in its notes)."""
    if "notes" not in cal_runs or "recorded_on" not in cal_runs:
        return ""
    notes = [str(n).strip() for n in cal_runs.loc[cal_runs["recorded_on"].astype(str) == day, "notes"]
             if isinstance(n, str) and n.strip()]
    return f" (manifest notes: {'; '.join(dict.fromkeys(notes))})" if notes else ""


def run(ctx: Context) -> StageResult:
    """Check every calibration run; flag results of failed days; write the tables."""
    t0 = time.perf_counter()
    res = StageResult("calibrate")
    manifest = ctx.read_table("manifest") if ctx.has_table("manifest") else pd.DataFrame()
    if "run_path" in manifest:  # relative to the build in the table (a moved build works)
        manifest = manifest.assign(run_path=[str(ctx.build_file(p)) for p in manifest["run_path"]])
    rows, tfs, averages = [], [], {}
    cal_runs = pd.DataFrame()
    # each check is kept under the digest of the converted run file it read, its axle mass and
    # sample rate (ItemCache): an added measurement run re-checks no calibration run
    cache = ItemCache(ctx, "calibrate")
    if not manifest.empty and "kind" in manifest:
        cal_runs = manifest[manifest["kind"].fillna("measurement") == "calibration"]
        res.n_in = len(cal_runs)
        progress = Progress("calibrate: force-plate checks", len(cal_runs), logger=ctx.log)
        for _, r in cal_runs.sort_values("run_id").iterrows():
            fs = _sample_rate(r)
            path, mass = r["run_path"], float(r["axle_mass_kg"])
            key = cache.key("check", cache.file_digest(Path(path)), mass, fs)  # an unchanged run file is not read
            check, tf = cache.get_or_compute(key, lambda: check_calibration_run(path, mass, fs))
            averages[r["run_id"]] = welch_averages(r.get("n_samples", 0) or 0, fs)
            day = str(r["recorded_on"])
            rows.append({"campaign": str(r.get("campaign", "")), "day": day, "run_id": r["run_id"],
                         "tyre_id": r["tyre_id"], **check})
            if not tf.empty:
                tf.insert(0, "run_id", r["run_id"])
                tf.insert(0, "day", day)
                tf.insert(0, "campaign", str(r.get("campaign", "")))
                tfs.append(tf)
            progress.step()
    checks = pd.DataFrame(rows)
    if checks.empty:
        checks = pd.DataFrame(columns=CALIBRATION_COLUMNS)
        days = pd.DataFrame(columns=["campaign", "day", "day_pass", "n_calibration_runs"])
    else:
        days = cal.day_summary(checks, ("campaign", "day"))
        checks = checks.merge(days[["campaign", "day", "day_pass"]], on=["campaign", "day"], how="left")
        checks = checks.reindex(columns=CALIBRATION_COLUMNS)
    tf_all = pd.concat(tfs, ignore_index=True) if tfs else pd.DataFrame(columns=TF_COLUMNS)
    ctx.write_table("calibration", checks)
    ctx.write_table("calibration_tf", tf_all)
    res.n_ok = int(checks["pass"].sum()) if len(checks) else 0
    failed_days = sorted(days.loc[~days["day_pass"].astype(bool), "day"]) if len(days) else []
    n_flagged = 0
    if ctx.has_table(ANALYSED):
        results = undo_correction(ctx.read_table(ANALYSED))
        if not results.empty and "recorded_on" in results:
            keys = ("campaign", "recorded_on") if "campaign" in results else ("recorded_on",)
            dkeys = ("campaign", "day") if "campaign" in results else ("day",)
            if ctx.calibration_correct:
                results = correct_results(results, tf_all, checks)
            progress = Progress("calibrate: uncertainty of passing days", len(passing_days(checks)), logger=ctx.log,
                                unit="days")
            results = day_uncertainty(results, tf_all, checks, averages, bool(ctx.calibration_correct), cache,
                                      on_day=progress.step)
            progress.close()
            results = cal.flag_failed_days(results, days, keys, dkeys)
            n_flagged = int(results["qc_reasons"].str.contains("calibration failed on", regex=False).sum())
        ctx.write_table("results", results)
    cache.prune()
    res.message = (f"{len(days)} days, {len(failed_days)} failed" + (f" ({', '.join(failed_days)})" if failed_days else "")
                   + (f"; {n_flagged} runs flagged" if n_flagged else ""))
    for d in failed_days:  # with the manifest's notes of the day's calibration runs: they may say why
        ctx.log.warning("calibrate: calibration failed on %s: runs of that day flagged%s", d, _day_notes(cal_runs, d))
    res.seconds = time.perf_counter() - t0
    return res
