"""Analyse: per run, the apparent mass, K and C, amplitude, coherence and QC.

Reads the ``manifest`` table and the per-run Parquet files written by ingest,
calls :func:`tyrelab.measurement.recording.analyse_batch` (the estimators of
:mod:`tyrelab.measurement.apparent_mass` and the QC) on batches of
equal-length runs (vectorised), and writes the table ``stages/analysed`` (one row
per measurement run; calibration runs are the calibrate stage's), which the calibrate stage
completes into ``results``: each table has one writer (:mod:`tyrelab.stages.dag`).

Both estimators are stored: the thesis' Welch H1 read at the excitation bin
(``welch_*`` columns) and the phase-locked synchronous demodulation used
downstream (``stiffness_kN_per_m``, ``damping_kN_s_per_m``).

Runs of the other methods (the manifest's ``method``: swept sine, random, free vibration,
load deflection; issue 34) are analysed one at a time by
:func:`tyrelab.measurement.rig_methods.analyse_method_run` into the same table, with their
K, C, 95 % intervals and QC reasons and the method's own columns
(:data:`~tyrelab.measurement.rig_methods.METHOD_COLUMNS`); a broadband run's frequency
response goes to the table ``frf``. Every row carries ``direction`` and ``method``; stepped-sine
rows are computed exactly as before. A free-vibration run that never decays or a
load-deflection run without a loading branch is quarantined with its reason; a broadband
run without coherence over its band keeps its row with the reason and no K or C.

Incremental: the stage is skipped when what it reads (:data:`tyrelab.stages.dag.STAGES`) is
unchanged (see :mod:`tyrelab.stages.state`); otherwise a run whose
``input_hash`` (file SHA-256, manifest row, and the code fingerprint of this stage: its source
and that of every module it imports, :func:`tyrelab.stages.state.code_fingerprint`) matches the previous ``stages/analysed`` row is not
re-analysed. Batches go to :func:`tyrelab.executor.map_batches` as file
paths, so any executor gives the same bytes.
"""

from __future__ import annotations

import ctypes
import hashlib
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.parquet as pq

from ..measurement.calibration import CALIBRATION_REASON
from ..measurement import qc
from ..measurement.recording import analyse_batch
from ..measurement import rig_methods as rm
from ..tyre.sizes import lugs_per_side, tyre_rolling_circumference_m
from ..executor import map_batches
from .base import Context, Progress, StageResult, write_quarantine
from .dag import ANALYSED
from .state import code_fingerprint
from ..rawformat import CHANNELS

__all__ = ["OUTPUT", "BATCH", "CONDITION_COLUMNS", "METHOD_CONDITION_COLUMNS", "input_hash", "analyse_method_path",
    "load_signals", "wheel_interference_Hz", "batches", "analyse_paths", "reuse_freed_memory", "run", "empty_results"]

#: The table the stage writes (declared in :data:`tyrelab.stages.dag.STAGES`); calibrate reads it.
OUTPUT = ANALYSED
#: Runs analysed together in one vectorised call.
BATCH = 32

CONDITION_COLUMNS = [
    "campaign", "run_id", "tyre_id", "kind", "speed_km_h", "pressure_bar", "load_kN",
    "excitation_frequency_Hz", "amplitude_mm_pp", "torque_kNm", "surface", "axle_mass_kg", "recorded_on",
]
#: Manifest columns of the other methods (issue 34) kept in ``results`` after the conditions.
METHOD_CONDITION_COLUMNS = ["direction", "method", "band_low_Hz", "band_high_Hz"]
#: Reasons of a method run that quarantine it (bad input rather than a QC finding).
QUARANTINE_REASONS = ("no free decay", "no loading branch", "the deflection does not change", "moving mass")


def input_hash(sha256: str, row_hash: str, code: str) -> str:
    """Hash of everything a run's result depends on: its file's bytes (``sha256``), its manifest row
    (``row_hash``) and the stage's ``code`` fingerprint (a change to any module it imports — the
    estimators, QC, uncertainty, tyre sizes — re-analyses every run; no hand-kept list or version)."""
    return hashlib.sha256(f"{sha256}|{row_hash}|{code}".encode()).hexdigest()


def load_signals(paths: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """Read runs of equal length; return (accelerations (runs, 2, n), load beams (runs, 4, n)).

    The channels keep the float32 they are stored in; the estimators promote
    to float64 inside their reductions.
    """
    out = None
    for i, p in enumerate(paths):
        t = pq.read_table(p, columns=CHANNELS)
        if out is None:
            out = np.empty((len(paths), len(CHANNELS), t.num_rows), dtype=np.float32)
        for j, c in enumerate(CHANNELS):
            out[i, j] = t.column(c).to_numpy()
    if out is None:
        return np.empty((0, 2, 0), np.float32), np.empty((0, 4, 0), np.float32)
    return out[:, :2], out[:, 2:]


def wheel_interference_Hz(speed_km_h: float, tyre: pd.Series | None) -> list[float]:
    """Wheel-rotation and lug-passing frequencies of a run (thesis §2.4.5), Hz.

    Uses the catalogue's ``rolling_circumference_m``, else its ``outer_diameter_m``,
    else an estimate from the size (:func:`tyrelab.tyre.sizes.tyre_rolling_circumference_m`);
    the catalogue's ``lugs_per_side`` where given; ribbed (undriven front) tyres have no lugs.
    """
    if tyre is None:
        return []
    circ = tyre_rolling_circumference_m(tyre["size"], catalogue_m=tyre.get("rolling_circumference_m"),
                                        outer_diameter_m=tyre.get("outer_diameter_m"))
    lugs = lugs_per_side(circ, ribbed=str(tyre.get("position", "")).endswith("ribbed"),
                         catalogue=tyre.get("lugs_per_side"))
    return qc.interference_frequencies_Hz(float(speed_km_h), float(circ), lugs)


def batches(runs: pd.DataFrame, size: int = BATCH) -> list[pd.DataFrame]:
    """Split runs into batches of equal length and sampling rate, at most ``size`` runs each.

    The split depends only on the manifest, never on the executor, so the
    results are the same whichever executor analyses the batches.
    """
    out = []
    for _, group in runs.groupby(["n_samples", "sample_rate_Hz"], sort=True):
        out.extend(group.iloc[start : start + size] for start in range(0, len(group), size))
    return out


def _batch_task(chunk: pd.DataFrame, tyres: dict) -> dict:
    return {
        "paths": chunk["run_path"].tolist(),
        "interference_Hz": [wheel_interference_Hz(v, tyres.get(t)) for v, t in zip(chunk["speed_km_h"], chunk["tyre_id"])],
        "axle_mass_kg": chunk["axle_mass_kg"].to_numpy(float).tolist(),
        "sample_rate_Hz": float(chunk["sample_rate_Hz"].iloc[0]),
    }


#: glibc ``mallopt`` parameters (malloc.h) and the values :func:`reuse_freed_memory` sets.
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3
_MMAP_THRESHOLD_BYTES, _TRIM_THRESHOLD_BYTES = 32 << 20, 128 << 20
_malloc_tuned: bool | None = None


def reuse_freed_memory() -> bool:
    """Let this process reuse the memory of freed arrays instead of returning it to the kernel (glibc).

    The estimators' temporaries are arrays of 0.1-4 MB. glibc's malloc serves
    such blocks by ``mmap`` and gives them back on ``free``, so every
    temporary is a fresh mapping whose pages the kernel must fault in again
    (~230 page faults per run, a third of the demodulation's CPU time on this
    machine). Raising the mmap threshold to 32 MB and the heap's trim
    threshold to 128 MB keeps them in the heap for reuse; it changes no
    number, only where the bytes come from. Idempotent; a no-op (False) off
    glibc.
    """
    global _malloc_tuned
    if _malloc_tuned is None:
        try:
            mallopt = ctypes.CDLL(None).mallopt if sys.platform.startswith("linux") else None
        except (OSError, AttributeError):
            mallopt = None
        _malloc_tuned = bool(mallopt) and bool(mallopt(_M_MMAP_THRESHOLD, _MMAP_THRESHOLD_BYTES)) and bool(
            mallopt(_M_TRIM_THRESHOLD, _TRIM_THRESHOLD_BYTES))
    return _malloc_tuned


def analyse_paths(task: dict) -> pd.DataFrame:
    """Read and analyse one batch of equal-length runs (runs in a worker process).

    Parameters
    ----------
    task : dict
        ``paths`` (per-run Parquet files written by ingest), ``axle_mass_kg``
        and ``interference_Hz`` (one per path) and ``sample_rate_Hz``.

    Returns
    -------
    DataFrame
        :func:`analyse_batch`'s rows, in the order of ``paths``.
    """
    reuse_freed_memory()
    accel, beams = load_signals(task["paths"])
    masses, interference = np.asarray(task["axle_mass_kg"], dtype=float), list(task["interference_Hz"])
    return analyse_batch(accel, beams, masses, task["sample_rate_Hz"], interference)


def _method_task(row: pd.Series) -> dict:
    """A run of another method, as paths and scalars for :func:`analyse_method_path`."""
    lo, hi = row.get("band_low_Hz"), row.get("band_high_Hz")
    band_Hz = (float(lo), float(hi)) if pd.notna(lo) and pd.notna(hi) else None
    return {"path": row["run_path"], "run_id": row["run_id"], "method": row["method"],
            "direction": row["direction"], "band_Hz": band_Hz, "axle_mass_kg": float(row["axle_mass_kg"]),
            "rolling": bool(float(row["speed_km_h"]) > 0)}


def analyse_method_path(task: dict) -> tuple[dict, pd.DataFrame]:
    """Read and analyse one run of another method (runs in a worker process): its ``results``
    fields and its ``frf`` rows (:func:`tyrelab.measurement.rig_methods.analyse_method_run`)."""
    pf = pq.ParquetFile(task["path"])
    names = set(pf.schema_arrow.names)
    table = pf.read(columns=["time_s", *CHANNELS, *([rm.DEFLECTION] if rm.DEFLECTION in names else [])])
    col = lambda c: table.column(c).to_numpy().astype(np.float64)  # noqa: E731
    accel = np.stack([col(c) for c in CHANNELS[:2]])
    beams = np.stack([col(c) for c in CHANNELS[2:]])
    row, frf = rm.analyse_method_run(task["method"], task["direction"], col("time_s"), accel, beams,
                                     task["axle_mass_kg"], band_Hz=task["band_Hz"], rolling=task["rolling"],
                                     deflection_m=col(rm.DEFLECTION) if rm.DEFLECTION in names else None,
                                     run_id=task["run_id"])
    return row, frf


def _method_rows(runs: pd.DataFrame, outs: list) -> pd.DataFrame:
    """``results`` rows of the other methods: conditions, K and C (N and kN), uncertainty, QC."""
    rows = []
    for (_, r), (fields, _) in zip(runs.iterrows(), outs):
        reasons = list(fields.pop("reasons", []))
        row = {**r.to_dict(), **fields}
        for q, unit in (("stiffness", "N_per_m"), ("damping", "N_s_per_m")):
            row[f"{q}_k{unit}"] = row.get(f"{q}_{unit}", np.nan) / 1e3
        row["qc_ok"] = not reasons and np.isfinite(row.get("stiffness_N_per_m", np.nan))
        row["qc_reasons"] = "; ".join(reasons)
        row["uncertainty_source"] = "type A of the method, §3.2.9 limits" if not reasons else ""
        rows.append(row)
    return pd.DataFrame(rows)


def _flagged_by_analyse(reasons: str) -> bool:
    """Whether a run's ``qc_reasons`` hold a reason of this stage's QC (not calibrate's day flag)."""
    prefix = CALIBRATION_REASON.split("{")[0]
    return any(r and not r.startswith(prefix) for r in reasons.split("; "))


def run(ctx: Context) -> StageResult:
    """Analyse every measurement run in ``manifest``; write ``results``."""
    t0 = time.perf_counter()
    res = StageResult("analyse")
    manifest = ctx.read_table("manifest") if ctx.has_table("manifest") else pd.DataFrame()
    if manifest.empty:
        ctx.write_table(OUTPUT, empty_results())  # an empty table with its columns, not no table
        write_quarantine(ctx, "analyse", [])
        res.seconds = time.perf_counter() - t0
        return res
    runs = manifest[manifest["kind"].fillna("measurement") == "measurement"].copy()
    runs["run_path"] = [str(ctx.build_file(p)) for p in runs["run_path"]]  # relative to the build in the table
    for name, default in (("direction", "vertical"), ("method", "stepped_sine")):
        runs[name] = runs[name].fillna(default) if name in runs else default
    code = code_fingerprint(__name__)
    runs["input_hash"] = [input_hash(s, h, code) for s, h in zip(runs["sha256"], runs["row_hash"])]
    previous = pd.DataFrame() if ctx.force else _previous(ctx)
    reuse = (
        previous[previous["input_hash"].isin(set(runs["input_hash"]))]
        if not previous.empty and "input_hash" in previous
        else pd.DataFrame()
    )
    if not reuse.empty:  # the same run and data may now sit in another campaign folder
        reuse = reuse.assign(campaign=reuse["run_id"].map(runs.set_index("run_id")["campaign"]))
    todo = runs[~runs["input_hash"].isin(set(reuse["input_hash"]) if not reuse.empty else set())]
    res.n_in = len(runs)
    other = todo[todo["method"] != "stepped_sine"]
    todo = todo[todo["method"] == "stepped_sine"]
    chunks = batches(todo)
    ctx.log.info("analyse: %d run(s) reused, %d to analyse in %d batch(es) (%s)",
                 len(reuse), len(todo), len(chunks), ctx.executor)
    catalogue = ctx.read_table("tyres") if ctx.has_table("tyres") else pd.DataFrame(columns=["tyre_id"])
    tyres = {r["tyre_id"]: r for _, r in catalogue.iterrows()}
    progress = Progress("analyse", len(todo) + len(other), logger=ctx.log)
    outs = map_batches(analyse_paths, [_batch_task(c, tyres) for c in chunks], ctx,
                       on_done=lambda i: progress.step(len(chunks[i])), alongside=True)
    frames = [pd.concat([c.reset_index(drop=True), o], axis=1) for c, o in zip(chunks, outs)]
    method_outs = map_batches(analyse_method_path, [_method_task(r) for _, r in other.iterrows()], ctx,
                              on_done=lambda i: progress.step(), alongside=True) if len(other) else []
    if len(other):
        frames.append(_method_rows(other, method_outs))
    new = pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()
    if not new.empty:
        new["rolling"] = new["speed_km_h"] > 0
    results = pd.concat([df for df in (reuse, new) if not df.empty], ignore_index=True) if len(reuse) or len(new) else new
    quarantine = []
    if not results.empty:
        results = results.sort_values("run_id", kind="stable").reset_index(drop=True)
        for name, kind in rm.METHOD_COLUMNS.items():  # every build has them, whatever methods it holds
            if name not in results:
                results[name] = pd.Series(dtype=object if kind is str else float, index=results.index)
        # the issue 34 columns after every earlier one (a reader of the old columns sees them unmoved)
        added = METHOD_CONDITION_COLUMNS + list(rm.METHOD_COLUMNS)
        keep = [c for c in CONDITION_COLUMNS if c in results] + [
            c for c in results.columns if c not in CONDITION_COLUMNS and c not in manifest.columns and c not in added
        ] + added + ["input_hash"]
        results = _with_every_column(results.reindex(columns=list(dict.fromkeys(keep))))
        stepped = (results["method"] == "stepped_sine").to_numpy()
        bad = results[stepped & ~results["excitation_frequency_measured_Hz"].notna()]
        refused = results[~stepped & results["qc_reasons"].fillna("").str.contains("|".join(QUARANTINE_REASONS))]
        files = manifest.set_index("run_id")["file"]
        quarantine = [
            {"campaign": r["campaign"], "run_id": r["run_id"], "file": str(Path(r["campaign"]) / files[r["run_id"]]),
             "stage": "analyse", "reason": reason}
            for frame, fixed in ((bad, "excitation not found"), (refused, None)) for _, r in frame.iterrows()
            for reason in [fixed or f"run {r['run_id']}: method {r['method']}: {r['qc_reasons']}"]
        ]
        for q in quarantine:
            ctx.log.error("%s: %s", q["file"], q["reason"])
        caveat = results.loc[(results["method"] == "free_vibration") & results["speed_km_h"].gt(0)
                             & results["method_note"].fillna("").str.contains(rm.ROLLING_CAVEAT, regex=False)]
        for _, r in caveat.iterrows():  # thesis §3.4's caveat, printed for every rolling free-vibration run
            ctx.log.warning("run %s (free vibration, %g km/h): %s", r["run_id"], r["speed_km_h"], rm.ROLLING_CAVEAT)
    ctx.write_table(OUTPUT, results)
    ctx.write_table("frf", _frf_table(ctx, reuse, other, method_outs))
    write_quarantine(ctx, "analyse", quarantine)
    # this stage's QC only: calibrate adds "calibration failed on <day>" to the results it keeps
    own_flag = results["qc_reasons"].fillna("").map(_flagged_by_analyse) if not results.empty else pd.Series([], dtype=bool)
    reported = results["excitation_frequency_measured_Hz"].notna() | (
        (results["method"] != "stepped_sine") & results["stiffness_N_per_m"].notna()) if not results.empty else None
    res.n_ok = int((~own_flag & reported).sum()) if not results.empty else 0
    res.n_quarantined = len(quarantine)
    flagged = len(results) - res.n_ok - len(quarantine) if not results.empty else 0
    res.message = f"{len(reuse)} reused, {len(new)} analysed" + (f", {flagged} flagged by QC" if flagged else "")
    res.seconds = time.perf_counter() - t0
    return res


def _with_every_column(results: pd.DataFrame) -> pd.DataFrame:
    """``results`` with every column of :func:`empty_results` (null where no run of its method gives
    it: a campaign without a stepped-sine run has no ``excitation_frequency_measured_Hz`` of its own,
    issue 44), each missing column placed after its predecessor in that template."""
    template = empty_results()
    missing = [c for c in template.columns if c not in results.columns]
    if not missing:
        return results
    for c in missing:
        results[c] = pd.Series(dtype=template[c].dtype, index=results.index)
    order = [c for c in results.columns if c not in missing]
    for c in missing:
        before = list(template.columns[: list(template.columns).index(c)])
        anchor = next((b for b in reversed(before) if b in order), None)
        order.insert(order.index(anchor) + 1 if anchor else 0, c)
    return results[order]


def _frf_table(ctx: Context, reuse: pd.DataFrame, other: pd.DataFrame, outs: list) -> pd.DataFrame:
    """Table ``frf``: the reused runs' rows of the last one, then the runs analysed now, by run and frequency."""
    parts = []
    if not reuse.empty and (reuse["method"] != "stepped_sine").any():
        try:
            previous = pd.read_parquet(ctx.table("frf"))
            parts.append(previous[previous["run_id"].isin(set(reuse["run_id"]))])
        except (OSError, ValueError):
            pass
    parts += [frf for _, frf in outs if len(frf)]
    if not parts:
        return pd.DataFrame({c: pd.Series(dtype=object if c in ("run_id", "direction", "method") else
                                          (bool if c == "in_fit" else float)) for c in rm.FRF_COLUMNS})
    out = pd.concat(parts, ignore_index=True).reindex(columns=rm.FRF_COLUMNS)
    return out.sort_values(["run_id", "frequency_Hz"], kind="stable").reset_index(drop=True)


def _previous(ctx: Context) -> pd.DataFrame:
    """The stage's last output, whose rows may be reused; empty if missing or unreadable (a damaged build)."""
    try:
        return pd.read_parquet(ctx.table(OUTPUT))
    except (OSError, ValueError):
        return pd.DataFrame()


def empty_results() -> pd.DataFrame:
    """The ``results`` table with no run: its columns (as :func:`run` writes them), no rows."""
    rows = analyse_batch(np.zeros((0, 2, 1024), np.float32), np.zeros((0, 4, 1024), np.float32), np.zeros(0), 256.0)
    text = {"campaign", "run_id", "tyre_id", "kind", "surface", "recorded_on", "direction", "method"}
    cond = {c: pd.Series(dtype="string" if c in text else float) for c in CONDITION_COLUMNS}
    added = {c: pd.Series(dtype="string" if c in text else float) for c in METHOD_CONDITION_COLUMNS}
    extra = {c: pd.Series(dtype="string" if kind is str else float) for c, kind in rm.METHOD_COLUMNS.items()}
    return pd.DataFrame({**cond, **{c: rows[c] for c in rows.columns}, "rolling": pd.Series(dtype=bool), **added,
                         **extra, "input_hash": pd.Series(dtype="string")})
