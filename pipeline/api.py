"""The library's entry points: one call per question, each returning a result object.

- :func:`analyse_recording` -- K, C and QC of one tyre-rig recording (``tyrelab analyse-run``);
  ``analyze_recording`` is the same function.
- :func:`ride` -- seat vibration and daily exposure of a tractor scenario (``tyrelab ride``).
- :func:`ride_sweep` -- the same for every variant of a sweep (``tyrelab ride`` with pressures, ``--set``).
- :func:`road_class` -- the ISO 8608 class of each track of a profile or an OpenCRG road (``tyrelab road``).
- :func:`exposure` -- a driver's daily exposure from seat recordings (``tyrelab exposure``).
- :func:`vehicle_frf` -- a vehicle's transfer functions and modes from a recording with wheel
  inputs (``tyrelab frf``; thesis ch. 2, issue 43).

Each answers without the stage machinery: reading the input is the only I/O here; the work is
the pure packages' (:func:`tyrelab.measurement.recording.analyse_frame`,
:func:`tyrelab.vehicle.ride.ride`, :func:`tyrelab.vehicle.daily_exposure.daily_exposure`), the
same code the pipeline's stages run. Every result has ``to_dict()`` (the command's JSON).

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

import numpy as np
import pandas as pd

from ._validate import finite, positive, shown
from .exposure import exposure
from .measurement.recording import RecordingResult, analyse_frame
from .rawformat import read_run_file

__all__ = ["analyse_recording", "analyze_recording", "ride", "ride_sweep", "road_class", "exposure", "vehicle_frf"]


def analyse_recording(
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

    See Also
    --------
    tyrelab.measurement.recording.analyse_frame : the same on a DataFrame, without reading.
    exposure : a seat recording's daily vibration exposure.

    Examples
    --------
    >>> analyse_recording("run.parquet", axle_mass_kg=0.0)
    Traceback (most recent call last):
    ...
    ValueError: axle_mass_kg must be finite and positive, got 0.0
    """
    positive("axle_mass_kg", axle_mass_kg)  # before reading a file
    if sample_rate_Hz is not None:
        positive("sample_rate_Hz", sample_rate_Hz)
    if interference_Hz is not None:
        if isinstance(interference_Hz, (str, bytes)) or not hasattr(interference_Hz, "__iter__"):
            raise ValueError(f"interference_Hz must be a list of frequencies, got {shown(interference_Hz)}")
        interference_Hz = [positive(f"interference_Hz[{i}]", f) for i, f in enumerate(interference_Hz)]
    if isinstance(recording, pd.DataFrame):
        return analyse_frame(recording, axle_mass_kg, sample_rate_Hz=sample_rate_Hz, interference_Hz=interference_Hz)
    if not isinstance(recording, (str, os.PathLike)):
        raise ValueError(f"recording must be a path or a pandas DataFrame, got {type(recording).__name__}")
    frame = read_run_file(Path(recording), channel_map=channel_map)
    return analyse_frame(frame, axle_mass_kg, sample_rate_Hz=sample_rate_Hz, interference_Hz=interference_Hz,
                         file=str(recording))


#: The same function as :func:`analyse_recording` (the American spelling, kept: ``tyrelab analyze-run``).
analyze_recording = analyse_recording


# --------------------------------------------------------------------------- vehicle
def _scenario(scenario):
    """A :class:`~tyrelab.vehicle.scenario.Scenario` from a path, TOML text, a dict or a Scenario."""
    from collections.abc import Mapping

    from .scenario_io import load_scenario, parse_scenario, scenario_from_dict
    from .vehicle.scenario import Scenario

    if isinstance(scenario, Scenario):
        return scenario
    if isinstance(scenario, Mapping):
        return scenario_from_dict(scenario, Path.cwd(), confine=False)
    if isinstance(scenario, str) and ("\n" in scenario or "=" in scenario):
        return parse_scenario(scenario, Path.cwd(), confine=False)
    if isinstance(scenario, (str, os.PathLike)):
        return load_scenario(scenario, confine=False)
    raise ValueError(f"scenario must be a path, TOML text, a dict or a Scenario, got {type(scenario).__name__}")


def ride(
    scenario,
    *,
    speeds_km_h: list[float] | None = None,
    front_pressure_bar: float | None = None,
    rear_pressure_bar: float | None = None,
    build: str | os.PathLike | None = None,
    with_spectra: bool = False,
    max_samples: int | None = None,
    max_rows: int | None = None,
):
    """Seat vibration and EU daily exposure of a tractor scenario: what ``tyrelab ride`` computes.

    Parameters
    ----------
    scenario : path, str, dict or Scenario
        A scenario file (``.toml``); its TOML text (a string holding a newline or ``=``); the
        same as a dict (``{"name": ..., "tractor": {...}, "tyres": {"front": {...}, "rear":
        {...}}, "surface": {...}, "exposure": {...}}``; every key with its unit, default and
        bounds: ``schemas/scenario.json``); or a parsed
        :class:`~tyrelab.vehicle.scenario.Scenario`. A ``surface.profile`` of text or a dict is
        relative to the current folder, of a file to the file's folder.
    speeds_km_h : list of float, optional
        Speeds to run instead of ``[exposure] speeds_km_h``, km/h.
    front_pressure_bar, rear_pressure_bar : float, optional
        Tyre pressures instead of the scenario's, bar.
    build : path, optional
        A build folder whose warehouse holds the tyres named by ``measured_tyre_id`` and the
        lab's fitted formula (``formula = "build"``).
    with_spectra : bool
        Also compute the seat PSD and transmissibility per speed (the page's figures).
    max_samples : int, optional
        Most 1 kHz samples the call may simulate over all speeds (default
        :data:`tyrelab.vehicle.scenario_limits.MAX_SAMPLES`, as ``tyrelab ride --max-samples``):
        more is refused with an estimate before any work.
    max_rows : int, optional
        Most spectral rows (speeds of a scenario whose ``[simulation] method`` is ``spectral``;
        default: what :data:`tyrelab.vehicle.scenario_limits.MAX_SPECTRAL_SECONDS` of the estimate
        allow, as ``tyrelab ride --max-rows``): more is refused before any work.

    Returns
    -------
    tyrelab.vehicle.ride.RideResult
        ``speeds`` (a DataFrame, one row per speed: ``a_wz_m_s2``, ``a_wx_m_s2``, ``a8_m_s2``,
        ``a8_axis``, ``hours_to_eav``, ``hours_to_elv``, ``verdict``, …), ``mode_table`` (a
        DataFrame: natural frequencies, their 95 % intervals, nodal points; ``modes`` holds the
        mode shapes), ``tyres``
        (stiffness and damping per tyre and speed with their sources), ``warnings``;
        ``to_dict()`` is the JSON of ``tyrelab ride``, ``to_json()`` its text.

    Raises
    ------
    tyrelab.vehicle.scenario.ScenarioError
        Every problem of the scenario at once (a ``ValueError``; ``.problems``, one per key).
    ValueError
        A bad argument, naming it (a speed or pressure outside what the model is built for, an
        integer too large for a float, a bool where a number belongs), or more work than
        ``max_samples`` allows.

    See Also
    --------
    exposure : the daily exposure from a seat recording instead of a prediction.
    tyrelab.vehicle.ride.ride_sweep : every pressure pair and swept key of a scenario.

    Examples
    --------
    >>> import tyrelab
    >>> r = tyrelab.ride(tyrelab.resources.scenarios_dir() / "modern_tractor.toml", speeds_km_h=[8])
    >>> row = r.speeds.iloc[0]
    >>> row["a8_axis"], row["verdict"], round(float(row["hours_to_eav"]), 1)
    ('z', 'above action value', 6.2)
    >>> list(r.mode_table["mode"])
    ['bounce', 'pitch']
    >>> r.to_dict()["speeds"][0]["a8_axis"]
    'z'
    """
    from .vehicle import ride as ride_module
    from .vehicle import scenario_limits as limits
    from .vehicle.scenario import with_overrides

    speeds, front, rear = _ride_arguments(speeds_km_h, front_pressure_bar, rear_pressure_bar, with_spectra,
                                          max_samples, max_rows)
    sc = with_overrides(_scenario(scenario), speeds, front, rear)
    # the work of one variant at every speed under the scenario's [simulation] method (spectral rows
    # or simulated samples), bounded as tyrelab ride bounds it, before any work
    method = sc.simulation.method
    too_much = limits.work_problems(sc, 1, speeds, method=method, with_spectra=bool(with_spectra), max_rows=max_rows,
                                    max_samples=limits.MAX_SAMPLES if max_samples is None else max_samples)
    if too_much:
        raise ValueError("; ".join(p.replace("--max-samples N", "max_samples=N").replace("--max-rows N", "max_rows=N")
                                   for p in too_much))
    if limits.uses_spectral(sc, method, 1):  # method = "spectral": the rows of tyrelab ride, in the frequency domain
        from .vehicle.run.frequency import spectral_variants

        result = spectral_variants([sc], _tyre_data(build), bool(with_spectra))[0]
        result.nominal = True
        return result
    return ride_module.ride(sc, _tyre_data(build), with_spectra=bool(with_spectra))


def _ride_arguments(speeds_km_h, front_pressure_bar, rear_pressure_bar, with_spectra, max_samples, max_rows=None):
    """:func:`ride`'s speeds and pressures as floats, checked like ``tyrelab ride``'s options (finite,
    within :data:`tyrelab.vehicle.scenario_limits.LIMITS`); ValueError naming every bad one at once."""
    from .vehicle import scenario_limits as limits

    problems = []

    def number(name, value):
        try:
            return finite(name, value)
        except ValueError as exc:
            problems.append(str(exc))
            return None

    speeds = None
    if speeds_km_h is not None:
        if isinstance(speeds_km_h, (str, bytes)) or not hasattr(speeds_km_h, "__iter__"):
            problems.append(f"speeds_km_h must be a list of numbers, got {shown(speeds_km_h)}")
        else:
            speeds = [number(f"speeds_km_h[{i}]", v) for i, v in enumerate(speeds_km_h)]
            if not speeds:
                problems.append("speeds_km_h must hold at least one speed (None: the scenario's)")
    front = None if front_pressure_bar is None else number("front_pressure_bar", front_pressure_bar)
    rear = None if rear_pressure_bar is None else number("rear_pressure_bar", rear_pressure_bar)
    if not isinstance(with_spectra, (bool, np.bool_)):
        problems.append(f"with_spectra must be True or False, got {shown(with_spectra)}")
    for name, value in (("max_samples", max_samples), ("max_rows", max_rows)):
        try:
            None if value is None else limits.bound_argument(name, value)
        except ValueError as exc:
            problems.append(str(exc))
    if not problems:
        problems = limits.override_problems(speeds, None if front is None else [front],
                                            None if rear is None else [rear])
        problems = [p.replace("front_pressures_bar", "front_pressure_bar").replace("rear_pressures_bar",
                                                                                     "rear_pressure_bar")
                    for p in problems]
    if problems:
        raise ValueError("; ".join(problems))
    return speeds, front, rear


def _numbers(name: str, values) -> list[float] | None:
    """``values`` (a list of numbers, or None) as floats; ValueError naming ``name[i]`` of a value
    that is no finite number (a bool, a string, an integer too large for a float)."""
    if values is None:
        return None
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise ValueError(f"{name} must be a list of numbers, got {shown(values)}")
    return [finite(f"{name}[{i}]", v) for i, v in enumerate(values)]


def _tyre_data(build):
    """The tyre data a ride reads: a build's warehouse (:class:`tyrelab.tyredata.WarehouseTyres`), else
    the shipped tables (None)."""
    if build is None:
        return None
    from .tyredata import WarehouseTyres

    return WarehouseTyres(build)


def ride_sweep(
    scenario,
    *,
    front_pressures_bar: list[float] | None = None,
    rear_pressures_bar: list[float] | None = None,
    speeds_km_h: list[float] | None = None,
    sets=None,
    build: str | os.PathLike | None = None,
    method: str | None = None,
    with_spectra: bool | str = False,
    max_variants: int | None = None,
    max_samples: int | None = None,
    map_fn=None,
    max_rows: int | None = None,
):
    """Every variant of a scenario's sweep: what ``tyrelab ride`` computes with pressures or ``--set``.

    Parameters
    ----------
    scenario : path, str, dict or Scenario
        As :func:`ride`.
    front_pressures_bar, rear_pressures_bar : list of float, optional
        Pressures to sweep, bar (default: the scenario's ``[sweep]``, else its tyres' pressures).
    speeds_km_h : list of float, optional
        Speeds instead of ``[exposure] speeds_km_h``, km/h.
    sets : dict or list of str, optional
        Numeric scenario keys to sweep: ``{"implement.mass_kg": [0, 500]}`` or ``--set``'s text
        ``["implement.mass_kg=0,500"]`` (:func:`tyrelab.vehicle.scenario.parse_sets`).
    build : path, optional
        As :func:`ride`.
    method : {"auto", "time", "spectral"}, optional
        How the rows are computed (default the scenario's ``[simulation] method``).
    with_spectra : bool or "nominal"
        Figure data of every variant, of none, or of the nominal variant alone.
    max_variants, max_samples : int, optional
        Bounds of the work (refused before any work, with the estimate).
    max_rows : int, optional
        Most spectral rows (variant x speed; default: what
        :data:`tyrelab.vehicle.scenario_limits.MAX_SPECTRAL_SECONDS` of the estimate allow).
    map_fn : callable, optional
        ``map_fn(task, items)``: the caller's executor (:func:`tyrelab.executor.map_batches`); default
        in-process.

    Returns
    -------
    list of tyrelab.vehicle.ride.RideResult
        One per variant (:func:`tyrelab.vehicle.ride.ride_sweep`); :func:`tyrelab.vehicle.ride.result_json`
        of the list is the command's JSON.

    Raises
    ------
    tyrelab.vehicle.scenario.ScenarioError
        The scenario's problems, or swept keys the model does not use, every one at once.
    ValueError
        A bad argument or too much work, naming it.

    See Also
    --------
    ride : one variant.
    tyrelab.vehicle.ride.ride_sweep : the same on a parsed scenario, with the tyre data handed in.

    Examples
    --------
    >>> import tyrelab
    >>> rs = tyrelab.ride_sweep(tyrelab.resources.scenarios_dir() / "modern_tractor.toml",
    ...                         front_pressures_bar=[1.2, 1.6], speeds_km_h=[8], method="spectral")
    >>> [(r.tyres["front"].pressure_bar, r.speeds.iloc[0]["method"]) for r in rs]
    [(1.2, 'spectral'), (1.6, 'spectral')]
    """
    from .vehicle import ride as ride_module
    from .vehicle.scenario import parse_sets

    if sets is None:
        sets = {}
    elif not hasattr(sets, "items"):
        sets = parse_sets(list(sets))
    else:  # every value a finite number, named (an integer of 400 digits, a bool, a string: one line)
        sets = {str(k): tuple(finite(f"sets[{str(k)!r}][{i}]", x)
                              for i, x in enumerate(v if hasattr(v, "__iter__") and not isinstance(v, str) else [v]))
                for k, v in sets.items()}
    front_pressures_bar, rear_pressures_bar = (_numbers(name, values) for name, values in (
        ("front_pressures_bar", front_pressures_bar), ("rear_pressures_bar", rear_pressures_bar)))
    return ride_module.ride_sweep(_scenario(scenario), front_pressures_bar, rear_pressures_bar, speeds_km_h,
                                  _tyre_data(build), map_fn, with_spectra=with_spectra, sets=sets,
                                  max_variants=max_variants, max_samples=max_samples, method=method,
                                  max_rows=max_rows)


def road_class(file: str | os.PathLike, *, track_width_m: float = 1.8, lateral_offset_m: float = 0.0,
               start_m: float = 0.0, length_m: float | None = None, fill_missing: bool = False) -> dict:
    """The ISO 8608 class, fitted ``G_d(n0)``, r.m.s. and length of each track of a road: what
    ``tyrelab road`` prints.

    Parameters
    ----------
    file : path
        A profile CSV (``distance_m`` and ``height_m``, or ``left_m``/``right_m``) or an OpenCRG
        road (``.crg``).
    track_width_m, lateral_offset_m : float
        An OpenCRG road's wheel tracks: their distance apart and the centre line's offset left of
        the road's reference line, m.
    start_m, length_m : float
        The stretch of an OpenCRG road read, m (default: all of it).
    fill_missing : bool
        An OpenCRG road's missing heights taken from their neighbours instead of refused.

    Returns
    -------
    dict
        ``file``, ``tracks`` (name -> ``class``, ``g0_m3``, ``rms_m``, ``length_m``,
        ``band_cycles_per_m``: :func:`tyrelab.vehicle.road_class.road_class`) and, for a CRG road,
        ``lateral_position_m`` of each track.

    Raises
    ------
    ValueError
        The file cannot be read or is no road the model takes, naming the file (and a CRG road's
        scenario key: ``surface.start_m``, ...).
    OSError
        The file cannot be opened.

    See Also
    --------
    tyrelab.vehicle.road_class.road_class : the class of one track's heights.

    Examples
    --------
    >>> import numpy as np, pandas as pd, tempfile, os
    >>> x = np.arange(0.0, 200.0, 0.05)
    >>> h = 2e-3 * np.sin(2 * np.pi * x / 3.0)  # one wavelength of 3 m, 2 mm
    >>> with tempfile.TemporaryDirectory() as d:
    ...     path = os.path.join(d, "road.csv")
    ...     pd.DataFrame({"distance_m": x, "height_m": h}).to_csv(path, index=False)
    ...     doc = road_class(path)
    >>> list(doc["tracks"]), round(doc["tracks"]["track"]["rms_m"] * 1e3, 2)  # 2 mm / sqrt(2)
    (['track'], 1.41)
    """
    from .scenario_io import read_crg, read_profile_csv
    from .vehicle import road_class as rc

    _road_arguments(track_width_m, lateral_offset_m, start_m, length_m, fill_missing)  # whatever the file
    path = Path(file)
    pos = None
    if path.suffix.lower() == ".crg":
        from .vehicle.crg import wheel_tracks

        data = read_crg(path)
        half = 0.5 * track_width_m
        pos = {"left": lateral_offset_m + half, "right": lateral_offset_m - half}
        x, tracks = wheel_tracks(data, pos, start_m, length_m, fill_missing)
        dx = data.u_inc_m
    else:
        from .vehicle.profiles import uniform_grid
        from .vehicle.scenario.limits import profile_problems

        x, left, right = read_profile_csv(path)
        problems = profile_problems(x, left, right)  # its grid bounded before it is built, as a ride's
        if problems:
            raise ValueError("; ".join(p.replace("surface.profile: ", "") for p in problems))
        grid, (left_u, right_u) = uniform_grid(x, left, right)
        dx = float(grid[1] - grid[0])
        tracks = {"track": left_u} if (left == right).all() else {"left": left_u, "right": right_u}
    doc = {"file": str(path), "tracks": {}}
    for name, h in tracks.items():
        c = rc.road_class(h, dx)
        doc["tracks"][name] = {"class": c["class"], "g0_m3": None if c["g0_m3"] is None else float(f"{c['g0_m3']:.6g}"),
                               "rms_m": round(c["rms_m"], 6), "length_m": round(c["length_m"], 6),
                               "band_cycles_per_m": None if c["band_cycles_per_m"] is None
                               else [round(b, 6) for b in c["band_cycles_per_m"]]}
    if pos is not None:
        doc["lateral_position_m"] = {k: round(v, 6) for k, v in pos.items()}
    return doc


def _argument_limits() -> dict[str, tuple[float, float, str]]:
    """:data:`~tyrelab.vehicle.scenario_limits.LIMITS` and the ranges of the arguments that are no
    scenario key: one home for the bounds of ``tyrelab``'s options and of this module's arguments
    (``frf_speed_km_h``: a standing vehicle to the ride model's fastest; ``frf_max_Hz``: up to the
    Nyquist frequency of raw format v1; ``stiffness_u_kN_per_m``)."""
    from .rawformat import SAMPLE_RATE_RANGE_Hz
    from .vehicle.scenario_limits import LIMITS

    return {**LIMITS, "stiffness_u_kN_per_m": (0.0, LIMITS["stiffness_kN_per_m"][1], "kN/m"),
            "frf_speed_km_h": (0.0, LIMITS["exposure.speeds_km_h"][1], "km/h"),
            "frf_max_Hz": (0.0, SAMPLE_RATE_RANGE_Hz[1] / 2, "Hz")}


def _in_range(name: str, value, key: str) -> float:
    """``value`` within :func:`_argument_limits`'s ``key`` range; ValueError naming ``name`` (as
    ``tyrelab``'s option of the same meaning says it)."""
    from ._validate import in_range

    low, high, unit = _argument_limits()[key]
    try:
        return in_range(name, value, low, high, unit)
    except ValueError as exc:
        raise ValueError(f"{exc} (the range the model is built for)" if "within" in str(exc) else str(exc)) from None


def _road_arguments(track_width_m, lateral_offset_m, start_m, length_m, fill_missing) -> None:
    """:func:`road_class`'s numbers in the ranges of ``tyrelab road``'s options, every problem at once."""
    problems = []
    for name, value, key in (("track_width_m", track_width_m, "tractor.front_track_m"),
                             ("lateral_offset_m", lateral_offset_m, "surface.lateral_offset_m"),
                             ("start_m", start_m, "surface.start_m"), ("length_m", length_m, "surface.length_m")):
        if value is None and name == "length_m":
            continue
        try:
            _in_range(name, value, key)
        except ValueError as exc:
            problems.append(str(exc))
    if not isinstance(fill_missing, (bool, np.bool_)):
        problems.append(f"fill_missing must be True or False, got {shown(fill_missing)}")
    if problems:
        raise ValueError("; ".join(problems))


class _FrameRecording:
    """A DataFrame of raw-format ride channels as an opened recording (one chunk)."""

    def __init__(self, frame: pd.DataFrame, sample_rate_Hz: float | None):
        import numpy as np

        from .rawformat import RunFileError
        from .rawformat.rides import RIDE_CHANNELS, Chunk

        self.channels = tuple(c for c in RIDE_CHANNELS if c in frame.columns)
        if not self.channels:
            raise RunFileError(f"no known channel (expected any of {', '.join(RIDE_CHANNELS)})")
        if "time_s" in frame.columns:
            t = frame["time_s"].to_numpy(dtype=float)
            dt = np.diff(t)
            if t.size < 2 or not np.all(np.isfinite(t)) or not (dt > 0).all():
                raise RunFileError("time_s is not finite and strictly increasing")
            fs = 1.0 / float(np.mean(dt))
            if sample_rate_Hz is not None and abs(fs - sample_rate_Hz) > 0.01 * sample_rate_Hz:
                raise RunFileError(f"time_s gives {fs:.6g} Hz, not the {sample_rate_Hz:g} Hz given")
        elif sample_rate_Hz is None:
            raise ValueError("sample_rate_Hz is needed for a frame without time_s")
        else:
            fs = float(sample_rate_Hz)
            t = np.arange(len(frame)) / fs
        data = {}
        for c in self.channels:
            v = frame[c].to_numpy(dtype=float)
            if not np.all(np.isfinite(v)):
                raise RunFileError(f"channel {c} has a NaN or infinite sample at row {int(np.flatnonzero(~np.isfinite(v))[0])}")
            data[c] = v
        self.sample_rate_Hz = fs
        self._chunk = Chunk(t, data)

    def chunks(self):
        yield self._chunk


def vehicle_frf(
    recording: str | os.PathLike | pd.DataFrame,
    *,
    speed_km_h: float = 0.0,
    scenario=None,
    sample_rate_Hz: float | None = None,
    channel_map: dict | None = None,
):
    """A vehicle's transfer functions from each wheel input to each output, and its modes.

    Thesis ch. 2: a four-post stand or a track with a measured profile (issue 43). The
    multiple-input H1 with its coherences, random error and conditioning, the rotation and
    lug-passing bins masked, the modes fitted with 95 % intervals
    (:func:`tyrelab.measurement.frf.recording_frf`, what the rides stage writes to
    ``vehicle_frf`` and ``vehicle_modes``).

    Parameters
    ----------
    recording : path or DataFrame
        Raw format v1 ride recording (``schemas/raw_ride.json``) with input channels
        ``input_<wheel>_z_m_s2`` or ``input_<wheel>_z_m``; or a DataFrame of them (without
        ``time_s``, give ``sample_rate_Hz``).
    speed_km_h : float
        Rolling speed (0: stationary).
    scenario : path, str, dict or Scenario, optional
        The vehicle (as :func:`ride`): with a speed above 0 its tyres' rotation and lug-passing
        bins are masked; its model at the speed (stationary tyres at 0 km/h, rolling above) gives
        the predicted FRFs (``predicted``, ``predicted_h_magnitude`` of the rows) and modes compared
        with the measured ones (``validation``: the rides stage's ``vehicle_frf_validation`` rows).
    sample_rate_Hz : float, optional
    channel_map : dict, optional
        For ``.mf4``/``.tdms``.

    Returns
    -------
    tyrelab.measurement.frf.RecordingFrf
        ``to_json()`` is ``tyrelab frf``'s JSON.

    Raises
    ------
    tyrelab.rawformat.RunFileError, ValueError
        One line: an unreadable recording, no input channel, a constant input, too short.

    See Also
    --------
    tyrelab.measurement.frf.recording_frf : the FRFs and modes of an opened recording.
    tyrelab.measurement.frf.fit_vehicle_modes : the modes' fit.

    Examples
    --------
    Four wheel inputs of random motion, a seat that follows the front left and rear left wheels by
    0.5 and 0.3 (and noise):

    >>> import numpy as np, pandas as pd, tyrelab
    >>> fs, n = 100.0, 100 * 120
    >>> x = np.random.default_rng(1).normal(size=(5, n))
    >>> wheels = ["front_left", "front_right", "rear_left", "rear_right"]
    >>> df = pd.DataFrame({"time_s": np.arange(n) / fs, **{f"input_{w}_z_m_s2": x[i] for i, w in enumerate(wheels)},
    ...                    "seat_z_m_s2": 0.5 * x[0] + 0.3 * x[2] + 0.05 * x[4]})
    >>> rows = pd.DataFrame(tyrelab.vehicle_frf(df).frf_rows())
    >>> rows.groupby("wheel")["h_magnitude"].median().round(2).to_dict()
    {'front_left': 0.5, 'front_right': 0.01, 'rear_left': 0.3, 'rear_right': 0.01}
    """
    from .measurement.frf import recording_frf
    from .rawformat.rides import open_recording

    speed = _in_range("speed_km_h", speed_km_h, "frf_speed_km_h")  # tyrelab frf --speed's range
    if sample_rate_Hz is not None:  # before reading the recording
        positive("sample_rate_Hz", sample_rate_Hz)
    wheels, sc = None, None
    if scenario is not None:
        from .measurement.frf import scenario_wheel_geometry

        sc = _scenario(scenario)
        wheels = scenario_wheel_geometry(sc) if speed > 0 else None
    if isinstance(recording, pd.DataFrame):
        rec = _FrameRecording(recording, sample_rate_Hz)
    else:
        rec = open_recording(Path(recording), channel_map)
    result = recording_frf(rec, speed, wheels)
    if sc is not None:  # the scenario's model at this speed beside the measurement (the rides stage's)
        from .stand import frf_validation_rows, predicted_frf

        result.predicted = predicted_frf(result, sc, speed)
        result.validation = frf_validation_rows(result, sc, speed, result.predicted)
    return result
