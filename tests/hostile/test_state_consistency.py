"""Stage state stays consistent with the outputs after an interruption (issue 11, defects 3 and 4)."""

import pytest

from tests.hostile.hostilekit import calibrated_campaign
from tyrelab.stages import Context, run_pipeline, run_stage

STAGES = ["ingest", "analyse", "calibrate"]


@pytest.fixture(scope="module")
def raw(tmp_path_factory):
    return calibrated_campaign(tmp_path_factory.mktemp("raw") / "c")


def flags(ctx):
    r = ctx.read_table("results").set_index("run_id")
    return r["qc_ok"].to_dict(), r["qc_reasons"].to_dict()


def test_analyse_force_then_run_keeps_the_calibration_flags(raw, tmp_path):
    ctx = Context(raw=raw, build=tmp_path / "b", jobs=1)
    run_pipeline(ctx, STAGES)
    clean = flags(ctx)
    assert list(clean[0].values()).count(False) >= 2  # the failed day's runs
    run_stage("analyse", Context(raw=raw, build=ctx.build, jobs=1, force=True))  # analyse's rows, without the flags
    assert flags(ctx) == clean  # results has one writer, calibrate: analyse never overwrites its flags
    run_pipeline(ctx, STAGES)
    assert flags(ctx) == clean


def test_an_output_overwritten_since_makes_its_stage_rerun(raw, tmp_path):
    ctx = Context(raw=raw, build=tmp_path / "b", jobs=1)
    run_pipeline(ctx, STAGES)
    before = ctx.table("calibration").read_bytes()
    ctx.table("calibration").write_bytes(b"")  # e.g. a write cut short by a full disk
    ran = {r.name: r.skipped for r in run_pipeline(ctx, STAGES)}
    assert ran == {"ingest": True, "analyse": True, "calibrate": False}
    assert ctx.table("calibration").read_bytes() == before


def test_calibration_correction_is_idempotent(raw, tmp_path):
    ctx = Context(raw=raw, build=tmp_path / "b", jobs=1, calibration_correct=True)
    run_pipeline(ctx, STAGES)
    once = ctx.table("results").read_bytes()
    run_stage("calibrate", Context(raw=raw, build=ctx.build, jobs=1, calibration_correct=True, force=True))
    assert ctx.table("results").read_bytes() == once
    run_pipeline(Context(raw=raw, build=ctx.build, jobs=1), STAGES)  # option off: analyse's values again
    off = Context(raw=raw, build=tmp_path / "clean", jobs=1)
    run_pipeline(off, STAGES)
    assert ctx.table("results").read_bytes() == off.table("results").read_bytes()
