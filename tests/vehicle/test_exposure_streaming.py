"""The streamed analysis of a recording (issue 24): how it is read and split over threads
changes no number, and a problem in a later chunk is still one line naming its row."""

import math

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from tyrelab.rawformat import RunFileError
from tyrelab.rawformat import rides
from tyrelab.rawformat.rides import open_recording
from tyrelab.vehicle import iso2631, iso2631_5, measured_ride

FS_HZ = 500.0
ROWS = 150_000  # 300 s


def _columns(rows=ROWS, seed=7):
    rng = np.random.default_rng(seed)
    t = np.arange(rows) / FS_HZ
    cols = {"time_s": t}
    for k, name in enumerate(("seat_x_m_s2", "seat_y_m_s2", "seat_z_m_s2", "floor_z_m_s2")):
        cols[name] = (0.3 * rng.standard_normal(rows) + np.sin(2 * np.pi * (1.3 + k) * t)
                      + (9.80665 if name.endswith("z_m_s2") else 0.0))
    return cols


def _parquet(path, cols):
    pq.write_table(pa.table(cols), path)
    return path


def _json_and_psd(analysis):
    return analysis.to_json(), {c: (r.frequency_Hz, r.psd) for c, r in analysis.channels.items()}


def test_threads_and_read_batches_do_not_change_a_number(tmp_path):
    """workers=1 (no thread) and workers=3 (read-ahead + pool) give the same bytes; a first chunk
    longer than a read batch, and not a multiple of it, is gathered from several batches."""
    path = _parquet(tmp_path / "r.parquet", _columns())
    one = measured_ride.analyse_recording(open_recording(path, chunk_rows=100_000), workers=1)
    three = measured_ride.analyse_recording(open_recording(path, chunk_rows=100_000), workers=3)
    (j1, p1), (j3, p3) = _json_and_psd(one), _json_and_psd(three)
    assert j1 == j3
    for c in p1:
        np.testing.assert_array_equal(p1[c][1], p3[c][1])
    assert one.channels["seat_z_m_s2"].n_samples == ROWS
    # the offsets are the first chunk's means, however the rows were read
    rec = open_recording(path, chunk_rows=100_000)
    z = _columns()["seat_z_m_s2"]
    assert rec.offsets["seat_z_m_s2"] == pytest.approx(float(z[:100_000].mean()), rel=1e-12)
    sizes = [c.time_s.size for c in rec.chunks()]
    assert sizes[0] == 100_000 and sum(sizes) == ROWS and max(sizes[1:]) <= rides.READ_ROWS


def test_streamed_recording_equals_the_same_analysis_in_memory_and_the_whole_record_functions(tmp_path):
    cols = _columns()
    path = _parquet(tmp_path / "r.parquet", cols)
    rec = measured_ride.analyse_recording(open_recording(path, chunk_rows=40_000), workers=2)
    mem = measured_ride.analyse_signals({c: v for c, v in cols.items() if c != "time_s"}, FS_HZ, chunk_rows=40_000)
    for c, r in rec.channels.items():
        m = mem.channels[c]
        for key in ("a_w_m_s2", "vdv_m_s1_75", "mtvv_m_s2", "crest_factor", "dz_m_s2", "unweighted_rms",
                    "peak_frequency_Hz"):
            assert getattr(r, key) == pytest.approx(getattr(m, key), rel=1e-12, nan_ok=True), (c, key)
        np.testing.assert_allclose(r.psd, m.psd, rtol=1e-12)
    # the whole-record functions remove the record's mean, the stream its first chunk's: 1e-4 here
    r = rec.channels["seat_z_m_s2"]
    x = cols["seat_z_m_s2"] - cols["seat_z_m_s2"].mean()
    aw = iso2631.weighted_signal(x, FS_HZ, "Wk")
    assert r.a_w_m_s2 == pytest.approx(float(np.sqrt(np.mean(aw**2))), rel=1e-4)
    assert r.vdv_m_s1_75 == pytest.approx(iso2631.vibration_dose_value(aw, FS_HZ), rel=1e-4)
    assert r.mtvv_m_s2 == pytest.approx(iso2631.mtvv(aw, FS_HZ), rel=1e-4)
    assert r.dz_m_s2 == pytest.approx(iso2631_5.acceleration_dose(x, FS_HZ), rel=1e-3)


@pytest.mark.parametrize("workers", [1, 2])
@pytest.mark.parametrize("problem,row,message", [
    ("nan", 123_457, "channel seat_y_m_s2 has a NaN, infinite or non-numeric sample at row 123457"),
    ("inf", 99_999, "channel seat_y_m_s2 has a NaN, infinite or non-numeric sample at row 99999"),
    ("back", 140_001, "time_s is not strictly increasing at row 140001"),
    ("gap", 70_000, "irregular sampling: interval at row 70000 is 0.004 s, expected 0.002 s"),
])
def test_a_problem_in_a_later_chunk_is_one_line_with_its_row(tmp_path, workers, problem, row, message):
    cols = _columns()
    if problem == "nan":
        cols["seat_y_m_s2"][row] = np.nan
    elif problem == "inf":
        cols["seat_y_m_s2"][row] = np.inf
    elif problem == "back":
        cols["time_s"][row] = cols["time_s"][row - 2]
    else:
        cols["time_s"][row:] += 1 / FS_HZ
    path = _parquet(tmp_path / "r.parquet", cols)
    with pytest.raises(RunFileError) as e:
        measured_ride.analyse_recording(open_recording(path, chunk_rows=30_000), workers=workers)
    assert str(e.value) == message


def test_finite_samples_whose_sum_overflows_are_not_called_nan(tmp_path):
    """Finite but implausible (issue 37): refused as beyond the bound, not as a NaN."""
    cols = _columns(rows=20_000)
    cols["seat_x_m_s2"][:] = 1e308
    path = _parquet(tmp_path / "r.parquet", cols)
    with pytest.raises(RunFileError, match=r"seat_x_m_s2 has a sample of 1e\+308 m/s² at row 0, beyond"):
        open_recording(path, chunk_rows=5_000)


def test_peak_dose_is_the_same_for_any_chunking():
    rng = np.random.default_rng(11)
    for _ in range(200):
        n = int(rng.integers(1, 400))
        a = rng.standard_normal(n) + rng.uniform(-2, 2)
        a[rng.random(n) < 0.1] = 0.0
        p, i = iso2631_5.PeakDose(), 0
        while i < n:
            k = int(rng.integers(1, 30))
            p.process(a[i:i + k])
            i += k
        peaks = iso2631_5.positive_peaks(a)
        assert p.finish() == pytest.approx(iso2631_5.dose_from_peaks(peaks), rel=1e-12)
        assert p.n_peaks == peaks.size


def test_response_filter_returns_arrays_it_does_not_reuse():
    fs = 100.0
    rng = np.random.default_rng(5)
    x = rng.standard_normal(60_000)
    f = iso2631.ResponseFilter([iso2631.impulse_response(lambda f: iso2631.weighting_response(f, "Wd"), fs, 20.0)])
    parts, cuts = [], np.sort(rng.integers(0, x.size, 12))
    for a, b in zip(np.concatenate(([0], cuts)), np.concatenate((cuts, [x.size]))):
        out = f.process(x[a:b])[0]
        parts.append((out, out.copy()))
    parts.append((f.finish()[0],) * 2)
    for kept, copy in parts:  # later blocks did not overwrite an array handed out earlier
        np.testing.assert_array_equal(kept, copy)
    y = np.concatenate([p for p, _ in parts])
    assert y.size == x.size
    one = iso2631.ResponseFilter([iso2631.impulse_response(lambda f: iso2631.weighting_response(f, "Wd"), fs, 20.0)])
    np.testing.assert_allclose(y, np.concatenate([one.process(x)[0], one.finish()[0]]), rtol=0, atol=1e-12)


def test_analyse_recording_checks_workers(tmp_path):
    path = _parquet(tmp_path / "r.parquet", _columns(rows=5_000))
    with pytest.raises(ValueError, match="workers"):
        measured_ride.analyse_recording(open_recording(path), workers=0)
    assert math.isfinite(measured_ride.analyse_recording(open_recording(path), workers=None).a_v())


def test_a_csv_recording_reads_in_batches_too(tmp_path):
    cols = _columns(rows=30_000)
    path = tmp_path / "r.csv"
    pd.DataFrame(cols).to_csv(path, index=False)
    rec = open_recording(path, chunk_rows=7_000)
    sizes = [c.time_s.size for c in rec.chunks()]
    assert sizes[0] == 7_000 and sum(sizes) == 30_000


def test_a_failing_task_stops_the_read_ahead_thread(tmp_path, monkeypatch):
    """An error in the analysis (here a task raising) reaches the caller, and the reading thread
    does not outlive the call."""
    import threading

    path = _parquet(tmp_path / "r.parquet", _columns())
    calls = {"n": 0}
    original = measured_ride.ChannelAnalyser._filtered

    def failing(self, x):
        calls["n"] += 1
        if calls["n"] == 4:
            raise RuntimeError("task failed")
        return original(self, x)

    monkeypatch.setattr(measured_ride.ChannelAnalyser, "_filtered", failing)
    with pytest.raises(RuntimeError, match="task failed"):
        measured_ride.analyse_recording(open_recording(path, chunk_rows=10_000), workers=2)
    assert not [t for t in threading.enumerate() if t.name.startswith(("tyrelab-read-ahead", "tyrelab-exposure"))]


def test_threads_asked_for_are_bounded_by_the_chunk_tasks():
    """``workers`` is a user's number: at most one thread per task of a chunk (two per channel),
    however many are asked for; a bad value is refused naming it."""
    assert measured_ride._workers(10**6, 6) == 6
    assert measured_ride._workers(1, 6) == 1
    with pytest.raises(ValueError, match="workers"):
        measured_ride._workers(0, 6)
