"""analyze-run band checks and OS errors as one line (issue 11, defects 4, 8, 10, 11)."""

import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from tests.holds import HANG_GUARD_S, Holds
from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
from tyrelab.cli import main
from tyrelab.warehouse import query

pytestmark = pytest.mark.long  # collected first: see tests/conftest.py

GOOD = spring_damper_recording(duration_s=20.0)
#: ``tyrelab`` with ``run`` restricted to the stages these tests need (the others take minutes).
PY = [sys.executable, "-c", "import sys, tyrelab.stages as s; s.ORDER[:] = ['ingest', 'analyse', 'calibrate', 'warehouse']\n"
      "from tyrelab.cli import main; sys.exit(main(sys.argv[1:]))"]
#: Lines that start the worker server and wait for its imports before ``main``: then the stages' pools
#: (and the work started ahead) start at once, whatever the machine's speed, instead of only when the
#: server is ready before this process has done the work alone.
READY_SERVER = ("from tyrelab import executor; import time; executor.start_worker_server()\n"
                "while executor.worker_server_state() == 'starting': time.sleep(0.01)\n")
#: :data:`PY` with the worker server ready first.
PY_READY = [PY[0], PY[1], PY[2].replace("from tyrelab.cli", READY_SERVER + "from tyrelab.cli")]


# -- 10. analyze-run ---------------------------------------------------------------------------------

@pytest.mark.parametrize("f0", [0.5, 12.0])
def test_analyze_run_refuses_an_excitation_outside_the_band(tmp_path, capsys, f0):
    path = tmp_path / "run.csv"
    spring_damper_recording(frequency_Hz=f0, duration_s=40.0, accel_noise_m_s2=0.02, force_noise_N=20).to_csv(path, index=False)
    assert main(["analyze-run", str(path), "--axle-mass", "600"]) == 3
    out = json.loads(capsys.readouterr().out)
    assert out["qc_ok"] is False and out["stiffness_kN_per_m"] is None and out["damping_kN_s_per_m"] is None
    assert out["welch"]["stiffness_N_per_m"] is None
    assert any("outside the analysis band 1-8 Hz" in r for r in out["qc_reasons"])
    assert out["excitation_frequency_Hz"] == pytest.approx(f0, abs=0.05)


def test_analyze_run_in_band_is_unchanged(tmp_path, capsys):
    path = tmp_path / "run.csv"
    GOOD.to_csv(path, index=False)
    assert main(["analyze-run", str(path), "--axle-mass", "600"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["qc_ok"] and out["stiffness_kN_per_m"] == pytest.approx(250, rel=0.01)


@pytest.mark.parametrize("value", ["inf", "nan", "-inf", "0", "-600"])
def test_numbers_must_be_finite_and_positive(tmp_path, capsys, value):
    path = tmp_path / "run.csv"
    GOOD.to_csv(path, index=False)
    with pytest.raises(SystemExit) as info:
        main(["analyze-run", str(path), "--axle-mass", value])
    assert info.value.code == 2 and "--axle-mass" in capsys.readouterr().err


@pytest.mark.parametrize("make, words", [
    (lambda p: p.mkdir(), "is a folder"), (lambda p: os.mkfifo(p), "named pipe (FIFO)"), (lambda p: None, "file not found")])
def test_analyze_run_names_what_the_path_is(tmp_path, capsys, make, words):
    path = tmp_path / "run.csv"
    make(path)
    assert main(["analyze-run", str(path), "--axle-mass", "600"]) == 2
    assert words in capsys.readouterr().err


# -- 8. OS errors: one line, the right exit code ----------------------------------------------------

def can_drop_dac() -> bool:
    return os.geteuid() != 0 or shutil.which("setpriv") is not None


def unprivileged(cmd):
    """``cmd`` without the capabilities that let root read and write any file."""
    if os.geteuid() != 0:
        return cmd
    if not shutil.which("setpriv"):
        pytest.skip("running as root without setpriv: cannot drop CAP_DAC_OVERRIDE")
    return ["setpriv", "--bounding-set", "-dac_override,-dac_read_search", *cmd]


def run_cli(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=300, **kw)


def test_a_run_file_without_read_permission_is_quarantined(tmp_path):
    raw = write_campaign(tmp_path / "raw" / "c", [(manifest_row("ok", "ok.parquet"), GOOD),
                                                  (manifest_row("locked", "locked.parquet"), GOOD)])
    (raw / "locked.parquet").chmod(0)
    other = write_campaign(tmp_path / "raw" / "d", [(manifest_row("d1", "d1.parquet"), GOOD)])
    (other / "manifest.csv").chmod(0)  # an unreadable manifest: that campaign is rejected, the other goes through
    out = run_cli(unprivileged([*PY, "run", "--raw", str(raw.parent), "--build", str(tmp_path / "b"), "--jobs", "1"]))
    assert out.returncode == 3, out.stderr
    assert "Traceback" not in out.stderr
    assert any(str(other / "manifest.csv") in line and "Permission denied" in line for line in out.stderr.splitlines())
    db = tmp_path / "b" / "warehouse.duckdb"
    assert query(db, "SELECT run_id FROM results")["run_id"].tolist() == ["ok"]
    reason = query(db, "SELECT reason FROM quarantine WHERE run_id = 'locked'")["reason"].iloc[0]
    assert "Permission denied" in reason


def test_a_build_folder_without_write_permission_is_one_line(tmp_path):
    raw = write_campaign(tmp_path / "raw", [(manifest_row("ok", "ok.parquet"), GOOD)])
    build = tmp_path / "b"
    build.mkdir()
    build.chmod(0o555)
    out = run_cli(unprivileged([*PY, "run", "--raw", str(raw), "--build", str(build), "--jobs", "1"]))
    assert out.returncode == 2 and "Traceback" not in out.stderr
    assert out.stderr.strip().splitlines()[-1].startswith("tyrelab run: ") and "Permission denied" in out.stderr


def limited(limit_bytes):
    def preexec():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))
    return preexec


def test_a_file_size_limit_is_one_line_and_the_next_run_repairs(tmp_path):
    raw = write_campaign(tmp_path / "raw", [(manifest_row(f"r{i}", f"r{i}.parquet"), GOOD) for i in range(3)])
    build = tmp_path / "b"
    args = ["--raw", str(raw), "--build", str(build), "--jobs", "1"]
    for stage in ("ingest", "analyse", "calibrate"):  # calibrate writes results
        assert run_cli([*PY, stage, *args]).returncode == 0
    # the warehouse write fails: exit 2 with one line, no empty warehouse left as if it were good
    out = run_cli([*PY, "warehouse", *args], preexec_fn=limited(64 * 1024))
    assert out.returncode == 2 and "Traceback" not in out.stderr, out.stderr
    assert "File too large" in out.stderr.strip().splitlines()[-1]
    out = run_cli([*PY, "warehouse", *args])
    assert out.returncode == 0, out.stderr
    assert "recomputing" in out.stderr
    assert len(query(build / "warehouse.duckdb", "SELECT * FROM results")) == 3
    # a Parquet write that fails half-way (ingest) is one line too
    out = run_cli([*PY, "ingest", "--force", *args], preexec_fn=limited(2 * 1024))
    assert out.returncode == 2 and "Traceback" not in out.stderr, out.stderr
    assert out.stderr.strip().splitlines()[-1].startswith("tyrelab ingest: ")
    out = run_cli([*PY, "run", *args])  # nothing was half-written: the build is as it was
    assert out.returncode == 0, out.stderr
    assert len(query(build / "warehouse.duckdb", "SELECT * FROM results")) == 3


# -- 11. Ctrl-C / SIGTERM leave no pymp-* folder ------------------------------------------------------

def test_sigterm_leaves_no_temporary_folders(tmp_path):
    raw = write_campaign(tmp_path / "raw", [(manifest_row(f"r{i}", f"r{i}.parquet", pressure_bar=1 + i / 10),
                                             spring_damper_recording(duration_s=60.0, seed=i)) for i in range(40)])
    tmp = Path(tempfile.mkdtemp(prefix="t11"))  # short: the forkserver's socket path must fit AF_UNIX's 108 bytes
    holds = Holds(tmp_path / "holds")
    holds.hold("worker")  # every pool worker holds once started: the signal lands while they exist
    proc = subprocess.Popen([*PY_READY, "run", "--raw", str(raw), "--build", str(tmp_path / "b"), "--jobs", "2"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={**holds.env, "TMPDIR": str(tmp)})
    assert holds.wait("worker", proc) != proc.pid
    assert list(tmp.glob("pymp-*"))
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=HANG_GUARD_S)
    assert proc.returncode == 130 and "Traceback" not in err, err
    assert not holds.passed("worker")  # the signal landed while the work was held
    left = list(tmp.iterdir())
    shutil.rmtree(tmp)
    assert not left


def test_ctrl_c_to_the_whole_process_group_prints_one_line(tmp_path):
    """A terminal's Ctrl-C signals the command *and* its pool workers: one line, exit 130.

    The workers ignore SIGINT and are ended by the parent, so none prints its own
    ``KeyboardInterrupt`` traceback, and the parent does not first run every queued run.
    """
    raw = write_campaign(tmp_path / "raw", [(manifest_row(f"r{i}", f"r{i}.parquet", pressure_bar=1 + i / 10),
                                             spring_damper_recording(duration_s=60.0, seed=i)) for i in range(40)])
    tmp = Path(tempfile.mkdtemp(prefix="t11"))
    holds = Holds(tmp_path / "holds")
    holds.hold("worker")
    proc = subprocess.Popen([*PY_READY, "run", "--raw", str(raw), "--build", str(tmp_path / "b"), "--jobs", "2"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={**holds.env, "TMPDIR": str(tmp)}, start_new_session=True)
    assert holds.wait("worker", proc) != proc.pid  # a worker is running (SIGINT ignored), held
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=HANG_GUARD_S)
    shutil.rmtree(tmp, ignore_errors=True)
    assert proc.returncode == 130, err
    assert not holds.passed("worker")
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err
    assert err.strip().splitlines()[-1].endswith("interrupted")


def test_ctrl_c_while_the_studies_run_ahead_prints_one_line(tmp_path):
    """Ctrl-C to the process group while the chapter 6-7 studies run ahead (first build, --jobs 2):
    one line, exit 130, their workers ended, no temporary folder left."""
    raw = write_campaign(tmp_path / "raw", [(manifest_row(f"r{i}", f"r{i}.parquet", pressure_bar=1 + i / 10),
                                             spring_damper_recording(duration_s=30.0, seed=i)) for i in range(24)])
    tmp = Path(tempfile.mkdtemp(prefix="t15"))
    holds = Holds(tmp_path / "holds")
    holds.hold("ahead")  # the study started ahead holds in its worker
    # the worker server ready before the run starts: the studies are started ahead after analyse
    # whatever the machine's speed (run_pipeline starts them only on a ready server)
    code = ("import sys, tyrelab.stages as s; s.ORDER[:] = ['ingest', 'analyse', 'calibrate', 'regress', 'simulate']\n"
            + READY_SERVER +
            "from tyrelab.cli import main; sys.exit(main(sys.argv[1:]))")
    proc = subprocess.Popen([sys.executable, "-c", code, "run", "--raw", str(raw), "--build", str(tmp_path / "b"),
                             "--jobs", "2"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={**holds.env, "TMPDIR": str(tmp)}, start_new_session=True)
    worker = holds.wait("ahead", proc)
    assert worker != proc.pid
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=HANG_GUARD_S)
    assert proc.returncode == 130, err
    assert not holds.passed("ahead")
    assert "started ahead" in err and "Traceback" not in err and "KeyboardInterrupt" not in err, err
    assert err.strip().splitlines()[-1].endswith("interrupted")
    with pytest.raises(ProcessLookupError):  # the command ended (and reaped) the study's worker before it exited
        os.kill(worker, 0)
    deadline = time.monotonic() + HANG_GUARD_S  # the worker server follows its parent (it reads its end of a pipe)
    while True:
        try:
            os.killpg(proc.pid, 0)
        except ProcessLookupError:
            break
        assert time.monotonic() < deadline, "processes of the interrupted run are still alive"
        time.sleep(0.05)
    left = list(tmp.iterdir())
    shutil.rmtree(tmp, ignore_errors=True)
    assert not left


def test_ctrl_c_while_an_extension_module_initialises_is_an_interrupt(tmp_path, monkeypatch, capsys):
    """Ctrl-C while a compiled module initialises (a stage importing scipy) surfaces as an ImportError
    caused by the KeyboardInterrupt ("initialization failed"): one line and exit 130, not a
    traceback. Any other error still propagates."""
    from tyrelab import cli

    def interrupted_import(args):
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as exc:
            raise ImportError("initialization failed") from exc

    monkeypatch.setattr(cli, "cmd_run", interrupted_import)
    assert main(["run", "--raw", str(tmp_path), "--build", str(tmp_path / "b")]) == 130
    assert capsys.readouterr().err.strip().splitlines()[-1] == "tyrelab run: interrupted"

    def broken(args):
        raise ImportError("a real import error")

    def broken_while_interrupted(args):
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt:
            raise OSError("cleaning up failed")  # an error of its own, raised while handling the interrupt

    for fn, error in ((broken, ImportError), (broken_while_interrupted, OSError)):
        monkeypatch.setattr(cli, "cmd_run", fn)
        with pytest.raises(error):
            main(["run", "--raw", str(tmp_path), "--build", str(tmp_path / "b")])


def test_published_tables_that_do_not_fit_together_are_one_line(tmp_path, capsys):
    """An edited <raw>/published whose Table XII has no stationary row for the heavy condition and
    whose Table XVI has none for load condition 4: one line naming the folder and both problems,
    exit 2, no table written. A table that does not match its schema: one line too (it was a
    traceback from the stage commands and `run`)."""
    from tests.synthetic import edit_csv
    from tyrelab import resources

    raw = tmp_path / "raw"
    shutil.copytree(resources.published_dir(), raw / "published")
    for stem, drop in (("table_xii", ("stationary", "heavy")), ("table_xvi", ("stationary", "4"))):
        def without(rows, drop=drop):
            rows[:] = [r for r in rows if (r["characteristics"], r["load_condition"]) != drop]

        edit_csv(raw / "published" / f"{stem}.csv", without)
    assert main(["simulate", "--raw", str(raw), "--build", str(tmp_path / "b"), "--jobs", "1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert "Traceback" not in "\n".join(err)
    assert err[-1] == (f"tyrelab simulate: {raw / 'published'}: tractor study (table_xv, table_xvi): table_xvi has "
                       "no stationary row for load condition 4; carriage study (table_xii): stationary has no row "
                       "for load condition heavy")
    assert not (tmp_path / "b" / "parquet").exists() or not list((tmp_path / "b" / "parquet").glob("*.parquet"))

    (raw / "published" / "table_xvi.csv").write_text("bogus,header\n1,2\n")
    assert main(["simulate", "--raw", str(raw), "--build", str(tmp_path / "b"), "--jobs", "1"]) == 2
    assert capsys.readouterr().err.strip().splitlines()[-1] == (
        f"tyrelab simulate: {raw / 'published' / 'table_xvi.csv'}: missing column 'characteristics'")
