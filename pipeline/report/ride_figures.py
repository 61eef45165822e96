"""Ride figures (issue 13): pure functions, DataFrame in, deterministic inline SVG out.

Same conventions as :mod:`tyrelab.report.figures` (its ``to_svg``: Agg, text as
text, fixed hash salt, no dates); ``None`` when there is nothing to plot.

- :func:`seat_psd` — seat vertical acceleration PSD per speed;
- :func:`seat_transmissibility` — |seat / ground| from ground input per speed;
- :func:`aw_against_speed` — a_wz and 1.4 a_wx against speed with the levels that
  reach the EU action and limit values in the daily exposure time;
- :func:`aw_against_pressure` — a_w against rear pressure per front pressure (sweeps);
- :func:`hours_heatmap` — hours to the action value over two swept keys;
- :func:`ride_aw_speed` — the report's Ride page: ride_results per scenario;
- :func:`study_aw_speed` — the report's Ride page: the ch. 6/7 studies' ISO 2631 values.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
from matplotlib.artist import Artist
from matplotlib.font_manager import FontProperties
from matplotlib.lines import Line2D

from ..vehicle import iso2631
from .figures import MARKERS, _figure, _has, _plain_log, to_svg
from ..vehicle.spectral_ride import primary_rows

__all__ = ["seat_psd", "seat_transmissibility", "aw_against_speed", "aw_against_pressure", "ride_aw_speed",
           "study_aw_speed", "exposure_levels", "hours_heatmap", "ride_aw_axes_speed"]


def exposure_levels(hours_per_day: float) -> dict[str, float]:
    """Weighted r.m.s. (highest axis, k applied) that reaches EAV / ELV in ``hours_per_day``.

    ``a_w = value sqrt(8 h / T)`` (Directive 2002/44/EC).

    Examples
    --------
    >>> exposure_levels(8.0)
    {'EAV': 0.5, 'ELV': 1.15}
    """
    s = math.sqrt(8.0 / float(hours_per_day))
    return {"EAV": iso2631.EU_ACTION_A8_M_S2 * s, "ELV": iso2631.EU_LIMIT_A8_M_S2 * s}


def _limit_lines(ax, hours_per_day: float, label: bool = True) -> None:
    """The levels that reach EAV and ELV in ``hours_per_day``, named (``label``) in the right margin,
    where they cover no data."""
    for (name, level), style in zip(exposure_levels(hours_per_day).items(), ("--", "-")):
        ax.axhline(level, color="tab:red", ls=style, lw=0.9)
        if label:
            ax.annotate(f"{name} ({hours_per_day:g} h)", (1.015, level), xycoords=("axes fraction", "data"),
                        va="center", ha="left", fontsize=7, color="tab:red", annotation_clip=False)


def _legend_below(fig, ax, max_entries: int = 12) -> None:
    """The legend of ``ax``'s lines under the panels (never over the data), in as many columns as
    fit the figure's width."""
    handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return
    if len(handles) > max_entries:  # say what is not listed rather than drop it silently
        rest = len(handles) - (max_entries - 1)
        handles = handles[:max_entries - 1] + [Line2D([], [], lw=0)]
        labels = labels[:max_entries - 1] + [f"… {rest} more lines (see the table)"]
    chars_per_inch = 15.0  # 7-pt legend text and its marker
    width = fig.get_size_inches()[0]
    ncol = max(1, min(len(labels), int(width * chars_per_inch // (max(map(len, labels)) + 6))))
    fig.legend(handles, labels, loc="outside lower center", ncol=ncol, fontsize=7, frameon=False)


def _no_motion(ax, title: str) -> None:
    """A panel of an axis whose signal is zero throughout (e.g. fore-aft of a model without it)."""
    ax.text(0.5, 0.5, f"{title}:\nzero throughout\n(no motion on this axis\nin this model)", ha="center",
            va="center", transform=ax.transAxes, fontsize=8, color="0.35")
    ax.set_xticks([])
    ax.set_yticks([])


_AXES = (("seat_vertical_psd_m2_s4_per_Hz", "seat vertical"), ("seat_longitudinal_psd_m2_s4_per_Hz", "seat fore-aft"),
          ("seat_lateral_psd_m2_s4_per_Hz", "seat lateral"))


def seat_psd(spectra: pd.DataFrame) -> str | None:
    """Seat acceleration PSD per speed (0.1 Hz bandwidth), one panel per axis (lateral in 3-D); the
    legend under the panels; an axis that does not move says so in its panel."""
    if not _has(spectra, "speed_km_h", "frequency_Hz", "seat_vertical_psd_m2_s4_per_Hz"):
        return None
    cols = [(c, t) for c, t in _AXES if c in spectra]
    moving = {c for c, _ in cols if (spectra[c] > 0).any()}
    fig, axes = _figure(1, len(cols), size=(3.7 * len(cols), 3.3), squeeze=False)
    axes = axes[0]
    for k, (speed, g) in enumerate(spectra.groupby("speed_km_h", sort=True)):
        for ax, (col, _) in zip(axes, cols):
            y = g[col].to_numpy(float)
            if col in moving:
                ax.loglog(g["frequency_Hz"], np.where(y > 0, y, np.nan), lw=0.9, label=f"{speed:g} km/h")
    top = float(spectra[sorted(moving)].max().max()) if moving else 0.0
    for ax, (col, title) in zip(axes, cols):
        ax.set_title(title)
        if col not in moving:
            _no_motion(ax, title)
            continue
        ax.set_xlabel("frequency, Hz")
        _plain_log(ax, "x")
        _plain_log(ax, "y")
        if top > 0:
            ax.set_ylim(top * 1e-6, top * 3)  # six decades: below is the track's band edge
    axes[0].set_ylabel("PSD, (m/s²)²/Hz")
    _legend_below(fig, next(ax for ax, (c, _) in zip(axes, cols) if c in moving) if moving else axes[0])
    return to_svg(fig)


def seat_transmissibility(trans: pd.DataFrame) -> str | None:
    """|seat / ground| per axis and speed: vertical (every wheel in phase, wheelbase delay, no
    enveloping), fore-aft per unit ground acceleration and, in 3-D, lateral per unit left/right
    anti-phase (roll) ground acceleration; the legend under the panels."""
    if not _has(trans, "speed_km_h", "frequency_Hz", "seat_vertical"):
        return None
    cols = [(c, t) for c, t in (("seat_vertical", "vertical"), ("seat_longitudinal_per_m", "fore-aft (per m)"),
                                ("seat_lateral_roll", "lateral (roll input)")) if c in trans]
    moving = {c for c, _ in cols if (trans[c] > 0).any()}
    fig, axes = _figure(1, len(cols), size=(3.7 * len(cols), 3.3), squeeze=False)
    axes = axes[0]
    for speed, g in trans.groupby("speed_km_h", sort=True):
        for ax, (col, _) in zip(axes, cols):
            y = g[col].to_numpy(float)
            if col in moving:
                ax.loglog(g["frequency_Hz"], np.where(y > 0, y, np.nan), lw=0.9, label=f"{speed:g} km/h")
    for ax, (col, title) in zip(axes, cols):
        ax.set_title(title)
        if col not in moving:
            _no_motion(ax, title)
            continue
        ax.set_xlabel("frequency, Hz")
        _plain_log(ax, "x")
        _plain_log(ax, "y")
    axes[0].set_ylabel("|seat / ground|")
    _legend_below(fig, axes[0])
    return to_svg(fig)


#: Top of the hours colour scale, h: a working day; more is the same green (the number says how much).
HOURS_SCALE_MAX = 8.0


def _hours_grid(table: pd.DataFrame, x_key: str, y_key: str) -> pd.DataFrame:
    """Hours to the action value over the two keys (the lowest where other swept keys vary)."""
    return table.groupby([y_key, x_key], sort=True)["hours_to_eav"].min().unstack(x_key)


class _CellNumbers(Artist):
    """The number written in each cell of a heatmap, centred, in one artist: a grid's hundreds of cells as
    :class:`~matplotlib.text.Text` artists cost most of the figure's time (each laid out on its own, twice
    per drawing under the constrained layout), while these are one size and font and need no layout
    (inside their axes: not part of the figure's layout either)."""

    def __init__(self, xs, ys, labels, colors, fontsize: float):
        super().__init__()
        self._xy = np.column_stack([np.asarray(xs, float), np.asarray(ys, float)])
        self._labels, self._colors = list(labels), list(colors)
        self._prop = FontProperties(size=fontsize)
        self._extents: dict = {}  # (renderer kind, label) -> width, height, descent (the same in every drawing)
        self.set_in_layout(False)

    def draw(self, renderer) -> None:
        if not self.get_visible():
            return
        renderer.open_group("cell_numbers", gid=self.get_gid())
        gc = renderer.new_gc()
        points = self.axes.transData.transform(self._xy)
        kind = (type(renderer), renderer.points_to_pixels(1.0))
        height = renderer.get_canvas_width_height()[1] if renderer.flipy() else None  # y down (SVG), as Text.draw
        for (x, y), label, color in zip(points, self._labels, self._colors):
            if (kind, label) not in self._extents:
                self._extents[kind, label] = renderer.get_text_width_height_descent(label, self._prop, ismath=False)
            w, h, d = self._extents[kind, label]
            gc.set_foreground(color)
            base = y - h / 2 + d  # the baseline of a box centred on the cell
            renderer.draw_text(gc, x - w / 2, base if height is None else height - base, label, self._prop, 0.0)
        gc.restore()
        renderer.close_group("cell_numbers")
        self.stale = False


def _draw_hours(ax, grid: pd.DataFrame, vmax: float, fontsize: float = 8):
    z = np.minimum(grid.to_numpy(float), 24.0)  # "never" (NaN, inf) and beyond a day: ≥ 24 h
    z = np.where(np.isnan(z), 24.0, z)
    im = ax.imshow(z, origin="lower", aspect="auto", cmap="RdYlGn", vmin=0.0, vmax=vmax)
    ax.grid(False)
    ax.set_xticks(range(grid.shape[1]), [f"{v:g}" for v in grid.columns])
    ax.set_yticks(range(grid.shape[0]), [f"{v:g}" for v in grid.index])
    rows, cols = np.indices(z.shape)
    dark = (z < 0.15 * vmax) | (z > 0.85 * vmax)  # the colour map's dark ends: white text
    ax.add_artist(_CellNumbers(cols.ravel(), rows.ravel(),
                               ["≥24" if v >= 24 else f"{v:.3g}" for v in z.ravel()],
                               np.where(dark.ravel(), "white", "black"), fontsize))
    return im


def hours_heatmap(table: pd.DataFrame, x_key: str, y_key: str, x_label: str | None = None,
                  y_label: str | None = None, speed_km_h: float | None = None) -> str | None:
    """Hours to the EU action value over two swept keys at one speed: a heatmap with the hours
    written in each cell.

    ``table``: one row per variant and speed with the two keys' columns, ``speed_km_h`` and
    ``hours_to_eav``; ``speed_km_h``: the speed drawn (the scenario's working speed; None: the
    worst speed of each variant); ``x_label``, ``y_label``: the axes' labels (default the keys).
    """
    if not _has(table, x_key, y_key, "hours_to_eav"):
        return None
    if speed_km_h is not None and "speed_km_h" in table:
        table = table[table["speed_km_h"] == speed_km_h]
    grid = _hours_grid(table, x_key, y_key)
    if grid.empty or (grid.shape[0] < 2 and grid.shape[1] < 2):
        return None
    # drawn at the page's width (the pages scale figures to it): wide and low, so the text stays small
    fig, ax = _figure(size=(9.0, min(1.6 + 0.42 * grid.shape[0], 6.0)))
    im = _draw_hours(ax, grid, HOURS_SCALE_MAX)
    ax.set_xlabel(x_label or x_key)
    ax.set_ylabel(y_label or y_key)
    if speed_km_h is not None:
        ax.set_title(f"at {speed_km_h:g} km/h", fontsize=9)
    fig.colorbar(im, ax=ax, label="hours to the action value")
    return to_svg(fig)


def hours_heatmaps(table: pd.DataFrame, x_key: str, y_key: str, speeds_km_h, x_label: str | None = None,
                   y_label: str | None = None) -> str | None:
    """Small multiples of :func:`hours_heatmap`: one panel per speed of ``speeds_km_h``, the same
    colour scale (0 to :data:`HOURS_SCALE_MAX` h) as the heatmap, so the panels compare at a glance."""
    if not _has(table, x_key, y_key, "hours_to_eav", "speed_km_h"):
        return None
    speeds = [float(v) for v in speeds_km_h if (table["speed_km_h"] == v).any()]
    if not speeds:
        return None
    grids = [_hours_grid(table[table["speed_km_h"] == v], x_key, y_key) for v in speeds]
    cols = min(len(speeds), 4)
    rows = -(-len(speeds) // cols)
    fig, axes = _figure(rows, cols, size=(9.0, 1.4 + 1.5 * rows), squeeze=False, sharex=True, sharey=True)
    vmax = HOURS_SCALE_MAX
    im = None
    for k, ax in enumerate(axes.flat):
        if k >= len(speeds):
            ax.set_visible(False)
            continue
        im = _draw_hours(ax, grids[k], vmax, fontsize=6.5)
        ax.set_title(f"{speeds[k]:g} km/h", fontsize=8)
        if k % cols == 0:
            ax.set_ylabel(y_label or y_key, fontsize=7)
        if k // cols == rows - 1:
            ax.set_xlabel(x_label or x_key, fontsize=7)
    fig.colorbar(im, ax=list(axes.flat), label="hours to the action value", shrink=0.9)
    return to_svg(fig)


def aw_against_speed(speeds: pd.DataFrame, hours_per_day: float = 8.0) -> str | None:
    """Per-axis a_wz, 1.4 a_wx and (3-D) 1.4 a_wy against speed, one panel per axis, one line per
    variant (dotted: the frequency-domain expectation of a single variant), with the levels that
    reach the EU action and limit values; the legend below the panels."""
    if not _has(speeds, "speed_km_h", "a_wz_m_s2", "a_wx_m_s2"):
        return None
    s = speeds.sort_values("speed_km_h", kind="stable")  # the variants in their order (legend)
    axes_cols = [("a_wz_m_s2", 1.0, "a_wz (vertical, W_k)"), ("a_wx_m_s2", 1.4, "1.4 a_wx (fore-aft, W_d)")]
    if "a_wy_m_s2" in s and (s["a_wy_m_s2"] > 0).any():
        axes_cols.append(("a_wy_m_s2", 1.4, "1.4 a_wy (lateral, W_d)"))
    key = "variant" if "variant" in s and s["variant"].nunique() > 1 else None
    groups = list(s.groupby(key, sort=False)) if key else [(None, s)]
    fig, axes = _figure(1, len(axes_cols), size=(3.5 * len(axes_cols), 3.4), sharey=True, squeeze=False)
    axes = axes[0]
    top = max(exposure_levels(hours_per_day)["ELV"], 0.0)
    for ax, (col, k_axis, title) in zip(axes, axes_cols):
        # a variant whose model has no motion on this axis (MF698T: no fore-aft element) gives 0
        # throughout: not a measured zero, so not drawn; said in the panel
        still = [str(name) for name, g in groups if not (g[col].fillna(0.0) != 0).any()]
        if len(still) == len(groups):  # the ticks stay: the panels share their y axis
            ax.text(0.5, 0.5, "zero throughout\n(no motion on this axis\nin this model)", ha="center", va="center",
                    transform=ax.transAxes, fontsize=8, color="0.35")
            ax.set_title(title, fontsize=8)
            ax.set_xlabel("speed, km/h")
            continue
        if still and key:
            ax.text(0.02, 0.98, "not drawn, no motion on this axis in its model:\n" + ", ".join(still),
                    transform=ax.transAxes, ha="left", va="top", fontsize=6, color="0.35")
        for k, (name, g) in enumerate(groups):
            if key and str(name) in still:
                continue
            ax.plot(g["speed_km_h"], k_axis * g[col], marker=MARKERS[k % len(MARKERS)], lw=0.9,
                    label=str(name) if name is not None else "simulated")
            top = max(top, float(np.nanmax(k_axis * g[col].to_numpy(float))))
            exp = f"expected_{col}"
            if name is None and exp in g:
                ax.plot(g["speed_km_h"], k_axis * g[exp], ls=":", color="0.3", label="expected")
                top = max(top, float(np.nanmax(k_axis * g[exp].to_numpy(float))))
        _limit_lines(ax, hours_per_day, label=ax is axes[-1])  # shared y: named once, right of the last panel
        ax.set_title(title, fontsize=8)
        ax.set_xlabel("speed, km/h")
    axes[0].set_ylim(0, 1.08 * top)  # shared: every panel's data and the ELV level
    axes[0].set_ylabel("weighted r.m.s., m/s²")
    _legend_below(fig, axes[0])
    return to_svg(fig)


def aw_against_pressure(speeds: pd.DataFrame) -> str | None:
    """Highest-axis a_w against rear pressure, one line per front pressure, one panel per speed."""
    if not _has(speeds, "speed_km_h", "front_pressure_bar", "rear_pressure_bar", "a_wz_m_s2", "a_wx_m_s2"):
        return None
    if speeds[["front_pressure_bar", "rear_pressure_bar"]].drop_duplicates().shape[0] < 2:
        return None
    s = speeds.assign(a_w=np.maximum(speeds["a_wz_m_s2"], 1.4 * np.maximum(
        speeds["a_wx_m_s2"], speeds["a_wy_m_s2"] if "a_wy_m_s2" in speeds else 0.0)))
    sp = sorted(s["speed_km_h"].unique())
    fig, axes = _figure(1, len(sp), size=(min(2.2 * len(sp) + 1.0, 9.0), 2.9), sharey=True, squeeze=False)
    for ax, speed in zip(axes[0], sp):
        for k, (front, g) in enumerate(s[s["speed_km_h"] == speed].groupby("front_pressure_bar", sort=True)):
            g = g.sort_values("rear_pressure_bar")
            ax.plot(g["rear_pressure_bar"], g["a_w"], marker=MARKERS[k % len(MARKERS)], lw=0.9,
                    label=f"front {front:g} bar")
        ax.set_title(f"{speed:g} km/h")
        ax.set_xlabel("rear pressure, bar")
    axes[0][0].set_ylabel("a_w (highest axis), m/s²")
    axes[0][0].legend()
    return to_svg(fig)


def ride_aw_speed(ride_results: pd.DataFrame) -> str | None:
    """Report: highest-axis a_w against speed per scenario (scenario pressures; of a sweep of other keys, its
    first variant), EAV/ELV in 8 h."""
    if not _has(ride_results, "scenario", "speed_km_h", "a_wz_m_s2", "a_wx_m_s2"):
        return None
    r = primary_rows(ride_results)
    if "is_nominal" in r:
        r = r[r["is_nominal"].astype(bool)]
    if "variant" in r:  # a sweep of other keys at the scenario's pressures: its first variant
        v = r["variant"].fillna("")
        r = r[v == v.groupby(r["scenario"]).transform("first")]
    fig, ax = _figure()
    for k, (name, g) in enumerate(r.groupby("scenario", sort=True)):
        g = g.sort_values("speed_km_h")
        lateral = g["a_wy_m_s2"].fillna(0.0) if "a_wy_m_s2" in g else 0.0
        ax.plot(g["speed_km_h"], np.maximum(g["a_wz_m_s2"], 1.4 * np.maximum(g["a_wx_m_s2"], lateral)),
                marker=MARKERS[k % len(MARKERS)],
                lw=0.9, label=str(name))
    _limit_lines(ax, 8.0)
    ax.set_xlabel("speed, km/h")
    ax.set_ylabel("a_w (highest axis), m/s²")
    ax.set_ylim(bottom=0)
    _legend_below(fig, ax)
    return to_svg(fig)


def ride_aw_axes_speed(ride_results: pd.DataFrame) -> str | None:
    """Report: per-axis a_wz, 1.4 a_wx and (3-D) 1.4 a_wy against speed, one line per scenario at its
    own tyre pressures (:func:`aw_against_speed` with the scenarios as its variants)."""
    if not _has(ride_results, "scenario", "speed_km_h", "a_wz_m_s2", "a_wx_m_s2"):
        return None
    r = primary_rows(ride_results)
    if "is_nominal" in r:
        r = r[r["is_nominal"].astype(bool)]
    return aw_against_speed(r.assign(variant=r["scenario"].astype(str)), 8.0)


def study_aw_speed(iso: pd.DataFrame) -> str | None:
    """Report: the ch. 6/7 studies' vertical weighted r.m.s. against speed, one panel per study.

    Carriage and tractor records are at the tyre/CG (no seat); lines join the
    mean over load conditions per characteristics (and track for the tractor).
    """
    if not _has(iso, "study", "speed_km_h", "characteristics"):
        return None
    iso = iso.assign(a_wz=iso.get("iso_weighted_rms_m_s2", pd.Series(np.nan, index=iso.index)).fillna(
        iso.get("iso_vertical_weighted_rms_m_s2", pd.Series(np.nan, index=iso.index))))
    studies = [s for s in ("carriage", "tractor") if s in set(iso["study"])]
    if not studies:
        return None
    fig, axes = _figure(1, len(studies), size=(7.4, 3.0), sharey=True, squeeze=False)
    for ax, study in zip(axes[0], studies):
        d = iso[iso["study"] == study].copy()
        if "longitudinal" in d:
            d = d[d["longitudinal"].isna() | d["longitudinal"].isin(["none", "maxwell"])]
        d["series"] = d["characteristics"].astype(str) + (
            " " + d["track"].astype(str) if "track" in d and d["track"].notna().any() else "")
        for k, (series, g) in enumerate(d.groupby("series", sort=True)):
            m = g.groupby("speed_km_h")["a_wz"].mean()
            ax.plot(m.index, m.to_numpy(), marker=MARKERS[k % len(MARKERS)], lw=0.9, label=series)
        _limit_lines(ax, 8.0, label=ax is axes[0][-1])
        ax.set_title(f"{study} (vertical, W_k)")
        ax.set_xlabel("speed, km/h")
        ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(0.0, 0.9))
    axes[0][0].set_ylabel("a_wz, m/s²")
    axes[0][0].set_ylim(bottom=0)
    return to_svg(fig)
