"""Lazy re-exports for tyrelab's packages (PEP 562), as scipy and lazy_loader do.

``import tyrelab`` or ``import tyrelab.measurement`` must stay cheap: the
command line imports only what a command needs (a no-op ``tyrelab run``
imports neither scipy nor matplotlib). A package therefore names its public
submodules, and each submodule's public names are those of its ``__all__``,
read from the source without importing it; the submodule is imported on
first access of one of its names.

Examples
--------
>>> import tyrelab.measurement as m
>>> "analyse_frame" in m.__all__ and "recording" in m.__all__
True
>>> m.tyre_force is m.apparent_mass.tyre_force
True
"""

from __future__ import annotations

import ast
import importlib
import pkgutil
import sys
from importlib.util import find_spec
from pathlib import Path

__all__ = ["attach", "module_all", "moved_to", "submodule_names", "collisions"]


def module_all(module: str) -> list[str]:
    """The literal ``__all__`` of a module's source (``[]`` if it has none), without importing it.

    A module moved elsewhere whose old file only aliases the new one (:func:`moved_to`) has the
    new module's ``__all__``.
    """
    spec = find_spec(module)
    if spec is None or spec.origin is None:
        raise ModuleNotFoundError(f"no module named {module!r}")
    origin = Path(spec.origin)
    tree = ast.parse(origin.read_text(encoding="utf-8"), str(origin))
    for node in tree.body:
        targets = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(node, ast.AnnAssign) else []
        if any(isinstance(t, ast.Name) and t.id == "__all__" for t in targets) and node.value is not None:
            return list(ast.literal_eval(node.value))
    target = moved_to(module, tree)
    return module_all(target) if target else []


def moved_to(module: str, tree: ast.Module | None = None) -> str | None:
    """The module an old import path aliases, or None.

    A module moved to a new home keeps its old path as a file that imports the new module and
    puts it in its own place (``from .terrain import profiles as _moved`` then
    ``sys.modules[__name__] = _moved``): ``import`` of the old path gives the same module object.

    Examples
    --------
    >>> moved_to("tyrelab._lazy") is None
    True
    """
    if tree is None:
        known = sys.modules.get(module)
        if known is not None:  # imported: an alias is the module of another name
            return known.__name__ if known.__name__ != module else None
        spec = find_spec(module)
        if spec is None or spec.origin is None:
            raise ModuleNotFoundError(f"no module named {module!r}")
        tree = ast.parse(Path(spec.origin).read_text(encoding="utf-8"), spec.origin)
    imported: dict[str, str] = {}
    package = module.rpartition(".")[0]
    for node in tree.body:
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[: len(parts) - node.level + 1] + ([base] if base else []))
            for alias in node.names:
                imported[alias.asname or alias.name] = f"{base}.{alias.name}"
        elif (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.value, ast.Name)
              and ast.unparse(node.targets[0]) == "sys.modules[__name__]" and node.value.id in imported):
            return imported[node.value.id]
    return None


def submodule_names(package: str) -> list[str]:
    """Public submodules of a package (names not starting with ``_``), sorted."""
    spec = find_spec(package)
    return sorted(m.name for m in pkgutil.iter_modules(spec.submodule_search_locations) if not m.name.startswith("_"))


def collisions(package: str) -> dict[str, list[str]]:
    """Names exported by more than one submodule of ``package`` -> those submodules."""
    seen: dict[str, list[str]] = {}
    for sub in submodule_names(package):
        for name in module_all(f"{package}.{sub}"):
            seen.setdefault(name, []).append(sub)
    return {k: v for k, v in seen.items() if len(v) > 1}


def attach(package: str, submodules: list[str] | None = None, attrs: dict[str, list[str]] | None = None,
           reexport: bool = True):
    """``__getattr__`` and ``__dir__`` for a package re-exporting its submodules (PEP 562).

    The package's ``__all__`` is answered by ``__getattr__`` too: the submodules' sources
    are read (their literal ``__all__``, :func:`module_all`) on the first name asked that
    is not a submodule, not when the package is imported (26 files parsed, ~0.05 s, in
    every process that imported a subpackage for one of its modules).

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    submodules : list of str, optional
        Submodules, attributes of the package (default: every public
        submodule found); with ``reexport`` their whole ``__all__`` is
        re-exported too. A name two submodules export is not re-exported
        (:func:`collisions` lists them; import it from its submodule), and a
        name that is also a submodule's name (``tyre.size_regressions``) stays
        the submodule.
    attrs : dict, optional
        Further (dotted) submodule -> names to re-export (a curated subset).
    reexport : bool
        Re-export every name of each submodule's ``__all__``.

    Returns
    -------
    (__getattr__, __dir__)
        Assign them to the package's ``__getattr__`` and ``__dir__``.
    """
    found: dict = {}

    def names() -> tuple[list[str], dict[str, str], list[str]]:
        """(submodules, name -> submodule, ``__all__``), read from the sources on first use: a
        command that imports the package for one submodule never parses the others."""
        if not found:
            subs = submodule_names(package) if submodules is None else list(submodules)
            where: dict[str, str] = {}
            ambiguous: set[str] = set()
            for sub in subs if reexport else ():
                for name in module_all(f"{package}.{sub}"):
                    if name in subs:  # the submodule itself wins (the import system sets it)
                        continue
                    if name in where and where[name] != sub:
                        ambiguous.add(name)
                    where.setdefault(name, sub)
            for name in ambiguous:  # which one would be a guess: import it from its submodule
                del where[name]
            for sub, attr_names in (attrs or {}).items():
                for name in attr_names:
                    where[name] = sub
            found.update(subs=subs, where=where, all=sorted(set(subs) | set(where)))
        return found["subs"], found["where"], found["all"]

    def __getattr__(name: str):
        if name == "__all__":
            return list(names()[2])
        subs, where, _ = names()
        if name in subs:
            return importlib.import_module(f"{package}.{name}")
        if name in where:
            return getattr(importlib.import_module(f"{package}.{where[name]}"), name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__():
        return list(names()[2])

    return __getattr__, __dir__
