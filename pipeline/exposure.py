"""A driver's daily vibration exposure from recordings: what ``tyrelab exposure`` prints.

Each task names a recording (raw format v1 for vehicles, :mod:`tyrelab.rawformat.rides`)
and its daily hours. Every recording is analysed once, streamed
(:func:`tyrelab.vehicle.measured_ride.analyse_recording`), and the day is combined by
:func:`tyrelab.vehicle.daily_exposure.daily_exposure`.

JSON (:func:`assess`): with one recording, its ``axes`` (``x``/``y``/``z``: ``a_w_m_s2``,
``vdv_m_s1_75``, ``mtvv_m_s2``, ``crest_factor``, ``duration_s``, …), ``a_v_m_s2``,
``dz_m_s2`` and ``seat_factor`` (when floor channels exist) at the top; with several, each
task carries its own. The day: ``tasks`` (each with ``partial_a8_m_s2`` per axis), ``a8_m_s2``
(the Directive's, highest axis), ``a8_axis``, ``vdv_daily_m_s1_75``, ``hours_to_eav``,
``hours_to_elv``, ``exposure_points``, ``verdict``, ``dzd_m_s2``. The command prints infinite
hours (no vibration) and NaN as ``null``.

A recording shorter than :data:`tyrelab.vehicle.daily_exposure.MIN_RECORD_S` (10 s) gives its
values with a warning and no verdict (``verdict`` "no verdict: …", the hours to the action and
limit values ``null``); the command then exits 3. Each task names its recording's duration
(``measured_s``) and sample rate (``sample_rate_Hz``). Names and file names are printed with
their control characters escaped (:func:`tyrelab.io.printable`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from .io import printable
from .rawformat import RunFileError

__all__ = ["Task", "RecordingProblem", "assess", "format_table"]


@dataclass(frozen=True)
class Task:
    """A task of the day: its name, recording and daily hours."""

    name: str
    file: Path
    hours: float


class RecordingProblem(Exception):
    """Problems with recordings, one line each (``file: problem``); ``usage`` if only missing/unknown files."""

    def __init__(self, lines: list[str], usage: bool):
        super().__init__("; ".join(lines))
        self.lines, self.usage = lines, usage


def _usage_problem(path: Path) -> str | None:
    from .rawformat.files import regular_file
    from .rawformat.rides import RECORDING_SUFFIXES

    try:
        regular_file(path)
    except RunFileError as exc:
        return str(exc)
    if path.suffix.lower() not in RECORDING_SUFFIXES:
        return f"unknown file type {path.suffix!r} (expected {', '.join(RECORDING_SUFFIXES)})"
    try:  # a file we may not open is the user's to fix (exit 2), not a corrupt recording (exit 3)
        with open(path, "rb"):
            pass
    except OSError as exc:
        return f"cannot read ({exc.strerror or exc})"
    return None


def assess(tasks, channel_map: dict | None = None) -> dict:
    """Analyse every task's recording and combine the day.

    Raises
    ------
    RecordingProblem
        Every recording that cannot be used, one line each (all of them, not the first).
    ValueError
        Bad hours (naming the task).
    """
    from .rawformat.rides import open_recording
    from .vehicle.daily_exposure import TaskExposure, daily_exposure
    from .vehicle.measured_ride import analyse_recording

    tasks = list(tasks)
    usage = {t.file: p for t in tasks if (p := _usage_problem(Path(t.file)))}
    if usage:
        raise RecordingProblem([f"{printable(f)}: {p}" for f, p in usage.items()], usage=True)
    analyses, problems = {}, []
    for t in tasks:
        key = Path(t.file).resolve()
        if key in analyses:
            continue
        try:
            analyses[key] = analyse_recording(open_recording(t.file, channel_map))
        except RunFileError as exc:
            problems.append(f"{printable(t.file)}: {exc}")
    if problems:
        raise RecordingProblem(problems, usage=False)
    exposures, per_task = [], []
    for t in tasks:
        a = analyses[Path(t.file).resolve()]
        axes = a.axes()
        if not axes:
            problems.append(f"{printable(t.file)}: no seat channel (seat_x_m_s2, seat_y_m_s2 or seat_z_m_s2): "
                            "the daily exposure is taken at the seat")
            continue
        doc = a.to_json()
        exposures.append(TaskExposure(t.name, t.hours, {ax: v["a_w_m_s2"] for ax, v in axes.items()},
                                      {ax: v["vdv_m_s1_75"] for ax, v in axes.items()}, a.duration_s,
                                      a.dz_m_s2, extra={"file": str(t.file), "sample_rate_Hz": a.sample_rate_Hz}))
        per_task.append(doc)
    if problems:
        raise RecordingProblem(problems, usage=False)
    day = daily_exposure(exposures)
    out: dict = {}
    if len(analyses) == 1:
        out.update(per_task[0])
    else:
        for row, doc in zip(day["tasks"], per_task):
            row.update(doc)
    out.update(day)
    warnings = [f"{printable(t.file)}: {w}" for t in tasks for w in analyses[Path(t.file).resolve()].warnings]
    if day["verdict"].startswith("no verdict"):
        warnings.append(f"{printable(day['verdict'])}: the values are printed, the verdict against the EU action "
                        "and limit values is withheld")
    out["warnings"] = list(dict.fromkeys(warnings))
    return out


def _f(v, fmt: str = ".3f") -> str:
    return "–" if v is None or (isinstance(v, float) and not math.isfinite(v)) else format(v, fmt)


def format_table(doc: dict) -> str:
    """The JSON of :func:`assess` as a short text report."""
    lines = []
    single = "axes" in doc
    for task in doc["tasks"]:
        axes = doc["axes"] if single else task["axes"]
        rate = task.get("sample_rate_Hz")
        lines.append(f"task {printable(task['name'])}: {task['hours']:g} h/day, {printable(task['file'])} "
                     f"({task['measured_s']:.3g} s recorded at {_f(rate, 'g')} Hz)")
        lines.append("  axis  a_w m/s²  k·a_w  VDV m/s^1.75  MTVV m/s²  crest  partial A(8)  method")
        for ax, v in axes.items():
            method = "r.m.s." if v["rms_method_sufficient"] else "VDV/MTVV: " + "; ".join(v["method_reasons"])
            lines.append(f"  {ax:>4}  {_f(v['a_w_m_s2']):>8}  {_f(None if v['a_w_m_s2'] is None else v['axis_factor'] * v['a_w_m_s2']):>5}  "
                         f"{_f(v['vdv_m_s1_75'], '.2f'):>12}  {_f(v['mtvv_m_s2']):>9}  {_f(v['crest_factor'], '.1f'):>5}  "
                         f"{_f(task['partial_a8_m_s2'].get(ax)):>12}  {method}")
        extra = doc if single else task
        seat = extra.get("seat_factor")
        lines.append(f"  a_v {_f(extra['a_v_m_s2'])} m/s², D_z {_f(extra['dz_m_s2'], '.2f')} m/s²"
                     + (", SEAT " + ", ".join(f"{a} {_f(s, '.2f')}" for a, s in seat.items()) if seat else ""))
    lines.append(f"day: A(8) {_f(doc['a8_m_s2'])} m/s² ({doc['a8_axis']} axis), {printable(doc['verdict'])}; "
                 f"{_f(doc['exposure_points'], '.0f')} HSE points")
    lines.append(f"     hours to EAV {_f(doc['hours_to_eav'], '.1f')}, to ELV {_f(doc['hours_to_elv'], '.1f')} "
                 f"(at this mix of tasks); daily VDV {_f(doc['vdv_daily_m_s1_75'], '.2f')} m/s^1.75 "
                 f"({doc['vdv_daily_axis']}), D_zd {_f(doc['dzd_m_s2'], '.2f')} m/s²")
    return "\n".join(lines) + "\n"
