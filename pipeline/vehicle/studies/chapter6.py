"""The chapter 6 study: the single-wheel carriage over the slatted track, its profile estimates
(§6.3) and Tables XIII/XIV (ours) of the predictions against the recordings (:mod:`tyrelab.vehicle.studies`)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ... import _validate
from . import carriage as cm
from ..comfort import iso2631
from ..comfort import metrics as mt
from ..terrain import enveloping as ev
from ..terrain import profiles as pr
from ..units import KILO, from_kilo, to_kilo
from .shared import (DT_S, FS_HZ, LEAD_IN_M, RECORDED_NOISE_RMS_M, RECORDED_SPIKE, SURVEY_ERROR_M,
                     T4_ROLLING_RADIUS_M, _by_condition, _given_cases, _plain, _refuse, record_spectra)

__all__ = ["carriage_case_inputs", "carriage_study", "carriage_key"]
# carriage_track, carriage_steps and profile_estimates are shared with tyrelab.vehicle.study_recordings
# (the virtual carriage drives the study's track); not part of the public interface.


def _lowpass_profile(h: np.ndarray, dx: float, length_m: float) -> np.ndarray:
    return ev.fixed_footprint(h, dx, length_m)


def profile_estimates(track: pr.Profile, radius_m: float, footprint_m: float, seed: int, side: str = "left") -> dict:
    """True effective input and the two profile estimates of one wheel track (thesis §6.3).

    Parameters
    ----------
    track : Profile
        Slatted track from :func:`tyrelab.vehicle.profiles.slatted_track` (no lead-in).
    radius_m, footprint_m : float
        Tyre rolling radius and contact length, m.
    seed : int
        Seed for the survey error and the recorded estimate's noise.

    Returns
    -------
    dict
        ``true``, ``surveyed``, ``recorded`` (enveloped elevations on ``track.x_m``)
        and ``surveyed_raw`` (before the enveloping filter), m.
    """
    rng = np.random.default_rng(seed)
    dx = track.dx_m
    surface = pr.slat_surface(track, side)
    true = ev.tapered_moving_average(ev.rigid_tread_band(surface, dx, radius_m), dx, footprint_m)
    slats = track.meta[f"{side}_slats_m"] + rng.uniform(-SURVEY_ERROR_M, SURVEY_ERROR_M, track.meta["slat_x_m"].size)
    surveyed_raw = np.interp(track.x_m, track.meta["slat_x_m"], slats)
    surveyed = ev.tapered_moving_average(surveyed_raw, dx, footprint_m)
    # recorded locus: true locus + band-limited noise floor + spurious narrow-band peak
    n_pts = track.x_m.size
    noise = _lowpass_profile(rng.standard_normal(n_pts), dx, 0.3)
    noise *= RECORDED_NOISE_RMS_M / noise.std()
    n, g = pr.profile_spectrum(true, dx)
    centre, half, factor = RECORDED_SPIKE
    band = (n >= centre - half) & (n <= centre + half)
    g_spike = (factor - 1.0) * float(g[band].mean())
    spike = pr.spectral_synthesis(
        n_pts, dx, g_spike * (centre / pr.ISO8608_N0_CYCLES_PER_M) ** 0, rng, 0.0, centre - half, centre + half
    )
    recorded = true + noise + spike
    return {"true": true, "surveyed": surveyed, "recorded": recorded, "surveyed_raw": surveyed_raw}


def _footprints(table_xii: pd.DataFrame, surface_stiffness_factor: float) -> dict:
    """Tyre footprint length (m) per load condition of Table XII's rolling rows.

    From the condition's static deflection under the mean rolling stiffness on the
    slatted surface: the enveloped profile estimates of the condition depend on it.
    """
    out = {}
    for load, g in table_xii.groupby("load_condition", sort=False):
        k_mean = surface_stiffness_factor * KILO * g["stiffness_kN_per_m"].mean()
        deflection = float(g["load_kg"].iloc[0]) * cm.THESIS_GRAVITY_M_S2 / k_mean
        out[load] = ev.contact_length(T4_ROLLING_RADIUS_M, deflection)
    return out


def carriage_case_inputs(
    table_xii: pd.DataFrame, stationary: pd.DataFrame, surface_stiffness_factor: float = 0.9
) -> list[dict]:
    """What each case of :func:`carriage_study` reads, one dict per row of ``table_xii``.

    A case is one rolling row of Table XII (speed and load condition): its reference
    run and its four predictions. It reads its own row, the stationary row of its
    load condition and its condition's tyre footprint (:func:`_footprints`, from the
    condition's mean stiffness); with the study's seed and surface factor that is
    everything. A cache keyed on these (the simulate stage's) recomputes only the
    cases whose inputs changed.

    See Also
    --------
    carriage_study : the study of these cases.

    Examples
    --------
    >>> import pandas as pd
    >>> xii = pd.DataFrame({"speed_km_h": [5.0, 10.0], "actual_speed_m_s": [1.4, 2.8],
    ...                     "load_condition": ["light", "light"], "load_kg": [1860, 1860],
    ...                     "damping_kN_s_per_m": [2.2, 1.7], "stiffness_kN_per_m": [403.0, 388.0]})
    >>> st = pd.DataFrame({"load_condition": ["light"], "load_kg": [1860],
    ...                    "damping_kN_s_per_m": [3.0], "stiffness_kN_per_m": [420.0]})
    >>> cases = carriage_case_inputs(xii, st)
    >>> len(cases), sorted(cases[0])
    (2, ['footprint_m', 'row', 'stationary', 'surface_stiffness_factor'])
    >>> cases[0]["footprint_m"] == cases[1]["footprint_m"]  # one condition, one footprint
    True
    """
    _validate.frame("table_xii", table_xii)
    _validate.frame("stationary", stationary)
    _validate.positive("surface_stiffness_factor", surface_stiffness_factor)
    problems: list[str] = []
    stat = _by_condition(stationary, table_xii["load_condition"], "stationary", "row", problems)
    _refuse(problems)
    foot = _footprints(table_xii, surface_stiffness_factor)
    return [
        {
            "row": _plain(row),
            "stationary": _plain(stat.loc[row["load_condition"]]),
            "footprint_m": float(foot[row["load_condition"]]),
            "surface_stiffness_factor": float(surface_stiffness_factor),
        }
        for row in table_xii.reset_index(drop=True).to_dict("records")
    ]


def carriage_track(conds: pd.DataFrame, seed: int, surface_stiffness_factor: float) -> tuple:
    """The slatted track of the carriage study and its profiles per load condition.

    Returns ``(track, lead, est_by_load, x)``: the track (:func:`tyrelab.vehicle.profiles.slatted_track`,
    seeded by ``seed``), the lead-in in samples, per load condition the enveloped ``true``
    surface and the ``surveyed``/``recorded`` estimates (:func:`profile_estimates`, seed
    ``seed + 1``) with the lead-in, and the distance axis, m. The virtual carriage that records
    the "measured" runs (:mod:`tyrelab.vehicle.study_recordings`) drives over ``true``; the
    predictions read the estimates.
    """
    track = pr.slatted_track(seed=seed)
    dx = track.dx_m
    lead = int(round(LEAD_IN_M / dx))
    est_by_load = {}
    for load, footprint in _footprints(conds, surface_stiffness_factor).items():
        est = profile_estimates(track, T4_ROLLING_RADIUS_M, footprint, seed + 1)
        est_by_load[load] = {k: np.concatenate([np.full(lead, v[0]), v, np.full(lead, v[-1])]) for k, v in est.items()}
        est_by_load[load]["footprint_m"] = footprint
    x = np.arange(track.x_m.size + 2 * lead) * dx
    return track, lead, est_by_load, x


def carriage_steps(speeds_m_s, track_end_m: float) -> tuple[np.ndarray, np.ndarray]:
    """Per run at ``speeds_m_s``: the first sample after the lead-in and the number of
    samples to the track's end (at :data:`DT_S`); a record is ``[start:stop]``."""
    v = np.asarray(speeds_m_s, float)
    start = np.ceil(LEAD_IN_M / (v * DT_S)).astype(int)
    stop = np.floor((LEAD_IN_M + track_end_m) / (v * DT_S)).astype(int) + 1
    return start, stop


def carriage_key(row: dict) -> tuple[float, str]:
    """The key of a carriage run (a Table XII row or a recording): ``(speed_km_h, load_condition)``.

    See Also
    --------
    carriage_study : keys its runs and recordings by it.

    Examples
    --------
    >>> carriage_key({"speed_km_h": "12.5", "load_condition": "heavy"})
    (12.5, 'heavy')
    """
    try:
        return float(row["speed_km_h"]), str(row["load_condition"])
    except (KeyError, TypeError, ValueError):
        raise ValueError(f"row: needs a speed_km_h number and a load_condition, got {row!r:.120}") from None


def _accuracy(kept: pd.DataFrame, estimate: str) -> pd.DataFrame:
    """Table XIII/XIV (ours) of the comparisons of one profile estimate; without any (no
    recordings) the table's rows with no value (a gap, not an error)."""
    rows = kept[kept["profile_estimate"] == estimate] if len(kept) else kept
    if not len(rows):
        shape = mt.accuracy_table(pd.DataFrame({"characteristics": ["rolling"], "profile_estimate": [estimate],
                                                **{c: [np.nan] for _, c in mt._XIII_ROWS},
                                                "envelope_correlation": [np.nan], "envelope_error": [np.nan]}))
        return shape[["quantity", "statistic"]].assign(rolling=np.nan, stationary=np.nan)
    table = mt.accuracy_table(rows, by="characteristics")
    for name in ("rolling", "stationary"):
        if name not in table:
            table[name] = np.nan
    return table


def carriage_study(
    table_xii: pd.DataFrame,
    stationary: pd.DataFrame,
    seed: int = 5007,
    surface_stiffness_factor: float = 0.9,
    cases: dict | None = None,
    recordings: dict | None = None,
) -> dict[str, pd.DataFrame]:
    """Chapter 6: carriage runs of Tables XI/XII, rolling vs stationary, two estimates,
    compared with the recordings of the runs.

    Parameters
    ----------
    table_xii : DataFrame
        ``speed_km_h, actual_speed_m_s, load_condition, load_kg, damping_kN_s_per_m,
        stiffness_kN_per_m`` (rolling, before the surface reduction).
    stationary : DataFrame
        ``load_condition, damping_kN_s_per_m, stiffness_kN_per_m``.
    seed : int
        Seed of the track stand-in and of the estimates.
    surface_stiffness_factor : float
        Stiffness factor on the slatted track (thesis §6.3: 0.9).
    cases : dict of int to dict, optional
        Cases computed before, by row position in ``table_xii``: items of a previous
        result's ``cases`` whose inputs (:func:`carriage_case_inputs`) are unchanged.
        Only the other rows are simulated; the result is the same, to the bit, as
        simulating every row (each run is simulated on its own).
    recordings : dict, optional
        The "measured" side: :func:`carriage_key` ``(speed_km_h, load_condition)`` -> the
        carriage body's vertical acceleration, m/s², at :data:`FS_HZ` from the end of the
        lead-in (the track's start; a recording in the raw ride format, e.g. of the virtual
        carriage of :mod:`tyrelab.vehicle.study_recordings`). A run without one has its
        predictions but no comparison; with none, Tables XIII and XIV have no values.

    Returns
    -------
    dict of DataFrame
        ``runs`` (one row per run with its metrics and ISO 2631 values; ``source``
        ``prediction`` or ``recording``, the latter with ``characteristics`` ``reference``),
        ``comparisons`` (one row per prediction vs recording), ``table_xiii``,
        ``table_xiv`` (ours, layout of the thesis), ``spectra`` (profile spectra);
        ``cases`` (list, per row of ``table_xii``: its runs, comparisons and example
        records, for a later call's ``cases``).

    See Also
    --------
    carriage_case_inputs : what each case reads.
    tyrelab.vehicle.study_recordings.carriage_recordings : the virtual recordings it is compared with.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> from tyrelab.vehicle.published_layouts import carriage_rolling, carriage_stationary
    >>> xii = carriage_rolling(read_published("table_xii")).head(2)      # two of Table XII's runs, for speed
    >>> stationary = carriage_stationary(read_published("table_xii"))
    >>> from tyrelab.vehicle.study_recordings import carriage_recordings
    >>> s = carriage_study(xii, stationary, recordings=carriage_recordings(xii, stationary))
    >>> sorted(s["runs"]["characteristics"].unique()), list(s["table_xiii"].columns[2:])
    (['reference', 'rolling', 'stationary'], ['rolling', 'stationary'])
    """
    _validate.frame("table_xii", table_xii)
    _validate.frame("stationary", stationary)
    _validate.positive_int("seed", seed, minimum=0)
    _validate.positive("surface_stiffness_factor", surface_stiffness_factor)
    conds = table_xii.reset_index(drop=True)
    cases = _given_cases(cases, len(conds), "row positions", "table_xii")
    problems: list[str] = []
    stat = _by_condition(stationary, conds["load_condition"], "stationary", "row", problems)
    _refuse(problems)
    track, lead, est_by_load, x = carriage_track(conds, seed, surface_stiffness_factor)
    recordings = recordings or {}
    todo = [i for i in range(len(conds)) if i not in cases]
    if todo:
        recs = [recordings.get(carriage_key(c)) for c in conds.iloc[todo].to_dict("records")]
        new = _carriage_cases(conds.iloc[todo], stat, x, est_by_load,
                              track.x_m[-1], surface_stiffness_factor, recs)
        cases.update(zip(todo, new))
    ordered = [cases[i] for i in range(len(conds))]
    runs = [r for case in ordered for r in case["runs"]]
    comparisons = pd.DataFrame([r for case in ordered for r in case["comparisons"]])
    records = {k: v for case in ordered for k, v in case["records"].items()}
    kept = comparisons[~comparisons["speed_km_h"].isin([5.0, 7.5])] if len(comparisons) else comparisons
    tables = {est: _accuracy(kept, est) for est in ("surveyed", "recorded")}
    fp = est_by_load[conds["load_condition"].iloc[0]]
    spectra = pr.spectra_table(
        {
            "slat_tops_left": track.left_m,
            "slat_tops_right": track.right_m,
            "surveyed_before_enveloping": fp["surveyed_raw"][lead:-lead],
            "surveyed_enveloped": fp["surveyed"][lead:-lead],
            "recorded_estimate": fp["recorded"][lead:-lead],
            "true_enveloped": fp["true"][lead:-lead],
        },
        track.dx_m,
    )
    spectra.insert(0, "track", track.label)
    return {
        "runs": pd.DataFrame(runs),
        "comparisons": comparisons,
        "table_xiii": tables["surveyed"],
        "table_xiv": tables["recorded"],
        "spectra": spectra,
        "records": records,
        "acceleration_spectra": record_spectra(records, FS_HZ, speed_km_h=12.5),
        "track": track,
        "cases": ordered,
    }


def _carriage_cases(conds: pd.DataFrame, stat: pd.DataFrame, x: np.ndarray, est_by_load: dict, track_end_m: float,
                    surface_stiffness_factor: float, recordings: list) -> list[dict]:
    """The cases of :func:`carriage_study` for the rows ``conds`` (and their ``recordings``, an
    array or None each): each its ``runs`` and ``comparisons`` rows and its example ``records``
    (those of 12.5 km/h, heavy)."""
    speeds = conds["actual_speed_m_s"].to_numpy(float)
    starts, stops = carriage_steps(speeds, track_end_m)
    out = []
    for i, (_, c) in enumerate(conds.iterrows()):
        runs, comps, records = [], [], {}
        v = speeds[i]
        start, stop = int(starts[i]), int(stops[i])
        measured = recordings[i]
        if measured is not None:
            measured = np.asarray(measured, float)
            stop = start + min(stop - start, measured.size)  # a recording may be shorter than the track
            measured = measured[:stop - start]
        base = {
            "speed_km_h": float(c["speed_km_h"]),
            "actual_speed_m_s": v,
            "load_condition": c["load_condition"],
            "load_kg": float(c["load_kg"]),
        }
        if measured is not None:
            nan = float("nan")  # what the recorded carriage is made of is not in its recording
            runs.append(
                {
                    **base,
                    "characteristics": "reference",
                    "profile_estimate": "true",
                    "quoted_stiffness_kN_per_m": nan,
                    "stiffness_kN_per_m": nan,
                    "damping_kN_s_per_m": nan,
                    "parasitic_damping_kN_s_per_m": nan,
                    "coulomb_friction_N": nan,
                    "lift_off_fraction": nan,
                    **mt.record_metrics(measured, FS_HZ),
                    **{f"iso_{k}": val for k, val in iso2631.evaluate(measured, FS_HZ, "z").items()},
                    "source": "recording",
                }
            )
        st = stat.loc[c["load_condition"]]
        chars = {
            "rolling": (float(c["stiffness_kN_per_m"]), float(c["damping_kN_s_per_m"])),
            "stationary": (float(st["stiffness_kN_per_m"]), float(st["damping_kN_s_per_m"])),
        }
        for name, (k_kn, c_kn) in chars.items():
            car = cm.Carriage(float(c["load_kg"]), surface_stiffness_factor * KILO * k_kn, from_kilo(c_kn))
            for estimate in ("surveyed", "recorded"):
                h = est_by_load[c["load_condition"]][estimate]
                _, u, ud = cm.ground_input(x, h, v, DT_S, 0.0, (stop - 1) * v * DT_S + 1e-9)
                pred = cm.simulate_linear(car, u - u[0], ud, DT_S)["a_m_s2"][start:stop]
                if measured is not None:
                    comp = mt.compare_records(pred, measured, FS_HZ)
                    comps.append({**base, "characteristics": name, "profile_estimate": estimate, **comp})
                runs.append(
                    {
                        **base,
                        "characteristics": name,
                        "profile_estimate": estimate,
                        "quoted_stiffness_kN_per_m": k_kn,
                        "stiffness_kN_per_m": surface_stiffness_factor * k_kn,
                        "damping_kN_s_per_m": c_kn,
                        "parasitic_damping_kN_s_per_m": to_kilo(cm.PARASITIC_DAMPING_N_S_PER_M),
                        "coulomb_friction_N": 0.0,
                        "lift_off_fraction": 0.0,
                        **mt.record_metrics(pred, FS_HZ),
                        **{f"iso_{k}": val for k, val in iso2631.evaluate(pred, FS_HZ, "z").items()},
                        "source": "prediction",
                    }
                )
                if c["speed_km_h"] == 12.5 and c["load_condition"] == "heavy":
                    records[(name, estimate)] = pred
        if c["speed_km_h"] == 12.5 and c["load_condition"] == "heavy" and measured is not None:
            records[("reference", "true")] = measured
        out.append({"runs": runs, "comparisons": comps, "records": records})
    return out
