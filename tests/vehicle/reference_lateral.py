"""An independent reference model of the 3-D tractor on vertical and lateral tyre springs (issue 33).

Written directly as mass, damping and stiffness matrices from the kinematics below, by hand,
using nothing of ``tyrelab.vehicle.model`` (the project's assembly), so that the project's
second system can be checked against it: natural frequencies and seat responses, rigid and
pivoting front axles, Kelvin-Voigt and Maxwell lateral tyres, the static loads' moment.

Co-ordinates (small angles, SI; ``x`` forward, ``y`` left, ``z`` up from the CG): body bounce
``z``, pitch ``th`` (nose up), roll ``phi`` (left side up), and with lateral tyre elements body
lateral ``y`` and yaw ``psi`` (nose left); a pivoting front axle adds its roll ``alpha`` about a
longitudinal pivot ``pivot_height_m`` above the ground. A body point ``p`` moves by
``dz = z + p_x th + p_y phi``, ``dy = y - p_z phi + p_x psi``, ``dx = -p_z th - p_y psi`` (no
fore-aft freedom: the lateral system is the issue's).

Tyre ``i`` at ``(a_i, b_i)`` (ahead of the CG, left of it), contact patch ``h`` (the CG height)
below the CG:

* vertical Kelvin-Voigt ``k_z, c_z``: deflection ``z + a_i th + b_i phi - u_i`` (a pivoting front
  axle: ``z + a_f th + b_i alpha - u_i``);
* lateral ``k_y, c_y`` at the patch: deflection ``y + h phi + a_i psi`` (a pivoting front axle: the
  pivot is a body point ``h - r`` below the CG, the patch ``r`` below the pivot:
  ``y + (h - r) phi + r alpha + a_f psi``); Kelvin-Voigt (``k_y``, ``c_y`` in parallel) or Maxwell
  (in series: dynamic stiffness ``jω c_y k_y / (k_y + jω c_y)``);
* the static loads ``F_i`` (``F_front = m g B / (A + B)`` per axle, half per tyre) act at the patches,
  which stay on the ground: about the CG they give the roll moment ``Σ (b_i - y) F_i = -m g y``; with
  a pivoting front axle the front loads act on the axle (``-F_f y_p`` about the pivot, ``y_p`` the
  pivot's lateral displacement ``y + (h - r) phi + a_f psi``) and reach the body at the pivot
  (``F_f (y_p - y)`` about the CG). Without lateral elements (``lateral = "none"``) there is no
  ``y`` and no such moment: the body rolls about its CG.

Outputs: the seat point ``(s_x, s_y, s_z)``: ``a_x = -s_z th'' - s_y psi''``,
``a_y = y'' - s_z phi'' + s_x psi''``, ``a_z = z'' + s_x th'' + s_y phi''`` (inertial axes, no
gravity tilt).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

G = 9.81


@dataclass(frozen=True)
class Tractor:
    mass_kg: float
    pitch_inertia_kg_m2: float
    roll_inertia_kg_m2: float
    yaw_inertia_kg_m2: float
    front_distance_m: float
    rear_distance_m: float
    cg_height_m: float
    front_track_m: float
    rear_track_m: float
    k_front: float  # vertical, per tyre, N/m
    c_front: float
    k_rear: float
    c_rear: float
    ky_front: float = 0.0  # lateral, per tyre, N/m
    cy_front: float = 0.0
    ky_rear: float = 0.0
    cy_rear: float = 0.0
    lateral: str = "none"  # "none" | "kelvin_voigt" | "maxwell"
    pivot_front: bool = False
    axle_roll_inertia_kg_m2: float = 0.0
    pivot_height_m: float = 0.6
    gravity: bool = True
    seat: tuple = (0.0, 0.0, 0.0)  # ahead, left, above the CG

    @property
    def tyres(self):
        a, b = self.front_distance_m, -self.rear_distance_m
        return (("front_left", a, self.front_track_m / 2), ("front_right", a, -self.front_track_m / 2),
                ("rear_left", b, self.rear_track_m / 2), ("rear_right", b, -self.rear_track_m / 2))


def coordinates(t: Tractor) -> list[str]:
    q = ["z", "th", "phi"]
    if t.lateral != "none":
        q += ["y", "psi"]
    if t.pivot_front:
        q.append("alpha")
    return q


def matrices(t: Tractor):
    """``M``, ``K`` (springs and the static loads' moment), ``C`` (Kelvin-Voigt dampers), the Maxwell
    elements ``[(g, k, c)]``, the input rows ``[(tyre, g_z, k, c)]`` and the co-ordinate names."""
    names = coordinates(t)
    ix = {n: i for i, n in enumerate(names)}
    n = len(names)

    def row(**coef):
        r = np.zeros(n)
        for k, v in coef.items():
            r[ix[k]] += v
        return r

    m = np.zeros((n, n))
    m[ix["z"], ix["z"]] = t.mass_kg
    m[ix["th"], ix["th"]] = t.pitch_inertia_kg_m2
    m[ix["phi"], ix["phi"]] = t.roll_inertia_kg_m2
    if "y" in ix:
        m[ix["y"], ix["y"]] = t.mass_kg
        m[ix["psi"], ix["psi"]] = t.yaw_inertia_kg_m2
    if "alpha" in ix:
        m[ix["alpha"], ix["alpha"]] = t.axle_roll_inertia_kg_m2
    k = np.zeros((n, n))
    c = np.zeros((n, n))
    maxwell, inputs = [], []
    h, r = t.cg_height_m, t.pivot_height_m
    for name, a, b in t.tyres:
        front = name.startswith("front")
        kz, cz = (t.k_front, t.c_front) if front else (t.k_rear, t.c_rear)
        gz = row(z=1.0, th=a, alpha=b) if (front and t.pivot_front) else row(z=1.0, th=a, phi=b)
        k += kz * np.outer(gz, gz)
        c += cz * np.outer(gz, gz)
        inputs.append((name, gz, kz, cz))
        if t.lateral == "none":
            continue
        ky, cy = (t.ky_front, t.cy_front) if front else (t.ky_rear, t.cy_rear)
        gy = row(y=1.0, phi=h - r, alpha=r, psi=a) if (front and t.pivot_front) else row(y=1.0, phi=h, psi=a)
        if t.lateral == "kelvin_voigt":
            k += ky * np.outer(gy, gy)
            c += cy * np.outer(gy, gy)
        else:
            maxwell.append((gy, ky, cy))
    if t.gravity and t.lateral != "none":
        wb = t.front_distance_m + t.rear_distance_m
        f_front = t.mass_kg * G * t.rear_distance_m / wb
        f_rear = t.mass_kg * G * t.front_distance_m / wb
        # generalised force Q = -K_g q: roll moment -F y at the patches (module docstring)
        if t.pivot_front:
            y_p_minus_y = row(phi=h - r, psi=t.front_distance_m)
            y_p = row(y=1.0) + y_p_minus_y
            k[ix["phi"]] += f_rear * row(y=1.0) - f_front * y_p_minus_y
            k[ix["alpha"]] += f_front * y_p
        else:
            k[ix["phi"]] += (f_front + f_rear) * row(y=1.0)
    return m, k, c, maxwell, inputs, names


def dynamic_stiffness(t: Tractor, omega: float):
    m, k, c, maxwell, _, _ = matrices(t)
    z = k + 1j * omega * c - omega**2 * m
    for g, ky, cy in maxwell:
        z += (1j * omega * cy * ky / (ky + 1j * omega * cy)) * np.outer(g, g)
    return z


def natural_frequencies_Hz(t: Tractor) -> np.ndarray:
    """Undamped: ``det(K - ω² M) = 0`` (a Maxwell element's spring counts, its damper locked: the
    damper is the slow part, as the project's undamped modes take it)."""
    m, k, _, maxwell, _, _ = matrices(t)
    for g, ky, _ in maxwell:
        k = k + ky * np.outer(g, g)
    lam = np.linalg.eigvals(np.linalg.solve(m, k))
    return np.sort(np.sqrt(np.abs(lam.real)) / (2 * math.pi))


def undamped_modes(t: Tractor):
    """Frequencies (Hz) and mode shapes (columns, co-ordinate order of :func:`coordinates`)."""
    m, k, _, maxwell, _, names = matrices(t)
    for g, ky, _ in maxwell:
        k = k + ky * np.outer(g, g)
    lam, vec = np.linalg.eig(np.linalg.solve(m, k))
    order = np.argsort(lam.real)
    return np.sqrt(np.abs(lam.real[order])) / (2 * math.pi), vec[:, order].real, names


def seat_response(t: Tractor, f_Hz: float, amplitudes: dict, speed_m_s: float) -> dict:
    """Complex seat accelerations (``x``, ``y``, ``z``, m/s²) under sinusoidal ground displacements of
    amplitude ``amplitudes[tyre]`` (m) at ``f_Hz``, the rear tyres a wheelbase later."""
    w = 2 * math.pi * f_Hz
    _, _, _, _, inputs, names = matrices(t)
    ix = {n: i for i, n in enumerate(names)}
    tau = (t.front_distance_m + t.rear_distance_m) / speed_m_s
    rhs = np.zeros(len(names), complex)
    for name, gz, kz, cz in inputs:
        u = amplitudes.get(name, 0.0) * (np.exp(-1j * w * tau) if name.startswith("rear") else 1.0)
        rhs += gz * (kz + 1j * w * cz) * u
    q = np.linalg.solve(dynamic_stiffness(t, w), rhs)
    acc = -(w**2) * q
    sx, sy, sz = t.seat

    def get(n):
        return acc[ix[n]] if n in ix else 0.0

    return {"x": -sz * get("th") - sy * get("psi"),
            "y": get("y") - sz * get("phi") + sx * get("psi"),
            "z": get("z") + sx * get("th") + sy * get("phi")}
