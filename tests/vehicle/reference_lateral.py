"""An independent reference model of the 3-D tractor on vertical and lateral tyre springs (issues 33, 42).

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

The rolling tyre (issue 42, thesis §2.5)
---------------------------------------
``lateral = "rolling"``: per tyre a Kelvin-Voigt unit ``k_y, c_y`` from the tyre's patch point on
the body (deflection ``d`` as above) to the *contact point*, whose lateral displacement ``s`` on
the ground is a coordinate of its own (massless), in series with a damper ``c2`` from the contact
point to the ground (``c2 = a / v``: it acts on the contact point's lateral velocity, the
single-point slip model; Lines 1987; Crolla, Horton & Stayner 1990):

    F = k_y (d - s) + c_y (d' - s')   (on the body, -dd/dq F),     c2 s' = F.

``c2 = inf`` (a stationary tyre) locks the contact point: the Kelvin-Voigt element; ``c2 = 0`` (v ->
infinity) frees it: no force. The static load ``F_i`` acts where the tyre touches the ground, at
the contact point: its roll moment about the CG is ``-F_i (y - s_i)`` (a pivot axle: ``-F_i (y_p -
s_i)`` about the pivot), so a tractor drifting sideways with its contact points feels nothing (two
zero roots: lateral and yaw drift). ``longitudinal = "kelvin_voigt"`` or ``"rolling"`` adds the
fore-aft ``x`` and per axle one element (two tyres) at the ground under the axle, deflection
``x + h th`` (``- s`` rolling), and the static loads' pitch moment ``-F (x - s)``.

With massless contact points the equations are ``M q'' + C q' + K q = f`` over ``q`` = the body's
coordinates then the contact points' ``s`` (zero mass on ``s``): :func:`augmented`. The complex
roots are the finite eigenvalues of the linearisation ``[[0, I], [-K, -C]] v = λ [[I, 0], [0, M]] v``
(:func:`complex_roots`), the seat response the solution of ``(K + jωC - ω²M) Q = f``. Seat outputs
with ``tilt``: body-fixed axes (ISO 2631-1's seat pad): ``a_x + g th``, ``a_y + g phi``.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

G = 9.80665  # the standard gravity, the model's since issue 45


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
    lateral: str = "none"  # "none" | "kelvin_voigt" | "maxwell" | "rolling"
    pivot_front: bool = False
    axle_roll_inertia_kg_m2: float = 0.0
    pivot_height_m: float = 0.6
    gravity: bool = True
    seat: tuple = (0.0, 0.0, 0.0)  # ahead, left, above the CG
    c2y_front: float = math.inf  # rolling: the series damper per tyre at the speed, N s/m (inf: locked)
    c2y_rear: float = math.inf
    longitudinal: str = "none"  # "none" | "kelvin_voigt" | "rolling" (per axle, both tyres)
    kx_front: float = 0.0  # per tyre, N/m
    cx_front: float = 0.0
    c2x_front: float = math.inf
    kx_rear: float = 0.0
    cx_rear: float = 0.0
    c2x_rear: float = math.inf
    tilt: bool = False  # seat outputs on body-fixed axes (gravity components g th, g phi)

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


def _vertical_tyres(t: Tractor, row, n: int):
    """``K``, ``C`` of the vertical tyres over ``n`` coordinates (rows from ``row(**coef)``) and the input
    rows ``[(tyre, g_z, k_z, c_z)]``."""
    k, c, inputs = np.zeros((n, n)), np.zeros((n, n)), []
    for name, a, b in t.tyres:
        front = name.startswith("front")
        kz, cz = (t.k_front, t.c_front) if front else (t.k_rear, t.c_rear)
        gz = row(z=1.0, th=a, alpha=b) if (front and t.pivot_front) else row(z=1.0, th=a, phi=b)
        k += kz * np.outer(gz, gz)
        c += cz * np.outer(gz, gz)
        inputs.append((name, gz, kz, cz))
    return k, c, inputs


def matrices(t: Tractor):
    """``M``, ``K`` (springs and the static loads' moment), ``C`` (Kelvin-Voigt dampers), the Maxwell
    elements ``[(g, k, c)]``, the input rows ``[(tyre, g_z, k, c)]`` and the co-ordinate names."""
    if t.lateral == "rolling" or t.longitudinal != "none":
        raise ValueError("matrices: issue 33's elements only; the rolling tyre and fore-aft: augmented()")
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
    k, c, inputs = _vertical_tyres(t, row, n)
    maxwell = []
    h, r = t.cg_height_m, t.pivot_height_m
    for name, a, b in t.tyres:
        front = name.startswith("front")
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


def ground_force(t: Tractor, inputs, n: int, w: float, amplitudes: dict, speed_m_s: float) -> np.ndarray:
    """The generalised force (complex amplitude over ``n`` coordinates) of sinusoidal ground displacements
    ``amplitudes[tyre]`` (m) at ``w`` rad/s through the vertical tyres ``inputs``, the rear a wheelbase later."""
    tau = (t.front_distance_m + t.rear_distance_m) / speed_m_s
    rhs = np.zeros(n, complex)
    for name, gz, kz, cz in inputs:
        u = amplitudes.get(name, 0.0) * (np.exp(-1j * w * tau) if name.startswith("rear") else 1.0)
        rhs += gz * (kz + 1j * w * cz) * u
    return rhs


def seat_response(t: Tractor, f_Hz: float, amplitudes: dict, speed_m_s: float) -> dict:
    """Complex seat accelerations (``x``, ``y``, ``z``, m/s²) under sinusoidal ground displacements of
    amplitude ``amplitudes[tyre]`` (m) at ``f_Hz``, the rear tyres a wheelbase later."""
    w = 2 * math.pi * f_Hz
    _, _, _, _, inputs, names = matrices(t)
    ix = {n: i for i, n in enumerate(names)}
    q = np.linalg.solve(dynamic_stiffness(t, w), ground_force(t, inputs, len(names), w, amplitudes, speed_m_s))
    acc = -(w**2) * q
    sx, sy, sz = t.seat

    def get(n):
        return acc[ix[n]] if n in ix else 0.0

    return {"x": -sz * get("th") - sy * get("psi"),
            "y": get("y") - sz * get("phi") + sx * get("psi"),
            "z": get("z") + sx * get("th") + sy * get("phi")}


# --------------------------------------------------------------------------- the rolling tyre (issue 42)
def at_speed(t: Tractor, speed_km_h: float, a_lateral=None, a_longitudinal=None) -> Tractor:
    """``t`` with the series dampers of its rolling elements at ``speed_km_h``: ``c2 = a / v``,
    ``a`` per tyre in N s/m x km/h as ``(front, rear)``; ``v = 0``: locked (``inf``)."""
    def c2(a):
        return math.inf if speed_km_h == 0 else a / speed_km_h
    kw = {}
    if a_lateral is not None:
        kw.update(c2y_front=c2(a_lateral[0]), c2y_rear=c2(a_lateral[1]))
    if a_longitudinal is not None:
        kw.update(c2x_front=c2(a_longitudinal[0]), c2x_rear=c2(a_longitudinal[1]))
    return dataclasses.replace(t, **kw)


def augmented(t: Tractor):
    """``(M, C, K, names, inputs)`` over the body's coordinates (:func:`coordinates`, plus ``x`` with a
    longitudinal element) then the contact points ``s_<tyre>`` of the rolling elements whose series
    damper is not locked (module docstring). ``inputs``: ``[(tyre, row, k_z, c_z)]`` of the vertical
    tyres. Maxwell lateral elements are a spring to a massless point and a damper from it to the
    ground, their static loads at the ground-fixed patch (issue 33's convention)."""
    body = coordinates(t) + (["x"] if t.longitudinal != "none" else [])
    h, r = t.cg_height_m, t.pivot_height_m
    wb = t.front_distance_m + t.rear_distance_m
    load = {"front": t.mass_kg * G * t.rear_distance_m / wb / 2, "rear": t.mass_kg * G * t.front_distance_m / wb / 2}
    # the horizontal elements: (name, row over body, k, c inside, c2 to the ground, kind, axle, per-tyre load)
    horiz = []
    for name, a, b in t.tyres:
        front = name.startswith("front")
        if t.lateral != "none":
            ky, cy = (t.ky_front, t.cy_front) if front else (t.ky_rear, t.cy_rear)
            c2 = (t.c2y_front if front else t.c2y_rear) if t.lateral == "rolling" else \
                (math.inf if t.lateral == "kelvin_voigt" else cy)
            inner_c = 0.0 if t.lateral == "maxwell" else cy
            coef = dict(y=1.0, phi=h - r, alpha=r, psi=a) if (front and t.pivot_front) else dict(y=1.0, phi=h, psi=a)
            horiz.append((f"{name}_y", coef, ky, inner_c, c2, "lateral", "front" if front else "rear", load["front" if front else "rear"]))
    if t.longitudinal != "none":
        for axle in ("front", "rear"):
            kx, cx, c2x = ((t.kx_front, t.cx_front, t.c2x_front) if axle == "front" else (t.kx_rear, t.cx_rear, t.c2x_rear))
            c2 = 2 * c2x if t.longitudinal == "rolling" else math.inf  # the axle's two tyres
            horiz.append((f"{axle}_x", dict(x=1.0, th=h), 2 * kx, 2 * cx, c2, "longitudinal", axle, 2 * load[axle]))
    slips = [e[0] for e in horiz if math.isfinite(e[4])]
    names = body + [f"s_{n}" for n in slips]
    ix = {n: i for i, n in enumerate(names)}
    n = len(names)

    def row(**coef):
        out = np.zeros(n)
        for key, v in coef.items():
            if key in ix:
                out[ix[key]] += v
        return out

    m = np.zeros((n, n))
    for key, value in (("z", t.mass_kg), ("th", t.pitch_inertia_kg_m2), ("phi", t.roll_inertia_kg_m2),
                       ("y", t.mass_kg), ("psi", t.yaw_inertia_kg_m2), ("alpha", t.axle_roll_inertia_kg_m2),
                       ("x", t.mass_kg)):
        if key in ix:
            m[ix[key], ix[key]] = value
    k, c, inputs = _vertical_tyres(t, row, n)
    for name, coef, ke, ce, c2, kind, axle, f_static in horiz:
        d = row(**coef)
        g = d - row(**{f"s_{name}": 1.0})  # the unit's deflection: patch point minus contact point
        k += ke * np.outer(g, g)
        c += ce * np.outer(g, g)
        if math.isfinite(c2):
            e = row(**{f"s_{name}": 1.0})
            c += c2 * np.outer(e, e)
        if not t.gravity:
            continue
        # the static load at the contact point (a Maxwell element's at the ground-fixed patch)
        at = row(**{f"s_{name}": 1.0}) if t.lateral == "rolling" or kind == "longitudinal" else np.zeros(n)
        if kind == "longitudinal":
            k[ix["th"]] += f_static * (row(x=1.0) - at)
        elif axle == "front" and t.pivot_front:
            y_p = row(y=1.0, phi=h - r, psi=t.front_distance_m)
            k[ix["alpha"]] += f_static * (y_p - at)
            k[ix["phi"]] -= f_static * (y_p - row(y=1.0))
        else:
            k[ix["phi"]] += f_static * (row(y=1.0) - at)
    return m, c, k, names, inputs


def complex_roots(t: Tractor, zero_tol: float = 1e-11):
    """The finite roots ``λ`` of ``det(λ² M + λ C + K) = 0`` (rad/s; :func:`augmented`) with their
    shapes over the coordinates, zero roots (``|λ| < zero_tol`` times the largest) left out, sorted
    by ``|λ|``: ``(roots, shapes, names)``."""
    m, c, k, names, _ = augmented(t)
    n = len(names)
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-k, -c]])
    b = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), m]])
    import scipy.linalg

    w, v = scipy.linalg.eig(a, b)
    finite = np.isfinite(w) & (np.abs(w) < 1e12)
    w, v = w[finite], v[:n, finite]
    scale = np.max(np.abs(w))
    keep = np.abs(w) > zero_tol * scale
    w, v = w[keep], v[:, keep]
    order = np.argsort(np.abs(w) + 1e-9 * np.abs(w.imag))
    return w[order], v[:, order], names


@dataclass(frozen=True)
class Mode:
    """One oscillating mode (a complex pair, ``Im λ > 0``) or one real root (``damped_Hz`` 0)."""

    name: str
    root: complex
    undamped_Hz: float
    damped_Hz: float
    damping_ratio: float
    shares: dict

    @property
    def oscillating(self) -> bool:
        return self.damped_Hz > 0


#: Mode names by the coordinate that moves most (the project's, issue 33).
_NAMES = {"z": "bounce", "th": "pitch", "phi": "roll", "y": "lateral", "psi": "yaw", "alpha": "front_axle_roll",
          "x": "longitudinal"}


def modes(t: Tractor, imag_tol: float = 1e-9) -> list[Mode]:
    """The oscillating modes (one per complex pair) and the real roots, each with its undamped
    frequency ``|λ|/2π``, damped frequency ``Im λ/2π`` and damping ratio ``-Re λ/|λ|``, named by the
    coordinate of the body that holds most kinetic energy (``|v_i|² M_ii``; the contact points are
    massless); ``lateral_roll`` where ``y`` or ``phi`` leads and the lesser holds at least 5 %."""
    roots, shapes, names = complex_roots(t)
    m = augmented(t)[0]
    out = []
    for lam, vec in zip(roots, shapes.T):
        if lam.imag < -imag_tol * abs(lam):
            continue
        energy = np.abs(vec) ** 2 * np.diag(m)
        total = energy.sum()
        shares = {nm: float(e / total) for nm, e in zip(names, energy) if not nm.startswith("s_")} if total > 0 else {}
        lead = max(shares, key=shares.get) if shares else "slip"
        name = _NAMES.get(lead, lead)
        if lead in ("y", "phi") and min(shares.get("y", 0.0), shares.get("phi", 0.0)) >= 0.05:
            name = "lateral_roll"
        osc = lam.imag > imag_tol * abs(lam)
        out.append(Mode(name, complex(lam), abs(lam) / (2 * math.pi), (lam.imag if osc else 0.0) / (2 * math.pi),
                        float(-lam.real / abs(lam)), shares))
    return out


def lateral_roll_damping(t: Tractor) -> float:
    """The damping ratio of the lowest oscillating mode led by the body's lateral or roll motion
    (``lateral_roll``, else ``lateral`` or ``roll``); ``inf`` where none oscillates (overdamped)."""
    for md in modes(t):
        if md.oscillating and md.name in ("lateral_roll", "lateral", "roll"):
            return md.damping_ratio
    return math.inf


def seat_response_augmented(t: Tractor, f_Hz: float, amplitudes: dict, speed_m_s: float) -> dict:
    """:func:`seat_response` from :func:`augmented` (every element kind; ``tilt``: body-fixed axes)."""
    w = 2 * math.pi * f_Hz
    m, c, k, names, inputs = augmented(t)
    ix = {n: i for i, n in enumerate(names)}
    q = np.linalg.solve(k + 1j * w * c - w**2 * m, ground_force(t, inputs, len(names), w, amplitudes, speed_m_s))
    sx, sy, sz = t.seat

    def acc(n):
        return -(w**2) * q[ix[n]] if n in ix else 0.0

    def pos(n):
        return q[ix[n]] if n in ix else 0.0

    g = G if t.tilt else 0.0
    return {"x": acc("x") - sz * acc("th") - sy * acc("psi") + g * pos("th"),
            "y": acc("y") - sz * acc("phi") + sx * acc("psi") + g * pos("phi"),
            "z": acc("z") + sx * acc("th") + sy * acc("phi")}


def _mac(m: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    """Mass-weighted modal assurance criterion of two (complex) shapes."""
    num = abs(np.conj(a) @ m @ b) ** 2
    den = abs(np.conj(a) @ m @ a) * abs(np.conj(b) @ m @ b)
    return float(num / den) if den > 0 else 0.0


def followed(build, speeds_km_h, start: str = "lateral_roll", step_km_h: float = 0.25) -> list:
    """The mode called ``start`` at the first speed (its lowest oscillating mode of that name), followed
    by its shape (mass-weighted MAC over the body's coordinates, one small speed step at a time) to each
    of ``speeds_km_h`` (ascending): a :class:`Mode` per speed; an overdamped mode is a real root
    (``damped_Hz`` 0). ``build(v)`` gives the tractor at ``v`` km/h."""
    speeds = sorted(float(v) for v in speeds_km_h)
    grid = sorted(set(np.round(np.concatenate([np.arange(speeds[0], speeds[-1], step_km_h), speeds]), 9)))
    first = build(grid[0])
    mds = modes(first)
    cur = next(md for md in mds if md.oscillating and md.name == start)
    _, shapes, names = complex_roots(first)
    roots = complex_roots(first)[0]
    vec = shapes[:, int(np.argmin(np.abs(roots - cur.root)))]
    body = [i for i, n in enumerate(names) if not n.startswith("s_")]
    out = {}
    for v in grid:
        t = build(v)
        roots, shapes, nm = complex_roots(t)
        m = augmented(t)[0]
        bi = [i for i, n in enumerate(nm) if not n.startswith("s_")]
        mb = m[np.ix_(bi, bi)]
        upper = [j for j, lam in enumerate(roots) if lam.imag >= -1e-9 * abs(lam)]
        j = max(upper, key=lambda j: _mac(mb, vec[body] if len(body) == len(bi) else vec[body], shapes[bi, j]))
        vec, body = shapes[:, j], bi
        lam = roots[j]
        osc = lam.imag > 1e-9 * abs(lam)
        if v in speeds:
            out[v] = Mode(start, complex(lam), abs(lam) / (2 * math.pi), (lam.imag if osc else 0.0) / (2 * math.pi),
                          float(-lam.real / abs(lam)), {})
    return [out[v] for v in speeds]
