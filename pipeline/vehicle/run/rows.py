"""One speed row of a ride, time or spectral (issue 45): :class:`SpeedRow`, and the exposure it carries.

A row is one speed of one variant. Its fields are the ``speeds`` columns of ``tyrelab ride``'s JSON
and of the ``ride_results`` table, in their order; a time row (``method = "time"``) has no
:data:`SPECTRAL_ONLY` fields, a spectral row (:mod:`tyrelab.vehicle.spectral_ride`) has them and
leaves a record's properties (VDV, MTVV, crest factor, lift-off fractions) None.

:func:`exposure` is the Directive's daily exposure of a row from its weighted r.m.s. values, with
the one verdict rule, hours-to-value rule and vector sum of :mod:`tyrelab.vehicle.daily_exposure`
and :mod:`tyrelab.vehicle.iso2631`.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from ..._validate import positive
from .. import daily_exposure as de
from .. import iso2631

__all__ = ["SpeedRow", "SPECTRAL_ONLY", "VERDICTS", "exposure"]

#: Verdicts against the Directive's daily values (A(8) at hours_per_day).
VERDICTS = tuple(de.EXPOSURE_VERDICTS)
#: Fields of a spectral row only.
SPECTRAL_ONLY = ("evdv_m_s1_75", "evdv_daily_m_s1_75", "front_tyre_force_sd_N", "rear_tyre_force_sd_N",
                 "lift_off_probability_front", "lift_off_probability_rear")


@dataclass
class SpeedRow:
    """One speed of one variant: the ``speeds`` row of ``tyrelab ride`` (:meth:`as_dict`).

    Every field is in the unit its name says; None where the row's method has no such number
    (a spectral row's VDV, MTVV, crest factor and lift-off fractions).
    """

    speed_km_h: float
    front_pressure_bar: float
    rear_pressure_bar: float
    front_stiffness_kN_per_m: float
    rear_stiffness_kN_per_m: float
    front_damping_kN_s_per_m: float
    rear_damping_kN_s_per_m: float
    a_wz_m_s2: float
    a_wx_m_s2: float
    a_wy_m_s2: float
    expected_a_wz_m_s2: float
    expected_a_wx_m_s2: float
    expected_a_wy_m_s2: float
    vdv_m_s1_75: float | None
    vdv_daily_m_s1_75: float | None
    evdv_m_s1_75: float | None
    evdv_daily_m_s1_75: float | None
    crest_factor: float | None
    mtvv_m_s2: float | None
    lift_off_fraction_front: float | None
    lift_off_fraction_rear: float | None
    front_tyre_force_sd_N: float | None
    rear_tyre_force_sd_N: float | None
    lift_off_probability_front: float | None
    lift_off_probability_rear: float | None
    a_v_m_s2: float
    a8_m_s2: float
    a8_axis: str | None
    hours_to_eav: float
    hours_to_elv: float
    verdict: str
    hours_per_day: float
    duration_s: float
    simulation: str
    method: str

    def as_dict(self) -> dict:
        """The row as the JSON's and the table's columns, in order (a time row without
        :data:`SPECTRAL_ONLY`)."""
        skip = SPECTRAL_ONLY if self.method == "time" else ()
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.name not in skip}


def tyre_columns(tyres: dict, i: int) -> dict:
    """The tyre columns of a speed row (time and spectral rows alike): each axle's pressure (bar),
    and its stiffness (kN/m) and damping (kN s/m) at speed index ``i``."""
    return {f"{axle}_{q}": v for q in ("pressure_bar", "stiffness_kN_per_m", "damping_kN_s_per_m")
            for axle in ("front", "rear")
            for v in [tyres[axle].pressure_bar if q == "pressure_bar" else float(getattr(tyres[axle], q)[i])]}


def exposure(a_wz_m_s2: float, a_wx_m_s2: float, hours_per_day: float, a_wy_m_s2: float = 0.0) -> dict:
    """Daily exposure by EU Directive 2002/44/EC from per-axis weighted r.m.s. values.

    ``A(8) = max(1.4 a_wx, 1.4 a_wy, a_wz) sqrt(T / 8 h)``; hours to reach the action
    (0.5 m/s²) and limit (1.15 m/s²) values ``8 h (value / a_w)²`` with
    ``a_w = max(1.4 a_wx, 1.4 a_wy, a_wz)``; ``a_v`` the ISO 2631-1 vector sum
    (:func:`tyrelab.vehicle.iso2631.vector_sum`); ``a8_axis`` the axis of that maximum
    (:func:`tyrelab.vehicle.daily_exposure.governing_axis`); the verdict
    :func:`tyrelab.vehicle.daily_exposure.verdict`.

    See Also
    --------
    tyrelab.vehicle.daily_exposure.daily_exposure : the same from recorded tasks of a day.

    Examples
    --------
    >>> e = exposure(0.8, 0.2, 4.0)
    >>> round(e["a8_m_s2"], 6), round(e["hours_to_elv"], 4), e["verdict"], e["a8_axis"]
    (0.565685, 16.5312, 'above action value', 'z')
    >>> exposure(0.5, 0.4, 8.0)["a8_axis"]  # 1.4 x 0.4 = 0.56 > 0.5
    'x'
    """
    positive("hours_per_day", hours_per_day)
    k = iso2631.AXIS_FACTOR
    weighted = {"x": k["x"] * a_wx_m_s2, "y": k["y"] * a_wy_m_s2, "z": k["z"] * a_wz_m_s2}
    axis = de.governing_axis(weighted)
    aw = max(weighted.values())
    a8 = iso2631.daily_exposure_a8(aw, hours_per_day)
    return {
        "a_v_m_s2": iso2631.vector_sum(a_wx_m_s2, a_wy_m_s2, a_wz_m_s2),
        "a8_m_s2": a8,
        "a8_axis": axis,
        "hours_to_eav": de.hours_to(iso2631.EU_ACTION_A8_M_S2, aw, 8.0),
        "hours_to_elv": de.hours_to(iso2631.EU_LIMIT_A8_M_S2, aw, 8.0),
        "verdict": de.verdict(a8),
    }
