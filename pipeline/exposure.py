"""A driver's daily vibration exposure from recordings: what ``tyrelab exposure`` prints.

Each task names a recording (raw format v1 for vehicles, :mod:`tyrelab.rawformat.rides`)
and its daily hours. Every recording is analysed once, streamed
(:func:`tyrelab.vehicle.measured_ride.analyse_recording`), and the day is combined by
:func:`tyrelab.vehicle.daily_exposure.daily_exposure`.

JSON (:func:`assess`): with one recording, its ``axes`` (``x``/``y``/``z``: ``a_w_m_s2``,
``vdv_m_s1_75``, ``mtvv_m_s2``, ``crest_factor``, ``duration_s``, …), ``a_v_m_s2``,
``dz_m_s2`` with its ISO 2631-5 regime (``dz_regime`` ``loss_of_contact``/``seated``, ``dz_model``,
``dz_applies``, ``seat_z_down_peak_m_s2``, ``loss_of_contact_s``:
:meth:`tyrelab.vehicle.measured_ride.RecordingAnalysis.regime_json`) and ``seat_factor`` (when
floor channels exist) at the top; with several, each task carries its own. The day: ``tasks`` (each with ``partial_a8_m_s2`` per axis), ``a8_m_s2``
(the Directive's, highest axis), ``a8_axis``, ``vdv_daily_m_s1_75``, ``hours_to_eav``,
``hours_to_elv``, ``exposure_points``, ``verdict``, ``dzd_m_s2``. The command prints infinite
hours (no vibration) and NaN as ``null``.

A recording shorter than :data:`tyrelab.vehicle.daily_exposure.MIN_RECORD_S` (10 s) gives its
values with a warning and no verdict (``verdict`` "no verdict: …", the hours to the action and
limit values ``null``); the command then exits 3. Each task names its recording's duration
(``measured_s``) and sample rate (``sample_rate_Hz``). Names and file names are printed with
their control characters escaped (:func:`tyrelab.io.printable`).

The module is also the library's call: ``tyrelab.exposure(recording, hours=…)`` is
:func:`tyrelab.api.exposure` (:func:`exposure`; a module object that can be called, so the name means one thing
whether or not this module was imported first).
"""

from __future__ import annotations

import math
import os
import sys
import types
from dataclasses import dataclass
from pathlib import Path

from ._validate import finite, shown
from .io import printable
from .rawformat import RunFileError

__all__ = ["Task", "RecordingProblem", "ExposureResult", "exposure", "assess", "format_table"]


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


@dataclass(frozen=True)
class ExposureResult:
    """A driver's daily exposure from recordings (:func:`tyrelab.exposure`): the JSON of
    ``tyrelab exposure`` with its main numbers as attributes and its tables as DataFrames.

    Attributes
    ----------
    doc : dict
        The document of :func:`assess` (NaN where a value does not exist, ``inf`` hours where the
        vibration never reaches a value).
    """

    doc: dict

    @property
    def a8_m_s2(self) -> float:
        """The Directive's daily exposure A(8), m/s²: the highest axis's."""
        return self.doc["a8_m_s2"]

    @property
    def a8_axis(self) -> str | None:
        """The axis that governs A(8): largest k·a_w (:func:`tyrelab.vehicle.daily_exposure.governing_axis`)."""
        return self.doc["a8_axis"]

    @property
    def verdict(self) -> str:
        """``below action value``, ``above action value`` or ``above limit value``."""
        return self.doc["verdict"]

    @property
    def hours_to_eav(self) -> float:
        """Hours a day at this mix of tasks to reach the action value (0.5 m/s²), h."""
        return self.doc["hours_to_eav"]

    @property
    def hours_to_elv(self) -> float:
        """Hours a day at this mix of tasks to reach the limit value (1.15 m/s²), h."""
        return self.doc["hours_to_elv"]

    @property
    def axes(self):
        """One row per task and seat axis: ``task``, ``axis``, ``a_w_m_s2`` (without k),
        ``axis_factor`` (k), ``vdv_m_s1_75``, ``mtvv_m_s2``, ``crest_factor``,
        ``partial_a8_m_s2``, ``rms_method_sufficient``."""
        import pandas as pd

        rows = []
        for task in self.doc["tasks"]:
            axes = self.doc["axes"] if "axes" in self.doc else task["axes"]
            for ax, v in axes.items():
                rows.append({"task": task["name"], "axis": ax, "a_w_m_s2": v["a_w_m_s2"], "axis_factor": v["axis_factor"],
                             "vdv_m_s1_75": v["vdv_m_s1_75"], "mtvv_m_s2": v["mtvv_m_s2"],
                             "crest_factor": v["crest_factor"], "partial_a8_m_s2": task["partial_a8_m_s2"].get(ax),
                             "rms_method_sufficient": v["rms_method_sufficient"]})
        return pd.DataFrame(rows)

    @property
    def warnings(self) -> list[str]:
        """What the analysis noticed about the recordings (one line each, naming the file)."""
        return list(self.doc.get("warnings", []))

    def to_dict(self) -> dict:
        """The JSON of ``tyrelab exposure`` (NaN and infinite hours as None)."""
        from .io import json_safe

        return json_safe(self.doc)

    def to_json(self) -> str:
        """:meth:`to_dict` as JSON text (indented)."""
        import json

        return json.dumps(self.to_dict(), indent=2, ensure_ascii=False) + "\n"

    def __str__(self) -> str:
        return format_table(self.doc)


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


#: How the text report states a recording's ISO 2631-5 regime (:mod:`tyrelab.vehicle.iso2631_5`).
REGIME_NOTE = {"loss_of_contact": "loss of seat contact: ISO 2631-5 clause 5",
               "seated": "seated: ISO 2631-5 Annex A, not computed"}


def _f(v, fmt: str = ".3f") -> str:
    return "–" if v is None or (isinstance(v, float) and not math.isfinite(v)) else format(v, fmt)


def format_table(doc: dict, width: int | None = None) -> str:
    """The JSON of :func:`assess` as a short text report, its lines at most ``width`` characters
    (``tyrelab exposure --format table``: 100; ``None``: as long as they are; :func:`tyrelab.io.fit_lines`)."""
    from .io import fit_lines
    from .vehicle.iso2631 import EU_ACTION_VDV, EU_LIMIT_VDV

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
                     + (f" ({REGIME_NOTE[extra['dz_regime']]})" if extra.get("dz_regime") in REGIME_NOTE else "")
                     + (", SEAT " + ", ".join(f"{a} {_f(s, '.2f')}" for a, s in seat.items()) if seat else ""))
    lines.append(f"day: A(8) {_f(doc['a8_m_s2'])} m/s² ({doc['a8_axis']} axis), {printable(doc['verdict'])}; "
                 f"{_f(doc['exposure_points'], '.0f')} HSE points")
    lines.append(f"     hours to EAV {_f(doc['hours_to_eav'], '.1f')}, to ELV {_f(doc['hours_to_elv'], '.1f')} "
                 f"(at this mix of tasks); D_zd {_f(doc['dzd_m_s2'], '.2f')} m/s²")
    # the Directive's second measure: the daily VDV against its own action and limit values
    lines.append(f"     VDV {_f(doc['vdv_daily_m_s1_75'], '.2f')} m/s^1.75 ({doc['vdv_daily_axis']} axis), "
                 f"{printable(doc.get('vdv_verdict', '–'))} (its action value {EU_ACTION_VDV:g}, limit value "
                 f"{EU_LIMIT_VDV:g} m/s^1.75)")
    return "\n".join(fit_lines(lines, width)) + "\n"


def exposure(recording, hours: float = 8.0, *, channel_map: dict | None = None) -> ExposureResult:
    """A driver's daily whole-body vibration exposure from seat recordings: what ``tyrelab exposure`` computes.

    Parameters
    ----------
    recording : path or list of (name, path, hours)
        One seat recording (raw format v1 for vehicles: ``time_s`` and any of ``seat_x_m_s2``,
        ``seat_y_m_s2``, ``seat_z_m_s2``, ``floor_*``; ``.parquet``, ``.csv``, or ``.mf4``/``.tdms``
        with ``channel_map``), or the tasks of a day, each ``(name, path, hours)``.
    hours : float
        Daily hours of a single recording's task, h (0.01 to 24: :func:`tyrelab.vehicle.daily_exposure.hours_problem`;
        not used with a list of tasks).
    channel_map : dict, optional
        For ``.mf4``/``.tdms`` recordings (:func:`tyrelab.rawformat.load_channel_map`).

    Returns
    -------
    tyrelab.exposure.ExposureResult
        ``a8_m_s2``, ``a8_axis`` (the axis that governs A(8)), ``verdict``, ``hours_to_eav``,
        ``hours_to_elv``, ``axes`` (a DataFrame: a_w, VDV, MTVV, crest factor per task and axis),
        ``warnings``; ``to_dict()`` is the JSON of ``tyrelab exposure``.

    Raises
    ------
    ValueError
        Bad hours (naming the task), or tasks adding up to more than a day.
    tyrelab.exposure.RecordingProblem
        Every recording that cannot be used, one line each naming the file.

    See Also
    --------
    tyrelab.api.ride : the same exposure predicted for a tractor scenario.
    tyrelab.vehicle.daily_exposure.daily_exposure : the day from per-task a_w values.

    Examples
    --------
    >>> import numpy as np, pandas as pd, tempfile, tyrelab
    >>> from pathlib import Path
    >>> path = Path(tempfile.mkdtemp()) / "seat.csv"
    >>> t = np.arange(0, 60, 1 / 200)
    >>> pd.DataFrame({"time_s": t, "seat_z_m_s2": 0.8 * np.sin(2 * np.pi * 4 * t)}).to_csv(path, index=False)
    >>> day = tyrelab.exposure(path, hours=8)

    A 4 Hz sine of 0.8 m/s² peak: a_w = 0.8/√2 × ``|W_k(4 Hz)|`` = 0.566 × 0.967 (ISO 2631-1,
    Table 3) = 0.547 m/s², above the action value of 0.5 m/s² over 8 h:

    >>> day.a8_axis, day.verdict, round(day.a8_m_s2, 3), round(day.hours_to_eav, 1)
    ('z', 'above action value', 0.547, 6.7)
    """
    if isinstance(recording, (str, os.PathLike)):
        tasks = [(Path(recording).stem, recording, hours)]
    elif isinstance(recording, (list, tuple)) and recording and all(isinstance(t, (list, tuple)) and len(t) == 3
                                                                   for t in recording):
        tasks = list(recording)
    else:
        raise ValueError("recording must be a path or a list of (name, path, hours) tasks, "
                         f"got {type(recording).__name__}")
    problems = [f"hours of task {name!r}: {p}" for name, _, h in tasks if (p := _hours_problem(h))]
    if problems:  # before any file is read
        raise ValueError("; ".join(problems))
    return ExposureResult(assess([Task(str(n), Path(p), float(h)) for n, p, h in tasks], channel_map))


def _hours_problem(hours) -> str | None:
    """:func:`tyrelab.vehicle.daily_exposure.hours_problem` of a number alone: a bool (``True`` is no
    hour) and an integer too large for a float are refused like every other argument
    (:func:`tyrelab._validate.finite`), never an ``OverflowError``."""
    from .vehicle.daily_exposure import hours_problem

    try:
        hours = finite("hours", hours)
    except ValueError as exc:
        return f"{shown(hours)} is not a {'finite ' if 'finite' in str(exc) else ''}number of hours"
    return hours_problem(hours)


class _CallableModule(types.ModuleType):
    """``tyrelab.exposure``: this module, and called, :func:`exposure`."""

    def __call__(self, recording, hours: float = 8.0, *, channel_map: dict | None = None) -> ExposureResult:
        return exposure(recording, hours, channel_map=channel_map)


sys.modules[__name__].__class__ = _CallableModule
