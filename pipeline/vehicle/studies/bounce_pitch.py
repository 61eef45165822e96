"""Bounce and pitch natural frequencies of an unsuspended tractor (thesis ch. 8).

The tractor is reduced to a rigid beam on two springs (thesis §8.2, Fig. 68): mass
``M``, pitch moment of inertia ``I``, front axle ``l1`` ahead of and rear axle ``l2``
behind the centre of gravity, axle stiffnesses ``K_f`` and ``K_r``. The axle
stiffness is the sum of the left and right tyres, i.e. twice the per-tyre stiffness.
Undamped free vibration obeys (thesis §8.2)::

    | K_f + K_r            K_f l1 - K_r l2        |   | z |         | M  0 | | z |
    | K_f l1 - K_r l2      K_f l1^2 + K_r l2^2    | . | g | = w^2 . | 0  I | | g |

solved by the engine's beam (:mod:`tyrelab.vehicle.solvers.beam`: ``natural_frequencies``,
``mode_shapes``, ``frequency_uncertainty``, importable from here too); this module is the
chapter 8 study on it (Table XX). SI inside; the per-tyre stiffness in the report is in kN/m,
the thesis' unit.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pandas as pd

from ... import _validate
from ...tyre.stiffness import estimate_stiffness
from ..comfort.metrics import ratio_error_statistics
from ..solvers.beam import _axle_N_per_m, _check, frequency_uncertainty, mode_shapes, natural_frequencies

__all__ = [
    "natural_frequencies",
    "tractor_natural_frequencies",
    "table_xx",
    "table_xx_statistics",
    "frequency_rounding_range",
    "mode_shapes", "FREQUENCY_INTERVAL_METHOD", "frequency_uncertainty"]


def tractor_natural_frequencies(
    mass_kg: float,
    pitch_inertia_kg_m2: float,
    front_distance_m: float,
    rear_distance_m: float,
    front_size: str,
    front_pressure_bar: float,
    rear_size: str,
    rear_pressure_bar: float,
    *,
    front_traction: bool = False,
    front_water_ballast: bool = False,
    rear_water_ballast: bool = False,
    age_years: float = 1.0,
    front_stiffness_kN_per_m: float | None = None,
    rear_stiffness_kN_per_m: float | None = None,
    front_stiffness_u_kN_per_m: float | None = None,
    rear_stiffness_u_kN_per_m: float | None = None,
    stiffness_model=None,
) -> dict:
    """Natural frequencies of a tractor from its tyre sizes and pressures (thesis §8.2).

    Per-tyre stiffnesses come from :func:`tyrelab.tyre.stiffness.estimate_tyre_stiffness`:
    traction tyres use ``K = 172 - 1.77 R + 5.6 A + 0.34 W R P``; undriven ribbed
    front tyres (``front_traction=False``) use ``K = 134/(7.5*18) W R P``; water
    ballast multiplies by 1.25. The axle stiffness is twice the per-tyre stiffness.

    Parameters
    ----------
    mass_kg, pitch_inertia_kg_m2, front_distance_m, rear_distance_m : float
        As :func:`natural_frequencies`.
    front_size, rear_size : str
        Tyre size designations, e.g. ``"7.50-16"``, ``"13.6-38"``.
    front_pressure_bar, rear_pressure_bar : float
        Inflation pressures in bar.
    front_traction : bool, optional
        Front tyres are traction tyres (four-wheel drive); default: undriven ribbed.
    front_water_ballast, rear_water_ballast : bool, optional
        Water-ballasted tyres (stiffness x1.25, Siefkes 1989, thesis §1.7.10).
    age_years : float, optional
        Tyre age in years (default 1, as thesis §8.2 assumes).
    front_stiffness_kN_per_m, rear_stiffness_kN_per_m : float, optional
        Per-tyre stiffnesses that override the formula.
    front_stiffness_u_kN_per_m, rear_stiffness_u_kN_per_m : float, optional
        Standard uncertainties of the per-tyre stiffnesses, kN/m. Default: the
        formula's (:attr:`~tyrelab.tyre.stiffness.StiffnessEstimate.stiffness_u_kN_per_m`,
        from the prediction interval of ``stiffness_model``; the undriven front rule's from
        the spread between tyres) for an estimated stiffness, 0 for a given one.
    stiffness_model : tyrelab.tyre.stiffness.StiffnessModel, optional
        The fitted formula behind the estimates (:func:`tyrelab.published.thesis_stiffness_model`);
        None: the printed formulas without uncertainty or range warnings.

    Returns
    -------
    dict
        ``front_tyre_stiffness_kN_per_m``, ``rear_tyre_stiffness_kN_per_m`` (per tyre),
        ``frequency_1_Hz``, ``frequency_2_Hz``, ``warnings`` (list of str: where an
        estimated tyre lies outside the thesis' data,
        :func:`tyrelab.tyre.stiffness.range_warnings`; none for given stiffnesses);
        the stiffness uncertainties ``front_tyre_stiffness_u_kN_per_m``,
        ``rear_tyre_stiffness_u_kN_per_m`` and the frequencies' ``frequency_1_u_Hz``,
        ``frequency_2_u_Hz``, ``frequency_1_Hz_ci95``, ``frequency_2_Hz_ci95`` ([low, high])
        from them (:func:`frequency_uncertainty`, ``frequency_interval_method``);
        ``natural_frequencies_Hz`` and ``nodal_points_m`` (``bounce``, ``pitch``: the same two
        frequencies by mode, and each mode's nodal point ahead of the CG in m, inf for a mode that
        does not pitch; :func:`mode_shapes`), as ``tyrelab ride`` reports them.

    See Also
    --------
    natural_frequencies : the same from axle stiffnesses.
    tyrelab.ride : the whole ride of a tractor scenario, these modes included.

    Examples
    --------
    Given stiffnesses, CG midway (a = b = 1 m): bounce and pitch decouple, ``ω² = 4k/m`` and
    ``ω² = 4k a²/I`` with k = 250 kN/m per tyre, m = 4000 kg, I = 2000 kg m² — √250/2π and
    √500/2π Hz:

    >>> r = tractor_natural_frequencies(4000, 2000, 1.0, 1.0, "13.6-38", 1.0, "13.6-38", 1.0, front_traction=True,
    ...                                 front_stiffness_kN_per_m=250, rear_stiffness_kN_per_m=250)
    >>> round(r["natural_frequencies_Hz"]["bounce"], 4), round(r["natural_frequencies_Hz"]["pitch"], 4)
    (2.5165, 3.5588)
    """
    _validate.non_negative("front_pressure_bar", front_pressure_bar)
    _validate.non_negative("rear_pressure_bar", rear_pressure_bar)
    _validate.non_negative("age_years", age_years)
    warnings: list[str] = []
    uf, ur = 0.0, 0.0
    if front_stiffness_kN_per_m is not None:
        kf = float(front_stiffness_kN_per_m)
    else:
        est = estimate_stiffness(front_size, front_pressure_bar, age_years, undriven_front=not front_traction,
                                 water_ballast=front_water_ballast, model=stiffness_model)
        kf = est.stiffness_kN_per_m
        uf = est.stiffness_u_kN_per_m or 0.0
        warnings += [f"front tyre {est.size.designation}: {w}" for w in est.warnings]
    if rear_stiffness_kN_per_m is not None:
        kr = float(rear_stiffness_kN_per_m)
    else:
        est = estimate_stiffness(rear_size, rear_pressure_bar, age_years, water_ballast=rear_water_ballast,
                                 model=stiffness_model)
        kr = est.stiffness_kN_per_m
        ur = est.stiffness_u_kN_per_m or 0.0
        warnings += [f"rear tyre {est.size.designation}: {w}" for w in est.warnings]
    for name, value in (("front_stiffness_u_kN_per_m", front_stiffness_u_kN_per_m),
                        ("rear_stiffness_u_kN_per_m", rear_stiffness_u_kN_per_m)):
        if value is not None and not (np.isfinite(value) and value >= 0):
            raise ValueError(f"{name} must be a non-negative number, got {value!r}")
    uf = uf if front_stiffness_u_kN_per_m is None else float(front_stiffness_u_kN_per_m)
    ur = ur if rear_stiffness_u_kN_per_m is None else float(rear_stiffness_u_kN_per_m)
    f1, f2 = natural_frequencies(
        mass_kg, pitch_inertia_kg_m2, front_distance_m, rear_distance_m, _axle_N_per_m(kf), _axle_N_per_m(kr)
    )
    modes = mode_shapes(mass_kg, pitch_inertia_kg_m2, front_distance_m, rear_distance_m, _axle_N_per_m(kf), _axle_N_per_m(kr))
    (u1, u2), (ci1, ci2) = frequency_uncertainty(mass_kg, pitch_inertia_kg_m2, front_distance_m, rear_distance_m,
                                                 kf, kr, uf, ur)
    return {
        "front_tyre_stiffness_kN_per_m": kf,
        "rear_tyre_stiffness_kN_per_m": kr,
        "frequency_1_Hz": f1,
        "frequency_2_Hz": f2,
        "front_tyre_stiffness_u_kN_per_m": uf,
        "rear_tyre_stiffness_u_kN_per_m": ur,
        "frequency_1_u_Hz": u1,
        "frequency_2_u_Hz": u2,
        "frequency_1_Hz_ci95": list(ci1),
        "frequency_2_Hz_ci95": list(ci2),
        "frequency_interval_method": FREQUENCY_INTERVAL_METHOD,
        # the modes by name, as ``tyrelab ride`` reports them (mode_shapes: the same eigenproblem)
        "natural_frequencies_Hz": {k: modes[k]["frequency_Hz"] for k in ("bounce", "pitch")},
        "nodal_points_m": {k: modes[k]["nodal_point_ahead_of_cg_m"] for k in ("bounce", "pitch")},
        "warnings": warnings,
    }


#: How :func:`frequency_uncertainty` carries the tyre stiffness uncertainty into the frequencies.
FREQUENCY_INTERVAL_METHOD = (
    "first order (GUM): sensitivities of both frequencies to the front and rear tyre stiffness by "
    "central differences, independent tyres, interval f ± 1.96 u(f)"
)


#: Half the last printed digit of each Table XIX / XX input: mass 1 kg, inertia 1 kg m²,
#: lever arms 0.01 m, tyre stiffness 1 kN/m.
PRINT_ROUNDING = {"mass": 0.5, "pitch_inertia": 0.5, "front_distance": 0.005, "rear_distance": 0.005,
                  "front_stiffness_kN_per_m": 0.5, "rear_stiffness_kN_per_m": 0.5}


def frequency_rounding_range(
    mass: float,
    pitch_inertia: float,
    front_distance: float,
    rear_distance: float,
    front_stiffness_kN_per_m: float,
    rear_stiffness_kN_per_m: float,
    rounding: dict[str, float] = PRINT_ROUNDING,
) -> np.ndarray:
    """Range of the two natural frequencies over the inputs' print-rounding box.

    The thesis printed Table XIX and XX inputs rounded (lever arms to 0.01 m,
    for instance) but computed its frequencies from unrounded values; the
    frequencies are sensitive to the lever arms (about 1.6 Hz per metre), so a
    printed frequency can differ from one recomputed from printed inputs by
    more than its own rounding. Evaluating :func:`natural_frequencies` at every
    corner of the box ``value ± rounding`` bounds what the unrounded inputs
    could have given (the frequencies are smooth and the box small).

    Parameters
    ----------
    mass, pitch_inertia, front_distance, rear_distance : float
        kg, kg m², m, m (as printed).
    front_stiffness_kN_per_m, rear_stiffness_kN_per_m : float
        Per-tyre stiffness as printed, kN/m (axle stiffness is twice this, §8.2).
    rounding : dict
        Half-widths per input name (:data:`PRINT_ROUNDING`).

    Returns
    -------
    ndarray, shape (2, 2)
        ``[[f1_low, f1_high], [f2_low, f2_high]]`` in Hz.

    See Also
    --------
    table_xx : whether the thesis' printed frequencies lie in this range.

    Examples
    --------
    >>> np.round(frequency_rounding_range(4700, 5500, 1.56, 0.99, 800, 1200), 2).tolist()   # [low, high] per mode, Hz
    [[4.63, 4.64], [5.35, 5.39]]
    """
    _check(positive=dict(mass=mass, pitch_inertia=pitch_inertia, front_stiffness_kN_per_m=front_stiffness_kN_per_m,
                         rear_stiffness_kN_per_m=rear_stiffness_kN_per_m),
           non_negative=dict(front_distance=front_distance, rear_distance=rear_distance))
    if not isinstance(rounding, dict):
        raise ValueError(f"rounding must be a dict of half-widths, got {type(rounding).__name__}")
    _validate.non_negative_array("rounding", list(rounding.values()))
    values = dict(mass=mass, pitch_inertia=pitch_inertia, front_distance=front_distance, rear_distance=rear_distance,
                  front_stiffness_kN_per_m=front_stiffness_kN_per_m, rear_stiffness_kN_per_m=rear_stiffness_kN_per_m)
    names = list(values)
    corners = []
    for signs in itertools.product((-1.0, 1.0), repeat=len(names)):
        v = {n: values[n] + sg * rounding.get(n, 0.0) for n, sg in zip(names, signs)}
        corners.append(natural_frequencies(v["mass"], v["pitch_inertia"], v["front_distance"], v["rear_distance"],
                                           _axle_N_per_m(v["front_stiffness_kN_per_m"]), _axle_N_per_m(v["rear_stiffness_kN_per_m"])))
    f = np.asarray(corners)
    return np.array([[f[:, 0].min(), f[:, 0].max()], [f[:, 1].min(), f[:, 1].max()]])


def table_xx(tractors: pd.DataFrame, published: pd.DataFrame | None = None, stiffness_model=None) -> pd.DataFrame:
    """Table XX: tyre stiffnesses and predicted natural frequencies, ours beside the thesis'.

    For each tractor of Table XIX two rows are produced:

    * ``stiffness_source = "formula"``: our per-tyre stiffnesses from the size
      formula (:func:`tractor_natural_frequencies`) and the frequencies they give,
      plus the frequencies recomputed from the thesis' *printed* stiffnesses;
    * ``stiffness_source = "stationary_free_vibration"``: the thesis' measured
      stationary stiffnesses (no formula), frequencies recomputed from them.

    Parameters
    ----------
    tractors : DataFrame
        Table XIX columns: ``tractor, mass_kg, pitch_inertia_kg_m2, front_distance_m,
        rear_distance_m, front_size, front_pressure_bar, rear_size, rear_pressure_bar,
        four_wheel_drive, front_water_ballast``.
    published : DataFrame, optional
        Table XX columns: ``tractor, stiffness_source, rear_stiffness_kN_per_m,
        front_stiffness_kN_per_m, predicted_frequency_1_Hz, predicted_frequency_2_Hz,
        measured_frequency_1_Hz, measured_frequency_2_Hz``.
    stiffness_model : tyrelab.tyre.stiffness.StiffnessModel, optional
        As :func:`tractor_natural_frequencies` (the stage passes the thesis' model).

    Returns
    -------
    DataFrame
        One row per tractor and stiffness source with ``thesis_*`` and ``ours_*``
        stiffnesses and frequencies, ``*_from_thesis_stiffness_Hz`` and differences.
        Formula rows also carry the formula's per-tyre stiffness uncertainties
        ``ours_{front,rear}_stiffness_u_kN_per_m`` (its prediction interval,
        :mod:`tyrelab.tyre.stiffness`; the undriven front rule's from the spread
        between tyres, :class:`tyrelab.tyre.formula_fit.FrontRule`) and the frequencies' ``ours_frequency_{1,2}_u_Hz`` and 95 %
        intervals ``ours_frequency_{1,2}_ci95_{low,high}_Hz``
        (:func:`frequency_uncertainty`); the measured-stiffness rows have none
        (the thesis states no uncertainty for them): NaN.

    See Also
    --------
    table_xx_statistics : its ratio errors.
    tyrelab.vehicle.published_layouts.tractors : the tractors it reads.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> from tyrelab.vehicle.published_layouts import tractors
    >>> t = table_xx(tractors(read_published("table_xix")), read_published("table_xx"))
    >>> len(t), sorted(t["stiffness_source"].unique())
    (10, ['formula', 'stationary_free_vibration'])
    """
    _validate.frame("tractors", tractors)
    if published is not None:
        _validate.frame("published", published)
    rows = []
    pub = published if published is not None else pd.DataFrame()
    for t in tractors.itertuples(index=False):
        ours = tractor_natural_frequencies(
            t.mass_kg,
            t.pitch_inertia_kg_m2,
            t.front_distance_m,
            t.rear_distance_m,
            t.front_size,
            t.front_pressure_bar,
            t.rear_size,
            t.rear_pressure_bar,
            front_traction=bool(t.four_wheel_drive),
            front_water_ballast=bool(t.front_water_ballast),
            stiffness_model=stiffness_model,
        )
        for source in ("formula", "stationary_free_vibration"):
            p = (
                pub[(pub["tractor"] == t.tractor) & (pub["stiffness_source"] == source)]
                if len(pub)
                else pub
            )
            rec = p.iloc[0] if len(p) else None
            row = {"tractor": t.tractor, "stiffness_source": source}
            if rec is not None:
                row.update(
                    thesis_rear_stiffness_kN_per_m=float(rec["rear_stiffness_kN_per_m"]),
                    thesis_front_stiffness_kN_per_m=float(rec["front_stiffness_kN_per_m"]),
                    thesis_frequency_1_Hz=float(rec["predicted_frequency_1_Hz"]),
                    thesis_frequency_2_Hz=float(rec["predicted_frequency_2_Hz"]),
                    measured_frequency_1_Hz=float(rec["measured_frequency_1_Hz"]),
                    measured_frequency_2_Hz=float(rec["measured_frequency_2_Hz"]),
                )
                g1, g2 = natural_frequencies(
                    t.mass_kg,
                    t.pitch_inertia_kg_m2,
                    t.front_distance_m,
                    t.rear_distance_m,
                    _axle_N_per_m(row["thesis_front_stiffness_kN_per_m"]),
                    _axle_N_per_m(row["thesis_rear_stiffness_kN_per_m"]),
                )
                row.update(frequency_1_from_thesis_stiffness_Hz=g1, frequency_2_from_thesis_stiffness_Hz=g2)
                rng = frequency_rounding_range(t.mass_kg, t.pitch_inertia_kg_m2, t.front_distance_m, t.rear_distance_m,
                                               row["thesis_front_stiffness_kN_per_m"], row["thesis_rear_stiffness_kN_per_m"])
                for i in (1, 2):
                    low, high = rng[i - 1]
                    printed = row[f"thesis_frequency_{i}_Hz"]
                    row[f"frequency_{i}_rounding_low_Hz"] = low
                    row[f"frequency_{i}_rounding_high_Hz"] = high
                    # printed to 0.01 Hz: consistent if its own rounding interval meets the range
                    row[f"thesis_frequency_{i}_consistent_with_rounding"] = bool(low - 0.005 <= printed <= high + 0.005)
            if source == "formula":
                row.update(
                    ours_rear_stiffness_kN_per_m=ours["rear_tyre_stiffness_kN_per_m"],
                    ours_front_stiffness_kN_per_m=ours["front_tyre_stiffness_kN_per_m"],
                    ours_frequency_1_Hz=ours["frequency_1_Hz"],
                    ours_frequency_2_Hz=ours["frequency_2_Hz"],
                    ours_front_stiffness_u_kN_per_m=ours["front_tyre_stiffness_u_kN_per_m"],
                    ours_rear_stiffness_u_kN_per_m=ours["rear_tyre_stiffness_u_kN_per_m"],
                )
                for i in (1, 2):
                    low, high = ours[f"frequency_{i}_Hz_ci95"]
                    row.update({f"ours_frequency_{i}_u_Hz": ours[f"frequency_{i}_u_Hz"],
                                f"ours_frequency_{i}_ci95_low_Hz": low, f"ours_frequency_{i}_ci95_high_Hz": high})
            else:
                # No formula: our stiffness is the thesis' measured stationary stiffness.
                row.update(
                    ours_rear_stiffness_kN_per_m=row.get("thesis_rear_stiffness_kN_per_m", math.nan),
                    ours_front_stiffness_kN_per_m=row.get("thesis_front_stiffness_kN_per_m", math.nan),
                    ours_frequency_1_Hz=row.get("frequency_1_from_thesis_stiffness_Hz", math.nan),
                    ours_frequency_2_Hz=row.get("frequency_2_from_thesis_stiffness_Hz", math.nan),
                )
            rows.append(row)
    out = pd.DataFrame(rows)
    for q in ("rear_stiffness_kN_per_m", "front_stiffness_kN_per_m", "frequency_1_Hz", "frequency_2_Hz"):
        if f"thesis_{q}" in out:
            out[f"difference_{q}"] = out[f"ours_{q}"] - out[f"thesis_{q}"]
    if "measured_frequency_1_Hz" in out:
        for i in (1, 2):
            out[f"ours_ratio_error_{i}"] = out[f"ours_frequency_{i}_Hz"] / out[f"measured_frequency_{i}_Hz"]
            out[f"thesis_ratio_error_{i}"] = out[f"thesis_frequency_{i}_Hz"] / out[f"measured_frequency_{i}_Hz"]
    return out


def table_xx_statistics(table: pd.DataFrame) -> pd.DataFrame:
    """Ratio-error statistics of Table XX per stiffness source (thesis §8.2).

    Pools both natural frequencies of every tractor (ten ratios per source).

    Returns
    -------
    DataFrame
        ``stiffness_source, basis (thesis|ours), n, mean, sd, p_within_10, p_within_30``.

    See Also
    --------
    table_xx : the table it summarises.
    tyrelab.vehicle.metrics.ratio_error_statistics : the statistics.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> from tyrelab.vehicle.published_layouts import tractors
    >>> t = table_xx(tractors(read_published("table_xix")), read_published("table_xx"))
    >>> s = table_xx_statistics(t).set_index(["stiffness_source", "basis"])
    >>> round(float(s.loc[("formula", "thesis"), "mean"]), 3), round(float(s.loc[("formula", "ours"), "mean"]), 3)
    (1.0, 1.004)
    """
    _validate.frame("table", table)
    rows = []
    for source, g in table.groupby("stiffness_source", sort=False):
        for basis in ("thesis", "ours"):
            cols = [f"{basis}_ratio_error_1", f"{basis}_ratio_error_2"]
            if not all(c in g for c in cols):
                continue
            r = np.concatenate([g[c].to_numpy(float) for c in cols])
            rows.append({"stiffness_source": source, "basis": basis, **ratio_error_statistics(r)})
    return pd.DataFrame(rows)
