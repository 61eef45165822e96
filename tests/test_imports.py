"""No import cycles, and no upward arrows between layers: every import of ``tyrelab``, read with :mod:`ast`.

Every ``import``/``from ... import`` of a ``tyrelab`` module counts, at module level or inside a
function (a function-level import is still a dependency, only a later one). An import of a name
from a package whose ``__init__`` re-exports its submodules lazily (:mod:`tyrelab._lazy`) counts
as an import of the submodule that defines it, and importing ``a.b.c`` from outside ``a.b`` runs
``a.b``'s ``__init__`` too.

Checked:

- no cycle between modules (:data:`ALLOWED_MODULE_CYCLES` lists the ones still being removed);
- no cycle between layers (``tyrelab.<layer>``: a subpackage or a top-level module);
- the pure packages (:data:`PURE`) never import :data:`UPPER` (:data:`ALLOWED_UPWARD` lists the
  arrows still being removed).

The allowlists cannot go stale: an allowed cycle or arrow that no longer exists fails the test
too, so whoever removes one removes its entry (and a cycle that shrinks is a new cycle to list,
or better, to remove).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from tyrelab import resources

#: Packages of pure computation: they take data and return data.
PURE = ("tyrelab.rawformat", "tyrelab.measurement", "tyrelab.tyre", "tyrelab.vehicle", "tyrelab.rig")
#: What a pure package must never import.
UPPER = ("tyrelab.stages", "tyrelab.report", "tyrelab.cli", "tyrelab.warehouse", "tyrelab.executor")

#: Module cycles that exist today and are being removed: each entry is the exact set of modules
#: of one cycle (a strongly connected component of the import graph) and who removes it.
#: Remove an entry when its cycle is gone; the test fails while a listed cycle is missing.
ALLOWED_MODULE_CYCLES: dict[frozenset, str] = {}  # none left (issue 23 removed vehicle.scenario <-> scenario_limits)
#: Upward arrows (importer, imported module) from a pure package that exist and are being removed,
#: and who removes them (none left: issue 23 moved the scenario tasks out of vehicle/ride.py).
ALLOWED_UPWARD: dict[tuple[str, str], str] = {}


def _modules() -> dict[str, Path]:
    root = resources.package_dir()
    out = {}
    for p in sorted(root.rglob("*.py")):
        parts = ("tyrelab", *p.relative_to(root).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = p
    return out


def _literal_all(path: Path) -> list[str]:
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "__all__" for t in node.targets):
            try:
                return list(ast.literal_eval(node.value))
            except ValueError:
                return []
    return []


def _lazy_exports(modules: dict[str, Path]) -> dict[str, dict[str, str]]:
    """package -> {name: submodule defining it} for packages re-exporting lazily (``_lazy.attach``)."""
    out = {}
    for name, path in modules.items():
        if path.name == "__init__.py" and "attach(__name__" in path.read_text(encoding="utf-8"):
            subs = {m: p for m, p in modules.items() if m.rpartition(".")[0] == name}
            out[name] = {n: m for m, p in sorted(subs.items()) for n in _literal_all(p)}
    return out


def import_graph() -> dict[str, set[str]]:
    """module -> the ``tyrelab`` modules it imports (module docstring)."""
    modules = _modules()
    lazy = _lazy_exports(modules)
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        found: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    parts = package.split(".")
                    base = ".".join(parts[: len(parts) - node.level + 1] + ([base] if base else []))
                if base.split(".")[0] != "tyrelab":
                    continue
                for alias in node.names:
                    sub = f"{base}.{alias.name}"
                    if sub in modules:
                        found.add(sub)
                    elif alias.name in lazy.get(base, {}):
                        found.add(lazy[base][alias.name])
                    else:
                        found.add(base)
            elif isinstance(node, ast.Import):
                found.update(a.name for a in node.names if a.name.split(".")[0] == "tyrelab")
        # importing a.b.c from outside a.b runs the __init__ of a.b first
        for target in list(found):
            parts = target.split(".")
            for i in range(2, len(parts)):
                parent = ".".join(parts[:i])
                if parent in modules and not name.startswith(parent + ".") and name != parent:
                    found.add(parent)
        graph[name] = {m for m in found if m in modules and m != name}
    return graph


def cycles(graph: dict[str, set[str]]) -> set[frozenset]:
    """The strongly connected components of more than one node (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: set[frozenset] = set()
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on.add(root)
        while work:
            v, children = work[-1]
            w = next(children, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(graph.get(w, ())))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = set()
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.add(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.add(frozenset(comp))
    return out


def layer(module: str) -> str:
    return ".".join(module.split(".")[:2])


def layer_graph(graph: dict[str, set[str]]) -> dict[str, set[str]]:
    out: dict[str, set[str]] = {}
    for m, targets in graph.items():
        out.setdefault(layer(m), set()).update(layer(t) for t in targets if layer(t) != layer(m))
    return out


@pytest.fixture(scope="module")
def graph():
    return import_graph()


def test_the_graph_sees_function_level_and_lazy_imports(graph):
    # a function-level import (ingest stage -> io) and an import through a lazy package
    assert "tyrelab.io" in graph["tyrelab.stages.ingest"]
    assert "tyrelab.itemcache" in graph["tyrelab.report.site"]
    assert "tyrelab.rig.experiments" in graph["tyrelab.stages.methods"]


def test_no_module_cycle_but_the_listed_ones(graph):
    found = cycles(graph)
    new = [sorted(c) for c in found if c not in ALLOWED_MODULE_CYCLES]
    assert not new, f"import cycle(s): {new}"
    gone = [f"{sorted(c)} ({who})" for c, who in ALLOWED_MODULE_CYCLES.items() if c not in found]
    assert not gone, f"listed cycle(s) no longer exist, remove them from ALLOWED_MODULE_CYCLES: {gone}"


def test_no_layer_cycle(graph):
    assert not [sorted(c) for c in cycles(layer_graph(graph))]


def test_pure_packages_never_import_upward(graph):
    arrows = {(m, t) for m, targets in graph.items() if layer(m) in PURE for t in targets
              if any(t == u or t.startswith(u + ".") for u in UPPER)}
    new = sorted(arrows - set(ALLOWED_UPWARD))
    assert not new, f"pure package(s) importing upward: {new}"
    gone = sorted(set(ALLOWED_UPWARD) - arrows)
    assert not gone, f"listed upward import(s) no longer exist, remove them from ALLOWED_UPWARD: {gone}"


def test_the_checks_can_fail():
    g = {"a.x": {"a.y"}, "a.y": {"a.z"}, "a.z": {"a.x"}, "b.q": {"a.x"}}
    assert cycles(g) == {frozenset({"a.x", "a.y", "a.z"})}
    assert cycles(layer_graph({"t.a.x": {"t.b.y"}, "t.b.y": {"t.a.z"}, "t.a.z": set()})) == {
        frozenset({"t.a", "t.b"})}


# --------------------------------------------------------------------------- the layers contract
def _lint_imports(*args: str):
    import shutil
    import subprocess
    import sys
    from pathlib import Path as _Path

    exe = _Path(sys.executable).with_name("lint-imports")
    exe = str(exe) if exe.exists() else shutil.which("lint-imports")
    assert exe, "lint-imports (PyPI import-linter, the dev extra) is not installed"
    root = _Path(__file__).resolve().parents[1]
    return subprocess.run([exe, "--no-cache", *args], cwd=root, capture_output=True, text=True, timeout=300)


def test_the_layers_contracts_are_kept():
    """pyproject.toml's [tool.importlinter] contracts (issue 45): tyrelab's layers, in
    tyrelab.vehicle the thesis' studies above the engine, and the order inside vehicle's model/,
    studies/ and solvers/ (``make test`` runs it too)."""
    run = _lint_imports()
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-2000:]
    assert "BROKEN" not in run.stdout and "Contracts: 5 kept" in run.stdout, run.stdout[-2000:]
    assert "ignored" not in run.stdout  # no climb left unchecked (issue 45)


def test_the_layers_contract_can_fail(tmp_path):
    # the engine's model imports the units: the reverse order is a broken contract
    config = tmp_path / "importlinter.ini"
    config.write_text("[importlinter]\nroot_package = tyrelab\n\n[importlinter:contract:reversed]\n"
                      "name = reversed\ntype = layers\nlayers =\n    tyrelab.vehicle.units\n    tyrelab.vehicle.model\n")
    run = _lint_imports("--config", str(config))
    assert run.returncode != 0 and "BROKEN" in run.stdout, run.stdout[-2000:]
