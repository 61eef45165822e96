"""Issue 43 with the rolling tyre of issue 42: the virtual stand's 3-D tractor on rolling tyres at 6 and
11 km/h (stationary tyres at 0) against an independent reference, and the estimator against it.

The reference is written here by hand with numpy only, not tyrelab's assembly: the stand's MF698T as
a rigid body (bounce ``z``, pitch ``th`` nose up, roll ``phi`` left side up, lateral ``y`` left, yaw
``psi`` nose left; small angles, SI) on four tyres at ``(a_i, b_i)`` from the CG, their contact
patches ``h`` (the CG height) below it:

* vertical Kelvin-Voigt tyres, deflection ``z + a_i th + b_i phi - u_i`` (``u_i`` the pad);
* the rolling tyre of thesis §2.5: a Kelvin-Voigt unit ``k_y, c_y`` from the patch point of the body
  (lateral displacement ``d_i = y + h phi + a_i psi``) to a massless contact point ``s_i``, in series
  with a damper ``c₂ = a / v`` from the contact point to the ground: ``c₂ s_i' = k_y (d_i - s_i) +
  c_y (d_i' - s_i')``; at 0 km/h ``c₂ = ∞`` (``s_i = 0``);
* each tyre's static load ``F_i`` (the axle's share of ``m g``) acts where the tyre touches the
  ground: about the CG it turns the body by ``F_i (s_i - y)`` in roll;
* the cab-floor channels at the seat point (the CG: the scenario has no ``[seat]``), read by
  body-fixed accelerometers: vertical ``z''``, longitudinal ``g th`` (no fore-aft freedom), lateral
  ``y'' + g phi``, and the angular accelerations.

The coefficients are given: the scenario's numbers, its tyres' lateral K, C and ``a`` (the model's
stand-ins, resolved once by the tyre layer), the stationary tyres' stiffness × 1.5 (the stand's
documented choice). Checked: the project's model (what the stand records and the prediction uses)
against the reference; the estimator's FRFs and modes from stand recordings against the reference;
road-correlated inputs flagged, not fitted; height inputs giving the FRFs of acceleration inputs.
"""

import dataclasses
import math

import numpy as np
import pandas as pd
import pytest

from tyrelab import stand
from tyrelab.api import vehicle_frf

G = 9.80665
OUTPUTS = ("floor_z_m_s2", "floor_x_m_s2", "floor_y_m_s2", "roll_rad_s2", "pitch_rad_s2", "yaw_rad_s2")
Z, TH, PHI, Y, PSI = range(5)


@pytest.fixture(scope="module")
def scenario():
    return stand.stand_scenario()


def _row(ride_id):
    return next(r for r in stand.stand_plan().to_dict("records") if r["ride_id"] == ride_id)


def _tyres(scenario, speed_km_h):
    """Per wheel ``(a, b, k_z, c_z, k_y, c_y, c₂, F)``, SI, wheels front left, front right, rear left,
    rear right."""
    from tyrelab.vehicle.tyres import resolve_tyres

    t = scenario.tractor
    rolling = dataclasses.replace(scenario, exposure=dataclasses.replace(scenario.exposure, speeds_km_h=(6.0,)))
    lat = resolve_tyres(rolling)  # the given coefficients: the tyres' lateral stand-ins
    factor = 1.5 if speed_km_h == 0 else 1.0
    wheelbase = t.front_distance_m + t.rear_distance_m
    out = []
    for axle, a, track, share in (("front", t.front_distance_m, t.front_track_m, t.rear_distance_m / wheelbase),
                                  ("rear", -t.rear_distance_m, t.rear_track_m, t.front_distance_m / wheelbase)):
        spec, ty = getattr(scenario, axle), lat[axle]
        kz, cz = float(spec.stiffness_kN_per_m) * 1e3 * factor, float(spec.damping_kN_s_per_m) * 1e3
        ky = float(ty.lateral_stiffness_kN_per_m[0]) * 1e3 * factor
        cy = float(ty.lateral_damping_kN_s_per_m[0]) * 1e3
        c2 = math.inf if speed_km_h == 0 else float(ty.lateral_series_damping_kN_s_per_m_km_h) * 1e3 / speed_km_h
        for b in (track / 2, -track / 2):
            out.append((a, b, kz, cz, ky, cy, c2, t.mass_kg * G * share / 2))
    return out


def _mass(scenario):
    t = scenario.tractor
    # no yaw inertia in the scenario: the pitch inertia (the model's documented stand-in)
    return np.diag([t.mass_kg, t.pitch_inertia_kg_m2, t.roll_inertia_kg_m2, t.mass_kg, t.pitch_inertia_kg_m2])


def _rows(scenario, a, b):
    h = scenario.tractor.cg_height_m
    return np.array([1.0, a, b, 0.0, 0.0]), np.array([0.0, 0.0, h, 1.0, a])


def _dynamic(scenario, speed_km_h, s, tyres=None):
    """The dynamic matrix over ``[q (5), s_i (rolling: 4)]`` at the Laplace variable ``s`` and the
    ground rows (``rhs[:, j]`` per metre of pad ``j``); ``tyres``: :func:`_tyres`' (resolved once)."""
    tyres = _tyres(scenario, speed_km_h) if tyres is None else tyres
    rolling = speed_km_h > 0
    n = 5 + (4 if rolling else 0)
    d = np.zeros((n, n), complex)
    d[:5, :5] = s ** 2 * _mass(scenario)
    rhs = np.zeros((n, 4), complex)
    for i, (a, b, kz, cz, ky, cy, c2, load) in enumerate(tyres):
        gz, gy = _rows(scenario, a, b)
        zz, zy = kz + s * cz, ky + s * cy
        d[:5, :5] += zz * np.outer(gz, gz) + zy * np.outer(gy, gy)
        d[PHI, Y] += load  # the load at the contact point: -F (y - s_i) in roll
        rhs[:5, i] = zz * gz
        if rolling:
            j = 5 + i
            d[:5, j] -= zy * gy
            d[j, :5] = -zy * gy
            d[j, j] = zy + s * c2
            d[PHI, j] -= load
    return d, rhs


def reference_frf(scenario, speed_km_h, frequency_Hz):
    """(F, 6 outputs of :data:`OUTPUTS`, 4 wheels) per m/s² of pad acceleration."""
    out = np.zeros((len(frequency_Hz), len(OUTPUTS), 4), complex)
    tyres = _tyres(scenario, speed_km_h)
    for n, f in enumerate(frequency_Hz):
        w = 2 * math.pi * f
        d, rhs = _dynamic(scenario, speed_km_h, 1j * w, tyres)
        q = np.linalg.solve(d, rhs)[:5]  # per metre of pad
        acc = -(w ** 2) * q
        rows = [acc[Z], G * q[TH], acc[Y] + G * q[PHI], acc[PHI], acc[TH], acc[PSI]]
        out[n] = np.array(rows) / -(w ** 2)
    return out


def reference_state_matrix(scenario, speed_km_h):
    """``x' = A x`` over ``[q, q', s_i]``: the contact points' ``s_i' = (k_y e + c_y d') / (c_y + c₂)``
    (``e = d - s``), the unit's force ``c₂ / (c_y + c₂) (k_y e + c_y d')`` on the body."""
    tyres = _tyres(scenario, speed_km_h)
    rolling = speed_km_h > 0
    ns = 4 if rolling else 0
    n = 10 + ns
    k, c = np.zeros((5, n)), np.zeros((5, n))  # generalised force = -(k x) (over the whole state)
    a_s = np.zeros((ns, n))
    for i, (a, b, kz, cz, ky, cy, c2, load) in enumerate(tyres):
        gz, gy = _rows(scenario, a, b)
        k[:, :5] += kz * np.outer(gz, gz)
        k[:, 5:10] += cz * np.outer(gz, gz)
        k[PHI, Y] += load
        if rolling:
            e = np.concatenate([gy, np.zeros(5), -np.eye(ns)[i]])  # e = d - s over the state
            dv = np.concatenate([np.zeros(5), gy, np.zeros(ns)])  # d'
            unit = c2 / (cy + c2) * (ky * e + cy * dv)
            k += np.outer(gy, unit)
            k[PHI, 10 + i] -= load
            a_s[i] = (ky * e + cy * dv) / (cy + c2)
        else:
            k[:, :5] += ky * np.outer(gy, gy)
            k[:, 5:10] += cy * np.outer(gy, gy)
    a = np.zeros((n, n))
    a[:5, 5:10] = np.eye(5)
    a[5:10] = -np.linalg.solve(_mass(scenario), k)
    a[10:] = a_s
    return a


def reference_modes(scenario, speed_km_h):
    """``{name: (damped Hz, damping ratio)}`` of the oscillating roots; bounce and pitch the pairs with
    the largest ``z`` and ``th`` kinetic-energy share, lateral–roll the lowest pair led by ``y`` and
    ``phi`` together."""
    lam, vec = np.linalg.eig(reference_state_matrix(scenario, speed_km_h))
    keep = (lam.imag > 1e-6 * np.abs(lam)) & (np.abs(lam) > 1e-6)
    lam, vel = lam[keep], vec[5:10][:, keep]
    m = np.diag(_mass(scenario))
    share = np.abs(vel) ** 2 * m[:, None]
    share = share / share.sum(axis=0)
    modes = [(l.imag / (2 * math.pi), -l.real / abs(l)) for l in lam]
    order = np.argsort([fd for fd, _ in modes])
    lateral = next(int(i) for i in order if share[Y, i] + share[PHI, i] > 0.6)
    return {"bounce": modes[int(np.argmax(share[Z]))], "pitch": modes[int(np.argmax(share[TH]))],
            "lateral_roll": modes[lateral], "all": sorted(modes)}


@pytest.mark.parametrize("speed", [0.0, 6.0, 11.0])
def test_the_reference_is_one_model_two_ways(scenario, speed):
    """The dynamic matrix is singular at each root of the state matrix (two derivations, one model)."""
    lam = np.linalg.eigvals(reference_state_matrix(scenario, speed))
    lam = lam[np.abs(lam) > 1e-6]
    for root in lam:
        sv = np.linalg.svd(_dynamic(scenario, speed, root)[0], compute_uv=False)
        assert sv[-1] < 1e-9 * sv[0], (root, sv[-1] / sv[0])


@pytest.mark.parametrize("speed", [0.0, 6.0, 11.0])
def test_the_stands_model_is_the_reference(scenario, speed):
    """What the stand records and the validation predicts (the project's assembly with the rolling
    element, :func:`stand.wheel_frf`, :func:`stand.model_modes`) is the reference's to rounding."""
    f = np.linspace(0.3, 20.0, 120)
    got = stand.wheel_frf(scenario, speed, f, OUTPUTS)
    ref = reference_frf(scenario, speed, f)
    assert np.max(np.abs(got - ref) / np.max(np.abs(ref), axis=0, keepdims=True)) < 1e-8
    predicted = stand.model_modes(scenario, speed)
    truth = reference_modes(scenario, speed)
    assert len(predicted) == len(truth["all"])
    for p, (fd, z) in zip(predicted, truth["all"]):
        assert p.frequency_Hz == pytest.approx(fd, rel=1e-8) and p.damping_ratio == pytest.approx(z, rel=1e-7)
    by_name = {p.name: p for p in predicted}
    for name in ("bounce", "pitch", "lateral_roll"):
        assert by_name[name].frequency_Hz == pytest.approx(truth[name][0], rel=1e-8), name
    if speed > 0:  # §2.4.3: the rolling tyre's lateral damping, 20-100 % of critical at 6-11 km/h
        assert 0.2 <= truth["lateral_roll"][1] <= 1.0


def _coherent(r, k, j, f):
    """The coherent band: 0.5-12 Hz, usable (separable, unmasked), multiple coherence ≥ 0.9 and a
    random error of ``|H|`` of 3 % or less (the estimate's own statistics, not the reference)."""
    e = r.estimate
    return ((f >= 0.5) & (f <= 12.0) & r.usable(k)[:, j] & (e.multiple_coherence[:, k] >= 0.9)
            & (e.random_error[:, k, j] <= 0.03))


@pytest.mark.parametrize("ride_id", ["stand_rear_left_still_0kmh", "stand_rear_left_still_6kmh",
                                     "stand_rear_left_still_11kmh", "stand_rear_left_correlated_6kmh"])
def test_stand_recordings_give_the_references_frfs_and_modes(scenario, ride_id):
    row = _row(ride_id)
    speed = row["speed_km_h"]
    r = vehicle_frf(stand.stand_recording(scenario, row, 1991), speed_km_h=speed, scenario=scenario)
    e, f = r.estimate, r.estimate.frequency_Hz
    j = r.inputs.index("input_rear_left_z_m_s2")
    ref = reference_frf(scenario, speed, np.where(f > 0, f, 1.0))[:, :, 2]
    checked = set()
    for k, out in enumerate(r.outputs):
        ok = _coherent(r, k, j, f)
        if ok.sum() < 15:  # floor_x (g th over sensor noise) and yaw: few bins that precise
            continue
        checked.add(out)
        rel = np.abs(np.abs(e.h[ok, k, j]) / np.abs(ref[ok, OUTPUTS.index(out)]) - 1)
        # within 5 % over the coherent band: the median well inside (2 %, or 1.5 times the bins' own median
        # random error where that is larger: 20.48 s segments leave 23 averages, and with correlated inputs
        # the scatter is 1.2-1.6 times B&P's n_d - q random error), 85 % of the bins (the rest: the sharp
        # bounce and pitch peaks, 2-4 % damped, where the Hann window's resolution bias is largest)
        limit = max(0.02, 1.5 * float(np.median(e.random_error[ok, k, j])))
        assert np.median(rel) < limit and np.mean(rel < 0.05) >= 0.85, (out, np.median(rel), limit, np.mean(rel < 0.05))
    assert {"floor_z_m_s2", "pitch_rad_s2", "roll_rad_s2"} <= checked, checked
    truth = reference_modes(scenario, speed)
    for name, out in (("bounce", "floor_z_m_s2"), ("pitch", "pitch_rad_s2")):
        fd, z = truth[name]
        m = min(r.modes[out], key=lambda m: abs(m.frequency_Hz - fd))
        assert m.frequency_Hz == pytest.approx(fd, rel=0.02) and abs(m.damping_ratio - z) < 0.03, (name, m, fd, z)
    # lateral-roll, 41 % damped at 6 km/h and 80 % at 11, overlapping yaw (44 %, 76 %), fitted with the
    # roll, lateral and yaw outputs' poles shared (fit_shared_modes): at 0 and 6 km/h determined, within 2 %
    # and 0.03 and inside its 95 % intervals in every output that shows it. At 11 km/h the pair is not
    # identifiable from this recording (the profile of the fit's cost, a second pole beside it fitting
    # alike): either the mode says so (determined false) or the reference is inside its intervals
    fd, z = truth["lateral_roll"]
    for out in ("roll_rad_s2", "floor_y_m_s2"):
        m = min(r.modes[out], key=lambda m: abs(m.frequency_Hz - fd))
        inside = m.frequency_low_Hz <= fd <= m.frequency_high_Hz and m.damping_low <= z <= m.damping_high
        if speed < 11:
            assert m.determined and inside, (out, m, fd, z)
            assert m.frequency_Hz == pytest.approx(fd, rel=0.02) and abs(m.damping_ratio - z) < 0.03, (out, m, fd, z)
        else:
            assert inside or (not m.determined and m.undetermined_reason), (out, m, fd, z)
    rows = pd.DataFrame(r.mode_rows())
    assert {"natural_frequency_Hz", "determined", "undetermined_reason"} <= set(rows.columns)
    assert (rows["natural_frequency_ci95_low_Hz"] <= rows["natural_frequency_Hz"]).all()


# 6 km/h (the case of issue 43) in the default run; 11 km/h (6.5 s a case) with -m slow (the budget)
@pytest.mark.parametrize("speed", [6.0, pytest.param(11.0, marks=pytest.mark.slow)])
@pytest.mark.parametrize("noise", [0.0, 0.02])
def test_road_correlated_inputs_are_flagged_not_fitted(scenario, speed, noise):
    """Pure road input from the reference (each rear pad its front's signal a wheelbase later: 1.46 s at
    6 km/h, 0.80 s at 11; left and right independent), with and without sensor noise (m/s², rad/s²):
    every input flagged in the band, its delay found, no mode fitted. At 6 km/h with 10.24 s segments (a
    shorter ``min_segment_s``) the delay is 14 % of a segment and the Welch coherence of the front and
    rear inputs only 0.77: the delay, not the coherence, says they cannot be separated."""
    fs, n = stand.STAND_FS_HZ, int(300 * stand.STAND_FS_HZ)
    rng = np.random.default_rng(43)
    f = np.fft.rfftfreq(n, 1 / fs)
    band = (f >= 0.5) & (f <= 12.0)
    lag = (scenario.tractor.front_distance_m + scenario.tractor.rear_distance_m) / (speed / 3.6)
    front = np.fft.rfft(rng.standard_normal((2, n)), axis=1) * band
    pads = np.vstack([front, front * np.exp(-2j * math.pi * f * lag)])  # FL, FR, RL, RR
    h = reference_frf(scenario, speed, np.where(f > 0, f, 1.0))
    h[0] = 0.0
    y = np.fft.irfft(np.einsum("fpq,qf->pf", h, pads), n, axis=1)
    x = np.fft.irfft(pads, n, axis=1)
    cols = {"time_s": np.arange(n) / fs}
    cols.update({f"input_{w}_z_m_s2": x[i] + noise * rng.standard_normal(n) for i, w in enumerate(stand.WHEELS)})
    cols.update({o: y[k] + noise * rng.standard_normal(n) for k, o in enumerate(OUTPUTS)})
    r = vehicle_frf(pd.DataFrame(cols))
    e = r.estimate
    inband = (e.frequency_Hz >= 0.5) & (e.frequency_Hz <= 12.0)
    assert e.ill_conditioned[inband].mean() > 0.98
    assert all(not m for m in r.modes.values())
    np.testing.assert_allclose(e.input_delay_s, [-lag, -lag, lag, lag], atol=1.5 / fs)  # rear behind front
    if speed == 6.0:  # what the Welch coherence alone would not flag: 10.24 s segments
        from tyrelab.measurement import frf

        short = frf.mimo_frf(frf.cross_spectra(np.vstack([cols[f"input_{w}_z_m_s2"] for w in stand.WHEELS]),
                                               np.vstack([cols[o] for o in OUTPUTS]), fs, 512))
        sb = (short.frequency_Hz >= 0.5) & (short.frequency_Hz <= 12.0)
        assert np.median(short.input_coherence[sb]) < 0.9 and short.ill_conditioned[sb].mean() > 0.98


def test_independent_and_partly_common_inputs_have_no_delay_relation(scenario):
    """The stand's correlated run: the rear right pad is the front right's a wheelbase later (flagged:
    those two cannot be separated), the front left shares only a common part with the front right (not
    a delay relation), the measured rear left is independent (never flagged in the band)."""
    r = vehicle_frf(stand.stand_recording(scenario, _row("stand_rear_left_correlated_6kmh"), 1991), speed_km_h=6.0)
    e = r.estimate
    inband = (e.frequency_Hz >= 0.5) & (e.frequency_Hz <= 12.0)
    j = {w: r.wheels.index(w) for w in r.wheels}
    assert not e.ill_conditioned[inband, j["rear_left"]].any()
    assert np.isnan(e.input_delay_s[[j["rear_left"], j["front_left"]]]).all()
    assert e.input_delay_s[j["rear_right"]] == pytest.approx(1.46, abs=0.03)
    assert e.ill_conditioned[inband, j["rear_right"]].mean() > 0.98


def test_height_and_acceleration_inputs_give_the_same_frfs(scenario):
    """The rear-left pad given as its height (m, integrated twice in the frequency domain) and as its
    acceleration: the same FRFs over the coherent band."""
    row = _row("stand_rear_left_still_6kmh")
    acc = stand.stand_recording(scenario, row, 1991)
    n, fs = len(acc), stand.STAND_FS_HZ
    f = np.fft.rfftfreq(n, 1 / fs)
    spec = np.fft.rfft(acc["input_rear_left_z_m_s2"].to_numpy())
    spec = np.where((f >= 0.3) & (f <= 15.0), spec / np.where(f > 0, -(2 * math.pi * f) ** 2, 1.0), 0.0)
    heights = acc.drop(columns="input_rear_left_z_m_s2").assign(input_rear_left_z_m=np.fft.irfft(spec, n))
    a = vehicle_frf(acc, speed_km_h=6.0, scenario=scenario)
    b = vehicle_frf(heights, speed_km_h=6.0, scenario=scenario)
    fa = a.estimate.frequency_Hz
    for k, out in enumerate(a.outputs):
        ok = _coherent(a, k, 0, fa)
        rel = np.abs(np.abs(b.estimate.h[ok, k, 0]) / np.abs(a.estimate.h[ok, k, 0]) - 1)
        assert np.max(rel) < 0.02, (out, np.max(rel))


@pytest.mark.parametrize("speed", [0.0, 6.0, 11.0])
def test_every_oscillating_root_is_named_by_its_shape(scenario, speed):
    """Issue 43 (3): the damped modes' names follow the shapes of the oscillating roots. Every complex
    pair of the reference is a mode, not overdamped, named by the body coordinate holding most of its
    kinetic energy (``lateral_roll`` for the lowest pair led by ``y`` or ``phi``; at 6 km/h the 2.15 Hz
    pair, 86 % yaw, is ``yaw``, not a real root); a real root named only as overdamped, and never under
    an oscillating mode's name."""
    from tyrelab.vehicle.solvers.modes import damped_modes

    modes = damped_modes(stand._assembly(scenario, speed))
    lam, vec = np.linalg.eig(reference_state_matrix(scenario, speed))
    pairs = (lam.imag > 1e-9 * np.abs(lam)) & (np.abs(lam) > 1e-6)
    m = np.diag(_mass(scenario))
    share = np.abs(vec[5:10][:, pairs]) ** 2 * m[:, None]
    names = ("bounce", "pitch", "roll", "lateral", "yaw")
    oscillating = {n: d for n, d in modes.items() if not d.overdamped}
    assert len(oscillating) == int(pairs.sum())
    lowest_lateral = True
    for root, sh in sorted(zip(lam[pairs], share.T), key=lambda t: abs(t[0])):
        name, d = min(oscillating.items(), key=lambda kv: abs(kv[1].root - root))
        assert abs(d.root - root) < 1e-6 * abs(root), (speed, root, d)
        lead = int(np.argmax(sh))
        expected = names[lead]
        if lead in (PHI, Y) and lowest_lateral:
            lowest_lateral = False
            if min(sh[PHI], sh[Y]) >= 0.05 * sh.sum():
                expected = "lateral_roll"
        if lead in (Z, TH):  # bounce and pitch by thesis §8.2's rule (z/θ ratio), as mode_set names them
            expected = d.name if d.name in ("bounce", "pitch") else expected
        assert d.name == expected, (speed, d.name, expected, sh / sh.sum())
    for name, d in modes.items():
        assert d.overdamped == (abs(d.root.imag) <= 1e-9 * abs(d.root)), name
        if d.overdamped:
            assert name not in {n for n, o in oscillating.items()}
    if speed == 6.0:
        assert modes["yaw"].damped_Hz == pytest.approx(2.15, abs=0.01) and not modes["yaw"].overdamped
