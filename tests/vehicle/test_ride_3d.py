"""The 3-D ride (issue 23): roll, left/right tracks, pivot axles, gravity tilt, parts; against
hand-derived steady-state answers (a rigid body rolling on its tyres' roll stiffness)."""

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tyrelab import cli
from tyrelab.vehicle import iso2631, ride
from tyrelab.scenario_io import ScenarioError, load_scenario, parse_scenario

M, I_PITCH, I_ROLL, A, B, H = 4700.0, 5500.0, 2400.0, 1.56, 0.95, 0.95
TF, TR = 1.90, 1.80
SEAT = dict(ahead=-0.4, left=0.35, height=1.0)
K_TYRE, C_TYRE = {"front": 500.0, "rear": 600.0}, {"front": 1.5, "rear": 2.0}  # kN/m, kN s/m per tyre
G = 9.80665  # the standard gravity, the model's since issue 45


def text(surface: str, speeds="[9]", front_axle="", extra="", tilt=False, roll=True, lateral="none") -> str:
    """The tractor of these tests; ``lateral``: its ``lateral_model`` (``none``: the body rolls about its
    CG, the hand-derived answers below; None: the key left out, the 3-D default)."""
    roll_keys = f"roll_inertia_kg_m2 = {I_ROLL}\nfront_track_m = {TF}\nrear_track_m = {TR}" if roll else ""
    if roll and lateral is not None:
        roll_keys += f'\nlateral_model = "{lateral}"'
    return f"""
name = "3-D tractor"
[tractor]
mass_kg = {M}
pitch_inertia_kg_m2 = {I_PITCH}
front_distance_m = {A}
rear_distance_m = {B}
cg_height_m = {H}
{roll_keys}
{front_axle}
[seat]
ahead_of_cg_m = {SEAT['ahead']}
left_of_cg_m = {SEAT['left']}
height_above_cg_m = {SEAT['height']}
gravity_tilt = {'true' if tilt else 'false'}
[tyres.front]
size = "380/85R28"
pressure_bar = 1.6
stiffness_kN_per_m = {K_TYRE['front']}
damping_kN_s_per_m = {C_TYRE['front']}
[tyres.rear]
size = "480/70R38"
pressure_bar = 1.2
stiffness_kN_per_m = {K_TYRE['rear']}
damping_kN_s_per_m = {C_TYRE['rear']}
[surface]
{surface}
[exposure]
speeds_km_h = {speeds}
hours_per_day = 8
{extra}
"""


RAMP_M = 25.0


def _envelope(x):
    """Raised-cosine ramp over the first RAMP_M (no start transient: the modes are hardly excited)."""
    return np.where(x < RAMP_M, 0.5 * (1 - np.cos(np.pi * np.clip(x, 0, RAMP_M) / RAMP_M)), 1.0)


#: r.m.s. of the envelope over the record (the whole track): the steady answer times this.
X = np.arange(0, 600.0, 0.05)
ENVELOPE_RMS = float(np.sqrt(np.mean(_envelope(X) ** 2)))


def sine_tracks(tmp_path: Path, left_amp: float, right_amp: float, wavelength=2.0) -> str:
    x = X
    s = np.sin(2 * np.pi * x / wavelength) * _envelope(x)
    pd.DataFrame({"distance_m": x, "height_left_m": left_amp * s, "height_right_m": right_amp * s}).to_csv(
        tmp_path / "tracks.csv", index=False)
    return 'kind = "profile"\nprofile = "tracks.csv"\nenveloping = "none"'


def run(tmp_path, body: str):
    p = tmp_path / "s.toml"
    p.write_text(body)
    res = ride.ride(load_scenario(p), with_spectra=False)
    return res.speeds.iloc[0]


def roll_answer(f_Hz: float, speed_m_s: float, amplitude_m: float, pivot_front: bool) -> complex:
    """Roll angle (complex amplitude) of a rigid body on its tyres under left/right anti-phase
    sinusoids ``±amplitude``: ``(k_r - I ω² + jω c_r) φ = Σ_axle (k + jω c) t A e^{-jωτ}`` with
    ``k_r = Σ k t²/2`` (per axle two tyres ``t/2`` off the centre); a pivoting front axle passes no
    roll moment (drops out of both sides)."""
    w = 2 * math.pi * f_Hz
    num, den = 0.0, -I_ROLL * w**2
    for axle, t, tau in (("front", TF, 0.0), ("rear", TR, (A + B) / speed_m_s)):
        if axle == "front" and pivot_front:
            continue
        z = 1e3 * K_TYRE[axle] + 1j * w * 1e3 * C_TYRE[axle]
        den += z * t**2 / 2
        num += z * t * amplitude_m * np.exp(-1j * w * tau)
    return num / den


def bounce_pitch_answer(f_Hz: float, speed_m_s: float, amplitude_m: float) -> tuple[complex, complex]:
    """(z, θ) of the beam on two (complex) springs under an in-phase sinusoid under every wheel."""
    w = 2 * math.pi * f_Hz
    zf = 2e3 * K_TYRE["front"] + 2j * w * 1e3 * C_TYRE["front"]
    zr = 2e3 * K_TYRE["rear"] + 2j * w * 1e3 * C_TYRE["rear"]
    delay = np.exp(-1j * w * (A + B) / speed_m_s)
    dyn = np.array([[zf + zr - M * w**2, zf * A - zr * B], [zf * A - zr * B, zf * A**2 + zr * B**2 - I_PITCH * w**2]])
    z, th = np.linalg.solve(dyn, amplitude_m * np.array([zf + zr * delay, zf * A - zr * B * delay]))
    return z, th


def weighted(amplitude: float, f_Hz: float, weighting: str) -> float:
    """Weighted r.m.s. of a sinusoid of complex amplitude ``amplitude`` under the ramped envelope."""
    return abs(amplitude) * abs(iso2631.weighting_response(f_Hz, weighting)) / math.sqrt(2) * ENVELOPE_RMS


@pytest.mark.parametrize("pivot", [False, True])
def test_pure_roll_input_gives_the_rigid_body_roll_answer(tmp_path, pivot):
    """Left and right in anti-phase: no bounce or pitch; the seat (0.35 m left, 1 m above the CG)
    moves vertically by y_s φ'' and laterally by -h_s φ''."""
    amp, speed_km_h, wavelength = 0.003, 9.0, 2.0
    axle = "[front_axle]\nmount = \"pivot\"\nroll_inertia_kg_m2 = 160" if pivot else ""
    row = run(tmp_path, text(sine_tracks(tmp_path, amp, -amp, wavelength), f"[{speed_km_h}]", axle))
    v = speed_km_h / 3.6
    f = v / wavelength
    phi = roll_answer(f, v, amp, pivot)
    w2 = (2 * math.pi * f) ** 2
    assert row["simulation"] == "linear"
    assert row["a_wy_m_s2"] == pytest.approx(weighted(SEAT["height"] * w2 * phi, f, "Wd"), rel=0.03)
    assert row["a_wz_m_s2"] == pytest.approx(weighted(SEAT["left"] * w2 * phi, f, "Wk"), rel=0.03)
    assert row["a_wx_m_s2"] < 1e-6 * row["a_wy_m_s2"]  # nothing pitches
    # the Directive's highest axis: 1.4 a_wy here
    assert row["a8_m_s2"] == pytest.approx(1.4 * max(row["a_wy_m_s2"], row["a_wx_m_s2"], row["a_wz_m_s2"] / 1.4),
                                           rel=1e-12)


def test_gravity_tilt_reads_h_omega2_plus_g_times_phi(tmp_path):
    """A body-fixed accelerometer reads (h ω² + g) φ laterally under a pure roll input."""
    amp, speed_km_h, wavelength = 0.003, 9.0, 2.0
    row = run(tmp_path, text(sine_tracks(tmp_path, amp, -amp, wavelength), f"[{speed_km_h}]", tilt=True))
    v = speed_km_h / 3.6
    f = v / wavelength
    phi = roll_answer(f, v, amp, False)
    reading = (SEAT["height"] * (2 * math.pi * f) ** 2 + G) * phi
    assert row["a_wy_m_s2"] == pytest.approx(weighted(reading, f, "Wd"), rel=0.03)


def test_one_sided_input_is_half_bounce_pitch_half_roll(tmp_path):
    """Left track only: the mean A/2 under every wheel (bounce, pitch) plus ±A/2 (roll)."""
    amp, speed_km_h, wavelength = 0.004, 9.0, 3.0  # not the wheelbase: the tractor pitches
    row = run(tmp_path, text(sine_tracks(tmp_path, amp, 0.0, wavelength), f"[{speed_km_h}]"))
    v = speed_km_h / 3.6
    f = v / wavelength
    w2 = (2 * math.pi * f) ** 2
    z, th = bounce_pitch_answer(f, v, amp / 2)
    phi = roll_answer(f, v, amp / 2, False)
    seat_z = w2 * (z + SEAT["ahead"] * th + SEAT["left"] * phi)
    seat_x = w2 * (-SEAT["height"] * th)
    seat_y = w2 * (-SEAT["height"] * phi)
    assert row["a_wz_m_s2"] == pytest.approx(weighted(seat_z, f, "Wk"), rel=0.03)
    assert row["a_wx_m_s2"] == pytest.approx(weighted(seat_x, f, "Wd"), rel=0.03)
    assert row["a_wy_m_s2"] == pytest.approx(weighted(seat_y, f, "Wd"), rel=0.03)


def test_roll_frequency_from_the_tyres_roll_stiffness(tmp_path):
    res = ride.ride(load_scenario(_write(tmp_path, text('kind = "iso8608"\nclass = "B"\nlength_m = 40'))),
                    with_spectra=False)
    k_roll = 1e3 * (K_TYRE["front"] * TF**2 + K_TYRE["rear"] * TR**2) / 2
    assert res.natural_frequencies_Hz["roll"] == pytest.approx(math.sqrt(k_roll / I_ROLL) / (2 * math.pi), abs=0.01)
    pivot = ride.ride(load_scenario(_write(tmp_path, text('kind = "iso8608"\nclass = "B"\nlength_m = 40', "[9]",
                                                           "[front_axle]\nmount = \"pivot\"\nroll_inertia_kg_m2 = 160"),
                                           "p.toml")), with_spectra=False)
    k_rear = 1e3 * K_TYRE["rear"] * TR**2 / 2
    assert pivot.natural_frequencies_Hz["roll"] == pytest.approx(math.sqrt(k_rear / I_ROLL) / (2 * math.pi), abs=0.01)
    k_axle = 1e3 * K_TYRE["front"] * TF**2 / 2
    assert pivot.natural_frequencies_Hz["front_axle_roll"] == pytest.approx(math.sqrt(k_axle / 160) / (2 * math.pi),
                                                                            abs=0.01)


def test_random_tracks_match_the_cross_spectral_expectation(tmp_path):
    """ISO 8608 tracks, isotropic coherence: the simulated a_w of each axis within sampling error of
    the frequency-domain expectation from the 4 x 4 input cross-spectral matrix."""
    body = text('kind = "iso8608"\nclass = "C"\nlength_m = 1600\ntracks = "isotropic"', "[10]")
    row = run(tmp_path, body)
    for ax in ("z", "x", "y"):
        assert row[f"a_w{ax}_m_s2"] == pytest.approx(row[f"expected_a_w{ax}_m_s2"], rel=0.08), ax


def test_identical_tracks_excite_no_roll(tmp_path):
    row = run(tmp_path, text('kind = "iso8608"\nclass = "C"\nlength_m = 100\ntracks = "identical"'))
    assert row["a_wy_m_s2"] < 1e-9 and row["expected_a_wy_m_s2"] < 1e-9


def _write(tmp_path, body, name="s.toml"):
    p = tmp_path / name
    p.write_text(body)
    return p


# ------------------------------------------------------------------ bad scenarios
def test_bad_3d_scenarios_list_every_problem_and_exit_2(tmp_path, capsys):
    body = text('kind = "iso8608"\nclass = "C"\nlength_m = 20', front_axle="[front_axle]\nmount = \"pivot\"",
                extra="[cab]\nmount = \"suspended\"\nmass_kg = 800\npitch_inertia_kg_m2 = 600\nroll_inertia_kg_m2 = 500\n"
                      "front_mount_ahead_of_cg_m = 0.2\nrear_mount_ahead_of_cg_m = -0.3\nmount_track_m = 1.0\n"
                      "mount_stiffness_kN_per_m = 200")
    body = body.replace(f"front_track_m = {TF}", "front_track_m = -1.9")
    path = _write(tmp_path, body)
    with pytest.raises(ScenarioError) as info:
        load_scenario(path)
    text_ = "\n".join(info.value.problems)
    for expected in ("tractor.front_track_m: -1.9", "front_axle.roll_inertia_kg_m2 is required",
                     "seat.ahead_of_cg_m = -0.4 m lies outside the cab"):
        assert expected in text_, (expected, text_)
    assert cli.main(["ride", str(path)]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and "lies outside the cab" in err and "front_track_m" in err


def test_pitch_plane_keys_refused_without_roll():
    body = text('kind = "iso8608"\nclass = "C"', front_axle="[front_axle]\nmount = \"pivot\"\nroll_inertia_kg_m2 = 160",
                roll=False)
    with pytest.raises(ScenarioError, match="pivot"):
        parse_scenario(body)


# ------------------------------------------------------------------ parts move the seat result
PARTS = {
    "front_suspension": '[front_axle]\nmount = "suspended"\nroll_inertia_kg_m2 = 160\nmass_kg = 400\n'
                        'suspension_stiffness_kN_per_m = 150\nsuspension_damping_kN_s_per_m = 8\n',
    "cab": '[cab]\nmount = "suspended"\nmass_kg = 800\npitch_inertia_kg_m2 = 600\nroll_inertia_kg_m2 = 500\n'
           'ahead_of_cg_m = -0.3\nheight_above_cg_m = 0.9\nfront_mount_ahead_of_cg_m = 0.5\n'
           'rear_mount_ahead_of_cg_m = -0.9\nmount_track_m = 1.2\nmount_stiffness_kN_per_m = 30\n'
           'mount_damping_kN_s_per_m = 2\n',
    "implement": '[implement]\nmass_kg = 800\npitch_inertia_kg_m2 = 300\nroll_inertia_kg_m2 = 300\n'
                 'behind_rear_axle_m = 1.2\nheight_m = 0.8\n',
}
PARTS["hitch_damping"] = PARTS["implement"] + ('mount = "hitch_spring"\nhitch_behind_rear_axle_m = 0.5\nhitch_height_m = 0.6\n'
                                               'hitch_stiffness_kN_m_per_rad = 150\nhitch_damping_kN_m_s_per_rad = 15\n')


@pytest.fixture(scope="module")
def parts_results():
    surface = 'kind = "iso8608"\nclass = "C"\nlength_m = 300\ntracks = "isotropic"'
    out = {}
    together = PARTS["front_suspension"] + PARTS["cab"] + PARTS["hitch_damping"]
    for name, extra in {"rigid": "", **PARTS, "together": together}.items():
        res = ride.ride(parse_scenario(text(surface, "[10]", extra=extra)), with_spectra=False)
        out[name] = (res.natural_frequencies_Hz, res.speeds.iloc[0])
    return out


def test_front_axle_suspension(parts_results):
    """A soft suspension (150 kN/m) in series with the front tyres lowers the body's lowest
    bounce/pitch frequency (the front support is softer) and isolates the seat vertically (a_wz falls); the suspended axle pivots, so the
    body's roll stiffness is the rear tyres' alone: the roll frequency falls to theirs and the
    seat's lateral vibration rises."""
    (f0, r0), (f1, r1) = parts_results["rigid"], parts_results["front_suspension"]
    assert min(f1["bounce"], f1["pitch"]) < 0.6 * min(f0["bounce"], f0["pitch"])
    assert f1["roll"] == pytest.approx(math.sqrt(1e3 * K_TYRE["rear"] * TR**2 / 2 / I_ROLL) / (2 * math.pi), abs=0.01)
    assert "front_axle_bounce" in f1 and "front_axle_roll" in f1
    assert r1["a_wz_m_s2"] < r0["a_wz_m_s2"]
    assert r1["a_wy_m_s2"] > r0["a_wy_m_s2"]


def test_suspended_cab(parts_results):
    """Cab mounts of 1.5-1.9 Hz isolate the seat above ~2.7 Hz (√2 times), where the body's bounce,
    pitch and roll modes put the energy: every axis falls."""
    (f0, r0), (f1, r1) = parts_results["rigid"], parts_results["cab"]
    assert max(f1["cab_bounce"], f1["cab_pitch"], f1["cab_roll"]) < 2.0
    for ax in ("z", "x", "y"):
        assert r1[f"a_w{ax}_m_s2"] < 0.8 * r0[f"a_w{ax}_m_s2"], ax


def test_implement_and_hitch_damping(parts_results):
    """800 kg 2.15 m behind the CG adds ~3,700 kg m² of pitch inertia: the pitch mode falls from ~3.5
    to ~2.1 Hz, where W_d weights fore-aft motion fully, and the seat's fore-aft a_wx rises. The
    same implement pitching on a damped hitch takes pitch energy out (a damped absorber): a_wx
    falls below the rigid implement's."""
    (f0, r0), (f1, r1), (f2, r2) = (parts_results[k] for k in ("rigid", "implement", "hitch_damping"))
    assert f1["pitch"] < f0["pitch"] - 1.0
    assert r1["a_wx_m_s2"] > r0["a_wx_m_s2"]
    assert "implement_pitch" in f2
    assert r2["a_wx_m_s2"] < r1["a_wx_m_s2"]


# ------------------------------------------------------------------ sweeps of any numeric key
def test_sweep_any_numeric_key_from_the_command_line_and_the_file(tmp_path, capsys):
    import json

    body = text('kind = "iso8608"\nclass = "B"\nlength_m = 30', "[10]",
                extra='[implement]\nmass_kg = 500\nbehind_rear_axle_m = 1.2\nheight_m = 0.8\n'
                      '[sweep]\n"tractor.cg_height_m" = [0.9, 1.1]')
    path = _write(tmp_path, body)
    assert cli.main(["ride", str(path), "--set", "implement.mass_kg=500,1500"]) == 0
    doc = json.loads(capsys.readouterr().out)
    variants = [s["variant"] for s in doc["sweep"]]
    assert variants == [{"tractor.cg_height_m": h, "implement.mass_kg": m} for h in (0.9, 1.1) for m in (500, 1500)]
    pitch = {(s["variant"]["tractor.cg_height_m"], s["variant"]["implement.mass_kg"]): s["natural_frequencies_Hz"]["pitch"]
             for s in doc["sweep"]}
    assert pitch[(0.9, 1500)] < pitch[(0.9, 500)]  # a heavier implement: more pitch inertia
    assert cli.main(["ride", str(path), "--set", "implement.colour=1,2", "--set", "tractor.mass_kg=-5"]) == 2
    err = capsys.readouterr().err
    assert "implement.colour" in err and "tractor.mass_kg" in err and "Traceback" not in err


def test_suspended_axle_cab_and_implement_together(parts_results):
    """All three parts in one scenario: it runs with one mode per coordinate (body z, θ, φ; axle z,
    roll; cab z, θ, φ; implement θ: 9, named by what moves most, mixed modes numbered), and the
    seat is better off than on the rigid tractor in every axis (the cab's isolation dominates)."""
    (f0, r0), (f1, r1) = parts_results["rigid"], parts_results["together"]
    assert len(f1) == 9 and "front_axle_roll" in f1 and "cab_pitch" in f1, f1
    for ax in ("z", "x", "y"):
        assert r1[f"a_w{ax}_m_s2"] < r0[f"a_w{ax}_m_s2"], ax


@pytest.mark.parametrize("shift_m", [0.5, -0.5])
def test_shifted_profile_pair_matches_the_cross_spectral_expectation(tmp_path, shift_m):
    """Issue 33 (4): a measured pair whose right track is the left one shifted by ``shift_m``: the
    expectation from the tracks' own cross-spectrum agrees with the simulation in both directions.
    ``scipy.signal.csd(L, R)`` is ``E[L* R]``; the model needs ``E[L R*]`` (conjugated, the two
    directions swapped their expected a_wz: 10 % and 30 % off at 8 and 12 km/h here). Tolerance: two
    standard errors of an r.m.s. over a record of ``T`` s, ``1/(2 sqrt(B T))`` with a (small,
    conservative) statistical bandwidth ``B`` = 1 Hz."""
    length, dx = 600.0, 0.05
    h = ride.pr.iso8608_track("C", seed=33, length_m=length + 1.0, dx_m=dx).left_m
    k = int(round(abs(shift_m) / dx))
    n = h.size - k
    a, b = h[:n], h[k:k + n]
    left, right = (a, b) if shift_m > 0 else (b, a)  # right(x) = left(x + shift)
    pd.DataFrame({"distance_m": np.arange(n) * dx, "height_left_m": left, "height_right_m": right}).to_csv(
        tmp_path / "tracks.csv", index=False)
    res = ride.ride(load_scenario(_write(tmp_path, text(
        'kind = "profile"\nprofile = "tracks.csv"\nenveloping = "none"', "[8, 12]"))), with_spectra=False)
    for _, row in res.speeds.iterrows():
        record_s = (n - 1) * dx / (row["speed_km_h"] / 3.6)
        tol = 2 * 1 / (2 * math.sqrt(1.0 * record_s))
        for ax in ("z", "x", "y"):
            assert row[f"a_w{ax}_m_s2"] == pytest.approx(row[f"expected_a_w{ax}_m_s2"], rel=tol), (ax, row["speed_km_h"])


def test_bad_lateral_keys_all_listed_exit_2(tmp_path, capsys):
    """Issue 33: a negative or NaN lateral stiffness, an unknown lateral model, lateral keys without the
    3-D model: every problem at once, exit 2."""
    body = text('kind = "iso8608"\nclass = "B"\nlength_m = 40', lateral="maxwell")
    body = body.replace("[tyres.front]\n", "[tyres.front]\nlateral_stiffness_kN_per_m = -5\n")
    body = body.replace("[tyres.rear]\n", "[tyres.rear]\nlateral_stiffness_kN_per_m = nan\nlateral_damping_kN_s_per_m = 0\n")
    p = _write(tmp_path, body)
    assert cli.main(["ride", str(p)]) == 2
    err = capsys.readouterr().err
    assert "tyres.front.lateral_stiffness_kN_per_m" in err and "tyres.rear.lateral_stiffness_kN_per_m" in err
    assert "tyres.rear.lateral_damping_kN_s_per_m" in err and "Traceback" not in err
    flat = text('kind = "iso8608"\nclass = "B"\nlength_m = 40', roll=False).replace(
        "[tractor]\n", "[tractor]\nlateral_model = \"kelvin_voigt\"\n").replace(
        "[tyres.rear]\n", "[tyres.rear]\nlateral_stiffness_kN_per_m = 300\n")
    assert cli.main(["ride", str(_write(tmp_path, flat, "flat.toml"))]) == 2
    err = capsys.readouterr().err
    assert "tractor.lateral_model needs tractor.roll_inertia_kg_m2" in err
    assert "tyres.rear.lateral_stiffness_kN_per_m needs the 3-D model" in err
    bad_model = _write(tmp_path, text('kind = "iso8608"\nclass = "B"\nlength_m = 40', lateral="coulomb"), "m.toml")
    assert cli.main(["ride", str(bad_model)]) == 2
    assert "tractor.lateral_model" in capsys.readouterr().err


def test_a_3d_scenario_defaults_to_lateral_tyre_elements(tmp_path):
    """Issues 33, 42: without lateral_model a 3-D scenario gets rolling lateral tyres (stand-in stiffness
    k_y = 0.57 k_z and series damper a = 100 kN s/m km/h, their intervals in ride.json) and a low coupled
    lateral-roll mode with its damping; "none" keeps the body rolling about its CG and says a_wy is
    indicative."""
    res = ride.ride(load_scenario(_write(tmp_path, text('kind = "iso8608"\nclass = "B"\nlength_m = 40',
                                                         lateral=None))), with_spectra=False)
    t = res.tyres["front"]
    assert t.lateral_stiffness_kN_per_m[0] == pytest.approx(0.5657 * K_TYRE["front"], rel=1e-3)
    doc = ride.result_json([res])
    assert doc["lateral_model"] == "rolling" and "stand-in" in doc["lateral_note"]
    assert doc["tyres"]["front"]["lateral_stiffness_ci95_kN_per_m"][0] < t.lateral_stiffness_kN_per_m[0]
    assert doc["tyres"]["front"]["lateral_series_damping_kN_s_per_m_km_h"] == 100.0
    assert doc["tyres"]["front"]["lateral_series_damping_ci95_kN_s_per_m_km_h"] == [50.0, 200.0]
    assert doc["tyres"]["front"]["lateral_sources"]["series_damping_kN_s_per_m_km_h"] == "stand-in"
    assert set(doc["damping_ratio"]) == set(doc["natural_frequencies_Hz"])
    roll_cg = math.sqrt(1e3 * (K_TYRE["front"] * TF**2 + K_TYRE["rear"] * TR**2) / 2 / I_ROLL) / (2 * math.pi)
    low = min(v for k, v in res.natural_frequencies_Hz.items() if k in ("lateral_roll", "lateral"))
    assert low < 0.75 * roll_cg and "yaw" in res.natural_frequencies_Hz
    none = ride.ride(load_scenario(_write(tmp_path, text('kind = "iso8608"\nclass = "B"\nlength_m = 40'), "n.toml")),
                     with_spectra=False)
    assert "indicative" in ride.result_json([none])["lateral_note"]
