"""Render report pages from the warehouse with jinja2 (autoescaped)."""

from __future__ import annotations

import math
import os
import re
import subprocess
from datetime import datetime, timezone
from pathlib import Path

import jinja2
import numpy as np
import pandas as pd
from markupsafe import Markup, escape

from .. import __version__, resources
from .tables import Note

__all__ = ["TEMPLATE_DIR", "environment", "visible_controls", "format_number", "breakable", "abbreviations_used", "SYMBOLS", "code_version", "provenance", "UNITS", "column_label"]

#: Templates live in the repository's ``reports/`` folder.
TEMPLATE_DIR = resources.templates_dir()


def environment() -> jinja2.Environment:
    """The jinja2 environment: templates from ``reports/``, HTML autoescaping on."""
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(TEMPLATE_DIR),
        autoescape=jinja2.select_autoescape(["html", "j2"], default=True),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        finalize=visible_controls,
    )
    env.filters["num"] = format_number
    env.filters["label"] = column_label
    env.filters["breakable"] = breakable
    env.tests["note"] = lambda value: isinstance(value, Note)
    return env


#: Control characters HTML may not hold (C0 but tab, newline and carriage return; DEL; C1).
_CONTROL = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f]")


def visible_controls(value):
    r"""A page's value with the control characters HTML may not hold written as their escapes
    (``\x1b``): what every ``{{ }}`` of a page prints (the environment's ``finalize``), so that a
    run id or a note of a user's with an ESC shows it instead of a raw byte (as every verb's
    terminal output does, :func:`tyrelab.io.printable`). Markup stays Markup; other values pass.

    See Also
    --------
    tyrelab.io.printable : the same for a terminal (every control character).

    Examples
    --------
    >>> visible_controls("run" + chr(27) + "[31m"), visible_controls(3)
    ('run\\x1b[31m', 3)
    """
    if isinstance(value, str) and _CONTROL.search(value):
        text = _CONTROL.sub(lambda m: m.group().encode("unicode_escape").decode("ascii"), value)
        return Markup(text) if isinstance(value, Markup) else text
    return value


def breakable(value) -> Markup:
    """Cell text that may wrap after ``_``, ``/`` and ``,`` (``stationary_free_vibration``), escaped.

    Examples
    --------
    >>> str(breakable("stationary_free_vibration"))
    'stationary_<wbr>free_<wbr>vibration'
    """
    text = str(escape(value))
    return Markup(text.replace("_", "_<wbr>").replace("/", "/<wbr>").replace(",", ",<wbr>"))


def format_number(value, digits: int = 3, decimals: int | None = None) -> str:
    """Format a cell: "–" for missing, yes/no for booleans, a number with ``decimals`` fixed
    decimals when given (one format for a whole column), else with at most ``digits`` decimals
    (trailing zeros dropped); no thousands separators, so a number copies into any tool.

    Examples
    --------
    >>> format_number(2241.4832), format_number(2241.4832, decimals=0), format_number(0.5, decimals=3)
    ('2241.483', '2241', '0.500')
    >>> format_number(float("nan")), format_number(True), format_number(-0.0001, decimals=2)
    ('–', 'yes', '0.00')
    """
    if value is None or (isinstance(value, float) and math.isnan(value)) or value is pd.NA:
        return "–"
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        v = float(value)
        if not math.isfinite(v):
            return "∞" if v > 0 else "−∞"
        if decimals is not None:
            text = f"{v:.{decimals}f}"
            return text[1:] if text.startswith("-") and float(text) == 0 else text
        if v != 0 and (abs(v) >= 1e5 or abs(v) < 1e-3):
            return f"{v:.{digits}g}"
        return f"{v:.{digits}f}".rstrip("0").rstrip(".")
    return str(value)


def code_version() -> str:
    """tyrelab version plus the git commit when run from a checkout."""
    try:
        sha = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], cwd=TEMPLATE_DIR.parent, capture_output=True, text=True, timeout=5
        ).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        sha = ""
    return f"{__version__}" + (f" ({sha})" if sha else "")


def generated_at() -> datetime:
    """Time of the build: now, or ``SOURCE_DATE_EPOCH`` (seconds, UTC) when set, for reproducible builds
    (https://reproducible-builds.org/specs/source-date-epoch/)."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH", "").strip()
    if epoch.isdigit():
        return datetime.fromtimestamp(int(epoch), tz=timezone.utc)
    return datetime.now(timezone.utc)


def provenance(raw: Path, dataset: dict) -> dict:
    """Data set, generator seed or raw source, code version and time for a page footer.

    Parameters
    ----------
    raw : Path
        Raw data folder of the run.
    dataset : dict
        ``campaigns``, ``seeds`` (from each campaign's ``generator.json``) and
        ``digest`` (of the run files' SHA-256) as built by the site builder.
    """
    return {
        "raw": str(raw),
        "campaigns": dataset.get("campaigns", []),
        "seeds": dataset.get("seeds", []),
        "digest": dataset.get("digest", "–"),
        "code_version": code_version(),
        "generated_at": generated_at().strftime("%Y-%m-%d %H:%M UTC"),
    }


#: Unit suffixes of column names and how headers show them.
UNITS = {
    "_kN_per_m_per_mm": " (kN/m per mm)", "_kN_s_per_m_per_mm": " (kN s/m per mm)",
    "_kN_per_m_bar": " (kN/m per bar)", "_kN_s_per_m_bar": " (kN s/m per bar)",
    "_kN_s_per_m_per_rad": " (kN s/m per rad)", "_kN_per_rad": " (kN/rad)",
    "_kN_per_m": " (kN/m)", "_kN_s_per_m": " (kN s/m)", "_km_h": " (km/h)", "_bar": " (bar)",
    "_kNm": " (kN m)", "_kN": " (kN)", "_kg": " (kg)", "_Hz": " (Hz)", "_mm_pp": " (mm p-p)",
    "_m_s2": " (m/s²)", "_rad_s2": " (rad/s²)", "_m_s1_75": " (m/s^1.75)", "_m_s": " (m/s)",
    "_percent": " (%)", "_in": " (in)", "_N": " (N)",
}


#: Symbols that keep their underscore in a header: the names the CLI and the JSON use (``a_wz``).
SYMBOLS = re.compile(r"(?<![A-Za-z0-9])a (w[xyz]|v)(?![A-Za-z0-9])")


def column_label(name: str) -> str:
    """A readable header from a column name: ``speed_km_h`` -> ``speed (km/h)``; the ISO 2631
    symbols keep the spelling of the CLI and the JSON (``a_wz_m_s2`` -> ``a_wz (m/s²)``).

    Examples
    --------
    >>> column_label("speed_km_h"), column_label("expected_a_wz_m_s2"), column_label("a_v_m_s2")
    ('speed (km/h)', 'expected a_wz (m/s²)', 'a_v (m/s²)')
    """
    for suffix, unit in UNITS.items():
        if name.endswith(suffix):
            return SYMBOLS.sub(r"a_\1", name[: -len(suffix)].replace("_", " ")) + unit
    return SYMBOLS.sub(r"a_\1", name.replace("_", " "))


def abbreviations_used(html: str, abbreviations: dict[str, str]) -> list[tuple[str, str]]:
    """The ``abbreviations`` whose short form appears in the page's text (markup, style and
    figures' SVG code aside), in the order of the dict.

    Examples
    --------
    >>> abbreviations_used("<p>SBT and HH tracks</p><style>.HH{}</style>", {"HH": "Hussey", "EAV": "x", "SBT": "s"})
    [('HH', 'Hussey'), ('SBT', 's')]
    """
    text = re.sub(r"(?s)<(style|script)\b.*?</\1>", " ", html).replace("<wbr>", "")
    text = re.sub(r"<[^>]+>", " ", text)
    return [(a, meaning) for a, meaning in abbreviations.items()
            if re.search(rf"(?<![A-Za-z0-9_]){re.escape(a)}(?![A-Za-z0-9_])", text)]
