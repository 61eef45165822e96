"""The ride in the frequency domain (issues 36, 45): per variant and speed a spectral row, the exact
expectation of the linear model for the track's spectrum (:mod:`tyrelab.vehicle.run.spectral`), no
simulation; :mod:`tyrelab.vehicle.spectral_ride` says what such a row holds and when a sweep takes it.
"""

from __future__ import annotations

import numpy as np

from ..units import km_h_to_m_s
from ... import _validate
from .. import spectral_ride as sr
from ..scenario import Scenario
from .plan import finish, prepare, record_window, speed_run
from .output import RideResult
from .records import FIGURE_BAND_HZ, RideCache, VariantPlan
from .rows import exposure
from .spectral import _expected_batch, _expected_psd, _transmissibility
from .track import DT_S

__all__ = ["spectral_variants"]


def spectral_variants(scenarios, tyre_data=None, with_spectra: bool = True,
                      cache: RideCache | None = None, a8_interval=None) -> list[RideResult]:
    """:func:`~tyrelab.vehicle.run.time.ride_variants` in the frequency domain: per variant and speed a spectral row
    (:func:`tyrelab.vehicle.spectral_ride.spectral_row`: the exact expectation of the linear model
    for the track's spectrum), no simulation.

    Parameters
    ----------
    scenarios : sequence of Scenario
    tyre_data : object, optional
        As :func:`~tyrelab.vehicle.run.time.ride`.
    with_spectra : bool
        Also the expected seat PSD per axis (on a 0.1 Hz grid of 0.2-20 Hz) and the transmissibility.
    cache : RideCache, optional
    a8_interval : sequence of bool, optional
        Per scenario, whether its result has the A(8) interval across the stand-in lateral
        stiffness (``a8_lateral_ci95_m_s2``; default every one's): a sweep computes it for the
        variant it reports (:func:`tyrelab.vehicle.ride.result_json`: the first).

    Returns
    -------
    list of RideResult
        One per scenario, its ``speeds`` the spectral rows.

    See Also
    --------
    tyrelab.vehicle.run.time.ride_variants : the same simulated.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> from tyrelab.vehicle.scenario.variants import with_overrides
    >>> r = spectral_variants([with_overrides(s, speeds_km_h=[8.0])], with_spectra=False)
    >>> r[0].speeds[["speed_km_h", "method"]].to_dict("records")
    [{'speed_km_h': 8.0, 'method': 'spectral'}]
    """
    for k, sc in enumerate(scenarios):
        _validate.instance(f"scenarios[{k}]", sc, Scenario)
    cache = cache or RideCache()
    flags = [True] * len(scenarios) if a8_interval is None else [bool(x) for x in a8_interval]
    if len(flags) != len(scenarios):
        raise ValueError(f"a8_interval: one flag per scenario ({len(scenarios)}), got {len(flags)}")
    preps = [prepare(sc, tyre_data, cache, with_spectra, False, f) for sc, f in zip(scenarios, flags)]
    groups: dict = {}
    for p in preps:
        for i, speed in enumerate(p.speeds_km_h):
            v = km_h_to_m_s(speed)
            start, stop = record_window(p.track, p.wheelbase_m, v, p.scenario.simulation.duration_s)
            speed_run(p, i, v, start, stop)
            groups.setdefault((p.track_key, v), []).append((p, i))
    for (_, v), members in groups.items():
        _expected_batch(members, v, forces=True)
        for p, i in members:
            _spectral_reduce(p, i)
    return [finish(p) for p in preps]


def _spectral_reduce(p: VariantPlan, i: int) -> None:
    """The spectral row of speed ``i`` of variant ``p`` (and its expected seat PSD and transmissibility)."""
    sc, tyres, r, axes = p.scenario, p.tyres, p.runs[i], p.axes
    hours = sc.exposure.hours_per_day
    aw = {ax: r.expected.get(ax, 0.0) for ax in ("z", "x", "y")}
    asm = r.asm
    k = (float(tyres["front"].stiffness_kN_per_m[i]), float(tyres["rear"].stiffness_kN_per_m[i]))
    static = p.static_loads  # they change with the tyres' stiffness only (statically indeterminate)
    if k not in static:
        static[k] = asm.static_tyre_loads_N()
    r.row = sr.spectral_row(p.speeds_km_h[i], tyres, i, aw, axes, hours, (r.stop - r.start) * DT_S,
                               r.force_sd_N, static[k], 1 if asm.parts.three_d else 2,
                               exposure(aw["z"], aw["x"], hours, aw["y"]))
    if p.with_spectra:
        speed = float(p.speeds_km_h[i])
        r.spectra = _expected_psd(p, i, sr.PSD_FREQUENCIES_HZ, speed)
        r.transmissibility = _transmissibility(r, axes, p.seat_abcd, np.geomspace(*FIGURE_BAND_HZ, 300), r.v_m_s, p.wheelbase_m, speed)
