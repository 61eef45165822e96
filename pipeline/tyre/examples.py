"""The example data of :mod:`tyrelab.tyre`'s Examples: one made-up tyre's runs, written once.

The regressions, conditions, formula accuracy and export functions read *results*: one row per run
with the columns the analyse stage writes (``tyre_id``, ``kind``, ``qc_ok``, the run's conditions
and its ``stiffness_kN_per_m`` and ``damping_kN_s_per_m``). Their Examples each need a few such
runs; :func:`demo_runs` is that table, so an Example shows the call and its answer, not a copy of
the data. The numbers are chosen to give round answers (made up, not measured; no thesis tyre):
standing, K = 300 + 100 P kN/m; rolling at 12 km/h, K = 280 + 100 P kN/m (P in bar).
"""

from __future__ import annotations

import pandas as pd

from .. import _validate

__all__ = ["DEMO_SERIES", "demo_runs"]

#: The series :func:`demo_runs` knows: a pressure series standing and rolling, a load series, an
#: amplitude series, and a mixed table (a calibration run, a run that failed QC).
DEMO_SERIES = ("pressure", "load", "amplitude", "mixed")


def demo_runs(series: str = "pressure") -> pd.DataFrame:
    """Runs of the made-up tyre ``T1`` in the analysed results' columns, for Examples and trials.

    Parameters
    ----------
    series : str
        One of :data:`DEMO_SERIES`:

        - ``pressure`` (6 runs): 1.0, 1.4 and 1.8 bar, standing and at 12 km/h (18.3 kN, 4 Hz,
          14 mm peak to peak, concrete); K 400, 440, 480 and 380, 420, 460 kN/m, C 3.0, 2.8, 2.6
          and 1.5, 1.4, 1.3 kN s/m;
        - ``load`` (3 runs): 14, 18 and 22 kN at 12 km/h and 1.38 bar; K 400, 420, 440 kN/m,
          C 1.0, 1.8, 2.6 kN s/m;
        - ``amplitude`` (3 runs): 10, 14 and 18 mm peak to peak at 12 km/h, 1.38 bar, 18.3 kN;
          K 430, 420, 410 kN/m, C 1.5 kN s/m;
        - ``mixed`` (4 rows, conditions only): a standing and a rolling run (grass) that passed QC,
          one at 6 Hz that failed it, and a calibration run.

    Returns
    -------
    DataFrame
        A new table on every call (a caller may change it).

    See Also
    --------
    tyrelab.tyre.regressions.pressure_regressions : fits the pressure series.
    tyrelab.tyre.conditions.usable : which rows of the mixed table count.

    Examples
    --------
    >>> runs = demo_runs()
    >>> runs[["speed_km_h", "pressure_bar", "stiffness_kN_per_m"]].head(2).to_dict("records")
    [{'speed_km_h': 0.0, 'pressure_bar': 1.0, 'stiffness_kN_per_m': 400.0}, {'speed_km_h': 0.0, 'pressure_bar': 1.4, 'stiffness_kN_per_m': 440.0}]
    >>> len(demo_runs("load")), demo_runs("mixed")["kind"].tolist()
    (3, ['measurement', 'measurement', 'measurement', 'calibration'])
    """
    _validate.choice("series", series, DEMO_SERIES)
    tyre = {"tyre_id": "T1", "kind": "measurement", "qc_ok": True, "surface": "concrete"}
    if series == "pressure":
        return pd.DataFrame({**tyre, "excitation_frequency_Hz": 4.0, "amplitude_mm_pp": 14.0, "load_kN": 18.3,
                             "speed_km_h": [0.0] * 3 + [12.0] * 3, "pressure_bar": [1.0, 1.4, 1.8] * 2,
                             "stiffness_kN_per_m": [400.0, 440.0, 480.0, 380.0, 420.0, 460.0],
                             "damping_kN_s_per_m": [3.0, 2.8, 2.6, 1.5, 1.4, 1.3]})
    if series == "load":
        return pd.DataFrame({**tyre, "speed_km_h": 12.0, "pressure_bar": 1.38, "load_kN": [14.0, 18.0, 22.0],
                             "excitation_frequency_Hz": 4.0, "amplitude_mm_pp": 14.0,
                             "stiffness_kN_per_m": [400.0, 420.0, 440.0], "damping_kN_s_per_m": [1.0, 1.8, 2.6]})
    if series == "amplitude":
        return pd.DataFrame({**tyre, "speed_km_h": 12.0, "pressure_bar": 1.38, "load_kN": 18.3,
                             "excitation_frequency_Hz": 4.0, "amplitude_mm_pp": [10.0, 14.0, 18.0],
                             "stiffness_kN_per_m": [430.0, 420.0, 410.0], "damping_kN_s_per_m": 1.5})
    return pd.DataFrame({"tyre_id": ["T1"] * 4, "kind": ["measurement"] * 3 + ["calibration"],
                         "qc_ok": [True, True, False, True], "speed_km_h": [0.0, 12.0, 12.0, 0.0],
                         "pressure_bar": [1.0, 1.4, 1.4, 1.0], "surface": ["concrete", "grass", None, None],
                         "excitation_frequency_Hz": [4.0, 4.0, 6.0, 4.0], "amplitude_mm_pp": [14.0, 14.0, 14.0, 30.0]})
