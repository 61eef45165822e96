"""A scenario's track and what the wheels see of it (issue 45): the profile with its lead-in and
spectrum, each wheel track enveloped, and the ground input under every tyre.

:func:`build_profile` generates or reads the track (ISO 8608, slatted, a profile file, a CRG road)
and describes its spectrum for the frequency-domain path; :func:`wheel_inputs` is the one
construction of the ground elevation and rate under each tyre element (the ch. 7 study's:
the enveloped wheel track as a spline, the rear wheels a wheelbase later, on their own tracks where
the road has them, each side's offset at the start removed), at the half steps the RK4 reads or the
full steps of the exact linear path.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ... import _validate
from ..._validate import positive
from .. import crg
from .. import enveloping as ev
from .. import profiles as pr
from .. import road_class as rc
from ..terrain.wheel_inputs import half_step_input
from ..model import Assembly
from ..scenario import Scenario

__all__ = ["DT_S", "FS_HZ", "Track", "build_profile", "road_classes", "crg_profile", "wheel_inputs",
           "axle_inputs", "tyre_inputs"]

#: Simulation step of the ride, s (the ch. 7 study's): the inputs are sampled at it.
DT_S = 1e-3
FS_HZ = 1.0 / DT_S


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
    """Generate or read the scenario's track, add the lead-in, describe its spectrum.

    See Also
    --------
    road_classes : the class of a profile or CRG road's tracks.
    tyrelab.vehicle.profiles.iso8608_track : a generated track.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> tr = build_profile(s)                            # class C, 400 m, seed 1, with its lead-in
    >>> round(tr.length_m, 1), bool(tr.lead_in_m >= s.tractor.wheelbase_m), tr.spectrum is not None
    (400.0, True, True)
    """
    _validate.instance("scenario", scenario, Scenario)
    s = scenario.surface
    lead = max(s.lead_in_m, scenario.tractor.wheelbase_m + 1.0)
    side = None
    width = track_width_m(scenario)
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
        # segments of at least 8 samples; each segment's mean taken out (profiles.side_spectra)
        seg = max(min(51.2, prof.x_m[-1] / 4), 8 * prof.dx_m)
        n_w, g_ll, g_rr, g_lr = pr.side_spectra(prof.left_m, prof.right_m, prof.dx_m, seg)
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
    own tracks, ``rear_left``, ``rear_right``.

    See Also
    --------
    tyrelab.vehicle.road_class.road_class : the class of one track.

    Examples
    --------
    >>> from tyrelab.vehicle.profiles import iso8608_track
    >>> {k: v["class"] for k, v in road_classes(iso8608_track("C", seed=1, length_m=400.0)).items()}
    {'left': 'C', 'right': 'C'}
    """
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
    track width differs from the front's).

    See Also
    --------
    build_profile : reads it for a ``kind = "crg"`` surface.
    tyrelab.vehicle.crg.wheel_tracks : the wheel lines of a CRG road.

    Examples
    --------
    A 60 m road with a 1 % cross-fall, ridden by the shipped 3-D tractor (tracks 1.95 m front, 1.90 m
    rear): each wheel on its own line.

    >>> import tempfile, pyopencrg
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> tmp = Path(tempfile.mkdtemp())
    >>> u, v = np.arange(0, 60.01, 0.05), np.arange(-1.5, 1.51, 0.1)
    >>> pyopencrg.CrgRoad(np.outer(np.ones(u.size), 0.01 * v), u_inc=0.05, v=v).save(str(tmp / "road.crg"), fmt="KRBI")
    >>> head, rest = (scenarios_dir() / "modern_3d_tractor.toml").read_text().split("[surface]")
    >>> surface = ["[surface]", 'kind = "crg"', 'file = "road.crg"', "", rest[rest.index("[exposure]"):]]
    >>> _ = (tmp / "tractor.toml").write_text(head + chr(10).join(surface))
    >>> p = crg_profile(load_scenario(tmp / "tractor.toml"))
    >>> float(p.x_m[-1]), [round(float(h[100]) * 1e3, 3) for h in (p.left_m, p.right_m, p.rear_left_m, p.rear_right_m)]
    (60.0, [9.75, -9.75, 9.5, -9.5])
    """
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


def track_width_m(scenario: Scenario) -> float | None:
    """Distance between the two wheel tracks: the mean of the front and rear track widths (3-D), m."""
    t = scenario.tractor
    return 0.5 * (t.front_track_m + t.rear_track_m) if t.three_d else None


def envelope_side(track: pr.Profile, side: str, kind: str, footprint_m: float, radius_m: float,
                  axle: str = "front") -> np.ndarray:
    """One wheel track's enveloped elevation under ``axle``'s wheels (:meth:`Profile.track`):
    ``side`` ``left``, ``right``, or ``mean`` (the two enveloped, then averaged, as the ch. 7 study)."""
    if side == "mean":
        return 0.5 * (envelope_side(track, "left", kind, footprint_m, radius_m, axle)
                      + envelope_side(track, "right", kind, footprint_m, radius_m, axle))
    dx = track.dx_m
    h = track.track(side, axle)
    if kind == "tapered":
        h = ev.tapered_moving_average(h, dx, footprint_m)
    elif kind == "fixed":
        h = ev.fixed_footprint(h, dx, footprint_m)
    elif kind == "rigid_band":
        h = ev.rigid_tread_band(h, dx, radius_m)
    return h


def wheel_inputs(tyres, three_d: bool, track: pr.Profile, kind: str, footprints: tuple[float, float],
                 radii: tuple[float, float], speed_m_s: float, wheelbase_m: float, n_steps: int, *,
                 half_steps: bool = True, enveloped=None, memo: dict | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Ground elevation and rate under each tyre element, shape ``(tyres, samples)``: the one
    construction of the ride's wheel inputs.

    The pitch plane: the axle-mean enveloped track under each axle; in 3-D each wheel on its own
    side's track. Each axle's wheels are enveloped with that axle's footprint (or radius) on that
    axle's tracks (a road with rear tracks of its own: :meth:`tyrelab.vehicle.profiles.Profile.track`),
    the front axle's input a wheelbase ahead (:func:`tyrelab.vehicle.carriage.half_step_input`), and
    each side's offset at the start (the mean of its front and rear elevation) removed.

    Parameters
    ----------
    tyres : sequence of str
        The tyre elements (``front``/``rear``, or ``front_left``, ...: :attr:`Assembly.tyres`), rows in order.
    three_d : bool
        Each wheel on its own side's track (else the axle mean).
    half_steps : bool
        At ``dt/2`` for RK4 (``2 n_steps - 1`` samples), else the full steps (``n_steps``) of the
        exact linear path.
    enveloped : callable, optional
        ``(side, axle, footprint_m, radius_m) -> elevation``: the enveloped wheel track
        (:meth:`tyrelab.vehicle.run.plan.RideCache.envelope` shares them between runs); default
        :func:`envelope_side`.
    memo : dict, optional
        Keeps each wheel's input by side, axle, enveloping, speed and steps (the variants of a speed share them).

    Returns
    -------
    u_m, u_dot_m_s : ndarray, shape (len(tyres), samples)
    """
    _validate.instance("track", track, pr.Profile)
    positive("speed_m_s", speed_m_s)
    _validate.positive_int("n_steps", n_steps)
    if enveloped is None:
        def enveloped(side, axle, fp, r):
            return envelope_side(track, side, kind, fp, r, axle)

    def wheel(side: str, j: int):
        axle = ("front", "rear")[j]
        key = (side, axle, kind, footprints[j], radii[j], speed_m_s, n_steps, half_steps)
        if memo is not None and key in memo:
            return memo[key]
        h = enveloped(side, axle, footprints[j], radii[j])
        out = half_step_input(track.x_m, h, speed_m_s, n_steps, wheelbase_m if j == 0 else 0.0, DT_S,
                              half_steps=half_steps)
        if memo is not None:
            memo[key] = out
        return out

    rows = {}
    for side in (("left", "right") if three_d else ("mean",)):
        (uf, udf), (ur, udr) = wheel(side, 0), wheel(side, 1)
        u0 = 0.5 * (uf[0] + ur[0])
        rows["front" if side == "mean" else f"front_{side}"] = (uf - u0, udf)
        rows["rear" if side == "mean" else f"rear_{side}"] = (ur - u0, udr)
    if not three_d:  # the pitch plane: every element of an axle on the axle mean
        rows = {t: rows[t.split("_")[0]] for t in tyres}
    return np.array([rows[t][0] for t in tyres]), np.array([rows[t][1] for t in tyres])


def axle_inputs(track: pr.Profile, kind: str, footprints: tuple[float, float], radii: tuple[float, float],
                speed_m_s: float, wheelbase_m: float, n_steps: int):
    """Front and rear ground elevation and rate at ``dt/2`` (for RK4), rear delayed by the wheelbase:
    the pitch plane's :func:`wheel_inputs` (the ch. 7 study's inputs).

    Returns
    -------
    uf, udf, ur, udr : ndarray, shape (2 n_steps - 1,)

    See Also
    --------
    tyre_inputs : the same under each tyre element of an assembly.
    build_profile : the track it reads.

    Examples
    --------
    >>> p = pr.add_lead_in(pr.iso8608_track("C", seed=1, length_m=50.0), 5.0)
    >>> uf, udf, ur, udr = axle_inputs(p, "fixed", (0.3, 0.3), (0.7, 0.7), speed_m_s=2.0, wheelbase_m=2.5, n_steps=4001)
    >>> uf.shape, bool(np.allclose(ur[2500:], uf[:-2500]))     # the rear follows 1.25 s (2500 half steps) later
    ((8001,), True)
    """
    u, du = wheel_inputs(("front", "rear"), False, track, kind, footprints, radii, speed_m_s, wheelbase_m, n_steps)
    return u[0], du[0], u[1], du[1]


def tyre_inputs(asm, track: pr.Profile, kind: str, footprints: tuple[float, float], radii: tuple[float, float],
                speed_m_s: float, wheelbase_m: float, n_steps: int) -> tuple[np.ndarray, np.ndarray]:
    """Ground elevation and rate under each tyre element of ``asm`` at ``dt/2``, shape
    ``(tyres, 2 n_steps - 1)``: :func:`wheel_inputs` for an assembly.

    See Also
    --------
    axle_inputs : the pitch plane's two axles.

    Examples
    --------
    >>> from tyrelab.vehicle.model import Axle, Chassis, Parts, assemble
    >>> asm = assemble(Parts(Chassis(5120.0, 6210.0, 0.838), Axle("front", 1.54, 4.25e5, 1.5e3),
    ...                      Axle("rear", -0.896, 3.3e5, 1e3)))            # the pitch plane: one element per axle
    >>> p = pr.add_lead_in(pr.iso8608_track("C", seed=1, length_m=50.0), 5.0)
    >>> u, du = tyre_inputs(asm, p, "fixed", (0.3, 0.3), (0.7, 0.7), 2.0, 2.5, 4001)
    >>> u.shape, bool(np.allclose(u, axle_inputs(p, "fixed", (0.3, 0.3), (0.7, 0.7), 2.0, 2.5, 4001)[::2]))
    ((2, 8001), True)
    """
    _validate.instance("asm", asm, Assembly)
    return wheel_inputs(asm.tyres, asm.parts.three_d, track, kind, footprints, radii, speed_m_s, wheelbase_m, n_steps)
