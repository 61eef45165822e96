"""The regress stage alone on the demo campaigns: clean, nothing changed, one run added.

Usage::

    python bench/bench_regress.py [--scales small full] [--data DIR] [--repeats 3] [--label before]

For each scale the seeded demo campaign of :mod:`bench_pipeline` (generated once into
``--data``) is taken through ingest, analyse and calibrate (not timed). Then
:func:`tyrelab.stages.regress.run` is timed in this process, each scenario ``--repeats``
times on a fresh copy of the build (the stage's code fingerprints are computed first, as
:func:`tyrelab.stages.run_stage` does before it calls the stage):

``clean``        no per-tyre cache: every tyre fitted;
``unchanged``    the cache of a clean run, nothing changed (the across-tyre tables and the
                 writes: the floor of any run of the stage);
``add_one_run``  one T1 run added in a new campaign folder (:func:`bench_pipeline.add_one_run`)
                 and ingest/analyse/calibrate run again: one tyre refitted.

CPU seconds (``time.process_time``, min over the repeats) are the measure on a shared
machine; wall seconds (median) are printed too, with the load average at the start.
The import of the stage module (statsmodels, scipy.stats) is reported separately
(``import_cpu_s``). To compare with another version of the code run it with that
version's ``pipeline`` folder first on ``PYTHONPATH`` (as a package named ``tyrelab``).
Prints one JSON object.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_pipeline import add_one_run, campaign  # noqa: E402

UPSTREAM = ["ingest", "analyse", "calibrate"]


def _timed(raw: Path, build: Path, jobs: int, repeats: int, prepare) -> dict:
    """CPU (min) and wall (median) seconds of ``regress.run`` on ``repeats`` copies of ``build``."""
    from tyrelab.stages import Context, regress, state

    cpu, wall, message = [], [], ""
    for i in range(repeats):
        work = build.with_name(f"{build.name}-run{i}")
        shutil.rmtree(work, ignore_errors=True)
        shutil.copytree(build, work)
        prepare(work)
        ctx = Context(raw=raw, build=work, jobs=jobs)
        state.load_code_index(work)
        state.code_fingerprint("tyrelab.stages.regress")
        c, t = time.process_time(), time.perf_counter()
        message = regress.run(ctx).message
        cpu.append(time.process_time() - c)
        wall.append(time.perf_counter() - t)
        shutil.rmtree(work)
    return {"cpu_s": round(min(cpu), 3), "wall_s": round(statistics.median(wall), 3),
            "all_cpu_s": [round(x, 3) for x in cpu], "message": message}


def bench_scale(scale: str, data: Path, work: Path, jobs: int, repeats: int) -> dict:
    """Every scenario on one scale (module docstring)."""
    from tyrelab.stages import Context, run_stage

    src = campaign(data, scale)
    raw, build = work / scale / "raw", work / scale / "build"
    shutil.rmtree(work / scale, ignore_errors=True)
    shutil.copytree(src, raw / "campaign", copy_function=os.link)
    ctx = Context(raw=raw, build=build, jobs=jobs)
    for name in UPSTREAM:
        run_stage(name, ctx)
    out: dict = {}
    out["clean"] = _timed(raw, build, jobs, repeats, lambda b: shutil.rmtree(b / "cache" / "regress", ignore_errors=True))
    run_stage("regress", ctx)  # the per-tyre cache of the campaign as it is
    out["unchanged"] = _timed(raw, build, jobs, repeats, lambda b: None)
    add_one_run(raw, raw / "campaign")
    for name in UPSTREAM:
        run_stage(name, ctx)
    out["add_one_run"] = _timed(raw, build, jobs, repeats, lambda b: None)
    return out


def main(argv=None) -> dict:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scales", nargs="+", choices=["small", "full"], default=["small", "full"])
    p.add_argument("--data", type=Path, default=Path(tempfile.gettempdir()) / "tyrelab-bench-data",
                   help="where the generated campaigns are kept between invocations")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--label", default="", help="free text stored in the JSON (e.g. before/after)")
    args = p.parse_args(argv)
    from tyrelab.executor import single_threaded_blas
    single_threaded_blas()  # as the tyrelab command does
    c = time.process_time()
    import tyrelab.stages.regress  # noqa: F401
    result = {"benchmark": "regress", "label": args.label, "cores": os.cpu_count(),
              "load_average_at_start": [round(x, 2) for x in os.getloadavg()],
              "import_cpu_s": round(time.process_time() - c, 3), "scales": {}}
    with tempfile.TemporaryDirectory() as tmp:
        for scale in args.scales:
            result["scales"][scale] = bench_scale(scale, args.data, Path(tmp), args.jobs, args.repeats)
    print(json.dumps(result))
    return result


if __name__ == "__main__":
    main()
