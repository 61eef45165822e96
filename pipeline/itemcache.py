"""Content digests of values and a cache of per-item results keyed by them.

The low-level home of :func:`digest` and :class:`ItemCache`: the stages keep their items here
(:class:`tyrelab.stages.state.ItemCache` adds the stage's code fingerprint) and the report
keys its shaped tables and figures with :func:`digest`, so neither imports the other.
Imports nothing heavy at import time (numpy and pandas where a digest needs them).
"""

from __future__ import annotations

import hashlib
import pickle
from pathlib import Path

from . import io

__all__ = ["digest", "ItemCache"]


def digest(obj) -> str:
    """SHA-256 of a value's content: DataFrames, Series, arrays, mappings, sequences, scalars.

    Two values with the same digest give the same result in every computation
    of the pipeline (floats are hashed exactly, column names and dtypes count).

    Examples
    --------
    >>> digest({"a": 1.0, "b": [1, 2]}) == digest({"b": [1, 2], "a": 1.0})
    True
    >>> digest(0.1) == digest(0.2), digest(1) == digest(1.0)
    (False, False)
    """
    h = hashlib.sha256()
    _feed(h, obj)
    return h.hexdigest()


def _feed(h, obj) -> None:
    import numpy as np
    import pandas as pd

    if isinstance(obj, pd.DataFrame):
        h.update(b"D" + repr([(str(c), str(t)) for c, t in obj.dtypes.items()]).encode())
        h.update(pd.util.hash_pandas_object(obj, index=False).to_numpy().tobytes() if len(obj.columns) else b"")
        h.update(repr(len(obj)).encode())
    elif isinstance(obj, pd.Series):
        h.update(b"S" + f"{obj.name}|{obj.dtype}".encode())
        h.update(pd.util.hash_pandas_object(obj, index=False).to_numpy().tobytes())
    elif isinstance(obj, np.ndarray):
        h.update(b"A" + f"{obj.dtype}|{obj.shape}".encode() + np.ascontiguousarray(obj).tobytes())
    elif isinstance(obj, dict):
        h.update(b"{")
        for k in sorted(obj, key=repr):
            h.update(repr(k).encode() + b":")
            _feed(h, obj[k])
        h.update(b"}")
    elif isinstance(obj, (list, tuple)):
        h.update(b"[" if isinstance(obj, list) else b"(")
        for v in obj:
            _feed(h, v)
            h.update(b",")
        h.update(b"]")
    else:
        if isinstance(obj, np.generic):
            obj = obj.item()
        h.update(f"{type(obj).__name__}:{obj!r};".encode())


class ItemCache:
    """Results of the items of one stage (a tyre's fits, a simulated case, a figure), by input digest.

    A stage that recomputes only what changed asks for each item with the
    digest of everything the item depends on (:func:`digest` of its inputs) and
    the stage's code fingerprint; a hit returns the stored result, a miss
    computes and stores it. The dependency is recorded, not guessed: an item is
    reused only when its own inputs and the code are unchanged, so the stage's
    outputs equal a clean rebuild's. Entries live in ``build/cache/<stage>/``
    (pickles written atomically; not stage outputs), ``--force`` ignores them,
    and :meth:`prune` drops those the last run did not use.

    Parameters
    ----------
    ctx : Context
        The run (``build``, ``force``).
    stage : str
        Stage name (folder of the entries).
    code : str
        Code fingerprint of what computes the items (a stage's:
        :func:`tyrelab.stages.state.stage_fingerprint`; :class:`tyrelab.stages.state.ItemCache`
        fills it in).
    """

    def __init__(self, ctx, stage: str, code: str):
        self.folder = Path(ctx.build) / "cache" / stage
        self.code = code
        self.force = bool(getattr(ctx, "force", False))
        self.used: set[str] = set()
        self.hits = 0
        self.misses = 0
        self.counts: dict[str, list[int]] = {}  # kind -> [reused, computed]
        self._files: dict | None = None  # path -> [size, mtime_ns, inode, sha256] (file_digest), loaded when asked
        self._files_used: dict = {}

    #: File of :meth:`file_digest`'s record in the cache folder.
    FILES = "file-digests.json"

    def file_digest(self, path) -> str:
        """SHA-256 of a file's content, read again only when its size, mtime or inode changed since
        the stage last hashed it (a record kept beside the entries, as the stage state keeps its
        inputs' hashes; ``--force`` reads every file): a stage that looks up many input files by
        content (the rides stage's recordings) does not re-read the unchanged ones.

        Raises
        ------
        OSError
            If the file cannot be read.
        """
        import json
        import os

        key = str(path)
        st = os.stat(key)
        if self._files is None:
            self._files = {}
            if not self.force:
                try:
                    found = json.loads((self.folder / self.FILES).read_text())
                    self._files = found if isinstance(found, dict) else {}
                except (OSError, ValueError):
                    pass
        now = [st.st_size, st.st_mtime_ns, st.st_ino]
        hit = self._files.get(key)
        if isinstance(hit, list) and len(hit) == 4 and hit[:3] == now and isinstance(hit[3], str):
            sha = hit[3]
        else:
            sha = io.file_sha256(key)
        self._files_used[key] = [*now, sha]
        return sha

    def key(self, kind: str, *inputs) -> str:
        """Key of one item: its kind, the code fingerprint and the digest of its inputs."""
        return f"{kind}-{digest([self.code, kind, *inputs])[:40]}"

    def has(self, key: str) -> bool:
        """Whether item ``key`` is stored and may be reused (never with ``--force``), without loading it."""
        return not self.force and self._path(key).is_file()

    def _path(self, key: str) -> Path:
        return self.folder / f"{key}.pkl"

    def get(self, key: str):
        """``(True, value)`` for a stored item, else ``(False, None)``."""
        self.used.add(key)
        hit, value = self.load(key)
        if hit:
            self.reused(key)
        return hit, value

    def load(self, key: str):
        """:meth:`get` without counting the item as used or reused (for a task whose results
        :meth:`reused` or :meth:`put` account for later)."""
        if not self.has(key):
            return False, None
        try:
            with open(self._path(key), "rb") as fh:
                return True, pickle.load(fh)
        except (OSError, EOFError, pickle.UnpicklingError, AttributeError, ImportError, IndexError, ValueError):
            return False, None  # unreadable entry: recompute

    def reused(self, key: str) -> None:
        """Count item ``key`` as used and reused by this run (loaded here or by a worker)."""
        self.used.add(key)
        self.hits += 1
        self.counts.setdefault(key.rsplit("-", 1)[0], [0, 0])[0] += 1

    def put(self, key: str, value) -> None:
        """Store an item (atomically)."""
        self.used.add(key)
        self.misses += 1
        self.counts.setdefault(key.rsplit("-", 1)[0], [0, 0])[1] += 1
        with io.atomic_path(self._path(key)) as tmp:
            with open(tmp, "wb") as fh:
                pickle.dump(value, fh, protocol=pickle.HIGHEST_PROTOCOL)

    def get_or_compute(self, key: str, compute):
        """The stored item ``key``, or ``compute()`` stored under it."""
        hit, value = self.get(key)
        if not hit:
            value = compute()
            self.put(key, value)
        return value

    def keep(self, keys) -> None:
        """Count the entries ``keys`` as used by this run without loading them (:meth:`prune` keeps them)."""
        self.used.update(keys)

    def prune(self) -> int:
        """Delete the entries this run did not use (and the file digests it did not ask for); return how many."""
        import json

        if self._files_used or (self.folder / self.FILES).is_file():
            self.folder.mkdir(parents=True, exist_ok=True)
            io.write_text_atomic(json.dumps(self._files_used, sort_keys=True), self.folder / self.FILES)
        n = 0
        for p in self.folder.glob("*.pkl") if self.folder.is_dir() else []:
            if p.stem not in self.used:
                p.unlink(missing_ok=True)
                n += 1
        return n

    def summary(self, kind: str | None = None, exclude: tuple = ()) -> str:
        """``"12 reused, 3 computed"`` (of the items of ``kind`` only, if given; else of all kinds
        but those in ``exclude``)."""
        if kind:
            hits, misses = self.counts.get(kind, [0, 0])
        else:
            hits = self.hits - sum(self.counts.get(k, [0, 0])[0] for k in exclude)
            misses = self.misses - sum(self.counts.get(k, [0, 0])[1] for k in exclude)
        return f"{hits} reused, {misses} computed"
