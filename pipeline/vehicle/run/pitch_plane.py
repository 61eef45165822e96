"""The pitch-plane :class:`~tyrelab.vehicle.tractor.Tractor`'s linear model in the form of the
ride's first version (issue 13): ``(A, B, C, D)`` of its 12 numbers, inputs ``[u_f, u_f', u_r, u_r']``,
outputs :data:`OUTPUTS` (run it with :func:`tyrelab.vehicle.solvers.lti.discretise`). The ride
itself assembles its parts (:meth:`tyrelab.vehicle.model.Assembly.linear`).
"""

from __future__ import annotations

import numpy as np  # noqa: F401  (the Examples)

from ... import _validate
from ..model import SeatPoint, assemble
from ..tractor import Tractor, tractor_parts

__all__ = ["OUTPUTS", "state_names", "state_space"]

#: Outputs of :func:`state_space`, in row order.
OUTPUTS = ("seat_vertical_m_s2", "seat_longitudinal_m_s2", "vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2",
           "front_force_N", "rear_force_N")


def state_names(tractor: Tractor) -> list[str]:
    """States of :func:`state_space` for a scalar ``tractor``, in order
    (:meth:`tyrelab.vehicle.model.Assembly.state_names` of its parts).

    ``z, θ`` ("th"), ``x`` (Kelvin-Voigt with ``k_x > 0`` only), ``z', θ'`` ("vz", "vth"),
    ``x'`` ("vx", any longitudinal element) and ``q = d - s`` (Maxwell). A Maxwell element
    without spring or damper carries no force and adds no state.

    See Also
    --------
    state_space : the model of those states.

    Examples
    --------
    >>> state_names(Tractor(1000, 250, 1.0, 1.0, 0.5, 1e5, 1e5, 0.0, 0.0, 1e5, 1e3, "maxwell"))
    ['z', 'th', 'vz', 'vth', 'vx', 'q']
    """
    _validate.instance("tractor", tractor, Tractor)
    return assemble(tractor_parts(tractor)).state_names()


def state_space(tractor: Tractor, seat_ahead_m: float = 0.0, seat_height_m: float = 0.0):
    """Linear pitch-plane tractor (both axles in contact) as ``(A, B, C, D)``, outputs :data:`OUTPUTS`.

    The assembled parts' linear model (:meth:`tyrelab.vehicle.model.Assembly.linear` of
    :func:`tyrelab.vehicle.tractor.tractor_parts`), inputs ``[u_f, u_f', u_r, u_r']``: seat-point
    vertical ``z'' + x_s θ''`` and fore-aft ``x'' - h_s θ''`` accelerations (rigid seat), CG
    vertical, pitch and longitudinal accelerations, and the dynamic axle tyre forces.

    Parameters
    ----------
    tractor : Tractor
        Scalar parameters.
    seat_ahead_m, seat_height_m : float
        Seat point ahead of and above the CG, m.

    See Also
    --------
    state_names : its states.
    tyrelab.vehicle.solvers.lti.discretise : runs it (exact first-order hold).

    Examples
    --------
    >>> t = Tractor(1000, 250, 1.0, 1.0, 0.5, 1e5, 1e5, 0.0, 0.0)
    >>> a, b, c, d = state_space(t)
    >>> sorted(np.round(np.abs(np.linalg.eigvals(a)) / (2 * np.pi), 4).tolist())
    [2.2508, 2.2508, 4.5016, 4.5016]
    """
    _validate.instance("tractor", tractor, Tractor)
    parts = tractor_parts(tractor, SeatPoint(float(seat_ahead_m), 0.0, float(seat_height_m)))
    return assemble(parts).linear(OUTPUTS).abcd
