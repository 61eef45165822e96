"""A driver's daily whole-body vibration exposure from tasks, as practice does it.

EU Directive 2002/44/EC (Annex, part B) and the HSE calculator's layout:

- per task ``i`` and axis, the partial exposure ``k a_w,i √(T_i / 8 h)`` (k = 1.4 on x and y,
  1.0 on z; ISO 2631-1 §8.2.3);
- per axis, the partials combine as ``A(8) = √(Σ_i (k a_w,i)² T_i / 8 h)``;
- the Directive's A(8) is the **highest axis** (not the vector sum ``a_v``);
- daily VDV per axis ``(Σ_i VDV_i⁴ T_i / T_meas,i)^(1/4)`` times k, highest axis;
- hours to the action (0.5 m/s²) and limit (1.15 m/s²) values at the day's mix of tasks,
  ``T_day (value / A(8))²`` (one task: ``8 h (value / (k a_w))²``);
- HSE exposure points ``400 A(8)²`` (EAV 100, ELV 529);
- ISO 2631-5:2018 daily dose ``D_zd`` (:func:`tyrelab.vehicle.iso2631_5.daily_dose`).

A day whose tasks' recordings include one shorter than :data:`MIN_RECORD_S` gets its values but
no verdict: ``verdict`` and ``vdv_verdict`` say ``"no verdict: …"`` and the hours to the action
and limit values are NaN. ISO 2631-1:1997 §5.5 asks for a measurement long enough for reasonable
statistical precision and typical of the exposure assessed, and names no figure; the floor is
the ride command's too (:data:`MIN_RECORD_S`, which the scenario's limits read as
:data:`tyrelab.vehicle.scenario_limits.MIN_VERDICT_DURATION_S`: four periods of 0.4 Hz, the lower
band limit of the weightings) — a documented choice, far below what a survey should record.

Examples
--------
>>> day = daily_exposure([TaskExposure("baling", 4.0, {"x": 0.3, "y": 0.2, "z": 0.6},
...                                    {"x": 5.0, "y": 3.0, "z": 9.0}, 3600.0)])
>>> round(day["a8_m_s2"], 4), day["a8_axis"], round(day["exposure_points"], 1), day["verdict"]
(0.4243, 'z', 72.0, 'below action value')
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ... import _validate
from . import iso2631
from . import iso2631_5

__all__ = ["TaskExposure", "daily_exposure", "governing_axis", "verdict", "EXPOSURE_VERDICTS", "MAX_HOURS_PER_DAY", "MIN_HOURS_PER_DAY",
           "HOURS_TOLERANCE_H", "MIN_RECORD_S", "hours_problem", "hours_to"]

#: Verdicts against the Directive's daily values (the strings of :data:`tyrelab.vehicle.ride.VERDICTS`).
EXPOSURE_VERDICTS = ("below action value", "above action value", "above limit value")
#: A day has 24 hours: longer task hours are refused.
MAX_HOURS_PER_DAY = 24.0
#: Shortest daily exposure to a task, h (36 s; the bound of a scenario's ``exposure.hours_per_day``
#: too, :data:`tyrelab.vehicle.scenario_limits.LIMITS`): shorter is a typo, and 1e-320 h would
#: overflow the hours to the action value.
MIN_HOURS_PER_DAY = 0.01
#: How far the tasks' hours may add up beyond :data:`MAX_HOURS_PER_DAY`, h: the rounding of a sum
#: of decimal hours (80 tasks of 0.3 h add up to 24.000000000000036 in floating point).
HOURS_TOLERANCE_H = 1e-9
#: Shortest recording a day's verdict is given on, s: four periods of 0.4 Hz, the lower band limit
#: of the ISO 2631-1 weightings (a documented choice; see the module docstring). The ride's
#: ``MIN_VERDICT_DURATION_S`` (:mod:`tyrelab.vehicle.scenario_limits`) is this one.
MIN_RECORD_S = 10.0


def hours_problem(hours) -> str | None:
    """Why ``hours`` cannot be a task's daily hours (``None`` if it can).

    See Also
    --------
    daily_exposure : refuses such hours.

    Examples
    --------
    >>> hours_problem(8.0) is None, hours_problem(30.0)
    (True, '30 h is not in 0.01 to 24 h (a day)')
    """
    try:
        h = float(hours)
    except (TypeError, ValueError):
        return f"{hours!r} is not a number of hours"
    if not math.isfinite(h):
        return f"{hours!r} is not a finite number of hours"
    if not MIN_HOURS_PER_DAY <= h <= MAX_HOURS_PER_DAY:
        return f"{h:g} h is not in {MIN_HOURS_PER_DAY:g} to {MAX_HOURS_PER_DAY:g} h (a day)"
    return None


@dataclass(frozen=True)
class TaskExposure:
    """One task of a working day: its daily duration and the measured values of its recording.

    Attributes
    ----------
    name : str
    hours : float
        Daily exposure to the task, h.
    a_w_m_s2 : dict
        Axis (``x``, ``y``, ``z``) -> weighted r.m.s. a_w, m/s², *without* the factor k.
    vdv_m_s1_75 : dict
        Axis -> VDV of the recording, m/s^1.75, without k.
    measured_s : float
        Duration of the recording, s.
    dz_m_s2 : float
        ISO 2631-5 dose D_z of the recording (NaN if no vertical seat channel).
    """

    name: str
    hours: float
    a_w_m_s2: dict
    vdv_m_s1_75: dict
    measured_s: float
    dz_m_s2: float = math.nan
    extra: dict = field(default_factory=dict)

    def __post_init__(self):
        problem = hours_problem(self.hours)
        if problem:
            raise ValueError(f"hours of task {self.name!r}: {problem}")
        if not (math.isfinite(self.measured_s) and self.measured_s > 0):
            raise ValueError(f"measured_s must be positive for task {self.name!r}")


def verdict(a8_m_s2: float) -> str:
    """The Directive's verdict on a daily A(8).

    See Also
    --------
    daily_exposure : the day's A(8) and its verdict.

    Examples
    --------
    >>> verdict(0.49), verdict(0.6), verdict(1.2)
    ('below action value', 'above action value', 'above limit value')
    """
    a8_m_s2 = _validate.non_negative("a8_m_s2", a8_m_s2)
    if a8_m_s2 > iso2631.EU_LIMIT_A8_M_S2:
        return EXPOSURE_VERDICTS[2]
    return EXPOSURE_VERDICTS[1] if a8_m_s2 > iso2631.EU_ACTION_A8_M_S2 else EXPOSURE_VERDICTS[0]


def governing_axis(k_a_w_m_s2) -> str | None:
    """The axis that governs the Directive's A(8): the one with the largest ``k·a_w``.

    EU Directive 2002/44/EC takes the daily exposure A(8) as the highest of the three axes'
    ``k·a_w`` (k = 1.4 on x and y, 1.0 on z; ISO 2631-1 §8.2.3), not their vector sum. This is
    the one rule by which ``tyrelab exposure`` (``a8_axis`` of the day), ``tyrelab ride``
    (``a8_axis`` of each speed row) and the pages name that axis.

    Parameters
    ----------
    k_a_w_m_s2 : mapping
        Axis (``x``, ``y``, ``z``) -> ``k·a_w``, m/s² (with the factor k; an axis's A(8) of a
        day does as well: it is ``k·a_w`` scaled by the same ``√(T/8 h)`` for every axis).

    Returns
    -------
    str or None
        The axis with the largest value; on a tie the first of ``x``, ``y``, ``z``; None if no
        axis has a finite value.

    See Also
    --------
    daily_exposure : the day's A(8) and its ``a8_axis``.
    tyrelab.vehicle.ride.exposure : a speed row's A(8) and its ``a8_axis``.

    Examples
    --------
    >>> governing_axis({"x": 1.4 * 0.3, "y": 1.4 * 0.2, "z": 0.4})
    'x'
    >>> governing_axis({"z": 0.6, "x": 0.6}), governing_axis({})
    ('x', None)
    """
    if not hasattr(k_a_w_m_s2, "items"):
        raise ValueError(f"k_a_w_m_s2 must be a mapping of axis to k·a_w, got {type(k_a_w_m_s2).__name__}")
    finite = {ax: float(v) for ax, v in k_a_w_m_s2.items() if v is not None and math.isfinite(v)}
    ordered = [ax for ax in ("x", "y", "z") if ax in finite] + [ax for ax in finite if ax not in ("x", "y", "z")]
    return max(ordered, key=lambda ax: finite[ax]) if ordered else None


def hours_to(value_m_s2: float, a8_m_s2: float, day_hours: float) -> float:
    """Hours a day at which a day's mix of exposure (``a8_m_s2`` over ``day_hours``) reaches the daily
    value ``value_m_s2``: ``T_day (value / A(8))²`` (EU Directive 2002/44/EC; one task of ``k a_w``
    over 8 h: ``8 h (value / (k a_w))²``); ``inf`` without vibration, NaN for an A(8) that is not a
    number. The one home of the hours to the action and limit values (the ride's rows read it).

    See Also
    --------
    daily_exposure : a day's A(8) and its hours to the action and limit values.

    Examples
    --------
    >>> round(hours_to(iso2631.EU_ACTION_A8_M_S2, 0.6, 8.0), 3), hours_to(0.5, 0.0, 8.0)
    (5.556, inf)
    """
    _validate.positive("value_m_s2", value_m_s2)
    _validate.non_negative("day_hours", day_hours)
    a8 = a8_m_s2
    if not a8 > 0:
        return math.inf if a8 == 0 else math.nan
    try:
        return day_hours * (value_m_s2 / a8) ** 2
    except OverflowError:  # an A(8) of ~1e-160 m/s²: no vibration to speak of
        return math.inf


def daily_exposure(tasks) -> dict:
    """Daily exposure of a driver from one or more tasks (see the module docstring).

    Parameters
    ----------
    tasks : sequence of TaskExposure

    Returns
    -------
    dict
        ``tasks`` (per task: ``name, hours, partial_a8_m_s2`` per axis with k, ``a_w_m_s2``
        per axis, ``hours_to_eav``, ``hours_to_elv``), ``a8_axes_m_s2`` (per axis, with k),
        ``a8_m_s2`` (the Directive's: highest axis), ``a8_axis``, ``vdv_daily_axes_m_s1_75``,
        ``vdv_daily_m_s1_75``, ``vdv_daily_axis``, ``hours_to_eav``, ``hours_to_elv``,
        ``exposure_points``, ``verdict``, ``vdv_verdict``, ``dzd_m_s2``, ``hours_per_day``.

    See Also
    --------
    governing_axis : the rule that names ``a8_axis``.
    tyrelab.exposure : the same from recordings.

    Examples
    --------
    Two tasks: 0.6 m/s² on z for 4 h and 0.3 m/s² for 4 h give A(8) = √(0.6²·4/8 + 0.3²·4/8) = 0.474 m/s²:

    >>> day = daily_exposure([TaskExposure("a", 4.0, {"z": 0.6}, {"z": 8.0}, 600.0),
    ...                       TaskExposure("b", 4.0, {"z": 0.3}, {"z": 4.0}, 600.0)])
    >>> round(day["a8_m_s2"], 3), day["a8_axis"], day["verdict"]
    (0.474, 'z', 'below action value')
    """
    tasks = list(tasks)
    if not tasks:
        raise ValueError("tasks must hold at least one task")
    day_hours = sum(float(t.hours) for t in tasks)
    if day_hours > MAX_HOURS_PER_DAY + HOURS_TOLERANCE_H:
        raise ValueError(f"tasks add up to {day_hours:g} h, more than a day ({MAX_HOURS_PER_DAY:g} h)")
    day_hours = min(day_hours, MAX_HOURS_PER_DAY)
    axes = [ax for ax in ("x", "y", "z") if any(ax in t.a_w_m_s2 for t in tasks)]
    k = iso2631.AXIS_FACTOR
    rows = []
    for t in tasks:
        partial = {ax: k[ax] * t.a_w_m_s2[ax] * math.sqrt(t.hours / 8.0) for ax in axes if ax in t.a_w_m_s2}
        top = max((k[ax] * t.a_w_m_s2[ax] for ax in partial), default=0.0)
        rows.append({"name": t.name, "hours": float(t.hours), "measured_s": float(t.measured_s),
                     "a_w_m_s2": {ax: float(t.a_w_m_s2[ax]) for ax in partial},
                     "partial_a8_m_s2": partial,
                     "hours_to_eav": hours_to(iso2631.EU_ACTION_A8_M_S2, top, 8.0),
                     "hours_to_elv": hours_to(iso2631.EU_LIMIT_A8_M_S2, top, 8.0), **t.extra})
    a8_axes = {ax: math.sqrt(sum(r["partial_a8_m_s2"].get(ax, 0.0) ** 2 for r in rows)) for ax in axes}
    a8_axis = governing_axis(a8_axes)
    a8 = a8_axes[a8_axis] if a8_axis else math.nan
    vdv_axes = {ax: k[ax] * sum(t.vdv_m_s1_75[ax] ** 4 * t.hours * 3600.0 / t.measured_s
                                for t in tasks if ax in t.vdv_m_s1_75) ** 0.25 for ax in axes}
    vdv_axis = max(vdv_axes, key=lambda ax: vdv_axes[ax]) if vdv_axes else None
    vdv = vdv_axes[vdv_axis] if vdv_axis else math.nan
    with_dz = [t for t in tasks if math.isfinite(t.dz_m_s2)]
    dzd = iso2631_5.daily_dose([t.dz_m_s2 for t in with_dz], [t.hours * 3600.0 for t in with_dz],
                               [t.measured_s for t in with_dz]) if with_dz else math.nan
    short = [t for t in tasks if t.measured_s < MIN_RECORD_S]
    withheld = None
    if short:
        withheld = "no verdict: " + "; ".join(
            f"task {t.name}: record {t.measured_s:.3g} s" for t in short) + f", shorter than {MIN_RECORD_S:g} s"
    elif not math.isfinite(a8) or not math.isfinite(vdv):
        withheld = "no verdict: the day's A(8) or VDV is not a finite number"
    if withheld:
        for r in rows:
            r["hours_to_eav"] = r["hours_to_elv"] = math.nan
    return {
        "tasks": rows,
        "hours_per_day": day_hours,
        "a8_axes_m_s2": a8_axes,
        "a8_m_s2": a8,
        "a8_axis": a8_axis,
        "vdv_daily_axes_m_s1_75": vdv_axes,
        "vdv_daily_m_s1_75": vdv,
        "vdv_daily_axis": vdv_axis,
        "hours_to_eav": math.nan if withheld else hours_to(iso2631.EU_ACTION_A8_M_S2, a8, day_hours),
        "hours_to_elv": math.nan if withheld else hours_to(iso2631.EU_LIMIT_A8_M_S2, a8, day_hours),
        "exposure_points": 400.0 * a8**2,
        "verdict": withheld or verdict(a8),
        "vdv_verdict": withheld or (EXPOSURE_VERDICTS[2] if vdv > iso2631.EU_LIMIT_VDV else
                                    EXPOSURE_VERDICTS[1] if vdv > iso2631.EU_ACTION_VDV else EXPOSURE_VERDICTS[0]),
        "dzd_m_s2": dzd,
    }
