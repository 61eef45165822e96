"""Across-tyre regressions of §4.4.4 and §4.5.3: what the formula's coefficients rest on.

Three fits over Table III's rolling rows (thesis §4.5.3, Figs 26, 30, 31):

* ``dkp_vs_wr`` — pressure dependence ΔK_p against W·R (in², W and R from the
  size designation), all tyres but F1: printed intercept 0.297 kN/m/bar,
  gradient 0.34 kN/m/bar/in², r² 0.82;
* ``kc_vs_rim`` — carcass stiffness K_c against rim diameter R, excluding AS3,
  T1, T2, T4 and F1: printed 172 kN/m, −1.77 kN/m/in, r² 0.70;
* ``kc_vs_age`` — K_c against age for T1–T5 rolling: printed 5.6 kN/m per year
  (§4.4.4; no intercept or r² printed).

Each is computed from the published Table III and from our own Table III, with
the printed value beside it, and a ``finding`` that says whether the printed
coefficients come out and, if not, which selection of tyres (if any) does
(:func:`selection_search`). The point is to find out, not to tune.
"""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd

from .. import _validate
from .regressions import fit_line
from .sizes import TyreSizeError, parse_tyre_size

__all__ = ["THESIS_FITS", "tyre_points", "select", "selection_search", "variants", "size_regressions"]

#: The three printed fits (thesis §4.4.4, §4.5.3).
THESIS_FITS: dict[str, dict] = {
    "dkp_vs_wr": dict(
        x="wr_in2", y="pressure_dependence_kN_per_m_bar", condition="rolling",
        exclude=("F1",), include=None, intercept=0.297, slope=0.34, r_squared=0.82,
        tolerance=dict(intercept=None, slope=0.01, r_squared=0.01),
        x_unit="in^2", y_unit="kN/m/bar", ref="thesis §4.5.3, Fig. 30",
    ),
    "kc_vs_rim": dict(
        x="rim_diameter_in", y="carcass_stiffness_kN_per_m", condition="rolling",
        exclude=("AS3", "T1", "T2", "T4", "F1"), include=None, intercept=172.0, slope=-1.77,
        r_squared=0.70, tolerance=dict(intercept=2.0, slope=0.05, r_squared=0.01),
        x_unit="in", y_unit="kN/m", ref="thesis §4.5.3, Fig. 31",
    ),
    "kc_vs_age": dict(
        x="age_years", y="carcass_stiffness_kN_per_m", condition="rolling",
        exclude=(), include=("T1", "T2", "T3", "T4", "T5"), intercept=None, slope=5.6,
        r_squared=None, tolerance=dict(intercept=None, slope=0.2, r_squared=None),
        x_unit="year", y_unit="kN/m", ref="thesis §4.4.4, Fig. 26",
    ),
}


def _size_numbers(size) -> tuple[float, float]:
    try:
        s = parse_tyre_size(size)
        return s.section_width_in, s.rim_diameter_in
    except (TyreSizeError, TypeError):
        return np.nan, np.nan


def tyre_points(table: pd.DataFrame, tyres: pd.DataFrame | None = None) -> pd.DataFrame:
    """Table III rows with W, R, W·R and age attached.

    Parameters
    ----------
    table : DataFrame
        Table III-like: ``tyre_id, condition, carcass_stiffness_kN_per_m,
        pressure_dependence_kN_per_m_bar`` and optionally ``size``.
    tyres : DataFrame, optional
        ``tyres`` table (tyre_id, size, age_years, ...). Its size (Table II)
        wins over the table's own (Table III prints some sizes differently,
        e.g. AS11 13.6R38 vs Table II 13.6-38; W·R is the same).

    Returns
    -------
    DataFrame
        Adds ``size_used, section_width_in, rim_diameter_in, wr_in2, age_years``
        and ``size_in_table`` (the table's own designation).

    See Also
    --------
    select : one fit's rows of them.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> points = tyre_points(read_published("table_iii"), read_published("table_ii"))
    >>> len(points), points.loc[points["tyre_id"] == "T1", ["rim_diameter_in", "wr_in2"]].iloc[0].round(2).tolist()
    (34, [38.0, 516.8])
    """
    _validate.frame("table", table, ["tyre_id", "condition", "carcass_stiffness_kN_per_m", "pressure_dependence_kN_per_m_bar"])
    if tyres is not None:
        _validate.frame("tyres", tyres)
    t = table.copy()
    t["tyre_id"] = t["tyre_id"].astype(str)
    t["size_in_table"] = t["size"] if "size" in t else None
    if tyres is not None and not tyres.empty:
        cols = [c for c in ("tyre_id", "size", "age_years") if c in tyres]
        ty = tyres[cols].copy()
        ty["tyre_id"] = ty["tyre_id"].astype(str)
        ty = ty.rename(columns={"size": "size_catalogue"})
        t = t.drop(columns=[c for c in ("age_years",) if c in t]).merge(ty, on="tyre_id", how="left")
    if "size_catalogue" not in t:
        t["size_catalogue"] = None
    if "age_years" not in t:
        t["age_years"] = np.nan
    t["size_used"] = t["size_catalogue"].where(t["size_catalogue"].notna(), t["size_in_table"])
    wr = [_size_numbers(s) for s in t["size_used"]]
    t["section_width_in"] = [w for w, _ in wr]
    t["rim_diameter_in"] = [r for _, r in wr]
    t["wr_in2"] = t["section_width_in"] * t["rim_diameter_in"]
    t["age_years"] = pd.to_numeric(t["age_years"], errors="coerce")
    return t


def select(points: pd.DataFrame, spec: dict, *, exclude=None, include=None, condition=None) -> pd.DataFrame:
    """Rows of one fit's selection: condition, include/exclude lists, non-null x and y.

    See Also
    --------
    tyre_points : the points it selects from.
    variants : the fit under other selections.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> points = tyre_points(read_published("table_iii"), read_published("table_ii"))
    >>> s = select(points, THESIS_FITS["dkp_vs_wr"])          # Fig. 30: rolling, F1 left out
    >>> len(s), "F1" in set(s["tyre_id"])
    (16, False)
    """
    _validate.frame("points", points, ["tyre_id", "condition"])
    missing = [] if not isinstance(spec, dict) else [k for k in ("x", "y", "exclude", "include", "condition") if k not in spec]
    if not isinstance(spec, dict) or missing:
        raise ValueError(f"spec must be a fit of THESIS_FITS (x, y, exclude, include, condition), got {spec!r}")
    exclude = spec["exclude"] if exclude is None else exclude
    include = spec["include"] if include is None else include
    condition = spec["condition"] if condition is None else condition
    p = points
    if condition != "pooled":
        p = p.loc[p["condition"] == condition]
    if include:
        p = p.loc[p["tyre_id"].isin(include)]
    p = p.loc[~p["tyre_id"].isin(exclude)]
    p = p.loc[pd.to_numeric(p[spec["x"]], errors="coerce").notna() & pd.to_numeric(p[spec["y"]], errors="coerce").notna()]
    return p


def _matches(fit: dict, spec: dict) -> bool:
    for k, tol in spec["tolerance"].items():
        if tol is None or spec[k] is None:
            continue
        if not (np.isfinite(fit[k]) and abs(fit[k] - spec[k]) <= tol):
            return False
    return True


def _quick_fit(x, y) -> dict:
    """Closed-form least-squares line (intercept, slope, r²) for the many fits of a search."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    n = len(x)
    if n < 2 or np.ptp(x) == 0:
        return {"n": n, "intercept": np.nan, "slope": np.nan, "r_squared": np.nan}
    xm, ym = x.mean(), y.mean()
    sxx, sxy, syy = ((x - xm) ** 2).sum(), ((x - xm) * (y - ym)).sum(), ((y - ym) ** 2).sum()
    b = sxy / sxx
    return {"n": n, "intercept": ym - b * xm, "slope": b, "r_squared": sxy**2 / (sxx * syy) if syy > 0 else np.nan}


def selection_search(points: pd.DataFrame, name: str, *, max_excluded: int = 3,
                     condition: str | None = None) -> pd.DataFrame:
    """Which extra exclusions (up to ``max_excluded`` tyres) reproduce the printed fit.

    Starts from the thesis' stated selection and removes every combination of
    up to ``max_excluded`` of the remaining tyres; also tries putting each
    excluded tyre back.

    Returns
    -------
    DataFrame
        ``fit, condition, change, n, intercept, slope, r_squared, matches_printed``, sorted with
        the matching selections first, then by how close r² and slope come.

    See Also
    --------
    variants : the fit under the other data choices.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> points = tyre_points(read_published("table_iii"), read_published("table_ii"))
    >>> s = selection_search(points, "kc_vs_rim", max_excluded=1)
    >>> s[["change", "n", "slope"]].round(3).iloc[0].to_dict()
    {'change': 'also excluding AS11', 'n': 11, 'slope': -1.775}
    """
    _validate.frame("points", points, ["tyre_id", "condition"])
    _validate.choice("name", name, tuple(THESIS_FITS))
    max_excluded = _validate.positive_int("max_excluded", max_excluded, minimum=0)
    spec = THESIS_FITS[name]
    cond = condition or spec["condition"]
    base = select(points, spec, condition=cond)
    ids = sorted(base["tyre_id"].unique())
    # The many subsets as boolean masks over numpy arrays (same rows in the same order as
    # ``base.loc[~base["tyre_id"].isin(ex)]``, so the same sums, bit for bit).
    codes = base["tyre_id"].map({t: i for i, t in enumerate(ids)}).to_numpy(dtype=np.int64) if ids else \
        np.zeros(len(base), dtype=np.int64)
    xs, ys = np.asarray(base[spec["x"]], dtype=float), np.asarray(base[spec["y"]], dtype=float)
    of_tyre = codes[None, :] == np.arange(len(ids))[:, None]  # row mask of each tyre
    rows = []
    for k in range(0, max_excluded + 1):
        for ex_codes in itertools.combinations(range(len(ids)), k):
            ex = tuple(ids[i] for i in ex_codes)
            keep = ~np.logical_or.reduce(of_tyre[list(ex_codes)]) if ex_codes else np.ones(len(codes), dtype=bool)
            f = _quick_fit(xs[keep], ys[keep])
            rows.append(dict(fit=name, condition=cond,
                             change=("as printed" if not ex else "also excluding " + ",".join(ex)),
                             n=f["n"], intercept=f["intercept"], slope=f["slope"], r_squared=f["r_squared"]))
    for back in spec["exclude"]:
        sub = pd.concat([base, select(points, spec, exclude=[e for e in spec["exclude"] if e != back], condition=cond)
                         .loc[lambda d: d["tyre_id"] == back]])
        f = _quick_fit(sub[spec["x"]], sub[spec["y"]])
        rows.append(dict(fit=name, condition=cond, change=f"including {back}", n=f["n"],
                         intercept=f["intercept"], slope=f["slope"], r_squared=f["r_squared"]))
    out = pd.DataFrame(rows)
    out["matches_printed"] = [_matches(r, spec) for r in out.to_dict("records")]
    dist = (out["slope"] - spec["slope"]).abs() / max(abs(spec["slope"]), 1e-9)
    if spec["r_squared"] is not None:
        dist = dist + (out["r_squared"] - spec["r_squared"]).abs()
    out["distance"] = dist
    return out.sort_values(["matches_printed", "distance"], ascending=[False, True]).reset_index(drop=True)


def variants(points: pd.DataFrame, name: str) -> pd.DataFrame:
    """The fit under the other plausible data choices: stationary, pooled, through origin.

    See Also
    --------
    select : the rows of each variant.
    selection_search : exclusions that reproduce the printed fit.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> points = tyre_points(read_published("table_iii"), read_published("table_ii"))
    >>> v = variants(points, "dkp_vs_wr")
    >>> v[["variant", "n", "slope", "r_squared"]].round(3).iloc[0].to_dict()     # thesis Fig. 30: 0.34, r² 0.82
    {'variant': 'rolling, printed exclusions', 'n': 16, 'slope': 0.334, 'r_squared': 0.819}
    """
    _validate.frame("points", points, ["tyre_id", "condition"])
    _validate.choice("name", name, tuple(THESIS_FITS))
    spec = THESIS_FITS[name]
    rows = []
    for cond in ("rolling", "stationary", "pooled"):
        sub = select(points, spec, condition=cond)
        f = fit_line(sub[spec["x"]], sub[spec["y"]])
        rows.append(dict(fit=name, variant=f"{cond}, printed exclusions", n=f["n"], intercept=f["intercept"],
                         slope=f["slope"], r_squared=f["r_squared"]))
    sub = select(points, spec)
    x, y = sub[spec["x"]].to_numpy(float), sub[spec["y"]].to_numpy(float)
    if len(x):
        b = float(x @ y / (x @ x))
        rows.append(dict(fit=name, variant="rolling, through the origin", n=len(x), intercept=0.0,
                         slope=b, r_squared=np.nan))
    out = pd.DataFrame(rows)
    out["matches_printed"] = [_matches(r, spec) for r in out.to_dict("records")]
    return out


def _fmt(v, d=3):
    return "null" if v is None or not np.isfinite(v) else f"{v:.{d}g}"


def _finding(name: str, spec: dict, f: dict, sub: pd.DataFrame, points: pd.DataFrame, search=None) -> str:
    if f["n"] == 0 or not np.isfinite(f["slope"]):
        return f"not computable: {f['reason'] or 'no tyres in the selection'}"
    parts = []
    ok = _matches(f, spec)
    printed = [f"slope {_fmt(f['slope'])} (printed {spec['slope']})"]
    if spec["r_squared"] is not None:
        printed.append(f"r² {_fmt(f['r_squared'])} (printed {spec['r_squared']})")
    if spec["intercept"] is not None:
        printed.append(f"intercept {_fmt(f['intercept'])} [95 % CI {_fmt(f['intercept_ci_low'])}, "
                       f"{_fmt(f['intercept_ci_high'])}] (printed {spec['intercept']})")
    parts.append(("reproduced: " if ok else "NOT reproduced: ") + "; ".join(printed) + f"; n={f['n']}")
    if name == "dkp_vs_wr" and np.isfinite(f["intercept_ci_low"]):
        x = sub[spec["x"]].to_numpy(float)
        y = sub[spec["y"]].to_numpy(float)
        given = float(y.mean() - spec["slope"] * x.mean())
        parts.append(
            f"the intercept CI contains both 0.297 and 29.7, but with the printed gradient 0.34 the "
            f"least-squares intercept is {given:.2g} kN/m/bar; an intercept of 29.7 would put the line "
            f"{29.7 - given:.0f} kN/m/bar above the data centroid, so the printed 0.297 is a real ~0.3 "
            "(not a slipped 29.7), indistinguishable from 0 as the formula's ΔK_p = 0.34 W R assumes")
    diff = points.loc[points["size_in_table"].notna() & points["size_catalogue"].notna()
                      & (points["size_in_table"].astype(str) != points["size_catalogue"].astype(str))] \
        if "size_catalogue" in points else points.iloc[0:0]
    if len(diff):
        same = all(np.isclose(np.prod(_size_numbers(a)), np.prod(_size_numbers(b)))
                   for a, b in zip(diff["size_in_table"], diff["size_catalogue"]))
        pairs = sorted({f"{t} {a} vs {b}" for t, a, b in zip(diff["tyre_id"], diff["size_in_table"], diff["size_catalogue"])})
        parts.append("Table III and Table II sizes differ (" + "; ".join(pairs) + ") — "
                     + ("W and R identical, no effect on the fit" if same else "W·R differs: Table II sizes used"))
    if not ok:
        search = selection_search(points, name, max_excluded=3) if search is None else search
        hits = search.loc[search["matches_printed"]]
        if len(hits):
            parts.append(f"{len(hits)} selection(s) reproduce the printed values, first: "
                         + "; ".join(f"{h.change} (n={h.n}, slope {_fmt(h.slope)}, r² {_fmt(h.r_squared)})"
                                     for h in hits.head(3).itertuples()))
        else:
            best = search.iloc[0]
            parts.append("no selection excluding up to 3 more tyres or re-including one reproduces all printed "
                         f"values; closest: {best.change} (slope {_fmt(best.slope)}, r² {_fmt(best.r_squared)}, "
                         f"intercept {_fmt(best.intercept)})")
        var = variants(points, name)
        parts.append("other data: " + "; ".join(f"{v.variant}: slope {_fmt(v.slope)}, r² {_fmt(v.r_squared)}"
                                                  for v in var.itertuples()))
    return ". ".join(parts)


def size_regressions(table: pd.DataFrame, tyres: pd.DataFrame | None, source: str, *,
                     searches: dict[str, pd.DataFrame] | None = None) -> pd.DataFrame:
    """The three across-tyre fits from one Table III (``source`` "published" or "ours").

    Parameters
    ----------
    table : DataFrame
        Table III-like (see :func:`tyre_points`).
    tyres : DataFrame or None
        ``tyres`` table for sizes and ages.
    source : str
        Label for the ``source`` column.
    searches : dict, optional
        :func:`selection_search` (``max_excluded=3``) of each fit on ``tyre_points(table, tyres)``
        where the caller has it already; the findings of fits not reproduced use it instead
        of searching again.

    Returns
    -------
    DataFrame
        Per fit: ``fit, source, x, y, condition, selection, tyres_used, n``, the
        :func:`~tyrelab.tyre.regressions.fit_line` statistics, ``thesis_intercept,
        thesis_slope, thesis_r_squared``, differences, ``reproduces_printed``,
        ``finding`` and ``thesis_ref``.
    """
    _validate.frame("table", table, ["tyre_id", "condition", "carcass_stiffness_kN_per_m", "pressure_dependence_kN_per_m_bar"])
    if tyres is not None:
        _validate.frame("tyres", tyres)
    points = tyre_points(table, tyres) if not table.empty else pd.DataFrame(
        columns=["tyre_id", "condition", "wr_in2", "rim_diameter_in", "age_years",
                 "carcass_stiffness_kN_per_m", "pressure_dependence_kN_per_m_bar"])
    rows = []
    for name, spec in THESIS_FITS.items():
        sub = select(points, spec) if not points.empty else points
        f = fit_line(sub[spec["x"]], sub[spec["y"]]) if len(sub) else fit_line([], [])
        sel = (f"only {','.join(spec['include'])}; " if spec["include"] else "") + \
              (f"excluding {','.join(spec['exclude'])}" if spec["exclude"] else "")
        row = dict(fit=name, source=source, x=f"{spec['x']} ({spec['x_unit']})",
                   y=f"{spec['y']} ({spec['y_unit']})", condition=spec["condition"], selection=sel.strip("; "),
                   tyres_used=",".join(sorted(sub["tyre_id"].unique())) if len(sub) else None)
        row.update(f)
        row.update(thesis_intercept=spec["intercept"], thesis_slope=spec["slope"],
                   thesis_r_squared=spec["r_squared"])
        for k in ("intercept", "slope", "r_squared"):
            row[f"{k}_difference"] = (f[k] - spec[k]) if spec[k] is not None else np.nan
        row["reproduces_printed"] = bool(_matches(f, spec))
        row["finding"] = _finding(name, spec, f, sub, points, (searches or {}).get(name)) \
            if not points.empty else "no Table III rows"
        row["thesis_ref"] = spec["ref"]
        rows.append(row)
    return pd.DataFrame(rows)
