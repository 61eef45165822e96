"""A tyre's lateral and longitudinal coefficients for the vehicle model (issue 34).

Where they come from, in order: the build's regressions of the tyre's lateral or longitudinal
runs (``<direction>_stiffness_pressure_by_speed`` and ``<direction>_damping_pressure_by_speed``:
``K = K_c + ΔK_p P`` and ``C = C_c + ΔC P`` per speed; ``series_damping_speed``: the series damper
``c₂ = a / v`` of a rolling tyre, thesis §2.5), else the tyre catalogue's columns for a tyre
measured elsewhere (``tyres.csv``: ``lateral_stiffness_kN_per_m``, ``lateral_damping_kN_s_per_m``,
``lateral_series_damping_kN_s_per_m_km_h`` and the same for ``longitudinal_``). Speeds between the
measured ones are interpolated, outside them held (as the vertical per-speed lines are,
:mod:`tyrelab.tyre.speed_dependence`); a stationary tyre (0 km/h) has no series damper.

Pure: the caller reads the tables (the warehouse, the catalogue) and passes them in.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import _validate
from .rolling import series_damping_N_s_per_m

__all__ = ["DIRECTIONS", "CATALOGUE_COLUMNS", "DirectionalTyre", "directional_tyre"]

#: Directions with coefficients of their own.
DIRECTIONS = ("lateral", "longitudinal")
#: Catalogue (``tyres.csv``) columns of a tyre measured elsewhere, per direction.
CATALOGUE_COLUMNS = tuple(f"{d}_{q}" for d in DIRECTIONS for q in (
    "stiffness_kN_per_m", "damping_kN_s_per_m", "series_damping_kN_s_per_m_km_h"))


@dataclass(frozen=True)
class DirectionalTyre:
    """One tyre's coefficients in one direction at one pressure and speed (SI).

    ``series_damping_N_s_per_m`` is ``inf`` where there is no series damper (a stationary tyre,
    or none measured): the Kelvin–Voigt unit alone; else the unit in series with it (``maxwell``).
    """

    direction: str
    stiffness_N_per_m: float
    damping_N_s_per_m: float
    series_damping_N_s_per_m: float
    source: str

    @property
    def model(self) -> str:
        """``"kelvin_voigt"`` or ``"maxwell"`` (the vehicle model's element kinds)."""
        return "maxwell" if math.isfinite(self.series_damping_N_s_per_m) else "kelvin_voigt"


def _line_at(table: pd.DataFrame | None, tyre_id: str, pressure_bar: float, speed_km_h: float) -> float | None:
    """``intercept + slope P`` of the tyre's per-speed lines at ``speed_km_h`` (interpolated between
    the fitted speeds, held outside), or None."""
    if table is None or table.empty or not {"tyre_id", "speed_km_h", "intercept", "slope"} <= set(table.columns):
        return None
    t = table.loc[(table["tyre_id"].astype(str) == str(tyre_id)) & table["intercept"].notna() & table["slope"].notna()]
    if t.empty:
        return None
    t = t.sort_values("speed_km_h")
    values = (t["intercept"] + t["slope"] * pressure_bar).to_numpy(float)
    return float(np.interp(speed_km_h, t["speed_km_h"].to_numpy(float), values))


def directional_tyre(tyre_id: str, direction: str, pressure_bar: float, speed_km_h: float, *,
                     stiffness_lines: pd.DataFrame | None = None, damping_lines: pd.DataFrame | None = None,
                     series_damping: pd.DataFrame | None = None, catalogue_row=None) -> DirectionalTyre | None:
    """The tyre's coefficients in ``direction`` (module docstring), or None where neither the build nor
    the catalogue has them.

    Parameters
    ----------
    tyre_id : str
    direction : {"lateral", "longitudinal"}
    pressure_bar, speed_km_h : float
    stiffness_lines, damping_lines : DataFrame, optional
        The build's ``<direction>_stiffness_pressure_by_speed`` and ``<direction>_damping_pressure_by_speed``.
    series_damping : DataFrame, optional
        The build's ``series_damping_speed``.
    catalogue_row : mapping, optional
        The tyre's ``tyres`` row (columns :data:`CATALOGUE_COLUMNS`).

    Examples
    --------
    >>> t = directional_tyre("X1", "lateral", 1.2, 5.0, catalogue_row={
    ...     "lateral_stiffness_kN_per_m": 250.0, "lateral_damping_kN_s_per_m": 1.5,
    ...     "lateral_series_damping_kN_s_per_m_km_h": 100.0})
    >>> t.stiffness_N_per_m, t.series_damping_N_s_per_m, t.model
    (250000.0, 20000.0, 'maxwell')
    """
    _validate.choice("direction", direction, DIRECTIONS)
    pressure_bar = _validate.non_negative("pressure_bar", pressure_bar)
    speed_km_h = _validate.non_negative("speed_km_h", speed_km_h)
    k = _line_at(stiffness_lines, tyre_id, pressure_bar, speed_km_h)
    c = _line_at(damping_lines, tyre_id, pressure_bar, speed_km_h)
    a = None
    if series_damping is not None and not series_damping.empty:
        s = series_damping.loc[(series_damping["direction"] == direction)
                               & (series_damping["tyre_id"].astype(str) == str(tyre_id))]
        if len(s) and np.isfinite(s["coefficient_kN_s_per_m_times_km_h"].iloc[0]):
            a = float(s["coefficient_kN_s_per_m_times_km_h"].iloc[0])
    source = f"the build's {direction} runs of {tyre_id}"
    if k is None or c is None:
        get = (catalogue_row.get if hasattr(catalogue_row, "get") else (lambda key, d=None: d)) \
            if catalogue_row is not None else (lambda key, d=None: d)
        kk, cc = get(f"{direction}_stiffness_kN_per_m"), get(f"{direction}_damping_kN_s_per_m")
        if kk is None or cc is None or not (pd.notna(kk) and pd.notna(cc)):
            return None
        k, c = float(kk), float(cc)
        aa = get(f"{direction}_series_damping_kN_s_per_m_km_h")
        a = float(aa) if aa is not None and pd.notna(aa) else None
        source = f"the tyre catalogue's {direction} coefficients of {tyre_id}"
    series = series_damping_N_s_per_m(a, speed_km_h) if a is not None and a > 0 else math.inf
    return DirectionalTyre(direction, k * 1e3, c * 1e3, series, source)
