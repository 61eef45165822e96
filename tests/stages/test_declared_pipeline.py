"""The pipeline as declared (:mod:`tyrelab.stages.dag`): order from the declarations, one writer per
output, and a damaged build repaired by the next run, byte for byte.

One raw folder and one build folder (the manifest stores absolute paths): a clean build is read,
then one output is deleted or overwritten with garbage, the pipeline runs again, and every
published file must be the clean build's bytes. ``SOURCE_DATE_EPOCH`` fixes the report's time.
"""

from __future__ import annotations

import itertools
import json
import logging
from pathlib import Path

import pytest

from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
from tyrelab.cli import main
from tyrelab.stages import ORDER, STAGES, Context, explain, plan, run_pipeline
from tyrelab.stages import dag

pytestmark = pytest.mark.long  # collected first: see tests/conftest.py

#: simulate reads only published tables and scenarios; its outputs are deleted from a copy of the
#: shared build of every stage (the tests at the end).
FAST = [s for s in ORDER if s != "simulate"]


def _campaign(raw: Path) -> Path:
    runs = []
    for i, (tyre, p) in enumerate([("T1", 0.83), ("T1", 1.93), ("T2", 1.38)], start=1):
        rec = spring_damper_recording(230e3 + 150e3 * p, 3000 + 400 * p, duration_s=12.0, seed=i)
        runs.append((manifest_row(f"r{i:03d}", f"r{i:03d}.parquet", tyre_id=tyre, pressure_bar=p), rec))
    return write_campaign(raw / "c", runs)


def _warehouse(db: Path) -> bytes:
    """The content of the warehouse, every table and view (a DuckDB file is not the same bytes twice)."""
    from tyrelab.warehouse import connect_read_only

    con = connect_read_only(db)
    try:
        names = sorted(r[0] for r in con.sql("SELECT table_name FROM information_schema.tables").fetchall())
        return "\n".join(f"{n}\n{con.sql(f'SELECT * FROM {chr(34)}{n}{chr(34)}').df().to_csv()}" for n in names).encode()
    finally:
        con.close()


def _outputs(build: Path) -> dict[str, bytes]:
    """Every file a stage writes (all of ``build/`` but state, the item cache and the lock); the
    warehouse by content."""
    return {str(p.relative_to(build)): _warehouse(p) if p.suffix == ".duckdb" else p.read_bytes()
            for p in sorted(build.rglob("*"))
            if p.is_file() and p.relative_to(build).parts[0] not in ("state", "cache") and p.name != ".tyrelab.lock"}


def _run(raw: Path, build: Path, caplog) -> str:
    caplog.clear()
    with caplog.at_level(logging.INFO, logger="tyrelab"):
        run_pipeline(Context(raw=raw, build=build, jobs=1), FAST)
    return caplog.text


@pytest.fixture(scope="module")
def clean(tmp_path_factory):
    """A clean build of a three-run campaign (every stage but simulate) and its files."""
    import os

    old = os.environ.get("SOURCE_DATE_EPOCH")
    os.environ["SOURCE_DATE_EPOCH"] = "631152000"
    root = tmp_path_factory.mktemp("declared")
    _campaign(root / "raw")
    run_pipeline(Context(raw=root / "raw", build=root / "build", jobs=1), FAST)
    yield root / "raw", root / "build", _outputs(root / "build")
    if old is None:
        os.environ.pop("SOURCE_DATE_EPOCH", None)
    else:
        os.environ["SOURCE_DATE_EPOCH"] = old


def test_order_follows_from_the_declarations():
    assert dag.check(STAGES) == []
    assert ORDER == list(dag.topological_order(STAGES))
    for i, name in enumerate(ORDER):  # every stage runs after each stage whose outputs it reads
        assert {ORDER.index(u) for u in dag.upstream(name)} <= set(range(i))
    # one writer per output, even through folders
    outs = [(o, s.name) for s in STAGES.values() for o in s.writes]
    assert len({o for o, _ in outs}) == len(outs)
    assert dag.writer("parquet/runs/tyre_id=T1/r001.parquet") == "ingest"
    assert dag.writer("reports/runs/r001.html") == "report"
    assert dag.writer("parquet/results.parquet") == "calibrate"


def test_a_bad_declaration_is_refused():
    a = dag.Stage("a", reads=("parquet/b.parquet",), writes=("parquet/a.parquet",))
    b = dag.Stage("b", reads=("parquet/a.parquet",), writes=("parquet/b.parquet",))
    assert any("cycle" in p for p in dag.check({"a": a, "b": b}))
    with pytest.raises(ValueError, match="cycle"):
        dag.topological_order({"a": a, "b": b})
    c = dag.Stage("c", reads=(), writes=("parquet/",))
    assert any("written by" in p for p in dag.check({"a": a, "c": c}))
    d = dag.Stage("d", reads=("parquet/nobody.parquet",), writes=("x",))
    assert dag.check({"d": d}) == ["d reads parquet/nobody.parquet, which no stage writes"]


def _some(outputs: dict, prefix: str) -> str:
    return next(name for name in sorted(outputs) if name.startswith(prefix))


#: One file of every kind of output, per stage (the slow test below takes every file).
SAMPLES = ["parquet/runs/", "parquet/manifest.parquet", "parquet/stages/quarantine_ingest.parquet",
           "parquet/stages/analysed.parquet", "parquet/results.parquet", "parquet/calibration.parquet",
           "parquet/table_iii.parquet", "parquet/published/", "parquet/quarantine.parquet", "warehouse.duckdb",
           "reports/index.html", "reports/runs/"]


def test_a_damaged_output_is_rebuilt_by_its_writer(clean, caplog):
    raw, build, files = clean
    for i, sample in enumerate(SAMPLES):  # deleted, or overwritten with garbage, in turn
        name = _some(files, sample)
        path = build / name
        if i % 2:
            path.write_bytes(b"not what the stage wrote\n")
        else:
            path.unlink()
        stale = [s for s, why in plan(Context(raw=raw, build=build, jobs=1), FAST) if why]
        assert stale and stale[0] == dag.writer(name), (name, stale)
        log = _run(raw, build, caplog)
        assert f"{dag.writer(name)}: recomputing" in log, (name, log)
        now = _outputs(build)
        assert sorted(now) == sorted(files), name
        assert [n for n in files if now[n] != files[n]] == [], name
    assert "recomputed: nothing" in _run(raw, build, caplog)


#: What a damaged state file may hold; every stage of :data:`FAST` gets one, in turn (there are
#: more stages than kinds of damage).
DAMAGE = ["null", "[]", "[1, 2]", '"text"', "{garbage", '{"inputs": 3}', ""]


def test_damaged_state_is_no_state(clean, caplog):
    raw, build, files = clean
    for name, content in zip(FAST, itertools.cycle(DAMAGE)):
        (build / "state" / f"{name}.json").write_text(content)
    (build / "state" / "ingest_runs.json").write_text('{"r001": null, "r002": [], "r003": {"size": 1}}')
    log = _run(raw, build, caplog)
    assert log.count("recomputing (no previous run recorded)") == len(FAST)
    assert "ingest: 3 in, 3 ok, 0 quarantined" in log and "3 converted" in log
    now = _outputs(build)
    assert [n for n in files if now.get(n) != files[n]] == []
    assert "recomputed: nothing" in _run(raw, build, caplog)


def test_explain_prints_the_plan_and_the_declared_graph(clean, capsys):
    raw, build, files = clean
    assert all(why is None for _, why in plan(Context(raw=raw, build=build, jobs=1), FAST))
    text = explain(Context(raw=raw, build=build, jobs=1))
    assert "ingest     up to date: skipped" in text
    assert "simulate   runs: no previous run recorded" in text
    assert text.endswith(dag.graph_text())
    for stage in STAGES.values():
        assert all(f"  writes {out}" in text for out in stage.writes)
    before = _outputs(build)
    assert main(["-q", "run", "--explain", "--raw", str(raw), "--build", str(build)]) == 0
    printed = capsys.readouterr().out
    assert "plan:" in printed and dag.graph_text() in printed
    assert _outputs(build) == before  # --explain runs nothing


@pytest.mark.slow
def test_deleting_any_single_output_restores_the_clean_bytes(clean, caplog):
    raw, build, files = clean
    for name in sorted(files):
        (build / name).unlink()
        _run(raw, build, caplog)
        now = _outputs(build)
        assert sorted(now) == sorted(files), name
        assert [n for n in files if now[n] != files[n]] == [], name


def test_the_architecture_document_shows_the_declared_graph():
    """docs/architecture.md's stage graph is generated: regenerate it with ``dag.graph_text()``."""
    doc = (Path(__file__).resolve().parents[2] / "docs" / "architecture.md").read_text(encoding="utf-8")
    block = doc.split("<!-- stage-graph:begin", 1)[1].split("<!-- stage-graph:end -->", 1)[0]
    assert block.split("```\n", 1)[1].rsplit("\n```", 1)[0] == dag.graph_text()


def test_every_declared_output_is_a_file_the_deletion_tests_take(clean, full_report):
    """Each output a stage declares is a file of the clean build above (every stage but simulate)
    or of the shared build of every stage (simulate), so that deleting "any single output file"
    (the tests above and below) reaches every declared output."""
    _, _, files = clean
    simulate_files = _outputs(full_report.build)
    for stage in STAGES.values():
        have = simulate_files if stage.name == "simulate" else files
        for out in stage.writes:
            assert any(dag._covers(out, name) for name in have), (stage.name, out)


def _simulate_outputs(build: Path) -> dict[str, bytes]:
    return {n: b for n, b in _outputs(build).items() if dag.writer(n) == "simulate"}


def _copy_of_the_full_build(full_report, tmp_path) -> Path:
    import shutil

    build = tmp_path / "build"
    shutil.copytree(full_report.build, build, ignore=shutil.ignore_patterns(".tyrelab.lock"))
    return build


#: One simulate output deleted in the default run (the slow test below takes each in turn).
SIMULATE_SAMPLE = "parquet/table_xviii.parquet"


def _restores(full_report, build: Path, names: list[str], caplog) -> None:
    clean = _simulate_outputs(build)
    assert SIMULATE_SAMPLE in clean and len(clean) == len(dag.STAGES["simulate"].writes)
    for name in names:
        (build / name).unlink()
        caplog.clear()
        with caplog.at_level(logging.INFO, logger="tyrelab"):
            run_pipeline(Context(raw=full_report.raw, build=build, jobs=1), ["simulate"])
        assert "simulate: recomputing" in caplog.text, name
        now = _simulate_outputs(build)
        assert [n for n in clean if now.get(n) != clean[n]] == [], name


def test_a_deleted_simulate_output_is_restored_byte_for_byte(full_report, tmp_path, caplog):
    build = _copy_of_the_full_build(full_report, tmp_path)
    _restores(full_report, build, [SIMULATE_SAMPLE], caplog)


@pytest.mark.slow
def test_deleting_any_single_simulate_output_restores_the_clean_bytes(full_report, tmp_path, caplog):
    build = _copy_of_the_full_build(full_report, tmp_path)
    _restores(full_report, build, sorted(_simulate_outputs(build)), caplog)
