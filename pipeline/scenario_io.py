"""Reading ride scenario files and track profiles (issues 13, 23): the file side of
:mod:`tyrelab.vehicle.scenario`, which parses TOML text and takes the profile's data, reading no
file itself (the pure package takes data, not paths).

:func:`load_scenario` reads a scenario file (bounded in size) and :func:`parse_scenario` parses
text, both reading a ``kind = "profile"`` track with :func:`read_profile_csv`; the CLI, the
simulate stage, the campaign generator and the benchmarks read scenarios through here.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pandas as pd

from . import _validate
from .io import head_lines, printable
from .vehicle.scenario import Scenario, ScenarioError
from .vehicle.scenario import parse_scenario as _parse_text
from .vehicle.scenario import scenario_from_dict as _from_dict

__all__ = ["MAX_CRG_BYTES", "MAX_PROFILE_BYTES", "MAX_SCENARIO_BYTES", "ScenarioError", "load_scenario", "parse_scenario", "read_crg", "scenario_from_dict",
           "read_profile_csv", "huge_number_problems", "crg_files"]

#: Largest OpenCRG file read, bytes (a text CRG holds about 20 bytes per height: 10 million heights).
MAX_CRG_BYTES = 200_000_000
#: Largest profile CSV read, bytes (about 40 bytes a row: 5 million points, 100 km at 2 cm), checked before
#: pandas reads it.
MAX_PROFILE_BYTES = 200_000_000


def read_crg(path: str | Path, *, confine_to: str | Path | None = None):
    """Read an OpenCRG road with ``pyopencrg`` (checked as it reads: a short binary section or a bad
    header is refused), bounded before the grid is loaded (:data:`MAX_CRG_BYTES`,
    :data:`tyrelab.vehicle.crg.MAX_GRID_VALUES`).

    With ``confine_to`` (a campaign's scenario folder, when the pipeline reads it), the data file a
    ``$ROAD_CRG_FILE`` block references must lie inside that folder after symlinks (and environment
    variables, which pyopencrg expands) are resolved: a campaign reads no file the build does not track.

    Returns
    -------
    tyrelab.vehicle.crg.CrgData

    Raises
    ------
    ValueError
        One line naming the file and its problem (missing, too large, not a readable OpenCRG file,
        a data file outside ``confine_to``).
    """
    import warnings

    import pyopencrg

    from .vehicle.crg import MAX_GRID_VALUES, CrgData

    _validate.instance("path", path, (str, Path))
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: no such file" if not path.exists() else f"{path}: not a regular file")
    size = path.stat().st_size
    if size > MAX_CRG_BYTES:
        raise ValueError(f"{path}: {size} bytes, above the {MAX_CRG_BYTES} bytes a CRG road may have")
    problem = _crg_header_problem(path)  # what the data would take, from the header alone, before pyopencrg reads it
    if confine_to is not None and not problem:
        data = _crg_data_file(path)
        try:
            inside = data is None or data.is_relative_to(Path(confine_to).resolve())
        except OSError:
            inside = False
        if not inside:  # named relative to the folder: a quarantine row holds no path of this machine
            problem = (f"its data file {printable(os.path.relpath(data, Path(confine_to).resolve()))} "
                       "($ROAD_CRG_FILE, symlinks resolved) is outside the campaign's folder: a campaign's road "
                       "reads only its own files")
    if problem:
        raise ValueError(f"{path}: {problem}")
    try:
        with warnings.catch_warnings():  # minor remarks of pyopencrg's checks are not the user's problem
            warnings.simplefilter("ignore")
            with pyopencrg.open(path) as f:
                if f.nu * f.nv > MAX_GRID_VALUES:
                    raise ValueError(f"{f.nu} x {f.nv} heights, above the {MAX_GRID_VALUES} a CRG road may have")
                road = f.read()
    except Exception as exc:  # noqa: BLE001 - a damaged file makes the parser fail in any way: one line
        lines = [ln.strip(" -").replace(f"{path}: ", "").replace(f"{path.name}: ", "") for ln in str(exc).splitlines()]
        lines = [ln for ln in lines if ln and not ln.startswith("To open it anyway")]
        if len(lines) > 1 and lines[0].endswith(":"):
            lines = [lines[0] + " " + "; ".join(lines[1:])]
        text = "; ".join(lines) or type(exc).__name__
        raise ValueError(f"{path}: not a readable OpenCRG file ({text})") from None
    return CrgData.of(road, path.name)


#: Bytes of one value in an OpenCRG data section, by format (binary float32/float64; ASCII fields of
#: 10 and 20 characters on lines of 80, plus their line ends: an upper bound on the value count).
_CRG_VALUE_BYTES = {"KRBI": 4, "KDBI": 8, "LRFI": 10, "LDFI": 20}


def crg_files(path: str | Path) -> list[Path]:
    """The files an OpenCRG road reads: the file, and the data file its ``$ROAD_CRG_FILE`` block
    references (resolved, symlinks included; the header alone is read). What a cache key of a
    result that read the road must hold (editing either re-runs it).

    Examples
    --------
    >>> crg_files("no-such.crg")
    [PosixPath('no-such.crg')]
    """
    path = Path(path)
    data = _crg_data_file(path)
    return [path] + ([data] if data is not None and data.resolve() != path.resolve() else [])


def _crg_data_file(path: Path) -> Path | None:
    """The data file of an OpenCRG road (the file itself, or the one its ``$ROAD_CRG_FILE`` block
    names), resolved; None where the header cannot be read (the reader says why)."""
    import warnings

    try:
        from pyopencrg import io as crg_io

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            _, ipl, _ = crg_io._decode_crg(str(path))
    except Exception:  # noqa: BLE001 - a damaged header (or another pyopencrg)
        return None
    data = Path(ipl.filename)
    return (data if data.is_absolute() or data.exists() else path.parent / data).resolve()


def _crg_header_problem(path: Path) -> str | None:
    """Why an OpenCRG file must be refused from its header alone (None: read it): its data file (a
    ``$ROAD_CRG_FILE`` reference, else the file itself) above :data:`MAX_CRG_BYTES`, or more heights
    than :data:`tyrelab.vehicle.crg.MAX_GRID_VALUES` by the data section's size (a sparse file of
    holes included): about what reading the header costs, never the data."""
    import warnings

    from .vehicle.crg import MAX_GRID_VALUES

    try:
        from pyopencrg import io as crg_io

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            _, ipl, layout = crg_io._decode_crg(str(path))  # header and channel layout; no data read
        data = Path(ipl.filename)
        if not data.is_absolute():
            data = path.parent / data if not data.exists() else data
        size = data.stat().st_size
    except Exception:  # noqa: BLE001 - a damaged header (or another pyopencrg): the reader below says what is wrong
        return None
    if data.resolve() != path.resolve() and size > MAX_CRG_BYTES:
        return (f"its data file {printable(data.name)} ($ROAD_CRG_FILE) has {size} bytes, above the {MAX_CRG_BYTES} "
                "bytes a CRG road may have")
    width = _CRG_VALUE_BYTES.get(str(ipl.fmt))
    channels = len(getattr(ipl, "kd_def", ()) or ())
    heights = len(layout.get("z_cols", ()) or ()) if isinstance(layout, dict) else 0
    if not width or not channels or not heights:
        return None
    values = max(0, size - int(ipl.data_offset)) // width
    if width >= 10:  # ASCII: a line end per 80 characters
        values = values * 80 // 81
    grid = values // channels * heights
    if grid > MAX_GRID_VALUES:
        return (f"its data section of {size - int(ipl.data_offset)} bytes ({ipl.fmt}, {channels} channels) holds about "
                f"{grid} heights, above the {MAX_GRID_VALUES} a CRG road may have")
    if not _crg_has_a_number(data, int(ipl.data_offset), str(ipl.fmt)):
        where = "" if data.resolve() == path.resolve() else f" (its data file {printable(data.name)}, $ROAD_CRG_FILE)"
        return (f"every value of its data section{where} is NaN, about {values // channels} cross sections of "
                f"{channels} channels: no height to drive on")
    return None


def _crg_has_a_number(data: Path, offset: int, fmt: str, chunk_bytes: int = 1 << 22) -> bool:
    """Whether an OpenCRG data section (``fmt``, from byte ``offset`` of ``data``) holds any value
    that is not NaN, read in chunks up to the first one (a road's first chunk): binary values by
    ``numpy.isnan``, text by its digits (OpenCRG writes NaN as asterisks). An all-NaN road is refused
    in a scan of its bytes (about 30 ms for 32 MB), not after pyopencrg's record-by-record trim of its
    NaN padding (seconds, then "at least 2 cross sections are required")."""
    dtype = {"KRBI": np.dtype(">f4"), "KDBI": np.dtype(">f8")}.get(fmt)
    with open(data, "rb") as f:
        f.seek(offset)
        while True:
            buf = f.read(chunk_bytes)
            if not buf:
                return False
            if dtype is None:  # text: a digit anywhere is a number
                if any(d in buf for d in b"0123456789"):
                    return True
                continue
            values = np.frombuffer(buf[: len(buf) - len(buf) % dtype.itemsize], dtype=dtype)
            if not np.isnan(values).all():
                return True


def read_profile_csv(path: str | Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Read a profile CSV: ``distance_m`` and ``height_m`` or ``height_left_m``/``height_right_m``.

    Returns
    -------
    distance_m, left_m, right_m : ndarray
        As written (not resampled); ``left == right`` for a single ``height_m``.

    Raises
    ------
    ValueError
        Naming the file and every problem (missing columns, non-numeric values,
        distances not strictly increasing, fewer than 16 points, above :data:`MAX_PROFILE_BYTES`).
    """
    _validate.instance("path", path, (str, Path))
    path = Path(path)
    shown = printable(path)
    if not path.is_file():
        raise ValueError(f"{shown}: no such file" if not path.exists() else f"{shown}: not a regular file")
    size = path.stat().st_size
    if size > MAX_PROFILE_BYTES:
        raise ValueError(f"{shown}: {size} bytes, above the {MAX_PROFILE_BYTES} bytes a profile CSV may have")
    try:  # the header line first, bounded: a file without line ends is not read whole as its header
        head_lines(path, 1, "distance_m, height_m")
    except ValueError as exc:
        raise ValueError(f"{shown}: {exc}") from None
    try:
        df = pd.read_csv(path)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise ValueError(f"{shown}: not a readable CSV ({printable(str(exc).splitlines()[0][:200])})") from None
    except OSError as exc:
        raise ValueError(f"{shown}: cannot read ({exc.strerror or exc})") from None
    problems = []
    if "distance_m" not in df:
        problems.append("no distance_m column")
    if "height_m" in df:
        cols = ["height_m", "height_m"]
    elif "height_left_m" in df and "height_right_m" in df:
        cols = ["height_left_m", "height_right_m"]
    else:
        cols = []
        problems.append("no height_m column (or height_left_m and height_right_m)")
    if problems:
        raise ValueError(f"{shown}: {'; '.join(problems)} (columns: {printable(', '.join(map(str, df.columns)))[:200]})")
    num = {c: pd.to_numeric(df[c], errors="coerce") for c in {"distance_m", *cols}}
    for c, v in num.items():
        if v.isna().any():
            problems.append(f"{c} has {int(v.isna().sum())} missing or non-numeric values")
    if problems:
        raise ValueError(f"{path}: {'; '.join(problems)}")
    x = num["distance_m"].to_numpy(float)
    if len(x) < 16:
        problems.append(f"only {len(x)} points (need at least 16)")
    elif not np.all(np.diff(x) > 0):
        problems.append("distance_m is not strictly increasing")
    if problems:
        raise ValueError(f"{path}: {'; '.join(problems)}")
    return x, num[cols[0]].to_numpy(float), num[cols[1]].to_numpy(float)


def parse_scenario(text: str, base_dir: str | Path = ".", path: str | Path | None = None, *,
                   confine: bool = True) -> Scenario:
    """:func:`tyrelab.vehicle.scenario.parse_scenario` with profiles read by :func:`read_profile_csv`.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> s = parse_scenario((scenarios_dir() / "mf698t.toml").read_text(), scenarios_dir())
    >>> s.surface.kind, s.surface.profile_data is None
    ('iso8608', True)
    """
    import tomllib

    try:
        doc = tomllib.loads(text) if isinstance(text, str) else None
    except (tomllib.TOMLDecodeError, RecursionError, ValueError):  # ValueError: an integer of over 4300 digits
        doc = None  # the parser below says what is wrong with the text
    _refuse_huge(doc, path, base_dir, confine)
    return _parse_text(text, base_dir, path, confine=confine, read_profile=read_profile_csv,
                       read_crg=_crg_reader(base_dir, confine))


def _crg_reader(base_dir, confine: bool):
    """:func:`read_crg` as a scenario reads it: confined to ``base_dir`` when ``confine`` is."""
    import functools

    return functools.partial(read_crg, confine_to=base_dir) if confine else read_crg


def huge_number_problems(doc, prefix: str = "", depth: int = 0) -> list[str]:
    """Every integer of a scenario document too large for a float (``mass_kg = 1`` and 400 zeros:
    TOML keeps it exactly, a model cannot use it), one line each naming its key.

    Examples
    --------
    >>> huge_number_problems({"tractor": {"mass_kg": 10**400, "pitch_inertia_kg_m2": 5500}})
    ['tractor.mass_kg: 1000000000…0000000000 (401 digits) is not a finite number']
    """
    if depth > 64:
        return []
    if isinstance(doc, dict):
        items = [(f"{prefix}.{k}" if prefix else str(k), v) for k, v in doc.items()]
    elif isinstance(doc, (list, tuple)):
        items = [(f"{prefix}[{i}]", v) for i, v in enumerate(doc)]
    else:
        items = []
    problems = []
    for key, value in items:
        if isinstance(value, int) and not isinstance(value, bool):
            try:
                float(value)
            except OverflowError:
                problems.append(f"{printable(key)}: {_validate.shown(value)} is not a finite number")
        elif isinstance(value, (dict, list, tuple)):
            problems += huge_number_problems(value, key, depth + 1)
    return problems


def _refuse_huge(doc, path, base_dir, confine: bool) -> None:
    """ScenarioError naming every key of ``doc`` that :func:`huge_number_problems` finds, with the
    document's other problems (those numbers taken as infinite), all at once."""
    problems = huge_number_problems(doc) if isinstance(doc, dict) else []
    if not problems:
        return
    keys = tuple(p.split(": ", 1)[0] + ":" for p in problems)
    try:
        _from_dict(_as_infinite(doc), base_dir, path, confine=confine, read_profile=read_profile_csv, read_crg=read_crg)
    except ScenarioError as exc:
        problems += [p for p in exc.problems if not p.startswith(keys)]
    raise ScenarioError(str(path) if path is not None else "<scenario>", problems)


def _as_infinite(doc, depth: int = 0):
    """``doc`` with every integer too large for a float as infinity (of its sign)."""
    if depth > 64:
        return doc
    if isinstance(doc, dict):
        return {k: _as_infinite(v, depth + 1) for k, v in doc.items()}
    if isinstance(doc, (list, tuple)):
        return [_as_infinite(v, depth + 1) for v in doc]
    if isinstance(doc, int) and not isinstance(doc, bool):
        try:
            float(doc)
        except OverflowError:
            return float("inf") if doc > 0 else float("-inf")
    return doc


def scenario_from_dict(doc, base_dir: str | Path = ".", path: str | Path | None = None, *,
                       confine: bool = True) -> Scenario:
    """:func:`tyrelab.vehicle.scenario.scenario_from_dict` with profiles read by :func:`read_profile_csv` and CRG roads by :func:`read_crg`.

    See Also
    --------
    parse_scenario : the same from TOML text.
    load_scenario : the same from a file.
    """
    from collections.abc import Mapping

    if isinstance(doc, Mapping):
        _refuse_huge(dict(doc), path, base_dir, confine)
    return _from_dict(doc, base_dir, path, confine=confine, read_profile=read_profile_csv,
                      read_crg=_crg_reader(base_dir, confine))


#: Largest scenario file read, bytes (the shipped ones are ~2 kB).
MAX_SCENARIO_BYTES = 1_000_000


def load_scenario(path: str | Path, *, confine: bool = True) -> Scenario:
    """Read and check a scenario file (see :func:`parse_scenario`, ``confine`` included).

    Raises
    ------
    ScenarioError
        If the file cannot be read or has problems (all listed).
    """
    _validate.instance("path", path, (str, Path))
    p = Path(path)
    try:
        if not p.is_file():  # a folder, a FIFO, /dev/zero (read for ever)
            raise ScenarioError(p, ["not a regular file"] if p.exists() else ["cannot read: No such file or directory"])
        if p.stat().st_size > MAX_SCENARIO_BYTES:
            raise ScenarioError(p, [f"{p.stat().st_size} bytes: a scenario file is at most {MAX_SCENARIO_BYTES}"])
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise ScenarioError(p, [f"cannot read: {exc.strerror if isinstance(exc, OSError) else exc}"]) from None
    return parse_scenario(text, p.resolve().parent, p, confine=confine)
