"""The hours heatmaps write every cell's number (issue 42, Cost: one artist for all of them)."""

from __future__ import annotations

import re

import numpy as np
import pandas as pd

from tyrelab.report import ride_figures as rf


def _table() -> pd.DataFrame:
    hours = {(1.0, 0.8): 0.5, (1.0, 1.2): 3.25, (1.5, 0.8): np.inf, (1.5, 1.2): 12.0, (2.0, 0.8): 7.5, (2.0, 1.2): 30.0}
    return pd.DataFrame([(f, r, s, h * (1 + s / 100)) for (f, r), h in hours.items() for s in (8.0, 12.0)],
                        columns=["front_pressure_bar", "rear_pressure_bar", "speed_km_h", "hours_to_eav"])


def _cells(svg: str) -> list[tuple[str, str]]:
    """(text, fill) of each text element of the cell numbers' group."""
    group = re.search(r'<g id="cell_numbers[^"]*">(.*?)</g>', svg, re.S)
    assert group is not None, "no cell_numbers group"
    out = []
    for style, text in re.findall(r'<text[^>]*style="([^"]*)"[^>]*>([^<]*)</text>', group.group(1)):
        fill = re.search(r"fill:\s*([^;]+)", style)
        out.append((text, fill.group(1) if fill else "#000000"))
    return out


def test_every_cell_has_its_hours_written_white_on_the_dark_ends():
    svg = rf.hours_heatmap(_table(), "front_pressure_bar", "rear_pressure_bar", speed_km_h=8.0)
    cells = _cells(svg)
    # row by row from the lowest rear pressure, as the image (origin lower); hours x 1.08
    expected = [("0.54", "#ffffff"), ("≥24", "#ffffff"), ("8.1", "#ffffff"),
                ("3.51", "#000000"), ("13", "#ffffff"), ("≥24", "#ffffff")]
    assert cells == expected


def test_the_small_multiples_write_each_speeds_numbers():
    svg = rf.hours_heatmaps(_table(), "front_pressure_bar", "rear_pressure_bar", [8.0, 12.0])
    groups = re.findall(r'<g id="cell_numbers[^"]*">(.*?)</g>', svg, re.S)
    assert len(groups) == 2
    assert [t for t, _ in _cells(svg)][:6] == ["0.54", "≥24", "8.1", "3.51", "13", "≥24"]
    assert "0.56" in groups[1] and "3.64" in groups[1]  # 12 km/h: hours x 1.12
