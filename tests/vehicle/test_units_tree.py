"""Issue 35, Deliver 1: no kilo factor written out in tyrelab.vehicle but its one conversion.

The model is SI inside; kN values become SI where they are read and kN again where written
out, through :mod:`tyrelab.vehicle.units` (``from_kilo``/``to_kilo``). A ``2e3 *`` or ``1e3 *``
(or ``/ 1e3``) anywhere else in ``pipeline/vehicle`` is a conversion written by hand again.
"""

import re
from pathlib import Path

import tyrelab.vehicle

FACTOR = re.compile(r"\b[12]e3\s*\*|\*\s*[12]e3\b|/\s*[12]e3\b|\b[12]000(\.0*)?\s*\*|/\s*[12]000(\.0*)?\b")
ALLOWED = {"units.py"}


def _code_lines(text: str):
    """(line number, line) of the code, comments and doctest prompts left out."""
    for no, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        if stripped.startswith(("#", ">>>", "...")):
            continue
        yield no, line.split("  #")[0]


def test_no_kilo_factor_outside_the_one_conversion():
    root = Path(tyrelab.vehicle.__file__).parent
    found = []
    for path in sorted(root.rglob("*.py")):
        if path.name in ALLOWED:
            continue
        for no, line in _code_lines(path.read_text(encoding="utf-8")):
            if FACTOR.search(line):
                found.append(f"{path.relative_to(root)}:{no}: {line.strip()}")
    assert not found, "kilo factors written by hand (use tyrelab.vehicle.units):\n" + "\n".join(found)


def test_the_pattern_finds_what_it_should():
    for text in ("k = 2e3 * r['x']", "k = 1e3*x", "x / 1e3", "2 * k * 1e3", "1000 * kN"):
        assert FACTOR.search(text), text
    for text in ("dt = 1e-3 * n", "n = 1e3", "x = 41e3 * 2", "m = 21000 * 2"):
        assert not FACTOR.search(text), text
