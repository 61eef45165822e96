"""A tyre's lateral and longitudinal coefficients for the vehicle model (issue 34).

Where they come from, in order: the build's regressions of the tyre's lateral or longitudinal
runs (``<direction>_stiffness_pressure_by_speed`` and ``<direction>_damping_pressure_by_speed``:
``K = K_c + ΔK_p P`` and ``C = C_c + ΔC P`` per speed; ``series_damping_speed``: the series damper
``c₂ = a / v`` of a rolling tyre, thesis §2.5), else the tyre catalogue's columns for a tyre
measured elsewhere (``tyres.csv``: ``lateral_stiffness_kN_per_m``, ``lateral_damping_kN_s_per_m``,
``lateral_series_damping_kN_s_per_m_km_h`` and the same for ``longitudinal_``). Speeds between the
measured ones are interpolated, outside them held (as the vertical per-speed lines are,
:mod:`tyrelab.tyre.speed_dependence`); a stationary tyre (0 km/h) has no series damper.

For the ride (issue 42) :func:`rolling_coefficients` gives every coefficient of the rolling
element (``K``, ``C`` of the Kelvin–Voigt unit and ``a`` of its series damper ``c₂ = a / v``) per
speed, each on its own from the first of: the scenario, the build's runs of the tyre
(``measured``), the tyre catalogue, the documented stand-in (:data:`STAND_INS`), with the source
of each (:data:`SOURCE_KINDS`) and the stand-ins' 95 % intervals.

Pure: the caller reads the tables (the warehouse, the catalogue) and passes them in.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import _validate
from . import lateral as _lateral
from . import rolling as _rolling
from .rolling import series_damping_N_s_per_m

__all__ = ["DIRECTIONS", "CATALOGUE_COLUMNS", "COEFFICIENTS", "SOURCE_KINDS", "LONGITUDINAL_STAND_IN",
           "DirectionalTyre", "directional_tyre", "RollingCoefficients", "rolling_coefficients"]

#: Directions with coefficients of their own.
DIRECTIONS = ("lateral", "longitudinal")
#: Catalogue (``tyres.csv``) columns of a tyre measured elsewhere, per direction.
CATALOGUE_COLUMNS = tuple(f"{d}_{q}" for d in DIRECTIONS for q in (
    "stiffness_kN_per_m", "damping_kN_s_per_m", "series_damping_kN_s_per_m_km_h"))
#: The rolling element's coefficients, by their key names (``[tyres.*] <direction>_<name>``).
COEFFICIENTS = ("stiffness_kN_per_m", "damping_kN_s_per_m", "series_damping_kN_s_per_m_km_h")
#: Where a coefficient may come from, first wins.
SOURCE_KINDS = ("scenario", "measured", "catalogue", "stand-in")
#: The longitudinal stand-ins per tyre where nothing else gives them: the thesis' fore-aft tyre
#: element of the pitch-plane study (§7.3, §7.5, Table XVIII: 455 kN/m, 0-5 kN s/m; the
#: scenario's ``tractor.longitudinal_*`` defaults), 95 % interval x/÷ 2 (no thesis spread).
LONGITUDINAL_STAND_IN = {"stiffness_kN_per_m": 455.0, "damping_kN_s_per_m": 3.0}


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

    See Also
    --------
    rolling_coefficients : the coefficients at several speeds.
    tyrelab.tyre.rolling.estimate_series_damping : the stand-in ``a``.

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


@dataclass(frozen=True)
class RollingCoefficients:
    """One tyre's rolling element in one direction, per speed (:func:`rolling_coefficients`).

    Attributes
    ----------
    direction : str
    speeds_km_h : ndarray
    stiffness_kN_per_m, damping_kN_s_per_m : ndarray
        The Kelvin–Voigt unit per speed.
    series_damping_kN_s_per_m_km_h : float
        ``a`` of the series damper ``c₂ = a / v``.
    sources : dict
        Coefficient (:data:`COEFFICIENTS`) -> its kind (:data:`SOURCE_KINDS`).
    source_text : dict
        Coefficient -> one line saying where it came from (for the tyres table and ``ride.json``).
    ci95 : dict
        Coefficient -> ``(low, high)`` (arrays per speed, or floats for ``a``) where it is a stand-in.
    """

    direction: str
    speeds_km_h: np.ndarray
    stiffness_kN_per_m: np.ndarray
    damping_kN_s_per_m: np.ndarray
    series_damping_kN_s_per_m_km_h: float
    sources: dict
    source_text: dict
    ci95: dict

    def series_damping_N_s_per_m(self) -> np.ndarray:
        """``c₂ = a / v`` per speed, N s/m (``inf`` at 0 km/h: the series damper locked)."""
        return np.array([series_damping_N_s_per_m(self.series_damping_kN_s_per_m_km_h, float(v))
                         for v in self.speeds_km_h])


def _number(name: str, value, blank_nan: bool) -> float | None:
    """``value`` as a float, None where blank (None; NaN too where ``blank_nan``: a catalogue's empty
    cell); ValueError naming ``name`` for anything else that is not a finite number."""
    if value is None or (blank_nan and isinstance(value, (float, np.floating)) and math.isnan(value)):
        return None
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    return float(_validate.finite_array(name, [value])[0])


def _lines_at(table, tyre_id, pressure_bar: float, speeds: np.ndarray) -> np.ndarray | None:
    if tyre_id is None:
        return None
    out = [_line_at(table, tyre_id, pressure_bar, float(v)) for v in speeds]
    return None if out and out[0] is None else np.array(out, float)


def rolling_coefficients(direction: str, pressure_bar: float, speeds_km_h, *, tyre_id: str | None = None,
                         vertical_stiffness_kN_per_m=None, vertical_damping_kN_s_per_m=None,
                         given: dict | None = None, stiffness_lines: pd.DataFrame | None = None,
                         damping_lines: pd.DataFrame | None = None, series_damping: pd.DataFrame | None = None,
                         catalogue_row=None) -> RollingCoefficients:
    """``K``, ``C`` and ``a`` of a tyre's rolling element in ``direction`` at each speed (module docstring).

    Each coefficient on its own, first of: ``given`` (the scenario's ``<direction>_<coefficient>``,
    None or NaN where blank), the build's runs of ``tyre_id`` (the per-speed pressure lines,
    interpolated in speed and held outside; ``a`` from ``series_damping_speed``), the catalogue row,
    the stand-in: laterally ``K = 0.57 k_z`` (:mod:`tyrelab.tyre.lateral`), ``C`` the tyre's vertical
    damping and ``a`` of :mod:`tyrelab.tyre.rolling`; longitudinally :data:`LONGITUDINAL_STAND_IN` and
    ``a`` of :mod:`tyrelab.tyre.rolling`. A measured ``K`` or ``C`` comes with its partner: a build
    with only one of the two lines is not used for either.

    Parameters
    ----------
    direction : {"lateral", "longitudinal"}
    pressure_bar : float
        Inflation pressure, bar.
    speeds_km_h : sequence of float
        Speeds, km/h (>= 0).
    tyre_id : str, optional
        The measured tyre (``measured_tyre_id``), or None.
    vertical_stiffness_kN_per_m, vertical_damping_kN_s_per_m : float or sequence, optional
        The tyre's vertical ``K`` and ``C`` per speed: the lateral stand-ins rest on them (needed
        only where a lateral ``K`` or ``C`` falls to its stand-in).
    given : dict, optional
        Coefficient name (:data:`COEFFICIENTS`) -> the scenario's value (None: not given; NaN or
        a non-number is refused).
    stiffness_lines, damping_lines, series_damping : DataFrame, optional
        The build's ``<direction>_stiffness_pressure_by_speed``, ``<direction>_damping_pressure_by_speed``
        and ``series_damping_speed``.
    catalogue_row : mapping, optional
        The tyre's ``tyres`` row (:data:`CATALOGUE_COLUMNS`).

    Returns
    -------
    RollingCoefficients

    See Also
    --------
    directional_tyre : one pressure and speed.
    tyrelab.tyre.speed_dependence.at_speeds : per-speed values at other speeds.

    Examples
    --------
    >>> r = rolling_coefficients("lateral", 1.2, [0.0, 8.0], vertical_stiffness_kN_per_m=400.0,
    ...                          vertical_damping_kN_s_per_m=1.5, given={"damping_kN_s_per_m": 2.0})
    >>> r.sources
    {'stiffness_kN_per_m': 'stand-in', 'damping_kN_s_per_m': 'scenario', 'series_damping_kN_s_per_m_km_h': 'stand-in'}
    >>> r.stiffness_kN_per_m.round(1).tolist(), r.series_damping_N_s_per_m().tolist()
    ([226.3, 226.3], [inf, 12500.0])
    """
    _validate.choice("direction", direction, DIRECTIONS)
    pressure_bar = _validate.non_negative("pressure_bar", pressure_bar)
    speeds = _validate.non_negative_array("speeds_km_h", np.atleast_1d(np.asarray(speeds_km_h, float)))
    given = dict(given or {})
    unknown = set(given) - set(COEFFICIENTS)
    if unknown:
        raise ValueError(f"given: unknown coefficients {sorted(unknown)}; expected {COEFFICIENTS}")
    catalogue = catalogue_row if hasattr(catalogue_row, "get") else {}

    def per_speed(value) -> np.ndarray:
        return np.broadcast_to(np.asarray(value, float), speeds.shape).astype(float)

    values: dict = {}
    kinds: dict = {}
    texts: dict = {}
    ci: dict = {}
    # the build: K and C as a pair (module docstring), a on its own
    k_m = _lines_at(stiffness_lines, tyre_id, pressure_bar, speeds)
    c_m = _lines_at(damping_lines, tyre_id, pressure_bar, speeds)
    measured = {}
    if k_m is not None and c_m is not None:
        measured["stiffness_kN_per_m"], measured["damping_kN_s_per_m"] = k_m, np.maximum(c_m, 0.0)
    if tyre_id is not None and series_damping is not None and not series_damping.empty:
        s = series_damping.loc[(series_damping["direction"] == direction)
                               & (series_damping["tyre_id"].astype(str) == str(tyre_id))]
        a_m = _number("series_damping_speed.coefficient_kN_s_per_m_times_km_h",
                      s["coefficient_kN_s_per_m_times_km_h"].iloc[0], True) if len(s) else None
        if a_m is not None and a_m > 0:
            measured["series_damping_kN_s_per_m_km_h"] = a_m
    tables = {"stiffness_kN_per_m": f"{direction}_stiffness_pressure_by_speed",
              "damping_kN_s_per_m": f"{direction}_damping_pressure_by_speed",
              "series_damping_kN_s_per_m_km_h": "series_damping_speed"}
    for name in COEFFICIENTS:
        scalar = name == "series_damping_kN_s_per_m_km_h"
        g = _number(f"given[{name!r}] ({direction}_{name})", given.get(name), False)
        cat = _number(f"tyres.{direction}_{name}", catalogue.get(f"{direction}_{name}"), True)
        if g is not None:
            values[name], kinds[name], texts[name] = g, "scenario", "override (scenario)"
        elif name in measured:
            values[name], kinds[name] = measured[name], "measured"
            texts[name] = f"measured tyre {tyre_id}: the build's {direction} runs ({tables[name]})"
        elif cat is not None:
            values[name], kinds[name] = cat, "catalogue"
            texts[name] = f"the tyre catalogue's {direction}_{name} of {tyre_id}"
        else:
            kinds[name] = "stand-in"
            if scalar:
                e = _rolling.estimate_series_damping(direction)
                values[name], texts[name] = e["series_damping_kN_s_per_m_km_h"], e["source"]
                ci[name] = tuple(e["ci95_kN_s_per_m_km_h"])
            elif direction == "lateral":
                vertical = vertical_stiffness_kN_per_m if name == "stiffness_kN_per_m" else vertical_damping_kN_s_per_m
                if vertical is None:
                    raise ValueError(f"vertical_{name}: needed for the lateral {name} stand-in (none given, measured "
                                     "or catalogued)")
                vz = per_speed(vertical)
                if name == "stiffness_kN_per_m":
                    est = [_lateral.estimate_lateral_stiffness(float(x)) for x in vz]
                    values[name], texts[name] = np.array([e["lateral_stiffness_kN_per_m"] for e in est]), est[0]["source"]
                    ci[name] = (np.array([e["ci95_kN_per_m"][0] for e in est]), np.array([e["ci95_kN_per_m"][1] for e in est]))
                else:
                    values[name] = np.maximum(vz, 0.0)
                    texts[name] = "stand-in: the tyre's vertical damping (no lateral damping measured; 95 % interval x/÷ 2)"
                    ci[name] = (values[name] / 2.0, values[name] * 2.0)
            else:
                v = LONGITUDINAL_STAND_IN[name]
                values[name] = v
                texts[name] = (f"stand-in {v:g} {'kN/m' if name == 'stiffness_kN_per_m' else 'kN s/m'} per tyre "
                               "(thesis §7.3, §7.5, Table XVIII; 95 % interval x/÷ 2)")
                ci[name] = (per_speed(v / 2.0), per_speed(v * 2.0))
        if not scalar:
            values[name] = per_speed(values[name])
    a = float(values["series_damping_kN_s_per_m_km_h"])
    if not a > 0:
        raise ValueError(f"{direction}_series_damping_kN_s_per_m_km_h must be finite and positive, got {a!r} "
                         f"({texts['series_damping_kN_s_per_m_km_h']})")
    if np.any(values["stiffness_kN_per_m"] <= 0):
        raise ValueError(f"{direction}_stiffness_kN_per_m must be positive, got "
                         f"{float(values['stiffness_kN_per_m'].min()):g} ({texts['stiffness_kN_per_m']})")
    return RollingCoefficients(direction, speeds, values["stiffness_kN_per_m"], np.maximum(values["damping_kN_s_per_m"], 0.0),
                               a, kinds, texts, ci)
