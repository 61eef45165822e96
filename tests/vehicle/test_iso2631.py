"""ISO 2631-1 weightings and exposure measures."""

import math

import numpy as np
import pytest
from scipy import signal

from tyrelab.vehicle import iso2631

# ISO 2631-1:1997 Table 3 (W_k) and field notes
WK = {0.5: 0.418, 1.0: 0.482, 4.0: 0.967, 6.3: 1.054, 8.0: 1.036, 16.0: 0.768, 80.0: 0.132}
WD = {1.0: 1.011, 2.0: 0.890, 4.0: 0.512, 8.0: 0.253}


@pytest.mark.parametrize("f,w", sorted(WK.items()))
def test_wk_within_01_dB(f, w):
    got = abs(iso2631.weighting_response(f, "Wk"))
    assert abs(20 * math.log10(got / w)) < 0.1


@pytest.mark.parametrize("f,w", sorted(WD.items()))
def test_wd_within_01_dB(f, w):
    assert abs(20 * math.log10(abs(iso2631.weighting_response(f, "Wd")) / w)) < 0.1


def test_weighted_sine_and_bilinear():
    fs = 200.0
    t = np.arange(int(60 * fs)) / fs
    a = 2.0 * np.sin(2 * np.pi * 4.0 * t)
    aw = iso2631.weighted_rms(a, fs, "Wk")
    assert aw == pytest.approx(math.sqrt(2) * 0.967, rel=0.01)
    b, den = iso2631.weighting_ba("Wk", 1000.0)
    w, h = signal.freqz(b, den, worN=[4.0], fs=1000.0)
    assert abs(h[0]) == pytest.approx(0.967, rel=0.01)


def test_vdv_crest_a8():
    fs = 100.0
    aw = np.ones(int(8 * 3600 * fs))[:1000]
    assert iso2631.vibration_dose_value(aw, fs) == pytest.approx((1000 / fs) ** 0.25)
    assert iso2631.crest_factor(np.array([1.0, -1.0, 1.0, -1.0])) == pytest.approx(1.0)
    assert iso2631.daily_exposure_a8(1.0, 2.0) == pytest.approx(0.5)
    r = iso2631.evaluate(0.8 * np.sin(2 * np.pi * 6.3 * np.arange(6000) / fs), fs, "z")
    assert r["exceeds_action"] and not r["exceeds_limit"]
    assert iso2631.EU_ACTION_A8_M_S2 == 0.5 and iso2631.EU_LIMIT_A8_M_S2 == 1.15
