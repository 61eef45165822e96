"""Issue 44: a legend for the warehouse — every column of every declared table has a unit and a
meaning in one place (schemas/warehouse_legend.json, tyrelab.legend), which the docs' reference and
``tyrelab sql --describe TABLE`` read; a table that gains a column without one fails here."""

import json

import duckdb
import pytest

from tyrelab import legend
from tyrelab.cli import main
from tyrelab.measurement import rig_methods as rm
from tyrelab.stages import dag


def _declared_columns(build) -> dict[str, list[str]]:
    con = duckdb.connect(str(build / "warehouse.duckdb"), read_only=True)
    try:
        present = {r[0] for r in con.execute("SELECT table_name FROM information_schema.tables").fetchall()}
        names = {p[len("parquet/"):-len(".parquet")] for s in dag.STAGES.values() for p in s.writes
                 if p.startswith("parquet/") and p.endswith(".parquet") and "/" not in p[len("parquet/"):]}
        return {t: [r[0] for r in con.execute("SELECT column_name FROM information_schema.columns WHERE table_name = ? "
                                              "ORDER BY ordinal_position", [t]).fetchall()]
                for t in sorted(names & present)}
    finally:
        con.close()


def test_every_column_of_every_declared_table_is_explained(full_report):
    tables = _declared_columns(full_report.build)
    assert "results" in tables and "results_lateral" in tables
    assert legend.undocumented(tables) == {}, "add the column's meaning to schemas/warehouse_legend.json"
    for t, cols in tables.items():
        for c in cols:
            assert legend.unit(t, c), (t, c)


def test_a_new_column_without_a_meaning_is_found():
    assert legend.undocumented({"results": ["stiffness_N_per_m", "a_column_nobody_explained"]}) == {
        "results": ["a_column_nobody_explained"]}


def test_the_method_columns_and_the_thesis_direction_are_explained():
    for c in rm.METHOD_COLUMNS:
        assert legend.meaning("results", c), c
    assert "vertical" in legend.meaning("results_vertical", "stiffness_kN_per_m").lower()
    assert legend.unit("results", "damping_u_a_N_s_per_m") == "N s/m"
    assert legend.unit("results", "creep_coefficient_N_s_per_m") == "N s/m"
    assert "creep" in legend.meaning("results", "creep_coefficient_N_s_per_m")
    assert "Ours − thesis" in legend.meaning("table_iii", "carcass_stiffness_kN_per_m_difference")
    # the meanings the audit found wrong
    assert "rig method" not in legend.meaning("ride_results", "method").lower().replace("not a rig method", "")
    assert "calibration" not in legend.meaning("ride_validation", "recorded_on")


def test_no_column_is_exempt():
    """The legend keeps no allow-list of columns still to be explained (it had 436; issue 44)."""
    assert "gaps" not in legend.legend()
    assert set(legend.legend()) == {"columns", "tables"}


def test_columns_whose_name_carries_no_unit_say_theirs():
    assert legend.unit("formula_fit", "wr_in2_min") == "in²"
    assert legend.unit("damping_fit", "age") == "kN s/m per year" and legend.unit("formula_fit", "age") == "kN/m per year"
    assert legend.unit("formula_accuracy", "thesis_p_within_10_percent") == "–"  # a probability, not a percentage
    assert legend.unit("table_xviii", "pitch_rms_rad_s2_ours") == "rad/s²"
    assert legend.unit("stiffness_pressure_by_speed", "between_run_sd") == "kN/m"
    assert legend.unit("damping_pressure_by_speed", "between_run_sd") == "kN s/m"
    # one name, two meanings: the regressions' weighting and the recordings' ISO weighting
    assert "WLS" in legend.meaning("table_iii", "weighting") and "Wk" in legend.meaning("recording_axes", "weighting")


def test_sql_describe_prints_unit_and_meaning(full_report, capsys):
    assert main(["sql", "--build", str(full_report.build), "--describe", "results", "--format", "json"]) == 0
    rows = {r["column"]: r for r in json.loads(capsys.readouterr().out)}
    assert rows["stiffness_kN_per_m"]["unit"] == "kN/m" and rows["stiffness_kN_per_m"]["meaning"] != "–"
    assert main(["sql", "--build", str(full_report.build), "--describe", "no_such_table"]) == 2
    assert "no such table" in capsys.readouterr().err
    assert main(["sql", "--build", str(full_report.build)]) == 2
    assert main(["sql", "--build", str(full_report.build), "--describe", "x; DROP"]) == 2
