"""Bad input never stops a campaign, never corrupts build/, and is quarantined with one clear line."""

import io as _io
import os
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from tyrelab.cli import main
from tyrelab.stages import Context, run_stage
from tests.synthetic import manifest_row, spring_damper_recording, write_campaign

GOOD = spring_damper_recording(duration_s=20.0)


def parquet_bytes(df: pd.DataFrame) -> bytes:
    buf = _io.BytesIO()
    df.to_parquet(buf, index=False)
    return buf.getvalue()


def with_nan(df, value):
    df = df.copy()
    df.loc[100, "load_beam_2_N"] = value
    return df


def resampled(fs):
    return spring_damper_recording(duration_s=20.0, sample_rate_Hz=fs)


def irregular():
    df = GOOD.copy()
    df.loc[500:, "time_s"] += 0.5 / 256
    return df


def non_monotonic():
    df = GOOD.copy()
    df.loc[[200, 201], "time_s"] = df.loc[[201, 200], "time_s"].to_numpy()
    return df


#: run_id -> (manifest overrides, file content, words expected in the reason)
BAD_RUNS = {
    "truncated": ({}, parquet_bytes(GOOD)[:4000], ["corrupt or truncated"]),
    "garbage": ({}, os.urandom(3000), ["corrupt or truncated"]),
    "no-channel": ({}, GOOD.drop(columns=["load_beam_3_N"]), ["missing channel", "load_beam_3_N"]),
    "nan": ({}, with_nan(GOOD, np.nan), ["load_beam_2_N", "NaN", "row 100"]),
    "inf": ({}, with_nan(GOOD, np.inf), ["load_beam_2_N", "infinite"]),
    "non-monotonic": ({}, non_monotonic(), ["not strictly increasing"]),
    "irregular": ({}, irregular(), ["irregular sampling"]),
    "wrong-rate": ({"sample_rate_Hz": 512.0}, GOOD, ["does not match the manifest", "512"]),
    "too-slow": ({"excitation_frequency_Hz": 6.0}, resampled(40.0), ["too low for 6 Hz"]),
    "unknown-tyre": ({"tyre_id": "NOPE"}, GOOD, ["unknown tyre_id", "NOPE"]),
    "bad-size-tyre": ({"tyre_id": "BAD1"}, GOOD, ["BAD1", "size"]),
    "negative-pressure": ({"pressure_bar": -0.5}, GOOD, ["pressure_bar", "minimum"]),
    "no-file": ({}, None, ["file not found"]),
    "huge": ({}, "sparse", ["GB", "limit"]),
}


def bad_suite(folder):
    """The bad-input campaign: every case of BAD_RUNS, a duplicate run id, an unlisted file, a bad tyre size."""
    runs = []
    for run_id, (over, content, _) in BAD_RUNS.items():
        runs.append((manifest_row(run_id, f"{run_id}.parquet", **over), None if isinstance(content, str) else content))
    runs.append((manifest_row("dup", "dup-1.parquet"), GOOD))
    runs.append((manifest_row("dup", "dup-2.parquet"), GOOD))
    write_campaign(folder, runs)
    with open(folder / "huge.parquet", "wb") as fh:  # 2 GB sparse file: must be rejected by size, unread
        fh.truncate(2 * 1024**3)
    parquet = folder / "orphan.parquet"
    GOOD.to_parquet(parquet, index=False)
    pd.DataFrame({"tyre_id": ["BAD1"], "size": ["not a size"]}).to_csv(folder / "tyres.csv", index=False)
    return folder


def good_campaign(folder, n=3):
    return write_campaign(folder, [(manifest_row(f"good-{i}", f"good-{i}.parquet"),
                                    spring_damper_recording(duration_s=20.0, seed=i)) for i in range(n)])


@pytest.fixture(scope="module")
def ingested(tmp_path_factory):
    raw = tmp_path_factory.mktemp("raw")
    good_campaign(raw / "good")
    bad_suite(raw / "bad")
    ctx = Context(raw=raw, build=tmp_path_factory.mktemp("build"), jobs=1)
    result = run_stage("ingest", ctx)
    return ctx, result, ctx.read_table("quarantine")


@pytest.mark.parametrize("run_id", sorted(BAD_RUNS))
def test_each_bad_run_is_quarantined_with_a_clear_reason(ingested, run_id):
    _, _, q = ingested
    rows = q[q["run_id"] == run_id]
    assert len(rows) == 1, f"{run_id} not quarantined exactly once"
    reason, file = rows["reason"].iloc[0], rows["file"].iloc[0]
    assert "\n" not in reason
    for word in BAD_RUNS[run_id][2]:
        assert word in reason, f"{word!r} not in {reason!r}"
    assert file.endswith(f"{run_id}.parquet")


def test_duplicate_run_id_keeps_the_first(ingested):
    ctx, _, q = ingested
    dup = q[q["run_id"] == "dup"]
    assert len(dup) == 1 and "duplicate run_id" in dup["reason"].iloc[0] and dup["file"].iloc[0].endswith("dup-2.parquet")
    assert (ctx.read_table("manifest")["run_id"] == "dup").sum() == 1


def test_file_without_manifest_row_and_bad_catalogue_are_reported(ingested):
    _, _, q = ingested
    no_id = q[q["run_id"].isna()]
    assert any(f.endswith("orphan.parquet") and "no row in manifest" in r for f, r in zip(no_id["file"], no_id["reason"]))
    assert any(f.endswith("tyres.csv") and "BAD1" in r for f, r in zip(no_id["file"], no_id["reason"]))


def test_good_runs_proceed(ingested):
    ctx, result, _ = ingested
    assert sorted(ctx.read_table("manifest")["run_id"]) == ["dup", "good-0", "good-1", "good-2"]
    assert result.n_ok == 4 and result.n_quarantined == len(BAD_RUNS) + 1


def test_cli_exit_code_says_runs_were_quarantined(ingested, capsys):
    ctx, _, _ = ingested
    assert main(["ingest", "--raw", str(ctx.raw), "--build", str(ctx.build), "--jobs", "1"]) == 3


def test_bad_suite_does_not_change_the_good_runs_in_the_warehouse(tmp_path):
    from tyrelab.warehouse import query

    def good_rows(raw, build):
        ctx = Context(raw=raw, build=build, jobs=1)
        for stage in ("ingest", "analyse", "calibrate", "warehouse"):
            run_stage(stage, ctx)
        return query(build / "warehouse.duckdb", "SELECT run_id, stiffness_kN_per_m FROM results WHERE qc_ok AND run_id LIKE 'good-%' ORDER BY run_id")

    good_campaign(tmp_path / "raw" / "good")
    alone = good_rows(tmp_path / "raw", tmp_path / "b1")
    bad_suite(tmp_path / "raw" / "bad")
    both = good_rows(tmp_path / "raw", tmp_path / "b1")
    assert len(alone) == 3
    pd.testing.assert_frame_equal(alone, both)


def assert_build_consistent(build):
    """No temporary file left, every Parquet readable."""
    assert not list(build.rglob("*.tmp"))
    for p in build.rglob("*.parquet"):
        pq.read_table(p)


signals = st.sampled_from(["good", "garbage", "empty", "nan", "short", "missing", "csv"])
rows = st.fixed_dictionaries({
    "signal": signals,
    "run_id": st.sampled_from(["a", "b", "c", "a/b", " ", ""]),
    "pressure_bar": st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.just("x")),
    "excitation_frequency_Hz": st.sampled_from([4.0, 0.0, 50.0, float("nan")]),
    "tyre_id": st.sampled_from(["T1", "T2", "??", ""]),
    "sample_rate_Hz": st.sampled_from([None, 256.0, 100.0, -1.0]),
})


def _content(kind):
    if kind == "good":
        return spring_damper_recording(duration_s=12.0)
    if kind == "garbage":
        return b"PAR1garbagePAR1"
    if kind == "empty":
        return b""
    if kind == "nan":
        return with_nan(spring_damper_recording(duration_s=12.0), np.nan)
    if kind == "short":
        return spring_damper_recording(duration_s=1.0)
    return None


@settings(max_examples=20, deadline=None, phases=[Phase.explicit, Phase.reuse, Phase.generate],
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(st.lists(rows, min_size=0, max_size=5))
def test_random_manifests_never_crash_or_leave_partial_files(tmp_path_factory, manifest):
    raw = tmp_path_factory.mktemp("raw")
    runs = []
    for i, r in enumerate(manifest):
        suffix = ".csv" if r["signal"] == "csv" else ".parquet"
        row = manifest_row(r["run_id"], f"r{i}{suffix}", tyre_id=r["tyre_id"], pressure_bar=r["pressure_bar"],
                           excitation_frequency_Hz=r["excitation_frequency_Hz"])
        if r["sample_rate_Hz"] is not None:
            row["sample_rate_Hz"] = r["sample_rate_Hz"]
        content = spring_damper_recording(duration_s=12.0) if r["signal"] == "csv" else _content(r["signal"])
        runs.append((row, content))
    write_campaign(raw, runs)
    ctx = Context(raw=raw, build=tmp_path_factory.mktemp("build"), jobs=1)
    run_stage("ingest", ctx)
    accounted = set(ctx.read_table("manifest").get("file", [])) | {
        Path(f).name for f in ctx.read_table("quarantine")["file"]}
    assert {f"r{i}{'.csv' if r['signal'] == 'csv' else '.parquet'}" for i, r in enumerate(manifest)} <= accounted
    assert_build_consistent(ctx.build)
    run_stage("analyse", ctx)
    assert_build_consistent(ctx.build)
