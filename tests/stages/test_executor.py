"""Executors: local pool and Dask give the same results, in order, as in-process."""

import os
import shutil
import time
from types import SimpleNamespace

import pytest

from tests.holds import HANG_GUARD_S
from tyrelab.executor import map_alongside, map_batches, map_in_background, worker_server_state
from tyrelab.stages import Context, run_pipeline
from tests.synthetic import manifest_row, spring_damper_recording, write_campaign

pytestmark = pytest.mark.long  # collected first: see tests/conftest.py

STAGES = ["ingest", "analyse", "calibrate", "warehouse"]
TABLES = ["manifest.parquet", "stages/analysed.parquet", "quarantine.parquet", "tyres.parquet"]


def square(x):
    return x * x


def square_and_pid(x):
    return x * x, os.getpid()


def write_marker(path):
    with open(path, "w") as fh:
        fh.write(str(os.getpid()))
    return path


@pytest.fixture(scope="module")
def cluster():
    distributed = pytest.importorskip("dask.distributed", reason="dask[distributed] not installed")
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) as c:
        yield c


def test_local_map_preserves_order():
    ctx = SimpleNamespace(executor="local", jobs=2, scheduler=None)
    assert map_batches(square, range(7), ctx) == [x * x for x in range(7)]
    assert map_batches(square, [], ctx) == []


def test_map_alongside_shares_the_work_and_keeps_the_order():
    """This process works until the worker server is ready; the results are in order wherever they ran."""
    assert map_alongside(square_and_pid, range(3), jobs=2)[0][0] == 0  # starts the server, need not wait for it
    deadline = time.monotonic() + 300
    while worker_server_state() != "ready" and time.monotonic() < deadline:
        time.sleep(0.05)
    out = map_alongside(square_and_pid, range(12), jobs=2)
    assert [r for r, _ in out] == [x * x for x in range(12)]
    pids = {p for _, p in out}
    assert os.getpid() in pids  # this process drew some
    assert len(pids) == 2  # and the one worker the others
    assert map_alongside(square, [3], jobs=2) == [9] and map_alongside(square, [], jobs=2) == []
    with pytest.raises(ValueError, match="jobs"):
        map_alongside(square, [1], jobs=0)


def test_unknown_executor_is_refused():
    with pytest.raises(ValueError, match="unknown executor"):
        map_batches(square, [1, 2], SimpleNamespace(executor="spark", jobs=1, scheduler=None))


def test_dask_map_runs_impure_tasks(cluster, tmp_path):
    ctx = SimpleNamespace(executor="dask", jobs=2, scheduler=cluster.scheduler_address)
    assert map_batches(square, range(5), ctx) == [0, 1, 4, 9, 16]
    paths = [str(tmp_path / f"m{i}") for i in range(4)]
    assert map_batches(write_marker, paths, ctx) == paths
    assert all(os.path.exists(p) for p in paths)


def test_same_bytes_whichever_executor(cluster, tmp_path):
    runs = []
    for i in range(9):  # three lengths -> three analyse batches; nine ingest tasks
        runs.append((manifest_row(f"r{i}", f"r{i}.parquet", pressure_bar=0.9 + 0.1 * i),
                     spring_damper_recording(duration_s=12.0 + 2 * (i % 3), force_noise_N=50, seed=i)))
    runs.append((manifest_row("bad", "bad.parquet"), b"garbage"))
    write_campaign(tmp_path / "raw" / "c", runs)
    outputs = {}
    for name, over in {"local1": dict(jobs=1), "local2": dict(jobs=2),
                       "dask": dict(executor="dask", scheduler=cluster.scheduler_address)}.items():
        ctx = Context(raw=tmp_path / "raw", build=tmp_path / "build", force=True, **over)
        run_pipeline(ctx, STAGES)
        outputs[name] = {t: (ctx.parquet / t).read_bytes() for t in TABLES}
        outputs[name]["runs"] = sorted(
            (str(p.relative_to(ctx.parquet)), p.read_bytes()) for p in (ctx.parquet / "runs").rglob("*.parquet"))
        shutil.rmtree(ctx.build / "state")
    assert len(outputs["local1"]["runs"]) == 9
    assert outputs["local1"] == outputs["local2"] == outputs["dask"]


@pytest.mark.parametrize("jobs", [1, 2])
def test_on_done_reports_every_batch_once(jobs):
    ctx = SimpleNamespace(executor="local", jobs=jobs, scheduler=None)
    seen = []
    assert map_batches(square, [1, 2, 3, 4], ctx, on_done=seen.append) == [1, 4, 9, 16]
    assert sorted(seen) == [0, 1, 2, 3]


def test_on_done_with_dask(cluster):
    ctx = SimpleNamespace(executor="dask", jobs=2, scheduler=cluster.scheduler_address)
    seen = []
    assert map_batches(square, [3, 1, 2], ctx, on_done=seen.append) == [9, 1, 4]
    assert sorted(seen) == [0, 1, 2]


def test_single_threaded_blas_keeps_what_the_user_set(monkeypatch):
    from tyrelab.executor import BLAS_THREAD_VARIABLES, single_threaded_blas

    for var in BLAS_THREAD_VARIABLES:
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("OMP_NUM_THREADS", "3")
    single_threaded_blas()
    assert os.environ["OMP_NUM_THREADS"] == "3"
    assert os.environ["OPENBLAS_NUM_THREADS"] == os.environ["MKL_NUM_THREADS"] == "1"


def test_the_tyrelab_command_defaults_blas_to_one_thread():
    """The command sets the default before parsing its arguments (before numpy is imported);
    worker processes inherit it with the environment."""
    import subprocess
    import sys

    code = ("import os, sys\nfor v in ('OMP_NUM_THREADS', 'OPENBLAS_NUM_THREADS', 'MKL_NUM_THREADS'): os.environ.pop(v, None)\n"
            "import tyrelab.cli as c\n"
            "try:\n    c.main(['--help'])\nexcept SystemExit:\n    pass\n"
            "import numpy\nprint(os.environ['OPENBLAS_NUM_THREADS'])\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.strip().splitlines()[-1] == "1", out.stderr


def _preloaded(_):
    import sys

    return all(m in sys.modules for m in ("tyrelab.stages.analyse", "tyrelab.report.site", "tyrelab.report.figures"))


def _wait_for_server():
    map_alongside(square, range(2), jobs=2)  # starts the server (idempotent)
    deadline = time.monotonic() + 300
    while worker_server_state() != "ready" and time.monotonic() < deadline:
        time.sleep(0.05)
    assert worker_server_state() == "ready"


def _square_once_released(x):
    """x[0] squared once the file x[1] exists (None after HANG_GUARD_S without it: a hang)."""
    deadline = time.monotonic() + HANG_GUARD_S
    while not os.path.exists(x[1]):
        if time.monotonic() > deadline:
            return None, os.getpid()
        time.sleep(0.01)
    return x[0] * x[0], os.getpid()


def test_map_in_background_returns_at_once_and_keeps_the_order(tmp_path):
    """With the server ready the batches run in workers while the caller goes on; results in order."""
    assert map_in_background(square, [1, 2], jobs=1) is None  # one process: the caller maps them
    assert map_in_background(square, [], jobs=2) is None
    with pytest.raises(ValueError, match="jobs"):
        map_in_background(square, [1], jobs=0)
    _wait_for_server()
    release = tmp_path / "release"
    bg = map_in_background(_square_once_released, [(i, str(release)) for i in range(4)], jobs=2)
    assert bg is not None  # returned while every batch still waits for this process
    release.touch()
    out = bg.results()
    assert [r for r, _ in out] == [0, 1, 4, 9]
    assert os.getpid() not in {p for _, p in out} and len({p for _, p in out}) == 2


def _announce_and_wait(x):
    """Say it runs (a file named after this worker's pid in folder x[0]), then wait for the file x[1]."""
    open(os.path.join(x[0], f"running-{os.getpid()}"), "w").close()
    while not os.path.exists(x[1]):
        time.sleep(0.01)
    return os.getpid()


def test_map_in_background_abandon_ends_the_workers(tmp_path):
    _wait_for_server()
    never = tmp_path / "never-released"
    bg = map_in_background(_announce_and_wait, [(str(tmp_path), str(never)) for _ in range(2)], jobs=2)
    procs = list(bg._pool._processes.values())
    manager, wakeup = bg._pool._executor_manager_thread, bg._pool._executor_manager_thread_wakeup
    deadline = time.monotonic() + HANG_GUARD_S  # until both workers say they run their batch
    while len(list(tmp_path.glob("running-*"))) < 2:
        assert time.monotonic() < deadline and all(p.is_alive() for p in procs)
        time.sleep(0.01)
    assert {p.pid for p in procs} == {int(f.name.split("-")[1]) for f in tmp_path.glob("running-*")}
    bg.abandon()  # terminates and joins them: none is left, and no batch finished
    assert not any(p.is_alive() for p in procs)
    # and the pool's manager thread has ended, its wake-up pipe closed: Python's exit hook, which writes
    # to that pipe, cannot meet it half-closed (an "Exception ignored ... Bad file descriptor" at exit)
    assert not manager.is_alive() and wakeup._closed


def test_command_gc_in_a_command_process():
    """The tyrelab command's collector thresholds, and gc.freeze run at the process's end (before
    the handlers registered earlier: atexit runs them last in, first out)."""
    import subprocess
    import sys

    code = ("import gc, atexit; from tyrelab.executor import command_gc, GC_THRESHOLDS\n"
            "atexit.register(lambda: print('frozen at exit:', gc.get_freeze_count() > 0))\n"
            "print('frozen before:', gc.get_freeze_count() > 0)\n"
            "command_gc(); command_gc(); assert gc.get_threshold() == GC_THRESHOLDS, gc.get_threshold()")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split("\n")[:2] == ["frozen before: False", "frozen at exit: True"]


def test_report_site_does_not_import_matplotlib():
    """The pipeline process shapes tables and writes pages; only figure workers need matplotlib."""
    import subprocess
    import sys

    code = "import sys, tyrelab.stages.report; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_workers_start_with_the_stage_modules_imported():
    """Workers are forked from a server that imported the stages' worker modules once."""
    from multiprocessing import forkserver

    from tyrelab import executor
    from tyrelab.stages import Context

    server = forkserver._forkserver
    if server._forkserver_pid is not None and "tyrelab._worker_ready" not in (server._preload_modules or []):
        pytest.skip("a forkserver without tyrelab's preload was started earlier in this process")
    assert executor.map_batches(_preloaded, [1, 2], Context(jobs=2)) == [True, True]
