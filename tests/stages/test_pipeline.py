"""End to end on analytic recordings: raw -> Parquet -> results -> warehouse -> report."""

import json

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest

from tyrelab.cli import main
from tyrelab.stages import Context, run_stage
from tyrelab.warehouse import query
from tests.synthetic import manifest_row, spring_damper_recording, write_campaign

K_C, DK_P, C_C, DC = 150e3, 180e3, 1000.0, 400.0  # N/m, N/m/bar, N s/m, N s/m/bar


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    raw = tmp_path_factory.mktemp("raw")
    runs = []
    for i, p in enumerate([0.8, 1.0, 1.2, 1.4, 1.6]):
        k, c = K_C + DK_P * p, C_C + DC * p
        runs.append((manifest_row(f"T1-{i}", f"T1-{i}.parquet", pressure_bar=p),
                     spring_damper_recording(k, c, force_noise_N=200, accel_noise_m_s2=0.05, seed=i)))
    runs.append((manifest_row("T1-csv", "T1-csv.csv", pressure_bar=1.1),
                 spring_damper_recording(K_C + DK_P * 1.1, C_C + DC * 1.1)))
    write_campaign(raw / "campaign-a", runs)
    build = tmp_path_factory.mktemp("build")
    ctx = Context(raw=raw, build=build, jobs=1)
    results = [run_stage(s, ctx) for s in ("ingest", "analyse", "calibrate", "warehouse", "report")]
    return raw, build, ctx, results


def test_every_run_goes_through(built):
    _, _, ctx, results = built
    assert [r.n_quarantined for r in results] == [0, 0, 0, 0, 0]
    assert results[0].n_ok == 6


def test_runs_partitioned_by_tyre_as_float32(built):
    _, build, _, _ = built
    files = sorted((build / "parquet" / "runs" / "tyre_id=T1").glob("*.parquet"))
    assert len(files) == 6
    schema = pq.read_schema(files[0])
    assert str(schema.field("load_beam_1_N").type) == "float"


def test_results_recover_k_and_c(built):
    _, _, ctx, _ = built
    res = ctx.read_table("results")
    k_true = (K_C + DK_P * res["pressure_bar"]) / 1e3
    c_true = (C_C + DC * res["pressure_bar"]) / 1e3
    np.testing.assert_allclose(res["stiffness_kN_per_m"], k_true, rtol=0.01)
    np.testing.assert_allclose(res["damping_kN_s_per_m"], c_true, rtol=0.03)
    assert res["qc_ok"].all()
    assert res["amplitude_measured_mm_pp"].between(13.5, 14.5).all()


def test_warehouse_views_and_sql(built):
    _, build, _, _ = built
    db = build / "warehouse.duckdb"
    n = query(db, "SELECT count(*) AS n FROM results")["n"].iloc[0]
    assert n == 6
    assert "published_table_iii" in set(query(db, "SELECT table_name FROM information_schema.tables")["table_name"])


def test_sql_cli_formats_and_refuses_writes(built, capsys):
    _, build, _, _ = built
    assert main(["sql", "--build", str(build), "--format", "json", "SELECT run_id, pressure_bar FROM results ORDER BY run_id"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert rows[0] == {"run_id": "T1-0", "pressure_bar": 0.8}
    assert main(["sql", "--build", str(build), "--format", "csv", "SELECT 1 AS one"]) == 0
    assert capsys.readouterr().out.splitlines() == ["one", "1"]
    for stmt in ["DROP VIEW results", "CREATE TABLE x AS SELECT 1", "SELECT 1; DELETE FROM results", "COPY results TO 'x.csv'"]:
        assert main(["sql", "--build", str(build), stmt]) == 2
        assert "refused" in capsys.readouterr().err


def test_report_written(built):
    _, build, _, _ = built
    html = (build / "reports" / "index.html").read_text()
    assert "<html" in html and "Campaign summary" in html


def test_rerun_reuses_everything(built):
    _, _, ctx, _ = built
    before = ctx.read_table("stages/analysed")
    r = run_stage("ingest", ctx)
    a = run_stage("analyse", ctx)
    assert r.skipped and a.skipped and r.n_ok == 6  # nothing changed: neither stage recomputes
    ctx.force = True
    a = run_stage("analyse", ctx)
    ctx.force = False
    assert "6 analysed" in a.message
    pd.testing.assert_frame_equal(before, ctx.read_table("stages/analysed"))


def test_analyze_run_json(built, capsys):
    raw, _, _, _ = built
    assert main(["analyze-run", str(raw / "campaign-a" / "T1-2.parquet"), "--axle-mass", "600"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["stiffness_N_per_m"] == pytest.approx(K_C + DK_P * 1.2, rel=0.01)
    assert out["damping_N_s_per_m"] == pytest.approx(C_C + DC * 1.2, rel=0.03)
    assert out["excitation_frequency_Hz"] == pytest.approx(4.0, abs=0.01)
    assert set(out) >= {"excitation_frequency_Hz", "stiffness_N_per_m", "damping_N_s_per_m", "amplitude_mm_pp", "coherence"}
    # issue 14: 95 % intervals and standard uncertainties; one recording has no day check -> §3.2.9 limits
    lo, hi = out["stiffness_ci95_N_per_m"]
    assert lo < out["stiffness_N_per_m"] < hi and lo < K_C + DK_P * 1.2 < hi
    lo, hi = out["damping_ci95_N_s_per_m"]
    assert lo < out["damping_N_s_per_m"] < hi
    assert 0.005 < out["stiffness_u_N_per_m"] / out["stiffness_N_per_m"] < 0.05  # the ±3 % gain limit dominates
    assert out["damping_u_N_s_per_m"] > 0 and out["uncertainty"]["instrument"] == "§3.2.9 limits"


def test_analyze_run_bad_file_is_one_line(tmp_path, capsys):
    bad = tmp_path / "bad.parquet"
    bad.write_bytes(b"not parquet")
    assert main(["analyze-run", str(bad), "--axle-mass", "600"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "bad.parquet" in err


def test_estimate_stiffness_cli(capsys):
    assert main(["estimate-stiffness", "--size", "13.6-38", "--pressure", "1.1", "--age", "1"]) == 0
    assert capsys.readouterr().out.strip().startswith("303.6 kN/m (95 % prediction interval")  # issue 14
    assert main(["estimate-stiffness", "--size", "banana", "--pressure", "1.1"]) == 2
    assert "does not parse" in capsys.readouterr().err
