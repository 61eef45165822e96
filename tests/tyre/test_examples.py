"""The example data of tyrelab.tyre's Examples (issue 45 review): written once, in tyre/examples.py."""

import ast
from pathlib import Path

import tyrelab.tyre
from tyrelab.tyre.examples import DEMO_SERIES, demo_runs
from tyrelab.tyre.regressions import pressure_regressions


def test_each_series_is_a_new_table_of_the_results_columns():
    for series in DEMO_SERIES:
        a, b = demo_runs(series), demo_runs(series)
        assert a is not b and a.equals(b)
        assert {"tyre_id", "kind", "qc_ok", "speed_km_h", "pressure_bar"} <= set(a.columns)
    a = demo_runs()
    a.loc[0, "stiffness_kN_per_m"] = 0.0
    assert demo_runs().loc[0, "stiffness_kN_per_m"] == 400.0


def test_the_pressure_series_gives_the_round_lines_its_docstring_promises():
    fit = pressure_regressions(demo_runs()).set_index("condition")
    assert fit.loc["stationary", ["intercept", "slope"]].round(9).tolist() == [300.0, 100.0]
    assert fit.loc["rolling", ["intercept", "slope"]].round(9).tolist() == [280.0, 100.0]


def test_no_example_of_the_tyre_package_writes_the_runs_out_again():
    """An Example that needs a tyre's runs calls demo_runs; a literal table of runs with their K in a
    docstring is a copy that drifts."""
    root = Path(tyrelab.tyre.__file__).parent
    copies = []
    for path in sorted(root.glob("*.py")):
        if path.name == "examples.py":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            doc = ast.get_docstring(node) if isinstance(node, (ast.FunctionDef, ast.ClassDef, ast.Module)) else None
            if doc and '"kind": "measurement", "qc_ok": True' in doc and '"stiffness_kN_per_m": [' in doc:
                copies.append(f"{path.name}: {getattr(node, 'name', '<module>')}")
    assert not copies, copies
