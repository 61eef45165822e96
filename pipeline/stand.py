"""A virtual four-post stand and one-wheel track run of a 3-D tractor (issue 43, thesis §2.2–2.3).

What ``tyrelab generate`` writes to ``rides/stand/``: recordings with wheel inputs whose
transfer functions the rides stage estimates (:mod:`tyrelab.measurement.frf`).

* **The tractor**: :data:`STAND_SCENARIO_TEXT`, the thesis' MF698T (Table XV: mass, pitch inertia,
  wheelbase, CG, track widths 1.41/1.64 m; Table XVI: rolling stiffness and damping of its
  tyres, HH, 10 km/h) made 3-D with the rolling tyre's lateral element (``lateral_model =
  "rolling"``, thesis §2.5, issue 42: a Kelvin-Voigt unit in series with a damper ``c₂ = a / v``;
  K, C and ``a`` the model's stand-ins, :mod:`tyrelab.tyre.rolling`); its roll inertia is not in
  the thesis: the mass times a radius of gyration of 0.6 m (1840 kg m², a documented choice; the
  modern tractor of the project's 3-D tests has 2400 kg m² for 4.7 t). Its responses are the
  model's (:func:`tyrelab.vehicle.tyres.build_parts`, :meth:`tyrelab.vehicle.model.Assembly.linear`):
  the stand records the model, which the FRFs then measure.
* **Stationary and rolling** (§2.2: "wheels driven ... on rollers" at 6 and 11 km/h): rolling, the
  scenario's tyres with the series damper of the speed (``c₂ = a / v``: 16.7 kN s/m per tyre at
  6 km/h, 9.1 at 11 with the stand-in ``a`` = 100 kN s/m·km/h); stationary, the series damper
  locked (``c₂ = ∞``: the Kelvin-Voigt unit alone, as the model has it at 0 km/h) and the vertical
  and lateral stiffness times :data:`STATIONARY_STIFFNESS_FACTOR` (§2.4.3: natural frequencies up
  to 30 % lower at the onset of rolling; 1.5 gives 18 % lower, a documented choice)
  (:func:`condition_scenario`).
* **Excitation** (§2.2): the measured wheel's pad driven with seeded Gaussian noise whose
  acceleration spectrum is flat from 0.5 to 12 Hz (:data:`INPUT_RMS_M_S2` r.m.s.); the other
  three pads either still (their channels not recorded: a single-input recording) or driven
  "similar to that which would be received travelling along a rough track and ... correlated
  accordingly": left and right partly coherent (a common part), each rear pad its front's signal a
  wheelbase later, about equal in r.m.s. to the measured wheel.
* **The tyres' own excitation** when rolling (§2.4.5): each wheel's run-out at the rotation
  frequency and its second harmonic, and on traction tyres lugs at half and full lug-passing
  frequency, following a slowly wandering speed (:func:`tyrelab.rig.instrument.ground_profile`,
  the rig's model, :data:`LUG_HEIGHT_MM`); not seen by the pad accelerometers, they are the
  coherence holes the estimator masks.
* **The track run** (§2.3): one wheel (rear left) on a rough profile (ISO 8608 class D, the farm
  track's class), the other three on smooth concrete, its ground height recorded as the optical
  transducer did (``input_rear_left_z_m``); no enveloping filter.
* **Sensors**: seeded white noise, :data:`SENSOR_NOISE_M_S2` on accelerations (pads and floor),
  :data:`SENSOR_NOISE_RAD_S2` on rotations, :data:`HEIGHT_NOISE_M` on the height; sampled at
  :data:`STAND_FS_HZ` for :data:`DURATION_S`.

Responses are computed in the frequency domain over the whole (periodic) record: exact for the
linear model. Every number is seeded from (seed, ride id).
"""

from __future__ import annotations

import dataclasses
import math
import zlib
from typing import NamedTuple

import numpy as np
import pandas as pd

from . import _validate
from .units import km_h_to_m_s

__all__ = ["STAND_SCENARIO_FILE", "STAND_SCENARIO_TEXT", "STAND_FS_HZ", "DURATION_S", "INPUT_RMS_M_S2",
           "SENSOR_NOISE_M_S2", "SENSOR_NOISE_RAD_S2", "HEIGHT_NOISE_M", "STATIONARY_STIFFNESS_FACTOR",
           "LUG_HEIGHT_MM", "STAND_SPEEDS_KM_H", "MODEL_OUTPUTS", "WHEELS", "stand_scenario", "condition_scenario",
           "wheel_frf", "PredictedMode", "model_modes", "predicted_frf", "frf_validation_rows", "VALIDATION_MODEL", "stand_plan", "stand_recording"]

STAND_SCENARIO_FILE = "stand_mf698t_3d.toml"
STAND_SCENARIO_TEXT = """# The thesis' MF698T (Table XV heavy; Table XVI rolling tyres, HH, 10 km/h) made 3-D for the virtual
# four-post stand of issue 43 (thesis ch. 2): track widths of Table XV; roll inertia = mass x (0.6 m)^2
# (not in the thesis: a documented choice); rolling lateral tyre elements (thesis 2.5, issue 42: a
# Kelvin-Voigt unit in series with a damper c2 = a/v) with the model's stand-ins for K, C and a.
name = "MF698T on a four-post stand (3-D, virtual)"
description = "Thesis ch. 2 stand: MF698T of Table XV with Table XVI tyres, 3-D (issue 43)."

[tractor]
mass_kg = 5120
pitch_inertia_kg_m2 = 6210
front_distance_m = 1.54
rear_distance_m = 0.896
cg_height_m = 0.838
longitudinal_model = "none"
roll_inertia_kg_m2 = 1840
front_track_m = 1.41
rear_track_m = 1.64
lateral_model = "rolling"

[tyres.front]
size = "7.50-18"
pressure_bar = 3.45
stiffness_kN_per_m = 473
damping_kN_s_per_m = 1.47
traction = false

[tyres.rear]
size = "13.6R38"
pressure_bar = 1.31
stiffness_kN_per_m = 364
damping_kN_s_per_m = 1.12

[surface]
kind = "iso8608"
class = "D"
length_m = 200
dx_m = 0.05
seed = 5017

[exposure]
speeds_km_h = [6, 11]
hours_per_day = 8
"""
#: Sampling rate of the stand recordings, Hz (the band is 0.5-12 Hz).
STAND_FS_HZ = 50.0
#: Length of each recording, s (47 independent 10.24 s segments).
DURATION_S = 480.0
#: r.m.s. of the measured wheel's pad acceleration, m/s².
INPUT_RMS_M_S2 = 1.0
#: Accelerometer noise, r.m.s., m/s² (as :data:`tyrelab.vehicle.virtual_rides.SENSOR_NOISE_M_S2`).
SENSOR_NOISE_M_S2 = 0.02
#: Angular accelerometer noise, r.m.s., rad/s² (0.02 m/s² over a 1 m base).
SENSOR_NOISE_RAD_S2 = 0.02
#: Height transducer noise, r.m.s., m.
HEIGHT_NOISE_M = 0.5e-3
#: Stationary tyre stiffness over rolling (vertical and lateral; a documented choice, see above).
STATIONARY_STIFFNESS_FACTOR = 1.5
#: Lug height of a traction tyre, mm (an R-1 rear tyre; a documented choice).
LUG_HEIGHT_MM = 35.0
#: Stand speeds, km/h (§2.2).
STAND_SPEEDS_KM_H = (0.0, 6.0, 11.0)
#: The wheels, in the model's tyre order and the raw format's input names.
WHEELS = ("front_left", "front_right", "rear_left", "rear_right")
#: Raw-format output channel -> the model output it records (the cab floor under the seat, read by
#: body-fixed accelerometers: the tilt's gravity components included).
MODEL_OUTPUTS = {"floor_z_m_s2": "seat_vertical_m_s2", "floor_x_m_s2": "seat_longitudinal_tilt_m_s2",
                 "floor_y_m_s2": "seat_lateral_tilt_m_s2", "roll_rad_s2": "roll_rad_s2",
                 "pitch_rad_s2": "pitch_rad_s2", "yaw_rad_s2": "yaw_rad_s2"}


def stand_scenario():
    """The stand's tractor (:data:`STAND_SCENARIO_TEXT`) as a scenario."""
    from pathlib import Path

    from .scenario_io import parse_scenario

    return parse_scenario(STAND_SCENARIO_TEXT, Path("."))


def condition_scenario(scenario, speed_km_h: float):
    """``scenario`` at one speed: its tyres rolling at ``speed_km_h`` > 0 (a rolling lateral element's
    series damper ``c₂ = a / v`` of that speed); at 0, stationary tyres: the rolling values of its
    first speed with the vertical and lateral stiffness × :data:`STATIONARY_STIFFNESS_FACTOR`, run
    at 0 km/h (a series damper locked: ``c₂ = ∞``).

    Examples
    --------
    >>> sc = stand_scenario()
    >>> condition_scenario(sc, 11.0).exposure.speeds_km_h, condition_scenario(sc, 0.0).exposure.speeds_km_h
    ((11.0,), (0.0,))
    >>> float(condition_scenario(sc, 0.0).rear.stiffness_kN_per_m[0])  # 364 x 1.5
    546.0
    """
    from .vehicle.tyres import resolve_tyres

    speed = _validate.non_negative("speed_km_h", speed_km_h)
    exp = scenario.exposure
    at = speed if speed > 0 else float(exp.list_speeds_km_h[0])
    sc = dataclasses.replace(scenario, exposure=dataclasses.replace(exp, speeds_km_h=(at,)))
    if speed > 0:
        return sc
    tyres = resolve_tyres(sc)
    f = STATIONARY_STIFFNESS_FACTOR
    axles = {}
    for axle in ("front", "rear"):
        spec, t = getattr(sc, axle), tyres[axle]
        kw = {"stiffness_kN_per_m": tuple(float(k) * f for k in t.stiffness_kN_per_m),
              "damping_kN_s_per_m": tuple(float(c) for c in t.damping_kN_s_per_m)}
        if t.lateral_stiffness_kN_per_m is not None:
            kw["lateral_stiffness_kN_per_m"] = float(t.lateral_stiffness_kN_per_m[0]) * f
            kw["lateral_damping_kN_s_per_m"] = float(t.lateral_damping_kN_s_per_m[0])
        if t.lateral_series_damping_kN_s_per_m_km_h is not None:
            kw["lateral_series_damping_kN_s_per_m_km_h"] = float(t.lateral_series_damping_kN_s_per_m_km_h)
        axles[axle] = dataclasses.replace(spec, **kw)
    # the rolling values fixed above; run at 0 km/h, where a series damper is rigid
    return dataclasses.replace(sc, exposure=dataclasses.replace(sc.exposure, speeds_km_h=(0.0,)), **axles)


def wheel_frf(scenario, speed_km_h: float, frequency_Hz, outputs=tuple(MODEL_OUTPUTS)) -> np.ndarray:
    """The model's FRFs from each wheel's vertical ground acceleration to each output.

    Parameters
    ----------
    scenario : Scenario
        A 3-D tractor (four tyres).
    speed_km_h : float
        0 (stationary tyres, :func:`condition_scenario`) or the rolling speed.
    frequency_Hz : array (F,)
    outputs : sequence of str
        Raw-format channels of :data:`MODEL_OUTPUTS`.

    Returns
    -------
    ndarray, shape (F, outputs, 4)
        Output unit per m/s² at the wheel (NaN at 0 Hz), wheels in :data:`WHEELS` order.
    """
    from .vehicle.run.spectral import frequency_response

    asm = _assembly(scenario, speed_km_h)
    if tuple(asm.tyres) != WHEELS:
        raise ValueError(f"scenario: a four-wheel 3-D tractor is needed (roll_inertia_kg_m2, tracks), got tyres "
                         f"{asm.tyres}")
    lm = asm.linear([MODEL_OUTPUTS[o] for o in outputs])
    f = np.asarray(frequency_Hz, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):  # 0 Hz on a series damper's drift roots: NaN, dropped
        h = frequency_response(*lm.abcd, f)  # (p, 8, F): per u (m) and du (m/s) of each tyre
    jw = 2j * math.pi * f
    with np.errstate(divide="ignore", invalid="ignore"):
        disp = np.stack([h[:, 2 * j] + jw * h[:, 2 * j + 1] for j in range(4)], axis=1)  # per m of ground
        out = np.where(f > 0, disp / -(2 * math.pi * f) ** 2, np.nan)  # per m/s² of ground
    return np.moveaxis(out, -1, 0)


def _assembly(scenario, speed_km_h: float):
    """The assembled model of ``scenario`` at one speed (:func:`condition_scenario`)."""
    from .vehicle.model import assemble
    from .vehicle.tyres import build_parts, resolve_tyres

    sc = condition_scenario(scenario, speed_km_h)
    return assemble(build_parts(sc, resolve_tyres(sc), 0))


class PredictedMode(NamedTuple):
    """One oscillating mode of the model (:func:`model_modes`)."""

    name: str
    #: ``Im λ / 2π``, Hz.
    frequency_Hz: float
    #: ``-Re λ / |λ|``.
    damping_ratio: float
    #: ``|λ| / 2π``, Hz.
    undamped_Hz: float


def model_modes(scenario, speed_km_h: float) -> list[PredictedMode]:
    """The model's oscillating modes at a speed, by frequency: each complex root pair ``λ`` of its
    linear model in contact (the rolling tyres' contact points among its states: issue 42's damped
    modes), damped frequency ``Im λ / 2π`` and damping ratio ``-Re λ / |λ|`` (real roots, an
    overdamped mode or a series damper's relaxation, are no resonance a stand can fit; left out).

    Names are :func:`tyrelab.vehicle.solvers.modes.damped_modes`' (every oscillating root named by its
    own shape, followed from the undamped modes; a real root is reported there as overdamped).

    Examples
    --------
    >>> modes = model_modes(stand_scenario(), 6.0)
    >>> [(m.name, round(m.frequency_Hz, 2), round(m.damping_ratio, 2)) for m in modes][:3]
    [('lateral_roll', 1.36, 0.41), ('yaw', 2.15, 0.44), ('bounce', 2.44, 0.02)]
    """
    from .vehicle.solvers.modes import damped_modes

    modes = [PredictedMode(d.name, d.damped_Hz, d.damping_ratio, d.undamped_Hz)
             for d in damped_modes(_assembly(scenario, speed_km_h)).values() if not d.overdamped]
    return sorted(modes, key=lambda m: m.frequency_Hz)


#: What the prediction of :func:`frf_validation_rows` is.
VALIDATION_MODEL = ("the scenario's model at the recording's speed: its tyres (stationary at 0 km/h: "
                    "stiffness x 1.5, series dampers locked; rolling: c2 = a/v of the speed), damped modes "
                    "from the complex roots")


def predicted_frf(result, scenario, speed_km_h: float):
    """The model's FRFs on ``result``'s bins, outputs and inputs, (F, p, q) complex per m/s² at the
    wheel (:func:`wheel_frf`; NaN for an output the model does not have), or None when the scenario is
    not a four-wheel 3-D tractor. ``result``: a :class:`tyrelab.measurement.frf.RecordingFrf`.

    Examples
    --------
    >>> from types import SimpleNamespace as S
    >>> r = S(estimate=S(frequency_Hz=np.array([1.0, 2.0])), outputs=("floor_z_m_s2", "seat_z_m_s2"),
    ...       wheels=("rear_left",))
    >>> h = predicted_frf(r, stand_scenario(), 6.0)
    >>> h.shape, bool(np.isnan(h[:, 1]).all()), round(float(abs(h[1, 0, 0])), 3)
    ((2, 2, 1), True, 0.976)
    """
    f = result.estimate.frequency_Hz
    known = [o for o in result.outputs if o in MODEL_OUTPUTS]
    out = np.full((f.size, len(result.outputs), len(result.wheels)), np.nan, complex)
    if not known:
        return out
    try:
        model = wheel_frf(scenario, speed_km_h, f, known)  # (F, known, 4)
    except ValueError:  # not a four-wheel 3-D tractor: no FRFs per wheel
        return None
    cols = [WHEELS.index(w) for w in result.wheels]
    for n, o in enumerate(known):
        out[:, result.outputs.index(o), :] = model[:, n, cols]
    return out


def frf_validation_rows(result, scenario, speed_km_h: float, predicted=None) -> list[dict]:
    """``vehicle_frf_validation`` rows: per output and measured mode, the nearest predicted mode
    (:func:`model_modes`; nearest root ``λ`` in the complex plane, so that a heavily damped mode is not
    taken for a lightly damped one of similar frequency) and its name: frequencies, damping ratios,
    their ratios and whether the prediction lies in the measured 95 % interval; per output the median
    FRF magnitude error (predicted / measured - 1, :func:`predicted_frf`, or ``predicted`` when given)
    over the coherent, separable, unmasked bins of 0.5-12 Hz (a 3-D four-wheel scenario only; NaN
    otherwise). An output without a fitted mode gets one row without one.

    ``result``: a :class:`tyrelab.measurement.frf.RecordingFrf`.
    """
    predicted_modes = model_modes(scenario, speed_km_h)
    e = result.estimate
    f = e.frequency_Hz
    model = predicted_frf(result, scenario, speed_km_h) if predicted is None else predicted
    rows = []
    for k, out in enumerate(result.outputs):
        err = math.nan
        if model is not None and not np.isnan(model[:, k]).all():
            usable = result.usable(k) & ((f >= 0.5) & (f <= 12.0))[:, None]
            with np.errstate(divide="ignore", invalid="ignore"):
                rel = np.abs(np.abs(model[:, k]) / np.abs(e.h[:, k, :]) - 1.0)[usable]
            rel = rel[np.isfinite(rel)]
            err = float(np.median(rel)) if rel.size else math.nan
        base = {"output": out, "frf_magnitude_error": err, "model": VALIDATION_MODEL}
        modes = result.modes.get(out, [])
        if not modes:
            rows.append({**base, "mode": None})
        for n, m in enumerate(modes, start=1):
            near = min(predicted_modes, key=lambda p: abs(_pole(p.frequency_Hz, p.damping_ratio)
                                                          - _pole(m.frequency_Hz, m.damping_ratio))) \
                if predicted_modes else None
            name, fd, z = (near.name, near.frequency_Hz, near.damping_ratio) if near else (None, math.nan, math.nan)
            rows.append({**base, "mode": n, "predicted_mode": name, "measured_frequency_Hz": m.frequency_Hz,
                         "measured_frequency_ci95_low_Hz": m.frequency_low_Hz,
                         "measured_frequency_ci95_high_Hz": m.frequency_high_Hz,
                         "predicted_frequency_Hz": fd, "frequency_ratio": fd / m.frequency_Hz,
                         "frequency_in_interval": bool(m.frequency_low_Hz <= fd <= m.frequency_high_Hz),
                         "measured_damping_ratio": m.damping_ratio, "measured_damping_ci95_low": m.damping_low,
                         "measured_damping_ci95_high": m.damping_high, "predicted_damping_ratio": z,
                         "damping_ratio_ratio": z / m.damping_ratio if m.damping_ratio > 0 else math.nan,
                         "damping_in_interval": bool(m.damping_low <= z <= m.damping_high),
                         "measured_determined": bool(getattr(m, "determined", True))})
    return rows


def _pole(frequency_Hz: float, damping_ratio: float) -> complex:
    """The root ``λ / 2π`` (Hz) of a mode of damped frequency ``frequency_Hz`` and damping ratio."""
    z = min(float(damping_ratio), 0.999999)
    return complex(-z * frequency_Hz / math.sqrt(1 - z * z), frequency_Hz)


def stand_plan() -> pd.DataFrame:
    """The ``rides.csv`` rows of the stand campaign (paths relative to the campaign folder)."""
    rows = []
    for speed in STAND_SPEEDS_KM_H:
        for others in ("still", "correlated"):
            ride_id = f"stand_rear_left_{others}_{speed:g}kmh"
            rows.append({"ride_id": ride_id, "file": f"rides/stand/{ride_id}.parquet",
                         "vehicle": "MF698T 3-D on a four-post stand (virtual)", "speed_km_h": float(speed),
                         "track": "inputs", "recorded_on": "1984-05-02", "scenario": f"rides/stand/{STAND_SCENARIO_FILE}",
                         "method": "four_post",
                         "notes": f"rear left pad excited, the others {others} (virtual, tyrelab generate)"})
    ride_id = "track_rear_left_6kmh"
    rows.append({"ride_id": ride_id, "file": f"rides/stand/{ride_id}.parquet",
                 "vehicle": "MF698T 3-D on the rough track (virtual)", "speed_km_h": 6.0, "track": "inputs",
                 "recorded_on": "1985-06-20", "scenario": f"rides/stand/{STAND_SCENARIO_FILE}", "method": "track",
                 "notes": "rear left wheel on an ISO 8608 class D profile, the others on concrete (virtual)"})
    return pd.DataFrame(rows)


def _rng(seed: int, key: str) -> np.random.Generator:
    return np.random.default_rng([int(seed), zlib.crc32(key.encode())])


def _band_noise(rng, n: int, fs: float, rms: float) -> np.ndarray:
    """Gaussian noise, flat spectrum 0.5-12 Hz, ``rms`` (periodic over the record)."""
    x = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, 1 / fs)
    x[(f < 0.5) | (f > 12.0)] = 0
    y = np.fft.irfft(x, n)
    return y * rms / y.std()


def stand_recording(scenario, row: dict, seed: int, duration_s: float = DURATION_S,
                    fs_Hz: float = STAND_FS_HZ) -> pd.DataFrame:
    """One recording of :func:`stand_plan`'s ``row`` (a dict): ``time_s``, the input channels, the outputs."""
    from .measurement.frf import scenario_wheel_geometry
    from .rig.instrument import RigConfig, ground_profile

    _validate.positive_int("seed", seed, minimum=0)
    rng = _rng(seed, row["ride_id"])
    n = int(round(_validate.positive("duration_s", duration_s) * fs_Hz))
    t = np.arange(n) / fs_Hz
    speed = float(row["speed_km_h"])
    track = row["method"] == "track"
    wheelbase = scenario.tractor.front_distance_m + scenario.tractor.rear_distance_m
    ground = np.zeros((4, n))  # ground (pad) vertical acceleration under each wheel, m/s²
    recorded: dict = {}
    if track:  # §2.3: one wheel on a rough profile (class D), the others on concrete
        from .vehicle import profiles as pr

        v = km_h_to_m_s(speed)
        prof = pr.iso8608_track("D", seed=int(rng.integers(2 ** 31)), length_m=v * duration_s + 10.0, dx_m=0.05)
        heights = np.interp(v * t, prof.x_m, prof.left_m)
        heights = heights - heights.mean()
        spec = np.fft.rfft(heights)
        fr = np.fft.rfftfreq(n, 1 / fs_Hz)
        spec[(fr < 0.3) | (fr > 15.0)] = 0  # the transducer's band
        heights = np.fft.irfft(spec, n)
        ground[2] = np.fft.irfft(-(2 * np.pi * fr) ** 2 * np.fft.rfft(heights), n)
        recorded["input_rear_left_z_m"] = heights + HEIGHT_NOISE_M * rng.standard_normal(n)
    else:
        ground[2] = _band_noise(rng, n, fs_Hz, INPUT_RMS_M_S2)
        if "correlated" in row["ride_id"]:
            common = _band_noise(rng, n, fs_Hz, 1.0)
            left = common + 0.7 * _band_noise(rng, n, fs_Hz, 1.0)
            right = common + 0.7 * _band_noise(rng, n, fs_Hz, 1.0)
            lag = int(round(wheelbase / km_h_to_m_s(max(speed, 6.0)) * fs_Hz))  # a wheelbase later at the stand's pace
            ground[0] = left / left.std() * INPUT_RMS_M_S2
            ground[1] = right / right.std() * INPUT_RMS_M_S2
            ground[3] = np.roll(ground[1], lag)
            # the measured wheel (rear left) keeps its own, independent signal
        for j, w in enumerate(WHEELS):
            if ground[j].any():
                recorded[f"input_{w}_z_m_s2"] = ground[j] + SENSOR_NOISE_M_S2 * rng.standard_normal(n)
    # the tyres' own excitation when rolling (§2.4.5): displacement at each wheel, not on the pads
    extra = np.zeros((4, n))
    if speed > 0:
        cfg = RigConfig(sample_rate_Hz=fs_Hz)
        for j, (circ, lugs) in enumerate(scenario_wheel_geometry(scenario)):
            extra[j] = ground_profile(rng, t, speed, "concrete", circ, LUG_HEIGHT_MM if lugs else 0.0, lugs > 0, cfg)
    f = np.fft.rfftfreq(n, 1 / fs_Hz)
    outputs = tuple(MODEL_OUTPUTS)
    h = wheel_frf(scenario, speed, f, outputs)  # (F, p, 4) per m/s²
    h[0] = 0.0
    a_total = np.fft.rfft(ground, axis=1) + np.fft.rfft(extra, axis=1) * -(2 * np.pi * f) ** 2
    y = np.fft.irfft(np.einsum("fpq,qf->pf", h, a_total), n, axis=1)
    cols = {"time_s": t, **recorded}
    for k, c in enumerate(outputs):
        noise = SENSOR_NOISE_RAD_S2 if c.endswith("rad_s2") else SENSOR_NOISE_M_S2
        cols[c] = y[k] + noise * rng.standard_normal(n)
    return pd.DataFrame(cols)
