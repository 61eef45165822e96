"""Doctests of the tyrelab source under its import name.

The source folder is ``pipeline/`` but the package is ``tyrelab`` (setuptools
``package-dir``). ``--doctest-modules`` would import ``pipeline/x.py`` as a
second copy named ``pipeline.x``, whose classes differ from ``tyrelab.x``'s
(``except tyrelab.rawformat.RunFileError`` would miss ``pipeline``'s). So,
before pytest imports a file under ``pipeline/``, the module is imported as
``tyrelab.…`` and registered under the name pytest will ask for: the doctests
run against the installed package's own modules.

A module's old import path that only aliases its new home (:func:`tyrelab._lazy.moved_to`) is not
collected: its doctests are the new module's, collected there.
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

SOURCE = Path(__file__).resolve().parent / "pipeline"


def pytest_collect_file(file_path: Path, parent):
    path = Path(file_path).resolve()
    if path.suffix != ".py" or SOURCE not in path.parents:
        return None
    parts = path.relative_to(SOURCE).with_suffix("").parts
    if parts[-1] == "__init__":
        parts = parts[:-1]
    for i in range(len(parts) + 1):
        alias = ".".join(("pipeline", *parts[:i]))
        if alias not in sys.modules:
            sys.modules[alias] = importlib.import_module(".".join(("tyrelab", *parts[:i])))
    return None


def pytest_ignore_collect(collection_path: Path, config):
    path = Path(collection_path).resolve()
    if path.suffix != ".py" or SOURCE not in path.parents or path.name == "__init__.py":
        return None
    import ast

    from tyrelab._lazy import moved_to

    parts = path.relative_to(SOURCE).with_suffix("").parts
    return True if moved_to(".".join(("tyrelab", *parts)), ast.parse(path.read_text(encoding="utf-8"))) else None
