"""Predictions checked against recordings (issue 24; thesis §6.4, §7.4).

A recording of a vehicle's seat, made at a speed on a track, is compared with the prediction
of the scenario describing that vehicle at that speed on that track
(:func:`tyrelab.vehicle.ride.ride` with ``with_signals``). Both go through the same analysis
(:func:`tyrelab.vehicle.measured_ride.analyse_signals` /
:func:`~tyrelab.vehicle.measured_ride.analyse_recording`), so a comparison compares like with
like. Per axis: measured and predicted a_w and their ratio (measured / predicted), the
dominant peak frequency and half-power width of the unweighted seat PSD of each, and, where
the track is a known profile (a profile CSV, or the scenario's own track), the envelope
similarity R by complex demodulation (:func:`tyrelab.vehicle.metrics.envelope`,
:func:`~tyrelab.vehicle.metrics.envelope_similarity`). Over a campaign, the thesis'
statistics of the ratio errors predicted / measured (mean, sd, P(±10 %), P(±30 %);
:func:`tyrelab.vehicle.metrics.ratio_error_statistics`).

The track of a recording (``rides.csv`` column ``track``): ``scenario`` (or empty) for the
scenario's own track; an ISO 8608 class (``C`` or ``ISO 8608 class C``): a seeded
realisation of that class, so only spectra compare (R is not computed); a profile CSV of the
campaign (``x_m, left_m, right_m``).
"""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path

import numpy as np
import pandas as pd

from ... import _validate
from ..comfort import metrics as mt
from ..comfort.measured_ride import RecordingAnalysis, analyse_signals

__all__ = ["ValidationTrack", "track_of", "predicted_seat", "validation_rows", "validation_statistics",
           "ENVELOPE_CUTOFF_HZ", "MAX_ENVELOPE_S", "SEAT_AXES"]

#: Low-pass cutoff of the complex demodulation (as :func:`tyrelab.vehicle.metrics.compare_records`), Hz.
ENVELOPE_CUTOFF_HZ = 0.5
#: Longest recording whose envelope is compared (held in memory), s: a pass over a track.
MAX_ENVELOPE_S = 3600.0
#: Seat channels compared, by axis.
SEAT_AXES = {"z": "seat_z_m_s2", "x": "seat_x_m_s2", "y": "seat_y_m_s2"}
_CLASS = re.compile(r"^\s*(?:iso\s*8608\s*)?(?:class\s*)?([A-H])\s*$", re.IGNORECASE)


@dataclasses.dataclass(frozen=True)
class ValidationTrack:
    """The track a recording was made on, as the prediction uses it."""

    kind: str  # "scenario", "iso8608" or "profile"
    road_class: str | None = None
    profile: Path | None = None

    @property
    def known_profile(self) -> bool:
        """Whether the recording and the prediction ran over the same elevations (R is meaningful)."""
        return self.kind in ("scenario", "profile")


def track_of(text, campaign: Path | None = None) -> ValidationTrack:
    """Parse a ``rides.csv`` ``track`` value (see the module docstring).

    Raises
    ------
    ValueError
        An unknown track, or a profile CSV outside the campaign or missing.

    See Also
    --------
    predicted_seat : the prediction on that track.

    Examples
    --------
    >>> track_of("ISO 8608 class d").road_class, track_of("").kind
    ('D', 'scenario')
    """
    _validate.instance("text", text, (str, float, type(None)))  # a blank cell of a table reads as None or NaN
    s = "" if text is None or (isinstance(text, float) and math.isnan(text)) else str(text).strip()
    if s.lower() in ("", "scenario"):
        return ValidationTrack("scenario")
    m = _CLASS.match(s)
    if m:
        return ValidationTrack("iso8608", road_class=m.group(1).upper())
    if s.lower().endswith(".csv"):
        if campaign is None:
            raise ValueError(f"track {s!r}: a profile CSV needs its campaign folder")
        from ...rawformat import RunFileError
        from ...rawformat.files import confined_run_path

        try:
            return ValidationTrack("profile", profile=confined_run_path(campaign, s))
        except RunFileError as exc:
            raise ValueError(f"track {s!r}: {exc}") from None
    raise ValueError(f"track {s!r}: expected 'scenario', an ISO 8608 class A-H or a profile CSV of the campaign")


def predicted_seat(scenario, speed_km_h: float, track: ValidationTrack, tyre_data=None) -> tuple[dict, float]:
    """The scenario's predicted seat record at one speed on the recording's track.

    ``tyre_data`` is :func:`tyrelab.vehicle.ride.ride`'s (default: the shipped tyre data).

    Returns
    -------
    signals : dict
        ``seat_z_m_s2``, ``seat_x_m_s2`` -> samples (the pitch-plane model has no y).
    fs_Hz : float

    See Also
    --------
    track_of : the track it rides.
    validation_rows : the comparison with the measured record.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> from tyrelab.vehicle.scenario.variants import with_values
    >>> s = with_values(load_scenario(scenarios_dir() / "modern_tractor.toml"), {"surface.length_m": 60})
    >>> signals, fs = predicted_seat(s, 8.0, track_of("scenario"))     # the scenario's own track, 8 km/h
    >>> sorted(signals), fs
    (['floor_x_m_s2', 'floor_z_m_s2', 'seat_x_m_s2', 'seat_z_m_s2'], 1000.0)
    """
    _validate.non_negative("speed_km_h", speed_km_h)
    _validate.instance("track", track, ValidationTrack)
    from ..ride import FS_HZ, ride
    from ..scenario import with_overrides

    s = with_overrides(scenario, speeds_km_h=[float(speed_km_h)])
    if track.kind == "iso8608":
        s = dataclasses.replace(s, surface=dataclasses.replace(s.surface, kind="iso8608", road_class=track.road_class,
                                                               profile=None))
    elif track.kind == "profile":
        s = dataclasses.replace(s, surface=dataclasses.replace(s.surface, kind="profile", profile=track.profile,
                                                               road_class=None, spectrum_g0_m3=None))
    res = ride(s, tyre_data, with_spectra=False, with_signals=True)
    return next(iter(res.signals.values())), FS_HZ


def _envelope_similarity(measured: np.ndarray, fs_m: float, f_m: float, predicted: np.ndarray, fs_p: float,
                         f_p: float) -> float:
    """R of the two envelopes on the recording's time base (the prediction interpolated onto it)."""
    n = min(measured.size, int(predicted.size * fs_m / fs_p))
    if n < 4 or not (math.isfinite(f_m) and math.isfinite(f_p)):
        return math.nan
    t = np.arange(n) / fs_m
    pred = np.interp(t, np.arange(predicted.size) / fs_p, predicted)
    env_m = mt.envelope(measured[:n], fs_m, f_m, ENVELOPE_CUTOFF_HZ)
    env_p = mt.envelope(pred, fs_m, f_p, ENVELOPE_CUTOFF_HZ)
    return mt.envelope_similarity(env_p, env_m, fs_m)


def validation_rows(measured: RecordingAnalysis, predicted_signals: dict, predicted_fs_Hz: float,
                    known_profile: bool, measured_signals: dict | None = None) -> list[dict]:
    """Per seat axis recorded and predicted (and moved by the model): the measured-vs-predicted values.

    Parameters
    ----------
    measured : RecordingAnalysis
        The recording's analysis.
    predicted_signals : dict
        Channel -> predicted samples at ``predicted_fs_Hz``.
    known_profile : bool
        Whether both ran over the same elevations (then R is computed).
    measured_signals : dict, optional
        Channel -> recorded samples (offset included or not), for R; without it R is NaN.

    Returns
    -------
    list of dict
        ``axis, measured_a_w_m_s2, predicted_a_w_m_s2, ratio_a_w`` (measured / predicted),
        ``measured_peak_frequency_Hz, predicted_peak_frequency_Hz, measured_half_power_width_Hz,
        predicted_half_power_width_Hz, envelope_similarity``.

    See Also
    --------
    predicted_seat : the predicted record.
    validation_statistics : the statistics over the rows.

    Examples
    --------
    >>> from tyrelab.vehicle.comfort.measured_ride import analyse_signals
    >>> fs = 200.0; t = np.arange(0, 60, 1 / fs); z = np.sin(2 * np.pi * 4 * t)
    >>> rows = validation_rows(analyse_signals({"seat_z_m_s2": z}, fs), {"seat_z_m_s2": 1.1 * z}, fs, known_profile=False)
    >>> round(rows[0]["ratio_a_w"], 4), rows[0]["measured_peak_frequency_Hz"]        # measured / predicted
    (0.9091, 4.0)
    """
    _validate.instance("measured", measured, RecordingAnalysis)
    _validate.positive("predicted_fs_Hz", predicted_fs_Hz)
    predicted = analyse_signals(predicted_signals, predicted_fs_Hz)
    rows = []
    for axis, c in SEAT_AXES.items():
        if c not in measured.channels or c not in predicted.channels:
            continue
        m, p = measured.channels[c], predicted.channels[c]
        if not p.a_w_m_s2 > 0:  # an axis the model does not move (e.g. fore-aft without a longitudinal model)
            continue
        r = math.nan
        if known_profile and measured_signals is not None and c in measured_signals:
            r = _envelope_similarity(np.asarray(measured_signals[c], float), measured.sample_rate_Hz,
                                     m.peak_frequency_Hz, np.asarray(predicted_signals[c], float), predicted_fs_Hz,
                                     p.peak_frequency_Hz)
        rows.append({
            "axis": axis,
            "measured_a_w_m_s2": m.a_w_m_s2, "predicted_a_w_m_s2": p.a_w_m_s2,
            "ratio_a_w": m.a_w_m_s2 / p.a_w_m_s2 if p.a_w_m_s2 > 0 else math.nan,
            "measured_peak_frequency_Hz": m.peak_frequency_Hz, "predicted_peak_frequency_Hz": p.peak_frequency_Hz,
            "measured_half_power_width_Hz": m.half_power_width_Hz,
            "predicted_half_power_width_Hz": p.half_power_width_Hz,
            "envelope_similarity": r,
        })
    return rows


def validation_statistics(rows: pd.DataFrame) -> pd.DataFrame:
    """The thesis' statistics of the ratio errors predicted / measured, per axis and quantity.

    Parameters
    ----------
    rows : DataFrame
        ``ride_validation`` rows (:func:`validation_rows` plus identifiers).

    Returns
    -------
    DataFrame
        ``axis, quantity`` (``a_w``, ``peak_frequency``, ``half_power_width``, and
        ``envelope_similarity`` with its mean and sd only), ``n, mean, sd, p_within_10, p_within_30``.

    See Also
    --------
    validation_rows : the rows it summarises.
    tyrelab.vehicle.metrics.ratio_error_statistics : the thesis' statistics.

    Examples
    --------
    >>> from tyrelab.vehicle.comfort.measured_ride import analyse_signals
    >>> fs = 200.0; t = np.arange(0, 60, 1 / fs); z = np.sin(2 * np.pi * 4 * t)
    >>> rows = validation_rows(analyse_signals({"seat_z_m_s2": z}, fs), {"seat_z_m_s2": 1.1 * z}, fs, known_profile=False)
    >>> s = validation_statistics(pd.DataFrame(rows * 3))
    >>> s.loc[s["quantity"] == "a_w", ["axis", "n", "mean"]].round(4).to_dict("records")    # predicted / measured
    [{'axis': 'z', 'n': 3, 'mean': 1.1}]
    """
    if rows is not None:
        _validate.frame("rows", rows)
    cols = ["axis", "quantity", "n", "mean", "sd", "p_within_10", "p_within_30"]
    out = []
    if rows is None or rows.empty:
        return pd.DataFrame(columns=cols)
    for axis, g in rows.groupby("axis", sort=True):
        for q, meas, pred in (("a_w", "measured_a_w_m_s2", "predicted_a_w_m_s2"),
                              ("peak_frequency", "measured_peak_frequency_Hz", "predicted_peak_frequency_Hz"),
                              ("half_power_width", "measured_half_power_width_Hz", "predicted_half_power_width_Hz")):
            ratio = g[pred].to_numpy(float) / g[meas].to_numpy(float)
            out.append({"axis": axis, "quantity": q, **mt.ratio_error_statistics(ratio)})
        r = g["envelope_similarity"].to_numpy(float)
        r = r[np.isfinite(r)]
        out.append({"axis": axis, "quantity": "envelope_similarity", "n": int(r.size),
                    "mean": float(r.mean()) if r.size else math.nan,
                    "sd": float(r.std(ddof=1)) if r.size > 1 else math.nan,
                    "p_within_10": math.nan, "p_within_30": math.nan})
    return pd.DataFrame(out, columns=cols)
