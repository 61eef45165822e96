"""How a ride's speed rows are computed: in the time domain, in the frequency domain, or both (issue 36).

A sweep asks about expectations on a random road, and a linear model's expectation on a
Gaussian (ISO 8608) surface is exact in the frequency domain
(:func:`tyrelab.vehicle.ride.spectral_variants`): for
the model ``(A, B, C, D)`` of :func:`tyrelab.vehicle.ride.state_space`'s assembly, each output's
spectrum ``h S h^H`` over the ground input's (cross-)spectrum ``S`` and its variance
``∫ S_y df`` (:func:`tyrelab.vehicle.ride.expected_weighted_rms`). A *spectral* speed row holds

* ``a_wz_m_s2``, ``a_wx_m_s2``, ``a_wy_m_s2``: the expected ISO 2631-1 weighted r.m.s. per axis
  (W_k, W_d; the seat suspension on z), the same numbers as a time row's ``expected_a_w*``;
* ``evdv_m_s1_75`` and ``evdv_daily_m_s1_75``: ISO 2631-1 §6.3.2's *estimated* vibration dose
  value ``eVDV = 1.4 a_w T^¼`` (highest axis, ``k a_w``) over the record a time row would take
  (``duration_s``) and over the daily exposure; ``vdv_m_s1_75`` (the fourth-power integral of a
  record) is empty;
* the exposure of :func:`tyrelab.vehicle.ride.exposure` (A(8), hours to the action and limit
  values, verdict) from those a_w;
* ``front_tyre_force_sd_N``, ``rear_tyre_force_sd_N``: the standard deviation of one tyre's
  dynamic vertical force (the axle's highest in 3-D), and ``lift_off_probability_front``/``_rear``:
  the probability that the tyre leaves the ground, ``Φ(-F_static / σ_F)`` (Gaussian; the most
  likely of the axle's tyres in 3-D);
* ``mtvv_m_s2``, ``crest_factor``, ``lift_off_fraction_*`` and ``vdv_*``: empty (None). They are
  properties of one record, which the frequency domain has not got; nothing is invented for them.

Every row carries ``method`` (``"time"`` or ``"spectral"``). :func:`tyrelab.vehicle.ride.ride_sweep`
chooses per variant (``[simulation] method`` or ``tyrelab ride --method``;
:func:`~tyrelab.vehicle.scenario.limits.uses_spectral`):

``time``
    Every variant simulated (today's rows: simulated and expected side by side).
``spectral``
    Every variant in the frequency domain.
``auto`` (the default)
    One variant: ``time``. A sweep on an ISO 8608 surface: ``spectral`` for every variant, and
    the time domain beside it (:attr:`tyrelab.vehicle.ride.RideResult.time_rows`) for the nominal
    variant (:func:`nominal_index`: the scenario's own values; else the first) and for every speed
    of a variant whose lift-off probability exceeds :data:`LIFT_OFF_PROBABILITY_LIMIT`
    (:func:`lifting_speeds`; the linear expectation no longer holds there). A sweep on a profile or
    any other deterministic road: ``time``.

This module makes the rows from the frequency domain's numbers and says which rows answer
(:func:`primary_rows`); :mod:`tyrelab.vehicle.ride` computes the numbers and runs the sweep.

Examples
--------
>>> from tyrelab.resources import scenarios_dir
>>> from tyrelab.scenario_io import load_scenario
>>> from tyrelab.vehicle.ride import ride, spectral_variants
>>> from tyrelab.vehicle.scenario import with_overrides
>>> sc = with_overrides(load_scenario(scenarios_dir() / "modern_tractor.toml"), [8.0])
>>> row = spectral_variants([sc], with_spectra=False)[0].speeds.iloc[0]
>>> expected = ride(sc, with_spectra=False).speeds.iloc[0]["expected_a_wz_m_s2"]
>>> row["method"], bool(abs(row["a_wz_m_s2"] / expected - 1) < 1e-12), row["crest_factor"] is None
('spectral', True, True)
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from scipy import special

from .. import _validate
from . import iso2631
from .run.rows import SpeedRow, tyre_columns
from .scenario import Scenario

__all__ = ["at_own_values", "LIFT_OFF_PROBABILITY_LIMIT", "EVDV_FACTOR", "SPECTRAL_SIMULATION", "SPECTRAL_CHUNK",
           "PSD_FREQUENCIES_HZ", "lift_off_probability", "nominal_index", "spectral_row", "lifting_speeds",
           "primary_rows"]

#: Under ``auto``, a variant's speed whose tyre lift-off probability exceeds this is simulated too.
LIFT_OFF_PROBABILITY_LIMIT = 1e-3
#: ISO 2631-1 §6.3.2: eVDV = 1.4 a_w T^¼ (crest factors below about 6).
EVDV_FACTOR = 1.4
#: The ``simulation`` text of a spectral row.
SPECTRAL_SIMULATION = "frequency domain (expectation)"
#: Variants per executor task of a spectral sweep (one task is about 10 ms a variant).
SPECTRAL_CHUNK = 200
#: Frequencies of a spectral variant's seat PSD figure data, Hz (the time rows' Welch grid: 0.1 Hz).
PSD_FREQUENCIES_HZ = np.round(np.arange(2, 201) * 0.1, 10)


def lift_off_probability(static_load_N, force_sd_N):
    """Probability that a tyre leaves the ground, ``Φ(-F_static / σ_F)``: its dynamic force, Gaussian
    with standard deviation ``force_sd_N``, pulls below minus its static load (0 where ``σ = 0``).

    See Also
    --------
    lifting_speeds : the speeds whose probability is too high.

    Examples
    --------
    >>> round(float(lift_off_probability(10e3, 10e3 / 3)), 6)  # 3 sigma
    0.00135
    >>> float(lift_off_probability(10e3, 0.0))
    0.0
    """
    _validate.finite_array("static_load_N", np.atleast_1d(static_load_N))
    _validate.non_negative_array("force_sd_N", np.atleast_1d(force_sd_N))
    f0, sd = np.asarray(static_load_N, float), np.asarray(force_sd_N, float)
    with np.errstate(divide="ignore"):
        return np.where(sd > 0, special.ndtr(-f0 / np.where(sd > 0, sd, 1.0)), 0.0)


def primary_rows(table: pd.DataFrame) -> pd.DataFrame:
    """The rows of ``ride_results`` (:func:`tyrelab.vehicle.ride.results_table`) that answer: per
    scenario, variant and speed its spectral row where it has one, else its time row (the time rows
    beside spectral ones are a comparison, not a second answer). The figures and variant tables
    of a ride read these.

    See Also
    --------
    spectral_row : the spectral rows it prefers.

    Examples
    --------
    >>> t = pd.DataFrame({"front_pressure_bar": [1.0, 1.0, 1.2], "rear_pressure_bar": 1.0, "speed_km_h": 8.0,
    ...                   "method": ["spectral", "time", "time"]})
    >>> primary_rows(t).index.tolist()
    [0, 2]
    """
    _validate.instance("table", table, pd.DataFrame)
    if "method" not in table or not (table["method"] == "spectral").any():
        return table
    cols = [c for c in ("scenario", "file", "variant", "front_pressure_bar", "rear_pressure_bar", "speed_km_h")
            if c in table]
    key = pd.Series(list(zip(*[table[c].astype(str) for c in cols])), index=table.index)
    spectral = table["method"] == "spectral"
    return table[spectral | ~key.isin(set(key[spectral]))]


def at_own_values(scenario: Scenario, variant: Scenario, combo: dict) -> bool:
    """Whether a variant (its scenario and swept values) is at ``scenario``'s own tyre pressures and
    swept keys' values (the file's).

    See Also
    --------
    nominal_index : the variant at them.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> from tyrelab.vehicle.scenario.variants import with_values
    >>> heavy = with_values(s, {"tractor.mass_kg": s.tractor.mass_kg + 500})
    >>> at_own_values(s, s, {}), at_own_values(s, heavy, {"tractor.mass_kg": s.tractor.mass_kg + 500})
    (True, False)
    """
    _validate.instance("scenario", scenario, Scenario)

    def own(key: str):
        node = scenario.doc or {}
        for part in key.split("."):
            if not isinstance(node, dict) or part not in node:
                return None
            node = node[part]
        return node

    return (variant.front.pressure_bar == scenario.front.pressure_bar
            and variant.rear.pressure_bar == scenario.rear.pressure_bar
            and all(own(key) is not None and float(own(key)) == float(v) for key, v in combo.items()))


def nominal_index(scenario: Scenario, variants: list[tuple[Scenario, dict]]) -> int:
    """The variant of ``variants`` (``(scenario, swept values)`` pairs of :func:`ride_sweep`) at the
    scenario's own tyre pressures and swept keys' values (the file's; :func:`at_own_values`), else 0
    (the first).

    See Also
    --------
    at_own_values : the test of each variant.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> from tyrelab.vehicle.scenario.variants import with_values
    >>> soft = with_values(s, {"tyres.rear.pressure_bar": 0.8})
    >>> nominal_index(s, [(soft, {"tyres.rear.pressure_bar": 0.8}), (s, {})]), nominal_index(s, [(soft, {})])
    (1, 0)
    """
    _validate.instance("scenario", scenario, Scenario)
    return next((k for k, (sc, combo) in enumerate(variants) if at_own_values(scenario, sc, combo)), 0)


# --------------------------------------------------------------------------- spectral rows
def spectral_row(speed_km_h: float, tyres: dict, i: int, aw_m_s2: dict, axes, hours_per_day: float,
                 duration_s: float, force_sd_N: dict, static_load_N: dict, tyres_per_element: int,
                 exposure: dict) -> SpeedRow:
    """One spectral speed row (module docstring; a :class:`~tyrelab.vehicle.run.rows.SpeedRow`) from the
    frequency domain's numbers.

    Parameters
    ----------
    speed_km_h : float
    tyres : dict
        ``front``/``rear`` -> :class:`tyrelab.vehicle.ride.AxleTyres`; ``i`` the speed's index.
    aw_m_s2 : dict
        Seat axis (``z``, ``x``, ``y``) -> expected weighted r.m.s.; ``axes`` the model's axes.
    hours_per_day, duration_s : float
        Daily exposure (h) and the record a simulation would take (s), for eVDV.
    force_sd_N, static_load_N : dict
        Tyre element (``front``, ``rear_left``, ...) -> dynamic force r.m.s. and static load, N.
    tyres_per_element : int
        Tyres an element stands for (2 in the pitch plane, 1 in 3-D): the per-tyre force.
    exposure : dict
        :func:`tyrelab.vehicle.ride.exposure` of ``aw_m_s2``.

    See Also
    --------
    lift_off_probability : its lift-off columns.
    primary_rows : the rows that answer.

    Examples
    --------
    The shipped tractor at 8 km/h with an expected a_wz of 0.6 and a_wx of 0.3 m/s²: eVDV
    ``1.4 a_w T^¼`` over a 180 s record and over the 8 h day, each axle's force per tyre (the pitch
    plane's element carries two), A(8) and the hours to the action value ``8 h (0.5 / 0.6)²``:

    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> from tyrelab.vehicle.run.rows import exposure
    >>> from tyrelab.vehicle.tyres import resolve_tyres
    >>> tyres = resolve_tyres(load_scenario(scenarios_dir() / "modern_tractor.toml"))
    >>> row = spectral_row(8.0, tyres, 0, {"z": 0.6, "x": 0.3}, ("z", "x"), 8.0, 180.0, {"front": 2000.0, "rear": 3000.0},
    ...                    {"front": 20e3, "rear": 40e3}, 2, exposure(0.6, 0.3, 8.0))
    >>> round(row.evdv_m_s1_75, 3), round(row.evdv_daily_m_s1_75, 2), row.front_tyre_force_sd_N, round(row.hours_to_eav, 2)
    (3.077, 10.94, 1000.0, 5.56)
    >>> row.method, row.a8_axis, row.verdict
    ('spectral', 'z', 'above action value')
    """
    aw = {ax: float(aw_m_s2.get(ax, 0.0)) for ax in ("z", "x", "y")}
    highest = max(iso2631.AXIS_FACTOR[ax] * aw[ax] for ax in axes)
    sd, prob = {}, {}
    for axle in ("front", "rear"):
        mine = [t for t in force_sd_N if t.split("_")[0] == axle]
        sd[axle] = max(force_sd_N[t] for t in mine) / tyres_per_element
        prob[axle] = max(float(lift_off_probability(static_load_N[t], force_sd_N[t])) for t in mine)
    return SpeedRow(
        float(speed_km_h), **tyre_columns(tyres, i), a_wz_m_s2=aw["z"], a_wx_m_s2=aw["x"], a_wy_m_s2=aw["y"],
        expected_a_wz_m_s2=aw["z"], expected_a_wx_m_s2=aw["x"], expected_a_wy_m_s2=aw["y"], vdv_m_s1_75=None,
        vdv_daily_m_s1_75=None, evdv_m_s1_75=EVDV_FACTOR * highest * duration_s ** 0.25,
        evdv_daily_m_s1_75=EVDV_FACTOR * highest * (hours_per_day * 3600.0) ** 0.25, crest_factor=None,
        mtvv_m_s2=None, lift_off_fraction_front=None, lift_off_fraction_rear=None, front_tyre_force_sd_N=sd["front"],
        rear_tyre_force_sd_N=sd["rear"], lift_off_probability_front=prob["front"],
        lift_off_probability_rear=prob["rear"], **exposure, hours_per_day=hours_per_day, duration_s=duration_s,
        simulation=SPECTRAL_SIMULATION, method="spectral")


def lifting_speeds(rows: pd.DataFrame) -> list[float]:
    """The speeds of a variant's spectral rows whose lift-off probability (either axle) exceeds
    :data:`LIFT_OFF_PROBABILITY_LIMIT`: ``auto`` simulates them too.

    See Also
    --------
    lift_off_probability : the probability of each row.

    Examples
    --------
    >>> lifting_speeds(pd.DataFrame({"speed_km_h": [8.0, 20.0], "lift_off_probability_front": [1e-5, 0.02],
    ...                              "lift_off_probability_rear": [0.0, 0.0]}))
    [20.0]
    """
    _validate.instance("rows", rows, pd.DataFrame)
    worst = np.maximum(rows["lift_off_probability_front"].to_numpy(float),
                       rows["lift_off_probability_rear"].to_numpy(float))
    return rows["speed_km_h"].to_numpy(float)[worst > LIFT_OFF_PROBABILITY_LIMIT].tolist()


