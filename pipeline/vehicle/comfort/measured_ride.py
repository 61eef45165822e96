"""Whole-body vibration of a recording, streamed: one analysis for measured and predicted signals.

Per channel of a vehicle recording (:mod:`tyrelab.rawformat.rides`), in one pass over
chunks and bounded memory:

- the offset (the mean of the first chunk, :data:`tyrelab.rawformat.rides.CHUNK_ROWS`
  rows) is removed — also a DC-coupled accelerometer's 1 g;
- seat and floor accelerations are frequency weighted (ISO 2631-1: W_k on z, W_d on x
  and y; :class:`~tyrelab.vehicle.iso2631.ResponseFilter` with the same analog responses
  :func:`~tyrelab.vehicle.iso2631.weighted_signal` uses), giving a_w, VDV, running r.m.s.
  (linear, τ = 1 s) and its maximum MTVV, the crest factor and the §6.2.1/§6.3.3 rule;
  axle and rotational channels are not weighted (ISO 2631-1 weights only where the
  body is supported; their r.m.s. and spectrum are reported);
- the seat's vertical acceleration also goes through the ISO 2631-5:2018 seat-to-spine
  model (:mod:`tyrelab.vehicle.iso2631_5`): D_z;
- the unweighted PSD (Welch, Hann, 50 % overlap, 0.1 Hz as thesis §7.4; the same segments
  as :func:`tyrelab.vehicle.metrics.acceleration_psd`), its dominant peak frequency and
  half-power width (thesis §6.4.2, :func:`tyrelab.vehicle.metrics.spectral_peak`).

The recording gives per-axis seat values, the vector sum a_v, SEAT = a_w(seat)/a_w(floor)
per axis (ISO 10326-1) where both are recorded, and the JSON of ``tyrelab exposure``.
Predicted signals go through :func:`analyse_signals`, the same code.

Examples
--------
>>> fs = 100.0
>>> t = np.arange(int(120 * fs)) / fs
>>> r = analyse_signals({"seat_z_m_s2": np.sin(2 * np.pi * 4.0 * t)}, fs)
>>> z = r.axes()["z"]
>>> round(z["a_w_m_s2"], 3), round(z["mtvv_m_s2"], 3), round(r.channels["seat_z_m_s2"].peak_frequency_Hz, 2)
(0.684, 0.686, 4.0)
"""

from __future__ import annotations

import functools
import math
import os
import queue
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np

from ... import _validate
from ..._validate import positive
from . import iso2631
from . import iso2631_5
from . import metrics as mt

__all__ = ["WEIGHTING_OF", "ChannelResult", "ChannelAnalyser", "RecordingAnalysis", "analyse_recording",
           "analyse_signals", "WEIGHTING_RING_S", "PSD_BANDWIDTH_HZ", "PEAK_BAND_HZ"]

#: Channel -> (ISO 2631-1 weighting, axis) for the channels weighted (seat and cab floor):
#: ``seat_x_m_s2`` ... ``floor_z_m_s2``, each axis's weighting :data:`~tyrelab.vehicle.comfort.iso2631.AXIS_WEIGHTING`.
WEIGHTING_OF = {f"{place}_{ax}_m_s2": (iso2631.AXIS_WEIGHTING[ax], ax) for place in ("seat", "floor") for ax in "xyz"}
#: Length after which the weightings' impulse responses have rung down (the 0.4 Hz
#: band-limiting high-pass decays as exp(-1.78 t): 1e-6 of its peak after 10 s), s.
WEIGHTING_RING_S = 20.0
#: Resolution of the seat PSD (thesis §7.4), Hz.
PSD_BANDWIDTH_HZ = 0.1
#: Band searched for the dominant spectral peak (thesis §6.4.2), Hz.
PEAK_BAND_HZ = (0.5, 10.0)


@dataclass
class ChannelResult:
    """The analysis of one channel (SI; NaN where a value does not apply).

    ``a_w_m_s2``, ``vdv_m_s1_75``, ``mtvv_m_s2`` are *without* the axis factor k;
    ``crest_factor`` is that of the weighted signal; ``dz_m_s2`` only for the seat's z.
    """

    channel: str
    weighting: str | None
    duration_s: float
    n_samples: int
    unweighted_rms: float
    a_w_m_s2: float = math.nan
    vdv_m_s1_75: float = math.nan
    mtvv_m_s2: float = math.nan
    crest_factor: float = math.nan
    dz_m_s2: float = math.nan
    peak_frequency_Hz: float = math.nan
    half_power_width_Hz: float = math.nan
    width_over_frequency: float = math.nan
    method: dict = field(default_factory=dict)
    frequency_Hz: np.ndarray = field(default_factory=lambda: np.empty(0), repr=False)
    psd: np.ndarray = field(default_factory=lambda: np.empty(0), repr=False)


class _Welch:
    """Streaming Welch PSD: Hann, 50 % overlap, constant detrend, density scaling (as scipy.signal.welch).

    The samples not yet in a whole segment are kept in one array the next chunk is written
    behind (:meth:`load`); :meth:`process` transforms the whole segments, a few at a time into
    arrays it reuses.
    """

    #: Segments transformed together (2 × 640 KiB of arrays at 500 Hz: in cache).
    BATCH = 16

    def __init__(self, fs_Hz: float, nperseg: int):
        self.fs, self.n, self.hop = fs_Hz, nperseg, nperseg - nperseg // 2
        self.win = np.hanning(nperseg + 1)[:-1] if nperseg > 1 else np.ones(1)  # periodic Hann (scipy's 'hann')
        # the constant detrend after the transform (linear: rfft(w (s - m)) = rfft(w s) - m rfft(w)); the
        # periodic Hann's spectrum is N/2, -N/4 at bins 0 and 1 and zero (rounding) elsewhere
        spectrum = np.fft.rfft(self.win)
        self._detrend_bins = np.flatnonzero(np.abs(spectrum) > 1e-9 * np.abs(spectrum).max())
        self._detrend_values = spectrum[self._detrend_bins]
        self._buf = np.empty(0)
        self._start = self._end = 0  # the samples not yet transformed: _buf[_start:_end]
        self._windowed = iso2631._aligned_empty((self.BATCH, nperseg))
        self._spectra = iso2631._aligned_empty((self.BATCH, nperseg // 2 + 1), complex)
        self._power = np.zeros(2 * (nperseg // 2 + 1))  # Σ re², Σ im² of the segments' spectra, interleaved
        self.count = 0

    def load(self, samples, offset: float) -> np.ndarray:
        """Write ``samples - offset`` behind the samples kept; returns them (a view, valid until
        the next ``load``)."""
        kept = self._end - self._start
        need = kept + len(samples)
        if self._buf.size < need:
            buf = iso2631._aligned_empty(need)
            buf[:kept] = self._buf[self._start:self._end]
            self._buf = buf
        elif self._start:
            self._buf[:kept] = self._buf[self._start:self._end].copy()
        self._start, self._end = 0, need
        x = self._buf[kept:need]
        np.subtract(samples, offset, out=x)
        return x

    def process(self) -> None:
        """Transform the whole segments among the samples loaded."""
        buf = self._buf[self._start:self._end]
        if buf.size < self.n:
            return
        m = (buf.size - self.n) // self.hop + 1
        segs = np.lib.stride_tricks.sliding_window_view(buf, self.n)[:: self.hop][:m]
        if self.n == 2 * self.hop:  # each segment two halves: their sums, one pass over the samples
            halves = buf[: (m + 1) * self.hop].reshape(m + 1, self.hop).sum(axis=1)
            means = (halves[:-1] + halves[1:]) / self.n
        else:
            means = segs.mean(axis=1)
        for i in range(0, m, self.BATCH):
            k = min(self.BATCH, m - i)
            windowed = np.multiply(segs[i:i + k], self.win, out=self._windowed[:k])
            spec = iso2631._rfft_into(windowed, self.n, self._spectra[:k])
            spec[:, self._detrend_bins] -= means[i:i + k, None] * self._detrend_values
            parts = spec.view(np.float64)  # re, im interleaved
            self._power += np.einsum("ij,ij->j", parts, parts)
        self.count += m
        self._start += m * self.hop

    def finish(self) -> tuple[np.ndarray, np.ndarray]:
        from scipy import signal

        if self.count == 0:  # shorter than a segment: one periodogram of it all (as acceleration_psd)
            left = self._buf[self._start:self._end]
            if left.size < 2:
                return np.empty(0), np.empty(0)
            return signal.welch(left, fs=self.fs, window="hann", nperseg=left.size, detrend="constant")
        total = self._power[0::2] + self._power[1::2]
        psd = total / self.count / (self.fs * np.sum(self.win**2))
        psd[1:] *= 2.0
        if self.n % 2 == 0:
            psd[-1] /= 2.0
        return np.fft.rfftfreq(self.n, 1.0 / self.fs), psd


#: Samples per pass of the weighted signal's sums (in cache: 256 KiB of float64).
_SUB_BLOCK = 1 << 15


class ChannelAnalyser:
    """Streaming analysis of one channel; :meth:`process` chunks, then :meth:`finish`.

    Parameters
    ----------
    channel : str
        Raw-format name; seat/floor channels are weighted (:data:`WEIGHTING_OF`).
    fs_Hz : float
        Sampling rate, Hz.
    offset : float
        Removed from every sample (the recording's first-chunk mean).
    """

    def __init__(self, channel: str, fs_Hz: float, offset: float = 0.0):
        self.channel = channel
        self.fs = positive("fs_Hz", fs_Hz)
        self.offset = float(offset)
        self.weighting = WEIGHTING_OF.get(channel, (None, None))[0]
        self.spine = channel == "seat_z_m_s2"
        responses = []
        if self.weighting:
            w = self.weighting
            responses.append(iso2631.impulse_response(lambda f: iso2631.weighting_response(f, w), self.fs,
                                                      WEIGHTING_RING_S))
        if self.spine:  # same length as the weighting's taps, so one FFT of each chunk serves both
            responses.append(iso2631.impulse_response(iso2631_5.spine_response, self.fs, WEIGHTING_RING_S))
        self._filter = iso2631.ResponseFilter(responses) if responses else None
        self._dose = iso2631_5.PeakDose() if self.spine else None
        self._welch = _Welch(self.fs, max(1, int(round(self.fs / PSD_BANDWIDTH_HZ))))
        self._window = k = max(1, int(round(iso2631.RUNNING_RMS_TAU_S * self.fs)))
        if self.weighting:
            # the last k squares of the weighted signal (zeros before the start), then a sub-block's;
            # their running sum; the window sums
            self._squares = np.zeros(k + _SUB_BLOCK)
            self._cumulative = np.zeros(k + _SUB_BLOCK + 1)
            self._window_sums = np.empty(_SUB_BLOCK)
        self.n = 0
        self._sum = self._sum2 = 0.0
        self._w2 = self._w4 = self._sq_max = self._window_max = 0.0
        self._nw = 0

    def process(self, samples) -> None:
        for task in self.tasks(samples):
            task()

    def tasks(self, samples) -> list:
        """The work of one chunk as independent calls (they share no state, so they may run in
        parallel threads; each must run once, and all before the next chunk's ``tasks``)."""
        samples = np.asarray(samples, dtype=float)
        if samples.size == 0:
            return []
        x = self._welch.load(samples, self.offset)
        self.n += x.size
        work = [functools.partial(self._unweighted, x)]
        if self._filter is not None:
            work.append(functools.partial(self._filtered, x))
        return work

    def _unweighted(self, x: np.ndarray) -> None:
        self._sum += float(x.sum())
        self._sum2 += float(np.einsum("i,i->", x, x))  # not np.dot: BLAS threads stall on a busy machine
        self._welch.process()

    def _filtered(self, x: np.ndarray) -> None:
        for outputs in self._filter.blocks(x):
            self._weighted(outputs)

    def _weighted(self, outputs) -> None:
        k = self._window
        if self.weighting:
            self._nw += outputs[0].size
        for i in range(0, outputs[0].size, _SUB_BLOCK):  # a few passes over each sub-block while it is in cache
            if self.weighting:
                part = outputs[0][i:i + _SUB_BLOCK]
                m = part.size
                sq, c, sums = self._squares, self._cumulative, self._window_sums
                new = np.multiply(part, part, out=sq[k:k + m])
                self._w2 += float(new.sum())
                self._w4 += float(np.einsum("i,i->", new, new))
                self._sq_max = max(self._sq_max, float(new.max()))
                np.cumsum(sq[:k + m], out=c[1:k + m + 1])
                window = np.subtract(c[k + 1:k + m + 1], c[1:m + 1], out=sums[:m])  # window sums ending at each new sample
                self._window_max = max(self._window_max, float(window.max()))
                sq[:k] = sq[m:m + k].copy()
            if self._dose is not None:
                self._dose.process(outputs[-1][i:i + _SUB_BLOCK])

    def finish(self) -> ChannelResult:
        if self._filter is not None:
            for outputs in self._filter.final_blocks():
                self._weighted(outputs)
        duration = self.n / self.fs
        mean = self._sum / self.n if self.n else math.nan
        res = ChannelResult(self.channel, self.weighting, duration, self.n,
                            math.sqrt(max(self._sum2 / self.n - mean**2, 0.0)) if self.n else math.nan)
        f, p = self._welch.finish()
        res.frequency_Hz, res.psd = f, p
        if f.size > 2 and np.any((f >= PEAK_BAND_HZ[0]) & (f <= PEAK_BAND_HZ[1])) and np.max(p) > 0:
            pk = mt.spectral_peak(f, p, *PEAK_BAND_HZ)
            res.peak_frequency_Hz = pk["peak_frequency_Hz"]
            res.half_power_width_Hz = pk["half_power_width_Hz"]
            res.width_over_frequency = pk["width_over_frequency"]
        if self.weighting and self._nw:
            res.a_w_m_s2 = math.sqrt(self._w2 / self._nw)
            res.vdv_m_s1_75 = (self._w4 / self.fs) ** 0.25
            res.mtvv_m_s2 = math.sqrt(max(self._window_max, 0.0) / self._window)
            res.crest_factor = math.sqrt(self._sq_max) / res.a_w_m_s2 if res.a_w_m_s2 > 0 else math.nan
            res.method = iso2631.method_check(res.a_w_m_s2, res.crest_factor, res.mtvv_m_s2, res.vdv_m_s1_75, duration)
        if self._dose is not None:
            res.dz_m_s2 = self._dose.finish()
        return res


@dataclass
class RecordingAnalysis:
    """The analysis of a recording (or of predicted signals).

    Attributes
    ----------
    sample_rate_Hz, duration_s : float
    channels : dict
        Channel -> :class:`ChannelResult`.
    warnings : list of str
    """

    sample_rate_Hz: float
    duration_s: float
    channels: dict
    warnings: list = field(default_factory=list)

    def axes(self) -> dict:
        """Seat axis (``x``, ``y``, ``z``) -> the issue's per-axis values (a_w etc. without k)."""
        out = {}
        for ax in ("x", "y", "z"):
            r = self.channels.get(f"seat_{ax}_m_s2")
            if r is None:
                continue
            out[ax] = {"a_w_m_s2": r.a_w_m_s2, "vdv_m_s1_75": r.vdv_m_s1_75, "mtvv_m_s2": r.mtvv_m_s2,
                       "crest_factor": r.crest_factor, "duration_s": r.duration_s, "weighting": r.weighting,
                       "axis_factor": iso2631.AXIS_FACTOR[ax], "rms_method_sufficient": r.method["rms_method_sufficient"],
                       "method_reasons": r.method["reasons"], "peak_frequency_Hz": r.peak_frequency_Hz,
                       "half_power_width_Hz": r.half_power_width_Hz}
        return out

    def seat_factor(self) -> dict:
        """Axis -> SEAT = a_w(seat) / a_w(floor) (ISO 10326-1), where both channels are recorded."""
        out = {}
        for ax in ("x", "y", "z"):
            s, f = self.channels.get(f"seat_{ax}_m_s2"), self.channels.get(f"floor_{ax}_m_s2")
            if s is not None and f is not None:
                out[ax] = s.a_w_m_s2 / f.a_w_m_s2 if f.a_w_m_s2 > 0 else math.nan
        return out

    def a_v(self) -> float:
        """ISO 2631-1 vector sum of the seat axes recorded (a missing axis counts as 0), m/s²."""
        ax = self.axes()
        return iso2631.vector_sum(*(ax[a]["a_w_m_s2"] if a in ax else 0.0 for a in ("x", "y", "z")))

    @property
    def dz_m_s2(self) -> float:
        r = self.channels.get("seat_z_m_s2")
        return r.dz_m_s2 if r is not None else math.nan

    def to_json(self) -> dict:
        """``axes``, ``a_v_m_s2``, ``dz_m_s2``, ``seat_factor`` (when floor channels exist), others."""
        out = {"axes": self.axes(), "a_v_m_s2": self.a_v(), "dz_m_s2": self.dz_m_s2,
               "duration_s": self.duration_s, "sample_rate_Hz": self.sample_rate_Hz}
        seat = self.seat_factor()
        if seat:
            out["seat_factor"] = seat
        other = {c: {"unweighted_rms": r.unweighted_rms, "peak_frequency_Hz": r.peak_frequency_Hz,
                     "half_power_width_Hz": r.half_power_width_Hz, **({"a_w_m_s2": r.a_w_m_s2} if r.weighting else {})}
                 for c, r in self.channels.items() if not c.startswith("seat_")}
        if other:
            out["channels"] = other
        if self.warnings:
            out["warnings"] = list(self.warnings)
        return out


def _read_ahead(chunks):
    """The chunks of ``chunks``, the next one read in a thread while the caller works on this one
    (Parquet decoding releases the GIL). At most two are held: the one handed over and the next."""
    hand_over: queue.Queue = queue.Queue(maxsize=1)
    stop = threading.Event()
    end = object()

    def put(item) -> bool:
        while not stop.is_set():
            try:
                hand_over.put(item, timeout=0.05)
                return True
            except queue.Full:
                continue
        return False

    def read() -> None:
        try:
            for chunk in chunks:
                if not put(chunk):
                    return
                del chunk
            put(end)
        except BaseException as exc:  # noqa: BLE001 - handed to the caller's thread, raised there
            put(exc)

    reader = threading.Thread(target=read, name="tyrelab-read-ahead", daemon=True)
    reader.start()
    try:
        while (item := hand_over.get()) is not end:
            if isinstance(item, BaseException):
                raise item
            yield item
            del item
    finally:
        stop.set()
        reader.join()


def _workers(workers: int | None, n_tasks: int) -> int:
    if workers is None:
        try:
            cpus = len(os.sched_getaffinity(0))
        except (AttributeError, OSError):
            cpus = os.cpu_count() or 1
        return max(1, min(cpus, n_tasks))
    return min(_validate.positive_int("workers", workers), n_tasks)  # a thread per task at most


def analyse_recording(recording, workers: int | None = None) -> RecordingAnalysis:
    """Analyse an opened recording (:func:`tyrelab.rawformat.rides.open_recording`) chunk by chunk.

    The next chunk is read in a thread while this one is analysed, and the channels' work on a
    chunk (per channel: the sums and the PSD; the weighting, its sums and the spine model) runs
    in ``workers`` threads (default: the CPUs this process may use, at most the tasks); the
    numbers do not depend on ``workers`` (each channel's work is done in the same order).

    Raises
    ------
    tyrelab.rawformat.RunFileError
        From the reader, if a later chunk is bad (NaN, time going back, irregular).

    See Also
    --------
    analyse_signals : the same for signals in memory.
    tyrelab.vehicle.daily_exposure.daily_exposure : the day from the tasks' values.

    Examples
    --------
    >>> import pandas as pd, tempfile
    >>> from pathlib import Path
    >>> from tyrelab.rawformat.rides import open_recording
    >>> fs = 200.0; t = np.arange(0, 60, 1 / fs)
    >>> path = Path(tempfile.mkdtemp()) / "seat.csv"
    >>> pd.DataFrame({"time_s": t, "seat_z_m_s2": np.sin(2 * np.pi * 4 * t)}).to_csv(path, index=False)
    >>> round(analyse_recording(open_recording(path)).axes()["z"]["a_w_m_s2"], 3)   # 0.7071 × |W_k(4 Hz)|
    0.683
    """
    if not all(hasattr(recording, a) for a in ("sample_rate_Hz", "offsets", "channels", "chunks", "warnings")):
        raise ValueError(f"recording must be an opened recording (rawformat.rides.open_recording), got "
                         f"{type(recording).__name__}")
    analysers = {c: ChannelAnalyser(c, recording.sample_rate_Hz, recording.offsets[c]) for c in recording.channels}
    n_workers = _workers(workers, 2 * len(analysers))
    if n_workers == 1:
        chunks = recording.chunks()
        while (chunk := next(chunks, None)) is not None:
            for c, a in analysers.items():
                a.process(chunk.channels[c])
            del chunk  # not alive while the next one is read
        results = {c: a.finish() for c, a in analysers.items()}
    else:
        with ThreadPoolExecutor(max_workers=n_workers, thread_name_prefix="tyrelab-exposure") as pool:
            chunks = _read_ahead(recording.chunks())
            try:
                while (chunk := next(chunks, None)) is not None:
                    # the weighting first (the longer tasks), so the pool's threads end a chunk together
                    tasks = [t for c, a in analysers.items() for t in a.tasks(chunk.channels[c])]
                    del chunk
                    tasks.sort(key=lambda t: t.func.__name__ != "_filtered")
                    for f in [pool.submit(t) for t in tasks]:
                        f.result()
            finally:
                chunks.close()  # stops the reading thread now, not when the generator is collected
            futures = {c: pool.submit(a.finish) for c, a in analysers.items()}
            results = {c: f.result() for c, f in futures.items()}
    n = max((r.n_samples for r in results.values()), default=0)
    return RecordingAnalysis(recording.sample_rate_Hz, n / recording.sample_rate_Hz, results, list(recording.warnings))


def analyse_signals(signals: dict, fs_Hz: float, chunk_rows: int | None = None) -> RecordingAnalysis:
    """The same analysis for signals in memory (e.g. a prediction), channel name -> samples.

    The offset is the mean of the first ``chunk_rows`` samples, as a recording's.

    See Also
    --------
    analyse_recording : the same for a recording file.

    Examples
    --------
    >>> fs = 200.0; t = np.arange(0, 60, 1 / fs)
    >>> z = analyse_signals({"seat_z_m_s2": np.sin(2 * np.pi * 4 * t)}, fs).axes()["z"]
    >>> round(z["a_w_m_s2"], 3), z["weighting"], z["rms_method_sufficient"], round(z["peak_frequency_Hz"], 2)
    (0.683, 'Wk', True, 4.0)
    """
    from ...rawformat.rides import CHUNK_ROWS

    fs_Hz = positive("fs_Hz", fs_Hz)
    rows = chunk_rows or CHUNK_ROWS
    results = {}
    for c, x in signals.items():
        x = np.asarray(x, dtype=float)
        a = ChannelAnalyser(c, fs_Hz, float(x[:rows].mean()) if x.size else 0.0)
        for i in range(0, x.size, rows):
            a.process(x[i:i + rows])
        results[c] = a.finish()
    n = max((r.n_samples for r in results.values()), default=0)
    return RecordingAnalysis(fs_Hz, n / fs_Hz, results)
