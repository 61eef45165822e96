"""Figures of the report's "Vehicle FRFs" page (issue 43, thesis ch. 2): per stand or track recording
and output, the measured FRF magnitude with its 95 % band and the model's prediction as a line, and
the output's coherence."""

from __future__ import annotations

import numpy as np
import pandas as pd

from .figures import _figure, _has, _plain_log, to_svg

__all__ = ["frf_panels", "MAX_RECORDINGS", "OUTPUT_ORDER", "BAND_Hz", "chosen_input"]

#: Recordings drawn (stand and track recordings first, then by ride_id); the rest are in the table
#: vehicle_frf.
MAX_RECORDINGS = 8
#: Outputs in the order of the panels (the cab floor's translations, then its rotations); others after.
OUTPUT_ORDER = ("floor_z_m_s2", "floor_x_m_s2", "floor_y_m_s2", "roll_rad_s2", "pitch_rad_s2", "yaw_rad_s2")
#: Band drawn, Hz: the stand's excitation (thesis §2.2: flat acceleration spectrum 0.5-12 Hz).
BAND_Hz = (0.5, 12.0)
#: Coverage factor of the band around the measured magnitude (normal, 95 %).
COVERAGE_95 = 1.96
#: Least multiple coherence of a bin the input choice counts (the modal fit's coherent band).
COHERENT = 0.5


def chosen_input(frf: pd.DataFrame) -> str | None:
    """The input of one recording's ``vehicle_frf`` rows whose FRFs are best determined: the one least
    coherent with the other inputs over the band (median ``input_coherence``: the wheel the stand
    excited on its own), then the one with the most bins that are separable, unmasked and coherent.

    Examples
    --------
    >>> import pandas as pd
    >>> t = pd.DataFrame({"input": ["a", "a", "b", "b"], "frequency_Hz": [1.0, 2.0, 1.0, 2.0],
    ...                   "ill_conditioned": [True, True, False, False], "masked": [False] * 4,
    ...                   "multiple_coherence": [0.9] * 4, "input_coherence": [0.2, 0.2, 0.2, 0.2]})
    >>> chosen_input(t)
    'b'
    >>> chosen_input(t.assign(ill_conditioned=False, input_coherence=[0.5, 0.5, 0.0, 0.1]))
    'b'
    """
    if frf is None or frf.empty:
        return None
    g = frf[frf["frequency_Hz"].between(*BAND_Hz)]
    if g.empty:
        return str(frf["input"].iloc[0])
    good = ~g["ill_conditioned"].fillna(True).astype(bool) & ~g["masked"].fillna(False).astype(bool) \
        & (g["multiple_coherence"].fillna(0.0) >= COHERENT)
    score = pd.DataFrame({"count": good.groupby(g["input"]).sum()})
    coherence = g["input_coherence"] if "input_coherence" in g.columns else pd.Series(0.0, index=g.index)
    score["coherence"] = coherence.fillna(1.0).groupby(g["input"]).median().round(2)
    score = score.sort_values(["coherence", "count"], ascending=[True, False], kind="stable")
    return str(score.index[0])


def _recordings(frf: pd.DataFrame, recordings: pd.DataFrame | None) -> list[str]:
    """Ride ids drawn: stand and track recordings (``method``) first, then the others, by ride_id."""
    rides = sorted(frf["ride_id"].astype(str).unique())
    if _has(recordings, "ride_id", "method"):
        method = dict(zip(recordings["ride_id"].astype(str), recordings["method"].fillna("")))
        rides = sorted(rides, key=lambda r: (method.get(r, "") not in ("four_post", "track"), r))
    return rides[:MAX_RECORDINGS]


def frf_panels(frf: pd.DataFrame, recordings: pd.DataFrame | None = None) -> str | None:
    """Per recording (up to :data:`MAX_RECORDINGS`) a row of panels, one per output: the measured FRF
    magnitude from its best-determined input (:func:`chosen_input`) with the 95 % band of its random
    error (``|H| (1 ± 1.96 ε)``), the prediction of the row's scenario as a dashed line where there is
    one (``predicted_h_magnitude``), and below it the output's multiple coherence with the bins the
    estimator cannot use shaded (masked at a wheel's rotation or lug passing, or inputs inseparable).
    """
    columns = ("ride_id", "input", "output", "frequency_Hz", "h_magnitude", "random_error", "multiple_coherence",
               "masked", "ill_conditioned")
    if frf is None or not all(c in frf.columns for c in columns):
        return None  # the rides stage has not run
    if frf.empty:  # the stage ran; no recording has wheel inputs
        fig, ax = _figure(size=(4.0, 1.2))
        ax.set_axis_off()
        ax.text(0.5, 0.5, "no recordings with wheel inputs (input_<wheel>_z_m_s2 or _z_m)", ha="center", va="center")
        return to_svg(fig)
    rides = _recordings(frf, recordings)
    outputs = sorted(frf["output"].astype(str).unique(),
                     key=lambda o: (OUTPUT_ORDER.index(o) if o in OUTPUT_ORDER else len(OUTPUT_ORDER), o))
    ncols = len(outputs)
    fig, axes = _figure(2 * len(rides), ncols, size=(1.95 * ncols + 0.4, 2.25 * len(rides) + 0.3), squeeze=False,
                        sharex=True, gridspec_kw={"height_ratios": [3, 1.1] * len(rides)})
    for n, ride in enumerate(rides):
        of_ride = frf[frf["ride_id"].astype(str) == ride]
        inp = chosen_input(of_ride)
        for c, out in enumerate(outputs):
            top, bottom = axes[2 * n, c], axes[2 * n + 1, c]
            g = of_ride[(of_ride["output"] == out) & (of_ride["input"] == inp)].sort_values("frequency_Hz")
            g = g[g["frequency_Hz"].between(0.0, BAND_Hz[1])]
            top.set_title(f"{ride}\n{out} / {inp}" if c == 0 else out, fontsize=6.5, loc="left")
            if g.empty:
                top.set_axis_off()
                bottom.set_axis_off()
                continue
            f = g["frequency_Hz"].to_numpy(float)
            h = g["h_magnitude"].to_numpy(float)
            eps = g["random_error"].to_numpy(float)
            unusable = g["masked"].fillna(False).astype(bool).to_numpy() \
                | g["ill_conditioned"].fillna(True).astype(bool).to_numpy()
            lo = np.where(np.isfinite(eps), h * (1 - COVERAGE_95 * eps), np.nan)
            hi = np.where(np.isfinite(eps), h * (1 + COVERAGE_95 * eps), np.nan)
            positive = np.isfinite(h) & (h > 0)
            if not positive.any():
                top.text(0.5, 0.5, "no FRF", ha="center", va="center", fontsize=7, transform=top.transAxes)
                continue
            top.fill_between(f, np.where(lo > 0, lo, h[positive].min() * 0.1), hi, color="tab:blue", alpha=0.25,
                             lw=0, label="measured, 95 %")
            top.plot(f, np.where(positive, h, np.nan), color="tab:blue", lw=0.9, label="measured |H1|")
            if "predicted_h_magnitude" in g.columns and g["predicted_h_magnitude"].notna().any():
                top.plot(f, g["predicted_h_magnitude"].to_numpy(float), color="tab:orange", lw=1.0, ls="--",
                         label="predicted")
            top.set_yscale("log")
            _plain_log(top)
            span = h[positive & ~unusable] if (positive & ~unusable).any() else h[positive]
            top.set_ylim(float(np.min(span)) / 3, float(np.max(span)) * 3)
            coh = g["multiple_coherence"].to_numpy(float)
            bottom.fill_between(f, 0, 1, where=unusable, step="mid", color="0.85", lw=0, label="not used")
            bottom.plot(f, coh, color="0.15", lw=0.8, label="coherence")
            bottom.set_ylim(0, 1.05)
            bottom.set_yticks([0, 0.5, 1])
            bottom.set_xlim(0, BAND_Hz[1])
        axes[2 * n, 0].set_ylabel("|H|", fontsize=7)
        axes[2 * n + 1, 0].set_ylabel("γ²", fontsize=7)
    for ax in axes[-1]:
        ax.set_xlabel("frequency, Hz", fontsize=7)
    handles, labels = [], []
    for ax in (axes[0, 0], axes[1, 0]):
        h_, l_ = ax.get_legend_handles_labels()
        handles += h_
        labels += l_
    fig.legend(handles, labels, loc="outside lower center", ncols=len(labels), fontsize=7, frameon=False)
    return to_svg(fig)
