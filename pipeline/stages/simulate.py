"""Stage ``simulate``: chapters 6-8 - carriage, tractor, Table XX, ISO 2631 (issue 5).

Reads the digitised thesis Tables XII-XX through :mod:`tyrelab.published`
(``<raw>/published/table_*.csv`` when the raw folder has one, else the copy shipped
with tyrelab, schema-checked; the file read is recorded in the ``source`` column of
``simulate_inputs``), puts them in the studies' layouts with
:mod:`tyrelab.vehicle.published_layouts`, runs the pure studies of
:mod:`tyrelab.vehicle.studies` and :mod:`tyrelab.vehicle.bounce_pitch`, and writes:

``carriage_runs``, ``carriage_comparisons``, ``table_xiii``, ``table_xiv``,
``tractor_runs``, ``table_xvii``, ``table_xviii``, ``table_xx``,
``table_xx_statistics``, ``iso2631``, ``profile_spectra``, ``simulate_inputs``, and the ride
predictions of every scenario (:mod:`tyrelab.vehicle.ride`; the shipped
``raw/scenarios/*.toml`` and any ``<raw>/scenarios/*.toml``, run through the
executor): ``ride_scenarios`` (one row per scenario), ``ride_results`` (one row per
scenario × speed × pressure pair), ``ride_spectra`` and ``ride_transmissibility`` (the seat PSD and
transmissibility per axis and speed of the scenario's own pressures, for the report's Ride page).
A wrong scenario is quarantined with its problems;
the others still run.

The "measured" side of the carriage (ch. 6) and tractor (ch. 7) studies is *recordings*: the
``rides`` stage's ``recordings`` rows that name a ``study`` run (``rides.csv``), read from their
files (:func:`read_study_recordings`); no measured number is made here. A run without a
recording has predictions but no comparison; without any, Tables XIII, XIV and XVII have no
values of ours (gaps) and the recordings' problems are quarantine rows. The demo campaign's
recordings are made by the virtual carriage and tractor of
:mod:`tyrelab.vehicle.study_recordings` (``tyrelab generate``).

The studies are cached as a whole under the digest of what each reads, and each of their cases
under the digest of what the case reads: a carriage case is one Table XII rolling row (its four
predictions and its recording's digest, :func:`tyrelab.vehicle.studies.carriage_case_inputs`),
a tractor case one Table XVI rolling row (its rolling and stationary predictions,
:func:`tyrelab.vehicle.studies.tractor_case_inputs`; the recordings are compared afresh, a
cheap step), so that an edited row or recording re-simulates only the cases that read it; each
ride scenario is cached under the digest of what it reads; those not cached
and Table XX run side by side in one :func:`tyrelab.executor.map_batches` call
(``--jobs``/``--executor``), longest first. The tractor runs are
exact while both axles are in contact and RK4 across lift-off, ``tractor_runs.method_used``
(``exact`` or ``exact+rk4``; ``recording`` for the recorded runs) says which.

Everything is seeded (``SEED``), so the same command gives the same bytes. If the
warehouse holds ``results`` with rolling T4 stiffness on a flat surface at the
Table XII conditions, those are *not* substituted automatically (the Table XII
values were measured immediately before the carriage runs, §6.3); see
``docs/simulation.md``.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pandas as pd

from .. import published
from .._hold import hold
from ..executor import map_batches
from ..tyre.models import THESIS_TABLES, thesis_stiffness_model
from ..vehicle import bounce_pitch, studies
from ..vehicle import published_layouts as layouts
from .base import Context, Progress, StageResult, write_quarantine
from .dag import RIDE_TABLES
from .state import ItemCache
from .ride_scenarios import (WarehouseTyres, _ride_finish, _ride_plan, _ride_todo, collect_scenario_spectra,  # noqa: F401
                             collect_scenarios, portable_path, run_scenarios, scenario_files, scenario_items,
                             scenario_task)

__all__ = ["SEED", "STEMS", "THESIS_XX_STATISTICS", "run", "start_studies_ahead", "abandon_studies_ahead",
           "start_ahead", "abandon_ahead", "item_plan",
           "WarehouseTyres", "scenario_files", "scenario_items", "scenario_task", "run_scenarios", "collect_scenarios",
           "collect_scenario_spectra", "RIDE_TABLES", "portable_path"]

SEED = 5007

#: Published tables the stage reads (stems under ``published/``).
STEMS = ("table_xii", "table_xiii", "table_xiv", "table_xv", "table_xvi", "table_xvii", "table_xviii", "table_xix", "table_xx",
         *THESIS_TABLES)

#: Table XX ratio-error statistics as printed in the prose of thesis §8.2 (not in a
#: table): mean, sd and fraction within ±10 % of predicted/measured frequency, per
#: stiffness source.
THESIS_XX_STATISTICS = {
    "formula": {"mean": 0.998, "sd": 0.09, "p_within_10": 0.75},
    "stationary_free_vibration": {"mean": 1.19, "sd": 0.11, "p_within_10": 0.19},
}


_STATISTIC_ORDER = ["mean_ratio_error", "sd_ratio_error", "p_within_10", "p_within_30", "mean", "sd"]


def _read(ctx: Context) -> tuple[dict[str, pd.DataFrame], pd.DataFrame]:
    """The published tables and the ``simulate_inputs`` record (file read, rows)."""
    tables, sources = {}, []
    for stem in STEMS:
        tables[stem] = published.read_published(stem, ctx.raw)
        path = published.published_dir(ctx.raw) / f"{stem}.csv"
        # relative to the raw folder (published/table_x.csv), a shipped table as shipped/table_x.csv: no
        # path of this machine in the warehouse
        shipped = published.published_dir(None)
        source = (f"shipped/{path.name}" if path.parent.resolve() == shipped.resolve() else
                  portable_path(str(path), ctx.raw))
        sources.append({"table": stem, "source": source, "rows": len(tables[stem])})
    return tables, pd.DataFrame(sources)


def _side_by_side(ours: pd.DataFrame, thesis: pd.DataFrame, keys: list[str]) -> pd.DataFrame:
    """Thesis beside ours for every key either has; blocks in the thesis' order."""
    out = thesis.merge(ours, on=keys, how="outer", sort=False)
    blocks = list(dict.fromkeys(map(tuple, pd.concat([thesis, ours])[keys[:-1]].to_numpy().tolist())))
    out["_block"] = [blocks.index(b) for b in map(tuple, out[keys[:-1]].to_numpy().tolist())]
    out["_stat"] = out[keys[-1]].map(_STATISTIC_ORDER.index)
    out = out.sort_values(["_block", "_stat"], kind="stable")
    for name in ("rolling", "stationary"):
        out[f"difference_{name}"] = out[f"ours_{name}"] - out[f"thesis_{name}"]
    cols = keys + ["thesis_rolling", "ours_rolling", "difference_rolling", "thesis_stationary", "ours_stationary", "difference_stationary"]
    return out[cols].reset_index(drop=True)


def _carriage_tables(car: dict) -> dict:
    """The parts of :func:`tyrelab.vehicle.studies.carriage_study` the stage writes (not the records)."""
    return {k: car[k] for k in ("runs", "comparisons", "table_xiii", "table_xiv", "spectra", "acceleration_spectra")}


def _study(item: tuple) -> dict:
    """One chapter 6/7 study: the tables the stage keeps, with its ``cases`` and the positions of
    those it was given (``reused``)."""
    name, (*args, done) = item
    if name == "carriage":
        xii, stationary, recordings = args
        car = studies.carriage_study(xii, stationary, seed=SEED, cases=done, recordings=recordings)
        return {**_carriage_tables(car), "cases": car["cases"], "reused": sorted(done)}
    mass, tyres, xviii = args
    return {**studies.tractor_study(mass, tyres, seed=SEED, cases=done, table_xviii=xviii), "reused": sorted(done)}


def _task(item: tuple):
    """Executor task (module level, picklable): a chapter 6/7 study (:func:`_study`), Table XX
    (:func:`tyrelab.vehicle.bounce_pitch.table_xx`) or one ride scenario
    (:func:`scenario_task`)."""
    kind, payload = item
    if kind == "ride":
        return scenario_task(payload)
    if kind == "table_xx":
        return bounce_pitch.table_xx(*payload)
    return _study((kind, payload))


def read_study_recordings(ctx: Context, cache: ItemCache | None = None) -> tuple[dict, dict, list[dict]]:
    """The recordings of the chapter 6-7 runs: the ``rides`` stage's ``recordings`` rows with a
    ``study`` (``rides.csv``), each read from its file through the raw ride reader
    (:func:`tyrelab.rawformat.rides.open_recording`) if its content is the one the rides stage
    ingested (``file_sha256``). The offset (mean) of each channel is removed: a recording's DC
    part is no vibration (a DC-coupled accelerometer reads 1 g). With ``cache``, a file's content is
    compared through :meth:`~tyrelab.itemcache.ItemCache.file_digest` (hashed again only if it changed).

    Returns
    -------
    carriage : dict
        :func:`~tyrelab.vehicle.studies.carriage_key` -> ``(digest, floor_z_m_s2 array)``.
    tractor : dict
        :func:`~tyrelab.vehicle.studies.tractor_key` -> ``(digest, {"label", "vertical_m_s2",
        "pitch_rad_s2", "longitudinal_m_s2"})``.
    problems : list of dict
        Quarantine rows, one line each (wrong sampling rate, channel missing, changed since
        ingested, duplicate run); the study goes on without that recording.
    """
    from .. import io
    from ..rawformat import RunFileError, load_channel_map
    from ..rawformat.rides import open_recording

    carriage, tractor, problems = {}, {}, []
    if not ctx.has_table("recordings"):
        return carriage, tractor, problems
    table = ctx.read_table("recordings")
    if "study" not in table.columns:
        return carriage, tractor, problems
    for row in table[table["study"].notna()].to_dict("records"):
        # the rides stage's campaign is relative to the raw folder (an absolute one, of an older build, stays)
        campaign, file = Path(ctx.raw) / str(row["campaign"]), str(row["file"])

        def refuse(reason: str) -> None:
            problems.append({"campaign": str(row["campaign"]), "run_id": str(row["ride_id"]), "file": file,
                             "stage": "simulate", "reason": f"{row['study']} study: {reason}"})
            ctx.log.warning("simulate: %s: %s study: %s", row["ride_id"], row["study"], reason)

        path = campaign / file
        try:
            if not path.is_file() or (cache.file_digest(path) if cache else io.file_sha256(path)) != row["file_sha256"]:
                refuse("the recording changed or went since the rides stage read it (run the rides stage)")
                continue
            cmap = load_channel_map(campaign / "channel_map.json") if (campaign / "channel_map.json").is_file() else None
            rec = open_recording(path, cmap)
            if abs(rec.sample_rate_Hz - studies.FS_HZ) > 1e-6 * studies.FS_HZ:
                refuse(f"sampled at {rec.sample_rate_Hz:g} Hz; the study's records are {studies.FS_HZ:g} Hz")
                continue
            if "floor_z_m_s2" not in rec.channels:
                refuse("no floor_z_m_s2 channel (the body's vertical acceleration)")
                continue
            parts: dict = {c: [] for c in rec.channels}
            for chunk in rec.chunks():
                for c in rec.channels:
                    parts[c].append(chunk.channels[c])
        except (RunFileError, OSError) as exc:
            refuse(str(exc).splitlines()[0])
            continue
        signals = {c: (lambda x: x - x.mean())(np.concatenate(v).astype(float)) for c, v in parts.items()}
        try:
            if row["study"] == "carriage":
                key, value = studies.carriage_key(row), signals["floor_z_m_s2"]
                found = carriage
            else:
                key = studies.tractor_key({**row, "track": row.get("study_track")})
                value = {"label": f"recording {row['ride_id']}", "vertical_m_s2": signals["floor_z_m_s2"],
                         "pitch_rad_s2": signals.get("pitch_rad_s2"), "longitudinal_m_s2": signals.get("floor_x_m_s2")}
                found = tractor
        except (TypeError, ValueError, KeyError):
            refuse(f"load_condition {row.get('load_condition')!r} / study_track {row.get('study_track')!r} do not "
                   "name a run of the study")
            continue
        if key in found:
            refuse(f"a second recording of the run {key} (the first is used)")
            continue
        found[key] = (row["file_sha256"], value)
    return carriage, tractor, problems


def _study_plan(pub: dict, cache: ItemCache, folder: Path, carriage_recordings: dict | None = None
                ) -> tuple[dict, dict, dict]:
    """The chapter 6 and 7 studies: cache key and inputs of each (``"tractor"``, ``"carriage"``),
    and the cache keys of each one's cases (one per Table XII or XVI rolling row).

    Each is kept under the digest of exactly what it reads (ItemCache): a new recording or a
    changed ride scenario re-runs neither, a changed Table XII only the carriage, and of a study
    only the cases whose inputs changed run again (:func:`_payload`). Tables that do not fit
    together (a rolling row whose load condition has no stationary or Table XV row, in
    ``folder``) raise :class:`tyrelab.published.PublishedTableError` naming every problem.
    """
    xii = layouts.carriage_rolling(pub["table_xii"])
    stationary = layouts.carriage_stationary(pub["table_xii"])
    mass, tyres = layouts.tractor_mass(pub["table_xv"]), layouts.tractor_tyres(pub["table_xvi"])
    recs = carriage_recordings or {}
    digests = {k: d for k, (d, _) in recs.items()}
    xviii = pub["table_xviii"]  # the sweep's longitudinal elements: <raw>/published when it has one
    keys = {"tractor": cache.key("tractor", mass, tyres, studies.longitudinal_grid(xviii), SEED),
            "carriage": cache.key("carriage", xii, stationary, SEED, sorted(digests.items()))}
    case_keys, problems = {}, []
    for name, what, cases in (("tractor", "tractor study (table_xv, table_xvi)",
                               lambda: studies.tractor_case_inputs(mass, tyres, table_xviii=xviii)),
                              ("carriage", "carriage study (table_xii)", lambda: studies.carriage_case_inputs(xii, stationary))):
        try:  # a carriage case reads its run's recording (its digest); a tractor case predictions only
            case_keys[name] = [cache.key(f"{name}-case", c, SEED,
                                         digests.get(studies.carriage_key(c["row"])) if name == "carriage" else None)
                               for c in cases()]
        except ValueError as exc:  # tables that do not fit together (an edited <raw>/published)
            problems.append(f"{what}: {exc}")
    if problems:
        raise published.PublishedTableError(f"{folder}: {'; '.join(problems)}")
    return keys, {"tractor": (mass, tyres, xviii),
                  "carriage": (xii, stationary, {k: a for k, (_, a) in recs.items()})}, case_keys


#: Item kinds of the studies' cases in the stage's cache (counted apart in its message).
CASE_KINDS = ("carriage-case", "tractor-case")


def _payload(name: str, inputs: tuple, case_keys: dict, cache: ItemCache) -> tuple:
    """The task payload of study ``name``: its inputs and its cases found (readable) in the cache,
    by position. Counted by :func:`_keep_study` when the study's result is taken."""
    return (*inputs, {i: v for i, k in enumerate(case_keys[name]) for hit, v in [cache.load(k)] if hit})


def _keep_study(cache: ItemCache, name: str, key: str, value: dict, case_keys: dict) -> dict:
    """Store a computed study under ``key`` and the cases it computed under theirs (an unreadable
    entry is replaced), count the ones it was given as reused; return the study's tables."""
    value = dict(value)
    reused = set(value.pop("reused"))
    for i, (k, case) in enumerate(zip(case_keys[name], value.pop("cases"))):
        if i in reused:
            cache.reused(k)
        else:
            cache.put(k, case)
    cache.put(key, value)
    return value


#: Studies started ahead of the stage (:func:`start_studies_ahead`), in this process: key -> (pool, future).
_AHEAD: dict = {}


def start_studies_ahead(ctx: Context) -> list[str]:
    """Start the chapter 6 and 7 studies that are not in the cache now, one worker each.

    They read only the published Tables XII, XV and XVI, not the recordings, so
    ``tyrelab run`` starts the ones not cached (both on a first build, the carriage after an
    edited Table XII) as soon as the per-run stages are done and the worker server is ready
    (:func:`tyrelab.stages.run_pipeline`): they then run while calibrate and regress keep
    one core busy, instead of after them. The stage takes their results as its own (the
    same task, inputs and cache key; one not yet started is cancelled and run by the stage).
    Returns the names of the studies started.
    """
    from ..executor import worker_pool

    if _AHEAD or ctx.executor != "local" or int(ctx.jobs or 1) < 2:
        return []
    cache = ItemCache(ctx, "simulate")
    try:
        pub, _ = _read(ctx)
        keys, inputs, case_keys = _study_plan(pub, cache, published.published_dir(ctx.raw))
    except published.PublishedTableError:
        return []  # the stage reports it, after the stages before it have run
    # the tractor's predictions read no recording; the carriage's cases compare with the
    # recordings, which the rides stage (after this point) may still change
    todo = [name for name in keys if name == "tractor" and not cache.has(keys[name])]
    if not todo:
        return []
    pool = worker_pool(len(todo))
    for name in todo:
        _AHEAD[keys[name]] = (pool, pool.submit(_ahead_task, (name, _payload(name, inputs[name], case_keys, cache))))
    ctx.log.info("simulate: %s started ahead, on %d worker(s)", " and ".join(todo), len(todo))
    return todo


def _ahead_task(item: tuple):
    """:func:`_task` of a study started ahead, in its worker (the hold point ``ahead`` of the tests:
    :mod:`tyrelab._hold`)."""
    hold("ahead")
    return _task(item)


def start_ahead(ctx: Context) -> list[str]:
    """The stage's work started ahead by :func:`tyrelab.stages.run_pipeline` (``Stage.ahead``):
    :func:`start_studies_ahead`."""
    return start_studies_ahead(ctx)


def abandon_studies_ahead() -> None:
    """End the studies started ahead that no stage took (an interrupt, an error, a stage skipped)."""
    from ..executor import abandon_pool

    pools = {id(pool): pool for pool, _ in _AHEAD.values()}
    _AHEAD.clear()
    for pool in pools.values():
        abandon_pool(pool)


#: What :func:`tyrelab.stages.run_pipeline` calls to end the work started ahead that no stage took.
abandon_ahead = abandon_studies_ahead


def _take_ahead(key: str):
    """``(True, result)`` of the study started ahead under ``key``, or ``(False, None)`` (none, or
    cancelled before it started: the stage runs it)."""
    pool, future = _AHEAD.pop(key, (None, None))
    if future is None:
        return False, None
    if not any(p is pool for p, _ in _AHEAD.values()):
        pool.shutdown(wait=False, cancel_futures=True)  # its last study: no new work for it
    if future.cancel():
        return False, None
    return True, future.result()


def _compute(ctx: Context, pub: dict, sources: pd.DataFrame, cache: ItemCache, files: list, ride_keys: list,
             ride_tyres: list) -> tuple[dict, list[dict], dict]:
    """The stage's tables and quarantine rows from its items (each computed or from the cache), and
    the counts of its result."""
    # the studies not in the cache (nor started ahead), the ride scenarios not in the cache and
    # Table XX run side by side, one executor call (tyrelab.executor.map_batches), longest first:
    # with two workers the tractor study runs on one while the carriage study, the scenarios and
    # Table XX share the other
    car_recs, tr_recs, rec_problems = read_study_recordings(ctx, cache)
    keys, inputs, case_keys = _study_plan(pub, cache, published.published_dir(ctx.raw), car_recs)
    cache.keep([k for ks in case_keys.values() for k in ks])  # a cached study's cases stay for the next edit
    done = {name: v for name, k in keys.items() for hit, v in [cache.get(k)] if hit}
    for name in [n for n in keys if n not in done]:
        took, value = _take_ahead(keys[name])
        if took:
            done[name] = _keep_study(cache, name, keys[name], value, case_keys)
    todo = [(name, _payload(name, inputs[name], case_keys, cache)) for name in ("tractor", "carriage") if name not in done]
    ride_done, ride_todo = _ride_todo(files, cache, ride_keys, ride_tyres)
    ride_items = [("ride", item) for item in scenario_items([f for f, _, _ in ride_todo],
                                                              tyre_data=[t for _, _, t in ride_todo])]
    # Table XX reads Tables XIX, XX and the thesis' stiffness formula (its tables)
    xx_key = cache.key("table_xx", pub["table_xix"], pub["table_xx"], *(pub[t] for t in THESIS_TABLES))
    xx_hit, xx = cache.get(xx_key)
    xx_items = [] if xx_hit else [("table_xx", (layouts.tractors(pub["table_xix"]), pub["table_xx"],
                                                thesis_stiffness_model(*(pub[t] for t in THESIS_TABLES))))]
    items = todo + ride_items + xx_items
    progress = Progress("simulate", len(items), logger=ctx.log, unit="studies/scenarios")
    outputs = map_batches(_task, items, ctx, on_done=lambda i: progress.step()) if items else []
    for (name, _), value in zip(todo, outputs):
        done[name] = _keep_study(cache, name, keys[name], value, case_keys)
    ride_outputs = outputs[len(todo):len(todo) + len(ride_items)]
    if not xx_hit:
        xx = outputs[-1]
        cache.put(xx_key, xx)
    car = done["carriage"]
    # the "measured" side: the recordings (no measured number is made here; none: the tables' gaps)
    tr = studies.with_tractor_recordings(done["tractor"], {k: v for k, (_, v) in tr_recs.items()})

    # chapter 6: carriage
    xiii = _side_by_side(
        car["table_xiii"].rename(columns={"rolling": "ours_rolling", "stationary": "ours_stationary"}),
        layouts.carriage_accuracy(pub["table_xiii"]),
        ["quantity", "statistic"],
    )
    xiv = _side_by_side(
        car["table_xiv"].rename(columns={"rolling": "ours_rolling", "stationary": "ours_stationary"}),
        layouts.carriage_accuracy(pub["table_xiv"]),
        ["quantity", "statistic"],
    )

    # chapter 7: tractor
    xvii = _side_by_side(tr["table_xvii"], layouts.tractor_accuracy(pub["table_xvii"]), ["track", "quantity", "statistic"])
    thesis_xviii = layouts.longitudinal_sweep(pub["table_xviii"])
    xviii = tr["table_xviii"].merge(
        thesis_xviii[thesis_xviii["row"] == "predicted"].drop(columns="row").assign(longitudinal="kelvin_voigt"),
        on=["longitudinal", "longitudinal_stiffness_kN_per_m", "longitudinal_damping_kN_s_per_m"],
        how="left",
        suffixes=("_ours", "_thesis"),
    )
    ref = tr["reference_xviii"].iloc[0] if len(tr["reference_xviii"]) else pd.Series(dtype=float)
    meas = thesis_xviii[thesis_xviii["row"] == "measured"].iloc[0]
    xviii = pd.concat(
        [
            xviii.assign(row="predicted"),
            pd.DataFrame(
                [
                    {
                        "row": "measured (ours: recording, load condition 1, SBT, 10 km/h)",
                        "longitudinal": "recorded",
                        "longitudinal_stiffness_kN_per_m": float("nan"),  # not in a recording
                        "longitudinal_damping_kN_s_per_m": float("nan"),
                        **{f"{c}_ours": ref.get(c, float("nan")) for c in ("vertical_rms_m_s2", "pitch_rms_rad_s2", "peak_1_Hz", "peak_2_Hz", "peak_3_Hz")},
                        **{f"{c}_thesis": meas[c] for c in ("vertical_rms_m_s2", "pitch_rms_rad_s2", "peak_1_Hz", "peak_2_Hz", "peak_3_Hz")},
                    }
                ]
            ),
        ],
        ignore_index=True,
    )

    # chapter 8: Table XX
    xx_stats = bounce_pitch.table_xx_statistics(xx)
    for stat in ("mean", "sd", "p_within_10"):
        printed = {source: s[stat] for source, s in THESIS_XX_STATISTICS.items()}
        xx_stats[f"thesis_printed_{stat}"] = xx_stats["stiffness_source"].map(printed)

    # ISO 2631 of every simulated run
    cr = car["runs"]
    iso_car = cr[["speed_km_h", "load_condition", "characteristics", "profile_estimate"] + [c for c in cr if c.startswith("iso_")]].copy()
    iso_car.insert(0, "study", "carriage")
    trr = tr["runs"]
    iso_tr = trr[["load_condition", "track", "speed_km_h", "characteristics", "longitudinal"] + [c for c in trr if c.startswith("iso_")]].copy()
    iso_tr["load_condition"] = iso_tr["load_condition"].astype(str)
    iso_tr.insert(0, "study", "tractor")
    iso = pd.concat([iso_car, iso_tr], ignore_index=True)

    spectra = pd.concat([car["spectra"], tr["spectra"]], ignore_index=True)

    tables = {
        "carriage_runs": cr,
        "carriage_comparisons": car["comparisons"],
        "carriage_spectra": car["acceleration_spectra"],
        "table_xiii": xiii,
        "table_xiv": xiv,
        "tractor_runs": trr,
        "table_xvii": xvii,
        "table_xviii": xviii,
        "table_xx": xx,
        "table_xx_statistics": xx_stats,
        "iso2631": iso,
        "profile_spectra": spectra,
        "simulate_inputs": sources,
    }
    # ride scenarios (issue 13)
    ride_tables, bad = _ride_finish(ctx, files, cache, ride_keys, ride_done, ride_todo, ride_outputs)
    portable = {path: portable_path(path, ctx.raw) for path, _ in files}
    for name, df in ride_tables.items():  # the warehouse holds no path of this machine (a build is portable)
        if "file" in df:
            ride_tables[name] = df.assign(file=df["file"].map(lambda f: portable.get(f, f)))
    bad = [{**b, "file": portable.get(b["file"], b["file"]),  # nor in a reason (a ScenarioError names its file)
            "reason": str(b["reason"]).replace(b["file"], portable.get(b["file"], b["file"]))} for b in bad]
    tables.update(ride_tables)
    quarantine = [{"campaign": None, "run_id": None, "file": b["file"], "stage": "simulate", "reason": b["reason"]}
                  for b in bad] + rec_problems
    n_runs = len(cr) + len(trr)
    counts = {"n_in": n_runs + len(files), "n_ok": n_runs + len(files) - len(bad), "n_quarantined": len(bad),
              "message": f"{len(tables)} tables; {len(files) - len(bad)} ride scenarios; recordings of the studies: "
                         f"{len(car_recs)} carriage, {len(tr_recs)} tractor"}
    return tables, quarantine, counts


def _study_recording_inputs(ctx: Context, cache: ItemCache):
    """What :func:`read_study_recordings` reads, by content: the ``recordings`` rows naming a study,
    the digest of each one's file now and of its campaign's channel map (files looked up by
    :meth:`~tyrelab.itemcache.ItemCache.file_digest`: an unchanged recording is not read)."""
    if not ctx.has_table("recordings"):
        return None
    table = ctx.read_table("recordings")
    if "study" not in table.columns:
        return list(table.columns)
    rows = table[table["study"].notna()].reset_index(drop=True)

    def content(path: Path) -> str:
        try:
            return cache.file_digest(path) if path.is_file() else "missing"
        except OSError as exc:
            return f"unreadable: {exc}"

    # the campaign is relative to the raw folder (as read_study_recordings reads it), not to this process's folder
    files = [content(ctx.raw_file(c, f)) for c, f in zip(rows["campaign"], rows["file"])]
    maps = {str(c): content(ctx.raw_file(c, "channel_map.json")) for c in sorted(set(map(str, rows["campaign"])))}
    return [rows, files, maps]


def item_plan(ctx: Context) -> list[str]:
    """What a run of the stage now would compute, item by item, computing nothing (``run --explain``)."""
    pub, sources = _read(ctx)
    cache = ItemCache(ctx, "simulate")
    files = scenario_files(ctx.raw)
    ride_keys, _ = _ride_plan(ctx, files, cache)
    if cache.has(cache.key("outputs", pub, sources, files, ride_keys, _study_recording_inputs(ctx, cache), SEED)):
        return ["the tables: kept (no item's inputs changed)"]
    kept = sum(cache.has(k) for k in ride_keys)
    xx = cache.has(cache.key("table_xx", pub["table_xix"], pub["table_xx"], *(pub[t] for t in THESIS_TABLES)))
    return [f"ride scenarios: {kept} kept, {len(ride_keys) - kept} to run; Table XX: {'kept' if xx else 'to run'}; "
            "the tables: assembled again"]


def run(ctx: Context) -> StageResult:
    """Run the chapter 6-8 simulations and write their tables (see module docstring).

    The whole set of tables is an item too, kept under the digest of everything the stage's items
    read (the published tables, the ride scenarios' keys, the study recordings by content): when
    the stage runs because an input changed that none of its items reads (the fits of a tyre no
    scenario names, a recording of no study), it writes the tables it kept, reading no recording
    and running nothing."""
    t0 = time.perf_counter()
    pub, sources = _read(ctx)
    cache = ItemCache(ctx, "simulate")
    files = scenario_files(ctx.raw)
    ride_keys, ride_tyres = _ride_plan(ctx, files, cache)
    whole = cache.key("outputs", pub, sources, files, ride_keys, _study_recording_inputs(ctx, cache), SEED)
    hit, kept = cache.get(whole)
    if hit:
        cache.keep(kept["items"])  # the items stay for the next change
        tables, quarantine, counts = kept["tables"], kept["quarantine"], kept["counts"]
        items = "no item's inputs changed: the tables of the last run"
    else:
        tables, quarantine, counts = _compute(ctx, pub, sources, cache, files, ride_keys, ride_tyres)
        cache.put(whole, {"tables": tables, "quarantine": quarantine, "counts": counts,
                          "items": sorted(cache.used - {whole})})
        items = (f"studies {cache.summary(exclude=(*CASE_KINDS, 'ride', 'table_xx', 'outputs'))}; "
                 f"ride scenarios {cache.summary('ride')}; carriage cases {cache.summary('carriage-case')}; "
                 f"tractor cases {cache.summary('tractor-case')}; Table XX {cache.summary('table_xx')}")
    write_quarantine(ctx, "simulate", quarantine)
    for name, df in tables.items():
        ctx.write_table(name, df.reset_index(drop=True))
    cache.prune()
    return StageResult(
        name="simulate", n_in=counts["n_in"], n_ok=counts["n_ok"], n_quarantined=counts["n_quarantined"],
        seconds=time.perf_counter() - t0,
        message=f"{counts['message']}; {items}; slatted track is a seeded stand-in",
    )
