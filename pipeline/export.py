"""A measured tyre exported for multibody tools: :func:`export_tyre` (``tyrelab export-tyre``).

Three steps, each its own function:

- querying: :func:`read_tyre_tables` reads what an export needs from the warehouse;
- domain logic: :func:`tyre_export` (pure: tables in, texts out) builds the MF-Tyre
  ``.tir`` texts (:mod:`tyrelab.tyre.mf_tyre`), the K(P), C(P) table per speed and the
  summary, and warns where a pressure asked for lies outside the tested range (the
  values there are extrapolated from the measured lines, and the files say so);
- file writing: :func:`write_export` writes the ``.tir`` file(s), the ``.csv`` and the
  ``.json`` as one set (:func:`tyrelab.io.write_texts_atomic`): all are replaced, or
  none is.

Examples
--------
>>> import pandas as pd
>>> tables = TyreTables(
...     tyres=pd.DataFrame({"tyre_id": ["MY1"], "size": ["480/70R38"], "carcass_stiffness_kN_per_m": [120.0],
...                         "pressure_dependence_kN_per_m_bar": [230.0], "tested_load_kN": [25.0],
...                         "measured_pressure_min_bar": [0.8], "measured_pressure_max_bar": [1.6]}),
...     runs=pd.DataFrame({"tyre_id": [], "kind": [], "pressure_bar": []}))
>>> e = tyre_export(tables, "MY1", [1.2, 3.0])
>>> e.pressures_bar, e.warnings
([1.2, 3.0], ['pressure 3 bar is outside the tested range 0.8-1.6 bar: K and C there are extrapolated from the measured lines'])
>>> sorted(p.name for p in e.files("out/MY1.tir"))
['MY1.csv', 'MY1.json', 'MY1_1.2bar.tir', 'MY1_3bar.tir']
"""

from __future__ import annotations

import dataclasses
import json
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from . import io
from .tyre.mf_tyre import MeasuredTyre, measured_tyre, pressure_table, property_file

__all__ = ["TyreTables", "TyreExport", "read_tyre_tables", "tyre_export", "write_export", "export_tyre"]

#: Warehouse tables an export reads (plus ``tyre_id, kind, pressure_bar`` of ``results``).
TABLES = ("tyres", "table_iii", "stiffness_pressure_by_speed", "damping_pressure_by_speed")


def _empty(*columns: str) -> pd.DataFrame:
    return pd.DataFrame({c: pd.Series(dtype=object if c in ("tyre_id", "kind") else float) for c in columns})


@dataclass(frozen=True)
class TyreTables:
    """The warehouse tables an export needs (any may be empty but ``tyres``)."""

    tyres: pd.DataFrame
    runs: pd.DataFrame = field(default_factory=lambda: _empty("tyre_id", "kind", "pressure_bar"))
    table_iii: pd.DataFrame | None = None
    stiffness_by_speed: pd.DataFrame = field(default_factory=lambda: _empty("tyre_id", "speed_km_h", "slope"))
    damping_by_speed: pd.DataFrame = field(default_factory=lambda: _empty("tyre_id", "speed_km_h", "slope"))


@dataclass(frozen=True)
class TyreExport:
    """What an export writes, before it is written.

    Attributes
    ----------
    tyre : MeasuredTyre
    pressures_bar : list of float
        One ``.tir`` each.
    tir_texts : list of str
        The ``.tir`` texts, in the order of ``pressures_bar``.
    table : DataFrame
        K(P), C(P) per speed at the tested and the asked pressures, with ``extrapolated``
        (the pressure lies outside the tested range).
    warnings : list of str
        One line each (the command prints them on stderr).
    """

    tyre: MeasuredTyre
    pressures_bar: list[float]
    tir_texts: list[str]
    table: pd.DataFrame
    warnings: list[str]

    def tir_paths(self, out: str | os.PathLike) -> list[Path]:
        """``out`` (``.tir`` added) for one pressure, ``<stem>_<P>bar.tir`` each for several."""
        out = _tir(out)
        if len(self.pressures_bar) == 1:
            return [out]
        return [out.with_name(f"{out.stem}_{p:g}bar.tir") for p in self.pressures_bar]

    def summary(self, out: str | os.PathLike) -> dict:
        """The ``.json`` document (NaN as null)."""
        t = self.tyre
        doc = {
            "tyre_id": t.tyre_id,
            "size": t.size.designation,
            "source": t.source,
            "stiffness_line_kN_per_m": dataclasses.asdict(t.stiffness),
            "damping_line_kN_s_per_m": dataclasses.asdict(t.damping) if t.damping else None,
            "damping_speed_km_h": t.damping_speed_km_h,
            "tested_load_kN": t.tested_load_kN,
            "pressure_range_bar": list(t.pressure_range_bar),
            "tir_files": dict(zip([f"{p:g}" for p in self.pressures_bar], map(str, self.tir_paths(out)))),
            "extrapolated_pressures_bar": [p for p in self.pressures_bar if not _tested(t, p)],
            "warnings": list(self.warnings),
            "by_speed": self.table.to_dict(orient="records"),
        }
        return io.json_safe(doc)

    def files(self, out: str | os.PathLike) -> dict[Path, str]:
        """Every file of the export: ``{path: text}`` (the ``.tir`` file(s), ``.csv``, ``.json``)."""
        base = _tir(out)
        files = dict(zip(self.tir_paths(out), self.tir_texts))
        files[base.with_suffix(".csv")] = self.table.to_csv(index=False)
        files[base.with_suffix(".json")] = json.dumps(self.summary(out), indent=2, ensure_ascii=False,
                                                     allow_nan=False) + "\n"
        return files


def _tir(out: str | os.PathLike) -> Path:
    out = Path(out)
    return out if out.suffix.lower() == ".tir" else out.with_name(out.name + ".tir")


def _pressures(pressures_bar) -> list[float]:
    """``pressures_bar`` as floats, each within the range the tyre models are built for
    (:data:`tyrelab.vehicle.scenario_limits.LIMITS` ``pressure_bar``: no ``INFLPRES = inf``);
    ValueError naming every bad one at once."""
    from . import _validate
    from .vehicle.scenario_limits import LIMITS

    if isinstance(pressures_bar, (str, bytes)) or not hasattr(pressures_bar, "__iter__"):
        raise ValueError(f"pressures_bar must be a list of pressures, bar, got {_validate.shown(pressures_bar)}")
    pressures, bad = [], []
    for i, p in enumerate(pressures_bar):
        try:
            pressures.append(_validate.in_range(f"pressures_bar[{i}]", p, *LIMITS["pressure_bar"]))
        except ValueError as exc:
            bad.append(str(exc))
    if not pressures and not bad:
        bad.append("pressures_bar must hold at least one pressure")
    if bad:
        raise ValueError("; ".join(bad))
    return pressures


def _tested(tyre: MeasuredTyre, pressure_bar: float) -> bool:
    low, high = tyre.pressure_range_bar
    return low - 1e-9 <= pressure_bar <= high + 1e-9


def read_tyre_tables(db_path: str | os.PathLike) -> TyreTables:
    """The tables of :class:`TyreTables` from a built warehouse (read-only).

    Raises
    ------
    FileNotFoundError
        No warehouse at ``db_path``.
    LookupError
        The warehouse lacks a table an export needs (the message names it; run ``tyrelab run``).
    """
    from .warehouse import query

    try:
        tables = {name: query(db_path, f"SELECT * FROM {name}") for name in TABLES}
        runs = query(db_path, "SELECT tyre_id, kind, pressure_bar FROM results")
    except FileNotFoundError:
        raise
    except Exception as exc:  # noqa: BLE001 - DuckDB's catalog error: a warehouse without the regress tables
        raise LookupError(f"{db_path}: {str(exc).splitlines()[0]} (run 'tyrelab run' first)") from None
    return TyreTables(tyres=tables["tyres"], runs=runs, table_iii=tables["table_iii"],
                      stiffness_by_speed=tables["stiffness_pressure_by_speed"],
                      damping_by_speed=tables["damping_pressure_by_speed"])


def tyre_export(tables: TyreTables, tyre_id: str, pressures_bar=None, *, source: str = "") -> TyreExport:
    """The ``.tir`` texts, the K(P), C(P) table and the warnings of one tyre's export (pure).

    Parameters
    ----------
    tables : TyreTables
    tyre_id : str
    pressures_bar : sequence of float, optional
        Nominal pressures, bar, one ``.tir`` each (default: the middle of the tested range).
        Outside the tested range a warning is given and the files mark the values as
        extrapolated.
    source : str
        Recorded in the files (e.g. the warehouse path).

    Raises
    ------
    ValueError
        Naming the tyre or ``pressures_bar``: an unknown tyre, one without a measured
        stiffness line, a pressure that is not finite and positive, or one where the
        measured line gives no positive stiffness.
    """
    runs = tables.runs
    kind = runs["kind"].fillna("measurement") if "kind" in runs else pd.Series("measurement", index=runs.index)
    tested = runs.loc[(runs["tyre_id"].astype(str) == tyre_id) & (kind == "measurement"), "pressure_bar"]
    tested = np.unique(np.round(pd.to_numeric(tested, errors="coerce").to_numpy(dtype=float), 3))
    pressures = None if pressures_bar is None else _pressures(pressures_bar)  # before any work
    tyre = measured_tyre(tyre_id, tables.tyres, tables.table_iii, tables.damping_by_speed, tested, source=source)
    if pressures is None:
        pressures = [round(float(np.mean(tyre.pressure_range_bar)), 3)]
    low, high = tyre.pressure_range_bar
    warnings = [f"pressure {p:g} bar is outside the tested range {low:g}-{high:g} bar: K and C there are "
                "extrapolated from the measured lines" for p in pressures if not _tested(tyre, p)]
    texts = [property_file(tyre, p) for p in pressures]
    grid = sorted(set(tested[np.isfinite(tested)].tolist()) | set(pressures))
    table = pressure_table(tyre_id, tables.stiffness_by_speed, tables.damping_by_speed, grid)
    table["extrapolated"] = [not _tested(tyre, p) for p in table["pressure_bar"]]
    return TyreExport(tyre=tyre, pressures_bar=pressures, tir_texts=texts, table=table, warnings=warnings)


def write_export(export: TyreExport, out: str | os.PathLike) -> list[Path]:
    """Write the export's files as one set (all replaced or none); return their paths.

    Raises
    ------
    OSError
        From the file system (a folder where a file should be, a file where a folder
        should be, a full disk, a file-size limit); then no file of the set was replaced.
    """
    files = export.files(out)
    for path in files:
        if path.is_dir():
            raise IsADirectoryError(21, "Is a directory", str(path))
    return io.write_texts_atomic(files)


def export_tyre(db_path: str | os.PathLike, tyre_id: str, pressures_bar=None,
                out: str | os.PathLike | None = None) -> tuple[TyreExport, list[Path]]:
    """Export a measured tyre from a built warehouse: read, build, write (see the module docstring).

    ``out`` defaults to ``<tyre id, file-name-safe>.tir`` in the working folder. Returns the
    export and the paths written (the ``.tir`` file(s), then the ``.csv`` and the ``.json``).
    """
    export = tyre_export(read_tyre_tables(db_path), tyre_id, pressures_bar, source=f"warehouse {db_path}")
    out = Path(out) if out else Path(f"{io.safe_name(tyre_id)}.tir")
    return export, write_export(export, out)
