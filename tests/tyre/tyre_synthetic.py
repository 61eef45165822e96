"""Synthetic ``results`` tables with known answers for the tyre regressions."""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd

#: Known truth: per tyre, stationary and rolling K = Kc + dKp P; damping C = Cc + dC P.
TRUTH = {
    "T3": {"stationary": (184.0, 200.0), "rolling": (112.0, 177.0), "damping": (0.67, 0.36)},
    "F1": {"stationary": (96.0, 158.0), "rolling": (-3.0, 134.0), "damping": (0.30, 0.32)},
}


def run(tyre_id, speed, pressure, k, c, **kw):
    row = dict(
        campaign="synthetic", run_id=f"{tyre_id}-{speed}-{pressure}-{len(kw)}-{np.random.randint(1e9)}",
        tyre_id=tyre_id, kind="measurement", speed_km_h=speed, pressure_bar=pressure, load_kN=18.3,
        excitation_frequency_Hz=4.0, amplitude_mm_pp=14.0, torque_kNm=0.0, surface="concrete",
        axle_mass_kg=1200.0, recorded_on="1989-06-01", rolling=speed > 0,
        excitation_frequency_measured_Hz=None, stiffness_kN_per_m=k, damping_kN_s_per_m=c,
        welch_stiffness_kN_per_m=k, welch_damping_kN_s_per_m=c, amplitude_measured_mm_pp=None,
        coherence=0.99, qc_ok=True, qc_reasons="",
    )
    row.update(kw)
    return row


def make_results(noise=0.0, seed=0):
    """Exact (noise=0) linear tyres over pressures 0.8-1.6 bar at 0, 10, 15 km/h."""
    rng = np.random.default_rng(seed)
    rows = []
    for tyre, truth in TRUTH.items():
        for speed, p in itertools.product((0.0, 10.0, 15.0), (0.8, 1.1, 1.38, 1.6)):
            kc, dk = truth["stationary" if speed == 0 else "rolling"]
            cc, dc = truth["damping"]
            k = kc + dk * p + noise * rng.standard_normal()
            c = cc + dc * p - 0.01 * speed
            rows.append(run(tyre, speed, p, k, c))
    return pd.DataFrame(rows)


