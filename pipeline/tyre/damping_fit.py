"""Damping of an unmeasured tyre: a fitted model of the Table VII lines (thesis §5.3, §5.4; issue 27).

Table VII gives, per tyre and rolling speed, ``C = C_c + ΔC P``. Its traction tyres are
all 13.6R38 (T1-T5, ages 1-16 years) at 10, 15 (and for T1 20) km/h, so no size term can
be fitted; what the lines do carry is age (older tyres damp more, §5.4.1), speed (damping
falls with speed, §5.3.2) and pressure (§5.3.1):

    C = c0 + c_A A + c_v v + c_P P          (kN s/m; A years, v km/h, P bar)

fitted by OLS to the lines evaluated on the rear pressure grid (0.8-1.6 bar) with a
cluster-robust covariance by tyre (CR1; the points of one tyre are one line) and Student
t on ``n_tyres − 1`` degrees of freedom. On the published table: ``c_A`` ≈ 0.10 kNs/m per
year (the thesis: about +2 kNs/m from new to very worn over 16 years, Table X), ``c_v``
≈ −0.06 per km/h, ``c_P`` ≈ 0.42 per bar, residual sd ≈ 0.2 kNs/m.

The prediction interval of a new tyre's damping is ``ĉ ± t sqrt(x0'Vx0 + s²)``. Outside
the fitted speeds the model is evaluated at the nearest fitted speed (held, as the thesis'
damping changes little from 15 km/h on, and a straight line would turn negative), and the
result says so; a tyre of another size is a 13.6R38 as far as this model knows, which the
warnings say too.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy.stats import t as student_t

from .. import _validate

__all__ = ["DAMPING_TERMS", "DampingPrediction", "DampingFit", "damping_points", "fit_damping", "damping_table"]

DAMPING_TERMS = ("intercept", "age", "speed", "pressure")
_GRID_BAR = (0.8, 1.0, 1.2, 1.4, 1.6)


@dataclass(frozen=True)
class DampingPrediction:
    """One prediction: ``damping_kN_s_per_m`` with its 95 % interval, standard uncertainty and notes."""

    damping_kN_s_per_m: float
    interval_kN_s_per_m: tuple[float, float]
    standard_uncertainty_kN_s_per_m: float
    speed_used_km_h: float
    warnings: tuple[str, ...] = ()


@dataclass(frozen=True)
class DampingFit:
    """``C = c0 + c_A A + c_v v + c_P P`` fitted to tyre × speed × pressure points (module docstring)."""

    source: str
    coefficients: tuple[float, float, float, float]
    covariance: tuple[tuple[float, ...], ...]
    residual_sd_kN_s_per_m: float
    r_squared: float
    n_tyres: int
    n_points: int
    ranges: dict = field(default_factory=dict)
    sizes: tuple[str, ...] = ()

    def predict(self, pressure_bar: float, speed_km_h: float, age_years: float = 1.0, *, size: str | None = None,
                level: float = 0.95) -> DampingPrediction:
        """Damping of a tyre the model has not measured, kN s/m, with its prediction interval.

        Examples
        --------
        >>> f = DampingFit("x", (0.9, 0.1, -0.06, 0.42), tuple(tuple(0.0 for _ in range(4)) for _ in range(4)),
        ...                0.2, 0.9, 5, 55, {"speed_km_h": (10.0, 20.0)})
        >>> p = f.predict(1.2, 30.0, 2.0)
        >>> round(p.damping_kN_s_per_m, 3), p.speed_used_km_h
        (0.404, 20.0)
        """
        pressure_bar = _validate.non_negative("pressure_bar", pressure_bar)
        speed_km_h = _validate.non_negative("speed_km_h", speed_km_h)
        age_years = _validate.non_negative("age_years", age_years)
        level = _validate.probability("level", level)
        notes = []
        lo, hi = self.ranges.get("speed_km_h", (speed_km_h, speed_km_h))
        v = min(max(speed_km_h, lo), hi)
        if v != speed_km_h:
            notes.append(f"speed {speed_km_h:g} km/h is outside the damping model's {lo:g}-{hi:g} km/h: "
                         f"evaluated at {v:g} km/h")
        for name, value in (("age_years", age_years), ("pressure_bar", pressure_bar)):
            a, b = self.ranges.get(name, (value, value))
            if not a <= value <= b:
                notes.append(f"{name} = {value:g} is outside the damping model's data ({a:g}-{b:g})")
        if size is not None and self.sizes and size not in self.sizes:
            notes.append(f"the damping model rests on {', '.join(self.sizes)} only (no size term); {size} is "
                         "treated as one of them")
        x0 = np.array([1.0, age_years, v, pressure_bar])
        c = float(x0 @ np.asarray(self.coefficients))
        u = math.sqrt(max(float(x0 @ np.asarray(self.covariance) @ x0), 0.0) + self.residual_sd_kN_s_per_m ** 2)
        t = float(student_t.ppf(0.5 + level / 2, max(self.n_tyres - 1, 1)))
        return DampingPrediction(c, (c - t * u, c + t * u), u, v, tuple(notes))

    def standard_errors(self) -> tuple[float, ...]:
        """Cluster-robust standard errors of :attr:`coefficients`."""
        return tuple(math.sqrt(max(self.covariance[i][i], 0.0)) for i in range(4))

    def row(self) -> dict:
        """One ``damping_fit`` row."""
        out = {"source": self.source, "n_tyres": self.n_tyres, "n_points": self.n_points, "r_squared": self.r_squared,
               "residual_sd_kN_s_per_m": self.residual_sd_kN_s_per_m, "sizes": " ".join(self.sizes)}
        for name, b, se in zip(DAMPING_TERMS, self.coefficients, self.standard_errors()):
            out[name], out[f"{name}_se"] = b, se
        for i, a in enumerate(DAMPING_TERMS):  # the whole covariance, so a fit can be read back (from_row)
            for j in range(i, len(DAMPING_TERMS)):
                out[f"cov_{a}_{DAMPING_TERMS[j]}"] = self.covariance[i][j]
        for name, (lo, hi) in self.ranges.items():
            out[f"{name}_min"], out[f"{name}_max"] = lo, hi
        return out

    @classmethod
    def from_row(cls, row) -> "DampingFit":
        """The fit one ``damping_fit`` row (:meth:`row`) holds: how a build's damping model is read back.

        Raises
        ------
        ValueError
            If ``row`` lacks a coefficient, the covariance or the counts (a row with a ``reason``).

        Examples
        --------
        >>> f = DampingFit("x", (0.9, 0.1, -0.06, 0.42), ((0.01, 0.0, 0.0, 0.0), (0.0, 0.02, 0.0, 0.0),
        ...                (0.0, 0.0, 0.03, 0.0), (0.0, 0.0, 0.0, 0.04)), 0.2, 0.9, 5, 55,
        ...                {"speed_km_h": (10.0, 20.0)}, ("13.6-38",))
        >>> DampingFit.from_row(f.row()) == f
        True
        """
        get = row.get if hasattr(row, "get") else (lambda k, d=None: getattr(row, k, d))
        names = list(DAMPING_TERMS) + [f"cov_{a}_{b}" for i, a in enumerate(DAMPING_TERMS) for b in DAMPING_TERMS[i:]]
        names += ["n_tyres", "n_points", "residual_sd_kN_s_per_m", "r_squared"]
        values = {k: get(k) for k in names}
        bad = sorted(k for k, v in values.items() if v is None or not math.isfinite(float(v)))
        if bad:
            raise ValueError(f"row: damping_fit row of {get('source')!r} has no {', '.join(bad)}"
                             + (f" ({get('reason')})" if isinstance(get("reason"), str) else ""))
        n = len(DAMPING_TERMS)
        cov = [[0.0] * n for _ in range(n)]
        for i, a in enumerate(DAMPING_TERMS):
            for j in range(i, n):
                cov[i][j] = cov[j][i] = float(values[f"cov_{a}_{DAMPING_TERMS[j]}"])
        ranges = {}
        for name in ("age_years", "speed_km_h", "pressure_bar"):
            lo, hi = get(f"{name}_min"), get(f"{name}_max")
            if lo is not None and hi is not None and math.isfinite(float(lo)) and math.isfinite(float(hi)):
                ranges[name] = (float(lo), float(hi))
        sizes = get("sizes")
        return cls(str(get("source")), tuple(float(values[t]) for t in DAMPING_TERMS),
                   tuple(tuple(r) for r in cov), float(values["residual_sd_kN_s_per_m"]), float(values["r_squared"]),
                   int(values["n_tyres"]), int(values["n_points"]), ranges,
                   tuple(str(sizes).split()) if isinstance(sizes, str) else ())


def damping_points(lines: pd.DataFrame, tyres: pd.DataFrame, source: str = "published",
                   grid_bar=_GRID_BAR) -> pd.DataFrame:
    """Tyre × speed × pressure points of per-speed damping lines (rolling traction tyres only).

    Parameters
    ----------
    lines : DataFrame
        ``tyre_id, speed_km_h`` and ``carcass_damping_kN_s_per_m``/``pressure_dependence_kN_s_per_m_bar``
        (Table VII) or ``intercept``/``slope`` (``damping_pressure_by_speed``).
    tyres : DataFrame
        ``tyre_id, size, age_years`` and ``group`` or ``position`` (ribbed fronts left out;
        a missing age is 0, as for Table II's new tyres).

    See Also
    --------
    fit_damping : the fit of these points.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> points = damping_points(read_published("table_vii"), read_published("table_ii"))
    >>> len(points), points["tyre_id"].nunique()          # Table VII's rolling traction tyres
    (55, 5)
    """
    _validate.frame("lines", lines, ["tyre_id", "speed_km_h"])
    _validate.frame("tyres", tyres, ["tyre_id", "size", "age_years"])
    _validate.positive_array("grid_bar", grid_bar)
    cc = "carcass_damping_kN_s_per_m" if "carcass_damping_kN_s_per_m" in lines else "intercept"
    dc = "pressure_dependence_kN_s_per_m_bar" if "pressure_dependence_kN_s_per_m_bar" in lines else "slope"
    cat = tyres.assign(tyre_id=tyres["tyre_id"].astype(str)).drop_duplicates("tyre_id", keep="last").set_index("tyre_id")
    kind = cat["group"] if "group" in cat else cat.get("position", pd.Series("", index=cat.index))
    rows = []
    for r in lines.itertuples(index=False):
        tid, v = str(r.tyre_id), float(r.speed_km_h)
        c0, dcp = float(getattr(r, cc)), float(getattr(r, dc))
        if tid not in cat.index or not (v > 0 and math.isfinite(c0) and math.isfinite(dcp)):
            continue
        if "ribbed" in str(kind.get(tid, "")) or "undriven" in str(kind.get(tid, "")):
            continue
        age = pd.to_numeric(pd.Series([cat.at[tid, "age_years"]]), errors="coerce").fillna(0.0).iloc[0]
        for p in grid_bar:
            rows.append(dict(source=source, tyre_id=tid, size=str(cat.at[tid, "size"]), age_years=float(age),
                             speed_km_h=v, pressure_bar=float(p), damping_kN_s_per_m=c0 + dcp * p))
    return pd.DataFrame(rows, columns=["source", "tyre_id", "size", "age_years", "speed_km_h", "pressure_bar",
                                       "damping_kN_s_per_m"])


def fit_damping(points: pd.DataFrame, source: str = "published") -> DampingFit:
    """Fit the damping model to :func:`damping_points` (module docstring).

    Raises
    ------
    ValueError
        With fewer than 5 tyres or a design that cannot separate age, speed and pressure.

    See Also
    --------
    damping_points : the points it fits.
    damping_table : the warehouse table of the fits.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> points = damping_points(read_published("table_vii"), read_published("table_ii"))
    >>> f = fit_damping(points)
    >>> f.n_tyres, f.n_points, round(f.r_squared, 3)
    (5, 55, 0.887)
    """
    _validate.frame("points", points, ["tyre_id", "size", "age_years", "speed_km_h", "pressure_bar", "damping_kN_s_per_m"])
    from statsmodels.regression.linear_model import OLS

    p = points.dropna(subset=["age_years", "speed_km_h", "pressure_bar", "damping_kN_s_per_m"])
    n_tyres = int(p["tyre_id"].nunique()) if len(p) else 0
    if n_tyres < 5:
        raise ValueError(f"points: the damping model needs at least 5 tyres, got {n_tyres}")
    x = np.column_stack([np.ones(len(p)), p["age_years"], p["speed_km_h"], p["pressure_bar"]]).astype(float)
    if np.linalg.matrix_rank(x) < 4:
        raise ValueError("points: the tyres do not separate age, speed and pressure (rank-deficient design)")
    y = p["damping_kN_s_per_m"].to_numpy(float)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = OLS(y, x).fit(cov_type="cluster", cov_kwds={"groups": pd.factorize(p["tyre_id"])[0]})
    beta = np.asarray(res.params, float)
    resid = y - x @ beta
    span = {c: (float(p[c].min()), float(p[c].max())) for c in ("age_years", "speed_km_h", "pressure_bar")}
    return DampingFit(source, tuple(float(b) for b in beta),
                      tuple(tuple(float(v) for v in r) for r in np.asarray(res.cov_params(), float)),
                      float(np.sqrt(np.sum(resid**2) / max(len(y) - 4, 1))),
                      float(1 - np.sum(resid**2) / np.sum((y - y.mean()) ** 2)), n_tyres, int(len(y)), span,
                      tuple(sorted(p["size"].astype(str).unique())))


def damping_table(fits: list[DampingFit], reasons: dict[str, str] | None = None) -> pd.DataFrame:
    """Table ``damping_fit``: one row per fitted source, plus a row with the reason for each that could not be.

    See Also
    --------
    fit_damping : the fits it lists.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> points = damping_points(read_published("table_vii"), read_published("table_ii"))
    >>> t = damping_table([fit_damping(points)], {"ours": "too few tyres"})
    >>> t["source"].tolist(), t["reason"].tolist()[1]
    (['published', 'ours'], 'too few tyres')
    """
    _validate.instances("fits", fits, DampingFit)
    rows = [f.row() for f in fits] + [{"source": s, "reason": r} for s, r in sorted((reasons or {}).items())]
    cols = ["source", "n_tyres", "n_points", "r_squared", "residual_sd_kN_s_per_m"]
    cols += [c for name in DAMPING_TERMS for c in (name, f"{name}_se")]
    cols += [f"{n}_{e}" for n in ("age_years", "speed_km_h", "pressure_bar") for e in ("min", "max")]
    cols += ["sizes", "reason"]
    cols += [f"cov_{a}_{b}" for i, a in enumerate(DAMPING_TERMS) for b in DAMPING_TERMS[i:]]
    return pd.DataFrame(rows).reindex(columns=cols)
