"""The command line as an engineer reads it (issue 26): global options anywhere, "did you mean",
aliases, help on every option with the exit codes, completion, the same names as ``ride``."""

from __future__ import annotations

import argparse
import json
import logging
import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tyrelab import cli, progress

from tests.scenarios import scenario_text, write


def _verbs(parser):
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return sub.choices


@pytest.mark.parametrize("argv", [["-q", "sql", "SELECT 1"], ["sql", "-q", "SELECT 1"], ["sql", "SELECT 1", "--quiet"]])
def test_global_options_before_or_after_the_verb(argv):
    args = cli.build_parser().parse_args(argv)
    assert args.quiet is True and args.verbose is False and args.command == "sql"


def test_verbose_after_the_verb_and_never_with_quiet(capsys):
    args = cli.build_parser().parse_args(["run", "--raw", "x", "-v"])
    assert args.verbose and not args.quiet
    with pytest.raises(SystemExit) as info:
        cli.main(["-q", "run", "--verbose"])
    assert info.value.code == 2 and "not allowed with" in capsys.readouterr().err


def test_verbose_logs_debug(tmp_path):
    cli._configure_output(argparse.Namespace(quiet=False, verbose=True))
    try:
        assert logging.getLogger("tyrelab").getEffectiveLevel() == logging.DEBUG
        cli._configure_output(argparse.Namespace(quiet=True, verbose=False))
        assert logging.getLogger("tyrelab").getEffectiveLevel() == logging.WARNING and not progress._bars_wanted
    finally:
        cli._configure_output(argparse.Namespace(quiet=False, verbose=False))


@pytest.mark.parametrize("typed,suggested", [("analyse-rn", "analyse-run"), ("natural-frequency", "natural-frequencies"),
                                             ("estimate-stifness", "estimate-stiffness"), ("sqll", "sql")])
def test_a_mistyped_verb_gets_did_you_mean(capsys, typed, suggested):
    with pytest.raises(SystemExit) as info:
        cli.main([typed])
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert info.value.code == 2
    assert err.startswith(f"tyrelab: error: unknown verb '{typed}'; did you mean") and repr(suggested) in err, err


@pytest.mark.parametrize("alias", ["analyze-run", "analyse-run", "analyze"])
def test_analyze_run_aliases(alias):
    args = cli.build_parser().parse_args([alias, "r.csv", "--axle-mass", "100"])
    assert args.func is cli.cmd_analyze_run and args.axle_mass == 100


def test_every_option_of_every_verb_has_help_and_every_help_has_the_exit_codes():
    parser = cli.build_parser()
    missing = []
    for name, verb in [("tyrelab", parser), *_verbs(parser).items()]:
        assert "exit codes:" in verb.format_help() and "130" in verb.format_help(), name
        for action in verb._actions:
            if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)):
                continue
            if not action.help or action.help == argparse.SUPPRESS:
                missing.append(f"{name} {'/'.join(action.option_strings) or action.dest}")
    assert missing == []
    from tyrelab.stages import ORDER

    stage_helps = {_verbs(parser)[s].description for s in ORDER}
    assert len(stage_helps) == len(ORDER)  # each stage verb says what it does, a new stage included
    assert not [s for s in ORDER if _verbs(parser)[s].description.startswith(f"the {s} stage")]  # no stand-in
    assert "The ``tyrelab`` command line" not in parser.format_help()


def test_completion_script_from_argcomplete(capsys):
    assert cli.main(["completion", "bash"]) == 0
    script = capsys.readouterr().out
    assert "tyrelab" in script and "complete " in script and "_ARGCOMPLETE" in script
    head = Path(cli.__file__).read_text(encoding="utf-8")[:1024]
    assert "PYTHON_ARGCOMPLETE_OK" in head  # argcomplete completes the console script


def test_completion_offers_the_verbs(monkeypatch):
    """What argcomplete answers the shell for ``tyrelab ana<TAB>``."""
    import argcomplete

    line = "tyrelab ana"
    monkeypatch.setenv("_ARGCOMPLETE", "1")
    monkeypatch.setenv("COMP_LINE", line)
    monkeypatch.setenv("COMP_POINT", str(len(line)))
    monkeypatch.setenv("_ARGCOMPLETE_IFS", "\n")
    out = []

    class Sink:
        def write(self, data):
            out.append(data if isinstance(data, str) else data.decode())

        def flush(self):
            pass

    with pytest.raises(SystemExit):
        argcomplete.autocomplete(cli.build_parser(), output_stream=Sink(), exit_method=sys.exit)
    offered = "".join(out).split()
    assert {"analyse", "analyze-run", "analyse-run"} <= set(offered), offered


NF = ["natural-frequencies", "--mass", "4700", "--pitch-inertia", "5500", "--front-distance", "1.56",
      "--rear-distance", "0.95", "--front-tyre", "14.9R28", "--front-pressure", "1.6", "--rear-tyre", "18.4R38",
      "--rear-pressure", "1.2"]


def test_natural_frequencies_by_mode_with_nodal_points(capsys):
    assert cli.main(NF) == 0
    out = json.loads(capsys.readouterr().out)
    modes = out["natural_frequencies_Hz"]
    assert sorted([modes["bounce"], modes["pitch"]]) == pytest.approx([out["frequency_1_Hz"], out["frequency_2_Hz"]])
    # independent check of a nodal point: the mode (z, θ) with x = -z/θ leaves the point x at rest,
    # so the undamped equations of motion hold there: K·v = ω² M·v for v = (z, θ) = (-x, 1)
    kf, kr = 2e3 * out["front_tyre_stiffness_kN_per_m"], 2e3 * out["rear_tyre_stiffness_kN_per_m"]
    a, b, m, inertia = 1.56, 0.95, 4700.0, 5500.0
    stiffness = np.array([[kf + kr, kf * a - kr * b], [kf * a - kr * b, kf * a * a + kr * b * b]])
    for mode in ("bounce", "pitch"):
        x, w2 = out["nodal_points_m"][mode], (2 * math.pi * modes[mode]) ** 2
        v = np.array([-x, 1.0])
        assert stiffness @ v == pytest.approx(w2 * np.array([m, inertia]) * v, rel=1e-9)
    assert abs(out["nodal_points_m"]["bounce"]) > abs(out["nodal_points_m"]["pitch"])


def test_a_pure_bounce_mode_has_no_nodal_point(capsys):
    """Front and rear alike about the CG: bounce does not pitch; its nodal point is null in JSON."""
    argv = NF[:]
    argv[argv.index("0.95")] = "1.56"
    argv += ["--front-stiffness", "300", "--rear-stiffness", "300"]
    assert cli.main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["nodal_points_m"]["bounce"] is None and out["nodal_points_m"]["pitch"] == pytest.approx(0, abs=1e-9)


def test_both_spellings_of_the_front_tyre_in_both_verbs(capsys):
    def run(argv):
        assert cli.main(argv) == 0
        return capsys.readouterr().out

    assert run(NF + ["--front-undriven"]) == run(NF)  # natural-frequencies: undriven is the default
    assert run(NF + ["--front-traction"]) != run(NF)
    es = ["estimate-stiffness", "--size", "14.9R28", "--pressure", "1.6", "--format", "json"]
    assert run(es + ["--front-traction"]) == run(es)  # estimate-stiffness: the size formula is the default
    assert run(es + ["--front-undriven"]) != run(es)
    with pytest.raises(SystemExit):
        cli.main(es + ["--front-traction", "--front-undriven"])
    assert "not allowed with" in capsys.readouterr().err


@pytest.fixture(scope="module")
def tiny_warehouse(tmp_path_factory) -> Path:
    import duckdb

    build = tmp_path_factory.mktemp("build")
    con = duckdb.connect(str(build / "warehouse.duckdb"))
    con.execute("CREATE TABLE quarantine AS SELECT 'c' AS campaign, 'r1' AS run_id, 'f' AS file, 'ingest' AS stage, "
                "'bad' AS reason")
    con.close()
    return build


def test_an_empty_result_says_no_rows(tiny_warehouse, capsys):
    q = "SELECT * FROM quarantine WHERE stage = 'analyse'"
    assert cli.main(["sql", "--build", str(tiny_warehouse), q]) == 0
    out = capsys.readouterr().out
    assert out == "no rows (columns: campaign, run_id, file, stage, reason)\n"
    assert cli.main(["sql", "--build", str(tiny_warehouse), "--format", "csv", q]) == 0
    assert capsys.readouterr().out == "campaign,run_id,file,stage,reason\n"  # CSV keeps its header
    assert cli.main(["sql", "--build", str(tiny_warehouse), "--format", "json", q]) == 0
    assert capsys.readouterr().out == "[]\n"


def test_warehouse_query_takes_the_build_folder(tiny_warehouse):
    from tyrelab import warehouse

    by_folder = warehouse.query(tiny_warehouse, "SELECT * FROM quarantine")
    by_file = warehouse.query(tiny_warehouse / "warehouse.duckdb", "SELECT * FROM quarantine")
    pd.testing.assert_frame_equal(by_folder, by_file)
    with pytest.raises(FileNotFoundError, match="no warehouse yet"):
        warehouse.query(tiny_warehouse / "nothing", "SELECT 1")


def test_ride_takes_an_absolute_profile_path_for_the_users_own_file(tmp_path, capsys):
    from tyrelab.scenario_io import ScenarioError, load_scenario

    track = tmp_path / "elsewhere" / "track.csv"
    track.parent.mkdir()
    x = np.arange(0.0, 400.0, 0.05)
    pd.DataFrame({"distance_m": x, "height_m": 0.01 * np.sin(2 * np.pi * x / 3.0)}).to_csv(track, index=False)
    (tmp_path / "mine").mkdir()
    path = write(tmp_path / "mine", scenario_text(f'kind = "profile"\nprofile = "{track}"', speeds="[8]"))
    with pytest.raises(ScenarioError, match="give a path relative to the scenario file"):
        load_scenario(path)  # campaign scenarios stay confined to their folder
    assert load_scenario(path, confine=False).surface.profile == track
    assert cli.main(["-q", "ride", str(path), "--format", "table"]) == 0
    assert "test tractor" in capsys.readouterr().out


def test_progress_bar_only_on_a_terminal_and_not_under_quiet(monkeypatch, capsys):
    class Tty:
        def __init__(self, real):
            self.real = real

        def isatty(self):
            return True

        def __getattr__(self, name):
            return getattr(self.real, name)

    progress.configure(bars=True)
    try:
        p = progress.Progress("analyse", 2, logger=logging.getLogger("test"))
        assert p.bar is None  # pytest's stderr is not a terminal
        monkeypatch.setattr(sys, "stderr", Tty(sys.stderr))
        p = progress.Progress("analyse", 2, logger=logging.getLogger("test"))
        assert p.bar is not None
        p.step(2)
        assert p.bar is None and progress._open == []  # removed at the end
        progress.configure(bars=False)  # -q
        assert progress.Progress("analyse", 2).bar is None
    finally:
        progress.configure(bars=False)
        progress.close_all()


def test_analyse_counts_its_own_qc_flags_not_calibrates():
    from tyrelab.stages.analyse import _flagged_by_analyse

    assert not _flagged_by_analyse("calibration failed on 1989-05-04")
    assert _flagged_by_analyse("coherence 0.42 below 0.8; calibration failed on 1989-05-04")
    assert not _flagged_by_analyse("")


def _ride_doc() -> dict:
    """A ride document whose hours span 6 to 1985 h and a_w 0.07 to 1.35 m/s² (the demo's modern tractor)."""
    speeds = []
    for v, aw, hours in ((4, 0.0731, 375.31), (8, 0.5691, 6.1702), (12, 1.3521, 2.1123)):
        speeds.append({"speed_km_h": v, "a_wz_m_s2": aw, "expected_a_wz_m_s2": aw * 0.97, "a_wx_m_s2": aw * 0.7,
                       "a_v_m_s2": aw * 1.4, "vdv_m_s1_75": aw * 5.3, "crest_factor": 3.5, "lift_off_fraction_front": 0.0,
                       "lift_off_fraction_rear": 0.0, "a8_m_s2": aw, "hours_to_eav": hours, "hours_to_elv": hours * 5.29,
                       "verdict": "above action value" if aw > 0.5 else "below action value", "simulation": "linear"})
    tyre = {"size": "380/85R28", "pressure_bar": 1.6, "stiffness_kN_per_m": 355.920315, "damping_kN_s_per_m": 1.089412,
            "stiffness_source": "formula", "damping_source": "model", "stiffness_u_kN_per_m": 24.768423}
    return {"name": "modern", "track": "ISO 8608 class C", "hours_per_day": 8.0, "tyres": {"front": tyre, "rear": tyre},
            "natural_frequencies_Hz": {"bounce": 2.725845, "pitch": 3.476311},
            "natural_frequencies_Hz_ci95": {"bounce": [2.539125, 2.912566], "pitch": [3.252511, 3.70011]},
            "nodal_points_m": {"bounce": 2.461186, "pitch": -0.475467}, "warnings": [], "speeds": speeds}


def test_ride_table_one_number_format_per_quantity_under_the_reports_names():
    """``tyrelab ride --format table``: 375 h and 6.17 h once read "375" and "6.170"; now each quantity
    has one format (significant digits by its uncertainty where it has one) and each column the
    report's name (``a_wz (m/s²)``, the JSON's ``a_wz_m_s2``)."""
    import re

    from tyrelab.report.ride_page import QUANTITIES, format_table, number_formats
    from tyrelab.report.render import column_label

    doc = _ride_doc()
    text = format_table(doc, width=None)  # --wide: every column of a row on one line
    lines = text.splitlines()
    first = next(i for i, line in enumerate(lines) if line.split()[:1] == ["speed"])
    rows = [line.split() for line in lines[first:] if re.match(r"\s*\d", line)]
    assert len(rows) == 3
    header = " ".join(lines[first:first + 4])
    for label in ("a_wz", "expected", "(m/s²)", "hours", "eav", "elv", "lift off"):
        assert label in header
    assert "a wz" not in text and "h->EAV" not in text
    fmt = number_formats(doc)
    for cols in QUANTITIES.values():  # every column of one quantity: the same decimals
        assert len({fmt["columns"][c] for c in cols}) == 1
    hours = [r[-6:-4] for r in rows]  # hours to EAV and ELV, before the two-word verdict and the simulation
    assert {len(h.partition(".")[2]) for pair in hours for h in pair} == {fmt["columns"]["hours_to_eav"]} == {1}
    assert hours[0] == ["375.3", "1985.4"] and hours[1] == ["6.2", "32.6"]
    assert "K = 356 ± 49 kN/m" in text  # 1.96 u = 48.5: two significant digits, the value to the same place
    assert "bounce 2.73 Hz [2.54, 2.91] (node 2.46 m ahead of the CG)" in text
    assert "pitch 3.48 Hz [3.25, 3.70] (node 0.48 m behind the CG)" in text
    assert column_label("a_wz_m_s2") == "a_wz (m/s²)"


def test_ride_table_fits_100_columns_and_keeps_every_number():
    """Issue 47: the ride table was 230-480 characters wide. By default every line fits 100 columns: the
    prose wraps and the per-speed table splits into blocks that repeat the speed; ``--wide`` has it whole."""
    from tyrelab.report.ride_page import format_table

    doc = _ride_doc()
    doc["warnings"] = ["tyres.rear: W·R = 718.1 in² is above the thesis' data (traction tyres of Tables II-III: "
                       "326.4-699.2 in²) by 18.9 in² (2.7 %) " * 2]
    narrow, wide = format_table(doc), format_table(doc, width=None)
    assert max(map(len, narrow.splitlines())) <= 100 < max(map(len, wide.splitlines()))
    assert sorted(narrow.split()) != sorted(wide.split())  # wrapped and split, but
    numbers = lambda text: sorted(w for w in text.split() if w[:1].isdigit() and w not in ("4", "8", "12"))
    assert numbers(narrow) == numbers(wide)  # every number is there, once (the speeds repeat per block)
    blocks = narrow.split("\n\n")
    assert len(blocks) > 1 and all("speed" in b for b in blocks)


def test_progress_iterate_counts_an_item_when_the_body_is_done_with_it(caplog):
    p = progress.Progress("rides: c1", 3, logger=logging.getLogger("tyrelab"), unit="recordings")
    seen = []
    with caplog.at_level(logging.INFO, logger="tyrelab"):
        for item in p.iterate(["a", "b", "c"]):
            seen.append((item, p.done))
            if item == "b":
                continue  # a refused row is counted too
    assert seen == [("a", 0), ("b", 1), ("c", 2)] and p.done == 3
    assert "rides: c1: 3/3 recordings" in caplog.text


def test_a_misspelt_scenario_key_gets_did_you_mean(tmp_path, capsys):
    """Issue 47: ``--set seat.dampingratio=0.2`` said "not a numeric scenario key" and no more."""
    from tests.scenarios import scenario_text, write

    path = write(tmp_path, scenario_text(speeds="[8]"))
    assert cli.main(["-q", "ride", str(path), "--set", "tractor.mas_kg=4000,4500"]) == 2
    assert "did you mean 'tractor.mass_kg'" in capsys.readouterr().err
    bad = tmp_path / "bad.toml"
    bad.write_text(path.read_text().replace("[tractor]", "[tractor]\nmas_kg = 1", 1))
    assert cli.main(["-q", "ride", str(bad)]) == 2
    assert "did you mean 'tractor.mass_kg'" in capsys.readouterr().err
