"""One number rule on the ride page (issue 38): a quantity the model does not have is not shown as a
measured 0; a fraction always to 0.001; hours never reached say so; a missing value is "–"."""

import re

from tests.scenarios import scenario_text, write
from tyrelab.report import ride_page
from tyrelab.report.ride_sections import answer
from tyrelab.scenario_io import load_scenario
from tyrelab.vehicle import ride


def test_pitch_plane_page_has_no_lateral_columns_and_fractions_have_three_decimals(tmp_path):
    res = ride.ride(load_scenario(write(tmp_path, scenario_text(speeds="[6, 12]"))), with_spectra=False)
    doc = ride.result_json([res])
    text = ride_page.format_table(doc)
    assert "a_wy" not in text.split("a_wz: W_k")[0]  # the table; the footnote still explains a_wy
    html = ride_page.render_page([res], doc)
    table = re.search(r'<table class="speeds">.*?</table>', html, re.S).group(0)
    assert "a_wy" not in table and "lift off fraction" in table
    lift = [c for c in re.findall(r"<td>([^<]*)</td>", table) if c in ("0", "0.000")]
    assert lift and set(lift) == {"0.000"}


def test_answer_says_never_and_dash():
    import pandas as pd

    t = pd.DataFrame({"speed_km_h": [4.0], "front_pressure_bar": 1.6, "rear_pressure_bar": 1.2, "a8_m_s2": [0.0],
                      "a8_axis": [None], "hours_to_eav": [float("inf")], "hours_to_elv": [float("nan")],
                      "verdict": ["below action value"]})
    row = answer(t)["rows"][0]
    assert row["hours_to_eav"] == float("inf") and row["hours_to_elv"] is None and row["a8_axis"] is None


def test_a_lift_off_below_the_printed_precision_is_a_bound_not_a_zero(tmp_path):
    res = ride.ride(load_scenario(write(tmp_path, scenario_text(speeds="[6, 12]"))), with_spectra=False)
    doc = ride.result_json([res])
    doc["speeds"][0]["lift_off_fraction_front"] = 2.2e-5  # as a nonlinear row that lifted a tyre briefly
    doc["speeds"][1]["lift_off_probability_rear"] = 3e-6  # as a spectral row
    doc["speeds"][0]["lift_off_probability_rear"] = 0.25
    rows = ride_page.format_table(doc, width=None).split("  a_wz: W_k")[0].splitlines()  # --wide: a row a line
    assert "< 1e-3" in rows[-2] and "0.2500" in rows[-2] and "< 1e-4" in rows[-1]
    html = ride_page.render_page([res], doc)
    table = re.search(r'<table class="speeds">.*?</table>', html, re.S).group(0)
    assert "&lt; 1e-3" in table and "&lt; 1e-4" in table


def test_a_sweeps_tyres_and_frequencies_are_the_scenarios_own_variant_and_say_so(tmp_path):
    """Issue 47: the page's Tyres and Natural-frequency sections showed the first variant (1.2 bar here)
    while its verdict and spectra are the nominal one's (1.6 bar, the scenario's)."""
    sc = load_scenario(write(tmp_path, scenario_text(speeds="[8]")))
    results = ride.ride_sweep(sc, front_pressures_bar=[1.2, 1.6], with_spectra=False)
    html = ride_page.render_page(results)
    tyres = re.search(r"<h2>Tyres</h2>.*?</table>", html, re.S).group(0)
    front = re.search(r'<td class="text">front</td><td class="text">[^<]*</td><td>([^<]*)</td>', tyres).group(1)
    assert front == "1.6" and "of the scenario's own values (1.6/1.2 bar)" in __import__("html").unescape(html)
    freq = re.search(r"<h2>Natural frequencies</h2>\s*<p>bounce ([0-9.]+) Hz", html).group(1)
    nominal = next(r for r in results if r.nominal)
    assert abs(float(freq) - nominal.natural_frequencies_Hz["bounce"]) < 0.01
