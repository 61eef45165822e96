"""A build's tyre fits, handed to a ride: what a scenario's tyres read, and nothing else.

A ride scenario reads a build's fits in two ways (:func:`tyrelab.vehicle.ride.resolve_tyres`):

- ``measured_tyre_id = "T3"``: the per-speed pressure fits of that tyre, the rows of tyre ``T3`` in
  ``stiffness_pressure_by_speed`` and ``damping_pressure_by_speed`` (:data:`MEASURED_TABLES`);
- ``formula = "build"``: the build's own stiffness formula and damping model, the ``ours`` rows of
  ``formula_fit`` and ``damping_fit`` (:data:`BUILD_FORMULA_TABLES`);
- a measured tyre's lateral and longitudinal fits, its series damper and its catalogue row
  (:data:`DIRECTIONAL_TABLES`: the rolling element of a 3-D scenario, issue 42; a build without them
  leaves those coefficients to the catalogue or the stand-in, :meth:`FitTyres.directional`).

A stage that runs scenarios (``simulate``, ``rides``) reads these tables of *this* run from Parquet
(declared in :data:`tyrelab.stages.dag.STAGES`, checked when read), picks with :func:`scenario_fits`
the rows each scenario reads, keys the scenario's item by them and hands it exactly those rows
(:class:`FitTyres`): a scenario cannot read what its key does not hold, and a new run of another tyre
leaves its key alone. :class:`WarehouseTyres` reads the same fits from a finished build's warehouse
(``tyrelab ride --build``).
"""

from __future__ import annotations

from pathlib import Path

from ..vehicle import ride

__all__ = ["MEASURED_TABLES", "BUILD_FORMULA_TABLES", "DIRECTIONAL_TABLES", "FIT_TABLES", "FitTyres", "WarehouseTyres",
           "scenario_fits", "read_fit_tables"]

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


class FitTyres(ride.ShippedTyres):
    """Tyre data of :func:`tyrelab.vehicle.ride.resolve_tyres` from fit tables handed in.

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
        from ..published import thesis_stiffness_model
        from ..tyre.models import build_stiffness_model

        thesis = thesis_stiffness_model()
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


class WarehouseTyres(FitTyres):
    """:class:`FitTyres` of a finished build's warehouse (``build/warehouse.duckdb``), read when asked
    (``tyrelab ride --build``; picklable: it travels with the executor's tasks)."""

    def __init__(self, build):
        self.build = str(build)
        super().__init__({}, str(self._db()))

    def _db(self) -> Path:
        return Path(self.build) / "warehouse.duckdb"

    def _table(self, name: str, why: str):
        from ..warehouse import query

        if name not in self.tables:
            db = self._db()
            if not db.is_file():
                raise ValueError(f"{why}: no warehouse at {db}")
            try:  # no SQL built from the user's text: the table's name is one of ours
                self.tables[name] = query(db, f"SELECT * FROM {name}")
            except Exception as exc:  # noqa: BLE001 - a warehouse without the table is the user's input problem
                raise ValueError(f"{why}: cannot read {name} from {db} ({str(exc).splitlines()[0]})") from None
        return self.tables[name]

    def __getstate__(self):
        return {"build": self.build, "tables": {}, "source": self.source}


def scenario_fits(scenario, tables: dict) -> dict:
    """The rows of the fit ``tables`` (name -> DataFrame or None) that ``scenario`` reads.

    Per axle: its measured tyre's rows of :data:`MEASURED_TABLES` (``measured_tyre_id``), the
    ``ours`` rows of :data:`BUILD_FORMULA_TABLES` (``formula = "build"``). A table the build
    lacks stays None (the scenario then fails naming it). Returns name -> DataFrame or None,
    only the tables read: the item key of the scenario and what :class:`FitTyres` is given.
    """
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


def read_fit_tables(ctx) -> dict:
    """This run's fit tables (:data:`FIT_TABLES`) of the build, from Parquet (None where missing).

    The running stage must declare them (:meth:`tyrelab.stages.base.Context.read_table`)."""
    return {name: ctx.read_table(name) if ctx.has_table(name) else None for name in FIT_TABLES}
