"""Raw format v1 for vehicle vibration recordings (issue 24): the one home of their contract.

A recording holds ``time_s`` and any of :data:`RIDE_CHANNELS` (x forward, y left, z up;
SI: m/s² and rad/s²), one row per sample at a constant rate. ``.parquet`` and ``.csv`` are
read as they are, in chunks (an 8 h day is never held whole); ``.mf4``/``.tdms`` go through
a channel map (:mod:`tyrelab.rawformat.mapped`) and are read whole. A campaign lists its
recordings in ``rides.csv`` (:data:`RIDES_SCHEMA`, ``schemas/raw_rides.json``).

A ``.csv`` is read as a spreadsheet saves it (as manifests are,
:func:`tyrelab.rawformat.files.read_delimited`): the separator (``,`` ``;`` or tab) is the one
whose header holds ``time_s``, a UTF-8 byte-order mark is accepted, and in a ``;``- or
tab-separated file decimal commas (``0,25``) are read as numbers; its header line is read
bounded (:data:`MAX_HEADER_BYTES`) before anything else, so a file without a line end is
refused unread.

Every problem raises :class:`RunFileError` with a one-line reason: no time base, no known
channel, a NaN, a sample beyond :data:`MAX_ABS_SAMPLE` (implausible for a vehicle's
vibration: a corrupt or mis-scaled file), a time base that goes back or is irregular, a
vertical channel that averages about ±1 (a channel in g, not m/s²); a file that cannot be
opened (no permission) is ``cannot read (…)``. A channel averaging about ±9.81 m/s² (a
DC-coupled accelerometer reading gravity) is accepted with a warning: the analysis removes
each channel's offset (the mean of its first chunk).

Examples
--------
>>> import tempfile, pathlib
>>> import numpy as np, pandas as pd
>>> with tempfile.TemporaryDirectory() as d:
...     p = pathlib.Path(d) / "r.csv"
...     t = np.arange(0, 20, 0.01)
...     pd.DataFrame({"time_s": t, "seat_z_m_s2": 9.81 + np.sin(t)}).to_csv(p, index=False)
...     rec = open_recording(p)
...     n = sum(len(c.time_s) for c in rec.chunks())
>>> rec.channels, round(rec.sample_rate_Hz, 6), n, rec.warnings[0][:44]
(('seat_z_m_s2',), 100.0, 2000, 'channel seat_z_m_s2 averages 9.84 m/s² (a ±1')
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from ..io import MAX_HEADER_BYTES as _io_MAX_HEADER_BYTES
from ..units import STANDARD_GRAVITY_M_S2
from . import mapped
from .mapped import RunFileError

__all__ = [
    "RIDE_CHANNELS", "SEAT_CHANNELS", "FLOOR_CHANNELS", "INPUT_CHANNELS", "INPUT_HEIGHT_CHANNELS", "RECORDING_SUFFIXES", "MAX_RECORDING_BYTES",
    "CHUNK_ROWS", "READ_ROWS", "GRAVITY_M_S2", "MAX_ABS_SAMPLE", "MAX_HEADER_BYTES", "Chunk", "Recording",
    "open_recording",
]

#: Seat accelerations, m/s² (x forward, y left, z up).
SEAT_CHANNELS = ["seat_x_m_s2", "seat_y_m_s2", "seat_z_m_s2"]
#: Cab-floor accelerations beneath the seat, m/s².
FLOOR_CHANNELS = ["floor_x_m_s2", "floor_y_m_s2", "floor_z_m_s2"]
#: Wheel inputs (issue 43, thesis ch. 2): the stand pad's or the ground's vertical acceleration under
#: each wheel, m/s² ...
INPUT_CHANNELS = [f"input_{w}_z_m_s2" for w in ("front_left", "front_right", "rear_left", "rear_right")]
#: ... or the ground height under it, m (the track method's optical transducer, §2.3).
INPUT_HEIGHT_CHANNELS = [c[:-len("_s2")] for c in INPUT_CHANNELS]
#: Every channel a recording may hold besides ``time_s``.
RIDE_CHANNELS = [*SEAT_CHANNELS, *FLOOR_CHANNELS, "front_axle_z_m_s2", "rear_axle_z_m_s2",
                 "pitch_rad_s2", "roll_rad_s2", "yaw_rad_s2", *INPUT_CHANNELS, *INPUT_HEIGHT_CHANNELS]
RECORDING_SUFFIXES = (".parquet", ".csv", *mapped.SUFFIXES)
#: Largest recording read, bytes (streamed: a bound on time, not memory). An 8 h day of
#: three axes at 500 Hz in float64 Parquet is about 0.5 GB.
MAX_RECORDING_BYTES = 8 * 1024**3
#: Largest ``.mf4``/``.tdms`` recording (read whole), bytes.
MAX_MAPPED_BYTES = 512 * 1024**2
#: Rows of a recording's first chunk: its checks and the offsets (the channels' means) the
#: analysis removes.
CHUNK_ROWS = 1 << 18
#: Rows read at a time after the first chunk (the reader holds about two such batches; a larger
#: batch made the peak RSS grow with the recording by the Parquet decoder's buffers).
READ_ROWS = 1 << 16
#: Accepted sampling rates, Hz.
SAMPLE_RATE_RANGE_Hz = (16.0, 20000.0)
#: Batches after which pyarrow's allocator (mimalloc) hands the pages of the batches it freed back:
#: it kept them, and the peak RSS crept up by ~20 MB over an hour of batches. After each batch
#: the pages were faulted in again (+70 % CPU for the reading); after 8, +3 %, the same peak.
RELEASE_EVERY = 8
#: Allowed relative jitter of the sampling interval.
MAX_DT_JITTER = 0.01
GRAVITY_M_S2 = STANDARD_GRAVITY_M_S2
#: Largest magnitude of a channel's sample accepted, m/s² (or rad/s² for ``pitch``/``roll``/``yaw``, m
#: for a ground height): 1000
#: m/s² is about 100 g, ten times the ±10 g range of the seat-pad accelerometers ISO 10326-1
#: describes and beyond the shocks ISO 2631-5 assesses (a documented choice). A sample beyond it
#: is a corrupt or mis-scaled file (mm/s² for m/s², a logger's overflow code such as 1e30), not
#: vibration: the recording is refused naming the channel and row (the sums of the analysis
#: would otherwise overflow, or give an A(8) of 1e27 m/s²).
MAX_ABS_SAMPLE = 1000.0
#: Longest header line of a ``.csv`` recording, bytes (:data:`tyrelab.io.MAX_HEADER_BYTES`; every
#: channel of :data:`RIDE_CHANNELS` makes under 1 kB).
MAX_HEADER_BYTES = _io_MAX_HEADER_BYTES
_DELIMITER_NAMES = {",": "','", ";": "';'", "\t": "tab"}


@dataclass
class Chunk:
    """Consecutive samples of a recording."""

    time_s: np.ndarray
    channels: dict


@dataclass
class Recording:
    """An opened recording: its channels, rate and a chunk iterator.

    Attributes
    ----------
    path : Path
    channels : tuple of str
        The :data:`RIDE_CHANNELS` it holds, in that order.
    sample_rate_Hz : float
        From the first chunk's mean interval.
    offsets : dict
        Channel -> mean of its first chunk (the analysis removes it).
    warnings : list of str
    """

    path: Path
    channels: tuple
    sample_rate_Hz: float
    offsets: dict
    warnings: list = field(default_factory=list)
    _first: Chunk | None = None
    _rest: Iterator | None = None
    _dt: float = math.nan

    def chunks(self) -> Iterator[Chunk]:
        """The samples, chunk after chunk, each checked; a problem raises :class:`RunFileError`."""
        first, self._first = self._first, None
        if first is None:
            raise RuntimeError("a recording's chunks can be read once")
        yield first
        last_t = float(first.time_s[-1])
        row = first.time_s.size
        batches = 0
        for frame in self._rest:
            if not _rows(frame):
                continue
            chunk = _checked(frame, self.channels, row)
            gap = float(chunk.time_s[0]) - last_t
            if abs(gap - self._dt) > MAX_DT_JITTER * self._dt:
                raise RunFileError(f"irregular sampling: interval at row {row} is {gap:.6g} s, expected {self._dt:.6g} s")
            _regular(chunk.time_s, self._dt, row)
            last_t = float(chunk.time_s[-1])
            row += chunk.time_s.size
            yield chunk
            del chunk, frame  # not alive while the next batch is decoded
            batches += 1
            if batches % RELEASE_EVERY == 0:
                pa.default_memory_pool().release_unused()


def _frames(path: Path, columns: list[str], chunk_rows: int, channel_map: dict | None,
            dialect: tuple[str, str] = (",", ".")) -> Iterator[pd.DataFrame]:
    suffix = path.suffix.lower()
    try:
        if suffix == ".parquet":
            pf = _parquet(path)
            for batch in pf.iter_batches(batch_size=chunk_rows, columns=columns, use_threads=False):
                # straight to numpy (no DataFrame): a null becomes NaN, which _checked refuses
                yield {name: col.to_numpy(zero_copy_only=False) for name, col in zip(batch.schema.names, batch.columns)}
        elif suffix == ".csv":
            sep, decimal = dialect
            with pd.read_csv(path, sep=sep, decimal=decimal, encoding="utf-8-sig",
                             usecols=lambda c: str(c).strip() in columns, chunksize=chunk_rows) as reader:
                for frame in reader:
                    frame.columns = [str(c).strip() for c in frame.columns]
                    yield frame
        else:
            frame = mapped.read_mapped(path, [], RIDE_CHANNELS, channel_map)
            for i in range(0, len(frame), chunk_rows):
                yield frame.iloc[i:i + chunk_rows]
    except RunFileError:
        raise
    except (pa.ArrowException, OSError, ValueError, UnicodeDecodeError, pd.errors.ParserError) as exc:
        raise _read_error(exc, suffix) from None


def _read_error(exc: Exception, suffix: str) -> RunFileError:
    """``cannot read (…)`` for a file the system will not let us read, else ``corrupt or truncated``."""
    from ..io import printable

    if isinstance(exc, OSError) and not isinstance(exc, (pa.ArrowException, UnicodeDecodeError)) and exc.errno:
        return RunFileError(f"cannot read ({exc.strerror or exc})")
    first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
    return RunFileError(f"corrupt or truncated {suffix[1:]} file ({printable(first[:200])})")


def _csv_dialect(path: Path) -> tuple[list[str], str, str]:
    """The header names, separator and decimal mark of a ``.csv`` recording, from its first two
    lines read bounded (:data:`MAX_HEADER_BYTES` each)."""
    from ..io import head_lines, printable

    try:
        head, second = head_lines(path, 2, "time_s, seat_z_m_s2, …")
    except ValueError as exc:
        raise RunFileError(str(exc)) from None
    try:
        header = head.decode("utf-8-sig").strip("\r\n")
        first_row = second.decode("utf-8", errors="replace").strip("\r\n")
    except UnicodeDecodeError:
        raise RunFileError("the header line is not UTF-8 text; save the recording as 'CSV UTF-8'") from None
    known = {"time_s", *RIDE_CHANNELS}
    best, names = None, []
    for sep in (",", ";", "\t"):
        cols = [c.strip().strip('"') for c in header.split(sep)]
        score = (("time_s" in cols), len(known.intersection(cols)), len(cols))
        if best is None or score > best[0]:
            best, names = (score, sep), cols
    (has_time, n_known, _), sep = best
    if not n_known:
        raise RunFileError(f"no known column in the header {printable(header[:80])!r} with ',', ';' or tab as "
                           f"separator (expected time_s and any of {', '.join(RIDE_CHANNELS)})")
    decimal = "."
    if sep != ",":
        values = [v.strip().strip('"') for v in first_row.split(sep)]
        if any(_DECIMAL_COMMA.match(v) for v in values) and not any(_DECIMAL_POINT.match(v) for v in values):
            decimal = ","
    return names, sep, decimal


#: A number written with a decimal comma (``0,25``, ``-1,5e-3``), and one with a decimal point.
_DECIMAL_COMMA = re.compile(r"^[+-]?\d*,\d+([eE][+-]?\d+)?$")
_DECIMAL_POINT = re.compile(r"^[+-]?\d*\.\d+([eE][+-]?\d+)?$")


def _parquet(path: Path) -> pq.ParquetFile:
    """Opened to stream: no pre-buffering of whole row groups (an 8 h day read with pyarrow's
    defaults peaks at ~0.5 GB more; with these at ~0.13 GB, and reads faster)."""
    return pq.ParquetFile(path, pre_buffer=False, buffer_size=1 << 20)


def _rows(frame) -> int:
    return len(next(iter(frame.values()))) if isinstance(frame, dict) else len(frame)


def _first_rows(frames: Iterator, n: int):
    """The first ``n`` rows of ``frames`` as one frame (fewer if there are no more), and the rest of
    the last frame read (``None`` if it ended there); ``(None, None)`` if there is no row."""
    parts, rows = [], 0
    for f in frames:
        if _rows(f):
            parts.append(f)
            rows += _rows(f)
        if rows >= n:
            break
    if not parts:
        return None, None
    if isinstance(parts[0], dict):
        first = {k: np.concatenate([p[k] for p in parts]) if len(parts) > 1 else parts[0][k] for k in parts[0]}
        if rows > n:
            return {k: v[:n] for k, v in first.items()}, {k: v[n:] for k, v in first.items()}
        return first, None
    first = pd.concat(parts, ignore_index=True) if len(parts) > 1 else parts[0]
    if rows > n:
        return first.iloc[:n], first.iloc[n:]
    return first, None


def _header(path: Path, channel_map: dict | None) -> list[str]:
    suffix = path.suffix.lower()
    try:
        if suffix == ".parquet":
            return list(_parquet(path).schema_arrow.names)
    except (pa.ArrowException, OSError, ValueError, UnicodeDecodeError, pd.errors.ParserError) as exc:
        raise _read_error(exc, suffix) from None
    return ["time_s", *RIDE_CHANNELS]  # mapped: the map decides; missing channels are dropped later


def _checked(frame, channels, row0: int) -> Chunk:
    """A chunk's ``time_s`` and ``channels`` as float arrays (``frame``: a DataFrame, or a dict of
    arrays from Parquet), each sample finite."""
    out = {}
    names = frame.keys() if isinstance(frame, dict) else frame.columns
    for c in ("time_s", *channels):
        if c not in names:
            raise RunFileError(f"channel {c} is missing")
        v = frame[c]
        if isinstance(v, np.ndarray) and v.dtype.kind in "fiu":
            v = v.astype(float, copy=False)
        else:
            v = pd.to_numeric(pd.Series(v) if isinstance(v, np.ndarray) else v, errors="coerce").to_numpy(dtype=float)
        if c == "time_s":  # one pass in the usual case; a sum of finite samples can still overflow
            with np.errstate(over="ignore"):
                finite = math.isfinite(float(np.add.reduce(v)))
        else:  # max and min: a NaN propagates, and the bound is checked in the same two passes
            finite = bool(v.size == 0 or (v.max() <= MAX_ABS_SAMPLE and v.min() >= -MAX_ABS_SAMPLE))
        if not finite:
            bad = ~np.isfinite(v)
            if bad.any():
                i = int(np.flatnonzero(bad)[0])
                every = _every_nth(bad)
                if every:
                    raise RunFileError(f"channel {c} has a sample only every {every} rows (rows {row0 + i} and on are "
                                       f"empty between them): recorded at 1/{every} of the rate of time_s? resample "
                                       "every channel to one rate")
                raise RunFileError(f"channel {c} has a NaN, infinite or non-numeric sample at row {row0 + i}")
            if c != "time_s":
                i = int(np.flatnonzero(np.abs(v) > MAX_ABS_SAMPLE)[0])
                unit = "rad/s²" if c.endswith("rad_s2") else "m" if c.endswith("_m") else "m/s²"
                raise RunFileError(f"channel {c} has a sample of {v[i]:.3g} {unit} at row {row0 + i}, beyond the "
                                   f"±{MAX_ABS_SAMPLE:g} {unit} a vehicle's vibration can reach (a corrupt or "
                                   "mis-scaled file?)")
        out[c] = v
    t = out.pop("time_s")
    return Chunk(t, out)


def _every_nth(bad: np.ndarray) -> int:
    """``k`` (2 or more) when the finite samples of a chunk recur exactly every ``k`` rows (a channel
    recorded at a lower rate, its rows between left empty), else 0."""
    good = np.flatnonzero(~bad)
    if good.size < 3 or bad.size < 8:
        return 0
    step = np.diff(good)
    k = int(step[0])
    if k < 2 or not (step == k).all() or good[0] >= k or bad.size - 1 - good[-1] >= k:
        return 0
    return k


def _regular(t: np.ndarray, dt: float, row0: int) -> None:
    d = np.diff(t)
    if d.size and float(d.min()) >= (1 - MAX_DT_JITTER) * dt and float(d.max()) <= (1 + MAX_DT_JITTER) * dt:
        return  # two passes for the usual, regular case; the row of a problem is looked for below
    if (d <= 0).any():
        i = int(np.flatnonzero(d <= 0)[0])
        raise RunFileError(f"time_s is not strictly increasing at row {row0 + i + 1}")
    bad = np.abs(d - dt) > MAX_DT_JITTER * dt
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise RunFileError(f"irregular sampling: interval at row {row0 + i + 1} is {d[i]:.6g} s, expected {dt:.6g} s")


def open_recording(path, channel_map: dict | None = None, chunk_rows: int = CHUNK_ROWS) -> Recording:
    """Open a recording and check its header and first chunk.

    Parameters
    ----------
    path : path
        ``.parquet``, ``.csv``, or ``.mf4``/``.tdms`` with ``channel_map``.
    channel_map : dict, optional
        For ``.mf4``/``.tdms`` (:func:`tyrelab.rawformat.load_channel_map`).
    chunk_rows : int
        Rows of the first chunk (its checks and the offsets); later chunks have at most
        ``min(chunk_rows, READ_ROWS)``.

    Raises
    ------
    RunFileError
        One line naming the problem.
    """
    from .files import regular_file

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in RECORDING_SUFFIXES:
        raise RunFileError(f"unknown file type {suffix!r} (expected {', '.join(RECORDING_SUFFIXES)})")
    size = regular_file(path).st_size
    limit = MAX_MAPPED_BYTES if suffix in mapped.SUFFIXES else MAX_RECORDING_BYTES
    if size > limit:
        raise RunFileError(f"file is {size / 1e9:.1f} GB, larger than the {limit / 1e9:.1f} GB limit")
    if size == 0:
        raise RunFileError("file is empty")
    dialect = (",", ".")
    if suffix == ".csv":
        names, *dialect = _csv_dialect(path)
    else:
        names = _header(path, channel_map)
    if "time_s" not in names:
        raise RunFileError("no time base: column time_s is missing")
    present = [c for c in RIDE_CHANNELS if c in names]
    if not present and suffix not in mapped.SUFFIXES:
        raise RunFileError(f"no known channel (expected any of {', '.join(RIDE_CHANNELS)})")
    frames = _frames(path, ["time_s", *present], min(chunk_rows, READ_ROWS), channel_map, tuple(dialect))
    frame, rest = _first_rows(frames, chunk_rows)
    if frame is None:
        raise RunFileError("no samples")
    if rest is not None:
        frames = itertools.chain([rest], frames)
    if suffix in mapped.SUFFIXES:
        present = [c for c in RIDE_CHANNELS if c in frame.columns]
        if not present:
            raise RunFileError(f"no known channel after the channel map (expected any of {', '.join(RIDE_CHANNELS)})")
    first = _checked(frame, present, 0)
    t = first.time_s
    if t.size < 2:
        raise RunFileError(f"only {t.size} sample(s)")
    dt = float(np.median(np.diff(t)))
    if not dt > 0:
        raise RunFileError("time_s is not strictly increasing at row 1")
    _regular(t, dt, 0)
    dt = float(np.mean(np.diff(t)))
    fs = 1.0 / dt
    if not SAMPLE_RATE_RANGE_Hz[0] <= fs <= SAMPLE_RATE_RANGE_Hz[1]:
        raise RunFileError(f"sample rate {fs:.4g} Hz outside {SAMPLE_RATE_RANGE_Hz[0]:g}-{SAMPLE_RATE_RANGE_Hz[1]:g} Hz")
    offsets = {c: float(v.mean()) for c, v in first.channels.items()}
    warnings = []
    for c, m in offsets.items():
        if not c.endswith("_m_s2"):
            continue
        spread = float(first.channels[c].std())
        if 0.85 < abs(m) < 1.15 and spread < 1.0 and c.endswith("z_m_s2"):
            raise RunFileError(f"channel {c} averages {m:.3f}: it looks like g, not m/s² (raw format v1 wants m/s²; "
                               f"multiply by {GRAVITY_M_S2})")
        if 0.85 * GRAVITY_M_S2 < abs(m) < 1.15 * GRAVITY_M_S2:
            warnings.append(f"channel {c} averages {m:.2f} m/s² (a ±1 g offset: gravity on a DC-coupled "
                            "accelerometer?); the offset is removed before the analysis")
    return Recording(path, tuple(present), fs, offsets, warnings, first, frames, dt)
