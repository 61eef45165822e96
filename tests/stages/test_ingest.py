"""Ingest basics; the full bad-input suite is in test_ingest_robustness.py."""

from pathlib import Path

import pandas as pd

from tyrelab.stages import Context, run_stage
from tyrelab.stages.ingest import discover_campaigns, run_key, tyre_partition
from tests.synthetic import manifest_row, spring_damper_recording, write_campaign


def test_discover_campaigns(tmp_path):
    write_campaign(tmp_path / "a", [(manifest_row("a1", "a1.parquet"), spring_damper_recording())])
    write_campaign(tmp_path / "b" / "deep", [(manifest_row("b1", "b1.parquet"), spring_damper_recording())])
    assert discover_campaigns(tmp_path) == [tmp_path / "a", tmp_path / "b" / "deep"]
    assert discover_campaigns(tmp_path / "a") == [tmp_path / "a"]


def test_run_key_and_partition_are_file_safe():
    assert run_key("T1-001") == "T1-001"
    assert "/" not in run_key("a/b") and run_key("a/b") != run_key("a_b")
    assert tyre_partition("<script>") == "tyre_id=%3Cscript%3E"


def test_bad_run_quarantined_good_runs_proceed(tmp_path):
    write_campaign(tmp_path / "raw", [
        (manifest_row("ok", "ok.parquet"), spring_damper_recording()),
        (manifest_row("bad", "bad.parquet"), b"\x00garbage"),
        (manifest_row("neg", "neg.parquet", pressure_bar=-1.0), spring_damper_recording()),
    ])
    ctx = Context(raw=tmp_path / "raw", build=tmp_path / "build", jobs=1)
    r = run_stage("ingest", ctx)
    assert (r.n_ok, r.n_quarantined) == (1, 2)
    q = ctx.read_table("quarantine").set_index("run_id")
    assert "corrupt" in q.loc["bad", "reason"] and q.loc["bad", "file"].endswith("bad.parquet")
    assert "pressure_bar" in q.loc["neg", "reason"] and "minimum" in q.loc["neg", "reason"]
    # a fresh build: the corrupt file is neither converted nor unchanged (issue 26: "1 converted, 1 unchanged")
    assert r.message == "1 converted, 0 unchanged"


def test_campaign_tyres_csv_extends_catalogue(tmp_path):
    raw = write_campaign(tmp_path / "raw", [(manifest_row("n1", "n1.parquet", tyre_id="NEW1"), spring_damper_recording())])
    pd.DataFrame({"tyre_id": ["NEW1"], "size": ["18.4R38"]}).to_csv(raw / "tyres.csv", index=False)
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1)
    assert run_stage("ingest", ctx).n_ok == 1
    tyres = ctx.read_table("tyres").set_index("tyre_id")
    assert tyres.loc["NEW1", "section_width_in"] == 18.4 and "T1" in tyres.index


def test_downward_positive_accelerations_are_rejected(tmp_path):
    rec = spring_damper_recording()
    for c in ("accel_left_m_s2", "accel_right_m_s2"):
        rec[c] = -(rec[c] + 9.80665)  # deflection-positive, DC-coupled: averages -g
    raw = write_campaign(tmp_path / "raw", [(manifest_row("down", "down.parquet"), rec)])
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1)
    assert run_stage("ingest", ctx).n_quarantined == 1
    assert "downward-positive" in ctx.read_table("quarantine")["reason"].iloc[0]


def test_runs_converted_by_other_code_are_converted_again(tmp_path):
    """The per-run reuse is valid only for the code that converted the run: after an upgrade that
    changes the conversion, a build must hold what a clean build of the new code holds."""
    import json
    import logging

    from tyrelab.stages.ingest import run as ingest_run

    raw = write_campaign(tmp_path / "raw", [(manifest_row(f"r{i}", f"r{i}.parquet"), spring_damper_recording(seed=i))
                                            for i in range(2)])
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1, log=logging.getLogger("tyrelab.test"))
    assert ingest_run(ctx).message == "2 converted, 0 unchanged"
    assert ingest_run(ctx).message == "0 converted, 2 unchanged"
    path = ctx.state / "ingest_runs.json"
    kept = json.loads(path.read_text())
    kept["r0"]["code"] = "an older version"
    path.write_text(json.dumps(kept))
    assert ingest_run(ctx).message == "1 converted, 1 unchanged"


def test_vehicle_recordings_of_rides_csv_are_not_orphan_runs(tmp_path):
    """A campaign's rides.csv lists vehicle recordings (issue 24; ``tyrelab generate`` writes
    them into the demo campaign): ingest must not reject them, nor rides.csv itself, as files
    without a manifest row (that made ``tyrelab run`` on the demo exit 3). A stray file still is."""
    raw = write_campaign(tmp_path / "raw", [(manifest_row("ok", "ok.parquet"), spring_damper_recording())])
    (raw / "rides").mkdir()
    t = pd.DataFrame({"time_s": [0.0, 0.01], "seat_z_m_s2": [0.0, 0.1]})
    t.to_parquet(raw / "rides" / "r1.parquet")
    t.to_csv(raw / "rides" / "r2.csv", index=False)
    t.to_parquet(raw / "stray.parquet")
    # a road profile a row's track names (generate writes rides/slatted_track.csv): not a run either
    pd.DataFrame({"x_m": [0.0, 1.0], "left_m": [0.0, 0.01], "right_m": [0.0, 0.01]}).to_csv(
        raw / "rides" / "slats.csv", index=False)
    pd.DataFrame({"ride_id": ["r1", "r2"], "file": ["rides/r1.parquet", "rides/r2.csv"],
                  "track": ["rides/slats.csv", "ISO 8608 class B"]}).to_csv(raw / "rides.csv", index=False)
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1)
    assert run_stage("ingest", ctx).n_ok == 1
    q = ctx.read_table("quarantine")
    assert [Path(f).name for f in q["file"]] == ["stray.parquet"], q


def test_a_rides_csv_is_read_by_the_project_reader(tmp_path):
    """``rides.csv`` written as a spreadsheet writes it (``;`` separated, a BOM) lists its
    recordings to ingest as it does to the rides stage: they are not orphan tyre runs."""
    raw = write_campaign(tmp_path / "raw", [(manifest_row("ok", "ok.parquet"), spring_damper_recording())])
    pd.DataFrame({"time_s": [0.0, 0.01], "seat_z_m_s2": [0.0, 0.1]}).to_parquet(raw / "r1.parquet")
    (raw / "rides.csv").write_bytes("\ufeffride_id;file;speed_km_h\nr1;r1.parquet;12,5\n".encode())
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1)
    assert run_stage("ingest", ctx).n_ok == 1
    assert ctx.read_table("quarantine").empty
