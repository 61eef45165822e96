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

__all__ = ["PRESSURE_COLUMNS", "method_note", "variant_name", "variant_decimals", "scenario_sections", "SECTION_TABLES", "variant_labels", "swept_columns", "variant_rows", "RideFigure", "scenario_figures",
           "surface_edge_note"]


def variant_name(front_bar: float, rear_bar: float, swept: dict) -> str:
    """A variant's name: its tyre pressures and swept values (``"1.6/1.2 bar, mass_kg=500"``)."""
    parts = [f"{front_bar:g}/{rear_bar:g} bar"]
    parts += [f"{k.rpartition('.')[2]}={v:g}" for k, v in swept.items()]
    return ", ".join(parts)


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
        out.append(RideFigure(
            "hours_heatmap", f"Hours to the EU action value (the worst speed of each variant) over {keys[0]} and "
                             f"{keys[1]}" + (" (other swept keys: the lowest hours)" if len(keys) > 2 else "") + ".",
            "hours_heatmap", (table, keys[0], keys[1]), {"x_label": _axis_label(keys[0]), "y_label": _axis_label(keys[1])}))
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
            f"stops at v × {n_max:g} cycles/m ({v / 3.6 * n_max:.1f} Hz at {v:g} km/h); above it only the "
            f"estimate's leakage is left, more than six decades down (not drawn).")
