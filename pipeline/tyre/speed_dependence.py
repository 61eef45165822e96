"""A measured tyre's stiffness or damping at any speed from its per-speed fits (thesis §4.3.2, §4.5.1; issue 27).

The per-speed pressure fits (``stiffness_pressure_by_speed``, ``damping_pressure_by_speed``)
give a tyre's value at the speeds it was measured, stationary (0 km/h) included. Between
the stationary value and the first rolling speed a straight line is wrong: the thesis
finds "a 25 % decrease in carcass stiffness between the speeds of 0 and 1 km/h" (§4.5.1,
Fig. 21: "at very low rolling speeds the tyre stiffness decreases rapidly", §4.3.2), so
the fall happens as soon as the tyre rolls. A rolling tyre therefore takes the rolling
values only: below the lowest measured rolling speed the value *at* that speed (held),
between rolling speeds linear interpolation, above the highest held (§4.3.2: "between
10 km/h and 50 km/h the tyre stiffness remains almost constant"). The stationary value
is used at 0 km/h only, and where no rolling speed was measured.
"""

from __future__ import annotations

import numpy as np

from .. import _validate

__all__ = ["at_speeds"]


def at_speeds(speeds_km_h, values, query_km_h) -> np.ndarray:
    """Values of a measured tyre at ``query_km_h`` from its per-speed values (module docstring).

    Parameters
    ----------
    speeds_km_h : array-like
        Measured speeds, km/h (0 = stationary), any order.
    values : array-like
        The tyre's value at each measured speed (e.g. ``K_c + ΔK_p P`` in kN/m).
    query_km_h : array-like
        Speeds wanted, km/h (>= 0).

    Returns
    -------
    ndarray
        One value per query speed.

    See Also
    --------
    tyrelab.tyre.directional.rolling_coefficients : a tyre's coefficients per speed.

    Examples
    --------
    >>> at_speeds([0, 10, 15], [545.0, 345.0, 335.0], [0, 2, 4, 10, 12.5, 30]).tolist()
    [545.0, 345.0, 345.0, 345.0, 340.0, 335.0]
    """
    v = _validate.finite_array("speeds_km_h", np.atleast_1d(np.asarray(speeds_km_h, float)))
    y = _validate.finite_array("values", np.atleast_1d(np.asarray(values, float)))
    _validate.same_last_axis(speeds_km_h=v, values=y)
    q = np.atleast_1d(np.asarray(query_km_h, float))
    if not (np.isfinite(q).all() and (q >= 0).all()):
        raise ValueError(f"query_km_h must be finite and non-negative, got {q.tolist()}")
    if (v < 0).any():
        raise ValueError(f"speeds_km_h must be non-negative, got {v.tolist()}")
    rolling = v > 0
    if not rolling.any():
        return np.full(q.shape, float(y[np.argmin(v)]))
    order = np.argsort(v[rolling], kind="stable")
    out = np.interp(q, v[rolling][order], y[rolling][order])
    stationary = ~rolling
    if stationary.any():
        out = np.where(q == 0, float(y[stationary][0]), out)
    return out
