"""The ground under a wheel in time: a profile run over at a speed, elevation and rate per sample.

The profile is interpolated with a cubic spline (thesis §6.3), so the elevation ``u`` and its rate
``u' = v dh/dx`` are smooth; :func:`half_step_input` samples them at ``dt/2``, the input of the
vehicles' RK4 (whose stages read the half steps) and of the exact path. Used by the ride (every
wheel of a scenario) and the thesis' studies (the carriage of ch. 6, the tractor of ch. 7); moved
here from :mod:`tyrelab.vehicle.carriage` by issue 45 (both names still importable from there).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import interpolate

from ..._validate import positive

__all__ = ["ground_input", "half_step_input"]


def ground_input(
    x_m, elevation_m, speed_m_s: float, dt_s: float, x_start_m: float, x_end_m: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Time histories of ground elevation and its rate under a wheel at constant speed.

    The profile is interpolated with a cubic spline (thesis §6.3), so ``u`` and
    ``u' = v dh/dx`` are smooth between survey points.

    Parameters
    ----------
    x_m, elevation_m : array_like
        Profile, m.
    speed_m_s : float
        Rolling speed v, m/s.
    dt_s : float
        Time step, s.
    x_start_m, x_end_m : float
        Stretch of profile travelled, m.

    Returns
    -------
    t_s, u_m, u_dot_m_s : ndarray

    See Also
    --------
    half_step_input : the input at half steps for RK4.

    Examples
    --------
    >>> x = np.linspace(0.0, 10.0, 101); h = 0.01 * x                 # a 1 % slope
    >>> t, u, du = ground_input(x, h, speed_m_s=2.0, dt_s=0.1, x_start_m=0.0, x_end_m=4.0)
    >>> round(float(t[-1]), 6), round(float(u[-1]), 6), round(float(du[5]), 6)     # 2 s; 40 mm up; 0.02 m/s
    (2.0, 0.04, 0.02)
    """
    speed_m_s, dt_s = positive("speed_m_s", speed_m_s), positive("dt_s", dt_s)
    if not float(x_end_m) > float(x_start_m):
        raise ValueError(f"x_end_m must lie beyond x_start_m, got {x_start_m!r} to {x_end_m!r}")
    spline = interpolate.CubicSpline(np.asarray(x_m, float), np.asarray(elevation_m, float))
    n = int(math.floor((x_end_m - x_start_m) / (speed_m_s * dt_s))) + 1
    t = np.arange(n) * dt_s
    x = x_start_m + speed_m_s * t
    return t, spline(x), speed_m_s * spline(x, 1)


def half_step_input(x_m, elevation_m, speed_m_s: float, n_steps: int, x_start_m: float = 0.0,
                    dt_s: float = 1e-3, half_steps: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Ground elevation and rate under a wheel at ``dt/2`` over ``n_steps`` steps of ``dt``
    (:func:`ground_input`; the profile continued level beyond its end): the input of the
    vehicles' RK4, whose stages read the half steps.

    With ``half_steps=False`` only the full steps (``t = k dt``), the same numbers as every other
    sample of the half-step input, at half the cost (the exact linear path reads no more).

    Returns
    -------
    u_m, u_dot_m_s : ndarray, shape (2 n_steps - 1,) (``n_steps`` without half steps)

    See Also
    --------
    ground_input : the input at whole steps.

    Examples
    --------
    >>> u, ud = half_step_input([0.0, 1.0, 2.0, 3.0], [0.0, 0.0, 0.0, 0.0], 1.0, 3)
    >>> u.shape, float(abs(u).max())
    ((5,), 0.0)
    >>> full, _ = half_step_input([0.0, 1.0, 2.0, 3.0], [0.0, 1.0, 0.0, 1.0], 1.0, 3, dt_s=0.5, half_steps=False)
    >>> bool(np.array_equal(full, half_step_input([0.0, 1.0, 2.0, 3.0], [0.0, 1.0, 0.0, 1.0], 1.0, 3, dt_s=0.5)[0][::2]))
    True
    """
    dt_s = positive("dt_s", dt_s)
    speed_m_s = positive("speed_m_s", speed_m_s)
    dt = dt_s / 2
    t_end = (2 * n_steps - 2) * dt
    x_end = x_start_m + speed_m_s * t_end
    xx = np.asarray(x_m, float)
    hh = np.asarray(elevation_m, float)
    if x_end > xx[-1]:
        extra = np.arange(xx[-1] + (xx[1] - xx[0]), x_end + 1.0, xx[1] - xx[0])
        xx = np.concatenate([xx, extra])
        hh = np.concatenate([hh, np.full(extra.size, hh[-1])])
    if not half_steps:  # t = (2k) dt/2 = k dt exactly: the even samples of the half-step input
        spline = interpolate.CubicSpline(xx, hh)
        x = x_start_m + speed_m_s * (np.arange(n_steps) * dt_s)
        return spline(x), speed_m_s * spline(x, 1)
    _, u, ud = ground_input(xx, hh, speed_m_s, dt, x_start_m, x_start_m + speed_m_s * t_end + 1e-9)
    return u[: 2 * n_steps - 1], ud[: 2 * n_steps - 1]
