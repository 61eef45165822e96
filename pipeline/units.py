"""The units of tyrelab, each written once: kilo, km/h and standard gravity (issues 35, 45).

The model and the estimators are SI inside (N/m, N s/m, N m/rad, m/s, m/s²). The thesis' tables,
the scenario file's keys and the tyre formula give stiffness and damping in kN/m, kN s/m and
kN m/rad. Their values become SI where they are read — :mod:`tyrelab.vehicle.scenario` (a
scenario's parts), :mod:`tyrelab.vehicle.studies.published_layouts` (the thesis' tables),
:class:`tyrelab.vehicle.tyres.AxleTyres` (a tyre's looked-up numbers) — and go back to kN where
they are written out (tables, JSON), with :func:`from_kilo` and :func:`to_kilo`; no other module of
``tyrelab.vehicle`` writes a factor of 1e3 (``tests/vehicle/test_units_tree.py`` checks it).

Speeds are given in km/h (scenario files, the raw format's ``speed_km_h``, the thesis' tables) and
are m/s inside: :func:`km_h_to_m_s` is the one conversion (no ``/ 3.6`` elsewhere in ``tyrelab``).
Gravity is the standard gravity :data:`STANDARD_GRAVITY_M_S2` (ISO 80000-3, CGPM 1901): the model,
the raw format's check of an accelerometer's orientation, the virtual rig and the measurement
methods all use this one constant; a thesis study that needs the thesis' 9.81 m/s² to reproduce its
printed numbers names it itself (:data:`tyrelab.vehicle.studies.carriage.THESIS_GRAVITY_M_S2`).
``tests/vehicle/test_units_one_home.py`` checks the whole package for a gravity or a km/h written
by hand.

This module is at the bottom of the package's layers (it imports nothing of tyrelab), so that the
raw format, the rig, the measurement methods and the tyre package can use it as the vehicle model
does; :mod:`tyrelab.vehicle.units` is the same module under its earlier name.
"""

from __future__ import annotations

__all__ = ["KILO", "from_kilo", "to_kilo", "KM_H_PER_M_S", "km_h_to_m_s", "m_s_to_km_h", "STANDARD_GRAVITY_M_S2"]

#: kN -> N (and kN s/m -> N s/m, kN m/rad -> N m/rad).
KILO = 1e3
#: km/h in one m/s (3600 s / 1000 m).
KM_H_PER_M_S = 3.6
#: Standard acceleration of gravity, m/s² (3rd CGPM 1901; ISO 80000-3).
STANDARD_GRAVITY_M_S2 = 9.80665


def from_kilo(value):
    """A value in kN/m, kN s/m or kN m/rad (scalar or array) in N/m, N s/m or N m/rad.

    See Also
    --------
    to_kilo : back to kN units.

    Examples
    --------
    >>> from_kilo(455.0)
    455000.0
    """
    return KILO * value


def to_kilo(value):
    """:func:`from_kilo` back: SI to kN/m, kN s/m or kN m/rad.

    See Also
    --------
    from_kilo : its inverse.

    Examples
    --------
    >>> to_kilo(455000.0)
    455.0
    """
    return value / KILO


def km_h_to_m_s(speed_km_h):
    """A speed in km/h (scalar or array) in m/s: ``speed_km_h / 3.6`` (the division, so the
    numbers are those of the ``/ 3.6`` it replaced, to the bit).

    See Also
    --------
    from_kilo, to_kilo : the kilo factor, the other unit conversion of the vehicle package.

    Examples
    --------
    >>> km_h_to_m_s(36.0)
    10.0
    >>> km_h_to_m_s(7.0) == 7.0 / 3.6
    True
    """
    return speed_km_h / KM_H_PER_M_S


def m_s_to_km_h(speed_m_s):
    """A speed in m/s (scalar or array) in km/h: ``speed_m_s * 3.6``, :func:`km_h_to_m_s` back.

    See Also
    --------
    km_h_to_m_s : its inverse.

    Examples
    --------
    >>> m_s_to_km_h(10.0)
    36.0
    >>> m_s_to_km_h(0.7) == 0.7 * 3.6
    True
    """
    return speed_m_s * KM_H_PER_M_S
