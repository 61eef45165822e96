# PYTHON_ARGCOMPLETE_OK  (shell completion: argcomplete; see `tyrelab completion --help`)
"""tyrelab: tractor-tyre stiffness and damping from rig recordings, thesis tables, ride vibration.

Verbs (a stable contract; see docs/architecture.md):

- ``generate``             write a seeded virtual campaign
- ``run``                  every stage: raw -> warehouse -> report
- ``watch``                ``run`` now and after every change of the raw folder, in one process
- ``ingest``, ``analyse``, ... one stage
- ``sql``                  read-only query of the warehouse
- ``analyze-run``          K and C of one recording, as JSON
- ``estimate-stiffness``   the empirical formula of thesis §4.5.3
- ``natural-frequencies``  bounce/pitch frequencies of a tractor (thesis ch. 8)
- ``export-tyre``          a measured tyre as MF-Tyre ``.tir`` files and K(P), C(P) tables
- ``ride``                 seat vibration and daily exposure of a tractor scenario (TOML)
- ``exposure``             a driver's daily vibration exposure from seat recordings
- ``road``                 ISO 8608 class, r.m.s. and length of a road profile's tracks (CSV or OpenCRG)
- ``frf``                  a vehicle's transfer functions and modes from a recording with wheel inputs

Exit codes: 0 success; 3 some runs (or a manifest/catalogue) were quarantined; 2 usage or input
error (also: the build is locked by another writer, an OS error); 130 interrupted; 141 the reader of
stdout went away (e.g. piped into ``head``).

Global options (``-q``, ``-v``) go before or after the verb; a mistyped verb gets a "did you
mean"; ``analyse-run`` and ``analyze`` are aliases of ``analyze-run``. Shell completion:
``tyrelab completion bash`` (argcomplete).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import logging
import math
import os
import sys
from pathlib import Path

from . import __version__
from .io import TEXT_WIDTH, MissingExtra, fit_lines, os_error_line, printable  # noqa: F401 - also this module's, for the commands' error lines

__all__ = ["EXIT_CODES_HELP", "STAGE_HELP", "ALIASES", "cmd_completion", "cmd_generate", "cmd_run", "cmd_watch", "cmd_stage", "cmd_sql", "cmd_analyze_run", "cmd_estimate_stiffness",
    "cmd_natural_frequencies", "cmd_road", "build_parser", "main"]

EXIT_OK, EXIT_USAGE, EXIT_QUARANTINE = 0, 2, 3
#: Exit code after Ctrl-C or SIGTERM (128 + SIGINT, as shells report it).
EXIT_INTERRUPTED = 130
#: Exit code when the reader of stdout went away (``tyrelab sql … | head``): 128 + SIGPIPE, as a
#: command killed by SIGPIPE reports it; nothing is printed.
EXIT_BROKEN_PIPE = 141

log = logging.getLogger("tyrelab")


class OutputError(OSError):
    """stdout cannot be written (a full device, ``> /dev/full``, an I/O error): one line, exit 2."""


#: Bytes handed to the operating system per write of stdout.
_WRITE_BYTES = 1 << 16


def _out(text: str) -> None:
    """Write ``text`` to stdout, every byte or an error.

    Through a file descriptor, each piece goes to ``os.write`` until it is all written: a pipe
    whose reader leaves in the middle of a long write (``tyrelab sql … | head``) gives a short
    write, which Python's buffered stdout dropped without a word (the command exited 0), and then
    ``BrokenPipeError`` (exit 141). Any other failure (a full device) raises :class:`OutputError`.
    """
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):  # a captured or replaced stdout (tests, a notebook)
        fd = None
    try:
        if fd is None:
            sys.stdout.write(text)
            return
        sys.stdout.flush()
        data = memoryview(text.encode(sys.stdout.encoding or "utf-8", errors=sys.stdout.errors or "strict"))
        while len(data):
            n = os.write(fd, data[:_WRITE_BYTES])
            data = data[n:]
    except BrokenPipeError:
        raise
    except OutputError:
        raise
    except OSError as exc:
        raise OutputError(exc.errno, f"cannot write the output ({exc.strerror or exc})") from None


def _context(args):
    from .stages.base import Context

    return Context(
        raw=Path(args.raw),
        build=Path(args.build),
        force=getattr(args, "force", False),
        jobs=getattr(args, "jobs", None) or Context().jobs,
        executor=getattr(args, "executor", "local"),
        scheduler=getattr(args, "scheduler", None),
        calibration_correct=getattr(args, "calibration_correct", False),
    )


def cmd_generate(args) -> int:
    from .generate import MAX_SEED, generate_campaign

    if not 0 <= args.seed <= MAX_SEED:
        print(f"tyrelab generate: --seed must be a whole number from 0 to {MAX_SEED}, got {_typed(str(args.seed))}",
              file=sys.stderr)
        return EXIT_USAGE
    summary = generate_campaign(Path(args.out), scale=args.scale, seed=args.seed, scatter=args.scatter,
                                rides=args.rides, tyre_population=getattr(args, "tyre_population", 0))
    log.info("generate: %s", json.dumps(summary, default=str))
    return EXIT_OK


def _check_raw(args, need_campaign: bool) -> str | None:
    """One-line problem with ``--raw``, or None."""
    from .io import raw_problem  # light: the ingest stage is imported only if it runs

    raw = Path(args.raw)
    if not raw.is_dir() or need_campaign:
        return raw_problem(raw)
    return None


def _writing(args, label: str, work) -> int:
    """Run ``work()`` holding the build's write lock; a second writer, or an OS error, is one line and exit 2."""
    from .buildlock import BuildLock, BuildLocked
    from .published import PublishedTableError

    try:
        with BuildLock(args.build, f"tyrelab {label}"):
            from . import io

            io.remove_stale_temporaries(args.build)  # left by a killed writer: we are the only one now
            return work()
    except (BuildLocked, PublishedTableError) as exc:  # a thesis table in <raw>/published that does not fit
        print(f"tyrelab {label}: {printable(str(exc).splitlines()[0])}", file=sys.stderr)
    except OSError as exc:
        print(f"tyrelab {label}: {printable(os_error_line(exc))}", file=sys.stderr)
    return EXIT_USAGE


def cmd_run(args) -> int:
    from .stages import run_pipeline

    problem = _check_raw(args, need_campaign=True)
    if problem:
        print(f"tyrelab run: {printable(problem)}", file=sys.stderr)
        return EXIT_USAGE
    if getattr(args, "explain", False):  # read-only: no lock, nothing written
        from .stages import explain

        _out(explain(_context(args)) + "\n")
        return EXIT_OK

    def work() -> int:
        results = run_pipeline(_context(args))
        return EXIT_QUARANTINE if any(r.n_quarantined or r.n_rejected for r in results) else EXIT_OK

    return _writing(args, "run", work)


def cmd_watch(args) -> int:
    from .watch import WatchOptions, watch

    problems = [_check_raw(args, need_campaign=True)]
    for field_name, option, kwargs in (("interval_s", "--interval", {"interval_s": args.interval}),
                                       ("settle_s", "--settle", {"settle_s": args.settle}),
                                       ("max_runs", "--max-runs", {"max_runs": args.max_runs})):
        try:  # each option alone: every problem at once
            WatchOptions(**kwargs)
        except ValueError as exc:
            problems.append(str(exc).replace(field_name, option))
    if _refused("tyrelab watch", [p for p in problems if p]):
        return EXIT_USAGE
    options = WatchOptions(interval_s=args.interval, settle_s=args.settle, max_runs=args.max_runs)

    def work() -> int:
        runs = watch(_context(args), options)
        last = runs[-1] if runs else None
        return EXIT_USAGE if last and last.error else EXIT_QUARANTINE if last and last.quarantined else EXIT_OK

    return _writing(args, "watch", work)


def cmd_stage(args) -> int:
    from .stages import run_stage

    problem = _check_raw(args, need_campaign=args.stage == "ingest")
    if problem:
        print(f"tyrelab {args.stage}: {printable(problem)}", file=sys.stderr)
        return EXIT_USAGE

    def work() -> int:
        result = run_stage(args.stage, _context(args))
        return EXIT_QUARANTINE if result.n_quarantined or result.n_rejected else EXIT_OK

    return _writing(args, args.stage, work)


#: Share of ``--memory-limit`` a ``--format table`` result may take (it is aligned whole; csv and
#: json stream).
TABLE_SHARE = 0.25


def _print_result(fmt: str, names: list, frames, first: bool, table_bytes: int, width: int | None = None) -> None:
    """One statement's result on stdout, batch after batch (csv, json) or aligned (table, at most
    ``table_bytes`` of result)."""
    import pandas as pd

    if fmt == "json":  # one JSON array per statement, on one line
        keys = unique_keys(names)
        if keys != list(names):
            print("tyrelab sql: warning: the result has columns of the same name; their JSON keys are "
                  + ", ".join(printable(str(k)) for k in keys), file=sys.stderr)
        _out("[")
        sep = ""
        for df in frames:
            if keys != list(names):
                df = df.set_axis(keys, axis=1)
            if len(df):
                _out(sep + df.to_json(orient="records", date_format="iso", double_precision=15)[1:-1])
                sep = ","
        _out("]\n")
        return
    if not first:
        _out("\n")
    if fmt == "csv":
        header = True
        for df in frames:
            if len(df) or header:
                _out(df.to_csv(index=False, header=header))
                header = False
        if header:
            _out(pd.DataFrame(columns=names).to_csv(index=False))
        return
    held, size = [], 0
    for df in frames:
        size += int(df.memory_usage(index=False, deep=True).sum())
        if size > table_bytes:
            raise _ResultTooLarge(len(pd.concat(held)) if held else 0)
        held.append(df)
    df = pd.concat(held, ignore_index=True) if held else pd.DataFrame(columns=names)
    # for a terminal: a name or text value's control characters escaped (an ESC drives no terminal,
    # a newline forges no row); csv and json keep the values as they are (json escapes them)
    df.columns = [printable(str(c)) for c in df.columns]
    for i in range(df.shape[1]):
        if df.dtypes.iloc[i] == object or isinstance(df.dtypes.iloc[i], pd.StringDtype):
            df.isetitem(i, df.iloc[:, i].map(lambda v: printable(v) if isinstance(v, str) else v))
    if df.empty:  # not pandas' "Empty DataFrame / Columns: [...] / Index: []"
        _out(f"no rows (columns: {', '.join(map(str, df.columns))})\n" if len(df.columns) else "no rows\n")
    else:
        _out(df.to_string(index=False, line_width=width) + "\n")  # wider than width: blocks of columns


def unique_keys(names) -> list[str]:
    """Column names as JSON keys: a repeated name gets ``_2``, ``_3``, … (a name not taken).

    Examples
    --------
    >>> unique_keys(["a", "a", "a_2", "b"])
    ['a', 'a_3', 'a_2', 'b']
    """
    names = [str(n) for n in names]
    taken, out = set(names), []
    seen = set()
    for n in names:
        if n in seen:
            k = 2
            while f"{n}_{k}" in taken:
                k += 1
            taken.add(f"{n}_{k}")
            n = f"{n}_{k}"
        seen.add(n)
        out.append(n)
    return out


class _ResultTooLarge(Exception):
    """A ``--format table`` result beyond its share of ``--memory-limit``."""


def cmd_sql(args) -> int:
    import duckdb

    from .warehouse import QueryLimits, QueryTimeout, WriteRefused, error_line, iter_query, memory_bound

    try:
        limits = QueryLimits(args.memory_limit, args.max_spill, args.timeout or None)
    except ValueError as exc:
        text = str(exc)
        for field_name, option in (("memory_limit_bytes", "--memory-limit"), ("spill_limit_bytes", "--max-spill"),
                                   ("timeout_s", "--timeout")):
            text = text.replace(field_name, option)
        print(f"tyrelab sql: {printable(text)}", file=sys.stderr)
        return EXIT_USAGE
    if (args.query is None) == (args.describe is None):
        print("tyrelab sql: give a query or --describe TABLE (one of them)", file=sys.stderr)
        return EXIT_USAGE
    if args.describe is not None:
        return _describe_table(args, limits)
    # Several statements: each result is printed, in order (a blank line between tables/CSV, one JSON
    # array per line), as it comes: a result is never held whole (but for --format table, which is
    # aligned whole: at most TABLE_SHARE of --memory-limit), and the process's memory is bounded by
    # --memory-limit (warehouse.memory_bound).
    try:
        with memory_bound(limits.memory_limit_bytes):
            for i, (names, frames) in enumerate(iter_query(Path(args.build) / "warehouse.duckdb", args.query, limits)):
                _print_result(args.format, names, frames, i == 0, int(TABLE_SHARE * limits.memory_limit_bytes),
                              None if args.wide else TEXT_WIDTH)
    except (WriteRefused, FileNotFoundError) as exc:
        print(f"tyrelab sql: {printable(exc)}", file=sys.stderr)
        return EXIT_USAGE
    except QueryTimeout as exc:
        print(f"tyrelab sql: {printable(f'{exc}; --timeout SECONDS changes it (0: none)')}", file=sys.stderr)
        return EXIT_USAGE
    except _ResultTooLarge as exc:
        print(f"tyrelab sql: the result is larger than --format table holds within --memory-limit "
              f"{args.memory_limit} bytes (stopped after {exc.args[0]} rows); --format csv or json stream it, or "
              "add a LIMIT", file=sys.stderr)
        return EXIT_USAGE
    except (duckdb.OutOfMemoryException, MemoryError) as exc:
        first = str(exc).splitlines()[0] if str(exc) else "out of memory"
        print(f"tyrelab sql: {first} (limits: --memory-limit {args.memory_limit} bytes, "
              f"--max-spill {args.max_spill} bytes; raise them, e.g. --memory-limit 8GB)", file=sys.stderr)
        return EXIT_USAGE
    except (BrokenPipeError, OutputError):
        raise
    except duckdb.Error as exc:  # the user's query errors: a misspelt name gets the closest the warehouse has
        print(f"tyrelab sql: {type(exc).__name__}: {error_line(Path(args.build), exc)}", file=sys.stderr)
        return EXIT_USAGE
    except Exception as exc:  # noqa: BLE001 - DuckDB errors are the user's query errors
        print(f"tyrelab sql: {printable(f'{type(exc).__name__}: {str(exc).splitlines()[0]}')}", file=sys.stderr)
        return EXIT_USAGE
    return EXIT_OK


def _describe_table(args, limits) -> int:
    """``tyrelab sql --describe TABLE``: the table's columns (DuckDB's DESCRIBE) with their unit and
    meaning from the legend (:func:`tyrelab.legend.describe`)."""
    import re

    import pandas as pd

    from .legend import describe
    from .warehouse import WriteRefused, query_all

    name = args.describe
    if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name):
        print(f"tyrelab sql: --describe {name!r}: not a table name", file=sys.stderr)
        return EXIT_USAGE
    try:
        present = query_all(Path(args.build) / "warehouse.duckdb",
                            f"SELECT column_name, data_type FROM information_schema.columns WHERE table_name = '{name}' "
                            "ORDER BY ordinal_position", limits)[-1]
    except (WriteRefused, FileNotFoundError) as exc:
        print(f"tyrelab sql: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except Exception as exc:  # noqa: BLE001 - DuckDB errors are the user's errors (an unreadable warehouse)
        print(f"tyrelab sql: {type(exc).__name__}: {str(exc).splitlines()[0]}", file=sys.stderr)
        return EXIT_USAGE
    if present.empty:
        print(f"tyrelab sql: --describe {name}: no such table in {Path(args.build) / 'warehouse.duckdb'}",
              file=sys.stderr)
        return EXIT_USAGE
    rows = describe(name, list(present["column_name"]))
    df = pd.DataFrame({"column": [r[0] for r in rows], "type": present["data_type"].str.lower().to_list(),
                       "unit": [r[1] for r in rows], "meaning": [r[2] or "–" for r in rows]})
    _print_result(args.format, list(df.columns), [df], True, int(TABLE_SHARE * limits.memory_limit_bytes))
    return EXIT_OK


def cmd_analyze_run(args) -> int:
    from .api import analyze_recording
    from .rawformat import SAMPLE_RATE_RANGE_Hz, RunFileError

    problems = _option_problems(args, ("axle_mass",))
    if args.sample_rate is not None and not SAMPLE_RATE_RANGE_Hz[0] <= args.sample_rate <= SAMPLE_RATE_RANGE_Hz[1]:
        problems.append(f"--sample-rate must be within {SAMPLE_RATE_RANGE_Hz[0]:g} to {SAMPLE_RATE_RANGE_Hz[1]:g} Hz "
                        f"(raw format v1), got {args.sample_rate:g}")
    if _refused("tyrelab analyze-run", problems):
        return EXIT_USAGE
    try:
        out = analyze_recording(Path(args.file), args.axle_mass, sample_rate_Hz=args.sample_rate).to_dict()
    except (RunFileError, ValueError) as exc:  # ValueError: e.g. no time_s column and no --sample-rate
        text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        text = text.replace("sample_rate_Hz is needed", "--sample-rate HZ is needed")
        print(f"tyrelab analyze-run: {printable(args.file)}: {printable(text)}", file=sys.stderr)
        return EXIT_USAGE
    _out(json.dumps(out, indent=2) + "\n")
    if out["stiffness_N_per_m"] is None and not out["qc_ok"]:  # e.g. excitation outside the band: refused
        print(f"tyrelab analyze-run: {printable(args.file)}: {'; '.join(out['qc_reasons'])}", file=sys.stderr)
        return EXIT_QUARANTINE
    return EXIT_OK


def _warn(prog: str, warnings) -> None:
    """Print range warnings on stderr, one line each (the result still goes to stdout)."""
    for w in warnings:
        print(f"{prog}: {printable(f'warning: {w}')}", file=sys.stderr)


#: Option ranges of the verbs that take a tractor's or a tyre's numbers: the ``dest`` of each option
#: and the :data:`tyrelab.vehicle.scenario_limits.LIMITS` key whose range (what the models are built
#: for) it shares with the scenario key of the same meaning.
OPTION_LIMITS = {
    "mass": "tractor.mass_kg", "pitch_inertia": "tractor.pitch_inertia_kg_m2",
    "front_distance": "tractor.front_distance_m", "rear_distance": "tractor.rear_distance_m",
    "pressure": "pressure_bar", "front_pressure": "pressure_bar", "rear_pressure": "pressure_bar",
    "age": "age_years", "front_stiffness": "stiffness_kN_per_m", "rear_stiffness": "stiffness_kN_per_m",
    "front_stiffness_u": "stiffness_u_kN_per_m", "rear_stiffness_u": "stiffness_u_kN_per_m",
    "axle_mass": "axle.mass_kg", "track_width_m": "tractor.front_track_m",
    "lateral_offset_m": "surface.lateral_offset_m", "start_m": "surface.start_m", "length_m": "surface.length_m",
    "speed": "frf_speed_km_h", "max_frequency": "frf_max_Hz",
}


def _option_problems(args, dests) -> list[str]:
    """One line per numeric option of ``dests`` outside its range (:data:`OPTION_LIMITS`), naming it:
    checked before any work, every problem at once (``--mass 1e308`` would give 1.8e-152 Hz)."""
    from . import _validate
    from .api import _argument_limits

    limits = _argument_limits()  # the library's arguments share them
    problems = []
    for dest in dests:
        value = getattr(args, dest, None)
        for v in value if isinstance(value, list) else [] if value is None else [value]:
            low, high, unit = limits[OPTION_LIMITS[dest]]
            try:
                _validate.in_range("--" + dest.replace("_", "-"), v, low, high, unit)
            except ValueError as exc:
                problems.append(f"{exc} (the range the model is built for)" if "within" in str(exc) else str(exc))
    return problems


def _refused(prog: str, problems: list[str]) -> bool:
    """Print ``problems`` one line each on stderr (True if there were any)."""
    for problem in problems:
        print(f"{prog}: {printable(problem)}", file=sys.stderr)
    return bool(problems)


def _stiffness_model(prog: str, build: str | None):
    """The thesis' stiffness model, or with ``build`` the one fitted to that warehouse's tyres
    (table ``formula_fit``); ValueError with one line for a missing or unfitted warehouse."""
    from .published import thesis_stiffness_model
    from .tyre.models import build_stiffness_model
    from .warehouse import query

    thesis = thesis_stiffness_model()
    if build is None:
        return thesis
    db = Path(build) / "warehouse.duckdb"
    try:
        table = query(db, "SELECT * FROM formula_fit")
    except FileNotFoundError as exc:
        raise ValueError(str(exc)) from None
    except Exception as exc:  # noqa: BLE001 - a warehouse without the table
        raise ValueError(f"{db}: {str(exc).splitlines()[0]} (run 'tyrelab run' first)") from None
    try:
        return build_stiffness_model(table, thesis)
    except ValueError as exc:
        raise ValueError(f"{db}: {exc}") from None


def cmd_estimate_stiffness(args) -> int:
    from .tyre.sizes import TyreSizeError
    from .tyre.stiffness import estimate_stiffness

    prog = "tyrelab estimate-stiffness"
    if _refused(prog, _option_problems(args, ("pressure", "age"))):
        return EXIT_USAGE
    try:
        model = _stiffness_model(prog, getattr(args, "build", None))
        est = estimate_stiffness(
            args.size, args.pressure, args.age, undriven_front=args.front_undriven, water_ballast=args.water_ballast,
            model=model,
        )
    except (TyreSizeError, ValueError) as exc:
        print(f"{prog}: {printable(exc)}", file=sys.stderr)
        return EXIT_USAGE
    if not math.isfinite(est.stiffness_kN_per_m):
        print(f"{prog}: --pressure {args.pressure:g} bar (with --size {printable(args.size)}): the formula gives no finite "
              "stiffness", file=sys.stderr)
        return EXIT_USAGE
    _warn(prog, est.warnings)
    if args.json or args.format == "json":
        from .io import json_safe

        _out(json.dumps(json_safe(est.to_dict()), indent=2, ensure_ascii=False, allow_nan=False) + "\n")
    else:
        pi = est.prediction_interval_kN_per_m
        _out(f"{est.stiffness_kN_per_m:.1f} kN/m" + (
            f" (95 % prediction interval {pi[0]:.1f} to {pi[1]:.1f} kN/m)" if pi else " (no prediction interval: "
            + est.prediction_interval_basis.removeprefix("none: ") + ")") + "\n")
    return EXIT_OK


def cmd_natural_frequencies(args) -> int:
    from .tyre.sizes import TyreSizeError
    from .vehicle.bounce_pitch import tractor_natural_frequencies

    prog = "tyrelab natural-frequencies"
    if _refused(prog, _option_problems(args, ("mass", "pitch_inertia", "front_distance", "rear_distance",
                                              "front_pressure", "rear_pressure", "age", "front_stiffness",
                                              "rear_stiffness", "front_stiffness_u", "rear_stiffness_u"))):
        return EXIT_USAGE
    try:
        out = tractor_natural_frequencies(
            args.mass, args.pitch_inertia, args.front_distance, args.rear_distance,
            args.front_tyre, args.front_pressure, args.rear_tyre, args.rear_pressure,
            front_traction=args.front_traction, front_water_ballast=args.front_water_ballast,
            age_years=args.age, front_stiffness_kN_per_m=args.front_stiffness,
            rear_stiffness_kN_per_m=args.rear_stiffness, front_stiffness_u_kN_per_m=args.front_stiffness_u,
            rear_stiffness_u_kN_per_m=args.rear_stiffness_u,
            stiffness_model=_stiffness_model(prog, getattr(args, "build", None)),
        )
    except (TyreSizeError, ValueError) as exc:
        print(f"{prog}: {printable(exc)}", file=sys.stderr)
        return EXIT_USAGE
    _warn(prog, out.get("warnings", ()))
    from .io import json_safe

    _out(json.dumps(json_safe(out), indent=2, ensure_ascii=False) + "\n")  # a nodal point at infinity: null
    return EXIT_OK


def cmd_export_tyre(args) -> int:
    from .export import export_tyre
    from .tyre.sizes import TyreSizeError

    prog = "tyrelab export-tyre"
    if _refused(prog, _option_problems(args, ("pressure",))):
        return EXIT_USAGE
    try:
        export, written = export_tyre(Path(args.build) / "warehouse.duckdb", args.tyre_id, args.pressure, args.out)
    except (LookupError, TyreSizeError, ValueError) as exc:
        print(f"{prog}: {printable(str(exc).splitlines()[0])}", file=sys.stderr)
        return EXIT_USAGE
    except OSError as exc:
        if isinstance(exc, FileNotFoundError) and not exc.filename:  # no warehouse yet
            print(f"{prog}: {printable(exc)}", file=sys.stderr)
        else:  # a folder in the way, a full disk, ulimit -f: no file of the set was replaced
            print(f"{prog}: {printable(f'{os_error_line(exc)} (nothing written)')}", file=sys.stderr)
        return EXIT_USAGE
    _warn(prog, export.warnings)
    for path in written:
        _out(f"{printable(path)}\n")
    return EXIT_OK


def _key_suggestion(problem: str) -> str:
    """A scenario problem naming a key that does not exist (``--set``, a TOML key), with the closest
    scenario keys: ``…; did you mean 'seat.damping_ratio'?``; any other problem as it is."""
    import re

    from .vehicle.scenario import key_table
    from .warehouse import did_you_mean

    m = (re.search(r"'([\w.]+)' is not a numeric scenario key", problem)
         or re.search(r"unknown key '([\w.]+)'", problem))
    if not m:
        return problem
    table = key_table()
    if "numeric scenario key" in problem:
        table = table[table["type"].astype(str).str.contains("number|integer")]
    keys = [f"{sec}.{key}" if sec else key for sec, key in table[["section", "key"]].itertuples(index=False)]
    close = did_you_mean(m.group(1), keys)
    return problem + ("; did you mean " + " or ".join(f"'{c}'" for c in close) + "?" if close else "")


def cmd_ride(args) -> int:
    from types import SimpleNamespace

    from .api import ride_sweep
    from .report.ride_page import dumps, format_table, write_outputs
    from .vehicle.ride import result_json
    from .scenario_io import ScenarioError, load_scenario

    try:
        scenario = load_scenario(args.scenario, confine=False)  # the user's own file: any profile path
    except ScenarioError as exc:
        for problem in exc.problems:
            print(f"tyrelab ride: {printable(exc.path)}: {printable(_key_suggestion(problem))}", file=sys.stderr)
        return EXIT_USAGE
    from .executor import map_batches

    ctx = SimpleNamespace(executor=args.executor, jobs=args.jobs, scheduler=args.scheduler)
    used = []

    def mapped(task, items):
        used.append(len(items))
        return map_batches(task, items, ctx)

    try:
        results = ride_sweep(scenario, front_pressures_bar=args.front_pressure, rear_pressures_bar=args.rear_pressure,
                             speeds_km_h=args.speeds, sets=args.set or [], build=args.build,
                             map_fn=mapped,
                             with_spectra="nominal" if args.out else False,
                             max_variants=args.max_variants, max_samples=args.max_samples, method=args.method,
                             max_rows=args.max_rows)
    except ScenarioError as exc:  # a swept value the scenario refuses: every problem, one line each
        for problem in exc.problems:
            print(f"tyrelab ride: {printable(exc.path)}: {printable(_key_suggestion(problem))}", file=sys.stderr)
        return EXIT_USAGE
    except ValueError as exc:
        print(f"tyrelab ride: {printable(args.scenario)}: {printable(_key_suggestion(str(exc)))}", file=sys.stderr)
        return EXIT_USAGE
    except OSError as exc:  # e.g. --scheduler unreachable
        print(f"tyrelab ride: {printable(os_error_line(exc))}", file=sys.stderr)
        return EXIT_USAGE
    if not used and (args.executor != "local" or args.scheduler):  # said, not silently ignored
        what = f"--executor {args.executor}" + (f" --scheduler {printable(args.scheduler)}" if args.scheduler else "")
        print(f"tyrelab ride: note: {what} was not used: every variant ran in this process (one variant, or "
              "the frequency domain's rows)", file=sys.stderr)
    doc = result_json(results)
    if args.out:
        try:
            paths = write_outputs(results, args.out)
        except OSError as exc:  # neither file replaced (write_outputs writes them as one set)
            print(f"tyrelab ride: {printable(f'--out {args.out}: {os_error_line(exc)} (nothing written)')}", file=sys.stderr)
            return EXIT_USAGE
        log.info("ride: wrote %s and %s", paths["json"], paths["html"])
    _out(dumps(doc) if args.format == "json" else format_table(doc, None if args.wide else TEXT_WIDTH))
    return EXIT_OK


def cmd_frf(args) -> int:
    import numpy as np

    from .api import vehicle_frf
    from .io import json_safe
    from .rawformat import RunFileError
    from .scenario_io import ScenarioError

    prog = "tyrelab frf"
    if _refused(prog, _option_problems(args, ("speed", "max_frequency"))):
        return EXIT_USAGE
    try:
        r = vehicle_frf(Path(args.file), speed_km_h=args.speed, scenario=args.scenario)
    except ScenarioError as exc:
        print(f"{prog}: --scenario {printable(args.scenario)}: {printable('; '.join(exc.problems))}", file=sys.stderr)
        return EXIT_USAGE
    except (RunFileError, ValueError, OSError) as exc:
        text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        print(f"{prog}: {printable(args.file)}: {printable(text)}", file=sys.stderr)
        return EXIT_USAGE
    if args.format == "json":
        _out(json.dumps(json_safe(r.to_json(args.max_frequency)), indent=2) + "\n")
    else:
        _out("\n".join(fit_lines(frf_table(r, args.max_frequency).splitlines(), None if args.wide else TEXT_WIDTH))
             + "\n")
    e = r.estimate
    band = (e.frequency_Hz >= 0.5) & (e.frequency_Hz <= 12.0)
    if band.any() and e.ill_conditioned[band].all():
        delays = e.input_delay_s if e.input_delay_s is not None else np.full(len(r.inputs), np.nan)
        why = (f"condition number {float(np.nanmedian(e.condition_number[band])):.3g}: inputs correlated as on a road?"
               if not np.isfinite(delays).any() else "one input is another delayed, as on a road: " + ", ".join(
                   f"{inp} {d:+.3g} s" for inp, d in zip(r.inputs, delays) if np.isfinite(d)))
        print(f"{prog}: {printable(args.file)}: the inputs cannot be separated in any bin of 0.5-12 Hz ({why}): "
              "no mode fitted", file=sys.stderr)
        return EXIT_QUARANTINE
    return EXIT_OK


def frf_table(r, max_Hz: float = 20.0) -> str:
    """``tyrelab frf --format table``: the modes per output, then per input and output the peak
    ``|H|``, its frequency and the share of bins flagged."""
    import numpy as np

    from .measurement.frf import frf_unit

    e = r.estimate
    lines = [f"{len(r.inputs)} inputs, {len(r.outputs)} outputs; {r.duration_s:.0f} s at {r.sample_rate_Hz:g} Hz, "
             f"bins {e.frequency_Hz[1]:.4g} Hz, n_d {e.n_d:.1f}; speed {r.speed_km_h:g} km/h", "",
             "modes (damped frequency, damping ratio, 95 % intervals)",
             f"{'output':<22}{'f_Hz':>8}{'f_95%_Hz':>18}{'zeta':>8}{'zeta_95%':>16}"]
    for row in r.mode_rows():
        lines.append(f"{row['output']:<22}{row['frequency_Hz']:>8.3f}"
                     f"{row['frequency_ci95_low_Hz']:>9.3f}-{row['frequency_ci95_high_Hz']:<8.3f}"
                     f"{row['damping_ratio']:>8.3f}{row['damping_ci95_low']:>8.3f}-{row['damping_ci95_high']:<7.3f}")
    if not r.mode_rows():
        lines.append("(none fitted)")
    compared = [v for v in getattr(r, "validation", []) if v.get("mode") is not None]
    if compared:  # --scenario: its model's nearest mode beside each measured one
        lines += ["", "the scenario's model at this speed (nearest mode; in = inside the measured 95 % interval)",
                  f"{'output':<22}{'mode':>5}  {'model mode':<14}{'f_Hz':>8}{'in':>5}{'zeta':>8}{'in':>5}"]
        for v in compared:
            lines.append(f"{v['output']:<22}{v['mode']:>5}  {str(v['predicted_mode']):<14}"
                         f"{v['predicted_frequency_Hz']:>8.3f}{('yes' if v['frequency_in_interval'] else 'no'):>5}"
                         f"{v['predicted_damping_ratio']:>8.3f}{('yes' if v['damping_in_interval'] else 'no'):>5}")
    lines += ["", "FRFs over 0.5-12 Hz", f"{'input':<26}{'output':<22}{'peak |H|':>10}{'at_Hz':>8}{'coh':>6}"
              f"{'flagged':>9}{'masked':>8}  unit"]
    band = (e.frequency_Hz >= 0.5) & (e.frequency_Hz <= min(12.0, max_Hz))
    for k, out in enumerate(r.outputs):
        for j, inp in enumerate(r.inputs):
            h = np.abs(e.h[band, k, j])
            ok = np.isfinite(h)
            i = int(np.nanargmax(np.where(ok, h, -1.0))) if ok.any() else 0
            lines.append(f"{inp:<26}{out:<22}{(h[i] if ok.any() else float('nan')):>10.4g}"
                         f"{e.frequency_Hz[band][i]:>8.3f}{float(np.nanmedian(e.multiple_coherence[band, k])):>6.2f}"
                         f"{100 * float(e.ill_conditioned[band, j].mean()):>8.0f}%"
                         f"{100 * float(r.masked[band].mean()):>7.0f}%  {frf_unit(out)}")
    return "\n".join(lines) + "\n"


def cmd_road(args) -> int:
    """``tyrelab road FILE``: the ISO 8608 class, r.m.s. and length of each track of a profile CSV
    or an OpenCRG road (:func:`tyrelab.api.road_class`)."""
    from .api import road_class

    path = Path(args.file)
    if _refused("tyrelab road", _option_problems(args, ("track_width_m", "lateral_offset_m", "start_m", "length_m"))):
        return EXIT_USAGE
    try:
        doc = road_class(path, track_width_m=args.track_width_m, lateral_offset_m=args.lateral_offset_m,
                         start_m=args.start_m, length_m=args.length_m, fill_missing=args.fill_missing)
    except ValueError as exc:
        text = str(exc)
        if path.suffix.lower() == ".crg":  # the scenario's keys are this verb's options
            for key, option in (("surface.lateral_offset_m", "--lateral-offset-m"), ("surface.start_m", "--start-m"),
                                ("surface.length_m", "--length-m"), ("surface.file: ", ""),
                                ("fill_missing = true", "--fill-missing"),
                                ("the track widths and the offset", "--track-width-m and --lateral-offset-m")):
                text = text.replace(key, option)
        text = text if text.startswith((str(path), printable(path))) else f"{path}: {text}"
        print(f"tyrelab road: {printable(text)}", file=sys.stderr)  # a name's control characters escaped
        return EXIT_USAGE
    if args.format == "json":
        _out(json.dumps(doc, indent=2) + "\n")
    else:
        lines = [f"{printable(path)}: ISO 8608 class from G_d(n0) fitted with waviness 2"]
        for name, c in doc["tracks"].items():
            where = f" (v = {doc['lateral_position_m'][name]:g} m)" if "lateral_position_m" in doc else ""
            g0 = f"G_d(n0) = {c['g0_m3']:.3g} m³" if c["g0_m3"] else "G_d(n0) not resolved (too short or coarse)"
            lines.append(f"  {name}{where}: class {c['class'] or '-'}, {g0}, r.m.s. {c['rms_m'] * 1000:.2f} mm, "
                         f"length {c['length_m']:g} m")
        _out("\n".join(fit_lines(lines, None if args.wide else TEXT_WIDTH)) + "\n")
    return EXIT_OK


def cmd_completion(args) -> int:
    import argcomplete

    _out(argcomplete.shellcode(["tyrelab"], shell=args.shell))
    return EXIT_OK


def cmd_exposure(args) -> int:
    from .exposure import RecordingProblem, Task, assess, format_table
    from .io import json_safe, printable
    from .vehicle.daily_exposure import HOURS_TOLERANCE_H, MAX_HOURS_PER_DAY, hours_problem

    prog = "tyrelab exposure"
    if bool(args.file) == bool(args.task):
        print(f"{prog}: give either FILE [--hours H] or one or more --task NAME FILE HOURS", file=sys.stderr)
        return EXIT_USAGE
    tasks, problems = [], []
    for name, file, hours in args.task or [(Path(args.file).stem, args.file, args.hours)]:
        problem = hours_problem(hours)
        if problem:
            problems.append(f"--hours {hours!r}: {problem}" if not args.task else
                            f"task {printable(name)}: HOURS {printable(hours)!r}: {problem}")
            h = math.nan
        else:
            h = float(hours)
        tasks.append(Task(name, Path(file), h))
    if len({t.name for t in tasks}) < len(tasks):
        problems.append("task names must differ")
    total = sum(t.hours for t in tasks)
    if not problems and total > MAX_HOURS_PER_DAY + HOURS_TOLERANCE_H:
        problems.append(f"the tasks add up to {total:g} h, more than a day ({MAX_HOURS_PER_DAY:g} h)")
    if problems:
        for line in problems:
            print(f"{prog}: {printable(line)}", file=sys.stderr)
        return EXIT_USAGE
    try:
        doc = json_safe(assess(tasks))
    except RecordingProblem as exc:
        for line in exc.lines:
            print(f"{prog}: {printable(line)}", file=sys.stderr)
        return EXIT_USAGE if exc.usage else EXIT_QUARANTINE
    except ValueError as exc:  # a value the analysis refuses: one line, never a traceback
        print(f"{prog}: {printable(str(exc).splitlines()[0] if str(exc) else type(exc).__name__)}", file=sys.stderr)
        return EXIT_QUARANTINE
    _warn(prog, doc["warnings"])
    _out(json.dumps(doc, indent=2, ensure_ascii=False) + "\n" if args.format == "json"
         else format_table(doc, None if args.wide else TEXT_WIDTH))
    return EXIT_QUARANTINE if str(doc.get("verdict", "")).startswith("no verdict") else EXIT_OK


def _typed(text: str) -> str:
    """``text`` as a bad option value is shown: at most about 40 characters (``1`` and 400 zeros is
    not printed whole)."""
    return text if len(text) <= 40 else f"{text[:18]}…{text[-18:]} ({len(text)} characters)"


def _finite(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{_typed(text)!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{_typed(text)} is not a finite number")
    return value


def _positive(text: str) -> float:
    """argparse type: a finite float > 0."""
    value = _finite(text)
    if not value > 0:
        raise argparse.ArgumentTypeError(f"{_typed(text)} is not a positive number")
    return value


def _integer(text: str) -> int:
    """argparse type: a whole number (its range is the command's to check, in one line with the others)."""
    try:
        return int(text)
    except ValueError:  # also Python's limit of 4300 digits
        raise argparse.ArgumentTypeError(f"{_typed(text)!r} is not a whole number") from None


def _population(text: str) -> int:
    """argparse type: a tyre population size, an integer 0-99."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{_typed(text)} is not an integer") from None
    if not 0 <= value <= 99:
        raise argparse.ArgumentTypeError(f"{_typed(text)} is not from 0 to 99")
    return value


def _non_negative(text: str) -> float:
    """argparse type: a finite float >= 0."""
    value = _finite(text)
    if not value >= 0:
        raise argparse.ArgumentTypeError(f"{_typed(text)} is negative")
    return value


#: Most worker processes ``--jobs`` may ask for (each holds a Python with numpy, scipy, pandas: ~150 MB).
MAX_JOBS = 256


def _whole(high: int):
    """argparse type: a whole number from 1 to ``high``."""
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{_typed(text)!r} is not a whole number") from None
        if not 1 <= value <= high:
            raise argparse.ArgumentTypeError(f"{_typed(text)} is not from 1 to {high}")
        return value
    return parse


#: argparse type of ``--jobs``: 1 to :data:`MAX_JOBS`.
_jobs = _whole(MAX_JOBS)


def _size(text: str) -> int:
    """argparse type: a size in bytes (``512MB``, ``2GiB``, ``0``)."""
    from .warehouse import parse_size

    try:
        return parse_size(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


#: ``tyrelab --help``: what the command is for and how it is used.
DESCRIPTION = """tyrelab: tractor-tyre stiffness and damping from rig recordings, the 1991 thesis' tables
reproduced, and the ride vibration a driver gets (ISO 2631-1, EU 2002/44/EC).

  tyrelab generate --out raw/demo          a seeded virtual campaign to try it on
  tyrelab run --raw raw/demo               every stage: raw -> build/warehouse.duckdb -> build/reports/
  tyrelab sql "SELECT * FROM table_iii"    query the warehouse (read-only)
  tyrelab ride raw/scenarios/mf698t.toml   seat vibration and daily exposure of one tractor

Options of a verb: tyrelab VERB --help. -q/-v work before or after the verb."""

#: What every ``--help`` ends with.
EXIT_CODES_HELP = """exit codes:
  0    success
  2    usage or input error (one line on stderr naming the file, key or option); also: the
       build is locked by another writer, an operating-system error
  3    done, but some runs (or a manifest or tyre catalogue) were quarantined
  130  interrupted (Ctrl-C or SIGTERM)
  141  the reader of the output went away (e.g. piped into head)"""

#: One line per stage verb (``tyrelab <stage> --help``).
STAGE_HELP = {
    "ingest": "validate the raw campaigns against the schemas and convert each run to Parquet (quarantines bad files)",
    "analyse": "K and C of every measurement run from its tyre force and axle acceleration (thesis §3.2-3.5), QC",
    "calibrate": "force-plate check of each day's load-beam calibration (thesis §3.6); flags runs of failed days",
    "regress": "per-tyre stiffness and damping fits, Tables III-X, the size regressions and the formula (ch. 4-5)",
    "simulate": "carriage and tractor ride simulations, Tables XI-XX, ride scenarios and ISO 2631 exposure (ch. 6-8)",
    "warehouse": "store every table and the thesis' published tables in build/warehouse.duckdb",
    "report": "render the static report site build/reports/ from the warehouse",
}

def _stage_help(name: str) -> str:
    """The help of a stage verb: :data:`STAGE_HELP`, else the stage's declared ``doc`` (dag.STAGES)."""
    from .stages.dag import STAGES

    return STAGE_HELP.get(name) or STAGES[name].doc


#: Verb aliases (``tyrelab analyse-run`` = ``tyrelab analyze-run``).
ALIASES = {"analyze-run": ["analyse-run", "analyze"]}


class _Parser(argparse.ArgumentParser):
    """argparse with "did you mean" for a mistyped verb or choice, the exit codes in ``--help``, and
    a usage error in one line on stderr (exit 2)."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("formatter_class", argparse.RawDescriptionHelpFormatter)
        kwargs.setdefault("epilog", EXIT_CODES_HELP)
        super().__init__(*args, **kwargs)

    def error(self, message: str):
        import difflib
        import re

        m = re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)", message)
        if m:
            choices = re.findall(r"'([^']*)'", m.group(2))
            close = difflib.get_close_matches(m.group(1), choices, n=3, cutoff=0.6)
            if not close:  # e.g. "analyse-run": the part before a dash or a spelling variant
                close = [c for c in choices if c.replace("analyse", "analyze") == m.group(1).replace("analyse", "analyze")]
            what = "verb" if message.startswith(("argument VERB", "argument command")) else "choice"
            message = f"unknown {what} '{m.group(1)}'" + (
                f"; did you mean {' or '.join(repr(c) for c in close)}?" if close else
                f" (choose from {', '.join(choices)})")
        # one line naming the option (the usage block is --help's): a bad value reads as every other refusal
        self.exit(2, f"{self.prog}: error: {printable(message)} (options: {self.prog} --help)\n")


def _global_options(parser: argparse.ArgumentParser, on_verb: bool) -> None:
    """``-q``/``--quiet`` and ``-v``/``--verbose``: on the main parser with their defaults, on each
    verb with none (``SUPPRESS``), so that either place sets them and a verb never resets them."""
    default = argparse.SUPPRESS if on_verb else False
    group = parser.add_mutually_exclusive_group()
    group.add_argument("-q", "--quiet", action="store_true", default=default,
                       help="only warnings and errors (no progress bars)")
    group.add_argument("-v", "--verbose", action="store_true", default=default,
                       help="also debug messages (why each stage runs, cache decisions)")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (exposed for tests and documentation)."""
    from .stages import ORDER

    p = _Parser(prog="tyrelab", description=DESCRIPTION)
    p.add_argument("--version", action="version", version=f"tyrelab {__version__}")
    _global_options(p, on_verb=False)
    sub = p.add_subparsers(dest="command", required=True, metavar="VERB", parser_class=_Parser)

    g = sub.add_parser("generate", help="write a seeded virtual campaign (manifest.csv + runs)")
    g.add_argument("--out", required=True, help="campaign folder to write")
    g.add_argument("--scale", choices=["small", "full"], default="small",
                   help="small: ~190 runs, a build in about a minute (default); full: the whole virtual campaign")
    g.add_argument("--seed", type=_integer, default=1991,
                   help="random seed, 0 to 2^63-1: the same seed gives the same bytes (default 1991)")
    g.add_argument("--no-scatter", dest="scatter", action="store_false",
                   help="no run-to-run / day-to-day tyre scatter (thesis §3.6 repeatability is on by default: "
                        "K 2 %% + 1.5 %% per day, C 4 %% + 3 %% per day, standard deviations)")
    g.add_argument("--no-rides", dest="rides", action="store_false",
                   help="no seat recordings of virtual tractors (rides.csv, rides/; written by default)")
    g.add_argument("--tyre-population", type=_population, default=0, metavar="N",
                   help="measure N (1-99) generated tyres whose true stiffness follows other coefficients than the "
                        "thesis' formula, instead of the thesis' programme (tyres.csv and generator.json record them)")
    g.set_defaults(func=cmd_generate)

    def io_options(sp):
        sp.add_argument("--raw", default="raw", help="raw data folder (default raw/)")
        sp.add_argument("--build", default="build", help="output folder (default build/)")
        sp.add_argument("--force", action="store_true", help="recompute everything")
        sp.add_argument("--jobs", type=_jobs, default=None, help="worker processes (default: cores)")
        sp.add_argument("--executor", choices=["local", "dask"], default="local",
                        help="local: worker processes on this machine (default); dask: a dask.distributed cluster")
        sp.add_argument("--scheduler", default=None, help="dask scheduler address (with --executor dask)")
        sp.add_argument("--calibration-correct", action="store_true",
                        help="correct runs by their day's force-plate transfer function (thesis §3.6)")

    r = sub.add_parser("run", help="run every stage: raw -> warehouse -> report")
    io_options(r)
    r.add_argument("--explain", action="store_true",
                   help="print the plan (each stage, why it will or will not run) and the stage graph; run nothing")
    r.set_defaults(func=cmd_run)
    w = sub.add_parser("watch", help="run every stage now and again whenever the raw folder changes "
                                     "(one process: the libraries are loaded once)")
    io_options(w)
    w.add_argument("--interval", type=float, default=1.0, help="seconds between looks at the raw folder (default 1)")
    w.add_argument("--settle", type=float, default=1.0,
                   help="act on a change once the raw folder has stayed unchanged this many seconds (default 1)")
    w.add_argument("--max-runs", type=_integer, default=None, help="stop after this many pipeline runs (default: until Ctrl-C)")
    w.set_defaults(func=cmd_watch)
    for name in ORDER:
        s = sub.add_parser(name, help=_stage_help(name),
                           description=f"{_stage_help(name)} (this stage only; "
                                       "'tyrelab run' runs every stage that is out of date)")
        io_options(s)
        s.set_defaults(func=cmd_stage, stage=name)

    q = sub.add_parser("sql", help="read-only SQL query of the warehouse")
    q.add_argument("query", nargs="?", help='e.g. "SELECT * FROM table_iii" (or --describe TABLE)')
    q.add_argument("--describe", metavar="TABLE",
                   help="every column of TABLE with its type, unit and meaning (the warehouse's legend, "
                        "schemas/warehouse_legend.json) instead of a query")
    q.add_argument("--build", default="build", help="build folder holding warehouse.duckdb (default build/)")
    q.add_argument("--format", choices=["table", "csv", "json"], default="table",
                   help="table: aligned text, 'no rows' for an empty result (default); csv; json: one array per "
                        "statement")
    q.add_argument("--wide", action="store_true",
                    help="with --format table: every column on one line per row, however wide (default: lines of at "
                         "most 100 characters; a wide table splits into blocks of columns)")
    q.add_argument("--memory-limit", type=_size, default="2GiB", metavar="SIZE",
                   help="DuckDB memory limit, e.g. 512MB, 8GiB (default 2GiB); the command's memory is bounded by "
                        "it too: results stream to the output (a --format table result may take a quarter of it)")
    q.add_argument("--max-spill", type=_size, default="4GiB", metavar="SIZE",
                   help="what may spill to disk, into a folder of its own inside the build only "
                        "(<build>/.sql-spill-<pid>-<n>/, removed afterwards; default 4GiB; 0: no spilling)")
    q.add_argument("--timeout", type=_non_negative, default=300.0, metavar="SECONDS",
                   help="stop a statement after this many seconds (default 300; 0: no limit)")
    q.set_defaults(func=cmd_sql)

    a = sub.add_parser("analyze-run", aliases=ALIASES["analyze-run"],
                       help="K and C of one recording (raw format v1), as JSON (aliases: analyse-run, analyze; "
                            "the stage over a whole campaign is 'analyse')")
    a.add_argument("file", help="recording: .parquet, .csv, .mf4 or .tdms (raw format v1)")
    a.add_argument("--axle-mass", type=_positive, required=True, help="axle+wheel+tyre mass M_a, kg")
    a.add_argument("--sample-rate", type=_positive, default=None, metavar="HZ",
                   help="sampling rate, Hz: checked against time_s, or the time base of a file without time_s")
    a.set_defaults(func=cmd_analyze_run)

    e = sub.add_parser("estimate-stiffness", help="rolling tyre stiffness from size, pressure and age (kN/m)",
                       description="K = 172 - 1.77 R + 5.6 A + 0.34 W R P (thesis §4.5.3) with the 95 %% prediction "
                       "interval of the same formula refitted to the thesis' Table III (or, with --build, the formula "
                       "fitted to a build's tyres); warns on stderr where the tyre or pressure lies outside the data.")
    e.add_argument("--size", required=True, help="tyre size, e.g. 480/70R38, IF 710/70R42 173D, 13.6R38")
    e.add_argument("--pressure", type=_non_negative, required=True, help="inflation pressure, bar")
    e.add_argument("--age", type=_non_negative, default=1.0, help="tyre age, years (default 1)")
    front = e.add_mutually_exclusive_group()
    front.add_argument("--front-undriven", action="store_true",
                       help="an undriven ribbed front tyre: K = 134/(7.5*18) W R P (thesis §8.2)")
    front.add_argument("--front-traction", dest="front_undriven", action="store_false",
                       help="a traction tyre, driven front or rear: the size formula (the default)")
    e.add_argument("--water-ballast", action="store_true", help="water-ballasted tyre (+25 %%)")
    e.add_argument("--build", default=None, metavar="DIR",
                   help="use the formula fitted to the tyres measured in DIR's warehouse (table formula_fit) and "
                        "its prediction interval, instead of the thesis' (default)")
    e.add_argument("--json", action="store_true", help="print JSON (same as --format json)")
    e.add_argument("--format", choices=["text", "json"], default="text",
                   help="text: K in kN/m; json: inputs, W, R, aspect ratio, construction, K, warnings")
    e.set_defaults(func=cmd_estimate_stiffness)

    n = sub.add_parser("natural-frequencies", help="bounce and pitch natural frequencies of a tractor (thesis ch. 8), JSON")
    n.add_argument("--mass", type=_positive, required=True, help="tractor mass, kg")
    n.add_argument("--pitch-inertia", type=_positive, required=True, help="pitch moment of inertia, kg m²")
    n.add_argument("--front-distance", type=_positive, required=True, help="centre of gravity to front axle, m")
    n.add_argument("--rear-distance", type=_positive, required=True, help="centre of gravity to rear axle, m")
    n.add_argument("--front-tyre", required=True, help="front tyre size, e.g. 7.50-18")
    n.add_argument("--front-pressure", type=_non_negative, required=True, help="front inflation pressure, bar")
    n.add_argument("--rear-tyre", required=True, help="rear tyre size, e.g. 13.6R38")
    n.add_argument("--rear-pressure", type=_non_negative, required=True, help="rear inflation pressure, bar")
    front = n.add_mutually_exclusive_group()
    front.add_argument("--front-traction", action="store_true",
                       help="front tyres are traction tyres (four-wheel drive): the size formula")
    front.add_argument("--front-undriven", dest="front_traction", action="store_false",
                       help="front tyres undriven and ribbed: K = 134/(7.5*18) W R P (thesis §8.2; the default)")
    n.add_argument("--front-water-ballast", action="store_true", help="front tyres water-ballasted (+25 %%)")
    n.add_argument("--age", type=_non_negative, default=1.0, help="tyre age, years (default 1, thesis §8.2)")
    n.add_argument("--front-stiffness", type=_positive, default=None, help="override: front stiffness per tyre, kN/m")
    n.add_argument("--rear-stiffness", type=_positive, default=None, help="override: rear stiffness per tyre, kN/m")
    n.add_argument("--front-stiffness-u", type=float, default=None,
                   help="standard uncertainty of the front stiffness per tyre, kN/m (default: the formula's, or 0 "
                        "for a given stiffness)")
    n.add_argument("--rear-stiffness-u", type=float, default=None,
                   help="standard uncertainty of the rear stiffness per tyre, kN/m (default: as for the front)")
    n.add_argument("--build", default=None, metavar="DIR",
                   help="estimate the stiffnesses with the formula fitted to the tyres measured in DIR's warehouse "
                        "(table formula_fit) instead of the thesis'")
    n.set_defaults(func=cmd_natural_frequencies)

    x = sub.add_parser("export-tyre", help="a measured tyre as MF-Tyre .tir file(s) plus K(P), C(P) per speed (CSV, JSON)",
                       description="Writes FILE.tir (one per --pressure when several: FILE_<P>bar.tir), FILE.csv "
                       "and FILE.json from the warehouse's fits (or the catalogue's measured coefficients).")
    x.add_argument("tyre_id", help="tyre id, as in the tyres table")
    x.add_argument("--build", default="build", help="build folder holding warehouse.duckdb (default build/)")
    x.add_argument("--pressure", type=_positive, nargs="+", default=None,
                   help="nominal pressure(s), bar: one .tir each (default: middle of the tested range)")
    x.add_argument("--out", default=None, help="output .tir path (default <tyre_id>.tir)")
    x.set_defaults(func=cmd_export_tyre)

    rd = sub.add_parser("ride", help="seat vibration and EU daily exposure of a tractor scenario (TOML)")
    rd.add_argument("scenario", help="scenario file (schema: tyrelab.schemas scenario.json)")
    rd.add_argument("--build", default=None, help="build folder whose warehouse holds measured tyres")
    rd.add_argument("--out", default=None, help="folder to write ride.json and ride.html into")
    rd.add_argument("--format", choices=["json", "table"], default="json",
                    help="json: the ride document (default); table: a text summary per speed")
    rd.add_argument("--wide", action="store_true",
                    help="with --format table: every column on one line per row, however wide (default: lines of at "
                         "most 100 characters; a wide table splits into blocks of columns)")
    rd.add_argument("--front-pressure", type=_positive, nargs="+", default=None, metavar="BAR",
                    help="front pressures to sweep, bar (default: the scenario's)")
    rd.add_argument("--rear-pressure", type=_positive, nargs="+", default=None, metavar="BAR",
                    help="rear pressures to sweep, bar (default: the scenario's)")
    rd.add_argument("--speeds", type=_positive, nargs="+", default=None, metavar="KM_H",
                    help="speeds, km/h (default: the scenario's)")
    rd.add_argument("--set", action="append", default=None, metavar="KEY=V1,V2,...",
                    help="sweep a numeric scenario key, e.g. implement.mass_kg=0,500,1000 (repeatable: every combination)")
    rd.add_argument("--jobs", type=_jobs, default=1, help="worker processes for a sweep (default 1)")
    rd.add_argument("--method", choices=["auto", "time", "spectral"], default=None,
                    help="how the rows are computed (default the scenario's [simulation] method, else auto): time "
                         "simulates every variant; spectral gives each its exact expectation in the frequency domain "
                         "(no MTVV or crest factor); auto simulates one variant, and a sweep on an ISO 8608 surface "
                         "spectrally with the nominal variant and any that may lift a tyre simulated beside")
    rd.add_argument("--max-variants", type=_whole(10**6),  # limits.BOUND_CEILINGS
                    default=None, metavar="N",
                    help="most variants a sweep may run (default 400 in the time domain, 20000 spectral; more is "
                         "refused with an estimate)")
    rd.add_argument("--max-samples", type=_whole(10**12),  # limits.BOUND_CEILINGS
                    default=None, metavar="N",
                    help="most 1 kHz samples the command may simulate over all pairs and speeds (default 10 million)")
    rd.add_argument("--max-rows", type=_whole(10**9),  # limits.BOUND_CEILINGS
                    default=None, metavar="N",
                    help="most spectral rows (variant x speed) the command may compute (default: what 300 s of the "
                         "estimate allow, about 100,000 rows of the pitch plane, 3,300 of the 3-D model)")
    rd.add_argument("--executor", choices=["local", "dask"], default="local",
                    help="local: worker processes on this machine (default); dask: a dask.distributed cluster")
    rd.add_argument("--scheduler", default=None, help="dask scheduler address (with --executor dask)")
    rd.set_defaults(func=cmd_ride)

    ro = sub.add_parser("road", help="ISO 8608 class, r.m.s. and length of each track of a road profile (CSV or OpenCRG)",
                        description="Per track: G_d(n0) fitted with waviness 2 over ISO 8608's band (0.011-2.83 "
                        "cycles/m, as far as the track resolves it), its class A-H, the r.m.s. about the mean and "
                        "the length. A CSV profile (distance_m, height_m or height_left_m/height_right_m) gives its "
                        "tracks; an OpenCRG file (.crg, read with pyopencrg) the lines of a pair of wheels. "
                        "Exit 2: a missing, damaged or unusable file.")
    ro.add_argument("file", help="profile CSV or OpenCRG .crg file")
    ro.add_argument("--track-width-m", type=_positive, default=1.8,
                    help=".crg: distance between the left and right wheel lines, m (default 1.8)")
    ro.add_argument("--lateral-offset-m", type=_finite, default=0.0,
                    help=".crg: the wheels' centre line, m left of the road's reference line (default 0)")
    ro.add_argument("--start-m", type=_non_negative, default=0.0, help=".crg: start past the first cross section, m (default 0)")
    ro.add_argument("--length-m", type=_positive, default=None, help=".crg: length, m (default: the rest of the file)")
    ro.add_argument("--fill-missing", action="store_true",
                    help=".crg: fill missing heights (NaN) as OpenCRG does (default: refuse them)")
    ro.add_argument("--format", choices=["json", "table"], default="table",
                    help="table: one line per track (default); json: the numbers")
    ro.add_argument("--wide", action="store_true",
                    help="with --format table: every column on one line per row, however wide (default: lines of at "
                         "most 100 characters; a wide table splits into blocks of columns)")
    ro.set_defaults(func=cmd_road)

    fr = sub.add_parser("frf", help="a vehicle's transfer functions from each wheel input to each output, and its modes "
                        "(thesis ch. 2), JSON",
                        description="A recording (raw format v1) with wheel inputs input_<wheel>_z_m_s2 or "
                                    "input_<wheel>_z_m. Exit 2: an unreadable recording, no input channel, a constant "
                                    "input, a recording too short; 3: the inputs cannot be separated in any bin "
                                    "(correlated as on a road): the FRFs are printed, no mode is fitted.")
    fr.add_argument("file", help="recording: .parquet, .csv, .mf4 or .tdms (raw format v1)")
    fr.add_argument("--speed", type=_non_negative, default=0.0, metavar="KM_H",
                    help="rolling speed, km/h (default 0: stationary)")
    fr.add_argument("--scenario", default=None, metavar="TOML",
                    help="the vehicle's scenario: its tyres' rotation and lug-passing bins are masked when rolling")
    fr.add_argument("--max-frequency", type=_positive, default=20.0, metavar="HZ",
                    help="highest bin printed, Hz (default 20)")
    fr.add_argument("--format", choices=["json", "table"], default="json",
                    help="json: inputs, outputs, modes and every bin (default); table: a text summary")
    fr.add_argument("--wide", action="store_true",
                    help="with --format table: every column on one line per row, however wide (default: lines of at "
                         "most 100 characters)")
    fr.set_defaults(func=cmd_frf)

    ex = sub.add_parser("exposure", help="a driver's daily whole-body vibration exposure from seat recordings "
                        "(ISO 2631-1/-5, EU Directive 2002/44/EC)",
                        description="Exit 2: usage, a missing, unreadable or unknown file; 3: a recording that cannot "
                                    "be used, or one shorter than 10 s (its values are printed with a warning and no "
                                    "verdict). Hours per task: 0.01 to 24; the tasks' sum at most 24 h (+1e-9 h of "
                                    "rounding).")
    ex.add_argument("file", nargs="?", default=None, help="one recording (raw format v1: time_s, seat_x/y/z_m_s2, …)")
    ex.add_argument("--hours", type=_positive, default=8.0,
                    help="daily hours of the recorded task, 0.01 to 24 (default 8)")
    ex.add_argument("--task", nargs=3, action="append", metavar=("NAME", "FILE", "HOURS"),
                    help="a task of the day: its name, recording and daily hours (repeat for each task)")
    ex.add_argument("--format", choices=["json", "table"], default="json",
                    help="json: the exposure document (default); table: a text summary per task")
    ex.add_argument("--wide", action="store_true",
                    help="with --format table: every column on one line per row, however wide (default: lines of at "
                         "most 100 characters; a wide table splits into blocks of columns)")
    ex.set_defaults(func=cmd_exposure)

    c = sub.add_parser("completion", help="print the shell code that completes tyrelab's verbs and options",
                       description="Tab completion by argcomplete. Enable it for this shell with\n"
                                   "  eval \"$(tyrelab completion bash)\"     (zsh: tyrelab completion zsh)\n"
                                   "or for every new shell by adding that line to ~/.bashrc (~/.zshrc); fish:\n"
                                   "  tyrelab completion fish > ~/.config/fish/completions/tyrelab.fish")
    c.add_argument("shell", choices=["bash", "zsh", "fish", "tcsh", "powershell"], help="the shell to complete in")
    c.set_defaults(func=cmd_completion)

    for verb in {id(sp): sp for sp in sub.choices.values()}.values():  # an alias shares its verb's parser
        _global_options(verb, on_verb=True)
    return p


def _discard_stdout() -> None:
    """Point stdout at /dev/null, so that the interpreter's last flush does not fail again."""
    import os

    try:
        fd = os.open(os.devnull, os.O_WRONLY)
        os.dup2(fd, sys.stdout.fileno())
        os.close(fd)
    except (OSError, ValueError, AttributeError):  # pragma: no cover - stdout without a file descriptor
        pass


def _caused_by_interrupt(exc: BaseException) -> bool:
    """Whether a KeyboardInterrupt is among the explicit causes (``raise ... from``) of ``exc``.

    Only causes: an error raised while an interrupt was being handled (its context) is
    an error of its own and keeps its traceback.
    """
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return True
        seen.add(id(exc))
        exc = exc.__cause__
    return False


def _configure_output(args) -> None:
    """Logging by ``-q``/``-v`` on stderr, and progress bars unless ``-q`` (drawn only on a terminal)."""
    from . import progress

    level = logging.WARNING if args.quiet else logging.DEBUG if args.verbose else logging.INFO
    root = logging.getLogger()
    if not any(isinstance(h, progress.StderrHandler) for h in root.handlers):
        handler = progress.StderrHandler()
        handler.setFormatter(logging.Formatter("%(message)s"))
        root.addHandler(handler)
    root.setLevel(level)
    if args.verbose:  # the libraries' own debug chatter is not ours
        for name in ("matplotlib", "PIL", "asyncio", "fsspec", "numba", "distributed"):
            logging.getLogger(name).setLevel(logging.INFO)
    progress.configure(bars=not args.quiet)


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``tyrelab`` console script.

    Ctrl-C (SIGINT) or SIGTERM ends a command with one line and exit 130, without a
    traceback; ``finally`` blocks and ``atexit`` handlers still run, so temporary
    files, worker pools and their ``pymp-*`` folders are cleaned up.

    Called from the command line (``argv`` None) the garbage collector is tuned for a
    short-lived process (:func:`tyrelab.executor.command_gc`).
    """
    from .executor import command_gc, single_threaded_blas

    single_threaded_blas()  # before anything imports numpy (see its docstring)
    if argv is None:
        command_gc()
    try:  # Ctrl-C while the options are read (a type such as --memory-limit's imports DuckDB)
        parser = build_parser()
        if "_ARGCOMPLETE" in os.environ:  # the shell asks for completions (tyrelab completion SHELL)
            import argcomplete

            argcomplete.autocomplete(parser)
        args = parser.parse_args(argv)
    except KeyboardInterrupt:
        verb = next((a for a in (sys.argv[1:] if argv is None else argv) if not a.startswith("-")), "")
        print(f"tyrelab {verb}: interrupted" if verb else "tyrelab: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    if args.quiet and args.verbose:  # one before the verb, the other after it
        parser.error("argument -v/--verbose: not allowed with argument -q/--quiet")
    _configure_output(args)
    import warnings

    from . import interrupts
    from .progress import say_library_warnings_once

    shown_before = say_library_warnings_once()  # no library's RuntimeWarning on stderr: ours, once each

    # Ctrl-C and SIGTERM recorded as well as raised: a library that swallows the KeyboardInterrupt
    # (DuckDB's signal check during a statement) cannot make a command run on (tyrelab.interrupts)
    previous = interrupts.install()
    try:
        code = args.func(args)
        if code != EXIT_INTERRUPTED:
            interrupts.check()
        try:
            sys.stdout.flush()  # here, not at exit: a reader gone is caught below
        except BrokenPipeError:
            raise
        except OSError as exc:
            raise OutputError(exc.errno, f"cannot write the output ({exc.strerror or exc})") from None
        return code
    except BrokenPipeError:  # stdout piped into `head` (or a pager) that quit reading: no traceback
        _discard_stdout()
        return EXIT_BROKEN_PIPE
    except OutputError as exc:  # a full device: one line, what was printed may be cut short
        _discard_stdout()
        print(f"tyrelab {args.command}: {exc.strerror}", file=sys.stderr)
        return EXIT_USAGE
    except MissingExtra as exc:  # e.g. --executor dask without dask installed
        print(f"tyrelab {args.command}: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print(f"tyrelab {args.command}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Exception as exc:
        if not (_caused_by_interrupt(exc) or interrupts.requested()):
            raise
        # Ctrl-C while an extension module initialises: it reports an ImportError whose cause is the
        # KeyboardInterrupt (pybind11's "initialization failed", scipy.optimize._highspy)
        print(f"tyrelab {args.command}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    finally:
        warnings.showwarning = shown_before
        interrupts.restore(previous)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
