"""Recordings written by ``tyrelab generate`` and the README's exposure example on them."""

import re
import shlex
from pathlib import Path

import pandas as pd
import pytest

from tyrelab.cli import main
from tyrelab.generate import write_rides
from tyrelab.rawformat.rides import open_recording
from tyrelab.schema import load_schema, validate_frame
from tyrelab.vehicle import measured_ride

README = Path(__file__).resolve().parents[2] / "README.md"


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    root = tmp_path_factory.mktemp("readme")
    # what `make all` writes (seed 1991), but the chapter 6-7 recordings (tests/vehicle/test_study_recordings.py):
    # the README's outputs read the tractors' rows only
    write_rides(root / "raw" / "demo", seed=1991, studies=False)
    return root


def test_rides_csv_fits_its_schema_and_names_readable_recordings(demo):
    campaign = demo / "raw" / "demo"
    rides = pd.read_csv(campaign / "rides.csv", dtype=str, keep_default_na=False)
    assert validate_frame(rides, load_schema("raw_rides")) == []
    for row in rides.itertuples():
        rec = open_recording(campaign / row.file)
        assert set(rec.channels) == {"seat_x_m_s2", "seat_z_m_s2", "floor_x_m_s2", "floor_z_m_s2"}
        assert rec.sample_rate_Hz == pytest.approx(500.0)
        assert (campaign / row.scenario).is_file()


@pytest.mark.slow
def test_same_seed_same_bytes(demo, tmp_path):
    write_rides(tmp_path, seed=1991, studies=False)
    for f in sorted((demo / "raw" / "demo" / "rides").iterdir()):
        assert (tmp_path / "rides" / f.name).read_bytes() == f.read_bytes(), f.name
    assert (tmp_path / "rides.csv").read_bytes() == (demo / "raw" / "demo" / "rides.csv").read_bytes()


def test_virtual_seat_suspension_shows_in_seat(demo):
    """The modern tractor's suspension seat (1.8 Hz, ζ 0.3) passes less than the floor: SEAT z < 1."""
    a = measured_ride.analyse_recording(open_recording(demo / "raw" / "demo" / "rides" / "modern_tractor_12kmh.parquet"))
    seat = a.seat_factor()
    assert 0.5 < seat["z"] < 1.0 and seat["x"] == pytest.approx(1.0, abs=0.01)


def test_readme_exposure_example_is_the_real_output(demo, monkeypatch, capsys):
    text = README.read_text(encoding="utf-8")
    section = re.search(r"## Assess a driver's exposure from a recording\n(.*?)\n## ", text, re.S).group(1)
    command = re.search(r"```sh\n(.*?)```", section, re.S).group(1).replace("\\\n", " ")
    expected = re.search(r"```text\n(.*?)```", section, re.S).group(1)
    argv = shlex.split(command)
    assert argv[0].endswith("tyrelab")
    monkeypatch.chdir(demo)
    assert main(argv[1:]) == 0
    assert capsys.readouterr().out == expected


def test_readme_validation_example_is_the_real_output(demo, monkeypatch, capsys):
    text = README.read_text(encoding="utf-8")
    section = re.search(r"## Check a prediction against a recording\n(.*?)\n## ", text, re.S).group(1)
    commands = re.search(r"```sh\n(.*?)```", section, re.S).group(1).strip().splitlines()
    expected = re.search(r"```text\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(demo)
    for line in commands:
        argv = shlex.split(line, comments=True)
        assert main(["-q", *argv[1:]]) == 0
    assert capsys.readouterr().out == expected
