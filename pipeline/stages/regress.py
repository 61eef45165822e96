"""Regress: thesis chapters 4–5 as tables (Tables III–X, size fits, formula accuracy, spoke model).

Reads ``results`` and ``tyres`` (``build/parquet``; ``raw/tyres.csv`` if the
``tyres`` table is missing) and the published tables ``raw/published/table_*.csv``;
calls the pure functions of :mod:`tyrelab.tyre` and writes, under ``build/parquet``:

=============================  =============================================================
table                          contents
=============================  =============================================================
``table_iii``                  K_c, ΔK_p, r² per tyre × stationary/rolling, thesis beside ours
``stiffness_pressure_by_speed`` K vs P per tyre × individual speed
``damping_pressure_by_speed``  C vs P per tyre × individual speed
``table_vii``                  C_c, ΔC, r² per tyre × speed, thesis beside ours
``factor_regressions``         stiffness/damping rate vs amplitude, frequency, load, torque
``table_iv`` / ``table_viii``  amplitude rates (stiffness / damping), thesis beside ours
``surface_cells``              matched surface-vs-concrete cells (stiffness and damping)
``table_v`` / ``table_ix``     percent change per surface, thesis beside ours
``table_vi`` / ``table_x``     summary of rates, thesis beside ours
``size_regressions``           ΔK_p~W·R, K_c~R, K_c~age from published and from our Table III
``size_regression_search``     which tyre selections reproduce the printed coefficients
``formula_predictions``        per tyre × pressure: formula and stationary predictions, errors
``formula_accuracy``           mean, sd, within ±10 %, normal P(|e|<10 %) per source × method
``formula_fit``                K = a + b R + c A + d W R P fitted (WLS, cluster-robust by tyre) to the
                               published Table III and to our tyres, beside the printed coefficients;
                               leave-one-tyre-out errors of the refit and of the printed formula
``formula_fit_loto``           per tyre × pressure: the leave-one-tyre-out predictions behind those
``damping_fit``                C = c0 + c_A A + c_v v + c_P P fitted to the Table VII lines and to ours
                               (damping of an unmeasured tyre, :mod:`tyrelab.tyre.damping_fit`)
``spoke_force``                Fig. 43 data; ``spoke_speed`` Figs 44–45; ``spoke_frequency``
                               Fig. 46; ``spoke_amplitude`` Fig. 47; ``spoke_deflection`` Fig. 48
``spoke_fit`` / ``spoke_fit_points``  Coulomb and viscous coefficients per tyre from our damping
``results_vertical``           the ``results`` rows of vertical runs (every method; the thesis' direction)
``results_lateral`` /          the ``results`` rows of lateral / longitudinal runs, which no table or
``results_longitudinal``       figure of the thesis reads (issue 44)
=============================  =============================================================

Every tyre with measurement runs has rows (null estimates and a ``reason``
where it cannot be fitted); tyres only in the thesis keep their thesis values
with null estimates of ours.

Incremental: the fits that read one tyre's runs (Table III, per-speed K and C, the
one-factor rates, the spoke fit) are kept per tyre in ``build/cache/regress`` under
the digest of that tyre's ``results`` rows (the columns they read,
:data:`FIT_INPUT_COLUMNS`) and catalogue row (:class:`tyrelab.stages.state.ItemCache`),
so one new run refits its tyre only, and the tyres to refit are fitted in one pass; the
across-tyre tables (surface effects, summaries, size regressions, formula accuracy)
are recomputed from the per-tyre fits whenever the stage runs, and the parts that
read only the published tables are kept under the digest of those tables.
"""

from __future__ import annotations

import time

import numpy as np
import pandas as pd

from .. import published
from ..measurement.methods import DIRECTIONS as ALL_DIRECTIONS, direction_runs, thesis_runs
from ..tyre import conditions as cond
from ..tyre import damping_fit as dfit
from ..tyre import formula_accuracy as fa
from ..tyre import formula_fit as ff
from ..tyre import models
from ..tyre import regressions as reg
from ..tyre import size_regressions as sr
from ..tyre import spoke
from .base import Context, Progress, StageResult
from .state import ItemCache

__all__ = ["FIT_INPUT_COLUMNS", "PUBLISHED", "FACTORS", "read_published", "read_tyres", "tyre_fits", "tyre_fits_each",
           "FIT_PASSES", "ACROSS_TYRE_STEPS", "all_tyre_fits", "formula_fits", "damping_fits", "compute", "thesis_pool", "direction_tables", "DIRECTIONS",
           "DIRECTIONAL_TABLES", "direction_pool", "directional_fits", "run"]

#: The ``results`` columns the per-tyre fits read (:mod:`tyrelab.tyre.conditions` and the
#: runs' uncertainties): the fits are given only these, and a tyre's cache key is the digest
#: of exactly these, so a change elsewhere in a run's row (e.g. its campaign) refits nothing.
FIT_INPUT_COLUMNS = (*cond.RESULTS_COLUMNS, *reg.RESPONSE_UNCERTAINTY.values())
PUBLISHED = ("table_iii", "table_iv", "table_v", "table_vi", "table_vii", "table_viii", "table_ix", "table_x")
FACTORS = ("amplitude", "frequency", "load", "torque")


def read_published(ctx: Context) -> dict[str, pd.DataFrame | None]:
    """Published thesis tables (:mod:`tyrelab.published`; None where absent)."""
    available = set(published.stems(ctx.raw))
    return {name: published.read_published(name, ctx.raw) if name in available else None for name in PUBLISHED}


def read_tyres(ctx: Context) -> pd.DataFrame | None:
    """The ``tyres`` table, or ``raw/tyres.csv`` before ingest has written it."""
    if ctx.has_table("tyres"):
        return ctx.read_table("tyres")
    path = ctx.raw / "tyres.csv"
    return pd.read_csv(path) if path.exists() else None


def tyre_fits(results: pd.DataFrame, tyre_ids: list[str], tyres: pd.DataFrame | None) -> dict[str, pd.DataFrame]:
    """The fits that read one tyre's runs only: Table III and per-speed K and C vs pressure, the
    one-factor rates, the spoke-model fit (:mod:`tyrelab.tyre.conditions` selects runs row by row)."""
    rates = pd.concat([reg.factor_regressions(results, f) for f in FACTORS], ignore_index=True)
    fit, points = spoke.fit_tyres(results, tyres)
    return {
        "k_cond": reg.pressure_regressions(results, reg.STIFFNESS, by="condition", tyre_ids=tyre_ids),
        "k_speed": reg.pressure_regressions(results, reg.STIFFNESS, by="speed", tyre_ids=tyre_ids),
        "c_speed": reg.pressure_regressions(results, reg.DAMPING, by="speed", tyre_ids=tyre_ids),
        "rates": rates, "spoke_fit": fit, "spoke_fit_points": points,
    }


def tyre_fits_each(results: pd.DataFrame, tyre_ids: list[str], tyres: pd.DataFrame | None) -> dict[str, dict]:
    """:func:`tyre_fits` of each tyre of ``tyre_ids`` on its own, all tyres in one pass.

    ``out[tyre]`` equals ``tyre_fits(<results rows of tyre>, [tyre], <tyres row of tyre>)``: the
    runs are selected and grouped once for all tyres (:func:`tyrelab.tyre.regressions.pressure_regressions_each`,
    :func:`~tyrelab.tyre.regressions.factor_regressions_each`, :func:`tyrelab.tyre.spoke.fit_tyres_each`)
    and every fit reads its own tyre's runs only.
    """
    tyre_ids = [str(t) for t in tyre_ids]
    k_cond = reg.pressure_regressions_each(results, (reg.STIFFNESS,), by="condition", tyre_ids=tyre_ids)
    by_speed = reg.pressure_regressions_each(results, (reg.STIFFNESS, reg.DAMPING), by="speed", tyre_ids=tyre_ids)
    rates = [reg.factor_regressions_each(results, f, tyre_ids=tyre_ids) for f in FACTORS]
    catalogue = tyres if tyres is not None and "tyre_id" in tyres else None
    spokes = spoke.fit_tyres_each(results, catalogue, tyre_ids=tyre_ids)
    return {t: {"k_cond": k_cond[t][reg.STIFFNESS], "k_speed": by_speed[t][reg.STIFFNESS],
                "c_speed": by_speed[t][reg.DAMPING], "rates": pd.concat([r[t] for r in rates], ignore_index=True),
                "spoke_fit": spokes[t][0], "spoke_fit_points": spokes[t][1]} for t in tyre_ids}


#: The tyres to refit are fitted in at most this many passes of :func:`tyre_fits_each` (progress
#: between passes). On the full campaign 4 passes cost ~1.1x the CPU of one, 8 passes ~1.25x and
#: a pass per tyre ~1.5x (bench/bench_fit_passes.py, docs/benchmarks.md).
FIT_PASSES = 4
#: Steps of :func:`compute` after the per-tyre fits (for progress): Tables III-X, the size
#: regressions, the formula fits and spoke model.
ACROSS_TYRE_STEPS = 3


def all_tyre_fits(results: pd.DataFrame, tyres: pd.DataFrame | None, cache=None,
                  on_done=None) -> dict[str, pd.DataFrame]:
    """:func:`tyre_fits` of every measured tyre, each computed from its own runs (reused from
    ``cache`` when that tyre's runs and catalogue row are unchanged), in the all-tyre order.

    The fits read the :data:`FIT_INPUT_COLUMNS` of ``results`` only (a tyre's cache key is their
    digest). The runs are grouped by tyre once; the tyres not in the cache are fitted together
    in at most :data:`FIT_PASSES` passes (:func:`tyre_fits_each`: the same per-tyre tables as one
    :func:`tyre_fits` per tyre). ``on_done(n)``, if given, is called with the number of tyres
    each pass (or cache look-up) finished.
    """
    on_done = on_done or (lambda n: None)
    tyre_ids = reg.measured_tyres(results)
    if not tyre_ids:
        return tyre_fits(results, tyre_ids, tyres)
    results = results[[c for c in FIT_INPUT_COLUMNS if c in results.columns]]
    rows_of = results.groupby(results["tyre_id"].astype(str), sort=False).indices
    cat_of = tyres.groupby(tyres["tyre_id"].astype(str), sort=False).indices \
        if tyres is not None and "tyre_id" in tyres else None
    parts, keys, todo = {}, {}, []
    for t in tyre_ids:
        if cache is None:
            todo.append(t)
            continue
        own = results.iloc[rows_of[t]]
        row = None if cat_of is None else tyres.iloc[cat_of.get(t, np.empty(0, dtype=np.intp))]
        keys[t] = cache.key("tyre", t, own, row)
        hit, value = cache.get(keys[t])
        if hit:
            parts[t] = value
            on_done(1)
        else:
            todo.append(t)
    size = -(-len(todo) // FIT_PASSES)
    for start in range(0, len(todo), size or 1):
        some = todo[start:start + size]
        mine = np.sort(np.concatenate([rows_of[t] for t in some]))
        for t, value in tyre_fits_each(results.iloc[mine], some, tyres).items():
            parts[t] = value
            if cache is not None:
                cache.put(keys[t], value)
        on_done(len(some))
    parts = [parts[t] for t in tyre_ids]
    out = {name: _text_columns(pd.concat([p[name] for p in parts], ignore_index=True)) for name in parts[0]}
    # factor_regressions orders rows by factor, response, then tyre: restore that order
    rates = out["rates"]
    if not rates.empty:
        order = pd.DataFrame({"f": rates["factor"].map({f: i for i, f in enumerate(FACTORS)}),
                              "r": rates["response"].map({reg.STIFFNESS: 0, reg.DAMPING: 1})})
        out["rates"] = rates.loc[order.sort_values(["f", "r"], kind="stable").index].reset_index(drop=True)
    return out


def _text_columns(df: pd.DataFrame) -> pd.DataFrame:
    """Give text columns the string dtype the all-tyre computation gives them: a tyre whose
    ``reason`` is all missing has an object column, which would make the concatenation object."""
    for c in df.columns:
        if df[c].dtype == object:
            values = df[c].dropna()
            if len(values) and all(isinstance(v, str) for v in values):
                df[c] = df[c].astype("str")
    return df


def _published_source(table: pd.DataFrame, tyres: pd.DataFrame | None) -> dict:
    """Size regressions, selection search and formula accuracy of the printed Table III."""
    size, searches = _size_fits(table, tyres, "published")
    p = fa.predictions_from_table(table, tyres, source="published")
    return {"size": size, "searches": searches, "predictions": p, "accuracy": fa.accuracy_summary(p, "published")}


def _size_fits(table: pd.DataFrame, tyres: pd.DataFrame | None, source: str) -> tuple[pd.DataFrame, list]:
    """Size regressions of one Table III and the 25 best selections of each fit's search (each
    search done once: the size regressions' findings reuse it)."""
    full = {}
    if not table.empty:
        points = sr.tyre_points(table, tyres)
        full = {name: sr.selection_search(points, name) for name in sr.THESIS_FITS}
    searches = [full[name].head(25).assign(source=source) for name in full]
    return sr.size_regressions(table, tyres, source, searches=full), searches


def formula_fits(predictions: list[pd.DataFrame], memo=None) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Tables ``formula_fit`` and ``formula_fit_loto`` from the formula-prediction points of each source.

    A source with fewer than 5 usable traction tyres gets a row with a ``reason`` and null
    statistics; each fitted source carries its leave-one-tyre-out summary (mean absolute
    error of the refit and of the printed formula on the same points, and the share of
    points inside the refit's 95 % interval). ``memo(kind, inputs, compute)`` (:func:`compute`'s)
    keeps each source's fit and leave-one-tyre-out refits under the digest of its points: the
    published source's are not refitted when our runs change.
    """
    memo = memo or (lambda kind, inputs, fn: fn())
    fits, loto, reasons = [], [], {}
    for points in predictions:
        if points.empty:
            continue
        source = str(points["source"].iloc[0])

        def one(points=points, source=source) -> tuple:
            try:
                fit = ff.fit_formula(points, source)
            except ValueError as exc:
                return None, None, str(exc)
            return fit, ff.leave_one_tyre_out(points, source), None

        fit, refits, reason = memo("formula", (points, source), one)
        if reason is not None:
            reasons[source] = reason
            continue
        fits.append(fit)
        loto.append(refits)
    table = ff.fit_table(fits)
    extra = [{**models.fit_row(f)} for f in fits]
    wide = pd.DataFrame(extra, columns=[c for c in (extra[0] if extra else {}) if c not in table.columns] + ["source"])
    table = table.merge(wide, on="source", how="left") if len(wide) else table
    loto_df = pd.concat(loto, ignore_index=True) if loto else ff.leave_one_tyre_out(pd.DataFrame(
        columns=list(ff.POINT_COLUMNS)))
    stats = {}
    for source, sub in loto_df.groupby("source"):
        stats[source] = dict(loto_n_points=len(sub), loto_n_tyres=sub["tyre_id"].nunique(),
                             loto_mean_abs_error_percent=float(sub["refit_error_percent"].abs().mean()),
                             printed_mean_abs_error_percent=float(sub["printed_error_percent"].abs().mean()),
                             loto_coverage_fraction=float(sub["refit_covers"].mean()))
    for col in ("loto_n_points", "loto_n_tyres", "loto_mean_abs_error_percent", "printed_mean_abs_error_percent",
                "loto_coverage_fraction"):
        table[col] = table["source"].map(lambda s, c=col: stats.get(s, {}).get(c, np.nan))
    table["reason"] = None
    for source, reason in sorted(reasons.items()):
        table = pd.concat([table, pd.DataFrame([{"source": source, "reason": reason}])], ignore_index=True)
    return table, loto_df


def damping_fits(table_vii: pd.DataFrame | None, damping_by_speed: pd.DataFrame,
                 tyres: pd.DataFrame | None) -> pd.DataFrame:
    """Table ``damping_fit``: the Table VII model of the published lines and of ours (a row with a
    ``reason`` where a source cannot be fitted)."""
    fits, reasons = [], {}
    if tyres is None or "tyre_id" not in tyres:
        return dfit.damping_table([], {"published": "no tyres table", "ours": "no tyres table"})
    sources = [("published", table_vii), ("ours", damping_by_speed)]
    for source, lines in sources:
        if lines is None or lines.empty:
            reasons[source] = "no damping lines"
            continue
        try:
            fits.append(dfit.fit_damping(dfit.damping_points(lines, tyres, source), source))
        except ValueError as exc:
            reasons[source] = str(exc)
    return dfit.damping_table(fits, reasons)


def _spoke_curves() -> dict[str, pd.DataFrame]:
    """Figs 43-48 of the spoke model (no data: they change only with the code)."""
    return {"spoke_force": spoke.force_curves(), "spoke_speed": spoke.speed_curves(),
            "spoke_frequency": spoke.frequency_curves(), "spoke_amplitude": spoke.amplitude_curves(),
            "spoke_deflection": spoke.deflection_curves()}


def compute(results: pd.DataFrame, tyres: pd.DataFrame | None,
            published: dict[str, pd.DataFrame | None], cache=None, on_done=None) -> dict[str, pd.DataFrame]:
    """All regress tables from in-memory inputs (no I/O); see the module docstring.

    ``cache`` (a :class:`tyrelab.stages.state.ItemCache`) keeps the per-tyre fits and the parts
    that read only the published tables; the across-tyre tables are recomputed from them.
    ``on_done(n)``, if given, counts progress: one per measured tyre, then
    :data:`ACROSS_TYRE_STEPS` steps.
    """
    step = on_done or (lambda n: None)
    memo = (lambda kind, inputs, fn: cache.get_or_compute(cache.key(kind, *inputs), fn)) if cache else \
        (lambda kind, inputs, fn: fn())
    out: dict[str, pd.DataFrame] = {}
    fits = all_tyre_fits(results, tyres, cache, step)
    k_cond, c_speed, rates = fits["k_cond"], fits["c_speed"], fits["rates"]

    out["table_iii"] = reg.table_iii(k_cond, published.get("table_iii"))
    out["stiffness_pressure_by_speed"] = fits["k_speed"]
    out["damping_pressure_by_speed"] = c_speed
    out["table_vii"] = reg.table_vii(c_speed, published.get("table_vii"))

    out["factor_regressions"] = rates
    out["table_iv"] = reg.amplitude_table(rates, published.get("table_iv"), reg.STIFFNESS)
    out["table_viii"] = reg.amplitude_table(rates, published.get("table_viii"), reg.DAMPING)

    cells_k, sum_k = reg.surface_effects(results, reg.STIFFNESS)
    cells_c, sum_c = reg.surface_effects(results, reg.DAMPING)
    out["surface_cells"] = pd.concat([cells_k.assign(response=reg.STIFFNESS), cells_c.assign(response=reg.DAMPING)],
                                     ignore_index=True)
    out["table_v"] = reg.surface_table(sum_k, published.get("table_v"), reg.STIFFNESS)
    out["table_ix"] = reg.surface_table(sum_c, published.get("table_ix"), reg.DAMPING)

    out["table_vi"] = reg.summary_rates(out["stiffness_pressure_by_speed"], rates, reg.STIFFNESS,
                                        published=published.get("table_vi"))
    out["table_x"] = reg.summary_rates(c_speed, rates, reg.DAMPING, published=published.get("table_x"))
    step(1)

    ours_iii = k_cond.rename(columns={"intercept": "carcass_stiffness_kN_per_m",
                                      "slope": "pressure_dependence_kN_per_m_bar"})
    pub_iii = published.get("table_iii")
    size_ours, searches = _size_fits(ours_iii, tyres, "ours")
    size_rows, preds, acc = [size_ours], [], []
    preds.append(fa.predictions_from_recordings(results, ours_iii, tyres))
    acc.append(fa.accuracy_summary(preds[-1], "ours"))
    if pub_iii is not None:
        pub = memo("published", (pub_iii, tyres), lambda: _published_source(pub_iii, tyres))
        size_rows.append(pub["size"])
        searches += pub["searches"]
        preds.append(pub["predictions"])
        acc.append(pub["accuracy"])
    out["size_regressions"] = pd.concat(size_rows, ignore_index=True)
    step(1)
    out["size_regression_search"] = pd.concat(searches, ignore_index=True) if searches else pd.DataFrame(
        columns=["fit", "condition", "change", "n", "intercept", "slope", "r_squared", "matches_printed",
                 "distance", "source"])
    out["formula_predictions"] = pd.concat(preds, ignore_index=True)
    out["formula_accuracy"] = pd.concat(acc, ignore_index=True)
    out["formula_fit"], out["formula_fit_loto"] = formula_fits(preds, memo)
    out["damping_fit"] = damping_fits(published.get("table_vii"), c_speed, tyres)

    out.update(memo("spoke_curves", (), _spoke_curves))
    out["spoke_fit"], out["spoke_fit_points"] = fits["spoke_fit"], fits["spoke_fit_points"]
    step(1)
    return out


#: Directions with tables of their own (issue 34) and the tables each gets.
DIRECTIONS = ("lateral", "longitudinal")
DIRECTIONAL_TABLES = tuple(f"{d}_{q}" for d in DIRECTIONS for q in (
    "stiffness_pressure_by_speed", "damping_pressure_by_speed", "factor_regressions")) + ("series_damping_speed",)


#: ``results`` columns the direction tables read (an empty frame of them stands for no runs).
DIRECTIONAL_INPUT_COLUMNS = ("tyre_id", "kind", "direction", "method", "band_low_Hz", "band_high_Hz", "speed_km_h",
                             "pressure_bar", "load_kN", "excitation_frequency_Hz", "amplitude_mm_pp", "torque_kNm",
                             "surface", "stiffness_kN_per_m", "damping_kN_s_per_m", "stiffness_u_N_per_m",
                             "damping_u_N_s_per_m", "qc_ok", "qc_reasons", "model", "series_damping_N_s_per_m")


def direction_pool(results: pd.DataFrame, direction: str) -> pd.DataFrame:
    """The runs of ``direction`` whose K and C passed QC, as the regressions read them: a broadband
    run's K and C hold over its band, so it counts as excited at the nominal frequency (4 Hz inside
    the band) and amplitude."""
    if results.empty or "direction" not in results:
        return results.iloc[0:0]
    pool = results.loc[results["direction"] == direction].copy()
    broadband = pool["method"].isin(("random", "swept_sine"))
    inside = (pool["band_low_Hz"].fillna(1.0) <= 4.0) & (pool["band_high_Hz"].fillna(8.0) >= 4.0)
    pool.loc[broadband & inside, "excitation_frequency_Hz"] = 4.0
    pool.loc[broadband, "amplitude_mm_pp"] = 14.0
    return pool


def directional_fits(results: pd.DataFrame) -> dict[str, pd.DataFrame]:
    """Tables of the lateral and longitudinal runs (issue 34), the shape of the vertical ones: K and C
    against pressure per tyre and speed (``<direction>_stiffness_pressure_by_speed``,
    ``<direction>_damping_pressure_by_speed``), the load rates per tyre and speed
    (``<direction>_factor_regressions``), and the series damper of rolling runs against 1/speed
    (``series_damping_speed``: ``c₂ = a / v``, thesis §2.5, per tyre and direction)."""
    out = {}
    rows = []
    if results.empty or "direction" not in results:  # no runs, or a build from before issue 34: the tables' columns
        results = pd.DataFrame({c: pd.Series(dtype=float) for c in DIRECTIONAL_INPUT_COLUMNS}).astype(
            {c: object for c in ("tyre_id", "direction", "method", "surface", "kind", "model", "qc_reasons")})
    for d in DIRECTIONS:
        pool = direction_pool(results, d)
        ids = reg.measured_tyres(pool) if len(pool) else []
        out[f"{d}_stiffness_pressure_by_speed"] = reg.pressure_regressions(pool, reg.STIFFNESS, by="speed", tyre_ids=ids)
        out[f"{d}_damping_pressure_by_speed"] = reg.pressure_regressions(pool, reg.DAMPING, by="speed", tyre_ids=ids)
        out[f"{d}_factor_regressions"] = reg.factor_regressions(pool, "load")
        mw = pool.loc[(pool.get("model", pd.Series(dtype=object)) == "maxwell") & (pool["speed_km_h"] > 0)
                      & pool["qc_ok"].fillna(False).astype(bool)] if len(pool) else pool
        for tyre, g in mw.groupby("tyre_id", sort=True):
            x = 1.0 / g["speed_km_h"].to_numpy(float)
            y = g["series_damping_N_s_per_m"].to_numpy(float) / 1e3
            a = float(np.sum(x * y) / np.sum(x * x))
            se = float(np.sqrt(np.sum((y - a * x) ** 2) / max(len(x) - 1, 1) / np.sum(x * x))) if len(x) > 1 else np.nan
            rows.append({"direction": d, "tyre_id": tyre, "n": len(x), "speeds_km_h": " ".join(f"{v:g}" for v in sorted(set(g["speed_km_h"]))),
                         "coefficient_kN_s_per_m_times_km_h": a, "coefficient_se": se,
                         "note": "series damper c2 = a / v of the rolling runs fitted with the maxwell model"})
    out["series_damping_speed"] = pd.DataFrame(rows, columns=["direction", "tyre_id", "n", "speeds_km_h",
                                                              "coefficient_kN_s_per_m_times_km_h", "coefficient_se", "note"])
    return out


def direction_tables(results: pd.DataFrame) -> dict[str, pd.DataFrame]:
    """``results_<direction>``: the ``results`` rows of each direction, every column (issue 44: the
    vertical runs — the thesis' direction — apart from the lateral and longitudinal ones, so a query
    of one direction never averages in another); an empty build gives the tables with no rows."""
    return {f"results_{d}": direction_runs(results, d).reset_index(drop=True) for d in ALL_DIRECTIONS}


def thesis_pool(results: pd.DataFrame) -> pd.DataFrame:
    """The runs the thesis' tables rest on: vertical stepped-sine runs
    (:func:`tyrelab.measurement.methods.thesis_runs`; runs of the other methods and directions have
    tables of their own; a build without the columns is all of them)."""
    return thesis_runs(results)


def run(ctx: Context) -> StageResult:
    """Compute and write every regress table (module docstring)."""
    t0 = time.perf_counter()
    res = StageResult("regress")
    results = ctx.read_table("results") if ctx.has_table("results") else pd.DataFrame()
    if not results.empty and "tyre_id" in results:
        results["tyre_id"] = results["tyre_id"].astype(str)
    directional = {**directional_fits(results), **direction_tables(results)}
    results = thesis_pool(results)
    cache = ItemCache(ctx, "regress")
    progress = Progress("regress", len(reg.measured_tyres(results)) + ACROSS_TYRE_STEPS + 1, logger=ctx.log, unit="steps")
    tables = compute(results, read_tyres(ctx), read_published(ctx), cache, on_done=progress.step)
    cache.prune()
    tables.update(directional)
    for name, df in tables.items():
        ctx.write_table(name, df.reset_index(drop=True))
    progress.step()
    t3 = tables["table_iii"]
    fitted = t3.loc[t3["carcass_stiffness_kN_per_m"].notna(), "tyre_id"].nunique()
    res.n_in = len(results)
    res.n_ok = len(results.loc[results["qc_ok"].fillna(False).astype(bool)]) if "qc_ok" in results else 0
    sz = tables["size_regressions"].set_index(["source", "fit"])
    msg = [f"{len(tables)} tables", f"{fitted} tyres with Table III fits", f"per-tyre fits {cache.summary('tyre')}"]
    if ("published", "dkp_vs_wr") in sz.index:
        r = sz.loc[("published", "dkp_vs_wr")]
        msg.append(f"published dKp~W.R gradient {r['slope']:.3f}, r2 {r['r_squared']:.3f}")
    res.message = "; ".join(msg)
    res.seconds = time.perf_counter() - t0
    return res
