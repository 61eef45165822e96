"""The report's page of the other rig methods and directions (issue 34): H(f), K(f), C(f) per tyre
(issue 44: a lateral or longitudinal tyre's stepped-sine runs get their own K(f), C(f) figure here).

For every tyre with broadband runs (``swept_sine``, ``random``) the frequency response of each
run from the warehouse's ``frf`` table — the apparent mass H (thesis convention), K(f) and C(f)
with their 95 % error bars and the fitted tyre model, and the coherence with the fit's 0.9
limit — and for every tyre with lateral or longitudinal runs a direction section: the runs'
K, C and series damping with their intervals, by direction. Drawn by
:func:`frf_figure` (one figure per run) through the report's figure cache.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import tables
from .chapters import CHAPTERS
from .pages import Output, Page, register

__all__ = ["BROADBAND", "RUN_COLUMNS", "frf_figure", "stepped_figure", "MethodsPage"]

#: Methods whose runs have a frequency response (``frf``).
BROADBAND = ("swept_sine", "random")
#: Columns of a tyre's run list.
RUN_COLUMNS = ["run_id", "direction", "method", "speed_km_h", "pressure_bar", "load_kN", "model",
               "stiffness_kN_per_m", "stiffness_ci95_low_N_per_m", "stiffness_ci95_high_N_per_m",
               "damping_kN_s_per_m", "damping_ci95_low_N_s_per_m", "damping_ci95_high_N_s_per_m",
               "series_damping_N_s_per_m", "coherence", "qc_reasons"]


def _model_curve(f_Hz: np.ndarray, fit: dict):
    from ..measurement.broadband import maxwell_impedance

    w = 2 * np.pi * f_Hz
    k, c, c2 = (fit.get(n) for n in ("stiffness_N_per_m", "damping_N_s_per_m", "series_damping_N_s_per_m"))
    if k is None or not np.isfinite(k):
        return None
    z = maxwell_impedance(w, k, c, c2) if fit.get("model") == "maxwell" and np.isfinite(c2 or np.nan) \
        else k + 1j * w * c
    return z.real, z.imag / w


def frf_figure(frf: pd.DataFrame, fit: dict) -> str | None:
    """One broadband run: H(f) (thesis convention, real and imaginary), K(f) and C(f) with ±2u bars and
    the fitted model, coherence with the 0.9 limit; bins used in the fit filled, others open."""
    from .figures import _figure, to_svg  # matplotlib in the figure workers only

    if frf is None or frf.empty:
        return None
    f = frf["frequency_Hz"].to_numpy(float)
    used = frf["in_fit"].fillna(False).astype(bool).to_numpy()
    fig, axes = _figure(2, 2, size=(7.6, 5.0), layout=None)
    fig.subplots_adjust(left=0.1, right=0.98, bottom=0.1, top=0.92, wspace=0.32, hspace=0.45)
    (a_h, a_coh), (a_k, a_c) = axes
    a_h.plot(f, frf["apparent_mass_real_kg"], "-o", ms=3, label="Re H")
    a_h.plot(f, frf["apparent_mass_imag_kg"], "-s", ms=3, label="Im H")
    a_h.set(xlabel="frequency (Hz)", ylabel="apparent mass H (kg)", title="H1 = −S_af/S_aa (thesis convention)")
    a_h.legend(fontsize=6)
    curve = _model_curve(f, fit)
    for ax, col, ucol, scale, unit, idx in ((a_k, "stiffness_N_per_m", "stiffness_u_N_per_m", 1e3, "kN/m", 0),
                                            (a_c, "damping_N_s_per_m", "damping_u_N_s_per_m", 1e3, "kN s/m", 1)):
        y, u = frf[col].to_numpy(float) / scale, frf[ucol].to_numpy(float) / scale
        ax.errorbar(f[used], y[used], yerr=2 * u[used], fmt="o", ms=3, lw=0.8, label="bins fitted (±2u)")
        ax.plot(f[~used], y[~used], "o", ms=3, mfc="none", color="0.5", label="not coherent")
        if curve is not None:
            ax.plot(f, curve[idx] / scale, "-", color="C3", lw=1.0, label=str(fit.get("model", "")).replace("_", "–"))
        ax.set(xlabel="frequency (Hz)", ylabel=f"{'K' if idx == 0 else 'C'}(f) ({unit})")
        if used.any():
            lo, hi = np.nanmin(y[used] - 2 * u[used]), np.nanmax(y[used] + 2 * u[used])
            pad = 0.15 * (hi - lo) if hi > lo else abs(hi) * 0.1 + 1e-9
            ax.set_ylim(lo - pad, hi + pad)
        ax.legend(fontsize=6)
    a_k.set_title("dynamic stiffness: K(f) = Re(ω² F/A)")
    a_c.set_title("damping: C(f) = Im(ω² F/A)/ω")
    a_coh.plot(f, frf["coherence"], "-", color="C2")
    a_coh.axhline(0.9, ls="--", color="0.5", lw=0.8)
    a_coh.set(xlabel="frequency (Hz)", ylabel="coherence", ylim=(0, 1.05), title="coherence force/acceleration")
    return to_svg(fig)


def stepped_figure(runs: pd.DataFrame) -> str | None:
    """The stepped-sine runs of one tyre and direction (issue 44: a lateral or longitudinal run's own
    figure, never a vertical one's): H at each run's excitation frequency (thesis convention), K(f)
    and C(f) with their 95 % intervals, coherence; QC-passed runs filled, the others open."""
    from .figures import _figure, to_svg  # matplotlib in the figure workers only

    need = {"excitation_frequency_Hz", "stiffness_N_per_m", "damping_N_s_per_m"}
    if runs is None or runs.empty or not need <= set(runs.columns):
        return None
    r = runs.loc[runs["stiffness_N_per_m"].notna()].sort_values("excitation_frequency_Hz")
    if r.empty:
        return None
    f = r["excitation_frequency_Hz"].to_numpy(float)
    ok = r["qc_ok"].fillna(False).astype(bool).to_numpy() if "qc_ok" in r else np.ones(f.size, bool)
    col = lambda c: r[c].to_numpy(float) if c in r else np.full(f.size, np.nan)  # noqa: E731
    fig, axes = _figure(2, 2, size=(7.6, 5.0), layout=None)
    fig.subplots_adjust(left=0.1, right=0.98, bottom=0.1, top=0.92, wspace=0.32, hspace=0.45)
    (a_h, a_coh), (a_k, a_c) = axes
    a_h.plot(f, col("apparent_mass_real_kg"), "o", ms=4, label="Re H")
    a_h.plot(f, col("apparent_mass_imag_kg"), "s", ms=4, label="Im H")
    a_h.set(xlabel="excitation frequency (Hz)", ylabel="apparent mass H (kg)", title="H at each run's frequency")
    a_h.legend(fontsize=6)
    for ax, name, unit, label in ((a_k, "stiffness", "N_per_m", "K (kN/m)"), (a_c, "damping", "N_s_per_m", "C (kN s/m)")):
        y = col(f"{name}_{unit}") / 1e3
        lo, hi = col(f"{name}_ci95_low_{unit}") / 1e3, col(f"{name}_ci95_high_{unit}") / 1e3
        err = np.vstack([np.where(np.isfinite(lo), y - lo, 0), np.where(np.isfinite(hi), hi - y, 0)])
        ax.errorbar(f[ok], y[ok], yerr=err[:, ok], fmt="o", ms=4, lw=0.8, label="QC passed (95 %)")
        if (~ok).any():
            ax.plot(f[~ok], y[~ok], "o", ms=4, mfc="none", color="0.5", label="QC flagged")
        ax.set(xlabel="excitation frequency (Hz)", ylabel=label)
        ax.legend(fontsize=6)
    a_k.set_title("stiffness K(f)")
    a_c.set_title("damping C(f)")
    a_coh.plot(f, col("coherence"), "o", color="C2")
    a_coh.axhline(0.9, ls="--", color="0.5", lw=0.8)
    a_coh.set(xlabel="excitation frequency (Hz)", ylabel="coherence", ylim=(0, 1.05), title="coherence force/acceleration")
    return to_svg(fig)


@dataclass(frozen=True)
class MethodsPage(Page):
    """``rig-methods.html``: per tyre, the broadband runs' H(f), K(f), C(f) and a direction section."""

    slug: str = "rig-methods"
    title: str = "Rig methods and directions — H(f), K(f), C(f) by tyre"
    order: float = 10 * (len(CHAPTERS) + 1) + 5  # after the chapters and the measured ride

    @property
    def nav_title(self) -> str:
        return "Methods"

    def _runs(self, site) -> pd.DataFrame:
        r = site.results
        if r.empty or "method" not in r:
            return r.head(0)
        return r.loc[(r["method"].fillna("stepped_sine") != "stepped_sine") | (r["direction"].fillna("vertical") != "vertical")]

    def _frf(self, site) -> pd.DataFrame:
        return site.memo((self.slug, "frf"), lambda: site.wh.table("frf") if "frf" in site.wh else pd.DataFrame())

    def figures(self, site):
        runs, frf = self._runs(site), self._frf(site)
        out = []
        for _, row in runs.loc[runs["method"].isin(BROADBAND)].iterrows() if len(runs) else []:
            rows = frf.loc[frf["run_id"] == row["run_id"]].reset_index(drop=True) if len(frf) else frf
            fit = {k: (row.get(k) if pd.notna(row.get(k)) else np.nan) for k in
                   ("model", "stiffness_N_per_m", "damping_N_s_per_m", "series_damping_N_s_per_m")}
            out.append((("frf", row["run_id"]), site.function_task("methods_page.frf_figure", (rows, fit))))
        for (tyre, d), g in (self._stepped(runs).groupby(["tyre_id", "direction"], sort=True) if len(runs) else []):
            out.append((("stepped", tyre, d), site.function_task("methods_page.stepped_figure",
                                                                 (g.reset_index(drop=True),))))
        return out

    @staticmethod
    def _stepped(runs: pd.DataFrame) -> pd.DataFrame:
        """The lateral and longitudinal stepped-sine runs (a vertical one is the thesis' chapters')."""
        if runs.empty:
            return runs
        return runs.loc[(runs["method"].fillna("stepped_sine") == "stepped_sine")
                        & (runs["direction"].fillna("vertical") != "vertical")]

    def render(self, site):
        runs = self._runs(site)
        tyres = []
        for tyre, g in runs.groupby("tyre_id", sort=True) if len(runs) else []:
            shown = g.assign(series_damping_N_s_per_m=g["series_damping_N_s_per_m"] / 1e3).rename(
                columns={"series_damping_N_s_per_m": "series_damping_kN_s_per_m"})
            cols = [c if c != "series_damping_N_s_per_m" else "series_damping_kN_s_per_m" for c in RUN_COLUMNS]
            broadband = [{"run_id": r["run_id"], "caption": f"{r['direction']} {r['method'].replace('_', ' ')}, "
                          f"{r['speed_km_h']:g} km/h, {r['pressure_bar']:g} bar, {r['load_kN']:g} kN",
                          "figure": site.figs[("frf", r["run_id"])]}
                         for _, r in g.loc[g["method"].isin(BROADBAND)].iterrows()]
            stepped = self._stepped(g)
            directions = [{"direction": d, "table": tables.plain_table(shown.loc[shown["direction"] == d], cols, 60),
                           "figure": site.figs[("stepped", tyre, d)] if (stepped["direction"] == d).any() else None}
                          for d in ("lateral", "longitudinal") if (g["direction"] == d).any()]
            tyres.append({"tyre_id": tyre, "runs": tables.plain_table(shown, cols, 60), "broadband": broadband,
                          "directions": directions})
        return [Output(self.href, "methods.html.j2", self.title, {"tyres": tyres})]


register(MethodsPage())
