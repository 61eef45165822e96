"""Argument checks shared by tyrelab's pure functions (scipy's habit).

Each raises :class:`ValueError` naming the offending parameter, so a caller's
mistake reads as one clear line instead of a ``ZeroDivisionError`` or a NaN
three functions later.

Examples
--------
>>> positive("sample_rate_Hz", 256)
256.0
>>> positive("sample_rate_Hz", 0.0)
Traceback (most recent call last):
...
ValueError: sample_rate_Hz must be finite and positive, got 0.0
>>> positive_array("axle_mass_kg", [600.0, -1.0])
Traceback (most recent call last):
...
ValueError: axle_mass_kg must be finite and positive, got [600.0, -1.0]
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["positive", "positive_array", "finite_array", "same_last_axis", "band", "non_negative", "probability",
           "positive_int", "frame", "choice", "instances", "instance", "non_negative_array", "finite", "in_range",
           "shown", "compared", "grouped_problems"]


def compared(value: float, op: str, limit: float, digits: int = 3) -> str:
    """``"<value> <op> <limit>"`` for a message that a value is beyond a limit, the value with
    ``digits`` significant digits or as many more as it takes to differ from the limit: never
    ``"1.5 > 1.5"`` for 1.5036 (issue 47).

    Examples
    --------
    >>> compared(1.5036, ">", 1.5), compared(1.83, ">", 1.5), compared(0.8996, "<", 0.9)
    ('1.504 > 1.5', '1.83 > 1.5', '0.8996 < 0.9')
    >>> compared(12.0, ">", 9)
    '12 > 9'
    """
    limit_text = f"{limit:g}"
    text = f"{value:.{digits}g}"
    for d in range(digits, 18):
        text = f"{value:.{d}g}"
        if not math.isfinite(value) or float(text) != float(limit_text):
            break
    return f"{text} {op} {limit_text}"


def shown(value, width: int = 40) -> str:
    """``repr(value)`` for a message, at most about ``width`` characters: a 400-digit integer is
    shown by its first and last digits and its length, not in full.

    Examples
    --------
    >>> shown(10**400)
    '1000000000…0000000000 (401 digits)'
    >>> shown(2.5)
    '2.5'
    """
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**width:
        try:
            digits = str(abs(value))
        except ValueError:  # more digits than Python converts (sys.get_int_max_str_digits): counted, not shown
            return f"{'-' if value < 0 else ''}an integer of about {int(abs(value).bit_length() * 0.30103) + 1} digits"
        return f"{'-' if value < 0 else ''}{digits[:10]}…{digits[-10:]} ({len(digits)} digits)"
    try:
        text = repr(value)
    except ValueError:  # a container holding such an integer
        return f"a {type(value).__name__} holding an integer too long to show"
    return text if len(text) <= 2 * width else text[:width] + "…"


def finite(name: str, value) -> float:
    """``value`` as a float; ValueError naming ``name`` unless it is a finite real number.

    A bool is no number here (``True`` is not one hour), and an integer too large for a float
    (``1`` and 400 zeros, which TOML and Python hold exactly) is refused like infinity, never an
    ``OverflowError``.

    Examples
    --------
    >>> finite("hours", 8)
    8.0
    >>> finite("hours", True)
    Traceback (most recent call last):
    ...
    ValueError: hours must be a number, got True
    >>> finite("mass_kg", 10**400)
    Traceback (most recent call last):
    ...
    ValueError: mass_kg must be a finite number, got 1000000000…0000000000 (401 digits)
    """
    v = _number(name, value)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be a finite number, got {shown(value)}")
    return v


def in_range(name: str, value, low: float, high: float, unit: str = "") -> float:
    """``value`` as a float; ValueError naming ``name`` and the range unless ``low <= value <= high``
    (finite, not a bool: :func:`finite`).

    Examples
    --------
    >>> in_range("--mass", 4000, 200, 50_000, "kg")
    4000.0
    >>> in_range("--mass", 1e308, 200, 50_000, "kg")
    Traceback (most recent call last):
    ...
    ValueError: --mass must be within 200 to 50000 kg, got 1e+308
    """
    v = finite(name, value)
    if not low <= v <= high:
        u = f" {unit}" if unit else ""
        raise ValueError(f"{name} must be within {low:g} to {high:g}{u}, got {v:g}")
    return v


def positive(name: str, value) -> float:
    """``value`` as a float; ValueError naming ``name`` unless it is a finite number > 0 (not a bool: True is no mass)."""
    v = _number(name, value)
    if not math.isfinite(v) or v <= 0:
        raise ValueError(f"{name} must be finite and positive, got {shown(value)}")
    return v


def _number(name: str, value) -> float:
    """``float(value)``, infinity for an integer too large for a float (the callers refuse it as
    not finite); ValueError naming ``name`` for a bool, a string or what is no number."""
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be a number, got {shown(value)}")
    try:
        return float(value)
    except OverflowError:
        return -math.inf if isinstance(value, int) and value < 0 else math.inf
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {shown(value)}") from None


def positive_int(name: str, value, minimum: int = 1) -> int:
    """``value`` as an int; ValueError naming ``name`` unless it is an integer >= ``minimum`` (a count).

    Examples
    --------
    >>> positive_int("n_cycles", 5)
    5
    >>> positive_int("min_run", 0)
    Traceback (most recent call last):
    ...
    ValueError: min_run must be an integer >= 1, got 0
    """
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {shown(value)}")
    return int(value)


def positive_array(name: str, value, allow_nan: bool = False) -> np.ndarray:
    """``value`` as a float array; ValueError naming ``name`` unless every element is finite and > 0.

    With ``allow_nan``, NaN ("not known", e.g. no excitation found) passes through.
    """
    return _signed_array(name, value, allow_nan, strict=True)


def _signed_array(name: str, value, allow_nan: bool, strict: bool) -> np.ndarray:
    """:func:`positive_array` (``strict``) and :func:`non_negative_array`."""
    try:
        if np.asarray(value).dtype == bool:
            raise ValueError(f"{name} must be numbers, got booleans {shown(value)}")
        a = np.asarray(value, dtype=float)
    except OverflowError:  # an integer too large for a float
        raise ValueError(f"{name} must be finite numbers, got {shown(value)}") from None
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be numbers, got {shown(value)}") from None
    ok = np.isfinite(a) & ((a > 0) if strict else (a >= 0))
    if allow_nan:
        ok |= np.isnan(a)
    if not ok.all():
        word = "positive" if strict else "non-negative"
        listed = a.tolist() if a.size <= 6 else f"{a.size} values, {int((~ok).sum())} bad"
        raise ValueError(f"{name} must be {f'{word} (or NaN)' if allow_nan else f'finite and {word}'}, got {listed}")
    return a


def finite_array(name: str, value, min_samples: int = 1) -> np.ndarray:
    """``value`` as a float array with at least ``min_samples`` along the last axis, every sample finite."""
    try:
        a = np.asarray(value, dtype=float)
    except OverflowError:
        raise ValueError(f"{name} has non-finite samples") from None
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be numeric samples") from None
    if a.ndim == 0 or a.shape[-1] < min_samples:
        raise ValueError(f"{name} needs at least {min_samples} samples along its last axis, got shape {a.shape}")
    if not np.isfinite(a).all():
        raise ValueError(f"{name} has non-finite samples")
    return a


def same_last_axis(**arrays: np.ndarray) -> None:
    """ValueError naming the arrays unless they have the same length along the last axis."""
    lengths = {k: np.shape(v)[-1] if np.ndim(v) else None for k, v in arrays.items()}
    if len(set(lengths.values())) > 1:
        raise ValueError("mismatched lengths: " + ", ".join(f"{k} has {n} samples" for k, n in lengths.items()))


def band(name: str, value) -> tuple[float, float]:
    """``(low, high)`` in Hz with ``0 <= low < high``, finite; ValueError naming ``name`` otherwise."""
    try:
        lo, hi = (_number(name, v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a (low, high) pair in Hz, got {shown(value)}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo < hi):
        raise ValueError(f"{name} must satisfy 0 <= low < high, got {shown(value)}")
    return lo, hi


def non_negative(name: str, value) -> float:
    """``value`` as a float; ValueError naming ``name`` unless it is a finite number >= 0.

    Examples
    --------
    >>> non_negative("age_years", 0)
    0.0
    """
    v = _number(name, value)
    if not math.isfinite(v) or v < 0:
        raise ValueError(f"{name} must be finite and non-negative, got {shown(value)}")
    return v


def probability(name: str, value) -> float:
    """``value`` as a float strictly between 0 and 1 (a level or an alpha); ValueError naming ``name`` otherwise.

    Examples
    --------
    >>> probability("alpha", 2)
    Traceback (most recent call last):
    ...
    ValueError: alpha must be a number in (0, 1), got 2
    """
    try:
        v = _number(name, value)
    except ValueError:
        raise ValueError(f"{name} must be a number in (0, 1), got {shown(value)}") from None
    if not 0 < v < 1:
        raise ValueError(f"{name} must be a number in (0, 1), got {shown(value)}")
    return v


def frame(name: str, value, columns=()):
    """``value`` if it is a DataFrame holding ``columns``; ValueError naming ``name`` (and the missing columns) otherwise.

    Examples
    --------
    >>> import pandas as pd
    >>> frame("results", pd.DataFrame({"tyre_id": ["T1"]}), ["tyre_id"]).shape
    (1, 1)
    >>> frame("results", pd.DataFrame({"tyre_id": ["T1"]}), ["tyre_id", "speed_km_h"])
    Traceback (most recent call last):
    ...
    ValueError: results lacks column(s) speed_km_h
    """
    import pandas as pd

    if not isinstance(value, pd.DataFrame):
        raise ValueError(f"{name} must be a table (pandas DataFrame), got {type(value).__name__}")
    missing = [str(c) for c in columns if c not in value.columns]
    if missing:
        raise ValueError(f"{name} lacks column(s) {', '.join(missing)}")
    return value


def choice(name: str, value, options):
    """``value`` if it is one of ``options``; ValueError naming ``name`` and the options otherwise.

    Examples
    --------
    >>> choice("name", "Wx", ("Wk", "Wd"))
    Traceback (most recent call last):
    ...
    ValueError: name must be one of 'Wk', 'Wd', got 'Wx'
    """
    try:
        ok = value in options
    except TypeError:
        ok = False
    if not ok:
        raise ValueError(f"{name} must be one of {', '.join(repr(o) for o in options)}, got {shown(value)}")
    return value


def instances(name: str, value, kind) -> list:
    """``value`` as a list whose every element is a ``kind``; ValueError naming ``name`` otherwise.

    Examples
    --------
    >>> instances("fits", [1.0, "x"], float)
    Traceback (most recent call last):
    ...
    ValueError: fits must be a list of float, got str at position 1
    """
    try:
        items = list(value)
    except TypeError:
        raise ValueError(f"{name} must be a list of {kind.__name__}, got {type(value).__name__}") from None
    for i, item in enumerate(items):
        if not isinstance(item, kind):
            raise ValueError(f"{name} must be a list of {kind.__name__}, got {type(item).__name__} at position {i}")
    return items


def non_negative_array(name: str, value, allow_nan: bool = False) -> np.ndarray:
    """``value`` as a float array; ValueError naming ``name`` unless every element is finite and >= 0.

    With ``allow_nan``, NaN ("not known") passes through.

    Examples
    --------
    >>> non_negative_array("speed_km_h", [0.0, 10.0]).tolist()
    [0.0, 10.0]
    """
    return _signed_array(name, value, allow_nan, strict=False)


def instance(name: str, value, kind):
    """``value`` if it is a ``kind``; ValueError naming ``name`` otherwise (a scenario, a tractor, a profile).

    Examples
    --------
    >>> instance("scenario", "modern.toml", dict)
    Traceback (most recent call last):
    ...
    ValueError: scenario must be a dict, got str
    """
    if not isinstance(value, kind):
        kinds = " or ".join(k.__name__ for k in (kind if isinstance(kind, tuple) else (kind,)))
        raise ValueError(f"{name} must be a {kinds}, got {type(value).__name__}")
    return value


#: How many values of one list key (``exposure.speeds_km_h`` ...) out of range for one reason are
#: named one line each; more are said in one line naming the first few (a scenario with thousands of
#: speeds out of range is one line, not thousands).
MAX_LINES_PER_KEY = 3


def grouped_problems(lines: list[str]) -> list[str]:
    """Problem lines (``"key: value is outside …"``, ``"key: value is not a finite number"``) with the
    lines of one key and one reason beyond :data:`MAX_LINES_PER_KEY` said once, where the first of them
    stood; other lines as they are.

    Examples
    --------
    >>> lines = [f"exposure.speeds_km_h: {v} km/h is outside 0.5 to 80 km/h, what the ride model is built for"
    ...          for v in (100, 101, 102, 103, 104)]
    >>> grouped_problems(lines)  # doctest: +NORMALIZE_WHITESPACE
    ['exposure.speeds_km_h: 5 values are outside 0.5 to 80 km/h, what the ride model is built for
      (100 km/h, 101 km/h, 102 km/h and 2 more)']
    >>> grouped_problems(lines[:2]) == lines[:2]
    True
    """
    def reason(line: str) -> tuple[str, str, str] | None:
        key, sep, rest = line.partition(": ")
        for mark in (" is outside ", " is not a finite number"):
            value, found, tail = rest.partition(mark)
            if sep and found:
                return key, value, mark + tail
        return None

    groups: dict[tuple[str, str], list[str]] = {}
    for line in lines:
        r = reason(line)
        if r is not None:
            groups.setdefault((r[0], r[2]), []).append(r[1])
    out, said = [], set()
    for line in lines:
        r = reason(line)
        if r is None or len(groups[(r[0], r[2])]) <= MAX_LINES_PER_KEY:
            out.append(line)
            continue
        if (r[0], r[2]) in said:
            continue
        said.add((r[0], r[2]))
        values = groups[(r[0], r[2])]
        head, _, why = r[2].removeprefix(" is ").partition(", ")
        shown = ", ".join(values[:MAX_LINES_PER_KEY])
        out.append(f"{r[0]}: {len(values)} values are {head}{', ' + why if why else ''} "
                   f"({shown} and {len(values) - MAX_LINES_PER_KEY} more)")
    return out
