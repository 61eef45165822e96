"""Doctests of the tyrelab source under its import name.

The source folder is ``pipeline/`` but the package is ``tyrelab`` (setuptools
``package-dir``). ``--doctest-modules`` would import ``pipeline/x.py`` as a
second copy named ``pipeline.x``, whose classes differ from ``tyrelab.x``'s
(``except tyrelab.rawformat.RunFileError`` would miss ``pipeline``'s). So,
before pytest imports a file under ``pipeline/``, the module is imported as
``tyrelab.…`` and registered under the name pytest will ask for: the doctests
run against the installed package's own modules.
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
