"""A finished build's tyre fits, read from its warehouse: the tyre data the command line and the
library hand to a ride (``tyrelab ride --build``, :func:`tyrelab.api.ride`; issue 45).

:class:`WarehouseTyres` is a :class:`tyrelab.vehicle.tyres.FitTyres` whose tables are read from
``build/warehouse.duckdb`` when a scenario's tyre asks (a measured tyre's per-speed fits,
``formula = "build"``). It sits above the pure packages (it reads the warehouse) and below the
stages and the command line, which hand it in.
"""

from __future__ import annotations

from pathlib import Path

from .vehicle.tyres import FitTyres

__all__ = ["WarehouseTyres"]


class WarehouseTyres(FitTyres):
    """:class:`FitTyres` of a finished build's warehouse (``build/warehouse.duckdb``), read when asked
    (``tyrelab ride --build``; picklable: it travels with the executor's tasks)."""

    def __init__(self, build):
        self.build = str(build)
        super().__init__({}, str(self._db()))

    def _db(self) -> Path:
        return Path(self.build) / "warehouse.duckdb"

    def _table(self, name: str, why: str):
        from .warehouse import query

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
