"""Issue 44: directions apart — the thesis' (vertical) tables, views and figures hold only vertical runs,
the lateral and longitudinal runs have tables of their own, and the docs' example queries return
what they say."""

import numpy as np
import pandas as pd
import pytest

from tests.report.test_querying_examples import querying_section, sql_blocks
from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
from tests.synthetic_methods import broadband_recording

from tyrelab.cli import main
from tyrelab.measurement.methods import direction_runs, thesis_runs
from tyrelab.report import figures
from tyrelab.warehouse import query

pytestmark = pytest.mark.long

#: Vertical and lateral stiffness of the campaign's tyre T1 (N/m): apart by a factor of two, so an
#: average of both is far from either.
K_VERTICAL, K_LATERAL = 500e3, 250e3


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    root = tmp_path_factory.mktemp("directions")
    runs = []
    for i, p in enumerate((0.83, 1.38, 1.93)):
        runs.append((manifest_row(f"v{i}", f"v{i}.parquet", pressure_bar=p),
                     spring_damper_recording(K_VERTICAL + 1e5 * (p - 1.38), 2500.0, duration_s=12.0, seed=i)))
        runs.append((manifest_row(f"s{i}", f"s{i}.parquet", pressure_bar=p, direction="lateral"),
                     spring_damper_recording(K_LATERAL, 1500.0, duration_s=12.0, seed=10 + i)))
    runs.append((manifest_row("l_rnd", "l_rnd.parquet", method="random", direction="lateral", band_low_Hz=1.0,
                              band_high_Hz=8.0, speed_km_h=0.0, excitation_frequency_Hz=""),
                 broadband_recording(K_LATERAL, 1.5e3, seed=21)))
    write_campaign(root / "raw" / "c", runs)
    for stage in ("ingest", "analyse", "calibrate", "regress", "warehouse"):
        assert main([stage, "--raw", str(root / "raw"), "--build", str(root / "build"), "--jobs", "1", "-q"]) == 0
    return root / "build"


def test_each_direction_has_its_own_table_and_the_thesis_tables_read_vertical_runs(build):
    db = build / "warehouse.duckdb"
    every = query(db, "SELECT run_id, direction FROM results ORDER BY run_id")
    for d in ("vertical", "lateral", "longitudinal"):
        own = query(db, f"SELECT run_id, direction FROM results_{d} ORDER BY run_id")
        assert set(own["direction"]) <= {d}
        assert list(own["run_id"]) == list(every.loc[every["direction"] == d, "run_id"])
    assert len(query(db, "SELECT * FROM results_lateral")) == 4
    by_speed = query(db, "SELECT * FROM stiffness_pressure_by_speed WHERE tyre_id = 'T1'")
    assert (by_speed["n"] == 3).all()  # the three vertical runs, none of the four lateral ones


def test_the_docs_examples_return_what_they_say(build):
    db = build / "warehouse.duckdb"
    results = pd.read_parquet(build / "parquet" / "results.parquet")
    blocks = sql_blocks(querying_section())
    for sql in (b for b in blocks if "results_" in b):  # the others: tests/report/test_querying_examples.py
        assert len(query(db, sql)) > 0, sql
    t1 = next(b for b in blocks if "tyre_id = 'T1'" in b)
    got = query(db, t1).set_index("pressure_bar")["stiffness_kN_per_m"]
    vertical = thesis_runs(results)
    want = vertical.loc[vertical["qc_ok"]].groupby("pressure_bar")["stiffness_kN_per_m"].mean().round(1)
    assert got.to_dict() == want.to_dict()
    assert np.allclose(got.to_numpy(), 500.0 + 100.0 * (got.index.to_numpy() - 1.38), rtol=0.02)
    lateral = next(b for b in blocks if "results_lateral" in b)
    got = query(db, lateral)
    assert got["stiffness_kN_per_m"].between(0.9 * K_LATERAL / 1e3, 1.1 * K_LATERAL / 1e3).all()


def test_the_thesis_figures_draw_no_lateral_run():
    rows = pd.DataFrame({"tyre_id": "T1", "speed_km_h": 0.0, "pressure_bar": [0.83, 1.38], "kind": "measurement",
                         "stiffness_kN_per_m": 250.0, "damping_kN_s_per_m": 1.5, "qc_ok": True,
                         "direction": "lateral", "method": "stepped_sine"})
    assert figures.stiffness_vs_pressure(rows, "T1") is None  # nothing vertical to draw
    assert figures.stiffness_vs_speed(rows) is None and figures.damping_vs_speed(rows) is None
    svg = figures.stiffness_vs_pressure(rows.assign(direction="vertical"), "T1")
    assert svg is not None and "vertical stiffness" in svg


def test_direction_runs_refuses_an_unknown_direction():
    with pytest.raises(ValueError, match="direction"):
        direction_runs(pd.DataFrame({"direction": ["vertical"]}), "diagonal")
