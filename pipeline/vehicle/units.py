"""The one unit conversion of the vehicle model: kilo (issue 35).

The model is SI inside (N/m, N s/m, N m/rad, per tyre or per element). The thesis' tables,
the scenario file's keys and the tyre formula give stiffness and damping in kN/m, kN s/m and
kN m/rad. Their values become SI where they are read — :mod:`tyrelab.vehicle.scenario` (a
scenario's parts), :mod:`tyrelab.vehicle.published_layouts` (the thesis' tables),
:class:`tyrelab.vehicle.ride.AxleTyres` (a tyre's looked-up numbers) — and go back to kN where
they are written out (tables, JSON), with these two functions; no other module of
``tyrelab.vehicle`` writes a factor of 1e3 (``tests/vehicle/test_units_tree.py`` checks it).
"""

from __future__ import annotations

__all__ = ["KILO", "from_kilo", "to_kilo"]

#: kN -> N (and kN s/m -> N s/m, kN m/rad -> N m/rad).
KILO = 1e3


def from_kilo(value):
    """A value in kN/m, kN s/m or kN m/rad (scalar or array) in N/m, N s/m or N m/rad.

    Examples
    --------
    >>> from_kilo(455.0)
    455000.0
    """
    return KILO * value


def to_kilo(value):
    """:func:`from_kilo` back: SI to kN/m, kN s/m or kN m/rad.

    Examples
    --------
    >>> to_kilo(455000.0)
    455.0
    """
    return value / KILO
