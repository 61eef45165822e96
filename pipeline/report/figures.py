"""Report figures: pure functions, DataFrame in, inline SVG string out.

Each function mirrors one thesis figure (numbers in the names and captions)
and returns a small ``<svg>`` element ready to inline into an HTML page:
:class:`matplotlib.figure.Figure` objects made directly (no pyplot state, no
backend switch: the SVG backend is used by ``savefig``), text kept as text (``svg.fonttype='none'``, so the
browser renders it with its own sans-serif font and nothing is embedded), a
fixed ``svg.hashsalt`` and no ``Date`` metadata so the output is
deterministic. A function returns ``None`` when its input holds nothing to
plot; the page then says which stage has not produced the data yet.

The per-run drill-down uses :func:`run_spectra` (pure numpy/scipy) to derive
the acceleration PSD, dynamic stiffness and coherence from a recording.
"""

from __future__ import annotations

import io
import re

import matplotlib
import matplotlib.axis
import matplotlib.text
import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from matplotlib.ticker import LogFormatter, NullFormatter, NullLocator

from ..measurement.methods import thesis_runs

__all__ = ["RC", "SIZE", "T_TYRES", "NOMINAL_PRESSURE_BAR", "MARKERS", "to_svg", "compact_svg",
    "stiffness_vs_pressure", "stiffness_vs_speed", "damping_vs_speed", "pressure_dependence_vs_wr",
    "carcass_stiffness_vs_rim", "predicted_vs_measured", "SPOKE_FIGURES", "spoke_curves", "profile_spectra",
    "carriage_rms", "carriage_ratio_errors", "acceleration_spectra", "natural_frequencies", "run_spectra",
    "run_drilldown"]

#: matplotlib settings for every report figure.
RC = {
    "svg.fonttype": "none",
    "svg.hashsalt": "tyrelab-report",
    "font.family": "sans-serif",
    "font.size": 8,
    "axes.titlesize": 9,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "legend.fontsize": 7,
    "legend.frameon": False,
    "lines.markersize": 4,
    "figure.dpi": 72,
    "figure.constrained_layout.w_pad": 0.12,
    # Titles at the top of the axes, not moved above top tick labels (there are none): the
    # automatic placement measures every axis' tick labels again for each title.
    "axes.titley": 1.0,
}
#: Default figure size in inches (one column of the report).
SIZE = (5.4, 3.2)
#: Thesis tyres of Figs 21 and 34.
T_TYRES = ("T1", "T2", "T3", "T4", "T5")
#: Nominal pressure of Figs 21 and 34 (bar).
NOMINAL_PRESSURE_BAR = 1.38
#: Markers cycled over series, as the thesis' plots distinguish series by symbol.
MARKERS = ("o", "s", "^", "v", "D", "x", "+", "*")


def to_svg(fig: Figure) -> str:
    """Serialise ``fig`` as a bare, deterministic ``<svg>`` element.

    Parameters
    ----------
    fig : matplotlib.figure.Figure

    Returns
    -------
    str
        The SVG markup from ``<svg`` on (no XML declaration, DOCTYPE or
        comments), with a ``role="img"`` attribute for accessibility.
    """
    buf = io.StringIO()
    # Labels carry ids from the user's data (tyre ids, sources): a ``$`` in them is text, not
    # mathtext (``$\\undefinedmacro{$`` would otherwise make savefig raise). No figure uses mathtext.
    for text in _texts(fig):
        if "$" in text.get_text():
            text.set_parse_math(False)
    with matplotlib.rc_context(RC):
        fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": None})
    return compact_svg(buf.getvalue())


def _texts(artist):
    """The :class:`matplotlib.text.Text` artists below ``artist`` that hold text before drawing:
    titles, axis labels, legend entries, annotations. An axis contributes only its label and
    offset text: its tick labels are numbers set while drawing, and listing its ticks (as
    ``findobj`` does) would make each axis create them ahead of the draw, outside :data:`RC`."""
    for child in artist.get_children():
        if isinstance(child, matplotlib.axis.Axis):
            yield child.label
            yield child.offsetText
        elif isinstance(child, matplotlib.text.Text):
            yield child
            yield from _texts(child)
        else:
            yield from _texts(child)


_GEOMETRY = re.compile(r'\b(d|x|y|x1|x2|y1|y2|width|height|transform|viewBox|points)="([^"]*)"')
_NUMBER = re.compile(r"-?\d+\.\d{2,}")


def compact_svg(text: str) -> str:
    """Shrink matplotlib's SVG for inlining: only the ``<svg>`` element, no metadata or
    comments, geometry rounded to 0.1 pt, no indentation; text content untouched."""
    text = text[text.index("<svg"):]
    text = re.sub(r"<!--.*?-->|<metadata>.*?</metadata>", "", text, flags=re.S)

    def geometry(m: re.Match) -> str:
        value = _NUMBER.sub(lambda n: f"{float(n.group()):.1f}", m.group(2))
        return f'{m.group(1)}="{" ".join(value.split())}"'

    text = _GEOMETRY.sub(geometry, text)
    text = re.sub(r"\n\s*", "\n", text)
    return text.replace("<svg ", '<svg role="img" ', 1)


def _figure(nrows: int = 1, ncols: int = 1, size=SIZE, layout: str | None = "constrained", **kw):
    """A :class:`matplotlib.figure.Figure` and its axes, made directly: no pyplot figure manager
    to create and close per figure, no global backend switch at import."""
    with matplotlib.rc_context(RC):
        fig = Figure(figsize=size, layout=layout)
        return fig, fig.subplots(nrows, ncols, **kw)


def _plain_log(ax, axis: str = "y") -> None:
    """Log-axis tick labels as plain text (``1e-05``) and no minor ticks: no mathtext to parse,
    a few tick artists instead of dozens, faster and smaller."""
    target = ax.yaxis if axis == "y" else ax.xaxis
    target.set_major_formatter(LogFormatter(labelOnlyBase=True))
    target.set_minor_formatter(NullFormatter())
    target.set_minor_locator(NullLocator())  # no minor ticks: each is an artist laid out and drawn


def _has(df: pd.DataFrame | None, *cols: str) -> bool:
    return df is not None and not df.empty and all(c in df.columns for c in cols)


def _measurements(results: pd.DataFrame) -> pd.DataFrame:
    """The QC-passed measurement runs the thesis' figures draw: vertical stepped-sine runs only
    (:func:`tyrelab.measurement.methods.thesis_runs`; issue 44: never a lateral or longitudinal run)."""
    r = thesis_runs(results)
    if "kind" in r.columns:
        r = r.loc[r["kind"].fillna("measurement") == "measurement"]
    if "qc_ok" in r.columns:
        r = r.loc[r["qc_ok"].fillna(False).astype(bool)]
    return r


def _near(values: pd.Series, target: float, tol: float = 0.06) -> pd.Series:
    return (pd.to_numeric(values, errors="coerce") - target).abs() <= tol


def _legend(ax) -> None:
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best")


def stiffness_vs_pressure(results: pd.DataFrame, tyre_id: str | None = "T2") -> str | None:
    """Fig. 20: vertical stiffness of one tyre against inflation pressure, one line per speed
    (vertical stepped-sine runs only).

    Parameters
    ----------
    results : DataFrame
        ``results`` table (tyre_id, speed_km_h, pressure_bar, stiffness_kN_per_m, qc_ok).
    tyre_id : str, optional
        Tyre to plot; falls back to the tyre with the most runs.
    """
    if not _has(results, "tyre_id", "speed_km_h", "pressure_bar", "stiffness_kN_per_m"):
        return None
    r = _measurements(results)
    if r.empty:
        return None
    if tyre_id not in set(r["tyre_id"].astype(str)):
        tyre_id = str(r["tyre_id"].astype(str).value_counts().index[0])
    r = r.loc[r["tyre_id"].astype(str) == tyre_id]
    fig, ax = _figure()
    for i, (speed, g) in enumerate(r.groupby("speed_km_h")):
        m = g.groupby("pressure_bar")["stiffness_kN_per_m"].mean()
        ax.plot(m.index, m.values, marker=MARKERS[i % len(MARKERS)], label=f"{speed:g} km/h")
    ax.set(xlabel="inflation pressure (bar)", ylabel="stiffness K (kN/m)",
           title=f"Fig. 20 — vertical stiffness of tyre {tyre_id} against pressure")
    _legend(ax)
    return to_svg(fig)


def _per_tyre_vs_speed(results: pd.DataFrame, column: str, ylabel: str, title: str) -> str | None:
    if not _has(results, "tyre_id", "speed_km_h", "pressure_bar", column):
        return None
    r = _measurements(results)
    r = r.loc[_near(r["pressure_bar"], NOMINAL_PRESSURE_BAR) & r[column].notna()]
    tyres = [t for t in T_TYRES if t in set(r["tyre_id"].astype(str))] or sorted(r["tyre_id"].astype(str).unique())[:6]
    if not tyres:
        return None
    fig, ax = _figure()
    for i, t in enumerate(tyres):
        m = r.loc[r["tyre_id"].astype(str) == t].groupby("speed_km_h")[column].mean()
        ax.plot(m.index, m.values, marker=MARKERS[i % len(MARKERS)], label=t)
    ax.set(xlabel="rolling speed (km/h)", ylabel=ylabel, title=title)
    _legend(ax)
    return to_svg(fig)


def stiffness_vs_speed(results: pd.DataFrame) -> str | None:
    """Fig. 21: vertical stiffness of tyres T1–T5 against rolling speed at 1.38 bar (vertical
    stepped-sine runs only).

    Parameters
    ----------
    results : DataFrame
        ``results`` table.
    """
    return _per_tyre_vs_speed(results, "stiffness_kN_per_m", "stiffness K (kN/m)",
                              "Fig. 21 — vertical stiffness against rolling speed, 1.38 bar")


def damping_vs_speed(results: pd.DataFrame) -> str | None:
    """Fig. 34: vertical damping coefficient of tyres T1–T5 against rolling speed at 1.38 bar
    (vertical stepped-sine runs only).

    Parameters
    ----------
    results : DataFrame
        ``results`` table.
    """
    return _per_tyre_vs_speed(results, "damping_kN_s_per_m", "damping C (kN s/m)",
                              "Fig. 34 — vertical damping against rolling speed, 1.38 bar")


def _size_points(table_iii: pd.DataFrame, tyres: pd.DataFrame) -> pd.DataFrame:
    cols = [c for c in ("tyre_id", "section_width_in", "rim_diameter_in") if c in tyres.columns]
    t = table_iii.copy()
    t["tyre_id"] = t["tyre_id"].astype(str)
    ty = tyres[cols].copy()
    ty["tyre_id"] = ty["tyre_id"].astype(str)
    t = t.merge(ty, on="tyre_id", how="left")
    if "condition" in t.columns:
        t = t.loc[t["condition"] == "rolling"]
    t["wr_in2"] = pd.to_numeric(t["section_width_in"], errors="coerce") * pd.to_numeric(t["rim_diameter_in"], errors="coerce")
    return t


def _fit_line(ax, fits: pd.DataFrame | None, name: str, x: np.ndarray) -> None:
    if not _has(fits, "fit", "source", "slope", "intercept") or x.size == 0:
        return
    xs = np.array([np.nanmin(x), np.nanmax(x)])
    for source, style in (("ours", "-"), ("published", ":")):
        row = fits.loc[(fits["fit"] == name) & (fits["source"] == source)]
        if len(row) and pd.notna(row["slope"].iloc[0]):
            r = row.iloc[0]
            label = f"{source} fit: {r['intercept']:.3g} + {r['slope']:.3g}·x"
            ax.plot(xs, r["intercept"] + r["slope"] * xs, style, color="0.3", label=label)


def _size_figure(table_iii, tyres, size_regressions, x, y, thesis_y, fit, xlabel, ylabel, title) -> str | None:
    if not _has(table_iii, "tyre_id", y) or not _has(tyres, "tyre_id", "section_width_in", "rim_diameter_in"):
        return None
    t = _size_points(table_iii, tyres)
    t = t.loc[t[x].notna()]
    if t[y].notna().sum() == 0:
        return None
    fig, ax = _figure()
    ax.plot(t[x], t[y], "o", label="ours")
    if thesis_y in t.columns:
        ax.plot(t[x], t[thesis_y], "x", color="C3", label="thesis (Table III)")
    for _, r in t.loc[t[y].notna()].iterrows():
        ax.annotate(str(r["tyre_id"]), (r[x], r[y]), fontsize=6, xytext=(2, 2), textcoords="offset points")
    _fit_line(ax, size_regressions, fit, t[x].to_numpy(float))
    ax.set(xlabel=xlabel, ylabel=ylabel, title=title)
    _legend(ax)
    return to_svg(fig)


def pressure_dependence_vs_wr(table_iii: pd.DataFrame, tyres: pd.DataFrame,
                              size_regressions: pd.DataFrame | None = None) -> str | None:
    """Fig. 30: rolling ΔK_p against section width × rim diameter W·R.

    Parameters
    ----------
    table_iii : DataFrame
        Our ``table_iii`` (with ``thesis_`` columns when available).
    tyres : DataFrame
        ``tyres`` table with ``section_width_in`` and ``rim_diameter_in``.
    size_regressions : DataFrame, optional
        Fitted lines (``fit == 'dkp_vs_wr'``) for ours and the published values.
    """
    return _size_figure(table_iii, tyres, size_regressions, "wr_in2", "pressure_dependence_kN_per_m_bar",
                        "thesis_pressure_dependence_kN_per_m_bar", "dkp_vs_wr", "W·R (in²)",
                        "ΔK_p (kN/m per bar)", "Fig. 30 — ΔK_p against W·R (rolling)")


def carcass_stiffness_vs_rim(table_iii: pd.DataFrame, tyres: pd.DataFrame,
                             size_regressions: pd.DataFrame | None = None) -> str | None:
    """Fig. 31: rolling carcass stiffness K_c against rim diameter R.

    Parameters
    ----------
    table_iii, tyres, size_regressions : DataFrame
        As for :func:`pressure_dependence_vs_wr` (``fit == 'kc_vs_rim'``).
    """
    return _size_figure(table_iii, tyres, size_regressions, "rim_diameter_in", "carcass_stiffness_kN_per_m",
                        "thesis_carcass_stiffness_kN_per_m", "kc_vs_rim", "rim diameter R (in)",
                        "K_c (kN/m)", "Fig. 31 — carcass stiffness against rim diameter (rolling)")


def predicted_vs_measured(predictions: pd.DataFrame) -> str | None:
    """Fig. 32: stiffness predicted by the empirical formula against measured.

    Parameters
    ----------
    predictions : DataFrame
        ``formula_predictions`` (source, measured_kN_per_m, formula_kN_per_m,
        stationary_kN_per_m).
    """
    if not _has(predictions, "measured_kN_per_m", "formula_kN_per_m"):
        return None
    p = predictions.loc[predictions["measured_kN_per_m"].notna()]
    if p.empty:
        return None
    fig, ax = _figure(size=(4.2, 3.6))
    for i, (source, g) in enumerate(p.groupby("source", sort=True)):
        ax.plot(g["measured_kN_per_m"], g["formula_kN_per_m"], MARKERS[i % len(MARKERS)], label=f"formula, {source}")
    lim = np.array([p[["measured_kN_per_m", "formula_kN_per_m"]].min().min(),
                    p[["measured_kN_per_m", "formula_kN_per_m"]].max().max()])
    ax.plot(lim, lim, "-", color="0.3", label="1:1")
    ax.plot(lim, 1.1 * lim, ":", color="0.5", label="±10 %")
    ax.plot(lim, 0.9 * lim, ":", color="0.5")
    ax.set(xlabel="measured rolling K (kN/m)", ylabel="predicted K (kN/m)",
           title="Fig. 32 — predicted against measured stiffness")
    _legend(ax)
    return to_svg(fig)


#: Spoke-model curves: table -> (x column, x label, thesis figure); defined with the pages
#: (:mod:`tyrelab.report.chapters`, which must not import matplotlib) and kept here by name.
from .chapters import SPOKE_FIGURES  # noqa: E402


def spoke_curves(curves: pd.DataFrame, x: str, xlabel: str, figure: str) -> str | None:
    """Figs 44–48: equivalent viscous damping of the rotating-spoke model.

    Parameters
    ----------
    curves : DataFrame
        A ``spoke_*`` table: ``figure``, ``model``, ``x`` and ``damping_N_s_per_m``.
    x : str
        Column on the horizontal axis.
    xlabel, figure : str
        Axis label and thesis figure number(s) for the title.
    """
    if not _has(curves, x, "damping_N_s_per_m"):
        return None
    groups = ["figure", "model"] if "figure" in curves.columns and curves["figure"].nunique() > 1 else ["model"]
    if "model" not in curves.columns:
        curves = curves.assign(model="model")
    fig, ax = _figure()
    for i, (key, g) in enumerate(curves.groupby(groups, sort=True)):
        key = key if isinstance(key, tuple) else (key,)
        label = ", ".join(f"Fig. {k}" if n == "figure" else str(k) for n, k in zip(groups, key))
        g = g.sort_values(x)
        ax.plot(g[x], g["damping_N_s_per_m"], marker=MARKERS[i % len(MARKERS)], markevery=max(1, len(g) // 8), label=label)
    ax.set(xlabel=xlabel, ylabel="equivalent damping (N s/m per unit coefficient)",
           title=f"{figure} — rotating-spoke damping model")
    _legend(ax)
    return to_svg(fig)


def profile_spectra(spectra: pd.DataFrame) -> str | None:
    """Fig. 51: power spectral density of the track profile estimates.

    Parameters
    ----------
    spectra : DataFrame
        ``profile_spectra`` (profile, n_cycles_per_m, psd_m3).
    """
    if not _has(spectra, "profile", "n_cycles_per_m", "psd_m3"):
        return None
    s = spectra.loc[(spectra["n_cycles_per_m"] > 0) & (spectra["psd_m3"] > 0)]
    if s.empty:
        return None
    fig, ax = _figure()
    for profile, g in s.groupby("profile", sort=True):
        g = g.sort_values("n_cycles_per_m")
        ax.loglog(g["n_cycles_per_m"], g["psd_m3"], lw=0.8, label=str(profile))
    ax.set(xlabel="wavenumber (cycles/m)", ylabel="PSD (m³/cycle)", title="Fig. 51 — track profile spectra")
    _legend(ax)
    return to_svg(fig)


def _carriage(comparisons: pd.DataFrame, estimate: str = "surveyed") -> pd.DataFrame:
    c = comparisons
    if "profile_estimate" in c.columns and (c["profile_estimate"] == estimate).any():
        c = c.loc[c["profile_estimate"] == estimate]
    return c.sort_values("speed_km_h")


def carriage_rms(comparisons: pd.DataFrame) -> str | None:
    """Fig. 54: measured and predicted rms acceleration of the carriage against speed.

    Parameters
    ----------
    comparisons : DataFrame
        ``carriage_comparisons`` (speed_km_h, characteristics, profile_estimate,
        load_condition, measured_rms, predicted_rms); the surveyed profile estimate.
    """
    if not _has(comparisons, "speed_km_h", "characteristics", "measured_rms", "predicted_rms"):
        return None
    c = _carriage(comparisons)
    fig, ax = _figure()
    meas = c.groupby("speed_km_h")["measured_rms"].mean()
    ax.plot(meas.index, meas.values, "+", ms=8, color="k", label="measured (+)")
    for (ch, marker) in (("rolling", "x"), ("stationary", "o")):
        g = c.loc[c["characteristics"] == ch].groupby("speed_km_h")["predicted_rms"].mean()
        if len(g):
            ax.plot(g.index, g.values, marker, mfc="none", label=f"predicted, {ch} tyre ({marker})")
    ax.set(xlabel="speed (km/h)", ylabel="rms acceleration (m/s²)",
           title="Fig. 54 — rms acceleration, surveyed profile")
    _legend(ax)
    return to_svg(fig)


def carriage_ratio_errors(comparisons: pd.DataFrame) -> str | None:
    """Fig. 55: ratio errors (predicted / measured) of rms acceleration against speed.

    Parameters
    ----------
    comparisons : DataFrame
        ``carriage_comparisons`` with ``ratio_rms``.
    """
    if not _has(comparisons, "speed_km_h", "characteristics", "ratio_rms"):
        return None
    c = _carriage(comparisons)
    fig, ax = _figure()
    for (ch, marker) in (("rolling", "x"), ("stationary", "o")):
        g = c.loc[c["characteristics"] == ch]
        if len(g):
            ax.plot(g["speed_km_h"], g["ratio_rms"], marker, mfc="none", label=f"{ch} tyre ({marker})")
    ax.axhline(1.0, color="0.3", lw=0.8)
    ax.set(xlabel="speed (km/h)", ylabel="ratio error (predicted / measured)",
           title="Fig. 55 — ratio errors of rms acceleration")
    _legend(ax)
    return to_svg(fig)


def acceleration_spectra(spectra: pd.DataFrame, speed_km_h: float = 12.5) -> str | None:
    """Fig. 56: measured and predicted vibration power spectra at one speed.

    Parameters
    ----------
    spectra : DataFrame
        Long table with ``frequency_Hz``, ``psd`` (or ``psd_m2_s4_per_Hz``),
        a series column (``series`` or ``characteristics``) and optionally
        ``speed_km_h`` (the speed nearest ``speed_km_h`` is plotted).
    """
    psd = next((c for c in ("psd", "psd_m2_s4_per_Hz", "acceleration_psd") if spectra is not None and c in spectra), None)
    series = next((c for c in ("series", "characteristics", "source") if spectra is not None and c in spectra), None)
    if psd is None or series is None or not _has(spectra, "frequency_Hz"):
        return None
    s = spectra
    if "speed_km_h" in s.columns:
        near = (s["speed_km_h"] - speed_km_h).abs()
        s = s.loc[near == near.min()]
    fig, ax = _figure()
    for key, g in s.groupby(series, sort=True):
        g = g.sort_values("frequency_Hz")
        ax.semilogy(g["frequency_Hz"], g[psd], lw=0.9, label=str(key))
    ax.set(xlabel="frequency (Hz)", ylabel="PSD ((m/s²)²/Hz)", title=f"Fig. 56 — vibration spectra at {speed_km_h:g} km/h")
    _legend(ax)
    return to_svg(fig)


def natural_frequencies(table_xx: pd.DataFrame) -> str | None:
    """Fig. 69: predicted against measured natural frequencies (bounce and pitch).

    Left: stiffness from the formula; right: measured stationary stiffness.

    Parameters
    ----------
    table_xx : DataFrame
        Our ``table_xx`` (tractor, stiffness_source, measured_frequency_{1,2}_Hz,
        ours_frequency_{1,2}_Hz, thesis_frequency_{1,2}_Hz).
    """
    if not _has(table_xx, "tractor", "stiffness_source", "measured_frequency_1_Hz", "measured_frequency_2_Hz"):
        return None
    ours = "ours_frequency_{}_Hz" if "ours_frequency_1_Hz" in table_xx else "frequency_{}_Hz"
    if ours.format(1) not in table_xx:
        return None
    sources = list(dict.fromkeys(table_xx["stiffness_source"]))[:2]
    fig, axes = _figure(1, len(sources), size=(6.4, 3.2), squeeze=False)
    tractors = list(dict.fromkeys(table_xx["tractor"]))
    for ax, source in zip(axes[0], sources):
        t = table_xx.loc[table_xx["stiffness_source"] == source]
        for i, tr in enumerate(tractors):
            r = t.loc[t["tractor"] == tr]
            for k in (1, 2):
                ax.plot(r[f"measured_frequency_{k}_Hz"], r[ours.format(k)], MARKERS[i % len(MARKERS)],
                        color=f"C{i}", mfc="none", label=tr if k == 1 else None)
                if f"thesis_frequency_{k}_Hz" in r:
                    ax.plot(r[f"measured_frequency_{k}_Hz"], r[f"thesis_frequency_{k}_Hz"], ".", color="0.5")
        lim = np.array([2.0, 4.5])
        ax.plot(lim, lim, "-", color="0.3", lw=0.8)
        ax.set(xlabel="measured (Hz)", ylabel="predicted (Hz)", title=str(source).replace("_", " "))
    axes[0][0].legend(loc="upper left", fontsize=6)
    fig.suptitle("Fig. 69 — natural frequencies (open: ours; grey dots: thesis)", fontsize=9)
    return to_svg(fig)


# ----------------------------------------------------------------- per-run drill-down

def run_spectra(signals: pd.DataFrame, axle_mass_kg: float, sample_rate_Hz: float,
                segment_s: float = 8.0) -> pd.DataFrame:
    """Acceleration PSD, dynamic stiffness and coherence of one recording.

    Tyre force ``f_t = M_a·mean(a_left, a_right) − Σ beams`` (thesis §3.2.8,
    :func:`tyrelab.measurement.recording.frame_tyre_force`); the apparent mass
    in the thesis convention is ``H = −f_t/a`` (Welch H1 estimate
    ``−S_af/S_aa``, :func:`tyrelab.measurement.apparent_mass.h1_spectrum`) and
    the dynamic stiffness is ``−ω²H`` whose real part is K and whose imaginary
    part over ω is C (docs/architecture.md).

    Parameters
    ----------
    signals : DataFrame
        Raw-format run columns (accel_left_m_s2, accel_right_m_s2, load_beam_1..4_N).
    axle_mass_kg : float
        Mass of the axle and everything below the load beams (kg).
    sample_rate_Hz : float
        Sampling rate (Hz).
    segment_s : float, optional
        Welch segment length (s).

    Returns
    -------
    DataFrame
        frequency_Hz, accel_psd_m2_s4_per_Hz, dynamic_stiffness_kN_per_m
        (magnitude), coherence; frequencies up to 20 Hz.
    """
    from ..measurement.apparent_mass import h1_spectrum
    from ..measurement.recording import frame_tyre_force, recording_arrays

    a = recording_arrays(signals)[0].mean(axis=0)
    f_t = frame_tyre_force(signals, axle_mass_kg)
    a, f_t = a - a.mean(), f_t - f_t.mean()
    nper = int(min(len(a), max(64, round(segment_s * sample_rate_Hz))))
    s = h1_spectrum(a, f_t, sample_rate_Hz, nper)
    f, saa, coh = s.frequency_Hz, s.psd_x, s.coherence
    with np.errstate(divide="ignore", invalid="ignore"):
        h = -s.h1
        kdyn = -(2 * np.pi * f) ** 2 * h
    keep = (f > 0) & (f <= 20.0)
    return pd.DataFrame({"frequency_Hz": f[keep], "accel_psd_m2_s4_per_Hz": saa[keep],
                         "dynamic_stiffness_kN_per_m": np.abs(kdyn[keep]) / 1e3, "coherence": coh[keep]})


def _draw_time_series(ax, signals: pd.DataFrame, seconds: float) -> None:
    s = signals.loc[signals["time_s"] <= signals["time_s"].iloc[0] + seconds]
    ax.plot(s["time_s"], s["accel_left_m_s2"], lw=0.8, label="accel left")
    ax.plot(s["time_s"], s["accel_right_m_s2"], lw=0.8, label="accel right")
    ax.set(xlabel="time (s)", ylabel="acceleration (m/s²)", title=f"axle accelerations, first {seconds:g} s")
    _legend(ax)


def _mark(ax, excitation_Hz: float | None, label: bool = True) -> None:
    if excitation_Hz is not None and np.isfinite(excitation_Hz):
        ax.axvline(excitation_Hz, ls="--", color="C3", lw=0.9,
                   label=f"excitation {excitation_Hz:g} Hz" if label else None)


def _draw_psd(ax, spectra: pd.DataFrame, excitation_Hz: float | None) -> None:
    psd = spectra["accel_psd_m2_s4_per_Hz"].to_numpy(float)
    ax.semilogy(spectra["frequency_Hz"], psd, lw=0.9)
    _plain_log(ax)
    if np.isfinite(psd).any() and np.nanmax(psd) > 0:  # six decades below the peak
        ax.set_ylim(np.nanmax(psd) * 1e-6, np.nanmax(psd) * 3)
    _mark(ax, excitation_Hz)
    ax.set(xlabel="frequency (Hz)", ylabel="PSD ((m/s²)²/Hz)", title="acceleration PSD")
    _legend(ax)


def _draw_transfer(ax, spectra: pd.DataFrame, excitation_Hz: float | None, stiffness_kN_per_m: float | None) -> None:
    k_dyn = spectra["dynamic_stiffness_kN_per_m"].to_numpy(float)
    ax.semilogy(spectra["frequency_Hz"], k_dyn, lw=0.9)
    _plain_log(ax)
    finite = k_dyn[np.isfinite(k_dyn) & (k_dyn > 0)]
    if finite.size:  # at most three decades around the median: spectral nulls would add dozens
        mid = np.median(finite)
        ax.set_ylim(max(finite.min(), mid / 30), min(finite.max(), mid * 30))
    _mark(ax, excitation_Hz, label=False)
    if stiffness_kN_per_m is not None and excitation_Hz is not None and np.isfinite(stiffness_kN_per_m):
        ax.plot([excitation_Hz], [abs(stiffness_kN_per_m)], "o", color="C3", label=f"K = {stiffness_kN_per_m:.0f} kN/m")
    ax.set(xlabel="frequency (Hz)", ylabel="|−ω²H| (kN/m)", title="transfer function (dynamic stiffness)")
    _legend(ax)


def _draw_coherence(ax, spectra: pd.DataFrame, excitation_Hz: float | None) -> None:
    ax.plot(spectra["frequency_Hz"], spectra["coherence"], lw=0.9, color="C2")
    _mark(ax, excitation_Hz, label=False)
    ax.set(xlabel="frequency (Hz)", ylabel="coherence", ylim=(0, 1.05), title="coherence force/acceleration")


def run_drilldown(signals: pd.DataFrame, spectra: pd.DataFrame, excitation_Hz: float | None = None,
                  stiffness_kN_per_m: float | None = None, seconds: float = 2.0) -> str | None:
    """Per-run page: time series, acceleration PSD, transfer function and coherence.

    One figure of four panels (one layout pass keeps the report build fast);
    the excitation frequency is marked on the three spectral panels.

    Parameters
    ----------
    signals : DataFrame
        Raw-format run columns with ``time_s``.
    spectra : DataFrame
        Output of :func:`run_spectra` (may be empty).
    excitation_Hz : float, optional
        Nominal excitation frequency (Hz), drawn as a dashed line.
    stiffness_kN_per_m : float, optional
        The run's estimated K, drawn as a dot at the excitation frequency.
    seconds : float, optional
        Length of the time-series window (keeps the SVG small).
    """
    has_time = _has(signals, "time_s", "accel_left_m_s2", "accel_right_m_s2")
    has_spec = _has(spectra, "frequency_Hz", "accel_psd_m2_s4_per_Hz", "dynamic_stiffness_kN_per_m", "coherence")
    if not has_time and not has_spec:
        return None
    fig, axes = _figure(2, 2, size=(7.6, 5.0), layout=None)  # fixed margins: constrained layout triples the time
    fig.subplots_adjust(left=0.11, right=0.98, bottom=0.09, top=0.94, wspace=0.34, hspace=0.45)
    (a_time, a_psd), (a_tf, a_coh) = axes
    if has_time:
        _draw_time_series(a_time, signals, seconds)
    if has_spec:
        _draw_psd(a_psd, spectra, excitation_Hz)
        _draw_transfer(a_tf, spectra, excitation_Hz, stiffness_kN_per_m)
        _draw_coherence(a_coh, spectra, excitation_Hz)
    return to_svg(fig)

