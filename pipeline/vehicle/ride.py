"""Ride prediction for any tractor: the operator's daily vibration exposure (issue 13).

A :class:`~tyrelab.vehicle.scenario.Scenario` (tractor, tyres, seat, track, speeds)
becomes, per speed and per front/rear pressure pair, the seat's ISO 2631-1
weighted accelerations and the EU Directive 2002/44/EC daily exposure:

1. **Tyres** (:func:`resolve_tyres`): stiffness and damping per tyre and speed,
   from an override, a measured tyre of the warehouse (``K = K_c + ΔK_p P`` and
   ``C = C_c + ΔC P`` per speed, tables ``stiffness_pressure_by_speed`` /
   ``damping_pressure_by_speed``) or the thesis formula (§4.5.3, §8.2); damping
   without either is the mean of the thesis' Table VII traction tyres.
2. **Model**: the pitch-plane tractor of :mod:`tyrelab.vehicle.tractor` (same
   equations, wheelbase delay, rear longitudinal element). While both axles stay
   on the ground the model is linear; :func:`state_space` writes it as
   ``x' = A x + B w``, ``y = C x + D w`` with inputs ``w = [u_f, u_f', u_r, u_r']``.
   The time path runs it exactly for piecewise-linear inputs (first-order hold,
   modal decomposition, one :func:`scipy.signal.lfilter` per mode); a run whose
   tyre force would pull (lift-off) is re-run with
   :func:`~tyrelab.vehicle.tractor.simulate_tractor` (exact in contact, the
   nonlinear RK4 across the lift-off intervals), so the numbers are those of the
   ch. 7 study. The seat suspension is a base-excited single-DOF filter on
   the seat-point vertical acceleration (no feedback on the tractor).
3. **Frequency-domain path** (:func:`frequency_response`, :func:`expected_rms`):
   the same ``(A, B, C, D)`` gives the seat's complex response to ground input
   with the wheelbase delay and the enveloping filter's spatial transfer
   function; for a track of known spectrum the expected weighted r.m.s. is
   ``sqrt(∫ |H(f)|² |W(f)|² S_u(f) df)``, printed beside the simulated value so a
   user sees the sampling error of one random track.
4. **Exposure** (:func:`exposure`): ``A(8)`` is the highest of ``1.4 a_wx``,
   ``1.4 a_wy`` and ``a_wz`` times ``sqrt(T/8 h)`` (Directive; not the vector sum
   ``a_v``, which is reported as well); hours to the action and limit values
   ``8 h (value / a_w)²``. The pitch-plane model has no lateral motion: ``a_wy``
   is not modelled (0).

SI inside; km/h, kN/m and bar at the edges, as in the key names.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd
from scipy import signal

from .. import published
from ..tyre.sizes import parse_tyre_size, rolling_circumference_m
from ..tyre.stiffness import estimate_stiffness
from . import bounce_pitch
from . import enveloping as ev
from . import iso2631
from . import lti
from . import metrics as mt
from . import profiles as pr
from .carriage import GRAVITY_M_S2
from .scenario import Scenario, read_profile_csv, with_overrides
from .scenario_limits import MIN_VERDICT_DURATION_S
from .studies import DT_S, _half_inputs
from .tractor import PARAMETERS, Tractor, simulate_tractor

__all__ = [
    "OUTPUTS",
    "AxleTyres",
    "Track",
    "RideResult",
    "per_speed",
    "resolve_tyres",
    "build_tractor",
    "state_names",
    "state_space",
    "simulate_state_space",
    "seat_filter",
    "frequency_response",
    "ground_response",
    "enveloping_response",
    "build_profile",
    "axle_inputs",
    "exposure",
    "expected_rms",
    "ride",
    "ride_sweep",
    "result_json",
    "results_table",
    "scenario_files",
    "run_scenarios",
    "scenario_items",
    "scenario_task",
    "collect_scenarios",
    "VERDICTS",
]

FS_HZ = 1.0 / DT_S
#: Outputs of :func:`state_space`, in row order.
OUTPUTS = ("seat_vertical_m_s2", "seat_longitudinal_m_s2", "vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2",
           "front_force_N", "rear_force_N")
#: Verdicts against the Directive's daily values (A(8) at hours_per_day).
VERDICTS = ("below action value", "above action value", "above limit value")
#: Frequency range of the seat PSD and transmissibility figures, Hz.
FIGURE_BAND_HZ = (0.2, 20.0)


# --------------------------------------------------------------------------- tyres
@dataclass(frozen=True)
class AxleTyres:
    """Resolved characteristics of one tyre of an axle, per scenario speed.

    Attributes
    ----------
    size : str
    pressure_bar : float
    stiffness_kN_per_m, damping_kN_s_per_m : ndarray
        Per tyre, one value per speed.
    stiffness_source, damping_source : str
        Where the numbers came from (override, measured tyre, formula, thesis table).
    radius_m : float
        Rolling radius used by the rigid tread band, m.
    footprint_m : ndarray
        Contact length used by the enveloping filter, one per speed, m.
    warnings : list of str
        The formula's out-of-range warnings and similar notes.
    stiffness_u_kN_per_m : float
        Standard uncertainty of the per-tyre stiffness, kN/m: the formula's (its
        prediction interval on the thesis' data, issue 14); 0 for an override or a
        measured tyre (not propagated).
    """

    size: str
    pressure_bar: float
    stiffness_kN_per_m: np.ndarray
    damping_kN_s_per_m: np.ndarray
    stiffness_source: str
    damping_source: str
    radius_m: float
    footprint_m: np.ndarray
    warnings: tuple[str, ...] = ()
    stiffness_u_kN_per_m: float = 0.0


def per_speed(values, list_speeds_km_h, speeds_km_h) -> np.ndarray:
    """A scenario value at each speed: a scalar everywhere, or a per-speed list interpolated.

    Parameters
    ----------
    values : float or sequence
        One value, or one per entry of ``list_speeds_km_h``.
    list_speeds_km_h, speeds_km_h : sequence of float
        The speeds the list refers to, and the speeds wanted (linear
        interpolation, held constant outside).

    Examples
    --------
    >>> per_speed([1.0, 2.0], [10, 20], [5, 15, 25]).tolist()
    [1.0, 1.5, 2.0]
    """
    v = np.atleast_1d(np.asarray(values, float))
    speeds = np.asarray(speeds_km_h, float)
    if v.size == 1:
        return np.full(speeds.shape, float(v[0]))
    ls = np.asarray(list_speeds_km_h, float)
    if ls.size != v.size:
        raise ValueError(f"values: {v.size} values for {ls.size} speeds")
    order = np.argsort(ls)
    return np.interp(speeds, ls[order], v[order])


def _measured(build: Path | None, table: str, tyre_id: str, pressure_bar: float) -> tuple[np.ndarray, np.ndarray]:
    """(speeds, value at pressure) of a measured tyre's per-speed pressure fits."""
    from ..warehouse import query

    if build is None:
        raise ValueError(f"measured_tyre_id {tyre_id!r} needs --build (a warehouse with {table})")
    db = Path(build) / "warehouse.duckdb"
    if not db.is_file():
        raise ValueError(f"measured_tyre_id {tyre_id!r}: no warehouse at {db}")
    tid = str(tyre_id).replace("'", "''")
    try:
        rows = query(db, f"SELECT speed_km_h, intercept, slope FROM {table} WHERE CAST(tyre_id AS VARCHAR) = '{tid}' "
                         "AND intercept IS NOT NULL AND slope IS NOT NULL AND speed_km_h IS NOT NULL ORDER BY speed_km_h")
    except Exception as exc:  # noqa: BLE001 - a warehouse without the table is the user's input problem
        raise ValueError(f"measured_tyre_id {tyre_id!r}: cannot read {table} from {db} ({str(exc).splitlines()[0]})") from None
    if rows.empty:
        raise ValueError(f"measured_tyre_id {tyre_id!r}: no fitted rows in {table} of {db}")
    return rows["speed_km_h"].to_numpy(float), (rows["intercept"] + rows["slope"] * pressure_bar).to_numpy(float)


def _stiffness_model(formula: str, build: Path | None):
    """The :class:`~tyrelab.tyre.stiffness.StiffnessModel` of ``[tyres.*] formula``: the thesis'
    (published Tables II, III, VI) or the build's (table ``formula_fit`` of its warehouse)."""
    from ..tyre.models import build_stiffness_model
    from ..warehouse import query

    thesis = published.thesis_stiffness_model()
    if formula != "build":
        return thesis
    if build is None:
        raise ValueError('formula = "build" needs --build (a warehouse with table formula_fit)')
    db = Path(build) / "warehouse.duckdb"
    if not db.is_file():
        raise ValueError(f'formula = "build": no warehouse at {db}')
    try:
        table = query(db, "SELECT * FROM formula_fit")
    except Exception as exc:  # noqa: BLE001 - a warehouse without the table is the user's input problem
        raise ValueError(f'formula = "build": cannot read formula_fit from {db} ({str(exc).splitlines()[0]})') from None
    try:
        return build_stiffness_model(table, thesis)
    except ValueError as exc:
        raise ValueError(f'formula = "build": {db}: {exc}') from None


def _formula_stiffness(spec, build: Path | None = None) -> tuple[float, str, list[str], float]:
    """Per-tyre formula stiffness (kN/m), its rule, the formula's range warnings and its standard uncertainty."""
    model = _stiffness_model(getattr(spec, "formula", "thesis"), build)
    est = estimate_stiffness(spec.size, spec.pressure_bar, spec.age_years, undriven_front=not spec.traction,
                             water_ballast=spec.water_ballast, model=model)
    rule = f"formula {est.rule}" + (" x1.25 water ballast" if spec.water_ballast else "")
    return est.stiffness_kN_per_m, rule, list(est.warnings), est.stiffness_u_kN_per_m or 0.0


def _thesis_damping(pressure_bar: float, speeds_km_h) -> np.ndarray:
    """Mean of the thesis' Table VII traction tyres, ``C_c + ΔC P``, at each speed (kN s/m)."""
    t = published.read_published("table_vii")
    t = t.assign(c=t["carcass_damping_kN_s_per_m"] + t["pressure_dependence_kN_s_per_m_bar"] * pressure_bar)
    mean = t.groupby("speed_km_h")["c"].mean()
    return np.interp(np.asarray(speeds_km_h, float), mean.index.to_numpy(float), mean.to_numpy(float))


def resolve_tyres(scenario: Scenario, build: Path | None = None) -> dict[str, AxleTyres]:
    """Stiffness, damping, radius and footprint of the front and rear tyres per speed.

    Order of precedence per quantity: the scenario's override, the measured tyre
    (``measured_tyre_id`` in the warehouse of ``build``; speeds interpolated, held
    outside the measured range), the formula (stiffness) or the mean of the
    thesis' Table VII (damping).

    Raises
    ------
    ValueError
        When a measured tyre cannot be found.
    """
    speeds = np.asarray(scenario.exposure.speeds_km_h, float)
    lists = scenario.exposure.list_speeds_km_h
    t = scenario.tractor
    load_n = {"front": t.mass_kg * GRAVITY_M_S2 * t.rear_distance_m / t.wheelbase_m / 2,
              "rear": t.mass_kg * GRAVITY_M_S2 * t.front_distance_m / t.wheelbase_m / 2}
    out = {}
    for axle, spec in (("front", scenario.front), ("rear", scenario.rear)):
        warnings: list[str] = []
        k_u = 0.0
        if spec.stiffness_kN_per_m is not None:
            k, k_src = per_speed(spec.stiffness_kN_per_m, lists, speeds), "override (scenario)"
        elif spec.measured_tyre_id:
            sp, val = _measured(build, "stiffness_pressure_by_speed", spec.measured_tyre_id, spec.pressure_bar)
            k = np.interp(speeds, sp, val)
            k_src = f"measured tyre {spec.measured_tyre_id}: K = Kc + dKp P per speed (stiffness_pressure_by_speed)"
        else:
            k0, k_src, warnings, k_u = _formula_stiffness(spec, build)
            k = np.full(speeds.shape, k0)
        if spec.damping_kN_s_per_m is not None:
            c, c_src = per_speed(spec.damping_kN_s_per_m, lists, speeds), "override (scenario)"
        elif spec.measured_tyre_id:
            sp, val = _measured(build, "damping_pressure_by_speed", spec.measured_tyre_id, spec.pressure_bar)
            c = np.interp(speeds, sp, val)
            c_src = f"measured tyre {spec.measured_tyre_id}: C = Cc + dC P per speed (damping_pressure_by_speed)"
        else:
            c = _thesis_damping(spec.pressure_bar, speeds)
            c_src = "mean of the thesis' Table VII traction tyres, Cc + dC P (no damping given)"
            warnings.append("damping not given: the thesis' Table VII mean is a rough stand-in (typical 0.8-3 kN s/m, §5.6)")
        if np.any(k <= 0):
            raise ValueError(f"tyres.{axle}: stiffness {k.min():.1f} kN/m is not positive")
        size = parse_tyre_size(spec.size)
        radius = spec.radius_m or rolling_circumference_m(size) / (2 * math.pi)
        if spec.footprint_m is not None:
            fp = np.full(speeds.shape, float(spec.footprint_m))
        else:
            fp = np.array([ev.contact_length(radius, load_n[axle] / (1e3 * kk)) for kk in k])
        out[axle] = AxleTyres(spec.size, spec.pressure_bar, k, np.maximum(c, 0.0), k_src, c_src, float(radius), fp,
                              tuple(warnings), float(k_u))
    return out


def build_tractor(scenario: Scenario, tyres: dict[str, AxleTyres], i: int) -> Tractor:
    """The :class:`~tyrelab.vehicle.tractor.Tractor` at speed index ``i`` (axle = two tyres, SI)."""
    t = scenario.tractor
    return Tractor(
        mass_kg=t.mass_kg, pitch_inertia_kg_m2=t.pitch_inertia_kg_m2, front_distance_m=t.front_distance_m,
        rear_distance_m=t.rear_distance_m, cg_height_m=t.cg_height_m,
        front_stiffness_N_per_m=2e3 * float(tyres["front"].stiffness_kN_per_m[i]),
        rear_stiffness_N_per_m=2e3 * float(tyres["rear"].stiffness_kN_per_m[i]),
        front_damping_N_s_per_m=2e3 * float(tyres["front"].damping_kN_s_per_m[i]),
        rear_damping_N_s_per_m=2e3 * float(tyres["rear"].damping_kN_s_per_m[i]),
        longitudinal_stiffness_N_per_m=2e3 * t.longitudinal_stiffness_kN_per_m if t.longitudinal_model != "none" else 0.0,
        longitudinal_damping_N_s_per_m=2e3 * t.longitudinal_damping_kN_s_per_m if t.longitudinal_model != "none" else 0.0,
        longitudinal_model=t.longitudinal_model,
    )


# --------------------------------------------------------------------------- linear model
def state_names(tractor: Tractor) -> list[str]:
    """States of :func:`state_space` for a scalar ``tractor``, in order.

    ``z, θ`` ("th"), ``x`` (Kelvin-Voigt with ``k_x > 0`` only), ``z', θ'`` ("vz", "vth"),
    ``x'`` ("vx", any longitudinal element) and ``q = d - s`` (Maxwell). A Maxwell element
    without spring or damper carries no force (as in
    :func:`tyrelab.vehicle.tractor.simulate_tractor`) and adds no state.

    Examples
    --------
    >>> state_names(Tractor(1000, 250, 1.0, 1.0, 0.5, 1e5, 1e5, 0.0, 0.0, 1e5, 1e3, "maxwell"))
    ['z', 'th', 'vz', 'vth', 'vx', 'q']
    """
    kx, cx = float(tractor.longitudinal_stiffness_N_per_m), float(tractor.longitudinal_damping_N_s_per_m)
    model = str(tractor.longitudinal_model)
    if model == "maxwell" and not (kx > 0 and cx > 0):
        model = "none"
    names = ["z", "th"] + (["x"] if model == "kelvin_voigt" and kx > 0 else []) + ["vz", "vth"]
    names += ["vx"] if model != "none" else []
    names += ["q"] if model == "maxwell" else []
    return names


def state_space(tractor: Tractor, seat_ahead_m: float = 0.0, seat_height_m: float = 0.0):
    """Linear pitch-plane tractor (both axles in contact) as ``(A, B, C, D)``.

    Same equations as :func:`tyrelab.vehicle.tractor.simulate_tractor` without the
    lift-off clamp. States: ``z, θ, z', θ'`` plus the longitudinal ones the model
    needs — Kelvin-Voigt: ``x`` (only when ``k_x > 0``; otherwise ``x`` is not
    observable) and ``x'``; Maxwell: ``x'`` and ``q = d - s`` (spring extension,
    ``F_x = -k_x q``, ``q' = d' - (k_x/c_x) q``). Inputs ``[u_f, u_f', u_r, u_r']``.
    Outputs :data:`OUTPUTS`: seat-point vertical ``z'' + x_s θ''`` and fore-aft
    ``x'' - h_s θ''`` accelerations (rigid seat), CG vertical, pitch and
    longitudinal accelerations, and the dynamic axle tyre forces.

    Parameters
    ----------
    tractor : Tractor
        Scalar parameters.
    seat_ahead_m, seat_height_m : float
        Seat point ahead of and above the CG, m.

    Returns
    -------
    A, B, C, D : ndarray

    Examples
    --------
    >>> t = Tractor(1000, 250, 1.0, 1.0, 0.5, 1e5, 1e5, 0.0, 0.0)
    >>> a, b, c, d = state_space(t)
    >>> sorted(np.round(np.abs(np.linalg.eigvals(a)) / (2 * np.pi), 4).tolist())
    [2.2508, 2.2508, 4.5016, 4.5016]
    """
    m, inertia = float(tractor.mass_kg), float(tractor.pitch_inertia_kg_m2)
    a, b, h = float(tractor.front_distance_m), float(tractor.rear_distance_m), float(tractor.cg_height_m)
    kf, kr = float(tractor.front_stiffness_N_per_m), float(tractor.rear_stiffness_N_per_m)
    cf, cr = float(tractor.front_damping_N_s_per_m), float(tractor.rear_damping_N_s_per_m)
    kx, cx = float(tractor.longitudinal_stiffness_N_per_m), float(tractor.longitudinal_damping_N_s_per_m)
    names = state_names(tractor)
    model = "maxwell" if "q" in names else "kelvin_voigt" if "vx" in names else "none"
    n = len(names)
    pos = {k: i for i, k in enumerate(names)} | {"uf": n, "udf": n + 1, "ur": n + 2, "udr": n + 3}

    def row(**coef) -> np.ndarray:
        r = np.zeros(n + 4)
        for k, v in coef.items():
            if k in pos:
                r[pos[k]] += v
        return r

    ff = row(z=-kf, th=-kf * a, vz=-cf, vth=-cf * a, uf=kf, udf=cf)
    fr = row(z=-kr, th=kr * b, vz=-cr, vth=cr * b, ur=kr, udr=cr)
    if model == "kelvin_voigt":
        fx = row(x=-kx, th=-kx * h, vx=-cx, vth=-cx * h)
    elif model == "maxwell":
        fx = row(q=-kx)
    else:
        fx = row()
    az = (ff + fr) / m
    ath = (a * ff - b * fr + h * fx) / inertia
    ax = fx / m
    deriv = {"z": row(vz=1.0), "th": row(vth=1.0), "x": row(vx=1.0), "vz": az, "vth": ath, "vx": ax,
             "q": row(vx=1.0, vth=h, q=-kx / cx if cx > 0 else 0.0)}
    rows = np.array([deriv[k] for k in names])
    outs = np.array([az + seat_ahead_m * ath, ax - seat_height_m * ath, az, ath, ax, ff, fr])
    return rows[:, :n], rows[:, n:], outs[:, :n], outs[:, n:]


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

    Examples
    --------
    Unit step into ``x' = -x``, ``y = x``: ``1 - exp(-t)``.

    >>> y = simulate_state_space([[-1.0]], [[1.0]], [[1.0]], [[0.0]], np.ones((1, 1001)), 1e-3)
    >>> round(float(y[0, -1]), 6), round(1 - math.exp(-1), 6)
    (0.632121, 0.632121)
    """
    a, b, c, d = (np.atleast_2d(np.asarray(v, float)) for v in (a, b, c, d))
    if outputs is not None:
        c, d = c[list(outputs)], d[list(outputs)]
    return lti.discretise(a, b, c, d, dt_s).run(w)


def seat_filter(natural_frequency_Hz: float, damping_ratio: float):
    """Base-excited single-DOF seat: ``(A, B, C, D)`` from seat-base to seat acceleration.

    ``T(s) = (2 ζ ω s + ω²) / (s² + 2 ζ ω s + ω²)``, the transmissibility of a seat
    on a linear spring and damper; it maps base acceleration to seat acceleration.
    """
    wn = 2 * math.pi * float(natural_frequency_Hz)
    z = float(damping_ratio)
    return signal.tf2ss([2 * z * wn, wn**2], [1.0, 2 * z * wn, wn**2])


def frequency_response(a, b, c, d, frequency_Hz) -> np.ndarray:
    """Complex response ``C (jω I - A)⁻¹ B + D`` of every output to every input.

    Computed modally (``A = V Λ V⁻¹``), vectorised over frequencies.

    Returns
    -------
    ndarray, shape (p, m, n_f)
    """
    a, b, c, d = (np.atleast_2d(np.asarray(v, float)) for v in (a, b, c, d))
    lam, vecs = np.linalg.eig(a)
    cv = c @ vecs
    vb = np.linalg.solve(vecs, b)
    jw = 2j * math.pi * np.asarray(frequency_Hz, float)
    inv = 1.0 / (jw[None, :] - lam[:, None])  # (n, nf)
    return np.einsum("pk,km,kf->pmf", cv, vb, inv) + d[:, :, None]


def enveloping_response(kind: str, footprint_m: float, dx_m: float, n_cycles_per_m) -> np.ndarray:
    """Spatial transfer function of the linear enveloping filters (real, symmetric windows).

    ``none`` and ``rigid_band`` (nonlinear; no transfer function) give 1.
    """
    n = np.asarray(n_cycles_per_m, float)
    if kind == "fixed":
        taps = np.ones(max(1, int(round(footprint_m / dx_m)) | 1))
    elif kind == "tapered":
        total = footprint_m * 1.25
        taps = ev.tapered_window(max(1, int(round(total / dx_m)) | 1), 0.5)
    else:
        return np.ones_like(n)
    taps = taps / taps.sum()
    k = np.arange(taps.size) - taps.size // 2
    return np.cos(2 * math.pi * np.outer(n, k * dx_m)) @ taps


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
    """
    jw = 2j * math.pi * np.asarray(frequency_Hz, float)
    front = (h[:, 0] + jw * h[:, 1]) * env_front
    rear = (h[:, 2] + jw * h[:, 3]) * env_rear * np.exp(-jw * wheelbase_m / speed_m_s)
    return front + rear


# --------------------------------------------------------------------------- profile and inputs
@dataclass(frozen=True)
class Track:
    """The track of a scenario with its lead-in, and the axle-input spectrum when known."""

    profile: pr.Profile
    lead_in_m: float
    length_m: float
    #: (n cycles/m, G of the axle-mean input m³) for the frequency-domain path, or None.
    spectrum: tuple[np.ndarray, np.ndarray] | None
    spectrum_source: str


def build_profile(scenario: Scenario) -> Track:
    """Generate or read the scenario's track, add the lead-in, describe its spectrum."""
    s = scenario.surface
    lead = max(s.lead_in_m, scenario.tractor.wheelbase_m + 1.0)
    if s.kind == "iso8608":
        prof = pr.iso8608_track(s.road_class, seed=s.seed, length_m=s.length_m, dx_m=s.dx_m)
        n = np.geomspace(0.011, 2.83, 4000)
        g = 0.5 * pr.ISO8608_CLASS_G0_M3[s.road_class] * (n / pr.ISO8608_N0_CYCLES_PER_M) ** -2.0
        spectrum, source = (n, g), f"ISO 8608 class {s.road_class} (geometric mean), independent left/right"
    elif s.kind == "slatted":
        prof = pr.slatted_track(seed=s.seed, length_m=s.length_m)
        spectrum, source = None, ""
    else:
        x, left, right = read_profile_csv(s.profile)
        dx = float(np.median(np.diff(x)))
        # the CSV's own grid: (end - start)/dx is a whole number up to the rounding of the
        # distances written in the file, which must not drop the last sample
        grid = x[0] + np.arange(int(math.floor((x[-1] - x[0]) / dx + 1e-6)) + 1) * dx
        prof = pr.Profile(grid - grid[0], np.interp(grid, x, left), np.interp(grid, x, right),
                          f"profile {Path(s.profile).name}", {"kind": "profile"})
        spectrum, source = None, ""
        if s.spectrum_g0_m3 is not None:
            correlated = s.spectrum_correlated if s.spectrum_correlated is not None else bool(np.array_equal(left, right))
            length = prof.x_m[-1]
            n = np.geomspace(1.0 / length, 0.5 / prof.dx_m, 4000)
            g = s.spectrum_g0_m3 * (n / pr.ISO8608_N0_CYCLES_PER_M) ** -s.spectrum_waviness * (1.0 if correlated else 0.5)
            spectrum = (n, g)
            source = f"declared G_d(n0) = {s.spectrum_g0_m3:g} m^3, w = {s.spectrum_waviness:g}"
    if spectrum is None:  # the track's own spectrum (Welch) of the axle-mean elevation
        mean = prof.track("mean")
        seg = min(51.2, prof.x_m[-1] / 4)
        n_w, g_w = pr.profile_spectrum(mean, prof.dx_m, seg)
        keep = (n_w > 0) & (g_w > 0)
        n = np.geomspace(n_w[keep][0], n_w[keep][-1], 4000)
        g = np.exp(np.interp(np.log(n), np.log(n_w[keep]), np.log(g_w[keep])))
        spectrum, source = (n, g), "the track's own Welch spectrum (axle mean)"
    length = float(prof.x_m[-1])
    return Track(pr.add_lead_in(prof, lead), float(round(lead / prof.dx_m) * prof.dx_m), length, spectrum, source)


def _envelope(track: pr.Profile, kind: str, footprint_m: float, radius_m: float) -> np.ndarray:
    """Axle-mean enveloped elevation (left and right enveloped, then averaged, as the ch. 7 study)."""
    dx = track.dx_m
    out = []
    for side in ("left", "right"):
        h = track.track(side)
        if kind == "tapered":
            h = ev.tapered_moving_average(h, dx, footprint_m)
        elif kind == "fixed":
            h = ev.fixed_footprint(h, dx, footprint_m)
        elif kind == "rigid_band":
            h = ev.rigid_tread_band(h, dx, radius_m)
        out.append(h)
    return 0.5 * (out[0] + out[1])


def axle_inputs(track: pr.Profile, kind: str, footprints: tuple[float, float], radii: tuple[float, float],
                speed_m_s: float, wheelbase_m: float, n_steps: int):
    """Front and rear ground elevation and rate at ``dt/2`` (for RK4), rear delayed by the wheelbase.

    The same construction as the ch. 7 study's inputs (cubic spline of the
    enveloped axle-mean profile, offsets relative to the start).

    Returns
    -------
    uf, udf, ur, udr : ndarray, shape (2 n_steps - 1,)
    """
    hf = _envelope(track, kind, footprints[0], radii[0])
    hr = hf if (footprints[0] == footprints[1] and radii[0] == radii[1]) or kind == "none" else \
        _envelope(track, kind, footprints[1], radii[1])
    uf, udf = _half_inputs(track.x_m, hf, speed_m_s, n_steps, x_start=wheelbase_m)
    ur, udr = _half_inputs(track.x_m, hr, speed_m_s, n_steps, x_start=0.0)
    u0 = 0.5 * (uf[0] + ur[0])
    return uf - u0, udf, ur - u0, udr


# --------------------------------------------------------------------------- exposure
def exposure(a_wz_m_s2: float, a_wx_m_s2: float, hours_per_day: float, a_wy_m_s2: float = 0.0) -> dict:
    """Daily exposure by EU Directive 2002/44/EC from per-axis weighted r.m.s. values.

    ``A(8) = max(1.4 a_wx, 1.4 a_wy, a_wz) sqrt(T / 8 h)``; hours to reach the action
    (0.5 m/s²) and limit (1.15 m/s²) values ``8 h (value / a_w)²`` with
    ``a_w = max(1.4 a_wx, 1.4 a_wy, a_wz)``; ``a_v`` the ISO 2631-1 vector sum.

    Examples
    --------
    >>> e = exposure(0.8, 0.2, 4.0)
    >>> round(e["a8_m_s2"], 6), round(e["hours_to_elv"], 4), e["verdict"]
    (0.565685, 16.5312, 'above action value')
    """
    if hours_per_day <= 0:
        raise ValueError("hours_per_day must be positive")
    k = iso2631.AXIS_FACTOR
    aw = max(k["x"] * a_wx_m_s2, k["y"] * a_wy_m_s2, k["z"] * a_wz_m_s2)
    a8 = iso2631.daily_exposure_a8(aw, hours_per_day)
    hours = (lambda v: 8.0 * (v / aw) ** 2) if aw > 0 else (lambda v: math.inf)
    verdict = VERDICTS[2] if a8 > iso2631.EU_LIMIT_A8_M_S2 else VERDICTS[1] if a8 > iso2631.EU_ACTION_A8_M_S2 else VERDICTS[0]
    return {
        "a_v_m_s2": math.sqrt((k["x"] * a_wx_m_s2) ** 2 + (k["y"] * a_wy_m_s2) ** 2 + (k["z"] * a_wz_m_s2) ** 2),
        "a8_m_s2": a8,
        "hours_to_eav": hours(iso2631.EU_ACTION_A8_M_S2),
        "hours_to_elv": hours(iso2631.EU_LIMIT_A8_M_S2),
        "verdict": verdict,
    }


def expected_rms(response: np.ndarray, frequency_Hz, input_psd, weighting: str) -> float:
    """``sqrt(∫ |H|² |W|² S df)``: expected weighted r.m.s. of a linear response, m/s².

    Parameters
    ----------
    response : ndarray
        Complex response to the input (per unit input) at ``frequency_Hz``.
    input_psd : ndarray
        One-sided input PSD (unit²/Hz) at the same frequencies.
    weighting : {"Wk", "Wd"}
    """
    f = np.asarray(frequency_Hz, float)
    w = np.abs(iso2631.weighting_response(f, weighting))
    return float(math.sqrt(np.trapezoid(np.abs(response) ** 2 * w**2 * np.asarray(input_psd, float), f)))


# --------------------------------------------------------------------------- the ride
@dataclass
class RideResult:
    """Everything :func:`ride` computed for one scenario and pressure pair.

    Attributes
    ----------
    scenario : Scenario
    tyres : dict
        ``front``/``rear`` -> :class:`AxleTyres`.
    natural_frequencies_Hz, nodal_points_m : dict
        ``bounce``/``pitch`` (at the first speed's stiffness); nodal point ahead of the CG.
    speeds : DataFrame
        One row per speed (see :func:`result_json` for the fields).
    spectra : DataFrame
        ``speed_km_h, frequency_Hz, seat_vertical_psd_m2_s4_per_Hz, seat_longitudinal_psd_m2_s4_per_Hz``.
    transmissibility : DataFrame
        ``speed_km_h, frequency_Hz, seat_vertical, seat_longitudinal_per_m`` (|seat
        acceleration / ground acceleration|, and fore-aft per unit ground acceleration).
    track_label, spectrum_source : str
    track_length_m : float
        Length of the track without lead-in, m.
    warnings : list of str
    """

    scenario: Scenario
    tyres: dict
    natural_frequencies_Hz: dict
    nodal_points_m: dict
    speeds: pd.DataFrame
    spectra: pd.DataFrame
    transmissibility: pd.DataFrame
    track_label: str
    spectrum_source: str
    track_length_m: float = math.nan
    warnings: list = field(default_factory=list)
    #: ``bounce``/``pitch`` -> [low, high], 95 %, from the tyres' stiffness uncertainty (:func:`_mode_intervals`)
    natural_frequency_intervals_Hz: dict = field(default_factory=dict)
    #: With ``ride(..., with_signals=True)``: speed (km/h) -> the seat's predicted record, raw-format channel
    #: name (``seat_z_m_s2``, ``seat_x_m_s2``, ``floor_z_m_s2``, ``floor_x_m_s2``) -> samples at ``FS_HZ`` from
    #: the front axle's entry on the track
    signals: dict = field(default_factory=dict)


def _record_window(track: Track, wheelbase_m: float, v: float, duration_s: float | None) -> tuple[int, int]:
    """First and one-past-last sample of the record: the front axle on the track."""
    start = int(math.ceil((track.lead_in_m - wheelbase_m) / (v * DT_S))) if track.lead_in_m > wheelbase_m else 0
    length = track.length_m / v if duration_s is None else min(duration_s, track.length_m / v)
    return start, start + int(round(length / DT_S))


def _mode_intervals(tr: Tractor, u_front_tyre_kN_per_m: float, u_rear_tyre_kN_per_m: float) -> dict:
    """95 % intervals of the bounce and pitch frequencies from the tyre stiffness uncertainties.

    First order as :func:`tyrelab.vehicle.bounce_pitch.frequency_uncertainty`
    (central differences, independent axles, ``f ± 1.96 u``); an axle is two tyres.
    """
    base, _ = _modes(tr)
    var = dict.fromkeys(base, 0.0)
    for attr, u in (("front_stiffness_N_per_m", 2e3 * u_front_tyre_kN_per_m),
                    ("rear_stiffness_N_per_m", 2e3 * u_rear_tyre_kN_per_m)):
        if not u > 0:
            continue
        k = getattr(tr, attr)
        up, _ = _modes(dataclasses.replace(tr, **{attr: 1.01 * k}))
        down, _ = _modes(dataclasses.replace(tr, **{attr: 0.99 * k}))
        for m in var:
            var[m] += ((up[m] - down[m]) / (0.02 * k) * u) ** 2
    return {m: [base[m] - 1.96 * math.sqrt(var[m]), base[m] + 1.96 * math.sqrt(var[m])] for m in base}


def _modes(tr: Tractor) -> tuple[dict, dict]:
    modes = bounce_pitch.mode_shapes(tr.mass_kg, tr.pitch_inertia_kg_m2, tr.front_distance_m, tr.rear_distance_m,
                                     tr.front_stiffness_N_per_m, tr.rear_stiffness_N_per_m)
    return ({k: modes[k]["frequency_Hz"] for k in ("bounce", "pitch")},
            {k: modes[k]["nodal_point_ahead_of_cg_m"] for k in ("bounce", "pitch")})


def ride(scenario: Scenario, build: Path | None = None, with_spectra: bool = True,
         with_signals: bool = False) -> RideResult:
    """Simulate a scenario at every speed and evaluate the seat vibration.

    Parameters
    ----------
    scenario : Scenario
    build : Path, optional
        Build folder whose warehouse holds measured tyres (``measured_tyre_id``).
    with_spectra : bool
        Also compute seat PSDs and transmissibilities (for figures).
    with_signals : bool
        Also keep the seat's predicted records (:attr:`RideResult.signals`), e.g. to compare
        with a recording (:mod:`tyrelab.vehicle.ride_validation`).

    Returns
    -------
    RideResult
    """
    tyres = resolve_tyres(scenario, build)
    track = build_profile(scenario)
    seat = scenario.seat
    seat_ss = seat_filter(seat.natural_frequency_Hz, seat.damping_ratio) if seat.suspension == "linear" else None
    hours = scenario.exposure.hours_per_day
    wb = scenario.tractor.wheelbase_m
    radii = (tyres["front"].radius_m, tyres["rear"].radius_m)
    f_grid = np.geomspace(*FIGURE_BAND_HZ, 300)
    rows, spectra, trans, signals = [], [], [], {}
    warnings = [f"tyres.{ax}: {w}" for ax in ("front", "rear") for w in tyres[ax].warnings]
    speeds = scenario.exposure.speeds_km_h
    runs = []  # per speed: tractor, window, footprints, state space, outputs, method, lift-off flags
    for i, speed in enumerate(speeds):
        v = speed / 3.6
        tr = build_tractor(scenario, tyres, i)
        start, stop = _record_window(track, wb, v, scenario.simulation.duration_s)
        fp = (float(tyres["front"].footprint_m[i]), float(tyres["rear"].footprint_m[i]))
        uf, udf, ur, udr = axle_inputs(track.profile, scenario.surface.enveloping, fp, radii, v, wb, stop)
        ss = state_space(tr, seat.ahead_of_cg_m, seat.height_above_cg_m)
        y = simulate_state_space(*ss, np.vstack([uf[::2], udf[::2], ur[::2], udr[::2]]), outputs=(0, 1, 5, 6))
        w_static = _static_axle_loads(tr)
        off = np.vstack([y[2] <= -w_static[0], y[3] <= -w_static[1]])
        runs.append({"tr": tr, "v": v, "start": start, "stop": stop, "fp": fp, "ss": ss, "y": y[:2], "off": off,
                     "method": "linear"})
    # runs whose tyres would pull: the nonlinear model, batched (vectorised over runs as simulate_tractor is)
    redo = [k for k, r in enumerate(runs) if scenario.simulation.lift_off and r["off"][:, r["start"]:r["stop"]].any()]
    if redo:
        n_max = max(runs[k]["stop"] for k in redo)
        inputs = [axle_inputs(track.profile, scenario.surface.enveloping, runs[k]["fp"], radii, runs[k]["v"], wb, n_max)
                  for k in redo]
        params = {f: np.array([float(getattr(runs[k]["tr"], f)) for k in redo]) for f in PARAMETERS}
        sim = simulate_tractor(Tractor(**params, longitudinal_model=scenario.tractor.longitudinal_model),
                               *[np.array([inp[j] for inp in inputs]) for j in range(4)], DT_S, lift_off=True,
                               method="auto")  # exact in contact, RK4 across the lift-off intervals (as the ch. 7 study)
        for row_i, k in enumerate(redo):
            r = runs[k]
            vert, pitch, lon = (sim[c][row_i, :r["stop"]] for c in ("vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2"))
            r["y"] = np.vstack([vert + seat.ahead_of_cg_m * pitch, lon - seat.height_above_cg_m * pitch])
            r["off"] = _lift_off_from_accelerations(r["tr"], vert, pitch, lon)
            r["method"] = "nonlinear (tyre lift-off)"
    nat, nodal = _modes(runs[0]["tr"])
    nat_ci = _mode_intervals(runs[0]["tr"], tyres["front"].stiffness_u_kN_per_m, tyres["rear"].stiffness_u_kN_per_m)
    for i, (speed, r) in enumerate(zip(speeds, runs)):
        v, start, stop, fp, method = r["v"], r["start"], r["stop"], r["fp"], r["method"]
        a_m, b_m, c_m, d_m = r["ss"]
        lift = tuple(float(o[start:stop].mean()) for o in r["off"])
        seat_z = r["y"][0]
        if seat_ss is not None:
            seat_z = simulate_state_space(*seat_ss, seat_z[None, :])[0]
        z, x = seat_z[start:stop], r["y"][1][start:stop]
        if with_signals:  # the cab floor beneath the seat: before the seat suspension (the model's seat x has none)
            signals[float(speed)] = {"seat_z_m_s2": z, "seat_x_m_s2": x, "floor_z_m_s2": r["y"][0][start:stop],
                                     "floor_x_m_s2": x}
        wz = iso2631.weighted_signal(z, FS_HZ, "Wk")
        wx = iso2631.weighted_signal(x, FS_HZ, "Wd")
        a_wz, a_wx = float(np.sqrt(np.mean(wz**2))), float(np.sqrt(np.mean(wx**2)))
        vdv_z = iso2631.vibration_dose_value(wz, FS_HZ)
        vdv_x = iso2631.AXIS_FACTOR["x"] * iso2631.vibration_dose_value(wx, FS_HZ)
        duration = z.size / FS_HZ
        vdv = max(vdv_z, vdv_x)
        # frequency-domain path: linear model, ground spectrum, enveloping and delay
        n_s, g_s = track.spectrum
        f_s = n_s * v
        keep = f_s <= FS_HZ / 2
        f_s, n_k, s_u = f_s[keep], n_s[keep], g_s[keep] / v
        h = frequency_response(a_m, b_m, c_m, d_m, f_s)
        env = [enveloping_response(scenario.surface.enveloping, fp[j], track.profile.dx_m, n_k) for j in (0, 1)]
        g_resp = ground_response(h, f_s, v, wb, env[0], env[1])
        g_z = g_resp[0] * (_seat_tf(seat_ss, f_s) if seat_ss is not None else 1.0)
        row = {
            "speed_km_h": float(speed),
            "front_pressure_bar": tyres["front"].pressure_bar,
            "rear_pressure_bar": tyres["rear"].pressure_bar,
            "front_stiffness_kN_per_m": float(tyres["front"].stiffness_kN_per_m[i]),
            "rear_stiffness_kN_per_m": float(tyres["rear"].stiffness_kN_per_m[i]),
            "front_damping_kN_s_per_m": float(tyres["front"].damping_kN_s_per_m[i]),
            "rear_damping_kN_s_per_m": float(tyres["rear"].damping_kN_s_per_m[i]),
            "a_wz_m_s2": a_wz,
            "a_wx_m_s2": a_wx,
            "expected_a_wz_m_s2": expected_rms(g_z, f_s, s_u, "Wk"),
            "expected_a_wx_m_s2": expected_rms(g_resp[1], f_s, s_u, "Wd"),
            "vdv_m_s1_75": vdv,
            "vdv_daily_m_s1_75": float(vdv * (hours * 3600.0 / duration) ** 0.25),
            "crest_factor": iso2631.crest_factor(wz),
            "lift_off_fraction_front": lift[0],
            "lift_off_fraction_rear": lift[1],
            **exposure(a_wz, a_wx, hours),
            "hours_per_day": hours,
            "duration_s": duration,
            "simulation": method,
        }
        if duration < MIN_VERDICT_DURATION_S:
            warnings.append(f"{speed:g} km/h: the seat record is {duration:.2f} s, shorter than "
                            f"{MIN_VERDICT_DURATION_S:g} s: too short for a reliable exposure verdict "
                            "(lengthen surface.length_m or simulation.duration_s)")
        rows.append(row)
        if with_spectra:
            fz, pz = mt.acceleration_psd(z, FS_HZ, 0.1)
            fx_, px = mt.acceleration_psd(x, FS_HZ, 0.1)
            band = (fz >= FIGURE_BAND_HZ[0]) & (fz <= FIGURE_BAND_HZ[1])
            spectra.append(pd.DataFrame({"speed_km_h": float(speed), "frequency_Hz": fz[band],
                                         "seat_vertical_psd_m2_s4_per_Hz": pz[band],
                                         "seat_longitudinal_psd_m2_s4_per_Hz": px[band]}))
            hg = ground_response(frequency_response(a_m, b_m, c_m, d_m, f_grid), f_grid, v, wb)
            w2 = (2 * math.pi * f_grid) ** 2
            tz = hg[0] * (_seat_tf(seat_ss, f_grid) if seat_ss is not None else 1.0)
            trans.append(pd.DataFrame({"speed_km_h": float(speed), "frequency_Hz": f_grid,
                                       "seat_vertical": np.abs(tz) / w2, "seat_longitudinal_per_m": np.abs(hg[1]) / w2}))
    cols = ["speed_km_h", "frequency_Hz"]
    return RideResult(
        scenario=scenario, tyres=tyres, natural_frequencies_Hz=nat, nodal_points_m=nodal,
        speeds=pd.DataFrame(rows),
        spectra=pd.concat(spectra, ignore_index=True) if spectra else pd.DataFrame(columns=cols),
        transmissibility=pd.concat(trans, ignore_index=True) if trans else pd.DataFrame(columns=cols),
        track_label=track.profile.label, spectrum_source=track.spectrum_source, track_length_m=track.length_m,
        warnings=warnings, natural_frequency_intervals_Hz=nat_ci, signals=signals,
    )


def _static_axle_loads(tr: Tractor) -> np.ndarray:
    """Static front and rear axle loads, N (a dynamic tyre force at minus this is lift-off)."""
    w = float(tr.mass_kg) * GRAVITY_M_S2 / float(tr.wheelbase_m)
    return np.array([w * float(tr.rear_distance_m), w * float(tr.front_distance_m)])


def _lift_off_from_accelerations(tr: Tractor, vert, pitch, lon) -> np.ndarray:
    """Per-step lift-off flags (front, rear) of a nonlinear run, from its accelerations.

    ``M z'' = F_f + F_r``, ``I θ'' = a F_f - b F_r + h F_x`` and ``M x'' = F_x`` give the
    dynamic axle forces; a tyre is off the ground where its force sits at minus the
    static load (the clamp of :func:`~tyrelab.vehicle.tractor.simulate_tractor`).
    """
    m, inertia, h = float(tr.mass_kg), float(tr.pitch_inertia_kg_m2), float(tr.cg_height_m)
    a, b = float(tr.front_distance_m), float(tr.rear_distance_m)
    fx = m * lon
    ff = (b * m * vert + inertia * pitch - h * fx) / (a + b)
    fr = (a * m * vert - inertia * pitch + h * fx) / (a + b)
    w = _static_axle_loads(tr)
    tol = 1e-6 * w
    return np.vstack([ff <= -w[0] + tol[0], fr <= -w[1] + tol[1]])


def _seat_tf(seat_ss, f_Hz) -> np.ndarray:
    return frequency_response(*seat_ss, f_Hz)[0, 0]


def _ride_batch(item: tuple) -> RideResult:
    """Executor task: one scenario variant (module level, picklable)."""
    scenario, build, with_spectra = item
    return ride(scenario, build, with_spectra)


def ride_sweep(
    scenario: Scenario,
    front_pressures_bar=None,
    rear_pressures_bar=None,
    speeds_km_h=None,
    build: Path | None = None,
    executor_ctx=None,
    with_spectra: bool = True,
    max_variants: int | None = None,
    max_samples: int | None = None,
) -> list[RideResult]:
    """:func:`ride` for every front × rear pressure pair (the scenario's own when not given).

    Parameters
    ----------
    scenario : Scenario
    front_pressures_bar, rear_pressures_bar : sequence of float, optional
        Default: the scenario's ``[sweep]``, else its tyres' pressures.
    speeds_km_h : sequence of float, optional
        Override the scenario's speeds.
    max_variants, max_samples : int, optional
        Bounds of the work (:mod:`tyrelab.vehicle.scenario_limits`; default its ``MAX_VARIANTS``,
        ``MAX_SAMPLES``): more is refused with a ValueError giving the estimate, before any work.
    build : Path, optional
        Warehouse of measured tyres.
    executor_ctx : object, optional
        Anything with ``executor``, ``jobs``, ``scheduler`` (a
        :class:`tyrelab.stages.base.Context`): the variants run through
        :func:`tyrelab.executor.map_batches` (local pool or Dask). Default: in-process.

    Returns
    -------
    list of RideResult
        In front-major order of the pairs.
    """
    from ..executor import map_batches

    fronts = list(front_pressures_bar or scenario.sweep.front_pressures_bar or [scenario.front.pressure_bar])
    rears = list(rear_pressures_bar or scenario.sweep.rear_pressures_bar or [scenario.rear.pressure_bar])
    from . import scenario_limits as limits

    bad = limits.override_problems(speeds_km_h, front_pressures_bar, rear_pressures_bar)
    if bad:
        raise ValueError("; ".join(bad))
    too_much = limits.work_problems(scenario, len(fronts) * len(rears), speeds_km_h,
                                    max_variants=max_variants or limits.MAX_VARIANTS,
                                    max_samples=max_samples or limits.MAX_SAMPLES)
    if too_much:  # before any work (the pairs are not even built)
        raise ValueError("; ".join(too_much))
    variants = [with_overrides(scenario, speeds_km_h, pf, pr_) for pf in fronts for pr_ in rears]
    items = [(v, build, with_spectra) for v in variants]
    if executor_ctx is None or len(items) == 1:
        return [_ride_batch(i) for i in items]
    return map_batches(_ride_batch, items, executor_ctx)


def _clean(v):
    if isinstance(v, (np.floating, float)):
        return None if not math.isfinite(float(v)) else round(float(v), 6)
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.bool_):
        return bool(v)
    return v


def _tyre_json(t: AxleTyres) -> dict:
    return {
        "size": t.size, "pressure_bar": t.pressure_bar,
        "stiffness_kN_per_m": _clean(t.stiffness_kN_per_m[0]), "damping_kN_s_per_m": _clean(t.damping_kN_s_per_m[0]),
        "stiffness_source": t.stiffness_source, "damping_source": t.damping_source,
        "rolling_radius_m": _clean(t.radius_m), "footprint_m": _clean(t.footprint_m[0]), "warnings": list(t.warnings),
        "stiffness_u_kN_per_m": _clean(t.stiffness_u_kN_per_m),
    }


def result_json(results: list[RideResult]) -> dict:
    """The ``tyrelab ride`` JSON: the first pressure pair at the top, every pair under ``sweep``.

    Top-level keys: ``name``, ``scenario``, ``track``, ``spectrum_source``,
    ``hours_per_day``, ``tyres`` (``front``/``rear``: size, pressure, stiffness and
    damping per tyre at the first speed, their sources, radius, footprint,
    warnings, ``stiffness_u_kN_per_m``), ``natural_frequencies_Hz`` (``bounce``, ``pitch``)
    and ``natural_frequencies_Hz_ci95`` (their 95 % intervals from the tyre stiffness uncertainty),
    ``nodal_points_m`` (ahead of the CG), ``speeds`` (one object per speed:
    ``speed_km_h``, pressures and tyre values used, ``a_wz_m_s2`` (W_k),
    ``a_wx_m_s2`` (W_d), ``expected_a_wz_m_s2``/``expected_a_wx_m_s2`` (frequency
    domain), ``a_v_m_s2`` (k = 1.4 on x), ``vdv_m_s1_75``, ``vdv_daily_m_s1_75``,
    ``crest_factor``, ``lift_off_fraction_front``/``_rear``, ``a8_m_s2``,
    ``hours_to_eav``, ``hours_to_elv``, ``verdict``, ``duration_s``,
    ``simulation``), ``warnings`` and, for more than one pressure pair, ``sweep``
    (one object per pair with ``front_pressure_bar``, ``rear_pressure_bar``,
    ``tyres``, ``natural_frequencies_Hz``, ``nodal_points_m``, ``speeds``).
    """
    def block(r: RideResult) -> dict:
        return {
            "tyres": {ax: _tyre_json(r.tyres[ax]) for ax in ("front", "rear")},
            "natural_frequencies_Hz": {k: _clean(v) for k, v in r.natural_frequencies_Hz.items()},
            "natural_frequencies_Hz_ci95": {k: [_clean(x) for x in v] for k, v in r.natural_frequency_intervals_Hz.items()},
            "nodal_points_m": {k: _clean(v) for k, v in r.nodal_points_m.items()},
            "speeds": [{k: _clean(v) for k, v in row.items()} for row in r.speeds.to_dict(orient="records")],
        }

    first = results[0]
    sc = first.scenario
    out = {"name": sc.name, "scenario": str(sc.path) if sc.path else None, "track": first.track_label,
           "spectrum_source": first.spectrum_source, "hours_per_day": sc.exposure.hours_per_day, **block(first),
           "warnings": sorted({w for r in results for w in r.warnings})}
    if len(results) > 1:
        out["sweep"] = [{"front_pressure_bar": r.tyres["front"].pressure_bar,
                         "rear_pressure_bar": r.tyres["rear"].pressure_bar, **block(r)} for r in results]
    return out


def results_table(results: list[RideResult], scenario_id: str | None = None) -> pd.DataFrame:
    """One row per speed × pressure pair (the ``ride_results`` layout).

    ``is_nominal`` marks the pair of the scenario's own tyre pressures.
    """
    frames = []
    for r in results:
        df = r.speeds.copy()
        df.insert(0, "scenario", scenario_id or r.scenario.name)
        df["bounce_Hz"] = r.natural_frequencies_Hz["bounce"]
        df["pitch_Hz"] = r.natural_frequencies_Hz["pitch"]
        df["front_stiffness_source"] = r.tyres["front"].stiffness_source
        df["rear_stiffness_source"] = r.tyres["rear"].stiffness_source
        frames.append(df)
    return pd.concat(frames, ignore_index=True)


# --------------------------------------------------------------------------- pipeline
def scenario_files(raw: Path | None) -> list[tuple[str, str]]:
    """``(path, source)`` of every shipped scenario and every ``<raw>/scenarios/*.toml``.

    A file of ``raw`` with the same bytes as a shipped one (the repository's own
    ``raw/`` folder) is listed once, as shipped.
    """
    from .. import resources

    shipped = sorted(resources.scenarios_dir().glob("*.toml"))
    seen = {p.read_bytes() for p in shipped}
    out = [(str(p), "shipped") for p in shipped]
    folder = Path(raw) / "scenarios" if raw is not None else None
    for p in sorted(folder.glob("*.toml")) if folder is not None and folder.is_dir() else []:
        if p.is_file() and p.read_bytes() not in seen:  # a named pipe is skipped (the raw walk warns of it)
            out.append((str(p), "raw"))
    return out


def scenario_items(files: list[tuple[str, str]], build: Path | None = None) -> list[tuple]:
    """The executor items of :func:`run_scenarios`, one per ``(path, source)`` of ``files``: run each
    with :func:`scenario_task` (in any process) and hand the results, in order, to
    :func:`collect_scenarios` (the simulate stage runs them beside its studies this way)."""
    return [(p, src, str(build) if build else None) for p, src in files]


def scenario_task(item: tuple) -> dict:
    """Executor task of the simulate stage: one scenario file, every pressure pair of its sweep."""
    from .scenario import ScenarioError, load_scenario

    path, source, build = item
    try:
        sc = load_scenario(path)
        results = ride_sweep(sc, build=Path(build) if build else None, with_spectra=False)
        # the scenario row's modes are those at the scenario's own pressures, which a [sweep] need not
        # list first, or at all: from the nominal pair's result, else from the nominal tyres
        nominal = [r for r in results if r.tyres["front"].pressure_bar == sc.front.pressure_bar
                   and r.tyres["rear"].pressure_bar == sc.rear.pressure_bar]
        nat, nodal = ((nominal[0].natural_frequencies_Hz, nominal[0].nodal_points_m) if nominal else
                      _modes(build_tractor(sc, resolve_tyres(sc, Path(build) if build else None), 0)))
    except (ScenarioError, ValueError) as exc:
        return {"file": path, "error": str(exc).replace("\n", "; ")}
    except (ArithmeticError, MemoryError, RecursionError) as exc:  # the model failed: this scenario only
        return {"file": path, "error": f"the ride model failed: {type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}"}
    table = results_table(results, sc.name)
    table["file"] = path  # rows are keyed by the scenario file: two files may share a name
    table["is_nominal"] = (table["front_pressure_bar"] == sc.front.pressure_bar) & \
        (table["rear_pressure_bar"] == sc.rear.pressure_bar)
    s = sc.surface
    row = {
        "scenario": sc.name, "file": path, "source": source, "description": sc.description,
        "mass_kg": sc.tractor.mass_kg, "pitch_inertia_kg_m2": sc.tractor.pitch_inertia_kg_m2,
        "front_distance_m": sc.tractor.front_distance_m, "rear_distance_m": sc.tractor.rear_distance_m,
        "cg_height_m": sc.tractor.cg_height_m, "longitudinal_model": sc.tractor.longitudinal_model,
        "seat_ahead_of_cg_m": sc.seat.ahead_of_cg_m, "seat_height_above_cg_m": sc.seat.height_above_cg_m,
        "seat_suspension": sc.seat.suspension,
        "front_size": sc.front.size, "front_pressure_bar": sc.front.pressure_bar,
        "rear_size": sc.rear.size, "rear_pressure_bar": sc.rear.pressure_bar,
        "surface": s.kind, "road_class": s.road_class, "track": results[0].track_label,
        "track_length_m": results[0].track_length_m,
        "seed": s.seed, "enveloping": s.enveloping,
        "speeds_km_h": ", ".join(f"{v:g}" for v in sc.exposure.speeds_km_h), "hours_per_day": sc.exposure.hours_per_day,
        "bounce_Hz": nat["bounce"], "pitch_Hz": nat["pitch"],
        "bounce_nodal_point_m": nodal["bounce"], "pitch_nodal_point_m": nodal["pitch"],
        "pressure_pairs": len(results), "warnings": "; ".join(sorted({w for r in results for w in r.warnings})),
    }
    return {"file": path, "scenario": row, "results": table}


def run_scenarios(files: list[tuple[str, str]], ctx=None, build: Path | None = None) -> tuple[pd.DataFrame, pd.DataFrame, list[dict]]:
    """Run scenario files (through :func:`tyrelab.executor.map_batches` when ``ctx`` is given).

    Returns
    -------
    ride_scenarios, ride_results : DataFrame
        One row per scenario; one row per scenario × speed × pressure pair.
    problems : list of dict
        ``file`` and ``reason`` of every scenario refused (the others still run).
    """
    from ..executor import map_batches

    items = scenario_items(files, build)
    return collect_scenarios(map_batches(scenario_task, items, ctx) if ctx is not None else [scenario_task(i) for i in items])


def collect_scenarios(outputs: list[dict]) -> tuple[pd.DataFrame, pd.DataFrame, list[dict]]:
    """The tables of :func:`run_scenarios` from the results of :func:`scenario_task`, in order."""
    ok = [o for o in outputs if "error" not in o]
    problems = [{"file": o["file"], "reason": o["error"]} for o in outputs if "error" in o]
    scenarios = pd.DataFrame([o["scenario"] for o in ok])
    results = pd.concat([o["results"] for o in ok], ignore_index=True) if ok else pd.DataFrame()
    return scenarios, results, problems
