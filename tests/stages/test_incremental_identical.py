"""Work proportional to the change, outputs as a clean rebuild: byte for byte, after each change.

One raw folder and one build folder (the manifest stores absolute paths, so a
clean rebuild must use the same folders): the build is brought up to date
incrementally after each change, its files are read, then it is deleted and
rebuilt from scratch, and every table, run file and report page must be the
same bytes. ``SOURCE_DATE_EPOCH`` fixes the report's "generated" time.
"""

from __future__ import annotations

import logging
import shutil
from pathlib import Path

import pytest

from tests.synthetic import edit_csv as _edit_csv
from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
from tyrelab import resources
from tyrelab.stages import ORDER, Context, run_pipeline

pytestmark = pytest.mark.long  # collected first: see tests/conftest.py

FAST = [s for s in ORDER if s != "simulate"]  # simulate has its own (slow) test below


def _campaign(raw: Path) -> Path:
    runs, i = [], 0
    for tyre, k0 in (("T1", 230e3), ("T2", 200e3)):
        for speed, c in ((0.0, 3000.0), (10.0, 1600.0)):
            for p in (0.83, 1.38, 1.93):
                i += 1
                rec = spring_damper_recording(k0 + 150e3 * p - (60e3 if speed else 0.0), c + 400 * p,
                                              duration_s=12.0, seed=i)
                runs.append((manifest_row(f"r{i:03d}", f"r{i:03d}.parquet", tyre_id=tyre, speed_km_h=speed,
                                          pressure_bar=p), rec))
    return write_campaign(raw / "c", runs)


def _outputs(build: Path) -> dict[str, bytes]:
    """Every file the pipeline publishes: tables, per-run files, report pages."""
    out = {}
    for sub in ("parquet", "runs", "reports"):
        for p in sorted((build / sub).rglob("*")) if (build / sub).is_dir() else []:
            if p.is_file():
                out[str(p.relative_to(build))] = p.read_bytes()
    return out


def _run(raw: Path, build: Path, stages: list[str], caplog) -> str:
    caplog.clear()
    with caplog.at_level(logging.INFO, logger="tyrelab"):
        run_pipeline(Context(raw=raw, build=build, jobs=1), stages)
    return caplog.text


def _assert_same_as_clean(raw: Path, build: Path, stages: list[str], caplog) -> str:
    """Update ``build`` incrementally, then compare it with a clean rebuild; return the incremental log."""
    log = _run(raw, build, stages, caplog)
    incremental = _outputs(build)
    shutil.rmtree(build)
    _run(raw, build, stages, caplog)
    clean = _outputs(build)
    assert sorted(incremental) == sorted(clean)
    different = [name for name in clean if incremental[name] != clean[name]]
    assert not different, different
    return log


@pytest.mark.slow  # 176 s on 2 busy cores; runs in `make test-all`, not in the default run
def test_add_remove_change_edit_published_match_clean_rebuild(tmp_path, caplog, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "631152000")
    raw, build = tmp_path / "raw", tmp_path / "build"
    folder = _campaign(raw)
    _run(raw, build, FAST, caplog)
    initial = _outputs(build)  # the clean build of the campaign as it is now

    # add one run, in a new campaign folder: only T1 is refitted, only its figures redrawn
    write_campaign(raw / "new", [(manifest_row("n001", "n001.parquet", tyre_id="T1", speed_km_h=10.0,
                                               pressure_bar=1.6), spring_damper_recording(400e3, 2500.0,
                                                                                          duration_s=12.0, seed=50))])
    log = _assert_same_as_clean(raw, build, FAST, caplog)
    assert "per-tyre fits 1 reused, 1 computed" in log
    assert "(0 drawn" not in log  # the figures of the new data are drawn ...
    # ... and the unchanged ones are not
    drawn = int(log.split("figures (")[1].split(" drawn")[0])
    total = int(log.split(" figures (")[0].rsplit(" ", 1)[1])
    assert 0 < drawn < total

    # remove it again: the campaign is the initial one, so its clean build is ``initial``
    shutil.rmtree(raw / "new")
    _run(raw, build, FAST, caplog)
    removed = _outputs(build)
    assert sorted(removed) == sorted(initial)
    assert not [name for name in initial if removed[name] != initial[name]]

    # change one manifest row (the load of one T2 run)
    _edit_csv(folder / "manifest.csv", lambda rows: rows[-1].update(load_kN="19.1"))
    log = _assert_same_as_clean(raw, build, FAST, caplog)
    assert "per-tyre fits 1 reused, 1 computed" in log

    # edit one published table: <raw>/published overrides the shipped tables
    shutil.copytree(resources.published_dir(), raw / "published")
    _edit_csv(raw / "published" / "table_iii.csv",
              lambda rows: rows[0].update(carcass_stiffness_kN_per_m=str(float(rows[0]["carcass_stiffness_kN_per_m"]) + 7)))
    log = _assert_same_as_clean(raw, build, FAST, caplog)
    assert "per-tyre fits 2 reused, 0 computed" in log  # our fits do not read the published tables
    assert "regress: recomputing (input(s) changed: " in log and "table_iii.csv" in log


@pytest.mark.slow
def test_edit_published_simulation_input_matches_clean_rebuild(tmp_path, caplog, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "631152000")
    raw, build = tmp_path / "raw", tmp_path / "build"
    _campaign(raw)
    stages = ["ingest", "simulate"]
    _run(raw, build, stages, caplog)
    shutil.copytree(resources.published_dir(), raw / "published")
    _edit_csv(raw / "published" / "table_xii.csv",
              lambda rows: rows[0].update(damping_kN_s_per_m=f"{float(rows[0]['damping_kN_s_per_m']) * 1.1:.3f}"))
    _edit_csv(raw / "published" / "table_xvi.csv",
              lambda rows: rows[3].update(rear_damping_kN_s_per_m=f"{float(rows[3]['rear_damping_kN_s_per_m']) * 1.1:.3f}"))
    log = _assert_same_as_clean(raw, build, stages, caplog)
    assert "simulate: recomputing" in log
    assert "studies 0 reused, 2 computed" in log  # both studies re-ran; the ride scenarios did not
    assert f"ride scenarios {len(list(resources.scenarios_dir().glob('*.toml')))} reused, 0 computed" in log
    # of them, only the edited rows' cases were simulated
    assert "carriage cases 11 reused, 1 computed" in log and "tractor cases 27 reused, 1 computed" in log
