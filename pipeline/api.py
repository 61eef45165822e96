"""The library's entry point for one recording: ``tyrelab.analyze_recording``.

What a scientist imports: K, C and QC of one recording, from a run file or a
DataFrame, without the stage machinery. Reading the file is the only I/O here;
the analysis is :func:`tyrelab.measurement.recording.analyse_frame` (pure), the
same code the analyse stage runs on batches.

Examples
--------
>>> import tyrelab
>>> from tyrelab.rawformat import RunFileError
>>> try:
...     tyrelab.analyze_recording("no-such-run.parquet", axle_mass_kg=600.0)
... except RunFileError as exc:
...     print(exc)
file not found
"""

from __future__ import annotations

import os
from pathlib import Path

import pandas as pd

from ._validate import positive
from .measurement.recording import RecordingResult, analyse_frame
from .rawformat import read_run_file

__all__ = ["analyze_recording"]


def analyze_recording(
    recording: str | os.PathLike | pd.DataFrame,
    axle_mass_kg: float,
    *,
    sample_rate_Hz: float | None = None,
    interference_Hz: list[float] | None = None,
    channel_map: dict | None = None,
) -> RecordingResult:
    """Stiffness K, damping C and QC of one recording (thesis ch. 3, §3.5).

    Parameters
    ----------
    recording : path or DataFrame
        A run file in raw format v1 (``.parquet``, ``.csv``; ``.mf4``/``.tdms``
        through ``channel_map``), or a DataFrame with its channels
        (:data:`tyrelab.rawformat.CHANNELS`; accelerations upward positive,
        m/s²; load-beam forces on the axle, N). A frame without ``time_s``
        needs ``sample_rate_Hz``.
    axle_mass_kg : float
        Mass of axle, wheel and tyre below the load beams M_a, kg (§3.2.8).
    sample_rate_Hz : float, optional
        Expected sampling rate, Hz: checked against the time base (or used to
        make one when the frame has no ``time_s``).
    interference_Hz : list of float, optional
        Frequencies of the wheel's own excitation (rotation, lug passing) for
        the QC of rolling runs (:func:`tyrelab.measurement.qc.interference_frequencies_Hz`).
    channel_map : dict, optional
        Channel map for ``.mf4``/``.tdms`` files (:mod:`tyrelab.rawformat.mapped`).

    Returns
    -------
    RecordingResult
        K, C, apparent mass, excitation frequency and amplitude, coherence,
        the thesis' Welch estimate, QC with reasons; ``to_dict()`` gives the
        JSON of ``tyrelab analyze-run``.

    Raises
    ------
    ValueError
        If ``axle_mass_kg`` or ``sample_rate_Hz`` is not finite and positive,
        or ``recording`` is neither a path nor a DataFrame.
    tyrelab.rawformat.RunFileError
        If the recording is unreadable or fails the raw-format checks.

    Examples
    --------
    >>> analyze_recording("run.parquet", axle_mass_kg=0.0)
    Traceback (most recent call last):
    ...
    ValueError: axle_mass_kg must be finite and positive, got 0.0
    """
    if isinstance(recording, pd.DataFrame):
        return analyse_frame(recording, axle_mass_kg, sample_rate_Hz=sample_rate_Hz, interference_Hz=interference_Hz)
    if not isinstance(recording, (str, os.PathLike)):
        raise ValueError(f"recording must be a path or a pandas DataFrame, got {type(recording).__name__}")
    positive("axle_mass_kg", axle_mass_kg)  # before reading a file
    frame = read_run_file(Path(recording), channel_map=channel_map)
    return analyse_frame(frame, axle_mass_kg, sample_rate_Hz=sample_rate_Hz, interference_Hz=interference_Hz,
                         file=str(recording))
