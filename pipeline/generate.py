"""Write a virtual measurement campaign (``tyrelab generate``).

The only I/O around :mod:`tyrelab.rig`: builds the plan
(:func:`tyrelab.rig.campaigns.campaign_plan`), simulates each run
(:func:`tyrelab.rig.campaigns.simulate_run`) and writes a campaign folder in
raw format v1 (docs/architecture.md): ``manifest.csv`` and ``runs/<run_id>.parquet``.
All tyres are Table II tyres of the built-in catalogue, so no ``tyres.csv`` is
written, unless a generated tyre population is asked for (``tyre_population``). With
``rides`` (the command's default), also seat and cab-floor recordings of
virtual tractors (:mod:`tyrelab.vehicle.virtual_rides`): ``rides.csv``,
``rides/<ride_id>.parquet`` and the scenarios they name, ``rides/<scenario>.toml``; and the
recordings of the thesis' carriage and MF698T made by virtual vehicles
(:mod:`tyrelab.vehicle.study_recordings`; ``study`` rows of ``rides.csv``, the slatted
track's slat tops in ``rides/slatted_track.csv``), which the ``simulate`` stage compares its
chapter 6-7 predictions with; and a four-post stand campaign and a one-wheel track run of a 3-D
tractor (:mod:`tyrelab.stand`, ``rides/stand/``; thesis ch. 2, issue 43), whose transfer
functions and modes the rides stage estimates. Output is byte-for-byte reproducible for the same (scale, seed): each
run's generator is seeded from (seed, run_id), Parquet is written by pyarrow
without timestamps, the manifest with fixed float formatting.
"""

from __future__ import annotations

import dataclasses
import json
import time
from pathlib import Path

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from . import __version__, io
from .rig.campaigns import MANIFEST_COLUMNS, campaign_plan, population_plan, simulate_run
from .rig.instrument import NO_SCATTER, RigConfig

__all__ = ["write_run", "write_rides", "write_study_recordings", "write_stand_recordings", "generate_campaign",
           "MAX_SEED"]

#: Largest campaign seed: what an int64 column (``generator.json`` read back by pandas, DuckDB) holds
#: exactly (a documented choice; numpy's generators take any non-negative integer).
MAX_SEED = 2**63 - 1


def write_run(run: pd.DataFrame, path: Path) -> None:
    """Write one run table to Parquet atomically (zstd, byte-stream-split floats)."""
    table = pa.Table.from_pandas(run, preserve_index=False)
    table = table.replace_schema_metadata(None)  # no pandas metadata: bytes depend on data only
    with io.atomic_path(path) as tmp:
        pq.write_table(table, tmp, compression="zstd", use_byte_stream_split=True, write_statistics=True)


def write_study_recordings(out: Path, seed: int) -> pd.DataFrame:
    """Write the recordings of the thesis' carriage and MF698T made by the virtual vehicles of
    :mod:`tyrelab.vehicle.study_recordings` (``rides/ch6_*``, ``rides/ch7_*``) and the slatted
    track's slat tops (``rides/slatted_track.csv``); returns their ``rides.csv`` rows."""
    from . import published
    from .vehicle.study_recordings import study_recordings

    rows, frames, track = study_recordings(
        {t: published.read_published(t) for t in ("table_xii", "table_xv", "table_xvi")}, seed)
    (out / "rides").mkdir(parents=True, exist_ok=True)
    for file, frame in frames.items():
        write_run(frame, out / file)
    io.write_text_atomic(track.to_csv(index=False, float_format="%.6g", lineterminator="\n"),
                         out / "rides" / "slatted_track.csv")
    return rows


def write_stand_recordings(out: Path, seed: int) -> pd.DataFrame:
    """Write the virtual four-post stand and track recordings and their 3-D tractor's scenario
    (:mod:`tyrelab.stand`, ``rides/stand/``); returns their ``rides.csv`` rows."""
    from . import stand

    plan = stand.stand_plan()
    (out / "rides" / "stand").mkdir(parents=True, exist_ok=True)
    io.write_text_atomic(stand.STAND_SCENARIO_TEXT, out / "rides" / "stand" / stand.STAND_SCENARIO_FILE)
    scenario = stand.stand_scenario()
    for row in plan.to_dict("records"):
        write_run(stand.stand_recording(scenario, row, seed), out / row["file"])
    return plan


def write_rides(out: Path, seed: int, tractors: bool = True, studies: bool = True, stands: bool = False) -> int:
    """Write ``rides.csv`` and its recordings; returns the count.

    ``tractors``: the virtual tractors' seat and cab-floor recordings and the scenarios they
    name (:mod:`tyrelab.vehicle.virtual_rides`). ``studies``: the chapter 6-7 recordings
    (:func:`write_study_recordings`), which the simulate stage compares its predictions with.
    ``stands``: the four-post stand and track recordings with wheel inputs
    (:func:`write_stand_recordings`).
    """
    from .resources import scenarios_dir
    from .scenario_io import load_scenario
    from .vehicle.virtual_rides import RIDE_PLAN, ride_plan, virtual_recordings

    parts = []
    if tractors:
        scenarios = {file: load_scenario(scenarios_dir() / file) for file, *_ in RIDE_PLAN}
        plan = ride_plan(scenarios)
        (out / "rides").mkdir(parents=True, exist_ok=True)
        for scenario_file, rows in plan.groupby("scenario", sort=False):
            name = Path(scenario_file).name
            io.write_text_atomic((scenarios_dir() / name).read_text(encoding="utf-8"), out / scenario_file)
            frames, _ = virtual_recordings(scenarios[name], name, seed)
            for row in rows.itertuples():
                write_run(frames[float(row.speed_km_h)], out / row.file)
        parts.append(plan)
    if studies:
        parts.append(write_study_recordings(out, seed))
    if stands:
        parts.append(write_stand_recordings(out, seed))
    if not parts:
        return 0
    plan = pd.concat(parts, ignore_index=True)
    io.write_text_atomic(plan.to_csv(index=False, float_format="%.6g", lineterminator="\n"), out / "rides.csv")
    return int(len(plan))


def generate_campaign(out: Path, scale: str = "small", seed: int = 1991, scatter: bool = True,
                      rides: bool = False, tyre_population: int = 0, runs=None) -> dict:
    """Simulate and write a virtual campaign folder.

    Parameters
    ----------
    out : Path
        Campaign folder (created). Existing run files of the same names are replaced.
    scale : {"small", "full"}
        ``small``: one run of each kind, Table III regressions possible, seconds.
        ``full``: the thesis programme (see :mod:`tyrelab.rig.campaigns`).
    seed : int
        Campaign seed, 0 to :data:`MAX_SEED`.
    scatter : bool
        The tyre's run-to-run and day-to-day scatter of thesis §3.6
        (:class:`tyrelab.rig.instrument.RigConfig` ``run_scatter``,
        ``day_scatter``; the default). False (``--no-scatter``): every run's
        tyre is exactly the truth model, for estimator benchmarks and
        truth-recovery tests.
    tyre_population : int
        0 (default): the thesis' programme on the Table II tyres. N > 0: pressure x speed
        sweeps of N generated tyres whose true rolling stiffness follows other coefficients
        than the thesis' formula (:mod:`tyrelab.rig.population`; seeded from ``seed``); their
        catalogue goes to ``tyres.csv`` and the true coefficients, ages and deviations to
        ``generator.json`` (``population``), so a refit can be checked against the truth.
    runs : callable, optional
        ``runs(plan) -> bool Series``: only the plan's rows it selects are simulated and written
        (a part of the campaign for a test; each run is the same as in the whole campaign: its
        seed comes from its run id, its instrument state from its day). None: every run.

    Returns
    -------
    dict
        ``runs`` (written), ``measurement_runs``, ``calibration_runs``, ``days``,
        ``seconds``, ``out``, ``scale``, ``seed``.
    """
    from . import _validate

    _validate.positive_int("seed", seed, minimum=0)  # before anything is written
    if seed > MAX_SEED:
        raise ValueError(f"seed must be an integer from 0 to {MAX_SEED}, got {_validate.shown(seed)}")
    t0 = time.perf_counter()
    out = Path(out)
    cfg = RigConfig() if scatter else dataclasses.replace(RigConfig(), **NO_SCATTER)
    population = ()
    if tyre_population:
        from .rig.population import MODERN_COEFFICIENTS, catalogue_rows, tyre_population as make_population

        population = make_population(int(tyre_population), seed)
        plan = population_plan(population, scale, cfg)
    else:
        plan = campaign_plan(scale, cfg)
    if runs is not None:
        plan = plan.loc[runs(plan)].reset_index(drop=True)
    (out / "runs").mkdir(parents=True, exist_ok=True)
    amplitudes = []
    for row in plan.to_dict("records"):
        run, info = simulate_run(row, seed, cfg)
        write_run(run, out / row["file"])
        amplitudes.append(info["amplitude_mm_pp"])
    manifest = plan[MANIFEST_COLUMNS].copy()
    cal = manifest["kind"] == "calibration"
    # calibration and broadband runs have no nominal sinusoid: record the p-p equivalent of the axle rms
    nominal = manifest["amplitude_mm_pp"].isna() | cal
    manifest.loc[nominal, "amplitude_mm_pp"] = [round(a, 2) for a, c in zip(amplitudes, nominal) if c]
    io.write_text_atomic(manifest.to_csv(index=False, float_format="%.6g", lineterminator="\n"),
                         out / "manifest.csv")
    # Provenance for the report (no timestamp: the same command gives the same bytes).
    meta = {"generator": "tyrelab virtual dynamic tyre test vehicle (tyrelab.rig)", "scale": scale, "seed": seed,
            "scatter": {"run": list(cfg.run_scatter), "day": list(cfg.day_scatter)},
            "tyrelab_version": __version__, "runs": int(len(plan))}
    if population:
        cat = pd.DataFrame(catalogue_rows(population))
        io.write_text_atomic(cat.to_csv(index=False, float_format="%.6g", lineterminator="\n"), out / "tyres.csv")
        meta["population"] = {
            "coefficients": dict(zip(("intercept_kN_per_m", "rim_diameter_kN_per_m_in", "age_kN_per_m_year",
                                      "wrp_kN_per_m_in2_bar"), MODERN_COEFFICIENTS)),
            "tyres": [{"tyre_id": m.params.tyre_id, "size": m.params.size, "age_years": m.params.age_years,
                       "deviation": round(m.deviation, 6), "carcass_stiffness_kN_per_m": round(m.params.k_rolling[0], 6),
                       "pressure_dependence_kN_per_m_bar": round(m.params.k_rolling[1], 6)} for m in population]}
    n_rides = write_rides(out, seed, stands=True) if rides else 0
    if rides:
        meta["rides"] = n_rides
    io.write_text_atomic(json.dumps(meta, indent=2, sort_keys=True) + "\n", out / "generator.json")
    return {
        "out": str(out), "scale": scale, "seed": seed, "scatter": bool(scatter), "runs": int(len(plan)),
        "measurement_runs": int((~cal).sum()), "calibration_runs": int(cal.sum()),
        "days": int(plan["recorded_on"].nunique()), "rides": n_rides, "seconds": round(time.perf_counter() - t0, 2),
    }
