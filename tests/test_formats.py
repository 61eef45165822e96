"""ASAM MDF4 and NI TDMS recordings ingested through channel_map.json into raw format v1."""

import json

import numpy as np
import pytest

from tyrelab.rawformat.mapped import FormatError, load_channel_map, read_mapped
from tyrelab.stages import Context, run_stage
from tests.synthetic import CHANNELS, manifest_row, spring_damper_recording, write_campaign

G = 9.80665
#: Lab channel names; accelerations recorded in g, forces in kN.
SOURCE = {"accel_left_m_s2": ("AccL_g", 1 / G), "accel_right_m_s2": ("AccR_g", 1 / G),
          **{f"load_beam_{i}_N": (f"LB{i}_kN", 1e-3) for i in range(1, 5)}}
CHANNEL_MAP = {"channels": {v1: {"source": src, "scale": 1 / k} for v1, (src, k) in SOURCE.items()},
               "tdms_group": "Rig"}


def write_mf4(df, path):
    asammdf = pytest.importorskip("asammdf", reason="asammdf not installed: pip install asammdf nptdms")
    mdf = asammdf.MDF(version="4.10")
    t = df["time_s"].to_numpy()
    mdf.append([asammdf.Signal(df[v1].to_numpy() * k, t, name=src) for v1, (src, k) in SOURCE.items()])
    mdf.save(str(path), overwrite=True)
    mdf.close()


def write_tdms(df, path):
    nptdms = pytest.importorskip("nptdms", reason="npTDMS not installed: pip install asammdf nptdms")
    dt = float(df["time_s"].iloc[1] - df["time_s"].iloc[0])
    props = {"wf_start_offset": 0.0, "wf_increment": dt}
    with nptdms.TdmsWriter(str(path)) as w:
        w.write_segment([nptdms.ChannelObject("Rig", src, df[v1].to_numpy() * k, properties=props)
                         for v1, (src, k) in SOURCE.items()])


WRITERS = {".mf4": write_mf4, ".tdms": write_tdms}


@pytest.mark.parametrize("suffix", sorted(WRITERS))
def test_read_mapped_recovers_v1_channels(tmp_path, suffix):
    df = spring_damper_recording(duration_s=12.0)
    path = tmp_path / f"run{suffix}"
    WRITERS[suffix](df, path)
    (tmp_path / "channel_map.json").write_text(json.dumps(CHANNEL_MAP))
    got = read_mapped(path, CHANNELS, ["force_plate_N"], load_channel_map(tmp_path / "channel_map.json"))
    assert list(got.columns) == ["time_s", *CHANNELS]
    np.testing.assert_allclose(got["time_s"], df["time_s"], atol=1e-9)
    for c in CHANNELS:
        np.testing.assert_allclose(got[c], df[c], rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("suffix", sorted(WRITERS))
def test_ingest_and_analyse_other_formats_like_parquet(tmp_path, suffix):
    df = spring_damper_recording(300e3, 2500.0, duration_s=12.0)
    raw = write_campaign(tmp_path / "raw", [(manifest_row("p", "p.parquet"), df), (manifest_row("x", f"x{suffix}"), None)])
    WRITERS[suffix](df, raw / f"x{suffix}")
    (raw / "channel_map.json").write_text(json.dumps(CHANNEL_MAP))
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1)
    assert run_stage("ingest", ctx).n_ok == 2
    run_stage("analyse", ctx)
    run_stage("calibrate", ctx)  # writes results
    res = ctx.read_table("results").set_index("run_id")
    assert res.loc["x", "stiffness_kN_per_m"] == pytest.approx(res.loc["p", "stiffness_kN_per_m"], rel=1e-6)
    assert res.loc["x", "stiffness_kN_per_m"] == pytest.approx(300, rel=0.01)


def test_missing_source_channel_is_one_clear_line(tmp_path):
    df = spring_damper_recording(duration_s=12.0)
    raw = write_campaign(tmp_path / "raw", [(manifest_row("x", "x.mf4"), None)])
    write_mf4(df, raw / "x.mf4")
    bad = {"channels": {**CHANNEL_MAP["channels"], "load_beam_4_N": {"source": "LB9_kN"}}}
    (raw / "channel_map.json").write_text(json.dumps(bad))
    ctx = Context(raw=raw, build=tmp_path / "build", jobs=1)
    assert run_stage("ingest", ctx).n_quarantined == 1
    reason = ctx.read_table("quarantine")["reason"].iloc[0]
    assert "LB9_kN" in reason and "\n" not in reason


def test_bad_channel_map_and_garbage_recording(tmp_path):
    (tmp_path / "channel_map.json").write_text('{"channels": {"accel_left_m_s2": {"scale": 2}}}')
    with pytest.raises(FormatError, match="needs a 'source'"):
        load_channel_map(tmp_path / "channel_map.json")
    pytest.importorskip("nptdms", reason="npTDMS not installed: pip install asammdf nptdms")
    (tmp_path / "g.tdms").write_bytes(b"TDSm" + bytes(200))
    with pytest.raises(FormatError, match="corrupt TDMS"):
        read_mapped(tmp_path / "g.tdms", CHANNELS, [])
