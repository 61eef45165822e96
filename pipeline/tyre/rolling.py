"""A rolling tyre's series damper ``c₂ = a / v`` and its stand-in where none is measured (issue 42).

A rolling tyre, laterally and longitudinally, is a Kelvin–Voigt unit (``k``, ``c`` in parallel) in
series with a damper inversely proportional to the rolling speed (thesis §2.5; Lines 1987; Crolla,
Horton & Stayner 1990): ``c₂ = a / v``, ``a`` in kN s/m × km/h, ``v`` in km/h. It is the single-point
slip model: the damper acts on the contact point's velocity over the ground, ``c₂ = C_α / V``
(``C_α`` the cornering stiffness, N/rad, ``V`` in m/s; relaxation length ``σ = C_α / k``; Pacejka,
*Tyre and Vehicle Dynamics*, ch. 7), so ``a = 3.6 C_α`` with ``C_α`` in kN/rad. A stationary tyre
(0 km/h) has no series damper (it is locked: the Kelvin–Voigt unit alone).

The stand-in for ``a`` where neither the scenario, the build nor the catalogue gives one
-----------------------------------------------------------------------------------------
:data:`SERIES_DAMPING_KN_S_PER_M_KM_H` ``["lateral"] = 100`` kN s/m·km/h per tyre, 95 % interval
×/÷ 2 (50–200; :data:`SERIES_DAMPING_95`). Where it comes from:

* the rig: the lateral runs of tyre T1 (13.6R38) give ``a ≈ 99`` (the build's
  ``series_damping_speed``; the rig's virtual test vehicle, :mod:`tyrelab.rig.method_runs`), i.e.
  ``C_α ≈ 28`` kN/rad, ``σ = C_α / k_y ≈ 0.10`` m at its 277 kN/m;
* the thesis' measured damping (§2.4.3: the lateral mode's damping rises from about 20 % to about
  100 % of critical between 0 and 11 km/h). With this element, the lateral-stiffness stand-in
  (:mod:`tyrelab.tyre.lateral`) and the tyres' vertical damping as the unit's ``c``, the lateral–roll
  mode of both shipped tractors made 3-D (``mf698t``, ``modern_tractor``; rigid and pivoting front
  axles) is damped 20–100 % of critical at 6–11 km/h for every ``a`` from 87 to 159 kN s/m·km/h
  (the lowest ``a`` that still leaves it oscillating at 11 km/h, the highest that damps it 20 % at
  6 km/h, over the four tractors): computed with the independent reference model
  ``tests/vehicle/reference_lateral.py`` (``test_reference_rolling.py`` checks it). At ``a = 100``:
  32–41 % at 6 km/h, 66–83 % at 11 km/h.

The interval ×/÷ 2 holds that range and the rig's value with room; the relaxation length of a
road-going off-road tyre (Chrono's HMMWV TMeasy set: ``dF_y/ds_y`` 50.9 kN at 8.6 kN load over
164 kN/m, ``σ ≈ 0.31`` m) would give ``a ≈ 220`` at ``k_y = 200`` kN/m, at the interval's upper edge.
Longitudinal: 140 kN s/m·km/h, the rig's longitudinal runs (no thesis damping range to check it
against: flagged as the weaker stand-in), the same ×/÷ 2.

Examples
--------
>>> series_damping_N_s_per_m(100.0, 8.0)
12500.0
>>> series_damping_N_s_per_m(100.0, 0.0)
inf
>>> e = estimate_series_damping("lateral")
>>> e["series_damping_kN_s_per_m_km_h"], e["ci95_kN_s_per_m_km_h"]
(100.0, [50.0, 200.0])
"""

from __future__ import annotations

import math

from .. import _validate

__all__ = ["DIRECTIONS", "SERIES_DAMPING_KN_S_PER_M_KM_H", "FACTOR_95", "SERIES_DAMPING_95", "SOURCE",
           "series_damping_N_s_per_m", "estimate_series_damping"]

#: Directions with a series damper.
DIRECTIONS = ("lateral", "longitudinal")
#: The stand-in ``a`` per tyre, kN s/m × km/h (module docstring).
SERIES_DAMPING_KN_S_PER_M_KM_H = {"lateral": 100.0, "longitudinal": 140.0}
#: The 95 % interval's factor: ×/÷ 2.
FACTOR_95 = 2.0
#: The stand-in's 95 % interval per direction, kN s/m × km/h.
SERIES_DAMPING_95 = {d: (a / FACTOR_95, a * FACTOR_95) for d, a in SERIES_DAMPING_KN_S_PER_M_KM_H.items()}
#: Where each stand-in comes from (one line, for tables).
SOURCE = {
    "lateral": ("stand-in a = 100 kN s/m·km/h (rig T1 ≈ 99; keeps the lateral–roll mode 20–100 % damped at "
                "6–11 km/h as thesis §2.4.3 measured, for a = 87–159; 95 % interval x/÷ 2)"),
    "longitudinal": ("stand-in a = 140 kN s/m·km/h (the rig's longitudinal runs; no thesis damping range to "
                     "check it; 95 % interval x/÷ 2)"),
}


def series_damping_N_s_per_m(a_kN_s_per_m_km_h: float, speed_km_h: float) -> float:
    """The series damper ``c₂ = a / v`` at ``speed_km_h``, N s/m (``inf`` at 0 km/h: locked).

    Parameters
    ----------
    a_kN_s_per_m_km_h : float
        ``a``, kN s/m × km/h (> 0).
    speed_km_h : float
        Rolling speed, km/h (>= 0).

    See Also
    --------
    estimate_series_damping : a stand-in ``a``.

    Examples
    --------
    >>> series_damping_N_s_per_m(100.0, 10.0), series_damping_N_s_per_m(100.0, 0.0)   # a = 100 kN s/m · km/h
    (10000.0, inf)
    """
    a = _validate.positive("a_kN_s_per_m_km_h", a_kN_s_per_m_km_h)
    v = _validate.non_negative("speed_km_h", speed_km_h)
    return math.inf if v == 0 else a * 1e3 / v


def estimate_series_damping(direction: str = "lateral") -> dict:
    """The stand-in ``a`` of ``direction`` (module docstring).

    Returns
    -------
    dict
        ``series_damping_kN_s_per_m_km_h``, ``ci95_kN_s_per_m_km_h`` ([low, high]), ``source``.

    See Also
    --------
    series_damping_N_s_per_m : ``c₂`` at a speed from ``a``.

    Examples
    --------
    >>> a = estimate_series_damping("lateral")
    >>> a["series_damping_kN_s_per_m_km_h"], a["ci95_kN_s_per_m_km_h"]
    (100.0, [50.0, 200.0])
    """
    _validate.choice("direction", direction, DIRECTIONS)
    return {"series_damping_kN_s_per_m_km_h": SERIES_DAMPING_KN_S_PER_M_KM_H[direction],
            "ci95_kN_s_per_m_km_h": list(SERIES_DAMPING_95[direction]), "source": SOURCE[direction]}
