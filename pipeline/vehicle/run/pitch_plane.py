"""The pitch-plane :class:`~tyrelab.vehicle.tractor.Tractor`'s linear model in the form of the
ride's first version (issue 13): ``(A, B, C, D)`` of its 12 numbers, inputs ``[u_f, u_f', u_r, u_r']``,
outputs :data:`OUTPUTS`; a run of it from rest and its response to one ground profile. The ride
itself assembles its parts (:meth:`tyrelab.vehicle.model.Assembly.linear`).
"""

from __future__ import annotations

import math

import numpy as np

from ... import _validate
from ..._validate import positive
from .. import lti
from ..model import SeatPoint, assemble
from ..tractor import Tractor, tractor_parts
from .track import DT_S

__all__ = ["OUTPUTS", "state_names", "state_space", "simulate_state_space", "ground_response"]

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
    simulate_state_space : simulates those states.

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


def simulate_state_space(a, b, c, d, w, dt_s: float = DT_S, outputs=None) -> np.ndarray:
    """Outputs of ``x' = A x + B w, y = C x + D w`` from rest, exact for piecewise-linear ``w``.

    First-order hold (:func:`scipy.signal.cont2discrete`, ``method="foh"``), the
    discrete system diagonalised and each mode run with :func:`scipy.signal.lfilter`
    (the method of :func:`tyrelab.vehicle.carriage.simulate_linear`, for any size;
    :func:`tyrelab.vehicle.lti.discretise` and :meth:`~tyrelab.vehicle.lti.FohSystem.run`).

    Parameters
    ----------
    a, b, c, d : ndarray
        Continuous state space (n×n, n×m, p×n, p×m).
    w : ndarray, shape (m, N)
        Inputs at ``t = k dt``.
    dt_s : float
        Step, s.
    outputs : sequence of int, optional
        Rows of ``C``/``D`` wanted (default all).

    Returns
    -------
    ndarray, shape (p, N)

    See Also
    --------
    tyrelab.vehicle.lti.discretise : the discretisation it uses.
    ground_response : the same system in the frequency domain.

    Examples
    --------
    Unit step into ``x' = -x``, ``y = x``: ``1 - exp(-t)``.

    >>> y = simulate_state_space([[-1.0]], [[1.0]], [[1.0]], [[0.0]], np.ones((1, 1001)), 1e-3)
    >>> round(float(y[0, -1]), 6), round(1 - math.exp(-1), 6)
    (0.632121, 0.632121)
    """
    dt_s = positive("dt_s", dt_s)
    a, b, c, d = (np.atleast_2d(np.asarray(v, float)) for v in (a, b, c, d))
    if outputs is not None:
        c, d = c[list(outputs)], d[list(outputs)]
    return lti.discretise(a, b, c, d, dt_s).run(w)


def ground_response(h: np.ndarray, frequency_Hz, speed_m_s: float, wheelbase_m: float,
                    env_front=1.0, env_rear=1.0) -> np.ndarray:
    """Response of every output to a ground profile's displacement (per metre).

    The front axle sees ``u``, the rear ``u`` delayed by ``wheelbase/speed``; rates
    are ``jω u``; ``env_*`` are the enveloping transfer functions at ``n = f/v``.

    Parameters
    ----------
    h : ndarray, shape (p, 4, n_f)
        :func:`frequency_response`.

    Returns
    -------
    ndarray, shape (p, n_f)

    See Also
    --------
    simulate_state_space : the same system in time.

    Examples
    --------
    An output that adds the front and rear ground displacements (bounce at the CG of a symmetric
    tractor, per unit): the wheelbase filter cancels it where the rear is half a period behind,
    ``f = v / (2 L)``:

    >>> f = np.array([0.0, 0.5, 1.0]); h = np.zeros((1, 4, f.size), complex)
    >>> h[:, 0] = h[:, 2] = 1.0                                 # to front and rear displacement; no rate terms
    >>> np.round(np.abs(ground_response(h, f, speed_m_s=2.5, wheelbase_m=2.5)), 9).tolist()
    [[2.0, 0.0, 2.0]]
    """
    positive("speed_m_s", speed_m_s)
    _validate.non_negative("wheelbase_m", wheelbase_m)
    jw = 2j * math.pi * np.asarray(frequency_Hz, float)
    front = (h[:, 0] + jw * h[:, 1]) * env_front
    rear = (h[:, 2] + jw * h[:, 3]) * env_rear * np.exp(-jw * wheelbase_m / speed_m_s)
    return front + rear
