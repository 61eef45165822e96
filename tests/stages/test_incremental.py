"""Make-style runs: nothing changed -> nothing recomputed; one run changed -> only what depends on it."""

import logging

import pandas as pd
import pytest

from tyrelab.stages import Context, dag, run_pipeline
from tests.synthetic import manifest_row, spring_damper_recording, write_campaign

STAGES = ["ingest", "analyse", "calibrate", "warehouse"]  # calibrate writes results


def run(ctx, caplog, **over):
    for k, v in over.items():
        setattr(ctx, k, v)
    caplog.clear()
    with caplog.at_level(logging.INFO, logger="tyrelab"):
        results = run_pipeline(ctx, STAGES)
    ctx.force = False
    return {r.name: r for r in results}, caplog.text


@pytest.fixture()
def campaign(tmp_path):
    raw = tmp_path / "raw"
    write_campaign(raw / "c", [(manifest_row(f"r{i}", f"r{i}.parquet", pressure_bar=1.0 + 0.1 * i),
                                spring_damper_recording(duration_s=12.0, seed=i)) for i in range(4)])
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1)
    return raw / "c", ctx


def test_noop_rerun_recomputes_nothing(campaign, caplog):
    _, ctx = campaign
    run(ctx, caplog)
    res, text = run(ctx, caplog)
    assert all(r.skipped for r in res.values())
    for s in STAGES:
        assert f"{s}: up to date: inputs unchanged" in text
    assert "recomputed: nothing" in text
    assert res["ingest"].n_ok == 4  # counts survive a skip (how fast: bench/, not a test)


def test_touch_without_content_change_stops_at_ingest(campaign, caplog):
    folder, ctx = campaign
    run(ctx, caplog)
    manifest = ctx.table("manifest").read_bytes()
    (folder / "r1.parquet").touch()
    res, text = run(ctx, caplog)
    assert not res["ingest"].skipped and "0 converted, 4 unchanged" in res["ingest"].message
    assert res["analyse"].skipped and res["warehouse"].skipped
    assert ctx.table("manifest").read_bytes() == manifest


def test_changed_run_is_the_only_one_reanalysed(campaign, caplog):
    folder, ctx = campaign
    run(ctx, caplog)
    before = ctx.read_table("results").set_index("run_id")
    spring_damper_recording(400e3, 2500.0, duration_s=12.0).to_parquet(folder / "r2.parquet", index=False)
    res, text = run(ctx, caplog)
    assert "ingest: recomputing (input(s) changed: raw)" in text
    assert "analyse: recomputing (input(s) changed: manifest" in text
    assert "1 converted, 3 unchanged" in res["ingest"].message
    assert "3 reused, 1 analysed" in res["analyse"].message
    after = ctx.read_table("results").set_index("run_id")
    assert after.loc["r2", "stiffness_kN_per_m"] == pytest.approx(400, rel=0.01)
    pd.testing.assert_frame_equal(before.drop(index="r2"), after.drop(index="r2"))


def test_added_and_deleted_runs(campaign, caplog):
    folder, ctx = campaign
    run(ctx, caplog)
    rows = pd.read_csv(folder / "manifest.csv")
    spring_damper_recording(duration_s=12.0, seed=9).to_parquet(folder / "r9.parquet", index=False)
    rows = pd.concat([rows[rows["run_id"] != "r0"], pd.DataFrame([manifest_row("r9", "r9.parquet")])])
    rows.to_csv(folder / "manifest.csv", index=False)
    (folder / "r0.parquet").unlink()
    res, _ = run(ctx, caplog)
    assert "1 converted, 3 unchanged" in res["ingest"].message
    assert "3 reused, 1 analysed" in res["analyse"].message
    assert sorted(ctx.read_table("results")["run_id"]) == ["r1", "r2", "r3", "r9"]
    assert len(list((ctx.parquet / "runs").rglob("*.parquet"))) == 4  # r0's output removed


def test_force_redoes_everything(campaign, caplog):
    _, ctx = campaign
    run(ctx, caplog)
    res, text = run(ctx, caplog, force=True)
    assert not any(r.skipped for r in res.values()) and "recomputing (--force)" in text
    assert "0 reused, 4 analysed" in res["analyse"].message


def test_deleted_output_is_rebuilt(campaign, caplog):
    _, ctx = campaign
    run(ctx, caplog)
    ctx.table("results").unlink()
    res, text = run(ctx, caplog)
    assert res["ingest"].skipped and res["analyse"].skipped and not res["calibrate"].skipped  # its one writer
    assert "output(s) missing: parquet/results.parquet" in text and ctx.has_table("results")


def test_noop_cli_does_not_import_heavy_modules(campaign, caplog):
    import subprocess
    import sys

    _, ctx = campaign
    run(ctx, caplog)
    code = (
        "import sys; import tyrelab.stages as s; s.ORDER[:] = %r;"
        "from tyrelab.cli import main; main(['run', '--raw', %r, '--build', %r]);"
        "heavy = [m for m in ('matplotlib', 'statsmodels', 'dask', 'scipy', 'pandas', 'pyarrow') if m in sys.modules];"
        "print('HEAVY', heavy)" % (STAGES, str(ctx.raw), str(ctx.build))
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "HEAVY []" in out.stdout, out.stdout + out.stderr


def test_changed_template_changes_only_the_report_fingerprint(tmp_path, monkeypatch):
    from tyrelab.stages import state

    reports = tmp_path / "reports"
    reports.mkdir()
    (reports / "page.html.j2").write_text("one")
    real = state.resources.resource_dir
    monkeypatch.setattr(state.resources, "resource_dir",
                        lambda package: reports if package == "tyrelab.templates" else real(package))
    before = {s: state.stage_fingerprint(dag.STAGES[s]) for s in ("report", "analyse")}
    (reports / "page.html.j2").write_text("two")
    after = {s: state.stage_fingerprint(dag.STAGES[s]) for s in ("report", "analyse")}
    assert before["report"] != after["report"]
    assert before["analyse"] == after["analyse"]


def test_build_folder_inside_raw_does_not_make_runs_stale(tmp_path):
    from tyrelab.stages import Context, run_stage
    from tests.synthetic import manifest_row, spring_damper_recording, write_campaign

    raw = write_campaign(tmp_path / "raw" / "c", [(manifest_row("a", "a.parquet"), spring_damper_recording())]).parent
    ctx = Context(raw=raw, build=raw / "build", jobs=1)
    for stage in ("ingest", "analyse"):
        run_stage(stage, ctx)
    assert all(run_stage(stage, ctx).skipped for stage in ("ingest", "analyse"))
