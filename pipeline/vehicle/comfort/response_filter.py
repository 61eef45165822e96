"""ISO 2631-1's weightings on a stream (issue 24; its own module since issue 45): a linear filter
given by its analog frequency response as taps (:func:`impulse_response`) and applied to a stream of
chunks in bounded memory (:class:`ResponseFilter`, overlap-save), so an 8 h recording is never held
whole; the aligned buffers and in-place transforms the streamed analyses share.

The names are :mod:`tyrelab.vehicle.comfort.iso2631`'s, which re-exports them (``iso2631.ResponseFilter``,
``iso2631.impulse_response``, as before; ``tyrelab.vehicle`` resolves them there): this module's
``__all__`` is empty so that no name has two homes in the package's namespace.
"""

from __future__ import annotations

import inspect
import math

import numpy as np

from ..._validate import positive

__all__: list[str] = []  # the names are iso2631's (see the module's text)


def impulse_response(response, fs_Hz: float, ring_s: float, lead_s: float = 0.2) -> tuple[np.ndarray, int]:
    """Taps of a linear filter given by its analog frequency response, and their lead.

    The response is sampled on the bins of a real FFT ``ring_s + lead_s`` long (at least 4×
    over), as :func:`weighted_signal` samples it on its record; the inverse FFT is that
    sampled system's impulse response. It keeps the first ``ring_s`` seconds (the causal part,
    by which the response has rung down) and the last ``lead_s`` seconds (the small
    non-causal part that sampling a response that is not band-limited leaves before t = 0).

    Parameters
    ----------
    response : callable
        ``response(frequency_Hz) -> complex ndarray``.
    fs_Hz : float
        Sampling rate, Hz.
    ring_s, lead_s : float
        Kept length after and before t = 0, s.

    Returns
    -------
    taps : ndarray
        ``h[-lead], ..., h[0], ..., h[ring - 1]``.
    lead : int
        Number of taps before t = 0 (the output delay of a plain convolution with ``taps``).

    See Also
    --------
    tyrelab.vehicle.comfort.iso2631.weighted_signal : applies a weighting on the whole record instead.

    Examples
    --------
    >>> taps, lead = impulse_response(lambda f: np.ones(f.shape, complex), 100.0, ring_s=1.0, lead_s=0.1)
    >>> lead, len(taps), round(float(taps[lead]), 12), round(float(np.abs(np.delete(taps, lead)).max()), 12)
    (10, 110, 1.0, 0.0)
    """
    fs_Hz = positive("fs_Hz", fs_Hz)
    n_ring = max(1, int(round(positive("ring_s", ring_s) * fs_Hz)))
    n_lead = int(round(lead_s * fs_Hz))
    nfft = 1 << int(math.ceil(math.log2(4 * (n_ring + n_lead))))
    h = np.fft.irfft(response(np.fft.rfftfreq(nfft, 1.0 / fs_Hz)), nfft)
    return np.concatenate((h[nfft - n_lead:], h[:n_ring])), n_lead


#: numpy >= 2 transforms into a given array (no fresh, page-faulting allocation per block).
_FFT_HAS_OUT = "out" in inspect.signature(np.fft.rfft).parameters


def _aligned_empty(shape, dtype=float) -> np.ndarray:
    """An uninitialised array starting on a 64-byte boundary: the SIMD loops of numpy's
    arithmetic then take the same path (and round the same way) every run."""
    dtype = np.dtype(dtype)
    n = int(np.prod(shape))
    raw = np.empty(n * dtype.itemsize + 64, dtype=np.uint8)
    start = (-raw.ctypes.data) % 64
    return raw[start: start + n * dtype.itemsize].view(dtype).reshape(shape)


def _raise_mmap_threshold(nbytes: int) -> None:
    """Let the C allocator reuse blocks of up to ``nbytes`` (capped at 32 MiB by glibc) instead of
    mapping fresh pages for each: glibc serves a malloc above its mmap threshold (128 KiB at
    first) by a new mapping, and raises the threshold to the size of such a block once one is
    freed (mallopt(3), "dynamic mmap threshold"). The FFTs' scratch (numpy's pocketfft mallocs
    a few MB per 2^18-point transform) otherwise page-faulted anew in every call when nothing
    larger had been freed before: 2 400 faults per block, the filter's transforms 2x slower.
    Elsewhere a no-op (an unused allocation)."""
    block = np.empty(nbytes, dtype=np.uint8)
    del block


def _rfft_into(a: np.ndarray, n: int, out: np.ndarray) -> np.ndarray:
    """``np.fft.rfft(a, n, axis=-1)`` written into ``out``."""
    if _FFT_HAS_OUT:
        return np.fft.rfft(a, n, axis=-1, out=out)
    out[...] = np.fft.rfft(a, n, axis=-1)
    return out


def _irfft_into(a: np.ndarray, n: int, out: np.ndarray) -> np.ndarray:
    """``np.fft.irfft(a, n, axis=-1)`` written into ``out``."""
    if _FFT_HAS_OUT:
        return np.fft.irfft(a, n, axis=-1, out=out)
    out[...] = np.fft.irfft(a, n, axis=-1)
    return out


class ResponseFilter:
    """Streaming linear filtering of one signal by several analog responses (overlap-save).

    Chunks of any length go in; each :meth:`process` returns, per response, the filtered
    samples ready so far, and :meth:`finish` the rest, so the outputs have exactly the
    input's length and equal those of filtering the whole record (zero before and after,
    as :func:`weighted_signal`'s zero padding). :meth:`blocks` and :meth:`final_blocks` hand each
    block's outputs over without copying them (for a caller that consumes them at once). Memory:
    the input block, its spectrum, a product and one output block per response, reused (2^18
    samples or 8× the taps each).

    Parameters
    ----------
    responses : sequence of (taps, lead)
        From :func:`impulse_response`; all with the same ``lead``.

    Examples
    --------
    >>> from tyrelab.vehicle.comfort.iso2631 import weighted_signal, weighting_response
    >>> fs = 200.0
    >>> f = ResponseFilter([impulse_response(lambda f: weighting_response(f, "Wk"), fs, 20.0)])
    >>> x = np.sin(2 * np.pi * 4.0 * np.arange(12000) / fs)
    >>> parts = [f.process(x[:5000])[0], f.process(x[5000:])[0], f.finish()[0]]
    >>> y = np.concatenate(parts)
    >>> y.size, bool(np.allclose(y, weighted_signal(x, fs, "Wk"), atol=1e-4))
    (12000, True)
    """

    def __init__(self, responses):
        leads = {lead for _, lead in responses}
        if len(leads) != 1:
            raise ValueError("responses must share one lead")
        self._lead = leads.pop()
        self._taps = [np.asarray(t, dtype=float) for t, _ in responses]
        n_taps = {t.size for t in self._taps}
        if len(n_taps) != 1:
            raise ValueError("responses must have the same number of taps")
        self._n_taps = n_taps.pop()
        # one power-of-two FFT per block of new samples (at least 2^18 and 8× the taps): a
        # power of two is 1.6× faster than the 5-smooth length next to it, and a block as long
        # as the FFT allows spends the fewest FFTs per sample
        self._nfft = 1 << max(18, int(math.ceil(math.log2(8 * self._n_taps))))
        self._hist = self._n_taps - 1
        self._block = self._nfft - self._hist
        # the input in place: the last n_taps - 1 samples before the block (zeros before the
        # record), then the block as it fills; no concatenation per chunk
        self._buf = _aligned_empty(self._nfft)
        self._buf[: self._hist] = 0.0
        self._fill = self._hist
        self._skip = self._lead  # outputs before t = 0 of the record
        # the transforms' arrays, reused block after block (a fresh 2 MB array costs its page faults,
        # more than the arithmetic on it): the block's spectrum, a product, one output per response
        bins = self._nfft // 2 + 1
        self._spectrum = _aligned_empty(bins, complex)
        self._product = _aligned_empty(bins, complex)
        self._outputs = [_aligned_empty(self._nfft) for _ in self._taps]
        self._spectra: dict[int, list[np.ndarray]] = {}
        _raise_mmap_threshold(32 * self._nfft)

    def _transform(self, n: int, nfft: int) -> list[np.ndarray]:
        """The outputs of the buffer's first ``n`` samples (the history and ``n - hist`` new ones)
        by an ``nfft``-point overlap-save step (views of the filter's arrays when ``nfft`` is the
        block's)."""
        spectra = self._spectra.get(nfft)
        if spectra is None:
            spectra = []
            for t in self._taps:
                s = _aligned_empty(nfft // 2 + 1, complex)
                spectra.append(_rfft_into(t, nfft, s))
            self._spectra[nfft] = spectra
        full = nfft == self._nfft
        bins = nfft // 2 + 1
        b = _rfft_into(self._buf[:n], nfft, self._spectrum if full else _aligned_empty(bins, complex))
        product = self._product if full else _aligned_empty(bins, complex)
        out = []
        for j, s in enumerate(spectra):
            np.multiply(b, s, out=product)
            y = _irfft_into(product, nfft, self._outputs[j] if full else _aligned_empty(nfft))
            out.append(y[self._hist: n])
        if self._skip:
            k = min(self._skip, out[0].size)
            out = [o[k:] for o in out]
            self._skip -= k
        return out

    def _shift(self) -> None:
        if self._hist:
            self._buf[: self._hist] = self._buf[self._fill - self._hist: self._fill]
        self._fill = self._hist

    def blocks(self, chunk):
        """Take the next chunk; yield, per completed block, one array per response (the new
        outputs). The arrays are the filter's: valid until the next block (copy to keep them)."""
        chunk = np.asarray(chunk, dtype=float)
        i = 0
        while i < chunk.size:
            k = min(chunk.size - i, self._nfft - self._fill)
            self._buf[self._fill: self._fill + k] = chunk[i: i + k]
            self._fill += k
            i += k
            if self._fill == self._nfft:
                out = self._transform(self._nfft, self._nfft)
                self._shift()
                yield out

    def final_blocks(self):
        """Yield the remaining outputs (the record continued by zeros for the lead), as :meth:`blocks`."""
        if self._lead:
            yield from self.blocks(np.zeros(self._lead))
            self._lead = 0
        if self._fill > self._hist:
            n = self._fill
            nfft = 1 << int(math.ceil(math.log2(n)))
            out = self._transform(n, nfft)
            self._shift()
            yield out

    def _joined(self, blocks) -> list[np.ndarray]:
        parts = [[o.copy() for o in outputs] for outputs in blocks]
        if not parts:
            return [np.empty(0) for _ in self._taps]
        return [np.concatenate([p[j] for p in parts]) if len(parts) > 1 else parts[0][j] for j in range(len(self._taps))]

    def process(self, chunk) -> list[np.ndarray]:
        """Filter the next chunk; returns one array per response, the outputs ready so far (they lag
        the input by up to a block)."""
        return self._joined(self.blocks(chunk))

    def finish(self) -> list[np.ndarray]:
        """The remaining output samples (the record continued by zeros for the lead)."""
        return self._joined(self.final_blocks())
