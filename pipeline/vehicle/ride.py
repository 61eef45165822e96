"""Ride prediction for any tractor: the operator's daily vibration exposure (issue 13).

A :class:`~tyrelab.vehicle.scenario.Scenario` (tractor, tyres, seat, track, speeds)
becomes, per speed and per front/rear pressure pair, the seat's ISO 2631-1
weighted accelerations and the EU Directive 2002/44/EC daily exposure:

1. **Tyres** (:func:`resolve_tyres`): stiffness and damping per tyre and speed,
   from an override, a measured tyre of the warehouse (``K = K_c + ΔK_p P`` and
   ``C = C_c + ΔC P`` per speed, tables ``stiffness_pressure_by_speed`` /
   ``damping_pressure_by_speed``; below the first rolling speed the rolling value,
   :func:`tyrelab.tyre.speed_dependence.at_speeds`) or the fitted formula (§4.5.3,
   §8.2; ``[tyres.*] formula``: the thesis' or the build's); damping without either
   from the model fitted to the thesis' Table VII lines (:mod:`tyrelab.tyre.damping_fit`).
2. **Model**: the pitch-plane tractor of :mod:`tyrelab.vehicle.tractor` (same
   equations, wheelbase delay, rear longitudinal element). While both axles stay
   on the ground the model is linear; :func:`state_space` writes it as
   ``x' = A x + B w``, ``y = C x + D w`` with inputs ``w = [u_f, u_f', u_r, u_r']``.
   The time path runs it exactly for piecewise-linear inputs (first-order hold,
   modal decomposition, one :func:`scipy.signal.lfilter` per mode); a run whose
   tyre force would pull (lift-off) is re-run with
   :func:`~tyrelab.vehicle.tractor.simulate_tractor` (exact in contact, the
   nonlinear RK4 across the lift-off intervals), so the numbers are those of the
   ch. 7 study. The seat suspension is a base-excited single-DOF filter on
   the seat-point vertical acceleration (no feedback on the tractor).
3. **Frequency-domain path** (:func:`frequency_response`, :func:`expected_weighted_rms`):
   the same ``(A, B, C, D)`` gives the seat's complex response to ground input
   with the wheelbase delay and the enveloping filter's spatial transfer
   function; for a track of known spectrum the expected weighted r.m.s. is
   ``sqrt(∫ |H(f)|² |W(f)|² S_u(f) df)``, printed beside the simulated value so a
   user sees the sampling error of one random track.
4. **Exposure** (:func:`exposure`): ``A(8)`` is the highest of ``1.4 a_wx``,
   ``1.4 a_wy`` and ``a_wz`` times ``sqrt(T/8 h)`` (Directive; not the vector sum
   ``a_v``, which is reported as well); hours to the action and limit values
   ``8 h (value / a_w)²``. The pitch-plane model has no lateral motion: ``a_wy``
   is not modelled (0).

This module runs a scenario (:func:`ride`) or a sweep (:func:`ride_sweep`); the work is done in
layers below it (issue 45): :mod:`tyrelab.vehicle.tyres` (where a tyre's numbers come from),
:mod:`tyrelab.vehicle.scenario` (the file, its limits and variants) and :mod:`tyrelab.vehicle.run`
(the typed record of a run, the track and wheel inputs, the time and spectral runs, the
frequency-domain core, sweeps, output). Every name this module held before is importable from it.

SI inside; km/h, kN/m and bar at the edges, as in the key names.
"""

from __future__ import annotations

from .. import _validate
from . import profiles as pr  # noqa: F401 (an old name of this module)
from .model import assemble  # noqa: F401 (an old name of this module)
from .modes import LATERAL_ROLL_SHARE, MODE_NAMES, ModeSet, follow_names, frequency_intervals, mode_set  # noqa: F401
from .scenario import Scenario, ScenarioError, sweep_variants, with_overrides, with_values  # noqa: F401
from .scenario.limits import RIDE_METHODS, bound_argument
from .spectral_ride import at_own_values, nominal_index
from .tractor import Tractor, simulate  # noqa: F401 (old names of this module)
from .tyres import AxleTyres, ShippedTyres, build_parts, per_speed, resolve_tyres  # noqa: F401
from .tyres import _damping_fit, _formula_stiffness, _lateral_tyre, _model_damping, _thesis_stiffness_model  # noqa: F401
from .run.frequency import _spectral_reduce, spectral_variants  # noqa: F401
from .run.output import RideResult, _clean, _clean_class, _lateral_note, _tyre_json, result_json, results_table  # noqa: F401
from .run.pitch_plane import OUTPUTS, state_names, state_space  # noqa: F401
from .run.plan import LATERAL_INTERVAL_STEPS, _lateral_interval, axle_flags as _axle_flags, finish as _finish  # noqa: F401
from .run.plan import modes, prepare as _prepare, record_window as _record_window, seat_axes  # noqa: F401
from .run.plan import speed_run as _linear_model  # noqa: F401
from .run.records import AXIS_WORDS, FIGURE_BAND_HZ, RideCache, SpeedRun, VariantPlan  # noqa: F401
from .run.rows import VERDICTS, SpeedRow, exposure  # noqa: F401
from .run.spectral import (_expected_batch, _expected_psd, _fd_grid, _rows, _seat_tf, _transmissibility,  # noqa: F401
                           _wheel_responses, enveloping_response, expected_weighted_rms, frequency_response,
                           input_cross_spectra)
from .run.sweep import SWEEP_CHUNK, _follow_modes, _ride_batch, _spectral_batch, _sweep_results  # noqa: F401
from .run.sweep import expected_sweep, in_chunks as _in_chunks, nominal_result  # noqa: F401
from .run.time import _linear_run, _redo_lifting, _reduce, ride_variants  # noqa: F401
from .run.track import (DT_S, FS_HZ, Track, axle_inputs, build_profile, crg_profile, envelope_side as _envelope_side,  # noqa: F401
                        road_classes, track_width_m as _track_width_m, tyre_inputs, wheel_inputs)
from .units import KILO, from_kilo, to_kilo  # noqa: F401 (old names of this module)

#: This module's names and those of the layers in vehicle/run/ (whose package lists none: these are
#: the names ``tyrelab.vehicle`` re-exports); the tyres' (AxleTyres, ShippedTyres, per_speed,
#: resolve_tyres, build_parts) are :mod:`tyrelab.vehicle.tyres`' and still import from here.
__all__ = [
    "OUTPUTS", "Track", "RideResult", "tyre_inputs", "state_names", "state_space", "frequency_response",
    "enveloping_response", "build_profile", "crg_profile", "road_classes", "axle_inputs",
    "exposure", "seat_axes", "modes", "input_cross_spectra", "ride", "ride_variants", "RideCache", "ride_sweep",
    "spectral_variants", "expected_weighted_rms", "expected_sweep", "result_json", "results_table", "VERDICTS",
]


def ride(scenario: Scenario, tyre_data=None, with_spectra: bool = True,
         with_signals: bool = False, cache: RideCache | None = None) -> RideResult:
    """Simulate a scenario at every speed and evaluate the seat vibration.

    Parameters
    ----------
    scenario : Scenario
    tyre_data : object, optional
        Measured tyres and the stiffness model (:class:`ShippedTyres` by default; a build's
        warehouse through :class:`tyrelab.tyredata.WarehouseTyres`).
    with_spectra : bool
        Also compute seat PSDs and transmissibilities (for figures).
    with_signals : bool
        Also keep the seat's predicted records (:attr:`RideResult.signals`), e.g. to compare
        with a recording (:mod:`tyrelab.vehicle.ride_validation`).
    cache : RideCache, optional
        Share tracks, enveloped wheel tracks and the seat filter with other calls.

    Returns
    -------
    RideResult
    """
    _validate.instance("scenario", scenario, Scenario)
    return ride_variants([scenario], tyre_data, with_spectra, with_signals, cache)[0]


def ride_sweep(
    scenario: Scenario,
    front_pressures_bar=None,
    rear_pressures_bar=None,
    speeds_km_h=None,
    tyre_data=None,
    map_fn=None,
    with_spectra: bool | str = True,
    sets: dict | None = None,
    max_variants: int | None = None,
    max_samples: int | None = None,
    method: str | None = None,
    max_rows: int | None = None,
) -> list[RideResult]:
    """:func:`ride` for every variant: each front × rear pressure pair (the scenario's own when not
    given) and every combination of the swept keys.

    Parameters
    ----------
    scenario : Scenario
    front_pressures_bar, rear_pressures_bar : sequence of float, optional
        Default: the scenario's ``[sweep]``, else its tyres' pressures.
    speeds_km_h : sequence of float, optional
        Override the scenario's speeds.
    tyre_data : object, optional
        As :func:`ride`.
    map_fn : callable, optional
        ``map_fn(task, items) -> results`` in order (the caller's executor, e.g.
        :func:`tyrelab.executor.map_batches` bound to a context); default in-process.
    with_spectra : bool or "nominal"
        Seat PSD and transmissibility (figure data) of every variant, of none, or (``"nominal"``)
        of the nominal variant alone (:func:`tyrelab.vehicle.spectral_ride.nominal_index`: what a
        sweep's page draws).
    sets : dict, optional
        Numeric scenario keys (``"section.key"``, :func:`tyrelab.vehicle.scenario.numeric_key`)
        -> values to run, on top of (and replacing the same keys of) the scenario's ``[sweep]``.
    max_variants, max_samples : int, optional
        Bounds of the work (:mod:`tyrelab.vehicle.scenario.limits`; default its ``MAX_VARIANTS``
        for the time domain, ``MAX_SPECTRAL_VARIANTS`` for spectral rows, and ``MAX_SAMPLES``): more
        is refused with a ValueError giving the estimate, before any work.
    max_rows : int, optional
        Most spectral rows (variant x speed; default: what
        :data:`~tyrelab.vehicle.scenario.limits.MAX_SPECTRAL_SECONDS` of the estimate allow, by the
        model's cost a row), refused alike before any work.
    method : {"auto", "time", "spectral"}, optional
        How the rows are computed (default the scenario's ``[simulation] method``;
        :func:`tyrelab.vehicle.spectral_ride`): ``auto`` simulates one variant, and computes a
        sweep on an ISO 8608 surface in the frequency domain with the time domain beside it for
        the nominal variant and for speeds that may lift a tyre.

    Returns
    -------
    list of RideResult
        Pressure pairs front-major, then the swept keys in order (the last varying fastest);
        :attr:`RideResult.variant` names each variant's swept values. Every variant's modes carry
        the first variant's names, followed by shape (:func:`tyrelab.vehicle.modes.follow_names`).
        The A(8) interval across a stand-in lateral stiffness (:attr:`RideResult.a8_lateral_ci95_m_s2`)
        is the first variant's alone, the one :func:`result_json` reports.

    Raises
    ------
    ScenarioError
        A swept key (or a swept pressure) that the scenario's model does not use, each with the
        reason (:func:`tyrelab.vehicle.scenario.variants.unused_key_problems`), before any work.
    ValueError
        A pressure given by option and swept key both, values out of range, too much work.

    See Also
    --------
    ride : one variant.
    tyrelab.vehicle.run.output.results_table : the ``ride_results`` rows of its results.
    tyrelab.vehicle.run.sweep.expected_sweep : the frequency-domain expectation alone.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> results = ride_sweep(s, rear_pressures_bar=[0.8, 1.2], speeds_km_h=[8.0], with_spectra=False)
    >>> [(r.tyres["rear"].pressure_bar, r.nominal) for r in results]     # 1.2 bar is the scenario's own
    [(0.8, False), (1.2, True)]
    """
    method = method or scenario.simulation.method
    _validate.choice("method", method, RIDE_METHODS)
    if with_spectra not in (True, False, "nominal"):
        raise ValueError(f"with_spectra must be True, False or 'nominal', got {with_spectra!r}")
    for name, value in (("max_variants", max_variants), ("max_samples", max_samples), ("max_rows", max_rows)):
        if value is not None:
            bound_argument(name, value)
    variants = sweep_variants(scenario, front_pressures_bar, rear_pressures_bar, speeds_km_h, sets, method,
                              max_variants, max_samples, max_rows=max_rows, with_spectra=with_spectra)
    scenarios = [v for v, _ in variants]
    nominal = nominal_index(scenario, variants)
    results = _sweep_results(scenarios, method, nominal, tyre_data, with_spectra, map_fn, max_samples)
    for r, (sc_v, combo) in zip(results, variants):
        r.variant = dict(combo)
        r.nominal = at_own_values(scenario, sc_v, combo)  # the scenario's own values
    _follow_modes(results)
    return results
