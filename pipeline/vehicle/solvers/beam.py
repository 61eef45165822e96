"""The beam on two springs of thesis §8.2 (Fig. 68): the undamped bounce and pitch of a rigid tractor.

Mass ``M``, pitch moment of inertia ``I``, front axle ``l1`` ahead of and rear axle ``l2`` behind
the centre of gravity, axle stiffnesses ``K_f`` and ``K_r`` (an axle is two tyres)::

    | K_f + K_r            K_f l1 - K_r l2        |   | z |         | M  0 | | z |
    | K_f l1 - K_r l2      K_f l1^2 + K_r l2^2    | . | θ | = w^2 . | 0  I | | θ |

solved as a generalised symmetric eigenproblem (:func:`scipy.linalg.eigh`) of the assembled
pitch-plane tractor (:meth:`tyrelab.vehicle.model.Assembly.undamped`). The modal solver
(:mod:`tyrelab.vehicle.solvers.modes`) names the modes of such a tractor with it; the chapter 8
study (:mod:`tyrelab.vehicle.bounce_pitch`, Table XX) calls it for the thesis' tractors.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy import linalg

from ... import _validate
from ..model import Axle, Chassis, Parts, assemble
from ..units import from_kilo

__all__ = ["natural_frequencies", "mode_shapes", "frequency_uncertainty"]


def natural_frequencies(
    mass_kg: float,
    pitch_inertia_kg_m2: float,
    front_distance_m: float,
    rear_distance_m: float,
    front_stiffness_N_per_m_axle: float,
    rear_stiffness_N_per_m_axle: float,
) -> tuple[float, float]:
    """Undamped bounce/pitch natural frequencies of a beam on two springs.

    Thesis §8.2, Fig. 68 and its matrix equation of motion.

    Parameters
    ----------
    mass_kg : float
        Tractor mass M in kg.
    pitch_inertia_kg_m2 : float
        Pitch moment of inertia I about the centre of gravity, kg m^2.
    front_distance_m, rear_distance_m : float
        Horizontal distances l1 (front axle) and l2 (rear axle) from the centre of
        gravity, m.
    front_stiffness_N_per_m_axle, rear_stiffness_N_per_m_axle : float
        Axle stiffnesses K_f and K_r in N/m (both tyres of the axle: twice the
        per-tyre stiffness).

    Returns
    -------
    tuple of float
        ``(f1_Hz, f2_Hz)`` in ascending order.

    See Also
    --------
    mode_shapes : with each mode's nodal point.
    frequency_uncertainty : their intervals.

    Examples
    --------
    Equal springs with the centre of gravity midway decouple bounce and pitch:

    >>> f1, f2 = natural_frequencies(1000, 250, 1.0, 1.0, 1e5, 1e5)
    >>> round(f1, 4), round(f2, 4)   # sqrt(2e5/1000)/2pi, sqrt(2e5*1/250)/2pi
    (2.2508, 4.5016)
    """
    m, inertia = _validate.positive("mass_kg", mass_kg), _validate.positive("pitch_inertia_kg_m2", pitch_inertia_kg_m2)
    l1 = _validate.non_negative("front_distance_m", front_distance_m)
    l2 = _validate.non_negative("rear_distance_m", rear_distance_m)
    kf = _validate.positive("front_stiffness_N_per_m_axle", front_stiffness_N_per_m_axle)
    kr = _validate.positive("rear_stiffness_N_per_m_axle", rear_stiffness_N_per_m_axle)
    if l1 < 0 or l2 < 0 or l1 + l2 <= 0:
        raise ValueError("axle distances must be non-negative with a positive wheelbase")
    if not all(math.isfinite(v) for v in (m, inertia, l1, l2, kf, kr, kf * l1 * l1 + kr * l2 * l2)):
        raise ValueError(f"front_distance_m {l1:g}, rear_distance_m {l2:g}, mass_kg {m:g}, pitch_inertia_kg_m2 "
                         f"{inertia:g} and axle stiffnesses {kf:g}, {kr:g} N/m: the pitch stiffness "
                         "K_f l1² + K_r l2² is beyond a float (inputs not finite or far too large)")
    stiffness, mass = _matrices(m, inertia, l1, l2, kf, kr)
    omega2 = linalg.eigh(stiffness, mass, eigvals_only=True)
    f = np.sqrt(np.clip(omega2, 0.0, None)) / (2.0 * math.pi)
    if not np.isfinite(f).all():
        raise ValueError(f"mass_kg {m:g} and pitch_inertia_kg_m2 {inertia:g} with axle stiffnesses {kf:g}, {kr:g} "
                         "N/m give no finite natural frequency (far too small a mass or inertia)")
    return float(f[0]), float(f[1])


def _check(positive: dict, non_negative: dict) -> None:
    """ValueError naming the first argument of ``positive`` not > 0 or of ``non_negative`` not >= 0."""
    for name, value in positive.items():
        _validate.positive(name, value)
    for name, value in non_negative.items():
        _validate.non_negative(name, value)


def _axle_N_per_m(tyre_kN_per_m):
    """An axle's stiffness (its two tyres), N/m, from one tyre's in kN/m (the thesis' tables)."""
    return 2 * from_kilo(tyre_kN_per_m)


@functools.lru_cache(maxsize=1024)
def _matrices(m, inertia, l1, l2, kf, kr) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness and mass matrices of the beam on two springs (thesis §8.2), coordinates (z, θ):
    the undamped eigenproblem of the assembled pitch-plane tractor
    (:meth:`tyrelab.vehicle.model.Assembly.undamped`; an axle is two tyres). Kept per arguments
    (read-only): a variant's modes and their interval ask for the same beam more than once."""
    parts = Parts(Chassis(m, inertia, 0.0), Axle("front", l1, kf / 2, 0.0), Axle("rear", -l2, kr / 2, 0.0))
    stiffness, mass, _ = assemble(parts).undamped(("z", "th"))
    stiffness.flags.writeable = mass.flags.writeable = False
    return stiffness, mass


def mode_shapes(
    mass_kg: float,
    pitch_inertia_kg_m2: float,
    front_distance_m: float,
    rear_distance_m: float,
    front_stiffness_N_per_m_axle: float,
    rear_stiffness_N_per_m_axle: float,
) -> dict:
    """Bounce and pitch modes: natural frequency and nodal point of each (thesis §8.2).

    The frequencies are those of :func:`natural_frequencies` (same eigenproblem);
    a mode ``(z, θ)`` moves a point ``x`` ahead of the CG by ``z + x θ``, so its
    nodal point is at ``x = -z/θ`` (infinite for pure bounce). The mode with the
    larger ``|z| / (r |θ|)``, ``r = sqrt(I/M)`` the radius of gyration, is called
    bounce; a tie goes to the lower frequency.

    Returns
    -------
    dict
        ``bounce`` and ``pitch``: ``frequency_Hz``, ``nodal_point_ahead_of_cg_m``
        (inf when the mode does not pitch).

    See Also
    --------
    natural_frequencies : the frequencies alone.

    Examples
    --------
    >>> m = mode_shapes(1000, 250, 1.0, 1.0, 1e5, 1e5)
    >>> round(m["bounce"]["frequency_Hz"], 4), m["bounce"]["nodal_point_ahead_of_cg_m"]
    (2.2508, inf)
    >>> round(m["pitch"]["frequency_Hz"], 4), abs(m["pitch"]["nodal_point_ahead_of_cg_m"])
    (4.5016, 0.0)
    """
    _check(positive=dict(mass_kg=mass_kg, pitch_inertia_kg_m2=pitch_inertia_kg_m2,
                         front_stiffness_N_per_m_axle=front_stiffness_N_per_m_axle,
                         rear_stiffness_N_per_m_axle=rear_stiffness_N_per_m_axle),
           non_negative=dict(front_distance_m=front_distance_m, rear_distance_m=rear_distance_m))
    f = natural_frequencies(mass_kg, pitch_inertia_kg_m2, front_distance_m, rear_distance_m,
                            front_stiffness_N_per_m_axle, rear_stiffness_N_per_m_axle)
    stiffness, mass = _matrices(float(mass_kg), float(pitch_inertia_kg_m2), float(front_distance_m),
                                float(rear_distance_m), float(front_stiffness_N_per_m_axle),
                                float(rear_stiffness_N_per_m_axle))
    _, vecs = linalg.eigh(stiffness, mass)
    r = math.sqrt(float(pitch_inertia_kg_m2) / float(mass_kg))
    ratio = [abs(vecs[0, i]) / max(r * abs(vecs[1, i]), 1e-300) for i in (0, 1)]
    bounce = 0 if ratio[0] >= ratio[1] else 1
    out = {}
    for name, i in (("bounce", bounce), ("pitch", 1 - bounce)):
        z, th = vecs[0, i], vecs[1, i]
        node = -z / th if abs(th) > 1e-12 * abs(z) else math.inf
        out[name] = {"frequency_Hz": f[i], "nodal_point_ahead_of_cg_m": float(node) + 0.0}
    return out


def frequency_uncertainty(mass_kg: float, pitch_inertia_kg_m2: float, front_distance_m: float, rear_distance_m: float,
                          front_tyre_kN_per_m: float, rear_tyre_kN_per_m: float, front_u_kN_per_m: float,
                          rear_u_kN_per_m: float) -> tuple[tuple[float, float], tuple[tuple[float, float], ...]]:
    """Standard uncertainties and 95 % intervals of the two natural frequencies from the tyre stiffnesses'.

    First order (GUM 5.1.2): ``u²(f_i) = Σ_j (∂f_i/∂K_j)² u²(K_j)`` over the front and
    rear per-tyre stiffness, derivatives by central differences (±1 % of K); the
    interval is ``f_i ± 1.96 u(f_i)`` (a normal distribution: the stiffness
    uncertainties have many degrees of freedom or none stated).

    Returns
    -------
    (u1_Hz, u2_Hz), ((lo1, hi1), (lo2, hi2))

    See Also
    --------
    natural_frequencies : the frequencies it brackets.

    Examples
    --------
    >>> (u1, u2), _ = frequency_uncertainty(3235, 2669, 1.33, 0.71, 247, 306, 0.0, 0.0)
    >>> u1, u2
    (0.0, 0.0)
    """
    _check(positive=dict(mass_kg=mass_kg, pitch_inertia_kg_m2=pitch_inertia_kg_m2,
                         front_tyre_kN_per_m=front_tyre_kN_per_m, rear_tyre_kN_per_m=rear_tyre_kN_per_m),
           non_negative=dict(front_distance_m=front_distance_m, rear_distance_m=rear_distance_m,
                             front_u_kN_per_m=front_u_kN_per_m, rear_u_kN_per_m=rear_u_kN_per_m))
    k = np.array([front_tyre_kN_per_m, rear_tyre_kN_per_m], dtype=float)
    u = np.array([front_u_kN_per_m, rear_u_kN_per_m], dtype=float)

    def freqs(kk):
        return np.array(natural_frequencies(mass_kg, pitch_inertia_kg_m2, front_distance_m, rear_distance_m,
                                            _axle_N_per_m(kk[0]), _axle_N_per_m(kk[1])))

    f0 = freqs(k)
    var = np.zeros(2)
    for j in range(2):
        if u[j] == 0:
            continue
        step = 0.01 * k[j]
        up, down = k.copy(), k.copy()
        up[j] += step
        down[j] -= step
        var += ((freqs(up) - freqs(down)) / (2 * step) * u[j]) ** 2
    uf = np.sqrt(var)
    return (float(uf[0]), float(uf[1])), tuple((float(f - 1.96 * s), float(f + 1.96 * s)) for f, s in zip(f0, uf))
