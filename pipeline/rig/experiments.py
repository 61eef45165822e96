"""Virtual experiments for the alternative measurement methods of §3.4 (Table I).

The same vehicle as :mod:`tyrelab.rig.instrument` (axle on stiff load beams,
carriage with inertial mass, linkage to the tractor with stiffness and
damping), stationary tyre:

* :func:`load_ramp` - slow load-deflection test with rubber creep (§3.4, Fig. 18, Fig. 28);
* :func:`free_decay` - release from a displaced position, free vibration (§3.4 b);
* :func:`random_force_response` - the carriage excited by band-limited random
  force, axle response recorded (§3.4 c);
* :func:`table_i` - Table I: the four methods of :mod:`tyrelab.measurement.methods` applied to
  these experiments, beside the thesis.

The response-based experiments see the linkage stiffness and damping in
parallel with the tyre, which the apparent-mass method does not (§3.4).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import fft as sfft
from scipy import signal

import pandas as pd

from ..measurement import apparent_mass as am
from ..measurement.methods import METHODS, TABLE_I_SOURCE, free_vibration, half_power, load_deflection_stiffness
from ..measurement.recording import frame_tyre_force, recording_arrays
from . import truth
from .instrument import G, DayCalibration, RigConfig, _system, carriage_mass_kg, record, simulate_axle

__all__ = ["CREEP_STIFFNESS_RATIO", "CREEP_TIME_S", "Recording", "load_ramp", "load_ramp_clean", "free_decay",
    "random_force_response", "suspended_mass_kg", "table_i"]

#: Creep of the tyre rubber (§3.4, §4.5.1, Fig. 28): a Kelvin element in series
#: with the tyre spring. Stiffness ratio chosen so that a slow ramp gives the
#: Table I ratio load-deflection/apparent mass (330/450); time constant a few
#: seconds ("decreases by several millimetres in the first few seconds").
CREEP_STIFFNESS_RATIO = (330 / 450) / (1 - 330 / 450)
CREEP_TIME_S = 3.0


@dataclass
class Recording:
    """Sampled signals of a virtual experiment (SI)."""

    time_s: np.ndarray
    force_N: np.ndarray
    displacement_m: np.ndarray
    acceleration_m_s2: np.ndarray


def load_ramp(stiffness_N_per_m: float, max_load_N: float = 18.3e3, ramp_s: float = 120.0,
              sample_rate_Hz: float = 20.0, creep_ratio: float = CREEP_STIFFNESS_RATIO,
              creep_time_s: float = CREEP_TIME_S, rng: np.random.Generator | None = None) -> Recording:
    """Slow loading then unloading of the stationary tyre; deflection with creep.

    ``d = F/K + d_cr``, ``tau d_cr' + d_cr = F/(creep_ratio K)`` (first-order creep).
    ``displacement_m`` is the tyre deflection (downward positive), ``force_N`` the
    applied load. Noise: 20 N, 0.05 mm.
    """
    rng = rng or np.random.default_rng(0)
    clean = load_ramp_clean(stiffness_N_per_m, max_load_N, ramp_s, sample_rate_Hz, creep_ratio, creep_time_s)
    t, F, d = clean.time_s, clean.force_N, clean.displacement_m
    return Recording(t, F + 20 * rng.standard_normal(t.size), d + 5e-5 * rng.standard_normal(t.size), np.zeros_like(t))


def load_ramp_clean(stiffness_N_per_m: float, max_load_N: float = 18.3e3, ramp_s: float = 120.0,
                    sample_rate_Hz: float = 20.0, creep_ratio: float = CREEP_STIFFNESS_RATIO,
                    creep_time_s: float = CREEP_TIME_S) -> Recording:
    """:func:`load_ramp` without its noise: the load and the tyre's deflection themselves (the
    generator's force on the tyre is computed from these, never from a noisy measured deflection:
    differentiating that noise made 62 % of a load-deflection run's loop, issue 44).

    Examples
    --------
    >>> r = load_ramp_clean(300e3, 18.3e3, ramp_s=60.0)
    >>> round(r.force_N.max()), bool(r.displacement_m.max() > 18.3e3 / 300e3)
    (18300, True)
    """
    dt = 1 / sample_rate_Hz
    t = np.arange(int(2 * ramp_s * sample_rate_Hz) + 1) * dt
    F = max_load_N * np.where(t <= ramp_s, t / ramp_s, 2 - t / ramp_s)
    k_cr = creep_ratio * stiffness_N_per_m
    a = np.exp(-dt / creep_time_s)
    d_cr = signal.lfilter([1 - a], [1, -a], F / k_cr)
    d = F / stiffness_N_per_m + d_cr
    return Recording(t, F, d, np.zeros_like(t))


def _state_space(K: float, C: float, load_kN: float, cfg: RigConfig):
    """2-DOF axle/carriage state space (x_a, v_a, x_c, v_c), force input on the carriage."""
    M_a = cfg.axle_mass_kg
    M_c = carriage_mass_kg(load_kN, cfg)
    kb, cb = cfg.beam_stiffness_N_per_m, cfg.beam_damping_N_s_per_m
    kl, cl = cfg.linkage_stiffness_N_per_m, cfg.linkage_damping_N_s_per_m
    A = np.array([
        [0, 1, 0, 0],
        [-(K + kb) / M_a, -(C + cb) / M_a, kb / M_a, cb / M_a],
        [0, 0, 0, 1],
        [kb / M_c, cb / M_c, -(kb + kl) / M_c, -(cb + cl) / M_c],
    ])
    B = np.array([[0], [0], [0], [1 / M_c]])
    Cm = np.vstack([np.eye(4)[0], A[1]])  # outputs: axle displacement, axle acceleration
    D = np.zeros((2, 1))
    return A, B, Cm, D


def free_decay(stiffness_N_per_m: float, damping_N_s_per_m: float, load_kN: float = 18.3,
               initial_displacement_m: float = 0.01, duration_s: float = 6.0, cfg: RigConfig = RigConfig(),
               rng: np.random.Generator | None = None) -> Recording:
    """Free vibration after releasing the whole vehicle side from ``initial_displacement_m``.

    Axle and carriage start displaced together (static beam deflection neglected).
    Recorded: axle displacement and acceleration with noise.
    """
    rng = rng or np.random.default_rng(0)
    fs = cfg.sample_rate_Hz
    t = np.arange(int(duration_s * fs)) / fs
    A, B, Cm, D = _state_space(stiffness_N_per_m, damping_N_s_per_m, load_kN, cfg)
    x0 = np.array([initial_displacement_m, 0.0, initial_displacement_m, 0.0])
    _, y, _ = signal.lsim((A, B, Cm, D), np.zeros(t.size), t, X0=x0)
    n = t.size
    return Recording(t, np.zeros(n), y[:, 0] + 2e-5 * rng.standard_normal(n),
                     y[:, 1] + cfg.noise_scale * cfg.accel_noise_m_s2 * rng.standard_normal(n))


def random_force_response(stiffness_N_per_m: float, damping_N_s_per_m: float, load_kN: float = 18.3,
                          duration_s: float = 600.0, band_Hz: tuple[float, float] = (1.0, 8.0),
                          force_rms_N: float = 2e3, cfg: RigConfig = RigConfig(),
                          rng: np.random.Generator | None = None) -> Recording:
    """Carriage driven by band-limited random force (the vibrator's reaction), axle response.

    Solved exactly in the frequency domain (periodic record). ``force_N`` is the
    drive force, ``acceleration_m_s2`` the axle acceleration (with noise).
    """
    rng = rng or np.random.default_rng(0)
    fs = cfg.sample_rate_Hz
    n = int(duration_s * fs)
    f = sfft.rfftfreq(n, 1 / fs)
    spec = np.where((f >= band_Hz[0]) & (f <= band_Hz[1]), np.exp(1j * rng.uniform(0, 2 * np.pi, f.size)), 0)
    F = sfft.irfft(spec, n)
    F *= force_rms_N / F.std()
    w = 2 * np.pi * f
    _, a12, _, det = _system(w, stiffness_N_per_m, damping_N_s_per_m, cfg.axle_mass_kg,
                             carriage_mass_kg(load_kN, cfg), cfg)
    X = -a12 * sfft.rfft(F) / det
    x = sfft.irfft(X, n)
    acc = sfft.irfft(-(w**2) * X, n)
    noise = cfg.noise_scale * cfg.accel_noise_m_s2 * rng.standard_normal(n)
    return Recording(np.arange(n) / fs, F, x, acc + noise)


def suspended_mass_kg(load_kN: float) -> float:
    """Total mass supported by the tyre, L/g (kg): the mass the response methods use."""
    return load_kN * 1e3 / G


def table_i(
    thesis: pd.DataFrame, tyre_id: str = "T1", pressure_bar: float = 1.38, load_kN: float = 18.25, seed: int = 1991
) -> pd.DataFrame:
    """Table I from virtual experiments on the stationary tyre, beside the thesis' Table I.

    Our values do not come from the campaign's recordings: no lab run does a
    load ramp, a free decay and a random-force test on the same tyre, so the
    four methods are applied to virtual experiments on the truth model's tyre
    (``source`` column says so).

    The tyre's K and C are the truth model's at 0 km/h, 4 Hz, 14 mm p-p; the
    apparent mass method analyses a virtual nominal run with
    :func:`tyrelab.measurement.apparent_mass.apparent_mass_demodulation`; the
    others analyse this module's recordings (:mod:`tyrelab.measurement.methods`). The response
    methods use the suspended mass L/g.

    Parameters
    ----------
    thesis : DataFrame
        The published Table I (``method, method_label, stiffness_kN_per_m,
        damping_kN_s_per_m``; ``raw/published/table_i.csv``).
    tyre_id, pressure_bar, load_kN, seed :
        The case (thesis: T1 at 1.38 bar and 1860 kg) and the experiments' seed.

    Returns
    -------
    DataFrame
        ``method``, ``method_label``, ``source``, ``thesis_stiffness_kN_per_m``,
        ``thesis_damping_kN_s_per_m``, ``stiffness_kN_per_m``,
        ``damping_kN_s_per_m``, ``stiffness_difference_kN_per_m`` (ours - thesis),
        ``damping_difference_kN_s_per_m``, ``thesis_stiffness_ratio`` and
        ``stiffness_ratio`` (to the apparent-mass row), ``thesis_damping_excess_kN_s_per_m``
        and ``damping_excess_kN_s_per_m`` (over the apparent-mass row), ``truth_*``.
    """
    cfg = RigConfig()
    rng = np.random.default_rng(seed)
    K = truth.stiffness(tyre_id, pressure_bar, 0.0, load_kN)
    C = truth.damping(tyre_id, pressure_bar, 0.0, load_kN)
    m = suspended_mass_kg(load_kN)
    sig = simulate_axle(K, C, 50.0, rng, cfg, load_kN=load_kN)
    run = record(sig, DayCalibration(), rng, cfg)
    accel, _ = recording_arrays(run)
    d = am.apparent_mass_demodulation(frame_tyre_force(run, cfg.axle_mass_kg), accel.mean(axis=0), cfg.sample_rate_Hz)
    ours = {"apparent_mass": (float(d.stiffness_N_per_m), float(d.damping_N_s_per_m))}
    ramp = load_ramp(K, load_kN * 1e3, rng=rng)
    ours["load_deflection"] = (load_deflection_stiffness(ramp.force_N, ramp.displacement_m), np.nan)
    dec = free_decay(K, C, load_kN, cfg=cfg, rng=rng)
    fv = free_vibration(dec.time_s, dec.displacement_m, m)
    ours["free_vibration"] = (fv["stiffness_N_per_m"], fv["damping_N_s_per_m"])
    rf = random_force_response(K, C, load_kN, cfg=cfg, rng=rng)
    hp = half_power(rf.force_N, rf.acceleration_m_s2, cfg.sample_rate_Hz, m)
    ours["forced_vibration"] = (hp["stiffness_N_per_m"], hp["damping_N_s_per_m"])
    rows = []
    th = thesis.set_index("method")
    missing = [m for m in METHODS if m not in th.index]
    if missing:
        raise ValueError(f"published Table I lacks method(s) {missing}")
    k0, c0 = ours["apparent_mass"]
    tk0, tc0 = (float(th.loc["apparent_mass", c]) for c in ("stiffness_kN_per_m", "damping_kN_s_per_m"))
    for method in METHODS:
        tk, tc = (float(th.loc[method, c]) for c in ("stiffness_kN_per_m", "damping_kN_s_per_m"))
        k, c = ours[method]
        rows.append({
            "method": method, "method_label": th.loc[method, "method_label"], "source": TABLE_I_SOURCE,
            "thesis_stiffness_kN_per_m": tk, "thesis_damping_kN_s_per_m": tc,
            "stiffness_kN_per_m": k / 1e3, "damping_kN_s_per_m": c / 1e3,
            "stiffness_difference_kN_per_m": k / 1e3 - tk, "damping_difference_kN_s_per_m": c / 1e3 - tc,
            "thesis_stiffness_ratio": tk / tk0, "stiffness_ratio": k / k0,
            "thesis_damping_excess_kN_s_per_m": tc - tc0, "damping_excess_kN_s_per_m": (c - c0) / 1e3,
            "truth_stiffness_kN_per_m": K / 1e3, "truth_damping_kN_s_per_m": C / 1e3,
        })
    return pd.DataFrame(rows)
