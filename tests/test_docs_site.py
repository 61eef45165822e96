"""The documentation site's generated reference (docs/site/_ext/tyrelab_reference.py, issue 38):
complete by construction — every scenario key, every declared table, every CLI verb."""

import importlib.util
import sys
from pathlib import Path

import pytest

from tyrelab.stages import dag
from tyrelab.vehicle.scenario import key_table

EXT = Path(__file__).resolve().parents[1] / "docs" / "site" / "_ext" / "tyrelab_reference.py"


@pytest.fixture(scope="module")
def ref():
    spec = importlib.util.spec_from_file_location("tyrelab_reference", EXT)
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("tyrelab_reference", module)
    spec.loader.exec_module(module)
    return module


def test_every_scenario_key_is_in_the_reference_with_unit_default_and_bounds(ref):
    rows = ref.scenario_rows()
    listed = {(title, r[0]) for title, (_, rs) in rows.items() for r in rs}
    for sec, key in key_table()[["section", "key"]].itertuples(index=False):
        assert (f"[{sec}]" if sec else "top level", key) in listed
    mass = next(r for r in rows["[tractor]"][1] if r[0] == "mass_kg")
    assert mass[2] == "kg" and mass[3] == "required" and "model: 200 to 50000" in mass[4]


def test_every_declared_table_is_in_the_reference(ref):
    tables = ref.declared_tables()
    published = {p.removeprefix("parquet/").removesuffix(".parquet") for s in dag.STAGES.values() for p in s.writes
                 if p.startswith("parquet/") and p.endswith(".parquet") and "/stages/" not in p}
    assert published <= set(tables) and tables["results"] == "calibrate" and "runs" in tables


def test_columns_get_their_meaning_from_the_schemas(ref):
    published, raw = ref._schema_descriptions()
    assert "Carcass stiffness" in ref.column_meaning("table_iii", "carcass_stiffness_kN_per_m", published, raw)
    assert ref.column_meaning("table_iii", "thesis_carcass_stiffness_kN_per_m", published, raw).startswith("The thesis' printed value")
    assert ref.column_meaning("table_iii", "carcass_stiffness_kN_per_m_difference", published, raw).startswith("Ours − thesis")
    assert ref.column_meaning("manifest", "axle_mass_kg", published, raw)


def test_the_cli_reference_has_every_verb_without_the_preformatted_epilogs(ref):
    import argparse

    from tyrelab.cli import build_parser

    verbs = lambda p: next(a for a in p._actions if isinstance(a, argparse._SubParsersAction)).choices
    ours, theirs = verbs(ref.cli_parser()), verbs(build_parser())
    assert set(ours) == set(theirs) and all(sp.epilog is None for sp in ours.values())


def test_a_missing_build_is_a_warning_not_an_empty_page(ref, tmp_path):
    said = []
    assert ref.table_nodes(str(tmp_path), said.append) == [] and "no built warehouse" in said[0]
