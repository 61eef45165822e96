"""3-D scenario keys, profiles and names the ride model cannot take (issue 37, classes 4, 8 and 9):
each refused in one line naming the key (or the file) and its bound, every problem at once, exit 2,
before any work; no library text ("Singular matrix", "not positive definite") reaches the user."""

import functools

import numpy as np
import pandas as pd
import pytest

from tests.scenarios import scenario_text
from tyrelab.cli import main
from tyrelab.scenario_io import ScenarioError, parse_scenario
from tyrelab.vehicle.scenario_limits import LIMITS

SHORT = 'kind = "iso8608"\nclass = "C"\nlength_m = 20'
THREE_D = "roll_inertia_kg_m2 = 2400\nfront_track_m = 1.9\nrear_track_m = 1.8"
text = functools.partial(scenario_text, surface=SHORT, name="hostile 3-D", tractor_extra=THREE_D)
CAB = ('[cab]\nmount = "suspended"\nmass_kg = {mass}\npitch_inertia_kg_m2 = 600\nroll_inertia_kg_m2 = 500\n'
       'ahead_of_cg_m = -0.3\nheight_above_cg_m = 0.9\nfront_mount_ahead_of_cg_m = 0.5\nrear_mount_ahead_of_cg_m = -0.9\n'
       'mount_track_m = 1.2\nmount_stiffness_kN_per_m = 30\n')
IMPLEMENT = '[implement]\nmass_kg = {mass}\nbehind_rear_axle_m = 1.2\nheight_m = 0.8\n'
SUSPENDED = ('[front_axle]\nmount = "suspended"\nroll_inertia_kg_m2 = 160\nmass_kg = {mass}\n'
             'suspension_stiffness_kN_per_m = 150\n')
BALLAST = '[ballast]\nmass_kg = {mass}\nahead_of_front_axle_m = 0.8\nheight_m = 0.7\n'
SEAT_IN_CAB = "[seat]\nahead_of_cg_m = -0.3\nleft_of_cg_m = {left}"


@pytest.mark.parametrize("kwargs, key, value", [
    (dict(tractor_extra=THREE_D.replace("2400", "1e12")), "tractor.roll_inertia_kg_m2", 1e12),
    (dict(tractor_extra=THREE_D.replace("1.9", "1e-6")), "tractor.front_track_m", 1e-6),
    (dict(tractor_extra=THREE_D.replace("1.8", "1e6")), "tractor.rear_track_m", 1e6),
    (dict(seat="[seat]\nleft_of_cg_m = 1e6"), "seat.left_of_cg_m", 1e6),
    (dict(extra=CAB.format(mass=1e-12)), "cab.mass_kg", 1e-12),
    (dict(extra=CAB.format(mass=800).replace("mount_stiffness_kN_per_m = 30", "mount_stiffness_kN_per_m = 1e12")),
     "cab.mount_stiffness_kN_per_m", 1e12),
    (dict(extra=IMPLEMENT.format(mass=1e9)), "implement.mass_kg", 1e9),
    (dict(extra=IMPLEMENT.format(mass=800).replace("behind_rear_axle_m = 1.2", "behind_rear_axle_m = 1e5")),
     "implement.behind_rear_axle_m", 1e5),
    (dict(extra=SUSPENDED.format(mass=1e-9)), "front_axle.mass_kg", 1e-9),
    (dict(extra=SUSPENDED.format(mass=400).replace("= 150", "= 1e-9")), "front_axle.suspension_stiffness_kN_per_m", 1e-9),
    (dict(extra=BALLAST.format(mass=1e7)), "ballast.mass_kg", 1e7),
])
def test_every_3d_key_is_range_checked_naming_key_and_bound(kwargs, key, value):
    """Was: implement.mass_kg = 1e9 gave A(8) 28,126 m/s² (exit 0); cab.mass_kg = 1e-12 a_wz 9.25e6."""
    with pytest.raises(ScenarioError) as info:
        parse_scenario(text(**kwargs))
    line = next(p for p in info.value.problems if p.startswith(key))
    low, high, _ = LIMITS[key if key in LIMITS else "axle." + key.split(".", 1)[1]]
    assert f"{value:g}" in line and f"{low:g} to {high:g}" in line


def test_the_bounds_are_documented_for_every_numeric_key_of_the_parts():
    from tyrelab.vehicle.scenario import _sections, numeric_key

    for section in ("front_axle", "rear_axle", "cab", "implement", "ballast"):
        for name in _sections()[section]["fields"]:
            if numeric_key(f"{section}.{name}"):
                assert f"{section}.{name}" in LIMITS or f"axle.{name}" in LIMITS, (section, name)
    for key in ("tractor.roll_inertia_kg_m2", "tractor.front_track_m", "tractor.rear_track_m", "seat.left_of_cg_m"):
        assert key in LIMITS


def test_every_problem_at_once_exit_2_and_no_library_text(tmp_path, capsys):
    body = text(seat="[seat]\nleft_of_cg_m = 1e6", extra=IMPLEMENT.format(mass=1e9) + BALLAST.format(mass=1e7))
    path = tmp_path / "s.toml"
    path.write_text(body.replace("length_m = 20", "length_m = 20\nseed = -5"))
    assert main(["ride", str(path)]) == 2
    err = capsys.readouterr().err.splitlines()
    keys = ("seat.left_of_cg_m", "implement.mass_kg", "ballast.mass_kg", "surface.seed")
    assert len(err) == len(keys) and all(any(f": {k}" in line for line in err) for k in keys), err


@pytest.mark.parametrize("extra, names", [
    ('[front_axle]\nmount = "pivot"\nroll_inertia_kg_m2 = 100\n[rear_axle]\nmount = "pivot"\nroll_inertia_kg_m2 = 100',
     ("front_axle.mount", "rear_axle.mount")),
    (SUSPENDED.format(mass=400) + '[rear_axle]\nmount = "pivot"\nroll_inertia_kg_m2 = 100',
     ("front_axle.mount", "rear_axle.mount")),
    (CAB.format(mass=6000), ("tractor.mass_kg", "cab.mass_kg")),
    (CAB.format(mass=3000).replace("ahead_of_cg_m = -0.3\n", "ahead_of_cg_m = 3\n", 1), ("tractor.pitch_inertia_kg_m2",)),
    # the cab and axle outweigh the tractor that holds them; an implement and a ballast (added, not held)
    # keep the whole mass matrix positive definite: the simulation overflowed
    (CAB.format(mass=800) + SUSPENDED.format(mass=400) + IMPLEMENT.format(mass=800) + BALLAST.format(mass=600)
     + "[tractor_mass]", ("tractor.mass_kg", "cab.mass_kg", "front_axle.mass_kg")),
    (IMPLEMENT.format(mass=800) + 'mount = "hitch_spring"\nhitch_behind_rear_axle_m = 1.2\nhitch_height_m = 0.8\n'
                                  'hitch_stiffness_kN_m_per_rad = 150', ("implement.pitch_inertia_kg_m2",)),
])
def test_parts_the_model_cannot_hold_are_refused_by_their_keys(tmp_path, capsys, extra, names):
    """Was: "Singular matrix" (both axles on pivots; an implement pitching about its own CG on the
    hitch), "The leading minor of order 1 of B is not positive definite" (a cab heavier than the
    tractor), or numbers for a body with no roll spring."""
    path = tmp_path / "s.toml"
    light = "[tractor_mass]" in extra
    path.write_text(text(seat=SEAT_IN_CAB.format(left=0.3) if "[cab]" in extra else "",
                         extra=extra.replace("[tractor_mass]", ""), tractor={"mass_kg": 1000} if light else None))
    assert main(["ride", str(path), "--speeds", "20"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and all(n in err for n in names), err
    for library in ("Singular", "leading minor", "positive definite of B", "Traceback"):
        assert library not in err


def test_a_negative_seed_is_refused_by_its_key():
    """Was: "expected non-negative integer" (numpy's words)."""
    with pytest.raises(ScenarioError) as info:
        parse_scenario(text(surface=SHORT + "\nseed = -5"))
    assert info.value.problems == ["surface.seed: -5 is negative (a seed is a whole number from 0)"]


def test_a_profile_with_a_tiny_step_is_refused_before_allocating(tmp_path, capsys, monkeypatch):
    """Was: 74.5 GiB asked for (a traceback): the track is resampled at the median step."""
    from tyrelab.vehicle import ride

    x = np.concatenate([np.arange(40) * 1e-9, 1.0 + np.arange(11) * 9.9])
    pd.DataFrame({"distance_m": x, "height_m": 0.0}).to_csv(tmp_path / "tiny.csv", index=False)
    path = tmp_path / "s.toml"
    path.write_text(text(surface='kind = "profile"\nprofile = "tiny.csv"'))
    monkeypatch.setattr("tyrelab.vehicle.run.records.build_profile", lambda *a: pytest.fail("work started"))
    assert main(["ride", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "tiny.csv" in err and "step of 1e-09 m" in err and "0.001 m" in err


def test_an_inf_height_names_the_profile_file(tmp_path):
    x = np.arange(64) * 0.1
    pd.DataFrame({"distance_m": x, "height_m": [0.0] * 63 + [np.inf]}).to_csv(tmp_path / "peak.csv", index=False)
    with pytest.raises(ScenarioError) as info:
        parse_scenario(text(surface='kind = "profile"\nprofile = "peak.csv"'), tmp_path)
    (line,) = info.value.problems
    assert "peak.csv" in line and "not finite" in line


@pytest.mark.parametrize("name", ["tractor\x1b[2J\x1b[H", "a\x00b", "line one\nday: forged", "bell\x07", "del\x7f",
                                  "c1\x9b31m"])
def test_control_characters_in_a_scenario_name_never_reach_the_outputs(tmp_path, capsys, name):
    """Was: NUL and ESC of a scenario name reached ride.html, the report and the terminal as they are."""
    path = tmp_path / "s.toml"
    escaped = name.encode("unicode_escape").decode().replace("\\x", "\\u00")
    path.write_text(scenario_text(SHORT, name=escaped))
    assert main(["ride", str(path), "--out", str(tmp_path / "o")]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "name: holds control characters (U+" in err
    assert all(c not in err[:-1] for c in name if ord(c) < 32 or 0x7F <= ord(c) <= 0x9F)
    assert not (tmp_path / "o").exists()
