"""Thesis numbers the simulate stage needs when ``raw/published/*.csv`` are absent.

Transcribed from the thesis text (Lines 1991) for Tables XII, XIII, XIV, XV, XVI,
XVII, XVIII, XIX and XX, in the column layout of ``schemas/published`` where one is
announced (XIX, XX). The simulate stage prefers ``raw/published/table_*.csv`` (the
project's digitised tables) and falls back to these frames, recording which was
used. No file I/O here.
"""

from __future__ import annotations

import pandas as pd

__all__ = [
    "table_xii",
    "table_xii_stationary",
    "table_xiii",
    "table_xiv",
    "table_xv",
    "table_xvi",
    "table_xvii",
    "table_xviii",
    "table_xix",
    "table_xx",
]


def table_xii() -> pd.DataFrame:
    """Table XII: rolling T4 13.6R38 characteristics per nominal speed and load (§6.3).

    The stiffness is as quoted (before the 10 % slat-surface reduction).
    Table XI gives the heavy load as 2230 kg, Table XII as 2300 kg; the simulation
    used Table XII's.
    """
    rows = [
        (17.5, 4.927, 1860, 1.30, 380), (17.5, 5.017, 2300, 0.99, 315),
        (15.0, 4.242, 1860, 1.44, 383), (15.0, 4.307, 2300, 1.24, 317),
        (12.5, 3.354, 1860, 1.68, 386), (12.5, 3.460, 2300, 1.37, 320),
        (10.0, 2.728, 1860, 1.72, 388), (10.0, 2.861, 2300, 1.60, 324),
        (7.5, 2.072, 1860, 1.96, 393), (7.5, 2.133, 2300, 1.44, 331),
        (5.0, 1.374, 1860, 2.24, 403), (5.0, 1.409, 2300, 1.66, 334),
    ]  # fmt: skip
    df = pd.DataFrame(
        rows, columns=["speed_km_h", "actual_speed_m_s", "load_kg", "damping_kN_s_per_m", "stiffness_kN_per_m"]
    )
    df.insert(2, "load_condition", df["load_kg"].map({1860: "light", 2300: "heavy"}))
    df.insert(1, "pressure_bar", df["load_kg"].map({1860: 1.38, 2300: 1.03}))
    return df


def table_xii_stationary() -> pd.DataFrame:
    """Stationary T4 characteristics used for comparison at all speeds (§6.3)."""
    return pd.DataFrame(
        {
            "load_condition": ["light", "heavy"],
            "load_kg": [1860, 2300],
            "damping_kN_s_per_m": [3.42, 3.80],
            "stiffness_kN_per_m": [545.0, 450.0],
        }
    )


_QUANT = ["rms_acceleration", "sqrt_peak_height", "peak_frequency", "half_power_width_over_frequency"]
_STATS = ["mean_ratio_error", "sd_ratio_error", "p_within_10", "p_within_30"]


def _accuracy(values: list[tuple[float, float]], envelope: list[tuple[float, float]]) -> pd.DataFrame:
    rows = []
    it = iter(values)
    for q in _QUANT:
        for s in _STATS:
            r, st = next(it)
            rows.append((q, s, r, st))
    for (q, s), (r, st) in zip(
        [("envelope_correlation", "mean"), ("envelope_correlation", "sd"), ("envelope_error", "mean"), ("envelope_error", "sd")],
        envelope,
    ):
        rows.append((q, s, r, st))
    return pd.DataFrame(rows, columns=["quantity", "statistic", "thesis_rolling", "thesis_stationary"])


def table_xiii() -> pd.DataFrame:
    """Table XIII (surveyed profile). '>0.9999' is entered as 0.9999.

    The text's peak-frequency block is garbled in the source transcription
    ("standard deviation 0.01 1.21 / 0.01 0.07"); by analogy with Table XIV and
    §6.4.2 (stationary ≈ 20 % high) it reads: mean 1.00 / 1.21, sd 0.01 / 0.07,
    P(±10 %) >0.9999 / 0.07 (our reading), P(±30 %) >0.9999 / (illegible, left NaN).
    """
    nan = float("nan")
    return _accuracy(
        [
            (0.92, 1.03), (0.12, 0.17), (0.51, 0.44), (0.97, 0.92),
            (0.88, 0.84), (0.13, 0.25), (0.44, 0.26), (0.93, 0.68),
            (1.00, 1.21), (0.01, 0.07), (0.9999, 0.07), (0.9999, nan),
            (1.02, 1.15), (0.07, 0.24), (0.84, 0.28), (0.9999, 0.71),
        ],
        [(0.91, 0.84), (0.07, 0.04), (0.36, 0.63), (0.07, 0.08)],
    )  # fmt: skip


def table_xiv() -> pd.DataFrame:
    """Table XIV (recorded profile estimate). '>0.9999' entered as 0.9999."""
    return _accuracy(
        [
            (1.04, 1.13), (0.14, 0.20), (0.52, 0.31), (0.97, 0.78),
            (1.01, 0.91), (0.19, 0.26), (0.40, 0.28), (0.89, 0.72),
            (1.01, 1.21), (0.01, 0.07), (0.9999, 0.05), (0.9999, 0.89),
            (0.96, 1.09), (0.12, 0.38), (0.55, 0.20), (0.90, 0.50),
        ],
        [(0.93, 0.86), (0.04, 0.03), (0.38, 0.68), (0.10, 0.09)],
    )  # fmt: skip


def table_xv() -> pd.DataFrame:
    """Table XV: Massey Ferguson MF698T (§7.2). Distances from the rear axle."""
    return pd.DataFrame(
        {
            "load_condition": [1, 2, 3, 4],
            "mass_class": ["heavy", "heavy", "heavy", "light"],
            "front_pressure_bar": [3.45, 3.45, 2.76, 3.45],
            "rear_pressure_bar": [1.31, 2.07, 1.03, 1.31],
            "mass_kg": [5120.0, 5120.0, 5120.0, 3617.0],
            "pitch_inertia_kg_m2": [6210.0, 6210.0, 6210.0, 4414.0],
            "cg_height_m": [0.838, 0.838, 0.838, 0.903],
            "cg_to_rear_axle_m": [0.896, 0.896, 0.896, 0.873],
            "wheelbase_m": [2.436] * 4,
            "front_size": ["7.50-18"] * 4,
            "rear_size": ["13.6R38"] * 4,
        }
    )


def table_xvi() -> pd.DataFrame:
    """Table XVI: tyre characteristics used for the MF698T simulation (per tyre, §7.3).

    ``characteristics`` is ``rolling`` (per speed; stiffness already reduced 10 % on
    the slatted track SBT) or ``stationary`` (speed NaN, one row per load condition
    and track). Note Table XVI lists load condition 4 at 1.38/2.76 bar while
    Table XV gives 1.31/3.45 bar; kept as printed.
    """
    rolling = [
        (1, 1.31, 3.45, "SBT", [(10, 328, 426, 1.12, 1.47), (12.5, 324, 426, 0.96, 1.34), (15, 320, 426, 0.77, 1.20), (17.5, 317, 426, 0.67, 1.00), (20, 313, 426, 0.57, 0.79)]),
        (1, 1.31, 3.45, "HH", [(10, 364, 473, 1.12, 1.47), (12.5, 360, 473, 0.96, 1.34), (15, 356, 473, 0.77, 1.20), (17.5, 352, 473, 0.67, 1.00), (20, 348, 473, 0.57, 0.79)]),
        (2, 2.07, 3.45, "SBT", [(10, 417, 435, 1.43, 1.47), (12.5, 431, 435, 1.25, 1.34), (15, 446, 435, 1.08, 1.20)]),
        (2, 2.07, 3.45, "HH", [(12.5, 499, 483, 1.25, 1.33), (15, 495, 483, 1.08, 1.20), (17.5, 491, 483, 0.98, 1.00)]),
        (3, 1.03, 2.76, "SBT", [(10, 283, 345, 1.08, 1.17), (12.5, 279, 345, 0.90, 1.04), (15, 275, 345, 0.73, 0.90)]),
        (3, 1.03, 2.76, "HH", [(12.5, 310, 383, 0.90, 1.03), (15, 306, 383, 0.73, 0.90), (17.5, 302, 383, 0.53, 0.70)]),
        (4, 1.38, 2.76, "SBT", [(10, 339, 345, 0.83, 1.17), (12.5, 336, 345, 0.65, 1.04), (15, 332, 345, 0.48, 0.90)]),
        (4, 1.38, 2.76, "HH", [(12.5, 373, 383, 0.65, 1.03), (15, 369, 383, 0.48, 0.90), (17.5, 365, 383, 0.38, 0.70)]),
    ]  # fmt: skip
    stationary = {1: (446, 630, 2.2, 2.9), 2: (598, 630, 2.6, 2.9), 3: (390, 532, 2.1, 2.5), 4: (460, 532, 2.2, 2.5)}
    rows = []
    for lc, pr, pf, track, speeds in rolling:
        for sp, kr, kf, cr, cf in speeds:
            rows.append((lc, pr, pf, track, float(sp), "rolling", kr, kf, cr, cf))
    for lc, (kr, kf, cr, cf) in stationary.items():
        pr, pf = {1: (1.31, 3.45), 2: (2.07, 3.45), 3: (1.03, 2.76), 4: (1.38, 2.76)}[lc]
        rows.append((lc, pr, pf, "any", float("nan"), "stationary", kr, kf, cr, cf))
    return pd.DataFrame(
        rows,
        columns=[
            "load_condition", "rear_pressure_bar", "front_pressure_bar", "track", "speed_km_h", "characteristics",
            "rear_stiffness_kN_per_m", "front_stiffness_kN_per_m", "rear_damping_kN_s_per_m", "front_damping_kN_s_per_m",
        ],
    )  # fmt: skip


def table_xvii() -> pd.DataFrame:
    """Table XVII: tractor prediction accuracy (§7.4); NaN where not printed."""
    nan = float("nan")
    rows = [
        ("SBT", "vertical_rms", (1.13, 0.25, 0.28, 0.68), (0.97, 0.18, 0.41, 0.89)),
        ("SBT", "pitch_rms", (0.72, 0.13, 0.08, 0.58), (0.65, 0.13, 0.07, 0.35)),
        ("HH", "vertical_rms", (2.08, 0.33, nan, nan), (1.50, 0.25, nan, nan)),
        ("HH", "pitch_rms", (1.37, 0.23, nan, nan), (0.94, 0.18, nan, nan)),
        ("SBT", "first_peak_frequency", (1.02, 0.09, 0.74, 0.999), (1.20, 0.12, 0.19, 0.80)),
        ("SBT", "second_peak_frequency", (1.03, 0.08, 0.74, 0.999), (1.28, 0.10, 0.04, 0.56)),
        ("HH", "first_peak_frequency", (0.94, 0.09, 0.64, 0.998), (1.14, 0.16, 0.43, 0.84)),
        ("HH", "second_peak_frequency", (0.95, 0.12, 0.55, 0.98), (1.12, 0.12, 0.40, 0.93)),
    ]
    out = []
    for track, q, r, s in rows:
        for i, stat in enumerate(_STATS):
            out.append((track, q, stat, r[i], s[i]))
    return pd.DataFrame(out, columns=["track", "quantity", "statistic", "thesis_rolling", "thesis_stationary"])


def table_xviii() -> pd.DataFrame:
    """Table XVIII: longitudinal stiffness/damping sweep, 10 km/h, SBT, load condition 1.

    Kelvin-Voigt longitudinal element on the rear tyres (per tyre). Peak columns as
    printed (blank = NaN); the row/column alignment of the peaks in the source
    transcription is partly ambiguous.
    """
    nan = float("nan")
    rows = [
        (0, 0, 1.91, 1.50, 1.65, 2.21, nan),
        (455, 0, 1.68, 1.66, 1.65, 2.63, 3.27),
        (455, 1, 1.42, 1.34, 1.65, 2.58, 3.65),
        (455, 3, 1.25, 1.15, 1.68, 2.57, 3.66),
        (455, 5, 1.15, 1.06, 1.70, 2.48, 3.67),
        (0, 1, 1.84, 1.44, nan, 2.21, 3.10),
        (0, 3, 1.74, 1.35, nan, 2.19, 3.24),
        (0, 5, 1.65, 1.25, nan, 2.20, 3.31),
    ]
    df = pd.DataFrame(
        rows,
        columns=[
            "longitudinal_stiffness_kN_per_m", "longitudinal_damping_kN_s_per_m", "vertical_rms_m_s2",
            "pitch_rms_rad_s2", "peak_1_Hz", "peak_2_Hz", "peak_3_Hz",
        ],
    )  # fmt: skip
    measured = pd.DataFrame(
        [dict(longitudinal_stiffness_kN_per_m=nan, longitudinal_damping_kN_s_per_m=nan, vertical_rms_m_s2=1.79,
              pitch_rms_rad_s2=1.98, peak_1_Hz=nan, peak_2_Hz=2.15, peak_3_Hz=3.09)]
    )  # fmt: skip
    df["row"] = "predicted"
    measured["row"] = "measured"
    return pd.concat([df, measured], ignore_index=True)


def table_xix() -> pd.DataFrame:
    """Table XIX: tractor data (§8.2). County 774 front tyres water ballasted."""
    return pd.DataFrame(
        [
            ("Leyland 272", 3235, 2669, 1.33, 0.71, "7.50-16", 2.06, "13.6-38", 1.1, False, False),
            ("Massey Ferguson 590", 3434, 3946, 1.48, 0.81, "7.50-18", 2.3, "12-38", 1.3, False, False),
            ("Deutz Intrac 2004A", 3748, 3666, 1.16, 1.04, "10.5-20", 2.06, "16.9/14R30", 1.1, True, False),
            ("County 774", 4767, 3862, 0.81, 1.01, "13.6R38", 0.83, "13.6R38", 1.2, True, True),
            ("David Brown 996", 3573, 4315, 1.06, 1.04, "11.2/10-24", 1.7, "13.6/12-36", 1.5, True, False),
        ],
        columns=[
            "tractor", "mass_kg", "pitch_inertia_kg_m2", "front_distance_m", "rear_distance_m", "front_size",
            "front_pressure_bar", "rear_size", "rear_pressure_bar", "four_wheel_drive", "front_water_ballast",
        ],
    )  # fmt: skip


def table_xx() -> pd.DataFrame:
    """Table XX: stiffnesses, predicted and measured natural frequencies (§8.2)."""
    nan = float("nan")
    meas = {
        "Leyland 272": (2.4, 3.4),
        "Massey Ferguson 590": (2.7, 3.7),
        "Deutz Intrac 2004A": (3.0, 3.4),
        "County 774": (2.5, 3.3),
        "David Brown 996": (2.5, 3.0),
    }
    formula = [
        ("Leyland 272", 306, 247, 2.76, 3.50),
        ("Massey Ferguson 590", 314, 311, 2.70, 3.64),
        ("Deutz Intrac 2004A", 316, 273, 2.82, 3.14),
        ("County 774", 323, 323, 2.49, 2.78),
        ("David Brown 996", 365, 271, 2.71, 3.14),
    ]
    stationary = [
        ("Leyland 272", 340, 332, 2.92, 4.05),
        ("Massey Ferguson 590", 360, 377, 2.89, 4.01),
        ("Deutz Intrac 2004A", 465, 571, 3.57, 4.35),
        ("County 774", 564, 653, 3.55, 3.68),
        ("David Brown 996", 432, 332, 2.99, 3.42),
    ]
    rows = []
    for source, block in (("formula", formula), ("stationary_free_vibration", stationary)):
        for t, kr, kf, f1, f2 in block:
            m1, m2 = meas.get(t, (nan, nan))
            rows.append((t, source, float(kr), float(kf), f1, f2, m1, m2))
    return pd.DataFrame(
        rows,
        columns=[
            "tractor", "stiffness_source", "rear_stiffness_kN_per_m", "front_stiffness_kN_per_m",
            "predicted_frequency_1_Hz", "predicted_frequency_2_Hz", "measured_frequency_1_Hz", "measured_frequency_2_Hz",
        ],
    )  # fmt: skip
