"""The pipeline, declared: what each stage reads and writes, in one place (DVC's ``dvc.yaml``).

:data:`STAGES` is the one declaration of the pipeline. Each :class:`Stage` names

- ``reads``: what it depends on. A path relative to the build folder (``parquet/manifest.parquet``;
  a folder ends with ``/``: ``parquet/runs/``), or one of the raw sources:

  ========================  ==========================================================================
  ``raw``                   every file below ``--raw``, by path, size and mtime (ingest re-hashes
                            the content of a changed file itself)
  ``raw-extras``            the raw files outside campaign folders (``published/``, ``tyres.csv``)
                            and the shipped ones, by content
  ``published``             the digitised thesis tables :mod:`tyrelab.published` resolves, by content
  ``scenarios``             the shipped and ``<raw>/scenarios`` ride scenarios, by content
  ``param:<name>``          a :class:`~tyrelab.stages.base.Context` option (``calibration_correct``)
  ``code:<package>``        non-Python files that are code of the stage (the report's templates and
                            the documents it renders)
  ========================  ==========================================================================

  A path may hold ``*`` (``parquet/*.parquet``: every table another stage declares there).
  The stage's own Python code (its module and every ``tyrelab`` module it imports, found by
  :mod:`ast`) is always read: :func:`tyrelab.stages.state.code_fingerprint`.
- ``writes``: every file or folder below the build folder it writes. Each has exactly one writer
  (:func:`check`), and the writer is the one stage that checks it: a missing, changed or
  unreadable output makes its writer run again (:func:`tyrelab.stages.state.why_stale`).

The order stages run in is not listed anywhere: :data:`ORDER` is the topological order of the
graph "A writes what B reads" (ties broken by name), and ``tyrelab run --explain`` prints it with
the reason each stage will or will not run. ``docs/architecture.md`` shows :func:`graph_text`.

This module imports nothing heavy: ``tyrelab --help`` and a no-op ``tyrelab run`` read it.

Examples
--------
>>> ORDER[:3]
['ingest', 'analyse', 'calibrate']
>>> writer("parquet/results.parquet")
'calibrate'
>>> sorted(upstream("regress"))
['analyse', 'calibrate', 'ingest']
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import PurePosixPath

__all__ = ["Item", "Stage", "STAGES", "ORDER", "RAW_SOURCES", "table", "ANALYSED", "RIDE_TABLES", "RIDES_TABLES", "FIT_TABLES",
           "SIMULATE_TABLES", "REGRESS_TABLES", "may_read", "QUARANTINE_PARTS", "quarantine_part", "expand", "writer", "upstream", "check", "topological_order",
           "graph_text"]

#: The raw-side sources a stage may read (see the module docstring); prefixes ``param:``, ``code:``.
RAW_SOURCES = ("raw", "raw-extras", "published", "scenarios")


@dataclass(frozen=True)
class Item:
    """One kind of item a stage keeps apart (:class:`tyrelab.itemcache.ItemCache`): its name and what
    it is computed again from (issue 45: data, not a line of prose). ``str(item)`` is the line
    ``--explain`` prints, ``"<name> <- <reads, comma-separated>"``.

    Examples
    --------
    >>> str(Item("day", ("its runs' results", "its transfer function")))
    "day <- its runs' results, its transfer function"
    """

    name: str
    reads: tuple[str, ...]

    def __str__(self) -> str:
        return f"{self.name} <- {', '.join(self.reads)}"


@dataclass(frozen=True)
class Stage:
    """One stage: its name (module ``tyrelab.stages.<name>``), what it reads and what it writes.

    Attributes
    ----------
    name : str
        Stage name; the module is ``tyrelab.stages.<name>`` with ``run(ctx) -> StageResult``.
    reads : tuple of str
        Inputs (module docstring).
    writes : tuple of str
        Outputs: paths below the build folder, folders ending in ``/``.
    doc : str
        One line for ``--explain`` and the architecture document.
    pools : bool
        It spreads per-run work over worker pools, which would share the cores with work started
        ahead: :func:`tyrelab.stages.run_pipeline` starts that work after such stages.
    items : tuple of Item
        The items the stage keeps apart (:class:`tyrelab.itemcache.ItemCache`), each an :class:`Item`
        (its name and what it reads): within a stage that runs, an item is computed again only when what it reads changed
        (the stage's log counts them, ``--explain`` lists them under a stage that will run).
    ahead : bool
        Its module has ``start_ahead(ctx)`` (start, on workers, the part of its work whose inputs
        are there before the stages it runs after: the raw-side ones) and ``abandon_ahead()``
        (end what no run took); :func:`tyrelab.stages.run_pipeline` calls them.
    """

    name: str
    reads: tuple[str, ...]
    writes: tuple[str, ...]
    doc: str = ""
    pools: bool = False
    ahead: bool = False
    items: tuple[Item, ...] = ()

    @property
    def module(self) -> str:
        """Import name of the stage module."""
        return f"{__package__}.{self.name}"

    @property
    def params(self) -> tuple[str, ...]:
        """Context options the stage reads (``param:<name>``)."""
        return tuple(r.partition(":")[2] for r in self.reads if r.startswith("param:"))

    @property
    def code_files(self) -> tuple[str, ...]:
        """Resource packages of non-Python code the stage reads (``code:<package>``)."""
        return tuple(r.partition(":")[2] for r in self.reads if r.startswith("code:"))

    @property
    def build_reads(self) -> tuple[str, ...]:
        """Inputs that are paths below the build folder."""
        return tuple(r for r in self.reads if r not in RAW_SOURCES and ":" not in r)


def table(name: str) -> str:
    """Build path of Parquet table ``name``: ``parquet/<name>.parquet``."""
    return f"parquet/{name}.parquet"


def _tables(*names: str) -> tuple[str, ...]:
    return tuple(table(n) for n in names)


#: Tables regress writes (thesis chapters 4-5; :mod:`tyrelab.stages.regress`).
REGRESS_TABLES = (
    "table_iii", "stiffness_pressure_by_speed", "damping_pressure_by_speed", "table_vii", "factor_regressions",
    "table_iv", "table_viii", "surface_cells", "table_v", "table_ix", "table_vi", "table_x", "size_regressions",
    "size_regression_search", "formula_predictions", "formula_accuracy", "formula_fit", "formula_fit_loto", "damping_fit",
    "spoke_force", "spoke_speed",
    "spoke_frequency", "spoke_amplitude", "spoke_deflection", "spoke_fit", "spoke_fit_points",
    # issue 34: the lateral and longitudinal runs (:func:`tyrelab.stages.regress.directional_fits`)
    *(f"{d}_{q}" for d in ("lateral", "longitudinal")
      for q in ("stiffness_pressure_by_speed", "damping_pressure_by_speed", "factor_regressions")),
    "series_damping_speed",
    # issue 44: the runs of each direction apart (:func:`tyrelab.stages.regress.direction_tables`)
    "results_vertical", "results_lateral", "results_longitudinal",
)
#: The ride tables simulate writes, per scenario file (:func:`tyrelab.stages.simulate.scenario_task`): one
#: row per scenario; per scenario × speed × variant; the seat PSD and the transmissibility per axis of the
#: variant the report shows.
RIDE_TABLES = ("ride_scenarios", "ride_results", "ride_spectra", "ride_transmissibility")
#: Tables simulate writes (thesis chapters 6-8 and the ride scenarios; :mod:`tyrelab.stages.simulate`).
SIMULATE_TABLES = (
    "carriage_runs", "carriage_comparisons", "carriage_spectra", "table_xiii", "table_xiv", "tractor_runs",
    "table_xvii", "table_xviii", "table_xx", "table_xx_statistics", "iso2631", "profile_spectra", "simulate_inputs",
    *RIDE_TABLES,
)
#: Tables the rides stage writes (vehicle recordings; :mod:`tyrelab.stages.rides`).
RIDES_TABLES = ("recordings", "recording_axes", "recording_spectra", "exposure_days", "ride_validation",
                "ride_validation_statistics", "vehicle_frf", "vehicle_modes", "vehicle_frf_validation")
#: The fits a ride scenario's tyres may read (:mod:`tyrelab.stages.tyredata`): a measured tyre's
#: per-speed pressure fits (``measured_tyre_id``; its lateral and longitudinal ones, series damper and
#: catalogue row: issue 42) and the build's formula (``formula = "build"``).
FIT_TABLES = ("stiffness_pressure_by_speed", "damping_pressure_by_speed", "formula_fit", "damping_fit",
              # issue 42: a measured tyre's lateral and longitudinal fits and catalogue row (the rolling element)
              *(f"{d}_{q}" for d in ("lateral", "longitudinal")
                for q in ("stiffness_pressure_by_speed", "damping_pressure_by_speed")),
              "series_damping_speed", "tyres")
#: Stages whose rows make up the ``quarantine`` table, each in its own part
#: (:func:`quarantine_part`); the warehouse stage publishes their union, in this order.
QUARANTINE_PARTS = ("ingest", "analyse", "simulate", "rides")


#: The analyse stage's table (one row per measurement run), which calibrate completes into ``results``.
ANALYSED = "stages/analysed"


def quarantine_part(stage: str) -> str:
    """Build path of the quarantine rows of ``stage``: ``parquet/stages/quarantine_<stage>.parquet``.

    Tables below ``parquet/stages/`` pass from one stage to another and are not published in
    the warehouse (which stores ``parquet/*.parquet``)."""
    return table(f"stages/quarantine_{stage}")


#: The pipeline. Add a stage here and in its module ``tyrelab.stages.<name>``; nothing else.
STAGES: dict[str, Stage] = {s.name: s for s in (
    Stage("ingest", reads=("raw",),
          writes=("parquet/runs/", *_tables("manifest", "tyres"), quarantine_part("ingest")), pools=True,
          items=(Item("run", ("its raw file (by content) and manifest row",)),),
          doc="validate raw campaigns against schemas/, convert each run to Parquet"),
    Stage("analyse", reads=(*_tables("manifest", "tyres"), "parquet/runs/"),
          writes=(table(ANALYSED), table("frf"), quarantine_part("analyse")), pools=True,
          items=(Item("run", ("its Parquet file and manifest row (a broadband run's frf rows with it)",)),),
          doc="per run and method: apparent mass (H(f) of broadband runs: frf), K, C, amplitude, coherence, QC"),
    Stage("calibrate", reads=(*_tables("manifest", ANALYSED), "parquet/runs/", "param:calibration_correct"),
          writes=_tables("calibration", "calibration_tf", "results"),
          items=(Item("check", ("its calibration run (by content)",)),
                 Item("day", ("its runs' results", "its transfer function")),),
          doc="force-plate check per day; results = analysed runs with their day's flags and uncertainty"),
    Stage("methods", reads=("published", table("results")), writes=(table("table_i"),),
          items=(Item("Table I from recordings", ("the results of several methods on one tyre and condition",)),
                 Item("Table I from virtual experiments", ("the published tables it reads",)),),
          doc="Table I: the measurement methods of §3.4, from recordings of several methods or virtual experiments"),
    Stage("regress", reads=(*_tables("results", "tyres"), "published"),
          writes=_tables(*REGRESS_TABLES),
          items=(Item("per-tyre fits", ("that tyre's results and catalogue row",)),
                 Item("formula fit of a source", ("its points (the published source's: the printed Table III)",)),
                 Item("published-only parts", ("the published tables they read",)),),
          doc="Tables III-X, size regressions, formula accuracy, spoke model"),
    Stage("simulate", reads=("raw", "published", "scenarios", *_tables(*FIT_TABLES, "recordings")),
          writes=(*_tables(*SIMULATE_TABLES), quarantine_part("simulate")), ahead=True,
          items=(Item("study, case", ("its published rows (a carriage case: its recording, by content)",)),
                 Item("ride scenario", ("its file", "the fit rows of its tyres (measured_tyre_id; formula = \"build\")")),
                 Item("Table XX", ("Tables XIX, XX and the formula's tables",)),
                 Item("the tables", ("every item's inputs (none changed: the last run's tables)",)),),
          doc="profiles, carriage and tractor studies (against the recordings), Table XX, ISO 2631, ride scenarios"),
    Stage("rides", reads=("raw", *_tables(*FIT_TABLES)),
          writes=(*_tables(*RIDES_TABLES), quarantine_part("rides")),
          items=(Item("recording", ("its file (by content; an unchanged file is not read again)",)),
                 Item("validation", ("its recording's analysis", "its scenario", "the fit rows of its tyres")),
                 Item("frf", ("its recording (with input channels)", "speed and the scenario's tyres")),),
          doc="vehicle recordings (rides.csv): whole-body vibration, daily exposure, predictions checked, "
              "transfer functions and modes"),
    Stage("warehouse", reads=("parquet/*.parquet", *(quarantine_part(s) for s in QUARANTINE_PARTS), "parquet/runs/",
                              "published"),
          writes=("parquet/published/", table("quarantine"), "warehouse.duckdb"),
          doc="publish the thesis tables and the quarantine; build warehouse.duckdb"),
    Stage("report", reads=("warehouse.duckdb", "parquet/runs/", "raw-extras", "code:tyrelab.templates", "code:tyrelab.docs"),
          writes=("reports/",),
          items=(Item("table", ("its spec and the frames it shapes",)),
                 Item("figure", ("its function and the data it draws",)),),
          doc="render the static site from the warehouse"),
)}


def _covers(out: str, path: str) -> bool:
    """Whether output ``out`` (a file, or a folder ending in ``/``) is or contains ``path``."""
    return out == path or (out.endswith("/") and path.startswith(out))


def _matches(path: str, pattern: str) -> bool:
    """Whether build path ``path`` matches ``pattern`` (``*`` within one path component)."""
    a, b = PurePosixPath(path), PurePosixPath(pattern)
    return len(a.parts) == len(b.parts) and a.match(pattern)


def expand(stage: Stage, stages: dict[str, Stage] | None = None) -> tuple[str, ...]:
    """The build paths ``stage`` reads, with patterns replaced by the other stages' outputs they match."""
    stages = stages or STAGES
    out: list[str] = []
    for r in stage.build_reads:
        if "*" in r:
            out.extend(sorted(p for s in stages.values() if s.name != stage.name for p in s.writes if _matches(p, r)))
        else:
            out.append(r)
    return tuple(dict.fromkeys(out))


def may_read(stage: str, path: str, stages: dict[str, Stage] | None = None) -> bool:
    """Whether ``stage`` may read build path ``path``: one of its reads or writes (a folder holding it
    included; its own outputs, to reuse what it wrote last time).

    Examples
    --------
    >>> may_read("rides", "parquet/formula_fit.parquet"), may_read("rides", "parquet/results.parquet")
    (True, False)
    """
    s = (stages or STAGES)[stage]
    return any(_covers(p, path) for p in (*expand(s, stages), *s.writes))


def writer(path: str, stages: dict[str, Stage] | None = None) -> str | None:
    """The stage that writes build path ``path`` (or the folder holding it), or None."""
    for s in (stages or STAGES).values():
        if any(_covers(out, path) for out in s.writes):
            return s.name
    return None


def check(stages: dict[str, Stage]) -> list[str]:
    """Problems of a declaration: an output with two writers, an input no stage writes, a cycle."""
    problems = []
    owners: dict[str, str] = {}
    for s in stages.values():
        for out in s.writes:
            for other, name in owners.items():
                if _covers(other, out) or _covers(out, other):
                    problems.append(f"{out} is written by {name} and {s.name}")
            owners[out] = s.name
    for s in stages.values():
        for path in expand(s, stages):
            if writer(path, stages) is None:
                problems.append(f"{s.name} reads {path}, which no stage writes")
            elif writer(path, stages) == s.name:
                problems.append(f"{s.name} reads its own output {path}")
    try:
        topological_order(stages)
    except ValueError as exc:
        problems.append(str(exc))
    return problems


def _edges(stages: dict[str, Stage]) -> dict[str, set[str]]:
    """stage -> the stages whose outputs it reads."""
    return {s.name: {w for p in expand(s, stages) for w in [writer(p, stages)] if w and w != s.name}
            for s in stages.values()}


def topological_order(stages: dict[str, Stage]) -> tuple[str, ...]:
    """Stages in an order where each runs after every stage it reads from (ties by name).

    Raises
    ------
    ValueError
        If the stages read from each other in a cycle.
    """
    deps = _edges(stages)
    order: list[str] = []
    while len(order) < len(deps):
        ready = sorted(n for n, d in deps.items() if n not in order and d <= set(order))
        if not ready:
            raise ValueError("stages read from each other in a cycle: "
                             + ", ".join(sorted(n for n in deps if n not in order)))
        order.append(ready[0])
    return tuple(order)


def upstream(name: str, stages: dict[str, Stage] | None = None) -> set[str]:
    """Every stage whose outputs ``name`` reads, directly or through others."""
    deps = _edges(stages or STAGES)
    seen: set[str] = set()
    todo = list(deps[name])
    while todo:
        n = todo.pop()
        if n not in seen:
            seen.add(n)
            todo.extend(deps[n])
    return seen


def graph_text(stages: dict[str, Stage] | None = None) -> str:
    """The stage graph as text: per stage in :data:`ORDER`, what it reads (and from whom) and writes."""
    stages = stages or STAGES
    lines = []
    for name in topological_order(stages):
        s = stages[name]
        lines.append(f"{name}: {s.doc}")
        for r in s.reads:
            if "*" in r:
                found = sorted({writer(p, stages) for p in expand(Stage(s.name, (r,), ()), stages)} - {None})
                lines.append(f"  reads  {r}  <- {', '.join(found)}")
                continue
            w = writer(r, stages) if r in s.build_reads else None
            lines.append(f"  reads  {r}" + (f"  <- {w}" if w else ""))
        for out in s.writes:
            lines.append(f"  writes {out}")
        for item in s.items:
            lines.append(f"  item   {item}")
    return "\n".join(lines)


#: The order ``tyrelab run`` runs the stages in: derived from :data:`STAGES`.
ORDER: list[str] = list(topological_order(STAGES))
