"""The fifth hostile probe's vehicle-side cases (issue 46, Deliver 2 and 4): the work a ride is asked
for bounded from the file's own content (a profile CSV's length) before any work, the same bound for
the CLI and the library; a road's heights bounded alike from every source (a CRG road in millimetres
stored as metres as the CSV profile); integers of any length one line naming their key; an element
state the lift-off path cannot follow named by its keys, not by a non-finite record."""

import functools
import math
import tomllib

import numpy as np
import pytest

import tyrelab
from tests.scenarios import scenario_text
from tyrelab import _validate
from tyrelab.cli import main
from tyrelab.resources import scenarios_dir
from tyrelab.scenario_io import ScenarioError, load_scenario, parse_scenario
from tyrelab.vehicle import ride as ride_module
from tyrelab.vehicle.scenario import limits
from tyrelab.vehicle.scenario.limits import long_integer_problems
from tyrelab.vehicle.scenario.parse import _is_number

text = functools.partial(scenario_text, name="round5 vehicle", hours_per_day=None)
MODERN = scenarios_dir() / "modern_tractor.toml"


def lines(err: str) -> list[str]:
    assert "Traceback" not in err and "Warning" not in err
    return err.splitlines()


def _profile(folder, length_m, step_m, amplitude_m=0.01, name="long.csv"):
    x = np.arange(0.0, length_m + step_m / 2, step_m)
    h = amplitude_m * np.sin(2 * np.pi * x / 7.0)
    (folder / name).write_text("distance_m,height_m\n" + "".join(f"{a:.4f},{b:.6f}\n" for a, b in zip(x, h)))
    return folder / name


def _write(folder, surface, speeds="[8]", **kw):
    p = folder / "s.toml"
    p.write_text(text(surface, speeds, **kw))
    return p


# ----------------------------------------------------------------------------- a profile's own length
def test_the_work_of_a_profile_ride_is_estimated_on_the_profiles_own_length(tmp_path):
    _profile(tmp_path, 20_000.0, 10.0)  # 20 km in 2001 rows (40 kB): surface.length_m (400 m) does not apply
    sc = load_scenario(_write(tmp_path, 'kind = "profile"\nprofile = "long.csv"', "[2]"))
    assert limits.track_length_m(sc) == pytest.approx(20_000.0)
    e = limits.work_estimate(sc, 1)
    assert e["samples"] > 20_000.0 / (2 / 3.6) * 1000  # 36 million 1 kHz samples at 2 km/h
    assert limits.work_problems(sc, 1)


def test_a_long_profile_at_a_walking_pace_is_refused_before_any_work_by_cli_library_and_stage(tmp_path, capsys,
                                                                                               monkeypatch):
    _profile(tmp_path, 20_000.0, 10.0)
    path = _write(tmp_path, 'kind = "profile"\nprofile = "long.csv"', "[2]")
    monkeypatch.setattr(ride_module, "ride_variants", lambda *a, **k: pytest.fail("simulated"))
    monkeypatch.setattr("tyrelab.vehicle.run.time.ride_variants", lambda *a, **k: pytest.fail("simulated"))
    assert main(["ride", str(path)]) == 2
    err = lines(capsys.readouterr().err)
    assert len(err) == 1 and "samples" in err[0] and "more than 10,000,000" in err[0]
    with pytest.raises(ValueError, match="more than 10,000,000; max_samples=N lifts"):
        tyrelab.ride(path)
    with pytest.raises(ValueError, match="more than 10,000,000"):  # what the simulate stage's task calls
        ride_module.ride_sweep(load_scenario(path))


def test_library_ride_bounds_a_spectral_scenario_by_what_it_computes(monkeypatch):
    doc = tomllib.loads(MODERN.read_text())
    doc.setdefault("simulation", {})["method"] = "spectral"  # tyrelab.ride computes spectral rows, as tyrelab ride
    monkeypatch.setattr(ride_module, "ride", lambda *a, **k: pytest.fail("ran"))
    monkeypatch.setattr("tyrelab.vehicle.run.frequency.spectral_variants", lambda *a, **k: pytest.fail("ran"))
    with pytest.raises(ValueError, match=r"1 variant\(s\) x 1000 speed\(s\) make 1,000 spectral rows"):
        tyrelab.ride(doc, speeds_km_h=[5 + 0.01 * i for i in range(1000)], max_rows=999)
    doc["simulation"]["method"] = "time"  # simulated: bounded by the samples
    with pytest.raises(ValueError, match=r"1 variant\(s\) x 1000 speed\(s\) simulate"):
        tyrelab.ride(doc, speeds_km_h=[5 + 0.01 * i for i in range(1000)])


def test_a_profiles_grid_is_bounded_in_the_one_check_of_its_data():
    x = np.concatenate([np.arange(6000) * 0.001, 6.0 + np.arange(1, 3000) * 9.99])  # median 1 mm over 30 km
    problems = limits.profile_problems(x, np.zeros_like(x), np.zeros_like(x), "long.csv")
    assert len(problems) == 1 and "makes 29,966,011 points, more than the 10,000,000" in problems[0]
    assert problems[0].startswith("surface.profile 'long.csv': ")
    x = np.arange(0.0, 1000.0, 0.01)
    assert limits.profile_problems(x, np.zeros_like(x), np.zeros_like(x)) == []


# ----------------------------------------------------------------------------- road heights from every source
def _crg(folder, scale=1.0, name="road.crg", banking=None):
    import pyopencrg

    v = np.round(np.arange(-1.5, 1.5001, 0.1), 10)
    z = np.random.default_rng(7).normal(0.0, 0.01, (2000, v.size)) * scale
    pyopencrg.CrgRoad(z, u_inc=0.05, v=v, **({} if banking is None else {"banking": banking})).save(folder / name,
                                                                                                  fmt="KDBI")
    return folder / name


def test_a_crg_road_in_millimetres_is_refused_like_a_csv_profile(tmp_path, capsys):
    from tyrelab.vehicle.terrain.profiles import ROAD_HEIGHT_BOUNDS_M

    assert limits.LIMITS["profile.height_m"][:2] == ROAD_HEIGHT_BOUNDS_M  # one bound, one home
    _crg(tmp_path, scale=1000.0)  # 10 mm r.m.s. written as 10 m
    path = _write(tmp_path, 'kind = "crg"\nfile = "road.crg"\nlength_m = 50')
    with pytest.raises(ScenarioError) as info:
        load_scenario(path)
    assert any(p.startswith("surface.file: road.crg's heights under the") and "must be within -2 to 2 m" in p
               for p in info.value.problems), info.value.problems
    assert main(["ride", str(path)]) == 2
    err = lines(capsys.readouterr().err)
    assert err and all("must be within -2 to 2 m" in e for e in err)
    assert main(["road", str(tmp_path / "road.crg")]) == 2
    err = lines(capsys.readouterr().err)
    assert len(err) == 1 and "heights under the left wheel" in err[0] and "surface." not in err[0]
    # the same heights as a CSV profile: the same bound
    x = np.arange(2000) * 0.05
    (tmp_path / "mm.csv").write_text("distance_m,height_m\n" + "".join(f"{a:.2f},{b:.4f}\n" for a, b in zip(
        x, np.random.default_rng(7).normal(0.0, 10.0, x.size))))
    assert main(["road", str(tmp_path / "mm.csv")]) == 2
    assert "must be finite and within -2 to 2 m" in capsys.readouterr().err


def test_a_crg_road_within_the_bound_still_runs(tmp_path, capsys):
    _crg(tmp_path)
    assert main(["road", str(tmp_path / "road.crg"), "--format", "json"]) == 0
    assert load_scenario(_write(tmp_path, 'kind = "crg"\nfile = "road.crg"\nlength_m = 50')).surface.crg_data


def test_the_crg_bound_is_on_the_wheels_line_banking_included(tmp_path):
    from tyrelab.scenario_io import read_crg
    from tyrelab.vehicle.crg import crg_problems

    _crg(tmp_path, banking=1.5)  # 1.5 m per m of v: 1.35 m at v = 0.9, 2.25 m at v = 1.5
    data = read_crg(tmp_path / "road.crg")
    assert crg_problems(data, {"left": 0.9, "right": -0.9}, 0.0, 50.0) == []
    problems = crg_problems(data, {"left": 1.5, "right": -1.5}, 0.0, 50.0)
    assert len(problems) == 2 and "left wheel (v = 1.5 m)" in problems[0] and "right wheel (v = -1.5 m)" in problems[1]


# ----------------------------------------------------------------------------- integers of any length
def test_is_number_and_the_limits_never_raise_overflow():
    assert not _is_number(10**400) and not _is_number(-(10**400)) and _is_number(5120)
    assert limits._out("tractor.mass_kg", 10**400) == \
        "tractor.mass_kg: 1000000000…0000000000 (401 digits) is not a finite number"


def test_an_integer_too_long_for_python_to_read_names_its_key(tmp_path, capsys):
    long = "1" + "0" * 5000  # tomllib refuses the whole text with a ValueError naming no key
    with pytest.raises(ScenarioError) as info:
        parse_scenario(text(tractor={"mass_kg": long}))
    assert info.value.problems == ["tractor.mass_kg: an integer of 5001 digits is not a finite number"]
    p = tmp_path / "long.toml"
    p.write_text(text(speeds=f"[8, {long}]"))
    assert main(["ride", str(p)]) == 2
    assert lines(capsys.readouterr().err) == [
        f"tyrelab ride: {p}: exposure.speeds_km_h: an integer of 5001 digits is not a finite number"]
    assert long_integer_problems('[a."b c"]\nd = -' + "9" * 4400) == ["a.bc.d: an integer of 4400 digits is not a finite number"]
    assert long_integer_problems("x = [\n  " + "1" * 4400 + "]") == ["line 2: an integer of 4400 digits is not a finite number"]


def test_shown_counts_an_integer_too_long_to_convert():
    assert _validate.shown(10**5000) == "an integer of about 5001 digits"
    assert _validate.shown([10**5000]) == "a list holding an integer too long to show"
    with pytest.raises(ValueError, match="x must be a finite number, got an integer of about 5001 digits"):
        _validate.finite("x", 10**5000)


# ----------------------------------------------------------------------------- a state the lift-off path cannot follow
def test_an_element_too_fast_for_the_lift_off_path_names_its_keys():
    from types import SimpleNamespace as NS

    from tyrelab.vehicle.elements import element
    from tyrelab.vehicle.run.time import RK4_REAL_STABILITY, fast_element_problems

    R = lambda z: 1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24  # noqa: E731 - RK4's amplification per step
    assert abs(R(-RK4_REAL_STABILITY)) <= 1.0 < abs(R(-RK4_REAL_STABILITY - 1e-3))
    g = np.array([1.0])
    fast = element("rear_right_lateral", g, 2.6e5, 10.0, "maxwell")  # k/c = 26,000 /s at 1 ms: 26 per step
    slow = element("front_left_lateral", g, 2.6e5, 1000.0, "maxwell")  # 260 /s
    lines_ = fast_element_problems(NS(elements=[fast, slow]), 1e-3, 8.0)
    assert len(lines_) == 1 and lines_[0].startswith(
        "tyres.rear.lateral_stiffness_kN_per_m, tyres.rear.lateral_damping_kN_s_per_m: the rear right lateral element")
    rolling = element("rear_longitudinal", g, 2.6e5, 10.0, "rolling", series_damping=1e3 / 80)  # a / v at 80 km/h, a = 1 kN s/m km/h
    line = fast_element_problems(NS(elements=[rolling]), 1e-3, 80.0)[0]
    assert line.startswith("tractor.longitudinal_stiffness_kN_per_m, tractor.longitudinal_damping_kN_s_per_m, "
                           "tractor.longitudinal_series_damping_kN_s_per_m_km_h: ") and "at 80 km/h" in line
    locked = element("rear_longitudinal", g, 2.6e5, 10.0, "rolling")  # standing: no state
    assert fast_element_problems(NS(elements=[locked]), 1e-3, 0.0) == []


def test_the_documented_minimum_lateral_damping_in_the_time_domain_names_its_keys():
    doc = tomllib.loads((scenarios_dir() / "modern_3d_tractor.toml").read_text())
    doc["tractor"]["lateral_model"] = "maxwell"
    for axle in ("front", "rear"):
        doc["tyres"][axle]["lateral_damping_kN_s_per_m"] = limits.LIMITS["lateral_damping_kN_s_per_m"][0]
    doc["exposure"]["speeds_km_h"] = [80]  # tyres lift off: the nonlinear path
    doc["simulation"] = {"method": "time", "duration_s": 10}
    with pytest.raises(ValueError) as info:
        tyrelab.ride(doc)
    text_ = str(info.value)
    assert "non-finite" not in text_ and text_.startswith(
        "tyres.front.lateral_stiffness_kN_per_m, tyres.front.lateral_damping_kN_s_per_m: ")
    assert "; tyres.rear.lateral_stiffness_kN_per_m" in text_ and text_.count("tyres.front.lateral_stiffness") == 1
    doc["simulation"]["lift_off"] = False  # the linear model: exact at any rate
    assert math.isfinite(float(tyrelab.ride(doc).speeds["a_wy_m_s2"].iloc[0]))
