"""The sixth hostile round (issue 46, after the fifth probe): the gaps the fifth probe's classes still
had. Spectral rows (variant x speed) bounded before any work by their measured cost, the same bound
for ``tyrelab ride``, ``tyrelab.ride``/``tyrelab.ride_sweep`` and the simulate stage's task;
``tyrelab.ride`` honouring a scenario's ``method = "spectral"`` as the CLI does; an all-NaN OpenCRG
road refused in our words from a scan of its bytes, before pyopencrg reads it."""

import json
import tomllib

import numpy as np
import pytest

import tyrelab
from tests.scenarios import scenario_text
from tyrelab.cli import main
from tyrelab.resources import scenarios_dir
from tyrelab.scenario_io import ScenarioError, load_scenario
from tyrelab.vehicle import ride as ride_module
from tyrelab.vehicle.scenario import limits

MODERN = scenarios_dir() / "modern_tractor.toml"
MODERN_3D = scenarios_dir() / "modern_3d_tractor.toml"


def lines(err: str) -> list[str]:
    assert "Traceback" not in err and "Warning" not in err
    return err.splitlines()


def _spectral(tmp_path, source=MODERN_3D, name="spectral.toml"):
    """``source`` with ``[simulation] method = "spectral"``, written to ``tmp_path``."""
    text = source.read_text()
    assert "[simulation]" not in text
    path = tmp_path / name
    path.write_text(text + '\n[simulation]\nmethod = "spectral"\n')
    return path


def _no_work(monkeypatch):
    """Any ride work fails the test: the refusal must come first."""
    def fail(*a, **k):
        pytest.fail("work started")

    for target in ("tyrelab.vehicle.run.sweep._sweep_results", "tyrelab.vehicle.ride._sweep_results",
                   "tyrelab.vehicle.run.frequency.spectral_variants", "tyrelab.vehicle.ride.ride_variants"):
        monkeypatch.setattr(target, fail)


SPEEDS = [f"{0.5 + i * 0.015:.3f}" for i in range(4400)]  # 4,400 speeds: 308 s of 3-D rows


# ----------------------------------------------------------------------------- spectral rows bounded
def test_the_estimate_prices_rows_by_model_and_figure_data():
    two_d, three_d = load_scenario(MODERN), load_scenario(MODERN_3D)
    e2 = limits.work_estimate(two_d, 10, [4, 8], method="spectral")
    e3 = limits.work_estimate(three_d, 10, [4, 8], method="spectral")
    assert e2["spectral_rows"] == e3["spectral_rows"] == 20 and e2["samples"] == e3["samples"] == 0
    assert e2["spectral_seconds"] == pytest.approx(20 * limits.SECONDS_PER_SPECTRAL_ROW
                                                   + 10 * limits.SECONDS_PER_SPECTRAL_VARIANT)
    assert e3["spectral_seconds"] == pytest.approx(20 * limits.SECONDS_PER_SPECTRAL_ROW_3D
                                                   + 10 * limits.SECONDS_PER_SPECTRAL_VARIANT_3D)
    every = limits.work_estimate(two_d, 10, [4, 8], method="spectral", with_spectra=True)["spectral_seconds"]
    nominal = limits.work_estimate(two_d, 10, [4, 8], method="spectral", with_spectra="nominal")["spectral_seconds"]
    fig = limits.SECONDS_PER_SPECTRAL_FIGURE_ROW
    assert (every - e2["spectral_seconds"], nominal - e2["spectral_seconds"]) == pytest.approx((20 * fig, 2 * fig))
    assert limits.work_estimate(two_d, 10, [4, 8], method="time")["spectral_rows"] == 0
    with pytest.raises(ValueError, match="with_spectra"):
        limits.work_estimate(two_d, 1, method="spectral", with_spectra="all")


def test_the_row_bound_is_what_the_time_allows_and_max_rows_replaces_it():
    sc = load_scenario(MODERN_3D)
    allowed = int((limits.MAX_SPECTRAL_SECONDS - limits.SECONDS_PER_SPECTRAL_VARIANT_3D)
                  / limits.SECONDS_PER_SPECTRAL_ROW_3D)
    speeds = [4.0] * allowed
    assert limits.work_problems(sc, 1, speeds, method="spectral") == []
    (line,) = limits.work_problems(sc, 1, speeds + [4.0], method="spectral")
    assert line.startswith(f"speeds_km_h: 1 variant(s) x {allowed + 1} speed(s) make {allowed + 1:,} spectral rows, "
                           "about 300 s of the 3-D model (0.070 s a row, 0.300 s a variant)"), line
    assert line.endswith("more than the 300 s a command's spectral rows may take; --max-rows N lifts the bound")
    assert limits.work_problems(sc, 1, speeds + [4.0], method="spectral", max_rows=allowed + 1) == []
    (line,) = limits.work_problems(sc, 1, [4.0] * 5, method="spectral", max_rows=4)
    assert "more than the 4 rows allowed; --max-rows N" in line
    # a time-domain ride has no spectral rows: the samples bound it
    assert not any("spectral rows" in p for p in limits.work_problems(sc, 1, speeds + [4.0], method="time"))


def test_tyrelab_ride_refuses_too_many_spectral_rows_before_work(tmp_path, capsys, monkeypatch):
    path = _spectral(tmp_path)
    _no_work(monkeypatch)
    assert main(["ride", str(path), "--speeds", *SPEEDS]) == 2
    (err,) = lines(capsys.readouterr().err)
    assert "speeds_km_h: 1 variant(s) x 4400 speed(s) make 4,400 spectral rows" in err and "--max-rows N" in err
    assert main(["ride", str(path), "--speeds", *SPEEDS, "--method", "time"]) == 2  # simulated: the samples' bound
    assert "samples" in capsys.readouterr().err
    with pytest.raises(BaseException, match="work started"):  # --max-rows lifts it: work starts
        main(["ride", str(path), "--speeds", *SPEEDS, "--max-rows", "4400"])


def test_a_sweep_of_many_variants_times_speeds_is_refused_by_its_rows(tmp_path, capsys, monkeypatch):
    _no_work(monkeypatch)
    pressures = [f"{1 + i / 100:g}" for i in range(60)]  # 60 x 60 = 3,600 variants: under MAX_SPECTRAL_VARIANTS
    args = ["ride", str(MODERN_3D), "--front-pressure", *pressures, "--rear-pressure", *pressures, "--speeds", "8"]
    assert main([*args, "--method", "spectral"]) == 2
    (err,) = lines(capsys.readouterr().err)
    assert "3600 variant(s) x 1 speed(s) make 3,600 spectral rows" in err
    assert main([*args, "--method", "auto"]) == 2  # auto on an ISO 8608 sweep: spectral rows alike
    assert "3,600 spectral rows" in capsys.readouterr().err


def test_the_library_and_the_stage_refuse_the_same_rows(tmp_path, monkeypatch):
    path = _spectral(tmp_path)
    doc = tomllib.loads(path.read_text())
    speeds = [float(v) for v in SPEEDS]
    _no_work(monkeypatch)
    with pytest.raises(ValueError, match=r"^speeds_km_h: 1 variant\(s\) x 4400 .*; max_rows=N lifts the bound$"):
        tyrelab.ride(doc, speeds_km_h=speeds)
    with pytest.raises(ValueError, match="4,400 spectral rows"):
        tyrelab.ride_sweep(path, speeds_km_h=speeds)
    with pytest.raises(ValueError, match="max_rows must be an integer from 1 to"):
        tyrelab.ride(doc, max_rows=0)
    # the simulate stage's task: the scenario's own speeds, every row with figure data
    many = path.read_text().replace("speeds_km_h = [4, 8, 12, 16, 20]", f"speeds_km_h = [{', '.join(SPEEDS[:4100])}]")
    (tmp_path / "many.toml").write_text(many)
    sc = load_scenario(tmp_path / "many.toml")
    assert limits.work_problems(sc, 1, method="spectral") == []  # 4,100 rows alone are within the bound
    with pytest.raises(ValueError, match=r"^exposure\.speeds_km_h: 1 variant\(s\) x 4100 .*figure data besides"):
        ride_module.ride_sweep(sc, with_spectra=True)
    from tyrelab.stages import ride_scenarios

    out = ride_scenarios.scenario_task((str(tmp_path / "many.toml"), "raw", None))
    assert out["error"].startswith(f"{tmp_path / 'many.toml'}: exposure.speeds_km_h: 1 variant(s) x 4100 speed(s) "
                                   "make 4,100 spectral rows")


# ----------------------------------------------------------------------------- the library honours the method
def test_library_ride_honours_a_spectral_scenario_as_the_cli_does(tmp_path, capsys):
    path = _spectral(tmp_path, MODERN)
    r = tyrelab.ride(path, speeds_km_h=[8, 12])
    assert list(r.speeds["method"]) == ["spectral", "spectral"]
    assert main(["ride", str(path), "--speeds", "8", "12", "--format", "json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    assert [s["method"] for s in cli["speeds"]] == ["spectral", "spectral"]
    for mine, theirs in zip(r.to_dict()["speeds"], cli["speeds"]):
        for key in ("a_wz_m_s2", "a_wx_m_s2", "a8_m_s2", "hours_to_eav", "evdv_m_s1_75"):
            assert mine[key] == pytest.approx(theirs[key], rel=1e-12), key  # the same computation
    assert list(tyrelab.ride(MODERN, speeds_km_h=[8]).speeds["method"]) == ["time"]  # auto, one variant: simulated


# ----------------------------------------------------------------------------- an all-NaN CRG road
def _nan_crg(folder, fmt, records=400, name="nan.crg"):
    import pyopencrg

    v = np.round(np.arange(-1.5, 1.5001, 0.1), 10)
    pyopencrg.CrgRoad(np.full((records, v.size), np.nan), u_inc=0.05, v=v).save(folder / name, fmt=fmt)
    return folder / name


@pytest.mark.parametrize("fmt", ["KRBI", "KDBI", "LRFI", "LDFI"])
def test_an_all_nan_crg_road_is_refused_in_our_words_before_pyopencrg_reads_it(tmp_path, capsys, monkeypatch, fmt):
    from tyrelab import scenario_io

    path = _nan_crg(tmp_path, fmt)
    opened = []
    monkeypatch.setattr("pyopencrg.open", lambda *a, **k: opened.append(a))
    with pytest.raises(ValueError, match=r"nan\.crg: every value of its data section is NaN, about 40\d cross "
                                         r"sections of 31 channels: no height to drive on"):
        scenario_io.read_crg(path)
    assert main(["road", str(path)]) == 2
    (err,) = lines(capsys.readouterr().err)
    assert "nan.crg" in err and "is NaN" in err and "at least 2 cross sections" not in err
    scenario = tmp_path / "s.toml"
    scenario.write_text(scenario_text('kind = "crg"\nfile = "nan.crg"\nlength_m = 10'))
    with pytest.raises(ScenarioError) as info:
        load_scenario(scenario)
    assert any("is NaN" in p for p in info.value.problems), info.value.problems
    assert not opened


def test_an_all_nan_data_file_behind_a_reference_is_named(tmp_path):
    from tyrelab import scenario_io

    _nan_crg(tmp_path, "KRBI", name="data.crg")
    (tmp_path / "ref.crg").write_text("$ROAD_CRG_FILE\ndata.crg\n$\n")
    with pytest.raises(ValueError, match=r"ref\.crg: every value of its data section \(its data file data\.crg"):
        scenario_io.read_crg(tmp_path / "ref.crg")


def test_a_crg_road_with_one_number_is_read_by_pyopencrg_as_before(tmp_path):
    import pyopencrg

    from tyrelab import scenario_io

    v = np.round(np.arange(-1.5, 1.5001, 0.1), 10)
    z = np.full((400, v.size), np.nan)
    z[:, 15] = 0.001  # one long section of numbers: read (the wheels' tracks are refused later, by their keys)
    pyopencrg.CrgRoad(z, u_inc=0.05, v=v).save(tmp_path / "thin.crg", fmt="KRBI")
    assert scenario_io.read_crg(tmp_path / "thin.crg").u_inc_m == pytest.approx(0.05)
