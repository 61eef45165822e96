"""The stiffness formula as a fitted model: ``K = a + b R + c A + d W R P`` (thesis §4.5.3, issue 27).

The thesis built its formula from three separate regressions over Table III's rolling
lines (ΔK_p on W·R; K_c on R with five tyres left out; K_c on age over T1–T5:
:mod:`tyrelab.tyre.size_regressions` reproduces them). Here the same form is fitted in
one step to tyre × pressure points, so that it has a covariance and a prediction interval
and can be refitted on any lab's measured tyres:

* **points**: each traction tyre's rolling stiffness at its pressures (published Table
  III: ``K_c + ΔK_p P`` on the pressure grid of :mod:`~tyrelab.tyre.formula_accuracy`;
  a lab's: the mean rolling-pool stiffness per tyre and measured pressure);
* **estimator**: weighted least squares (statsmodels ``WLS``) with weights ``1/K̂²``
  from an OLS first pass: the scatter about the formula grows with the stiffness (on
  the published points |residual| rises with the fitted value, Spearman 0.26, p 0.02;
  the relative residual does not, 0.07, p 0.5), and the thesis states the formula's
  error in percent;
* **covariance**: cluster-robust by tyre (CR1, statsmodels ``cov_type="cluster"``),
  with Student t on ``n_tyres − 1`` degrees of freedom. The points of one tyre are
  one measured line, not independent observations; a mixed model would need a random
  intercept *and* a random pressure slope (tyres differ in both, Table III) from 16
  clusters, and the formula is a population-average model in any case, which is what
  OLS/WLS with a cluster-robust covariance estimates without assuming the within-tyre
  correlation structure;
* **prediction interval** of *that* tyre's measured stiffness at ``x0`` (issue 34):
  ``x0'β̂ ± t · sqrt(lev(x0) + (s K̂0)²)``. ``s K̂0`` is the tyre-to-tyre scatter (``s``
  the relative residual sd). ``lev(x0)`` is the variance of the fitted mean at the tyre's
  W, R, A and P, the larger of two leave-one-tyre-out jackknife (CR3) variances: that of
  the formula itself, ``x0' V_J x0``, and that of the formula extended by W and P as
  separate terms, ``xe' V_E xe`` with ``xe = [1, R, A, W R P, W, P]``. CR1 with 16
  clusters is optimistic where a tyre has leverage (its own residual is shrunk towards
  the fit; leave-one-tyre-out coverage 89 % for a nominal 95 %); the jackknife leaves the
  tyre out (MacKinnon & White 1985; Bell & McCaffrey 2002). The extension is there
  because the formula's terms are well determined along W·R·P — so its own leverage
  grows about as fast as K and the relative width barely moved far outside the data
  (0.32 → 0.35 for an IF 710/70R42) — while a tyre far from the data in W or P
  separately is an extrapolation of the formula's *form* the 16 tyres cannot check; how
  much the extended fit's mean can move there says how far the data pin the form.
  Where the extended design (or a replicate of it) cannot separate its terms, the
  formula's jackknife is used alone; where that cannot be formed either, the CR1 ``V``.

All stiffnesses in kN/m per tyre; W and R in inches, A in years, P in bar.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy.stats import t as student_t

from .. import _validate
from .sizes import TyreSize, TyreSizeError, parse_tyre_size

__all__ = ["TERMS", "EXTENDED_TERMS", "TERM_UNITS", "POINT_COLUMNS", "PRINTED_COEFFICIENTS", "FormulaPrediction", "FormulaFit",
           "design_matrix", "extended_design_matrix", "fit_formula",
           "leave_one_tyre_out", "FrontRule", "front_rule", "fit_table"]

#: The formula's terms, in coefficient order, with units of their coefficients.
TERMS = ("intercept", "rim_diameter", "age", "wrp")
TERM_UNITS = ("kN/m", "kN/m/in", "kN/m/year", "kN/m/in²/bar")
#: The formula's terms and the two size terms it leaves out (section width W, in; pressure P,
#: bar), whose fit's jackknife covariance enters the leverage of a prediction (module docstring).
EXTENDED_TERMS = TERMS + ("width", "pressure")
#: The thesis' printed coefficients (§4.5.3, §4.6): K = 172 − 1.77 R + 5.6 A + 0.34 W R P.
PRINTED_COEFFICIENTS = (172.0, -1.77, 5.6, 0.34)

#: Columns of the points a fit needs (those of :data:`tyrelab.tyre.formula_accuracy.PRED_COLUMNS`).
POINT_COLUMNS = ("tyre_id", "size", "age_years", "pressure_bar", "measured_kN_per_m")


def _size(size) -> TyreSize:
    return size if isinstance(size, TyreSize) else parse_tyre_size(size)


def design_matrix(sizes, age_years, pressure_bar) -> np.ndarray:
    """Rows ``[1, R, A, W R P]`` of the formula for sizes, ages (years) and pressures (bar).

    See Also
    --------
    fit_formula : fits the formula on these rows.
    extended_design_matrix : with W and P besides.

    Examples
    --------
    >>> design_matrix(["13.6R38"], [1.0], [1.2]).round(2).tolist()
    [[1.0, 38.0, 1.0, 620.16]]
    """
    _validate.non_negative_array("age_years", age_years)
    _validate.non_negative_array("pressure_bar", pressure_bar)
    s = [_size(x) for x in sizes]
    a = np.asarray(age_years, float)
    p = np.asarray(pressure_bar, float)
    if len(s) != len(a) or len(s) != len(p):
        raise ValueError(f"sizes, age_years and pressure_bar must have the same length, got {len(s)}, {len(a)}, {len(p)}")
    return np.column_stack([np.ones(len(s)), [z.rim_diameter_in for z in s], a,
                            np.array([z.width_times_rim_in2 for z in s]) * p]) if s else np.empty((0, 4))


def extended_design_matrix(sizes, age_years, pressure_bar) -> np.ndarray:
    """Rows ``[1, R, A, W R P, W, P]`` (:data:`EXTENDED_TERMS`) for sizes, ages (years) and pressures (bar).

    See Also
    --------
    design_matrix : the formula's own four terms.

    Examples
    --------
    >>> extended_design_matrix(["13.6R38"], [1.0], [1.2]).round(2).tolist()
    [[1.0, 38.0, 1.0, 620.16, 13.6, 1.2]]
    """
    x = design_matrix(sizes, age_years, pressure_bar)
    w = np.array([_size(z).section_width_in for z in sizes], float).reshape(-1)
    return np.column_stack([x, w, np.asarray(pressure_bar, float).reshape(-1)]) if len(x) else np.empty((0, 6))


def _wls_beta(x: np.ndarray, y: np.ndarray) -> np.ndarray | None:
    """The fit's estimator in numpy: OLS, then WLS with weights 1/K̂² (None if rank-deficient)."""
    if np.linalg.matrix_rank(x) < x.shape[1]:
        return None
    b0 = np.linalg.lstsq(x, y, rcond=None)[0]
    sw = 1.0 / np.maximum(x @ b0, 0.05 * np.abs(y).max())
    return np.linalg.lstsq(x * sw[:, None], y * sw, rcond=None)[0]


def _jackknife_covariance(x: np.ndarray, y: np.ndarray, groups: np.ndarray) -> np.ndarray | None:
    """Leave-one-tyre-out jackknife covariance (CR3) of :func:`_wls_beta`:
    ``(G − 1)/G Σ_g (β̂_(g) − β̄)(β̂_(g) − β̄)'``; None if any replicate cannot be fitted."""
    labels = np.unique(groups)
    if len(labels) < 3 or _wls_beta(x, y) is None:
        return None
    reps = []
    for g in labels:
        keep = groups != g
        b = _wls_beta(x[keep], y[keep])
        if b is None:
            return None
        reps.append(b)
    d = np.asarray(reps) - np.mean(reps, axis=0)
    return (len(labels) - 1) / len(labels) * d.T @ d


def _as_tuple(matrix) -> tuple | None:
    return None if matrix is None else tuple(tuple(float(v) for v in row) for row in np.asarray(matrix))


@dataclass(frozen=True)
class FormulaPrediction:
    """One prediction of a fitted formula.

    Attributes
    ----------
    stiffness_kN_per_m : float
        ``x0'β̂``, kN/m.
    interval_kN_per_m : (float, float)
        95 % (or ``level``) prediction interval of the tyre's measured rolling stiffness, kN/m.
    standard_uncertainty_kN_per_m : float
        ``sqrt(lev(x0) + (s K̂0)²)``, kN/m (module docstring).
    mean_se_kN_per_m : float
        Standard error of the fitted mean alone, ``sqrt(lev(x0))`` (the leverage part), kN/m.
    coverage_factor : float
        Student t factor used.
    """

    stiffness_kN_per_m: float
    interval_kN_per_m: tuple[float, float]
    standard_uncertainty_kN_per_m: float
    mean_se_kN_per_m: float
    coverage_factor: float


@dataclass(frozen=True)
class FormulaFit:
    """``K = a + b R + c A + d W R P`` fitted to tyre × pressure points (module docstring).

    Attributes
    ----------
    source : str
        Which points (``"published"``: thesis Table III; ``"ours"``: the build's tyres).
    coefficients : tuple of float
        ``(a, b, c, d)`` in :data:`TERMS` order (kN/m, kN/m/in, kN/m/year, kN/m/in²/bar).
    covariance : tuple of tuple of float
        Cluster-robust (by tyre, CR1) covariance of the coefficients.
    relative_residual_sd : float
        ``s``: residual sd of the weighted fit, a fraction of the stiffness.
    residual_sd_kN_per_m : float
        Root mean square of the unweighted residuals over the fit's degrees of freedom, kN/m.
    r_squared : float
        ``Σ(K̂−K̄)²/Σ(K−K̄)²`` (unweighted, the thesis' r², §4.3.1).
    n_tyres, n_points : int
    tyre_ids : tuple of str
    ranges : dict
        (min, max) of ``wr_in2``, ``rim_diameter_in``, ``age_years``, ``pressure_bar`` of the points.
    method : str
    leverage_covariance : tuple of tuple of float or None
        Leave-one-tyre-out jackknife (CR3) covariance of :attr:`coefficients` (None: not
        formed, :attr:`covariance` is used).
    extended_covariance : tuple of tuple of float or None
        Jackknife covariance of the fit extended by W and P (:data:`EXTENDED_TERMS`; None:
        the extension cannot be fitted).
    """

    source: str
    coefficients: tuple[float, float, float, float]
    covariance: tuple[tuple[float, ...], ...]
    relative_residual_sd: float
    residual_sd_kN_per_m: float
    r_squared: float
    n_tyres: int
    n_points: int
    tyre_ids: tuple[str, ...] = ()
    ranges: dict = field(default_factory=dict)
    method: str = ("WLS (weights 1/K̂² from an OLS pass), cluster-robust covariance by tyre (CR1), "
                   "t with n_tyres − 1 degrees of freedom")
    leverage_covariance: tuple[tuple[float, ...], ...] | None = None
    extended_covariance: tuple[tuple[float, ...], ...] | None = None

    @property
    def dof(self) -> int:
        """Degrees of freedom of the t factor: ``n_tyres − 1`` (clusters, not points)."""
        return max(self.n_tyres - 1, 1)

    def standard_errors(self) -> tuple[float, ...]:
        """Cluster-robust standard errors of :attr:`coefficients`."""
        return tuple(float(math.sqrt(max(self.covariance[i][i], 0.0))) for i in range(len(TERMS)))

    def coverage_factor(self, level: float = 0.95) -> float:
        """Student t factor for ``level`` on :attr:`dof` degrees of freedom."""
        level = _validate.probability("level", level)
        return float(student_t.ppf(0.5 + level / 2, self.dof))

    def predict(self, size, pressure_bar: float, age_years: float = 1.0, *, level: float = 0.95) -> FormulaPrediction:
        """Prediction and prediction interval for one tyre (kN/m).

        Examples
        --------
        >>> f = FormulaFit("x", (172.0, -1.77, 5.6, 0.34), tuple(tuple(0.0 for _ in range(4)) for _ in range(4)),
        ...                0.1, 30.0, 0.9, 14, 56)
        >>> p = f.predict("13.6-38", 1.1, 1)
        >>> round(p.stiffness_kN_per_m, 1), round(p.standard_uncertainty_kN_per_m, 2)
        (303.6, 30.36)
        """
        s = _size(size)
        return self.predict_terms(s.rim_diameter_in, s.width_times_rim_in2, pressure_bar, age_years, level=level)

    def predict_terms(self, rim_diameter_in: float, wr_in2: float, pressure_bar: float, age_years: float = 1.0, *,
                      level: float = 0.95) -> FormulaPrediction:
        """:meth:`predict` from the terms themselves: rim diameter R (in), W·R (in²), P (bar), A (years).

        Examples
        --------
        >>> f = FormulaFit("x", (172.0, -1.77, 5.6, 0.34), tuple(tuple(0.0 for _ in range(4)) for _ in range(4)),
        ...                0.1, 30.0, 0.9, 14, 56)
        >>> round(f.predict_terms(38, 13.6 * 38, 1.1, 1).stiffness_kN_per_m, 1)
        303.6
        """
        rim = _validate.positive("rim_diameter_in", rim_diameter_in)
        wr = _validate.positive("wr_in2", wr_in2)
        pressure_bar = _validate.non_negative("pressure_bar", pressure_bar)
        age_years = _validate.non_negative("age_years", age_years)
        x0 = np.array([1.0, rim, age_years, wr * pressure_bar])
        k = float(x0 @ np.asarray(self.coefficients))
        var_mean = self.mean_variance(rim, wr, pressure_bar, age_years)
        u = math.sqrt(var_mean + (self.relative_residual_sd * k) ** 2)
        t = self.coverage_factor(level)
        return FormulaPrediction(k, (k - t * u, k + t * u), u, math.sqrt(max(var_mean, 0.0)), t)

    def mean_variance(self, rim_diameter_in: float, wr_in2: float, pressure_bar: float, age_years: float) -> float:
        """``lev(x0)``: variance of the fitted mean, (kN/m)², for a tyre of rim diameter R (in), W·R
        (in²) at P (bar) and age A (years): the larger of the formula's and the extended fit's
        jackknife variances (module docstring); the CR1 variance when neither was formed."""
        x0 = np.array([1.0, rim_diameter_in, age_years, wr_in2 * pressure_bar])
        v = np.asarray(self.leverage_covariance if self.leverage_covariance is not None else self.covariance)
        var = float(x0 @ v @ x0)
        if self.extended_covariance is not None:
            xe = np.concatenate([x0, [wr_in2 / rim_diameter_in, pressure_bar]])
            var = max(var, float(xe @ np.asarray(self.extended_covariance) @ xe))
        return max(var, 0.0)

    def row(self) -> dict:
        """One ``formula_fit`` row: coefficients, standard errors, counts, r², residual sd."""
        out = {"source": self.source, "method": self.method, "n_tyres": self.n_tyres, "n_points": self.n_points,
               "dof": self.dof, "r_squared": self.r_squared, "residual_sd_kN_per_m": self.residual_sd_kN_per_m,
               "relative_residual_sd_percent": 100 * self.relative_residual_sd}
        for name, b, se in zip(TERMS, self.coefficients, self.standard_errors()):
            out[name] = b
            out[f"{name}_se"] = se
        out["tyre_ids"] = " ".join(self.tyre_ids)
        return out


def _points(points: pd.DataFrame) -> pd.DataFrame:
    missing = [c for c in POINT_COLUMNS if c not in points.columns]
    if missing:
        raise ValueError(f"points lack columns {missing}")
    p = points.loc[:, list(POINT_COLUMNS)].copy()
    p["tyre_id"] = p["tyre_id"].astype(str)
    for c in ("age_years", "pressure_bar", "measured_kN_per_m"):
        p[c] = pd.to_numeric(p[c], errors="coerce")

    def ok_size(s):
        try:
            _size(s)
            return True
        except (TyreSizeError, TypeError, ValueError):
            return False

    keep = p["size"].map(ok_size) & np.isfinite(p[["age_years", "pressure_bar", "measured_kN_per_m"]]).all(axis=1)
    return p.loc[keep & (p["measured_kN_per_m"] > 0)].reset_index(drop=True)


def fit_formula(points: pd.DataFrame, source: str = "published") -> FormulaFit:
    """Fit ``K = a + b R + c A + d W R P`` to tyre × pressure points (module docstring).

    Parameters
    ----------
    points : DataFrame
        Columns ``tyre_id, size, age_years, pressure_bar, measured_kN_per_m`` (e.g.
        :func:`tyrelab.tyre.formula_accuracy.predictions_from_table` or
        ``predictions_from_recordings``); rows with an unreadable size or a missing
        number are left out.
    source : str
        Label of the points.

    Returns
    -------
    FormulaFit

    Raises
    ------
    ValueError
        With fewer than 5 tyres (4 coefficients and a cluster-robust covariance need
        more tyres than coefficients) or a design that cannot separate the terms.

    See Also
    --------
    design_matrix : its regressors.
    leave_one_tyre_out : each tyre predicted by the others' fit.
    fit_table : the fits beside the printed coefficients.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> from tyrelab.tyre.formula_accuracy import predictions_from_table
    >>> table_ii, table_iii = read_published("table_ii"), read_published("table_iii")
    >>> points = predictions_from_table(table_iii, table_ii)      # the published rolling lines, 16 tyres
    >>> f = fit_formula(points)
    >>> f.source, f.n_tyres, f.n_points, [round(c, 2) for c in f.coefficients]
    ('published', 16, 80, [154.03, -1.05, 5.5, 0.31])
    """
    _validate.frame("points", points)
    from statsmodels.regression.linear_model import OLS, WLS

    p = _points(points)
    n_tyres = int(p["tyre_id"].nunique())
    if n_tyres < 5:
        raise ValueError(f"points: the formula needs at least 5 tyres with usable points, got {n_tyres}")
    x = design_matrix(p["size"], p["age_years"], p["pressure_bar"])
    if np.linalg.matrix_rank(x) < x.shape[1]:
        raise ValueError("points: the tyres do not separate rim diameter, age and W·R·P (rank-deficient design)")
    y = p["measured_kN_per_m"].to_numpy(float)
    groups = pd.factorize(p["tyre_id"])[0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        first = OLS(y, x).fit()
        fitted0 = np.maximum(x @ first.params, 0.05 * np.abs(y).max())
        res = WLS(y, x, weights=1.0 / fitted0**2).fit(cov_type="cluster", cov_kwds={"groups": groups})
    beta = np.asarray(res.params, float)
    fitted = x @ beta
    resid = y - fitted
    dof_resid = max(len(y) - x.shape[1], 1)
    s = float(np.sqrt(np.sum((resid / fitted0) ** 2) / dof_resid))
    cov = np.asarray(res.cov_params(), float)
    wr = x[:, 3] / p["pressure_bar"].replace(0, np.nan).to_numpy(float)
    xe = extended_design_matrix(p["size"], p["age_years"], p["pressure_bar"])
    return FormulaFit(
        source=source,
        coefficients=tuple(float(b) for b in beta),
        covariance=tuple(tuple(float(v) for v in row) for row in cov),
        relative_residual_sd=s,
        residual_sd_kN_per_m=float(np.sqrt(np.sum(resid**2) / dof_resid)),
        r_squared=float(np.sum((fitted - y.mean()) ** 2) / np.sum((y - y.mean()) ** 2)),
        n_tyres=n_tyres,
        n_points=int(len(y)),
        tyre_ids=tuple(sorted(p["tyre_id"].unique())),
        ranges={"wr_in2": (float(np.nanmin(wr)), float(np.nanmax(wr))),
                "rim_diameter_in": (float(x[:, 1].min()), float(x[:, 1].max())),
                "age_years": (float(x[:, 2].min()), float(x[:, 2].max())),
                "pressure_bar": (float(p["pressure_bar"].min()), float(p["pressure_bar"].max()))},
        method=("WLS (weights 1/K̂² from an OLS pass), cluster-robust covariance by tyre (CR1), t with "
                "n_tyres − 1 degrees of freedom; prediction leverage: leave-one-tyre-out jackknife of the "
                "formula and of the formula extended by W and P, the larger"),
        leverage_covariance=_as_tuple(_jackknife_covariance(x, y, groups)),
        extended_covariance=_as_tuple(_jackknife_covariance(xe, y, groups)),
    )


def leave_one_tyre_out(points: pd.DataFrame, source: str = "ours") -> pd.DataFrame:
    """Each tyre predicted by the fit of the others, and by the printed formula (issue 27).

    Returns
    -------
    DataFrame
        Per point: ``source, tyre_id, size, age_years, pressure_bar, measured_kN_per_m,
        refit_kN_per_m, refit_ci95_low_kN_per_m, refit_ci95_high_kN_per_m, refit_covers,
        printed_kN_per_m, refit_error_percent, printed_error_percent`` (error =
        100 (predicted − measured)/measured). Tyres whose left-out fit cannot be made
        (fewer than 5 others) are skipped.

    See Also
    --------
    fit_formula : the fit left out one tyre at a time.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> from tyrelab.tyre.formula_accuracy import predictions_from_table
    >>> table_ii, table_iii = read_published("table_ii"), read_published("table_iii")
    >>> points = predictions_from_table(table_iii, table_ii)      # the published rolling lines, 16 tyres
    >>> loto = leave_one_tyre_out(points, "published")
    >>> len(loto), round(float(loto["refit_covers"].mean()), 2)     # 90 % of the points inside their 95 % interval
    (80, 0.9)
    """
    _validate.frame("points", points)
    p = _points(points)
    rows = []
    printed = np.asarray(PRINTED_COEFFICIENTS)
    for tid in sorted(p["tyre_id"].unique()):
        others, own = p.loc[p["tyre_id"] != tid], p.loc[p["tyre_id"] == tid]
        try:
            fit = fit_formula(others, source)
        except ValueError:
            continue
        for r in own.itertuples(index=False):
            pr = fit.predict(r.size, r.pressure_bar, r.age_years)
            k_printed = float(design_matrix([r.size], [r.age_years], [r.pressure_bar])[0] @ printed)
            m = float(r.measured_kN_per_m)
            lo, hi = pr.interval_kN_per_m
            rows.append(dict(source=source, tyre_id=tid, size=r.size, age_years=r.age_years,
                             pressure_bar=r.pressure_bar, measured_kN_per_m=m, refit_kN_per_m=pr.stiffness_kN_per_m,
                             refit_ci95_low_kN_per_m=lo, refit_ci95_high_kN_per_m=hi, refit_covers=bool(lo <= m <= hi),
                             printed_kN_per_m=k_printed,
                             refit_error_percent=100 * (pr.stiffness_kN_per_m - m) / m,
                             printed_error_percent=100 * (k_printed - m) / m))
    cols = ["source", "tyre_id", "size", "age_years", "pressure_bar", "measured_kN_per_m", "refit_kN_per_m",
            "refit_ci95_low_kN_per_m", "refit_ci95_high_kN_per_m", "refit_covers", "printed_kN_per_m",
            "refit_error_percent", "printed_error_percent"]
    return pd.DataFrame(rows, columns=cols)


@dataclass(frozen=True)
class FrontRule:
    """Undriven ribbed front tyre: ``K = g W R P`` with ``g`` = F1's ΔK_p / (W·R) (thesis §8.2).

    The rule rests on one tyre (F1). Its uncertainty is the spread of the pressure
    dependence per W·R between tyres of one kind, taken from the traction tyres of
    Table III (the coefficient of variation ``cv`` of ΔK_p/(W·R) over ``n`` tyres): a new
    ribbed tyre differs from F1 by two draws of that spread, ``u = K cv √2`` (F1's own
    value is one draw, the new tyre another), with Student t on ``n − 1`` degrees of freedom.

    Attributes
    ----------
    coefficient_kN_per_m_in2_bar : float
        ``g``, kN/m per in² per bar.
    relative_sd : float
        ``cv``, a fraction.
    n_tyres : int
        Tyres behind ``cv``.
    basis : str
    """

    coefficient_kN_per_m_in2_bar: float
    relative_sd: float
    n_tyres: int
    basis: str = ""

    def predict(self, size, pressure_bar: float, *, level: float = 0.95) -> FormulaPrediction:
        """Per-tyre stiffness and its prediction interval (kN/m).

        Examples
        --------
        >>> r = FrontRule(134 / 135, 0.1, 16)
        >>> p = r.predict("7.50-18", 2.0)
        >>> round(p.stiffness_kN_per_m, 1), round(p.standard_uncertainty_kN_per_m, 1)
        (268.0, 37.9)
        """
        pressure_bar = _validate.non_negative("pressure_bar", pressure_bar)
        level = _validate.probability("level", level)
        s = _size(size)
        k = self.coefficient_kN_per_m_in2_bar * s.width_times_rim_in2 * pressure_bar
        u = k * self.relative_sd * math.sqrt(2.0)
        t = float(student_t.ppf(0.5 + level / 2, max(self.n_tyres - 1, 1)))
        return FormulaPrediction(k, (k - t * u, k + t * u), u, k * self.relative_sd, t)


def front_rule(table_iii: pd.DataFrame, table_ii: pd.DataFrame, front_id: str = "F1") -> FrontRule:
    """:class:`FrontRule` from Table III's rolling rows (F1 for ``g``, the traction tyres for ``cv``).

    Raises
    ------
    ValueError
        If ``front_id`` or fewer than 3 traction tyres have a rolling ΔK_p.

    See Also
    --------
    tyrelab.tyre.stiffness.StiffnessModel : uses it for ribbed front tyres.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> r = front_rule(read_published("table_iii"), read_published("table_ii"))
    >>> round(r.coefficient_kN_per_m_in2_bar, 4), r.n_tyres, round(r.relative_sd, 3)
    (0.9926, 16, 0.101)
    """
    _validate.frame("table_iii", table_iii, ["tyre_id", "condition", "pressure_dependence_kN_per_m_bar", "size"])
    _validate.frame("table_ii", table_ii, ["tyre_id", "size"])
    rolling = table_iii.loc[(table_iii["condition"] == "rolling")
                            & table_iii["pressure_dependence_kN_per_m_bar"].notna()].copy()
    rolling["tyre_id"] = rolling["tyre_id"].astype(str)
    sizes = dict(zip(table_ii["tyre_id"].astype(str), table_ii["size"].astype(str)))
    ratio = {}
    for r in rolling.itertuples(index=False):
        try:
            ratio[r.tyre_id] = float(r.pressure_dependence_kN_per_m_bar) / _size(sizes.get(r.tyre_id, r.size)).width_times_rim_in2
        except (TyreSizeError, TypeError, ValueError):
            continue
    if front_id not in ratio:
        raise ValueError(f"table_iii has no rolling ΔK_p for the front tyre {front_id}")
    others = np.array([v for k, v in ratio.items() if k != front_id])
    if len(others) < 3:
        raise ValueError("table_iii has fewer than 3 traction tyres with a rolling ΔK_p")
    cv = float(others.std(ddof=1) / others.mean())
    return FrontRule(ratio[front_id], cv, len(others),
                     basis=(f"g = ΔK_p/(W·R) of {front_id} (thesis §8.2); u = K·{100 * cv:.1f} %·√2, the spread of "
                            f"ΔK_p/(W·R) between the {len(others)} traction tyres of Table III taken as that between "
                            f"ribbed tyres; t with {len(others) - 1} degrees of freedom"))


def fit_table(fits: list[FormulaFit]) -> pd.DataFrame:
    """Table ``formula_fit``: the thesis' printed coefficients and each fit, side by side.

    The first row (``source = "thesis_printed"``) carries the printed coefficients
    with null statistics; each fit adds a row (:meth:`FormulaFit.row`) with the printed
    value and the difference in standard errors, ``<term>_vs_printed_se``.

    See Also
    --------
    fit_formula : the fits it lists.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> from tyrelab.tyre.formula_accuracy import predictions_from_table
    >>> table_ii, table_iii = read_published("table_ii"), read_published("table_iii")
    >>> points = predictions_from_table(table_iii, table_ii)      # the published rolling lines, 16 tyres
    >>> t = fit_table([fit_formula(points)])
    >>> t["source"].tolist(), "wrp_vs_printed_se" in t.columns
    (['thesis_printed', 'published'], True)
    """
    _validate.instances("fits", fits, FormulaFit)
    printed = {"source": "thesis_printed", "method": "thesis §4.5.3: three separate regressions (Figs 26, 30, 31)",
               **dict(zip(TERMS, PRINTED_COEFFICIENTS))}
    rows = [printed]
    for f in fits:
        row = f.row()
        for name, b_p in zip(TERMS, PRINTED_COEFFICIENTS):
            se = row[f"{name}_se"]
            row[f"{name}_vs_printed_se"] = (row[name] - b_p) / se if se > 0 else np.nan
        rows.append(row)
    cols = ["source", "method", "n_tyres", "n_points", "dof", "r_squared", "residual_sd_kN_per_m",
            "relative_residual_sd_percent"]
    cols += [c for name in TERMS for c in (name, f"{name}_se", f"{name}_vs_printed_se")] + ["tyre_ids"]
    return pd.DataFrame(rows).reindex(columns=cols)
