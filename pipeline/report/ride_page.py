"""Outputs of ``tyrelab ride``: the JSON document, a text table and a self-contained HTML page.

:func:`write_outputs` writes ``ride.json`` and ``ride.html`` atomically into a
folder; the page inlines its style and SVG figures and carries no time stamp,
so the same scenario gives the same bytes.
"""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

from .. import __version__, io
from ..vehicle.ride import RideResult, result_json
from . import ride_figures as rf
from .render import environment
from .tables import significant_decimals

__all__ = ["SPEED_COLUMNS", "format_table", "figures", "psd_edge_note", "render_page", "write_outputs", "dumps", "variants",
           "variant_label", "swept_keys"]

#: Columns of the per-speed table (text and HTML), in order.
SPEED_COLUMNS = ["speed_km_h", "front_pressure_bar", "rear_pressure_bar", "a_wz_m_s2", "expected_a_wz_m_s2",
                 "a_wx_m_s2", "expected_a_wx_m_s2", "a_wy_m_s2", "expected_a_wy_m_s2", "a_v_m_s2", "vdv_m_s1_75", "crest_factor",
                 "lift_off_fraction_front", "lift_off_fraction_rear", "a8_m_s2", "hours_to_eav", "hours_to_elv",
                 "verdict", "simulation"]

_SHORT = {"speed_km_h": "km/h", "front_pressure_bar": "Pf bar", "rear_pressure_bar": "Pr bar", "a_wz_m_s2": "a_wz",
          "expected_a_wz_m_s2": "(exp.)", "a_wx_m_s2": "a_wx", "expected_a_wx_m_s2": "(exp.)", "a_wy_m_s2": "a_wy",
          "expected_a_wy_m_s2": "(exp.)", "a_v_m_s2": "a_v",
          "vdv_m_s1_75": "VDV", "crest_factor": "CF", "lift_off_fraction_front": "lift F",
          "lift_off_fraction_rear": "lift R", "a8_m_s2": "A(8)", "hours_to_eav": "h->EAV", "hours_to_elv": "h->ELV",
          "verdict": "verdict", "simulation": "simulation"}


def dumps(doc: dict) -> str:
    """JSON text of a ride document (indented, keys in insertion order, ends with a newline)."""
    return json.dumps(doc, indent=2, ensure_ascii=False, allow_nan=False) + "\n"


def _rows(doc: dict) -> list[dict]:
    blocks = doc.get("sweep") or [doc]
    return [row for b in blocks for row in b["speeds"]]


def format_table(doc: dict) -> str:
    """A plain-text summary of a ride document (what ``--format table`` prints)."""
    lines = [f"{doc['name']}", f"  track: {doc['track']}; daily exposure {doc['hours_per_day']:g} h"]
    for axle in ("front", "rear"):
        t = doc["tyres"][axle]
        lines.append(f"  {axle:5s} {t['size']} at {t['pressure_bar']:g} bar: K = {t['stiffness_kN_per_m']:.1f} kN/m "
                     f"({t['stiffness_source']}), C = {t['damping_kN_s_per_m']:.2f} kN s/m ({t['damping_source']})")
    nf, nodal = doc["natural_frequencies_Hz"], doc["nodal_points_m"]
    lines.append(f"  bounce {nf['bounce']:.2f} Hz (node {nodal['bounce']:+.2f} m ahead of CG), "
                 f"pitch {nf['pitch']:.2f} Hz (node {nodal['pitch']:+.2f} m)" if nodal["bounce"] is not None
                 else f"  bounce {nf['bounce']:.2f} Hz, pitch {nf['pitch']:.2f} Hz")
    for w in doc.get("warnings", []):
        lines.append(f"  warning: {w}")
    df = pd.DataFrame(_rows(doc))
    cols = [c for c in SPEED_COLUMNS if c in df and (c not in ("front_pressure_bar", "rear_pressure_bar")
                                                      or "sweep" in doc)]
    show = df[cols].copy()
    for c in cols:
        if c in ("speed_km_h", "front_pressure_bar", "rear_pressure_bar"):
            show[c] = show[c].map(lambda v: f"{v:g}")
        elif c not in ("verdict", "simulation"):
            show[c] = show[c].map(lambda v: "inf" if v is None else f"{v:.3g}" if abs(v) >= 100 else f"{v:.3f}")
    show.columns = [_SHORT[c] for c in cols]
    lines.append(show.to_string(index=False))
    lines.append("  a_w in m/s² (a_wz W_k, a_wx and a_wy W_d; exp. = frequency-domain expectation); VDV m/s^1.75; "
                 "A(8) = max(1.4 a_wx, 1.4 a_wy, a_wz) sqrt(T/8 h)")
    return "\n".join(lines) + "\n"


def variant_label(r: RideResult) -> str:
    """A variant's name: its tyre pressures and swept values."""
    parts = [f"{r.tyres['front'].pressure_bar:g}/{r.tyres['rear'].pressure_bar:g} bar"]
    parts += [f"{k.rpartition('.')[2]}={v:g}" for k, v in r.variant.items()]
    return ", ".join(parts)


def _speeds(results: list[RideResult]) -> pd.DataFrame:
    """Every variant's speed rows with its label and swept values (pressures under their scenario keys)."""
    frames = []
    for r in results:
        df = r.speeds.copy()
        df["variant"] = variant_label(r)
        df["tyres.front.pressure_bar"] = r.tyres["front"].pressure_bar
        df["tyres.rear.pressure_bar"] = r.tyres["rear"].pressure_bar
        for k, v in r.variant.items():
            df[k] = v
        frames.append(df)
    return pd.concat(frames, ignore_index=True)


def swept_keys(results: list[RideResult]) -> list[str]:
    """The keys that take more than one value across the variants (pressures first)."""
    df = _speeds(results)
    keys = ["tyres.front.pressure_bar", "tyres.rear.pressure_bar"] + list(results[0].variant)
    return [k for k in dict.fromkeys(keys) if k in df and df[k].nunique() > 1]


def variants(results: list[RideResult]) -> list[dict]:
    """Per variant: label, tyre stiffness (first speed) and natural frequencies, for the page."""
    return [{"label": variant_label(r),
             "front_stiffness_kN_per_m": float(r.tyres["front"].stiffness_kN_per_m[0]),
             "rear_stiffness_kN_per_m": float(r.tyres["rear"].stiffness_kN_per_m[0]),
             "modes": {k: float(v) for k, v in r.natural_frequencies_Hz.items()}} for r in results]


def figures(results: list[RideResult]) -> list[dict]:
    """The page's figures (caption + inline SVG)."""
    first = results[0]
    hours = first.scenario.exposure.hours_per_day
    speeds = _speeds(results)
    keys = swept_keys(results)
    out = [
        {"caption": "Weighted r.m.s. at the seat against speed per axis, one line per variant (dotted: the "
                    "frequency-domain expectation), with the levels that reach the EU action (EAV) and limit (ELV) "
                    f"values in {hours:g} h.",
         "svg": rf.aw_against_speed(speeds, hours)},
    ]
    if len(keys) >= 2:
        out.append({"caption": f"Hours to the EU action value (the worst speed of each variant) over {keys[0]} and "
                               f"{keys[1]}" + (f" (other swept keys: the lowest hours)" if len(keys) > 2 else "") + ".",
                    "svg": rf.hours_heatmap(speeds, keys[0], keys[1])})
    elif len(results) > 1 and "front_pressure_bar" in speeds:
        out.append({"caption": "Highest-axis a_w against rear pressure, one line per front pressure.",
                    "svg": rf.aw_against_pressure(speeds)})
    out += [
        {"caption": f"Seat acceleration PSD (0.1 Hz bandwidth) per speed and axis ({variant_label(first)}). "
                    + psd_edge_note(first),
         "svg": rf.seat_psd(first.spectra)},
        {"caption": "Seat transmissibility per axis from ground input (every wheel in phase with the wheelbase delay; "
                    f"lateral: left/right in anti-phase; no enveloping) ({variant_label(first)}).",
         "svg": rf.seat_transmissibility(first.transmissibility)},
    ]
    return out


def psd_edge_note(result: RideResult) -> str:
    """Why the PSD curves drop to nothing at a frequency that grows with speed (the track's band edge).

    A track has no unevenness shorter than its shortest wavelength, so at speed ``v`` the ground
    input ends at ``v × n_max`` (``n_max`` in cycles/m); above it only the estimate's leakage is
    left, more than six decades down, which the figure does not draw.
    """
    import inspect

    from ..vehicle import profiles

    surface = result.scenario.surface
    if surface.kind != "iso8608":
        return ("Each curve stops where the track's unevenness stops: above v / (shortest wavelength of the "
                "profile) the ground gives no input, and what is left is more than six decades down (not drawn).")
    n_max = inspect.signature(profiles.iso8608_track).parameters["n_max_cycles_per_m"].default
    v = min(result.scenario.exposure.speeds_km_h)
    return (f"Each curve drops where the track's unevenness ends: a generated ISO 8608 track holds wavelengths "
            f"down to {1 / n_max:.2f} m ({n_max:g} cycles/m, the standard's band), so at speed v the ground input "
            f"stops at v × {n_max:g} cycles/m ({v / 3.6 * n_max:.1f} Hz at {v:g} km/h); above it only the "
            f"estimate's leakage is left, more than six decades down (not drawn).")


def render_page(results: list[RideResult], doc: dict | None = None) -> str:
    """The self-contained HTML page of a ride (no time stamp)."""
    doc = doc or result_json(results)
    rows = _rows(doc)
    cols = [c for c in SPEED_COLUMNS if c in rows[0] and (c not in ("front_pressure_bar", "rear_pressure_bar")
                                                          or "sweep" in doc)]
    # one number format per column (decimals by the column's magnitude: 604.649 and 12.418 h read 605, 12)
    decimals = {c: significant_decimals([r[c] for r in rows if isinstance(r[c], float)]) for c in cols
                if any(isinstance(r[c], float) for r in rows)}
    return environment().get_template("ride.html.j2").render(
        r=doc, description=results[0].scenario.description, columns=cols, rows=rows, figures=figures(results),
        variants=variants(results), three_d=results[0].scenario.tractor.three_d, version=__version__, decimals=decimals)


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
