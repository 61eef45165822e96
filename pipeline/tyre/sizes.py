"""Agricultural tyre size designations: the thesis' inch sizes and today's metric sizes.

The empirical stiffness formula of §4.5.3 takes the section width ``W`` and
rim diameter ``R`` "as given in the tyre size specification by the
manufacturer (in inches)". This module turns a designation into those two
numbers and everything else the designation says:

* inch sizes as in thesis Table II: ``13.6R38``, ``13.6-38``, ``16.9/14R30``
  (dual designation), ``7.50-18``, ``18.4R38``; and inch-width low-section
  implement sizes ``10.0/75-15.3`` (second number an aspect ratio in %);
* ETRTO/ISO metric sizes: ``480/70R38`` = section width 480 mm, aspect ratio
  70 %, radial, rim diameter 38 **inches** (ISO 4251-1, ETRTO Agricultural
  Tyres section);
* the markings around the size: ``IF`` (Improved Flexion) and ``VF`` (Very
  high Flexion) classes, ``CFO``/``PFO`` service markings, a service
  description (load index + speed symbol, ``145D``, ``157A8/154B`` or the
  older ``146/A8``), a tread code (``R-1W``), ``TL``/``TT`` and a ply rating
  (``8PR``).

Load indices and speed symbols are those of ISO 4000-1 / ETRTO (tabulated
below as data, :data:`LOAD_INDEX_kg`, :data:`SPEED_SYMBOL_km_h`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from .. import _validate

__all__ = [
    "DEFAULT_ASPECT_RATIO",
    "FLEXION_LOAD_FACTOR",
    "LOAD_INDEX_kg",
    "LUG_PITCH_m",
    "ROLLING_FACTOR",
    "SPEED_SYMBOL_km_h",
    "ServiceDescription",
    "TyreSize",
    "TyreSizeError",
    "load_index_kg",
    "lugs_per_side",
    "parse_tyre_size",
    "rolling_circumference_m",
    "speed_symbol_km_h",
    "tyre_rolling_circumference_m",
]

#: Section height / section width of an inch-designated tractor tyre, which prints no aspect
#: ratio. Conventional ("standard series") agricultural inch sizes are the 85 series: ETRTO
#: gives their metric equivalents as x/85 (13.6R38 = 340/85R38, 16.9R34 = 420/85R34,
#: 18.4R38 = 460/85R38). Also the value that, with :data:`ROLLING_FACTOR`, gives the 4.66 m
#: rolling circumference of a 13.6R38 (thesis §4.5.1). Narrow ribbed front tyres (7.50-18)
#: are taller (about 1.0), so a catalogue circumference is preferred for them.
DEFAULT_ASPECT_RATIO = 0.85
#: Free diameter to loaded rolling circumference factor; makes 13.6R38 give the
#: 4.66 m of thesis §4.5.1 / §6.5.3.
ROLLING_FACTOR = 0.956
#: Typical circumferential lug pitch of a traction tyre, m (one lug per side every ~0.2 m).
LUG_PITCH_m = 0.2
#: Load a flexion-class tyre carries at the same pressure, relative to a standard tyre of the
#: same size: IF +20 %, VF +40 % (ETRTO / ISO 4251 IF and VF definitions). The load index
#: printed on an IF/VF tyre already includes it.
FLEXION_LOAD_FACTOR = {"IF": 1.2, "VF": 1.4}

#: Load index -> load capacity per tyre, kg: ISO 4000-1 / ETRTO load index table, LI 0-279,
#: one row per ten indices. Checked in the tests against known points (LI 142 = 2650 kg,
#: 165 = 5150 kg, 168 = 5600 kg) and the table's own structure: from LI 100 on, 80 indices
#: further is exactly ten times the load (LI n+80 = 10 x LI n; LI 20-99 are the same series
#: rounded to fewer digits). Project Chrono's ``GetTireMaxLoad`` prints the same table with
#: slips at LI 1 (46.5), 169 (5850), 203 (15550) and 275 (121000) for 46.2, 5800, 15500
#: and 121500; the rule exposes the last three.
LOAD_INDEX_kg: tuple[float, ...] = (
    45, 46.2, 47.5, 48.7, 50, 51.5, 53, 54.5, 56, 58,                       # 0-9
    60, 61.5, 63, 65, 67, 69, 71, 73, 75, 77.5,                             # 10-19
    80, 82.5, 85, 87.5, 90, 92.5, 95, 97.5, 100, 103,                       # 20-29
    106, 109, 112, 115, 118, 121, 125, 128, 132, 136,                       # 30-39
    140, 145, 150, 155, 160, 165, 170, 175, 180, 185,                       # 40-49
    190, 195, 200, 206, 212, 218, 224, 230, 236, 243,                       # 50-59
    250, 257, 265, 272, 280, 290, 300, 307, 315, 325,                       # 60-69
    335, 345, 355, 365, 375, 387, 400, 412, 425, 437,                       # 70-79
    450, 462, 475, 487, 500, 515, 530, 545, 560, 580,                       # 80-89
    600, 615, 630, 650, 670, 690, 710, 730, 750, 775,                       # 90-99
    800, 825, 850, 875, 900, 925, 950, 975, 1000, 1030,                     # 100-109
    1060, 1090, 1120, 1150, 1180, 1215, 1250, 1285, 1320, 1360,             # 110-119
    1400, 1450, 1500, 1550, 1600, 1650, 1700, 1750, 1800, 1850,             # 120-129
    1900, 1950, 2000, 2060, 2120, 2180, 2240, 2300, 2360, 2430,             # 130-139
    2500, 2575, 2650, 2725, 2800, 2900, 3000, 3075, 3150, 3250,             # 140-149
    3350, 3450, 3550, 3650, 3750, 3875, 4000, 4125, 4250, 4375,             # 150-159
    4500, 4625, 4750, 4875, 5000, 5150, 5300, 5450, 5600, 5800,             # 160-169
    6000, 6150, 6300, 6500, 6700, 6900, 7100, 7300, 7500, 7750,             # 170-179
    8000, 8250, 8500, 8750, 9000, 9250, 9500, 9750, 10000, 10300,           # 180-189
    10600, 10900, 11200, 11500, 11800, 12150, 12500, 12850, 13200, 13600,   # 190-199
    14000, 14500, 15000, 15500, 16000, 16500, 17000, 17500, 18000, 18500,   # 200-209
    19000, 19500, 20000, 20600, 21200, 21800, 22400, 23000, 23600, 24300,   # 210-219
    25000, 25750, 26500, 27250, 28000, 29000, 30000, 30750, 31500, 32500,   # 220-229
    33500, 34500, 35500, 36500, 37500, 38750, 40000, 41250, 42500, 43750,   # 230-239
    45000, 46250, 47500, 48750, 50000, 51500, 53000, 54500, 56000, 58000,   # 240-249
    60000, 61500, 63000, 65000, 67000, 69000, 71000, 73000, 75000, 77500,   # 250-259
    80000, 82500, 85000, 87500, 90000, 92500, 95000, 97500, 100000, 103000,  # 260-269
    106000, 109000, 112000, 115000, 118000, 121500, 125000, 128500, 132000, 136000,  # 270-279
)

#: Speed symbol -> reference speed, km/h (ISO 4000-1 / ETRTO; A1-A8 the agricultural
#: 5 km/h steps, then B 50 ... Y 300; H sits between U and V).
SPEED_SYMBOL_km_h: dict[str, float] = {
    "A1": 5, "A2": 10, "A3": 15, "A4": 20, "A5": 25, "A6": 30, "A7": 35, "A8": 40,
    "B": 50, "C": 60, "D": 65, "E": 70, "F": 80, "G": 90, "J": 100, "K": 110, "L": 120,
    "M": 130, "N": 140, "P": 150, "Q": 160, "R": 170, "S": 180, "T": 190, "U": 200,
    "H": 210, "V": 240, "W": 270, "Y": 300,
}

_EXAMPLES = "e.g. 480/70R38 145D, IF 710/70R42 173D, 520/85R42 157A8/154B, 13.6R38, 16.9/14R30, 7.50-18"

_NUM = r"\d+(?:\.\d+)?"
_CORE = re.compile(
    rf"""^
    (?P<first>{_NUM})                   # section width: mm (metric) or inches
    (?:/(?P<second>{_NUM}))?            # aspect ratio % (metric) or alternative width, inches
    (?P<sep>R|-|D|B)                    # R radial, - or D cross-ply (diagonal), B belted bias
    (?P<rim>{_NUM})                     # rim diameter, inches
    $""",
    re.VERBOSE,
)
_SPEED = r"A[1-8]|[BCDEFGJKLMNPQRSTUHVWY]"
_SERVICE = re.compile(rf"^(?P<li>\d{{2,3}})(?P<ss>{_SPEED})(?:/(?P<li2>\d{{2,3}})(?P<ss2>{_SPEED}))?$")
_SERVICE_OLD = re.compile(rf"^(?P<li>\d{{2,3}})/(?P<ss>{_SPEED})$")  # Table II's "146/A8"
_TREAD = re.compile(r"^(?:R|F|G|I|HF|LS)-\d[A-Z]?$")
_PLY = re.compile(r"^(?P<ply>\d{1,2})PR$")
_MARKINGS = ("IF", "VF", "CFO", "PFO")
_ASPECTS_INCH_WIDTH = range(30, 100, 5)  # 10.0/75-15.3: the second number an aspect ratio


class TyreSizeError(ValueError):
    """Raised when a tyre size designation cannot be parsed."""


def load_index_kg(load_index: int) -> float:
    """Load capacity per tyre, kg, of an ISO 4000-1 / ETRTO load index (0-279).

    See Also
    --------
    speed_symbol_km_h : the service description's other half.
    parse_tyre_size : reads both from a designation.

    Examples
    --------
    >>> load_index_kg(142)
    2650
    """
    if isinstance(load_index, bool) or not isinstance(load_index, int):
        raise ValueError(f"load_index {load_index!r} is not an integer")
    if not 0 <= load_index < len(LOAD_INDEX_kg):
        raise ValueError(f"load_index {load_index} is outside the table (0-{len(LOAD_INDEX_kg) - 1})")
    return LOAD_INDEX_kg[load_index]


def speed_symbol_km_h(symbol: str) -> float:
    """Reference speed, km/h, of an ISO 4000-1 speed symbol (``"A8"`` -> 40, ``"D"`` -> 65).

    See Also
    --------
    load_index_kg : the service description's other half.
    parse_tyre_size : reads both from a designation.

    Examples
    --------
    >>> speed_symbol_km_h("A8")
    40
    """
    if not isinstance(symbol, str) or symbol.upper() not in SPEED_SYMBOL_km_h:
        raise ValueError(f"symbol {symbol!r} is not a speed symbol (A1-A8, B, C, D, ... Y)")
    return SPEED_SYMBOL_km_h[symbol.upper()]


@dataclass(frozen=True)
class ServiceDescription:
    """Load index and speed symbol, e.g. ``157A8`` (ISO 4000-1).

    Attributes
    ----------
    load_index : int
    speed_symbol : str
    """

    load_index: int
    speed_symbol: str

    @property
    def load_kg(self) -> float:
        """Load capacity per tyre at the reference speed, kg."""
        return load_index_kg(self.load_index)

    @property
    def speed_km_h(self) -> float:
        """Reference speed, km/h."""
        return speed_symbol_km_h(self.speed_symbol)

    def __str__(self) -> str:
        return f"{self.load_index}{self.speed_symbol}"


@dataclass(frozen=True)
class TyreSize:
    """A parsed tyre size.

    Attributes
    ----------
    designation : str
        The text as given (stripped), e.g. ``"IF 710/70R42 173D"``.
    section_width_in : float
        Section width W in inches (mm / 25.4 for metric sizes).
    rim_diameter_in : float
        Rim diameter R in inches.
    construction : str
        ``"radial"`` (``R``) or ``"cross-ply"`` (``-``, ``D``, ``B``).
    alternative_width_in : float or None
        The second width of a dual inch designation (``16.9/14R30`` -> 14).
    aspect_ratio : float
        Section height / section width: as stated (``480/70R38`` -> 0.70), else
        :data:`DEFAULT_ASPECT_RATIO` (0.85, the inch series).
    aspect_ratio_stated : bool
        Whether the designation prints the aspect ratio.
    metric : bool
        ETRTO/ISO metric designation (width in mm).
    flexion_class : str or None
        ``"IF"``, ``"VF"`` or None.
    markings : tuple of str
        Every class/service marking found (``IF``, ``VF``, ``CFO``, ``PFO``), in order.
    service : ServiceDescription or None
        First service description (``157A8`` of ``157A8/154B``).
    alternative_service : ServiceDescription or None
        Second service description (``154B`` of ``157A8/154B``).
    tread_code : str or None
        Tread code such as ``R-1W``.
    ply_rating : int or None
        From a ``8PR`` marking.
    tubeless : bool or None
        ``TL`` True, ``TT`` False, None when not marked.
    """

    designation: str
    section_width_in: float
    rim_diameter_in: float
    construction: str
    alternative_width_in: float | None = None
    aspect_ratio: float = DEFAULT_ASPECT_RATIO
    aspect_ratio_stated: bool = False
    metric: bool = False
    flexion_class: str | None = None
    markings: tuple[str, ...] = ()
    service: ServiceDescription | None = None
    alternative_service: ServiceDescription | None = None
    tread_code: str | None = None
    ply_rating: int | None = None
    tubeless: bool | None = None

    @property
    def width_times_rim_in2(self) -> float:
        """Product W*R in square inches (thesis Fig. 30 abscissa)."""
        return self.section_width_in * self.rim_diameter_in

    @property
    def section_width_mm(self) -> float:
        """Section width, mm."""
        return self.section_width_in * 25.4

    @property
    def section_height_mm(self) -> float:
        """Section height = aspect ratio x section width, mm."""
        return self.aspect_ratio * self.section_width_mm

    @property
    def rim_diameter_m(self) -> float:
        """Rim diameter, m."""
        return self.rim_diameter_in * 0.0254

    @property
    def outer_diameter_m(self) -> float:
        """Free (unloaded) outer diameter ``R + 2 * aspect * W``, m."""
        return self.rim_diameter_m + 2.0 * self.section_height_mm / 1000.0

    @property
    def load_index(self) -> int | None:
        """Load index of the first service description, or None."""
        return self.service.load_index if self.service else None

    @property
    def load_kg(self) -> float | None:
        """Load capacity per tyre of the first service description, kg, or None."""
        return self.service.load_kg if self.service else None

    @property
    def speed_symbol(self) -> str | None:
        """Speed symbol of the first service description, or None."""
        return self.service.speed_symbol if self.service else None

    @property
    def speed_km_h(self) -> float | None:
        """Reference speed of the first service description, km/h, or None."""
        return self.service.speed_km_h if self.service else None

    @property
    def flexion_load_factor(self) -> float:
        """Load at the same pressure relative to a standard tyre of this size (IF 1.2, VF 1.4, else 1)."""
        return FLEXION_LOAD_FACTOR.get(self.flexion_class, 1.0)


def _tokens(text: str) -> list[str]:
    """Upper-case tokens; the size itself may contain spaces (``13.6 R 38``, ``480/70 R38``)."""
    t = re.sub(r"\s*([/R-])\s*(?=\d)", r"\1", text.upper().strip())
    t = re.sub(r"^(IF|VF|CFO|PFO)(?=\d)", r"\1 ", t)  # "IF710/70R42"
    return t.split()


def parse_tyre_size(text: str) -> TyreSize:
    """Parse a tyre size designation: inch, metric, markings and service description.

    Parameters
    ----------
    text : str
        Designations such as ``480/70R38``, ``IF 710/70R42 173D``,
        ``520/85R42 157A8/154B``, ``VF 600/70R30 CFO``, ``13.6R38``,
        ``13.6-38``, ``16.9/14R30``, ``11.2/10-24``, ``7.50-18``,
        ``18.4R38 146A8 R-1W``, ``13.6 R 38``.

    Returns
    -------
    TyreSize

    Raises
    ------
    TyreSizeError
        If the text is not a size designation; the message names the text
        (and the part that does not parse) and gives examples.

    See Also
    --------
    rolling_circumference_m : the circumference of a size.
    load_index_kg : a load index's capacity.

    Examples
    --------
    >>> parse_tyre_size("16.9/14R30").section_width_in
    16.9
    >>> s = parse_tyre_size("480/70R38 145D")
    >>> round(s.section_width_in, 2), s.aspect_ratio, s.rim_diameter_in, s.load_kg, s.speed_km_h
    (18.9, 0.7, 38.0, 2900, 65)
    """
    if not isinstance(text, str):
        raise TyreSizeError(f"tyre size {text!r} is not text ({_EXAMPLES})")
    tokens = _tokens(text)
    cores = [i for i, tok in enumerate(tokens) if _CORE.match(tok)]
    if len(cores) != 1:
        why = "no size in it" if not cores else "more than one size in it"
        raise TyreSizeError(f"tyre size {text!r} does not parse: {why} ({_EXAMPLES})")
    m = _CORE.match(tokens[cores[0]])
    first, second, rim = float(m["first"]), m["second"], float(m["rim"])
    metric = second is not None and first >= 100 and first.is_integer()
    aspect, stated, alt = DEFAULT_ASPECT_RATIO, False, None
    if metric:
        width = first / 25.4
        aspect, stated = float(second) / 100.0, True
    else:
        width = first
        if second is not None:
            s2 = float(second)
            if s2 > first and s2.is_integer() and int(s2) in _ASPECTS_INCH_WIDTH:
                aspect, stated = s2 / 100.0, True
            else:
                alt = s2
    if not (2.0 <= width <= 60.0 and 8.0 <= rim <= 60.0 and 0.2 <= aspect <= 1.2):
        raise TyreSizeError(
            f"tyre size {text!r} gives implausible W={width:.3g} in, R={rim:g} in, aspect {aspect:g} "
            f"(metric widths are in mm with an aspect ratio: {_EXAMPLES})"
        )
    markings: list[str] = []
    services: list[ServiceDescription] = []
    tread = ply = tubeless = None
    for tok in tokens[: cores[0]] + tokens[cores[0] + 1:]:
        if tok in _MARKINGS:
            markings.append(tok)
        elif (sm := _SERVICE.match(tok) or _SERVICE_OLD.match(tok)) and not services:
            services.append(ServiceDescription(int(sm["li"]), sm["ss"]))
            if sm.groupdict().get("li2"):
                services.append(ServiceDescription(int(sm["li2"]), sm["ss2"]))
        elif _TREAD.match(tok) and tread is None:
            tread = tok
        elif (pm := _PLY.match(tok)) and ply is None:
            ply = int(pm["ply"])
        elif tok in ("TL", "TT") and tubeless is None:
            tubeless = tok == "TL"
        else:
            raise TyreSizeError(
                f"tyre size {text!r} does not parse: {tok!r} is not a size, IF/VF/CFO/PFO, "
                f"load index + speed symbol, tread code or ply rating ({_EXAMPLES})"
            )
    for sd in services:
        if sd.load_index >= len(LOAD_INDEX_kg):
            raise TyreSizeError(f"tyre size {text!r}: load index {sd.load_index} is outside the ISO table (0-279)")
    flex = [k for k in markings if k in FLEXION_LOAD_FACTOR]
    if len(set(flex)) > 1:
        raise TyreSizeError(f"tyre size {text!r} is marked both IF and VF")
    return TyreSize(
        designation=text.strip(),
        section_width_in=width,
        rim_diameter_in=rim,
        construction="radial" if m["sep"] == "R" else "cross-ply",
        alternative_width_in=alt,
        aspect_ratio=aspect,
        aspect_ratio_stated=stated,
        metric=metric,
        flexion_class=flex[0] if flex else None,
        markings=tuple(markings),
        service=services[0] if services else None,
        alternative_service=services[1] if len(services) > 1 else None,
        tread_code=tread,
        ply_rating=ply,
        tubeless=tubeless,
    )


def rolling_circumference_m(size: TyreSize | str, aspect_ratio: float | None = None) -> float:
    """Estimated rolling circumference of a tyre, m.

    ``pi * (R + 2 * aspect * W) * 0.0254 * 0.956``: the free diameter from the
    size, reduced to the loaded rolling circumference (:data:`ROLLING_FACTOR`)
    so that a 13.6R38 gives the 4.66 m of thesis §4.5.1. The aspect ratio is
    the argument if given, else the size's (stated, or the inch-series 0.85).
    A ribbed front tyre has taller sidewalls: a 7.50-18 comes out at 2.35 m
    against the 2.63 m of §5.5.4, so a catalogue value is preferred where one
    is given.

    See Also
    --------
    tyre_rolling_circumference_m : a catalogue's value first.

    Examples
    --------
    >>> round(rolling_circumference_m("13.6R38"), 2)
    4.66
    >>> round(rolling_circumference_m("480/70R38"), 2)
    4.92
    """
    s = size if isinstance(size, TyreSize) else parse_tyre_size(size)
    a = s.aspect_ratio if aspect_ratio is None else float(aspect_ratio)
    if not 0.0 < a <= 2.0:
        raise ValueError(f"aspect_ratio {a} is outside (0, 2]")
    return math.pi * (s.rim_diameter_in + 2 * a * s.section_width_in) * 0.0254 * ROLLING_FACTOR


def _given(value) -> float | None:
    """A catalogue cell as a positive float, or None (blank, NaN, text, non-positive)."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) and v > 0 else None


def tyre_rolling_circumference_m(
    size: TyreSize | str, *, catalogue_m: float | None = None, outer_diameter_m: float | None = None
) -> float:
    """Rolling circumference of a catalogue tyre, m: the best of what the catalogue gives.

    The catalogue's ``rolling_circumference_m`` where given (thesis §4.5.1, or a
    user's measurement); else its measured ``outer_diameter_m`` times pi times
    :data:`ROLLING_FACTOR`; else :func:`rolling_circumference_m` from the size.

    See Also
    --------
    rolling_circumference_m : the estimate from the size alone.

    Examples
    --------
    >>> tyre_rolling_circumference_m("7.50-18", catalogue_m=2.63)
    2.63
    >>> round(tyre_rolling_circumference_m("480/70R38", outer_diameter_m=1.65), 3)
    4.956
    """
    if (c := _given(catalogue_m)) is not None:
        return c
    if (d := _given(outer_diameter_m)) is not None:
        return math.pi * d * ROLLING_FACTOR
    return rolling_circumference_m(size)


def lugs_per_side(circumference_m: float, *, ribbed: bool = False, catalogue: float | None = None) -> int:
    """Lugs on one side of a tyre's tread (lug passing per revolution, thesis §2.4.5).

    The catalogue's ``lugs_per_side`` where given; 0 for a ribbed tyre; else one
    lug every :data:`LUG_PITCH_m` of circumference, at least 8.

    See Also
    --------
    tyre_rolling_circumference_m : the circumference it takes.

    Examples
    --------
    >>> lugs_per_side(4.66), lugs_per_side(4.66, catalogue=22), lugs_per_side(2.63, ribbed=True)
    (23, 22, 0)
    """
    if (n := _given(catalogue)) is not None:
        return int(round(n))
    if ribbed:
        return 0
    circumference_m = _validate.positive("circumference_m", circumference_m)
    return max(int(round(circumference_m / LUG_PITCH_m)), 8)
