"""Ingest: validate raw campaigns against ``schemas/`` and write per-run Parquet.

Reads every campaign below ``ctx.raw`` (a folder holding ``manifest.csv``),
the tyre catalogue (``raw/tyres.csv`` shipped with tyrelab, extended by any
``tyres.csv`` in ``ctx.raw`` or a campaign), and each run file. A bad run
never stops the batch: it is written to the ``quarantine`` table with a
one-line reason naming the file, and good runs go through.

Each row's ``method`` and ``direction`` (issue 34, :mod:`tyrelab.measurement.rig_methods`;
defaults ``stepped_sine`` and ``vertical``) are checked against what the row and the file hold,
one line naming run, method and what is missing: ``excitation_frequency_Hz`` for a stepped
sine, ``band_low_Hz``/``band_high_Hz`` for a random run, ``deflection_m`` in the file of a
load-deflection run. The ``manifest`` table carries ``direction`` and ``method`` with their
defaults filled in; a manifest without these columns converts exactly as before.

Run files may be ``.parquet``/``.csv`` (raw format v1) or ``.mf4``/``.tdms``
read through the campaign's ``channel_map.json`` (:mod:`tyrelab.rawformat.mapped`).
Files are hashed, checked and converted in parallel by
:func:`tyrelab.executor.map_batches` (paths go to the workers, not data).

Incremental: the stage is skipped when no file below ``--raw`` changed size or
mtime (it reads ``raw``: :data:`tyrelab.stages.dag.STAGES`) and its outputs are as it wrote them
(:mod:`tyrelab.stages.state`); otherwise a run
whose file bytes (SHA-256, re-hashed only when size or mtime changed) and
manifest row are unchanged, that this code converted and whose converted file is still the one it
wrote (size and mtime), is not re-read, and outputs of runs that
disappeared from the raw folder are removed. Per-run state
(``build/state/ingest_runs.json``) is written after the outputs it describes.

Outputs: ``runs/tyre_id=<id>/<run_key>.parquet`` (channels, float32),
tables ``manifest``, ``tyres`` and its ``quarantine`` rows.
"""

from __future__ import annotations

import hashlib
import json
import logging
import time
import urllib.parse
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from .. import io, resources
from ..io import discover_campaigns
from .. import rawformat as rf
from ..rawformat import CHANNEL_MAP, CHANNELS, MAX_RUN_FILE_BYTES, RUN_SUFFIXES, RunFileError, check_run, read_run_file
from ..rawformat.files import confined_run_path, read_delimited
from ..executor import map_batches
from ..measurement.rig_methods import BAND_REQUIRED, channel_problem
from ..schema import field_names, load_schema, row_problems, validate_frame
from ..tyre.sizes import TyreSizeError, parse_tyre_size
from .base import Context, Progress, StageResult, write_quarantine
from .state import code_fingerprint

__all__ = ["BUILTIN_TYRES", "INFO_KEYS", "discover_campaigns", "run_key", "tyre_partition",
    "load_catalogue", "convert_run", "run", "MANIFEST_EXTRA", "manifest_columns"]

#: The built-in tyre catalogue (thesis Table II).
BUILTIN_TYRES = resources.builtin_tyres()

#: Longest hive partition folder name (``tyre_id=<percent-encoded id>``), bytes: file systems
#: allow 255; a longer tyre id is quarantined rather than crash the write.
MAX_PARTITION_BYTES = 240

#: Sampling facts ingest adds to the ``manifest`` table, in this column order.
INFO_KEYS = ("sample_rate_Hz", "n_samples", "duration_s")


#: A campaign's list of vehicle recordings (raw format of :mod:`tyrelab.rawformat.rides`).
RIDES_FILE = "rides.csv"


def run_key(run_id: str) -> str:
    """A file-name-safe, unique key for a run id (:func:`tyrelab.io.safe_name`)."""
    return io.safe_name(run_id)


def tyre_partition(tyre_id: str) -> str:
    """Hive partition folder name for a tyre (percent-encoded)."""
    return "tyre_id=" + urllib.parse.quote(str(tyre_id), safe="")


def load_catalogue(raw: Path, campaigns: list[Path]) -> tuple[pd.DataFrame, list[str]]:
    """Merge the tyre catalogues; return (tyres with W and R, problems).

    Later catalogues (``raw/tyres.csv``, then each campaign's) override
    earlier rows with the same ``tyre_id``. A row whose size does not parse
    is dropped with a one-line problem naming the file.
    """
    sources = [BUILTIN_TYRES]
    for p in [Path(raw) / "tyres.csv", *[c / "tyres.csv" for c in campaigns]]:
        if p.is_file() and p.resolve() not in {s.resolve() for s in sources}:
            sources.append(p)
    frames, problems = [], []
    schema = load_schema("tyres")
    for src in sources:
        try:
            table = read_delimited(src, schema)
        except RunFileError as exc:
            problems.append(f"{src}: unreadable tyre catalogue ({exc})")
            continue
        df = table.frame
        if table.notes:
            logging.getLogger("tyrelab").info("%s: %s", src, table.describe())
        issues = [p for p in validate_frame(df, {**schema, "additionalFields": True}) if "size" not in p]
        if "tyre_id" not in df.columns or "size" not in df.columns:
            problems.append(f"{src}: tyre catalogue needs columns tyre_id and size")
            continue
        problems.extend(f"{src}: {p}" for p in issues)
        df["catalogue_file"] = str(src)
        frames.append(df)
    cat = pd.concat(frames, ignore_index=True).drop_duplicates("tyre_id", keep="last")
    widths, rims, cons, ok = [], [], [], []
    for _, row in cat.iterrows():
        try:
            s = parse_tyre_size(row["size"])
        except TyreSizeError as exc:
            problems.append(f"{row['catalogue_file']}: tyre {row['tyre_id']!r}: {exc}")
            widths.append(np.nan), rims.append(np.nan), cons.append(None), ok.append(False)
            continue
        widths.append(s.section_width_in), rims.append(s.rim_diameter_in), cons.append(s.construction)
        ok.append(True)
    cat["section_width_in"] = widths
    cat["rim_diameter_in"] = rims
    if "construction" not in cat.columns:
        cat["construction"] = cons
    else:
        cat["construction"] = cat["construction"].fillna(pd.Series(cons, index=cat.index))
    cat["size_ok"] = ok
    return cat.reset_index(drop=True), problems


def _run_table(df: pd.DataFrame, run_id: str, channels: tuple[str, ...]) -> pa.Table:
    # one dictionary entry and all-zero indices: what ``dictionary_encode`` of a column of equal
    # strings gives, without first making a Python string object per sample
    cols = {"run_id": pa.DictionaryArray.from_arrays(pa.array(np.zeros(len(df), dtype=np.int32)),
                                                     pa.array([run_id], pa.string()))}
    cols["time_s"] = pa.array(df["time_s"].to_numpy(dtype=np.float64))
    for c in channels:
        if c != "time_s":
            cols[c] = pa.array(pd.to_numeric(df[c]).to_numpy(dtype=np.float32))
    return pa.table(cols)


def run_file_options(columns: list[str]) -> dict:
    """``pyarrow.parquet.write_table`` options of a converted run file.

    The samples are stored BYTE_STREAM_SPLIT (the bytes of each float grouped by
    significance, which zstd compresses as well as the default encoding) and without
    dictionary encoding, which pyarrow would first try on every float column and give
    up on: writing a run takes ~2.5x less CPU, reading its six channels no more, and
    the file is no larger (docs/benchmarks.md). ``run_id`` stays dictionary-encoded.
    """
    return {"compression": "zstd", "use_dictionary": ["run_id"],
            "column_encoding": {c: "BYTE_STREAM_SPLIT" for c in columns if c != "run_id"}}


def _row_hash(row) -> str:
    return hashlib.sha256(json.dumps({k: str(v) for k, v in row.items()}, sort_keys=True).encode()).hexdigest()


def _read_manifest(path: Path, schema: dict, logger) -> pd.DataFrame:
    """The manifest as strings; separator, decimal mark, BOM and line ends detected (one line if refused)."""
    try:
        table = read_delimited(path, schema)
    except RunFileError as exc:
        raise RunFileError(f"unreadable manifest: {exc}") from None
    if table.notes:
        logger.warning("%s: %s", path, table.describe())
    return table.frame


def convert_run(task: dict) -> dict:
    """Hash, read, check and convert one run file (runs in a worker process).

    Parameters
    ----------
    task : dict
        ``run_id``, ``src`` (raw file), ``out`` (Parquet to write),
        ``excitation_frequency_Hz``, ``sample_rate_Hz`` (manifest, or None),
        ``channel_map`` (path or None), ``size`` (bytes, from ``stat``) and
        ``prev`` (the run's previous state or None): when the file's bytes
        and manifest row are unchanged and the output exists, nothing is read
        beyond hashing.

    Returns
    -------
    dict
        ``run_id``, ``sha256``, and either ``info`` (sampling facts) or
        ``reason`` (one line, the run is quarantined).
    """
    src, out, prev = Path(task["src"]), Path(task["out"]), task.get("prev")
    if task["size"] > MAX_RUN_FILE_BYTES:
        sha = "too-large"  # rejected by size below, never read
    else:
        try:
            sha = io.file_sha256(src)
        except OSError as exc:  # e.g. no read permission: quarantined like any bad run
            return {"run_id": task["run_id"], "sha256": "unreadable", "reason": f"cannot read ({exc.strerror or exc})"}
    done = {"run_id": task["run_id"], "sha256": sha}
    if prev and prev["sha256"] == sha and prev["row"] == task["row"] and prev["out"] == str(out) and out.exists():
        return {**done, "info": prev["info"], "converted": False}
    try:
        cmap = rf.load_channel_map(task["channel_map"]) if task.get("channel_map") else None
        df = read_run_file(src, channel_map=cmap)
        problem = channel_problem(task["run_id"], task.get("method", "stepped_sine"), df.columns)
        if problem:
            raise RunFileError(problem)
        ri = check_run(df, task["excitation_frequency_Hz"], task["sample_rate_Hz"],
                       method=task.get("method", "stepped_sine"))
        with io.atomic_path(out) as tmp:
            table = _run_table(df, task["run_id"], ri.channels)
            pq.write_table(table, tmp, **run_file_options(table.column_names))
    except RunFileError as exc:
        return {**done, "reason": str(exc)}
    info = {"sample_rate_Hz": ri.sample_rate_Hz, "n_samples": ri.n_samples, "duration_s": ri.duration_s}
    return {**done, "info": info, "converted": True}


def _optional_float(row, name: str) -> float | None:
    value = row.get(name)
    return float(value) if value is not None and pd.notna(value) and str(value).strip() != "" else None


def _method(row) -> str:
    """A manifest row's method (``stepped_sine`` where the column is absent or blank)."""
    value = row.get("method")
    return str(value).strip() if isinstance(value, str) and value.strip() else "stepped_sine"


def method_problem(row) -> str | None:
    """One line naming run, method and what its manifest row lacks for the method, or None (issue 34)."""
    run_id, method = row.get("run_id"), _method(row)
    if method == "stepped_sine" and _optional_float(row, "excitation_frequency_Hz") is None:
        return f"run {run_id}: method stepped_sine needs excitation_frequency_Hz, which the row leaves empty"
    lo, hi = _optional_float(row, "band_low_Hz"), _optional_float(row, "band_high_Hz")
    if method in BAND_REQUIRED and (lo is None or hi is None):
        missing = " and ".join(n for n, v in (("band_low_Hz", lo), ("band_high_Hz", hi)) if v is None)
        return f"run {run_id}: method {method} needs its excitation band, {missing} missing"
    if lo is not None and hi is not None and not lo < hi:
        return f"run {run_id}: band_low_Hz {lo:g} is not below band_high_Hz {hi:g}"
    return None


def _cycle_frequency(row) -> float:
    """The frequency the sampling rate must resolve (8 samples a cycle): the excitation of a stepped
    sine, the band's top of a broadband run, none (0) otherwise."""
    if _method(row) == "stepped_sine":
        return float(row["excitation_frequency_Hz"])
    return _optional_float(row, "band_high_Hz") or 0.0


@dataclass
class _Plan:
    """What a pass over the raw folder found: runs to convert and problems."""

    todo: list = field(default_factory=list)  # (campaign, manifest row)
    quarantine: list = field(default_factory=list)
    rejected: int = 0  # manifests or catalogues refused as a whole


def _quarantine_entry(ctx: Context, campaign: Path, run_id, file, reason: str, plan: _Plan) -> None:
    where = campaign / file if isinstance(file, str) and file else campaign / "manifest.csv"
    ctx.log.error("%s: %s", where, reason)
    plan.quarantine.append(  # paths relative to the raw folder: a moved raw folder keeps its table
        {"campaign": ctx.raw_relative(campaign), "run_id": run_id, "file": ctx.raw_relative(where), "stage": "ingest",
         "reason": reason}
    )


def _plan(ctx: Context, schema: dict, campaigns: list[Path], sizes_ok: dict) -> _Plan:
    """Check every manifest row and every file of every campaign; collect the runs to convert."""
    plan = _Plan()
    seen: dict[str, str] = {}
    for campaign in campaigns:
        manifest_path = campaign / "manifest.csv"
        reject = lambda run_id, file, reason: _quarantine_entry(ctx, campaign, run_id, file, reason, plan)  # noqa: E731
        try:
            manifest = _read_manifest(manifest_path, schema, ctx.log)
        except RunFileError as exc:
            reject(None, None, str(exc))
            plan.rejected += 1
            continue
        missing = [c for c in field_names(schema, required_only=True) if c not in manifest.columns]
        if missing:
            found = ", ".join(map(repr, manifest.columns[:6])) + (" …" if len(manifest.columns) > 6 else "")
            reject(None, None, f"manifest lacks column(s) {', '.join(missing)} (found {found})")
            plan.rejected += 1
            continue
        listed = set()
        _, by_row = row_problems(manifest, schema)
        for i, row in enumerate(manifest.to_dict("records")):  # plain dicts: a Series per row cost ~0.3 s per 1 000 runs
            run_id = row["run_id"] if isinstance(row["run_id"], str) else None
            listed.add(str(Path(str(row.get("file")))))
            problems = by_row.get(i, [])
            if problems:
                reject(run_id, row.get("file"), f"manifest row {i + 2}: " + "; ".join(problems))
            elif run_id in seen:
                reject(run_id, row["file"], f"duplicate run_id {run_id!r} (already in {seen[run_id]})")
            elif method_problem(row):
                reject(run_id, row["file"], method_problem(row))
            elif row["tyre_id"] not in sizes_ok:
                reject(run_id, row["file"], f"unknown tyre_id {row['tyre_id']!r} (not in any tyres.csv)")
            elif not sizes_ok[row["tyre_id"]]:
                reject(run_id, row["file"], f"tyre {row['tyre_id']!r} has a size that does not parse")
            elif len(tyre_partition(row["tyre_id"]).encode()) > MAX_PARTITION_BYTES:
                reject(run_id, row["file"], f"tyre_id is {len(row['tyre_id'])} characters long: too long for a folder "
                                            f"name ({MAX_PARTITION_BYTES} bytes once percent-encoded)")
            else:
                plan.todo.append((campaign, row))
            if run_id is not None:
                seen.setdefault(run_id, str(manifest_path))
        recordings = _ride_files(campaign)
        for f in sorted(_run_files(campaign)):
            rel = f.relative_to(campaign)
            if str(rel) in recordings:
                continue  # a vehicle recording of rides.csv (issue 24), not a tyre run
            if str(rel) not in listed and f.name not in listed:
                reject(None, str(rel), "file has no row in manifest.csv")
    return plan


def _run_files(campaign: Path):
    """Regular files of a campaign folder (and its sub-folders without their own manifest) that look like runs.

    Special files (FIFOs, devices) are skipped with a warning by :func:`tyrelab.io.regular_files`."""
    for f in io.regular_files(campaign):
        if f.suffix.lower() not in RUN_SUFFIXES or f.name in ("manifest.csv", "tyres.csv", RIDES_FILE):
            continue
        if any((p / "manifest.csv").is_file() for p in f.parents if p != campaign and campaign in p.parents):
            continue
        yield f


def _ride_files(campaign: Path) -> set[str]:
    """The files a campaign's ``rides.csv`` names (relative paths as written): the vehicle
    recordings of ``file`` and the road-profile CSVs of ``track`` (e.g. the slatted track's
    ``rides/slatted_track.csv`` that ``tyrelab generate`` writes), read by the rides and simulate
    stages, never tyre runs. A ``rides.csv`` that cannot be read names nothing here; the stage
    that reads recordings reports it."""
    path = campaign / RIDES_FILE
    if not path.is_file():
        return set()
    try:  # the project's reader: separator, BOM, decimal commas and size bound as the rides stage reads it
        frame = read_delimited(path, load_schema("raw_rides")).frame
    except RunFileError:
        return set()
    named = set()
    for column in ("file", "track"):
        for f in frame[column].dropna() if column in frame.columns else ():
            text = str(f).strip()
            if text and (column == "file" or text.lower().endswith(".csv")):
                named.add(str(Path(text)))
    return named


def _sweep(runs_dir: Path, keep: set[str]) -> None:
    """Remove run outputs no longer produced and temporary files left by a killed run."""
    for f in runs_dir.rglob("*") if runs_dir.is_dir() else []:
        if f.is_file() and str(f) not in keep:
            f.unlink()
    for d in sorted(runs_dir.glob("*"), reverse=True) if runs_dir.is_dir() else []:
        if d.is_dir() and not any(d.iterdir()):
            d.rmdir()


def run(ctx: Context) -> StageResult:
    """Validate and convert every raw run below ``ctx.raw``; see the module docstring."""
    t0 = time.perf_counter()
    result = StageResult("ingest")
    schema = load_schema("raw_manifest")
    numeric = [f["name"] for f in schema["fields"] if f["type"] in ("number", "integer")]
    campaigns = discover_campaigns(ctx.raw)
    catalogue, cat_problems = load_catalogue(ctx.raw, campaigns)
    plan = _Plan()
    for problem in cat_problems:
        src, _, reason = problem.partition(": ")
        _quarantine_entry(ctx, Path(src).parent, None, Path(src).name, reason, plan)
        plan.rejected += reason.startswith(("unreadable tyre catalogue", "tyre catalogue needs columns"))
    sizes_ok = dict(zip(catalogue["tyre_id"], catalogue["size_ok"]))
    found = _plan(ctx, schema, campaigns, sizes_ok)
    plan.todo, plan.quarantine = found.todo, plan.quarantine + found.quarantine
    plan.rejected += found.rejected

    # a run converted by other code is converted again: its file must be what this code writes
    code = code_fingerprint(__name__)
    state = {} if ctx.force else {k: {**v, "out": str(ctx.build_file(v["out"]))}  # kept relative to the build
                                  for k, v in _load_run_state(ctx).items() if v.get("code") == code}
    runs_dir = ctx.path("parquet/runs/")
    tasks, rows = [], {}
    for campaign, row in plan.todo:
        run_id = row["run_id"]
        out = runs_dir / tyre_partition(row["tyre_id"]) / f"{run_key(run_id)}.parquet"
        row_hash, prev = _row_hash(row), state.get(run_id)
        if prev and _out_stat(out) != prev.get("out_stat"):
            prev = None  # its converted file is missing or not what ingest wrote: convert again
        try:  # inside the campaign after symlinks, a regular file: checked before anything opens it
            src = confined_run_path(campaign, row["file"])
        except RunFileError as exc:
            _quarantine_entry(ctx, campaign, run_id, row["file"], str(exc), plan)
            continue
        st = src.stat()
        cmap = campaign / CHANNEL_MAP
        rows[run_id] = (campaign, row, row_hash, out, st)
        tasks.append({
            "run_id": run_id, "src": str(src), "out": str(out), "row": row_hash, "size": st.st_size, "prev": prev,
            "touched": not prev or (prev["size"], prev["mtime_ns"]) != (st.st_size, st.st_mtime_ns),
            "excitation_frequency_Hz": _cycle_frequency(row), "method": _method(row),
            "sample_rate_Hz": _optional_float(row, "sample_rate_Hz"),
            "channel_map": str(cmap) if cmap.is_file() and src.suffix.lower() in rf.mapped.SUFFIXES else None,
        })
    cached = [t for t in tasks if not t["touched"] and t["prev"]["row"] == t["row"] and t["prev"]["out"] == t["out"]]
    cached_ids = {t["run_id"] for t in cached}
    work = [t for t in tasks if t["run_id"] not in cached_ids]
    ctx.log.info("ingest: %d run(s) unchanged, %d to convert", len(cached), len(work))
    done = {t["run_id"]: {"run_id": t["run_id"], "sha256": t["prev"]["sha256"], "info": t["prev"]["info"]} for t in cached}
    progress = Progress("ingest", len(work), logger=ctx.log)
    done.update((d["run_id"], d) for d in map_batches(convert_run, work, ctx, on_done=lambda i: progress.step(),
                                                      alongside=True))

    new_state, records = {}, []
    for t in tasks:
        campaign, row, row_hash, out, st = rows[t["run_id"]]
        d = done[t["run_id"]]
        if "reason" in d:
            _quarantine_entry(ctx, campaign, t["run_id"], row["file"], d["reason"], plan)
            continue
        new_state[t["run_id"]] = {"size": st.st_size, "mtime_ns": st.st_mtime_ns, "sha256": d["sha256"],
                                  "row": row_hash, "out": ctx.build_relative(out), "info": d["info"], "code": code,
                                  "out_stat": _out_stat(out)}
        rec = {c: row.get(c) for c in manifest_columns(schema, row)}
        rec.update(campaign=ctx.raw_relative(campaign), sha256=d["sha256"], row_hash=row_hash,
                   run_path=ctx.build_relative(out))  # relative: a moved raw or build folder keeps its tables
        rec.update((k, d["info"][k]) for k in INFO_KEYS)  # fixed order: same bytes however info was obtained
        records.append(rec)

    ctx.write_table("manifest", _manifest_table(records, numeric))
    ctx.write_table("tyres", catalogue.drop(columns=["catalogue_file"]))
    write_quarantine(ctx, "ingest", plan.quarantine)
    _sweep(runs_dir, {str(ctx.build_file(s["out"])) for s in new_state.values()})
    io.write_text_atomic(json.dumps(new_state, sort_keys=True), _run_state_path(ctx))  # after the outputs

    result.n_ok = len(records)
    result.n_quarantined = sum(1 for q in plan.quarantine if q["run_id"] is not None)
    unlisted = sum(1 for q in plan.quarantine if q["run_id"] is None)
    # Every entry without a run id is a file, manifest or catalogue refused (a manifest or catalogue
    # refused as a whole is one of them): the command exits 3 for these too (a manifest cut short
    # leaves its runs' files without a row and exited 0).
    result.n_rejected = max(plan.rejected, unlisted)
    result.n_in = result.n_ok + result.n_quarantined
    converted = sum(1 for d in done.values() if d.get("converted") is True)
    unchanged = sum(1 for d in done.values() if not d.get("converted") and "reason" not in d)  # refused: neither
    result.message = f"{converted} converted, {unchanged} unchanged" + (
        f"; {unlisted} file/manifest/catalogue problem(s) without a run id" if unlisted else "")
    result.seconds = time.perf_counter() - t0
    return result


def _run_state_path(ctx: Context) -> Path:
    return ctx.state / "ingest_runs.json"


def _out_stat(path) -> list[int] | None:
    """``[size, mtime_ns]`` of a converted run file (None if missing): a file deleted, truncated or
    overwritten since ingest wrote it is converted again."""
    try:
        st = Path(path).stat()
    except OSError:
        return None
    return [st.st_size, st.st_mtime_ns]


_RUN_STATE_KEYS = {"size", "mtime_ns", "sha256", "row", "out", "info", "code"}


def _load_run_state(ctx: Context) -> dict:
    """Per-run state of the last ingest; entries that are not what :func:`run` writes are dropped
    (a damaged state file is no state: those runs are converted again)."""
    try:
        state = json.loads(_run_state_path(ctx).read_text())
    except (OSError, ValueError):
        return {}
    if not isinstance(state, dict):
        return {}
    return {k: v for k, v in state.items()
            if isinstance(v, dict) and _RUN_STATE_KEYS <= v.keys() and isinstance(v["info"], dict)}


#: Columns ingest adds to the manifest's own.
MANIFEST_EXTRA = {"kind": str, "campaign": str, "sha256": str, "row_hash": str, "run_path": str,
                  "sample_rate_Hz": float, "n_samples": "int64", "duration_s": float}


def _manifest_table(records: list[dict], numeric: list[str]) -> pd.DataFrame:
    df = pd.DataFrame(records)
    if df.empty:  # keep the columns, so the warehouse view and later stages still bind
        names = field_names(load_schema("raw_manifest"))
        types = {c: (float if c in numeric else str) for c in names} | MANIFEST_EXTRA
        return pd.DataFrame({c: pd.Series(dtype=t) for c, t in types.items()})
    for c in numeric:
        if c in df:
            df[c] = pd.to_numeric(df[c])
    if "kind" not in df:
        df["kind"] = "measurement"
    df["kind"] = df["kind"].fillna("measurement")
    for name, default in (("direction", "vertical"), ("method", "stepped_sine")):
        df[name] = df[name].where(df[name].notna() & (df[name].astype(str).str.strip() != ""), default) \
            if name in df else default
    return df.sort_values("run_id", kind="stable").reset_index(drop=True)


def manifest_columns(schema: dict, row) -> list[str]:
    """Manifest columns to carry into the ``manifest`` table: the schema's, then any extras of ``row`` (a mapping)."""
    names = field_names(schema)
    return names + [c for c in row.keys() if c not in names]
