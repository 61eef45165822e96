"""Rotating-spoke tyre damping model (thesis §5.5.2, Figs 42–48).

The tyre is a set of radial spokes of unloaded length ``r0`` at fixed angles,
rotating with the wheel at angular speed ``θ̇ = v / r0`` (``v`` the
circumferential speed, km/h at the edges). A spoke at angle ``θ`` from the
vertical is in contact with the flat ground while ``|θ| < α = acos(h / r0)``
(``h`` the axle height) and then has length ``r = h / cos θ`` and rate

    ṙ = ḣ / cos θ + h θ̇ sin θ / cos² θ

(the thesis writes the second term with a minus sign, measuring θ against the
rotation; the two are mirror images and give the same vertical force). Each
spoke's damping element gives a force ``f = c1 sign(ṙ) + c2 ṙ`` (Coulomb friction
``c1`` in N per radian of tyre, viscous ``c2`` in Ns/m per radian of tyre), and
the vertical force on the axle, taken positive when it opposes the axle motion
(dissipated power ``F ḣ``), is

    F = ∫_{-α}^{α} f cos θ dθ.

Both parts integrate in closed form, which is what :func:`vertical_force` uses:
ṙ cos²θ = ḣ cos θ + h θ̇ sin θ changes sign once, at θ₀ = −atan(ḣ / (h θ̇)), so

    F = 2 c1 sin(clip(atan2(ḣ, h θ̇), −α, α)) + 2 α c2 ḣ.

:func:`vertical_force_spokes` sums a finite number of spokes as the thesis did
("ten or twenty spokes") and converges to the closed form. The equivalent
viscous damping is the energy dissipated per cycle of sinusoidal axle motion
``h = h0 + A sin ωt`` divided by ``π A² ω`` (thesis §5.5.2). It is linear in
``(c1, c2)``, so two coefficients are fitted to measured damping at two or more
speeds by linear least squares (:func:`fit_coefficients`).

Units: SI inside (m, s, N); speeds in km/h and amplitudes in mm at the edges,
with the unit in every column name.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from scipy.optimize import lsq_linear

from .. import _validate
from ..units import KM_H_PER_M_S
from . import conditions as cond
from .sizes import parse_tyre_size

__all__ = ["R0_13_6R38_M", "H_OVER_R0", "FREQUENCY_HZ", "AMPLITUDE_M", "C_COULOMB_FIG45_N_PER_RAD",
    "C_VISCOUS_FIG45_N_S_PER_M_PER_RAD", "ASPECT_RATIO_DEFAULT", "unloaded_radius_m", "contact_half_angle",
    "spoke_rate", "vertical_force", "vertical_force_spokes", "damping_basis", "equivalent_damping",
    "fit_coefficients", "force_curves", "speed_curves", "frequency_curves", "amplitude_curves",
    "deflection_curves", "SPOKE_FIT_COLUMNS", "fit_tyres", "fit_tyres_each"]

#: Unloaded radius of the 13.6R38 tyre used in the thesis' model, m (§5.5.2).
R0_13_6R38_M = 0.795
#: Axle height as a fraction of r0 for a properly inflated tyre (§5.5.2).
H_OVER_R0 = 0.92
#: Thesis model excitation: 4 Hz, ±8 mm (§5.5.2).
FREQUENCY_HZ = 4.0
AMPLITUDE_M = 0.008
#: Coefficients of Fig. 45: viscous 4 × Coulomb (§5.5.2).
C_COULOMB_FIG45_N_PER_RAD = 0.25
C_VISCOUS_FIG45_N_S_PER_M_PER_RAD = 1.0
#: Section height / section width that makes 13.6R38 give r0 = 0.795 m (assumption, see
#: :func:`unloaded_radius_m`).
ASPECT_RATIO_DEFAULT = (R0_13_6R38_M - 38 * 0.0254 / 2) / (13.6 * 0.0254)

_KMH = 1.0 / KM_H_PER_M_S  # the bits of 1.0 / 3.6 (tyrelab.units)


def unloaded_radius_m(size: str, aspect_ratio: float = ASPECT_RATIO_DEFAULT) -> float:
    """Unloaded tyre radius ``R/2 + aspect · W`` in m from a size designation.

    The thesis gives r0 only for 13.6R38 (0.795 m, §5.5.2); the default aspect
    ratio (0.904) is chosen to reproduce it. An assumption for other sizes.

    Parameters
    ----------
    size : str
        E.g. ``"13.6R38"``.
    aspect_ratio : float
        Section height over section width.

    See Also
    --------
    tyrelab.tyre.sizes.parse_tyre_size : the size designation.

    Examples
    --------
    >>> round(unloaded_radius_m("13.6R38"), 3)     # the thesis' r0 (§5.5.2)
    0.795
    """
    s = parse_tyre_size(size)
    aspect_ratio = _validate.positive("aspect_ratio", aspect_ratio)
    return 0.0254 * (s.rim_diameter_in / 2.0 + aspect_ratio * s.section_width_in)


def contact_half_angle(h, r0):
    """Half-angle α = acos(h / r0) of the contact zone, rad (0 when h ≥ r0).

    See Also
    --------
    vertical_force : the spokes within ±α carry the force.

    Examples
    --------
    >>> round(float(contact_half_angle(0.92 * 0.795, 0.795)), 4), float(contact_half_angle(0.9, 0.795))
    (0.4027, 0.0)
    """
    r0 = _validate.positive("r0", r0)
    return np.arccos(np.clip(np.asarray(h, dtype=float) / r0, -1.0, 1.0))


def spoke_rate(theta, h, h_dot, wheel_rate_rad_s):
    """Rate of change of spoke length ṙ, m/s (thesis §5.5.2).

    Parameters
    ----------
    theta : array-like
        Spoke angle from the vertical, rad (increasing with time).
    h, h_dot : array-like
        Axle height (m) and its rate (m/s).
    wheel_rate_rad_s : array-like
        θ̇, rad/s.

    See Also
    --------
    vertical_force : the damping force from these rates.

    Examples
    --------
    >>> float(spoke_rate(0.0, 0.73, 0.2, 3.5))     # the vertical spoke shortens as the axle moves
    0.2
    >>> round(float(spoke_rate(0.1, 0.73, 0.0, 3.5)), 4)   # ahead of the vertical a rolling wheel lengthens it
    0.2576
    """
    _validate.non_negative_array("wheel_rate_rad_s", wheel_rate_rad_s)
    c = np.cos(theta)
    return h_dot / c + h * wheel_rate_rad_s * np.sin(theta) / c**2


def vertical_force(h, h_dot, wheel_rate_rad_s, r0, c_coulomb, c_viscous):
    """Vertical damping force on the axle from all spokes in contact, N (closed form).

    ``F = 2 c1 sin(clip(atan2(ḣ, h θ̇), −α, α)) + 2 α c2 ḣ`` with α = acos(h/r0);
    positive when opposing the axle motion (thesis §5.5.2, Fig. 43). Broadcasts.

    Parameters
    ----------
    h : array-like
        Axle height, m.
    h_dot : array-like
        Rate of change of axle height, m/s.
    wheel_rate_rad_s : array-like
        Wheel angular speed θ̇ ≥ 0, rad/s.
    r0 : float
        Unloaded spoke length, m.
    c_coulomb : float
        Coulomb friction per radian of tyre, N/rad.
    c_viscous : float
        Viscous coefficient per radian of tyre, Ns/m/rad.

    See Also
    --------
    vertical_force_spokes : the same summed over discrete spokes.
    equivalent_damping : its energy per cycle as a viscous damping.

    Examples
    --------
    A stationary wheel (θ̇ = 0) moving up: every spoke in the contact zone slides, the Coulomb
    part is ``2 c1 sin α``:

    >>> round(float(vertical_force(0.92 * 0.795, 0.1, 0.0, 0.795, 1.0, 0.0)), 4), round(float(2 * np.sin(np.arccos(0.92))), 4)
    (0.7838, 0.7838)
    >>> float(vertical_force(0.92 * 0.795, 0.0, 3.5, 0.795, 1.0, 1.0))   # no axle motion, no force
    0.0
    """
    _validate.non_negative_array("wheel_rate_rad_s", wheel_rate_rad_s)
    r0 = _validate.positive("r0", r0)
    _validate.finite_array("c_coulomb", np.atleast_1d(c_coulomb))  # negative in an unconstrained fit (spoke_fit)
    _validate.finite_array("c_viscous", np.atleast_1d(c_viscous))
    h = np.asarray(h, dtype=float)
    h_dot = np.asarray(h_dot, dtype=float)
    alpha = contact_half_angle(h, r0)
    theta0 = np.clip(np.arctan2(h_dot, h * np.asarray(wheel_rate_rad_s, dtype=float)), -alpha, alpha)
    return 2.0 * c_coulomb * np.sin(theta0) + 2.0 * alpha * c_viscous * h_dot


def vertical_force_spokes(h, h_dot, wheel_angle_rad, wheel_rate_rad_s, r0, c_coulomb, c_viscous,
                          n_spokes: int = 20):
    """Vertical damping force summed over ``n_spokes`` discrete spokes, N (thesis' method).

    Spoke ``i`` is at angle ``wheel_angle + 2π i / n`` (wrapped to (−π, π]); each
    stands for ``2π / n`` rad of tyre. Arguments broadcast like
    :func:`vertical_force`; the spoke axis is appended last and summed.

    See Also
    --------
    vertical_force : the closed form it converges to.

    Examples
    --------
    >>> closed = float(vertical_force(0.73, 0.05, 3.5, 0.795, 1.0, 1.0))
    >>> many = float(vertical_force_spokes(0.73, 0.05, 0.0, 3.5, 0.795, 1.0, 1.0, n_spokes=4000))
    >>> bool(abs(many / closed - 1) < 0.01)          # within 1 % with 4000 spokes
    True
    """
    n_spokes = _validate.positive_int("n_spokes", n_spokes)
    r0 = _validate.positive("r0", r0)
    _validate.non_negative_array("wheel_rate_rad_s", wheel_rate_rad_s)
    h = np.asarray(h, dtype=float)[..., None]
    hd = np.asarray(h_dot, dtype=float)[..., None]
    w = np.asarray(wheel_rate_rad_s, dtype=float)[..., None]
    ang = np.asarray(wheel_angle_rad, dtype=float)[..., None] + 2 * np.pi * np.arange(n_spokes) / n_spokes
    theta = (ang + np.pi) % (2 * np.pi) - np.pi
    alpha = contact_half_angle(h, r0)
    inside = np.abs(theta) < alpha
    th = np.where(inside, theta, 0.0)
    rd = spoke_rate(th, h, hd, w)
    f = c_coulomb * np.sign(rd) + c_viscous * rd
    return np.sum(np.where(inside, f * np.cos(th), 0.0), axis=-1) * (2 * np.pi / n_spokes)


def _cycle(speed_km_h, frequency_Hz, amplitude_m, h_over_r0, r0, n_time):
    """Broadcast inputs to (..., n_time) arrays of h, ḣ, θ̇ over one excitation cycle."""
    v = np.asarray(speed_km_h, dtype=float)[..., None] * _KMH
    f = np.asarray(frequency_Hz, dtype=float)[..., None]
    a = np.asarray(amplitude_m, dtype=float)[..., None]
    q = np.asarray(h_over_r0, dtype=float)[..., None]
    phase = 2 * np.pi * (np.arange(n_time) + 0.5) / n_time
    omega = 2 * np.pi * f
    h = q * r0 + a * np.sin(phase)
    h_dot = a * omega * np.cos(phase)
    return h, h_dot, v / r0, omega, a


def damping_basis(speed_km_h, frequency_Hz=FREQUENCY_HZ, amplitude_m=AMPLITUDE_M,
                  h_over_r0=H_OVER_R0, r0=R0_13_6R38_M, n_time: int = 2048):
    """Equivalent viscous damping per unit Coulomb and per unit viscous coefficient.

    Returns ``(g_coulomb, g_viscous)`` such that the equivalent damping is
    ``c1 g_coulomb + c2 g_viscous`` (Ns/m for c1 in N/rad and c2 in Ns/m/rad).
    Energy per cycle / (π A² ω), thesis §5.5.2. Arguments broadcast.

    See Also
    --------
    equivalent_damping : ``c1 g_coulomb + c2 g_viscous``.
    fit_coefficients : fits c1 and c2 on this basis.

    Examples
    --------
    >>> g1, g2 = damping_basis([1.0, 10.0])
    >>> bool(g1[0] > g1[1]), bool(np.allclose(equivalent_damping([1.0, 10.0], c_coulomb=0.25, c_viscous=1.0), 0.25 * g1 + g2))
    (True, True)
    """
    _validate.positive_array("frequency_Hz", frequency_Hz)
    _validate.positive_array("amplitude_m", amplitude_m)
    _validate.positive_array("h_over_r0", h_over_r0)
    _validate.positive("r0", r0)
    if not isinstance(n_time, (int, np.integer)) or n_time < 8:
        raise ValueError(f"n_time must be an integer >= 8, got {n_time!r}")
    if np.any(np.asarray(speed_km_h, dtype=float) < 0) or not np.all(np.isfinite(np.asarray(speed_km_h, dtype=float))):
        raise ValueError(f"speed_km_h must be finite and non-negative, got {speed_km_h!r}")
    h, h_dot, w, omega, a = _cycle(speed_km_h, frequency_Hz, amplitude_m, h_over_r0, r0, n_time)
    period = 2 * np.pi / omega
    norm = np.pi * a**2 * omega
    e1 = np.mean(vertical_force(h, h_dot, w, r0, 1.0, 0.0) * h_dot, axis=-1, keepdims=True) * period
    e2 = np.mean(vertical_force(h, h_dot, w, r0, 0.0, 1.0) * h_dot, axis=-1, keepdims=True) * period
    return (e1 / norm)[..., 0], (e2 / norm)[..., 0]


def equivalent_damping(speed_km_h, frequency_Hz=FREQUENCY_HZ, amplitude_m=AMPLITUDE_M,
                       h_over_r0=H_OVER_R0, r0=R0_13_6R38_M,
                       c_coulomb=C_COULOMB_FIG45_N_PER_RAD,
                       c_viscous=C_VISCOUS_FIG45_N_S_PER_M_PER_RAD, n_time: int = 2048):
    """Equivalent viscous damping of the spoke model, Ns/m (thesis §5.5.2, Figs 44–48).

    Parameters
    ----------
    speed_km_h : array-like
        Circumferential (rolling) speed, km/h.
    frequency_Hz : array-like
        Excitation frequency, Hz.
    amplitude_m : array-like
        Amplitude A of ``h = h0 + A sin ωt``, m (half the peak-to-peak).
    h_over_r0 : array-like
        Mean axle height as a fraction of r0 (1 − relative deflection).
    r0 : float
        Unloaded spoke length, m.
    c_coulomb, c_viscous : float
        N/rad and Ns/m/rad.

    Returns
    -------
    ndarray
        Broadcast shape of the inputs.

    See Also
    --------
    damping_basis : the same per unit coefficient.
    speed_curves : Figs 44 and 45 from it.

    Examples
    --------
    Coulomb friction damps less the faster the tyre rolls (thesis Fig. 44):

    >>> c = equivalent_damping([1.0, 5.0, 20.0], c_coulomb=1.0, c_viscous=0.0)
    >>> bool(c[0] > c[1] > c[2] > 0)
    True
    """
    _validate.finite_array("c_coulomb", np.atleast_1d(c_coulomb))  # negative in an unconstrained fit (spoke_fit)
    _validate.finite_array("c_viscous", np.atleast_1d(c_viscous))
    g1, g2 = damping_basis(speed_km_h, frequency_Hz, amplitude_m, h_over_r0, r0, n_time)
    return c_coulomb * g1 + c_viscous * g2


def fit_coefficients(speed_km_h, damping, frequency_Hz=FREQUENCY_HZ, amplitude_m=AMPLITUDE_M,
                     h_over_r0=H_OVER_R0, r0=R0_13_6R38_M, *, nonnegative: bool = True) -> dict:
    """Fit the Coulomb and viscous coefficients to damping measured at several speeds.

    The equivalent damping is linear in (c1, c2); solved by linear least squares
    (``scipy.optimize.lsq_linear``), with c ≥ 0 when ``nonnegative`` (physical
    coefficients) or unconstrained (reproduces two speeds exactly, but a negative
    coefficient has no physical meaning). Thesis §5.5.2: "determine these
    parameters by measuring tyre damping at two rolling speeds ... and fitting".

    Parameters
    ----------
    speed_km_h, damping : array-like
        Speeds (km/h) and damping (any unit; the coefficients come out in the
        same unit per Ns/m, e.g. kNs/m gives kN/rad and kNs/m/rad).
    frequency_Hz, amplitude_m, h_over_r0 : array-like
        Conditions of each measurement (broadcast).

    Returns
    -------
    dict
        ``c_coulomb, c_viscous, fitted (ndarray), relative_error (ndarray),
        max_abs_relative_error, n, status``.

    See Also
    --------
    damping_basis : the basis it fits on.
    fit_tyres : the fit per measured tyre.

    Examples
    --------
    >>> speeds = [10.0, 15.0]
    >>> damping = equivalent_damping(speeds, c_coulomb=0.3, c_viscous=0.9)
    >>> fit = fit_coefficients(speeds, damping)
    >>> round(fit["c_coulomb"], 6), round(fit["c_viscous"], 6)
    (0.3, 0.9)
    """
    _validate.finite_array("damping", damping)
    v = np.asarray(speed_km_h, dtype=float)
    y = np.asarray(damping, dtype=float)
    g1, g2 = damping_basis(v, frequency_Hz, amplitude_m, h_over_r0, r0)
    A = np.column_stack([np.broadcast_to(g1, v.shape), np.broadcast_to(g2, v.shape)])
    if len(np.unique(v)) < 2:
        nan = float("nan")
        return {"c_coulomb": nan, "c_viscous": nan, "fitted": np.full_like(y, np.nan),
                "relative_error": np.full_like(y, np.nan), "max_abs_relative_error": nan,
                "n": int(len(v)), "status": "fewer than 2 distinct speeds"}
    res = lsq_linear(A, y, bounds=(0.0, np.inf) if nonnegative else (-np.inf, np.inf), method="bvls")
    fitted = A @ res.x
    rel = (fitted - y) / y
    active = [name for name, c in zip(("c_coulomb", "c_viscous"), res.x) if c <= 0.0]
    if not active:
        status = "ok"
    elif nonnegative:
        status = f"bound active ({', '.join(active)} = 0): damping vs speed outside the model's c >= 0 shapes"
    else:
        status = f"unphysical ({', '.join(active)} <= 0): damping vs speed outside the model's c >= 0 shapes"
    return {"c_coulomb": float(res.x[0]), "c_viscous": float(res.x[1]), "fitted": fitted,
            "relative_error": rel, "max_abs_relative_error": float(np.max(np.abs(rel))),
            "n": int(len(v)), "status": status}


# --------------------------------------------------------------------------- figure data


def force_curves(speeds_km_h=(0.5, 1, 2, 5, 10, 20), c_coulomb=1.0, c_viscous=0.0,
                 h_over_r0=H_OVER_R0, r0=R0_13_6R38_M, n_points: int = 41) -> pd.DataFrame:
    """Fig. 43: damping force vs rate of change of axle height at several speeds.

    ḣ spans ±A ω of the 4 Hz, ±8 mm excitation; h = 0.92 r0; Coulomb 1 N/rad.

    Returns
    -------
    DataFrame
        ``speed_km_h, h_dot_m_per_s, force_N, c_coulomb_N_per_rad, c_viscous_N_s_per_m_per_rad``.

    See Also
    --------
    vertical_force : what it draws.

    Examples
    --------
    >>> f = force_curves(speeds_km_h=[0.5, 10.0], n_points=5)    # slower: nearer the full slide, 2 sin α
    >>> f.groupby("speed_km_h")["force_N"].max().round(3).to_dict()
    {0.5: 0.784, 10.0: 0.157}
    """
    _validate.non_negative_array("speeds_km_h", speeds_km_h)
    n_points = _validate.positive_int("n_points", n_points, minimum=2)
    r0 = _validate.positive("r0", r0)
    h_over_r0 = _validate.positive("h_over_r0", h_over_r0)
    hd = np.linspace(-1, 1, n_points) * AMPLITUDE_M * 2 * np.pi * FREQUENCY_HZ
    v = np.asarray(speeds_km_h, dtype=float)[:, None]
    f = vertical_force(h_over_r0 * r0, hd[None, :], v * _KMH / r0, r0, c_coulomb, c_viscous)
    return pd.DataFrame({
        "speed_km_h": np.repeat(v[:, 0], n_points), "h_dot_m_per_s": np.tile(hd, len(v)),
        "force_N": f.ravel(), "c_coulomb_N_per_rad": c_coulomb, "c_viscous_N_s_per_m_per_rad": c_viscous,
    })


def _curve(figure, variable, values, speeds, frequency, amplitude_m, h_over_r0, c1, c2, model, r0):
    vals = np.asarray(values, dtype=float)
    sp = np.asarray(speeds, dtype=float)
    grid = {"speed_km_h": sp[:, None] * np.ones_like(vals)[None, :]}
    f = np.full(grid["speed_km_h"].shape, float(frequency))
    a = np.full_like(f, float(amplitude_m))
    q = np.full_like(f, float(h_over_r0))
    if variable == "speed_km_h":
        grid["speed_km_h"] = np.broadcast_to(vals, f.shape).copy()
    elif variable == "frequency_Hz":
        f = np.broadcast_to(vals, f.shape).copy()
    elif variable == "amplitude_mm":
        a = np.broadcast_to(vals / 1000.0, f.shape).copy()
    elif variable == "deflection_percent":
        q = np.broadcast_to(1.0 - vals / 100.0, f.shape).copy()
    c = equivalent_damping(grid["speed_km_h"], f, a, q, r0, c1, c2)
    return pd.DataFrame({
        "figure": figure, "model": model, "speed_km_h": grid["speed_km_h"].ravel(),
        "frequency_Hz": f.ravel(), "amplitude_mm": (a * 1000).ravel(),
        "amplitude_mm_pp": (2 * a * 1000).ravel(), "deflection_percent": (100 * (1 - q)).ravel(),
        "deflection_mm": ((1 - q) * r0 * 1000).ravel(), "r0_m": r0,
        "c_coulomb_N_per_rad": c1, "c_viscous_N_s_per_m_per_rad": c2,
        "damping_N_s_per_m": c.ravel(),
    })


def speed_curves(speeds_km_h=None, r0=R0_13_6R38_M) -> pd.DataFrame:
    """Figs 44 and 45: equivalent damping vs rolling speed (4 Hz, ±8 mm, h = 0.92 r0).

    Models: ``coulomb`` (Fig. 44, c1 = 1 N/rad), ``combined`` (Fig. 45, c1 = 0.25 N/rad,
    c2 = 1 Ns/m/rad) and ``viscous`` (c2 = 1 Ns/m/rad alone, for reference).

    See Also
    --------
    equivalent_damping : the damping drawn.
    frequency_curves, amplitude_curves, deflection_curves : Figs 46–48.

    Examples
    --------
    >>> c = speed_curves([1.0, 10.0])
    >>> sorted(set(zip(c["figure"], c["model"]))), len(c)
    ([('44', 'coulomb'), ('45', 'combined'), ('45', 'viscous')], 6)
    """
    r0 = _validate.positive("r0", r0)
    if speeds_km_h is not None:
        _validate.non_negative_array("speeds_km_h", speeds_km_h)
    v = np.r_[0.1, 0.2, 0.3, 0.5, 0.75, np.arange(1.0, 20.01, 0.5)] if speeds_km_h is None else speeds_km_h
    parts = [
        _curve("44", "speed_km_h", v, [0], FREQUENCY_HZ, AMPLITUDE_M, H_OVER_R0, 1.0, 0.0, "coulomb", r0),
        _curve("45", "speed_km_h", v, [0], FREQUENCY_HZ, AMPLITUDE_M, H_OVER_R0,
               C_COULOMB_FIG45_N_PER_RAD, C_VISCOUS_FIG45_N_S_PER_M_PER_RAD, "combined", r0),
        _curve("45", "speed_km_h", v, [0], FREQUENCY_HZ, AMPLITUDE_M, H_OVER_R0, 0.0, 1.0, "viscous", r0),
    ]
    return pd.concat(parts, ignore_index=True)


_FIG_SPEEDS = (1.0, 5.0, 10.0, 15.0, 20.0)


def frequency_curves(frequencies_Hz=np.arange(1.0, 8.01, 0.25), speeds_km_h=_FIG_SPEEDS,
                     r0=R0_13_6R38_M) -> pd.DataFrame:
    """Fig. 46: equivalent damping vs excitation frequency at several speeds (Fig. 45 coefficients).

    See Also
    --------
    speed_curves : Figs 44 and 45.
    equivalent_damping : the damping drawn.

    Examples
    --------
    >>> c = frequency_curves([2.0, 4.0], speeds_km_h=[10.0])
    >>> c[["frequency_Hz", "speed_km_h"]].to_dict("records")
    [{'frequency_Hz': 2.0, 'speed_km_h': 10.0}, {'frequency_Hz': 4.0, 'speed_km_h': 10.0}]
    """
    _validate.positive_array("frequencies_Hz", frequencies_Hz)
    _validate.non_negative_array("speeds_km_h", speeds_km_h)
    r0 = _validate.positive("r0", r0)
    return _curve("46", "frequency_Hz", frequencies_Hz, speeds_km_h, FREQUENCY_HZ, AMPLITUDE_M,
                  H_OVER_R0, C_COULOMB_FIG45_N_PER_RAD, C_VISCOUS_FIG45_N_S_PER_M_PER_RAD, "combined", r0)


def amplitude_curves(amplitudes_mm=np.arange(2.0, 15.01, 0.5), speeds_km_h=_FIG_SPEEDS,
                     r0=R0_13_6R38_M) -> pd.DataFrame:
    """Fig. 47: equivalent damping vs amplitude (±2–15 mm, i.e. 4–30 mm p-p as measured).

    See Also
    --------
    speed_curves : Figs 44 and 45.
    equivalent_damping : the damping drawn.

    Examples
    --------
    >>> c = amplitude_curves([4.0, 8.0], speeds_km_h=[10.0])
    >>> c["amplitude_mm_pp"].tolist(), c["figure"].unique().tolist()
    ([8.0, 16.0], ['47'])
    """
    _validate.positive_array("amplitudes_mm", amplitudes_mm)
    _validate.non_negative_array("speeds_km_h", speeds_km_h)
    r0 = _validate.positive("r0", r0)
    return _curve("47", "amplitude_mm", amplitudes_mm, speeds_km_h, FREQUENCY_HZ, AMPLITUDE_M,
                  H_OVER_R0, C_COULOMB_FIG45_N_PER_RAD, C_VISCOUS_FIG45_N_S_PER_M_PER_RAD, "combined", r0)


def deflection_curves(deflection_percent=np.arange(2.0, 15.01, 0.5), speeds_km_h=_FIG_SPEEDS,
                      r0=R0_13_6R38_M) -> pd.DataFrame:
    """Fig. 48: equivalent damping vs tyre deflection (1 − h/r0, %); 8 % is the thesis' h = 0.92 r0.

    See Also
    --------
    speed_curves : Figs 44 and 45.
    equivalent_damping : the damping drawn.

    Examples
    --------
    >>> c = deflection_curves([8.0], speeds_km_h=[10.0])
    >>> round(float(c["deflection_mm"].iloc[0]), 1), c["figure"].iloc[0]     # 8 % of r0 = 0.795 m
    (63.6, '48')
    """
    d = _validate.positive_array("deflection_percent", deflection_percent)
    if np.any(d >= 100):
        raise ValueError(f"deflection_percent must be below 100, got {d.max():g}")
    _validate.non_negative_array("speeds_km_h", speeds_km_h)
    r0 = _validate.positive("r0", r0)
    return _curve("48", "deflection_percent", deflection_percent, speeds_km_h, FREQUENCY_HZ,
                  AMPLITUDE_M, H_OVER_R0, C_COULOMB_FIG45_N_PER_RAD, C_VISCOUS_FIG45_N_S_PER_M_PER_RAD,
                  "combined", r0)


# --------------------------------------------------------------------------- per-tyre fits

SPOKE_FIT_COLUMNS = [
    "tyre_id", "size", "r0_m", "h_over_r0", "pressure_bar", "load_kN", "n_runs", "n_speeds",
    "speeds_km_h", "frequency_Hz", "amplitude_mm_pp", "c_coulomb_kN_per_rad",
    "c_viscous_kN_s_per_m_per_rad", "viscous_to_coulomb_ratio_s_per_m", "max_abs_error_percent",
    "physical", "c_coulomb_nonneg_kN_per_rad", "c_viscous_nonneg_kN_s_per_m_per_rad",
    "max_abs_error_nonneg_percent", "status", "note",
]


def fit_tyres(results: pd.DataFrame, tyres: pd.DataFrame | None = None, *,
              min_speed_km_h: float = 10.0, h_over_r0: float = H_OVER_R0) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Fit spoke coefficients per tyre from measured damping vs rolling speed.

    Fitting speeds: nominal runs (:mod:`tyrelab.tyre.conditions`) at speed ≥
    ``min_speed_km_h`` (default 10 km/h: the Table VII speeds; the thesis
    suggests fitting "at two rolling speeds", and the model cannot describe the
    rise of damping below 0.6 km/h). Pressure and load held at one level (most
    distinct speeds; nearest 1.38 bar). Damping averaged per speed, with the
    mean measured frequency and amplitude. r0 from the size
    (:func:`unloaded_radius_m`), h = ``h_over_r0`` r0. Thesis §5.5.2.

    The main coefficients are the unconstrained linear least-squares solution
    (exact at two speeds); ``physical`` says whether both are ≥ 0, and the
    ``*_nonneg_*`` columns give the best physical (c ≥ 0) fit with its error.
    ``points`` also evaluates the fit at the lower rolling speeds of the same
    pressure and load (``used_in_fit`` false): an out-of-sample check.

    Parameters
    ----------
    results : DataFrame
        The ``results`` table.
    tyres : DataFrame, optional
        ``tyres`` table (tyre_id, size); without a size, r0 = 0.795 m.

    Returns
    -------
    fits : DataFrame
        One row per tyre with measurement runs (:data:`SPOKE_FIT_COLUMNS`).
    points : DataFrame
        Per tyre and speed: measured and fitted damping (kNs/m) and error.

    See Also
    --------
    fit_tyres_each : the same per tyre in one pass.
    fit_coefficients : the fit of one tyre.
    unloaded_radius_m : r0 from the size.

    Examples
    --------
    >>> speeds = np.array([10.0, 15.0, 20.0])
    >>> kNs = equivalent_damping(speeds, c_coulomb=300.0, c_viscous=900.0) / 1000   # a spoke tyre, kNs/m
    >>> results = pd.DataFrame({"tyre_id": "T1", "kind": "measurement", "qc_ok": True, "surface": "concrete",
    ...                         "excitation_frequency_Hz": 4.0, "amplitude_mm_pp": 16.0, "pressure_bar": 1.38,
    ...                         "load_kN": 18.3, "speed_km_h": speeds, "damping_kN_s_per_m": kNs})
    >>> fits, points = fit_tyres(results, pd.DataFrame({"tyre_id": ["T1"], "size": ["13.6R38"]}))
    >>> fits[["n_speeds", "c_coulomb_kN_per_rad", "c_viscous_kN_s_per_m_per_rad", "physical"]].round(4).to_dict("records")
    [{'n_speeds': 3, 'c_coulomb_kN_per_rad': 0.3, 'c_viscous_kN_s_per_m_per_rad': 0.9, 'physical': True}]
    """
    _validate.frame("results", results)
    min_speed_km_h = _validate.positive("min_speed_km_h", min_speed_km_h)
    h_over_r0 = _validate.positive("h_over_r0", h_over_r0)
    items = list(_fit_items(results, tyres, None, min_speed_km_h, h_over_r0))
    return _fit_frames([row for _, row, _ in items], [p for _, _, p in items if p is not None])


def fit_tyres_each(results: pd.DataFrame, tyres: pd.DataFrame | None = None, *, tyre_ids: list[str],
                   min_speed_km_h: float = 10.0,
                   h_over_r0: float = H_OVER_R0) -> dict[str, tuple[pd.DataFrame, pd.DataFrame]]:
    """:func:`fit_tyres` of each tyre on its own, all tyres in one pass.

    ``out[tyre]`` equals ``fit_tyres(<results rows of tyre>, <tyres row of tyre>)``: the
    nominal runs are selected once.

    See Also
    --------
    fit_tyres : one tyre's (or every tyre's) fit.

    Examples
    --------
    >>> fits, points = fit_tyres_each(pd.DataFrame(), tyre_ids=["T1"])["T1"]
    >>> len(fits), len(points)
    (0, 0)
    """
    _validate.frame("results", results)
    min_speed_km_h = _validate.positive("min_speed_km_h", min_speed_km_h)
    h_over_r0 = _validate.positive("h_over_r0", h_over_r0)
    tyre_ids = [str(t) for t in tyre_ids]
    out = {t: _fit_frames([], []) for t in tyre_ids}  # a tyre without rows: no fit, as fit_tyres
    for tid, row, pts in _fit_items(results, tyres, set(tyre_ids), min_speed_km_h, h_over_r0):
        out[tid] = _fit_frames([row], [] if pts is None else [pts])
    return out


_POINTS_COLUMNS = ["tyre_id", "speed_km_h", "used_in_fit", "frequency_Hz", "amplitude_mm_pp", "damping_kN_s_per_m",
                   "fitted_damping_kN_s_per_m", "error_percent", "fitted_nonneg_damping_kN_s_per_m",
                   "error_nonneg_percent"]


def _fit_frames(fits: list[dict], points: list[pd.DataFrame]) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The two tables of :func:`fit_tyres` from the tyres' rows and point tables."""
    pts = pd.concat(points, ignore_index=True) if points else pd.DataFrame(columns=_POINTS_COLUMNS)
    return pd.DataFrame(fits, columns=SPOKE_FIT_COLUMNS), pts


def _fit_items(results, tyres, only, min_speed_km_h, h_over_r0):
    """``(tyre_id, fit row, points or None)`` per tyre of ``results`` (of ``only`` if given), sorted."""
    results = cond.with_columns(results)
    sizes = {}
    if tyres is not None and not tyres.empty and "size" in tyres and "tyre_id" in tyres:
        sizes = dict(zip(tyres["tyre_id"].astype(str), tyres["size"]))
    ids = sorted(results["tyre_id"].dropna().astype(str).unique()) if not results.empty else []
    if only is not None:
        ids = [t for t in ids if t in only]
    runs = results.loc[cond.nominal(results)].copy() if not results.empty else results
    if not runs.empty:
        runs["tyre_id"] = runs["tyre_id"].astype(str)
        runs["x"] = pd.to_numeric(runs["speed_km_h"], errors="coerce").round(cond.SPEED_DECIMALS)
        runs = runs.loc[(runs["x"] > 0) & runs["damping_kN_s_per_m"].notna()]
    for tid in ids:
        size = sizes.get(tid)
        note = []
        try:
            r0 = unloaded_radius_m(size) if isinstance(size, str) else R0_13_6R38_M
        except ValueError:
            r0 = R0_13_6R38_M
            note.append(f"size {size!r} unparsed: r0 = 0.795 m")
        if not isinstance(size, str):
            note.append("no size: r0 = 0.795 m")
        sub = runs.loc[runs["tyre_id"] == tid] if not runs.empty else runs
        fast = sub.loc[sub["x"] >= min_speed_km_h] if len(sub) else sub
        fast, levels, hold_note = cond.hold_constant(fast, "x", ["pressure_bar", "load_kN"],
                                                     prefer={"pressure_bar": cond.STANDARD_PRESSURE_BAR})
        if len(sub) and not hold_note:
            for c in ("pressure_bar", "load_kN"):
                if levels.get(c) is not None:
                    d = cond.PRESSURE_DECIMALS if c == "pressure_bar" else cond.LOAD_DECIMALS
                    sub = sub.loc[pd.to_numeric(sub[c], errors="coerce").round(d) == levels[c]]
        else:
            sub = fast
        if hold_note:
            note.append(hold_note)
        row = dict.fromkeys(SPOKE_FIT_COLUMNS, None)
        row.update(tyre_id=tid, size=size, r0_m=r0, h_over_r0=h_over_r0,
                   pressure_bar=levels.get("pressure_bar"), load_kN=levels.get("load_kN"),
                   n_runs=int(len(fast)))
        if fast.empty:
            row.update(n_speeds=0, status=f"no nominal runs at >= {min_speed_km_h:g} km/h")
            row["note"] = "; ".join(note) or None
            yield tid, row, None
            continue
        freq = cond.regressor(sub, "frequency").fillna(cond.NOMINAL_FREQUENCY_HZ)
        amp = cond.regressor(sub, "amplitude").fillna(14.0)
        g_all = pd.DataFrame({"speed_km_h": sub["x"], "damping": sub["damping_kN_s_per_m"],
                              "f": freq, "a": amp}).groupby("speed_km_h").mean().reset_index()
        g = g_all.loc[g_all["speed_km_h"] >= min_speed_km_h].reset_index(drop=True)
        fit = fit_coefficients(g["speed_km_h"], g["damping"], g["f"], g["a"] / 2000.0, h_over_r0, r0,
                               nonnegative=False)
        phys = fit_coefficients(g["speed_km_h"], g["damping"], g["f"], g["a"] / 2000.0, h_over_r0, r0)
        row.update(
            n_speeds=int(len(g)), speeds_km_h=",".join(f"{v:g}" for v in g["speed_km_h"]),
            frequency_Hz=float(g["f"].mean()), amplitude_mm_pp=float(g["a"].mean()),
            c_coulomb_kN_per_rad=fit["c_coulomb"], c_viscous_kN_s_per_m_per_rad=fit["c_viscous"],
            viscous_to_coulomb_ratio_s_per_m=(fit["c_viscous"] / fit["c_coulomb"]
                                              if fit["c_coulomb"] and np.isfinite(fit["c_coulomb"]) else None),
            max_abs_error_percent=100 * fit["max_abs_relative_error"],
            physical=bool(fit["c_coulomb"] >= 0 and fit["c_viscous"] >= 0) if fit["status"] != "fewer than 2 distinct speeds" else None,
            c_coulomb_nonneg_kN_per_rad=phys["c_coulomb"], c_viscous_nonneg_kN_s_per_m_per_rad=phys["c_viscous"],
            max_abs_error_nonneg_percent=100 * phys["max_abs_relative_error"],
            status=fit["status"], note="; ".join(note) or None,
        )
        if np.isfinite(fit["c_coulomb"]):
            pred = equivalent_damping(g_all["speed_km_h"], g_all["f"], g_all["a"] / 2000.0, h_over_r0, r0,
                                      fit["c_coulomb"], fit["c_viscous"])
            pred_phys = equivalent_damping(g_all["speed_km_h"], g_all["f"], g_all["a"] / 2000.0, h_over_r0, r0,
                                           phys["c_coulomb"], phys["c_viscous"])
        else:
            pred = pred_phys = np.full(len(g_all), np.nan)
        yield tid, row, pd.DataFrame({
            "tyre_id": tid, "speed_km_h": g_all["speed_km_h"], "used_in_fit": g_all["speed_km_h"] >= min_speed_km_h,
            "frequency_Hz": g_all["f"], "amplitude_mm_pp": g_all["a"], "damping_kN_s_per_m": g_all["damping"],
            "fitted_damping_kN_s_per_m": pred, "error_percent": 100 * (pred / g_all["damping"] - 1),
            "fitted_nonneg_damping_kN_s_per_m": pred_phys,
            "error_nonneg_percent": 100 * (pred_phys / g_all["damping"] - 1),
        })
