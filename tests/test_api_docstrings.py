"""Every public function of ``tyrelab``, ``tyrelab.tyre``, ``tyrelab.vehicle`` and
``tyrelab.measurement`` has numpydoc ``Examples`` (run as doctests by ``make test``) and ``See Also``
(issue 47: the API reference had Examples on 82 of 246 and See Also on 12).

Those that lacked them when this test was written are listed in ``tests/api_docstrings_missing.txt``
with what they lack: the list may only shrink. A new public function without both sections fails
the first test; a listed function that gained a section (or is no longer public) fails the second,
until its line is removed.
"""

from __future__ import annotations

import importlib
import inspect
import re
from pathlib import Path

PACKAGES = ("tyrelab", "tyrelab.tyre", "tyrelab.vehicle", "tyrelab.measurement")
MISSING = Path(__file__).with_name("api_docstrings_missing.txt")
SECTIONS = {
    "Examples": re.compile(r"^\s*Examples\s*\n\s*-{3,}\s*\n(?:.*\n)*?\s*>>> ", re.M),
    "See Also": re.compile(r"^\s*See Also\s*\n\s*-{3,}\s*\n\s*\S", re.M),
}


def public_functions() -> dict[str, object]:
    """``package.name`` -> function, for every function in the packages' ``__all__`` (each once, under
    the first package that exports it: the name a user imports, whichever module defines it)."""
    found, seen = {}, set()
    for package in PACKAGES:
        module = importlib.import_module(package)
        for name in module.__all__:
            obj = getattr(module, name)
            if (inspect.isfunction(obj) or (callable(obj) and type(obj).__name__ == "module")) and id(obj) not in seen:
                seen.add(id(obj))
                found[f"{package}.{name}"] = obj
    return found


def lacking(obj) -> list[str]:
    """The sections among :data:`SECTIONS` that ``obj``'s docstring lacks."""
    doc = (inspect.getdoc(obj) or "") + "\n"
    return [section for section, pattern in SECTIONS.items() if not pattern.search(doc)]


def listed() -> dict[str, set[str]]:
    out = {}
    for line in MISSING.read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.startswith("#"):
            name, _, sections = line.partition(":")
            out[name.strip()] = {s.strip() for s in sections.split(",")}
    return out


def test_every_public_function_has_examples_and_see_also():
    known = listed()
    new = {name: lack for name, obj in public_functions().items()
           if (lack := lacking(obj)) and not set(lack) <= known.get(name, set())}
    assert not new, "public functions without numpydoc sections (add them): " + "; ".join(
        f"{n}: {', '.join(lack)}" for n, lack in sorted(new.items()))


def test_the_list_of_functions_still_lacking_them_only_shrinks():
    functions = public_functions()
    stale = [f"{name}: {', '.join(sorted(sections))}" for name, sections in listed().items()
             if name not in functions or set(lacking(functions[name])) != sections]
    assert not stale, f"update {MISSING.name}: these lines are no longer true: " + "; ".join(stale)


def test_the_check_sees_a_missing_section():
    def documented():
        """Do nothing.

        See Also
        --------
        lacking : the check.

        Examples
        --------
        >>> documented()
        """

    def bare():
        """Do nothing."""

    assert lacking(documented) == [] and lacking(bare) == ["Examples", "See Also"]
