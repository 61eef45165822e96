"""Measured roads (issue 33, Deliver 5): OpenCRG files read with pyopencrg (the test files are written
with pyopencrg itself, seeded), each wheel on its own line, the ISO 8608 class of a profile."""

import json

import numpy as np
import pandas as pd
import pyopencrg
import pytest

from tyrelab import cli
from tyrelab.scenario_io import ScenarioError, load_scenario
from tyrelab.vehicle import profiles as pr
from tyrelab.vehicle import ride
from tyrelab.vehicle.road_class import class_of, road_class

from .test_ride_3d import TF, TR, text

DX = 0.05
V = np.round(np.arange(-1.5, 1.5001, 0.1), 10)


def two_track_road(tmp_path, length_m=150.0, seed=5, fmt="KDBI"):
    """A CRG road whose heights are one ISO 8608 class C track left of v = 0.5 m and another right of
    v = -0.5 m (linear between), and the CSV of its two wheel tracks."""
    p = pr.iso8608_track("C", seed=seed, length_m=length_m, dx_m=DX)
    w = np.clip(V + 0.5, 0.0, 1.0)
    z = np.outer(p.right_m, 1 - w) + np.outer(p.left_m, w)
    pyopencrg.CrgRoad(z, u_inc=DX, v=V).save(tmp_path / "road.crg", fmt=fmt)
    pd.DataFrame({"distance_m": p.x_m, "height_left_m": p.left_m, "height_right_m": p.right_m}).to_csv(
        tmp_path / "tracks.csv", index=False)
    return p


def write(tmp_path, surface, name="s.toml", **kw):
    path = tmp_path / name
    path.write_text(text(surface, **kw))
    return path


def test_the_same_road_as_crg_and_as_csv_gives_the_same_numbers(tmp_path, capsys):
    two_track_road(tmp_path)
    runs = {}
    for kind, surface in (("crg", 'kind = "crg"\nfile = "road.crg"'), ("csv", 'kind = "profile"\nprofile = "tracks.csv"')):
        res = ride.ride(load_scenario(write(tmp_path, surface, f"{kind}.toml", speeds="[8]")), with_spectra=False)
        runs[kind] = res
    a, b = runs["crg"].speeds.iloc[0], runs["csv"].speeds.iloc[0]
    # the CSV's grid is its distances' median step (0.05 up to the decimal rounding of the file): the
    # record may differ by one 1 ms sample
    for col in ("a_wz_m_s2", "a_wx_m_s2", "a_wy_m_s2", "expected_a_wz_m_s2", "expected_a_wy_m_s2"):
        assert a[col] == pytest.approx(b[col], rel=2e-4), col
    assert a["a_wy_m_s2"] > 0.05
    for side in ("left", "right"):
        x, y = runs["crg"].road_classes[side], runs["csv"].road_classes[side]
        assert x["class"] == y["class"] and x["g0_m3"] == pytest.approx(y["g0_m3"], rel=1e-6)
    assert {c["class"] for c in runs["crg"].road_classes.values()} == {"C"}
    outs = {}
    for f in ("road.crg", "tracks.csv"):
        assert cli.main(["road", str(tmp_path / f), "--format", "json", "--track-width-m", "1.8"]) == 0
        outs[f] = json.loads(capsys.readouterr().out)["tracks"]
    for side in ("left", "right"):
        assert outs["road.crg"][side]["class"] == outs["tracks.csv"][side]["class"] == "C"
        assert outs["road.crg"][side]["g0_m3"] == pytest.approx(outs["tracks.csv"][side]["g0_m3"], rel=1e-6)
        assert outs["road.crg"][side]["rms_m"] == pytest.approx(outs["tracks.csv"][side]["rms_m"], abs=2e-6)


def test_front_and_rear_wheels_take_their_own_lines(tmp_path):
    """A ridge along the front wheels' lines (v = ±TF/2) only: the rear wheels (±TR/2) do not see it."""
    u = np.arange(0, 60.0001, DX)
    v = np.round(np.arange(-1.2, 1.2001, 0.025), 10)
    z = np.zeros((u.size, v.size))
    ridge = 0.02 * np.sin(2 * np.pi * u / 3.0)
    for side in (1, -1):
        z[:, np.argmin(abs(v - side * TF / 2))] = ridge * side
    pyopencrg.CrgRoad(z, u_inc=DX, v=v).save(tmp_path / "ridge.crg")
    sc = load_scenario(write(tmp_path, 'kind = "crg"\nfile = "ridge.crg"\nlateral_offset_m = 0.0'))
    prof = ride.crg_profile(sc)
    assert np.abs(prof.track("left") - ridge).max() < 1e-6 and np.abs(prof.track("right") + ridge).max() < 1e-6
    assert np.abs(prof.track("left", "rear")).max() < 1e-9 and np.abs(prof.track("right", "rear")).max() < 1e-9
    moved = load_scenario(write(tmp_path, 'kind = "crg"\nfile = "ridge.crg"\nlateral_offset_m = 0.05\n'
                                          'start_m = 10\nlength_m = 30', "m.toml"))
    p2 = ride.crg_profile(moved)
    assert p2.x_m[-1] == pytest.approx(30.0) and np.abs(p2.track("left")).max() < 0.011  # half-way to the ridge


def test_missing_heights_refused_or_filled(tmp_path):
    u = np.arange(0, 40.0001, DX)
    z = 0.01 * np.outer(np.sin(u), np.ones(V.size))
    z[100:110, V > 0.8] = np.nan  # a hole under the front left wheel (v = 0.95)
    pyopencrg.CrgRoad(z, u_inc=DX, v=V).save(tmp_path / "hole.crg", fmt="KDBI")
    with pytest.raises(ScenarioError) as err:
        load_scenario(write(tmp_path, 'kind = "crg"\nfile = "hole.crg"'))
    msg = "\n".join(err.value.problems)
    assert "missing heights (NaN) under the front left wheel" in msg and "fill_missing" in msg
    sc = load_scenario(write(tmp_path, 'kind = "crg"\nfile = "hole.crg"\nfill_missing = true', "f.toml"))
    prof = ride.crg_profile(sc)
    assert np.isfinite(prof.left_m).all()


def test_a_damaged_crg_is_one_line_exit_2(tmp_path, capsys):
    two_track_road(tmp_path, length_m=40.0, fmt="KRBI")
    data = (tmp_path / "road.crg").read_bytes()
    (tmp_path / "short.crg").write_bytes(data[:-1000])  # a short binary section
    (tmp_path / "header.crg").write_bytes(data.replace(b"#:KRBI", b"#:KXBI", 1))  # a bad header
    for name in ("short.crg", "header.crg"):
        path = write(tmp_path, f'kind = "crg"\nfile = "{name}"', f"{name}.toml")
        assert cli.main(["ride", str(path)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and name in err[0] and "not a readable OpenCRG file" in err[0], err
        assert cli.main(["road", str(tmp_path / name)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "not a readable OpenCRG file" in err[0] and "Traceback" not in err[0], err


def test_bad_crg_keys_all_listed_exit_2(tmp_path, capsys):
    two_track_road(tmp_path, length_m=40.0)
    path = write(tmp_path, 'kind = "crg"\nfile = "road.crg"\nlateral_offset_m = 1.0\nstart_m = 39\nlength_m = 5')
    assert cli.main(["ride", str(path)]) == 2
    err = capsys.readouterr().err
    assert "front left wheel's line v = 1.95 m lies outside road.crg's width" in err
    assert "rear left wheel's line v = 1.9 m" in err
    missing = write(tmp_path, 'kind = "crg"\nfile = "nowhere.crg"\nstart_m = -1', "m.toml")
    assert cli.main(["ride", str(missing)]) == 2
    err = capsys.readouterr().err
    assert "surface.file" in err and "nowhere.crg: no such file" in err and "surface.start_m" in err
    past = write(tmp_path, 'kind = "crg"\nfile = "road.crg"\nstart_m = 30\nlength_m = 20', "p.toml")
    assert cli.main(["ride", str(past)]) == 2
    assert "runs past the end of road.crg" in capsys.readouterr().err
    nofile = write(tmp_path, 'kind = "crg"', "n.toml")
    assert cli.main(["ride", str(nofile)]) == 2
    assert "surface.file (an OpenCRG .crg path) is required" in capsys.readouterr().err


def test_road_class_recovers_the_generating_class():
    for c in "BDF":
        t = pr.iso8608_track(c, seed=7, length_m=800.0)
        r = road_class(t.left_m, t.dx_m)
        assert r["class"] == c and r["g0_m3"] == pytest.approx(pr.ISO8608_CLASS_G0_M3[c], rel=0.15)
        assert r["rms_m"] == pytest.approx(float(np.std(t.left_m))) and r["length_m"] == pytest.approx(t.x_m[-1])
    assert class_of(31.9e-6) == "A" and class_of(32.1e-6) == "B"  # the A/B boundary: the geometric mean 32e-6


def test_the_ride_page_and_json_state_a_profile_roads_class(tmp_path, capsys):
    two_track_road(tmp_path, length_m=60.0)
    path = write(tmp_path, 'kind = "profile"\nprofile = "tracks.csv"', speeds="[8]")
    assert cli.main(["ride", str(path), "--out", str(tmp_path / "out")]) == 0
    doc = json.loads((tmp_path / "out" / "ride.json").read_text())
    assert set(doc["road_class"]) == {"left", "right"} and doc["road_class"]["left"]["class"] in "BCD"
    assert "ISO 8608 class" in (tmp_path / "out" / "ride.html").read_text()
    capsys.readouterr()
    iso = write(tmp_path, 'kind = "iso8608"\nclass = "C"\nlength_m = 40', "i.toml", speeds="[8]")
    assert cli.main(["ride", str(iso)]) == 0
    assert json.loads(capsys.readouterr().out)["road_class"] is None



def test_a_coarse_road_is_not_resolved_not_a_traceback(tmp_path, capsys):
    """Cross sections 300 m apart: no Welch segment of the classification fits (scipy raised
    'nperseg=0' through ``tyrelab road``, a traceback) (review of issue 33)."""
    rng = np.random.default_rng(0)
    assert road_class(rng.normal(0, 0.01, 20), 300.0)["class"] is None
    pyopencrg.CrgRoad(rng.normal(0, 0.01, (20, V.size)), u_inc=300.0, v=V).save(tmp_path / "c300.crg")
    assert cli.main(["road", str(tmp_path / "c300.crg"), "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out)["tracks"]["left"]["class"] is None


def test_a_ride_refuses_a_crg_spaced_above_a_profiles_gap(tmp_path, capsys):
    """A CRG road's cross sections 20 m apart are refused as a profile CSV's 20 m gap is, with the
    scenario's other problems (review of issue 33)."""
    rng = np.random.default_rng(0)
    pyopencrg.CrgRoad(rng.normal(0, 0.01, (100, V.size)), u_inc=20.0, v=V).save(tmp_path / "c20.crg")
    path = write(tmp_path, 'kind = "crg"\nfile = "c20.crg"\nlateral_offset_m = 1.0')
    assert cli.main(["ride", str(path)]) == 2
    err = capsys.readouterr().err
    assert "surface.file: c20.crg's cross sections are 20 m apart, above 10 m" in err
    assert "surface.lateral_offset_m: the front left wheel" in err


def test_tyrelab_road_names_its_own_options(tmp_path, capsys):
    """``tyrelab road`` on a CRG names its options, not the scenario's surface keys it has no scenario
    for, and refuses a NaN start as argparse does (it was 'cannot convert float NaN to integer')."""
    two_track_road(tmp_path, length_m=40.0)
    crg = str(tmp_path / "road.crg")
    assert cli.main(["road", crg, "--lateral-offset-m", "1.0"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--lateral-offset-m: the left wheel's line v = 1.9 m" in err
    assert "surface." not in err
    with pytest.raises(SystemExit) as e:
        cli.main(["road", crg, "--start-m", "nan"])
    assert e.value.code == 2 and "--start-m: nan is not a finite number" in capsys.readouterr().err


def test_a_profile_csv_is_bounded_before_it_is_read(tmp_path, capsys, monkeypatch):
    """A profile CSV above MAX_PROFILE_BYTES is one line, exit 2, before pandas reads it (a CRG has
    its bound; a CSV had none), and a directory is 'not a regular file' (review of issue 33)."""
    from tyrelab import scenario_io

    two_track_road(tmp_path, length_m=40.0)
    monkeypatch.setattr(scenario_io, "MAX_PROFILE_BYTES", 1000, raising=False)
    monkeypatch.setattr(scenario_io.pd, "read_csv", lambda *a, **k: pytest.fail("read before the bound"))
    assert cli.main(["road", str(tmp_path / "tracks.csv")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "bytes, above the 1000 bytes a profile CSV may have" in err
    assert cli.main(["road", str(tmp_path)]) == 2
    assert "not a regular file" in capsys.readouterr().err
