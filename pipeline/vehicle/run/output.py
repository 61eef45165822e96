"""A ride's result and its output (issues 13, 36, 45): :class:`RideResult`, the ``tyrelab ride`` JSON
document and the ``ride_results`` table of a run's results.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ... import _validate
from ..modes import ModeSet
from ..scenario import Scenario
from ..tyres import AxleTyres

__all__ = ["RideResult", "result_json", "results_table"]


@dataclass
class RideResult:
    """Everything :func:`~tyrelab.vehicle.ride.ride` computed for one scenario and pressure pair.

    Attributes
    ----------
    scenario : Scenario
    tyres : dict
        ``front``/``rear`` -> :class:`~tyrelab.vehicle.tyres.AxleTyres`.
    natural_frequencies_Hz, nodal_points_m : dict
        ``bounce``/``pitch`` (at the first speed's stiffness); nodal point ahead of the CG.
    speeds : DataFrame
        One row per speed (:class:`~tyrelab.vehicle.run.rows.SpeedRow`; see
        :func:`~tyrelab.vehicle.ride.result_json` for the fields).
    spectra : DataFrame
        ``speed_km_h, frequency_Hz, seat_vertical_psd_m2_s4_per_Hz, seat_longitudinal_psd_m2_s4_per_Hz``.
    transmissibility : DataFrame
        ``speed_km_h, frequency_Hz, seat_vertical, seat_longitudinal_per_m`` (``|seat
        acceleration / ground acceleration|``, and fore-aft per unit ground acceleration).
    track_label, spectrum_source : str
    track_length_m : float
        Length of the track without lead-in, m.
    warnings : list of str
    """

    scenario: Scenario
    tyres: dict
    natural_frequencies_Hz: dict
    nodal_points_m: dict
    speeds: pd.DataFrame
    spectra: pd.DataFrame
    transmissibility: pd.DataFrame
    track_label: str
    spectrum_source: str
    track_length_m: float = math.nan
    warnings: list = field(default_factory=list)
    #: mode -> [low, high], 95 %, from the tyres' stiffness uncertainty (:func:`~tyrelab.vehicle.modes.frequency_intervals`;
    #: None where the mode cannot be followed: :attr:`warnings` says why)
    natural_frequency_intervals_Hz: dict = field(default_factory=dict)
    #: With ``ride(..., with_signals=True)``: speed (km/h) -> the seat's predicted record, raw-format channel
    #: name (``seat_z_m_s2``, ``seat_x_m_s2``, ``floor_z_m_s2``, ``floor_x_m_s2``; in 3-D also
    #: ``seat_y_m_s2``, ``floor_y_m_s2``) -> samples at ``FS_HZ`` from the front axle's entry on the track
    signals: dict = field(default_factory=dict)
    #: The swept keys' values of this variant (:func:`~tyrelab.vehicle.ride.ride_sweep`), ``{"section.key": value}``.
    variant: dict = field(default_factory=dict)
    #: A profile or CRG road's ISO 8608 class per wheel track (:func:`~tyrelab.vehicle.run.track.road_classes`); empty otherwise.
    road_classes: dict = field(default_factory=dict)
    #: 3-D with a stand-in lateral stiffness (issue 33): speed (km/h) -> A(8) (m/s²) with every stand-in
    #: lateral stiffness at the low and at the high end of its 95 % interval. A sweep computes it for
    #: its first variant alone (the one :func:`result_json` reports); the others' are empty.
    a8_lateral_ci95_m_s2: dict = field(default_factory=dict)
    #: The undamped modes (:class:`~tyrelab.vehicle.modes.ModeSet`) the natural frequencies name.
    modes: ModeSet | None = field(default=None, repr=False)
    #: 3-D with horizontal tyre elements (issue 42): the modes with their damping from the complex roots
    #: (:func:`~tyrelab.vehicle.modes.damped_modes`), per speed (each speed its own series dampers), the
    #: names the first speed's followed by shape; ``natural_frequencies_Hz`` is then ``|λ| / 2π`` of the
    #: first speed's. Empty otherwise (the undamped modes of the pitch plane, thesis §8.2).
    modes_by_speed: dict = field(default_factory=dict, repr=False)
    #: mode -> [low, high] of the first speed's damping ratio across the same perturbations as the
    #: frequencies' intervals (issue 42).
    damping_ratio_intervals: dict = field(default_factory=dict)

    @property
    def damping_ratios(self) -> dict:
        """``{mode: ζ}`` at the first speed (None: overdamped); empty without :attr:`modes_by_speed`."""
        if not self.modes_by_speed:
            return {}
        first = next(iter(self.modes_by_speed.values()))
        return {n: (None if d is None or d.overdamped else d.damping_ratio) for n, d in first.items()}

    #: The variant at the scenario's own values (its tyre pressures and the file's value of every swept
    #: key; :func:`~tyrelab.vehicle.ride.ride_sweep`): the one whose spectra the pages show.
    nominal: bool = True

    #: Of a variant whose ``speeds`` are spectral rows: its time-domain rows where it was simulated too
    #: (``method = "auto"``, :mod:`tyrelab.vehicle.spectral_ride`), else empty.
    time_rows: pd.DataFrame = field(default_factory=pd.DataFrame)

    @property
    def mode_table(self) -> pd.DataFrame:
        """The natural frequencies as a table, one row per mode (:attr:`modes` holds the shapes): ``mode``, ``frequency_Hz``, ``low_Hz``/``high_Hz`` (its 95 %
        interval from the tyre stiffness uncertainty; NaN without one) and ``nodal_point_m``
        (ahead of the CG; NaN for a mode that does not pitch); with the damped modes (3-D, issue 42) also
        ``damping_ratio`` (NaN: overdamped) and ``overdamped``, at the first speed."""
        rows = []
        zeta = self.damping_ratios
        for mode, f in self.natural_frequencies_Hz.items():
            lo, hi = self.natural_frequency_intervals_Hz.get(mode) or (None, None)  # None: no interval
            rows.append({"mode": mode, "frequency_Hz": float(f), "low_Hz": math.nan if lo is None else float(lo),
                         "high_Hz": math.nan if hi is None else float(hi),
                         "nodal_point_m": float(self.nodal_points_m.get(mode, math.nan))})
            if zeta:
                rows[-1].update(damping_ratio=math.nan if zeta.get(mode) is None else float(zeta[mode]),
                                overdamped=zeta.get(mode) is None)
        cols = ["mode", "frequency_Hz", "low_Hz", "high_Hz", "nodal_point_m"]
        return pd.DataFrame(rows, columns=cols + (["damping_ratio", "overdamped"] if zeta else []))

    def to_dict(self) -> dict:
        """The JSON document of ``tyrelab ride`` for this result (:func:`~tyrelab.vehicle.ride.result_json`)."""
        return result_json([self])

    def to_json(self) -> str:
        """:meth:`to_dict` as JSON text (indented, no NaN: a missing value is ``null``)."""
        import json

        return json.dumps(self.to_dict(), indent=2, ensure_ascii=False, allow_nan=False) + "\n"


def _lateral_note(sc: Scenario) -> str | None:
    """What a_wy rests on (issue 33): None in the pitch plane (no a_wy)."""
    t = sc.tractor
    if not t.three_d:
        return None
    if t.lateral_model == "none":
        return ("lateral_model = \"none\": no lateral tyre force, the body rolls about its CG; a_wy is indicative "
                "only (give the tyres' lateral elements: tractor.lateral_model)")
    given = all(x.lateral_stiffness_kN_per_m is not None for x in (sc.front, sc.rear))
    return (f"lateral tyre elements ({t.lateral_model}); lateral stiffness "
            + ("as given" if given else "partly or wholly the stand-in k_y = 0.57 k_z (95 % interval x/÷ 2)"))


def _clean_class(c: dict) -> dict:
    """A road class (:func:`tyrelab.vehicle.road_class.road_class`) for JSON (``g0_m3`` to 6 significant
    digits: it is of the order of 1e-5 m³)."""
    out = {k: ([_clean(x) for x in v] if isinstance(v, list) else v if isinstance(v, str) or v is None else _clean(v))
           for k, v in c.items()}
    if c.get("g0_m3") is not None:
        out["g0_m3"] = float(f"{c['g0_m3']:.6g}")
    return out


def _clean(v):
    if isinstance(v, (np.floating, float)):
        return None if not math.isfinite(float(v)) else round(float(v), 6)
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.bool_):
        return bool(v)
    return v


def _tyre_json(t: AxleTyres) -> dict:
    return {
        "size": t.size, "pressure_bar": t.pressure_bar,
        "stiffness_kN_per_m": _clean(t.stiffness_kN_per_m[0]), "damping_kN_s_per_m": _clean(t.damping_kN_s_per_m[0]),
        "stiffness_source": t.stiffness_source, "damping_source": t.damping_source,
        "rolling_radius_m": _clean(t.radius_m), "footprint_m": _clean(t.footprint_m[0]), "warnings": list(t.warnings),
        "stiffness_u_kN_per_m": _clean(t.stiffness_u_kN_per_m),
        **({"lateral_stiffness_kN_per_m": _clean(t.lateral_stiffness_kN_per_m[0]),
            "lateral_damping_kN_s_per_m": _clean(t.lateral_damping_kN_s_per_m[0]),
            "lateral_source": t.lateral_source,
            "lateral_stiffness_ci95_kN_per_m": None if t.lateral_ci95_kN_per_m is None
            else [_clean(t.lateral_ci95_kN_per_m[0][0]), _clean(t.lateral_ci95_kN_per_m[1][0])],
            "lateral_series_damping_kN_s_per_m_km_h": _clean(t.lateral_series_damping_kN_s_per_m_km_h),
            "lateral_series_damping_ci95_kN_s_per_m_km_h": None if t.lateral_series_ci95_kN_s_per_m_km_h is None
            else [_clean(x) for x in t.lateral_series_ci95_kN_s_per_m_km_h],
            "lateral_sources": dict(t.lateral_sources)}
           if t.lateral_stiffness_kN_per_m is not None else {}),
        **({"longitudinal_series_damping_kN_s_per_m_km_h": _clean(t.longitudinal_series_damping_kN_s_per_m_km_h),
            "longitudinal_series_source": t.longitudinal_series_source}
           if t.longitudinal_series_damping_kN_s_per_m_km_h is not None else {}),
    }


def _damped_json(r: RideResult) -> dict:
    """The modes with their damping (issue 42): ``damping_ratio`` beside ``natural_frequencies_Hz`` (null:
    overdamped), ``damped_frequencies_Hz`` (``Im λ / 2π``; null: overdamped), ``overdamped_modes``,
    ``damping_ratio_ci95`` and, per speed, ``modes_by_speed``."""
    first = next(iter(r.modes_by_speed.values()))

    def one(d):
        return None if d is None else {"natural_frequency_Hz": _clean(d.undamped_Hz),
                                       "damped_frequency_Hz": None if d.overdamped else _clean(d.damped_Hz),
                                       "damping_ratio": None if d.overdamped else _clean(d.damping_ratio),
                                       "overdamped": bool(d.overdamped)}

    return {"damping_ratio": {k: _clean(v) for k, v in r.damping_ratios.items()},
            "damped_frequencies_Hz": {k: None if d is None or d.overdamped else _clean(d.damped_Hz)
                                      for k, d in first.items()},
            "overdamped_modes": [k for k, d in first.items() if d is not None and d.overdamped],
            "damping_ratio_ci95": {k: None if v is None else [_clean(x) for x in v]
                                   for k, v in r.damping_ratio_intervals.items()},
            "modes_by_speed": [{"speed_km_h": v, "modes": {k: one(d) for k, d in ms.items()}}
                               for v, ms in r.modes_by_speed.items()]}


def result_json(results: list[RideResult]) -> dict:
    """The ``tyrelab ride`` JSON: the first pressure pair at the top, every pair under ``sweep``.

    Top-level keys: ``name``, ``scenario``, ``track``, ``lateral_model`` and ``lateral_note`` (3-D:
    the tyres' lateral elements and what a_wy rests on; null in the pitch plane),
    ``a8_lateral_ci95_m_s2`` (a stand-in lateral stiffness: per speed A(8) with it at the ends of its
    95 % interval; else null), ``road_class`` (a profile or CRG road: per
    wheel track its ISO 8608 ``class``, fitted ``g0_m3``, ``rms_m``, ``length_m``, ``band_cycles_per_m``;
    null for a generated track), ``spectrum_source``,
    ``hours_per_day``, ``working_speed_km_h`` (``[exposure]``'s, else the middle speed), ``tyres`` (``front``/``rear``: size, pressure, stiffness and
    damping per tyre at the first speed, their sources, radius, footprint,
    warnings, ``stiffness_u_kN_per_m``), ``natural_frequencies_Hz`` (``bounce``, ``pitch``)
    and ``natural_frequencies_Hz_ci95`` (their 95 % intervals from the tyre stiffness uncertainty),
    ``nodal_points_m`` (ahead of the CG), ``speeds`` (one object per speed:
    ``speed_km_h``, pressures and tyre values used, ``a_wz_m_s2`` (W_k),
    ``a_wx_m_s2`` (W_d), ``expected_a_wz_m_s2``/``expected_a_wx_m_s2`` (frequency
    domain), ``a_v_m_s2`` (k = 1.4 on x), ``vdv_m_s1_75``, ``vdv_daily_m_s1_75``,
    ``crest_factor``, ``mtvv_m_s2``, ``lift_off_fraction_front``/``_rear``, ``a8_m_s2``, ``a8_axis`` (the
    axis that governs A(8): largest k·a_w),
    ``hours_to_eav``, ``hours_to_elv``, ``verdict``, ``duration_s``,
    ``simulation``, ``method``: ``"time"``), ``warnings`` and, for more than one pressure pair, ``sweep``
    (one object per pair with ``front_pressure_bar``, ``rear_pressure_bar``,
    ``tyres``, ``natural_frequencies_Hz``, ``nodal_points_m``, ``speeds``).

    A variant computed in the frequency domain (:mod:`tyrelab.vehicle.spectral_ride`) has spectral
    ``speeds`` (``method``: ``"spectral"``; ``vdv_*``, ``mtvv_m_s2``, ``crest_factor`` and
    ``lift_off_fraction_*`` null; ``evdv_m_s1_75``, ``evdv_daily_m_s1_75``, ``front_tyre_force_sd_N``,
    ``rear_tyre_force_sd_N``, ``lift_off_probability_front``/``_rear`` besides) and, where it was
    simulated too, ``time_domain``: those speeds' time rows.

    See Also
    --------
    results_table : the same results as table rows.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> from tyrelab.vehicle.ride import ride_sweep
    >>> results = ride_sweep(s, rear_pressures_bar=[0.8, 1.2], speeds_km_h=[8.0], with_spectra=False)
    >>> doc = result_json(results)
    >>> doc["name"] == s.name, [v["rear_pressure_bar"] for v in doc["sweep"]], doc["speeds"][0]["method"]
    (True, [0.8, 1.2], 'spectral')
    """
    if not _validate.instances("results", results, RideResult):
        raise ValueError("results must hold at least one RideResult")
    def block(r: RideResult) -> dict:
        return {
            "tyres": {ax: _tyre_json(r.tyres[ax]) for ax in ("front", "rear")},
            "natural_frequencies_Hz": {k: _clean(v) for k, v in r.natural_frequencies_Hz.items()},
            "natural_frequencies_Hz_ci95": {k: None if v is None else [_clean(x) for x in v]
                                            for k, v in r.natural_frequency_intervals_Hz.items()},
            **(_damped_json(r) if r.modes_by_speed else {}),
            "nodal_points_m": {k: _clean(v) for k, v in r.nodal_points_m.items()},
            "speeds": [{k: _clean(v) for k, v in row.items()} for row in r.speeds.to_dict(orient="records")],
            **({"time_domain": [{k: _clean(v) for k, v in row.items()} for row in r.time_rows.to_dict(orient="records")]}
               if len(r.time_rows) else {}),
        }

    first = results[0]
    sc = first.scenario
    out = {"name": sc.name, "scenario": str(sc.path) if sc.path else None, "track": first.track_label,
           "road_class": {k: _clean_class(v) for k, v in first.road_classes.items()} or None,
           "lateral_model": sc.tractor.lateral_model if sc.tractor.three_d else None,
           "lateral_note": _lateral_note(sc),
           "a8_lateral_ci95_m_s2": [{"speed_km_h": k, "a8_m_s2": [_clean(x) for x in v]}
                                    for k, v in first.a8_lateral_ci95_m_s2.items()] or None,
           "spectrum_source": first.spectrum_source, "hours_per_day": sc.exposure.hours_per_day,
           "working_speed_km_h": sc.exposure.working_speed, **block(first),
           "warnings": sorted({w for r in results for w in r.warnings})}
    if len(results) > 1:
        out["sweep"] = [{"front_pressure_bar": r.tyres["front"].pressure_bar,
                         "rear_pressure_bar": r.tyres["rear"].pressure_bar,
                         **({"variant": {k: _clean(v) for k, v in r.variant.items()}} if r.variant else {}),
                         **block(r)} for r in results]
    return out


def results_table(results: list[RideResult], scenario_id: str | None = None) -> pd.DataFrame:
    """One row per speed × pressure pair (the ``ride_results`` layout).

    ``scenario`` is ``scenario_id`` (default: the scenario's name), ``name`` the scenario's name.
    ``is_nominal`` marks the pair of the scenario's own tyre pressures. The natural frequencies are
    ``modes_Hz`` (text) and one ``<mode>_Hz`` column per mode (``bounce_Hz``, ``pitch_Hz``,
    ``roll_Hz`` always; ``front_axle_roll_Hz``, ``cab_pitch_Hz``, ... where the model has them).
    ``method`` says how a row was computed (``time``, ``spectral``): a variant computed both ways
    (:attr:`RideResult.time_rows`) has its spectral rows, then its time rows.

    See Also
    --------
    result_json : the same results as JSON.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> from tyrelab.vehicle.ride import ride_sweep
    >>> results = ride_sweep(s, rear_pressures_bar=[0.8, 1.2], speeds_km_h=[8.0], with_spectra=False)
    >>> t = results_table(results)          # the nominal variant is also simulated: a time row beside its spectral one
    >>> t[["rear_pressure_bar", "method", "is_nominal"]].to_dict("records")
    [{'rear_pressure_bar': 0.8, 'method': 'spectral', 'is_nominal': False}, {'rear_pressure_bar': 1.2, 'method': 'spectral', 'is_nominal': True}, {'rear_pressure_bar': 1.2, 'method': 'time', 'is_nominal': True}]
    """
    _validate.instances("results", results, RideResult)
    frames = []
    for r in results:
        df = pd.concat([r.speeds, r.time_rows], ignore_index=True) if len(r.time_rows) else r.speeds.copy()
        df.insert(0, "scenario", scenario_id or r.scenario.name)
        df.insert(1, "name", r.scenario.name)  # the scenario's own name (``scenario`` may be an id given)
        df["bounce_Hz"] = r.natural_frequencies_Hz.get("bounce", math.nan)
        df["pitch_Hz"] = r.natural_frequencies_Hz.get("pitch", math.nan)
        df["roll_Hz"] = r.natural_frequencies_Hz.get("roll", math.nan)
        for mode, f in r.natural_frequencies_Hz.items():  # every further mode (front_axle_roll_Hz, cab_pitch_Hz, ...)
            df[f"{mode}_Hz"] = f
        df["modes_Hz"] = "; ".join(f"{k} {v:.3f}" if math.isfinite(v) else f"{k} not followed"
                                   for k, v in r.natural_frequencies_Hz.items())
        if r.modes_by_speed:  # issue 42: each speed's modes with their damping (its own series dampers)
            df["modes_damping"] = [
                "; ".join(f"{k} overdamped ({d.undamped_Hz:.3f} Hz)" if d.overdamped else
                          f"{k} {d.undamped_Hz:.3f} Hz ζ {d.damping_ratio:.3f}"
                          for k, d in r.modes_by_speed.get(float(v), {}).items() if d is not None)
                for v in df["speed_km_h"]]
        df["front_stiffness_source"] = r.tyres["front"].stiffness_source
        df["rear_stiffness_source"] = r.tyres["rear"].stiffness_source
        df["working_speed_km_h"] = r.scenario.exposure.working_speed  # the heatmap's speed ([exposure])
        df["is_nominal"] = r.nominal
        df["variant"] = ", ".join(f"{k}={v:g}" for k, v in r.variant.items())
        for k, v in r.variant.items():  # one column per swept key
            df[k] = v
        frames.append(df)
    return pd.concat(frames, ignore_index=True)
