"""The sixth hostile round, the simulate stage (issue 46, Deliver 5): one bad campaign scenario of
each kind (an integer too large for a float, one too long to read, NaN, a CRG road outside the raw
folder directly or through its ``$ROAD_CRG_FILE``, a key outside its bound, too many spectral rows,
too many samples) is quarantined with one line naming its file and key; the good scenario beside
them runs; ``tyrelab simulate`` exits 3."""

import shutil

import numpy as np
import pytest

from tests.scenarios import scenario_text
from tyrelab.cli import main

pytestmark = pytest.mark.slow  # the shared small build (minutes when this file runs alone), then the stage

SPECTRAL = '[simulation]\nmethod = "spectral"'
BAD = {  # file -> (scenario text, what its one line must say)
    "huge.toml": (scenario_text(name="huge", tractor={"mass_kg": "1" + "0" * 400}),
                  "tractor.mass_kg: 1000000000…0000000000 (401 digits) is not a finite number"),
    "long.toml": (scenario_text(name="long", tractor={"mass_kg": "1" + "0" * 5000}),
                  "tractor.mass_kg: an integer of 5001 digits is not a finite number"),
    "nan.toml": (scenario_text(name="nan", tractor={"mass_kg": "nan"}), "tractor.mass_kg"),
    "escape.toml": (scenario_text('kind = "crg"\nfile = "../../outside/road.crg"\nlength_m = 50', name="escape"),
                    "escapes the scenario's folder"),
    "reference.toml": (scenario_text('kind = "crg"\nfile = "ref.crg"\nlength_m = 50', name="reference"),
                       "outside the campaign's folder"),
    "bound.toml": (scenario_text(name="bound", tractor={"mass_kg": "1e9"}),
                   "tractor.mass_kg: 1e+09 kg is outside 200 to 50000 kg"),
    "rows.toml": (scenario_text(name="rows", extra=SPECTRAL, speeds="[" + ", ".join(
        f"{0.5 + i * 0.002:.3f}" for i in range(35_000)) + "]"), "exposure.speeds_km_h: 1 variant(s) x 35000 speed(s)"),
    "samples.toml": (scenario_text(name="samples", speeds="[0.5, 0.6]",
                                   surface='kind = "iso8608"\nclass = "C"\nlength_m = 2000'), "--max-samples N"),
}


def test_each_bad_scenario_is_its_own_quarantine_line_and_the_good_one_runs(full_report, tmp_path, capsys):
    import pandas as pd
    import pyopencrg

    raw, build = tmp_path / "raw", tmp_path / "build"
    shutil.copytree(full_report.raw, raw)
    shutil.copytree(full_report.build, build)
    folder = raw / "scenarios"
    folder.mkdir(exist_ok=True)
    (tmp_path / "outside").mkdir()
    v = np.round(np.arange(-1.5, 1.5001, 0.1), 10)
    pyopencrg.CrgRoad(np.random.default_rng(3).normal(0, 0.005, (1200, v.size)), u_inc=0.05, v=v).save(
        tmp_path / "outside" / "road.crg", fmt="KDBI")
    (folder / "ref.crg").write_text("$ROAD_CRG_FILE\n../../outside/road.crg\n$\n")
    for name, (text, _) in BAD.items():
        (folder / name).write_text(text)
    (folder / "good.toml").write_text(scenario_text(name="good beside them"))
    code = main(["simulate", "--raw", str(raw), "--build", str(build), "--jobs", "1", "-q"])
    err = capsys.readouterr().err
    assert code == 3, err
    assert "Traceback" not in err and "Warning" not in err
    quarantine = pd.read_parquet(build / "parquet" / "stages" / "quarantine_simulate.parquet")
    quarantine = quarantine[quarantine["file"].str.startswith("scenarios/")]
    assert sorted(quarantine["file"]) == sorted(f"scenarios/{name}" for name in BAD)
    for row in quarantine.itertuples():
        reason = str(row.reason)
        assert "\n" not in reason and reason.startswith(f"{row.file}: "), reason  # one line, its file first
        assert BAD[row.file.split("/")[-1]][1] in reason, reason
        assert str(tmp_path) not in reason  # the warehouse holds no path of this machine
    scenarios = pd.read_parquet(build / "parquet" / "ride_scenarios.parquet")
    assert "scenarios/good.toml" in set(scenarios["file"])
    assert not set(scenarios["file"]) & {f"scenarios/{name}" for name in BAD}
