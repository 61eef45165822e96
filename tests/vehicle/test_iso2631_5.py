"""ISO 2631-5:2018 as the standard applies it (issue 44, Deliver 7): the regime of a recording from
its signal, the 0.01–80 Hz band, offsets removed — checked against closed forms worked by hand from
the standard's formulae, not against tyrelab's own functions.

The reference values below use Formula 1 written out here with the printed (ω, ζ) and the
magnitude of the analog second-order Butterworth band edges; a sinusoid of amplitude A at f Hz,
n whole cycles, has one positive response peak per cycle, A |H(f)| |B(f)|, so Formula 3 gives
``D_z = 1.07 A |H(f)| |B(f)| n^(1/6)``; its time below ``−g`` is ``T (π − 2 asin(g / A')) / 2π``.
"""

import math

import numpy as np
import pytest

from tyrelab.exposure import assess, Task
from tyrelab.vehicle import iso2631_5, measured_ride

#: ISO 2631-5:2018 Formula 1 as printed: the complex zero and the six complex pole pairs (ω rad/s, ζ).
ZERO = (34.0, 0.35)
POLES = ((31.0, 0.21), (230.0, 0.88), (260.0, 0.80), (320.0, 0.40), (380.0, 0.75), (420.0, 0.65))
G = 9.80665


def spine(f_Hz: float) -> complex:
    s = 2j * math.pi * f_Hz
    w, z = ZERO
    h = 1 + 2 * z * s / w + (s / w) ** 2
    for w, z in POLES:
        h /= 1 + 2 * z * s / w + (s / w) ** 2
    return h


def band(f_Hz: float) -> complex:
    """Second-order Butterworth edges at 0.01 Hz (high-pass) and 80 Hz (low-pass)."""
    s = 2j * math.pi * f_Hz
    wh, wl = 2 * math.pi * 0.01, 2 * math.pi * 80.0
    return s * s / (s * s + math.sqrt(2) * wh * s + wh * wh) * wl * wl / (s * s + math.sqrt(2) * wl * s + wl * wl)


def sine(amplitude, f_Hz, fs_Hz, duration_s, offset=0.0):
    t = np.arange(int(round(duration_s * fs_Hz))) / fs_Hz
    return offset + amplitude * np.sin(2 * np.pi * f_Hz * t)


@pytest.mark.parametrize("f_Hz, fs_Hz", [(4.0, 256.0), (2.0, 256.0), (6.25, 500.0), (2.5, 100.0)])
def test_the_dose_of_a_sinusoid_is_formula_3_worked_by_hand(f_Hz, fs_Hz):
    """The response's samples, A |H B| sin(2π k f/fs + φ), φ = arg(H B), have the same largest one in
    every cycle (fs a multiple of f): the crest as sampled. What is left is the start — the
    spine's ring-in (about 1 s) and the 0.01 Hz high-pass's (a sine switched on has low-frequency
    content of about f_c/f its amplitude, decaying with 1/(ζω) = 23 s): 1e-4 of D_z at most over
    600 s, half as much over twice the record."""
    A, T = 3.0, 600.0
    g = spine(f_Hz) * band(f_Hz)
    k = np.arange(int(round(fs_Hz / f_Hz)))
    crest = float(np.max(np.sin(2 * np.pi * k * f_Hz / fs_Hz + np.angle(g))))
    expected = 1.07 * A * abs(g) * crest * (f_Hz * T) ** (1 / 6)
    dz = iso2631_5.acceleration_dose(sine(A, f_Hz, fs_Hz, T), fs_Hz)
    assert dz == pytest.approx(expected, rel=2e-4)
    longer = iso2631_5.acceleration_dose(sine(A, f_Hz, fs_Hz, 2 * T), fs_Hz) / (expected * 2 ** (1 / 6))
    assert abs(longer - 1) <= 0.6 * abs(dz / expected - 1) + 1e-6
    # the streamed analysis of a recording (a DC-coupled 1 g, removed) gives the same; at 100 Hz the
    # response is still 0.14 at Nyquist, and the streamed filter's taps (0.2 s before t = 0) leave 1e-3
    streamed = measured_ride.analyse_signals({"seat_z_m_s2": sine(A, f_Hz, fs_Hz, T, offset=G)}, fs_Hz)
    assert streamed.dz_m_s2 == pytest.approx(dz, rel=1e-4 if fs_Hz >= 256 else 2e-3)


def test_the_time_without_seat_contact_of_a_sinusoid_is_worked_by_hand():
    """12 m/s² at 3.7 Hz (not a divisor of fs, so the samples counted below −g average out; each
    of the 2 crossings per cycle is off by at most one sample)."""
    A, f, fs, T = 12.0, 3.7, 256.0, 300.0
    a = A * abs(band(f))
    expected_s = T * (math.pi - 2 * math.asin(G / a)) / (2 * math.pi)
    r = iso2631_5.contact_regime(sine(A, f, fs, T, offset=G), fs)
    assert r.regime == "loss_of_contact" and r.model == "clause 5" and r.dz_applies
    assert r.loss_of_contact_s == pytest.approx(expected_s, abs=2 * f * T / fs / 10)
    assert r.down_peak_m_s2 == pytest.approx(A, rel=0.01)
    streamed = measured_ride.analyse_signals({"seat_z_m_s2": sine(A, f, fs, T, offset=G)}, fs).contact
    # the same recursive filters, chunk after chunk: a sample at the threshold at most
    assert streamed.regime == r.regime and streamed.loss_of_contact_s == pytest.approx(r.loss_of_contact_s, abs=2 / fs)
    assert streamed.down_peak_m_s2 == pytest.approx(r.down_peak_m_s2, rel=1e-9)


def test_a_seated_recording_says_the_standard_assigns_annex_a():
    fs = 256.0
    x = sine(5.0, 4.0, fs, 60.0, offset=G)
    r = iso2631_5.contact_regime(x, fs)
    assert r.regime == "seated" and r.model == "Annex A" and not r.dz_applies and r.loss_of_contact_s == 0.0
    assert r.down_peak_m_s2 == pytest.approx(5.0, rel=0.01)
    doc = measured_ride.analyse_signals({"seat_z_m_s2": x}, fs).to_json()
    assert (doc["dz_regime"], doc["dz_model"], doc["dz_applies"]) == ("seated", "Annex A", False)
    assert doc["dz_m_s2"] > 0  # clause 5's dose is still reported, marked
    no_seat_z = measured_ride.analyse_signals({"seat_x_m_s2": x}, fs).to_json()
    assert no_seat_z["dz_regime"] is None and math.isnan(no_seat_z["loss_of_contact_s"])


def _shocks(fs, duration_s, rng):
    """Half-sine shocks of 8 m/s², 0.1 s, every 2 s on 0.3 m/s² of noise."""
    n = int(duration_s * fs)
    x = 0.3 * rng.standard_normal(n)
    width = int(0.1 * fs)
    for k in range(int(5 * fs), n - width, int(2 * fs)):
        x[k:k + width] += 8.0 * np.sin(np.pi * np.arange(width) / width)
    return x


def test_a_residual_offset_does_not_raise_the_dose():
    """The offset a recording's analysis removes is its first chunk's mean; an offset of 0.2 m/s²
    arriving after it (a drift, a tilt) passes the spine's unity gain at 0 Hz into every later peak
    (+2.3 % of D_z here without the band) — the band's 0.01 Hz high-pass takes it out within a minute."""
    fs, T = 100.0, 1800.0
    x = _shocks(fs, T, np.random.default_rng(4)) + G
    chunk = int(60 * fs)
    step = x + 0.2 * (np.arange(x.size) >= chunk)
    base = measured_ride.analyse_signals({"seat_z_m_s2": x}, fs, chunk_rows=chunk)
    shifted = measured_ride.analyse_signals({"seat_z_m_s2": step}, fs, chunk_rows=chunk)
    assert shifted.dz_m_s2 == pytest.approx(base.dz_m_s2, rel=2e-4)
    assert shifted.contact.regime == base.contact.regime == "seated"
    # what the band prevents: the spine response alone, the same offsets removed
    n = 2 * x.size
    spine = iso2631_5.spine_response(np.fft.rfftfreq(n, 1 / fs))
    dose = lambda a: iso2631_5.dose_from_peaks(iso2631_5.positive_peaks(  # noqa: E731
        np.fft.irfft(np.fft.rfft(a - a[:chunk].mean(), n) * spine, n)[: x.size]))
    assert dose(step) / dose(x) - 1 > 0.01
    # an offset over the whole record is the mean: removed exactly
    assert iso2631_5.acceleration_dose(x + 0.2, fs) == pytest.approx(iso2631_5.acceleration_dose(x, fs), rel=1e-9)


def test_the_exposure_json_states_the_regime(tmp_path):
    import pandas as pd

    fs = 256.0
    x = sine(12.0, 3.7, fs, 30.0, offset=G)
    path = tmp_path / "bumpy.parquet"
    pd.DataFrame({"time_s": np.arange(x.size) / fs, "seat_z_m_s2": x}).to_parquet(path)
    doc = assess([Task("bumpy", path, 1.0)])
    assert doc["dz_regime"] == "loss_of_contact" and doc["dz_applies"] is True and doc["loss_of_contact_s"] > 0
