"""The sixth hostile round, output (issue 46, Deliver 7): ``tyrelab sql``'s table (the default
format, for a terminal) escapes the control characters of names and text values as every other
verb does, and so do the report's pages (a run id with an ESC); a result of duplicate column names
is answered in each format."""

import json

import pytest

from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
from tyrelab.cli import main
from tyrelab.stages import Context, run_stage


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    root = tmp_path_factory.mktemp("sql6")
    raw = write_campaign(root / "raw", [(manifest_row("a1", "a1.parquet"), spring_damper_recording(duration_s=20))])
    ctx = Context(raw=raw, build=root / "build", jobs=1)
    for s in ("ingest", "analyse", "calibrate", "warehouse"):
        run_stage(s, ctx)
    return ctx.build


def sql(build, text, capsys, *fmt):
    rc = main(["sql", "--build", str(build), *fmt, text])
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_the_table_escapes_control_characters_of_values_and_names(build, capsys):
    rc, out, err = sql(build, "SELECT 'a' || chr(27) || '[2J' AS x, 'p' || chr(10) || 'day: q' AS \"n\x07m\", 3 AS k", capsys)
    assert rc == 0 and err == ""
    assert "\x1b" not in out and "\x07" not in out
    assert out.splitlines() == [out.splitlines()[0], out.splitlines()[1]]  # a header and one row: no forged line
    assert "a\\x1b[2J" in out and "p\\nday: q" in out and "n\\x07m" in out
    rc, out, _ = sql(build, "SELECT 'a' || chr(27) AS x", capsys, "--format", "json")
    assert json.loads(out) == [{"x": "a\x1b"}]  # json keeps the value (escaped by JSON itself)


@pytest.mark.parametrize("fmt", ["table", "csv", "json"])
def test_duplicate_column_names_are_answered(build, capsys, fmt):
    rc, out, err = sql(build, "SELECT 1 AS a, 'x' AS a", capsys, "--format", fmt)
    assert rc == 0 and "Traceback" not in err and "TypeError" not in err
    if fmt == "json":
        assert json.loads(out) == [{"a": 1, "a_2": "x"}] and "same name" in err
    else:
        assert "x" in out and out.count("a") >= 2


def test_a_report_page_shows_a_control_character_as_its_escape():
    from tyrelab.report.render import environment

    page = environment().from_string("<td>{{ run_id }}</td><td>{{ run_id|breakable }}</td><td>{{ n }}</td><p>{{ text }}</p>")
    html = page.render(run_id="esc\x1b[31m_<b>", n=3, text="two\nlines\ttab")
    assert "\x1b" not in html
    assert html == ("<td>esc\\x1b[31m_&lt;b&gt;</td><td>esc\\x1b[31m_<wbr>&lt;b&gt;</td><td>3</td>"
                    "<p>two\nlines\ttab</p>")  # escaped for HTML too; a newline and a tab are HTML's own
