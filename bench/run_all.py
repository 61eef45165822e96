"""Run every benchmark in bench/ and print their JSON/text output (``make bench``).

Usage: ``python bench/run_all.py [--quick]``. ``--quick`` uses small sizes
(200 -> 50 analysis runs; scaling 100 and 1000 runs only; the pipeline on the small
campaign only) for a smoke run.
Each benchmark runs in its own process, one after the other (no contention).
Benchmarks owned by other parts of the project (``bench_carriage.py``,
``bench_accuracy.py``) are run if present.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def plan(quick: bool) -> list[list[str]]:
    """Command lines of the benchmarks to run."""
    cmds = [
        ["bench_analysis.py", "--runs", "50" if quick else "200"],
        ["bench_scaling.py", "--sizes", *(["100", "1000"] if quick else ["100", "1000", "10000"])],
    ]
    cmds.append(["bench_pipeline.py", "--scales", "small"] if quick else ["bench_pipeline.py"])
    cmds += [[name] for name in ("bench_carriage.py", "bench_accuracy.py") if (HERE / name).exists()]
    cmds += [["bench_ride.py", *(["--skip-sweep"] if quick else [])]] if (HERE / "bench_ride.py").exists() else []
    cmds += [["bench_simulate.py", *([] if quick else ["--stage"])]] if (HERE / "bench_simulate.py").exists() else []
    return cmds


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true")
    args = p.parse_args(argv)
    failed = 0
    for cmd in plan(args.quick):
        print(f"== {' '.join(cmd)}", flush=True)
        t0 = time.perf_counter()
        rc = subprocess.run([sys.executable, str(HERE / cmd[0]), *cmd[1:]]).returncode
        print(f"== {cmd[0]}: exit {rc}, {time.perf_counter() - t0:.0f} s", flush=True)
        failed += rc != 0
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
