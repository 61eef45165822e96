"""Hostile and careless raw folders (issue 11, defects 1, 5, 6, 7, 8, 9b, 11): one line each, never a hang."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
from tyrelab import io
from tyrelab.cli import main
from tyrelab.stages import Context, run_pipeline
from tyrelab.warehouse import query

GOOD = spring_damper_recording(duration_s=20.0)
STAGES = ["ingest", "analyse", "calibrate", "warehouse"]  # calibrate writes results


def build(raw, tmp_path, name="b"):
    ctx = Context(raw=raw, build=tmp_path / name, jobs=1)
    return ctx, run_pipeline(ctx, STAGES)


def quarantine(ctx) -> dict:
    q = ctx.read_table("quarantine")
    return dict(zip(q["file"].map(lambda f: Path(f).name), q["reason"]))


#: ``tyrelab`` with ``run`` restricted to :data:`STAGES` (regress, simulate and the report take minutes).
CLI = [sys.executable, "-c", "import sys, tyrelab.stages as s; s.ORDER[:] = %r\n"
       "from tyrelab.cli import main; sys.exit(main(sys.argv[1:]))" % STAGES]


@pytest.fixture(autouse=True)
def few_stages(monkeypatch):
    monkeypatch.setattr("tyrelab.stages.ORDER", STAGES)


def tyrelab(*args, timeout=180, **kw):
    """The CLI in a subprocess (for what must not hang the test process)."""
    return subprocess.run([*CLI, *map(str, args)], capture_output=True, text=True, timeout=timeout, **kw)


# -- 1. manifests as spreadsheets save them ---------------------------------------------------------

def european(manifest: Path) -> None:
    """Rewrite a manifest as European Excel saves it: BOM, ';', decimal commas, CRLF."""
    df = pd.read_csv(manifest, dtype=str)
    text = df.to_csv(index=False, sep=";", lineterminator="\r\n")
    numeric = ["speed_km_h", "pressure_bar", "load_kN", "excitation_frequency_Hz", "amplitude_mm_pp",
               "torque_kNm", "axle_mass_kg"]
    for c in numeric:
        df[c] = df[c].str.replace(".", ",", regex=False)
    manifest.write_bytes(b"\xef\xbb\xbf" + df.to_csv(index=False, sep=";", lineterminator="\r\n").encode())
    assert text != manifest.read_text(encoding="utf-8-sig")


def test_european_excel_manifest_is_read_correctly(tmp_path, caplog):
    rows = [(manifest_row("e1", "e1.parquet", pressure_bar=1.38, load_kN=18.3), GOOD),
            (manifest_row("e2", "e2.parquet", pressure_bar=0.85), GOOD)]
    plain = write_campaign(tmp_path / "plain", rows)
    euro = write_campaign(tmp_path / "euro", rows)
    european(euro / "manifest.csv")
    ctx_p, _ = build(plain, tmp_path, "bp")
    ctx_e, res = build(euro, tmp_path, "be")
    assert res[0].n_ok == 2 and res[0].n_rejected == 0
    cols = ["run_id", "pressure_bar", "load_kN", "excitation_frequency_Hz", "axle_mass_kg"]
    assert ctx_e.read_table("manifest")[cols].equals(ctx_p.read_table("manifest")[cols])
    assert any("';'-separated" in r.message and "decimal commas" in r.message for r in caplog.records)


@pytest.mark.parametrize("content, words", [
    (b"run_id|file|tyre_id\nx|x.parquet|T1\n", ["run_id|file|tyre_id", "separator", "CSV UTF-8"]),
    (b"run_id,file,tyre_id\n\xe9t\xe9,x.parquet,T1\n", ["not UTF-8", "0xE9", "CSV UTF-8"]),
])
def test_a_manifest_that_cannot_be_read_is_named_and_exits_non_zero(tmp_path, caplog, content, words):
    raw = write_campaign(tmp_path / "raw" / "c", [(manifest_row("a1", "a1.parquet"), GOOD)])
    good = write_campaign(tmp_path / "raw" / "d", [(manifest_row("d1", "d1.parquet"), GOOD)])
    (raw / "manifest.csv").write_bytes(content)
    rc = main(["run", "--raw", str(raw.parent), "--build", str(tmp_path / "b"), "--jobs", "1"])
    assert rc == 3
    line = next(r.getMessage() for r in caplog.records if str(raw / "manifest.csv") in r.getMessage())
    assert all(w in line for w in words), line
    db = tmp_path / "b" / "warehouse.duckdb"
    assert query(db, "SELECT run_id FROM results")["run_id"].tolist() == ["d1"]  # the good campaign went through
    assert good.is_dir()


def test_empty_tables_are_views_with_their_columns(tmp_path):
    raw = write_campaign(tmp_path / "raw", [(manifest_row("a1", "a1.parquet"), GOOD)])
    (raw / "manifest.csv").write_text("run_id;file\n")  # no usable column: rejected
    assert main(["run", "--raw", str(raw), "--build", str(tmp_path / "b"), "--jobs", "1"]) == 3
    db = tmp_path / "b" / "warehouse.duckdb"
    assert query(db, "SELECT count(*) AS n FROM results")["n"].iloc[0] == 0
    columns = set(query(db, "DESCRIBE results")["column_name"])
    assert {"run_id", "campaign", "stiffness_kN_per_m", "damping_kN_s_per_m", "qc_ok", "qc_reasons"} <= columns
    assert {"run_id", "file", "tyre_id"} <= set(query(db, "DESCRIBE manifest")["column_name"])


# -- 6. reading confined to the campaign ------------------------------------------------------------

def test_paths_outside_the_campaign_are_refused_unread(tmp_path, monkeypatch):
    outside = tmp_path / "outside"
    outside.mkdir()
    GOOD.to_parquet(outside / "secret.parquet", index=False)
    camp = tmp_path / "raw" / "c"
    camp.mkdir(parents=True)
    (camp / "linked").symlink_to(outside, target_is_directory=True)
    (camp / "link.parquet").symlink_to(outside / "secret.parquet")
    GOOD.to_parquet(camp / "inside.parquet", index=False)
    (camp / "alias.parquet").symlink_to(camp / "inside.parquet")  # a symlink inside the campaign is fine
    write_campaign(camp, [
        (manifest_row("abs", str(outside / "secret.parquet")), None),
        (manifest_row("up", "../../outside/secret.parquet"), None),
        (manifest_row("link", "link.parquet"), None),
        (manifest_row("folder", "linked/secret.parquet"), None),
        (manifest_row("ok", "inside.parquet"), None),
        (manifest_row("alias", "alias.parquet"), None),
    ])
    opened = []
    real = io.file_sha256
    monkeypatch.setattr(io, "file_sha256", lambda p, *a: opened.append(Path(p).resolve()) or real(p, *a))
    ctx, res = build(camp.parent, tmp_path)
    q = ctx.read_table("quarantine").set_index("run_id")["reason"]
    assert "absolute path" in q["abs"]
    for run in ("up", "link", "folder"):
        assert "outside the campaign folder" in q[run], q[run]
    assert sorted(ctx.read_table("manifest")["run_id"]) == ["alias", "ok"]
    assert (outside / "secret.parquet").resolve() not in opened and opened


# -- 5, 11. special files: never opened, never a hang --------------------------------------------

def test_fifos_below_raw_are_skipped_with_a_warning(tmp_path):
    raw = tmp_path / "raw"
    camp = write_campaign(raw / "c", [(manifest_row("ok", "ok.parquet"), GOOD),
                                      (manifest_row("pipe", "pipe.parquet"), None),
                                      (manifest_row("dir", "dir.parquet"), None)])
    os.mkfifo(camp / "pipe.parquet")
    os.mkfifo(camp / "notes.txt")
    os.mkfifo(raw / "tyres.csv")
    (raw / "scenarios").mkdir()
    os.mkfifo(raw / "scenarios" / "ride.toml")
    (camp / "dir.parquet").mkdir()
    out = tyrelab("run", "--raw", raw, "--build", tmp_path / "b", "--jobs", "1", timeout=300)
    assert out.returncode == 3, out.stderr
    assert "Traceback" not in out.stderr
    from tyrelab.stages.simulate import scenario_files

    assert all(source == "shipped" for _, source in scenario_files(raw))  # the FIFO is not read
    for name in ("notes.txt", "tyres.csv", "ride.toml"):
        assert any(name in line and "named pipe (FIFO)" in line and "skipped" in line for line in out.stderr.splitlines())
    q = query(tmp_path / "b" / "warehouse.duckdb", "SELECT run_id, reason FROM quarantine").set_index("run_id")["reason"]
    assert "named pipe (FIFO), not a regular file" in q["pipe"]
    assert "folder, not a regular file" in q["dir"]


# -- 7. ids that break file names or figures -------------------------------------------------------

def test_a_tyre_id_longer_than_a_file_name_is_quarantined(tmp_path):
    long_id = "T" * 300
    raw = write_campaign(tmp_path / "raw", [(manifest_row("ok", "ok.parquet"), GOOD),
                                            (manifest_row("long", "long.parquet", tyre_id=long_id), GOOD)])
    pd.DataFrame({"tyre_id": [long_id], "size": ["13.6R38"]}).to_csv(raw / "tyres.csv", index=False)
    ctx, res = build(raw, tmp_path)
    q = ctx.read_table("quarantine").set_index("run_id")["reason"]
    assert "tyre_id is 300 characters" in q["long"]
    assert ctx.read_table("manifest")["run_id"].tolist() == ["ok"]


def test_mathtext_in_a_tyre_id_is_plain_text_in_figures():
    from tyrelab.report import figures

    tid = "$\\undefinedmacro{$"
    r = pd.DataFrame({"tyre_id": tid, "speed_km_h": [0.0, 0.0, 10.0, 10.0], "pressure_bar": [1.0, 2.0, 1.0, 2.0],
                      "stiffness_kN_per_m": [300.0, 400.0, 310.0, 410.0], "qc_ok": True})
    svg = figures.stiffness_vs_pressure(r, None)
    assert "undefinedmacro" in svg


# -- 9b. the same runs in another campaign folder --------------------------------------------------

def test_results_name_the_current_campaign(tmp_path):
    a = write_campaign(tmp_path / "a" / "camp", [(manifest_row("s1", "s1.parquet"), GOOD)])
    b = tmp_path / "b" / "other"
    shutil.copytree(a, b)
    ctx = Context(raw=a.parent, build=tmp_path / "build", jobs=1)
    run_pipeline(ctx, STAGES)
    ctx = Context(raw=b.parent, build=tmp_path / "build", jobs=1)
    run_pipeline(ctx, STAGES)
    # relative to the raw folder (issue 46: no table holds a path of this machine)
    assert ctx.read_table("results")["campaign"].tolist() == ["other"]
    assert query(ctx.build / "warehouse.duckdb", "SELECT campaign FROM results")["campaign"].tolist() == ["other"]


def test_a_copied_build_reads_only_itself(tmp_path):
    raw = write_campaign(tmp_path / "raw", [(manifest_row("s1", "s1.parquet"), GOOD)])
    ctx, _ = build(raw, tmp_path, "orig")
    copy = tmp_path / "copy"
    shutil.copytree(ctx.build, copy)
    shutil.rmtree(ctx.build)
    db = copy / "warehouse.duckdb"
    assert query(db, "SELECT run_id FROM results")["run_id"].tolist() == ["s1"]
    assert query(db, "SELECT count(DISTINCT run_id) AS n FROM runs")["n"].iloc[0] == 1  # the copy's own signals
