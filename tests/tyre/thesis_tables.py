"""Literal thesis tables for tests (Table II sizes/ages, Table III as printed, thesis §4.2, §4.3.1)."""

import pandas as pd

# tyre, Table III size, stationary Kc, dKp, r2, rolling Kc, dKp, r2  (">0.99" -> 0.99)
TABLE_III_ROWS = [
    ("T2", "13.6R38", 393, 166, 0.99, 150, 217, 0.99), ("T1", "13.6R38", 396, 172, 0.99, 141, 175, 0.99),
    ("T4", "13.6R38", None, None, None, 145, 179, 0.99), ("T3", "13.6R38", 184, 200, 0.99, 112, 177, 0.99),
    ("T5", "13.6R38", 176, 174, 0.96, 80, 181, 0.99), ("F1", "7.5-18", 96, 158, 0.96, -3, 134, 0.99),
    ("AS2", "16.9R34", 145, 139, 0.99, 112, 191, 0.99), ("AS12", "16.9R34", 159, 129, 0.99, 112, 194, 0.98),
    ("AS3", "16.9R34", 125, 116, 0.99, 55, 182, 0.99), ("AS10", "18.4R38", 190, 116, 0.99, 114, 197, 0.99),
    ("AS11", "13.6R38", 121, 181, 0.96, 108, 201, 0.99), ("AS9", "9.5R44", 86, 134, 0.99, 99, 141, 0.99),
    ("AS1", "12.4R28", None, None, None, 134, 112, 0.96), ("AS6", "14.9R24", 125, 139, 0.99, 131, 109, 0.99),
    ("AS4", "13.6R24", None, None, None, 120, 98, 0.99), ("AS8", "13.6R24", 59, 166, 0.99, 132, 98, 0.99),
    ("AS7", "13.6R24", 94, 189, 0.99, 131, 107, 0.99),
]


def table_iii() -> pd.DataFrame:
    rows = []
    for t, size, skc, sdk, sr2, rkc, rdk, rr2 in TABLE_III_ROWS:
        if skc is not None:
            rows.append((t, size, "stationary", skc, sdk, sr2))
        rows.append((t, size, "rolling", rkc, rdk, rr2))
    return pd.DataFrame(rows, columns=["tyre_id", "size", "condition", "carcass_stiffness_kN_per_m",
                                       "pressure_dependence_kN_per_m_bar", "r_squared"])


def tyres() -> pd.DataFrame:
    """Table II: sizes as in Table II (AS11 13.6-38, AS7 13.6-24, AS1 12.4-28), ages of T1-T5."""
    rows = [("T2", "13.6R38", "rear", 16), ("T1", "13.6R38", "rear", 11), ("T4", "13.6R38", "rear", 9),
            ("T3", "13.6R38", "rear", 4), ("T5", "13.6R38", "rear", 1), ("F1", "7.50-18", "front undriven", None),
            ("AS10", "18.4R38", "rear", None), ("AS2", "16.9R34", "rear", None), ("AS12", "16.9R34", "rear", None),
            ("AS3", "16.9R34", "rear", None), ("AS11", "13.6-38", "rear", None), ("AS9", "9.5R44", "rear", None),
            ("AS6", "14.9R24", "front", None), ("AS4", "13.6R24", "front", None), ("AS8", "13.6R24", "front", None),
            ("AS7", "13.6-24", "front", None), ("AS1", "12.4-28", "front", None)]
    return pd.DataFrame(rows, columns=["tyre_id", "size", "position", "age_years"])
