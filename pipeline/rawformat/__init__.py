"""Raw recording format v1: the one home of the run-file contract.

A run file holds one row per sample at a constant rate: ``time_s`` and the
channels :data:`CHANNELS` (accelerations of the two axle ends, upward
positive, m/s²; the four load-beam forces the carriage exerts on the axle,
upward positive, N), plus ``force_plate_N`` on force-plate calibration runs
and ``deflection_m`` (tyre deflection, m, compression positive) on
``load_deflection`` runs (issue 34). A lateral or longitudinal run records the
same channels along its direction (:mod:`tyrelab.measurement.rig_methods`).
``.parquet`` and ``.csv`` are read as they are; ``.mf4``/``.tdms`` go through
a channel map (:mod:`tyrelab.rawformat.mapped`). Every problem raises
:class:`RunFileError` with a one-line reason, which the stages put in the
quarantine table and the CLI prints.

Used by ingest, analyse, calibrate, the CLI, the library API and the virtual
rig (which writes exactly these channels).

Examples
--------
>>> from tyrelab.rawformat import CHANNELS, ACCEL_CHANNELS, BEAM_CHANNELS
>>> CHANNELS[:2] == ACCEL_CHANNELS and CHANNELS[2:] == BEAM_CHANNELS
True
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from . import mapped
from ..units import STANDARD_GRAVITY_M_S2
from .mapped import CHANNEL_MAP, FormatError, RunFileError, load_channel_map, read_mapped

__all__ = [
    "CHANNELS", "ACCEL_CHANNELS", "BEAM_CHANNELS", "OPTIONAL_CHANNELS", "TIME", "RUN_SUFFIXES",
    "MAX_RUN_FILE_BYTES", "SAMPLE_RATE_RANGE_Hz", "MIN_SAMPLES_PER_CYCLE", "MIN_DURATION_s", "TRANSIENT_MIN_DURATION_s", "MAX_DT_JITTER",
    "RunFileError", "FormatError", "RunInfo", "read_run_file", "check_run",
    "CHANNEL_MAP", "load_channel_map", "read_mapped",
]

#: Name of the time channel, s.
TIME = "time_s"

#: Largest run file read, bytes; larger files are quarantined unread.
MAX_RUN_FILE_BYTES = 512 * 1024**2

#: Accepted sampling rates, Hz, and the minimum samples per excitation cycle.
SAMPLE_RATE_RANGE_Hz = (32.0, 20000.0)
MIN_SAMPLES_PER_CYCLE = 8
#: Shortest usable run, s (at least a few dozen cycles at 1.5 Hz).
MIN_DURATION_s = 10.0
#: Shortest free-vibration (transient) record, s (issue 44): a decay is over in a few seconds, so it
#: is not held to the stepped sine's minimum; two seconds hold three cycles of a 1.5 Hz decay
#: (the analysis needs three, :func:`tyrelab.measurement.rig_methods.free_vibration_run`).
TRANSIENT_MIN_DURATION_s = 2.0
#: Methods whose records are transients (:data:`TRANSIENT_MIN_DURATION_s`).
TRANSIENT_METHODS = ("free_vibration",)
#: Allowed relative jitter of the sampling interval.
MAX_DT_JITTER = 0.01

#: Axle-end accelerations, upward positive, m/s².
ACCEL_CHANNELS = ["accel_left_m_s2", "accel_right_m_s2"]
#: Load-beam forces on the axle, upward positive, N.
BEAM_CHANNELS = ["load_beam_1_N", "load_beam_2_N", "load_beam_3_N", "load_beam_4_N"]
#: Every required channel but time, in this order (accelerations, then beams).
CHANNELS = [*ACCEL_CHANNELS, *BEAM_CHANNELS]
#: Channels some runs add: the force plate of a calibration run, the deflection of a load-deflection run.
OPTIONAL_CHANNELS = ["force_plate_N", "deflection_m"]
#: Suffixes of run files: raw format v1, and other formats read through a channel map.
RUN_SUFFIXES = (".parquet", ".csv", *mapped.SUFFIXES)



@dataclass(frozen=True)
class RunInfo:
    """What ingest learns from a valid run file."""

    sample_rate_Hz: float
    n_samples: int
    duration_s: float
    channels: tuple[str, ...]


#: The largest magnitude a converted channel (float32) holds; a sample beyond it would become infinite.
_FLOAT32_MAX = float(np.finfo(np.float32).max)


def read_run_file(path: Path, columns: list[str] | None = None, channel_map: dict | None = None) -> pd.DataFrame:
    """Read a run file into a DataFrame of raw-format-v1 columns.

    ``.parquet`` and ``.csv`` are raw format v1; ``.mf4`` (ASAM MDF4) and
    ``.tdms`` (NI TDMS) are read through ``channel_map``
    (:mod:`tyrelab.rawformat.mapped`). The size is checked before anything is read.

    Raises
    ------
    RunFileError
        With a one-line reason if the file is missing, too large, truncated,
        corrupt or of an unknown type.

    See Also
    --------
    check_run : validates what it read.
    load_channel_map : the map of an ``.mf4`` or ``.tdms`` file.

    Examples
    --------
    >>> t = np.arange(0, 20, 1 / 256)
    >>> run = pd.DataFrame({"time_s": t, **{c: np.sin(2 * np.pi * 4 * t) for c in CHANNELS}})
    >>> import tempfile
    >>> path = Path(tempfile.mkdtemp()) / "r1.csv"
    >>> run.to_csv(path, index=False)
    >>> list(read_run_file(path, columns=["time_s", "accel_left_m_s2"]).columns)
    ['time_s', 'accel_left_m_s2']
    """
    path = Path(path)
    from .files import regular_file  # a folder, FIFO or device is named (a FIFO would block the read)

    size = regular_file(path).st_size
    if size > MAX_RUN_FILE_BYTES:
        raise RunFileError(f"file is {size / 1e9:.1f} GB, larger than the {MAX_RUN_FILE_BYTES / 1e6:.0f} MB limit")
    if size == 0:
        raise RunFileError("file is empty")
    suffix = path.suffix.lower()
    try:
        if suffix == ".parquet":
            pf = pq.ParquetFile(path)
            wanted = None if columns is None else [c for c in columns if c in pf.schema_arrow.names]
            return pf.read(columns=wanted).to_pandas()
        if suffix == ".csv":
            return pd.read_csv(path, usecols=lambda c: columns is None or c in columns)
        if suffix in mapped.SUFFIXES:
            return mapped.read_mapped(path, CHANNELS, OPTIONAL_CHANNELS, channel_map)
    except RunFileError:
        raise
    except (pa.ArrowException, OSError, ValueError, UnicodeDecodeError, pd.errors.ParserError) as exc:
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise RunFileError(f"corrupt or truncated {suffix[1:]} file ({first})") from None
    raise RunFileError(f"unknown file type {suffix!r} (expected {', '.join(RUN_SUFFIXES)})")


def check_run(df: pd.DataFrame, excitation_frequency_Hz: float, sample_rate_Hz: float | None = None,
              method: str = "stepped_sine") -> RunInfo:
    """Validate a run's channels; return its sampling facts.

    Checks required channels, numeric finite samples, a strictly increasing
    and regular time base, the sampling rate (accepted range, enough samples
    per excitation cycle, agreement with the manifest's ``sample_rate_Hz``
    when given) and a minimum duration (:data:`MIN_DURATION_s`; a ``method`` of
    :data:`TRANSIENT_METHODS`: :data:`TRANSIENT_MIN_DURATION_s`).

    Raises
    ------
    RunFileError
        With a one-line reason.

    See Also
    --------
    read_run_file : reads the file it checks.

    Examples
    --------
    >>> t = np.arange(0, 20, 1 / 256)
    >>> run = pd.DataFrame({"time_s": t, **{c: np.sin(2 * np.pi * 4 * t) for c in CHANNELS}})
    >>> check_run(run, excitation_frequency_Hz=4.0)
    RunInfo(sample_rate_Hz=256.0, n_samples=5120, duration_s=20.0, channels=('time_s', 'accel_left_m_s2', 'accel_right_m_s2', 'load_beam_1_N', 'load_beam_2_N', 'load_beam_3_N', 'load_beam_4_N'))
    >>> try:
    ...     check_run(run.iloc[:1000], excitation_frequency_Hz=4.0)
    ... except RunFileError as exc:
    ...     print(exc)
    run is 3.9 s long, shorter than 10 s (truncated?)
    """
    # the manifest's numbers (excitation_frequency_Hz 0: not known, no cycle check; sample_rate_Hz None: not given)
    for name, value, least in (("excitation_frequency_Hz", excitation_frequency_Hz, 0.0), ("sample_rate_Hz", sample_rate_Hz, None)):
        if value is None and name == "sample_rate_Hz":
            continue
        try:
            ok = np.isfinite(float(value)) and (float(value) >= least if least is not None else float(value) > 0)
        except (TypeError, ValueError):
            ok = False
        if not ok:
            raise RunFileError(f"{name} must be finite and {'non-negative' if least is not None else 'positive'}, "
                               f"got {value!r}")
    missing = [c for c in ["time_s", *CHANNELS] if c not in df.columns]
    if missing:
        raise RunFileError(f"missing channel(s) {', '.join(missing)}")
    present = ["time_s", *CHANNELS, *[c for c in OPTIONAL_CHANNELS if c in df.columns]]
    for c in present:
        values = pd.to_numeric(df[c], errors="coerce").to_numpy(dtype=float)
        if np.isnan(values).any():
            i = int(np.flatnonzero(np.isnan(values))[0])
            raise RunFileError(f"channel {c} has a NaN or non-numeric sample at row {i}")
        if np.isinf(values).any():
            i = int(np.flatnonzero(np.isinf(values))[0])
            raise RunFileError(f"channel {c} has an infinite sample at row {i}")
        if c != "time_s" and (np.abs(values) > _FLOAT32_MAX).any():  # stored as float32 (the ingest stage)
            i = int(np.flatnonzero(np.abs(values) > _FLOAT32_MAX)[0])
            raise RunFileError(f"channel {c} has a sample of {values[i]:g} at row {i}, beyond the "
                               f"{_FLOAT32_MAX:.3g} a float32 channel holds (not a measurement)")
    g = STANDARD_GRAVITY_M_S2
    mean_accel = [float(pd.to_numeric(df[c]).mean()) for c in ("accel_left_m_s2", "accel_right_m_s2")]
    if all(-1.15 * g < m < -0.85 * g for m in mean_accel):
        raise RunFileError(
            f"accelerations average {np.mean(mean_accel):.2f} m/s²: they look downward-positive; "
            "raw format v1 wants upward-positive (+g at rest, or 0 if AC-coupled)"
        )
    t = df["time_s"].to_numpy(dtype=float)
    if t.size < 2:
        raise RunFileError(f"only {t.size} sample(s)")
    dt = np.diff(t)
    if (dt <= 0).any():
        i = int(np.flatnonzero(dt <= 0)[0])
        raise RunFileError(f"time_s is not strictly increasing at row {i + 1}")
    dt_med = float(np.median(dt))
    jitter = np.abs(dt - dt_med) / dt_med
    if (jitter > MAX_DT_JITTER).any():
        i = int(np.flatnonzero(jitter > MAX_DT_JITTER)[0])
        raise RunFileError(f"irregular sampling: interval at row {i + 1} is {dt[i]:.6g} s, median {dt_med:.6g} s")
    fs = 1.0 / float(np.mean(dt))
    if not SAMPLE_RATE_RANGE_Hz[0] <= fs <= SAMPLE_RATE_RANGE_Hz[1]:
        raise RunFileError(f"sample rate {fs:.4g} Hz outside {SAMPLE_RATE_RANGE_Hz[0]:g}-{SAMPLE_RATE_RANGE_Hz[1]:g} Hz")
    if sample_rate_Hz is not None and not np.isnan(sample_rate_Hz) and abs(fs / sample_rate_Hz - 1) > 0.005:
        raise RunFileError(f"sample rate {fs:.4g} Hz does not match the manifest's {sample_rate_Hz:g} Hz")
    if fs < MIN_SAMPLES_PER_CYCLE * excitation_frequency_Hz:
        raise RunFileError(
            f"sample rate {fs:.4g} Hz too low for {excitation_frequency_Hz:g} Hz excitation "
            f"(need {MIN_SAMPLES_PER_CYCLE} samples per cycle)"
        )
    duration = float(t[-1] - t[0] + np.mean(dt))
    shortest = TRANSIENT_MIN_DURATION_s if method in TRANSIENT_METHODS else MIN_DURATION_s
    if duration < shortest:
        raise RunFileError(f"run is {duration:.1f} s long, shorter than {shortest:g} s (truncated?)")
    return RunInfo(fs, int(t.size), duration, tuple(present))
