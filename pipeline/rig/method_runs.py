"""Rig runs of every method and direction from the truth model (issue 34).

The virtual test vehicle of :mod:`tyrelab.rig.instrument` (axle on four stiff load beams,
carriage and inertial mass, linkage to the tractor) recorded the way a lab records today:

* ``random`` — the vibrator driven with band-limited random force (flat over the band,
  random phases; the thesis' calibration runs, §3.2.9, and its "narrow band random
  vibration", §3.2.5); a rolling tyre also rides the ground's roughness, run-out and lugs
  (:func:`~tyrelab.rig.instrument.ground_profile` of the run's surface, issue 44), a second input
  the drive does not control;
* ``swept_sine`` — a linear sweep over the band;
* ``free_vibration`` — a few seconds of sine drive near the system's natural frequency,
  then the release (no drive after it) and the free decay;
* ``load_deflection`` — a slow triangular load cycle (:func:`tyrelab.rig.experiments.load_ramp`:
  rubber creep, §3.4, Fig. 18), with the ``deflection_m`` channel.

Each direction has its own truth (:func:`directional_truth`): vertical the truth model of
:mod:`tyrelab.rig.truth`; lateral and longitudinal with the thesis' tendencies (Stayner &
Boldero 1973 as the thesis reports them, §2.4; field notes): lateral stiffness about
independent of load and rising a little with pressure, horizontal damping rising with load,
and for a rolling tyre a damper in series (§2.5, Lines 1987) inversely proportional to
speed. The dynamics are solved exactly in the frequency domain (periodic record with quiet
pads, as :func:`~tyrelab.rig.instrument.simulate_axle`), the tyre as its dynamic stiffness
``Z(ω)`` (Kelvin–Voigt, or Kelvin–Voigt in series with a damper), and recorded by
:func:`~tyrelab.rig.instrument.record` (gains, offsets, noise, 16-bit converters).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import fft as sfft
from scipy import signal

from ..measurement.broadband import maxwell_impedance
from . import truth
from .instrument import G, RigConfig, RunSignals, carriage_mass_kg, ground_profile, record

__all__ = ["LATERAL_STIFFNESS_RATIO", "LONGITUDINAL_STIFFNESS_RATIO", "LATERAL_PRESSURE_SLOPE_PER_BAR",
           "HORIZONTAL_DAMPING_N_S_PER_M", "SERIES_DAMPING_AT_10_KM_H", "METHOD_DURATION_S", "METHOD_DISPLACEMENT_M",
           "method_amplitude_mm_pp", "directional_truth",
           "method_signals", "simulate_method_run"]

#: Lateral and longitudinal stiffness of a tyre at the nominal pressure as fractions of its vertical
#: stationary stiffness there (documented choice: agricultural tyres' lateral/vertical ratio 0.3-0.6).
LATERAL_STIFFNESS_RATIO = 0.45
LONGITUDINAL_STIFFNESS_RATIO = 0.6
#: Relative rise of the horizontal stiffness per bar above the nominal pressure ("possibly rising
#: with pressure", §2.4); independent of load.
LATERAL_PRESSURE_SLOPE_PER_BAR = 0.15
#: Horizontal Kelvin-Voigt damping at the nominal load, N s/m, proportional to the load ("rising with load").
HORIZONTAL_DAMPING_N_S_PER_M = 1.5e3
#: Series damper of a rolling tyre at 10 km/h, N s/m, inversely proportional to speed (§2.5).
SERIES_DAMPING_AT_10_KM_H = {"lateral": 10e3, "longitudinal": 14e3}
#: Record length per method, s (a load cycle is slow; a decay is short).
METHOD_DURATION_S = {"random": 50.0, "swept_sine": 50.0, "free_vibration": 16.0, "load_deflection": 120.0}
#: Axle motion per method (documented choice): broadband runs 6 mm rms (coherence over the whole
#: band), a decay released from 2 mm (the vibrator rings the system, it does not lift it). The tyre's
#: stiffness falls with amplitude (thesis §4.3.4, Table IV; the truth model's amplitude term), so the
#: small decay sees a stiffer tyre than the forced run: Table I's free vibration is the stiffest.
METHOD_DISPLACEMENT_M = {"random": 6e-3, "swept_sine": 6e-3, "free_vibration": 2e-3}


def directional_truth(tyre, direction: str, pressure_bar: float, speed_km_h: float, load_kN: float,
                      **conditions) -> tuple[float, float, float]:
    """``(K N/m, C N s/m, c₂ N s/m)`` of the tyre in ``direction`` (module docstring; c₂ = inf: none).

    Examples
    --------
    >>> k, c, c2 = directional_truth("T1", "lateral", 1.38, 10.0, truth.NOMINAL_LOAD_KN)
    >>> round(k / directional_truth("T1", "vertical", 1.38, 0.0, truth.NOMINAL_LOAD_KN)[0], 2), c2
    (0.45, 10000.0)
    """
    if direction == "vertical":
        return (truth.stiffness(tyre, pressure_bar, speed_km_h, load_kN, **conditions),
                truth.damping(tyre, pressure_bar, speed_km_h, load_kN, **conditions), math.inf)
    if direction not in SERIES_DAMPING_AT_10_KM_H:
        raise ValueError(f"direction must be vertical, lateral or longitudinal, got {direction!r}")
    p0, l0 = truth.NOMINAL_PRESSURE_BAR, truth.NOMINAL_LOAD_KN
    ratio = LATERAL_STIFFNESS_RATIO if direction == "lateral" else LONGITUDINAL_STIFFNESS_RATIO
    k = ratio * truth.stiffness(tyre, p0, 0.0, l0) * (1 + LATERAL_PRESSURE_SLOPE_PER_BAR * (pressure_bar - p0))
    c = HORIZONTAL_DAMPING_N_S_PER_M * load_kN / l0
    c2 = SERIES_DAMPING_AT_10_KM_H[direction] * 10.0 / speed_km_h if speed_km_h > 0 else math.inf
    return k, c, c2


def method_amplitude_mm_pp(method: str) -> float:
    """Peak-to-peak equivalent of a method run's axle motion, mm (what the truth model's amplitude
    term is evaluated at): 2√2 × rms for a broadband run, the mean p-p of a decay from its peak
    (about the peak, as the analysed extrema fall from it to a few per cent)."""
    x = METHOD_DISPLACEMENT_M.get(method)
    if x is None:
        return truth.NOMINAL_AMPLITUDE_MM_PP
    return 2 * math.sqrt(2) * x * 1e3 if method in ("random", "swept_sine") else x * 1e3


def _impedance(omega, k, c, c2):
    return k + 1j * omega * c if not np.isfinite(c2) else maxwell_impedance(omega, k, c, c2)


def method_signals(method: str, direction: str, stiffness_N_per_m: float, damping_N_s_per_m: float,
                   series_damping_N_s_per_m: float, load_kN: float, rng: np.random.Generator,
                   cfg: RigConfig = RigConfig(), *, band_Hz=(1.0, 8.0), duration_s: float | None = None,
                   displacement_m: float | None = None, road: dict | None = None) -> tuple[RunSignals, np.ndarray | None]:
    """Physical signals of one run (and the tyre deflection of a load-deflection run, m); the axle
    motion ``displacement_m`` (rms of a broadband run, peak of a decay; default
    :data:`METHOD_DISPLACEMENT_M`).

    ``road``: the keyword arguments of :func:`~tyrelab.rig.instrument.ground_profile` but ``rng``
    and ``t`` (``speed_km_h``, ``surface``, ``circumference_m``, ``lug_height_mm``, ``traction``):
    a broadband run on a rolling tyre then has the ground's height under the tyre as a second input
    (issue 44), drawn after the drive; the drive alone sets the scale to ``displacement_m``."""
    fs = cfg.sample_rate_Hz
    dur = duration_s or METHOD_DURATION_S[method]
    M_a, M_c = cfg.axle_mass_kg, carriage_mass_kg(load_kN, cfg)
    if method == "load_deflection":
        from .experiments import load_ramp, load_ramp_clean

        # the recorded deflection (with the ramp's measurement noise; its draws keep every later run's
        # random stream), and the tyre's force from the deflection itself: differentiating the noisy
        # channel would turn its noise into force (issue 44: 62 % of the loop's "damping" was that)
        ramp = load_ramp(stiffness_N_per_m, load_kN * 1e3, ramp_s=dur / 2, sample_rate_Hz=fs, rng=rng)
        clean = load_ramp_clean(stiffness_N_per_m, load_kN * 1e3, ramp_s=dur / 2, sample_rate_Hz=fs)
        n = ramp.time_s.size
        # quasi-static: the axle barely accelerates; the beams carry the applied load onto the tyre
        d = clean.displacement_m
        f_t = clean.force_N + damping_N_s_per_m * np.gradient(d, clean.time_s)  # compression force on the tyre
        weight = G * M_a if direction == "vertical" else 0.0
        sig = RunSignals(ramp.time_s, -d, np.zeros(n), np.zeros(n), f_t, weight - f_t)
        return sig, ramp.displacement_m
    n_keep = int(round(dur * fs))
    pad = int(round(6.0 * fs))
    n = n_keep + 2 * pad
    t = np.arange(n) / fs
    if method == "random":
        f = sfft.rfftfreq(n, 1 / fs)
        spec = np.where((f >= band_Hz[0]) & (f <= band_Hz[1]), np.exp(1j * rng.uniform(0, 2 * np.pi, f.size)), 0)
        drive = sfft.irfft(spec, n)
        drive[:pad] = 0
        drive[-pad:] = 0
    elif method == "swept_sine":
        tt = np.clip(t - pad / fs, 0, dur)
        drive = signal.chirp(tt, band_Hz[0], dur, band_Hz[1], method="linear")
        drive *= (t >= pad / fs) & (t < pad / fs + dur)
    elif method == "free_vibration":
        fn = math.sqrt((stiffness_N_per_m + cfg.linkage_stiffness_N_per_m) / (M_a + M_c)) / (2 * math.pi)
        on = (t >= pad / fs) & (t < pad / fs + 4.0)
        ramp = np.clip((t - pad / fs) / 1.0, 0, 1)
        drive = np.sin(2 * np.pi * fn * t) * on * ramp
        pad_end = n - int(round(4.0 * fs))  # the decay must end inside the record (periodic solve)
        drive[pad_end:] = 0
    else:
        raise ValueError(f"method must be random, swept_sine, free_vibration or load_deflection, got {method!r}")
    omega = 2 * np.pi * sfft.rfftfreq(n, 1 / fs)
    jw = 1j * omega
    kb = cfg.beam_stiffness_N_per_m + jw * cfg.beam_damping_N_s_per_m
    z = _impedance(omega, stiffness_N_per_m, damping_N_s_per_m, series_damping_N_s_per_m)
    a11 = z + kb - omega**2 * M_a
    a22 = kb + cfg.linkage_stiffness_N_per_m + jw * cfg.linkage_damping_N_s_per_m - omega**2 * M_c
    det = a11 * a22 - kb * kb
    D = sfft.rfft(drive)
    X = kb * D / det
    x = sfft.irfft(X, n)
    target = displacement_m or METHOD_DISPLACEMENT_M[method]
    scale = target / float(np.std(x[pad:pad + n_keep])) if method != "free_vibration" else \
        target / float(np.max(np.abs(x)))
    X *= scale
    G_road = 0.0
    if road is not None and method in ("random", "swept_sine") and road.get("speed_km_h", 0.0) > 0:
        # the ground's height under the tyre, tapered into the quiet pads (the solve is periodic)
        taper = signal.windows.tukey(n, min(1.0, 2 * pad / n))
        G_road = sfft.rfft(ground_profile(rng, t, cfg=cfg, **road) * taper)
        X = X + a22 * z * G_road / det  # the tyre pushes the axle by Z (ground − axle)
    x = sfft.irfft(X, n)
    xdd = sfft.irfft(-(omega**2) * X, n)
    f_dyn = sfft.irfft(-z * (X - G_road), n)  # tyre force on the axle about the static load
    f_b = M_a * xdd - f_dyn + (G * M_a - load_kN * 1e3 if direction == "vertical" else 0.0)
    f_t = f_dyn + (load_kN * 1e3 if direction == "vertical" else 0.0)
    sl = slice(pad, pad + n_keep)
    return RunSignals(np.arange(n_keep) / fs, x[sl], xdd[sl], np.zeros(n_keep), f_t[sl], f_b[sl],
                      sfft.irfft(D * scale, n)[sl]), None


def simulate_method_run(row, rng: np.random.Generator, day, cfg: RigConfig = RigConfig()):
    """Simulate and record one planned run of another method (a :func:`tyrelab.rig.campaigns.campaign_plan`
    row with ``method`` and ``direction``) with the run's generator ``rng`` and its day's instrument
    state ``day`` (:func:`tyrelab.rig.campaigns.simulate_run` passes both); return (run table, info with
    the truth used)."""
    import pandas as pd

    get = row.get if hasattr(row, "get") else (lambda k, d=None: getattr(row, k, d))
    tyre = get("plan_tyre", None) or truth.tyre_params(get("tyre_id"))
    method, direction = get("method"), get("direction")
    v, p, load = float(get("speed_km_h")), float(get("pressure_bar")), float(get("load_kN"))
    extra = {"amplitude_mm_pp": method_amplitude_mm_pp(method)} if direction == "vertical" else {}
    k, c, c2 = directional_truth(tyre, direction, p, v, load, **extra)
    lo, hi = get("band_low_Hz", None), get("band_high_Hz", None)
    band_Hz = (float(lo), float(hi)) if lo is not None and pd.notna(lo) else (1.0, 8.0)
    road = ({"speed_km_h": v, "surface": str(get("surface", None) or "concrete"), "circumference_m": tyre.circumference_m,
             "lug_height_mm": tyre.lug_height_mm, "traction": tyre.traction} if v > 0 else None)
    sig, deflection = method_signals(method, direction, k, c, c2, load, rng, cfg, band_Hz=band_Hz,
                                     duration_s=float(get("plan_duration_s", 0.0) or 0.0) or None, road=road)
    run = record(sig, day, rng, cfg, gravity_m_s2=G if direction == "vertical" else 0.0)
    if deflection is not None:
        run["deflection_m"] = (deflection + 2e-5 * rng.standard_normal(deflection.size)).astype(np.float32)
    return run, {"stiffness_N_per_m": k, "damping_N_s_per_m": c, "series_damping_N_s_per_m": c2,
                 "displacement_rms_m": float(np.std(sig.axle_displacement_m))}
