"""The units of the vehicle model: :mod:`tyrelab.units` under its earlier name (issues 35, 45).

Kilo, km/h and standard gravity moved to :mod:`tyrelab.units`, below every package of tyrelab, so
that the raw format, the rig and the measurement methods take them from the one home the vehicle
model uses; every name importable from here before still is, and is the same object.

Examples
--------
>>> from tyrelab import units as package_units
>>> km_h_to_m_s is package_units.km_h_to_m_s and STANDARD_GRAVITY_M_S2 == 9.80665
True
"""

from __future__ import annotations

from ..units import (  # noqa: F401  (re-exported: the names of issue 35)
    KILO,
    KM_H_PER_M_S,
    STANDARD_GRAVITY_M_S2,
    from_kilo,
    km_h_to_m_s,
    to_kilo,
)

__all__ = ["KILO", "from_kilo", "to_kilo", "KM_H_PER_M_S", "km_h_to_m_s", "STANDARD_GRAVITY_M_S2"]
