"""A full working day of seat vibration: streamed analysis against the Parquet read floor (issue 24).

Usage: ``python bench/bench_exposure.py [--hours 8] [--fs 500] [--dir DIR]``. Writes (once, not
timed) a seeded recording of ``--hours`` at ``--fs`` with ``time_s`` and the three seat axes in
float64 Parquet (pyarrow defaults: snappy, 1 Mi-row groups), then times, each in a fresh child
process, one after the other on the same file:

- *read floor*: reading the four columns batch by batch with pyarrow into numpy, nothing else
  (the recording reader's batch size and options: no pre-buffering, 1 MiB buffered stream);
- *exposure*: :func:`tyrelab.rawformat.rides.open_recording` +
  :func:`tyrelab.vehicle.measured_ride.analyse_recording` (all the per-axis values, D_z, the
  PSDs), i.e. what ``tyrelab exposure FILE`` computes;
- *idle*: the child importing the same modules and nothing else (its peak RSS is the floor of
  the memory figure);
- *fft floor*: only the transforms the analysis cannot do without, on as many samples as the
  recording, into reused arrays as the analysis does: per axis the 2^18-point overlap-save
  weighting (one forward, one inverse per block; a second inverse for z, the ISO 2631-5 spine
  model) and the 0.1 Hz Welch PSD (5 000-point segments, 50 % overlap), on one thread and with
  the three axes on two threads.

Prints one JSON object: file size, rows, seconds, the speed ratio ``read / exposure`` (issue
target ≥ 0.7) and each child's peak RSS (``VmHWM``; issue target ≤ 500 MB).
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

COLUMNS = ["time_s", "seat_x_m_s2", "seat_y_m_s2", "seat_z_m_s2"]


def write_day(path: Path, hours: float, fs: float, seed: int = 24) -> int:
    """A seeded day: band noise plus sines per axis, 1 g on z, written in 1 Mi-row slices."""
    import pyarrow as pa
    import pyarrow.parquet as pq
    from scipy import signal

    n = int(round(hours * 3600 * fs))
    rng = np.random.default_rng(seed)
    sos = signal.butter(2, [0.8, 12.0], "bandpass", fs=fs, output="sos")
    zi = np.zeros((3, sos.shape[0], 2))
    schema = pa.schema([(c, pa.float64()) for c in COLUMNS])
    step = 1 << 20
    with pq.ParquetWriter(path, schema) as w:
        for i0 in range(0, n, step):
            i = np.arange(i0, min(n, i0 + step))
            t = i / fs
            cols = {"time_s": t}
            for k, (ax, amp, f) in enumerate((("x", 0.6, 1.7), ("y", 0.4, 1.1), ("z", 1.0, 3.2))):
                noise, zi[k] = signal.sosfilt(sos, rng.standard_normal(i.size), zi=zi[k])
                cols[f"seat_{ax}_m_s2"] = amp * (noise + 0.5 * np.sin(2 * np.pi * f * t)) + (9.80665 if ax == "z" else 0)
            w.write_table(pa.table(cols, schema=schema))
    return n


def fft_floor(rows: int, fs: float, threads: int) -> float:
    """Seconds for the transforms of :mod:`tyrelab.vehicle.measured_ride` on ``rows`` samples of
    three axes (the same lengths and counts, random data), ``threads`` axes at a time."""
    from concurrent.futures import ThreadPoolExecutor

    from tyrelab.vehicle import iso2631
    from tyrelab.vehicle.measured_ride import PSD_BANDWIDTH_HZ, WEIGHTING_RING_S

    nfft = 1 << 18
    hist = int(round(WEIGHTING_RING_S * fs)) + int(round(0.2 * fs)) - 1
    n_blocks = -(-rows // (nfft - hist))
    nseg = int(round(fs / PSD_BANDWIDTH_HZ))
    n_segments = (rows - nseg) // (nseg - nseg // 2) + 1
    rng = np.random.default_rng(1)

    def arrays() -> dict:
        a = {"buf": iso2631._aligned_empty(nfft), "spec": iso2631._aligned_empty(nfft // 2 + 1, complex),
             "out": iso2631._aligned_empty(nfft), "segs": iso2631._aligned_empty((16, nseg)),
             "seg_spec": iso2631._aligned_empty((16, nseg // 2 + 1), complex)}
        a["buf"][:] = rng.standard_normal(nfft)
        a["segs"][:] = rng.standard_normal((16, nseg))
        return a

    def axis(job) -> None:
        inverses, a = job
        for _ in range(n_blocks):
            iso2631._rfft_into(a["buf"], nfft, a["spec"])
            for _ in range(inverses):
                iso2631._irfft_into(a["spec"], nfft, a["out"])
        for i in range(0, n_segments, 16):
            k = min(16, n_segments - i)
            iso2631._rfft_into(a["segs"][:k], nseg, a["seg_spec"][:k])

    jobs = [(2, arrays()), (1, arrays()), (1, arrays())]  # z (weighting + spine), x, y
    iso2631._raise_mmap_threshold(32 * nfft)
    t0 = time.perf_counter()
    with ThreadPoolExecutor(threads) as pool:
        list(pool.map(axis, jobs))
    return time.perf_counter() - t0


def child(mode: str, path: str, workers: int | None = None) -> dict:
    import pyarrow.parquet as pq

    from tyrelab.rawformat.rides import CHUNK_ROWS, open_recording
    from tyrelab.vehicle.measured_ride import analyse_recording

    t0 = time.perf_counter()
    out: dict = {}
    if mode == "read":
        total = 0.0
        for batch in pq.ParquetFile(path, pre_buffer=False, buffer_size=1 << 20).iter_batches(batch_size=CHUNK_ROWS,
                                                                                             columns=COLUMNS):
            for col in batch.columns:
                total += float(col.to_numpy()[-1])
        out["checksum"] = total
    elif mode == "fft":
        import pyarrow.parquet as pq

        rows = pq.ParquetFile(path).metadata.num_rows
        fs = 1.0 / float(np.diff(pq.ParquetFile(path).read_row_group(0, columns=["time_s"]).column(0).to_numpy()[:2])[0])
        out["seconds_one_thread"] = fft_floor(rows, fs, 1)
        out["seconds_two_threads"] = fft_floor(rows, fs, 2)
    elif mode == "exposure":
        a = analyse_recording(open_recording(path), **({"workers": workers} if workers else {}))  # older commits: none
        out["a_w_z_m_s2"] = a.axes()["z"]["a_w_m_s2"]
        out["dz_m_s2"] = a.dz_m_s2
    out["seconds"] = time.perf_counter() - t0
    use = resource.getrusage(resource.RUSAGE_SELF)
    out["cpu_s"] = use.ru_utime + use.ru_stime  # all threads, imports included
    out["peak_rss_MB"] = _peak_rss_MB()
    return out


def _peak_rss_MB() -> float:
    """This process's peak resident set (VmHWM; ``ru_maxrss`` would carry the parent's over exec)."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--hours", type=float, default=8.0)
    p.add_argument("--fs", type=float, default=500.0)
    p.add_argument("--dir", default=None, help="where to write the recording (default: a temporary folder)")
    p.add_argument("--file", default=None, help="the recording to use: written there if missing, kept (for repeated runs)")
    p.add_argument("--workers", type=int, default=None,
                   help="threads of the analysis (default: the library's, the CPUs available)")
    p.add_argument("--child", nargs=2, metavar=("MODE", "PATH"), help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.child:
        print(json.dumps(child(*args.child, workers=args.workers)))
        return 0
    with tempfile.TemporaryDirectory(dir=args.dir) as d:
        path = Path(args.file) if args.file else Path(d) / "day.parquet"
        t0 = time.perf_counter()
        if path.exists():  # kept from an earlier run with the same --hours/--fs (checked by the row count)
            import pyarrow.parquet as pq

            rows = pq.ParquetFile(path).metadata.num_rows
            if rows != int(round(args.hours * 3600 * args.fs)):
                p.error(f"{path} has {rows} rows, not those of --hours {args.hours} --fs {args.fs}")
        else:
            rows = write_day(path, args.hours, args.fs)
        written_s = time.perf_counter() - t0
        res = {}
        for mode in ("idle", "read", "fft", "exposure"):
            extra = ["--workers", str(args.workers)] if args.workers else []
            cp = subprocess.run([sys.executable, __file__, "--child", mode, str(path), *extra], capture_output=True,
                                text=True, check=True)
            res[mode] = json.loads(cp.stdout)
        print(json.dumps({
            "hours": args.hours, "fs_Hz": args.fs, "rows": rows, "file_MB": round(path.stat().st_size / 1e6, 1),
            "write_s": round(written_s, 1),
            "read_floor_s": round(res["read"]["seconds"], 2), "exposure_s": round(res["exposure"]["seconds"], 2),
            "fft_floor_s": {"one_thread": round(res["fft"]["seconds_one_thread"], 2),
                            "two_threads": round(res["fft"]["seconds_two_threads"], 2)},
            "speed_ratio_read_over_exposure": round(res["read"]["seconds"] / res["exposure"]["seconds"], 3),
            "exposure_Msamples_per_s": round(3 * rows / res["exposure"]["seconds"] / 1e6, 2),
            "peak_rss_MB": {m: round(r["peak_rss_MB"], 1) for m, r in res.items()},
            "cpu_s": {m: round(r["cpu_s"], 2) for m, r in res.items()},
            "a_w_z_m_s2": res["exposure"]["a_w_z_m_s2"], "dz_m_s2": res["exposure"]["dz_m_s2"],
        }, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
