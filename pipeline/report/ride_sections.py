"""A ride's figures and variant table, from tables: one implementation for ``tyrelab ride``'s page
and the report's Ride page (issue 23, deliver 6).

Both pages hold the same data in the same layout — the ``ride_results`` rows of a scenario
(:func:`tyrelab.vehicle.ride.results_table`; the simulate stage writes them to the warehouse) and
one variant's seat PSD and transmissibility per axis (``RideResult.spectra``/``transmissibility``;
the stage's ``ride_spectra``/``ride_transmissibility``) — and pass them here (compute → result →
plot): :func:`variant_rows` names each variant with its tyres and natural frequencies,
:func:`scenario_figures` says which figures a scenario gets (per-axis a_w against speed, the hours
to the action value over two swept keys or the sentence why there is none, the seat PSD and
transmissibility per axis) as :class:`RideFigure` objects that either page draws
(:mod:`tyrelab.report.ride_figures`). Imports no matplotlib: the report draws its figures in
worker processes.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import pandas as pd

from ..vehicle.spectral_ride import LIFT_OFF_PROBABILITY_LIMIT, primary_rows
from ..units import km_h_to_m_s

__all__ = ["PRESSURE_COLUMNS", "VERDICT_ORDER", "AXIS_WORDS", "answer", "split_warnings", "warning_groups", "method_note", "variant_name", "variant_decimals", "scenario_sections", "SECTION_TABLES", "variant_labels", "swept_columns", "variant_rows", "RideFigure", "scenario_figures",
           "surface_edge_note"]


def variant_name(front_bar: float, rear_bar: float, swept: dict) -> str:
    """A variant's name: its tyre pressures and swept values, each by its whole key
    (``"1.6/1.2 bar, tractor.mass_kg=500"``: ``tyres.front.…`` and ``tyres.rear.…`` differ)."""
    parts = [f"{front_bar:g}/{rear_bar:g} bar"]
    parts += [f"{k}={v:g}" for k, v in swept.items()]
    return ", ".join(parts)


#: The Directive's verdicts, best to worst (a withheld verdict, "no verdict: …", sorts before them).
VERDICT_ORDER = ("below action value", "above action value", "above limit value")
#: What each seat axis is, for a reader.
AXIS_WORDS = {"x": "fore-aft", "y": "lateral", "z": "vertical"}


def answer(table: pd.DataFrame) -> dict:
    """What a ride page states first, from one scenario's ``ride_results`` rows: per speed of the
    variant at the scenario's own values (``is_nominal``, else the first variant) A(8), the axis
    that governs it (``a8_axis``), the hours to the action and limit values and the verdict.

    Returns
    -------
    dict
        ``rows`` (per speed, in speed order: ``speed_km_h``, ``a8_m_s2``, ``a8_axis``,
        ``hours_to_eav``, ``hours_to_elv``, ``verdict``; a missing value None), ``verdict`` (the
        worst), ``worst_speeds_km_h`` (the speeds with that verdict), ``axes`` (governing axis ->
        its speeds), ``variant`` (the variant's name) and ``working_speed_km_h``.

    Examples
    --------
    >>> t = pd.DataFrame({"speed_km_h": [8.0, 4.0], "front_pressure_bar": 1.6, "rear_pressure_bar": 1.2,
    ...                   "a8_m_s2": [0.6, 0.1], "a8_axis": ["x", "z"], "hours_to_eav": [5.6, 200.0],
    ...                   "hours_to_elv": [29.4, 1000.0], "verdict": ["above action value", "below action value"]})
    >>> a = answer(t)
    >>> a["verdict"], a["worst_speeds_km_h"], a["axes"], [r["speed_km_h"] for r in a["rows"]]
    ('above action value', [8.0], {'z': [4.0], 'x': [8.0]}, [4.0, 8.0])
    """
    t = primary_rows(table)  # a spectral row where there is one, not the time row simulated beside it
    if "is_nominal" in t and t["is_nominal"].astype(bool).any():
        t = t[t["is_nominal"].astype(bool)]
    labels = variant_labels(t)
    t = t[labels == labels.iloc[0]].sort_values("speed_km_h", kind="stable")

    def value(row, col):
        v = row.get(col)
        return None if v is None or (isinstance(v, float) and pd.isna(v)) else v

    rows = [{c: value(r, c) for c in ("speed_km_h", "a8_m_s2", "a8_axis", "hours_to_eav", "hours_to_elv", "verdict")}
            for r in t.to_dict(orient="records")]
    rank = {v: k for k, v in enumerate(VERDICT_ORDER)}
    worst = max((r["verdict"] for r in rows if r["verdict"] in rank), key=rank.get, default=None)
    axes: dict = {}
    for r in rows:
        if r["a8_axis"]:
            axes.setdefault(r["a8_axis"], []).append(r["speed_km_h"])
    working = t["working_speed_km_h"].iloc[0] if "working_speed_km_h" in t and len(t) else None
    from .tables import significant_decimals

    finite = lambda col: [r[col] for r in rows if isinstance(r[col], (int, float)) and abs(r[col]) != float("inf")]
    return {"rows": rows, "decimals": {"a8": significant_decimals(finite("a8_m_s2")),
                                       "hours": significant_decimals(finite("hours_to_eav") + finite("hours_to_elv"))}, "verdict": worst, "worst_speeds_km_h": [r["speed_km_h"] for r in rows if r["verdict"] == worst],
            "axes": axes, "variant": labels.iloc[0] if len(labels) else "",
            "working_speed_km_h": None if working is None or pd.isna(working) else float(working)}


def split_warnings(text) -> list[str]:
    """The warnings of a ``ride_scenarios.warnings`` cell (joined by ``"; "``, which a warning may hold
    too): split where the next one starts with its subject (``tyres.rear:``, ``8 km/h:``).

    Examples
    --------
    >>> split_warnings("tyres.front: a (x; y); tyres.rear: b; 8 km/h: c")
    ['tyres.front: a (x; y)', 'tyres.rear: b', '8 km/h: c']
    >>> split_warnings(None)
    []
    """
    import re

    text = "" if text is None or (isinstance(text, float) and pd.isna(text)) else str(text)
    return [w for w in re.split(r"; (?=(?:[A-Za-z_][\w.]*|[\d.]+ km/h): )", text) if w.strip()]


def warning_groups(warnings) -> list[tuple[str, list[str]]]:
    """Warnings grouped by what they are about: the front tyre, the rear tyre, the rest (in that
    order, empty groups left out), each without its ``tyres.front:`` prefix.

    Examples
    --------
    >>> warning_groups(["tyres.rear: a", "track: b", "tyres.front: c", "tyres.rear: d"])
    [('front tyre', ['c']), ('rear tyre', ['a', 'd']), ('scenario', ['track: b'])]
    """
    groups = {"front tyre": [], "rear tyre": [], "scenario": []}
    for w in warnings:
        for axle in ("front", "rear"):
            if w.startswith(f"tyres.{axle}:"):
                groups[f"{axle} tyre"].append(w.partition(":")[2].strip())
                break
        else:
            groups["scenario"].append(w)
    return [(k, v) for k, v in groups.items() if v]


#: The ``ride_results`` columns of the tyre pressures, and the scenario keys they are.
PRESSURE_COLUMNS = {"front_pressure_bar": "tyres.front.pressure_bar", "rear_pressure_bar": "tyres.rear.pressure_bar"}


def _swept_values(variant: str) -> dict:
    """``{key: value}`` of a ``ride_results.variant`` text (``"implement.mass_kg=500, cab.x=1"``)."""
    pairs = [p.partition("=") for p in str(variant or "").split(", ") if "=" in p]
    return {k: float(v) for k, _, v in pairs}


def variant_labels(table: pd.DataFrame) -> pd.Series:
    """The variant name of every row of a ``ride_results`` table (tyre pressures and swept values, as
    :func:`tyrelab.report.ride_page.variant_label`)."""
    variant = table["variant"] if "variant" in table else pd.Series("", index=table.index)
    return pd.Series([variant_name(f, r, _swept_values(v)) for f, r, v in
                      zip(table["front_pressure_bar"], table["rear_pressure_bar"], variant.fillna(""))],
                     index=table.index, dtype=object)


def swept_columns(table: pd.DataFrame) -> list[str]:
    """The columns of one scenario's ``ride_results`` rows that take more than one value: the tyre
    pressures first, then the swept scenario keys (columns named ``section.key``; a swept pressure
    key is its pressure column)."""
    keys = [c for c in PRESSURE_COLUMNS if c in table]
    keys += [c for c in table.columns if "." in c and c not in PRESSURE_COLUMNS.values()]
    return [k for k in keys if table[k].nunique() > 1]


def _axis_label(column: str) -> str:
    return {"front_pressure_bar": "front tyre pressure, bar", "rear_pressure_bar": "rear tyre pressure, bar"}.get(
        column, column)


def _mode_names(table: pd.DataFrame) -> list[str]:
    """The natural modes of a scenario's rows, in order (from ``modes_Hz``: ``"bounce 2.436; pitch 3.7"``)."""
    names = [part.split()[0] for text in table.get("modes_Hz", pd.Series(dtype=object)).dropna()
             for part in str(text).split("; ") if part.strip()]
    return [n for n in dict.fromkeys(names) if f"{n}_Hz" in table]


def variant_rows(table: pd.DataFrame) -> list[dict]:
    """Per variant of one scenario's ``ride_results`` rows, in their order: ``label``, the tyre
    stiffness and damping per tyre at the slowest speed (``front_stiffness_kN_per_m``, ``rear_…``,
    ``front_damping_kN_s_per_m``, ``rear_…``), ``modes``
    (name -> natural frequency, Hz) and ``hours_to_eav`` (at the worst speed; None: never reached)."""
    table = primary_rows(table)
    t = table.assign(_label=variant_labels(table))
    modes = _mode_names(t)
    out = []
    for label, g in t.groupby("_label", sort=False):
        first = g.sort_values("speed_km_h", kind="stable").iloc[0]
        hours = pd.to_numeric(g["hours_to_eav"], errors="coerce").min() if "hours_to_eav" in g else float("nan")
        out.append({"label": label, "front_stiffness_kN_per_m": float(first["front_stiffness_kN_per_m"]),
                    "rear_stiffness_kN_per_m": float(first["rear_stiffness_kN_per_m"]),
                    "front_damping_kN_s_per_m": float(first["front_damping_kN_s_per_m"]),
                    "rear_damping_kN_s_per_m": float(first["rear_damping_kN_s_per_m"]),
                    "modes": {m: float(first[f"{m}_Hz"]) for m in modes},
                    "hours_to_eav": None if pd.isna(hours) else float(hours)})
    return out


def variant_decimals(rows: list[dict]) -> dict:
    """Decimals of the variant table's quantities (``stiffness``, ``damping``, ``frequency``, ``hours``): three
    significant digits of each one's median (:func:`tyrelab.report.tables.significant_decimals`)."""
    from .tables import significant_decimals

    return {"stiffness": significant_decimals([v[f"{ax}_stiffness_kN_per_m"] for v in rows for ax in ("front", "rear")]),
            "damping": significant_decimals([v[f"{ax}_damping_kN_s_per_m"] for v in rows for ax in ("front", "rear")]),
            "frequency": significant_decimals([f for v in rows for f in v["modes"].values()]),
            "hours": significant_decimals([v["hours_to_eav"] for v in rows if v["hours_to_eav"] is not None])}


@dataclass(frozen=True)
class RideFigure:
    """One figure of a ride's page: ``tyrelab.report.ride_figures.<function>(*args, **kwargs)``, or,
    when there is nothing to draw (``function`` None), the sentence ``note`` saying why.

    ``tyrelab ride``'s page draws it at once, the report's Ride page through its figure cache.
    """

    name: str
    caption: str
    function: str | None = None
    args: tuple = ()
    kwargs: dict = field(default_factory=dict)
    note: str = ""

    def draw(self) -> str | None:
        """The SVG (None without a function or when the function has nothing to plot)."""
        if not self.function:
            return None
        from . import ride_figures  # matplotlib: imported only where a figure is drawn

        return getattr(ride_figures, self.function)(*self.args, **self.kwargs)


def _heatmap_note(keys: list[str], n_variants: int) -> str:
    if n_variants < 2:
        return ("No heatmap of the hours to the action value: this scenario runs one variant. A scenario whose "
                "[sweep] (or tyrelab ride --set KEY=V1,V2,…) varies two keys, e.g. front_pressures_bar and "
                "rear_pressures_bar, gets a heatmap of the hours over those two keys.")
    swept = f"one key ({keys[0]})" if keys else "no key whose values differ between the variants"
    return (f"No heatmap of the hours to the action value: this scenario sweeps {swept}; a heatmap "
            "needs two (add a second key to its [sweep], or tyrelab ride --set KEY=V1,V2,…). The hours per "
            "variant are in the table above.")


def scenario_figures(table: pd.DataFrame, spectra: pd.DataFrame, transmissibility: pd.DataFrame,
                     hours_per_day: float, psd_note: str = "", shown: str = "") -> list[RideFigure]:
    """The figures of one scenario, for ``tyrelab ride``'s page and the report's Ride page alike.

    Parameters
    ----------
    table : DataFrame
        The scenario's ``ride_results`` rows (:func:`tyrelab.vehicle.ride.results_table`): every
        variant and speed.
    spectra, transmissibility : DataFrame
        Seat PSD and transmissibility per axis and speed of one variant
        (:attr:`~tyrelab.vehicle.ride.RideResult.spectra`, ``…transmissibility``; the simulate
        stage's ``ride_spectra``, ``ride_transmissibility``).
    hours_per_day : float
        Daily exposure time of the EAV/ELV levels drawn.
    psd_note : str
        Why the PSD curves end (:func:`surface_edge_note`).
    shown : str
        The name of the variant of ``spectra`` (:func:`variant_labels`).

    Returns
    -------
    list of RideFigure
        Per-axis a_w against speed (one line per variant), the hours to the action value over two
        swept keys (else a sentence why not; a pressure sweep of one key: a_w against pressure),
        and the seat PSD and transmissibility per axis.
    """
    table = primary_rows(table).dropna(axis=1, how="all")
    keys = swept_columns(table)
    n_variants = variant_labels(table).nunique()
    out = [RideFigure("aw_speed", "Weighted r.m.s. at the seat against speed per axis, one line per variant (dotted: "
                      "the frequency-domain expectation), with the levels that reach the EU action (EAV) and limit "
                      f"(ELV) values in {hours_per_day:g} h.", "aw_against_speed",
                      (table.assign(variant=variant_labels(table)), hours_per_day))]
    if len(keys) >= 2:
        speeds = sorted(float(v) for v in table["speed_km_h"].unique())
        working = (float(table["working_speed_km_h"].iloc[0]) if "working_speed_km_h" in table
                   and float(table["working_speed_km_h"].iloc[0]) in speeds else speeds[(len(speeds) - 1) // 2])
        labels = {"x_label": _axis_label(keys[0]), "y_label": _axis_label(keys[1])}
        other = " (other swept keys: the lowest hours)" if len(keys) > 2 else ""
        out.append(RideFigure(
            "hours_heatmap", f"Hours to the EU action value over {keys[0]} and {keys[1]} at the working speed, "
                             f"{working:g} km/h ([exposure] working_speed_km_h; default: the middle speed){other}.",
            "hours_heatmap", (table, keys[0], keys[1]), {**labels, "speed_km_h": working}))
        rest = [v for v in speeds if v != working]
        if rest:
            out.append(RideFigure(
                "hours_heatmaps", "The same at the other speeds (one colour scale).",
                "hours_heatmaps", (table, keys[0], keys[1], rest), labels))
    else:
        out.append(RideFigure("hours_heatmap", "Hours to the action value over two swept keys",
                              note=_heatmap_note(keys, n_variants)))
        if n_variants > 1 and any(k in PRESSURE_COLUMNS for k in keys):
            out.append(RideFigure("aw_pressure", "Highest-axis a_w against rear pressure, one line per front pressure.",
                                  "aw_against_pressure", (table,)))
    of = f" ({shown})" if shown else ""
    spectra = spectra.dropna(axis=1, how="all")
    transmissibility = transmissibility.dropna(axis=1, how="all")
    psd = RideFigure("seat_psd", f"Seat acceleration PSD (0.1 Hz bandwidth) per speed and axis{of}. " + psd_note,
                     "seat_psd", (spectra,))
    trans = RideFigure("seat_transmissibility", "Seat transmissibility per axis from ground input (every wheel in "
                       "phase with the wheelbase delay; lateral: left/right in anti-phase; no enveloping)" + of + ".",
                       "seat_transmissibility", (transmissibility,))
    for fig, frame, what in ((psd, spectra, "seat PSD"), (trans, transmissibility, "seat transmissibility")):
        out.append(fig if len(frame) else RideFigure(fig.name, fig.caption, note=f"No {what} of this scenario in the "
                                                      "data (the simulate stage writes it; run it again)."))
    return out


#: The warehouse tables of the report's scenario sections (:func:`scenario_sections`), in its order.
SECTION_TABLES = ("ride_scenarios", "ride_results", "ride_spectra", "ride_transmissibility")


def _of(table: pd.DataFrame, file: str) -> pd.DataFrame:
    return table[table["file"] == file] if "file" in table else table.iloc[0:0]


def scenario_sections(scenarios: pd.DataFrame, results: pd.DataFrame, spectra: pd.DataFrame,
                      transmissibility: pd.DataFrame) -> list[dict]:
    """One section per scenario of a build (the report's Ride page), from the simulate stage's tables
    (:data:`SECTION_TABLES`; missing ones empty).

    Returns
    -------
    list of dict
        In the order of ``scenarios``: ``scenario`` (its name), ``file``, ``anchor`` (an HTML id),
        ``answer`` (:func:`answer`: verdict, governing axis and hours per speed), ``warning_groups``
        (:func:`warning_groups` of the scenario's warnings),
        ``method`` (:func:`method_note`), ``variants`` (:func:`variant_rows`), their ``decimals`` (:func:`variant_decimals`) and ``figures`` (:func:`scenario_figures` of its
        ``ride_results`` rows and the PSD and transmissibility of the variant shown there).
    """
    if not {"scenario", "file"} <= set(scenarios.columns) or not {"file", "speed_km_h"} <= set(results.columns):
        return []
    out = []
    for k, row in enumerate(scenarios.itertuples(index=False)):
        rows = _of(results, row.file).dropna(axis=1, how="all")
        if rows.empty:
            continue
        psd, trans = _of(spectra, row.file), _of(transmissibility, row.file)
        shown = variant_labels(psd.head(1)).iloc[0] if len(psd) and "front_pressure_bar" in psd else ""
        hours = float(rows["hours_per_day"].iloc[0]) if "hours_per_day" in rows else 8.0
        note = surface_edge_note(getattr(row, "surface", "iso8608"), float(rows["speed_km_h"].min()))
        variants = variant_rows(rows)
        out.append({"scenario": row.scenario, "file": row.file, "anchor": f"scenario-{k + 1}",
                    "answer": answer(rows), "hours_per_day": hours,
                    "warning_groups": warning_groups(split_warnings(getattr(row, "warnings", ""))),
                    "method": method_note(rows), "variants": variants, "decimals": variant_decimals(variants),
                    "figures": scenario_figures(rows, psd, trans, hours, note, shown)})
    return out


def method_note(table: pd.DataFrame) -> str:
    """How a scenario's ``ride_results`` rows were computed, in a sentence (``method``:
    :mod:`tyrelab.vehicle.spectral_ride`).

    Examples
    --------
    >>> method_note(pd.DataFrame({"method": ["spectral"] * 4 + ["time"]}))[:44]
    '4 rows in the frequency domain (the linear m'
    """
    methods = table["method"].value_counts() if "method" in table else pd.Series(dtype=int)
    spectral, timed = int(methods.get("spectral", 0)), int(methods.get("time", 0))
    if not spectral:
        return "Every row simulated in the time domain (one realisation of the track; expected_*: the expectation)."
    return (f"{spectral} rows in the frequency domain (the linear model's exact expectation for the track's "
            "spectrum; no MTVV or crest factor), "
            + (f"{timed} simulated beside them (the nominal variant, and speeds whose lift-off probability exceeds "
               f"{LIFT_OFF_PROBABILITY_LIMIT:g})" if timed else "none simulated") + "; the figures and the variant table read the spectral rows.")


def surface_edge_note(surface_kind: str, speed_km_h: float) -> str:
    """:func:`tyrelab.report.ride_page.psd_edge_note` from the kind of surface (``iso8608`` or a profile) and the slowest speed."""
    import inspect

    from ..vehicle import profiles

    if surface_kind != "iso8608":
        return ("Each curve stops where the track's unevenness stops: above v / (shortest wavelength of the "
                "profile) the ground gives no input, and what is left is more than six decades down (not drawn).")
    n_max = inspect.signature(profiles.iso8608_track).parameters["n_max_cycles_per_m"].default
    v = float(speed_km_h)
    return (f"Each curve drops where the track's unevenness ends: a generated ISO 8608 track holds wavelengths "
            f"down to {1 / n_max:.2f} m ({n_max:g} cycles/m, the standard's band), so at speed v the ground input "
            f"stops at v × {n_max:g} cycles/m ({km_h_to_m_s(v) * n_max:.1f} Hz at {v:g} km/h); above it only the "
            f"estimate's leakage is left, more than six decades down (not drawn).")
