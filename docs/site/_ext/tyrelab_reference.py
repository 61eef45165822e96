"""Sphinx directives that write tyrelab's reference pages from the code's own declarations.

- ``tyrelab-scenario-keys``: every scenario key, section by section, with its type, unit,
  default, bounds and meaning, from ``schemas/scenario.json`` and the model's bounds
  (:data:`tyrelab.vehicle.scenario_limits.LIMITS`).
- ``tyrelab-tables``: every warehouse table the stages declare (:data:`tyrelab.stages.dag.STAGES`)
  and the digitised thesis tables, each column with its type (from a built warehouse: the
  environment variable ``TYRELAB_DOCS_BUILD``, which ``make docs`` builds from the demo
  campaign), unit (from its name: :func:`tyrelab.report.render.column_label`) and meaning (the
  schemas' descriptions, else the naming rules of ``docs/architecture.md``).

A table the stages declare but the build lacks, or a build that cannot be read, is a warning:
``make docs`` runs Sphinx with ``-W``, so the reference cannot silently fall behind the code.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path


def _table(headers: list[str], rows: list[list[str]], widths: list[int]):
    from docutils import nodes

    table = nodes.table(classes=["tyrelab-reference"])
    group = nodes.tgroup(cols=len(headers))
    table += group
    for w in widths:
        group += nodes.colspec(colwidth=w)
    head = nodes.thead()
    group += head
    row = nodes.row()
    for h in headers:
        row += nodes.entry("", nodes.paragraph(text=h))
    head += row
    body = nodes.tbody()
    group += body
    for cells in rows:
        row = nodes.row()
        for i, text in enumerate(cells):
            para = nodes.paragraph()
            para += nodes.literal(text=text) if i == 0 and text else nodes.Text(text)
            row += nodes.entry("", para)
        body += row
    return table


def _section(parent_id: str, title: str, *content):
    from docutils import nodes

    sec = nodes.section(ids=[nodes.make_id(f"{parent_id}-{title}")])
    sec += nodes.title(text=title)
    for c in content:
        sec += c
    return sec


def _number(v) -> str:
    return f"{v:g}" if isinstance(v, (int, float)) and not isinstance(v, bool) else json.dumps(v, ensure_ascii=False)


# ----------------------------------------------------------------------------- scenario keys
def scenario_rows() -> dict[str, tuple[str, list[list[str]]]]:
    """Section -> (its description, rows of key, type, unit, default, bounds, meaning)."""
    from tyrelab.schema import load_schema
    from tyrelab.vehicle.scenario_limits import LIMITS

    schema = load_schema("scenario")["sections"]
    out = {}
    for name, sec in schema.items():
        src = schema[sec["same_as"]] if "same_as" in sec else sec
        rows = []
        for f in src["fields"]:
            c = f.get("constraints", {})
            bounds = []
            if "enum" in c:
                bounds.append("one of " + ", ".join(_number(v) for v in c["enum"]))
            for k, sym in (("minimum", "≥"), ("exclusiveMinimum", ">"), ("maximum", "≤"), ("exclusiveMaximum", "<")):
                if k in c:
                    bounds.append(f"{sym} {_number(c[k])}")
            model = LIMITS.get(f"{name}.{f['name']}") or LIMITS.get(f["name"])
            if model:
                bounds.append(f"model: {model[0]:g} to {model[1]:g}")
            default = "required" if c.get("required") else ("–" if f.get("default") is None else _number(f["default"]))
            rows.append([f["name"], f["type"], f.get("unit", "") or "–", default, "; ".join(bounds) or "–",
                         f.get("description", "")])
        title = f"[{name}]" if name else "top level"
        desc = sec.get("description", "") + (f" Same keys as [{sec['same_as']}]." if "same_as" in sec else "")
        out[title] = (desc, rows)
    return out


def scenario_nodes() -> list:
    """Every scenario key (``schemas/scenario.json``), one section and table per scenario section."""
    from docutils import nodes

    out = []
    for title, (desc, rows) in scenario_rows().items():
        out.append(_section("scenario", title, nodes.paragraph(text=desc),
                            _table(["key", "type", "unit", "default", "bounds", "meaning"], rows, [14, 6, 6, 6, 12, 40])))
    return out


# ----------------------------------------------------------------------------- warehouse tables
def declared_tables() -> dict[str, str]:
    """Every table of the warehouse the stages declare -> the stage that writes it."""
    from tyrelab.stages import dag

    out = {}
    for stage in dag.STAGES.values():
        for path in stage.writes:
            m = re.fullmatch(r"parquet/([a-z0-9_]+)\.parquet", path)
            if m:
                out[m.group(1)] = stage.name
            elif path == "parquet/runs/":
                out["runs"] = stage.name
    return out


def _schema_descriptions() -> tuple[dict[str, dict[str, str]], dict[str, str]]:
    """(published table -> column -> description), (column -> description of the raw schemas):
    :func:`tyrelab.legend.schema_descriptions`, the one reader of those schemas."""
    from tyrelab import legend

    published, raw, _ = legend.schema_descriptions()
    return published, raw


def column_meaning(table: str, column: str, published: dict | None = None, raw: dict | None = None) -> str:
    """What a column means: :func:`tyrelab.legend.meaning` (the legend, the published tables' and
    the raw formats' schemas, the warehouse's naming rules; ``published`` and ``raw`` are kept for
    callers of the former signature and not needed)."""
    from tyrelab import legend

    return legend.meaning(table, column)


def table_nodes(build: str | None, warn) -> list:
    """Every declared table and its columns (type, unit, meaning) from the warehouse of ``build``;
    ``warn(message)`` for a missing build or a declared table the build lacks."""
    db = Path(build or "") / "warehouse.duckdb"
    if not build or not db.is_file():
        warn(f"tyrelab-tables: no built warehouse at TYRELAB_DOCS_BUILD={build!r} (make docs builds one)")
        return []
    import duckdb
    from docutils import nodes

    from tyrelab import legend

    published, _, titles = legend.schema_descriptions()
    con = duckdb.connect(str(db), read_only=True)
    try:
        con.execute(f"SET file_search_path = '{Path(build).resolve()}'")
        present = {r[0] for r in con.execute("SELECT table_name FROM information_schema.tables").fetchall()}
        tables = declared_tables()
        tables.update({f"published_{t}": "warehouse (the digitised thesis tables)" for t in published})
        out = []
        for name, stage in sorted(tables.items()):
            if name not in present:
                warn(f"tyrelab-tables: declared table {name!r} (written by {stage}) is not in the warehouse")
                continue
            cols = con.execute(f'DESCRIBE "{name}"').fetchall()
            key = name.removeprefix("published_")
            rows = []
            for (col, unit, text), (_, typ, *_) in zip(legend.describe(name, [c[0] for c in cols]), cols):
                rows.append([col, typ.lower(), unit, text or "–"])
            about = legend.legend().get("tables", {}).get(name, {}).get("description", "")
            intro = (f"Written by {stage}." + (f" {titles[key]}." if key in titles else "")
                     + (f" {about}" if about else ""))
            out.append(_section("table", name, nodes.paragraph(text=intro),
                                _table(["column", "type", "unit", "meaning"], rows, [18, 8, 8, 50])))
        return out
    finally:
        con.close()


# ----------------------------------------------------------------------------- command line
def cli_parser():
    """:func:`tyrelab.cli.build_parser` for sphinx-argparse: every verb's epilog (the exit codes, a
    preformatted text block the page states once above) left out."""
    import argparse

    from tyrelab.cli import build_parser

    parser = build_parser()
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                sub.epilog = None
    return parser


def setup(app):
    from sphinx.util import logging
    from sphinx.util.docutils import SphinxDirective

    logger = logging.getLogger(__name__)

    class ScenarioKeys(SphinxDirective):
        def run(self):
            return scenario_nodes()

    class WarehouseTables(SphinxDirective):
        def run(self):
            return table_nodes(os.environ.get("TYRELAB_DOCS_BUILD"),
                               lambda msg: logger.warning(msg, location=(self.env.docname, self.lineno)))

    app.add_directive("tyrelab-scenario-keys", ScenarioKeys)
    app.add_directive("tyrelab-tables", WarehouseTables)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
