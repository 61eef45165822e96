"""The tractor in the time domain: exact while every tyre is on the ground, RK4 across lift-off.

Any tractor assembled from parts (:mod:`tyrelab.vehicle.model`) is simulated here; the
equations are the assembly's (its linear model for the exact path, its force elements for
the nonlinear right-hand side), none are written in this module. :class:`Tractor` is the
pitch-plane tractor of thesis ch. 7 (MF698T of Table XV) as twelve numbers, the form the
ch. 7 study sweeps: rigid body with vertical ``z`` (up), pitch ``θ`` (nose up) and
longitudinal ``x`` (forward) freedom, small angles, front axle ``a`` ahead of and rear axle
``b`` behind the centre of gravity (CG) at height ``h``; each axle a Kelvin-Voigt vertical
tyre element (both tyres together) that may lift off; the rear tyres optionally a
longitudinal element at the ground contact, Kelvin-Voigt (the thesis' ADAMS model, §7.3) or
Maxwell (§7.5)::

    z_f = z + a θ,  z_r = z - b θ,  d = x + h θ     (rear contact, fore-aft)
    F_f = max(K_f (u_f - z_f) + C_f (u_f' - z_f'), -W_f)        (same for the rear)
    Kelvin-Voigt: F_x = -(k_x d + c_x d');  Maxwell: F_x = -k_x (d - s), c_x s' = k_x (d - s)
    M z'' = F_f + F_r;  I θ'' = a F_f - b F_r + h F_x;  M x'' = F_x

(:func:`tractor_parts` gives its parts). The rear wheel sees the front wheel's input delayed
by wheelbase/speed. In the pitch plane the vertical, longitudinal and pitch motions are
independent of roll, lateral and yaw (Stayner, Collins and Lines 1984), so the thesis'
7-DOF ADAMS model (§7.3) and this one carry the same information for Tables XVII/XVIII.

The time domain itself (:func:`simulate`: exact while every tyre is in contact, RK4 across
lift-off, switched within a run) is :mod:`tyrelab.vehicle.solvers.time_domain` (issue 45), the solver
the ride scenarios share; this module is the twelve-number tractor on it (:func:`simulate_tractor`),
and keeps the solver's names (``simulate``, ``INTEGRATION_METHODS``, ``CALM_STEPS``, ``off_ground``, ...) importable
from here (and so from :mod:`tyrelab.vehicle`).
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from .. import _validate
from .model import Axle, Chassis, Parts, SeatPoint, assemble
from .solvers.time_domain import CALM_STEPS, INTEGRATION_METHODS, LIFT_OFF_RTOL, METHODS, RECORDED_OUTPUTS, off_ground, simulate  # noqa: F401  (METHODS: the old name)
from .units import STANDARD_GRAVITY_M_S2 as GRAVITY_M_S2  # noqa: F401  (the name of issue 35)

__all__ = ["Tractor", "tractor_parts", "simulate", "simulate_tractor", "TRACTOR_LONGITUDINAL_MODELS",
           "INTEGRATION_METHODS", "CALM_STEPS", "PARAMETERS", "TRACTOR_OUTPUTS",
           # the time domain's (solvers/time_domain.py) too, so that tyrelab.vehicle re-exports them
           "off_ground", "LIFT_OFF_RTOL", "RECORDED_OUTPUTS"]

#: What :func:`simulate_tractor` records per sample (the time domain's default record).
TRACTOR_OUTPUTS = RECORDED_OUTPUTS

#: Rear longitudinal element: none, Kelvin-Voigt (parallel) or Maxwell (series) (an assembled axle
#: has the rolling tyre too: :data:`tyrelab.vehicle.model.AXLE_LONGITUDINAL_MODELS`).
TRACTOR_LONGITUDINAL_MODELS = ("none", "kelvin_voigt", "maxwell")
#: The names of :data:`TRACTOR_LONGITUDINAL_MODELS` and :data:`INTEGRATION_METHODS` before issue 45:
#: still importable from here, not in ``__all__`` (another module's name meant another thing).
LONGITUDINAL_MODELS = TRACTOR_LONGITUDINAL_MODELS


@dataclass(frozen=True)
class Tractor:
    """Pitch-plane tractor parameters; any field may be an array (one per run). A constructor of
    pitch-plane parts (:meth:`parts`, :func:`tractor_parts`; :meth:`of_parts` the other way): the
    form the ch. 7 study sweeps, one array per parameter over a batch of runs.

    Attributes
    ----------
    mass_kg, pitch_inertia_kg_m2 : float
        Mass and pitch moment of inertia about the CG.
    front_distance_m, rear_distance_m : float
        Horizontal CG-to-axle distances a (front) and b (rear), m.
    cg_height_m : float
        CG height above the ground, m (lever arm of the longitudinal force).
    front_stiffness_N_per_m, rear_stiffness_N_per_m : float
        Axle vertical stiffness (two tyres), N/m.
    front_damping_N_s_per_m, rear_damping_N_s_per_m : float
        Axle vertical damping (two tyres), N s/m.
    longitudinal_stiffness_N_per_m, longitudinal_damping_N_s_per_m : float
        Rear axle longitudinal element (two tyres), N/m and N s/m.
    longitudinal_model : str or array of str
        One of :data:`TRACTOR_LONGITUDINAL_MODELS`, for the whole batch or one per run.
    """

    mass_kg: float
    pitch_inertia_kg_m2: float
    front_distance_m: float
    rear_distance_m: float
    cg_height_m: float
    front_stiffness_N_per_m: float
    rear_stiffness_N_per_m: float
    front_damping_N_s_per_m: float
    rear_damping_N_s_per_m: float
    longitudinal_stiffness_N_per_m: float = 0.0
    longitudinal_damping_N_s_per_m: float = 0.0
    longitudinal_model: str = "none"

    @property
    def wheelbase_m(self):
        """Wheelbase a + b, m."""
        return np.asarray(self.front_distance_m) + np.asarray(self.rear_distance_m)

    def parts(self, seat: SeatPoint | None = None) -> Parts:
        """The pitch-plane parts of a scalar tractor (:func:`tractor_parts`): a constructor of parts."""
        return tractor_parts(self, seat)

    @classmethod
    def of_parts(cls, parts: Parts) -> "Tractor":
        """The twelve numbers of pitch-plane ``parts`` (an axle's values are its two tyres'; the rear
        axle's longitudinal element).

        Examples
        --------
        >>> t = Tractor(1000, 250, 1.0, 1.2, 0.5, 1e5, 2e5, 1e3, 2e3, 1e5, 1e3, "maxwell")
        >>> Tractor.of_parts(t.parts()) == t
        True
        """
        _validate.instance("parts", parts, Parts)
        ch, f, r = parts.chassis, parts.front, parts.rear
        return cls(ch.mass_kg, ch.pitch_inertia_kg_m2, f.ahead_of_cg_m, -r.ahead_of_cg_m, ch.cg_height_m,
                   2 * f.tyre_stiffness_N_per_m, 2 * r.tyre_stiffness_N_per_m, 2 * f.tyre_damping_N_s_per_m,
                   2 * r.tyre_damping_N_s_per_m, 2 * r.longitudinal_stiffness_N_per_m,
                   2 * r.longitudinal_damping_N_s_per_m, r.longitudinal_model)


#: The numeric parameters of :class:`Tractor` (all but ``longitudinal_model``).
PARAMETERS = tuple(f.name for f in fields(Tractor) if f.name != "longitudinal_model")

def tractor_parts(tractor: Tractor, seat: SeatPoint | None = None) -> Parts:
    """The parts of a scalar pitch-plane :class:`Tractor` (axle values split over its two tyres).

    A Maxwell element without spring or damper carries no force (the model ``"none"``).

    See Also
    --------
    simulate_tractor : simulates them.
    tyrelab.vehicle.model.assemble : assembles them.

    Examples
    --------
    >>> p = tractor_parts(Tractor(1000, 250, 1.0, 1.0, 0.5, 1e5, 1e5, 0.0, 0.0, 1e5, 1e3, "maxwell"))
    >>> p.rear.longitudinal_model, p.rear.tyre_stiffness_N_per_m
    ('maxwell', 50000.0)
    """
    _validate.instance("tractor", tractor, Tractor)
    model = str(tractor.longitudinal_model)
    if model not in TRACTOR_LONGITUDINAL_MODELS:
        raise ValueError(f"longitudinal_model {model!r}: expected one of {TRACTOR_LONGITUDINAL_MODELS}")
    kx, cx = float(tractor.longitudinal_stiffness_N_per_m), float(tractor.longitudinal_damping_N_s_per_m)
    if model == "maxwell" and not (kx > 0 and cx > 0):
        model = "none"
    return Parts(
        Chassis(float(tractor.mass_kg), float(tractor.pitch_inertia_kg_m2), float(tractor.cg_height_m)),
        Axle("front", float(tractor.front_distance_m), float(tractor.front_stiffness_N_per_m) / 2,
             float(tractor.front_damping_N_s_per_m) / 2),
        Axle("rear", -float(tractor.rear_distance_m), float(tractor.rear_stiffness_N_per_m) / 2,
             float(tractor.rear_damping_N_s_per_m) / 2, longitudinal_model=model,
             longitudinal_stiffness_N_per_m=kx / 2, longitudinal_damping_N_s_per_m=cx / 2),
        seat or SeatPoint(),
    )


def _params(tractor: Tractor, runs: int) -> dict[str, np.ndarray]:
    return {k: np.broadcast_to(np.asarray(getattr(tractor, k), float), (runs,)) for k in PARAMETERS}


def _models(tractor: Tractor, runs: int) -> np.ndarray:
    """``longitudinal_model`` per run (a string for all runs, or one per run), checked."""
    models = np.asarray(tractor.longitudinal_model, dtype=object)
    if models.ndim > 1 or (models.ndim == 1 and models.size != runs):
        raise ValueError(f"longitudinal_model: expected one value or {runs} (one per run), got shape {models.shape}")
    bad = sorted({str(m) for m in models.ravel()} - set(TRACTOR_LONGITUDINAL_MODELS))
    if bad:
        raise ValueError(f"longitudinal_model {bad[0]!r}: expected one of {TRACTOR_LONGITUDINAL_MODELS}")
    return np.broadcast_to(models, (runs,))


def _scalar(p: dict[str, np.ndarray], models: np.ndarray, i: int) -> Tractor:
    return Tractor(**{k: float(v[i]) for k, v in p.items()}, longitudinal_model=str(models[i]))


def simulate_tractor(
    tractor: Tractor,
    front_half,
    front_rate_half,
    rear_half,
    rear_rate_half,
    dt_s: float = 1e-3,
    lift_off: bool = True,
    gravity_m_s2: float | None = None,
    method: str = "auto",
) -> dict[str, np.ndarray]:
    """Simulate the pitch-plane tractor (:func:`simulate` on :func:`tractor_parts`).

    Parameters
    ----------
    tractor : Tractor
        Scalars or arrays of shape ``(n_runs,)``; ``longitudinal_model`` one string or one per run.
    front_half, front_rate_half, rear_half, rear_rate_half : array_like
        Ground elevation (m) and rate (m/s) under the front and rear axles sampled at
        ``dt/2``, shape ``(2N-1,)`` or ``(n_runs, 2N-1)``; the rear input is the
        front one delayed by wheelbase/speed (the caller builds it from the profile).
    dt_s : float
        Step, s.
    lift_off : bool
        Let tyres leave the ground.
    gravity_m_s2 : float, optional
        Gravity, m/s² (the static tyre loads: the lift-off floors); default the standard gravity
        (:func:`~tyrelab.vehicle.model.assemble`), the ch. 7 study passes the thesis' 9.81.
    method : str
        One of :data:`INTEGRATION_METHODS`.

    Returns
    -------
    dict
        ``vertical_m_s2`` (CG), ``pitch_rad_s2``, ``longitudinal_m_s2`` (CG), ``z_m``,
        ``theta_rad`` per sample, ``lift_off_fraction_front``/``_rear`` (fraction of the
        samples at which the axle is off the ground) and ``method_used`` per run.

    See Also
    --------
    tractor_parts : the parts it simulates.
    tyrelab.vehicle.solvers.time_domain.simulate : the solver.

    Examples
    --------
    A 60 mm step under both axles at once lifts the front briefly; the run switches:

    >>> t = Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3)
    >>> u = np.r_[np.zeros(1001), np.full(2000, -0.06)]
    >>> out = simulate_tractor(t, u, 0 * u, u, 0 * u)
    >>> str(out["method_used"]), bool(out["lift_off_fraction_front"] > 0)
    ('exact+rk4', True)
    """
    uf, udf, ur, udr = (np.atleast_2d(np.asarray(v, float)) for v in (front_half, front_rate_half, rear_half, rear_rate_half))
    squeeze = np.ndim(front_half) == 1
    if not uf.shape == udf.shape == ur.shape == udr.shape:
        raise ValueError("front_half, front_rate_half, rear_half, rear_rate_half: shapes differ")
    if uf.shape[1] % 2 == 0:
        raise ValueError("inputs must be sampled at dt/2 (odd length)")
    runs = uf.shape[0]
    p, models = _params(tractor, runs), _models(tractor, runs)
    assemblies = [assemble(tractor_parts(_scalar(p, models, i)), gravity_m_s2) for i in range(runs)]
    out = simulate(assemblies, np.stack([uf, ur], axis=1), np.stack([udf, udr], axis=1), dt_s, lift_off,
                   method=method, record=TRACTOR_OUTPUTS)
    return {k: v[0] for k, v in out.items()} if squeeze else out
