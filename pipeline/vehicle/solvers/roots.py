"""The damped model's roots (issue 42): the series dampers released along a path, each step's state
matrix from rows kept between the steps (:func:`_release_path`, which :func:`~tyrelab.vehicle.solvers.modes.damped_modes`
follows the modes along), and the roots' first-order sensitivities to a parameter
(:func:`root_sensitivities`, the ±1 % tyre stiffness intervals of the damped modes). Split from
:mod:`tyrelab.vehicle.solvers.modes`, which imports these names.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy import linalg

from ... import _validate
from ..elements import Maxwell, Rolling, StaticLoadMoment
from ..model import Assembly
from ..model.assembly import _solve_mass, _weighted as _weighted_row

__all__ = ["ZERO_ROOT", "DampedMode", "SENSITIVITY_SHAPE_SHARE", "root_sensitivities"]

#: A root ``λ`` with ``|λ|`` below this share of the largest is a zero root (a series damper's drift:
#: the body and its contact points moving sideways together feel nothing), left out. The roots of
#: the linear model come from a nonsymmetric eigenproblem whose rounding is ~1e-13 of the largest.
ZERO_ROOT = 1e-9


@dataclass(frozen=True)
class DampedMode:
    """One mode of the damped model (issue 42): the root ``λ`` (rad/s) of the linear model followed
    from the undamped mode of the same name by its shape.

    ``undamped_Hz = |λ| / 2π``, ``damped_Hz = Im λ / 2π`` and ``damping_ratio = -Re λ / |λ|`` of an
    oscillating mode (a complex pair); an overdamped mode is a real root: ``overdamped`` True,
    ``damped_Hz`` 0 and ``damping_ratio`` 1 (``-Re λ/|λ|`` of a real root; its frequency ``|λ|/2π`` is
    the decay rate's, not an oscillation's). ``mac``: the shape's match to the undamped mode."""

    name: str
    root: complex
    undamped_Hz: float
    damped_Hz: float
    damping_ratio: float
    overdamped: bool
    mac: float
    #: The shape over ``coordinates`` (complex, the velocity part of the eigenvector) and the mass matrix
    #: over them (:func:`follow_damped`).
    shape: np.ndarray | None = dataclasses.field(default=None, repr=False, compare=False)
    coordinates: tuple = dataclasses.field(default=(), repr=False, compare=False)
    mass: np.ndarray | None = dataclasses.field(default=None, repr=False, compare=False)


def _released_by(asm: Assembly) -> bool:
    """Whether ``asm`` has a series damper that is not locked (a rolling or a Maxwell element)."""
    return any((isinstance(e, Rolling) and not e.locked) or (isinstance(e, Maxwell) and e.active) for e in asm.elements)


def _released(asm: Assembly, share: float) -> Assembly:
    """``asm`` with every series damper's ``1/c₂`` times ``share`` (0: locked, the Kelvin-Voigt unit): a
    rolling element's, and a Maxwell element's (a rolling element without the unit's damper)."""
    import copy

    if not _released_by(asm):
        return asm
    new = {}
    for e in asm.elements:
        if isinstance(e, Maxwell) and e.active:  # a spring in series with a damper: the unit without damper
            e = Rolling(e.name, e.g, e.stiffness, 0.0, e.gate, e.floor_N, series_damping=e.damping)
        if isinstance(e, Rolling):
            new[e.name] = dataclasses.replace(e, series_damping=e.series_damping / share if share > 0 else math.inf)
    other = copy.copy(asm)
    other.elements = [new.get(e.name, e) if not isinstance(e, StaticLoadMoment) or e.contact is None
                      else dataclasses.replace(e, contact=new[e.contact.name]) for e in asm.elements]
    return other


def _roots(asm: Assembly, gravity_m_s2: float | None, coordinates) -> tuple[np.ndarray, np.ndarray]:
    """The non-zero roots of the upper half plane (and the real ones) and their shapes over ``coordinates``
    (the velocity part of the eigenvector, ``λ q``)."""
    lm = asm.linear(list(asm.kinematic_outputs)[:1], gravity_m_s2=gravity_m_s2)
    lay = asm.layout
    roots, vecs = linalg.eig(lm.a)
    scale = float(np.max(np.abs(roots))) if roots.size else 0.0
    keep = (np.abs(roots) > ZERO_ROOT * scale) & (roots.imag >= -ZERO_ROOT * np.abs(roots))
    idx = [lay.vel_cols[asm.coordinates.index(c)] for c in coordinates]
    return roots[keep], vecs[np.ix_(idx, np.flatnonzero(keep))]


def _release_path(asm: Assembly, gravity_m_s2: float | None, coordinates):
    """``share -> _roots(_released(asm, share), gravity_m_s2, coordinates)`` for ``share > 0``, the same
    numbers from the same operations (:meth:`~tyrelab.vehicle.model.Assembly.state_rows`, to the bit),
    cheaper: every released model has one layout, and only the series elements' rows change with
    ``share``. What does not change is computed once: the other elements' force rows (a static load's
    moment at a contact point among them) and their generalised forces, the position rows and the other
    elements' state-derivative rows; at each share the series elements' force and derivative rows
    (:class:`~tyrelab.vehicle.elements.Rolling`, its damper ``c₂`` as :func:`_released` sets it) and
    the sum of the generalised forces in the elements' order. The tilt outputs' gravity does not enter
    the roots."""
    one = _released(asm, 1.0)
    lay = one.layout
    known, _, _ = one.state_rows(lay, [e for e in one.elements if not isinstance(e, Rolling)])
    idx = [lay.vel_cols[asm.coordinates.index(c)] for c in coordinates]
    n, nq = lay.n, len(one.coordinates)
    series = {e.name for e in one.elements if isinstance(e, Rolling)}  # their rows follow the share
    _, _, fixed = one.state_rows(lay, [e for e in one.elements if e.name not in series], known)
    for j in range(nq):  # what state_rows writes from the generalised forces: set at each share
        fixed[lay.vel_cols[j]] = 0.0
    generalised = [(e, None if e.name in series else np.outer(-e.g, known[e.name])) for e in one.elements]
    mass = one.mass

    def rows_at(share: float) -> np.ndarray:
        gen = np.zeros((nq, lay.width))
        rows = fixed.copy()
        for e, g_f in generalised:
            if g_f is None:  # a series element at this share, as _released and state_rows build it
                e = dataclasses.replace(e, series_damping=e.series_damping / share)
                g_f = np.outer(-e.g, _weighted_row(e, e.force_row(lay)))
                for state, r in e.derivative_rows(lay).items():
                    rows[lay.index[state]] = r
            gen += g_f
        acc = _solve_mass(mass, gen)
        for j in range(nq):
            rows[lay.vel_cols[j]] = acc[j]
        return rows

    def roots_at(share: float) -> tuple[np.ndarray, np.ndarray]:
        roots, vecs = linalg.eig(rows_at(share)[:, :n])
        scale = float(np.max(np.abs(roots))) if roots.size else 0.0
        keep = (np.abs(roots) > ZERO_ROOT * scale) & (roots.imag >= -ZERO_ROOT * np.abs(roots))
        return roots[keep], vecs[np.ix_(idx, np.flatnonzero(keep))]

    roots_at.rows_at = rows_at  # (the tests compare it with state_rows)
    return roots_at


#: :func:`root_sensitivities` answers only where every mode's first-order shape change under the step it
#: is asked about stays below this share (the largest coefficient of another eigenvector in its
#: perturbed eigenvector): then the perturbed model's modes are the nominal ones moved a little, no two
#: trading places (the full solve follows them with a MAC of about ``1 - share²``). Measured on the 3-D
#: bench tractor and ``modern_3d_tractor`` (4 pressure pairs x 3 speeds each, 330 oscillating modes and
#: axles; ``bench/bench_ride.py --sensitivities``): no axle refused, and the derivatives of frequency and
#: damping ratio differ from the ±1 % full solves' central differences by a median 8e-5 and 1.1e-4, at
#: most 6e-3 of themselves.
SENSITIVITY_SHAPE_SHARE = 0.05


def root_sensitivities(a: np.ndarray, modes: dict, da: np.ndarray, step: float) -> dict | None:
    """First-order sensitivities of damped modes' undamped frequency and damping ratio to a parameter:
    ``{name: (df/dp, dζ/dp)}`` (Hz and 1 per unit of the parameter), or None where first order is not
    to be trusted.

    For a simple root ``λ`` of ``A`` with right and left eigenvectors ``v``, ``w`` the derivative is
    ``dλ/dp = wᴴ (dA/dp) v / (wᴴ v)`` (Wilkinson 1965, §2.8); ``f = |λ|/2π`` and ``ζ = -Re λ/|λ|``
    follow by the chain rule. None (the caller solves the perturbed models in full) where a mode is
    overdamped (a real root's following through the step is the full solve's: on the 3-D bench tractor
    one such root's central difference and its first-order derivative disagree), a mode's root is not a root of ``A`` to
    1e-8 or two share one, or the first-order shape change over a parameter change ``step`` exceeds
    :data:`SENSITIVITY_SHAPE_SHARE` (roots near each other: near a repeated root the derivative
    does not describe a finite step).

    Parameters
    ----------
    a : ndarray
        The state matrix whose roots the modes are (the model at share 1, :func:`damped_modes`).
    modes : dict
        ``{name: DampedMode}`` of ``a``.
    da : ndarray
        ``dA/dp`` (same shape as ``a``).
    step : float
        The parameter change the answer stands for (the full solve's ±1 % step).

    See Also
    --------
    tyrelab.vehicle.solvers.modes.damped_modes : the modes whose roots these are.
    tyrelab.vehicle.solvers.modes.frequency_intervals : the undamped modes' intervals (central differences).

    Examples
    --------
    A mass on a spring and damper, ``p`` the stiffness: ``f = √(k/m)/2π`` and ``ζ = c/(2√(km))``.

    >>> m, k, c = 1000.0, 1e5, 2e3
    >>> a = np.array([[0.0, 1.0], [-k / m, -c / m]]); da = np.array([[0.0, 0.0], [-1.0 / m, 0.0]])
    >>> lam = complex(np.linalg.eigvals(a)[np.argmax(np.linalg.eigvals(a).imag)])
    >>> mode = DampedMode("bounce", lam, abs(lam) / (2 * math.pi), lam.imag / (2 * math.pi), -lam.real / abs(lam), False, 1.0)
    >>> dfdk, dzdk = root_sensitivities(a, {"bounce": mode}, da, 0.01 * k)["bounce"]
    >>> round(dfdk / (0.5 / (2 * math.pi * math.sqrt(k * m))), 9), round(dzdk / (-0.5 * c / (2 * math.sqrt(m) * k ** 1.5)), 9)
    (1.0, 1.0)
    """
    a, da = _validate.finite_array("a", a), _validate.finite_array("da", da)
    if a.ndim != 2 or a.shape[0] != a.shape[1]:
        raise ValueError(f"a must be a square state matrix, got shape {a.shape}")
    if da.shape != a.shape:
        raise ValueError(f"da must have a's shape {a.shape}, got {da.shape}")
    if not isinstance(modes, dict) or not all(isinstance(d, DampedMode) for d in modes.values()):
        raise ValueError("modes must be a dict of DampedMode (damped_modes)")
    step = _validate.positive("step", step)
    if not modes or any(d.overdamped for d in modes.values()):
        return None
    lam, left, right = linalg.eig(a, left=True, right=True)
    scale = float(np.max(np.abs(lam)))
    pair = left.conj().T @ right  # wᵢᴴ vⱼ (diagonal: the normalisation; off it ~0)
    coupling = left.conj().T @ (step * da) @ right  # wᵢᴴ δA vⱼ
    norms = np.linalg.norm(right, axis=0)
    out, used = {}, set()
    for name, d in modes.items():
        i = int(np.argmin(np.abs(lam - d.root)))
        if abs(lam[i] - d.root) > 1e-8 * abs(d.root) or i in used or abs(pair[i, i]) == 0:
            return None
        used.add(i)
        for j in range(lam.size):  # the other eigenvectors' share in the perturbed one
            if j == i or abs(lam[j]) <= ZERO_ROOT * scale:
                continue
            share = abs(coupling[j, i]) / (abs(lam[i] - lam[j]) * abs(pair[j, j])) * norms[j] / norms[i]
            if not share <= SENSITIVITY_SHAPE_SHARE:
                return None
        dl = (left[:, i].conj() @ da @ right[:, i]) / pair[i, i]
        root = complex(d.root)
        size = abs(root)
        dsize = (root.real * dl.real + root.imag * dl.imag) / size
        out[name] = (float(dsize / (2 * math.pi)), float(-(dl.real * size - root.real * dsize) / size**2))
    return out
