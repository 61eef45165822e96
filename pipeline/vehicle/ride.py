"""Ride prediction for any tractor: the operator's daily vibration exposure (issue 13).

A :class:`~tyrelab.vehicle.scenario.Scenario` (tractor, tyres, seat, track, speeds)
becomes, per speed and per front/rear pressure pair, the seat's ISO 2631-1
weighted accelerations and the EU Directive 2002/44/EC daily exposure:

1. **Tyres** (:func:`resolve_tyres`): stiffness and damping per tyre and speed,
   from an override, a measured tyre of the warehouse (``K = K_c + ΔK_p P`` and
   ``C = C_c + ΔC P`` per speed, tables ``stiffness_pressure_by_speed`` /
   ``damping_pressure_by_speed``; below the first rolling speed the rolling value,
   :func:`tyrelab.tyre.speed_dependence.at_speeds`) or the fitted formula (§4.5.3,
   §8.2; ``[tyres.*] formula``: the thesis' or the build's); damping without either
   from the model fitted to the thesis' Table VII lines (:mod:`tyrelab.tyre.damping_fit`).
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
import itertools
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd
from scipy import signal

from .. import _validate
from .._validate import positive
from . import crg
from . import road_class as rc
from . import enveloping as ev
from . import iso2631
from . import spectral_ride
from . import lti
from . import metrics as mt
from . import profiles as pr
from .scenario import Scenario, ScenarioError, with_overrides, with_values
from .carriage import half_step_input
from .model import Assembly, Parts, SeatPoint, SeatSuspension, assemble
from .tractor import Tractor, simulate, tractor_parts
from .units import KILO, from_kilo, to_kilo
from .tyres import AxleTyres, ShippedTyres, _resolve, build_parts, build_tractor, per_speed, resolve_tyres  # noqa: F401 (their old home)
from .tyres import _damping_fit, _formula_stiffness, _lateral_tyre, _model_damping, _thesis_stiffness_model  # noqa: F401
from .scenario_limits import MIN_VERDICT_DURATION_S
from .daily_exposure import governing_axis
from .modes import LATERAL_ROLL_SHARE, MODE_NAMES, ModeSet, follow_names, frequency_intervals, mode_set  # noqa: F401 (names: their old home)

__all__ = [
    "OUTPUTS",
    "AxleTyres",
    "Track",
    "RideResult",
    "per_speed",
    "resolve_tyres",
    "ShippedTyres",
    "build_tractor",
    "build_parts",
    "tyre_inputs",
    "state_names",
    "state_space",
    "simulate_state_space",
    "seat_filter",
    "frequency_response",
    "ground_response",
    "enveloping_response",
    "build_profile",
    "crg_profile",
    "road_classes",
    "axle_inputs",
    "exposure",
    "expected_rms",
    "seat_axes",
    "modes",
    "input_cross_spectra",
    "ride",
    "ride_variants",
    "RideCache",
    "ride_sweep",
    "spectral_variants",
    "expected_weighted_rms",
    "expected_sweep",
    "result_json",
    "results_table",
    "VERDICTS",
]

#: Simulation step of the ride, s (the ch. 7 study's).
DT_S = 1e-3
FS_HZ = 1.0 / DT_S
#: Steps across a stand-in lateral stiffness' interval for :func:`_lateral_interval` (odd: the middle is the stand-in).
LATERAL_INTERVAL_STEPS = 9
#: Outputs of :func:`state_space`, in row order.
OUTPUTS = ("seat_vertical_m_s2", "seat_longitudinal_m_s2", "vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2",
           "front_force_N", "rear_force_N")
#: Verdicts against the Directive's daily values (A(8) at hours_per_day).
VERDICTS = ("below action value", "above action value", "above limit value")
#: Frequency range of the seat PSD and transmissibility figures, Hz.
FIGURE_BAND_HZ = (0.2, 20.0)


# --------------------------------------------------------------------------- linear model
def state_names(tractor: Tractor) -> list[str]:
    """States of :func:`state_space` for a scalar ``tractor``, in order
    (:meth:`tyrelab.vehicle.model.Assembly.state_names` of its parts).

    ``z, θ`` ("th"), ``x`` (Kelvin-Voigt with ``k_x > 0`` only), ``z', θ'`` ("vz", "vth"),
    ``x'`` ("vx", any longitudinal element) and ``q = d - s`` (Maxwell). A Maxwell element
    without spring or damper carries no force and adds no state.

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


def seat_filter(natural_frequency_Hz: float, damping_ratio: float):
    """Base-excited single-DOF seat: ``(A, B, C, D)`` from seat-base to seat acceleration.

    ``T(s) = (2 ζ ω s + ω²) / (s² + 2 ζ ω s + ω²)``, the transmissibility of a seat
    on a linear spring and damper; it maps base acceleration to seat acceleration.
    """
    wn = 2 * math.pi * positive("natural_frequency_Hz", natural_frequency_Hz)
    z = float(damping_ratio)
    if not (math.isfinite(z) and z >= 0):
        raise ValueError(f"damping_ratio must be finite and non-negative, got {damping_ratio!r}")
    return SeatSuspension(natural_frequency_Hz, damping_ratio).linear().abcd


def frequency_response(a, b, c, d, frequency_Hz) -> np.ndarray:
    """Complex response ``C (jω I - A)⁻¹ B + D`` of every output to every input.

    Computed modally (``A = V Λ V⁻¹``), vectorised over frequencies.

    Returns
    -------
    ndarray, shape (p, m, n_f)
    """
    _validate.non_negative_array("frequency_Hz", frequency_Hz)
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
    _validate.choice("kind", kind, ("none", "fixed", "tapered", "rigid_band"))
    _validate.non_negative("footprint_m", footprint_m)
    positive("dx_m", dx_m)
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
    positive("speed_m_s", speed_m_s)
    _validate.non_negative("wheelbase_m", wheelbase_m)
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
    #: (n cycles/m, G_LL, G_RR, G_LR m³): the two tracks' spectra and cross-spectrum (3-D model).
    side_spectrum: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None
    #: A profile or CRG road's ISO 8608 class per wheel track (:func:`road_classes`), else empty.
    road_classes: dict = field(default_factory=dict)


def build_profile(scenario: Scenario) -> Track:
    """Generate or read the scenario's track, add the lead-in, describe its spectrum."""
    _validate.instance("scenario", scenario, Scenario)
    s = scenario.surface
    lead = max(s.lead_in_m, scenario.tractor.wheelbase_m + 1.0)
    side = None
    width = _track_width_m(scenario)
    if s.kind == "iso8608":
        prof = pr.iso8608_track(s.road_class, seed=s.seed, length_m=s.length_m, dx_m=s.dx_m, tracks=s.tracks,
                                track_width_m=width)
        n = np.geomspace(0.011, 2.83, 4000)
        g_one = pr.ISO8608_CLASS_G0_M3[s.road_class] * (n / pr.ISO8608_N0_CYCLES_PER_M) ** -2.0
        rho = {"independent": np.zeros_like(n), "identical": np.ones_like(n)}.get(s.tracks)
        if rho is None:
            rho = pr.isotropic_coherence(n, width)
        if s.tracks == "independent":
            g = 0.5 * g_one  # as before: the mean of two independent tracks
        else:
            g = 0.5 * (1.0 + rho) * g_one
        side = (n, g_one, g_one, rho * g_one)
        words = (f"isotropic surface, left/right coherence 2 pi n b K1(2 pi n b), b = {width:g} m (Dodds & Robson 1973)"
                 if s.tracks == "isotropic" else f"{s.tracks} left/right")
        spectrum, source = (n, g), f"ISO 8608 class {s.road_class} (geometric mean), {words}"
    elif s.kind == "slatted":
        prof = pr.slatted_track(seed=s.seed, length_m=s.length_m)
        spectrum, source = None, ""
    elif s.kind == "crg":
        prof = crg_profile(scenario)
        spectrum, source = None, ""
    else:
        if s.profile_data is None:
            raise ValueError(f"surface.profile {s.profile}: its data were not read (read scenarios with "
                             "tyrelab.scenario_io.load_scenario or parse_scenario)")
        x, left, right = s.profile_data
        grid, (left_u, right_u) = pr.uniform_grid(x, left, right)
        prof = pr.Profile(grid - grid[0], left_u, right_u, f"profile {Path(s.profile).name}", {"kind": "profile"})
        spectrum, source = None, ""
        if s.spectrum_g0_m3 is not None:
            correlated = s.spectrum_correlated if s.spectrum_correlated is not None else bool(np.array_equal(left, right))
            length = prof.x_m[-1]
            n = np.geomspace(1.0 / length, 0.5 / prof.dx_m, 4000)
            g = s.spectrum_g0_m3 * (n / pr.ISO8608_N0_CYCLES_PER_M) ** -s.spectrum_waviness * (1.0 if correlated else 0.5)
            spectrum = (n, g)
            g_one = s.spectrum_g0_m3 * (n / pr.ISO8608_N0_CYCLES_PER_M) ** -s.spectrum_waviness
            side = (n, g_one, g_one, g_one * (1.0 if correlated else 0.0))
            source = f"declared G_d(n0) = {s.spectrum_g0_m3:g} m^3, w = {s.spectrum_waviness:g}"
    if spectrum is None:  # the track's own spectrum (Welch) of the axle-mean elevation
        mean = prof.track("mean")
        seg = min(51.2, prof.x_m[-1] / 4)
        n_w, g_w = pr.profile_spectrum(mean, prof.dx_m, seg)
        keep = (n_w > 0) & (g_w > 0)
        if keep.sum() >= 2:
            n = np.geomspace(n_w[keep][0], n_w[keep][-1], 4000)
            g = np.exp(np.interp(np.log(n), np.log(n_w[keep]), np.log(g_w[keep])))
        else:  # a flat axle mean (left and right in anti-phase, or a flat track): no axle-mean input
            n, g = np.geomspace(n_w[1], n_w[-1], 4000), np.zeros(4000)
        spectrum, source = (n, g), "the track's own Welch spectrum (axle mean)"
    if side is None and scenario.tractor.three_d:  # the tracks' own spectra and cross-spectrum (Welch)
        seg = min(51.2, prof.x_m[-1] / 4)
        nper = max(8, int(round(seg / prof.dx_m)))
        n_w, g_ll = signal.welch(prof.left_m, 1.0 / prof.dx_m, nperseg=nper)
        _, g_rr = signal.welch(prof.right_m, 1.0 / prof.dx_m, nperseg=nper)
        # the model's S_LR is E[L R*] (the output spectrum is h S h^H); scipy.signal.csd(x, y)
        # averages conj(X) Y, i.e. E[L* R]: hence csd(right, left) (field notes)
        _, g_lr = signal.csd(prof.right_m, prof.left_m, 1.0 / prof.dx_m, nperseg=nper)
        keep = n_w > 0
        side = (n_w[keep], g_ll[keep], g_rr[keep], g_lr[keep])
        source = "the tracks' own Welch spectra and cross-spectrum"
    length = float(prof.x_m[-1])
    classes = road_classes(prof) if s.kind in ("profile", "crg") else {}
    return Track(pr.add_lead_in(prof, lead), float(round(lead / prof.dx_m) * prof.dx_m), length, spectrum, source, side,
                 classes)


def road_classes(profile: pr.Profile) -> dict:
    """ISO 8608 class of each wheel track of ``profile`` (:func:`tyrelab.vehicle.road_class.road_class`):
    ``left``, ``right`` (one ``track`` when they are the same) and, where the rear wheels have their
    own tracks, ``rear_left``, ``rear_right``."""
    _validate.instance("profile", profile, pr.Profile)
    tracks = {"left": profile.left_m, "right": profile.right_m}
    if np.array_equal(profile.left_m, profile.right_m):
        tracks = {"track": profile.left_m}
    if profile.rear_left_m is not None:
        tracks.update({"rear_left": profile.rear_left_m, "rear_right": profile.rear_right_m})
    return {name: rc.road_class(h, profile.dx_m) for name, h in tracks.items()}


def crg_profile(scenario: Scenario) -> pr.Profile:
    """The wheels' tracks on the scenario's CRG road (:mod:`tyrelab.vehicle.crg`): the front wheels'
    lines as the profile's left and right, the rear wheels' as its rear tracks (3-D, when their
    track width differs from the front's)."""
    _validate.instance("scenario", scenario, Scenario)
    s = scenario.surface
    if s.crg_data is None:
        raise ValueError(f"surface.file {s.file}: its road was not read (read scenarios with "
                         "tyrelab.scenario_io.load_scenario or parse_scenario)")
    pos = s.wheel_positions(scenario.tractor)
    x, h = crg.wheel_tracks(s.crg_data, pos, s.start_m, s.length_m, s.fill_missing)
    same = pos["rear_left"] == pos["front_left"] and pos["rear_right"] == pos["front_right"]
    where = (f"v = {pos['front_left']:+g}/{pos['front_right']:+g} m front, {pos['rear_left']:+g}/{pos['rear_right']:+g} m rear"
             if not same else f"v = {pos['front_left']:+g}/{pos['front_right']:+g} m")
    return pr.Profile(x, h["front_left"], h["front_right"],
                      f"CRG road {s.crg_data.name}, {s.start_m:g}-{s.start_m + x[-1]:g} m, wheels at {where}",
                      {"kind": "crg", "file": s.crg_data.name, "wheel_v_m": pos},
                      None if same else h["rear_left"], None if same else h["rear_right"])


def _track_width_m(scenario: Scenario) -> float | None:
    """Distance between the two wheel tracks: the mean of the front and rear track widths (3-D), m."""
    t = scenario.tractor
    return 0.5 * (t.front_track_m + t.rear_track_m) if t.three_d else None


def _envelope_side(track: pr.Profile, side: str, kind: str, footprint_m: float, radius_m: float,
                   axle: str = "front") -> np.ndarray:
    """One wheel track's enveloped elevation (under ``axle``'s wheels: :meth:`Profile.track`)."""
    dx = track.dx_m
    h = track.track(side, axle)
    if kind == "tapered":
        h = ev.tapered_moving_average(h, dx, footprint_m)
    elif kind == "fixed":
        h = ev.fixed_footprint(h, dx, footprint_m)
    elif kind == "rigid_band":
        h = ev.rigid_tread_band(h, dx, radius_m)
    return h


def _envelope(track: pr.Profile, kind: str, footprint_m: float, radius_m: float) -> np.ndarray:
    """Axle-mean enveloped elevation (left and right enveloped, then averaged, as the ch. 7 study)."""
    out = [_envelope_side(track, side, kind, footprint_m, radius_m) for side in ("left", "right")]
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
    _validate.instance("track", track, pr.Profile)
    positive("speed_m_s", speed_m_s)
    _validate.positive_int("n_steps", n_steps)
    hf = _envelope(track, kind, footprints[0], radii[0])
    hr = hf if (footprints[0] == footprints[1] and radii[0] == radii[1]) or kind == "none" else \
        _envelope(track, kind, footprints[1], radii[1])
    uf, udf = half_step_input(track.x_m, hf, speed_m_s, n_steps, wheelbase_m, DT_S)
    ur, udr = half_step_input(track.x_m, hr, speed_m_s, n_steps, 0.0, DT_S)
    u0 = 0.5 * (uf[0] + ur[0])
    return uf - u0, udf, ur - u0, udr


def tyre_inputs(asm, track: pr.Profile, kind: str, footprints: tuple[float, float], radii: tuple[float, float],
                speed_m_s: float, wheelbase_m: float, n_steps: int) -> tuple[np.ndarray, np.ndarray]:
    """Ground elevation and rate under each tyre element of ``asm`` at ``dt/2``, shape
    ``(tyres, 2 n_steps - 1)``: the axle-mean input of :func:`axle_inputs` in the pitch plane; in
    3-D each wheel on its own side's track (enveloped with its axle's footprint), the rear one a
    wheelbase later, each side's offset at the start removed."""
    _validate.instance("asm", asm, Assembly)
    positive("speed_m_s", speed_m_s)
    _validate.positive_int("n_steps", n_steps)
    if asm.parts.three_d:
        u, du = {}, {}
        for side in ("left", "right"):
            hf = _envelope_side(track, side, kind, footprints[0], radii[0])
            hr = _envelope_side(track, side, kind, footprints[1], radii[1], "rear")
            u[f"front_{side}"], du[f"front_{side}"] = half_step_input(track.x_m, hf, speed_m_s, n_steps, wheelbase_m, DT_S)
            u[f"rear_{side}"], du[f"rear_{side}"] = half_step_input(track.x_m, hr, speed_m_s, n_steps, 0.0, DT_S)
            u0 = 0.5 * (u[f"front_{side}"][0] + u[f"rear_{side}"][0])
            u[f"front_{side}"], u[f"rear_{side}"] = u[f"front_{side}"] - u0, u[f"rear_{side}"] - u0
        return np.array([u[t] for t in asm.tyres]), np.array([du[t] for t in asm.tyres])
    uf, udf, ur, udr = axle_inputs(track, kind, footprints, radii, speed_m_s, wheelbase_m, n_steps)
    by_axle = {"front": (uf, udf), "rear": (ur, udr)}
    return (np.array([by_axle[t.split("_")[0]][0] for t in asm.tyres]),
            np.array([by_axle[t.split("_")[0]][1] for t in asm.tyres]))


# --------------------------------------------------------------------------- exposure
def exposure(a_wz_m_s2: float, a_wx_m_s2: float, hours_per_day: float, a_wy_m_s2: float = 0.0) -> dict:
    """Daily exposure by EU Directive 2002/44/EC from per-axis weighted r.m.s. values.

    ``A(8) = max(1.4 a_wx, 1.4 a_wy, a_wz) sqrt(T / 8 h)``; hours to reach the action
    (0.5 m/s²) and limit (1.15 m/s²) values ``8 h (value / a_w)²`` with
    ``a_w = max(1.4 a_wx, 1.4 a_wy, a_wz)``; ``a_v`` the ISO 2631-1 vector sum; ``a8_axis`` the
    axis of that maximum (:func:`tyrelab.vehicle.daily_exposure.governing_axis`).

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
    axis = governing_axis(weighted)
    aw = max(weighted.values())
    a8 = iso2631.daily_exposure_a8(aw, hours_per_day)
    hours = (lambda v: 8.0 * (v / aw) ** 2) if aw > 0 else (lambda v: math.inf)
    verdict = VERDICTS[2] if a8 > iso2631.EU_LIMIT_A8_M_S2 else VERDICTS[1] if a8 > iso2631.EU_ACTION_A8_M_S2 else VERDICTS[0]
    return {
        "a_v_m_s2": math.sqrt((k["x"] * a_wx_m_s2) ** 2 + (k["y"] * a_wy_m_s2) ** 2 + (k["z"] * a_wz_m_s2) ** 2),
        "a8_m_s2": a8,
        "a8_axis": axis,
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
    _validate.choice("weighting", weighting, tuple(iso2631.WEIGHTINGS))
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
        ``speed_km_h, frequency_Hz, seat_vertical, seat_longitudinal_per_m`` (``|seat
        acceleration / ground acceleration|``, and fore-aft per unit ground acceleration).
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
    #: mode -> [low, high], 95 %, from the tyres' stiffness uncertainty (:func:`~tyrelab.vehicle.modes.frequency_intervals`;
    #: None where the mode cannot be followed: :attr:`warnings` says why)
    natural_frequency_intervals_Hz: dict = field(default_factory=dict)
    #: With ``ride(..., with_signals=True)``: speed (km/h) -> the seat's predicted record, raw-format channel
    #: name (``seat_z_m_s2``, ``seat_x_m_s2``, ``floor_z_m_s2``, ``floor_x_m_s2``; in 3-D also
    #: ``seat_y_m_s2``, ``floor_y_m_s2``) -> samples at ``FS_HZ`` from the front axle's entry on the track
    signals: dict = field(default_factory=dict)
    #: The swept keys' values of this variant (:func:`ride_sweep`), ``{"section.key": value}``.
    variant: dict = field(default_factory=dict)
    #: A profile or CRG road's ISO 8608 class per wheel track (:func:`road_classes`); empty otherwise.
    road_classes: dict = field(default_factory=dict)
    #: 3-D with a stand-in lateral stiffness (issue 33): speed (km/h) -> A(8) (m/s²) with every stand-in
    #: lateral stiffness at the low and at the high end of its 95 % interval (:func:`_lateral_interval`).
    a8_lateral_ci95_m_s2: dict = field(default_factory=dict)
    #: The undamped modes (:class:`~tyrelab.vehicle.modes.ModeSet`) the natural frequencies name.
    modes: ModeSet | None = field(default=None, repr=False)
    #: The variant at the scenario's own values (its tyre pressures and the file's value of every swept
    #: key; :func:`ride_sweep`): the one whose spectra the pages show.
    nominal: bool = True

    #: Of a variant whose ``speeds`` are spectral rows: its time-domain rows where it was simulated too
    #: (``method = "auto"``, :mod:`tyrelab.vehicle.spectral_ride`), else empty.
    time_rows: pd.DataFrame = field(default_factory=pd.DataFrame)

    @property
    def mode_table(self) -> pd.DataFrame:
        """The natural frequencies as a table, one row per mode (:attr:`modes` holds the shapes): ``mode``, ``frequency_Hz``, ``low_Hz``/``high_Hz`` (its 95 %
        interval from the tyre stiffness uncertainty; NaN without one) and ``nodal_point_m``
        (ahead of the CG; NaN for a mode that does not pitch)."""
        rows = []
        for mode, f in self.natural_frequencies_Hz.items():
            lo, hi = self.natural_frequency_intervals_Hz.get(mode) or (None, None)  # None: no interval
            rows.append({"mode": mode, "frequency_Hz": float(f), "low_Hz": math.nan if lo is None else float(lo),
                         "high_Hz": math.nan if hi is None else float(hi),
                         "nodal_point_m": float(self.nodal_points_m.get(mode, math.nan))})
        return pd.DataFrame(rows, columns=["mode", "frequency_Hz", "low_Hz", "high_Hz", "nodal_point_m"])

    def to_dict(self) -> dict:
        """The JSON document of ``tyrelab ride`` for this result (:func:`result_json`)."""
        return result_json([self])

    def to_json(self) -> str:
        """:meth:`to_dict` as JSON text (indented, no NaN: a missing value is ``null``)."""
        import json

        return json.dumps(self.to_dict(), indent=2, ensure_ascii=False, allow_nan=False) + "\n"


def _record_window(track: Track, wheelbase_m: float, v: float, duration_s: float | None) -> tuple[int, int]:
    """First and one-past-last sample of the record: the front axle on the track."""
    start = int(math.ceil((track.lead_in_m - wheelbase_m) / (v * DT_S))) if track.lead_in_m > wheelbase_m else 0
    length = track.length_m / v if duration_s is None else min(duration_s, track.length_m / v)
    return start, start + int(round(length / DT_S))


def modes(asm) -> tuple[dict, dict]:
    """Undamped natural frequencies (Hz) of an assembled tractor, each named by the coordinate
    that moves most (:func:`tyrelab.vehicle.modes.mode_set`: kinetic-energy share,
    :data:`~tyrelab.vehicle.modes.MODE_NAMES`, a second mode of the same name ``_2``), and the
    bounce and pitch modes' nodal points ahead of the CG (m).

    The pitch-plane tractor on rigid axles is thesis §8.2's beam on two springs
    (:func:`tyrelab.vehicle.bounce_pitch.mode_shapes`, the same eigenproblem).
    """
    _validate.instance("asm", asm, Assembly)
    m = mode_set(asm)
    return m.frequencies(), m.nodal()


class RideCache:
    """What the runs of several variants share in one process: the tracks (by surface), each wheel
    track enveloped (by footprint or radius) and the seat filter's discretisation. :func:`ride_sweep`
    passes one to all its variants; a caller running variants one by one may pass its own."""

    def __init__(self):
        self.tracks: dict = {}
        self.enveloped: dict = {}
        self.seat: dict = {}
        #: :func:`resolve_tyres`' memo
        self.tyres: dict = {}

    def track(self, scenario: Scenario) -> tuple[tuple, Track]:
        """(key, :class:`Track`) of ``scenario``'s surface (:func:`build_profile`, once per surface)."""
        t = scenario.tractor
        key = (scenario.surface, t.wheelbase_m, t.three_d, _track_width_m(scenario))
        if key not in self.tracks:
            self.tracks[key] = build_profile(scenario)
        return key, self.tracks[key]

    def envelope(self, key: tuple, track: pr.Profile, side: str, kind: str, footprint_m: float,
                 radius_m: float) -> np.ndarray:
        """One wheel track (``left``, ``right`` or the axle ``mean`` of the two enveloped) enveloped."""
        what = footprint_m if kind in ("tapered", "fixed") else radius_m if kind == "rigid_band" else None
        k = (key, side, kind, what)
        if k not in self.enveloped:
            if side == "mean":
                self.enveloped[k] = 0.5 * (self.envelope(key, track, "left", kind, footprint_m, radius_m)
                                           + self.envelope(key, track, "right", kind, footprint_m, radius_m))
            else:
                self.enveloped[k] = _envelope_side(track, side, kind, footprint_m, radius_m)
        return self.enveloped[k]

    def seat_system(self, seat) -> lti.FohSystem | None:
        """The seat's suspension (a scenario's ``[seat]`` or a :class:`~tyrelab.vehicle.model.SeatSuspension`
        part) discretised at :data:`DT_S` (None for a rigid seat)."""
        part = seat if isinstance(seat, SeatSuspension) else seat.part().suspension
        if part is None:
            return None
        if part not in self.seat:
            self.seat[part] = lti.discretise(*part.linear().abcd, DT_S)
        return self.seat[part]


def ride(scenario: Scenario, tyre_data=None, with_spectra: bool = True,
         with_signals: bool = False, cache: RideCache | None = None) -> RideResult:
    """Simulate a scenario at every speed and evaluate the seat vibration.

    Parameters
    ----------
    scenario : Scenario
    tyre_data : object, optional
        Measured tyres and the stiffness model (:class:`ShippedTyres` by default; a build's
        warehouse through :class:`tyrelab.stages.simulate.WarehouseTyres`).
    with_spectra : bool
        Also compute seat PSDs and transmissibilities (for figures).
    with_signals : bool
        Also keep the seat's predicted records (:attr:`RideResult.signals`), e.g. to compare
        with a recording (:mod:`tyrelab.vehicle.ride_validation`).
    cache : RideCache, optional
        Share tracks, enveloped wheel tracks and the seat filter with other calls.

    Returns
    -------
    RideResult
    """
    _validate.instance("scenario", scenario, Scenario)
    return ride_variants([scenario], tyre_data, with_spectra, with_signals, cache)[0]


def ride_variants(scenarios, tyre_data=None, with_spectra: bool = True, with_signals: bool = False,
                  cache: RideCache | None = None) -> list[RideResult]:
    """:func:`ride` for several scenarios (variants) at once, batched: the runs are taken speed by
    speed, so the wheel inputs of a speed are built once for every variant that shares its track,
    footprints and radii, and a run's record is reduced to its numbers as soon as it is simulated.
    Each result is what :func:`ride` gives for that scenario alone."""
    for k, sc in enumerate(scenarios):
        _validate.instance(f"scenarios[{k}]", sc, Scenario)
    cache = cache or RideCache()
    preps = [_prepare(sc, tyre_data, cache) for sc in scenarios]
    for p in preps:
        p["with_spectra"], p["with_signals"] = with_spectra, with_signals
    groups: dict = {}
    for j, p in enumerate(preps):
        for i, speed in enumerate(p["speeds"]):
            v = speed / 3.6
            start, stop = _record_window(p["track"], p["wb"], v, p["sc"].simulation.duration_s)
            groups.setdefault((p["track_key"], v, start, stop), []).append((j, i))
    for (track_key, v, start, stop), members in groups.items():
        for j, i in members:
            _linear_model(preps[j], i, v, start, stop)
        _expected_batch([(preps[j], i) for j, i in members], v)
        inputs: dict = {}  # wheel input (full steps) -> (u, du), this speed only
        for j, i in members:
            _linear_run(preps[j], i, track_key, inputs, cache)
        del inputs
    for p in preps:
        _redo_lifting(p)
    return [_finish(p) for p in preps]


def _prepare(scenario: Scenario, tyre_data, cache: RideCache) -> dict:
    """Per variant: tyres, track, seat filter, outputs; the runs are filled in by :func:`_linear_run`."""
    tyres, asms = _resolve(scenario, tyre_data, cache.tyres)
    track_key, track = cache.track(scenario)
    axes = seat_axes(scenario)  # axis -> output name
    seat = scenario.seat.part().suspension  # the seat part's filter (no feedback on the tractor)
    return {"sc": scenario, "tyres": tyres, "track": track, "track_key": track_key,
            "wb": scenario.tractor.wheelbase_m, "speeds": scenario.exposure.speeds_km_h, "axes": axes,
            "seat_sys": cache.seat_system(seat) if seat is not None else None,
            "seat_ss": seat.linear().abcd if seat is not None else None,
            "radii": (tyres["front"].radius_m, tyres["rear"].radius_m), "runs": {}, "asms": asms}


def _wheel_inputs(p: dict, asm, fp, v: float, n_steps: int, track_key, inputs: dict, cache: RideCache):
    """Ground elevation and rate under each tyre element of ``asm`` at the full steps (the exact
    path's inputs ``w``, rows ``u, u'`` per tyre): the even samples of :func:`tyre_inputs`."""
    track, kind, wb = p["track"].profile, p["sc"].surface.enveloping, p["wb"]
    sides = ("left", "right") if asm.parts.three_d else ("mean",)

    def wheel(side: str, axle: int):
        key = (track_key, side, axle, kind, fp[axle], p["radii"][axle], v, n_steps)
        if key not in inputs:
            h = cache.envelope(track_key, track, side, kind, fp[axle], p["radii"][axle])
            inputs[key] = half_step_input(track.x_m, h, v, n_steps, wb if axle == 0 else 0.0, DT_S, half_steps=False)
        return inputs[key]

    rows = {}
    for side in sides:
        (uf, udf), (ur, udr) = wheel(side, 0), wheel(side, 1)
        u0 = 0.5 * (uf[0] + ur[0])
        rows["front" if side == "mean" else f"front_{side}"] = (uf - u0, udf)
        rows["rear" if side == "mean" else f"rear_{side}"] = (ur - u0, udr)
    w = np.empty((2 * len(asm.tyres), n_steps))
    for j, t in enumerate(asm.tyres):
        w[2 * j], w[2 * j + 1] = rows[t]
    return w


def _linear_model(p: dict, i: int, v: float, start: int, stop: int) -> None:
    """Speed ``i`` of variant ``p``: its assembly and linear model (seat outputs, then the tyre
    forces), in ``p["runs"][i]``."""
    sc, tyres = p["sc"], p["tyres"]
    asm = p["asms"][i] if p["asms"][i] is not None else assemble(build_parts(sc, tyres, i))  # the footprints' assembly
    fp = (float(tyres["front"].footprint_m[i]), float(tyres["rear"].footprint_m[i]))
    lm = asm.linear(tuple(p["axes"].values()) + tuple(f"{t}_force_N" for t in asm.tyres))
    p["runs"][i] = {"asm": asm, "v": v, "start": start, "stop": stop, "fp": fp, "lm": lm, "method": "linear"}


def _linear_run(p: dict, i: int, track_key, inputs: dict, cache: RideCache) -> None:
    """Speed ``i`` of variant ``p`` (:func:`_linear_model`) on the exact linear path; a run whose
    tyres stay on the ground (or without lift-off) is reduced to its numbers now, one that would
    pull is left for :func:`_redo_lifting`."""
    sc, run = p["sc"], p["runs"][i]
    asm, lm, start, stop = run["asm"], run["lm"], run["start"], run["stop"]
    w = _wheel_inputs(p, asm, run["fp"], run["v"], stop, track_key, inputs, cache)
    system = lti.discretise(*lm.abcd, DT_S)
    kept = system.modes(w)
    ns = len(p["axes"])
    # the tyre forces on the record only (lift-off before it does not count)
    forces = system.outputs(kept, range(ns, ns + len(asm.tyres)), stop, 1, start)
    static = asm.static_tyre_loads_N()
    off = _axle_flags(asm, {t: forces[j] <= -static[t] for j, t in enumerate(asm.tyres)})
    run["lift"] = tuple(float(o.mean()) for o in off)
    if sc.simulation.lift_off and off.any():
        return  # the nonlinear model, batched per variant (_redo_lifting)
    _reduce(p, i, system.outputs(kept, range(ns)))


def _redo_lifting(p: dict) -> None:
    """The runs of ``p`` whose tyres would pull: the nonlinear model, batched (exact in contact,
    RK4 across the lift-off intervals, as the ch. 7 study)."""
    sc = p["sc"]
    redo = [i for i, r in sorted(p["runs"].items()) if "row" not in r]
    if not redo:
        return
    seat_outputs = tuple(p["axes"].values())
    runs = [p["runs"][i] for i in redo]
    n_max = max(r["stop"] for r in runs)
    inputs = [tyre_inputs(r["asm"], p["track"].profile, sc.surface.enveloping, r["fp"], p["radii"], r["v"], p["wb"],
                          n_max) for r in runs]
    asms = [r["asm"] for r in runs]
    forces = tuple(f"{t}_force_N" for t in asms[0].tyres)
    sim = simulate(asms, np.array([x[0] for x in inputs]), np.array([x[1] for x in inputs]), DT_S, lift_off=True,
                   method="auto", record=seat_outputs + forces)
    for row_i, (i, r) in enumerate(zip(redo, runs)):
        static = r["asm"].static_tyre_loads_N()
        # off the ground: the tyre force at minus its static load (the clamp), to rounding
        off = _axle_flags(r["asm"], {t: sim[f"{t}_force_N"][row_i, :r["stop"]] <= -static[t] * (1 - 1e-6)
                                     for t in r["asm"].tyres})
        r["lift"] = tuple(float(o[r["start"]:r["stop"]].mean()) for o in off)
        r["method"] = "nonlinear (tyre lift-off)"
        _reduce(p, i, np.vstack([sim[o][row_i, :r["stop"]] for o in seat_outputs]))


def _reduce(p: dict, i: int, y: np.ndarray) -> None:
    """The numbers of run ``i`` of ``p`` from its seat-point records ``y`` (one row per seat axis)."""
    sc, tyres, r, axes = p["sc"], p["tyres"], p["runs"][i], p["axes"]
    hours = sc.exposure.hours_per_day
    speed = p["speeds"][i]
    start, stop, v = r["start"], r["stop"], r["v"]
    series = dict(zip(axes, y))
    floor = {ax: sig[start:stop] for ax, sig in series.items()}
    if p["seat_sys"] is not None:
        series["z"] = p["seat_sys"].run(series["z"][None, :])[0]
    series = {ax: sig[start:stop] for ax, sig in series.items()}
    weightings = {"x": "Wd", "y": "Wd", "z": "Wk"}
    weighted = {ax: iso2631.weighted_signal(sig, FS_HZ, weightings[ax]) for ax, sig in series.items()}
    aw = {ax: float(np.sqrt(np.mean(sig**2))) for ax, sig in weighted.items()}
    aw.setdefault("y", 0.0)  # the pitch-plane model has no lateral motion
    vdv = max(iso2631.AXIS_FACTOR[ax] * iso2631.vibration_dose_value(sig, FS_HZ) for ax, sig in weighted.items())
    duration = series["z"].size / FS_HZ
    expected = r["expected"]  # frequency-domain path (_expected_batch)
    row = {
        "speed_km_h": float(speed),
        **spectral_ride.tyre_columns(tyres, i),
        "a_wz_m_s2": aw["z"],
        "a_wx_m_s2": aw["x"],
        "a_wy_m_s2": aw["y"],
        "expected_a_wz_m_s2": expected["z"],
        "expected_a_wx_m_s2": expected["x"],
        "expected_a_wy_m_s2": expected.get("y", 0.0),
        "vdv_m_s1_75": vdv,
        "vdv_daily_m_s1_75": float(vdv * (hours * 3600.0 / duration) ** 0.25),
        "crest_factor": iso2631.crest_factor(weighted["z"]),
        "mtvv_m_s2": max(iso2631.AXIS_FACTOR[ax] * iso2631.mtvv(sig, FS_HZ) for ax, sig in weighted.items()),
        "lift_off_fraction_front": r["lift"][0],
        "lift_off_fraction_rear": r["lift"][1],
        **exposure(aw["z"], aw["x"], hours, aw["y"]),
        "hours_per_day": hours,
        "duration_s": duration,
        "simulation": r["method"],
        "method": "time",
    }
    if duration < MIN_VERDICT_DURATION_S:  # the exposure numbers stay; the verdict is withheld
        row["verdict"] = f"no verdict: record {duration:.2f} s, shorter than {MIN_VERDICT_DURATION_S:g} s"
        r["warning"] = (f"{speed:g} km/h: the seat record is {duration:.2f} s, shorter than "
                        f"{MIN_VERDICT_DURATION_S:g} s: too short for a reliable exposure verdict "
                        "(lengthen surface.length_m or simulation.duration_s)")
    r["row"] = row
    if p["with_signals"]:
        r["signals"] = {**{f"seat_{ax}_m_s2": sig for ax, sig in series.items()},
                        **{f"floor_{ax}_m_s2": sig for ax, sig in floor.items()}}
    if p["with_spectra"]:
        psd = {ax: mt.acceleration_psd(sig, FS_HZ, 0.1) for ax, sig in series.items()}
        fz = psd["z"][0]
        band = (fz >= FIGURE_BAND_HZ[0]) & (fz <= FIGURE_BAND_HZ[1])
        r["spectra"] = pd.DataFrame({"speed_km_h": float(speed), "frequency_Hz": fz[band],
                                     **{f"seat_{AXIS_WORDS[ax]}_psd_m2_s4_per_Hz": psd[ax][1][band] for ax in axes}})
        r["trans"] = _transmissibility(r, axes, p["seat_ss"], np.geomspace(*FIGURE_BAND_HZ, 300), v, p["wb"],
                                       float(speed))


def _finish(p: dict) -> RideResult:
    """The :class:`RideResult` of variant ``p`` from its reduced runs (in speed order)."""
    sc, tyres, track, axes = p["sc"], p["tyres"], p["track"], p["axes"]
    warnings = [f"tyres.{ax}: {w}" for ax in ("front", "rear") for w in tyres[ax].warnings]
    rows, spectra, trans, signals = [], [], [], {}
    for i, speed in enumerate(p["speeds"]):
        r = p["runs"][i]
        rows.append(r["row"])
        if "warning" in r:
            warnings.append(r["warning"])
        if "signals" in r:  # the cab floor beneath the seat: before the seat suspension (the model's seat x, y have none)
            signals[float(speed)] = r.pop("signals")
        if "spectra" in r:
            spectra.append(r.pop("spectra"))
            trans.append(r.pop("trans"))
    first = p["runs"][0]["asm"]
    shapes = mode_set(first)
    nat, nodal = shapes.frequencies(), shapes.nodal()
    nat_ci, notes = frequency_intervals(first, tyres["front"].stiffness_u_kN_per_m, tyres["rear"].stiffness_u_kN_per_m)
    warnings += [f"natural frequencies: {n}" for n in notes]
    cols = ["speed_km_h", "frequency_Hz"]
    return RideResult(
        scenario=sc, tyres=tyres, natural_frequencies_Hz=nat, nodal_points_m=nodal,
        speeds=pd.DataFrame(rows),
        spectra=pd.concat(spectra, ignore_index=True) if spectra else pd.DataFrame(columns=cols),
        transmissibility=pd.concat(trans, ignore_index=True) if trans else pd.DataFrame(columns=cols),
        track_label=track.profile.label, spectrum_source=track.spectrum_source, track_length_m=track.length_m,
        warnings=warnings, natural_frequency_intervals_Hz=nat_ci, signals=signals, road_classes=track.road_classes,
        a8_lateral_ci95_m_s2=_lateral_interval(p, rows),
        modes=shapes,
    )


def _lateral_interval(p: dict, rows: list) -> dict:
    """How far A(8) moves across the stand-in lateral stiffness' 95 % interval (issue 33), per speed:
    the frequency-domain expectation of each seat axis with every stand-in lateral stiffness scaled
    across its interval (:data:`LATERAL_INTERVAL_STEPS` log-spaced factors from ÷ 2 to × 2, the
    stand-in among them: a_wy need not be monotonic in it, a resonance may sit inside), over the
    expectation at the stand-in, scales the simulated a_w of that axis; the lowest and highest A(8)
    of those. Empty unless a tyre's lateral stiffness is the stand-in."""
    sc, tyres, track, axes = p["sc"], p["tyres"], p["track"], p["axes"]
    stand_in = [ax for ax in ("front", "rear") if tyres[ax].lateral_ci95_kN_per_m is not None]
    if not stand_in or track.side_spectrum is None:
        return {}
    factors = np.geomspace(0.5, 2.0, LATERAL_INTERVAL_STEPS)
    out = {}
    for i, speed in enumerate(p["speeds"]):
        v = speed / 3.6
        base = build_parts(sc, tyres, i)
        variants = [dataclasses.replace(base, **{ax: dataclasses.replace(getattr(base, ax), lateral_stiffness_N_per_m=f * getattr(
            base, ax).lateral_stiffness_N_per_m) for ax in stand_in}) for f in factors]
        lms = [assemble(v_).linear(tuple(axes.values())) for v_ in variants]
        grid = _fd_grid(sc, track, v)
        fp = (float(tyres["front"].footprint_m[i]), float(tyres["rear"].footprint_m[i]))
        env = {axle: enveloping_response(sc.surface.enveloping, fp[j], track.profile.dx_m, grid["n"])
               for j, axle in enumerate(("front", "rear"))}
        seat_tf = _seat_tf(p["seat_ss"], grid["f"]) if p["seat_ss"] is not None else None
        exp = expected_weighted_rms(np.array([m.a for m in lms]), np.array([m.b for m in lms]),
                                    np.array([m.c for m in lms]), np.array([m.d for m in lms]),
                                    assemble(base).tyres, grid, env, seat_tf, list(axes))
        mid = LATERAL_INTERVAL_STEPS // 2  # the stand-in itself (factor 1)
        row = rows[i]
        a8 = []
        for k in range(len(factors)):
            scaled = {ax: row[f"a_w{ax}_m_s2"] * (exp[ax][k] / exp[ax][mid] if exp[ax][mid] > 0 else 1.0) for ax in axes}
            a8.append(exposure(scaled["z"], scaled["x"], sc.exposure.hours_per_day, scaled.get("y", 0.0))["a8_m_s2"])
        out[float(speed)] = [min(a8), max(a8)]
    return out


#: Seat axes and their words in column names.
AXIS_WORDS = {"z": "vertical", "x": "longitudinal", "y": "lateral"}


def seat_axes(scenario: Scenario) -> dict[str, str]:
    """Seat axis (``z``, ``x``, and ``y`` in 3-D) -> the assembly output that gives it: the seat
    point's acceleration in space, or with ``[seat] gravity_tilt`` what a body-fixed
    accelerometer reads (plus ``g θ`` fore-aft and ``g φ`` lateral)."""
    _validate.instance("scenario", scenario, Scenario)
    tilt = "_tilt" if scenario.seat.gravity_tilt else ""
    axes = {"z": "seat_vertical_m_s2", "x": f"seat_longitudinal{tilt}_m_s2"}
    if scenario.tractor.three_d:
        axes["y"] = f"seat_lateral{tilt}_m_s2"
    return axes


def _wheel_responses(r: dict, f_Hz, v: float, env) -> tuple[np.ndarray, list[str]]:
    """Response of every output to each tyre's ground displacement (p, tyres, f), with the
    enveloping filter of its axle (``env[axle]``), without the wheelbase delay; and the tyres."""
    h = frequency_response(*r["lm"].abcd, f_Hz)
    jw = 2j * math.pi * np.asarray(f_Hz, float)
    tyres = list(r["asm"].tyres)
    out = np.stack([(h[:, 2 * j] + jw * h[:, 2 * j + 1]) * env[t.split("_")[0]] for j, t in enumerate(tyres)], axis=1)
    return out, tyres


def input_cross_spectra(tyres: list[str], side_spectrum, f_Hz, v: float, wheelbase_m: float) -> np.ndarray:
    """The tyres' input cross-spectral matrix (tyres, tyres, f), m²/Hz: per pair the two tracks'
    spectrum or cross-spectrum (``G_LL``, ``G_RR``, ``G_LR`` at ``n = f/v``, per Hz ``/v``) times
    ``exp(-jω (τ_i - τ_j))``, ``τ`` = 0 front, ``wheelbase/v`` rear (the front/rear delay)."""
    positive("v", v)
    _validate.non_negative("wheelbase_m", wheelbase_m)
    n_s, g_ll, g_rr, g_lr = side_spectrum
    n = np.asarray(f_Hz, float) / v
    g = {("left", "left"): np.interp(n, n_s, g_ll), ("right", "right"): np.interp(n, n_s, g_rr),
         ("left", "right"): np.interp(n, n_s, g_lr.real) + 1j * np.interp(n, n_s, np.imag(g_lr))}
    g[("right", "left")] = np.conj(g[("left", "right")])
    jw = 2j * math.pi * np.asarray(f_Hz, float)
    tau = {t: (wheelbase_m / v if t.startswith("rear") else 0.0) for t in tyres}
    out = np.empty((len(tyres), len(tyres), n.size), dtype=complex)
    for i, a in enumerate(tyres):
        for j, b in enumerate(tyres):
            out[i, j] = g[(a.split("_")[1], b.split("_")[1])] / v * np.exp(-jw * (tau[a] - tau[b]))
    return out


def _expected_batch(members: list, v: float, forces: bool = False) -> None:
    """Expected weighted r.m.s. per seat axis (``run["expected"]``) of the runs ``members``
    (``(variant, speed index)`` pairs sharing a track and speed ``v``, m/s) from the
    frequency-domain path: one batched :func:`expected_weighted_rms` per model structure; with
    ``forces`` also the r.m.s. of every tyre element's dynamic force (``run["force_sd"]``, N)."""
    batches: dict = {}
    for p, i in members:
        r, sc = p["runs"][i], p["sc"]
        seat = sc.seat
        key = (r["lm"].a.shape, r["asm"].tyres, tuple(p["axes"]), sc.surface.enveloping,
               (seat.natural_frequency_Hz, seat.damping_ratio) if p["seat_ss"] is not None else None)
        batches.setdefault(key, []).append((p, i))
    for batch in batches.values():
        p0, i0 = batch[0]
        sc, track, axes = p0["sc"], p0["track"], list(p0["axes"])
        grid = _fd_grid(sc, track, v)
        runs = [p["runs"][i] for p, i in batch]
        env = {}
        for j, axle in enumerate(("front", "rear")):
            fps = sorted({r["fp"][j] for r in runs})
            table = np.array([enveloping_response(sc.surface.enveloping, fp, track.profile.dx_m, grid["n"]) for fp in fps])
            env[axle] = (table, np.array([fps.index(r["fp"][j]) for r in runs]))
        seat_tf = _seat_tf(p0["seat_ss"], grid["f"]) if p0["seat_ss"] is not None else None
        tyres = runs[0]["asm"].tyres
        rows = axes + [f"force:{t}" for t in tyres] if forces else axes  # the rows of lm: seat axes, tyre forces
        na = len(rows)
        lms = [r["lm"] for r in runs]
        out = expected_weighted_rms(np.array([m.a for m in lms]), np.array([m.b for m in lms]),
                                    np.array([m.c[:na] for m in lms]), np.array([m.d[:na] for m in lms]),
                                    tyres, grid, env, seat_tf, rows, chunk=4 if forces else 8)
        for k, r in enumerate(runs):
            r["expected"] = {ax: float(out[ax][k]) for ax in axes}
            if forces:
                r["force_sd"] = {t: float(out[f"force:{t}"][k]) for t in tyres}


def _fd_grid(scenario: Scenario, track: Track, v: float) -> dict:
    """The frequency-domain path's grid at speed ``v`` (m/s): frequencies ``f`` (Hz, up to the
    Nyquist frequency of the time path), wavenumbers ``n`` (cycles/m) for the enveloping filters,
    and the ground input: the pitch plane's axle-mean spectrum ``s_u`` (m²/Hz, as the ch. 7 study),
    in 3-D the tyres' full cross-spectral matrix (:func:`input_cross_spectra`)."""
    wb = scenario.tractor.wheelbase_m
    if not scenario.tractor.three_d:
        n_s, g_s = track.spectrum
        f_s = n_s * v
        keep = f_s <= FS_HZ / 2
        return {"f": f_s[keep], "n": n_s[keep], "s_u": g_s[keep] / v, "wb": wb, "v": v}
    f_s = track.side_spectrum[0] * v
    f_s = f_s[f_s <= FS_HZ / 2]
    return {"f": f_s, "n": f_s / v, "side_spectrum": track.side_spectrum, "wb": wb, "v": v}


def expected_weighted_rms(a, b, c, d, tyres, grid: dict, env: dict, seat_tf, axes, chunk: int = 8) -> dict:
    """Expected ISO 2631-1 weighted r.m.s. of outputs of many linear models on one frequency grid.

    For each model ``(A, B, C, D)`` (stacked, leading axis: the variants) with inputs ``u, u'`` per
    tyre (:meth:`tyrelab.vehicle.model.Assembly.linear`), the response of output ``p`` to tyre
    ``t``'s ground displacement is, modally (``A = V Λ V⁻¹``, ``c = C V``, ``b = V⁻¹ B``),
    ``h_pt(jω) = env_t [ Σ_k c_pk b_k,u' + D_p,u + jω D_p,u' + Σ_k c_pk (b_k,u + λ_k b_k,u') / (jω - λ_k) ]``
    (``(b_u + jω b_u') / (jω - λ) = b_u' + (b_u + λ b_u') / (jω - λ)``): one small matrix product
    per variant over the frequencies. The output spectrum is ``h S h^H`` (``S`` the tyres' input
    cross-spectral matrix; the pitch plane: ``|Σ_t h_t e^{-jωτ_t}|² S_u``, the rear tyre a wheelbase
    later) and the expected value ``sqrt(∫ S_y |W|² df)`` (W_k on ``z``, W_d on ``x``, ``y``; the seat
    suspension's transmissibility ``seat_tf`` on ``z``).

    Parameters
    ----------
    a, b, c, d : ndarray, shape (V, n, n), (V, n, 2T), (V, p, n), (V, p, 2T)
        The variants' linear models, rows of ``c``/``d`` in the order of ``axes``.
    tyres : sequence of str
        The tyre elements (``front``/``rear`` or ``front_left``, ...), the inputs' order.
    grid : dict
        :func:`_fd_grid`.
    env : dict
        Axle (``front``/``rear``) -> enveloping transfer function on the grid: shape (F,) for
        all variants, (V, F), or ``(table, index)``: row ``index[v]`` of ``table`` for variant ``v``.
    seat_tf : ndarray or None
        Seat suspension transmissibility on the grid (applied to ``z``).
    axes : sequence of str
        Names of the output rows: seat axes (``z``, ``x``, ``y``: weighted) or any other name (an
        output taken unweighted, e.g. a tyre force: its r.m.s. in its own unit).
    chunk : int
        Variants per vectorised step (memory).

    Returns
    -------
    dict
        Axis -> ndarray (V,), m/s².
    """
    _validate.positive_int("chunk", chunk)
    a, b, c, d = (np.asarray(x, float) for x in (a, b, c, d))
    if not (a.ndim == 3 and a.shape[1] == a.shape[2] and b.shape[:2] == a.shape[:2] and c.shape[0] == a.shape[0]
            and c.shape[2] == a.shape[1] and d.shape == (c.shape[0], c.shape[1], b.shape[2])
            and b.shape[2] == 2 * len(tyres) and c.shape[1] >= len(axes)):
        raise ValueError(f"a, b, c, d: shapes {a.shape}, {b.shape}, {c.shape}, {d.shape} are not (V, n, n), "
                         f"(V, n, 2T), (V, p, n), (V, p, 2T) with T = {len(tyres)} tyres and p >= {len(axes)} axes")
    f = np.asarray(grid["f"], float)
    omega = 2 * math.pi * f
    n_t, n_f = len(tyres), f.size
    axle = [t.split("_")[0] for t in tyres]
    # the integral sqrt(∫ S_y |W|² df) by the trapezoidal rule as one weighted sum over the grid:
    # per axis the weights (trapezoid × |W|² × the seat's |T|² on z × S_u in the pitch plane)
    trap = np.zeros(n_f)
    if n_f > 1:
        df = np.diff(f)
        trap[:-1] += 0.5 * df
        trap[1:] += 0.5 * df
    seat2 = np.abs(seat_tf) ** 2 if seat_tf is not None else None
    quad = {}
    for ax in axes:
        weighting = {"x": "Wd", "y": "Wd", "z": "Wk"}.get(ax)  # any other output (a force): unweighted
        q = trap * np.abs(iso2631.weighting_response(f, weighting)) ** 2 if weighting else trap
        if seat2 is not None and ax == "z":
            q = q * seat2
        quad[ax] = q * grid["s_u"] if "s_u" in grid else q
    if "s_u" in grid:  # the pitch plane: rear a wheelbase later, one spectrum
        delay = np.array([np.exp(-1j * omega * grid["wb"] / grid["v"]) if t.startswith("rear") else np.ones(n_f)
                          for t in tyres])
        s_in = None
    else:
        s_in = input_cross_spectra(list(tyres), grid["side_spectrum"], f, grid["v"], grid["wb"])
    out = {ax: np.empty(a.shape[0]) for ax in axes}
    n_p, n_s = len(axes), a.shape[1]
    n_h = n_p * n_t
    for lo in range(0, a.shape[0], chunk):
        sl = slice(lo, lo + chunk)
        lam, vecs = np.linalg.eig(a[sl])
        cv = c[sl][:, :n_p] @ vecs  # (V, p, n)
        vb = np.linalg.solve(vecs, b[sl].astype(complex))  # (V, n, 2T)
        vb_u, vb_du = vb[:, :, 0::2], vb[:, :, 1::2]
        nv = lam.shape[0]
        # h_pt(jw) = sum_k beta_ptk / (jw - lam_k) + alpha0_pt + jw alpha1_pt as one real matrix
        # product per variant: rows [Re h; Im h], columns over the basis [br_k; x_k; 1; w] with
        # 1/(jw - lam) = br - j x, br = a / (a² + x²), x = (w - Im lam) / (a² + x²), a = -Re lam
        beta = (cv[:, :, :, None] * (vb_u + lam[:, :, None] * vb_du)[:, None, :, :]).transpose(0, 1, 3, 2)
        beta = beta.reshape(nv, n_h, n_s)
        alpha0 = (cv @ vb_du + d[sl][:, :n_p, 0::2]).reshape(nv, n_h)  # (V, p T)
        alpha1 = d[sl][:, :n_p, 1::2].reshape(nv, n_h)
        big = np.zeros((nv, 2 * n_h, 2 * n_s + 2))
        big[:, :n_h, :n_s], big[:, :n_h, n_s:2 * n_s] = beta.real, beta.imag
        big[:, n_h:, :n_s], big[:, n_h:, n_s:2 * n_s] = beta.imag, -beta.real
        big[:, :n_h, 2 * n_s], big[:, n_h:, 2 * n_s], big[:, n_h:, 2 * n_s + 1] = alpha0.real, alpha0.imag, alpha1
        basis = np.empty((nv, 2 * n_s + 2, n_f))
        x = np.subtract(omega[None, None, :], lam.imag[:, :, None], out=basis[:, n_s:2 * n_s])
        inv = x * x
        inv += (lam.real**2)[:, :, None]
        np.reciprocal(inv, out=inv)
        np.multiply(inv, -lam.real[:, :, None], out=basis[:, :n_s])
        x *= inv
        basis[:, 2 * n_s] = 1.0
        basis[:, 2 * n_s + 1] = omega
        h = np.matmul(big, basis).reshape(nv, 2, n_p, n_t, n_f)  # [Re h, Im h] (V, 2, p, T, F)
        env_t = np.stack([_rows(env[x_], sl, nv, n_f) for x_ in axle], axis=1)  # (V, T, F)
        # a variant's numbers do not depend on the others in its chunk (how a sweep is cut into
        # executor tasks): elementwise operations, and per variant one sum over the grid
        h_re, h_im = h[:, 0], h[:, 1]  # (V, p, T, F)
        if s_in is None:  # |sum_t h_t env_t e^{-jw tau_t}|² S_u
            e_re, e_im = env_t * delay.real, env_t * delay.imag  # (V, T, F)
            r_re = np.zeros((nv, n_p, n_f))
            r_im = np.zeros((nv, n_p, n_f))
            for t in range(n_t):
                r_re += h_re[:, :, t] * e_re[:, None, t] - h_im[:, :, t] * e_im[:, None, t]
                r_im += h_re[:, :, t] * e_im[:, None, t] + h_im[:, :, t] * e_re[:, None, t]
            power = r_re * r_re
            power += r_im * r_im
        else:  # h S h^H, S Hermitian: sum_i |h_i|² S_ii + 2 sum_{i<j} Re(h_i conj(h_j) S_ij)
            h_re = h_re * env_t[:, None]
            h_im = h_im * env_t[:, None]
            power = np.zeros((nv, n_p, n_f))
            for i in range(n_t):
                power += (h_re[:, :, i] ** 2 + h_im[:, :, i] ** 2) * s_in[i, i].real
                for j in range(i + 1, n_t):
                    # Re(h_i conj(h_j) S_ij) with h_i conj(h_j) = (a_i a_j + b_i b_j) + j (b_i a_j - a_i b_j)
                    x_re = h_re[:, :, i] * h_re[:, :, j] + h_im[:, :, i] * h_im[:, :, j]
                    x_im = h_im[:, :, i] * h_re[:, :, j] - h_re[:, :, i] * h_im[:, :, j]
                    power += 2.0 * (x_re * s_in[i, j].real - x_im * s_in[i, j].imag)
        for k, ax in enumerate(axes):  # numpy's sum per row (BLAS' dot rounds with the memory alignment)
            out[ax][sl] = np.sqrt(np.maximum(np.sum(power[:, k] * quad[ax], axis=-1), 0.0))
    return out


def _rows(env, sl: slice, nv: int, n_f: int) -> np.ndarray:
    """An axle's enveloping transfer function for the variants ``sl``: one row for all, a row per
    variant, or ``(table, index)`` (a row of ``table`` per variant)."""
    if isinstance(env, tuple):
        table, index = env
        return np.asarray(table, float)[np.asarray(index)[sl]]
    env = np.asarray(env, float)
    return np.broadcast_to(env, (nv, n_f)) if env.ndim < 2 else env[sl]


def _transmissibility(r: dict, axes: dict, seat_ss, f_grid, v: float, wb: float, speed: float) -> pd.DataFrame:
    """|seat acceleration / ground acceleration| per axis on the figure grid (all wheels in phase
    on both sides, the rear a wheelbase later): ``seat_vertical``, ``seat_longitudinal_per_m``
    (fore-aft per unit ground acceleration, as before) and in 3-D ``seat_lateral_roll``: lateral
    seat acceleration per unit left/right anti-phase ground acceleration."""
    w2 = (2 * math.pi * f_grid) ** 2
    ones = {"front": 1.0, "rear": 1.0}
    h, tyres = _wheel_responses(r, f_grid, v, ones)
    delay = np.array([np.exp(-2j * math.pi * f_grid * wb / v) if t.startswith("rear") else np.ones_like(f_grid)
                      for t in tyres])
    in_phase = np.einsum("ptf,tf->pf", h, delay)
    out = {"speed_km_h": speed, "frequency_Hz": f_grid}
    k = list(axes)
    tz = in_phase[k.index("z")] * (_seat_tf(seat_ss, f_grid) if seat_ss is not None else 1.0)
    out["seat_vertical"] = np.abs(tz) / w2
    out["seat_longitudinal_per_m"] = np.abs(in_phase[k.index("x")]) / w2
    if "y" in axes:
        sign = np.array([1.0 if t.endswith("left") else -1.0 for t in tyres])[:, None]
        anti = np.einsum("ptf,tf->pf", h, 0.5 * sign * delay)
        out["seat_lateral_roll"] = np.abs(anti[k.index("y")]) / w2
    return pd.DataFrame(out)


def _axle_flags(asm, flags: dict) -> np.ndarray:
    """Per-sample lift-off flags (front, rear) from per-tyre flags: an axle is off the ground
    where any of its tyres is."""
    return np.vstack([np.logical_or.reduce([flags[t] for t in asm.tyres if t.startswith(axle)]) for axle in ("front", "rear")])


def _seat_tf(seat_ss, f_Hz) -> np.ndarray:
    return frequency_response(*seat_ss, f_Hz)[0, 0]


def _ride_batch(item: tuple) -> list[RideResult]:
    """Executor task: a chunk of scenario variants, batched (:func:`ride_variants`; module level, picklable)."""
    scenarios, tyre_data, with_spectra = item
    return ride_variants(scenarios, tyre_data, with_spectra)


# --------------------------------------------------------------------------- spectral rows (issue 36)
def spectral_variants(scenarios, tyre_data=None, with_spectra: bool = True,
                      cache: RideCache | None = None) -> list[RideResult]:
    """:func:`ride_variants` in the frequency domain: per variant and speed a spectral row
    (:func:`tyrelab.vehicle.spectral_ride.spectral_row`: the exact expectation of the linear model
    for the track's spectrum), no simulation.

    Parameters
    ----------
    scenarios : sequence of Scenario
    tyre_data : object, optional
        As :func:`ride`.
    with_spectra : bool
        Also the expected seat PSD per axis (on a 0.1 Hz grid of 0.2-20 Hz) and the transmissibility.
    cache : RideCache, optional

    Returns
    -------
    list of RideResult
        One per scenario, its ``speeds`` the spectral rows.
    """
    for k, sc in enumerate(scenarios):
        _validate.instance(f"scenarios[{k}]", sc, Scenario)
    cache = cache or RideCache()
    preps = [_prepare(sc, tyre_data, cache) for sc in scenarios]
    groups: dict = {}
    for p in preps:
        p["with_spectra"], p["with_signals"] = with_spectra, False
        for i, speed in enumerate(p["speeds"]):
            v = speed / 3.6
            start, stop = _record_window(p["track"], p["wb"], v, p["sc"].simulation.duration_s)
            _linear_model(p, i, v, start, stop)
            groups.setdefault((p["track_key"], v), []).append((p, i))
    for (_, v), members in groups.items():
        _expected_batch(members, v, forces=True)
        for p, i in members:
            _spectral_reduce(p, i)
    return [_finish(p) for p in preps]


def _spectral_reduce(p: dict, i: int) -> None:
    """The spectral row of speed ``i`` of variant ``p`` (and its expected seat PSD and transmissibility)."""
    from . import spectral_ride as sr

    sc, tyres, r, axes = p["sc"], p["tyres"], p["runs"][i], p["axes"]
    hours = sc.exposure.hours_per_day
    aw = {ax: r["expected"].get(ax, 0.0) for ax in ("z", "x", "y")}
    asm = r["asm"]
    k = (float(tyres["front"].stiffness_kN_per_m[i]), float(tyres["rear"].stiffness_kN_per_m[i]))
    static = p.setdefault("static_loads", {})  # they change with the tyres' stiffness only (statically indeterminate)
    if k not in static:
        static[k] = asm.static_tyre_loads_N()
    r["row"] = sr.spectral_row(p["speeds"][i], tyres, i, aw, axes, hours, (r["stop"] - r["start"]) * DT_S,
                               r["force_sd"], static[k], 1 if asm.parts.three_d else 2,
                               exposure(aw["z"], aw["x"], hours, aw["y"]))
    if p["with_spectra"]:
        speed = float(p["speeds"][i])
        r["spectra"] = _expected_psd(p, i, sr.PSD_FREQUENCIES_HZ, speed)
        r["trans"] = _transmissibility(r, axes, p["seat_ss"], np.geomspace(*FIGURE_BAND_HZ, 300), r["v"], p["wb"], speed)


def _expected_psd(p: dict, i: int, f_Hz: np.ndarray, speed: float) -> pd.DataFrame:
    """The expected seat acceleration PSD per axis (m²/s⁴/Hz, unweighted; the seat suspension on z) of
    run ``i`` of ``p`` at ``f_Hz``: ``h S h^H`` with the enveloping filters and the wheelbase delay."""
    r, sc, track, axes = p["runs"][i], p["sc"], p["track"], p["axes"]
    v = r["v"]
    n = f_Hz / v
    env = {axle: enveloping_response(sc.surface.enveloping, r["fp"][j], track.profile.dx_m, n)
           for j, axle in enumerate(("front", "rear"))}
    h, tyres = _wheel_responses(r, f_Hz, v, env)
    h = h[:len(axes)]
    if not sc.tractor.three_d:
        n_s, g_s = track.spectrum
        s_u = np.interp(n, n_s, g_s, left=0.0, right=0.0) / v
        delay = np.array([np.exp(-2j * math.pi * f_Hz * p["wb"] / v) if t.startswith("rear") else np.ones_like(f_Hz)
                          for t in tyres])
        power = np.abs(np.einsum("ptf,tf->pf", h, delay)) ** 2 * s_u
    else:
        n_s = track.side_spectrum[0]
        inside = (n >= n_s[0]) & (n <= n_s[-1])
        s_in = input_cross_spectra(list(tyres), track.side_spectrum, f_Hz, v, p["wb"]) * inside
        power = np.einsum("pif,ijf,pjf->pf", h, s_in, np.conj(h)).real
    out = {"speed_km_h": speed, "frequency_Hz": f_Hz}
    for k, ax in enumerate(axes):
        s = power[k]
        if ax == "z" and p["seat_ss"] is not None:
            s = s * np.abs(_seat_tf(p["seat_ss"], f_Hz)) ** 2
        out[f"seat_{AXIS_WORDS[ax]}_psd_m2_s4_per_Hz"] = np.maximum(s, 0.0)
    return pd.DataFrame(out)


def _spectral_batch(item: tuple) -> list[RideResult]:
    """Executor task: a chunk of variants in the frequency domain (module level, picklable)."""
    scenarios, tyre_data, with_spectra = item
    return spectral_variants(scenarios, tyre_data, with_spectra)


def _in_chunks(task, scenarios: list, size: int, tyre_data, with_spectra: bool, map_fn) -> list[RideResult]:
    """``task`` (:func:`_ride_batch`, :func:`_spectral_batch`) over chunks of ``scenarios`` of
    ``size``, through the caller's executor ``map_fn``; results in order."""
    chunks = [(scenarios[k:k + size], tyre_data, with_spectra) for k in range(0, len(scenarios), size)]
    return [r for chunk in map_fn(task, chunks) for r in chunk]


def _sweep_results(scenarios: list, method: str, nominal: int, tyre_data, with_spectra: bool | str, map_fn,
                   max_samples: int | None) -> list[RideResult]:
    """The results of a sweep's variants under ``method`` (:mod:`tyrelab.vehicle.spectral_ride`), in
    order, with figure data as :func:`ride_sweep`'s ``with_spectra`` says. ``auto``'s time-domain
    checks stay within ``max_samples`` (the nominal variant first, then the lifting speeds in order;
    those beyond are left spectral, with a warning)."""
    from . import scenario_limits as limits
    from . import spectral_ride as sr

    cache = RideCache()  # shared by the runs in this process (tracks, enveloped wheel tracks, tyres)

    def timed(chosen: list, spectra: bool) -> list[RideResult]:  # chunks of variants, each batched in its task
        if map_fn is None or len(chosen) <= 1:
            return ride_variants(chosen, tyre_data, spectra, cache=cache) if chosen else []
        return _in_chunks(_ride_batch, chosen, max(1, min(SWEEP_CHUNK, -(-len(chosen) // 8))), tyre_data, spectra,
                          map_fn)

    def spectral(chosen: list, spectra: bool) -> list[RideResult]:
        if map_fn is None or len(chosen) <= sr.SPECTRAL_CHUNK:
            return spectral_variants(chosen, tyre_data, spectra, cache) if chosen else []
        return _in_chunks(_spectral_batch, chosen, sr.SPECTRAL_CHUNK, tyre_data, spectra, map_fn)

    run = spectral if limits.uses_spectral(scenarios[0], method, len(scenarios)) else timed
    if with_spectra == "nominal":  # the figure data of the nominal variant alone (what a sweep's page draws)
        results = run(scenarios[:nominal] + scenarios[nominal + 1:], False)
        results.insert(nominal, run([scenarios[nominal]], True)[0])
    else:
        results = run(scenarios, bool(with_spectra))
    if run is timed or method == "spectral":
        return results
    checks = [(nominal, scenarios[nominal])]  # auto: the nominal variant and the speeds that may lift a tyre
    budget = (max_samples or limits.MAX_SAMPLES) - limits.work_estimate(scenarios[nominal], 1)["samples"]
    skipped = []
    for j, r in enumerate(results):
        lifting = sr.lifting_speeds(r.speeds) if j != nominal else []
        if not lifting:
            continue
        sc = with_overrides(scenarios[j], lifting)
        cost = limits.work_estimate(sc, 1)["samples"]
        if cost > budget:
            skipped.append(j)
            continue
        budget -= cost
        checks.append((j, sc))
    for (j, _), t in zip(checks, timed([sc for _, sc in checks], False)):
        results[j].time_rows = t.speeds
        results[j].warnings = list(dict.fromkeys(results[j].warnings + t.warnings))
    for j in skipped:
        results[j].warnings.append(
            f"{len(skipped)} variant(s) whose lift-off probability exceeds {sr.LIFT_OFF_PROBABILITY_LIMIT:g} were not "
            "simulated in the time domain (the --max-samples budget): their rows are the linear expectation, which "
            "does not hold where tyres lift off")
    return results


#: Variants per executor task of :func:`ride_sweep` (a task shares its wheel inputs between them).
SWEEP_CHUNK = 25


def ride_sweep(
    scenario: Scenario,
    front_pressures_bar=None,
    rear_pressures_bar=None,
    speeds_km_h=None,
    tyre_data=None,
    map_fn=None,
    with_spectra: bool | str = True,
    sets: dict | None = None,
    max_variants: int | None = None,
    max_samples: int | None = None,
    method: str | None = None,
) -> list[RideResult]:
    """:func:`ride` for every variant: each front × rear pressure pair (the scenario's own when not
    given) and every combination of the swept keys.

    Parameters
    ----------
    scenario : Scenario
    front_pressures_bar, rear_pressures_bar : sequence of float, optional
        Default: the scenario's ``[sweep]``, else its tyres' pressures.
    speeds_km_h : sequence of float, optional
        Override the scenario's speeds.
    tyre_data : object, optional
        As :func:`ride`.
    map_fn : callable, optional
        ``map_fn(task, items) -> results`` in order (the caller's executor, e.g.
        :func:`tyrelab.executor.map_batches` bound to a context); default in-process.
    with_spectra : bool or "nominal"
        Seat PSD and transmissibility (figure data) of every variant, of none, or (``"nominal"``)
        of the nominal variant alone (:func:`tyrelab.vehicle.spectral_ride.nominal_index`: what a
        sweep's page draws).
    sets : dict, optional
        Numeric scenario keys (``"section.key"``, :func:`tyrelab.vehicle.scenario.numeric_key`)
        -> values to run, on top of (and replacing the same keys of) the scenario's ``[sweep]``.
    max_variants, max_samples : int, optional
        Bounds of the work (:mod:`tyrelab.vehicle.scenario_limits`; default its ``MAX_VARIANTS``
        for the time domain, ``MAX_SPECTRAL_VARIANTS`` for spectral rows, and ``MAX_SAMPLES``): more
        is refused with a ValueError giving the estimate, before any work.
    method : {"auto", "time", "spectral"}, optional
        How the rows are computed (default the scenario's ``[simulation] method``;
        :func:`tyrelab.vehicle.spectral_ride`): ``auto`` simulates one variant, and computes a
        sweep on an ISO 8608 surface in the frequency domain with the time domain beside it for
        the nominal variant and for speeds that may lift a tyre.

    Returns
    -------
    list of RideResult
        Pressure pairs front-major, then the swept keys in order (the last varying fastest);
        :attr:`RideResult.variant` names each variant's swept values. Every variant's modes carry
        the first variant's names, followed by shape (:func:`tyrelab.vehicle.modes.follow_names`).

    Raises
    ------
    ScenarioError
        A swept key (or a swept pressure) that the scenario's model does not use, each with the
        reason (:func:`tyrelab.vehicle.sweeps.unused_key_problems`), before any work.
    ValueError
        A pressure given by option and swept key both, values out of range, too much work.
    """
    from .scenario_limits import METHODS
    from .spectral_ride import at_own_values, nominal_index

    method = method or scenario.simulation.method
    _validate.choice("method", method, METHODS)
    if with_spectra not in (True, False, "nominal"):
        raise ValueError(f"with_spectra must be True, False or 'nominal', got {with_spectra!r}")
    if max_variants is not None:
        _validate.positive_int("max_variants", max_variants)
    if max_samples is not None:
        _validate.positive_int("max_samples", max_samples)
    from . import scenario_limits as limits
    from . import sweeps

    # the pressures are the sweep's pressure axes however given (an option, --set or [sweep])
    fronts, rears, swept, pressures = sweeps.pressure_axes(scenario, front_pressures_bar, rear_pressures_bar,
                                                           {**scenario.sweep.keys, **(sets or {})})
    combos = [dict(zip(swept, values)) for values in itertools.product(*swept.values())] if swept else [{}]
    bad = limits.override_problems(speeds_km_h, fronts, rears)
    if bad:
        raise ValueError("; ".join(bad))
    spectral = limits.uses_spectral(scenario, method, len(fronts) * len(rears) * len(combos))
    bad = sweeps.unused_key_problems(scenario, pressures) + sweeps.unused_key_problems(scenario, swept, spectral)
    if bad:  # a key that changes nothing would run identical variants under different labels
        raise ScenarioError(scenario.path or "<scenario>", bad)
    too_much = limits.work_problems(scenario, len(fronts) * len(rears) * len(combos), speeds_km_h,
                                    max_variants=max_variants, max_samples=max_samples or limits.MAX_SAMPLES,
                                    method=method)
    if too_much:  # before any work (the variants are not even built)
        raise ValueError("; ".join(too_much))
    variants = []
    for pf in fronts:
        for pr_ in rears:
            for combo in combos:
                base = with_values(scenario, combo) if combo else scenario
                variants.append((with_overrides(base, speeds_km_h, pf, pr_), combo))
    scenarios = [v for v, _ in variants]
    nominal = nominal_index(scenario, variants)
    results = _sweep_results(scenarios, method, nominal, tyre_data, with_spectra, map_fn, max_samples)
    for r, (sc_v, combo) in zip(results, variants):
        r.variant = dict(combo)
        r.nominal = at_own_values(scenario, sc_v, combo)  # the scenario's own values
    _follow_modes(results)
    return results


def nominal_result(results: list[RideResult]) -> RideResult:
    """The variant at the scenario's own values (:attr:`RideResult.nominal`), else the first."""
    return next((r for r in results if r.nominal), results[0])


def _follow_modes(results: list[RideResult]) -> None:
    """Every variant's modes under the first variant's names, followed by shape
    (:func:`tyrelab.vehicle.modes.follow_names`): a sweep's ``bounce_Hz`` is one mode in every
    variant. A mode of the first variant that a variant does not have (by shape) is NaN there,
    with a warning."""
    ref = results[0].modes
    for r in results[1:]:
        if ref is None or r.modes is None:
            continue
        mapping, notes = follow_names(ref, r.modes)
        back = {new: own for own, new in mapping.items()}
        r.natural_frequencies_Hz = {n: r.natural_frequencies_Hz[back[n]] if n in back else math.nan for n in ref.names}
        r.natural_frequency_intervals_Hz = {n: r.natural_frequency_intervals_Hz.get(back[n]) if n in back else None
                                            for n in ref.names}
        r.nodal_points_m = {n: r.modes.nodal_points_m[r.modes.names.index(back[n])] if n in back else math.nan
                            for n in ref.nodal()}
        r.warnings += [f"natural frequencies: {n}" for n in notes]


def expected_sweep(scenario: Scenario, front_pressures_bar, rear_pressures_bar, speeds_km_h=None,
                   tyre_data=None, cache: RideCache | None = None) -> pd.DataFrame:
    """The frequency-domain expectation alone (no simulation) for every front × rear pressure
    pair and speed: a large pressure study in seconds.

    The tyres are resolved once per axle and pressure, the linear models of all pairs at a speed
    come from one assembly (:meth:`tyrelab.vehicle.model.Assembly.linear_tyres`) and their
    expected weighted r.m.s. from one batched :func:`expected_weighted_rms`; each number is the
    ``expected_a_w*_m_s2`` :func:`ride` gives for that pair, speed and the scenario's track spectrum.

    Returns
    -------
    DataFrame
        One row per pair and speed: ``front_pressure_bar``, ``rear_pressure_bar``, ``speed_km_h``,
        ``expected_a_wz_m_s2``, ``expected_a_wx_m_s2``, ``expected_a_wy_m_s2``, and the exposure
        of these (``a8_m_s2``, ``hours_to_eav``, ``hours_to_elv``, ``verdict``) at the scenario's
        hours per day.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> sc = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> t = expected_sweep(sc, [1.2, 1.6], [1.2], [8.0])
    >>> row = t.iloc[1]
    >>> r = ride(with_overrides(sc, [8.0], 1.6, 1.2), with_spectra=False).speeds.iloc[0]
    >>> bool(abs(row["expected_a_wz_m_s2"] / r["expected_a_wz_m_s2"] - 1) < 1e-9)
    True
    """
    _validate.instance("scenario", scenario, Scenario)
    cache = cache or RideCache()
    fronts, rears = [float(x) for x in front_pressures_bar], [float(x) for x in rear_pressures_bar]
    if not fronts or not rears:
        raise ValueError("front_pressures_bar, rear_pressures_bar: give at least one pressure each")
    base = with_overrides(scenario, speeds_km_h, fronts[0], rears[0])
    from . import scenario_limits as limits

    bad = limits.override_problems(speeds_km_h, fronts, rears)
    if bad:
        raise ValueError("; ".join(bad))
    speeds = base.exposure.speeds_km_h
    front = {pf: resolve_tyres(with_overrides(base, None, pf, rears[0]), tyre_data)["front"] for pf in fronts}
    rear = {pr_: resolve_tyres(with_overrides(base, None, fronts[0], pr_), tyre_data)["rear"] for pr_ in rears}
    _, track = cache.track(base)
    axes = seat_axes(base)
    tyres0 = {"front": front[fronts[0]], "rear": rear[rears[0]]}
    seat = base.seat
    seat_ss = seat.part().suspension.linear().abcd if seat.suspension == "linear" else None
    pf_all = np.repeat(fronts, len(rears))
    pr_all = np.tile(rears, len(fronts))
    frames = []
    for i, speed in enumerate(speeds):
        v = speed / 3.6
        asm = assemble(build_parts(base, tyres0, i))
        k = {"front": np.array([from_kilo(front[p].stiffness_kN_per_m[i]) for p in pf_all]),
             "rear": np.array([from_kilo(rear[p].stiffness_kN_per_m[i]) for p in pr_all])}
        c = {"front": np.array([from_kilo(front[p].damping_kN_s_per_m[i]) for p in pf_all]),
             "rear": np.array([from_kilo(rear[p].damping_kN_s_per_m[i]) for p in pr_all])}
        if base.tractor.three_d and base.tractor.lateral_model != "none":
            # the lateral elements follow each pair's tyres (the stand-in scales with k_z; a Maxwell
            # element is not affine in its damping): one assembly per pair
            lms = [assemble(build_parts(base, {"front": front[pf], "rear": rear[pr_]}, i)).linear(tuple(axes.values()))
                   for pf, pr_ in zip(pf_all, pr_all)]
            a, b, cc, d = (np.array([getattr(m, x) for m in lms]) for x in "abcd")
        else:
            a, b, cc, d = asm.linear_tyres(tuple(axes.values()), k, c)
        grid = _fd_grid(base, track, v)
        env_f = {p: enveloping_response(base.surface.enveloping, float(front[p].footprint_m[i]), track.profile.dx_m,
                                        grid["n"]) for p in fronts}
        env_r = {p: enveloping_response(base.surface.enveloping, float(rear[p].footprint_m[i]), track.profile.dx_m,
                                        grid["n"]) for p in rears}
        env = {"front": (np.array([env_f[p] for p in fronts]), np.repeat(np.arange(len(fronts)), len(rears))),
               "rear": (np.array([env_r[p] for p in rears]), np.tile(np.arange(len(rears)), len(fronts)))}
        seat_tf = _seat_tf(seat_ss, grid["f"]) if seat_ss is not None else None
        got = expected_weighted_rms(a, b, cc, d, asm.tyres, grid, env, seat_tf, list(axes))
        frame = pd.DataFrame({"front_pressure_bar": pf_all, "rear_pressure_bar": pr_all, "speed_km_h": float(speed),
                              **{f"expected_a_w{ax}_m_s2": got[ax] for ax in axes}})
        frames.append(frame)
    out = pd.concat(frames, ignore_index=True)
    if "expected_a_wy_m_s2" not in out:
        out["expected_a_wy_m_s2"] = 0.0
    hours = base.exposure.hours_per_day
    ex = [exposure(z, x, hours, y) for z, x, y in
          zip(out["expected_a_wz_m_s2"], out["expected_a_wx_m_s2"], out["expected_a_wy_m_s2"])]
    for key in ("a8_m_s2", "a8_axis", "hours_to_eav", "hours_to_elv", "verdict"):
        out[key] = [e[key] for e in ex]
    return out


def _lateral_note(sc: Scenario) -> str | None:
    """What a_wy rests on (issue 33): None in the pitch plane (no a_wy)."""
    t = sc.tractor
    if not t.three_d:
        return None
    if t.lateral_model == "none":
        return ("lateral_model = \"none\": no lateral tyre force, the body rolls about its CG; a_wy is indicative "
                "only (give the tyres' lateral elements: tractor.lateral_model)")
    given = all(x.lateral_stiffness_kN_per_m is not None for x in (sc.front, sc.rear))
    return (f"lateral tyre elements ({t.lateral_model}); lateral stiffness "
            + ("as given" if given else "partly or wholly the stand-in k_y = 0.57 k_z (95 % interval x/÷ 2)"))


def _clean_class(c: dict) -> dict:
    """A road class (:func:`tyrelab.vehicle.road_class.road_class`) for JSON (``g0_m3`` to 6 significant
    digits: it is of the order of 1e-5 m³)."""
    out = {k: ([_clean(x) for x in v] if isinstance(v, list) else v if isinstance(v, str) or v is None else _clean(v))
           for k, v in c.items()}
    if c.get("g0_m3") is not None:
        out["g0_m3"] = float(f"{c['g0_m3']:.6g}")
    return out


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
        **({"lateral_stiffness_kN_per_m": _clean(t.lateral_stiffness_kN_per_m[0]),
            "lateral_damping_kN_s_per_m": _clean(t.lateral_damping_kN_s_per_m[0]),
            "lateral_source": t.lateral_source,
            "lateral_stiffness_ci95_kN_per_m": None if t.lateral_ci95_kN_per_m is None
            else [_clean(t.lateral_ci95_kN_per_m[0][0]), _clean(t.lateral_ci95_kN_per_m[1][0])]}
           if t.lateral_stiffness_kN_per_m is not None else {}),
    }


def result_json(results: list[RideResult]) -> dict:
    """The ``tyrelab ride`` JSON: the first pressure pair at the top, every pair under ``sweep``.

    Top-level keys: ``name``, ``scenario``, ``track``, ``lateral_model`` and ``lateral_note`` (3-D:
    the tyres' lateral elements and what a_wy rests on; null in the pitch plane),
    ``a8_lateral_ci95_m_s2`` (a stand-in lateral stiffness: per speed A(8) with it at the ends of its
    95 % interval; else null), ``road_class`` (a profile or CRG road: per
    wheel track its ISO 8608 ``class``, fitted ``g0_m3``, ``rms_m``, ``length_m``, ``band_cycles_per_m``;
    null for a generated track), ``spectrum_source``,
    ``hours_per_day``, ``working_speed_km_h`` (``[exposure]``'s, else the middle speed), ``tyres`` (``front``/``rear``: size, pressure, stiffness and
    damping per tyre at the first speed, their sources, radius, footprint,
    warnings, ``stiffness_u_kN_per_m``), ``natural_frequencies_Hz`` (``bounce``, ``pitch``)
    and ``natural_frequencies_Hz_ci95`` (their 95 % intervals from the tyre stiffness uncertainty),
    ``nodal_points_m`` (ahead of the CG), ``speeds`` (one object per speed:
    ``speed_km_h``, pressures and tyre values used, ``a_wz_m_s2`` (W_k),
    ``a_wx_m_s2`` (W_d), ``expected_a_wz_m_s2``/``expected_a_wx_m_s2`` (frequency
    domain), ``a_v_m_s2`` (k = 1.4 on x), ``vdv_m_s1_75``, ``vdv_daily_m_s1_75``,
    ``crest_factor``, ``mtvv_m_s2``, ``lift_off_fraction_front``/``_rear``, ``a8_m_s2``, ``a8_axis`` (the
    axis that governs A(8): largest k·a_w),
    ``hours_to_eav``, ``hours_to_elv``, ``verdict``, ``duration_s``,
    ``simulation``, ``method``: ``"time"``), ``warnings`` and, for more than one pressure pair, ``sweep``
    (one object per pair with ``front_pressure_bar``, ``rear_pressure_bar``,
    ``tyres``, ``natural_frequencies_Hz``, ``nodal_points_m``, ``speeds``).

    A variant computed in the frequency domain (:mod:`tyrelab.vehicle.spectral_ride`) has spectral
    ``speeds`` (``method``: ``"spectral"``; ``vdv_*``, ``mtvv_m_s2``, ``crest_factor`` and
    ``lift_off_fraction_*`` null; ``evdv_m_s1_75``, ``evdv_daily_m_s1_75``, ``front_tyre_force_sd_N``,
    ``rear_tyre_force_sd_N``, ``lift_off_probability_front``/``_rear`` besides) and, where it was
    simulated too, ``time_domain``: those speeds' time rows.
    """
    if not _validate.instances("results", results, RideResult):
        raise ValueError("results must hold at least one RideResult")
    def block(r: RideResult) -> dict:
        return {
            "tyres": {ax: _tyre_json(r.tyres[ax]) for ax in ("front", "rear")},
            "natural_frequencies_Hz": {k: _clean(v) for k, v in r.natural_frequencies_Hz.items()},
            "natural_frequencies_Hz_ci95": {k: None if v is None else [_clean(x) for x in v]
                                            for k, v in r.natural_frequency_intervals_Hz.items()},
            "nodal_points_m": {k: _clean(v) for k, v in r.nodal_points_m.items()},
            "speeds": [{k: _clean(v) for k, v in row.items()} for row in r.speeds.to_dict(orient="records")],
            **({"time_domain": [{k: _clean(v) for k, v in row.items()} for row in r.time_rows.to_dict(orient="records")]}
               if len(r.time_rows) else {}),
        }

    first = results[0]
    sc = first.scenario
    out = {"name": sc.name, "scenario": str(sc.path) if sc.path else None, "track": first.track_label,
           "road_class": {k: _clean_class(v) for k, v in first.road_classes.items()} or None,
           "lateral_model": sc.tractor.lateral_model if sc.tractor.three_d else None,
           "lateral_note": _lateral_note(sc),
           "a8_lateral_ci95_m_s2": [{"speed_km_h": k, "a8_m_s2": [_clean(x) for x in v]}
                                    for k, v in first.a8_lateral_ci95_m_s2.items()] or None,
           "spectrum_source": first.spectrum_source, "hours_per_day": sc.exposure.hours_per_day,
           "working_speed_km_h": sc.exposure.working_speed, **block(first),
           "warnings": sorted({w for r in results for w in r.warnings})}
    if len(results) > 1:
        out["sweep"] = [{"front_pressure_bar": r.tyres["front"].pressure_bar,
                         "rear_pressure_bar": r.tyres["rear"].pressure_bar,
                         **({"variant": {k: _clean(v) for k, v in r.variant.items()}} if r.variant else {}),
                         **block(r)} for r in results]
    return out


def results_table(results: list[RideResult], scenario_id: str | None = None) -> pd.DataFrame:
    """One row per speed × pressure pair (the ``ride_results`` layout).

    ``scenario`` is ``scenario_id`` (default: the scenario's name), ``name`` the scenario's name.
    ``is_nominal`` marks the pair of the scenario's own tyre pressures. The natural frequencies are
    ``modes_Hz`` (text) and one ``<mode>_Hz`` column per mode (``bounce_Hz``, ``pitch_Hz``,
    ``roll_Hz`` always; ``front_axle_roll_Hz``, ``cab_pitch_Hz``, ... where the model has them).
    ``method`` says how a row was computed (``time``, ``spectral``): a variant computed both ways
    (:attr:`RideResult.time_rows`) has its spectral rows, then its time rows.
    """
    _validate.instances("results", results, RideResult)
    frames = []
    for r in results:
        df = pd.concat([r.speeds, r.time_rows], ignore_index=True) if len(r.time_rows) else r.speeds.copy()
        df.insert(0, "scenario", scenario_id or r.scenario.name)
        df.insert(1, "name", r.scenario.name)  # the scenario's own name (``scenario`` may be an id given)
        df["bounce_Hz"] = r.natural_frequencies_Hz.get("bounce", math.nan)
        df["pitch_Hz"] = r.natural_frequencies_Hz.get("pitch", math.nan)
        df["roll_Hz"] = r.natural_frequencies_Hz.get("roll", math.nan)
        for mode, f in r.natural_frequencies_Hz.items():  # every further mode (front_axle_roll_Hz, cab_pitch_Hz, ...)
            df[f"{mode}_Hz"] = f
        df["modes_Hz"] = "; ".join(f"{k} {v:.3f}" if math.isfinite(v) else f"{k} not followed"
                                   for k, v in r.natural_frequencies_Hz.items())
        df["front_stiffness_source"] = r.tyres["front"].stiffness_source
        df["rear_stiffness_source"] = r.tyres["rear"].stiffness_source
        df["working_speed_km_h"] = r.scenario.exposure.working_speed  # the heatmap's speed ([exposure])
        df["is_nominal"] = r.nominal
        df["variant"] = ", ".join(f"{k}={v:g}" for k, v in r.variant.items())
        for k, v in r.variant.items():  # one column per swept key
            df[k] = v
        frames.append(df)
    return pd.concat(frames, ignore_index=True)
