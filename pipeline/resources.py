"""Where the data tyrelab ships lives, found through :mod:`importlib.resources`.

The repository keeps the layout the project is known by — the schemas in
``schemas/``, the report templates in ``reports/``, the thesis tables, the
tyre catalogue and the example scenarios in ``raw/`` — and ``pyproject.toml``
maps each folder to a package of the installed distribution:

==========================  =================  ===========================================
package                     repository folder  contents
==========================  =================  ===========================================
``tyrelab.schemas``         ``schemas/``       Table Schemas (raw format, catalogue, thesis)
``tyrelab.templates``       ``reports/``       jinja2 templates of the report
``tyrelab.data``            ``raw/``           ``tyres.csv``, ``published/*.csv``, ``scenarios/``
``tyrelab.docs``            ``docs/``          the documents (``*.md``) the report links to
==========================  =================  ===========================================

The same code therefore reads the same files from an editable checkout and
from an installed wheel. Only files on a file system are supported (tyrelab is
not zip-safe): each function returns a :class:`pathlib.Path`.

Examples
--------
>>> (schemas_dir() / "raw_manifest.json").is_file()
True
>>> sorted(p.name for p in published_dir().glob("table_i*.csv"))[:3]
['table_i.csv', 'table_ii.csv', 'table_iii.csv']
"""

from __future__ import annotations

from functools import cache
from importlib.resources import files
from pathlib import Path

__all__ = ["resource_dir", "package_dir", "schemas_dir", "templates_dir", "data_dir", "docs_dir", "published_dir",
           "builtin_tyres", "scenarios_dir"]


def resource_dir(package: str) -> Path:
    """Folder of an installed tyrelab package (code or data), e.g. ``"tyrelab.templates"``."""
    root = files(package)
    if not isinstance(root, Path):  # pragma: no cover - zip imports are not supported
        raise RuntimeError(f"{package} is not installed on a file system ({root!r}); reinstall tyrelab unzipped")
    return root


@cache
def package_dir() -> Path:
    """Folder of the ``tyrelab`` code (``pipeline/`` in the repository)."""
    return resource_dir("tyrelab")


@cache
def schemas_dir() -> Path:
    """Folder of the shipped Table Schemas (``schemas/``)."""
    return resource_dir("tyrelab.schemas")


@cache
def templates_dir() -> Path:
    """Folder of the report's jinja2 templates (``reports/``)."""
    return resource_dir("tyrelab.templates")


@cache
def data_dir() -> Path:
    """Folder of the shipped data (``raw/``: catalogue, thesis tables, scenarios)."""
    return resource_dir("tyrelab.data")


@cache
def docs_dir() -> Path:
    """Folder of the project's documents (``docs/``: the ``*.md`` the report renders and links to)."""
    return resource_dir("tyrelab.docs")


def published_dir() -> Path:
    """The digitised thesis tables shipped with tyrelab (``raw/published``)."""
    return data_dir() / "published"


def builtin_tyres() -> Path:
    """The built-in tyre catalogue, thesis Table II (``raw/tyres.csv``)."""
    return data_dir() / "tyres.csv"


def scenarios_dir() -> Path:
    """The example ride scenarios shipped with tyrelab (``raw/scenarios``)."""
    return data_dir() / "scenarios"
