"""The ride scenarios of the simulate stage (issues 13, 45): every shipped and raw scenario file run
beside the thesis' studies, each kept under the digest of what it reads (its file, its profile's
data, the fit rows its tyres read), and the ride tables (:data:`~tyrelab.stages.dag.RIDE_TABLES`)
from their results. The thesis' studies are :mod:`tyrelab.stages.simulate`'s.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from .. import resources
from ..executor import map_batches
from ..scenario_io import ScenarioError, crg_files, load_scenario
from ..tyredata import WarehouseTyres
from ..vehicle import ride
from ..vehicle.model import assemble
from .base import Context
from .dag import RIDE_TABLES
from .state import ItemCache
from .tyredata import FitTyres, read_fit_tables, scenario_fits

__all__ = ["WarehouseTyres", "scenario_files", "scenario_items", "scenario_task", "run_scenarios", "collect_scenarios",
           "collect_scenario_spectra", "portable_path"]


def _ride_plan(ctx: Context, files: list[tuple[str, str]], cache: ItemCache) -> tuple[list, list]:
    """The ride scenarios, each kept under the digest of what it reads: its file (and the data of the
    profile CSV its surface names), and the rows of this run's fit tables its tyres read (:func:`tyrelab.stages.tyredata.scenario_fits`: a measured tyre's
    per-speed fits, the build's formula), which its task is handed (:class:`~tyrelab.stages.tyredata.FitTyres`)
    and nothing else. Returns the keys and the tyre data, one per file (:func:`_ride_todo`)."""
    tables = read_fit_tables(ctx)
    keys, tyres = [], []
    for path, source in files:
        try:
            text = Path(path).read_bytes()
        except OSError as exc:  # unreadable (its task says why): keyed by the error, re-tried next run
            text = f"unreadable: {exc}".encode()
        try:
            sc = load_scenario(path)
            fits, profile = scenario_fits(sc, tables), sc.surface.profile_data  # a profile CSV's data, as read
            if sc.surface.kind == "crg" and sc.surface.file is not None:  # a CRG road and its data file, by content
                profile = [cache.file_digest(f) for f in crg_files(sc.surface.file)]
        except Exception:  # noqa: BLE001 - any failure of one file: its task refuses it (one quarantine line)
            fits, profile = {}, None  # its task refuses the file, reading the same bytes
        keys.append(cache.key("ride", path, source, text, fits, profile))
        tyres.append(FitTyres(fits, str(ctx.parquet)))
    return keys, tyres


def _ride_todo(files: list[tuple[str, str]], cache: ItemCache, keys: list, tyres: list) -> tuple[dict, list]:
    """The cached results by key (:func:`_ride_plan`) and the ``(file, key, tyre data)`` triples to run
    (:func:`scenario_task`)."""
    done = {k: v for k in keys for hit, v in [cache.get(k)] if hit}
    todo = [(f, k, t) for f, k, t in zip(files, keys, tyres) if k not in done]
    return done, todo


def _ride_finish(ctx: Context, files: list[tuple[str, str]], cache: ItemCache, keys: list, done: dict, todo: list,
                 outputs: list[dict]) -> tuple[dict[str, pd.DataFrame], list[dict]]:
    """The ride tables (:data:`RIDE_TABLES`) and the refused files, from the cached scenarios and the
    ``outputs`` of the ``todo`` ones (:func:`_ride_plan`), which are stored."""
    if todo:
        scenarios, results, bad = collect_scenarios(outputs)
        spectra, trans = collect_scenario_spectra(outputs)
        for (path, _), k, _ in todo:
            failed = [b for b in bad if b["file"] == path]
            # keyed by the scenario file (ride_results.file): two files may give the same name
            mine = [t[t["file"] == path] if len(t) else t.iloc[0:0] for t in (scenarios, results, spectra, trans)]
            done[k] = (*mine, failed)
            cache.put(k, done[k])
    parts = [done[k] for k in keys]
    frames = [p for p in parts if not p[-1]]
    tables = {name: pd.concat([p[i] for p in frames], ignore_index=True) if frames else pd.DataFrame()
              for i, name in enumerate(RIDE_TABLES)}
    return tables, [b for p in parts for b in p[-1]]


def scenario_files(raw: Path | None) -> list[tuple[str, str]]:
    """``(path, source)`` of every shipped scenario and every ``<raw>/scenarios/*.toml``.

    A file of ``raw`` with the same bytes as a shipped one (the repository's own
    ``raw/`` folder) is listed once, as shipped.
    """
    shipped = sorted(resources.scenarios_dir().glob("*.toml"))
    seen = {p.read_bytes() for p in shipped}
    out = [(str(p), "shipped") for p in shipped]
    folder = Path(raw) / "scenarios" if raw is not None else None
    for p in sorted(folder.glob("*.toml")) if folder is not None and folder.is_dir() else []:
        if p.is_file() and p.read_bytes() not in seen:  # a named pipe is skipped (the raw walk warns of it)
            out.append((str(p), "raw"))
    return out


def portable_path(path: str, raw: Path | None) -> str:
    """A file read as the warehouse holds it (``ride_results.file`` and the other ride tables,
    ``simulate_inputs.source``): relative to the raw folder (``scenarios/field.toml``), a shipped
    scenario relative to the shipped folder (``mf698t.toml``), never this machine's absolute path.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> portable_path(str(scenarios_dir() / "mf698t.toml"), None)
    'mf698t.toml'
    """
    p = Path(path).resolve()
    for base in ([Path(raw)] if raw is not None else []) + [resources.scenarios_dir()]:
        try:
            return p.relative_to(Path(base).resolve()).as_posix()
        except ValueError:
            continue
    return p.name


def scenario_items(files: list[tuple[str, str]], build: Path | None = None, tyre_data: list | None = None) -> list[tuple]:
    """The executor items of :func:`run_scenarios`, one per ``(path, source)`` of ``files``: run each
    with :func:`scenario_task` (in any process) and hand the results, in order, to
    :func:`collect_scenarios` (the simulate stage runs them beside its studies this way).

    The tyre data of each (:func:`tyrelab.vehicle.ride.resolve_tyres`): ``tyre_data[i]``, else a finished
    build's warehouse (``build``, :class:`~tyrelab.stages.tyredata.WarehouseTyres`), else the shipped."""
    if tyre_data is None:
        tyre_data = [WarehouseTyres(build) if build else None] * len(files)
    return [(p, src, t) for (p, src), t in zip(files, tyre_data)]


def scenario_task(item: tuple) -> dict:
    """Executor task of the simulate stage: one scenario file, every pressure pair of its sweep."""
    path, source, tyre_data = item
    try:
        sc = load_scenario(path)
        results = ride.ride_sweep(sc, tyre_data=tyre_data, with_spectra=True)
        # the scenario row's modes are those at the scenario's own pressures, which a [sweep] need not
        # list first, or at all: from the nominal pair's result, else from the nominal tyres
        nominal = [r for r in results if r.nominal]  # its pressures and the file's value of each swept key
        nat, nodal = ((nominal[0].natural_frequencies_Hz, nominal[0].nodal_points_m) if nominal else
                      ride.modes(assemble(ride.build_parts(sc, ride.resolve_tyres(sc, tyre_data), 0))))
    except ScenarioError as exc:  # names its file
        return {"file": path, "error": str(exc).replace("\n", "; ")}
    except ValueError as exc:  # too much work, a value the model refuses: named with its file alike
        return {"file": path, "error": f"{path}: {exc}".replace("\n", "; ")}
    except Exception as exc:  # noqa: BLE001 - the model failed: this scenario only (quarantined), the others run
        return {"file": path, "error": f"{path}: the ride model failed: {type(exc).__name__}: "
                                       f"{str(exc).splitlines()[0] if str(exc) else ''}"}
    table = ride.results_table(results, sc.name)
    table["file"] = path  # rows are keyed by the scenario file: two files may share a name
    s = sc.surface
    row = {
        "scenario": sc.name, "file": path, "source": source, "description": sc.description,
        "mass_kg": sc.tractor.mass_kg, "pitch_inertia_kg_m2": sc.tractor.pitch_inertia_kg_m2,
        "front_distance_m": sc.tractor.front_distance_m, "rear_distance_m": sc.tractor.rear_distance_m,
        "cg_height_m": sc.tractor.cg_height_m, "longitudinal_model": sc.tractor.longitudinal_model,
        "seat_ahead_of_cg_m": sc.seat.ahead_of_cg_m, "seat_height_above_cg_m": sc.seat.height_above_cg_m,
        "seat_suspension": sc.seat.suspension,
        "front_size": sc.front.size, "front_pressure_bar": sc.front.pressure_bar,
        "rear_size": sc.rear.size, "rear_pressure_bar": sc.rear.pressure_bar,
        "surface": s.kind, "road_class": s.road_class, "track": results[0].track_label,
        "track_length_m": results[0].track_length_m,
        "seed": s.seed, "enveloping": s.enveloping,
        "speeds_km_h": ", ".join(f"{v:g}" for v in sc.exposure.speeds_km_h), "hours_per_day": sc.exposure.hours_per_day,
        "bounce_Hz": nat["bounce"], "pitch_Hz": nat["pitch"],
        "bounce_nodal_point_m": nodal["bounce"], "pitch_nodal_point_m": nodal["pitch"],
        "pressure_pairs": len(results), "warnings": "; ".join(sorted({w for r in results for w in r.warnings})),
    }
    # the report's seat PSD and transmissibility per axis: of the nominal variant (else the first)
    shown = nominal[0] if nominal else results[0]
    where = {"scenario": sc.name, "file": path, "front_pressure_bar": shown.tyres["front"].pressure_bar,
             "rear_pressure_bar": shown.tyres["rear"].pressure_bar,
             "variant": ", ".join(f"{k}={v:g}" for k, v in shown.variant.items())}
    spectra, trans = (frame.assign(**where)[list(where) + list(frame.columns)]
                      for frame in (shown.spectra, shown.transmissibility))
    return {"file": path, "scenario": row, "results": table, "spectra": spectra, "transmissibility": trans}


def run_scenarios(files: list[tuple[str, str]], ctx=None, build: Path | None = None) -> tuple[pd.DataFrame, pd.DataFrame, list[dict]]:
    """Run scenario files (through :func:`tyrelab.executor.map_batches` when ``ctx`` is given).

    Returns
    -------
    ride_scenarios, ride_results : DataFrame
        One row per scenario; one row per scenario × speed × pressure pair.
    problems : list of dict
        ``file`` and ``reason`` of every scenario refused (the others still run).
    """
    items = scenario_items(files, build)
    return collect_scenarios(map_batches(scenario_task, items, ctx) if ctx is not None else [scenario_task(i) for i in items])


def collect_scenario_spectra(outputs: list[dict]) -> tuple[pd.DataFrame, pd.DataFrame]:
    """``ride_spectra`` and ``ride_transmissibility`` from the results of :func:`scenario_task`, in
    order: per scenario file, the seat PSD and transmissibility per axis and speed of the variant
    the report shows (the scenario's own pressures, else the first variant)."""
    ok = [o for o in outputs if "error" not in o]
    return tuple(pd.concat([o[k] for o in ok], ignore_index=True) if ok else pd.DataFrame()
                 for k in ("spectra", "transmissibility"))


def collect_scenarios(outputs: list[dict]) -> tuple[pd.DataFrame, pd.DataFrame, list[dict]]:
    """The tables of :func:`run_scenarios` from the results of :func:`scenario_task`, in order."""
    ok = [o for o in outputs if "error" not in o]
    problems = [{"file": o["file"], "reason": o["error"]} for o in outputs if "error" in o]
    scenarios = pd.DataFrame([o["scenario"] for o in ok])
    results = pd.concat([o["results"] for o in ok], ignore_index=True) if ok else pd.DataFrame()
    return scenarios, results, problems
