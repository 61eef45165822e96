"""A recording is analysed in bounded memory (issue 24: a full 8 h day of three seat axes at
500 Hz within 500 MB): the peak RSS of a process analysing a recording does not grow with its
length. The full day itself is ``bench/bench_exposure.py --hours 8`` (docs/benchmarks.md)."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[2] / "bench" / "bench_exposure.py"


def _peak_rss_MB(path: Path, workers: int) -> float:
    out = subprocess.run([sys.executable, str(BENCH), "--child", "exposure", str(path), "--workers", str(workers)],
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out)["peak_rss_MB"]


@pytest.mark.slow
@pytest.mark.parametrize("workers", [1, 2])  # 2: the read-ahead thread and the pool
def test_peak_memory_does_not_grow_with_the_recording(tmp_path, workers):
    sys.path.insert(0, str(BENCH.parent))
    try:
        from bench_exposure import write_day
    finally:
        sys.path.remove(str(BENCH.parent))
    short, long_ = tmp_path / "short.parquet", tmp_path / "long.parquet"
    write_day(short, 0.25, 500.0)  # 450 000 rows
    write_day(long_, 1.5, 500.0)  # 2 700 000 rows, 6x: held whole it would be 65 MB more per copy
    a, b = _peak_rss_MB(short, workers), _peak_rss_MB(long_, workers)
    assert b < 500.0 and b - a < 30.0, (a, b)
