"""Stress campaign of the virtual rig: runs with the artefacts of real recordings (issue 14).

Each artefact is a set of :class:`~tyrelab.rig.instrument.RigConfig` overrides,
applied to measurement runs drawn from the full campaign
(:func:`tyrelab.rig.campaigns.campaign_plan`), at instrument noise ×1 and ×10:

=================  ==========================================================
``none``           the rig as ``tyrelab generate`` makes it
``startup``        the vibrator starts and stops inside the record (8 s ramps)
``harmonics``      2nd (8 %) and 3rd (4 %) harmonic of the drive
``hum``            50 Hz hum, 0.2 m/s² on the accelerometers, 30 N per beam
``drift``          accelerometer offset drift, 0.1 m/s² over the run
``nonlinear``      hardening tyre, ``−0.1 K d³/d₀²`` (+7.5 % stiffness at d₀)
``lug_modulation`` stiffness varies by ±10 % with the lug under the patch
``all``            all of the above at once
=================  ==========================================================

What "truth" is. A non-linear or lug-modulated tyre has no single K, and even
the rig's nearly linear tyre (a small quadratic force, §3.3.1 eq. 1) turns
drive harmonics into a little force at the excitation frequency. So the truth
of every stress run is defined as the *first-harmonic (describing-function)
stiffness and damping* — the ratio, at the excitation frequency, of the
physical tyre force to the physical tyre deflection, demodulated with the
vibrator's commanded phase and weighted over the run by the same Hann taper
the estimator uses (:func:`describing_function_truth`). It is computed from
the simulation's error-free signals (no instrument, no derived force, no
phase reference from a noisy accelerometer), so it states what a perfect
instrument would report for that tyre at that amplitude and frequency. For a
linear tyre it equals the truth model's K and C times the §3.6 scatter
factors (to 0.05 %, tested); ``model_*`` keep those.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd

from .campaigns import campaign_plan, run_seed, simulate_run
from .instrument import RigConfig

__all__ = ["ARTEFACTS", "NOISE_SCALES", "stress_plan", "stress_config", "describing_function_truth",
           "simulate_stress_run"]

#: Artefact name -> RigConfig overrides.
ARTEFACTS: dict[str, dict] = {
    "none": {},
    "startup": {"startup_s": 8.0},
    "harmonics": {"drive_harmonics": (0.08, 0.04)},
    "hum": {"hum_accel_m_s2": 0.2, "hum_beam_N": 30.0},
    "drift": {"accel_drift_m_s2": 0.1},
    "nonlinear": {"cubic_fraction": 0.1},
    "lug_modulation": {"lug_stiffness_modulation": 0.1},
}
ARTEFACTS["all"] = {k: v for overrides in list(ARTEFACTS.values()) for k, v in overrides.items()}
#: Instrument noise multipliers of the campaign.
NOISE_SCALES = (1.0, 10.0)


def stress_config(artefact: str, noise_scale: float, base: RigConfig = RigConfig()) -> RigConfig:
    """The rig of one cell of the stress campaign."""
    if artefact not in ARTEFACTS:
        raise ValueError(f"artefact must be one of {sorted(ARTEFACTS)}, not {artefact!r}")
    if not noise_scale > 0:
        raise ValueError(f"noise_scale must be positive, got {noise_scale!r}")
    return dataclasses.replace(base, noise_scale=float(noise_scale), **ARTEFACTS[artefact])


def stress_plan(runs_per_cell: int, seed: int = 1991) -> pd.DataFrame:
    """Runs of the stress campaign: ``runs_per_cell`` per (artefact, noise scale).

    Measurement runs of the full campaign on properly calibrated days (the
    deliberately miscalibrated day is QC's business), drawn without
    replacement per cell, deterministically from ``seed``. Lug modulation
    needs a rolling traction tyre, so its cells draw from those runs only.

    Returns
    -------
    DataFrame
        Plan rows plus ``artefact``, ``noise_scale`` and ``stress_id`` (unique).
    """
    if runs_per_cell < 1:
        raise ValueError(f"runs_per_cell must be at least 1, got {runs_per_cell!r}")
    plan = campaign_plan("full")
    pool = plan[(plan["kind"] == "measurement") & (plan["plan_beam_gain_error"] == 0)
                & (plan["method"] == "stepped_sine")].reset_index(drop=True)  # the stress artefacts are the stepped sine's
    from . import truth

    traction = np.array([truth.tyre_params(t).traction for t in pool["tyre_id"]], dtype=bool)
    rolling_traction = pool[(pool["speed_km_h"] > 0).to_numpy() & traction]
    cells = []
    for i, artefact in enumerate(ARTEFACTS):
        for j, noise in enumerate(NOISE_SCALES):
            source = rolling_traction if artefact in ("lug_modulation", "all") else pool
            rng = np.random.default_rng(run_seed(seed, f"stress:{artefact}:{noise}"))
            take = source.iloc[np.sort(rng.choice(len(source), size=min(runs_per_cell, len(source)), replace=False))]
            take = take.assign(artefact=artefact, noise_scale=noise)
            take["stress_id"] = [f"{r}@{artefact}x{noise:g}" for r in take["run_id"]]
            cells.append(take)
    return pd.concat(cells, ignore_index=True)


def describing_function_truth(signals, sample_rate_Hz: float) -> tuple[float, float]:
    """First-harmonic K (N/m) and C (N s/m) of the physical tyre force over the physical deflection.

    ``Z = Σ w (f_t − mean) e^{-jφ} / Σ w (d − mean) e^{-jφ}`` with ``d = x_axle − z_ground``, ``φ`` the
    vibrator's commanded phase and ``w`` a Hann taper; ``f_t = −Z d`` in the upward
    convention, so ``K = Re(−Z)`` and ``C = Im(−Z)/ω̄`` with ``ω̄`` the taper-weighted mean of
    ``dφ/dt``. See the module docstring for why this is the truth of a non-linear tyre.
    """
    phase = np.asarray(signals.excitation_phase_rad, dtype=float)
    if phase.size == 0:
        raise ValueError("signals has no commanded excitation phase (a random-excitation run)")
    d = signals.axle_displacement_m - signals.ground_displacement_m
    f = signals.tyre_force_N
    w = np.hanning(d.size)
    e = np.exp(-1j * phase)
    z = np.sum(w * (f - f.mean()) * e) / np.sum(w * (d - d.mean()) * e)
    omega = np.gradient(np.unwrap(phase)) * sample_rate_Hz
    omega_mean = float(np.sum(w * omega) / np.sum(w))
    return float(-z.real), float(-z.imag / omega_mean)


def simulate_stress_run(row, seed: int, base: RigConfig = RigConfig()) -> tuple[pd.DataFrame, dict]:
    """Simulate one stress run; ``info`` adds ``truth_stiffness_N_per_m``, ``truth_damping_N_s_per_m``
    (the describing-function truth, module docstring) and ``model_*`` (the truth model with its scatter)."""
    get = row.get if hasattr(row, "get") else (lambda k, d=None: getattr(row, k, d))
    cfg = stress_config(get("artefact"), float(get("noise_scale")), base)
    run, info = simulate_run(row, seed, cfg, keep_signals=True)
    sig = info.pop("signals")
    k_df, c_df = describing_function_truth(sig, cfg.sample_rate_Hz)
    info.update(model_stiffness_N_per_m=info["stiffness_N_per_m"], model_damping_N_s_per_m=info["damping_N_s_per_m"],
                truth_stiffness_N_per_m=k_df, truth_damping_N_s_per_m=c_df)
    return run, info
