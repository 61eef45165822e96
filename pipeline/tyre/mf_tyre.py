"""A measured tyre as MF-Tyre property files (``.tir``) and plain K(P), C(P) tables.

Multibody tools read tyres as MF-Tyre property files (MF 6.1/6.2, ``.tir``). The
rig measures the vertical behaviour only, so the file carries what was measured
and says so; everything else an MF model needs is not measured here.

MF 6.1's vertical stiffness is ``C_z = C_z0 (1 + PFZ1 dp_i)`` with
``dp_i = (p - NOMPRES) / NOMPRES``. The measured line ``K = K_c + ΔK_p P``
(thesis §4.3.1, Table III) gives ``C_z0 = K(p_0)`` and
``PFZ1 = p_0 ΔK_p / K(p_0)``, so the file reproduces the line at every
pressure. MF has no pressure term for damping, so ``VERTICAL_DAMPING`` is
``C(p_0)`` of the damping line (thesis §5.3.1, Table VII) and a file per
pressure is written where damping matters.

Keys and where their values come from (the ``$`` comment of each line says the same):

=========================  ==========================================================
measured                   ``VERTICAL_STIFFNESS``, ``PFZ1``, ``VERTICAL_DAMPING``,
                           ``FNOMIN`` (the load of the pressure sweep),
                           ``PRESMIN``/``PRESMAX`` (tested pressures), ``LONGVL``
                           (the speed of the damping fit)
operating condition        ``INFLPRES``, ``NOMPRES`` (the pressure asked for)
from the size designation  ``UNLOADED_RADIUS`` (or the catalogue's outer diameter),
                           ``WIDTH``, ``ASPECT_RATIO``, ``RIM_RADIUS``
placeholder                ``RIM_WIDTH`` (0.8 x section width, a typical ratio of
                           measuring rim to section width of radial agricultural
                           tyres), ``Q_FZ2 = 0`` (linear in deflection, as measured
                           about the mean deflection), ``Q_V2 = 0`` (no speed term:
                           see the per-speed table), ``VXLOW``, ``TYRESIDE``
=========================  ==========================================================

Pure functions: the CLI (``tyrelab export-tyre``) reads the warehouse and writes files.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy import stats

from .. import _validate
from ..units import km_h_to_m_s
from .sizes import TyreSize, parse_tyre_size

__all__ = [
    "MeasuredTyre",
    "PressureLine",
    "RIM_WIDTH_RATIO",
    "measured_tyre",
    "pressure_table",
    "property_file",
    "tir_parameters",
]

#: Measuring-rim width / section width used for RIM_WIDTH (a placeholder: about 15 in / 18.9 in
#: for a 480/70R38 on its W15L measuring rim; not measured on the rig).
RIM_WIDTH_RATIO = 0.8
#: Speed of the damping that goes into a .tir by default: the thesis' Table VII lists
#: 10 and 15 km/h rows, Table III pools 10-15 km/h for rolling stiffness.
DEFAULT_DAMPING_SPEED_km_h = 10.0


@dataclass(frozen=True)
class PressureLine:
    """A fitted line ``y = intercept + slope * P`` (P in bar) with standard errors.

    Attributes
    ----------
    intercept, slope : float
        Carcass value and pressure dependence (kN/m and kN/m/bar, or kNs/m and kNs/m/bar).
    intercept_se, slope_se : float
        Standard errors (NaN where unknown, e.g. coefficients typed into a catalogue).
    n : int
        Runs in the fit (0 where unknown).
    """

    intercept: float
    slope: float
    intercept_se: float = math.nan
    slope_se: float = math.nan
    n: int = 0

    def at(self, pressure_bar):
        """The line at ``pressure_bar``.

        Examples
        --------
        >>> float(PressureLine(141.0, 175.0).at(1.2))
        351.0
        """
        return self.intercept + self.slope * np.asarray(pressure_bar, dtype=float)

    def se_bound(self, pressure_bar):
        """``sqrt(se_a^2 + P^2 se_b^2)``: an upper bound of the standard error of the line at P.

        The exact value also has ``2 P cov(a, b)``, which the warehouse does not store;
        for a fit over positive pressures ``cov(a, b) = -mean(P) var(b) < 0``, so
        leaving it out can only widen the interval.
        """
        p = np.asarray(pressure_bar, dtype=float)
        return np.sqrt(self.intercept_se**2 + (p * self.slope_se) ** 2)


@dataclass(frozen=True)
class MeasuredTyre:
    """What the rig measured of one tyre, ready to export.

    Attributes
    ----------
    tyre_id : str
    size : TyreSize
    stiffness : PressureLine
        Rolling stiffness vs pressure, kN/m (Table III rolling fit).
    damping : PressureLine or None
        Damping vs pressure at ``damping_speed_km_h``, kNs/m (Table VII fit).
    damping_speed_km_h : float or None
    tested_load_kN : float
        Load of the pressure sweep (FNOMIN).
    pressure_range_bar : tuple of float
        Lowest and highest tested pressure.
    outer_diameter_m : float or None
        Measured outer diameter (catalogue), else None (the size's is used).
    source : str
        Where the numbers come from.
    """

    tyre_id: str
    size: TyreSize
    stiffness: PressureLine
    damping: PressureLine | None
    damping_speed_km_h: float | None
    tested_load_kN: float
    pressure_range_bar: tuple[float, float]
    outer_diameter_m: float | None = None
    source: str = ""

    @property
    def unloaded_radius_m(self) -> float:
        """Half the catalogue's outer diameter, else half the size's."""
        return (self.outer_diameter_m if self.outer_diameter_m else self.size.outer_diameter_m) / 2.0


def _num(value) -> float:
    v = pd.to_numeric(pd.Series([value]), errors="coerce").iloc[0]
    return float(v) if pd.notna(v) else math.nan


def _line(row: pd.Series, intercept: str, slope: str) -> PressureLine:
    n = _num(row.get("n", math.nan))
    return PressureLine(_num(row[intercept]), _num(row[slope]), _num(row.get(f"{intercept}_se", math.nan)),
                        _num(row.get(f"{slope}_se", math.nan)), int(n) if math.isfinite(n) else 0)


def measured_tyre(
    tyre_id: str,
    tyres: pd.DataFrame,
    table_iii: pd.DataFrame | None = None,
    damping_by_speed: pd.DataFrame | None = None,
    pressures_bar=None,
    *,
    damping_speed_km_h: float = DEFAULT_DAMPING_SPEED_km_h,
    source: str = "",
) -> MeasuredTyre:
    """Collect a tyre's measured lines from the warehouse tables, else from its catalogue row.

    Parameters
    ----------
    tyre_id : str
    tyres : DataFrame
        The ``tyres`` table (catalogue; optional measured columns, ``schemas/tyres.json``).
    table_iii : DataFrame, optional
        The warehouse's ``table_iii`` (our ``carcass_stiffness_kN_per_m``,
        ``pressure_dependence_kN_per_m_bar`` with ``_se``, ``n``, ``held_load_kN``).
    damping_by_speed : DataFrame, optional
        The warehouse's ``damping_pressure_by_speed`` (``intercept``, ``slope``, ``_se``).
    pressures_bar : array-like, optional
        Pressures of the tyre's measurement runs (for PRESMIN/PRESMAX).
    damping_speed_km_h : float
        Rolling speed whose damping fit is used: the fitted speed nearest to it.
    source : str
        Recorded in the result.

    Raises
    ------
    ValueError
        If the tyre is not in the catalogue, or has neither a rolling stiffness fit
        nor measured catalogue coefficients; the message names the tyre.

    See Also
    --------
    property_file : the ``.tir`` text of the tyre.
    pressure_table : K(P) and C(P) per speed.

    Examples
    --------
    >>> tyres = pd.DataFrame([{"tyre_id": "MY1", "size": "480/70R38", "carcass_stiffness_kN_per_m": 120.0,
    ...     "pressure_dependence_kN_per_m_bar": 230.0, "carcass_damping_kN_s_per_m": 1.1,
    ...     "pressure_dependence_kN_s_per_m_bar": 0.4, "measured_speed_km_h": 12.0, "tested_load_kN": 25.0,
    ...     "measured_pressure_min_bar": 0.8, "measured_pressure_max_bar": 1.6}])
    >>> t = measured_tyre("MY1", tyres)                  # no warehouse tables: the catalogue's coefficients
    >>> t.source, (t.stiffness.intercept, t.stiffness.slope), t.pressure_range_bar
    ('catalogue tyres.csv', (120.0, 230.0), (0.8, 1.6))
    """
    _validate.frame("tyres", tyres, ["tyre_id", "size"])
    damping_speed_km_h = _validate.positive("damping_speed_km_h", damping_speed_km_h)
    ids = tyres["tyre_id"].astype(str)
    if tyre_id not in set(ids):
        raise ValueError(f"tyre_id {tyre_id!r} is not in the tyre catalogue")
    cat = tyres.loc[ids == tyre_id].iloc[-1]
    size = parse_tyre_size(str(cat["size"]))
    stiffness = damping = None
    load = speed = math.nan
    if table_iii is not None and not table_iii.empty:
        rows = table_iii.loc[(table_iii["tyre_id"].astype(str) == tyre_id) & (table_iii["condition"] == "rolling")]
        if len(rows):
            line = _line(rows.iloc[0], "carcass_stiffness_kN_per_m", "pressure_dependence_kN_per_m_bar")
            if math.isfinite(line.intercept) and math.isfinite(line.slope):
                stiffness = line
                load = _num(rows.iloc[0].get("held_load_kN", math.nan))
    if damping_by_speed is not None and not damping_by_speed.empty and stiffness is not None:
        d = damping_by_speed.loc[(damping_by_speed["tyre_id"].astype(str) == tyre_id)
                                 & (pd.to_numeric(damping_by_speed["speed_km_h"], errors="coerce") > 0)
                                 & pd.to_numeric(damping_by_speed["slope"], errors="coerce").notna()]
        if len(d):
            row = d.iloc[int(np.argmin(np.abs(pd.to_numeric(d["speed_km_h"]).to_numpy() - damping_speed_km_h)))]
            damping, speed = _line(row, "intercept", "slope"), float(row["speed_km_h"])
    if stiffness is None:  # the catalogue's measured coefficients
        stiffness = PressureLine(_num(cat.get("carcass_stiffness_kN_per_m")), _num(cat.get("pressure_dependence_kN_per_m_bar")))
        if not (math.isfinite(stiffness.intercept) and math.isfinite(stiffness.slope)):
            stationary = table_iii is not None and not table_iii.empty and bool(
                ((table_iii["tyre_id"].astype(str) == tyre_id) & (table_iii["condition"] != "rolling")).any())
            raise ValueError(
                f"tyre {tyre_id!r} has no rolling stiffness fit in the warehouse"
                + (" (its runs are stationary only: an MF-Tyre file describes a rolling tyre)" if stationary else "")
                + " and no measured carcass_stiffness_kN_per_m / pressure_dependence_kN_per_m_bar in the catalogue: "
                "record rolling runs of it (manifest speed_km_h > 0) at two or more pressures and run the pipeline "
                "again, or give those two columns (and carcass_damping_kN_s_per_m, "
                "pressure_dependence_kN_s_per_m_bar) in its tyres.csv row"
            )
        c = PressureLine(_num(cat.get("carcass_damping_kN_s_per_m")), _num(cat.get("pressure_dependence_kN_s_per_m_bar")))
        damping = c if math.isfinite(c.intercept) and math.isfinite(c.slope) else None
        speed = _num(cat.get("measured_speed_km_h"))
        load = _num(cat.get("tested_load_kN"))
        pressures_bar = [_num(cat.get("measured_pressure_min_bar")), _num(cat.get("measured_pressure_max_bar"))]
        source = f"catalogue {cat.get('catalogue_file', 'tyres.csv')}"
    p = np.asarray([] if pressures_bar is None else pressures_bar, dtype=float)
    p = p[np.isfinite(p)]
    if not math.isfinite(load) or not p.size:
        raise ValueError(f"tyre {tyre_id!r}: the tested load and pressures are unknown (no runs, no catalogue values)")
    diameter = _num(cat.get("outer_diameter_m"))
    return MeasuredTyre(
        tyre_id=tyre_id, size=size, stiffness=stiffness, damping=damping,
        damping_speed_km_h=speed if damping is not None and math.isfinite(speed) else None,
        tested_load_kN=load, pressure_range_bar=(float(p.min()), float(p.max())),
        outer_diameter_m=diameter if math.isfinite(diameter) else None, source=source,
    )


def tir_parameters(tyre: MeasuredTyre, pressure_bar: float) -> dict[str, list[tuple[str, object, str]]]:
    """The sections of a ``.tir`` file at nominal pressure ``pressure_bar``: {section: [(key, value, comment)]}.

    Values in SI (m, N, N/m, N s/m, Pa, m/s), as MF-Tyre property files use.

    Raises
    ------
    ValueError
        If ``pressure_bar`` is not positive or the stiffness there is not positive.

    See Also
    --------
    property_file : the file's text from them.

    Examples
    --------
    >>> t = MeasuredTyre("MY1", parse_tyre_size("480/70R38"), PressureLine(120.0, 230.0),
    ...                  PressureLine(1.1, 0.4), 12.0, 25.0, (0.8, 1.6))
    >>> p = tir_parameters(t, 1.2)
    >>> dict((k, v) for k, v, _ in p["VERTICAL"] if k in ("VERTICAL_STIFFNESS", "VERTICAL_DAMPING"))
    {'VERTICAL_STIFFNESS': 396000.0, 'VERTICAL_DAMPING': 1580.0}
    """
    _validate.instance("tyre", tyre, MeasuredTyre)
    p0 = _validate.positive("pressure_bar", pressure_bar)
    k0 = float(tyre.stiffness.at(p0))
    if not k0 > 0:
        raise ValueError(f"pressure_bar {p0}: the measured line gives K = {k0:.1f} kN/m, not positive")
    s = tyre.size
    speed = tyre.damping_speed_km_h
    low, high = tyre.pressure_range_bar
    # Outside the tested pressures the line is extrapolated, not measured: the file says so.
    at = "measured" if low - 1e-9 <= p0 <= high + 1e-9 else f"extrapolated to NOMPRES outside the tested {low:g}-{high:g} bar"
    model = [("FITTYP", 61, "Magic Formula 6.1"), ("TYRESIDE", "'LEFT'", "placeholder")]
    if speed is not None:
        model.append(("LONGVL", round(km_h_to_m_s(speed), 6), f"measured: speed of the damping fit, {speed:g} km/h (m/s)"))
    model.append(("VXLOW", 1, "placeholder: MF default (m/s)"))
    diameter_note = "measured: catalogue outer diameter / 2" if tyre.outer_diameter_m else "from the size: rim/2 + aspect x width"
    vertical = [
        ("FNOMIN", round(tyre.tested_load_kN * 1e3, 3), "measured: load of the pressure sweep (N)"),
        ("VERTICAL_STIFFNESS", round(k0 * 1e3, 3), f"{at}: K_c + dK_p P at NOMPRES, {tyre.source} (N/m)"),
    ]
    if tyre.damping is not None:
        c0 = float(tyre.damping.at(p0))
        vertical.append(("VERTICAL_DAMPING", round(c0 * 1e3, 3),
                         f"{at}: C_c + dC P at NOMPRES and {speed:g} km/h (N s/m); no pressure term in MF"))
    vertical += [
        ("PFZ1", round(p0 * tyre.stiffness.slope / k0, 9), f"{at}: p0 dK_p / K(p0), pressure effect on stiffness"),
        ("Q_FZ2", 0, "placeholder: linear in deflection (measured about the mean deflection)"),
        ("Q_V2", 0, "placeholder: no speed term (see the per-speed K(P), C(P) table)"),
    ]
    return {
        "UNITS": [("LENGTH", "'meter'", ""), ("FORCE", "'newton'", ""), ("ANGLE", "'radians'", ""),
                  ("MASS", "'kg'", ""), ("TIME", "'second'", "")],
        "MODEL": model,
        "DIMENSION": [
            ("UNLOADED_RADIUS", round(tyre.unloaded_radius_m, 6), diameter_note + " (m)"),
            ("WIDTH", round(s.section_width_mm / 1e3, 6), f"from the size {s.designation} (m)"),
            ("ASPECT_RATIO", round(s.aspect_ratio, 4),
             "from the size" if s.aspect_ratio_stated else "inch size: 85-series default (tyrelab.tyre.sizes)"),
            ("RIM_RADIUS", round(s.rim_diameter_m / 2, 6), "from the size (m)"),
            ("RIM_WIDTH", round(RIM_WIDTH_RATIO * s.section_width_mm / 1e3, 6), "placeholder: 0.8 x section width (m)"),
        ],
        "OPERATING_CONDITIONS": [
            ("INFLPRES", round(p0 * 1e5, 3), "inflation pressure (Pa)"),
            ("NOMPRES", round(p0 * 1e5, 3), "nominal pressure of this file (Pa)"),
        ],
        "INFLATION_PRESSURE_RANGE": [
            ("PRESMIN", round(tyre.pressure_range_bar[0] * 1e5, 3), "measured: lowest tested pressure (Pa)"),
            ("PRESMAX", round(tyre.pressure_range_bar[1] * 1e5, 3), "measured: highest tested pressure (Pa)"),
        ],
        "VERTICAL": vertical,
    }


def property_file(tyre: MeasuredTyre, pressure_bar: float, *, tool: str = "tyrelab") -> str:
    """Text of an MF-Tyre 6.1 property file (``.tir``) at nominal pressure ``pressure_bar``.

    See the module docstring for which keys are measured and which are placeholders.

    See Also
    --------
    tir_parameters : its sections.
    measured_tyre : the tyre it describes.

    Examples
    --------
    >>> t = MeasuredTyre("MY1", parse_tyre_size("480/70R38"), PressureLine(120.0, 230.0),
    ...                  PressureLine(1.1, 0.4), 12.0, 25.0, (0.8, 1.6))
    >>> text = property_file(t, 1.2)
    >>> [line.split("$")[0].strip() for line in text.splitlines() if line.startswith(("VERTICAL_", "PFZ1"))]
    ['VERTICAL_STIFFNESS       = 396000.0', 'VERTICAL_DAMPING         = 1580.0', 'PFZ1                     = 0.696969697']
    """
    _validate.instance("tyre", tyre, MeasuredTyre)
    lines = [
        "[MDI_HEADER]",
        "FILE_TYPE                = 'tir'",
        "FILE_VERSION             = 3.0",
        "FILE_FORMAT              = 'ASCII'",
        f"! : TIRE_VERSION : MF61  written by {tool} export-tyre",
        f"! : COMMENT : tyre {tyre.tyre_id!r} {tyre.size.designation}: vertical stiffness and damping measured on the",
        "! : COMMENT : tyrelab rig (thesis ch. 3-5); keys marked 'placeholder' are not measured here.",
    ]
    for section, items in tir_parameters(tyre, pressure_bar).items():
        lines.append("$" + "-" * 60 + section.lower())
        lines.append(f"[{section}]")
        for key, value, comment in items:
            text = f"{key:<25}= {value}"
            lines.append(f"{text:<45}$ {comment}" if comment else text)
    return "\n".join(lines) + "\n"


def pressure_table(
    tyre_id: str,
    stiffness_by_speed: pd.DataFrame,
    damping_by_speed: pd.DataFrame,
    pressures_bar,
    *,
    alpha: float = 0.05,
) -> pd.DataFrame:
    """K(P) and C(P) per speed from the per-speed pressure fits, with intervals.

    Parameters
    ----------
    tyre_id : str
    stiffness_by_speed, damping_by_speed : DataFrame
        The warehouse's ``stiffness_pressure_by_speed`` / ``damping_pressure_by_speed``.
    pressures_bar : array-like
        Pressures to tabulate.
    alpha : float
        1 - confidence of the interval (default 95 %).

    Returns
    -------
    DataFrame
        ``tyre_id, speed_km_h, pressure_bar, stiffness_kN_per_m, stiffness_se_bound_kN_per_m,
        stiffness_ci_low_kN_per_m, stiffness_ci_high_kN_per_m`` and the same for
        ``damping_kN_s_per_m``, plus ``n_stiffness``, ``n_damping``. The interval is
        ``t(1 - alpha/2, n - 2) x`` :meth:`PressureLine.se_bound` (conservative: the
        intercept-slope covariance is not stored).

    See Also
    --------
    measured_tyre : the tyre's lines.

    Examples
    --------
    >>> from tyrelab.tyre.regressions import DAMPING, pressure_regressions, table_iii
    >>> from tyrelab.tyre.examples import demo_runs
    >>> runs = demo_runs()                                  # tyre T1: 1.0-1.8 bar, standing and at 12 km/h
    >>> t = pressure_table("T1", pressure_regressions(runs, by="speed"), pressure_regressions(runs, DAMPING, by="speed"), [1.6])
    >>> t[["speed_km_h", "pressure_bar", "stiffness_kN_per_m", "damping_kN_s_per_m"]].round(3).to_dict("records")
    [{'speed_km_h': 0.0, 'pressure_bar': 1.6, 'stiffness_kN_per_m': 460.0, 'damping_kN_s_per_m': 2.7}, {'speed_km_h': 12.0, 'pressure_bar': 1.6, 'stiffness_kN_per_m': 440.0, 'damping_kN_s_per_m': 1.35}]
    """
    alpha = _validate.probability("alpha", alpha)
    p = np.unique(_validate.positive_array("pressures_bar", pressures_bar))
    rows = []
    for name, table, unit in (("stiffness", stiffness_by_speed, "kN_per_m"), ("damping", damping_by_speed, "kN_s_per_m")):
        t = table.loc[(table["tyre_id"].astype(str) == tyre_id) & pd.to_numeric(table["slope"], errors="coerce").notna()]
        for _, r in t.iterrows():
            line = _line(r, "intercept", "slope")
            se = line.se_bound(p)
            tq = stats.t.ppf(1 - alpha / 2, line.n - 2) if line.n > 2 else math.nan
            for pi, v, s in zip(p, line.at(p), se):
                rows.append({"speed_km_h": float(r["speed_km_h"]), "pressure_bar": float(pi), "quantity": name,
                             "value": float(v), "se": float(s), "low": float(v - tq * s), "high": float(v + tq * s),
                             "n": line.n, "unit": unit})
    long = pd.DataFrame(rows, columns=["speed_km_h", "pressure_bar", "quantity", "value", "se", "low", "high", "n", "unit"])
    long = long.astype({"speed_km_h": float, "pressure_bar": float})  # also with no fit at all (no rows)
    out = pd.DataFrame({"speed_km_h": pd.Series(dtype=float), "pressure_bar": pd.Series(dtype=float)})
    for name, unit in (("stiffness", "kN_per_m"), ("damping", "kN_s_per_m")):
        q = long.loc[long["quantity"] == name].drop(columns=["quantity", "unit"]).rename(columns={
            "value": f"{name}_{unit}", "se": f"{name}_se_bound_{unit}", "low": f"{name}_ci_low_{unit}",
            "high": f"{name}_ci_high_{unit}", "n": f"n_{name}"})
        out = out.merge(q, on=["speed_km_h", "pressure_bar"], how="outer")
    out.insert(0, "tyre_id", tyre_id)
    return out.sort_values(["speed_km_h", "pressure_bar"]).reset_index(drop=True)
