"""A vehicle's transfer functions and modes against scipy.signal.csd of the same channel pairs (issue 43).

Usage: ``python bench/bench_frf.py [--minutes 10] [--fs 500] [--repeat 3]``. Writes, once and
untimed, a four-post stand recording (4 inputs, 6 outputs, ``--fs`` Hz, ``--minutes`` long, Parquet):
band-limited random pad accelerations (0.5–12 Hz, thesis §2.2) through a linear system with modes
at 1.6 Hz (ζ 0.25) and 2.9 Hz (ζ 0.12), sensor noise added. Then times in this process
(``time.process_time``, CPU seconds, best of ``--repeat``):

- *frf*: :func:`tyrelab.api.vehicle_frf` on the file: the streamed read, the Welch matrices,
  MIMO H1, coherences, random error, conditioning, the modal fit of every output;
- *csd alone*: ``scipy.signal.csd`` of the same channel pairs (inputs with inputs, inputs with
  outputs, each output with itself; same segments) on the arrays already in memory.

And the peak of memory allocated (``tracemalloc``) while *frf* runs on the recording and on one
of twice its length: bounded by the segment length (and the reader's first chunk), not the
recording, the two peaks are alike. Then the estimator's own part of it: the peak while the Welch
matrices stream through :class:`tyrelab.measurement.frf.CrossSpectraAccumulator` in the reader's
batches (:data:`tyrelab.rawformat.rides.READ_ROWS` rows), for segments of 1, 2 and 4 times the
default length, on the recording and on the one of twice its length: it follows the segment, not
the recording.

Prints one JSON object: seconds of each, ``ratio`` = frf / csd alone (issue 43: ≤ 2), the peaks
(``stream_peak_MB``: segment samples -> [peak on the recording, peak on twice its length]).
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np
import pandas as pd
from scipy import signal

from tyrelab.api import vehicle_frf
from tyrelab.measurement.frf import CrossSpectraAccumulator, segment_samples
from tyrelab.rawformat.rides import INPUT_CHANNELS, READ_ROWS

OUTPUTS = ["floor_x_m_s2", "floor_y_m_s2", "floor_z_m_s2", "roll_rad_s2", "pitch_rad_s2", "yaw_rad_s2"]


def write_recording(path: Path, minutes: float, fs: float, seed: int = 43) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    n = int(minutes * 60 * fs)
    b, a = signal.butter(4, [0.5, 12.0], btype="bandpass", fs=fs)
    x = signal.lfilter(b, a, rng.standard_normal((4, n)), axis=1)
    y = np.zeros((6, n))
    for fn, z in ((1.6, 0.25), (2.9, 0.12)):
        wn = 2 * np.pi * fn
        bz, az = signal.bilinear([2 * z * wn, wn ** 2], [1, 2 * z * wn, wn ** 2], fs=fs)
        resp = signal.lfilter(bz, az, x, axis=1)
        y += rng.uniform(-1, 1, (6, 4)) @ resp
    y += 0.02 * rng.standard_normal(y.shape)
    frame = pd.DataFrame({"time_s": np.arange(n) / fs, **dict(zip(INPUT_CHANNELS, x)), **dict(zip(OUTPUTS, y))})
    frame.to_parquet(path)
    return frame


def csd_alone(frame: pd.DataFrame, fs: float) -> None:
    nperseg = segment_samples(fs)
    x = [frame[c].to_numpy() for c in INPUT_CHANNELS]
    y = [frame[c].to_numpy() for c in OUTPUTS]
    for i in range(4):
        for j in range(i, 4):
            signal.csd(x[i], x[j], fs=fs, nperseg=nperseg)
        for k in range(6):
            signal.csd(x[i], y[k], fs=fs, nperseg=nperseg)
    for k in range(6):
        signal.csd(y[k], y[k], fs=fs, nperseg=nperseg)


def stream(frame: pd.DataFrame, fs: float, nperseg: int) -> None:
    """The Welch matrices of ``frame`` streamed in the reader's batches (the estimator's part of *frf*)."""
    x = frame[INPUT_CHANNELS].to_numpy().T
    y = frame[OUTPUTS].to_numpy().T
    acc = CrossSpectraAccumulator(4, 6, fs, nperseg)
    for i in range(0, x.shape[1], READ_ROWS):
        acc.add(x[:, i:i + READ_ROWS], y[:, i:i + READ_ROWS])
    acc.finish()


def _best(fn, repeat: int) -> float:
    best = np.inf
    for _ in range(repeat):
        t0 = time.process_time()
        fn()
        best = min(best, time.process_time() - t0)
    return best


def _peak_mb(fn) -> float:
    tracemalloc.start()
    fn()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak / 1e6


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--minutes", type=float, default=10.0)
    ap.add_argument("--fs", type=float, default=500.0)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as d:
        path, double = Path(d) / "stand.parquet", Path(d) / "double.parquet"
        frame = write_recording(path, args.minutes, args.fs)
        write_recording(double, 2 * args.minutes, args.fs)
        result = vehicle_frf(path)
        t_frf = _best(lambda: vehicle_frf(path), args.repeat)
        t_csd = _best(lambda: csd_alone(frame, args.fs), args.repeat)
        twice = pd.read_parquet(double)
        base = segment_samples(args.fs)
        stream_peak = {n: [round(_peak_mb(lambda: stream(f, args.fs, n)), 1) for f in (frame, twice)]
                       for n in (base, 2 * base, 4 * base)}
        del frame, twice
        peak_full = _peak_mb(lambda: vehicle_frf(path))
        peak_double = _peak_mb(lambda: vehicle_frf(double))
    out = {"minutes": args.minutes, "fs_Hz": args.fs, "inputs": 4, "outputs": 6,
           "modes_fitted": len(result.mode_rows()), "frf_s": round(t_frf, 3), "csd_alone_s": round(t_csd, 3),
           "ratio": round(t_frf / t_csd, 2), "peak_MB": round(peak_full, 1), "peak_double_length_MB": round(peak_double, 1),
           "recording_MB": round(args.minutes * 60 * args.fs * 11 * 8 / 1e6, 1), "stream_peak_MB": stream_peak}
    print(json.dumps(out))
    return out


if __name__ == "__main__":
    main()
