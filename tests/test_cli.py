import json

import pytest

from tyrelab.cli import build_parser, main



def test_every_contract_verb_exists():
    verbs = set(build_parser()._subparsers._group_actions[0].choices)
    assert {"generate", "run", "sql", "analyze-run", "estimate-stiffness", "natural-frequencies",
            "ingest", "analyse", "calibrate", "regress", "simulate", "warehouse", "report", "watch"} <= verbs


def test_natural_frequencies_leyland_with_thesis_stiffnesses(capsys):
    # Table XIX/XX: Leyland 272 with the thesis' tyre stiffnesses -> 2.76 and 3.50 Hz
    argv = ["natural-frequencies", "--mass", "3235", "--pitch-inertia", "2669", "--front-distance", "1.33",
            "--rear-distance", "0.71", "--front-tyre", "7.50-16", "--front-pressure", "2.06",
            "--rear-tyre", "13.6-38", "--rear-pressure", "1.1", "--front-stiffness", "247", "--rear-stiffness", "306"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert {"front_tyre_stiffness_kN_per_m", "rear_tyre_stiffness_kN_per_m", "frequency_1_Hz", "frequency_2_Hz"} <= set(out)
    assert out["frequency_1_Hz"] == pytest.approx(2.76, abs=0.01)
    assert out["frequency_2_Hz"] == pytest.approx(3.50, abs=0.01)


def test_natural_frequencies_uses_formula_and_front_rule(capsys):
    argv = ["natural-frequencies", "--mass", "3235", "--pitch-inertia", "2669", "--front-distance", "1.33",
            "--rear-distance", "0.71", "--front-tyre", "7.50-16", "--front-pressure", "2.06",
            "--rear-tyre", "13.6-38", "--rear-pressure", "1.1"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["rear_tyre_stiffness_kN_per_m"] == pytest.approx(303.6, abs=0.05)
    assert out["front_tyre_stiffness_kN_per_m"] == pytest.approx(134 / (7.5 * 18) * 7.5 * 16 * 2.06, rel=1e-9)


def test_natural_frequencies_bad_size(capsys):
    argv = ["natural-frequencies", "--mass", "3235", "--pitch-inertia", "2669", "--front-distance", "1.33",
            "--rear-distance", "0.71", "--front-tyre", "huge", "--front-pressure", "2.06",
            "--rear-tyre", "13.6-38", "--rear-pressure", "1.1"]
    assert main(argv) == 2
    assert "huge" in capsys.readouterr().err


def test_run_with_missing_or_empty_raw_is_a_usage_error(tmp_path, capsys):
    assert main(["run", "--raw", str(tmp_path / "nowhere"), "--build", str(tmp_path / "b")]) == 2
    assert "no such folder" in capsys.readouterr().err
    (tmp_path / "empty").mkdir()
    assert main(["run", "--raw", str(tmp_path / "empty"), "--build", str(tmp_path / "b")]) == 2
    assert "no campaign" in capsys.readouterr().err
    assert not (tmp_path / "b").exists()


@pytest.mark.parametrize("argv", [
    ["analyze-run", "x.parquet", "--axle-mass", "-5"],
    ["estimate-stiffness", "--size", "13.6R38", "--pressure", "-1"],
    ["natural-frequencies", "--mass", "0", "--pitch-inertia", "2669", "--front-distance", "1.33",
     "--rear-distance", "0.71", "--front-tyre", "7.50-16", "--front-pressure", "2.06",
     "--rear-tyre", "13.6-38", "--rear-pressure", "1.1"],
])
def test_impossible_numbers_are_refused(argv, capsys):
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
