"""Ride prediction (issue 13): scenario files, the linear model, exposure, the CLI."""

import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from tests.scenarios import TRACTOR, scenario_text, write
from tyrelab import cli
from tyrelab.stages import simulate as simulate_stage
from tyrelab.vehicle import iso2631, ride
from tyrelab.vehicle import profiles as pr
from tyrelab.scenario_io import ScenarioError, load_scenario, parse_scenario
from tyrelab.vehicle.model import SeatSuspension
from tyrelab.vehicle.solvers import lti
from tyrelab.vehicle.tractor import Tractor, simulate_tractor


def run_linear(a, b, c, d, w, dt_s: float = ride.DT_S) -> np.ndarray:
    """Outputs of ``(A, B, C, D)`` from rest at the samples of ``w`` (exact first-order hold)."""
    return lti.discretise(np.asarray(a, float), np.asarray(b, float), np.asarray(c, float), np.asarray(d, float), dt_s).run(w)


def pitch_plane_tractor(scenario, tyres, i: int) -> Tractor:
    """The twelve-number tractor of a scenario's parts at speed index ``i``."""
    return Tractor.of_parts(ride.build_parts(scenario, tyres, i))


# ------------------------------------------------------------------ checked by: sinusoid
def steady_state_seat_accel(t: Tractor, f_Hz: float, speed_m_s: float, amplitude_m: float, seat_ahead_m: float):
    """|seat vertical acceleration| of the bounce-pitch model under a sinusoidal track (rear delayed)."""
    w = 2 * math.pi * f_Hz
    m, inertia, a, b = t.mass_kg, t.pitch_inertia_kg_m2, t.front_distance_m, t.rear_distance_m
    zf = t.front_stiffness_N_per_m + 1j * w * t.front_damping_N_s_per_m   # complex axle stiffnesses
    zr = t.rear_stiffness_N_per_m + 1j * w * t.rear_damping_N_s_per_m
    delay = np.exp(-1j * w * (a + b) / speed_m_s)
    dyn = np.array([[zf + zr - m * w**2, zf * a - zr * b], [zf * a - zr * b, zf * a**2 + zr * b**2 - inertia * w**2]])
    force = amplitude_m * np.array([zf + zr * delay, zf * a - zr * b * delay])
    z, th = np.linalg.solve(dyn, force)
    return abs(-(w**2) * (z + seat_ahead_m * th))


def test_sinusoidal_profile_matches_the_steady_state_answer(tmp_path):
    wavelength, amplitude, speed_km_h = 2.5, 0.004, 9.0
    x = np.arange(0, 1000.0, 0.05)
    pd.DataFrame({"distance_m": x, "height_m": amplitude * np.sin(2 * np.pi * x / wavelength)}).to_csv(
        tmp_path / "sine.csv", index=False)
    text = scenario_text('kind = "profile"\nprofile = "sine.csv"\nenveloping = "none"', f"[{speed_km_h}]",
                         'longitudinal_model = "none"', "[seat]\nahead_of_cg_m = -0.4\nsuspension = \"rigid\"")
    res = ride.ride(load_scenario(write(tmp_path, text)), with_spectra=False)
    row = res.speeds.iloc[0]
    assert row["lift_off_fraction_front"] == 0 and row["lift_off_fraction_rear"] == 0
    assert row["simulation"] == "linear"
    v = speed_km_h / 3.6
    f0 = v / wavelength
    t = pitch_plane_tractor(res.scenario, res.tyres, 0)
    expected = steady_state_seat_accel(t, f0, v, amplitude, -0.4) * abs(iso2631.weighting_response(f0, "Wk")) / math.sqrt(2)
    assert row["a_wz_m_s2"] == pytest.approx(expected, rel=0.02)
    assert row["expected_a_wz_m_s2"] > 0  # a declared spectrum is needed for a line spectrum's expectation


# ------------------------------------------------------------------ checked by: random profile of known spectrum
def test_random_profile_matches_the_frequency_domain_expectation(tmp_path):
    # ISO 8608 class B-C boundary: a track on which the tractor stays on the ground at 6 and 12 km/h with the
    # damping of a new tyre (issue 27: the Table VII model, no longer the mean of old and new tyres)
    g0, dx = 32e-6, 0.05
    h = pr.spectral_synthesis(20000, dx, g0, np.random.default_rng(3))
    pd.DataFrame({"distance_m": np.arange(h.size) * dx, "height_m": h}).to_csv(tmp_path / "random.csv", index=False)
    text = scenario_text(f'kind = "profile"\nprofile = "random.csv"\nspectrum_g0_m3 = {g0}\nenveloping = "tapered"',
                         "[6, 12]")
    res = ride.ride(load_scenario(write(tmp_path, text)), with_spectra=False)
    assert (res.speeds["simulation"] == "linear").all()
    for _, row in res.speeds.iterrows():
        assert row["a_wz_m_s2"] == pytest.approx(row["expected_a_wz_m_s2"], rel=0.05)
        assert row["a_wx_m_s2"] == pytest.approx(row["expected_a_wx_m_s2"], rel=0.05)


# ------------------------------------------------------------------ the linear path is the tractor model
@pytest.mark.parametrize("model,kx,cx", [("none", 0.0, 0.0), ("kelvin_voigt", 9.1e5, 2e3), ("kelvin_voigt", 0.0, 6e3),
                                         ("maxwell", 9.1e5, 6e3)])
def test_linear_path_equals_simulate_tractor_without_lift_off(model, kx, cx):
    t = Tractor(5120, 6210, 1.54, 0.896, 0.838, 9.46e5, 7.28e5, 2.9e3, 2.2e3, kx, cx, model)
    dt, n = 1e-3, 6001
    th = np.arange(2 * n - 1) * dt / 2
    rng = np.random.default_rng(1)
    freqs, phases = rng.uniform(0.5, 8, 12), rng.uniform(0, 2 * np.pi, 12)
    ramp = np.clip(th / 0.5, 0, 1) ** 3
    u = 0.003 * ramp * np.sin(2 * np.pi * freqs[:, None] * th + phases[:, None]).sum(0)
    ud = np.gradient(u, dt / 2)
    ur, udr = 0.7 * np.roll(u, 400), 0.7 * np.roll(ud, 400)
    ur[:400] = udr[:400] = 0
    sim = simulate_tractor(t, u, ud, ur, udr, dt, lift_off=False)
    a, b, c, d = ride.state_space(t, 0.3, 1.1)
    y = run_linear(a, b, c, d, np.vstack([u[::2], ud[::2], ur[::2], udr[::2]]), dt)
    out = dict(zip(ride.OUTPUTS, y))
    for key in ("vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2"):
        scale = np.sqrt(np.mean(sim[key] ** 2)) + 1e-12
        assert np.max(np.abs(out[key] - sim[key])) / scale < 2e-3, key
    seat = sim["vertical_m_s2"] + 0.3 * sim["pitch_rad_s2"]
    assert np.max(np.abs(out["seat_vertical_m_s2"] - seat)) / np.sqrt(np.mean(seat**2)) < 2e-3


def test_frequency_response_is_the_time_path_at_one_frequency():
    t = Tractor(4700, 5500, 1.56, 0.95, 0.95, 7e5, 8e5, 3e3, 3e3, 9.1e5, 6e3, "maxwell")
    a, b, c, d = ride.state_space(t, -0.4, 1.0)
    f = 2.3
    time = np.arange(40000) * 1e-3
    u = np.sin(2 * np.pi * f * time)
    w = np.vstack([u, 2 * np.pi * f * np.cos(2 * np.pi * f * time), np.zeros_like(u), np.zeros_like(u)])
    y = run_linear(a, b, c, d, w)
    h = ride.frequency_response(a, b, c, d, [f])[:, :, 0]
    amp = np.abs(h[:, 0] + 2j * np.pi * f * h[:, 1])
    tail = y[:, -10000:]
    assert np.allclose(np.sqrt(2) * np.sqrt(np.mean(tail**2, axis=1)), amp, rtol=1e-3)


# ------------------------------------------------------------------ natural frequencies
def test_natural_frequencies_equal_the_cli(tmp_path, capsys):
    res = ride.ride(load_scenario(write(tmp_path, scenario_text('kind = "iso8608"\nclass = "B"\nlength_m = 40'))),
                    with_spectra=False)
    assert cli.main(["natural-frequencies", "--mass", "4700", "--pitch-inertia", "5500", "--front-distance", "1.56",
                     "--rear-distance", "0.95", "--front-tyre", "14.9R28", "--front-pressure", "1.6",
                     "--rear-tyre", "18.4R38", "--rear-pressure", "1.2"]) == 0
    nf = json.loads(capsys.readouterr().out)
    got = sorted(res.natural_frequencies_Hz.values())
    assert got == pytest.approx([nf["frequency_1_Hz"], nf["frequency_2_Hz"]], rel=1e-12)
    assert res.tyres["front"].stiffness_kN_per_m[0] == pytest.approx(nf["front_tyre_stiffness_kN_per_m"], rel=1e-12)


# ------------------------------------------------------------------ exposure arithmetic
def test_a8_and_hours_are_exact():
    e = ride.exposure(0.8, 0.7, 6.0)
    aw = max(0.8, 1.4 * 0.7)
    assert e["a8_m_s2"] == pytest.approx(aw * math.sqrt(6 / 8), rel=1e-15)
    assert e["hours_to_eav"] == pytest.approx(8 * (0.5 / aw) ** 2, rel=1e-15)
    assert e["hours_to_elv"] == pytest.approx(8 * (1.15 / aw) ** 2, rel=1e-15)
    assert e["a_v_m_s2"] == pytest.approx(math.hypot(0.8, 1.4 * 0.7), rel=1e-15)
    assert e["verdict"] == "above action value"
    assert ride.exposure(0.3, 0.1, 8)["verdict"] == "below action value"
    assert ride.exposure(1.3, 0.1, 8)["verdict"] == "above limit value"
    with pytest.raises(ValueError, match="hours_per_day"):
        ride.exposure(0.3, 0.1, 0)


def test_rows_carry_the_exposure_of_their_own_a_w(tmp_path):
    res = ride.ride(load_scenario(write(tmp_path, scenario_text('kind = "iso8608"\nclass = "C"\nlength_m = 60',
                                                                "[6, 14]"))), with_spectra=False)
    for _, r in res.speeds.iterrows():
        aw = max(r["a_wz_m_s2"], 1.4 * r["a_wx_m_s2"])
        assert r["a8_m_s2"] == pytest.approx(aw * math.sqrt(6 / 8), rel=1e-12)
        assert r["hours_to_elv"] == pytest.approx(8 * (1.15 / aw) ** 2, rel=1e-12)


# ------------------------------------------------------------------ bad scenarios
BAD = """
name = "bad"
colour = "red"
[tractor]
pitch_inertia_kg_m2 = -5500
front_distance_m = 1.56
rear_distance_m = 0.95
cg_height_m = 0.95
wheels = 4
[tyres.front]
size = "huge"
pressure_bar = 1.6
[tyres.rear]
size = "18.4R38"
pressure_bar = 1.2
[surface]
kind = "profile"
profile = "track.csv"
[exposure]
speeds_km_h = [4]
"""


def test_a_bad_scenario_lists_every_problem(tmp_path):
    pd.DataFrame({"x_m": np.arange(20.0), "height_m": 0.0}).to_csv(tmp_path / "track.csv", index=False)
    with pytest.raises(ScenarioError) as info:
        load_scenario(write(tmp_path, BAD))
    text = "\n".join(info.value.problems)
    for expected in ("unknown key 'colour'", "unknown key 'tractor.wheels'", "missing tractor.mass_kg (kg)",
                     "tractor.pitch_inertia_kg_m2: -5500", "tyres.front.size: tyre size 'huge' does not parse",
                     "no distance_m column"):
        assert expected in text, (expected, text)
    assert len(info.value.problems) == 6


def test_a_profile_outside_the_scenario_folder_is_refused(tmp_path):
    (tmp_path / "sub").mkdir()
    text = scenario_text('kind = "profile"\nprofile = "../outside.csv"')
    with pytest.raises(ScenarioError, match="escapes the scenario's folder"):
        load_scenario(write(tmp_path / "sub", text))
    with pytest.raises(ScenarioError, match="missing table \\[surface\\]"):
        parse_scenario(scenario_text("").replace("[surface]\n", ""))
    with pytest.raises(ScenarioError, match="not valid TOML"):
        parse_scenario("name = ")


@pytest.mark.parametrize("edit,message", [
    (lambda s: s.replace("[tractor]", "[tractor]\nmass = 1"), "unknown key 'tractor.mass'"),
    (lambda s: s.replace("mass_kg = 4700.0", ""), "missing tractor.mass_kg"),
    (lambda s: s.replace("pitch_inertia_kg_m2 = 5500.0", "pitch_inertia_kg_m2 = -1"), "pitch_inertia_kg_m2: -1"),
    (lambda s: s.replace('"14.9R28"', '"14.9XR"'), "does not parse"),
    (lambda s: s.replace('class = "C"', 'class = "Z"'), "not one of A, B"),
])
def test_cli_refuses_bad_scenarios_with_exit_2(tmp_path, capsys, edit, message):
    path = write(tmp_path, edit(scenario_text('kind = "iso8608"\nclass = "C"\nlength_m = 20')))
    assert cli.main(["ride", str(path)]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err and str(path) in err


# ------------------------------------------------------------------ the command
def test_ride_cli_json_fields_and_outputs(tmp_path, capsys):
    path = write(tmp_path, scenario_text('kind = "iso8608"\nclass = "C"\nlength_m = 50', "[6, 12]",
                                         'longitudinal_model = "maxwell"',
                                         "[seat]\nahead_of_cg_m = -0.4\nheight_above_cg_m = 1.0\nsuspension = \"linear\"\n"
                                         "natural_frequency_Hz = 1.8\ndamping_ratio = 0.3"))
    assert cli.main(["ride", str(path), "--out", str(tmp_path / "out")]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert set(doc["natural_frequencies_Hz"]) == {"bounce", "pitch"}
    assert set(doc["nodal_points_m"]) == {"bounce", "pitch"}
    assert [s["speed_km_h"] for s in doc["speeds"]] == [6, 12]
    for key in ("a_wz_m_s2", "a_wx_m_s2", "a_v_m_s2", "vdv_m_s1_75", "crest_factor", "lift_off_fraction_front",
                "lift_off_fraction_rear", "a8_m_s2", "hours_to_eav", "hours_to_elv", "verdict",
                "expected_a_wz_m_s2", "expected_a_wx_m_s2"):
        assert key in doc["speeds"][0], key
    assert doc["tyres"]["front"]["stiffness_source"].startswith("formula front undriven K = 134")
    assert doc["tyres"]["rear"]["stiffness_source"].startswith("formula K = 172")
    assert doc["tyres"]["front"]["damping_source"].startswith("Table VII model C =")  # issue 27
    assert any("95 % prediction interval" in w for w in doc["tyres"]["front"]["warnings"])
    html = (tmp_path / "out" / "ride.html").read_text()
    assert html.count("<svg") == 3 and "http" not in html.replace("http://www.w3.org", "")
    assert json.loads((tmp_path / "out" / "ride.json").read_text()) == doc
    first = html
    assert cli.main(["ride", str(path), "--out", str(tmp_path / "out"), "--format", "table"]) == 0
    table = capsys.readouterr().out
    assert "A(8)" in table and "bounce" in table
    assert (tmp_path / "out" / "ride.html").read_text() == first  # same input, same bytes


def test_pressure_sweep_through_the_executor(tmp_path):
    sc = load_scenario(write(tmp_path, scenario_text('kind = "iso8608"\nclass = "B"\nlength_m = 30', "[10]")))
    local = ride.ride_sweep(sc, [1.2, 2.0], [1.0], with_spectra=False, method="time")
    from tyrelab.executor import map_batches

    ctx = SimpleNamespace(executor="local", jobs=2, scheduler=None)
    for method in ("time", "auto"):  # auto: the spectral rows here, the time rows of the first variant there
        pooled = ride.ride_sweep(sc, [1.2, 2.0], [1.0], map_fn=lambda task, items: map_batches(task, items, ctx),
                                 with_spectra=False, method=method)
        assert [r.tyres["front"].pressure_bar for r in pooled] == [1.2, 2.0]
        here = local if method == "time" else ride.ride_sweep(sc, [1.2, 2.0], [1.0], with_spectra=False)
        assert ride.results_table(here).equals(ride.results_table(pooled))
    k = ride.results_table(local)["front_stiffness_kN_per_m"]
    assert k.iloc[1] > k.iloc[0]  # stiffer at the higher pressure
    doc = ride.result_json(local)
    assert len(doc["sweep"]) == 2 and doc["sweep"][1]["front_pressure_bar"] == 2.0


def test_per_speed_values_and_overrides(tmp_path):
    text = scenario_text('kind = "iso8608"\nclass = "B"\nlength_m = 30', "[10, 20]",
                         front="stiffness_kN_per_m = [300, 400]\ndamping_kN_s_per_m = 1.5")
    sc = load_scenario(write(tmp_path, text))
    t = ride.resolve_tyres(ride.with_overrides(sc, [15.0]))
    assert t["front"].stiffness_kN_per_m.tolist() == [350.0] and t["front"].stiffness_source == "override (scenario)"
    with pytest.raises(ScenarioError, match="2 values but exposure.speeds_km_h has 1"):
        parse_scenario(text.replace("speeds_km_h = [10, 20]", "speeds_km_h = [10]"))


def test_run_scenarios_quarantines_a_bad_file_and_runs_the_rest(tmp_path):
    good = write(tmp_path, scenario_text('kind = "iso8608"\nclass = "B"\nlength_m = 30', "[10]",
                                         extra="[sweep]\nrear_pressures_bar = [1.0, 1.4]"), "good.toml")
    bad = write(tmp_path, "name = 1\n", "bad.toml")
    scen, res, problems = simulate_stage.run_scenarios([(str(good), "raw"), (str(bad), "raw")])
    # auto: two spectral rows, and the first variant simulated beside them (no variant is the nominal one)
    assert list(scen["scenario"]) == ["test tractor"] and res["method"].tolist() == ["spectral", "time", "spectral"]
    assert res["is_nominal"].tolist() == [False, False, False]  # the sweep does not include 1.2 bar
    assert problems[0]["file"] == str(bad) and "name: expected text" in problems[0]["reason"]


def test_metric_tyres_pass_the_formula_range_warnings_on(tmp_path):
    from tyrelab.published import thesis_stiffness_model
    from tyrelab.tyre.stiffness import estimate_stiffness

    text = scenario_text('kind = "iso8608"\nclass = "B"\nlength_m = 30', "[10]").replace('"18.4R38"', '"480/70R38"')
    res = ride.ride(load_scenario(write(tmp_path, text)), with_spectra=False)
    est = estimate_stiffness("480/70R38", 1.2, 1.0, model=thesis_stiffness_model())
    assert res.tyres["rear"].stiffness_kN_per_m[0] == pytest.approx(est.stiffness_kN_per_m)
    assert est.warnings and set(est.warnings) <= set(res.tyres["rear"].warnings)
    assert any("480/70R38" in w or w.startswith("tyres.rear:") for w in ride.result_json([res])["warnings"])


def test_measured_tyre_from_the_warehouse(tmp_path):
    import duckdb

    con = duckdb.connect(str(tmp_path / "warehouse.duckdb"))
    con.execute("CREATE TABLE stiffness_pressure_by_speed AS SELECT * FROM (VALUES ('T9', 0.0, 200.0, 150.0), "
                "('T9', 10.0, 150.0, 140.0), ('T9', 20.0, 140.0, 130.0)) t(tyre_id, speed_km_h, intercept, slope)")
    con.execute("CREATE TABLE damping_pressure_by_speed AS SELECT * FROM (VALUES ('T9', 10.0, 1.0, 0.5), "
                "('T9', 20.0, 0.6, 0.4)) t(tyre_id, speed_km_h, intercept, slope)")
    con.close()
    text = scenario_text('kind = "iso8608"\nclass = "B"\nlength_m = 30', "[10, 15]").replace(
        'size = "18.4R38"', 'size = "18.4R38"\nmeasured_tyre_id = "T9"')
    sc = load_scenario(write(tmp_path, text))
    t = ride.resolve_tyres(sc, simulate_stage.WarehouseTyres(tmp_path))["rear"]
    assert t.stiffness_kN_per_m.tolist() == pytest.approx([150 + 140 * 1.2, 0.5 * (150 + 140 * 1.2) + 0.5 * (140 + 130 * 1.2)])
    assert t.damping_kN_s_per_m.tolist() == pytest.approx([1.6, 0.5 * 1.6 + 0.5 * (0.6 + 0.48)])
    assert "measured tyre T9" in t.stiffness_source
    with pytest.raises(ValueError, match="needs --build"):
        ride.resolve_tyres(sc, None)
    bad = write(tmp_path, text.replace('"T9"', '"T0"'), "t0.toml")
    assert cli.main(["ride", str(bad), "--build", str(tmp_path)]) == 2


def test_scenario_files_lists_shipped_then_new_raw_ones(tmp_path):
    from tyrelab.resources import scenarios_dir

    (tmp_path / "scenarios").mkdir()
    shipped = sorted(scenarios_dir().glob("*.toml"))
    (tmp_path / "scenarios" / "copy.toml").write_bytes(shipped[0].read_bytes())
    (tmp_path / "scenarios" / "mine.toml").write_text(scenario_text('kind = "iso8608"\nclass = "B"'))
    files = simulate_stage.scenario_files(tmp_path)
    assert files == [(str(p), "shipped") for p in shipped] + [(str(tmp_path / "scenarios" / "mine.toml"), "raw")]


def test_cli_out_that_is_a_file_is_a_usage_error(tmp_path, capsys):
    path = write(tmp_path, scenario_text('kind = "iso8608"\nclass = "B"\nlength_m = 20'))
    (tmp_path / "taken").write_text("")
    assert cli.main(["ride", str(path), "--out", str(tmp_path / "taken")]) == 2
    err = capsys.readouterr().err
    assert "--out" in err and "Traceback" not in err


def test_scenario_row_gives_the_modes_at_its_own_pressures(tmp_path):
    """The ride_scenarios row's natural frequencies and nodal points are those of the scenario's own
    (nominal) pressures, whether its [sweep] lists them second or not at all, not the first pair's."""
    base = scenario_text('kind = "iso8608"\nclass = "A"\nlength_m = 12', "[10]")
    second = write(tmp_path, base + "[sweep]\nfront_pressures_bar = [0.8, 1.6]\n", "second.toml")
    absent = write(tmp_path, base.replace('name = "test tractor"', 'name = "absent"')
                   + "[sweep]\nfront_pressures_bar = [0.8, 2.4]\n", "absent.toml")
    scen, res, problems = simulate_stage.run_scenarios([(str(second), "raw"), (str(absent), "raw")])
    assert not problems and (res["method"] == "spectral").sum() == 4
    # the modes at 1.6/1.2 bar from the tyres alone (bounce_pitch through the CLI's own path)
    nominal = ride.ride(load_scenario(write(tmp_path, base, "nominal.toml")), with_spectra=False)
    low = res[(res["scenario"] == "test tractor") & (res["front_pressure_bar"] == 0.8)]
    for name in ("test tractor", "absent"):
        row = scen[scen["scenario"] == name].iloc[0]
        for mode in ("bounce", "pitch"):
            assert row[f"{mode}_Hz"] == pytest.approx(nominal.natural_frequencies_Hz[mode], rel=1e-12)
            assert row[f"{mode}_nodal_point_m"] == pytest.approx(nominal.nodal_points_m[mode], rel=1e-12)
    # and the first pair's (0.8 bar front: a softer front tyre) differ by far more than rounding
    # (bounce -1.0 %, pitch -29 %: the pitch mode leans on the front axle)
    for mode, least in (("bounce", 0.005), ("pitch", 0.2)):
        assert low[f"{mode}_Hz"].iloc[0] < (1 - least) * nominal.natural_frequencies_Hz[mode], mode
    nominal_rows = res[res["is_nominal"]]  # its spectral row and, beside it, its time row
    assert nominal_rows["method"].tolist() == ["spectral", "time"]
    assert nominal_rows["bounce_Hz"].tolist() == pytest.approx([nominal.natural_frequencies_Hz["bounce"]] * 2)


def _profile_scenario(tmp_path, length_m: float, name: str, extra_surface: str = "") -> Path:
    """A scenario on a random profile of ``length_m`` (5 cm spacing) with no declared spectrum."""
    dx = 0.05
    h = pr.spectral_synthesis(int(round(length_m / dx)) + 1, dx, 16e-6, np.random.default_rng(5))
    pd.DataFrame({"distance_m": np.arange(h.size) * dx, "height_m": h}).to_csv(tmp_path / f"{name}.csv", index=False)
    return write(tmp_path, scenario_text(f'kind = "profile"\nprofile = "{name}.csv"\n{extra_surface}', "[10]"),
                 f"{name}.toml")


@pytest.mark.parametrize("length_m,segment_m", [(100.0, 25.0), (300.0, 51.2)])
def test_a_track_without_declared_spectrum_uses_its_own_welch_spectrum(tmp_path, length_m, segment_m):
    """The frequency-domain expectation of a profile without a declared spectrum uses the track's Welch
    spectrum: segments of 51.2 m (resolution 0.0195 cycles/m, 0.054 Hz at 10 km/h, well below W_k's
    0.5 Hz band) but at most a quarter of the track, so that a short track still averages seven
    half-overlapping segments. The lowest wavenumber of the spectrum is its first Welch bin,
    1/segment, exactly."""
    track = ride.build_profile(load_scenario(_profile_scenario(tmp_path, length_m, f"t{length_m:g}")))
    n, g = track.spectrum
    assert track.length_m == pytest.approx(length_m, abs=1e-9)  # the CSV's grid, its last sample kept
    assert n[0] == pytest.approx(1.0 / segment_m, rel=1e-9)
    assert n[-1] == pytest.approx(0.5 / 0.05, rel=1e-9)  # up to Nyquist
    assert "Welch" in track.spectrum_source and np.all(g > 0)


def test_tyre_footprint_is_the_chord_at_the_static_deflection(tmp_path):
    """Footprint of each tyre: the chord 2 sqrt(2 R d - d^2) at the static deflection d = W / K of its
    own load, W = m g b / (a + b) / 2 on a front tyre (m g a / (a + b) / 2 on a rear one)."""
    sc = load_scenario(write(tmp_path, scenario_text('kind = "iso8608"\nclass = "A"\nlength_m = 10', "[10]")))
    tyres = ride.resolve_tyres(sc)
    m, a, b, g = TRACTOR["mass_kg"], TRACTOR["front_distance_m"], TRACTOR["rear_distance_m"], 9.80665  # the model's g (the standard gravity)
    for axle, arm in (("front", b), ("rear", a)):
        t = tyres[axle]
        d = m * g * arm / (a + b) / 2 / (1e3 * t.stiffness_kN_per_m[0])
        assert 0.005 < d < 0.08, (axle, d)  # a loaded tractor tyre deflects centimetres
        chord = 2 * math.sqrt(2 * t.radius_m * d - d * d)
        assert t.footprint_m[0] == pytest.approx(chord, rel=1e-12), axle


def test_record_is_the_track_or_the_duration_whichever_is_shorter(tmp_path):
    """The record starts with the front axle on the track and lasts track length / speed, or
    ``simulation.duration_s`` when that is shorter (a longer one cannot run off the track's end)."""
    sc = load_scenario(write(tmp_path, scenario_text('kind = "iso8608"\nclass = "A"\nlength_m = 30', "[10]")))
    track = ride.build_profile(sc)
    wb, v = sc.tractor.wheelbase_m, 10 / 3.6
    start, stop = ride._record_window(track, wb, v, None)
    assert start == math.ceil((track.lead_in_m - wb) / (v * ride.DT_S))
    assert (stop - start) * ride.DT_S == pytest.approx(track.length_m / v, abs=ride.DT_S)
    assert track.length_m == pytest.approx(30, abs=0.1)
    assert ride._record_window(track, wb, v, 100.0) == (start, stop)
    s2, e2 = ride._record_window(track, wb, v, 4.0)
    assert s2 == start and (e2 - s2) * ride.DT_S == pytest.approx(4.0, abs=1e-9)


def test_rear_tyre_envelopes_the_track_with_its_own_radius():
    """Equal footprints but different radii (rigid tread band): the rear input is the track enveloped
    by the rear tyre's radius, not a copy of the front's."""
    rng = np.random.default_rng(2)
    dx = 0.05
    h = pr.spectral_synthesis(1200, dx, 64e-6, rng)
    track = pr.Profile(np.arange(h.size) * dx, h, h, "test", {})
    fp, radii, v, wb, n = (0.3, 0.3), (0.5, 0.9), 3.0, 2.5, 2000
    uf, udf, ur, udr = ride.axle_inputs(track, "rigid_band", fp, radii, v, wb, n)
    front_only = ride.axle_inputs(track, "rigid_band", fp, (0.5, 0.5), v, wb, n)
    rear_only = ride.axle_inputs(track, "rigid_band", fp, (0.9, 0.9), v, wb, n)
    assert np.array_equal(udf, front_only[1]) and np.array_equal(udr, rear_only[3])
    assert np.max(np.abs(ur - front_only[2])) > 1e-4  # a 0.9 m tyre bridges more than a 0.5 m one


@pytest.mark.parametrize("wavelength_m,amplitude_m,lifted", [(0.8, 0.008, "front"), (1.255, 0.013, "rear")])
def test_one_axle_lifting_off_sends_the_run_to_the_nonlinear_model(tmp_path, wavelength_m, amplitude_m, lifted):
    """A sinusoidal track at 10 km/h that starts abruptly after the lead-in: the start-up transient on
    top of the steady response (0.8 m waves, 3.5 Hz: front force 57 % of its static load; 1.255 m,
    2.2 Hz: rear 76 %) pulls one axle's linear tyre force below minus its static load, the other's
    not. The run goes to the nonlinear model and only that axle spends time off the ground."""
    x = np.arange(0, 30.0, 0.05)
    pd.DataFrame({"distance_m": x, "height_m": amplitude_m * np.sin(2 * np.pi * x / wavelength_m)}).to_csv(
        tmp_path / "sine.csv", index=False)
    text = scenario_text('kind = "profile"\nprofile = "sine.csv"\nenveloping = "none"', "[10]", 'longitudinal_model = "none"')
    sc = load_scenario(write(tmp_path, text))
    t = pitch_plane_tractor(sc, ride.resolve_tyres(sc), 0)
    v = 10 / 3.6
    track = ride.build_profile(sc)
    _, stop = ride._record_window(track, t.wheelbase_m, v, None)
    u = ride.axle_inputs(track.profile, "none", (0.3, 0.3), (0.7, 0.9), v, t.wheelbase_m, stop)
    y = run_linear(*ride.state_space(t), np.vstack([w[::2] for w in u]))
    forces = dict(zip(ride.OUTPUTS, y))
    static = dict(zip(("front", "rear"), t.mass_kg * 9.80665 * np.array([t.rear_distance_m, t.front_distance_m])
                      / t.wheelbase_m))
    other = "rear" if lifted == "front" else "front"
    assert forces[f"{lifted}_force_N"].min() < -static[lifted]
    assert forces[f"{other}_force_N"].min() > -0.95 * static[other]
    row = ride.ride(sc, with_spectra=False).speeds.iloc[0]
    assert row["simulation"] == "nonlinear (tyre lift-off)"
    assert row[f"lift_off_fraction_{lifted}"] > 0.002 and row[f"lift_off_fraction_{other}"] == 0


def test_the_parts_put_two_tyres_on_each_axle(tmp_path):
    """Axle values are two tyres' in SI (kN -> N); the longitudinal tyre values only with a longitudinal model."""
    text = scenario_text('kind = "iso8608"\nclass = "A"\nlength_m = 10', "[10, 20]",
                         'longitudinal_model = "kelvin_voigt"\nlongitudinal_stiffness_kN_per_m = 400\n'
                         'longitudinal_damping_kN_s_per_m = 2.5',
                         front="stiffness_kN_per_m = [300, 400]\ndamping_kN_s_per_m = 1.5")
    sc = load_scenario(write(tmp_path, text))
    tyres = ride.resolve_tyres(sc)
    t = pitch_plane_tractor(sc, tyres, 1)
    assert (t.front_stiffness_N_per_m, t.front_damping_N_s_per_m) == (800e3, 3e3)
    assert t.rear_stiffness_N_per_m == pytest.approx(2e3 * tyres["rear"].stiffness_kN_per_m[1], rel=1e-15)
    assert (t.longitudinal_stiffness_N_per_m, t.longitudinal_damping_N_s_per_m) == (800e3, 5e3)
    none = pitch_plane_tractor(load_scenario(write(tmp_path, text.replace('"kelvin_voigt"', '"none"'), "n.toml")), tyres, 0)
    assert (none.longitudinal_stiffness_N_per_m, none.longitudinal_damping_N_s_per_m) == (0.0, 0.0)


def test_json_numbers_are_rounded_to_six_decimals_and_the_transmissibility_grid(tmp_path):
    """result_json rounds every number to 6 decimals (non-finite: null); the transmissibility is given on
    300 log-spaced frequencies over FIGURE_BAND_HZ per speed (the contract of docs/simulation.md, "Outputs")."""
    res = ride.ride(load_scenario(write(tmp_path, scenario_text('kind = "iso8608"\nclass = "A"\nlength_m = 10',
                                                                "[10]"))))
    doc = ride.result_json([res])
    for mode in ("bounce", "pitch"):
        raw = res.natural_frequencies_Hz[mode]
        assert doc["natural_frequencies_Hz"][mode] == round(raw, 6) and round(raw, 6) != round(raw, 7)
    assert doc["speeds"][0]["a_wz_m_s2"] == round(float(res.speeds["a_wz_m_s2"].iloc[0]), 6)
    assert ride._clean(float("nan")) is None and ride._clean(np.float64(np.inf)) is None
    f = res.transmissibility["frequency_Hz"].to_numpy()
    assert f.size == 300 and (f[0], f[-1]) == pytest.approx(ride.FIGURE_BAND_HZ, rel=1e-12)
    np.testing.assert_allclose(f[1:] / f[:-1], (ride.FIGURE_BAND_HZ[1] / ride.FIGURE_BAND_HZ[0]) ** (1 / 299), rtol=1e-9)


def test_natural_frequency_intervals_with_one_tyre_given_and_one_from_the_formula(tmp_path):
    """A front stiffness given without uncertainty and the rear from the formula: the 95 % intervals come from
    the rear tyre's uncertainty alone, as bounce_pitch.frequency_uncertainty's first-order ones."""
    from tyrelab.vehicle.bounce_pitch import frequency_uncertainty

    text = scenario_text('kind = "iso8608"\nclass = "A"\nlength_m = 10', "[10]", front="stiffness_kN_per_m = 300")
    res = ride.ride(load_scenario(write(tmp_path, text)), with_spectra=False)
    kf, kr = res.tyres["front"].stiffness_kN_per_m[0], res.tyres["rear"].stiffness_kN_per_m[0]
    assert res.tyres["front"].stiffness_u_kN_per_m == 0 and res.tyres["rear"].stiffness_u_kN_per_m > 0
    (u1, u2), _ = frequency_uncertainty(*(TRACTOR[k] for k in ("mass_kg", "pitch_inertia_kg_m2", "front_distance_m",
                                                                "rear_distance_m")),
                                        kf, kr, 0.0, res.tyres["rear"].stiffness_u_kN_per_m)
    nat, ci = res.natural_frequencies_Hz, res.natural_frequency_intervals_Hz
    lower, upper = sorted(nat, key=nat.get)
    for mode, u in ((lower, u1), (upper, u2)):
        assert u > 0
        assert ci[mode] == pytest.approx([nat[mode] - 1.96 * u, nat[mode] + 1.96 * u], rel=1e-4)


def test_the_seat_part_is_the_base_excited_transmissibility():
    """|T| of a seat on a spring and damper: 1 far below its frequency, sqrt(1 + (2 zeta)^2) / (2 zeta) at
    it (1.84 for zeta = 0.3), and 2 zeta f_n / f (plus the spring's (f_n/f)^2) far above."""
    fn, z = 1.8, 0.3
    f = np.array([0.01, fn, 40.0])
    t = ride.frequency_response(*SeatSuspension(fn, z).linear().abcd, f)[0, 0]
    r = f / fn
    exact = np.abs((1 + 2j * z * r) / (1 - r**2 + 2j * z * r))
    np.testing.assert_allclose(np.abs(t), exact, rtol=1e-9)
    assert abs(t[0]) == pytest.approx(1.0, abs=1e-3) and abs(t[1]) == pytest.approx(math.sqrt(1 + 0.36) / 0.6, rel=1e-9)


def test_iso8608_track_spectrum_is_half_the_class_mean_with_waviness_two(tmp_path):
    """ISO 8608 class B: geometric mean G_d(n0 = 0.1 cycles/m) = 64e-6 m^3, G_d(n) = G_d(n0) (n/n0)^-2; the
    axle mean of two independent tracks has half of it (the frequency-domain path's input)."""
    sc = load_scenario(write(tmp_path, scenario_text('kind = "iso8608"\nclass = "B"\nlength_m = 10', "[10]")))
    n, g = ride.build_profile(sc).spectrum
    assert pr.ISO8608_CLASS_G0_M3["B"] == pytest.approx(64e-6, rel=1e-12)
    np.testing.assert_allclose(g, 0.5 * 64e-6 * (n / 0.1) ** -2.0, rtol=1e-12)
    assert n[0] < 0.1 < n[-1]
