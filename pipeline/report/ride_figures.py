"""Ride figures (issue 13): pure functions, DataFrame in, deterministic inline SVG out.

Same conventions as :mod:`tyrelab.report.figures` (its ``to_svg``: Agg, text as
text, fixed hash salt, no dates); ``None`` when there is nothing to plot.

- :func:`seat_psd` — seat vertical acceleration PSD per speed;
- :func:`seat_transmissibility` — |seat / ground| from ground input per speed;
- :func:`aw_against_speed` — a_wz and 1.4 a_wx against speed with the levels that
  reach the EU action and limit values in the daily exposure time;
- :func:`aw_against_pressure` — a_w against rear pressure per front pressure (sweeps);
- :func:`ride_aw_speed` — the report's Ride page: ride_results per scenario;
- :func:`study_aw_speed` — the report's Ride page: the ch. 6/7 studies' ISO 2631 values.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..vehicle import iso2631
from .figures import MARKERS, _figure, _has, _plain_log, to_svg

__all__ = ["seat_psd", "seat_transmissibility", "aw_against_speed", "aw_against_pressure", "ride_aw_speed",
           "study_aw_speed", "exposure_levels"]


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


def _limit_lines(ax, hours_per_day: float) -> None:
    for (name, level), style in zip(exposure_levels(hours_per_day).items(), ("--", "-")):
        ax.axhline(level, color="tab:red", ls=style, lw=0.9)
        ax.annotate(f"{name} in {hours_per_day:g} h", (0.01, level), xycoords=("axes fraction", "data"),
                    va="bottom", fontsize=7, color="tab:red")


def seat_psd(spectra: pd.DataFrame) -> str | None:
    """Seat vertical (and fore-aft) acceleration PSD per speed (0.1 Hz bandwidth)."""
    if not _has(spectra, "speed_km_h", "frequency_Hz", "seat_vertical_psd_m2_s4_per_Hz"):
        return None
    fig, axes = _figure(1, 2, size=(7.4, 3.0), sharey=True)
    for k, (speed, g) in enumerate(spectra.groupby("speed_km_h", sort=True)):
        for ax, col in zip(axes, ("seat_vertical_psd_m2_s4_per_Hz", "seat_longitudinal_psd_m2_s4_per_Hz")):
            y = g[col].to_numpy(float)
            if np.any(y > 0):
                ax.loglog(g["frequency_Hz"], np.where(y > 0, y, np.nan), lw=0.9, label=f"{speed:g} km/h")
    for ax, title in zip(axes, ("seat vertical", "seat fore-aft")):
        ax.set_title(title)
        ax.set_xlabel("frequency, Hz")
        _plain_log(ax, "x")
    _plain_log(axes[0], "y")
    top = float(spectra[["seat_vertical_psd_m2_s4_per_Hz", "seat_longitudinal_psd_m2_s4_per_Hz"]].max().max())
    if top > 0:
        axes[0].set_ylim(top * 1e-6, top * 3)  # six decades: below is the track's band edge
    axes[0].set_ylabel("PSD, (m/s²)²/Hz")
    axes[0].legend()
    return to_svg(fig)


def seat_transmissibility(trans: pd.DataFrame) -> str | None:
    """|seat vertical / ground| (both axles, wheelbase delay, no enveloping) per speed."""
    if not _has(trans, "speed_km_h", "frequency_Hz", "seat_vertical"):
        return None
    fig, ax = _figure()
    for speed, g in trans.groupby("speed_km_h", sort=True):
        ax.loglog(g["frequency_Hz"], g["seat_vertical"], lw=0.9, label=f"{speed:g} km/h")
    ax.set_xlabel("frequency, Hz")
    ax.set_ylabel("|seat vertical / ground|")
    _plain_log(ax, "x")
    _plain_log(ax, "y")
    ax.legend()
    return to_svg(fig)


def aw_against_speed(speeds: pd.DataFrame, hours_per_day: float = 8.0) -> str | None:
    """a_wz, 1.4 a_wx (simulated, and the frequency-domain expectation) against speed."""
    if not _has(speeds, "speed_km_h", "a_wz_m_s2", "a_wx_m_s2"):
        return None
    fig, ax = _figure()
    s = speeds.sort_values("speed_km_h")
    groups = s.groupby(["front_pressure_bar", "rear_pressure_bar"], sort=True) if "front_pressure_bar" in s and \
        s[["front_pressure_bar", "rear_pressure_bar"]].drop_duplicates().shape[0] > 1 else [(None, s)]
    for k, (key, g) in enumerate(groups):
        tag = "" if key is None else f" {key[0]:g}/{key[1]:g} bar"
        ax.plot(g["speed_km_h"], g["a_wz_m_s2"], marker=MARKERS[k % len(MARKERS)], color="tab:blue",
                label=f"a_wz{tag}" if k < 4 else None, lw=0.9)
        ax.plot(g["speed_km_h"], 1.4 * g["a_wx_m_s2"], marker=MARKERS[k % len(MARKERS)], color="tab:green",
                label=f"1.4 a_wx{tag}" if k < 4 else None, lw=0.9)
        if key is None and "expected_a_wz_m_s2" in g:
            ax.plot(g["speed_km_h"], g["expected_a_wz_m_s2"], ls=":", color="tab:blue", label="a_wz expected")
    _limit_lines(ax, hours_per_day)
    ax.set_xlabel("speed, km/h")
    ax.set_ylabel("weighted r.m.s., m/s²")
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper left", bbox_to_anchor=(0.0, 0.93))
    return to_svg(fig)


def aw_against_pressure(speeds: pd.DataFrame) -> str | None:
    """Highest-axis a_w against rear pressure, one line per front pressure, one panel per speed."""
    if not _has(speeds, "speed_km_h", "front_pressure_bar", "rear_pressure_bar", "a_wz_m_s2", "a_wx_m_s2"):
        return None
    if speeds[["front_pressure_bar", "rear_pressure_bar"]].drop_duplicates().shape[0] < 2:
        return None
    s = speeds.assign(a_w=np.maximum(speeds["a_wz_m_s2"], 1.4 * speeds["a_wx_m_s2"]))
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
    """Report: highest-axis a_w against speed per scenario (scenario pressures), EAV/ELV in 8 h."""
    if not _has(ride_results, "scenario", "speed_km_h", "a_wz_m_s2", "a_wx_m_s2"):
        return None
    r = ride_results
    if "is_nominal" in r:
        r = r[r["is_nominal"].astype(bool)]
    fig, ax = _figure()
    for k, (name, g) in enumerate(r.groupby("scenario", sort=True)):
        g = g.sort_values("speed_km_h")
        ax.plot(g["speed_km_h"], np.maximum(g["a_wz_m_s2"], 1.4 * g["a_wx_m_s2"]), marker=MARKERS[k % len(MARKERS)],
                lw=0.9, label=str(name)[:48])
    _limit_lines(ax, 8.0)
    ax.set_xlabel("speed, km/h")
    ax.set_ylabel("a_w (highest axis), m/s²")
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper left", bbox_to_anchor=(0.0, 0.93))
    return to_svg(fig)


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
        _limit_lines(ax, 8.0)
        ax.set_title(f"{study} (vertical, W_k)")
        ax.set_xlabel("speed, km/h")
        ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(0.0, 0.9))
    axes[0][0].set_ylabel("a_wz, m/s²")
    axes[0][0].set_ylim(bottom=0)
    return to_svg(fig)
