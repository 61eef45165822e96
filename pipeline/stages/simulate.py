"""Stage ``simulate``: chapters 6-8 - carriage, tractor, Table XX, ISO 2631 (issue 5).

Reads the digitised thesis tables ``raw/published/table_{xii,xv,xvi,xix,xx}.csv``
when present (falling back to :mod:`pipeline.vehicle.thesis_data`, recorded in the
``source`` column of ``simulate_inputs``), runs the pure studies of
:mod:`pipeline.vehicle.studies` and :mod:`pipeline.vehicle.bounce_pitch`, and writes:

``carriage_runs``, ``carriage_comparisons``, ``table_xiii``, ``table_xiv``,
``tractor_runs``, ``table_xvii``, ``table_xviii``, ``table_xx``,
``table_xx_statistics``, ``iso2631``, ``profile_spectra``, ``simulate_inputs``.

Everything is seeded (``SEED``), so the same command gives the same bytes. If the
warehouse holds ``results`` with rolling T4 stiffness on a flat surface at the
Table XII conditions, those are *not* substituted automatically (the Table XII
values were measured immediately before the carriage runs, §6.3); see
``docs/simulation.md``.
"""

from __future__ import annotations

import time

import numpy as np
import pandas as pd

from ..vehicle import bounce_pitch, studies, thesis_data
from .base import Context, StageResult

SEED = 5007

#: (stem, fallback, required columns)
_INPUTS = {
    "table_xii": (thesis_data.table_xii, ["speed_km_h", "actual_speed_m_s", "load_kg", "damping_kN_s_per_m", "stiffness_kN_per_m"]),
    "table_xv": (thesis_data.table_xv, ["load_condition", "mass_kg", "pitch_inertia_kg_m2", "cg_height_m", "cg_to_rear_axle_m", "wheelbase_m"]),
    "table_xvi": (thesis_data.table_xvi, ["load_condition", "track", "speed_km_h", "characteristics", "rear_stiffness_kN_per_m", "front_stiffness_kN_per_m", "rear_damping_kN_s_per_m", "front_damping_kN_s_per_m"]),
    "table_xix": (thesis_data.table_xix, ["tractor", "mass_kg", "pitch_inertia_kg_m2", "front_distance_m", "rear_distance_m", "front_size", "front_pressure_bar", "rear_size", "rear_pressure_bar", "four_wheel_drive", "front_water_ballast"]),
    "table_xx": (thesis_data.table_xx, ["tractor", "stiffness_source", "rear_stiffness_kN_per_m", "front_stiffness_kN_per_m", "predicted_frequency_1_Hz", "predicted_frequency_2_Hz", "measured_frequency_1_Hz", "measured_frequency_2_Hz"]),
}  # fmt: skip


def _xv_wide(long: pd.DataFrame) -> pd.DataFrame:
    """Table XV as digitised (``parameter, condition, value``) -> one row per load condition."""
    v = {(r.parameter, r.condition): r.value for r in long.itertuples(index=False)}
    rows = []
    for lc in (1, 2, 3, 4):
        cond = f"load_condition_{lc}"
        case = str(long[(long["parameter"] == "load_case") & (long["condition"] == cond)]["value_text"].iloc[0]).strip()
        mass_class = "light" if "light" in case.lower() else "heavy"
        rows.append(
            {
                "load_condition": lc,
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


def _adapt(stem: str, df: pd.DataFrame) -> pd.DataFrame:
    """Map the digitised CSV layouts onto the columns the studies use."""
    if stem == "table_xii" and "nominal_speed_km_h" in df and "speed_km_h" not in df:
        df = df.rename(columns={"nominal_speed_km_h": "speed_km_h"})
    if stem == "table_xii" and "characteristics" in df:
        df = df[df["characteristics"] == "rolling"]
    if stem == "table_xv" and {"parameter", "condition", "value"} <= set(df.columns):
        df = _xv_wide(df)
    return df.reset_index(drop=True)


def _load(ctx: Context, stem: str) -> tuple[pd.DataFrame, str]:
    fallback, required = _INPUTS[stem]
    path = ctx.raw / "published" / f"{stem}.csv"
    if path.exists():
        try:
            df = _adapt(stem, pd.read_csv(path))
        except (KeyError, ValueError, IndexError) as exc:
            ctx.log.warning("simulate: cannot read %s (%s); using the built-in transcription", path, exc)
            return fallback(), "pipeline.vehicle.thesis_data"
        missing = [c for c in required if c not in df.columns]
        if not missing:
            return df, f"raw/published/{stem}.csv"
        ctx.log.warning("simulate: %s lacks columns %s; using the built-in transcription", path, missing)
    return fallback(), "pipeline.vehicle.thesis_data"


def _bool(s: pd.Series) -> pd.Series:
    return s.map(lambda v: str(v).strip().lower() in ("true", "1", "yes", "y")) if s.dtype != bool else s


def _side_by_side(ours: pd.DataFrame, thesis: pd.DataFrame, keys: list[str]) -> pd.DataFrame:
    out = thesis.merge(ours, on=keys, how="left", sort=False)
    for name in ("rolling", "stationary"):
        out[f"difference_{name}"] = out[f"ours_{name}"] - out[f"thesis_{name}"]
    cols = keys + ["thesis_rolling", "ours_rolling", "difference_rolling", "thesis_stationary", "ours_stationary", "difference_stationary"]
    return out[cols]


def run(ctx: Context) -> StageResult:
    """Run the chapter 6-8 simulations and write their tables (see module docstring)."""
    t0 = time.perf_counter()
    inputs, sources = {}, []
    for stem in _INPUTS:
        inputs[stem], src = _load(ctx, stem)
        sources.append({"table": stem, "source": src, "rows": len(inputs[stem])})
    xii = inputs["table_xii"].copy()
    if "load_condition" not in xii:
        xii["load_condition"] = np.where(xii["load_kg"] < 2000, "light", "heavy")
    stationary = thesis_data.table_xii_stationary()

    # chapter 6: carriage
    car = studies.carriage_study(xii, stationary, seed=SEED)
    xiii = _side_by_side(
        car["table_xiii"].rename(columns={"rolling": "ours_rolling", "stationary": "ours_stationary"}),
        thesis_data.table_xiii(),
        ["quantity", "statistic"],
    )
    xiv = _side_by_side(
        car["table_xiv"].rename(columns={"rolling": "ours_rolling", "stationary": "ours_stationary"}),
        thesis_data.table_xiv(),
        ["quantity", "statistic"],
    )

    # chapter 7: tractor
    tr = studies.tractor_study(inputs["table_xv"], inputs["table_xvi"], seed=SEED)
    xvii = _side_by_side(tr["table_xvii"], thesis_data.table_xvii(), ["track", "quantity", "statistic"])
    thesis_xviii = thesis_data.table_xviii()
    xviii = tr["table_xviii"].merge(
        thesis_xviii[thesis_xviii["row"] == "predicted"].drop(columns="row").assign(longitudinal="kelvin_voigt"),
        on=["longitudinal", "longitudinal_stiffness_kN_per_m", "longitudinal_damping_kN_s_per_m"],
        how="left",
        suffixes=("_ours", "_thesis"),
    )
    ref = tr["reference_xviii"].iloc[0]
    meas = thesis_xviii[thesis_xviii["row"] == "measured"].iloc[0]
    xviii = pd.concat(
        [
            xviii.assign(row="predicted"),
            pd.DataFrame(
                [
                    {
                        "row": "measured (ours: reference virtual tractor)",
                        "longitudinal": "maxwell",
                        "longitudinal_stiffness_kN_per_m": studies.REFERENCE_LONGITUDINAL[0] / 1e3,
                        "longitudinal_damping_kN_s_per_m": studies.REFERENCE_LONGITUDINAL[1] / 1e3,
                        **{f"{c}_ours": ref[c] for c in ("vertical_rms_m_s2", "pitch_rms_rad_s2", "peak_1_Hz", "peak_2_Hz", "peak_3_Hz")},
                        **{f"{c}_thesis": meas[c] for c in ("vertical_rms_m_s2", "pitch_rms_rad_s2", "peak_1_Hz", "peak_2_Hz", "peak_3_Hz")},
                    }
                ]
            ),
        ],
        ignore_index=True,
    )

    # chapter 8: Table XX
    xix = inputs["table_xix"].copy()
    for c in ("four_wheel_drive", "front_water_ballast"):
        xix[c] = _bool(xix[c])
    xx = bounce_pitch.table_xx(xix, inputs["table_xx"])
    xx_stats = bounce_pitch.table_xx_statistics(xx)
    xx_stats["thesis_printed_mean"] = xx_stats["stiffness_source"].map({"formula": 0.998, "stationary_free_vibration": 1.19})
    xx_stats["thesis_printed_sd"] = xx_stats["stiffness_source"].map({"formula": 0.09, "stationary_free_vibration": 0.11})
    xx_stats["thesis_printed_p_within_10"] = xx_stats["stiffness_source"].map({"formula": 0.75, "stationary_free_vibration": 0.19})

    # ISO 2631 of every simulated run
    cr = car["runs"]
    iso_car = cr[["speed_km_h", "load_condition", "characteristics", "profile_estimate"] + [c for c in cr if c.startswith("iso_")]].copy()
    iso_car.insert(0, "study", "carriage")
    trr = tr["runs"]
    iso_tr = trr[["load_condition", "track", "speed_km_h", "characteristics", "longitudinal"] + [c for c in trr if c.startswith("iso_")]].copy()
    iso_tr["load_condition"] = iso_tr["load_condition"].astype(str)
    iso_tr.insert(0, "study", "tractor")
    iso = pd.concat([iso_car, iso_tr], ignore_index=True)

    spectra = pd.concat([car["spectra"], tr["spectra"]], ignore_index=True)

    tables = {
        "carriage_runs": cr,
        "carriage_comparisons": car["comparisons"],
        "table_xiii": xiii,
        "table_xiv": xiv,
        "tractor_runs": trr,
        "table_xvii": xvii,
        "table_xviii": xviii,
        "table_xx": xx,
        "table_xx_statistics": xx_stats,
        "iso2631": iso,
        "profile_spectra": spectra,
        "simulate_inputs": pd.DataFrame(sources),
    }
    for name, df in tables.items():
        ctx.write_table(name, df.reset_index(drop=True))
    n_runs = len(cr) + len(trr)
    return StageResult(
        name="simulate",
        n_in=n_runs,
        n_ok=n_runs,
        seconds=time.perf_counter() - t0,
        message=f"{len(tables)} tables; slatted track is a seeded stand-in",
    )
