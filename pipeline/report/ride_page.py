"""Outputs of ``tyrelab ride``: the JSON document, a text table and a self-contained HTML page.

:func:`write_outputs` writes ``ride.json`` and ``ride.html`` atomically into a
folder; the page inlines its style and SVG figures and carries no time stamp,
so the same scenario gives the same bytes.
"""

from __future__ import annotations

import json
import textwrap
from pathlib import Path

from .. import __version__, io
from ..vehicle.ride import RideResult, nominal_result, result_json, results_table
from .ride_sections import (AXIS_WORDS, answer, scenario_figures, surface_edge_note, variant_name, variant_rows,
                            warning_groups)
from .render import column_label, environment, format_number
from .tables import significant_decimals, uncertainty_decimals

__all__ = ["SPEED_COLUMNS", "QUANTITIES", "method_words", "number_formats", "below_precision", "format_table", "figures", "psd_edge_note", "render_page", "write_outputs", "dumps", "variants",
           "variant_label"]

#: Columns of the per-speed table (text and HTML), in order; those no row has are left out. A
#: spectral row (:mod:`tyrelab.vehicle.spectral_ride`) with a time row beside it shows the simulated
#: a_w and their difference (``simulated_*``, ``difference_*_percent``: :func:`_rows`).
SPEED_COLUMNS = ["speed_km_h", "front_pressure_bar", "rear_pressure_bar", "variant", "a_wz_m_s2", "expected_a_wz_m_s2",
                 "simulated_a_wz_m_s2", "difference_a_wz_percent",
                 "a_wx_m_s2", "expected_a_wx_m_s2", "simulated_a_wx_m_s2", "difference_a_wx_percent",
                 "a_wy_m_s2", "expected_a_wy_m_s2", "simulated_a_wy_m_s2", "difference_a_wy_percent",
                 "a_v_m_s2", "vdv_m_s1_75", "evdv_m_s1_75", "mtvv_m_s2", "crest_factor",
                 "lift_off_fraction_front", "lift_off_fraction_rear", "lift_off_probability_front",
                 "lift_off_probability_rear", "front_tyre_force_sd_N", "rear_tyre_force_sd_N",
                 "a8_m_s2", "a8_axis", "hours_to_eav", "hours_to_elv", "verdict", "simulation", "method"]

#: Per-speed columns that hold one quantity and so share one number format (:func:`number_formats`).
QUANTITIES = {
    "weighted acceleration": ("a_wz_m_s2", "expected_a_wz_m_s2", "simulated_a_wz_m_s2", "a_wx_m_s2",
                              "expected_a_wx_m_s2", "simulated_a_wx_m_s2", "a_wy_m_s2", "expected_a_wy_m_s2",
                              "simulated_a_wy_m_s2", "a_v_m_s2", "mtvv_m_s2", "a8_m_s2"),
    "difference": ("difference_a_wz_percent", "difference_a_wx_percent", "difference_a_wy_percent"),
    "vibration dose value": ("vdv_m_s1_75", "evdv_m_s1_75"),
    "crest factor": ("crest_factor",),
    "lift-off fraction": ("lift_off_fraction_front", "lift_off_fraction_rear"),
    "lift-off probability": ("lift_off_probability_front", "lift_off_probability_rear"),
    "tyre force": ("front_tyre_force_sd_N", "rear_tyre_force_sd_N"),
    "hours": ("hours_to_eav", "hours_to_elv"),
}
#: Decimals of a fraction of the record (lift-off): one sample in a thousand.
FRACTION_DECIMALS = 3
#: Decimals of a probability (a spectral row's lift-off probability); one below it is "< 1e-4".
PROBABILITY_DECIMALS = 4
#: Quantities whose value between 0 and the printed precision is shown as ``< 1e-N``, not as 0
#: (:func:`below_precision`): a tyre that left the ground for 2e-5 of the record did leave it.
SMALL_SHOWN_AS_BOUND = ("lift-off fraction", "lift-off probability")
#: Columns whose empty value (JSON null) is "never reached" (inf), not "no value".
INFINITE_WHEN_EMPTY = ("hours_to_eav", "hours_to_elv")
#: Columns shown as given (the scenario's speeds and pressures).
KEY_COLUMNS = ("speed_km_h", "front_pressure_bar", "rear_pressure_bar")
#: Narrowest column of ``--format table`` (a header wraps at word boundaries within it).
MIN_HEADER_WIDTH = 8
#: Coverage factor of the 95 % intervals of a tyre stiffness (normal; as the natural frequencies').
COVERAGE_95 = 1.96


def dumps(doc: dict) -> str:
    """JSON text of a ride document (indented, keys in insertion order, ends with a newline)."""
    return json.dumps(doc, indent=2, ensure_ascii=False, allow_nan=False) + "\n"


#: Per-speed columns shown as text.
TEXT_COLUMNS = ("variant", "a8_axis", "verdict", "simulation", "method")


def _beside(row: dict, time_rows: dict) -> dict:
    """A speed row as the table shows it: a spectral row without its ``expected_*`` (the same
    numbers) and, where the variant was simulated at that speed too, the simulated a_w per axis and
    their difference from the expectation (%), as a time row's expected/simulated pair."""
    if row.get("method") != "spectral":
        return row
    out = {k: v for k, v in row.items() if not k.startswith("expected_")}
    t = time_rows.get(row["speed_km_h"])
    if t is not None:
        for ax in ("z", "x", "y"):
            s, m = row.get(f"a_w{ax}_m_s2"), t.get(f"a_w{ax}_m_s2")
            if m is None or (ax == "y" and not s and not m):
                continue
            out[f"simulated_a_w{ax}_m_s2"] = m
            out[f"difference_a_w{ax}_percent"] = 100.0 * (m - s) / s if s else None
        out["simulation"] = f"{row['simulation']}; simulated beside: {t['simulation']}"
    return out


def _rows(doc: dict) -> list[dict]:
    """Every speed row of every variant; a sweep of scenario keys names each row's swept values
    (``variant``, as the variant table: ``mass_kg=500, cg_height_m=0.9``); a spectral row carries
    its variant's time row of the same speed beside it (:func:`_beside`)."""
    blocks = doc.get("sweep") or [doc]
    out = []
    for b in blocks:
        named = {"variant": ", ".join(f"{k}={v:g}" for k, v in b["variant"].items())} \
            if b.get("variant") else {}
        time_rows = {t["speed_km_h"]: t for t in b.get("time_domain", [])}
        out += [{**_beside(row, time_rows), **named} for row in b["speeds"]]
    return out


def method_words(rows: list[dict]) -> str:
    """How the rows of a ride were computed, in words (the page and ``--format table`` say it under
    the table): the time domain, the frequency domain, and where both stand side by side.

    Examples
    --------
    >>> method_words([{"method": "time"}])[:60]
    'Every row was simulated in the time domain: one realisation '
    """
    from ..vehicle.spectral_ride import LIFT_OFF_PROBABILITY_LIMIT

    spectral = [r for r in rows if r.get("method") == "spectral"]
    if not spectral:
        return ("Every row was simulated in the time domain: one realisation of the track (the generated random "
                "track, or the given profile); expected_* beside it is the frequency-domain expectation of the "
                "linear model for the track's spectrum.")
    n, k = len(rows), len(spectral)
    text = (f"{'Every row was' if k == n else f'{k} of {n} rows were'} computed in the frequency domain "
            "(method = spectral): the exact expectation of the linear model for the track's spectrum: a_w per axis, evdv = the estimated VDV 1.4 a_w T^¼ of ISO 2631-1 §6.3.2 (T the "
            "record a simulation would take; daily: the exposure time), A(8) and the hours to the EU values, the "
            "standard deviation of a tyre's dynamic force and the probability that a tyre leaves the ground "
            "(Gaussian: Φ(−static load / standard deviation)). MTVV and crest factor are properties of one "
            "record: a spectral row has none (–).")
    beside = [r for r in spectral if "simulated_a_wz_m_s2" in r]
    lifting = [r for r in spectral if max(r.get("lift_off_probability_front") or 0.0,
                                          r.get("lift_off_probability_rear") or 0.0) > LIFT_OFF_PROBABILITY_LIMIT]
    if beside:
        lifted = sum(1 for r in beside if r in lifting)
        text += (f" {len(beside)} of them were also simulated in the time domain (the nominal variant's"
                 + (f", and those whose lift-off probability exceeds {LIFT_OFF_PROBABILITY_LIMIT:g}: {lifted} rows, "
                    "where the linear expectation no longer holds" if lifted else "")
                 + "): the simulated a_w stands beside the expectation with their difference, the sampling error "
                   "of one random track (and the effect of tyre lift-off where the simulation is nonlinear). The "
                   "heatmap and the variant table use the spectral rows.")
    missing = [r for r in lifting if r not in beside]
    if missing:
        text += (f" {len(missing)} spectral row(s) have a lift-off probability above {LIFT_OFF_PROBABILITY_LIMIT:g} "
                 "and no simulation beside them: there tyres leave the ground and the linear expectation does not "
                 "hold (--method auto simulates them).")
    return text


#: Columns shown even where every row leaves them empty: what a spectral row has not got ("–").
SHOWN_EMPTY = ("crest_factor", "mtvv_m_s2", *INFINITE_WHEN_EMPTY)


#: Columns of a quantity the pitch-plane model does not have (its a_wy is 0 by construction): left
#: out of the table when every row has 0, rather than shown as a measured 0.
LATERAL_COLUMNS = ("a_wy_m_s2", "expected_a_wy_m_s2")


def _columns(doc: dict, rows: list[dict]) -> list[str]:
    present = {c for r in rows for c, v in r.items() if v is not None or c in SHOWN_EMPTY}
    no_lateral = all(not r.get(c) for r in rows for c in LATERAL_COLUMNS)
    return [c for c in SPEED_COLUMNS if c in present and (c not in ("front_pressure_bar", "rear_pressure_bar")
                                                          or "sweep" in doc)
            and not (no_lateral and c in LATERAL_COLUMNS)]


def number_formats(doc: dict) -> dict:
    """Decimals of each quantity of a ride document, one format per quantity wherever it is shown
    (``--format table`` and the ``--out`` page).

    Where the quantity has an uncertainty (a tyre stiffness from the formula, the natural
    frequencies' 95 % intervals) two significant digits of it decide
    (:func:`~tyrelab.report.tables.uncertainty_decimals`); else three significant digits of the
    quantity's median magnitude over every row and column that holds it
    (:func:`~tyrelab.report.tables.significant_decimals`; :data:`QUANTITIES`).

    Returns
    -------
    dict
        ``columns`` (per-speed column -> decimals; the :data:`KEY_COLUMNS` are absent: shown as
        given), ``stiffness``, ``damping``, ``frequency``, ``nodal``; and ``frequency_intervals``:
        whether a natural frequency has a 95 % interval of non-zero width.
    """
    rows = _rows(doc)
    blocks = doc.get("sweep") or [doc]
    columns = {}
    for quantity, cols in QUANTITIES.items():
        values = [r[c] for r in rows for c in cols if c in r and isinstance(r[c], (int, float))]
        for c in cols:  # a fraction of the record: to 0.001 always (a 0 is a measured none, "0.000")
            columns[c] = (FRACTION_DECIMALS if quantity == "lift-off fraction" else PROBABILITY_DECIMALS
                          if quantity == "lift-off probability" else significant_decimals(values))
    tyres = [b["tyres"][axle] for b in blocks for axle in ("front", "rear")]
    u = [COVERAGE_95 * t.get("stiffness_u_kN_per_m", 0.0) for t in tyres if t.get("stiffness_u_kN_per_m")]
    stiffness = uncertainty_decimals(u) if u else significant_decimals([t["stiffness_kN_per_m"] for t in tyres])
    ci = [(hi - lo) / 2 for b in blocks for lo, hi in filter(None, b.get("natural_frequencies_Hz_ci95", {}).values())
          if lo is not None and hi is not None and hi > lo]
    freqs = [f for b in blocks for f in b["natural_frequencies_Hz"].values() if f is not None]
    nodal = [x for b in blocks for x in b.get("nodal_points_m", {}).values() if x is not None]
    return {"columns": columns, "stiffness": stiffness,
            "damping": significant_decimals([t["damping_kN_s_per_m"] for t in tyres]),
            "frequency": uncertainty_decimals(ci) if ci else significant_decimals(freqs), "frequency_intervals": bool(ci),
            "nodal": significant_decimals(nodal)}


_BOUNDED_COLUMNS = {c for q in SMALL_SHOWN_AS_BOUND for c in QUANTITIES[q]}


def below_precision(value, decimals: int | None, column: str) -> str | None:
    """``"< 1e-N"`` for a lift-off fraction or probability above 0 that ``N`` decimals would print
    as 0 (a probability of 2.2e-5 is not "0.0000"); ``None`` for any other value or column.

    Examples
    --------
    >>> below_precision(2.2e-5, 4, "lift_off_probability_rear"), below_precision(0.0, 3, "lift_off_fraction_front")
    ('< 1e-4', None)
    >>> below_precision(0.0004, 3, "lift_off_fraction_front"), below_precision(2e-5, 3, "a_wz_m_s2")
    ('< 1e-3', None)

    See Also
    --------
    number_formats : the decimals of each column.
    """
    if column not in _BOUNDED_COLUMNS or decimals is None or not isinstance(value, (int, float)):
        return None
    return f"< 1e-{decimals}" if 0 < value < 0.5 * 10.0 ** -decimals else None


def _cell(value, decimals: int | None, column: str = "") -> str:
    if value is None:  # hours to a value the vibration never reaches; else no value (a spectral row's MTVV)
        return "inf" if column in INFINITE_WHEN_EMPTY else "–"
    if isinstance(value, str):
        return value
    bound = below_precision(value, decimals, column)
    if bound:
        return bound
    return f"{value:g}" if decimals is None else format_number(float(value), decimals=decimals)


def _html_cell(value, decimals: int | None, column: str) -> str:
    """A per-speed cell of the page: as ``format_number`` (the report's), a lift-off value below
    the printed precision as ``< 1e-N`` (:func:`below_precision`)."""
    return below_precision(value, decimals, column) or format_number(value, decimals=decimals)


def _text_table(header: list[str], cells: list[list[str]], numeric: list[bool], keys: int = 0,
                width: int | None = None) -> list[str]:
    """Lines of a plain-text table; each header is the report's column label wrapped over lines
    (its unit on the last) to the width of the column's values or longest word.

    A table wider than ``width`` is split into blocks of columns, one under the other (a blank line
    between), each repeating the first ``keys`` columns (the speed, the variant) so that every row
    can be read across; ``width=None``: one block.
    """
    wrapped = []
    for h, col in zip(header, zip(*cells) if cells else [()] * len(header)):
        name, _, unit = h.partition(" (")
        words = name.split()
        size = max([len(v) for v in col] + [len(w) for w in words] + [len(unit) + 1 if unit else 0, MIN_HEADER_WIDTH])
        lines = textwrap.wrap(name, width=size, break_long_words=False) + ([f"({unit}"] if unit else [])
        wrapped.append((size, lines))

    def block(index: list[int]) -> list[str]:
        depth = max(len(wrapped[i][1]) for i in index)
        out = []
        for d in range(depth):
            parts = []
            for i in index:
                size, lines = wrapped[i]
                text = lines[d] if d < len(lines) else ""
                parts.append(text.rjust(size) if numeric[i] else text.ljust(size))
            out.append("  ".join(parts).rstrip())
        for row in cells:
            out.append("  ".join(row[i].rjust(wrapped[i][0]) if numeric[i] else row[i].ljust(wrapped[i][0])
                                 for i in index).rstrip())
        return out

    if not wrapped:
        return []
    lead = list(range(min(keys, len(wrapped))))
    blocks, current = [], list(lead)
    used = sum(wrapped[i][0] + 2 for i in lead)
    for i in range(len(lead), len(wrapped)):
        need = wrapped[i][0] + 2
        if width is not None and len(current) > len(lead) and used + need - 2 > width:
            blocks.append(current)
            current, used = list(lead), sum(wrapped[j][0] + 2 for j in lead)
        current.append(i)
        used += need
    blocks.append(current)
    out = []
    for n, index in enumerate(blocks):
        out += ([""] if n else []) + block(index)
    return out


#: A variant name longer than this is a number in the table, with the names listed above it.
VARIANT_WIDTH = 24


def _narrow(doc: dict, rows: list[dict]) -> tuple[list[str], list[dict], list[tuple[str, str]]]:
    """The per-speed columns and rows as a narrow table shows them (``--format table``, the page): a
    tyre pressure every row shares is left out (the tyre lines above give it), and variant names
    longer than :data:`VARIANT_WIDTH` become numbers, with ``(number, name)`` of each in the legend."""
    cols = [c for c in _columns(doc, rows) if c not in ("front_pressure_bar", "rear_pressure_bar")
            or len({r.get(c) for r in rows}) > 1]
    names = list(dict.fromkeys(r["variant"] for r in rows if r.get("variant")))
    if not names or max(map(len, names)) <= VARIANT_WIDTH:
        return cols, rows, []
    number = {name: str(i) for i, name in enumerate(names, start=1)}
    return cols, [{**r, "variant": number[r["variant"]]} if r.get("variant") else r for r in rows], \
        [(number[name], name) for name in names]


def format_table(doc: dict, width: int | None = io.TEXT_WIDTH) -> str:
    """A plain-text summary of a ride document (what ``--format table`` prints): the JSON's
    quantities under the report's names (``a_wz (m/s²)``), one number format per quantity
    (:func:`number_formats`).

    No line is wider than ``width`` (``--format table``'s 100 characters; ``None``, ``--wide``: one
    line per row of every column): the text wraps, the per-speed table splits into blocks of
    columns that repeat the speed and variant (:func:`_text_table`), and variant names longer than
    :data:`VARIANT_WIDTH` are numbered in the table and listed above it.

    See Also
    --------
    number_formats : the decimals of each quantity.
    render_page : the same as an HTML page.

    Examples
    --------
    >>> doc = {"name": "demo", "track": "a track", "hours_per_day": 8, "natural_frequencies_Hz": {"bounce": 2.5},
    ...        "nodal_points_m": {}, "tyres": {a: {"size": "13.6R38", "pressure_bar": 1.2, "stiffness_kN_per_m": 350.0,
    ...        "stiffness_source": "given", "damping_kN_s_per_m": 1.0, "damping_source": "given"} for a in ("front", "rear")},
    ...        "speeds": [{"speed_km_h": 8.0, "a_wz_m_s2": 0.61, "a8_m_s2": 0.61, "a8_axis": "z", "hours_to_eav": 5.4,
    ...                    "hours_to_elv": 28.4, "verdict": "above action value", "simulation": "linear"}]}
    >>> print(format_table(doc).split("  a_wz: W_k")[0])
    demo
      track: a track; daily exposure 8 h
      front 13.6R38 at 1.2 bar: K = 350 kN/m (given), C = 1 kN s/m (given)
      rear  13.6R38 at 1.2 bar: K = 350 kN/m (given), C = 1 kN s/m (given)
      bounce 2.50 Hz
       speed      a_wz        a8  a8 axis   hours to  hours to  verdict             simulation
      (km/h)    (m/s²)    (m/s²)                 eav       elv
           8     0.610     0.610  z              5.4      28.4  above action value  linear
    <BLANKLINE>
    >>> max(len(line) for line in format_table(doc, width=60).splitlines()) <= 60
    True
    """
    fmt = number_formats(doc)
    lines = [f"{doc['name']}", f"  track: {doc['track']}; daily exposure {doc['hours_per_day']:g} h"]
    if doc.get("road_class"):
        lines.append("  ISO 8608 class (G_d(n0), waviness 2): " + "; ".join(
            f"{name.replace('_', ' ')} {c['class'] or 'not resolved'}"
            + (f" ({c['g0_m3']:.3g} m³)" if c.get("g0_m3") else "") for name, c in doc["road_class"].items()))
    for axle in ("front", "rear"):
        t = doc["tyres"][axle]
        u = COVERAGE_95 * (t.get("stiffness_u_kN_per_m") or 0.0)
        k = format_number(t["stiffness_kN_per_m"], decimals=fmt["stiffness"]) + (
            f" ± {format_number(u, decimals=fmt['stiffness'])}" if u > 0 else "")
        lines.append(f"  {axle:5s} {t['size']} at {t['pressure_bar']:g} bar: K = {k} kN/m "
                     f"({t['stiffness_source']}), C = {format_number(t['damping_kN_s_per_m'], decimals=fmt['damping'])} "
                     f"kN s/m ({t['damping_source']})")
        if t.get("lateral_stiffness_kN_per_m") is not None:  # issue 33: the lateral element
            ci = t.get("lateral_stiffness_ci95_kN_per_m")
            lines.append(f"        lateral: K_y = {format_number(t['lateral_stiffness_kN_per_m'], decimals=fmt['stiffness'])}"
                         + (f" [{format_number(ci[0], decimals=fmt['stiffness'])}, "
                            f"{format_number(ci[1], decimals=fmt['stiffness'])}]" if ci else "")
                         + f" kN/m, C_y = {format_number(t['lateral_damping_kN_s_per_m'], decimals=fmt['damping'])} kN s/m "
                         f"({t['lateral_source']})")
    if doc.get("lateral_note"):
        lines.append(f"  a_wy: {doc['lateral_note']}")
    if doc.get("a8_lateral_ci95_m_s2"):
        lines.append("  A(8) across the stand-in lateral stiffness' 95 % interval: " + "; ".join(
            f"{e['speed_km_h']:g} km/h {format_number(e['a8_m_s2'][0], decimals=2)}-"
            f"{format_number(e['a8_m_s2'][1], decimals=2)} m/s²" for e in doc["a8_lateral_ci95_m_s2"]))
    nf, nodal, ci = doc["natural_frequencies_Hz"], doc["nodal_points_m"], doc.get("natural_frequencies_Hz_ci95", {})
    parts = []
    for mode in nf:  # bounce, pitch and, in 3-D, roll and the parts' modes
        if nf[mode] is None:
            continue
        text = f"{mode} {format_number(nf[mode], decimals=fmt['frequency'])} Hz"
        if mode in doc.get("damping_ratio", {}):  # issue 42: the modes with their damping
            z = doc["damping_ratio"][mode]
            text = (f"{mode} overdamped (real root at {format_number(nf[mode], decimals=fmt['frequency'])} Hz)"
                    if z is None else text + f" ζ {format_number(z, decimals=2)}")
        lo, hi = ci.get(mode) or (None, None)
        if lo is not None and hi is not None and hi > lo:
            text += (f" [{format_number(lo, decimals=fmt['frequency'])}, "
                     f"{format_number(hi, decimals=fmt['frequency'])}]")
        elif mode in ci and fmt["frequency_intervals"]:  # a mode that cannot be followed (a warning says why)
            text += " [no interval]"
        if nodal.get(mode) is not None:
            where = "ahead of" if nodal[mode] >= 0 else "behind"
            text += f" (node {format_number(abs(nodal[mode]), decimals=fmt['nodal'])} m {where} the CG)"
        parts.append(text)
    lines.append("  " + ", ".join(parts))
    for entry in (doc.get("modes_by_speed") or [])[1:]:  # issue 42: each speed its own series dampers
        lines.append(f"  modes at {entry['speed_km_h']:g} km/h: " + ", ".join(
            f"{m} overdamped ({format_number(d['natural_frequency_Hz'], decimals=fmt['frequency'])} Hz)"
            if d["overdamped"] else f"{m} {format_number(d['natural_frequency_Hz'], decimals=fmt['frequency'])} Hz "
            f"ζ {format_number(d['damping_ratio'], decimals=2)}" for m, d in entry["modes"].items() if d is not None))
    if fmt["frequency_intervals"]:
        lines.append("  [ ]: 95 % interval from the tyre stiffness uncertainty; K ± the 95 % half-width")
    for w in doc.get("warnings", []):
        lines.append(f"  warning: {w}")
    rows = _rows(doc)
    cols, rows, legend = _narrow(doc, rows) if width is not None else (_columns(doc, rows), rows, [])
    lines += [f"  variant {n}: {name}" for n, name in legend]
    cells = [[_cell(r.get(c), fmt["columns"].get(c), c) for c in cols] for r in rows]
    numeric = [c not in TEXT_COLUMNS for c in cols]
    keys = next((i for i, c in enumerate(cols) if c not in (*KEY_COLUMNS, "variant")), len(cols))
    lines = io.fit_lines(lines, width)
    lines += _text_table([column_label(c) for c in cols], cells, numeric, keys, width)
    lines += io.fit_lines(["  a_wz: W_k-weighted, a_wx and a_wy: W_d-weighted r.m.s. (ISO 2631-1); expected: the "
                           "frequency-domain expectation; a_v: vector sum; a8 = A(8) = max(1.4 a_wx, 1.4 a_wy, a_wz) "
                           "sqrt(T/8 h); vdv: vibration dose value; inf: never reached"], width)
    lines += ["  " + line for line in textwrap.wrap(method_words(rows), min(110, (width or 112) - 2))]
    return "\n".join(lines) + "\n"


def variant_label(r: RideResult) -> str:
    """A variant's name: its tyre pressures and swept values."""
    return variant_name(r.tyres["front"].pressure_bar, r.tyres["rear"].pressure_bar, r.variant)


def variants(results: list[RideResult]) -> list[dict]:
    """Per variant: label, tyre stiffness (first speed), natural frequencies and hours to the action
    value, for the page (:func:`variant_rows` of the results' table)."""
    return variant_rows(results_table(results))


def figures(results: list[RideResult]) -> list[dict]:
    """The page's figures (caption + inline SVG, or the sentence why a figure is not drawn), those of
    :func:`scenario_figures` with the spectra of the variant at the scenario's own values
    (:func:`~tyrelab.vehicle.ride.nominal_result`; a sweep computes them for it alone:
    ``ride_sweep(with_spectra="nominal")``), named."""
    shown = nominal_result(results)
    if not len(shown.spectra):
        shown = next((r for r in results if len(r.spectra)), shown)
    name = variant_label(shown)
    if len(results) > 1:
        name = (f"the scenario's own values ({name})" if shown.nominal
                else f"{name}: the sweep does not hold the scenario's own values, so its first variant")
    specs = scenario_figures(results_table(results), shown.spectra, shown.transmissibility,
                             shown.scenario.exposure.hours_per_day, psd_edge_note(shown), name)
    return [{"name": f.name, "caption": f.caption, "svg": f.draw(), "note": f.note} for f in specs]


def psd_edge_note(result: RideResult) -> str:
    """Why the PSD curves drop to nothing at a frequency that grows with speed (the track's band edge).

    A track has no unevenness shorter than its shortest wavelength, so at speed ``v`` the ground
    input ends at ``v × n_max`` (``n_max`` in cycles/m); above it only the estimate's leakage is
    left, more than six decades down, which the figure does not draw.
    """
    return surface_edge_note(result.scenario.surface.kind, min(result.scenario.exposure.speeds_km_h))


def render_page(results: list[RideResult], doc: dict | None = None) -> str:
    """The self-contained HTML page of a ride (no time stamp)."""
    doc = doc or result_json(results)
    rows = _rows(doc)
    fmt = number_formats(doc)  # one number format per quantity, as --format table
    columns, shown, legend = _narrow(doc, rows)  # fits a 1400 px window: long variant names numbered
    # the Tyres and Natural frequencies sections: the variant at the scenario's own values, as the
    # verdict and the spectra (said), not whichever variant came first
    nominal = nominal_result(results)
    blocks = doc.get("sweep") or []
    n = blocks[results.index(nominal)] if len(blocks) == len(results) > 1 else doc
    shown_words = (f"the scenario's own values ({variant_label(nominal)})" if nominal.nominal else
                   f"the first variant ({variant_label(nominal)}: the sweep does not hold the scenario's own values)")
    return environment().get_template("ride.html.j2").render(n=n, shown_words=shown_words,
        r=doc, description=results[0].scenario.description, columns=columns, rows=shown, legend=legend,
        method_note=method_words(rows),
        figures=figures(results), variants=variants(results), three_d=results[0].scenario.tractor.three_d,
        version=__version__, decimals=fmt["columns"], fmt=fmt, answer=answer(results_table(results)),
        axis_words=AXIS_WORDS, warning_groups=warning_groups(doc.get("warnings", [])), cell=_html_cell,
        working_source=results[0].scenario.exposure.working_speed_source)


def write_outputs(results: list[RideResult], out: str | Path) -> dict[str, Path]:
    """Write ``ride.json`` and ``ride.html`` into ``out`` (created) as one set: both are replaced or neither.

    Returns
    -------
    dict
        ``json`` and ``html`` paths.
    """
    out = Path(out)
    doc = result_json(results)
    paths = {"json": out / "ride.json", "html": out / "ride.html"}
    io.write_texts_atomic({paths["json"]: dumps(doc), paths["html"]: render_page(results, doc)})  # both or neither
    return paths
