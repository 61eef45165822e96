"""Profiles (ISO 8608, slatted stand-in) and tyre enveloping (thesis §1.5)."""

import math

import numpy as np
import pytest

from tyrelab.vehicle import enveloping as ev
from tyrelab.vehicle import profiles as pr


def test_iso8608_class_mean_spectrum():
    p = pr.iso8608_track("D", seed=1, length_m=2000.0, dx_m=0.05)
    n, g = pr.profile_spectrum(p.left_m, p.dx_m, segment_m=51.2)
    band = (n > 0.05) & (n < 1.0)
    ratio = g[band] / (1024e-6 * (n[band] / 0.1) ** -2)
    assert np.exp(np.mean(np.log(ratio))) == pytest.approx(1.0, rel=0.15)
    assert pr.ISO8608_CLASS_G0_M3["A"] == pytest.approx(16e-6)  # means, not the 32e-6 upper bound


def test_seeded_and_labelled():
    a, b = pr.slatted_track(seed=7), pr.slatted_track(seed=7)
    np.testing.assert_array_equal(a.left_m, b.left_m)
    assert "stand-in" in a.label and a.meta["stand_in"]
    assert a.meta["slat_x_m"].size == 625 and a.x_m[-1] == pytest.approx(100.0)
    assert not np.allclose(a.left_m, a.right_m)
    surf = pr.slat_surface(a)
    gaps = (np.abs(((a.x_m % 0.16) - 0.08)) > 0.045)
    assert np.all(surf[gaps] == 0.0)


def test_moving_averages_analytic():
    dx = 0.01
    x = np.arange(0, 20, dx)
    lam = 2.0
    h = np.sin(2 * np.pi * x / lam)
    L = 0.5
    out = ev.fixed_footprint(h, dx, L)
    gain = np.sinc(L / lam)  # rectangular average of a sine
    mid = slice(200, -200)
    assert np.max(np.abs(out[mid])) == pytest.approx(gain, rel=0.02)
    step = (x > 10).astype(float)
    tap = ev.tapered_moving_average(step, dx, L)
    assert tap[0] == 0 and tap[-1] == pytest.approx(1.0)
    assert np.all(np.diff(tap) >= -1e-12)
    assert tap[int(10 / dx)] == pytest.approx(0.5, abs=0.02)


def test_rigid_tread_band_bridges_gap_and_climbs_step():
    dx = 0.005
    x = np.arange(0, 4, dx)
    h = np.zeros_like(x)
    h[(x > 1.0) & (x < 1.08)] = -0.05  # 80 mm gap
    e = ev.rigid_tread_band(h, dx, 0.74)
    r = 0.74
    assert e.min() == pytest.approx(-(r - math.sqrt(r * r - 0.04**2)), abs=2e-4)
    s = ev.rigid_tread_band((x > 2).astype(float) * 0.05, dx, r)
    assert s.max() == pytest.approx(0.05) and s[0] == 0.0


def test_contact_length():
    assert ev.contact_length(0.742, 0.047) == pytest.approx(2 * math.sqrt(2 * 0.742 * 0.047 - 0.047**2))
