"""Sweeps of scenario keys (issue 37): a swept key reaches the model or is refused by name, never
accepted and ignored; a pressure given by ``--set`` is the pressure ``--rear-pressure`` gives."""

import functools
from types import SimpleNamespace
import json
import math
import re
import shlex
from pathlib import Path
import pytest

from tests.scenarios import scenario_text
from tyrelab.cli import main
from tyrelab.scenario_io import ScenarioError, parse_scenario
from tyrelab.vehicle import ride
from tyrelab.vehicle.scenario import _sections, numeric_key
from tyrelab.vehicle.scenario_limits import LIMITS

#: A short track at one speed: every variant simulates ~2 s.
TINY = 'kind = "iso8608"\nclass = "C"\nlength_m = 10\nseed = 3'
text = functools.partial(scenario_text, surface=TINY, speeds="[20]", name="sweep", hours_per_day=6)

#: The pitch-plane template: a rigid seat, no longitudinal element, formula tyres, no parts.
PLAIN = text()
#: Everything the model has: 3-D, a linear seat, Maxwell fore-aft, a suspended front axle, a pivot
#: rear axle is not allowed beside it (both pivoting is refused), a suspended cab, an implement on
#: a hitch spring, a front ballast; the tyres' radius and footprint given.
RICH = text(
    tractor_extra='roll_inertia_kg_m2 = 2400\nfront_track_m = 1.9\nrear_track_m = 1.8\nlongitudinal_model = "maxwell"',
    seat='[seat]\nahead_of_cg_m = -0.3\nleft_of_cg_m = 0.3\nheight_above_cg_m = 1.0\nsuspension = "linear"\n'
         'natural_frequency_Hz = 1.8\ndamping_ratio = 0.3',
    front="radius_m = 0.7\nfootprint_m = 0.3", rear="radius_m = 0.85\nfootprint_m = 0.4",
    extra='[simulation]\nduration_s = 1.5\n'
          '[front_axle]\nmount = "suspended"\nroll_inertia_kg_m2 = 160\nmass_kg = 400\nheight_m = 0.7\n'
          'suspension_stiffness_kN_per_m = 150\nsuspension_damping_kN_s_per_m = 8\n'
          '[cab]\nmount = "suspended"\nmass_kg = 800\npitch_inertia_kg_m2 = 600\nroll_inertia_kg_m2 = 500\n'
          'ahead_of_cg_m = -0.3\nheight_above_cg_m = 0.9\nfront_mount_ahead_of_cg_m = 0.5\n'
          'rear_mount_ahead_of_cg_m = -0.9\nmount_track_m = 1.2\nmount_stiffness_kN_per_m = 30\n'
          'mount_damping_kN_s_per_m = 2\n'
          '[implement]\nmass_kg = 800\npitch_inertia_kg_m2 = 300\nroll_inertia_kg_m2 = 300\nbehind_rear_axle_m = 1.2\n'
          'height_m = 0.8\nmount = "hitch_spring"\nhitch_behind_rear_axle_m = 0.5\nhitch_height_m = 0.6\n'
          'hitch_stiffness_kN_m_per_rad = 150\nhitch_damping_kN_m_s_per_rad = 15\n'
          '[ballast]\nmass_kg = 600\nahead_of_front_axle_m = 0.8\nheight_m = 0.7\npitch_inertia_kg_m2 = 50\n'
          'roll_inertia_kg_m2 = 40\n')

#: Two plausible values of every numeric scenario key (the test below checks it names them all).
PROBE = {
    "tractor.mass_kg": (4500, 5200), "tractor.pitch_inertia_kg_m2": (5000, 6500),
    "tractor.front_distance_m": (1.4, 1.7), "tractor.rear_distance_m": (0.9, 1.1), "tractor.cg_height_m": (0.8, 1.1),
    "tractor.longitudinal_stiffness_kN_per_m": (300, 600), "tractor.longitudinal_damping_kN_s_per_m": (2, 5),
    "tractor.roll_inertia_kg_m2": (2000, 3000), "tractor.front_track_m": (1.7, 2.0), "tractor.rear_track_m": (1.6, 2.0),
    "seat.ahead_of_cg_m": (-0.5, 0.0), "seat.height_above_cg_m": (0.8, 1.2), "seat.natural_frequency_Hz": (1.5, 2.2),
    "seat.damping_ratio": (0.2, 0.5), "seat.left_of_cg_m": (0.1, 0.4),
    "surface.length_m": (10, 12), "surface.seed": (1, 2), "surface.dx_m": (0.04, 0.05),
    "surface.spectrum_g0_m3": (1e-5, 4e-5), "surface.spectrum_waviness": (1.8, 2.5), "surface.lead_in_m": (5, 8),
    "exposure.hours_per_day": (4, 8), "simulation.duration_s": (1.2, 1.6),
    "surface.lateral_offset_m": (0.0, 0.4), "surface.start_m": (0.0, 3.0),
    "cab.mass_kg": (700, 900), "cab.pitch_inertia_kg_m2": (500, 700), "cab.roll_inertia_kg_m2": (400, 600),
    "cab.ahead_of_cg_m": (-0.4, -0.2), "cab.height_above_cg_m": (0.8, 1.0), "cab.front_mount_ahead_of_cg_m": (0.4, 0.6),
    "cab.rear_mount_ahead_of_cg_m": (-1.0, -0.8), "cab.mount_track_m": (1.0, 1.3),
    "cab.mount_stiffness_kN_per_m": (25, 40), "cab.mount_damping_kN_s_per_m": (1, 3),
    "implement.mass_kg": (600, 1000), "implement.pitch_inertia_kg_m2": (200, 400),
    "implement.roll_inertia_kg_m2": (200, 400), "implement.behind_rear_axle_m": (1.0, 1.4),
    "implement.height_m": (0.6, 1.0), "implement.hitch_behind_rear_axle_m": (0.4, 0.6),
    "implement.hitch_height_m": (0.5, 0.7), "implement.hitch_stiffness_kN_m_per_rad": (120, 200),
    "implement.hitch_damping_kN_m_s_per_rad": (10, 20),
    "ballast.mass_kg": (400, 800), "ballast.ahead_of_front_axle_m": (0.6, 1.0), "ballast.height_m": (0.6, 0.8),
    "ballast.pitch_inertia_kg_m2": (30, 80), "ballast.roll_inertia_kg_m2": (30, 60),
}
for _axle in ("front", "rear"):
    PROBE.update({f"tyres.{_axle}.pressure_bar": (1.0, 1.6), f"tyres.{_axle}.stiffness_kN_per_m": (300, 450),
                  f"tyres.{_axle}.damping_kN_s_per_m": (1.0, 2.0), f"tyres.{_axle}.age_years": (1, 8),
                  f"tyres.{_axle}.radius_m": (0.6, 0.9), f"tyres.{_axle}.footprint_m": (0.25, 0.35)})
    PROBE.update({f"{_axle}_axle.roll_inertia_kg_m2": (120, 200), f"{_axle}_axle.mass_kg": (300, 500),
                  f"{_axle}_axle.height_m": (0.6, 0.8), f"{_axle}_axle.suspension_stiffness_kN_per_m": (120, 200),
                  f"{_axle}_axle.suspension_damping_kN_s_per_m": (5, 10)})


def _probe(key: str):
    """Two values of ``key`` to sweep: :data:`PROBE`'s, else 30 % and 60 % into its
    :data:`~tyrelab.vehicle.scenario_limits.LIMITS` range, else 0.8 and 1.25 times its default."""
    if key in PROBE:
        return PROBE[key]
    section, _, name = key.rpartition(".")
    for k in (key, f"axle.{name}" if section.endswith("_axle") else None, name if section.startswith("tyres.") else None):
        if k in LIMITS:
            low, high, _ = LIMITS[k]
            return (low + 0.3 * (high - low), low + 0.6 * (high - low))
    default = numeric_key(key).get("default")
    if isinstance(default, (int, float)) and default:
        return (0.8 * default, 1.25 * default)
    return None


def _numeric_keys() -> set:
    return {f"{s}.{n}" for s, spec in _sections().items() for n in spec["fields"] if numeric_key(f"{s}.{n}")}


def test_every_numeric_key_is_probed():
    """A key added to the schema is swept below too: PROBE's values, or ones from its bound or default."""
    missing = [k for k in sorted(_numeric_keys()) if _probe(k) is None]
    assert not missing, f"no values to sweep {missing}: give a bound in scenario_limits.LIMITS (or PROBE values here)"


#: What a run gives (not what it was given: pressures, tyre values and hours are echoed inputs).
RESULTS = ("a_wz_m_s2", "a_wx_m_s2", "a_wy_m_s2", "expected_a_wz_m_s2", "expected_a_wx_m_s2", "expected_a_wy_m_s2",
           "vdv_m_s1_75", "vdv_daily_m_s1_75", "crest_factor", "lift_off_fraction_front", "lift_off_fraction_rear",
           "a_v_m_s2", "a8_m_s2", "hours_to_eav", "hours_to_elv", "verdict", "duration_s")


def _numbers(result) -> dict:
    """A variant's results: natural frequencies and nodal points, and every speed's seat values."""
    doc = ride.result_json([result])
    return {"modes": (doc["natural_frequencies_Hz"], doc["natural_frequencies_Hz_ci95"], doc["nodal_points_m"]),
            "speeds": [{k: row[k] for k in RESULTS} for row in doc["speeds"]]}


def _ignored_and_unnamed(scenario, keys) -> tuple[list, list]:
    """Sweep each key of ``keys`` (its :func:`_probe` values) through ``ride_sweep``: the keys whose two
    variants give the same results, and the refusals that do not name their key."""
    variants, unnamed = {}, []
    for key in sorted(keys):
        def keep(task, chunks, key=key):  # ride_sweep's executor: keep the variants, run them all at once below
            variants[key] = [sc for chunk in chunks for sc in chunk[0]]
            return [[SimpleNamespace(modes=None) for _ in chunk[0]] for chunk in chunks]

        try:
            ride.ride_sweep(scenario, sets={key: _probe(key)}, map_fn=keep, with_spectra=False, method="time")
        except ValueError as exc:  # ScenarioError included
            if key not in str(exc):
                unnamed.append((key, str(exc)))
    runs = iter(ride.ride_variants([sc for pair in variants.values() for sc in pair], with_spectra=False))
    return [key for key in variants if _numbers(next(runs)) == _numbers(next(runs))], unnamed


# "rich" sweeps every key of a 3-D scenario with rolling tyres (damped modes per variant): 100 s on
# 2 cores, a third of the default run's critical path, so it runs in `make test-all`; "plain" stays.
@pytest.mark.parametrize("base", ["plain", pytest.param("rich", marks=pytest.mark.slow)])
def test_every_swept_key_reaches_the_model_or_is_refused_by_name(base):
    ignored, unnamed = _ignored_and_unnamed(parse_scenario({"plain": PLAIN, "rich": RICH}[base]),
                                            (_numeric_keys() | set(PROBE)) - {k for k in _numeric_keys() if _probe(k) is None})
    assert not ignored and not unnamed, f"{base}: swept and ignored: {ignored}; refused without the key: {unnamed}"


@pytest.mark.parametrize("kind", ["profile", "slatted", "crg"])
def test_every_swept_surface_key_of_a_profile_slatted_or_crg_road_reaches_the_model_or_is_refused(tmp_path, kind):
    import numpy as np
    import pandas as pd

    rng = np.random.default_rng(5)
    x = np.arange(400) * 0.05
    pd.DataFrame({"distance_m": x, "height_m": 0.01 * rng.standard_normal(400)}).to_csv(tmp_path / "p.csv", index=False)
    if kind == "crg":
        pyopencrg = pytest.importorskip("pyopencrg")
        v = np.round(np.arange(-1.5, 1.5001, 0.1), 10)
        pyopencrg.CrgRoad(0.01 * rng.standard_normal((400, v.size)), u_inc=0.05, v=v).save(tmp_path / "road.crg")
    surface = {"profile": 'kind = "profile"\nprofile = "p.csv"\nspectrum_g0_m3 = 2e-5',
               "slatted": 'kind = "slatted"\nlength_m = 10',
               "crg": 'kind = "crg"\nfile = "road.crg"\nlength_m = 12'}[kind]
    keys = [k for k in _numeric_keys() | set(PROBE) if k.startswith(("surface.", "simulation.")) and _probe(k)]
    ignored, unnamed = _ignored_and_unnamed(parse_scenario(text(surface=surface), tmp_path), keys)
    assert not ignored and not unnamed, f"{kind}: swept and ignored: {ignored}; refused without the key: {unnamed}"


def test_a_spectral_sweep_refuses_a_track_length_its_record_never_reaches():
    """Spectral rows (a sweep's default on an ISO 8608 track) of a record capped by simulation.duration_s
    do not depend on the track's length: identical variants under different labels."""
    scenario = parse_scenario(RICH)
    with pytest.raises(ScenarioError, match="surface.length_m: spectral rows"):
        ride.ride_sweep(scenario, sets={"surface.length_m": (10, 12)}, with_spectra=False)
    a, b = ride.ride_sweep(scenario, sets={"surface.length_m": (10, 12)}, with_spectra=False, method="time")
    assert _numbers(a) != _numbers(b)


def _ride_json(capsys, *args) -> dict:
    assert main(["ride", *map(str, args)]) == 0
    return json.loads(capsys.readouterr().out)


def test_a_pressure_by_set_is_the_pressure_by_option_number_for_number(tmp_path, capsys):
    """Was: ``--set tyres.rear.pressure_bar=0.8,1.4`` ran both variants at the scenario's 1.2 bar."""
    path = tmp_path / "s.toml"
    path.write_text(PLAIN)
    by_set = _ride_json(capsys, path, "--set", "tyres.rear.pressure_bar=0.8,1.4")
    by_option = _ride_json(capsys, path, "--rear-pressure", "0.8", "1.4")
    assert by_set == by_option
    assert [v["rear_pressure_bar"] for v in by_set["sweep"]] == [0.8, 1.4]
    assert by_set["sweep"][0]["speeds"][0]["a_wz_m_s2"] != by_set["sweep"][1]["speeds"][0]["a_wz_m_s2"]
    both = ["--rear-pressure", "1.0", "--set", "tyres.rear.pressure_bar=0.8"]
    assert main(["ride", str(path), *both]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "tyres.rear.pressure_bar" in err and "--rear-pressure" in err


def test_two_swept_keys_both_apply(tmp_path, capsys):
    """Was: beside a swept implement mass every variant ran at the scenario's own pressure."""
    path = tmp_path / "s.toml"
    path.write_text(text(extra="[implement]\nmass_kg = 800\nbehind_rear_axle_m = 1.2\nheight_m = 0.8"))
    doc = _ride_json(capsys, path, "--method", "time", "--set", "tyres.rear.pressure_bar=0.8,1.4", "--set",
                     "implement.mass_kg=300,1200")  # the time domain, as the single run below (issue 36: auto)
    got = {(v["rear_pressure_bar"], v["variant"]["implement.mass_kg"]): v["speeds"][0]["a_wz_m_s2"] for v in doc["sweep"]}
    assert sorted(got) == [(0.8, 300), (0.8, 1200), (1.4, 300), (1.4, 1200)]
    assert len(set(got.values())) == 4  # every variant its own numbers
    alone = _ride_json(capsys, path, "--rear-pressure", "1.4", "--set", "implement.mass_kg=1200")
    assert alone["speeds"][0]["a_wz_m_s2"] == got[(1.4, 1200)]


def test_the_issue_s_pressure_sweep_writes_its_page(tmp_path, capsys):
    """Was: IndexError in the heatmap note (the page thought no key was swept)."""
    path = tmp_path / "s.toml"
    path.write_text(PLAIN)
    assert main(["ride", str(path), "--set", "tyres.rear.pressure_bar=0.8,1.4", "--out", str(tmp_path / "o"),
                 "--format", "table"]) == 0
    page = (tmp_path / "o" / "ride.html").read_text()
    assert "sweeps one key (rear_pressure_bar)" in page or "rear_pressure_bar" in page


def test_a_swept_key_the_model_does_not_use_is_refused_in_one_line_each(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(PLAIN)
    assert main(["ride", str(path), "--set", "seat.natural_frequency_Hz=1.5,2", "--set", "cab.mass_kg=500,900"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and "seat.natural_frequency_Hz: seat.suspension is \"rigid\"" in err[0]
    assert "cab.mass_kg: cab.mount is \"rigid\"" in err[1] and "Traceback" not in "".join(err)


ROOT = Path(__file__).resolve().parents[2]


def test_the_documented_sweep_examples_run_as_printed(capsys, monkeypatch):
    """Was: the README's ``--set implement.mass_kg=0,500,1000`` exited 2 (0 kg; and modern_tractor.toml
    has no [implement]). Every ``tyrelab ride … --set …`` of the README and docs runs, one variant per value."""
    docs = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md")), *sorted((ROOT / "docs").rglob("*.rst"))]
    found = [m.group(1) for p in docs for m in re.finditer(r"`(?:\.venv/bin/)?tyrelab (ride [^`]*--set [^`]*)`",
                                                             p.read_text(encoding="utf-8"))
             if "[" not in m.group(1)]  # not a synopsis (`tyrelab ride SCENARIO.toml [--set KEY=V1,V2,…]`)
    assert found, "the README (or docs) shows a sweep with --set"
    monkeypatch.chdir(ROOT)
    for command in found:
        args = shlex.split(command)
        assert main(args) == 0, command
        doc = json.loads(capsys.readouterr().out)
        sets = [a.split("=", 1) for a in args[args.index("--set") + 1:] if "=" in a]
        n = math.prod(len(v.split(",")) for _, v in sets)
        assert len(doc.get("sweep", [doc])) == n, command
