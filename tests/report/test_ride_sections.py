"""The report's Ride page and ``tyrelab ride``'s page draw the same figures from the same code
(issue 23, deliver 6): each variant named with its tyres and natural frequencies, the hours to
the action value over two swept keys (or a sentence why there is none), per-axis a_w against
speed, and the seat PSD and transmissibility per axis."""

from __future__ import annotations

import re

import duckdb
import pytest

from tests.scenarios import scenario_text
from tyrelab.report import pages, ride_page, site
from tyrelab.report.ride_sections import scenario_sections
from tyrelab.scenario_io import load_scenario
from tyrelab.stages import simulate
from tyrelab.vehicle import ride

ISO_A = 'kind = "iso8608"\nclass = "C"\nlength_m = 24\nseed = 2'
TWO_KEYS = "[sweep]\nfront_pressures_bar = [1.6, 2.0]\nrear_pressures_bar = [1.2, 0.9]\n"


def _write(tmp_path, name, body):
    path = tmp_path / f"{name}.toml"
    path.write_text(body)
    return path


def _report(tmp_path, files) -> str:
    """The Ride page of a build whose simulate stage ran ``files``: the stage's own tasks and
    tables, stored in a warehouse file, rendered by the report."""
    outputs = [simulate.scenario_task(item) for item in simulate.scenario_items([(str(f), "raw") for f in files])]
    assert all("error" not in o for o in outputs), outputs
    scenarios, results, _ = simulate.collect_scenarios(outputs)
    spectra, trans = simulate.collect_scenario_spectra(outputs)
    db = tmp_path / "warehouse.duckdb"
    with duckdb.connect(str(db)) as con:
        for name, df in (("ride_scenarios", scenarios), ("ride_results", results), ("ride_spectra", spectra),
                         ("ride_transmissibility", trans)):
            con.register("df", df)
            con.execute(f'CREATE TABLE "{name}" AS SELECT * FROM df')
            con.unregister("df")
    page = next(p for p in pages.registered() if p.slug == "ride")
    site.build_site(db, tmp_path / "site", tmp_path, pages=[page])
    return (tmp_path / "site" / "ride.html").read_text(encoding="utf-8")


def _figure(html: str, fig_id: str) -> str:
    m = re.search(rf'<figure id="{fig_id}">(.*?)</figure>', html, re.S)
    assert m, f"no figure {fig_id}"
    return m.group(1)


def _svg(html: str) -> str:
    return re.search(r"<svg.*?</svg>", html, re.S).group(0)


def test_a_two_key_sweep_gets_the_hours_heatmap_and_per_axis_psd_as_tyrelab_ride_draws_them(tmp_path):
    body = scenario_text(ISO_A, "[6, 12]", name="two keys") + TWO_KEYS  # two speeds: a line per variant
    path = _write(tmp_path, "two", body)
    html = _report(tmp_path, [path])
    # each variant named (pressures), with its tyres and natural frequencies
    table = re.search(r'<table class="variants">.*?</table>', html, re.S).group(0)
    for label in ("1.6/1.2 bar", "1.6/0.9 bar", "2/1.2 bar", "2/0.9 bar"):
        assert f"<td class=\"text\">{label}</td>" in table
    assert "bounce (Hz)" in table and "pitch (Hz)" in table and "front K per tyre" in table
    heatmap = _figure(html, "scenario-1-hours-heatmap")
    assert "hours to the action value" in heatmap and "front tyre pressure, bar" in heatmap
    psd = _figure(html, "scenario-1-seat-psd")
    assert "seat vertical" in psd and "seat fore-aft" in psd and "(1.6/1.2 bar)" in psd
    trans = _figure(html, "scenario-1-seat-transmissibility")
    assert "vertical" in trans and "fore-aft (per m)" in trans
    aw = _figure(html, "scenario-1-aw-speed")
    assert "a_wz (vertical, W_k)" in aw and "1.4 a_wx (fore-aft, W_d)" in aw and "2/0.9 bar" in aw
    assert "No heatmap" not in html
    # one implementation: tyrelab ride's page of the same scenario holds the same drawings
    results = ride.ride_sweep(load_scenario(path))
    figs = {f["name"]: f for f in ride_page.figures(results)}
    for name in ("hours_heatmap", "seat_psd", "seat_transmissibility", "aw_speed"):
        assert figs[name]["svg"].strip() == _svg(_figure(html, f"scenario-1-{name.replace('_', '-')}")), name


def test_without_a_two_key_sweep_a_sentence_says_why_there_is_no_heatmap(tmp_path):
    single = _write(tmp_path, "single", scenario_text(ISO_A, "[8]", name="single"))
    one_key = _write(tmp_path, "one", scenario_text(ISO_A, "[8]", name="one key")
                     + "[sweep]\nrear_pressures_bar = [0.9, 1.2]\n")
    html = _report(tmp_path, [single, one_key])
    assert "scenario-1-hours-heatmap" not in html and "scenario-2-hours-heatmap" not in html
    first = re.search(r'id="scenario-1-no-hours-heatmap">(.*?)</p>', html, re.S).group(1)
    assert first.startswith("No heatmap of the hours to the action value: this scenario runs one variant")
    second = re.search(r'id="scenario-2-no-hours-heatmap">(.*?)</p>', html, re.S).group(1)
    assert "sweeps one key (rear_pressure_bar)" in second and "needs two" in second
    for k in (1, 2):  # the rest of the section is there
        assert f'id="scenario-{k}-seat-psd"' in html and f'id="scenario-{k}-aw-speed"' in html


@pytest.mark.parametrize("kind", ["psd", "transmissibility"])
def test_an_axis_without_motion_says_so_in_its_panel(kind):
    import numpy as np
    import pandas as pd

    from tyrelab.report import ride_figures

    f = np.geomspace(0.5, 10, 20)
    if kind == "psd":
        df = pd.DataFrame({"speed_km_h": 10.0, "frequency_Hz": f, "seat_vertical_psd_m2_s4_per_Hz": 1 / f,
                           "seat_longitudinal_psd_m2_s4_per_Hz": 0.0})
        svg = ride_figures.seat_psd(df)
    else:
        df = pd.DataFrame({"speed_km_h": 10.0, "frequency_Hz": f, "seat_vertical": 1 / f, "seat_longitudinal_per_m": 0.0})
        svg = ride_figures.seat_transmissibility(df)
    assert "zero throughout" in svg and "10 km/h" in svg


def test_sections_of_an_empty_build_are_none():
    import pandas as pd

    assert scenario_sections(*(pd.DataFrame() for _ in range(4))) == []


def test_a_sweep_of_scenario_keys_names_the_variant_of_every_speed_row(tmp_path):
    """Without it the rows of ``--set tractor.mass_kg=4500,5000`` read the same pressures twice."""
    path = _write(tmp_path, "keys", scenario_text(ISO_A, "[8]", name="keys"))
    results = ride.ride_sweep(load_scenario(path), sets={"tractor.mass_kg": [4500, 5000]}, with_spectra=False)
    text = ride_page.format_table(ride.result_json(results), width=None)  # --wide: one line per row
    rows = [line for line in text.splitlines() if "mass_kg=" in line]
    assert len(rows) == 2 and "tractor.mass_kg=4500" in rows[0] and "tractor.mass_kg=5000" in rows[1]
    text = ride_page.format_table(ride.result_json(results))  # 100 columns: blocks that repeat the variant
    rows = [line for line in text.splitlines() if "mass_kg=" in line]
    assert len(rows) >= 4 and all("=4500" in r for r in rows[0::2]) and all("=5000" in r for r in rows[1::2])
    assert max(map(len, text.splitlines())) <= 100
    html = ride_page.render_page(results)
    table = re.search(r"<h2>Seat vibration per speed</h2>.*?</table>", html, re.S).group(0)
    assert "<th>variant</th>" in table and '<td class="text">tractor.mass_kg=5000</td>' in table


def test_a_legend_too_long_to_fit_says_how_many_lines_it_leaves_out():
    import pandas as pd

    from tyrelab.report import ride_figures

    rows = [{"speed_km_h": v, "a_wz_m_s2": 0.1 * v + i / 100, "a_wx_m_s2": 0.05 * v, "variant": f"variant {i}"}
            for i in range(20) for v in (4.0, 8.0)]
    svg = ride_figures.aw_against_speed(pd.DataFrame(rows), 8.0)
    assert "9 more lines (see the table)" in svg and "variant 10" in svg and "variant 11" not in svg


def test_a_model_without_fore_aft_motion_is_not_drawn_as_measured_zeros():
    """Issue 47: the Ride page drew MF698T's 1.4 a_wx (no fore-aft element: 0 throughout) as a line of zeros."""
    import pandas as pd

    from tyrelab.report import ride_figures

    rows = [{"speed_km_h": v, "a_wz_m_s2": 0.1 * v, "a_wx_m_s2": 0.05 * v if name == "modern" else 0.0, "variant": name}
            for name in ("modern", "MF698T") for v in (4.0, 8.0)]
    svg = ride_figures.aw_against_speed(pd.DataFrame(rows), 8.0)
    assert "not drawn, no motion on this axis in its model" in svg and svg.count("MF698T") >= 2  # legend and note
    alone = ride_figures.aw_against_speed(pd.DataFrame([r for r in rows if r["variant"] == "MF698T"]), 8.0)
    assert "zero throughout" in alone
