"""Agricultural tyre size designations (thesis Table II, §4.5.3).

The empirical stiffness formula of §4.5.3 takes the section width ``W`` and
rim diameter ``R`` "as given in the tyre size specification by the
manufacturer (in inches)". This module turns a designation such as
``13.6R38`` into those two numbers.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

_SIZE = re.compile(
    r"""^\s*
    (?P<width>\d+(?:\.\d+)?)            # section width, inches
    (?:\s*/\s*(?P<alt>\d+(?:\.\d+)?))?  # optional older / alternative designation
    \s*(?P<sep>R|-|D|B)\s*              # R radial, - or D cross-ply, B belted bias
    (?P<rim>\d+(?:\.\d+)?)              # rim diameter, inches
    \s*$""",
    re.VERBOSE | re.IGNORECASE,
)


class TyreSizeError(ValueError):
    """Raised when a tyre size designation cannot be parsed."""


@dataclass(frozen=True)
class TyreSize:
    """A parsed tyre size.

    Attributes
    ----------
    designation : str
        The text as given, e.g. ``"16.9/14R30"``.
    section_width_in : float
        Section width W in inches (the first number of the designation).
    rim_diameter_in : float
        Rim diameter R in inches.
    construction : str
        ``"radial"`` (``R``) or ``"cross-ply"`` (``-``, ``D``, ``B``).
    alternative_width_in : float or None
        The second width of a dual designation (``16.9/14R30`` -> 14).
    """

    designation: str
    section_width_in: float
    rim_diameter_in: float
    construction: str
    alternative_width_in: float | None = None

    @property
    def width_times_rim_in2(self) -> float:
        """Product W*R in square inches (thesis Fig. 30 abscissa)."""
        return self.section_width_in * self.rim_diameter_in


def parse_tyre_size(text: str) -> TyreSize:
    """Parse a tyre size designation into section width and rim diameter.

    Parameters
    ----------
    text : str
        Designations such as ``13.6R38``, ``13.6-38``, ``16.9/14R30``,
        ``11.2/10-24``, ``7.50-18``, ``9.5R44`` or ``13.6 R 38``.

    Returns
    -------
    TyreSize

    Raises
    ------
    TyreSizeError
        If the text is not a size designation; the message names the text.

    Examples
    --------
    >>> parse_tyre_size("16.9/14R30").section_width_in
    16.9
    """
    if not isinstance(text, str):
        raise TyreSizeError(f"tyre size {text!r} is not text")
    m = _SIZE.match(text)
    if m is None:
        raise TyreSizeError(
            f"tyre size {text!r} does not parse (expected e.g. 13.6R38, 13.6-38, 16.9/14R30)"
        )
    width = float(m["width"])
    rim = float(m["rim"])
    if not (2.0 <= width <= 60.0 and 8.0 <= rim <= 60.0):
        raise TyreSizeError(f"tyre size {text!r} gives implausible W={width} in, R={rim} in")
    sep = m["sep"].upper()
    return TyreSize(
        designation=text.strip(),
        section_width_in=width,
        rim_diameter_in=rim,
        construction="radial" if sep == "R" else "cross-ply",
        alternative_width_in=float(m["alt"]) if m["alt"] else None,
    )


#: Sidewall height / section width assumed for a tractor tyre without a printed aspect ratio.
DEFAULT_ASPECT_RATIO = 0.85
#: Free diameter to loaded rolling circumference factor; makes 13.6R38 give the
#: 4.66 m of thesis §4.5.1 / §6.5.3.
ROLLING_FACTOR = 0.956
#: Typical circumferential lug pitch of a traction tyre, m (one lug per side every ~0.2 m).
LUG_PITCH_m = 0.2


def rolling_circumference_m(size: TyreSize, aspect_ratio: float = DEFAULT_ASPECT_RATIO) -> float:
    """Estimated rolling circumference of a tyre, m.

    ``pi * (R + 2 * aspect * W) * 0.0254 * 0.956``: the free diameter from the
    size, reduced to the loaded rolling circumference so that a 13.6R38 gives
    the 4.66 m of thesis §4.5.1. A ribbed front tyre has taller sidewalls: a
    7.50-18 comes out at 2.35 m against the 2.63 m of §5.5.4, so a catalogue
    value is preferred where one is given.
    """
    return math.pi * (size.rim_diameter_in + 2 * aspect_ratio * size.section_width_in) * 0.0254 * ROLLING_FACTOR
