"""What the chapter 6 and 7 studies share (issue 45): their sampling, the survey and recorded
estimates' constants, the checks of their tables and the records' spectra."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..comfort import metrics as mt
from ..run.track import DT_S, FS_HZ  # noqa: F401  (the ride's step is the studies': one home, issue 45)

__all__ = ["T4_ROLLING_RADIUS_M", "FRONT_7_50_18_RADIUS_M", "SURVEY_ERROR_M", "RECORDED_NOISE_RMS_M", "RECORDED_SPIKE",
           "DT_S", "LEAD_IN_M", "FS_HZ"]


#: T4 13.6R38 rolling circumference 4.66 m (thesis §6.5.3) -> radius, m.
T4_ROLLING_RADIUS_M = 4.66 / (2 * math.pi)
#: Approximate 7.50-18 front tyre radius, m (0.8 m overall diameter).
FRONT_7_50_18_RADIUS_M = 0.40
#: Survey error of slat heights (uniform, ±), m (thesis §6.3 a: ±3 mm).
SURVEY_ERROR_M = 0.003
#: Recorded-estimate noise floor (rms), m (§6.5.1: about 1 mm).
RECORDED_NOISE_RMS_M = 0.001
#: Recorded-estimate spurious peak (§6.5.1): centre, half-width (cycles/m), power factor.
RECORDED_SPIKE = (1.35, 0.05, 13.0)
#: Road driven before a study's track starts, m.
LEAD_IN_M = 5.0


def _by_condition(table: pd.DataFrame, needed, name: str, what: str, problems: list[str]) -> pd.DataFrame:
    """``table`` indexed by ``load_condition``; appends to ``problems`` each condition of ``needed``
    without a row, or with more than one (``name`` and ``what`` word the message)."""
    indexed = table.set_index("load_condition")
    missing = [str(c) for c in dict.fromkeys(needed) if c not in indexed.index]
    repeated = sorted({str(c) for c in indexed.index[indexed.index.duplicated()]})
    if missing:
        problems.append(f"{name} has no {what} for load condition {', '.join(missing)}")
    if repeated:
        problems.append(f"{name} has more than one {what} for load condition {', '.join(repeated)}")
    return indexed


def _given_cases(cases: dict | None, n: int, positions: str, table: str) -> dict:
    """A copy of a study's ``cases`` argument, checked to be keyed by positions 0..n-1 of ``table``."""
    cases = dict(cases or {})
    if any(not isinstance(i, (int, np.integer)) or not 0 <= i < n for i in cases):
        raise ValueError(f"cases must be keyed by {positions} 0..{n - 1} of {table}, got {sorted(cases)!r}")
    return cases


def _refuse(problems: list[str]) -> None:
    """Raise every problem of the studies' tables at once (ValueError)."""
    if problems:
        raise ValueError("; ".join(problems))


def record_spectra(records: dict, fs_Hz: float, speed_km_h: float, f_max_Hz: float = 10.0) -> pd.DataFrame:
    """Acceleration PSDs (0.1 Hz bandwidth, §7.4) of the example records of Fig. 56.

    Parameters
    ----------
    records : dict
        ``(characteristics, profile estimate) -> acceleration record`` (m/s²).
    fs_Hz : float
        Sampling rate, Hz.
    speed_km_h : float
        Speed of the records (for the table), km/h.
    f_max_Hz : float
        Highest frequency kept, Hz.

    Returns
    -------
    DataFrame
        ``speed_km_h, series, frequency_Hz, psd_m2_s4_per_Hz``; the series
        ``reference (true)`` is the "measured" side.
    """
    rows = []
    for (name, estimate), a in sorted(records.items()):
        f, p = mt.acceleration_psd(a, fs_Hz)
        keep = f <= f_max_Hz
        rows.append(pd.DataFrame({"speed_km_h": speed_km_h, "series": f"{name} ({estimate})",
                                  "frequency_Hz": f[keep], "psd_m2_s4_per_Hz": p[keep]}))
    return pd.concat(rows, ignore_index=True) if rows else pd.DataFrame(
        columns=["speed_km_h", "series", "frequency_Hz", "psd_m2_s4_per_Hz"])


def _plain(row) -> dict:
    """A table row as a dict of Python scalars (a cache key's input)."""
    return {k: (v.item() if hasattr(v, "item") else v) for k, v in dict(row).items()}
