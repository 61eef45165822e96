"""How wall time and peak memory of ingest + analyse grow with the number of runs.

Usage: ``python bench/bench_scaling.py [--sizes 100 1000 10000] [--duration 20] [--jobs 1]``.
For each size, a fresh closed-form campaign is written to a temporary folder
and ``ingest`` + ``analyse`` run in a *separate process* (so that
``resource.getrusage`` gives that size's own peak RSS), then a no-op re-run
is timed. Prints one JSON object per size.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent

CHILD = """
import json, resource, sys, time
sys.path.insert(0, {here!r})
from tyrelab.executor import command_gc, single_threaded_blas
single_threaded_blas()  # as the tyrelab command does
command_gc()
from tyrelab.stages import Context, run_pipeline
ctx = Context(raw={raw!r}, build={build!r}, jobs={jobs})
t0 = time.perf_counter()
res = run_pipeline(ctx, ["ingest", "analyse"])
t1 = time.perf_counter()
run_pipeline(ctx, ["ingest", "analyse"])
t2 = time.perf_counter()
rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
rss_children = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
print(json.dumps({{"seconds": round(t1 - t0, 2), "noop_seconds": round(t2 - t1, 3),
                  "analysed": res[1].n_ok, "peak_rss_MB": round(max(rss, rss_children))}}))
"""


def measure(n: int, duration: float, jobs: int) -> dict:
    """Generate ``n`` runs, then time ingest + analyse in a child process."""
    sys.path.insert(0, str(HERE))
    from synthetic_runs import write_campaign

    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        raw = write_campaign(Path(tmp) / "raw", n, duration)
        gen = time.perf_counter() - t0
        code = CHILD.format(here=str(HERE), raw=str(raw), build=str(Path(tmp) / "build"), jobs=jobs)
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
        mb = sum(p.stat().st_size for p in (raw / "runs").glob("*.parquet")) / 1e6
    res = json.loads(out.stdout.strip().splitlines()[-1])
    res.update(benchmark="scaling", runs=n, duration_s=duration, jobs=jobs, raw_MB=round(mb),
               generate_seconds=round(gen, 1), runs_per_s=round(n / res["seconds"]))
    return res


def main(argv=None) -> list[dict]:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--sizes", type=int, nargs="+", default=[100, 1000, 10000])
    p.add_argument("--duration", type=float, default=20.0)
    p.add_argument("--jobs", type=int, default=1)
    args = p.parse_args(argv)
    out = []
    for n in args.sizes:
        out.append(measure(n, args.duration, args.jobs))
        print(json.dumps(out[-1]), flush=True)
    return out


if __name__ == "__main__":
    main()
