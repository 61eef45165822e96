"""Rides: vehicle recordings -> whole-body vibration, daily exposure, predictions checked (issue 24).

Every campaign folder of ``--raw`` holding ``rides.csv`` (``schemas/raw_rides.json``; beside or
instead of ``manifest.csv``) lists recordings of a vehicle's seat and cab floor
(:mod:`tyrelab.rawformat.rides`). Per recording, streamed in bounded memory, the analysis of
:mod:`tyrelab.vehicle.measured_ride`; for a row naming a ``scenario`` (a TOML of the campaign),
the check against that scenario's prediction at the row's speed on the row's track
(:mod:`tyrelab.vehicle.ride_validation`); per vehicle and day, the daily exposure of the rows
with ``task`` and ``hours_per_day`` (:mod:`tyrelab.vehicle.daily_exposure`).

A row that cannot be used — schema problem, duplicate ``ride_id``, a ``file``/``scenario``/profile
outside the campaign or missing, a bad scenario, a bad recording — goes to the ``quarantine``
table with one line naming it; the other rows go through. A ``rides.csv`` that cannot be read is
rejected as a whole (exit 3). Each recording's analysis and validation is kept by the digest of
what it reads (:class:`tyrelab.stages.state.ItemCache`): an added or edited recording is the only
one analysed again.

Tables: ``recordings`` (one row per recording; with the file's digest ``file_sha256`` and the
thesis study it is a run of, ``study``/``load_condition``/``study_track``, which the
``simulate`` stage reads), ``recording_axes`` (per recording and channel),
``recording_spectra`` (seat PSDs, measured and predicted, for the report), ``exposure_days``,
``ride_validation`` (per recording and axis), ``ride_validation_statistics``.

Recordings with wheel input channels (issue 43, thesis ch. 2: a four-post stand or a track with a
measured profile; ``track = "inputs"`` says the inputs are the excitation) also give their
transfer functions and modes (:func:`tyrelab.measurement.frf.recording_frf`): ``vehicle_frf``
(per recording, input, output and bin) and ``vehicle_modes`` (per recording, output and mode). The
rotation and lug-passing bins of a rolling row naming a scenario are masked from its tyres; such a
row's measured modes and FRFs are compared with the scenario's model at the row's speed
(``vehicle_frf_validation``, :func:`tyrelab.stand.frf_validation_rows`; the model's FRF magnitude
beside the measured one in ``vehicle_frf.predicted_h_magnitude``).
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np
import pandas as pd

from ..io import printable
from ..rawformat import RunFileError
from ..rawformat.files import confined_run_path, read_delimited
from ..schema import load_schema, row_problems
from .base import Context, Progress, StageResult, write_quarantine
from .dag import FIT_TABLES, RIDES_TABLES
from .state import ItemCache

__all__ = ["INPUTS", "OUTPUTS", "discover_ride_campaigns", "run"]

#: What the stage reads and writes (declared in :data:`tyrelab.stages.dag.STAGES`; these are its names).
INPUTS = ["raw", *FIT_TABLES]
OUTPUTS = list(RIDES_TABLES)
#: Columns of ``rides.csv`` naming a thesis study's run (the simulate stage reads these recordings
#: by ``file_sha256``, Tables XIII, XIV, XVII).
STUDY_COLUMNS = ("study", "load_condition", "study_track")
#: Upper frequency of the stored spectra, Hz.
SPECTRA_MAX_HZ = 20.0
#: Columns of each table when it has no row (so the warehouse still has the table, with its columns).
EMPTY_COLUMNS = {
    "recordings": ["ride_id", "campaign", "file", "vehicle", "speed_km_h", "track", "recorded_on", "scenario", "task",
                   "hours_per_day", "sample_rate_Hz", "duration_s", "a_v_m_s2", "dz_m_s2", "dz_regime", "dz_model",
                   "dz_applies", "seat_z_down_peak_m_s2", "loss_of_contact_s", "channels", "warnings",
                   "study", "load_condition", "study_track", "file_sha256", "method"],
    "recording_axes": ["ride_id", "channel", "axis", "weighting", "a_w_m_s2", "vdv_m_s1_75", "mtvv_m_s2", "crest_factor",
                       "rms_method_sufficient", "method_reasons", "unweighted_rms", "peak_frequency_Hz",
                       "half_power_width_Hz", "duration_s"],
    "recording_spectra": ["ride_id", "source", "channel", "frequency_Hz", "psd_m2_s4_per_Hz"],
    "exposure_days": ["campaign", "vehicle", "recorded_on", "tasks", "hours_per_day", "a8_m_s2", "a8_axis",
                      "vdv_daily_m_s1_75", "vdv_daily_axis", "hours_to_eav", "hours_to_elv", "exposure_points", "verdict",
                      "dzd_m_s2", "vdv_verdict"],
    "vehicle_frf": ["ride_id", "input", "wheel", "output", "frequency_Hz", "h_magnitude", "h_phase_deg", "h_unit",
                    "h2_magnitude", "h2_phase_deg", "coherence", "partial_coherence", "multiple_coherence",
                    "random_error", "condition_number", "input_coherence", "ill_conditioned", "masked",
                    "predicted_h_magnitude", "delay_coherence", "input_delay_s"],
    "vehicle_modes": ["ride_id", "output", "mode", "frequency_Hz", "damping_ratio", "frequency_ci95_low_Hz",
                      "frequency_ci95_high_Hz", "damping_ci95_low", "damping_ci95_high", "inputs",
                      "natural_frequency_Hz", "natural_frequency_ci95_low_Hz", "natural_frequency_ci95_high_Hz",
                      "determined", "undetermined_reason"],
    "vehicle_frf_validation": ["ride_id", "speed_km_h", "scenario", "output", "frf_magnitude_error", "model", "mode",
                               "predicted_mode", "measured_frequency_Hz", "measured_frequency_ci95_low_Hz",
                               "measured_frequency_ci95_high_Hz", "predicted_frequency_Hz", "frequency_ratio",
                               "frequency_in_interval", "measured_damping_ratio", "measured_damping_ci95_low",
                               "measured_damping_ci95_high", "predicted_damping_ratio", "damping_ratio_ratio",
                               "damping_in_interval", "measured_determined"],
    "ride_validation": ["ride_id", "campaign", "file", "vehicle", "speed_km_h", "track", "recorded_on", "scenario", "task",
                        "axis", "measured_a_w_m_s2", "predicted_a_w_m_s2", "ratio_a_w", "measured_peak_frequency_Hz",
                        "predicted_peak_frequency_Hz", "measured_half_power_width_Hz", "predicted_half_power_width_Hz",
                        "envelope_similarity"],
}


def _frame(name: str, rows) -> pd.DataFrame:
    if isinstance(rows, pd.DataFrame):
        return rows if len(rows.columns) else pd.DataFrame(columns=EMPTY_COLUMNS[name])
    return pd.DataFrame(rows) if rows else pd.DataFrame({c: pd.Series(dtype="object") for c in EMPTY_COLUMNS[name]})


def discover_ride_campaigns(raw: Path) -> list[Path]:
    """Folders holding ``rides.csv``: ``raw`` itself, else every folder below it that does."""
    raw = Path(raw)
    if (raw / "rides.csv").is_file():
        return [raw]
    return sorted(p.parent for p in raw.rglob("rides.csv") if p.is_file())


def _analyse(path: Path, channel_map) -> dict:
    """Analysis rows of one recording, or ``{"error": reason}``."""
    from ..rawformat.rides import open_recording
    from ..vehicle.measured_ride import analyse_recording

    try:
        a = analyse_recording(open_recording(path, channel_map))
    except (ValueError, ArithmeticError) as exc:  # RunFileError, or a value the analysis refuses: this row only
        return {"error": printable(str(exc).splitlines()[0] if str(exc) else type(exc).__name__)}
    axes = []
    spectra = []
    for c, r in a.channels.items():
        axes.append({"channel": c, "axis": c.split("_")[-2] if c.endswith("_m_s2") else "",
                     "weighting": r.weighting or "", "a_w_m_s2": r.a_w_m_s2, "vdv_m_s1_75": r.vdv_m_s1_75,
                     "mtvv_m_s2": r.mtvv_m_s2, "crest_factor": r.crest_factor,
                     "rms_method_sufficient": bool(r.method.get("rms_method_sufficient", True)) if r.weighting else None,
                     "method_reasons": "; ".join(r.method.get("reasons", [])),
                     "unweighted_rms": r.unweighted_rms, "peak_frequency_Hz": r.peak_frequency_Hz,
                     "half_power_width_Hz": r.half_power_width_Hz, "duration_s": r.duration_s})
        if c.startswith("seat_") and r.frequency_Hz.size:
            keep = (r.frequency_Hz > 0) & (r.frequency_Hz <= SPECTRA_MAX_HZ)
            spectra.append({"channel": c, "frequency_Hz": r.frequency_Hz[keep], "psd": r.psd[keep]})
    ax = a.axes()
    summary = {"sample_rate_Hz": a.sample_rate_Hz, "duration_s": a.duration_s, "a_v_m_s2": a.a_v(),
               "dz_m_s2": a.dz_m_s2, **a.regime_json(), "channels": ",".join(a.channels),
               **{f"seat_factor_{k}": v for k, v in a.seat_factor().items()},
               **{f"a_w_{k}_m_s2": ax[k]["a_w_m_s2"] for k in ax},
               **{f"vdv_{k}_m_s1_75": ax[k]["vdv_m_s1_75"] for k in ax},
               "warnings": "; ".join(a.warnings)}
    return {"summary": summary, "axes": axes, "spectra": spectra,
            "exposure": {k: (ax[k]["a_w_m_s2"], ax[k]["vdv_m_s1_75"]) for k in ax}, "analysis": a}


def _validate(path: Path, channel_map, scenario_path: Path, speed_km_h: float, track, tyre_data,
              measured=None) -> dict:
    """Validation rows of one recording against its scenario's prediction, or ``{"error": reason}``.

    ``tyre_data``: the fits of this run the scenario's tyres read (:class:`tyrelab.stages.tyredata.FitTyres`);
    ``measured``: the recording's analysis (its item, :func:`_analyse`): the recording is then read
    again only on a track of known profile (the envelope similarity compares the signals)."""
    from ..rawformat.rides import open_recording
    from ..vehicle import ride_validation as rv
    from ..vehicle.measured_ride import analyse_recording
    from ..scenario_io import ScenarioError, load_scenario

    try:
        scenario = load_scenario(scenario_path)
    except ScenarioError as exc:
        return {"error": f"scenario {scenario_path.name}: {'; '.join(exc.problems)}"}
    try:
        signals = None
        if track.known_profile or measured is None:
            rec = open_recording(path, channel_map)
        if track.known_profile:
            n = 0
            parts: dict = {c: [] for c in rec.channels}
            for chunk in rec.chunks():
                n += chunk.time_s.size
                if n / rec.sample_rate_Hz > rv.MAX_ENVELOPE_S:
                    parts = None
                    break
                for c in rec.channels:
                    parts[c].append(chunk.channels[c])
            if parts is not None:
                signals = {c: np.concatenate(v) for c, v in parts.items()}
            rec = open_recording(path, channel_map)
        if measured is None:
            measured = analyse_recording(rec)
        predicted, fs = rv.predicted_seat(scenario, speed_km_h, track, tyre_data)
    except (ValueError, ArithmeticError) as exc:  # RunFileError included: this row only
        return {"error": printable(str(exc).splitlines()[0] if str(exc) else type(exc).__name__)}
    rows = rv.validation_rows(measured, predicted, fs, track.known_profile, signals)
    from ..vehicle.measured_ride import analyse_signals

    pred = analyse_signals(predicted, fs)
    spectra = []
    for c, r in pred.channels.items():
        if c.startswith("seat_") and r.frequency_Hz.size:
            keep = (r.frequency_Hz > 0) & (r.frequency_Hz <= SPECTRA_MAX_HZ)
            spectra.append({"channel": c, "frequency_Hz": r.frequency_Hz[keep], "psd": r.psd[keep]})
    return {"rows": rows, "spectra": spectra}


#: The ``track`` of a row whose excitation is the recording's own input channels (issue 43).
INPUTS_TRACK = "inputs"


def _frf(path: Path, channel_map, speed_km_h: float, wheels, scenario=None) -> dict:
    """``vehicle_frf``, ``vehicle_modes`` (and with a scenario ``vehicle_frf_validation``) rows of one
    recording with inputs, or ``{"error": reason}``."""
    from ..measurement.frf import recording_frf
    from ..rawformat.rides import open_recording

    try:
        r = recording_frf(open_recording(path, channel_map), speed_km_h, wheels)
    except (ValueError, ArithmeticError) as exc:
        return {"error": printable(str(exc).splitlines()[0] if str(exc) else type(exc).__name__)}
    predicted, validation = None, []
    if scenario is not None:
        from ..stand import frf_validation_rows, predicted_frf

        try:
            predicted = predicted_frf(r, scenario, speed_km_h)
            validation = frf_validation_rows(r, scenario, speed_km_h, predicted)
        except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
            return {"error": f"prediction: {printable(str(exc).splitlines()[0] if str(exc) else type(exc).__name__)}"}
    return {"frf": pd.DataFrame(r.frf_rows(predicted=predicted)), "modes": r.mode_rows(), "validation": validation}


def _plain(row: dict) -> dict:
    return {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in row.items()}


def run(ctx: Context) -> StageResult:
    """Analyse every recording of every ``rides.csv``; write the tables and quarantine rows."""
    from ..rawformat import load_channel_map
    from ..vehicle import ride_validation as rv
    from ..vehicle.daily_exposure import (HOURS_TOLERANCE_H, MAX_HOURS_PER_DAY, TaskExposure, daily_exposure,
                                          hours_problem)
    from ..scenario_io import ScenarioError, load_scenario
    from .tyredata import FitTyres, read_fit_tables, scenario_fits

    t0 = time.perf_counter()
    schema = load_schema("raw_rides")
    cache = ItemCache(ctx, "rides")
    quarantine: list[dict] = []
    recordings, axes, spectra, validation, tasks = [], [], [], [], []
    frf_parts, mode_rows, frf_validation = [], [], []
    seen: dict[str, str] = {}
    n_in = n_rejected = 0
    fit_tables = read_fit_tables(ctx)

    def where(campaign) -> str:
        """A campaign folder as the warehouse holds it: relative to the raw folder (``.`` for the raw
        folder itself), never this machine's path."""
        try:
            return Path(campaign).resolve().relative_to(Path(ctx.raw).resolve()).as_posix()
        except ValueError:
            return Path(campaign).name

    def refuse(campaign: Path, ride_id, file, reason: str) -> None:
        reason = printable(reason)
        quarantine.append({"campaign": where(campaign), "run_id": None if ride_id is None else str(ride_id),
                           "file": None if file is None else str(file), "stage": "rides", "reason": reason})
        ctx.log.warning("rides: %s: %s: %s", printable(campaign.name),
                        printable(ride_id) if ride_id is not None else "rides.csv", reason)

    for campaign in discover_ride_campaigns(ctx.raw):
        try:
            table = read_delimited(campaign / "rides.csv", schema)
        except RunFileError as exc:
            n_rejected += 1
            refuse(campaign, None, "rides.csv", f"rides.csv: {exc}")
            continue
        frame = table.frame
        whole, by_row = row_problems(frame, schema)
        if whole:
            n_rejected += 1
            refuse(campaign, None, "rides.csv", "rides.csv: " + "; ".join(whole))
            continue
        channel_map = None
        if (campaign / "channel_map.json").is_file():
            try:
                channel_map = load_channel_map(campaign / "channel_map.json")
            except RunFileError as exc:
                channel_map = None
                ctx.log.warning("rides: %s: channel_map.json: %s", campaign.name, exc)
        progress = Progress(f"rides: {campaign.name}", len(frame), logger=ctx.log, unit="recordings")
        for i, row in enumerate(progress.iterate(frame.to_dict("records"))):
            n_in += 1
            ride_id, file = row.get("ride_id"), row.get("file")
            if by_row.get(i):
                refuse(campaign, ride_id, file, "; ".join(by_row[i]))
                continue
            if ride_id in seen:
                refuse(campaign, ride_id, file, f"duplicate ride_id (also in {seen[ride_id]})")
                continue
            seen[ride_id] = where(campaign)
            try:
                path = confined_run_path(campaign, file)
            except RunFileError as exc:
                refuse(campaign, ride_id, file, str(exc))
                continue
            scenario_path = track = fits = profiles = scenario = None
            by_inputs = str(row.get("track") or "").strip().lower() == INPUTS_TRACK
            try:
                track = None if by_inputs else rv.track_of(row.get("track"), campaign)
                if isinstance(row.get("scenario"), str) and row["scenario"].strip():
                    scenario_path = confined_run_path(campaign, row["scenario"].strip())
                    scenario = load_scenario(scenario_path)
                    fits = scenario_fits(scenario, fit_tables)
                    # the profiles the prediction reads: the scenario's (as read) or the row's track file
                    profiles = (scenario.surface.profile_data,
                                cache.file_digest(track.profile) if track is not None and track.kind == "profile"
                                else None)
            except (ValueError, RunFileError, OSError) as exc:  # OSError: the track's profile went unreadable
                problems = exc.problems if isinstance(exc, ScenarioError) else [str(exc)]
                refuse(campaign, ride_id, file, f"scenario {row.get('scenario')}: {'; '.join(problems)}"
                       if isinstance(exc, (ScenarioError, RunFileError)) else str(exc))
                continue
            hours = row.get("hours_per_day")
            hours = float(hours) if hours not in (None, "") and not (isinstance(hours, float) and math.isnan(hours)) \
                else None
            if hours is not None and hours_problem(hours):  # e.g. 1e-320 h: refused before anything is read
                refuse(campaign, ride_id, file, f"hours_per_day: {hours_problem(hours)}")
                continue
            speed = float(row["speed_km_h"])
            if scenario_path is not None and not speed > 0 and not by_inputs:
                refuse(campaign, ride_id, file, f"speed_km_h {speed:g}: a row with a scenario is checked against its "
                                                "prediction at this speed, which needs a speed above 0")
                continue
            digest = cache.file_digest(path)  # by content; an unchanged file (size, mtime) is not read again
            key = cache.key("recording", digest, str(path.suffix), channel_map)
            result = cache.get_or_compute(key, lambda: _analyse(path, channel_map))
            if "error" in result:
                refuse(campaign, ride_id, file, result["error"])
                continue
            from ..measurement.frf import input_channel_wheel, scenario_wheel_geometry

            has_inputs = any(input_channel_wheel(c) for c in result["summary"]["channels"].split(","))
            if by_inputs and not has_inputs:
                refuse(campaign, ride_id, file, f"track = {INPUTS_TRACK!r} but the recording has no input channel "
                                                "(input_<wheel>_z_m_s2 or input_<wheel>_z_m)")
                continue
            frf = None
            if has_inputs:
                wheels = scenario_wheel_geometry(scenario) if scenario is not None and speed > 0 else None
                fkey = cache.key("frf", digest, str(path.suffix), channel_map, speed, wheels,
                                 cache.file_digest(scenario_path) if scenario_path is not None else None, fits)
                frf = cache.get_or_compute(fkey, lambda: _frf(path, channel_map, speed, wheels, scenario))
                if "error" in frf:
                    refuse(campaign, ride_id, file, f"transfer functions: {frf['error']}")
                    continue
            ident = {"ride_id": ride_id, "campaign": where(campaign), "file": str(file), "vehicle": row["vehicle"],
                     "speed_km_h": speed, "track": str(row.get("track") or "scenario"),
                     "recorded_on": str(row["recorded_on"]), "scenario": row.get("scenario") or None,
                     "task": row.get("task") or None}
            val = None
            if scenario_path is not None and not by_inputs:  # checked before the row is kept: a row is kept or quarantined, not both
                # its recording, its scenario and the fits of ITS tyres (scenario_fits): a new run of
                # another tyre leaves the key alone
                vkey = cache.key("validation", digest, cache.file_digest(scenario_path), speed, repr(track), fits,
                                 channel_map, profiles)
                val = cache.get_or_compute(vkey, lambda: _validate(path, channel_map, scenario_path, speed, track,
                                                                   FitTyres(fits, str(ctx.parquet)),
                                                                   result.get("analysis")))
                if "error" in val:
                    refuse(campaign, ride_id, file, f"prediction: {val['error']}")
                    continue
            study = {k: (str(row[k]).strip() if isinstance(row.get(k), str) and row[k].strip() else None)
                     for k in STUDY_COLUMNS}
            method = row.get("method")
            recordings.append({**ident, "hours_per_day": hours, **result["summary"], **study, "file_sha256": digest,
                               "method": method.strip() if isinstance(method, str) and method.strip() else None})
            if frf is not None:
                if len(frf["frf"]):
                    frf_parts.append(frf["frf"].assign(ride_id=ride_id))
                mode_rows.extend({"ride_id": ride_id, **m} for m in frf["modes"])
                frf_validation.extend({"ride_id": ride_id, "speed_km_h": speed, "scenario": ident["scenario"], **v}
                                      for v in frf.get("validation", []))
            axes.extend({"ride_id": ride_id, **a} for a in result["axes"])
            for s in result["spectra"]:
                spectra.append(pd.DataFrame({"ride_id": ride_id, "source": "measured", "channel": s["channel"],
                                             "frequency_Hz": s["frequency_Hz"], "psd_m2_s4_per_Hz": s["psd"]}))
            if hours and row.get("task"):  # a task without a seat channel stays in its day (no verdict), named
                tasks.append((ident, hours, result))
            if val is not None:
                validation.extend({**ident, **r} for r in val["rows"])
                for s in val["spectra"]:
                    spectra.append(pd.DataFrame({"ride_id": ride_id, "source": "predicted", "channel": s["channel"],
                                                 "frequency_Hz": s["frequency_Hz"],
                                                 "psd_m2_s4_per_Hz": s["psd"]}))
    days = []
    by_day: dict = {}
    for ident, hours, result in tasks:
        by_day.setdefault((ident["campaign"], ident["vehicle"], ident["recorded_on"]), []).append((ident, hours, result))
    for (campaign, vehicle, day), items in sorted(by_day.items()):
        # a task whose recording has no seat channel cannot be in the day's A(8): the day keeps it,
        # named, and gets no verdict (its A(8) would leave those hours out)
        seatless = [(i, h) for i, h, r in items if not r["exposure"]]
        seated = [(i, h, r) for i, h, r in items if r["exposure"]]
        try:
            if not seated:
                raise ValueError("no task has a seat channel (seat_x_m_s2, seat_y_m_s2 or seat_z_m_s2)")
            total = sum(h for _, h, _ in items)
            if total > MAX_HOURS_PER_DAY + HOURS_TOLERANCE_H:
                raise ValueError(f"tasks add up to {total:g} h, more than a day ({MAX_HOURS_PER_DAY:g} h)")
            d = daily_exposure([TaskExposure(i["task"], h, {k: v[0] for k, v in r["exposure"].items()},
                                             {k: v[1] for k, v in r["exposure"].items()}, r["summary"]["duration_s"],
                                             r["summary"]["dz_m_s2"]) for i, h, r in seated])
        except ValueError as exc:
            refuse(Path(ctx.raw) / campaign, None, "rides.csv", f"{vehicle} on {day}: {exc}")
            continue
        if seatless:
            names = ", ".join(f"{i['task']} ({h:g} h, {i['ride_id']})" for i, h in seatless)
            withheld = (f"no verdict: task(s) {names} without a seat channel: the daily exposure is taken at the "
                        "seat, and the A(8) leaves those hours out")
            ctx.log.warning("rides: %s on %s: %s", printable(vehicle), day, printable(withheld))
            d = {**d, "verdict": withheld, "vdv_verdict": withheld, "hours_to_eav": math.nan, "hours_to_elv": math.nan,
                 "hours_per_day": d["hours_per_day"] + sum(h for _, h in seatless)}
        days.append({"campaign": campaign, "vehicle": vehicle, "recorded_on": day, "tasks": len(items),
                     "hours_per_day": d["hours_per_day"], "a8_m_s2": d["a8_m_s2"], "a8_axis": d["a8_axis"],
                     **{f"a8_{k}_m_s2": v for k, v in d["a8_axes_m_s2"].items()},
                     "vdv_daily_m_s1_75": d["vdv_daily_m_s1_75"], "vdv_daily_axis": d["vdv_daily_axis"],
                     "hours_to_eav": d["hours_to_eav"], "hours_to_elv": d["hours_to_elv"],
                     "exposure_points": d["exposure_points"], "verdict": d["verdict"], "dzd_m_s2": d["dzd_m_s2"],
                     "vdv_verdict": d["vdv_verdict"]})  # issue 47: the daily VDV's verdict beside A(8)'s
    val_frame = _frame("ride_validation", validation)
    ctx.write_table("recordings", _frame("recordings", recordings))
    ctx.write_table("recording_axes", _frame("recording_axes", axes))
    ctx.write_table("recording_spectra", _frame("recording_spectra", pd.concat(spectra, ignore_index=True) if spectra
                                                else []))
    ctx.write_table("exposure_days", _frame("exposure_days", days))
    ctx.write_table("ride_validation", val_frame)
    frf_frame = pd.concat(frf_parts, ignore_index=True) if frf_parts else []
    if len(frf_parts):
        frf_frame = frf_frame[["ride_id", *[c for c in frf_frame.columns if c != "ride_id"]]]
    ctx.write_table("vehicle_frf", _frame("vehicle_frf", frf_frame))
    ctx.write_table("vehicle_modes", _frame("vehicle_modes", mode_rows))
    ctx.write_table("vehicle_frf_validation", _frame("vehicle_frf_validation", frf_validation))
    ctx.write_table("ride_validation_statistics", rv.validation_statistics(val_frame))
    write_quarantine(ctx, "rides", quarantine)
    cache.prune()
    n_bad = sum(1 for q in quarantine if q["run_id"] is not None)
    return StageResult("rides", n_in=n_in, n_ok=len(recordings), n_quarantined=n_bad, n_rejected=n_rejected,
                       seconds=time.perf_counter() - t0,
                       message=f"recordings {cache.summary('recording')}, validations {cache.summary('validation')}"
                               + (f", transfer functions {cache.summary('frf')}" if mode_rows or frf_parts else ""))
