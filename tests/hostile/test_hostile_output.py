"""stdout that fails or goes away, `tyrelab sql` results bounded, missing extras (issue 37, I/O side)."""

import os
import resource
import subprocess
import sys

import duckdb
import numpy as np
import pandas as pd
import pytest

from tyrelab.cli import main

TYRELAB = [sys.executable, "-m", "tyrelab.cli"]


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    """A build folder whose warehouse holds one small table (the queries below make their rows)."""
    b = tmp_path_factory.mktemp("out_build")
    con = duckdb.connect(str(b / "warehouse.duckdb"))
    con.execute("CREATE TABLE t AS SELECT 1 AS a")
    con.close()
    return b


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    path = tmp_path_factory.mktemp("out_rec") / "r.csv"
    t = np.arange(2000) / 100.0
    pd.DataFrame({"time_s": t, "seat_z_m_s2": np.sin(2 * np.pi * 4 * t)}).to_csv(path, index=False)
    return path


def test_a_reader_that_leaves_after_a_partial_write_gives_141(build):
    proc = subprocess.Popen([*TYRELAB, "sql", "--build", str(build), "SELECT * FROM range(300000)"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    first = proc.stdout.read(100)  # as `head -c 100`: some of the output, then the reader goes away
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 141 and first.startswith(b" range")
    assert err == ""


@pytest.mark.parametrize("verb", ["exposure", "ride", "sql", "estimate-stiffness", "completion"])
def test_stdout_on_a_full_device_is_one_line_exit_2(build, recording, verb):
    from tyrelab.resources import scenarios_dir

    args = {"exposure": [str(recording)],
            "ride": [str(scenarios_dir() / "mf698t.toml"), "--speeds", "10"],
            "sql": ["--build", str(build), "SELECT * FROM range(10)"],
            "estimate-stiffness": ["--size", "13.6R38", "--pressure", "1.2"],
            "completion": ["bash"]}[verb]
    with open("/dev/full", "w") as full:
        out = subprocess.run([*TYRELAB, verb, *args], stdout=full, stderr=subprocess.PIPE, text=True, timeout=300)
    assert out.returncode == 2, out.stderr
    assert out.stderr.count("\n") == 1 and "Traceback" not in out.stderr
    assert out.stderr == f"tyrelab {verb}: cannot write the output (No space left on device)\n"


def test_sql_streams_its_result_batch_by_batch(build, capsys, monkeypatch):
    """Bounded by design: the first rows are printed before most of the result is read."""
    import tyrelab.warehouse as wh

    monkeypatch.setattr(wh, "BATCH_ROWS", 1000, raising=False)
    read, seen_at_first_write = [], []
    real = getattr(wh, "_pandas", None)

    def counting(batch):
        read.append(len(batch))
        return real(batch)

    monkeypatch.setattr(wh, "_pandas", counting, raising=False)
    import tyrelab.cli as cli

    real_out = getattr(cli, "_out", None)

    def out(text):
        if not seen_at_first_write:
            seen_at_first_write.append(len(read))
        real_out(text)

    monkeypatch.setattr(cli, "_out", out, raising=False)
    assert main(["sql", "--build", str(build), "--format", "csv", "SELECT * FROM range(20000) t(i)"]) == 0
    assert capsys.readouterr().out.count("\n") == 20001
    assert sum(read) == 20000 and seen_at_first_write and seen_at_first_write[0] <= 3


def test_a_table_larger_than_its_share_of_the_memory_limit_is_refused_by_name(build, capsys):
    rc = main(["sql", "--build", str(build), "--memory-limit", "2MB", "SELECT * FROM range(200000)"])
    out, err = capsys.readouterr()
    assert rc == 2 and err.count("\n") == 1 and "--memory-limit" in err and "--format csv" in err
    rc = main(["sql", "--build", str(build), "--memory-limit", "2MB", "--format", "csv", "SELECT * FROM range(200000)"])
    assert rc == 0 and capsys.readouterr().out.count("\n") == 200001  # csv streams: not bounded by it


def test_a_huge_value_is_refused_by_the_memory_limit(build):
    """repeat('x', 1e9) took 7 GB: now the allocation is refused (one line) before it is made. A 3 GB
    ceiling keeps the machine safe from the code before the fix; the child reports its peak RSS."""
    def ceiling():
        resource.setrlimit(resource.RLIMIT_DATA, (3 * 2**30, resource.RLIM_INFINITY))

    code = ("import resource, sys\nfrom tyrelab.cli import main\nrc = main(sys.argv[1:])\n"
            "print('peak', resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr)\nsys.exit(rc)")
    out = subprocess.run([sys.executable, "-c", code, "sql", "--build", str(build), "--memory-limit", "64MB",
                          "SELECT repeat('x', 1000000000) AS s"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                         text=True, timeout=300, preexec_fn=ceiling)
    *lines, peak = out.stderr.splitlines()
    assert out.returncode == 2, out.stderr[-500:]
    assert len(lines) == 1 and "--memory-limit" in lines[0] and "Traceback" not in out.stderr
    assert int(peak.split()[1]) < 600 * 1024, peak  # KiB: the 1 GB string was never made


def test_sql_help_and_readme_name_the_spill_folder_alike(capsys):
    from pathlib import Path

    with pytest.raises(SystemExit):
        main(["sql", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text(encoding="utf-8")
    assert ".sql-spill-<pid>-<n>" in text and ".sql-spill-<pid>-<n>" in readme


def test_executor_dask_without_dask_is_one_line(monkeypatch, capsys):
    from tyrelab.resources import scenarios_dir

    monkeypatch.setitem(sys.modules, "dask.distributed", None)  # as if the extra were not installed
    rc = main(["ride", str(scenarios_dir() / "mf698t.toml"), "--speeds", "10", "--set", "tractor.mass_kg=5000,5200",
               "--executor", "dask"])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and "pip install 'tyrelab[dask]'" in err


# -- ride profiles: the header bounded, an unreadable file named ---------------------------------------

def _profile_scenario(folder):
    from tyrelab.resources import scenarios_dir

    text = (scenarios_dir() / "modern_tractor.toml").read_text(encoding="utf-8")
    old = 'kind = "iso8608"\nclass = "C"\nlength_m = 400\nseed = 1\n'
    assert old in text
    (folder / "s.toml").write_text(text.replace(old, 'kind = "profile"\nprofile = "p.csv"\n'), encoding="utf-8")
    x = np.arange(0, 200, 0.05)
    pd.DataFrame({"distance_m": x, "height_m": 0.01 * np.sin(x)}).to_csv(folder / "p.csv", index=False)
    return folder / "s.toml"


def test_a_profile_without_line_ends_is_refused_before_it_is_read(tmp_path, capsys, monkeypatch):
    import tyrelab.scenario_io as sio

    scenario = _profile_scenario(tmp_path)
    (tmp_path / "p.csv").write_bytes(b"distance_m," + b"x" * (70 * 1024))

    def no_read(*a, **k):  # bounded by design: nothing parses the file before its header is checked
        raise AssertionError("read_csv called on a file without a header line")

    monkeypatch.setattr(sio.pd, "read_csv", no_read)
    assert main(["ride", str(scenario), "--speeds", "8"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and len(err) < 400 and "header line is longer than 64 KiB" in err


def test_an_unreadable_profile_cannot_be_read_exit_2(tmp_path):
    from tests.hostile.test_hostile_cli import unprivileged

    scenario = _profile_scenario(tmp_path)
    (tmp_path / "p.csv").chmod(0)
    out = subprocess.run(unprivileged([*TYRELAB, "ride", str(scenario), "--speeds", "8"]), capture_output=True,
                         text=True, timeout=300)
    assert out.returncode == 2 and "Traceback" not in out.stderr, out.stderr[-800:]
    assert out.stderr.count("\n") == 1 and "p.csv: cannot read (Permission denied)" in out.stderr


@pytest.mark.parametrize("argv", [["analyze-run", "{f}", "--axle-mass", "600"], ["ride", "{f}"]])
def test_a_file_name_with_control_characters_stays_one_line(tmp_path, capsys, argv):
    name = str(tmp_path / "a\nday: fake\x1b[2J.csv")
    rc = main([a.replace("{f}", name) for a in argv])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and "\x1b" not in err and "a\\nday: fake\\x1b[2J" in err
