"""A build's tyre fits, handed to a ride (issue 45: the readers moved below the stages).

:class:`~tyrelab.vehicle.tyres.FitTyres` and :func:`~tyrelab.vehicle.tyres.scenario_fits` live in
:mod:`tyrelab.vehicle.tyres`, :class:`~tyrelab.tyredata.WarehouseTyres` in :mod:`tyrelab.tyredata`;
this module keeps their old names and reads a stage's fit tables (:func:`read_fit_tables`).

A stage that runs scenarios (``simulate``, ``rides``) reads these tables of *this* run from Parquet
(declared in :data:`tyrelab.stages.dag.STAGES`, checked when read), picks with ``scenario_fits``
the rows each scenario reads, keys the scenario's item by them and hands it exactly those rows
(``FitTyres``): a scenario cannot read what its key does not hold, and a new run of another tyre
leaves its key alone.
"""

from __future__ import annotations

from ..tyredata import WarehouseTyres
from ..vehicle.tyres import (BUILD_FORMULA_TABLES, DIRECTIONAL_TABLES, FIT_TABLES, MEASURED_TABLES, FitTyres, _concat, _measured_rows,  # noqa: F401
                             _ours, _safe, scenario_fits)

__all__ = ["MEASURED_TABLES", "BUILD_FORMULA_TABLES", "DIRECTIONAL_TABLES", "FIT_TABLES", "FitTyres", "WarehouseTyres", "scenario_fits",
           "read_fit_tables"]


def read_fit_tables(ctx) -> dict:
    """This run's fit tables (:data:`FIT_TABLES`) of the build, from Parquet (None where missing).

    The running stage must declare them (:meth:`tyrelab.stages.base.Context.read_table`)."""
    return {name: ctx.read_table(name) if ctx.has_table(name) else None for name in FIT_TABLES}
