"""Figures of the report's "Measured ride" page (issue 24): seat PSDs, measured against predicted."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .figures import _figure, _has, _plain_log, to_svg

__all__ = ["psd_overlay", "MAX_PANELS"]

#: Recordings drawn (the first, by ride_id); the rest are in the table recording_spectra.
MAX_PANELS = 12


def psd_overlay(spectra: pd.DataFrame) -> str | None:
    """Seat vertical PSD of each recording (0.1 Hz), with its scenario's prediction where there is one."""
    columns = ("ride_id", "source", "channel", "frequency_Hz", "psd_m2_s4_per_Hz")
    if spectra is None or not all(c in spectra.columns for c in columns):
        return None  # the rides stage has not run
    z = spectra[spectra["channel"] == "seat_z_m_s2"] if _has(spectra, *columns) else spectra.iloc[:0]
    rides = sorted(z["ride_id"].unique())[:MAX_PANELS]
    if not rides:  # the stage ran; no campaign has a rides.csv with a seat z recording
        fig, ax = _figure(size=(4.0, 1.2))
        ax.set_axis_off()
        ax.text(0.5, 0.5, "no seat recordings (no rides.csv in the raw folder)", ha="center", va="center")
        return to_svg(fig)
    ncols = min(3, len(rides))
    nrows = math.ceil(len(rides) / ncols)
    fig, axes = _figure(nrows, ncols, size=(2.6 * ncols, 2.1 * nrows), sharex=True, squeeze=False)
    for ax, ride in zip(axes.flat, rides):
        g = z[z["ride_id"] == ride]
        for source, style in (("measured", dict(color="tab:blue", lw=0.9)),
                              ("predicted", dict(color="tab:orange", lw=0.9, ls="--"))):
            s = g[g["source"] == source]
            y = s["psd_m2_s4_per_Hz"].to_numpy(float)
            if np.any(y > 0):
                ax.loglog(s["frequency_Hz"], np.where(y > 0, y, np.nan), label=source, **style)
        ax.set_title(str(ride), fontsize=8)
        _plain_log(ax, "x")
        top = float(g["psd_m2_s4_per_Hz"].max())
        if top > 0:
            ax.set_ylim(top * 1e-4, top * 3)
    for ax in list(axes.flat)[len(rides):]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel("frequency, Hz")
    for ax in axes[:, 0]:
        ax.set_ylabel("PSD, (m/s²)²/Hz")
    axes.flat[0].legend(fontsize=7)
    return to_svg(fig)
