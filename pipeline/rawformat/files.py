"""What ingest may open: campaign confinement, regular files only, and delimited tables.

- :func:`confined_run_path`: a manifest's ``file`` must be relative, must resolve
  (after symlinks) inside its campaign folder, and must be a regular file. It is
  checked with ``stat`` before anything opens it, so ``/etc/shadow``, ``../x`` or a
  symlink out of the campaign is refused unread, and a named pipe never blocks a run.
- :func:`read_delimited`: a manifest or tyre catalogue as a spreadsheet saves it. The
  separator (``,`` ``;`` or tab) is found from the header (the one that yields the
  schema's column names), a UTF-8 byte-order mark and CRLF line ends are accepted, and
  in a ``;``- or tab-separated file decimal commas (``1,38``, ``1.234,5``) of the
  schema's numeric columns are read as numbers. What was found is returned as notes;
  a file that cannot be read so is refused with one line naming what was found and
  how to fix it.

Examples
--------
>>> import tempfile, pathlib
>>> from tyrelab.schema import load_schema
>>> with tempfile.TemporaryDirectory() as d:
...     p = pathlib.Path(d) / "tyres.csv"
...     _ = p.write_bytes(b"\\xef\\xbb\\xbftyre_id;size;age_years\\r\\nT9;13.6R38;2,5\\r\\n")
...     t = read_delimited(p, load_schema("tyres"))
>>> t.frame.to_dict("records"), t.delimiter, t.notes
([{'tyre_id': 'T9', 'size': '13.6R38', 'age_years': '2.5'}], ';', ["';'-separated", 'decimal commas', 'a UTF-8 byte-order mark', 'CRLF line ends'])
"""

from __future__ import annotations

import csv
import io as _io
import os
import re
import stat
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from ..io import file_kind
from .mapped import RunFileError

__all__ = ["MAX_TABLE_BYTES", "DELIMITERS", "DelimitedTable", "regular_file", "confined_run_path", "read_delimited"]

#: Largest manifest or catalogue read, bytes.
MAX_TABLE_BYTES = 64 * 1024**2
#: Separators tried on the header line, in order of preference.
DELIMITERS = (",", ";", "\t")
_NAMES = {",": "','", ";": "';'", "\t": "tab"}
_DECIMAL_COMMA = re.compile(r"^\s*[+-]?(\d{1,3}(\.\d{3})+|\d*),\d+\s*$")


def regular_file(path: str | os.PathLike) -> os.stat_result:
    """``stat`` of ``path`` (following symlinks) if it is a regular file.

    Raises
    ------
    RunFileError
        ``file not found``, ``is a folder/named pipe (FIFO)/device…, not a regular
        file``, or ``cannot read (…)`` for a folder without permission on the way.
    """
    try:
        st = os.stat(path)
    except FileNotFoundError:
        raise RunFileError("file not found") from None
    except OSError as exc:
        raise RunFileError(f"cannot read ({exc.strerror or exc})") from None
    if not stat.S_ISREG(st.st_mode):
        raise RunFileError(f"is a {file_kind(st.st_mode)}, not a regular file")
    return st


def confined_run_path(campaign: str | os.PathLike, name: str) -> Path:
    """The run file ``name`` of ``campaign`` (as the manifest gives it), resolved and checked.

    Parameters
    ----------
    campaign : path
        The campaign folder (holding ``manifest.csv``).
    name : str
        The manifest's ``file``: relative to the campaign folder.

    Raises
    ------
    RunFileError
        If ``name`` is absolute, resolves (after symlinks) outside the campaign folder,
        or is not a regular file. Nothing is opened.
    """
    if not isinstance(name, str) or not name.strip():
        raise RunFileError("empty file name")
    if Path(name).is_absolute():
        raise RunFileError(f"absolute path {name!r}: run files are named relative to manifest.csv")
    root = Path(campaign).resolve()
    target = (root / name).resolve()
    if not target.is_relative_to(root):
        raise RunFileError(f"{name!r} resolves outside the campaign folder ({target}); "
                           "run files must sit in the campaign folder or below it")
    regular_file(target)
    return target


@dataclass
class DelimitedTable:
    """A delimited text table as read: all values as strings (decimal commas made points)."""

    frame: pd.DataFrame
    delimiter: str
    notes: list[str] = field(default_factory=list)

    def describe(self) -> str:
        """``"read as ';'-separated with decimal commas, …"``, or ``""`` for a plain UTF-8 CSV."""
        return "read as " + ", ".join(self.notes) if self.notes else ""


def _decode(data: bytes) -> tuple[str, list[str]]:
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        return data.decode("utf-16"), ["UTF-16 text"]
    notes = []
    if data.startswith(b"\xef\xbb\xbf"):
        data, notes = data[3:], ["a UTF-8 byte-order mark"]
    try:
        return data.decode("utf-8"), notes
    except UnicodeDecodeError as exc:
        raise RunFileError(
            f"not UTF-8 text (byte 0x{data[exc.start]:02X} at offset {exc.start}, e.g. a spreadsheet saved in a "
            "Windows code page); save it as 'CSV UTF-8'") from None


def read_delimited(path: str | os.PathLike, schema: dict) -> DelimitedTable:
    """Read a manifest or catalogue (see the module docstring).

    Parameters
    ----------
    path : path
        The file; it must be a regular file of at most :data:`MAX_TABLE_BYTES`.
    schema : dict
        Its Table Schema: field names find the separator, numeric fields get decimal commas read.

    Raises
    ------
    RunFileError
        One line: not a regular file, too large, not UTF-8, no known column with any
        separator (naming the header found), or unparseable.
    """
    st = regular_file(path)
    if st.st_size > MAX_TABLE_BYTES:
        raise RunFileError(f"file is {st.st_size / 1e6:.0f} MB, larger than the {MAX_TABLE_BYTES / 1e6:.0f} MB limit")
    try:
        with open(path, "rb") as fh:
            data = fh.read(MAX_TABLE_BYTES + 1)
    except OSError as exc:  # e.g. no read permission
        raise RunFileError(f"cannot read ({exc.strerror or exc})") from None
    text, notes = _decode(data)
    lines = text.splitlines()
    header = next((line for line in lines if line.strip()), "")
    if not header:
        raise RunFileError("empty file (no header line)")
    known = {f["name"] for f in schema["fields"]}
    scores = {}
    for d in DELIMITERS:
        names = [n.strip() for n in next(csv.reader([header], delimiter=d))]
        scores[d] = (len(known.intersection(names)), len(names))
    delimiter = max(DELIMITERS, key=lambda d: scores[d])  # most known names, then most columns; ',' on ties
    if scores[delimiter][0] == 0:
        wanted = ", ".join(f["name"] for f in schema["fields"] if f.get("constraints", {}).get("required"))
        raise RunFileError(f"no known column in the header {header[:80]!r} with ',', ';' or tab as separator "
                           f"(expected {wanted}); save it as 'CSV UTF-8 (comma delimited)' with that header")
    try:
        frame = pd.read_csv(_io.StringIO(text), sep=delimiter, dtype=str, keep_default_na=False, na_values=[""],
                            skipinitialspace=False)
    except (ValueError, csv.Error) as exc:  # pandas' ParserError is a ValueError
        raise RunFileError(f"unreadable as {_NAMES[delimiter]}-separated text ({str(exc).strip()[:120]})") from None
    frame.columns = [str(c).strip() for c in frame.columns]
    if delimiter != ",":
        notes.insert(0, f"{_NAMES[delimiter]}-separated")
        numeric = [f["name"] for f in schema["fields"] if f["type"] in ("number", "integer") and f["name"] in frame]
        converted = False
        for c in numeric:
            values = frame[c]
            mask = values.notna() & values.astype(str).str.match(_DECIMAL_COMMA)
            if mask.any():
                frame.loc[mask, c] = values[mask].str.strip().str.replace(".", "", regex=False).str.replace(",", ".")
                converted = True
        if converted:
            notes.insert(1, "decimal commas")
    if "\r\n" in text:
        notes.append("CRLF line ends")
    return DelimitedTable(frame, delimiter, notes)
