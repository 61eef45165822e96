"""Tyre truth model of the virtual dynamic tyre test vehicle (thesis ch. 4 and 5).

The radial stiffness ``K`` and damping coefficient ``C`` of each of the 17 tyres
of Table II as pure functions of the test conditions: inflation pressure,
rolling speed, load, vibration amplitude, frequency, driving torque and surface.
Tyre-specific factors (age, wear, ply rating, lug length; §4.4, §5.4) enter
through the per-tyre calibration constants, which are taken from Tables III and
VII, and through :func:`aged` and :func:`buffed` for derived tyres.

The model is *calibrated*, not fitted: a straight-line regression of ``K`` on
pressure over nominal runs gives back Table III (stationary at 0 km/h, rolling
over pooled 10, 12.5 and 15 km/h runs) and a regression of ``C`` gives back
Table VII at its speeds, exactly (the constants are the printed values).

Nominal conditions (§3.5): concrete, 4 Hz, 14 mm peak-to-peak (5 mm rms), no
driving torque, load 18.3 kN. All secondary effects are zero there.

Units: inputs in thesis units (bar, km/h, kN, mm p-p, Hz, kNm); the constants are
stored in thesis units (kN/m, kN/m/bar, kNs/m); the public functions return SI
(N/m, N s/m). The module reads no files; ``tests/rig/test_truth.py`` cross-checks
the constants against ``raw/published/table_iii.csv`` and ``table_vii.csv``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..tyre.sizes import DEFAULT_ASPECT_RATIO, parse_tyre_size, rolling_circumference_m
from ..units import m_s_to_km_h

__all__ = ["NOMINAL_FREQUENCY_HZ", "NOMINAL_AMPLITUDE_MM_PP", "NOMINAL_LOAD_KN", "NOMINAL_PRESSURE_BAR",
    "REFERENCE_SURFACE", "SURFACE_STIFFNESS_CHANGE", "SURFACE_DAMPING_CHANGE", "SURFACES", "TyreParams",
    "TYRES", "SILSOE_TYRES", "BERLIN_TYRES", "aged", "buffed", "onset_shape", "carcass_stiffness_kN_per_m",
    "carcass_damping_kN_s_per_m", "tyre_params", "stiffness", "damping", "truth_frame"]

# --------------------------------------------------------------------------- #
# Nominal conditions (§3.5, §4.3.3)
NOMINAL_FREQUENCY_HZ = 4.0  # §3.5: "a frequency of 4 Hz"
NOMINAL_AMPLITUDE_MM_PP = 14.0  # §3.5: 5 mm rms = 14.1 mm p-p of a sinusoid
NOMINAL_LOAD_KN = 18.3  # §4.3.3 middle load; Table I: 1860 kg
NOMINAL_PRESSURE_BAR = 1.38  # 20 psi, Fig. 21, Fig. 34, Table I
REFERENCE_SURFACE = "concrete"

# Speed shape of the carcass stiffness (§4.3.2, §4.5.1, Fig. 21, Table VI) ---- #
#: Table VI: "Rolling speed 10-15 km/h: -8 (total)" kN/m. The drift is a tanh
#: centred on 12.5 km/h so that pooled 10/12.5/15 km/h runs average to the
#: Table III rolling value; it saturates at +-_DRIFT_AMP_KN beyond (§4.3.2:
#: "between 10 and 50 km/h the tyre stiffness remains almost constant").
_DRIFT_WIDTH_KMH = 5.0
_DRIFT_AMP_KN = 8.0 / (2.0 * math.tanh(2.5 / _DRIFT_WIDTH_KMH))
_DRIFT_CENTRE_KMH = 12.5
#: §4.5.1: "a 25% decrease in carcass stiffness between the speeds of 0 and 1 km/h".
_ONSET_DROP = 0.25
_FAST_KMH = 0.2  # e-folding speed of the fast (creep) part of the drop, Fig. 21
_SLOW_KMH = 8.0  # the slow part is complete by 8 km/h (plateau from 10 km/h, §4.3.2)

# Damping speed shape (§5.3.2, §5.5.4, Fig. 34, Fig. 49) -------------------- #
#: §5.5.4: damping maximum at 0.04 +- 0.005 rev/s for T1-T5 and F1.
_PEAK_REV_S = 0.04
#: §5.3.2: the rise is "from no observable increase to as much as 10%".
_PEAK_RISE = 0.05
#: §5.3.2: back to the non-rolling level at about 2 km/h for 13.6R38
#: (0.6 km/h peak) -> three times the peak speed.
_BACK_FACTOR = 3.0
#: Stationary carcass damping / carcass damping at 10 km/h for traction tyres,
#: derived from Table I (apparent mass, T1 stationary, 1.38 bar: 3.0 kNs/m) with
#: the pressure dependence at 0 km/h equal to that at 10 km/h (F1, Table VII:
#: 0.39 vs 0.32) -> (3.0 - 0.44*1.38)/1.63. Gives T2 a 0-15 km/h fall of 1.9
#: kNs/m, matching Table X "Rolling speed 0-15 km/h: -2 (total)".
_STATIONARY_DAMPING_RATIO = (3.0 - 0.44 * 1.38) / 1.63
#: Beyond the last tabulated speed the damping keeps falling (§5.3.2, Kising up
#: to 50 km/h) exponentially at the relative rate of the last two nodes,
#: bounded to this range (1/km/h).
_EXTRAP_RATE_RANGE = (0.005, 0.08)

# Amplitude (Tables IV, VIII), speeds 0, 1, 10, 15 km/h, slopes per mm p-p ---- #
_AMPLITUDE_SPEEDS = (0.0, 1.0, 10.0, 15.0)
_K_AMPLITUDE = {  # Table IV, kN/m per mm
    "T1": (-1.6, -0.41, -0.24, -0.39),
    "T2": (-9.8, -0.21, 0.53, -0.21),
    "T3": (-2.4, -0.35, 0.81, 0.76),
    "F1": (-15.5, -1.59, -1.09, -0.86),
}
_C_AMPLITUDE = {  # Table VIII, kNs/m per mm (printed without leading zero/sign: '-.010')
    "T1": (-0.010, -0.007, 0.017, 0.024),
    "T2": (-0.142, -0.049, -0.042, -0.030),
    "T3": (-0.034, -0.025, 0.002, 0.008),
    "F1": (-0.105, -0.036, 0.018, 0.012),
}
#: Tyres not in Tables IV/VIII: traction tyres take the mean of T1 and T3 (T2 is
#: "a peculiarity", §4.4.4); the ribbed front tyre has its own row.
_K_AMPLITUDE["traction"] = tuple((a + b) / 2 for a, b in zip(_K_AMPLITUDE["T1"], _K_AMPLITUDE["T3"]))
_C_AMPLITUDE["traction"] = tuple((a + b) / 2 for a, b in zip(_C_AMPLITUDE["T1"], _C_AMPLITUDE["T3"]))

# Frequency (§4.3.5, §4.5.1, §5.3.5), exponent of (f / 4 Hz) at 0, 1, >=10 km/h #
_FREQ_SPEEDS = (0.0, 1.0, 10.0)
#: §4.3.5: stationary +10 %/octave, 10 km/h "less than 6 %/octave" (5 % used);
#: §4.5.1: 1 km/h about 2.5 %/Hz (~9 %/octave at 4 Hz). Table VI: +5 kN/m per Hz.
_K_FREQ_EXPONENT = (math.log2(1.10), math.log2(1.09), math.log2(1.05))
#: §5.3.5: stationary damping falls "by more than 50 %/octave", rolling at
#: 10 km/h about 20 %/octave. Table X: -0.3 kNs/m per Hz.
_C_FREQ_EXPONENT = (1.0, 0.8, math.log2(1.0 / 0.8))

# Load (§4.3.3, §5.3.3, Table VI, Table X) --------------------------------- #
#: §4.3.3/Fig. 22: a small stiffness increase with load when stationary and at
#: low speed, none at 10-15 km/h (Table VI "(none)"): 3 kN/m per kN x onset shape.
_K_LOAD_KN_PER_M_PER_KN = 3.0
#: §5.3.3: +0.05 to 0.2 kNs/m per kN; Table X: +0.1 /kN.
_C_LOAD_KNS_PER_M_PER_KN = 0.1

# Torque (§4.3.6, §5.3.6, Table X) ----------------------------------------- #
#: §4.3.6: no significant stiffness change up to 4.7 kNm. §5.3.6: damping at
#: >= 8 km/h falls 0.06-0.15 kNs/m per kNm (Table X: -0.1), at 1 km/h between
#: no change and +0.04 (0.02 used).
_C_TORQUE_SPEEDS = (0.0, 1.0, 8.0)
_C_TORQUE = (0.0, 0.02, -0.10)  # kNs/m per kNm

# Surfaces (Table V stiffness change on T5, Table IX damping change on T4/T5) #
#: Table V names are lost in the OCR; the changes are assigned in Table IX's
#: surface order (as raw/published/table_v.csv does). Table IX prints '-' for
#: the rough track ("no consistent change", §5.3.7): 0 used.
SURFACE_STIFFNESS_CHANGE = {
    "concrete": 0.0,
    "dry_farm_track": 0.0,
    "hard_parkland_grass": -0.03,
    "pasture_grass": -0.03,
    "dry_cultivated_land": -0.05,
    "dry_seedbed": -0.05,
    "stubble_field": -0.07,
    "artificial_rough_track": -0.10,  # §4.6: "reduces the effective stiffness by 10%"
}
SURFACE_DAMPING_CHANGE = {
    "concrete": 0.0,
    "dry_farm_track": 0.0,
    "hard_parkland_grass": 0.20,
    "pasture_grass": 0.20,
    "dry_cultivated_land": 1.90,
    "dry_seedbed": 0.80,
    "stubble_field": 0.20,
    "artificial_rough_track": 0.0,
}
SURFACES = tuple(SURFACE_STIFFNESS_CHANGE)


@dataclass(frozen=True)
class TyreParams:
    """Calibration constants of one tyre.

    Attributes
    ----------
    tyre_id, size : str
        Table II identity.
    group : str
        ``rear_traction``, ``front_traction`` or ``front_ribbed``.
    ply_rating : int
    age_years : float
        Table II; Berlin tyres are new (0).
    lug_height_mm : float
        Table II (Berlin tyres: 45 mm assumed as for new Silsoe tyres; AS3 buffed 0).
    circumference_m : float
        Rolling circumference (§4.5.1, §5.5.4: 4.66 m for 13.6R38, 2.63 m for F1;
        others from the size, see :func:`tyrelab.tyre.sizes.rolling_circumference_m`).
    pressure_range_bar : tuple of float
        Range of the pressure sweeps.
    k_stationary, k_rolling : tuple of float
        (carcass stiffness kN/m, pressure dependence kN/m/bar), Table III.
    damping_nodes : tuple
        ((speed km/h, carcass damping kNs/m, pressure dependence kNs/m/bar), ...),
        Table VII or derived; must include 0 km/h.
    source : str
        Where the constants come from.
    """

    tyre_id: str
    size: str
    group: str
    ply_rating: int
    age_years: float
    lug_height_mm: float
    circumference_m: float
    pressure_range_bar: tuple[float, float]
    k_stationary: tuple[float, float]
    k_rolling: tuple[float, float]
    damping_nodes: tuple[tuple[float, float, float], ...]
    source: str = ""
    notes: str = field(default="", compare=False)

    @property
    def traction(self) -> bool:
        """Whether the tyre has traction lugs (wheel-rotation *and* lug excitation)."""
        return self.group != "front_ribbed" and self.lug_height_mm > 0


def _new_tyre_damping(ply: int, factor: float = 1.0) -> tuple[tuple[float, float, float], ...]:
    """Derived Table VII rows for the (new) Berlin tyres, which have none.

    New 8-ply traction tyre = mean of the new Silsoe tyres T3 and T5 (Table VII);
    6-ply: carcass damping 0.3 kNs/m lower (§5.4.2, Table X "+0.15 /ply");
    ``factor`` for lugs (§5.4.3: lugs give ~30 % of the damping of a new tyre).
    Stationary row from :data:`_STATIONARY_DAMPING_RATIO`.
    """
    c10, d10 = (0.67 + 0.49) / 2, (0.31 + 0.35) / 2
    c15, d15 = (0.67 + 0.32) / 2, (0.36 + 0.37) / 2
    if ply <= 6:
        c10, c15 = c10 - 0.3, c15 - 0.3
    rows = ((10.0, c10, d10), (15.0, c15, d15))
    rows = tuple((v, c * factor, d * factor) for v, c, d in rows)
    return ((0.0, rows[0][1] * _STATIONARY_DAMPING_RATIO, rows[0][2]),) + rows


def _silsoe_damping(rows: tuple[tuple[float, float, float], ...]) -> tuple[tuple[float, float, float], ...]:
    """Table VII rows plus the derived stationary row (see _STATIONARY_DAMPING_RATIO)."""
    if rows[0][0] == 0.0:
        return rows
    v10, c10, d10 = rows[0]
    return ((0.0, c10 * _STATIONARY_DAMPING_RATIO, d10),) + rows


_C13_6R38 = 4.66  # §4.5.1, §5.5.4
_SILSOE_P = (0.83, 1.93)  # 12-28 psi, Table VI ".7-2 bar"
_F1_P = (1.38, 2.62)  # 20-38 psi: front tyre runs at higher pressure
_BERLIN_P = (0.8, 2.0)


def _t(tyre_id, size, group, ply, age, lug, circ, prange, kst, kro, damp, source, notes=""):
    """A :class:`TyreParams`; ``circ`` None (or an aspect ratio given as ``("aspect", a)``)
    estimates the rolling circumference from the size (:func:`tyrelab.tyre.sizes.rolling_circumference_m`)."""
    if circ is None or isinstance(circ, tuple):
        aspect = circ[1] if isinstance(circ, tuple) else DEFAULT_ASPECT_RATIO
        circ = rolling_circumference_m(parse_tyre_size(size), aspect)
    return TyreParams(tyre_id, size, group, ply, age, lug, circ, prange, kst, kro, damp, source, notes)


#: The 17 tyres of Table II. k_* from Table III (kN/m, kN/m/bar); damping rows
#: from Table VII (kNs/m, kNs/m/bar) or derived as documented.
TYRES: dict[str, TyreParams] = {
    p.tyre_id: p
    for p in [
        _t("T2", "13.6R38", "rear_traction", 6, 16, 20, _C13_6R38, _SILSOE_P, (393, 166), (150, 217),
           _silsoe_damping(((10, 2.09, 0.59), (15, 1.26, 0.53))), "Table III, VII",
           "stationary K_c printed '39^3', read as 393"),
        _t("T1", "13.6R38", "rear_traction", 8, 11, 42, _C13_6R38, _SILSOE_P, (396, 172), (141, 175),
           _silsoe_damping(((10, 1.63, 0.44), (15, 1.31, 0.39), (20, 0.91, 0.44))), "Table III, VII"),
        # T4: Table III prints no stationary values. Carcass stiffness interpolated in
        # age between T3 (4 y, 184) and T1 (11 y, 396) at 9 years (Fig. 26: stationary
        # carcass stiffness rises with age); pressure dependence = mean of the T1,
        # T3, T5 stationary values (§4.4.4: independent of age).
        _t("T4", "13.6R38", "rear_traction", 6, 9, 38, _C13_6R38, _SILSOE_P,
           (184 + (396 - 184) * 5 / 7, (172 + 200 + 174) / 3), (145, 179),
           _silsoe_damping(((10, 1.00, 0.43), (15, 0.75, 0.40))), "Table III rolling, VII; stationary derived"),
        _t("T3", "13.6R38", "rear_traction", 8, 4, 45, _C13_6R38, _SILSOE_P, (184, 200), (112, 177),
           _silsoe_damping(((10, 0.67, 0.31), (15, 0.67, 0.36))), "Table III, VII"),
        _t("T5", "13.6R38", "rear_traction", 8, 1, 45, _C13_6R38, _SILSOE_P, (176, 174), (80, 181),
           _silsoe_damping(((10, 0.49, 0.35), (15, 0.32, 0.37))), "Table III, VII"),
        _t("F1", "7.50-18", "front_ribbed", 8, 0, 0, 2.63, _F1_P, (96, 158), (-3, 134),
           ((0, 1.34, 0.39), (10, 0.30, 0.32), (15, -0.15, 0.38)), "Table III, VII"),
        _t("AS2", "16.9R34", "rear_traction", 6, 0, 45, None, _BERLIN_P,
           (145, 139), (112, 191), _new_tyre_damping(6), "Table III; damping derived (§5.3.1, §5.4.2, Table X)"),
        # AS12: 30 % lower tread -> 30 % of the 30 % lug share of damping (§5.4.3)
        _t("AS12", "16.9R34", "rear_traction", 6, 0, 31.5, None, _BERLIN_P,
           (159, 129), (112, 194), _new_tyre_damping(6, 1 - 0.3 * 0.3), "Table III; damping derived"),
        # AS3: buffed, lugs give ~30 % of the damping of a new tyre (§5.4.3, Fig. 40)
        _t("AS3", "16.9R34", "rear_traction", 6, 0, 0, None, _BERLIN_P,
           (125, 116), (55, 182), _new_tyre_damping(6, 0.7), "Table III; damping derived (§5.4.3)"),
        _t("AS10", "18.4R38", "rear_traction", 8, 0, 45, None, _BERLIN_P,
           (190, 116), (114, 197), _new_tyre_damping(8), "Table III; damping derived"),
        _t("AS11", "13.6-38", "rear_traction", 6, 0, 45, _C13_6R38, _BERLIN_P,
           (121, 181), (108, 201), _new_tyre_damping(6), "Table III; damping derived"),
        _t("AS9", "9.5R44", "rear_traction", 8, 0, 45, None, _BERLIN_P,
           (86, 134), (99, 141), _new_tyre_damping(8), "Table III; damping derived"),
        _t("AS6", "14.9R24", "front_traction", 6, 0, 45, ("aspect", 0.70), _BERLIN_P,  # aspect 0.70: "70 % low aspect ratio", Table II
           (125, 139), (131, 109), _new_tyre_damping(6), "Table III; damping derived"),
        # AS4: no stationary values in Table III. Same size and construction as AS8:
        # AS8's stationary-minus-rolling differences (-73 kN/m, +68 kN/m/bar) applied.
        _t("AS4", "13.6R24", "front_traction", 6, 0, 45, None, _BERLIN_P,
           (120 + (59 - 132), 98 + (166 - 98)), (120, 98), _new_tyre_damping(6),
           "Table III rolling; stationary derived from AS8; damping derived"),
        _t("AS8", "13.6R24", "front_traction", 6, 0, 45, None, _BERLIN_P,
           (59, 166), (132, 98), _new_tyre_damping(6), "Table III; damping derived"),
        _t("AS7", "13.6-24", "front_traction", 6, 0, 45, None, _BERLIN_P,
           (94, 189), (131, 107), _new_tyre_damping(6), "Table III; damping derived"),
        # AS1: no stationary values. Cross-ply front traction tyre like AS7: AS7's
        # stationary-minus-rolling differences (-37 kN/m, +82 kN/m/bar) applied.
        _t("AS1", "12.4-28", "front_traction", 6, 0, 45, None, _BERLIN_P,
           (134 + (94 - 131), 112 + (189 - 107)), (134, 112), _new_tyre_damping(6),
           "Table III rolling; stationary derived from AS7; damping derived"),
    ]
}
SILSOE_TYRES = ("T1", "T2", "T3", "T4", "T5", "F1")
BERLIN_TYRES = tuple(t for t in TYRES if t.startswith("AS"))


def aged(tyre: TyreParams, years: float) -> TyreParams:
    """The same tyre ``years`` older (§4.4.4, §5.4.1).

    Rolling carcass stiffness +5.6 kN/m per year (§4.4.4, Fig. 26); the stationary
    carcass stiffness is "more dependent on tyre age": twice that rate is used.
    Pressure dependences unchanged (§4.4.4). Carcass damping +2 kNs/m from new to
    very worn (Table X) over the 16 years of T2: +0.125 kNs/m per year (Fig. 39).
    """
    ks, kr = tyre.k_stationary, tyre.k_rolling
    rows = tuple((v, c + 0.125 * years, d) for v, c, d in tyre.damping_nodes)
    return replace(tyre, age_years=tyre.age_years + years,
                   k_stationary=(ks[0] + 11.2 * years, ks[1]), k_rolling=(kr[0] + 5.6 * years, kr[1]),
                   damping_nodes=rows)


def buffed(tyre: TyreParams) -> TyreParams:
    """The same tyre with its lugs removed (§4.4.5, §5.4.3; AS2 -> AS3).

    Carcass stiffness halved, pressure dependence unchanged (§4.4.5); damping
    -30 % (lugs give about 30 % of the damping of a new tyre below 30 km/h).
    """
    ks, kr = tyre.k_stationary, tyre.k_rolling
    rows = tuple((v, 0.7 * c, 0.7 * d) for v, c, d in tyre.damping_nodes)
    return replace(tyre, lug_height_mm=0.0, k_stationary=(ks[0] / 2, ks[1]), k_rolling=(kr[0] / 2, kr[1]),
                   damping_nodes=rows)


# --------------------------------------------------------------------------- #
def _drift(v: float) -> float:
    """Plateau drift of the carcass stiffness, kN/m (Table VI: -8 over 10-15 km/h)."""
    return -_DRIFT_AMP_KN * math.tanh((v - _DRIFT_CENTRE_KMH) / _DRIFT_WIDTH_KMH)


def _slow(v: float) -> float:
    return max(0.0, 1.0 - v / _SLOW_KMH) ** 2


def _onset_fraction(tyre: TyreParams) -> float:
    """Weight of the fast part of the stationary->rolling transition.

    Chosen so the carcass stiffness falls by 25 % between 0 and 1 km/h (§4.5.1);
    clipped to [0, 1] (tyres whose stationary carcass stiffness is close to or
    below the rolling one, e.g. AS8, then change mostly in the first km/h).
    """
    ks, kr = tyre.k_stationary[0], tyre.k_rolling[0]
    span = ks - kr - _drift(0.0)
    if abs(span) < 1e-9:
        return 0.5
    g1 = ((1 - _ONSET_DROP) * ks - kr - _drift(1.0)) / span
    e1, s1 = math.exp(-1.0 / _FAST_KMH), _slow(1.0)
    return float(np.clip((s1 - g1) / (s1 - e1), 0.0, 1.0))


def onset_shape(tyre: TyreParams, speed_km_h: float) -> float:
    """Stationary->rolling weight g(v): 1 at rest, 0 from 8 km/h (Fig. 21)."""
    a = _onset_fraction(tyre)
    v = max(float(speed_km_h), 0.0)
    return a * math.exp(-v / _FAST_KMH) + (1 - a) * _slow(v)


def carcass_stiffness_kN_per_m(tyre: TyreParams, speed_km_h: float) -> tuple[float, float]:
    """Carcass stiffness K_c(v) (kN/m) and pressure dependence dK_p(v) (kN/m/bar).

    ``K_c(0)`` = Table III stationary; 10-15 km/h = Table III rolling +- 4 kN/m
    (Table VI drift, centred on 12.5 km/h).
    """
    g = onset_shape(tyre, speed_km_h)
    ks, kr = tyre.k_stationary, tyre.k_rolling
    kc = kr[0] + _drift(speed_km_h) + (ks[0] - kr[0] - _drift(0.0)) * g
    dk = kr[1] + (ks[1] - kr[1]) * g
    return kc, dk


def _interp(x: float, xs, ys) -> float:
    return float(np.interp(x, xs, ys))


def _damping_nodes_at(tyre: TyreParams, v: float) -> tuple[float, float]:
    """Carcass damping and pressure dependence at speed v, before the low-speed bump."""
    rows = sorted(tyre.damping_nodes)
    vs = [r[0] for r in rows]
    cc = [r[1] for r in rows]
    dc = [r[2] for r in rows]
    v_back = _BACK_FACTOR * _peak_speed_km_h(tyre)
    if v <= v_back:
        return cc[0], dc[0]
    if v <= vs[-1]:
        # stationary level held until v_back (§5.3.2), then linear through the nodes
        xs = [v_back] + vs[1:]
        return _interp(v, xs, [cc[0]] + cc[1:]), _interp(v, xs, [dc[0]] + dc[1:])
    # beyond the last node: exponential decay at the last relative rate
    c_last = cc[-1] + dc[-1] * NOMINAL_PRESSURE_BAR
    c_prev = cc[-2] + dc[-2] * NOMINAL_PRESSURE_BAR
    rate = math.log(max(c_prev, 1e-3) / max(c_last, 1e-3)) / (vs[-1] - vs[-2])
    rate = float(np.clip(rate, *_EXTRAP_RATE_RANGE))
    f = math.exp(-rate * (v - vs[-1]))
    return cc[-1] * f, dc[-1] * f


def _peak_speed_km_h(tyre: TyreParams) -> float:
    """Speed of the damping maximum: 0.04 rev/s (§5.5.4) -> km/h."""
    return m_s_to_km_h(_PEAK_REV_S * tyre.circumference_m)


def _bump(tyre: TyreParams, v: float) -> float:
    """Low-speed damping rise: 0 at rest, +_PEAK_RISE at 0.04 rev/s, 0 again at 3x."""
    vp = _peak_speed_km_h(tyre)
    if v <= 0:
        return 0.0
    if v <= vp:
        return _PEAK_RISE * v / vp
    if v <= _BACK_FACTOR * vp:
        return _PEAK_RISE * (_BACK_FACTOR * vp - v) / ((_BACK_FACTOR - 1) * vp)
    return 0.0


def carcass_damping_kN_s_per_m(tyre: TyreParams, speed_km_h: float) -> tuple[float, float]:
    """Carcass damping C_c(v) (kNs/m) and pressure dependence dC(v) (kNs/m/bar).

    Equal to Table VII at its speeds (linear in between); stationary level up to
    ~2 km/h with the 0.04 rev/s maximum of §5.5.4; falling beyond the last node.
    """
    v = max(float(speed_km_h), 0.0)
    cc, dc = _damping_nodes_at(tyre, v)
    b = 1.0 + _bump(tyre, v)
    return cc * b, dc * b


def _lookup(tyre_id: str, table: dict, group: str) -> tuple:
    if tyre_id in table:
        return table[tyre_id]
    return table["F1"] if group == "front_ribbed" else table["traction"]


def _surface(surface: str, table: dict) -> float:
    try:
        return table[surface]
    except KeyError:
        raise ValueError(f"unknown surface {surface!r}; known: {', '.join(table)}") from None


def tyre_params(tyre_id: str) -> TyreParams:
    """The calibration constants of a Table II tyre."""
    try:
        return TYRES[tyre_id]
    except KeyError:
        raise ValueError(f"unknown tyre {tyre_id!r}; known: {', '.join(TYRES)}") from None


def stiffness(
    tyre: str | TyreParams,
    pressure_bar: float,
    speed_km_h: float = 0.0,
    load_kN: float = NOMINAL_LOAD_KN,
    amplitude_mm_pp: float = NOMINAL_AMPLITUDE_MM_PP,
    frequency_Hz: float = NOMINAL_FREQUENCY_HZ,
    torque_kNm: float = 0.0,
    surface: str = REFERENCE_SURFACE,
) -> float:
    """Radial tyre stiffness K (N/m) under the given conditions.

    ``K = [K_c(v) + dK_p(v) P + load + amplitude terms] * (f/4)^a(v) * (1 + surface)``;
    K_c, dK_p from Table III (:func:`carcass_stiffness_kN_per_m`), amplitude
    Table IV, frequency §4.3.5, load §4.3.3, surface Table V, torque none (§4.3.6).
    """
    p = tyre if isinstance(tyre, TyreParams) else tyre_params(tyre)
    v = max(float(speed_km_h), 0.0)
    kc, dk = carcass_stiffness_kN_per_m(p, v)
    k = kc + dk * pressure_bar
    k += _K_LOAD_KN_PER_M_PER_KN * (load_kN - NOMINAL_LOAD_KN) * onset_shape(p, v)
    k += _interp(v, _AMPLITUDE_SPEEDS, _lookup(p.tyre_id, _K_AMPLITUDE, p.group)) * (
        amplitude_mm_pp - NOMINAL_AMPLITUDE_MM_PP
    )
    k *= (frequency_Hz / NOMINAL_FREQUENCY_HZ) ** _interp(v, _FREQ_SPEEDS, _K_FREQ_EXPONENT)
    k *= 1.0 + _surface(surface, SURFACE_STIFFNESS_CHANGE)
    return max(k, 10.0) * 1e3


def damping(
    tyre: str | TyreParams,
    pressure_bar: float,
    speed_km_h: float = 0.0,
    load_kN: float = NOMINAL_LOAD_KN,
    amplitude_mm_pp: float = NOMINAL_AMPLITUDE_MM_PP,
    frequency_Hz: float = NOMINAL_FREQUENCY_HZ,
    torque_kNm: float = 0.0,
    surface: str = REFERENCE_SURFACE,
) -> float:
    """Radial tyre damping coefficient C (N s/m) under the given conditions.

    ``C = [C_c(v) + dC(v) P + load + amplitude + torque terms] * (f/4)^-b(v) * (1 + surface)``;
    C_c, dC from Table VII (:func:`carcass_damping_kN_s_per_m`), load §5.3.3,
    amplitude Table VIII, torque §5.3.6, frequency §5.3.5, surface Table IX.
    """
    p = tyre if isinstance(tyre, TyreParams) else tyre_params(tyre)
    v = max(float(speed_km_h), 0.0)
    cc, dc = carcass_damping_kN_s_per_m(p, v)
    c = cc + dc * pressure_bar
    c += _C_LOAD_KNS_PER_M_PER_KN * (load_kN - NOMINAL_LOAD_KN)
    c += _interp(v, _AMPLITUDE_SPEEDS, _lookup(p.tyre_id, _C_AMPLITUDE, p.group)) * (
        amplitude_mm_pp - NOMINAL_AMPLITUDE_MM_PP
    )
    c += _interp(v, _C_TORQUE_SPEEDS, _C_TORQUE) * torque_kNm
    c *= (frequency_Hz / NOMINAL_FREQUENCY_HZ) ** (-_interp(v, _FREQ_SPEEDS, _C_FREQ_EXPONENT))
    c *= 1.0 + _surface(surface, SURFACE_DAMPING_CHANGE)
    return max(c, 0.02) * 1e3


def truth_frame(plan) -> "pd.DataFrame":
    """K and C (SI) for every row of a plan/manifest DataFrame.

    Returns a DataFrame indexed like ``plan`` with ``stiffness_N_per_m`` and
    ``damping_N_s_per_m`` (NaN for calibration rows).
    """
    import pandas as pd

    ks, cs = [], []
    for row in plan.itertuples(index=False):
        if getattr(row, "kind", "measurement") != "measurement":
            ks.append(np.nan)
            cs.append(np.nan)
            continue
        args = (row.tyre_id, row.pressure_bar, row.speed_km_h, row.load_kN, row.amplitude_mm_pp,
                row.excitation_frequency_Hz, row.torque_kNm, row.surface)
        ks.append(stiffness(*args))
        cs.append(damping(*args))
    return pd.DataFrame({"stiffness_N_per_m": ks, "damping_N_s_per_m": cs}, index=plan.index)
