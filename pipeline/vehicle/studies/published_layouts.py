"""The digitised thesis Tables XII-XX in the layouts the chapter 6-8 studies use.

Pure functions on the DataFrames returned by
:func:`tyrelab.published.read_published` (no file I/O, no thesis numbers: the
numbers live only in ``raw/published/table_*.csv``). Each adapter renames the
digitised labels to the ones of :mod:`tyrelab.vehicle.studies`,
:mod:`tyrelab.vehicle.metrics` and :mod:`tyrelab.vehicle.bounce_pitch`, and
raises ``ValueError`` on a label it does not know rather than dropping the row.
"""

from __future__ import annotations

import pandas as pd

from ... import _validate
from ..units import from_kilo

__all__ = [
    "tractor_axles_si",
    "carriage_rolling",
    "carriage_stationary",
    "carriage_accuracy",
    "tractor_mass",
    "tractor_tyres",
    "tractor_accuracy",
    "longitudinal_sweep",
    "tractors",
]

#: Statistic labels of Tables XIII, XIV and XVII -> :func:`metrics.accuracy_table`.
_STATISTIC = {
    "mean_ratio_error": "mean_ratio_error",
    "sd_ratio_error": "sd_ratio_error",
    "p_within_10pct": "p_within_10",
    "p_within_30pct": "p_within_30",
}
#: Ratio quantities of Tables XIII/XIV -> :func:`metrics.accuracy_table`.
_CARRIAGE_QUANTITY = {
    "rms_acceleration": "rms_acceleration",
    "peak_height": "sqrt_peak_height",
    "peak_frequency": "peak_frequency",
    "peak_width": "half_power_width_over_frequency",
}
#: Envelope rows of Tables XIII/XIV (statistic label) -> (quantity, statistic).
_ENVELOPE = {
    "mean_cross_correlation": ("envelope_correlation", "mean"),
    "sd_cross_correlation": ("envelope_correlation", "sd"),
    "mean_rms_envelope_error": ("envelope_error", "mean"),
    "sd_rms_envelope_error": ("envelope_error", "sd"),
}
#: Table XVII (quantity, component) -> :func:`studies.tractor_study` quantity.
_TRACTOR_QUANTITY = {
    ("rms", "vertical"): "vertical_rms",
    ("rms", "pitch"): "pitch_rms",
    ("peak_frequency", "first_peak"): "first_peak_frequency",
    ("peak_frequency", "second_peak"): "second_peak_frequency",
}
_XVIII_COLUMNS = [
    "longitudinal_stiffness_kN_per_m",
    "longitudinal_damping_kN_s_per_m",
    "vertical_rms_m_s2",
    "pitch_rms_rad_s2",
    "peak_1_Hz",
    "peak_2_Hz",
    "peak_3_Hz",
]


def _lookup(mapping: dict, key, table: str):
    if key not in mapping:
        raise ValueError(f"{table}: unknown label {key!r}")
    return mapping[key]


def _as_bool(s: pd.Series) -> pd.Series:
    return s if s.dtype == bool else s.map(lambda v: str(v).strip().lower() in ("true", "1", "yes", "y"))


def carriage_rolling(xii: pd.DataFrame) -> pd.DataFrame:
    """Table XII rolling rows: ``speed_km_h, actual_speed_m_s, load_condition, load_kg,
    damping_kN_s_per_m, stiffness_kN_per_m`` (input of :func:`studies.carriage_study`).

    See Also
    --------
    carriage_stationary : the stationary rows.
    tyrelab.vehicle.studies.carriage_study : reads these rows.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> r = carriage_rolling(read_published("table_xii"))
    >>> len(r), r[["tyre_id", "speed_km_h", "load_kg", "stiffness_kN_per_m"]].to_dict("records")[0]
    (12, {'tyre_id': 'T4', 'speed_km_h': 17.5, 'load_kg': 1860, 'stiffness_kN_per_m': 380})
    """
    _validate.frame("xii", xii, ["characteristics", "nominal_speed_km_h"])
    rolling = xii[xii["characteristics"] == "rolling"].rename(columns={"nominal_speed_km_h": "speed_km_h"})
    return rolling.reset_index(drop=True)


def carriage_stationary(xii: pd.DataFrame) -> pd.DataFrame:
    """Table XII stationary rows: ``load_condition, load_kg, damping_kN_s_per_m, stiffness_kN_per_m``.

    See Also
    --------
    carriage_rolling : the rolling rows.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> carriage_stationary(read_published("table_xii"))[["load_condition", "stiffness_kN_per_m"]].to_dict("records")[:2]
    [{'load_condition': 'light', 'stiffness_kN_per_m': 545}, {'load_condition': 'heavy', 'stiffness_kN_per_m': 450}]
    """
    _validate.frame("xii", xii, ["characteristics", "load_condition", "load_kg", "damping_kN_s_per_m", "stiffness_kN_per_m"])
    cols = ["load_condition", "load_kg", "damping_kN_s_per_m", "stiffness_kN_per_m"]
    return xii.loc[xii["characteristics"] == "stationary", cols].reset_index(drop=True)


def carriage_accuracy(table: pd.DataFrame) -> pd.DataFrame:
    """Table XIII or XIV as ``quantity, statistic, thesis_rolling, thesis_stationary``.

    Labels follow :func:`tyrelab.vehicle.metrics.accuracy_table`; the ``>``
    qualifiers of '>0.9999' cells are dropped (the value 0.9999 is kept).

    See Also
    --------
    tractor_accuracy : Table XVII, the same for the tractor.
    tyrelab.vehicle.metrics.accuracy_table : ours in the same layout.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> carriage_accuracy(read_published("table_xiii")).iloc[0].to_dict()
    {'quantity': 'rms_acceleration', 'statistic': 'mean_ratio_error', 'thesis_rolling': 0.92, 'thesis_stationary': 1.03}
    """
    _validate.frame("table", table, ["quantity", "statistic", "rolling", "stationary"])
    rows = []
    for r in table.itertuples(index=False):
        if r.quantity == "envelope":
            quantity, statistic = _lookup(_ENVELOPE, r.statistic, "carriage accuracy")
        else:
            quantity = _lookup(_CARRIAGE_QUANTITY, r.quantity, "carriage accuracy")
            statistic = _lookup(_STATISTIC, r.statistic, "carriage accuracy")
        rows.append((quantity, statistic, float(r.rolling), float(r.stationary)))
    return pd.DataFrame(rows, columns=["quantity", "statistic", "thesis_rolling", "thesis_stationary"])


def tractor_mass(xv: pd.DataFrame) -> pd.DataFrame:
    """Table XV (long: ``parameter, condition, value``) -> one row per load condition.

    Columns ``load_condition, mass_class, front_pressure_bar, rear_pressure_bar,
    mass_kg, pitch_inertia_kg_m2, cg_height_m, cg_to_rear_axle_m, wheelbase_m``.

    See Also
    --------
    tractor_tyres : Table XVI, the tyres of each run.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> m = tractor_mass(read_published("table_xv"))
    >>> len(m), list(m.columns[:4])
    (4, ['load_condition', 'mass_class', 'front_pressure_bar', 'rear_pressure_bar'])
    """
    _validate.frame("xv", xv, ["parameter", "condition", "value", "value_text"])
    v = {(r.parameter, r.condition): r.value for r in xv.itertuples(index=False)}
    text = {(r.parameter, r.condition): str(r.value_text).strip() for r in xv.itertuples(index=False)}
    conditions = sorted(c for p, c in v if p == "load_case")
    rows = []
    for cond in conditions:
        mass_class = "light" if "light" in text[("load_case", cond)].lower() else "heavy"
        rows.append(
            {
                "load_condition": int(cond.rsplit("_", 1)[1]),
                "mass_class": mass_class,
                "front_pressure_bar": float(v[("front_pressure_bar", cond)]),
                "rear_pressure_bar": float(v[("rear_pressure_bar", cond)]),
                "mass_kg": float(v[("total_mass_kg", mass_class)]),
                "pitch_inertia_kg_m2": float(v[("pitch_inertia_kg_m2", mass_class)]),
                "cg_height_m": float(v[("cg_height_m", mass_class)]),
                "cg_to_rear_axle_m": float(v[("cg_to_rear_axle_m", mass_class)]),
                "wheelbase_m": float(v[("wheelbase_m", "all")]),
            }
        )
    return pd.DataFrame(rows)


def tractor_tyres(xvi: pd.DataFrame) -> pd.DataFrame:
    """Table XVI as :func:`studies.tractor_study` reads it (the digitised layout already is).

    See Also
    --------
    tractor_axles_si : one row's axles in SI.
    tractor_mass : Table XV, the tractor's masses.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> len(tractor_tyres(read_published("table_xvi")))
    32
    """
    _validate.frame("xvi", xvi)
    return xvi.reset_index(drop=True)


def tractor_axles_si(row) -> dict[str, float]:
    """A Table XVI row's tyres (per tyre, kN/m and kN s/m) as the pitch-plane tractor's axles in SI:
    ``front_stiffness_N_per_m``, ``rear_stiffness_N_per_m``, ``front_damping_N_s_per_m``,
    ``rear_damping_N_s_per_m`` (an axle is its two tyres).

    See Also
    --------
    tractor_tyres : the rows it takes.

    Examples
    --------
    >>> tractor_axles_si({"front_stiffness_kN_per_m": 425.0, "rear_stiffness_kN_per_m": 330.0,
    ...                   "front_damping_kN_s_per_m": 1.5, "rear_damping_kN_s_per_m": 1.0})["front_stiffness_N_per_m"]
    850000.0
    """
    keys = [f"{axle}_{q}_{kn}" for axle in ("front", "rear") for q, kn in (("stiffness", "kN_per_m"), ("damping", "kN_s_per_m"))]
    missing = [k for k in keys if k not in row]
    if missing:
        raise ValueError(f"row: missing {', '.join(missing)}")
    return {f"{axle}_{q}_{si}": 2 * from_kilo(row[f"{axle}_{q}_{kn}"])
            for axle in ("front", "rear") for q, kn, si in (("stiffness", "kN_per_m", "N_per_m"),
                                                             ("damping", "kN_s_per_m", "N_s_per_m"))}


def tractor_accuracy(xvii: pd.DataFrame) -> pd.DataFrame:
    """Table XVII as ``track, quantity, statistic, thesis_rolling, thesis_stationary``.

    See Also
    --------
    carriage_accuracy : Tables XIII and XIV, the same for the carriage.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> tractor_accuracy(read_published("table_xvii")).iloc[0].to_dict()
    {'track': 'SBT', 'quantity': 'vertical_rms', 'statistic': 'mean_ratio_error', 'thesis_rolling': 1.13, 'thesis_stationary': 0.97}
    """
    _validate.frame("xvii", xvii, ["surface", "quantity", "component", "statistic", "rolling", "stationary"])
    rows = [
        (
            r.surface,
            _lookup(_TRACTOR_QUANTITY, (r.quantity, r.component), "table_xvii"),
            _lookup(_STATISTIC, r.statistic, "table_xvii"),
            float(r.rolling),
            float(r.stationary),
        )
        for r in xvii.itertuples(index=False)
    ]
    return pd.DataFrame(rows, columns=["track", "quantity", "statistic", "thesis_rolling", "thesis_stationary"])


def longitudinal_sweep(xviii: pd.DataFrame) -> pd.DataFrame:
    """Table XVIII: the sweep columns plus ``row`` = ``predicted`` | ``measured``.

    See Also
    --------
    tractor_tyres : the runs of the tractor study.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> longitudinal_sweep(read_published("table_xviii"))["row"].value_counts().to_dict()
    {'predicted': 8, 'measured': 1}
    """
    _validate.frame("xviii", xviii, [*_XVIII_COLUMNS, "is_measured"])
    out = xviii[_XVIII_COLUMNS].astype(float)
    out["row"] = _as_bool(xviii["is_measured"]).map({True: "measured", False: "predicted"})
    return out.reset_index(drop=True)


def tractors(xix: pd.DataFrame) -> pd.DataFrame:
    """Table XIX with boolean ``four_wheel_drive`` and ``front_water_ballast``
    (input of :func:`bounce_pitch.table_xx`).

    See Also
    --------
    tyrelab.vehicle.bounce_pitch.table_xx : reads these rows.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> t = tractors(read_published("table_xix"))
    >>> len(t), t["four_wheel_drive"].dtype.name
    (5, 'bool')
    """
    _validate.frame("xix", xix, ["four_wheel_drive", "front_water_ballast"])
    out = xix.copy()
    for c in ("four_wheel_drive", "front_water_ballast"):
        out[c] = _as_bool(out[c])
    return out.reset_index(drop=True)
