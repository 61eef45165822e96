"""Seeded vehicle recordings from virtual tractors (what ``tyrelab generate`` writes to ``rides/``).

A *virtual tractor* is a shipped scenario (:func:`tyrelab.resources.scenarios_dir`) whose
real counterpart differs from its description as a real one would: the mass (and with it
the pitch inertia) off by a seeded factor N(1, 0.04), the tyre stiffness by N(1, 0.06) per
axle (a measured tractor never matches the data sheet). It is driven over
the scenario's own track at each of its speeds by the same ride model
(:func:`tyrelab.vehicle.ride.ride`), and the seat and cab floor are "recorded" as an
accelerometer pad and a floor accelerometer would: DC-coupled (the floor and seat z read
+1 g at rest), with seeded sensor noise (0.02 m/s² r.m.s., white to the Nyquist frequency)
and sampled at 500 Hz (the model's 1 kHz decimated by 2 after its anti-alias filter).
Each recording row names the scenario, so a campaign of them checks the prediction against
"measurements" (:mod:`tyrelab.vehicle.ride_validation`), and each carries a task and hours
for the daily exposure.

Every number is seeded from (seed, scenario) and (seed, scenario, speed): the same seed gives
the same recordings.
"""

from __future__ import annotations

import dataclasses
import zlib

import numpy as np
import pandas as pd

from ... import _validate
from ..units import STANDARD_GRAVITY_M_S2

__all__ = ["RIDE_PLAN", "RECORDING_FS_HZ", "SENSOR_NOISE_M_S2", "ride_plan", "virtual_recordings"]

#: Sampling rate of the recordings, Hz.
RECORDING_FS_HZ = 500.0
#: Accelerometer noise, r.m.s., m/s².
SENSOR_NOISE_M_S2 = 0.02
#: What a DC-coupled vertical accelerometer reads at rest (the standard gravity).
GRAVITY_M_S2 = STANDARD_GRAVITY_M_S2
#: (scenario file, vehicle, task, hours per day, recorded_on): the demo's recordings, one per speed.
RIDE_PLAN = (
    ("mf698t.toml", "MF698T (virtual, thesis ch. 7)", "farm track", 2.0, "1991-06-12"),
    ("modern_tractor.toml", "modern 4WD tractor (virtual)", "field transport", 4.0, "2024-09-03"),
)


def ride_plan(scenarios: dict) -> pd.DataFrame:
    """The ``rides.csv`` rows of the demo campaign (without files written).

    Parameters
    ----------
    scenarios : dict
        Scenario file name of :data:`RIDE_PLAN` -> its loaded :class:`~tyrelab.vehicle.scenario.Scenario`.

    See Also
    --------
    virtual_recordings : the recordings of its rows.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> p = ride_plan({f: load_scenario(scenarios_dir() / f) for f in ("mf698t.toml", "modern_tractor.toml")})
    >>> len(p), p.loc[0, ["ride_id", "speed_km_h", "hours_per_day"]].to_dict()
    (9, {'ride_id': 'mf698t_10kmh', 'speed_km_h': 10.0, 'hours_per_day': 0.4})
    """
    _validate.instance("scenarios", scenarios, dict)
    rows = []
    for file, vehicle, task, hours, day in RIDE_PLAN:
        sc = scenarios[file]
        stem = file.removesuffix(".toml")
        for v in sc.exposure.speeds_km_h:
            ride_id = f"{stem}_{v:g}kmh".replace(".", "p")
            rows.append({"ride_id": ride_id, "file": f"rides/{ride_id}.parquet", "vehicle": vehicle,
                         "speed_km_h": float(v), "track": "scenario", "recorded_on": day,
                         "scenario": f"rides/{file}", "task": f"{task} {v:g} km/h", "hours_per_day": hours / len(
                             sc.exposure.speeds_km_h), "notes": "virtual recording (tyrelab generate)"})
    return pd.DataFrame(rows)


def _rng(seed: int, key: str) -> np.random.Generator:
    return np.random.default_rng([int(seed), zlib.crc32(key.encode())])


def virtual_recordings(scenario, key: str, seed: int) -> tuple[dict, dict]:
    """Recordings of the virtual tractor of ``scenario`` at each of its speeds.

    One tractor per ``key`` (its factors are seeded from (seed, key)), driven at every speed
    in one :func:`~tyrelab.vehicle.ride.ride` call; each recording's sensor noise is seeded
    from (seed, key, speed).

    Returns
    -------
    frames : dict
        Speed (km/h) -> DataFrame ``time_s, seat_x_m_s2, seat_z_m_s2, floor_x_m_s2,
        floor_z_m_s2`` at :data:`RECORDING_FS_HZ`.
    truth : dict
        The factors the virtual tractor differs by (``mass_factor``, ``front_stiffness_factor``,
        ``rear_stiffness_factor``).

    See Also
    --------
    ride_plan : the campaign's rows.
    tyrelab.vehicle.ride.ride : the ride each recording comes from.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> from tyrelab.vehicle.scenario.variants import with_overrides, with_values
    >>> s = with_overrides(with_values(load_scenario(scenarios_dir() / "modern_tractor.toml"), {"surface.length_m": 60}), [8.0])
    >>> frames, tractor = virtual_recordings(s, "demo", seed=1)
    >>> list(frames[8.0].columns), sorted(tractor)          # the tractor differs from its scenario, seeded
    (['time_s', 'seat_x_m_s2', 'seat_z_m_s2', 'floor_x_m_s2', 'floor_z_m_s2'], ['front_stiffness_factor', 'mass_factor', 'rear_stiffness_factor'])
    """
    _validate.instance("key", key, str)
    _validate.positive_int("seed", seed, minimum=0)
    from scipy import signal

    from ..ride import FS_HZ, resolve_tyres, ride

    rng = _rng(seed, key)
    mass_f, kf, kr = (1.0 + s * rng.standard_normal() for s in (0.04, 0.06, 0.06))
    tyres = resolve_tyres(scenario)
    tr = dataclasses.replace(scenario.tractor, mass_kg=scenario.tractor.mass_kg * mass_f,
                             pitch_inertia_kg_m2=scenario.tractor.pitch_inertia_kg_m2 * mass_f)
    front = dataclasses.replace(scenario.front, stiffness_kN_per_m=tuple(
        float(k) * kf for k in tyres["front"].stiffness_kN_per_m))
    rear = dataclasses.replace(scenario.rear, stiffness_kN_per_m=tuple(
        float(k) * kr for k in tyres["rear"].stiffness_kN_per_m))
    sc = dataclasses.replace(scenario, tractor=tr, front=front, rear=rear)
    q = int(round(FS_HZ / RECORDING_FS_HZ))
    frames = {}
    for speed, sig in ride(sc, with_spectra=False, with_signals=True).signals.items():
        noise = _rng(seed, f"{key}@{speed:g}")
        cols = {}
        for c in ("seat_x_m_s2", "seat_z_m_s2", "floor_x_m_s2", "floor_z_m_s2"):
            x = signal.decimate(np.asarray(sig[c], float), q, ftype="fir", zero_phase=True) if q > 1 else sig[c]
            cols[c] = x + SENSOR_NOISE_M_S2 * noise.standard_normal(x.size) + (GRAVITY_M_S2 if c.endswith("z_m_s2")
                                                                               else 0.0)
        n = cols["seat_z_m_s2"].size
        frames[speed] = pd.DataFrame({"time_s": np.arange(n) / RECORDING_FS_HZ, **cols})
    return frames, {"mass_factor": mass_f, "front_stiffness_factor": kf, "rear_stiffness_factor": kr}
