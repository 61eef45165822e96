"""Exact-discretisation carriage vs scipy.integrate.solve_ivp on the same case.

Table XII, 10 km/h light load (1860 kg, 0.9 x 388 kN/m, 1.72 kNs/m, C_p 1 kNs/m),
100 m of the seeded slatted-track stand-in after the tapered enveloping filter,
1 ms output. Prints wall times, their ratio and the relative rms difference.

    .venv/bin/python bench/bench_carriage.py
"""

from __future__ import annotations

import time

import numpy as np

from tyrelab.vehicle import carriage as cm
from tyrelab.vehicle import enveloping as ev
from tyrelab.vehicle import profiles as pr


def main() -> None:
    track = pr.add_lead_in(pr.slatted_track(seed=5007), 5.0)
    h = ev.tapered_moving_average(track.left_m, track.dx_m, 0.53)
    car = cm.Carriage(1860.0, 0.9 * 388e3, 1720.0)
    speed, dt = 2.728, 1e-3
    t0 = time.perf_counter()
    _, u, ud = cm.ground_input(track.x_m, h, speed, dt, 0.0, 105.0)
    exact = cm.simulate_linear(car, u - u[0], ud, dt)["a_m_s2"]
    t_exact = time.perf_counter() - t0
    t0 = time.perf_counter()
    ivp = cm.simulate_ivp(car, track.x_m, h, speed, (u.size - 1) * dt, dt)["a_m_s2"]
    t_ivp = time.perf_counter() - t0
    n = min(exact.size, ivp.size)
    err = float(np.sqrt(np.mean((exact[:n] - ivp[:n]) ** 2)) / np.sqrt(np.mean(ivp[:n] ** 2)))
    print(f"samples: {n} ({n * dt:.1f} s simulated)")
    print(f"exact discretisation (incl. spline sampling): {t_exact * 1e3:.1f} ms")
    print(f"solve_ivp DOP853 rtol 1e-9:                  {t_ivp * 1e3:.1f} ms")
    print(f"speed ratio solve_ivp / exact: {t_ivp / t_exact:.0f}x")
    print(f"relative rms difference of acceleration: {err:.2e} (rms {np.sqrt(np.mean(ivp**2)):.3f} m/s^2)")


if __name__ == "__main__":
    main()
