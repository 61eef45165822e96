"""estimate_stiffness: the formula on modern sizes, with where the thesis' data end (issue 12)."""

import dataclasses
import json

import pytest

from tyrelab.cli import main
from tyrelab.published import read_published
from tyrelab.tyre.stiffness import (
    FormulaDataRange,
    StiffnessEstimate,
    estimate_stiffness,
    range_warnings,
)


def thesis_data_range():
    return FormulaDataRange.from_tables(read_published("table_ii"), read_published("table_iii"),
                                        read_published("table_vi"))


def test_480_70R38_at_1_2_bar_two_years(thesis_model):
    e = estimate_stiffness("480/70R38", 1.2, 2, model=thesis_model)
    w, r = 480 / 25.4, 38
    assert e.stiffness_kN_per_m == pytest.approx(172 - 1.77 * r + 5.6 * 2 + 0.34 * w * r * 1.2)
    assert round(e.stiffness_kN_per_m, 1) == 408.9
    # W·R = 718.1 in² against the largest thesis tyre, 18.4R38 (699.2 in²)
    assert len(e.warnings) == 1
    assert "W·R = 718.1 in² is above" in e.warnings[0] and "by 18.9 in² (2.7 %)" in e.warnings[0]


def test_data_range_of_the_shipped_tables():
    r = thesis_data_range()
    # traction tyres of Table III (F1 excluded): smallest W·R 13.6R24/13.6-24, largest 18.4R38; R 24-44 in
    assert r.wr_in2 == pytest.approx((13.6 * 24, 18.4 * 38))
    assert r.rim_diameter_in == (24, 44)
    assert r.pressure_bar == (0.7, 2.0)  # Table VI 'Pressure .7-2 bar'
    assert r.age_years == (0, 16)  # T2 is 16 years old; Berlin tyres new
    assert r.front_wr_in2 == (7.5 * 18, 7.5 * 18)


def test_no_warning_inside_the_data_and_one_per_quantity_outside(thesis_model):
    assert estimate_stiffness("13.6R38", 1.2, 4, model=thesis_model).warnings == ()
    assert thesis_model.data_range == thesis_data_range()
    low = range_warnings("13.6R38", 0.5, 4, data_range=thesis_data_range())
    assert len(low) == 1 and low[0].startswith("P = 0.5 bar is below") and "by 0.2 bar" in low[0]
    many = range_warnings("9.5R48", 2.4, 20, data_range=thesis_data_range())
    assert [w.split(" =")[0] for w in many] == ["R", "A", "P"]
    assert "by 4 in" in many[0] and "by 4 years" in many[1] and "by 0.4 bar" in many[2]


def test_given_data_range_is_used():
    narrow = dataclasses.replace(thesis_data_range(), wr_in2=(100.0, 200.0))
    w = estimate_stiffness("13.6R38", 1.2, 4, data_range=narrow).warnings
    assert len(w) == 1 and "above" in w[0] and "100-200 in²" in w[0]


def test_front_rule_checks_against_f1_and_flexion_class_is_noted(thesis_model):
    w = estimate_stiffness("7.50-16", 2.06, undriven_front=True, model=thesis_model).warnings
    assert [x.split(" =")[0] for x in w] == ["W·R", "R"]
    assert estimate_stiffness("7.50-18", 2.06, undriven_front=True, model=thesis_model).warnings == ()
    vf = estimate_stiffness("VF 600/70R30", 1.0).warnings
    assert any(x.startswith("VF tyre") and "1.4 x the load" in x for x in vf)


def test_result_to_dict_carries_inputs_size_and_any_added_field():
    d = estimate_stiffness("520/85R42 157A8/154B", 1.6, 3).to_dict()
    assert d["size"] == "520/85R42 157A8/154B"
    assert d["section_width_mm"] == pytest.approx(520) and d["aspect_ratio"] == 0.85
    assert (d["load_index"], d["load_kg"], d["speed_km_h"], d["construction"]) == (157, 4125, 40, "radial")
    assert d["pressure_bar"] == 1.6 and d["age_years"] == 3 and isinstance(d["warnings"], list)
    json.dumps(d)
    # a later field (e.g. an interval) appears in the dict without touching to_dict
    Extended = dataclasses.make_dataclass(
        "Extended", [("interval_kN_per_m", tuple, (1.0, 2.0))], bases=(StiffnessEstimate,), frozen=True)
    e = Extended(**{f.name: getattr(estimate_stiffness("13.6R38", 1.2), f.name)
                    for f in dataclasses.fields(StiffnessEstimate)})
    assert e.to_dict()["interval_kN_per_m"] == [1.0, 2.0]


def test_bad_arguments():
    with pytest.raises(ValueError, match="age_years"):
        estimate_stiffness("13.6R38", 1.2, -1)
    with pytest.raises(ValueError, match="pressure"):
        estimate_stiffness("13.6R38", -1.2)


def test_cli_text_json_and_warning(capsys):
    assert main(["estimate-stiffness", "--size", "480/70R38", "--pressure", "1.2", "--age", "2"]) == 0
    cap = capsys.readouterr()
    assert cap.out.strip().startswith("408.9 kN/m (95 % prediction interval ")  # issue 14: with its interval
    assert "warning: W·R = 718.1 in² is above" in cap.err
    assert main(["estimate-stiffness", "--size", "480/70R38", "--pressure", "1.2", "--age", "2",
                 "--format", "json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["stiffness_kN_per_m"] == pytest.approx(408.929, abs=1e-3)
    assert {"size", "pressure_bar", "age_years", "section_width_in", "rim_diameter_in", "aspect_ratio",
            "construction", "rule", "water_ballast", "warnings"} <= set(out)
    assert out["rim_diameter_in"] == 38 and len(out["warnings"]) == 1
    assert main(["estimate-stiffness", "--size", "13.6R38", "--pressure", "1.2", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["warnings"] == []


def test_natural_frequencies_pass_the_warnings_on(capsys):
    argv = ["natural-frequencies", "--mass", "3235", "--pitch-inertia", "2669", "--front-distance", "1.33",
            "--rear-distance", "0.71", "--front-tyre", "7.50-18", "--front-pressure", "2.0",
            "--rear-tyre", "480/70R38", "--rear-pressure", "1.1"]
    assert main(argv) == 0
    cap = capsys.readouterr()
    out = json.loads(cap.out)
    assert len(out["warnings"]) == 1 and out["warnings"][0].startswith("rear tyre 480/70R38: W·R")
    assert "warning: rear tyre 480/70R38" in cap.err
    # given stiffnesses: nothing estimated, nothing to warn about
    assert main(argv + ["--front-stiffness", "247", "--rear-stiffness", "306"]) == 0
    assert json.loads(capsys.readouterr().out)["warnings"] == []
