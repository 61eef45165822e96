"""The independent reference model of the second system (tests/vehicle/reference_lateral.py, issue 33):
checked against closed forms, and against the project's 3-D model where both have no lateral tyre
elements (today's ``lateral_model = "none"``): frequencies within 1 %, seat a_wx, a_wy, a_wz within 3 %."""

import math

import numpy as np
import pytest

from tyrelab.vehicle import iso2631, ride
from tyrelab.scenario_io import load_scenario

from . import reference_lateral as ref
from .test_ride_3d import A, B, C_TYRE, H, I_PITCH, I_ROLL, K_TYRE, M, SEAT, TF, TR, sine_tracks, text, weighted

I_AXLE = 160.0


def tractor(**kw) -> ref.Tractor:
    base = dict(mass_kg=M, pitch_inertia_kg_m2=I_PITCH, roll_inertia_kg_m2=I_ROLL, yaw_inertia_kg_m2=6000.0,
                front_distance_m=A, rear_distance_m=B, cg_height_m=H, front_track_m=TF, rear_track_m=TR,
                k_front=1e3 * K_TYRE["front"], c_front=1e3 * C_TYRE["front"], k_rear=1e3 * K_TYRE["rear"],
                c_rear=1e3 * C_TYRE["rear"], axle_roll_inertia_kg_m2=I_AXLE,
                seat=(SEAT["ahead"], SEAT["left"], SEAT["height"]))
    base.update(kw)
    return ref.Tractor(**base)


def test_laterally_rigid_tyres_roll_about_the_ground_with_the_gravity_term():
    """k_y -> inf: y = -h phi, (I + m h²) phi'' + (k_r - m g h) phi = 0 (the familiar m g h)."""
    t = tractor(lateral="kelvin_voigt", ky_front=1e12, ky_rear=1e12)
    k_r = 1e3 * (K_TYRE["front"] * TF**2 + K_TYRE["rear"] * TR**2) / 2
    expected = math.sqrt((k_r - M * ref.G * H) / (I_ROLL + M * H**2)) / (2 * math.pi)
    f = ref.natural_frequencies_Hz(t)
    assert np.min(np.abs(f - expected)) / expected < 1e-4
    no_gravity = ref.natural_frequencies_Hz(tractor(lateral="kelvin_voigt", ky_front=1e12, ky_rear=1e12,
                                                    gravity=False))
    assert np.min(np.abs(no_gravity - math.sqrt(k_r / (I_ROLL + M * H**2)) / (2 * math.pi))) < 1e-4


def test_lateral_springs_give_a_low_coupled_lateral_roll_mode():
    """The issue's point: a body on lateral tyre springs has a lateral-roll mode below the roll-about-
    the-CG frequency; the lateral and roll-about-CG systems are its limits."""
    none = ref.natural_frequencies_Hz(tractor())
    roll_cg = math.sqrt(1e3 * (K_TYRE["front"] * TF**2 + K_TYRE["rear"] * TR**2) / 2 / I_ROLL) / (2 * math.pi)
    assert np.min(np.abs(none - roll_cg)) < 1e-6
    soft = ref.natural_frequencies_Hz(tractor(lateral="kelvin_voigt", ky_front=100e3, ky_rear=150e3))
    assert soft.min() < 0.75 * roll_cg  # 2 x 100 + 2 x 150 kN/m: the low lateral-roll mode


def test_maxwell_limits():
    """A Maxwell element with a locked damper is the Kelvin-Voigt spring alone; with a free damper
    it carries nothing (the lateral rigid-body motion is free: zero frequencies)."""
    kv = tractor(lateral="kelvin_voigt", ky_front=200e3, ky_rear=300e3)
    locked = tractor(lateral="maxwell", ky_front=200e3, ky_rear=300e3, cy_front=1e12, cy_rear=1e12)
    for f in (0.7, 1.5, 3.0):
        a = ref.seat_response(kv, f, {"front_left": 0.01, "rear_left": 0.01}, 2.5)
        b = ref.seat_response(locked, f, {"front_left": 0.01, "rear_left": 0.01}, 2.5)
        for ax in "xyz":
            assert b[ax] == pytest.approx(a[ax], rel=1e-6, abs=1e-12)
    # a free damper: the body floats laterally (the patches hold nothing; gravity's -m g y with no
    # lateral spring would tip it, so without gravity): the vertical answer of no lateral element
    free_ng = tractor(lateral="maxwell", ky_front=200e3, ky_rear=300e3, cy_front=1e-9, cy_rear=1e-9, gravity=False)
    c = ref.seat_response(free_ng, 1.5, {"front_left": 0.01, "rear_left": 0.01}, 2.5)
    n = ref.seat_response(tractor(), 1.5, {"front_left": 0.01, "rear_left": 0.01}, 2.5)
    assert c["z"] == pytest.approx(n["z"], rel=1e-6)


def _project(tmp_path, left, right, pivot):
    front_axle = f'[front_axle]\nmount = "pivot"\nroll_inertia_kg_m2 = {I_AXLE}' if pivot else ""
    body = text(sine_tracks(tmp_path, left, right), "[9]", front_axle)
    (tmp_path / "s.toml").write_text(body)
    return ride.ride(load_scenario(tmp_path / "s.toml"), with_spectra=False)


@pytest.mark.parametrize("pivot", [False, True])
@pytest.mark.parametrize("inputs", ["pure_roll", "one_sided"])
def test_reference_agrees_with_the_project_without_lateral_elements(tmp_path, pivot, inputs):
    """Today's 3-D model (no lateral tyre force) against the reference with ``lateral = "none"``: the
    same frequencies (1 %) and seat a_w (3 %) for pure-roll and one-sided sinusoids, rigid and
    pivoting front axles."""
    amp = 0.01
    left, right = (amp, -amp) if inputs == "pure_roll" else (amp, 0.0)
    res = _project(tmp_path, left, right, pivot)
    t = tractor(pivot_front=pivot)
    freqs = ref.natural_frequencies_Hz(t)
    for name, f in res.natural_frequencies_Hz.items():
        assert np.min(np.abs(freqs - f)) / f < 0.01, (name, f, freqs)
    v = 9 / 3.6
    f = v / 2.0  # the tracks' 2 m wavelength
    amps = {"front_left": left, "rear_left": left, "front_right": right, "rear_right": right}
    seat = ref.seat_response(t, f, amps, v)
    row = res.speeds.iloc[0]
    for ax, wname in (("z", "Wk"), ("x", "Wd"), ("y", "Wd")):
        expected = weighted(seat[ax], f, wname)
        assert row[f"a_w{ax}_m_s2"] == pytest.approx(expected, rel=0.03, abs=1e-6), (ax, row[f"a_w{ax}_m_s2"], expected)


KY, CY = {"front": 200.0, "rear": 300.0}, {"front": 2.0, "rear": 3.0}  # kN/m, kN s/m per tyre
I_YAW = 6000.0


def _project_lateral(tmp_path, left, right, pivot, lateral):
    front_axle = (f'[front_axle]\nmount = "pivot"\nroll_inertia_kg_m2 = {I_AXLE}\nheight_m = 0.6' if pivot else "")
    body = text(sine_tracks(tmp_path, left, right), "[9]", front_axle, lateral=lateral)
    body = body.replace(f'lateral_model = "{lateral}"', f'lateral_model = "{lateral}"\nyaw_inertia_kg_m2 = {I_YAW}')
    for axle in ("front", "rear"):
        body = body.replace(f"[tyres.{axle}]\n", f"[tyres.{axle}]\nlateral_stiffness_kN_per_m = {KY[axle]}\n"
                                                 f"lateral_damping_kN_s_per_m = {CY[axle]}\n")
    (tmp_path / "s.toml").write_text(body)
    return ride.ride(load_scenario(tmp_path / "s.toml"), with_spectra=False)


@pytest.mark.parametrize("lateral", ["kelvin_voigt", "maxwell"])
@pytest.mark.parametrize("pivot", [False, True])
@pytest.mark.parametrize("inputs", ["pure_roll", "one_sided"])
def test_reference_agrees_with_the_projects_second_system(tmp_path, lateral, pivot, inputs):
    """Issue 33's check: the project's 3-D tractor on lateral tyre elements (y, yaw, the static loads'
    moment) against the independent reference: natural frequencies within 1 %, seat a_wx, a_wy, a_wz
    within 3 %, rigid and pivoting front axles, Kelvin-Voigt and Maxwell lateral tyres, pure-roll and
    one-sided sinusoids."""
    amp = 0.01
    left, right = (amp, -amp) if inputs == "pure_roll" else (amp, 0.0)
    res = _project_lateral(tmp_path, left, right, pivot, lateral)
    t = tractor(pivot_front=pivot, lateral=lateral, yaw_inertia_kg_m2=I_YAW, pivot_height_m=0.6,
                ky_front=1e3 * KY["front"], ky_rear=1e3 * KY["rear"], cy_front=1e3 * CY["front"],
                cy_rear=1e3 * CY["rear"])
    # issue 42: the modes are the roots of the damped model (a Maxwell element's too: no mode the roots do not have)
    freqs = np.abs(ref.complex_roots(t)[0]) / (2 * math.pi)
    assert len(res.natural_frequencies_Hz) >= 5
    for name, f in res.natural_frequencies_Hz.items():
        assert np.min(np.abs(freqs - f)) / f < 0.01, (name, f, freqs)
    assert {"yaw", "roll"} <= set(res.natural_frequencies_Hz) and \
        ({"lateral_roll", "lateral"} & set(res.natural_frequencies_Hz))
    v = 9 / 3.6
    f = v / 2.0
    amps = {"front_left": left, "rear_left": left, "front_right": right, "rear_right": right}
    seat = ref.seat_response(t, f, amps, v)
    row = res.speeds.iloc[0]
    for ax, wname in (("z", "Wk"), ("x", "Wd"), ("y", "Wd")):
        expected = weighted(seat[ax], f, wname)
        assert row[f"a_w{ax}_m_s2"] == pytest.approx(expected, rel=0.03, abs=1e-6), (ax, row[f"a_w{ax}_m_s2"], expected)


def test_a_lateral_element_acts_only_while_its_tyre_touches_the_ground():
    """Issue 33: the ground under the front left wheel falls away (the tyre lifts off for the whole run):
    its lateral element carries nothing, so the run is the same with that element's stiffness zeroed;
    without lift-off (the tyre pulled down with the ground) the element acts and the runs differ."""
    import dataclasses

    from tyrelab.vehicle.model import Axle, Chassis, Parts, SeatPoint, assemble
    from tyrelab.vehicle.tractor import simulate

    def assembly(zero_front_left: bool):
        fa = Axle("front", A, 1e3 * K_TYRE["front"], 1e3 * C_TYRE["front"], TF, lateral_model="kelvin_voigt",
                  lateral_stiffness_N_per_m=2e5, lateral_damping_N_s_per_m=2e3)
        ra = Axle("rear", -B, 1e3 * K_TYRE["rear"], 1e3 * C_TYRE["rear"], TR, lateral_model="kelvin_voigt",
                  lateral_stiffness_N_per_m=3e5, lateral_damping_N_s_per_m=3e3)
        asm = assemble(Parts(Chassis(M, I_PITCH, H, I_ROLL, I_YAW), fa, ra, SeatPoint(SEAT["ahead"], SEAT["left"],
                                                                                    SEAT["height"]),
                             static_load_moment=True))
        if zero_front_left:
            asm.elements = [dataclasses.replace(e, stiffness=0.0, damping=0.0) if e.name == "front_left_lateral" else e
                            for e in asm.elements]
        return asm

    asms = [assembly(False), assembly(True)]
    t = np.arange(2 * 2000 - 1) * 0.5e-3
    u = np.zeros((2, len(asms[0].tyres), t.size))
    du = np.zeros_like(u)
    j = asms[0].tyres.index("front_left")
    u[:, j] = -0.5 * np.clip(t / 0.01, 0.0, 1.0)  # 0.5 m down in 10 ms
    du[:, j] = np.where(t < 0.01, -50.0, 0.0)
    lifted = simulate(asms, u, du, method="rk4", record=("seat_lateral_m_s2",))
    assert lifted["lift_off_fraction_front_left"][0] == 1.0
    assert np.max(np.abs(lifted["seat_lateral_m_s2"][0])) > 0.5  # the body does move sideways
    assert np.array_equal(lifted["seat_lateral_m_s2"][0], lifted["seat_lateral_m_s2"][1])
    held = simulate(asms, u, du, method="rk4", lift_off=False, record=("seat_lateral_m_s2",))
    assert np.max(np.abs(held["seat_lateral_m_s2"][0] - held["seat_lateral_m_s2"][1])) > 0.05
