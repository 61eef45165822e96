"""Virtual experiments for the alternative measurement methods of §3.4 (Table I).

The same vehicle as :mod:`tyrelab.rig.instrument` (axle on stiff load beams,
carriage with inertial mass, linkage to the tractor with stiffness and
damping), stationary tyre:

* :func:`load_ramp` - slow load-deflection test with rubber creep (§3.4, Fig. 18, Fig. 28);
* :func:`free_decay` - release from a displaced position, free vibration (§3.4 b);
* :func:`random_force_response` - the carriage excited by band-limited random
  force, axle response recorded (§3.4 c).

The response-based experiments see the linkage stiffness and damping in
parallel with the tyre, which the apparent-mass method does not (§3.4).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import fft as sfft
from scipy import signal

from .instrument import G, RigConfig, _system, carriage_mass_kg

__all__ = ["CREEP_STIFFNESS_RATIO", "CREEP_TIME_S", "Recording", "load_ramp", "free_decay",
    "random_force_response", "suspended_mass_kg"]

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
    dt = 1 / sample_rate_Hz
    t = np.arange(int(2 * ramp_s * sample_rate_Hz) + 1) * dt
    F = max_load_N * np.where(t <= ramp_s, t / ramp_s, 2 - t / ramp_s)
    k_cr = creep_ratio * stiffness_N_per_m
    a = np.exp(-dt / creep_time_s)
    d_cr = signal.lfilter([1 - a], [1, -a], F / k_cr)
    d = F / stiffness_N_per_m + d_cr
    return Recording(t, F + 20 * rng.standard_normal(t.size), d + 5e-5 * rng.standard_normal(t.size), np.zeros_like(t))


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
