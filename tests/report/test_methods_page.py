"""Issue 34: the report's page of rig methods and directions."""

import numpy as np
import pandas as pd

from tyrelab.report import pages
from tyrelab.report.methods_page import frf_figure


def test_the_page_is_registered_and_says_when_there_is_nothing_to_show(small_report):
    assert "rig-methods" in [p.slug for p in pages.registered()]
    html = (small_report.build / "reports" / "rig-methods.html").read_text(encoding="utf-8")
    assert "every run is a vertical stepped sine" in html and "docs/rig_methods.html" in html


def test_frf_figure_draws_h_k_c_and_coherence_with_the_fitted_model():
    f = np.arange(1.0, 8.01, 0.25)
    w = 2 * np.pi * f
    z = 3e5 + 1j * w * 2e3
    frf = pd.DataFrame({"frequency_Hz": f, "apparent_mass_real_kg": (-z / w**2).real,
                        "apparent_mass_imag_kg": (-z / w**2).imag, "stiffness_N_per_m": z.real,
                        "damping_N_s_per_m": z.imag / w, "stiffness_u_N_per_m": 3e3, "damping_u_N_s_per_m": 50.0,
                        "coherence": 0.97, "in_fit": (f > 1) & (f < 8)})
    svg = frf_figure(frf, {"model": "kelvin_voigt", "stiffness_N_per_m": 3e5, "damping_N_s_per_m": 2e3,
                           "series_damping_N_s_per_m": np.nan})
    assert svg.startswith("<svg") and "coherence" in svg and "kelvin" in svg
    assert frf_figure(frf.head(0), {}) is None


def test_stepped_figure_draws_a_directions_stepped_sine_runs():
    """Issue 44: a lateral tyre's stepped-sine runs get their own K(f), C(f) figure."""
    from tyrelab.report.methods_page import stepped_figure

    runs = pd.DataFrame({"excitation_frequency_Hz": [2.0, 3.0, 4.0], "stiffness_N_per_m": [2.5e5, 2.6e5, 2.6e5],
                         "damping_N_s_per_m": [1.5e3, 1.4e3, 1.5e3], "stiffness_ci95_low_N_per_m": 2.4e5,
                         "stiffness_ci95_high_N_per_m": 2.7e5, "damping_ci95_low_N_s_per_m": 1.2e3,
                         "damping_ci95_high_N_s_per_m": 1.8e3, "coherence": 0.99, "qc_ok": [True, True, False],
                         "apparent_mass_real_kg": -1e3, "apparent_mass_imag_kg": -50.0})
    svg = stepped_figure(runs)
    assert svg.startswith("<svg") and "stiffness K(f)" in svg and "QC flagged" in svg
    assert stepped_figure(runs.head(0)) is None
