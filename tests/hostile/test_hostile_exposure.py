"""`tyrelab exposure` and vehicle recordings against hostile and mistaken input (issue 37, I/O side)."""

import json
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

from tyrelab.cli import main
from tyrelab.rawformat import rides
from tyrelab.rawformat.rides import open_recording

#: As the module states them (read here so that the tests fail, not error, on code without them).
MAX_ABS_SAMPLE = getattr(rides, "MAX_ABS_SAMPLE", 1000.0)
MAX_HEADER_BYTES = getattr(rides, "MAX_HEADER_BYTES", 64 * 1024)


def recording(path, duration_s=20.0, fs=100.0, **channels):
    t = np.arange(int(round(duration_s * fs))) / fs
    cols = {"time_s": t, "seat_z_m_s2": np.sin(2 * np.pi * 4 * t)}
    for name, f in channels.items():
        cols[name] = f(t)
    df = pd.DataFrame(cols)
    df.to_csv(path, index=False)
    return df


def exposure(capsys, *args):
    rc = main(["exposure", *map(str, args)])
    out = capsys.readouterr()
    return rc, out.out, out.err


# -- a minimum record for a verdict ------------------------------------------------------------------

def test_a_two_row_recording_gets_values_and_no_verdict(tmp_path, capsys):
    path = tmp_path / "tiny.csv"
    pd.DataFrame({"time_s": [0.0, 0.004], "seat_z_m_s2": [0.1, 0.2]}).to_csv(path, index=False)
    rc, out, err = exposure(capsys, path, "--format", "table")
    assert rc == 3 and max(map(len, out.splitlines())) <= 100  # long lines wrap (issue 47)
    out = " ".join(out.split())
    assert "below action value" not in out and "no verdict" in out and "shorter than 10 s" in out
    assert "recorded at 250 Hz" in out and "0.008 s recorded" in out  # duration and sample rate named
    assert "warning: no verdict" in err


def test_a_five_second_recording_gets_no_verdict_a_twenty_second_one_does(tmp_path, capsys):
    recording(tmp_path / "five.csv", duration_s=5.0)
    rc, out, err = exposure(capsys, tmp_path / "five.csv")
    doc = json.loads(out)
    assert rc == 3 and doc["verdict"].startswith("no verdict") and doc["hours_to_eav"] is None
    assert doc["a8_m_s2"] > 0 and doc["duration_s"] == pytest.approx(5.0) and doc["sample_rate_Hz"] == 100.0
    recording(tmp_path / "long.csv", duration_s=20.0)
    rc, out, err = exposure(capsys, tmp_path / "long.csv")
    assert rc == 0 and json.loads(out)["verdict"] == "above action value"


def test_the_table_gives_the_vdv_verdict_beside_the_a8_one(tmp_path, capsys):
    """Issue 47: the JSON's ``vdv_verdict`` was missing from ``--format table``."""
    recording(tmp_path / "r.csv", seat_z_m_s2=lambda t: 6 * np.sin(2 * np.pi * 4 * t))  # VDV above 21 over 8 h
    rc, out, err = exposure(capsys, tmp_path / "r.csv", "--format", "json")
    doc = json.loads(out)
    rc, out, err = exposure(capsys, tmp_path / "r.csv", "--format", "table")
    vdv = next(line for line in out.splitlines() if line.strip().startswith("VDV"))
    assert doc["vdv_verdict"] == "above limit value" and f"({doc['vdv_daily_axis']} axis), above limit value" in vdv
    assert "action value 9.1, limit value 21 m/s^1.75" in vdv


# -- spreadsheet CSV: ';' and decimal commas, as manifests ------------------------------------------

def test_a_spreadsheet_recording_reads_as_the_plain_one(tmp_path, capsys):
    df = recording(tmp_path / "plain.csv")
    df.to_csv(tmp_path / "sheet.csv", index=False, sep=";", decimal=",", encoding="utf-8-sig")
    df.to_csv(tmp_path / "tabs.csv", index=False, sep="\t")
    docs = []
    for name in ("plain", "sheet", "tabs"):
        rc, out, err = exposure(capsys, tmp_path / f"{name}.csv")
        assert rc == 0, err
        docs.append(json.loads(out))
    assert docs[1]["a8_m_s2"] == pytest.approx(docs[0]["a8_m_s2"], rel=1e-9)
    assert docs[2]["a8_m_s2"] == pytest.approx(docs[0]["a8_m_s2"], rel=1e-9)


# -- hours -------------------------------------------------------------------------------------------

@pytest.mark.parametrize("hours", ["30", "1e-320"])
def test_hours_out_of_a_day_are_refused_by_the_option_s_name(tmp_path, capsys, hours):
    recording(tmp_path / "r.csv")
    rc, out, err = exposure(capsys, tmp_path / "r.csv", "--hours", hours)
    assert rc == 2 and out == "" and err.count("\n") == 1
    assert err.startswith("tyrelab exposure: --hours ") and "task" not in err and "HOURS" not in err


def test_eighty_tasks_of_0_3_h_are_a_day(tmp_path, capsys):
    recording(tmp_path / "r.csv")
    tasks = [a for i in range(80) for a in ("--task", f"t{i}", tmp_path / "r.csv", "0.3")]
    rc, out, err = exposure(capsys, *tasks)
    assert rc == 0, err
    assert json.loads(out)["hours_per_day"] == pytest.approx(24.0)
    rc, out, err = exposure(capsys, *tasks, "--task", "more", tmp_path / "r.csv", "0.01")
    assert rc == 2 and "more than a day" in err


# -- implausible samples: one line, never a traceback, never a silent null --------------------------

@pytest.mark.parametrize("values", [(1e200,), (-1e200,), (1e30,), (1e308, -1e308)])
def test_samples_beyond_the_bound_are_refused_naming_channel_and_row(tmp_path, capsys, values):
    df = recording(tmp_path / "r.csv", seat_x_m_s2=lambda t: np.sin(t))
    for i, v in enumerate(values):
        df.loc[50 + i, "seat_z_m_s2"] = v
    df.to_csv(tmp_path / "r.csv", index=False)
    rc, out, err = exposure(capsys, tmp_path / "r.csv")
    assert rc == 3 and out == "" and err.count("\n") == 1
    assert "seat_z_m_s2" in err and "row 50" in err and f"±{MAX_ABS_SAMPLE:g}" in err


# -- the documented formats --------------------------------------------------------------------------

def test_mf4_and_tdms_recordings_work(tmp_path, capsys):
    asammdf = pytest.importorskip("asammdf")
    nptdms = pytest.importorskip("nptdms")
    t = np.arange(0, 20, 0.002)
    z = np.sin(2 * np.pi * 4 * t)
    mdf = asammdf.MDF(version="4.10")
    mdf.append([asammdf.Signal(z, t, name="seat_z_m_s2")])
    mdf.save(str(tmp_path / "valid.mf4"), overwrite=True)
    mdf.close()
    with nptdms.TdmsWriter(str(tmp_path / "valid.tdms")) as w:
        w.write_segment([nptdms.ChannelObject("g", "seat_z_m_s2", z,
                                              properties={"wf_start_offset": 0.0, "wf_increment": 0.002})])
    a8 = []
    for name in ("valid.mf4", "valid.tdms"):
        rc, out, err = exposure(capsys, tmp_path / name)
        assert rc == 0, err
        a8.append(json.loads(out)["a8_m_s2"])
    assert a8[0] == pytest.approx(a8[1], rel=1e-9) and a8[0] == pytest.approx(0.68, abs=0.01)


# -- unbounded header ----------------------------------------------------------------------------------

def test_a_csv_without_a_line_end_is_refused_before_it_is_read(tmp_path, capsys, monkeypatch):
    path = tmp_path / "flat.csv"
    path.write_bytes(b"time_s," + b"x" * (MAX_HEADER_BYTES + 10))
    import pandas

    def no_read(*a, **k):  # bounded by design: nothing parses the file before its header is checked
        raise AssertionError("read_csv called on a file without a header line")

    monkeypatch.setattr(pandas, "read_csv", no_read)
    rc, out, err = exposure(capsys, path)
    assert rc == 3 and err.count("\n") == 1 and len(err) < 400
    assert "header line is longer than 64 KiB" in err


# -- control characters --------------------------------------------------------------------------------

def test_control_characters_of_a_task_name_are_escaped_in_the_table(tmp_path, capsys):
    recording(tmp_path / "r.csv")
    rc, out, err = exposure(capsys, "--task", "bal\x1b[2J\nday: A(8) 0.1 m/s²", tmp_path / "r.csv", "4",
                            "--format", "table")
    assert rc == 0, err
    assert "\x1b" not in out and "\\x1b[2J\\nday: A(8)" in out
    assert sum(line.startswith("day:") for line in out.splitlines()) == 1


def test_a_file_name_with_a_newline_is_one_line(tmp_path, capsys):
    rc, out, err = exposure(capsys, tmp_path / "a\nb.csv")
    assert rc == 2 and err.count("\n") == 1 and "a\\nb.csv: file not found" in err


# -- OS errors -----------------------------------------------------------------------------------------

def test_an_unreadable_recording_cannot_be_read_exit_2(tmp_path):
    from tests.hostile.test_hostile_cli import unprivileged

    recording(tmp_path / "r.csv")
    (tmp_path / "r.csv").chmod(0)
    out = subprocess.run(unprivileged([sys.executable, "-m", "tyrelab.cli", "exposure", str(tmp_path / "r.csv")]),
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 2, out.stderr
    assert out.stderr.count("\n") == 1 and "cannot read (Permission denied)" in out.stderr


def test_open_recording_says_cannot_read_not_corrupt(tmp_path, monkeypatch):
    import builtins

    from tyrelab.rawformat import RunFileError

    recording(tmp_path / "r.csv")
    real = builtins.open

    def refusing(file, *a, **k):
        if str(file) == str(tmp_path / "r.csv"):
            raise PermissionError(13, "Permission denied", str(file))
        return real(file, *a, **k)

    monkeypatch.setattr(builtins, "open", refusing)
    with pytest.raises(RunFileError, match=r"^cannot read \(Permission denied\)$"):
        open_recording(tmp_path / "r.csv")
