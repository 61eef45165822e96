"""The thesis' tables, digitised by hand into ``raw/published/*.csv``.

One resolver for every stage: the tables come from ``<raw>/published`` when
the raw folder has one (a lab may ship corrected transcriptions with its
data), otherwise from the copy shipped with tyrelab. Each CSV is read with
blanks as missing values only ("None", "NA" are text in these tables) and
checked against ``schemas/published/<stem>.json``.
"""

from __future__ import annotations

import hashlib
import logging
from pathlib import Path
from typing import TYPE_CHECKING

from . import resources

if TYPE_CHECKING:  # imported where used: resolving the folder needs no pandas
    import pandas as pd

__all__ = ["SHIPPED_DIR", "PublishedTableError", "published_dir", "stems", "read_published", "thesis_stiffness_model"]

#: Digitised thesis tables shipped with tyrelab.
SHIPPED_DIR = resources.published_dir()

log = logging.getLogger("tyrelab")


class PublishedTableError(ValueError):
    """A published table is missing or does not match its schema."""


def published_dir(raw: Path | None = None) -> Path:
    """``<raw>/published`` if it exists, else the tables shipped with tyrelab."""
    if raw is not None and (Path(raw) / "published").is_dir():
        return Path(raw) / "published"
    return SHIPPED_DIR


def stems(raw: Path | None = None) -> list[str]:
    """Names of the available published tables, e.g. ``["table_i", ..., "table_xx"]``."""
    return sorted(p.stem for p in published_dir(raw).glob("*.csv") if p.is_file())  # not a FIFO: it would block


def read_published(stem: str, raw: Path | None = None, strict: bool = True) -> pd.DataFrame:
    """Read published table ``stem`` (e.g. ``"table_iii"``).

    Parameters
    ----------
    stem : str
        File stem under ``published/``.
    raw : Path, optional
        The run's raw folder (see :func:`published_dir`).
    strict : bool
        Raise on schema problems (default); otherwise log them.

    Raises
    ------
    PublishedTableError
        If the table is missing, or (``strict``) does not match its schema.
    """
    path = published_dir(raw) / f"{stem}.csv"
    if not path.is_file():
        raise PublishedTableError(f"{path}: published table not found")
    with open(path, "rb") as fh:
        data = fh.read()
    key = (str(path), hashlib.sha256(data).digest())
    if key not in _READ:  # stages in one process read the same tables: parse and check once
        if len(_READ) > 64:  # bounded: a long-lived process may see many edited copies
            _READ.clear()
        _READ[key] = _parse(stem, data)
    df, problems = _READ[key]
    if problems and strict:
        raise PublishedTableError(f"{path}: {problems[0]}")
    for p in problems:
        log.error("%s: %s", path, p)
    return df.copy()


#: (path, SHA-256 of the bytes) -> (frame, schema problems) of the tables read in this process.
_READ: dict[tuple[str, bytes], tuple[pd.DataFrame, list[str]]] = {}


def _parse(stem: str, data: bytes) -> tuple[pd.DataFrame, list[str]]:
    """A published table's bytes as a frame, with its schema problems (empty: it conforms)."""
    import io

    import pandas as pd

    from .schema import SCHEMA_DIR, load_schema, validate_frame  # pandas and numpy

    df = pd.read_csv(io.BytesIO(data), keep_default_na=False, na_values=[""])
    problems: list[str] = []
    if (SCHEMA_DIR / "published" / f"{stem}.json").exists():
        problems = validate_frame(df, load_schema(f"published/{stem}"))
    return df, problems


def thesis_stiffness_model(raw: Path | None = None):
    """The thesis' :class:`tyrelab.tyre.stiffness.StiffnessModel` from Tables II, III and VI.

    Reads the tables (``<raw>/published`` if ``raw`` has one, else the shipped copies) and
    builds the model with the pure :func:`tyrelab.tyre.models.thesis_stiffness_model`.
    """
    from .tyre.models import THESIS_TABLES
    from .tyre.models import thesis_stiffness_model as build

    return build(*(read_published(t, raw) for t in THESIS_TABLES))

