"""Make-style bookkeeping: what each stage consumed and produced, so unchanged stages are skipped.

What a stage reads and writes is declared once, in :data:`tyrelab.stages.dag.STAGES`. After a
stage ran, its *fingerprint* is stored in ``build/state/<stage>.json``:

- ``code``: :func:`stage_fingerprint`: SHA-256 of the stage module's source and of every
  ``tyrelab`` module it imports (followed transitively, read with :mod:`ast`, so nothing heavy is
  imported to decide), the ``schemas/`` files, the non-Python code it declares
  (``code:<package>``) and its declaration;
- ``inputs``: one digest per declared input (:func:`input_digests`): a build file by content, a
  build folder by the content of every file in it, ``raw`` by the path, size and mtime of every
  file below ``--raw`` (ingest then re-hashes the content of each changed file itself),
  ``raw-extras``/``published``/``scenarios`` by content, ``param:<name>`` by value;
- ``outputs``: one digest per declared output, computed the same way (:func:`output_digests`).

A stage is skipped when its code and input digests equal the recorded ones and every output it
declares still has the digest it had when the stage wrote it: a missing, truncated or overwritten
output — a single file below ``parquet/runs/`` or ``reports/runs/`` included — makes its writer
run again. Each output has one writer, so no stage checks another's files. The state file is
written only after the stage's outputs, so a stage interrupted while writing finds its state old
and reruns: a re-run after any interruption converges to the bytes of a clean build. A state file
that cannot be read, or holds anything but a JSON object (``null``, a list), is no state.
Content hashes are cached by (size, mtime) in the state, so a no-op run hashes nothing.
"""

from __future__ import annotations

import ast
import hashlib
import json
import os
import pickle
from pathlib import Path

from .. import io, resources
from ..buildlock import LOCK_NAME
from ..itemcache import ItemCache as _ItemCache
from ..itemcache import digest

__all__ = ["PACKAGE", "BUILTIN_RAW", "code_fingerprint", "stage_fingerprint", "HashCache",
    "stat_digest", "folder_digest", "raw_digest", "raw_extras", "state_path", "load", "input_digests",
    "output_digests", "why_stale", "record", "load_code_index", "save_code_index", "digest", "ItemCache"]

#: Folder of the ``tyrelab`` code, and the name modules are looked up under.
PACKAGE = "tyrelab"
#: Built-in raw files every stage may read (tyre catalogue, digitised thesis tables, ride scenarios).
BUILTIN_RAW = [resources.builtin_tyres(), resources.published_dir(), resources.scenarios_dir()]


def _sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _module_file(name: str) -> Path | None:
    """Source file of a ``tyrelab`` module, found without importing anything (None if not a module)."""
    top, *parts = name.split(".")
    if top != PACKAGE:
        return None
    base = resources.package_dir().joinpath(*parts)
    for path in (base.with_suffix(".py"), base / "__init__.py"):
        if path.is_file():
            return path
    return None


#: Per process: ``(path, size, mtime_ns, inode) -> (source bytes, their SHA-256)``.
_SOURCES: dict[tuple, tuple[bytes, str]] = {}
#: ``(module, SHA-256 of its source) -> (imported tyrelab modules, top-level literals)``: what
#: :func:`_parse` found in that exact source. Kept in ``build/state/code-index.pickle`` between
#: runs (:func:`load_code_index`), so a no-op run parses no Python file.
_PARSED: dict[tuple[str, str], tuple[frozenset, dict]] = {}
_PARSED_SAVED = 0  # entries of _PARSED when last loaded or saved
_PARSED_USED: set[tuple[str, str]] = set()  # entries this process looked up
_INDEX_LOADED: set[str] = set()  # build folders whose index this process has read
#: File name of the kept parse results in ``build/state``, and how many entries it may hold
#: before those this process did not use are dropped.
CODE_INDEX = "code-index.pickle"
CODE_INDEX_MAX = 2000


def _source(path: Path) -> tuple[bytes, str]:
    """The bytes of a source file and their SHA-256, read once per process while the file's
    size, mtime and inode stay the same (the digest is always of the bytes read)."""
    st = path.stat()
    key = (str(path), st.st_size, st.st_mtime_ns, st.st_ino)
    hit = _SOURCES.get(key)
    if hit is None:
        data = path.read_bytes()
        hit = _SOURCES[key] = (data, _sha(data))
    return hit


def _imports(path: Path, module: str) -> tuple[set[str], dict]:
    """``tyrelab`` modules imported by a module, and its literal top-level assignments.

    Parsed once per distinct source content (:data:`_PARSED`, keyed by the SHA-256 of the bytes,
    so an edited file is always parsed again)."""
    data, sha = _source(path)
    _PARSED_USED.add((module, sha))
    hit = _PARSED.get((module, sha))
    if hit is None:
        found, literals = _parse(data, path, module)
        hit = _PARSED[(module, sha)] = (frozenset(found), literals)
    return set(hit[0]), dict(hit[1])


def _parse(data: bytes, path: Path, module: str) -> tuple[set[str], dict]:
    """:func:`_imports` of a module's source ``data``, by :mod:`ast`."""
    tree = ast.parse(data.decode("utf-8"))
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found, literals = set(), {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                parts = parts[: len(parts) - node.level + 1]
                base = ".".join(parts + ([base] if base else []))
            if base.split(".")[0] == PACKAGE:
                subs = {f"{base}.{a.name}" for a in node.names}
                modules = {m for m in subs if _module_file(m) is not None}
                found.update(modules)
                # ``from pkg import submodule`` depends on the submodule, not on the package's
                # __init__ (which may re-export the whole library): a stage's fingerprint then
                # changes only with the code it really uses.
                if modules != subs or _module_file(base) is None or not _module_file(base).name == "__init__.py":
                    found.add(base)
        elif isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name.split(".")[0] == PACKAGE)
    for node in tree.body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            try:
                literals[node.targets[0].id] = ast.literal_eval(node.value)
            except ValueError:
                pass
    return found, literals


def load_code_index(build: Path) -> None:
    """Merge the parse results kept in ``build/state`` into this process's (:data:`_PARSED`).

    An unreadable or foreign index is ignored: its entries are only a cache of :mod:`ast`
    results keyed by the SHA-256 of the source they came from.
    """
    global _PARSED_SAVED
    if str(build) in _INDEX_LOADED:
        return
    _INDEX_LOADED.add(str(build))
    try:
        with open(Path(build) / "state" / CODE_INDEX, "rb") as fh:
            stored = pickle.load(fh)
    except (OSError, EOFError, pickle.UnpicklingError, AttributeError, ImportError, IndexError, ValueError):
        return
    if isinstance(stored, dict):
        for k, v in stored.items():
            _PARSED.setdefault(k, v)
    _PARSED_SAVED = len(_PARSED)


def save_code_index(build: Path) -> None:
    """Write :data:`_PARSED` to ``build/state`` if it grew since it was loaded or saved."""
    global _PARSED_SAVED
    if len(_PARSED) == _PARSED_SAVED or not (Path(build) / "state").is_dir():
        return
    live = _PARSED if len(_PARSED) <= CODE_INDEX_MAX else {k: _PARSED[k] for k in _PARSED_USED if k in _PARSED}
    with io.atomic_path(Path(build) / "state" / CODE_INDEX) as tmp:
        with open(tmp, "wb") as fh:
            pickle.dump(live, fh, protocol=pickle.HIGHEST_PROTOCOL)
    _PARSED_SAVED = len(_PARSED)


def code_fingerprint(stage_module: str, code_files=()) -> str:
    """Hash of the source of ``stage_module``, every ``tyrelab`` module it imports, ``schemas/``,
    and the files of the resource packages ``code_files`` (e.g. the report's templates)."""
    seen: dict[str, Path] = {}
    todo = [stage_module]
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        path = _module_file(name)
        if path is None:
            seen[name] = Path()
            continue
        seen[name] = path
        todo.extend(_imports(path, name)[0])
    h = hashlib.sha256()
    for name in sorted(seen):
        if seen[name].name:
            h.update(name.encode() + b"\0" + _source(seen[name])[0] + b"\0")
    schemas = resources.schemas_dir()
    for p in sorted(schemas.rglob("*.json")):
        h.update(str(p.relative_to(schemas)).encode() + b"\0" + p.read_bytes())
    for package in code_files:
        root = resources.resource_dir(package)
        for p in sorted(q for q in root.rglob("*") if q.is_file() and q.suffix != ".pyc"):
            h.update(f"{package}/{p.relative_to(root)}".encode() + b"\0" + p.read_bytes())
    return h.hexdigest()


def stage_fingerprint(stage) -> str:
    """Code fingerprint of a :class:`~tyrelab.stages.dag.Stage`: its module and the modules it imports
    (:func:`code_fingerprint`), its ``code:`` packages and its declaration (a stage that now reads or
    writes something else runs again)."""
    code = code_fingerprint(stage.module, stage.code_files)
    return _sha(f"{code}\0{stage!r}".encode())


#: Per process: ``(path, size, mtime_ns, inode) -> SHA-256``, shared by every stage's
#: :class:`HashCache` (the run files ingest wrote are read once, not once per stage reading them).
_CONTENT: dict[tuple, str] = {}


class HashCache:
    """Content hashes of files, re-computed only when a file's size or mtime changed."""

    def __init__(self, entries: dict | None = None):
        self.entries: dict[str, list] = dict(entries or {})
        self.used: dict[str, list] = {}

    def digest(self, path: Path) -> str:
        """SHA-256 of ``path`` (``"missing"`` if it does not exist)."""
        key = str(path)
        try:
            st = path.stat()
        except FileNotFoundError:
            return "missing"
        hit = self.entries.get(key)
        if isinstance(hit, list) and len(hit) == 3 and hit[0] == st.st_size and hit[1] == st.st_mtime_ns:
            sha = hit[2]
        else:
            memo = (key, st.st_size, st.st_mtime_ns, st.st_ino)
            sha = _CONTENT.get(memo)
            if sha is None:
                sha = _CONTENT[memo] = io.file_sha256(path)
        self.used[key] = [st.st_size, st.st_mtime_ns, sha]
        return sha


def stat_digest(paths) -> str:
    """Hash of the (path, size, mtime) of files: changes when any is added, removed or touched."""
    h = hashlib.sha256()
    for p in sorted(paths):
        try:
            st = os.stat(p)
        except FileNotFoundError:
            continue
        h.update(f"{p}\0{st.st_size}\0{st.st_mtime_ns}\n".encode())
    return h.hexdigest()


def _files_below(folder: Path, exclude: Path | None = None):
    """Regular files below ``folder``, skipping hidden folders and ``exclude`` (a build folder inside raw).

    Named pipes and devices are skipped with a warning (:func:`tyrelab.io.regular_files`):
    hashing a FIFO would block the run for ever."""
    yield from io.regular_files(folder, exclude)


def raw_digest(raw: Path, exclude: Path | None = None) -> str:
    """Stat digest of every file below ``raw`` (but ``exclude``) and of the built-in raw files."""
    files = [p for src in [raw, *BUILTIN_RAW] for p in (_files_below(src, exclude) if src.is_dir() else [src])]
    return stat_digest(str(p) for p in files)


def raw_extras(raw: Path, exclude: Path | None = None) -> list[Path]:
    """Raw files outside campaign folders (``published/``, ``tyres.csv``, ...), plus the built-in ones.

    A campaign folder is one holding ``manifest.csv``: it is not entered (one walk, no second
    search for manifests)."""
    out = []
    for src in [Path(raw), *BUILTIN_RAW]:
        if src.is_dir():
            out.extend(io.regular_files(src, exclude, skip_folders_with="manifest.csv"))
        elif src.exists():
            out.append(src)
    return sorted(set(out))


def published_digests(raw: Path, cache: HashCache) -> dict[str, str]:
    """Content digest of each published table a stage reads (``<raw>/published`` or the shipped copy)."""
    from .. import published  # light: the resolver only (no pandas work at import)

    folder = published.published_dir(raw)
    return {f"published:{p}": cache.digest(p) for p in sorted(folder.glob("*.csv"))}


def _folder_files(folder: Path) -> list[Path]:
    """Regular files below a build folder, but temporaries of a writer (``*.tmp``) and the build lock."""
    if not folder.is_dir():
        return []
    return sorted(p for p in io.regular_files(folder) if not p.name.endswith(".tmp") and p.name != LOCK_NAME)


def folder_digest(folder: Path, cache: HashCache) -> str:
    """Digest of the relative path and content of every file below ``folder`` (``"missing"`` if it
    is not a folder): changes when any file is added, removed, truncated or rewritten."""
    if not folder.is_dir():
        return "missing"
    h = hashlib.sha256()
    for p in _folder_files(folder):
        h.update(f"{p.relative_to(folder)}\0{cache.digest(p)}\n".encode())
    return h.hexdigest()


def _path_digest(build: Path, rel: str, cache: HashCache) -> str:
    """Digest of a build file or (``rel`` ending in ``/``) folder."""
    return folder_digest(build / rel, cache) if rel.endswith("/") else cache.digest(build / rel)


def state_path(build: Path, stage: str) -> Path:
    """``build/state/<stage>.json``."""
    return build / "state" / f"{stage}.json"


def load(build: Path, stage: str) -> dict:
    """The recorded fingerprint of ``stage``; empty if none, unreadable or not a JSON object
    (``null``, a list, garbage: damaged state is no state)."""
    try:
        state = json.loads(state_path(build, stage).read_text())
    except (OSError, ValueError):
        return {}
    if not isinstance(state, dict):
        return {}
    for key in ("inputs", "outputs", "counts", "hash_cache"):
        if not isinstance(state.get(key, {}), dict):
            return {}
    return state


def input_digests(ctx, stage, cache: HashCache) -> dict[str, str]:
    """Digest of each input the :class:`~tyrelab.stages.dag.Stage` ``stage`` declares (module docstring)."""
    from .dag import expand

    digests: dict[str, str] = {f"param:{p}": repr(getattr(ctx, p)) for p in stage.params}
    for name in stage.reads:
        if name == "raw":
            digests["raw"] = raw_digest(ctx.raw, exclude=ctx.build)
        elif name == "raw-extras":
            for p in raw_extras(ctx.raw, exclude=ctx.build):
                digests[f"raw:{p}"] = cache.digest(p)
        elif name == "published":
            digests.update(published_digests(ctx.raw, cache))
        elif name == "scenarios":
            for folder in (resources.scenarios_dir(), Path(ctx.raw) / "scenarios"):
                for p in sorted(folder.glob("*.toml")) if folder.is_dir() else []:
                    digests[f"scenario:{p}"] = cache.digest(p)
    for rel in expand(stage):
        digests[rel] = _path_digest(ctx.build, rel, cache)
    return digests


def output_digests(ctx, stage, cache: HashCache) -> dict[str, str]:
    """Digest of each output ``stage`` declares (``"missing"`` for one that does not exist)."""
    return {rel: _path_digest(ctx.build, rel, cache) for rel in stage.writes}


def _label(key: str) -> str:
    """Short name of an input for a log line: a table's name, a folder's path, a raw file's name."""
    if key.startswith("parquet/") and key.endswith(".parquet"):
        return key[len("parquet/"):-len(".parquet")]
    if key.endswith("/"):
        return key
    return Path(key).name if key.startswith("raw:") or "/" in key else key


def why_stale(ctx, stage, code: str, inputs: dict[str, str], cache: HashCache | None = None) -> str | None:
    """Why ``stage`` (a :class:`~tyrelab.stages.dag.Stage`) must run (one phrase), or None if it is up to date.

    ``cache`` hashes the outputs (by size and mtime).
    """
    if ctx.force:
        return "--force"
    prev = load(ctx.build, stage.name)
    if not prev:
        return "no previous run recorded"
    if prev.get("code") != code:
        return "code changed"
    old = prev.get("inputs", {})
    changed = sorted(k for k in inputs.keys() | old.keys() if inputs.get(k) != old.get(k))
    if changed:
        names = [_label(k) for k in changed]
        more = f" and {len(names) - 3} more" if len(names) > 3 else ""
        return "input(s) changed: " + ", ".join(names[:3]) + more
    # Outputs must still be the bytes this stage wrote: one deleted, truncated or overwritten
    # (a run file below parquet/runs/ included) makes it rerun, and it alone writes them.
    recorded = prev.get("outputs", {})
    now = output_digests(ctx, stage, cache or HashCache())
    missing = [rel for rel in stage.writes if now[rel] == "missing" != recorded.get(rel)]
    if missing:
        return "output(s) missing: " + ", ".join(missing[:3])
    changed = [rel for rel in stage.writes if now[rel] != recorded.get(rel)]
    if changed:
        return "output(s) changed since this stage wrote them: " + ", ".join(changed[:3])
    return None


def record(ctx, stage, code: str, inputs: dict[str, str], cache: HashCache, counts: dict | None = None) -> None:
    """Write the state of ``stage`` after it ran: its code, inputs and the digests of its outputs.

    ``counts`` (runs in, ok, quarantined) are kept so that a skipped stage
    still reports them, and the exit code still says runs are quarantined.
    """
    outputs = output_digests(ctx, stage, cache)
    state = {"stage": stage.name, "code": code, "inputs": inputs, "outputs": outputs,
             "counts": counts or {}, "hash_cache": cache.used}
    io.write_text_atomic(json.dumps(state, indent=1, sort_keys=True), state_path(ctx.build, stage.name))


# ------------------------------------------------------------------ per-item work inside a stage


class ItemCache(_ItemCache):
    """:class:`tyrelab.itemcache.ItemCache` of a stage, whose code fingerprint is by default the
    stage's (:func:`stage_fingerprint`: its module, the modules it imports, its declaration).

    Parameters
    ----------
    ctx : Context
        The run (``build``, ``force``).
    stage : str
        Stage name (folder of the entries, ``build/cache/<stage>``).
    code : str, optional
        Code fingerprint; default :func:`stage_fingerprint` of the stage.
    """

    def __init__(self, ctx, stage: str, code: str | None = None):
        if code is None:
            from .dag import STAGES

            code = stage_fingerprint(STAGES[stage]) if stage in STAGES else code_fingerprint(f"{PACKAGE}.stages.{stage}")
        super().__init__(ctx, stage, code)
