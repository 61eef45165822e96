"""Report figures are small, deterministic, self-contained inline SVG."""

import re

import numpy as np
import pandas as pd

from tyrelab.report import figures
from tests.synthetic import spring_damper_recording


def _results():
    rows = []
    for t in ("T1", "T2"):
        for v in (0.0, 10.0):
            for p in (0.83, 1.38, 1.93):
                rows.append({"tyre_id": t, "speed_km_h": v, "pressure_bar": p, "kind": "measurement", "qc_ok": True,
                             "stiffness_kN_per_m": 200 + 150 * p - 5 * v, "damping_kN_s_per_m": 3 - 0.1 * v})
    return pd.DataFrame(rows)


def test_svg_is_deterministic_inline_and_offline():
    a = figures.stiffness_vs_pressure(_results())
    b = figures.stiffness_vs_pressure(_results())
    assert a == b
    assert a.startswith("<svg") and a.rstrip().endswith("</svg>")
    assert "<?xml" not in a and "<!DOCTYPE" not in a and "<metadata>" not in a
    urls = set(re.findall(r"https?://[^\"' )]+", a))
    assert urls <= {"http://www.w3.org/2000/svg", "http://www.w3.org/1999/xlink"}
    assert "T2" in a  # text kept as text (svg.fonttype none)
    assert len(a) < 40_000


def test_figures_return_none_without_data():
    empty = pd.DataFrame()
    assert figures.stiffness_vs_speed(empty) is None
    assert figures.profile_spectra(empty) is None
    assert figures.natural_frequencies(empty) is None
    assert figures.acceleration_spectra(empty) is None


def test_run_spectra_recovers_the_stiffness_at_the_excitation():
    rec = spring_damper_recording(250e3, 2000.0, frequency_Hz=4.0, duration_s=16.0)
    sp = figures.run_spectra(rec, axle_mass_kg=600.0, sample_rate_Hz=256.0)
    at = sp.iloc[(sp["frequency_Hz"] - 4.0).abs().argmin()]
    w = 2 * np.pi * 4.0
    assert np.isclose(at["dynamic_stiffness_kN_per_m"], np.hypot(250.0, w * 2.0), rtol=0.02)
    assert at["coherence"] > 0.99
    svg = figures.run_drilldown(rec, sp, 4.0, 250.0)
    assert "excitation 4 Hz" in svg and "K = 250 kN/m" in svg


def test_ride_page_draws_a_w_per_axis_one_line_per_scenario():
    from tyrelab.report import ride_figures

    rows = [{"scenario": name, "speed_km_h": v, "a_wz_m_s2": 0.1 * v, "a_wx_m_s2": 0.05 * v, "a_wy_m_s2": 0.02 * v,
             "is_nominal": nominal} for name in ("tractor A", "tractor B") for v in (4.0, 8.0) for nominal in (True, False)]
    svg = ride_figures.ride_aw_axes_speed(pd.DataFrame(rows))
    assert svg is not None
    for title in ("a_wz (vertical", "1.4 a_wx (fore-aft", "1.4 a_wy (lateral"):
        assert title in svg, title
    assert "tractor A" in svg and "tractor B" in svg
    assert ride_figures.ride_aw_axes_speed(pd.DataFrame()) is None
