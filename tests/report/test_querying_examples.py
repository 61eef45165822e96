"""The README's "Querying the warehouse" examples run and return rows."""

import re
from pathlib import Path

from tyrelab.warehouse import query

ROOT = Path(__file__).resolve().parents[2]


def querying_section() -> str:
    """The README section between the querying markers (docs/querying.md as a fallback)."""
    readme = ROOT / "README.md"
    text = readme.read_text(encoding="utf-8") if readme.exists() else ""
    m = re.search(r"<!-- querying:start -->(.*?)<!-- querying:end -->", text, re.S)
    if m and m.group(1).strip():
        return m.group(1)
    return (ROOT / "docs" / "querying.md").read_text(encoding="utf-8")


def sql_blocks(markdown: str) -> list[str]:
    return [b.strip() for b in re.findall(r"```sql\n(.*?)```", markdown, re.S)]


def test_section_has_five_examples():
    assert len(sql_blocks(querying_section())) >= 5


def test_every_example_returns_rows(small_report):
    """The small campaign is vertical stepped sine only: an example over the lateral or longitudinal
    runs runs here, and returns rows in tests/report/test_directions.py's build, which has them."""
    db = small_report.build / "warehouse.duckdb"
    for sql in sql_blocks(querying_section()):
        df = query(db, sql)
        if "results_lateral" in sql or "results_longitudinal" in sql:
            continue
        assert len(df) > 0, f"no rows from:\n{sql}"
