"""Where a tyre's numbers come from: stiffness, damping, radius and footprint per speed (issue 45).

:func:`resolve_tyres` takes each axle's tyre (``[tyres.front]``, ``[tyres.rear]``) to its numbers at
every scenario speed, by precedence: the scenario's override, a measured tyre of a build (the
``tyre_data`` reader a caller hands in: :class:`ShippedTyres` without a build), the fitted stiffness
formula (§4.5.3, §8.2) and the damping model fitted to the thesis' Table VII lines
(:mod:`tyrelab.tyre.damping_fit`). The footprint the enveloping filters use is the contact length
(:func:`tyrelab.vehicle.enveloping.contact_length`) at the tyre's static deflection under the static
load the assembled vehicle carries on it (:meth:`tyrelab.vehicle.model.Assembly.static_tyre_loads_N`:
the tractor with its implement, ballast and cab), one per speed. :func:`build_parts` turns the
numbers at a speed into the model's parts (SI).

SI inside; the looked-up numbers keep the scenario's kN/m and kN s/m (their key names).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass

import numpy as np

from .. import _validate
from .. import published
from ..tyre.directional import rolling_coefficients
from ..tyre.rolling import series_damping_N_s_per_m
from ..tyre.sizes import parse_tyre_size, rolling_circumference_m
from ..tyre.speed_dependence import at_speeds
from ..tyre.stiffness import estimate_stiffness
from . import enveloping as ev
from .model import Assembly, Parts, assemble
from .scenario import Scenario
from .units import from_kilo

__all__ = ["AxleTyres", "ShippedTyres", "FitTyres", "MEASURED_TABLES", "BUILD_FORMULA_TABLES", "DIRECTIONAL_TABLES", "FIT_TABLES",
           "scenario_fits", "per_speed", "resolve_tyres", "static_tyre_loads", "build_parts"]


@dataclass(frozen=True)
class AxleTyres:
    """Resolved characteristics of one tyre of an axle, per scenario speed.

    Attributes
    ----------
    size : str
    pressure_bar : float
    stiffness_kN_per_m, damping_kN_s_per_m : ndarray
        Per tyre, one value per speed.
    stiffness_source, damping_source : str
        Where the numbers came from (override, measured tyre, formula, thesis table).
    radius_m : float
        Rolling radius used by the rigid tread band, m.
    footprint_m : ndarray
        Contact length used by the enveloping filter, one per speed, m.
    warnings : list of str
        The formula's out-of-range warnings and similar notes.
    stiffness_u_kN_per_m : float
        Standard uncertainty of the per-tyre stiffness, kN/m: the formula's (its
        prediction interval on the thesis' data, issue 14); 0 for an override or a
        measured tyre (not propagated).
    """

    size: str
    pressure_bar: float
    stiffness_kN_per_m: np.ndarray
    damping_kN_s_per_m: np.ndarray
    stiffness_source: str
    damping_source: str
    radius_m: float
    footprint_m: np.ndarray
    warnings: tuple[str, ...] = ()
    stiffness_u_kN_per_m: float = 0.0
    #: Lateral element of one tyre per speed (3-D with lateral_model; issue 33), kN/m and kN s/m,
    #: where they came from, and the stiffness' 95 % interval per speed when it is the stand-in.
    lateral_stiffness_kN_per_m: np.ndarray | None = None
    lateral_damping_kN_s_per_m: np.ndarray | None = None
    lateral_source: str = ""
    lateral_ci95_kN_per_m: tuple | None = None
    #: The rolling element (issue 42): ``a`` of the series damper ``c₂ = a / v`` (kN s/m × km/h), its
    #: 95 % interval where it is the stand-in, and per coefficient where it came from
    #: (``{"stiffness_kN_per_m": "measured", ...}``: :data:`tyrelab.tyre.directional.SOURCE_KINDS`).
    lateral_series_damping_kN_s_per_m_km_h: float | None = None
    lateral_series_ci95_kN_s_per_m_km_h: tuple | None = None
    lateral_sources: dict = dataclasses.field(default_factory=dict)
    #: The rear tyres' longitudinal rolling element's ``a`` and its source (``longitudinal_model = "rolling"``).
    longitudinal_series_damping_kN_s_per_m_km_h: float | None = None
    longitudinal_series_source: str = ""


def per_speed(values, list_speeds_km_h, speeds_km_h) -> np.ndarray:
    """A scenario value at each speed: a scalar everywhere, or a per-speed list interpolated.

    Parameters
    ----------
    values : float or sequence
        One value, or one per entry of ``list_speeds_km_h``.
    list_speeds_km_h, speeds_km_h : sequence of float
        The speeds the list refers to, and the speeds wanted (linear
        interpolation, held constant outside).

    See Also
    --------
    resolve_tyres : where the scenario's per-speed values are read.

    Examples
    --------
    >>> per_speed([1.0, 2.0], [10, 20], [5, 15, 25]).tolist()
    [1.0, 1.5, 2.0]
    """
    v = np.atleast_1d(np.asarray(values, float))
    speeds = np.asarray(speeds_km_h, float)
    if v.size == 1:
        return np.full(speeds.shape, float(v[0]))
    ls = np.asarray(list_speeds_km_h, float)
    if ls.size != v.size:
        raise ValueError(f"values: {v.size} values for {ls.size} speeds")
    order = np.argsort(ls)
    return np.interp(speeds, ls[order], v[order])


class ShippedTyres:
    """Where :func:`resolve_tyres` finds tyre data without a build: the thesis' stiffness formula
    (published Tables II, III, VI); a measured tyre or ``formula = "build"`` is refused. A caller
    with a build hands in a :class:`FitTyres` of its fit tables (a stage: this run's Parquet; the
    command line and the library: :class:`tyrelab.tyredata.WarehouseTyres`): this package reads no
    warehouse."""

    def measured(self, table: str, tyre_id: str, pressure_bar: float) -> tuple[np.ndarray, np.ndarray]:
        """(speeds km/h, value at ``pressure_bar``) of a measured tyre's per-speed pressure fits."""
        raise ValueError(f"measured_tyre_id {tyre_id!r} needs --build (a warehouse with {table})")

    def stiffness_model(self, formula: str):
        """The :class:`~tyrelab.tyre.stiffness.StiffnessModel` of ``[tyres.*] formula``."""
        if formula == "build":
            raise ValueError('formula = "build" needs --build (a warehouse with table formula_fit)')
        return _thesis_stiffness_model()

    def damping_model(self, formula: str):
        """The :class:`~tyrelab.tyre.damping_fit.DampingFit` for an unmeasured tyre of ``[tyres.*] formula``:
        the Table VII model (``"thesis"``); ``"build"`` needs a warehouse."""
        if formula == "build":
            raise ValueError('formula = "build" needs --build (a warehouse with table damping_fit)')
        return _damping_fit()


@functools.lru_cache(maxsize=1)
def _thesis_stiffness_model():
    """The shipped thesis stiffness model (built once per process: a sweep asks for it per variant)."""
    return published.thesis_stiffness_model()


# --------------------------------------------------------------------------- a build's fits
#: Per-speed pressure fits of the measured tyres (``measured_tyre_id``).
MEASURED_TABLES = ("stiffness_pressure_by_speed", "damping_pressure_by_speed")
#: The build's stiffness formula and damping model (``formula = "build"``).
BUILD_FORMULA_TABLES = ("formula_fit", "damping_fit")
#: A measured tyre's lateral and longitudinal per-speed fits, series damper and catalogue row (issue 42).
DIRECTIONAL_TABLES = tuple(f"{d}_{q}" for d in ("lateral", "longitudinal")
                           for q in ("stiffness_pressure_by_speed", "damping_pressure_by_speed")) + (
    "series_damping_speed", "tyres")
#: Every table a scenario's tyres may read.
FIT_TABLES = MEASURED_TABLES + BUILD_FORMULA_TABLES + DIRECTIONAL_TABLES


def _measured_rows(table, tyre_id: str):
    """The fitted rows of ``tyre_id`` in a per-speed fit table, by speed (as the warehouse query)."""
    rows = table.loc[table["intercept"].notna() & table["slope"].notna() & table["speed_km_h"].notna(),
                     ["tyre_id", "speed_km_h", "intercept", "slope"]]
    rows = rows.loc[rows["tyre_id"].astype(str) == str(tyre_id)]
    return rows.sort_values("speed_km_h", kind="stable").reset_index(drop=True)


def _ours(table):
    """The ``ours`` rows of ``formula_fit``/``damping_fit`` (the build's own fit)."""
    return table.loc[table["source"].astype(str) == "ours"].reset_index(drop=True)


class FitTyres(ShippedTyres):
    """Tyre data of :func:`resolve_tyres` from a build's fit tables handed in (a stage's Parquet, a
    warehouse read by :class:`tyrelab.tyredata.WarehouseTyres`): this package reads no file.

    Parameters
    ----------
    tables : dict
        Table name (:data:`FIT_TABLES`) -> DataFrame, or None where the build has no such table.
        Only the rows the scenario reads are needed (:func:`scenario_fits`).
    source : str
        Where the tables came from, for the error messages (``build/parquet``).
    """

    def __init__(self, tables: dict, source: str):
        self.tables = dict(tables)
        self.source = str(source)

    def _table(self, name: str, why: str):
        table = self.tables.get(name)
        if table is None:
            raise ValueError(f"{why}: no table {name} in {self.source}")
        return table

    def measured(self, table: str, tyre_id: str, pressure_bar: float):
        """(speeds km/h, value at ``pressure_bar``) of a measured tyre's per-speed pressure fits (``table``)."""
        why = f"measured_tyre_id {tyre_id!r}"
        try:
            rows = _measured_rows(self._table(table, why), tyre_id)
        except KeyError as exc:
            raise ValueError(f"{why}: {table} of {self.source} lacks column {exc}") from None
        if rows.empty:
            raise ValueError(f"{why}: no fitted rows in {table} of {self.source}")
        return rows["speed_km_h"].to_numpy(float), (rows["intercept"] + rows["slope"] * pressure_bar).to_numpy(float)

    def directional(self, tyre_id: str, direction: str) -> dict:
        """The tables of ``tyre_id`` in ``direction`` as :func:`tyrelab.tyre.directional.rolling_coefficients`
        takes them (``stiffness_lines``, ``damping_lines``, ``series_damping``, ``catalogue_row``); a table the
        build lacks (one from before issue 34) is left out: those coefficients fall to the catalogue or the
        stand-in, whose source the ride names."""
        out = {}
        for key, name in (("stiffness_lines", f"{direction}_stiffness_pressure_by_speed"),
                          ("damping_lines", f"{direction}_damping_pressure_by_speed"),
                          ("series_damping", "series_damping_speed"), ("catalogue_row", "tyres")):
            try:
                table = self._table(name, f"measured_tyre_id {tyre_id!r}")
            except ValueError:
                continue
            if key == "catalogue_row":
                rows = table.loc[table["tyre_id"].astype(str) == str(tyre_id)] if "tyre_id" in table else table.iloc[:0]
                if len(rows):
                    out[key] = rows.iloc[0].to_dict()
            elif key == "series_damping" or {"tyre_id", "speed_km_h", "intercept", "slope"} <= set(table.columns):
                out[key] = table
        return out

    def stiffness_model(self, formula: str):
        """The thesis' stiffness formula, or the build's fit (table ``formula_fit``) for ``"build"``."""
        from ..tyre.models import build_stiffness_model

        thesis = _thesis_stiffness_model()
        if formula != "build":
            return thesis
        return self._build_fit("formula_fit", lambda table: build_stiffness_model(table, thesis))

    def damping_model(self, formula: str):
        """The Table VII damping model, or the build's own fit (table ``damping_fit``, source
        ``ours``) for ``"build"``: an unmeasured tyre's damping follows the same choice as its stiffness."""
        from ..tyre.damping_fit import DampingFit

        if formula != "build":
            return super().damping_model(formula)

        def ours(table):
            rows = _ours(table)
            if rows.empty:
                raise ValueError("damping_fit has no 'ours' row (fewer than 5 measured traction tyres?)")
            return DampingFit.from_row(rows.iloc[0].to_dict())

        return self._build_fit("damping_fit", ours)

    def _build_fit(self, name: str, make):
        """``make(table)`` of table ``name`` (a fit of ``formula = "build"``); a missing table, or one
        ``make`` refuses, is one line naming where it was read."""
        table = self._table(name, 'formula = "build"')
        try:
            return make(table)
        except (ValueError, KeyError) as exc:
            raise ValueError(f'formula = "build": {name} of {self.source}: {exc}') from None


def scenario_fits(scenario, tables: dict) -> dict:
    """The rows of the fit ``tables`` (name -> DataFrame or None) that ``scenario`` reads.

    Per axle: its measured tyre's rows of :data:`MEASURED_TABLES` (``measured_tyre_id``), the
    ``ours`` rows of :data:`BUILD_FORMULA_TABLES` (``formula = "build"``). A table the build
    lacks stays None (the scenario then fails naming it). Returns name -> DataFrame or None,
    only the tables read: the item key of the scenario and what :class:`FitTyres` is given.

    See Also
    --------
    FitTyres : the tyre data these rows make.

    Examples
    --------
    >>> import pandas as pd
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> sc = load_scenario(scenarios_dir() / "modern_tractor.toml")  # formula tyres: no fit read
    >>> scenario_fits(sc, {"formula_fit": pd.DataFrame({"source": ["ours"]})})
    {}
    """
    _validate.instance("scenario", scenario, Scenario)
    out: dict = {}
    for spec in (scenario.front, scenario.rear):
        tyre_id = getattr(spec, "measured_tyre_id", None)
        if tyre_id:
            for name in DIRECTIONAL_TABLES:  # issue 42: the rolling element's fits and catalogue row
                t = tables.get(name)
                if t is None:
                    continue
                part = _safe(lambda: t.loc[t["tyre_id"].astype(str) == str(tyre_id)].reset_index(drop=True), t)
                out[name] = part if out.get(name) is None else _concat(out[name], part)
            for name in MEASURED_TABLES:
                t = tables.get(name)
                part = None if t is None else _safe(lambda: _measured_rows(t, tyre_id), t)
                out[name] = part if name not in out or out[name] is None or part is None else \
                    _concat(out[name], part)
        if getattr(spec, "formula", "thesis") == "build":
            for name in BUILD_FORMULA_TABLES:
                t = tables.get(name)
                out[name] = None if t is None else _safe(lambda: _ours(t), t)
    return out


def _safe(pick, table):
    """``pick()``, or the whole ``table`` when it lacks the columns to pick by (the ride then names them)."""
    try:
        return pick()
    except KeyError:
        return table


def _concat(a, b):
    import pandas as pd

    return pd.concat([a, b], ignore_index=True).drop_duplicates(ignore_index=True)



def _formula_stiffness(spec, tyre_data=None) -> tuple[float, str, list[str], float]:
    """Per-tyre formula stiffness (kN/m), its rule, the formula's range warnings and its standard uncertainty."""
    model = (tyre_data or ShippedTyres()).stiffness_model(getattr(spec, "formula", "thesis"))
    est = estimate_stiffness(spec.size, spec.pressure_bar, spec.age_years, undriven_front=not spec.traction,
                             water_ballast=spec.water_ballast, model=model)
    rule = f"formula {est.rule}" + (" x1.25 water ballast" if spec.water_ballast else "")
    return est.stiffness_kN_per_m, rule, list(est.warnings), est.stiffness_u_kN_per_m or 0.0


def _model_damping(spec, speeds_km_h, tyre_data: ShippedTyres) -> tuple[np.ndarray, str, list[str]]:
    """Damping of an unmeasured tyre per speed from the damping model of ``[tyres.*] formula``
    (:mod:`tyrelab.tyre.damping_fit`: the Table VII lines', or the build's own for ``"build"``),
    its source text and warnings (the interval at the first speed, where the model extrapolates)."""
    fit = tyre_data.damping_model(getattr(spec, "formula", "thesis"))
    published_model = fit.source == "published"
    which = "Table VII model" if published_model else "build's damping model (its measured tyres)"
    preds = [fit.predict(spec.pressure_bar, float(v), spec.age_years, size=parse_tyre_size(spec.size).designation)
             for v in np.asarray(speeds_km_h, float)]
    c = np.array([p.damping_kN_s_per_m for p in preds])
    b = fit.coefficients
    src = (f"{which} C = {b[0]:.3g} {b[1]:+.3g} A {b[2]:+.3g} v {b[3]:+.3g} P (kN s/m; {fit.n_tyres} "
           f"traction tyres, cluster-robust by tyre)")
    lo, hi = preds[0].interval_kN_s_per_m
    warnings = [f"damping not given: the {'Table VII damping model' if published_model else which} gives "
                f"{c[0]:.2f} kN s/m at "
                f"{float(np.asarray(speeds_km_h, float)[0]):g} km/h (95 % prediction interval {max(lo, 0.0):.2f} to "
                f"{hi:.2f}; a rough stand-in, typical 0.8-3 kN s/m, §5.6)"]
    v = np.asarray(speeds_km_h, float)
    held = [(float(a), p.speed_used_km_h) for a, p in zip(v, preds) if p.speed_used_km_h != float(a)]
    if held:
        lo_v, hi_v = fit.ranges["speed_km_h"]
        warnings.append(f"speeds {', '.join(f'{a:g}' for a, _ in held)} km/h are outside the damping model's "
                        f"{lo_v:g}-{hi_v:g} km/h: evaluated at the nearest of those")
    warnings += sorted({w for p in preds for w in p.warnings if not w.startswith("speed ")})
    return c, src, warnings


@functools.lru_cache(maxsize=1)
def _damping_fit():
    """The Table VII damping model fitted to the shipped tables (once per process: a sweep asks per variant)."""
    from ..tyre import damping_fit

    return damping_fit.fit_damping(damping_fit.damping_points(published.read_published("table_vii"),
                                                             published.read_published("table_ii")))


def resolve_tyres(scenario: Scenario, tyre_data=None, memo: dict | None = None) -> dict[str, AxleTyres]:
    """Stiffness, damping, radius and footprint of the front and rear tyres per speed.

    Order of precedence per quantity: the scenario's override, the measured tyre
    (``measured_tyre_id``, from ``tyre_data.measured``; speeds interpolated, held
    outside the measured range; a rolling tyre takes the rolling values only,
    :func:`~tyrelab.tyre.speed_dependence.at_speeds`), the fitted formula (stiffness,
    ``tyre_data.stiffness_model``: ``formula`` = thesis or build) or the Table VII damping
    model (damping, with its prediction interval in the warnings). ``tyre_data`` default
    :class:`ShippedTyres` (no warehouse). The footprint (``footprint_m`` given, else the contact
    length at the static deflection) takes each tyre's static load from the assembled vehicle
    (:func:`static_tyre_loads`: implement, ballast and cab included). ``memo``: a dict that keeps
    each axle's numbers by its tyre, speeds and ``tyre_data`` (:class:`tyrelab.vehicle.ride.RideCache`:
    the variants of a sweep share most axles).

    Raises
    ------
    ValueError
        When a measured tyre cannot be found.

    See Also
    --------
    build_parts : the parts at one speed from these numbers.
    tyrelab.tyre.directional.rolling_coefficients : a rolling tyre's lateral and longitudinal numbers.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.vehicle import parse_scenario
    >>> sc = parse_scenario((scenarios_dir() / "mf698t.toml").read_text())
    >>> tyres = resolve_tyres(sc)
    >>> sorted(tyres), float(tyres["rear"].stiffness_kN_per_m[0])
    (['front', 'rear'], 364.0)
    """
    return _resolve(scenario, tyre_data, memo)[0]


def _resolve(scenario: Scenario, tyre_data=None, memo: dict | None = None) -> tuple[dict[str, AxleTyres], list]:
    """:func:`resolve_tyres`, and the assembly of each speed that gave the static loads (the ride
    runs that assembly: it is built once)."""
    _validate.instance("scenario", scenario, Scenario)
    source = id(tyre_data) if tyre_data is not None else None
    tyre_data = tyre_data or ShippedTyres()
    speeds = np.asarray(scenario.exposure.speeds_km_h, float)
    lists = scenario.exposure.list_speeds_km_h
    lateral_too = scenario.tractor.three_d and scenario.tractor.lateral_model != "none"
    t = scenario.tractor  # issue 42: the rear tyres' longitudinal rolling element
    rolling_lon = (t.longitudinal_stiffness_kN_per_m, t.longitudinal_damping_kN_s_per_m,
                   t.longitudinal_series_damping_kN_s_per_m_km_h) if t.longitudinal_model == "rolling" else None
    out = {}
    for axle, spec in (("front", scenario.front), ("rear", scenario.rear)):
        lon = rolling_lon if axle == "rear" else None
        key = (axle, spec, tuple(speeds), tuple(lists), lateral_too, lon, source)
        if memo is not None and key in memo:
            out[axle] = memo[key]
            continue
        out[axle] = _axle_tyres(axle, spec, speeds, lists, lateral_too, tyre_data, lon)
        if memo is not None:
            memo[key] = out[axle]
    if scenario.front.footprint_m is not None and scenario.rear.footprint_m is not None:
        return out, [None] * speeds.size
    # the footprints: the contact length at each tyre's static deflection under the whole vehicle
    asms = [assemble(build_parts(scenario, out, i)) for i in range(speeds.size)]
    loads = [static_tyre_loads(a) for a in asms]
    for axle, spec in (("front", scenario.front), ("rear", scenario.rear)):
        if spec.footprint_m is not None:
            continue
        ty = out[axle]
        fp = np.array([ev.contact_length(ty.radius_m, load[axle] / from_kilo(kk))
                       for load, kk in zip(loads, ty.stiffness_kN_per_m)])
        out[axle] = dataclasses.replace(ty, footprint_m=fp)
    return out, asms


def static_tyre_loads(asm) -> dict[str, float]:
    """Static load of one tyre of each axle (``front``, ``rear``), N, from an assembled vehicle
    (:meth:`tyrelab.vehicle.model.Assembly.static_tyre_loads_N`): the pitch plane's element carries
    the axle's two tyres; in 3-D the mean of the axle's left and right tyres (one footprint per axle).

    See Also
    --------
    build_parts : the tyre elements it loads.

    Examples
    --------
    >>> from tyrelab.vehicle.tractor import Tractor, tractor_parts
    >>> asm = assemble(tractor_parts(Tractor(1000, 250, 1.0, 1.5, 0.5, 1e5, 1e5, 0.0, 0.0)))
    >>> {k: round(v, 3) for k, v in static_tyre_loads(asm).items()}  # m g b / L / 2, m g a / L / 2
    {'front': 2941.995, 'rear': 1961.33}
    """
    _validate.instance("asm", asm, Assembly)
    per = asm.static_tyre_loads_N()
    out = {}
    for axle in ("front", "rear"):
        own = [v for t, v in per.items() if t.split("_")[0] == axle]
        out[axle] = (sum(own) / len(own)) / (1.0 if asm.parts.three_d else 2.0)
    return out


def _axle_tyres(axle: str, spec, speeds: np.ndarray, lists, lateral_too: bool, tyre_data,
                longitudinal: tuple | None = None) -> AxleTyres:
    """One axle's tyre numbers per speed (:func:`resolve_tyres`), the footprint a given one or NaN
    (the contact length needs the vehicle's static loads: :func:`_resolve`); ``longitudinal``: the
    ``[tractor]`` K, C and ``a`` of a rolling longitudinal element on this axle's tyres (issue 42)."""
    warnings: list[str] = []
    k_u = 0.0
    if spec.stiffness_kN_per_m is not None:
        k, k_src = per_speed(spec.stiffness_kN_per_m, lists, speeds), "override (scenario)"
    elif spec.measured_tyre_id:
        sp, val = tyre_data.measured("stiffness_pressure_by_speed", spec.measured_tyre_id, spec.pressure_bar)
        k = at_speeds(sp, val, speeds)  # rolling values for a rolling tyre (§4.5.1)
        k_src = f"measured tyre {spec.measured_tyre_id}: K = Kc + dKp P per speed (stiffness_pressure_by_speed)"
    else:
        k0, k_src, warnings, k_u = _formula_stiffness(spec, tyre_data)
        k = np.full(speeds.shape, k0)
    if spec.damping_kN_s_per_m is not None:
        c, c_src = per_speed(spec.damping_kN_s_per_m, lists, speeds), "override (scenario)"
    elif spec.measured_tyre_id:
        sp, val = tyre_data.measured("damping_pressure_by_speed", spec.measured_tyre_id, spec.pressure_bar)
        c = at_speeds(sp, val, speeds)
        c_src = f"measured tyre {spec.measured_tyre_id}: C = Cc + dC P per speed (damping_pressure_by_speed)"
    else:
        c, c_src, c_warnings = _model_damping(spec, speeds, tyre_data)
        warnings += c_warnings
    if np.any(k <= 0):
        raise ValueError(f"tyres.{axle}: stiffness {k.min():.1f} kN/m is not positive")
    size = parse_tyre_size(spec.size)
    radius = spec.radius_m or rolling_circumference_m(size) / (2 * math.pi)
    fp = np.full(speeds.shape, math.nan if spec.footprint_m is None else float(spec.footprint_m))
    lateral = _lateral_tyre(spec, k, np.maximum(c, 0.0), speeds, tyre_data) if lateral_too else {}
    if longitudinal is not None:
        lateral.update(_longitudinal_series(longitudinal, spec, speeds, tyre_data))
    return AxleTyres(spec.size, spec.pressure_bar, k, np.maximum(c, 0.0), k_src, c_src, float(radius), fp,
                     tuple(warnings), float(k_u), **lateral)


def _directional_tables(tyre_data, spec, direction: str) -> dict:
    """The build's tables of ``spec``'s measured tyre in ``direction`` and its catalogue row, as
    :func:`tyrelab.tyre.directional.rolling_coefficients` takes them (none without a measured tyre or
    a reader that has them: ``tyre_data.directional``)."""
    if not spec.measured_tyre_id or not hasattr(tyre_data, "directional"):
        return {}
    return tyre_data.directional(spec.measured_tyre_id, direction)


def _lateral_tyre(spec, k: np.ndarray, c: np.ndarray, speeds: np.ndarray | None = None, tyre_data=None) -> dict:
    """One tyre's lateral element per speed (issues 33, 42): K, C and the rolling element's ``a``, each
    from the scenario, the measured tyre's build, the catalogue or the stand-in (from the tyre's vertical
    stiffness, :mod:`tyrelab.tyre.lateral`; its vertical damping; :mod:`tyrelab.tyre.rolling`):
    :func:`tyrelab.tyre.directional.rolling_coefficients`. ``speeds``: the scenario's (default: one per
    value of ``k``, at rest)."""
    speeds = np.zeros(np.shape(k)) if speeds is None else speeds
    r = rolling_coefficients("lateral", spec.pressure_bar, speeds, tyre_id=spec.measured_tyre_id or None,
                             vertical_stiffness_kN_per_m=k, vertical_damping_kN_s_per_m=c,
                             given={"stiffness_kN_per_m": spec.lateral_stiffness_kN_per_m,
                                    "damping_kN_s_per_m": spec.lateral_damping_kN_s_per_m,
                                    "series_damping_kN_s_per_m_km_h": spec.lateral_series_damping_kN_s_per_m_km_h},
                             **_directional_tables(tyre_data, spec, "lateral"))
    texts = r.source_text
    src = (texts["stiffness_kN_per_m"] + "; damping: " + texts["damping_kN_s_per_m"]
           + "; series damper a: " + texts["series_damping_kN_s_per_m_km_h"])
    cy = np.where(r.damping_kN_s_per_m > 0, r.damping_kN_s_per_m, 1e-3)  # a Maxwell element needs a damper: 1 N s/m
    return {"lateral_stiffness_kN_per_m": r.stiffness_kN_per_m, "lateral_damping_kN_s_per_m": cy,
            "lateral_source": src, "lateral_ci95_kN_per_m": r.ci95.get("stiffness_kN_per_m"),
            "lateral_series_damping_kN_s_per_m_km_h": r.series_damping_kN_s_per_m_km_h,
            "lateral_series_ci95_kN_s_per_m_km_h": r.ci95.get("series_damping_kN_s_per_m_km_h"),
            "lateral_sources": dict(r.sources)}


def _longitudinal_series(given: tuple, spec, speeds: np.ndarray, tyre_data=None) -> dict:
    """``a`` of the rear tyres' longitudinal rolling element (issue 42): ``[tractor]``'s, the measured
    tyre's, the catalogue's or the stand-in (``given``: ``[tractor]``'s K, C and ``a``; the element's K
    and C are ``[tractor]``'s)."""
    k, c, a = given
    r = rolling_coefficients("longitudinal", spec.pressure_bar, speeds, tyre_id=spec.measured_tyre_id or None,
                             given={"stiffness_kN_per_m": k, "damping_kN_s_per_m": c,
                                    "series_damping_kN_s_per_m_km_h": a},
                             **_directional_tables(tyre_data, spec, "longitudinal"))
    return {"longitudinal_series_damping_kN_s_per_m_km_h": r.series_damping_kN_s_per_m_km_h,
            "longitudinal_series_source": r.source_text["series_damping_kN_s_per_m_km_h"]}


def build_parts(scenario: Scenario, tyres: dict[str, AxleTyres], i: int) -> Parts:
    """The tractor's :class:`~tyrelab.vehicle.model.Parts` at speed index ``i`` (per tyre, SI).

    The looked-up tyre numbers at that speed in SI, then the scenario's own parts
    (:meth:`tyrelab.vehicle.scenario.Scenario.parts`, where its kN values become SI). Without
    ``tractor.roll_inertia_kg_m2`` the parts are those of a pitch-plane
    :class:`~tyrelab.vehicle.tractor.Tractor` (:meth:`~tyrelab.vehicle.tractor.Tractor.of_parts`).

    See Also
    --------
    resolve_tyres : the tyre numbers per speed it takes.
    tyrelab.vehicle.model.assemble : the assembly of the parts.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.vehicle import parse_scenario
    >>> sc = parse_scenario((scenarios_dir() / "mf698t.toml").read_text())
    >>> parts = build_parts(sc, resolve_tyres(sc), 0)
    >>> parts.chassis.mass_kg
    5120.0
    """
    _validate.instance("scenario", scenario, Scenario)
    _validate.positive_int("i", i, minimum=0)
    si = {}
    for axle, ty in tyres.items():  # the looked-up tyre numbers (kN) at this speed, in SI
        si[axle] = {"stiffness_N_per_m": from_kilo(float(ty.stiffness_kN_per_m[i])),
                    "damping_N_s_per_m": from_kilo(float(ty.damping_kN_s_per_m[i])), "radius_m": ty.radius_m}
        if ty.lateral_stiffness_kN_per_m is not None:
            si[axle].update(lateral_stiffness_N_per_m=from_kilo(float(ty.lateral_stiffness_kN_per_m[i])),
                            lateral_damping_N_s_per_m=from_kilo(float(ty.lateral_damping_kN_s_per_m[i])))
        speed = float(scenario.exposure.speeds_km_h[i])  # issue 42: each speed its own c2 = a / v
        if ty.lateral_series_damping_kN_s_per_m_km_h is not None:
            si[axle]["lateral_series_damping_N_s_per_m"] = series_damping_N_s_per_m(
                ty.lateral_series_damping_kN_s_per_m_km_h, speed)
        if ty.longitudinal_series_damping_kN_s_per_m_km_h is not None:
            si[axle]["longitudinal_series_damping_N_s_per_m"] = series_damping_N_s_per_m(
                ty.longitudinal_series_damping_kN_s_per_m_km_h, speed)
    return scenario.parts(si)
