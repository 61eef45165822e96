"""A list key with many values out of range is one line, not one per value (issue 46's leftover: a
scenario with thousands of out-of-range speeds printed thousands of lines)."""
from tyrelab.cli import main
from tyrelab.resources import scenarios_dir

SCENARIO = (scenarios_dir() / "modern_tractor.toml").read_text(encoding="utf-8")


def _with_speeds(tmp_path, speeds):
    text = SCENARIO.replace("speeds_km_h = [4, 8, 12, 16]", f"speeds_km_h = [{', '.join(map(str, speeds))}]")
    assert text != SCENARIO
    path = tmp_path / "s.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_thousands_of_speeds_out_of_range_are_one_line(tmp_path, capsys):
    path = _with_speeds(tmp_path, [8] + list(range(100, 3100)))
    assert main(["ride", str(path), "--out", str(tmp_path / "out")]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert lines == [f"tyrelab ride: {path}: exposure.speeds_km_h: 3000 values are outside 0.5 to 80 km/h, what the "
                     "ride model is built for (100 km/h, 101 km/h, 102 km/h and 2997 more)"]
    assert not (tmp_path / "out").exists()


def test_a_few_are_one_line_each_and_other_keys_still_said(tmp_path, capsys):
    path = _with_speeds(tmp_path, [8, 100, 200])
    path.write_text(path.read_text(encoding="utf-8").replace("mass_kg = ", "mass_kg = 1e9 #", 1), encoding="utf-8")
    assert main(["ride", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "exposure.speeds_km_h: 100 km/h is outside" in err and "exposure.speeds_km_h: 200 km/h is outside" in err
    assert "mass_kg: 1e+09 kg is outside" in err


def test_speeds_given_on_the_command_line_too(tmp_path, capsys):
    args = ["ride", str(scenarios_dir() / "modern_tractor.toml"), "--out", str(tmp_path / "out"), "--speeds"]
    assert main(args + [str(v) for v in range(100, 1100)]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and "1000 values are outside 0.5 to 80 km/h" in lines[0], lines
