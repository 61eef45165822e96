"""The chapter 6 and 7 validation studies as pure functions (no file I/O).

**What "measured" means here.** The thesis compared simulations with vibration
recorded on the real carriage and tractor (§6.3, §7.1). Here the "measured" side is
*recordings*: arrays the caller passes (``recordings``), read by the ``simulate`` stage
from the campaign's vehicle recordings (``rides.csv`` rows with a ``study``, ingested by
the ``rides`` stage). Nothing here makes a measured number: the predictions are compared
with whatever was recorded, and a run without a recording has no comparison. The demo
campaign's recordings come from the *virtual carriage and tractor* of
:mod:`tyrelab.vehicle.study_recordings` (``tyrelab generate``), which include what the
linear prediction model leaves out (see ``docs/simulation.md``).

Predictions use the linear models and a profile *estimate*: for the carriage the
"surveyed" estimate (slat tops with ±3 mm survey error, §6.3 a) or the "recorded"
estimate (the enveloped locus plus a 1 mm noise floor and a spurious narrow-band peak at
1.35 cycles/m with 13x the power, as Fig. 51 and §6.5.1 describe; both seeded); for the
tractor the surveyed slatted track (SBT) or the farm track's (HH) survey, another
realisation of the same ISO 8608 class (the thesis' survey was years older than the runs,
§7.3). Every measure of a recording is made by the same function as the prediction's
(:func:`tyrelab.vehicle.metrics.compare_records`, :func:`run_metrics`).

Agreement statistics therefore measure how far the linear prediction is from the
recordings, not from the thesis' tractor; they are reported beside the thesis'.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .. import _validate
from . import carriage as cm
from .terrain import enveloping as ev
from .comfort import iso2631
from .comfort import metrics as mt
from .terrain import profiles as pr
from . import published_layouts as layouts
from .tractor import PARAMETERS, Tractor, simulate_tractor
from .units import KILO, from_kilo, km_h_to_m_s, to_kilo

__all__ = [
    "T4_ROLLING_RADIUS_M",
    "carriage_case_inputs",
    "carriage_study",
    "tractor_case_inputs",
    "longitudinal_grid",
    "tractor_study",
    "carriage_key",
    "tractor_key",
    "run_metrics",
    "with_tractor_recordings",
]
# carriage_track, carriage_steps, tractor_tracks, tractor_inputs and tractor_record_window are
# shared with tyrelab.vehicle.study_recordings (the virtual vehicles drive the studies' tracks
# and are recorded over the studies' windows); not part of the public interface.

#: T4 13.6R38 rolling circumference 4.66 m (thesis §6.5.3) -> radius, m.
T4_ROLLING_RADIUS_M = 4.66 / (2 * math.pi)
#: Approximate 7.50-18 front tyre radius, m (0.8 m overall diameter).
FRONT_7_50_18_RADIUS_M = 0.40
#: Survey error of slat heights (uniform, ±), m (thesis §6.3 a: ±3 mm).
SURVEY_ERROR_M = 0.003
#: Recorded-estimate noise floor (rms), m (§6.5.1: about 1 mm).
RECORDED_NOISE_RMS_M = 0.001
#: Recorded-estimate spurious peak (§6.5.1): centre, half-width (cycles/m), power factor.
RECORDED_SPIKE = (1.35, 0.05, 13.0)
DT_S = 1e-3
LEAD_IN_M = 5.0
FS_HZ = 1.0 / DT_S


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


def _by_condition(table: pd.DataFrame, needed, name: str, what: str, problems: list[str]) -> pd.DataFrame:
    """``table`` indexed by ``load_condition``; appends to ``problems`` each condition of ``needed``
    without a row, or with more than one (``name`` and ``what`` word the message)."""
    indexed = table.set_index("load_condition")
    missing = [str(c) for c in dict.fromkeys(needed) if c not in indexed.index]
    repeated = sorted({str(c) for c in indexed.index[indexed.index.duplicated()]})
    if missing:
        problems.append(f"{name} has no {what} for load condition {', '.join(missing)}")
    if repeated:
        problems.append(f"{name} has more than one {what} for load condition {', '.join(repeated)}")
    return indexed


def _given_cases(cases: dict | None, n: int, positions: str, table: str) -> dict:
    """A copy of a study's ``cases`` argument, checked to be keyed by positions 0..n-1 of ``table``."""
    cases = dict(cases or {})
    if any(not isinstance(i, (int, np.integer)) or not 0 <= i < n for i in cases):
        raise ValueError(f"cases must be keyed by {positions} 0..{n - 1} of {table}, got {sorted(cases)!r}")
    return cases


def _refuse(problems: list[str]) -> None:
    """Raise every problem of the studies' tables at once (ValueError)."""
    if problems:
        raise ValueError("; ".join(problems))


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


def record_spectra(records: dict, fs_Hz: float, speed_km_h: float, f_max_Hz: float = 10.0) -> pd.DataFrame:
    """Acceleration PSDs (0.1 Hz bandwidth, §7.4) of the example records of Fig. 56.

    Parameters
    ----------
    records : dict
        ``(characteristics, profile estimate) -> acceleration record`` (m/s²).
    fs_Hz : float
        Sampling rate, Hz.
    speed_km_h : float
        Speed of the records (for the table), km/h.
    f_max_Hz : float
        Highest frequency kept, Hz.

    Returns
    -------
    DataFrame
        ``speed_km_h, series, frequency_Hz, psd_m2_s4_per_Hz``; the series
        ``reference (true)`` is the "measured" side.
    """
    rows = []
    for (name, estimate), a in sorted(records.items()):
        f, p = mt.acceleration_psd(a, fs_Hz)
        keep = f <= f_max_Hz
        rows.append(pd.DataFrame({"speed_km_h": speed_km_h, "series": f"{name} ({estimate})",
                                  "frequency_Hz": f[keep], "psd_m2_s4_per_Hz": p[keep]}))
    return pd.concat(rows, ignore_index=True) if rows else pd.DataFrame(
        columns=["speed_km_h", "series", "frequency_Hz", "psd_m2_s4_per_Hz"])


def tractor_inputs(profile: pr.Profile, radii, footprints, speed, wheelbase, n_steps):
    """Axle inputs (mean of left/right enveloped tracks), rear delayed by wheelbase/speed."""
    dx = profile.dx_m
    out = []
    for axle, offset in (("front", wheelbase), ("rear", 0.0)):
        tracks = [
            ev.tapered_moving_average(ev.rigid_tread_band(profile.track(s), dx, radii[axle]) if radii[axle] else profile.track(s), dx, footprints[axle])
            for s in ("left", "right")
        ]
        h = 0.5 * (tracks[0] + tracks[1])
        out.append(cm.half_step_input(profile.x_m, h, speed, n_steps, x_start_m=offset, dt_s=DT_S))
    (uf, udf), (ur, udr) = out
    u0 = 0.5 * (uf[0] + ur[0])
    return uf - u0, udf, ur - u0, udr


def _plain(row) -> dict:
    """A table row as a dict of Python scalars (a cache key's input)."""
    return {k: (v.item() if hasattr(v, "item") else v) for k, v in dict(row).items()}


def _tractor_conditions(table_xv: pd.DataFrame, table_xvi: pd.DataFrame, rolling: pd.DataFrame):
    """Table XV and the stationary rows of Table XVI by load condition, each rolling row's condition
    present once in both (ValueError naming every problem otherwise)."""
    problems: list[str] = []
    needed = rolling["load_condition"].astype(int)
    xv = _by_condition(table_xv, needed, "table_xv", "row", problems)
    stat = _by_condition(table_xvi[table_xvi["characteristics"] == "stationary"], needed, "table_xvi",
                         "stationary row", problems)
    _refuse(problems)
    return xv, stat


def longitudinal_grid(table_xviii: pd.DataFrame | None = None) -> dict[str, list[tuple[float, float]]]:
    """The Table XVIII sweep's rear longitudinal elements per model, (k, c) per tyre in kN/m and
    kN s/m: Kelvin-Voigt at the thesis' predicted rows, in their order; Maxwell (§7.5's proposal,
    our addition) at those of them with both a spring and a damper.

    Examples
    --------
    >>> g = longitudinal_grid()
    >>> g["kelvin_voigt"][:3], g["maxwell"]
    ([(0.0, 0.0), (455.0, 0.0), (455.0, 1.0)], [(455.0, 1.0), (455.0, 3.0), (455.0, 5.0)])
    """
    if table_xviii is not None:
        _validate.frame("table_xviii", table_xviii)
    if table_xviii is None:
        from .. import published

        table_xviii = published.read_published("table_xviii")
    measured = table_xviii["is_measured"].astype(str).str.lower().isin(["true", "1"])
    rows = table_xviii[~measured]
    kv = [(float(k), float(c)) for k, c in zip(rows["longitudinal_stiffness_kN_per_m"],
                                               rows["longitudinal_damping_kN_s_per_m"])]
    return {"kelvin_voigt": kv, "maxwell": [(k, c) for k, c in kv if k > 0 and c > 0]}


def tractor_case_inputs(
    table_xv: pd.DataFrame, table_xvi: pd.DataFrame, farm_class: str = "D", duration_s: float = 30.0,
    table_xviii: pd.DataFrame | None = None,
) -> list[dict]:
    """What each case of :func:`tractor_study` reads, one dict per rolling row of ``table_xvi``.

    A case is one rolling row of Table XVI (load condition, track, speed): its rolling,
    stationary and reference runs (and, for load condition 1 on SBT at 10 km/h, the
    Table XVIII sweep). It reads its row, the stationary row and the Table XV row of
    its load condition, and the study's track and duration; with the seed that is
    everything (the tracks are seeded). A cache keyed on these (the simulate stage's)
    recomputes only the cases whose inputs changed. The sweep's case also reads the
    longitudinal elements of ``table_xviii`` (:func:`longitudinal_grid`, default the shipped one).
    """
    _validate.frame("table_xv", table_xv)
    _validate.frame("table_xvi", table_xvi)
    _validate.choice("farm_class", farm_class, tuple("ABCDEFGH"))
    _validate.positive("duration_s", duration_s)
    rolling = table_xvi[table_xvi["characteristics"] == "rolling"].reset_index(drop=True)
    xv, stat = _tractor_conditions(table_xv, table_xvi, rolling)
    out = []
    for _, r in rolling.iterrows():
        case = {"row": _plain(r), "stationary": _plain(stat.loc[int(r["load_condition"])]),
                "mass": _plain(xv.loc[int(r["load_condition"])]), "farm_class": farm_class, "duration_s": float(duration_s)}
        if _is_sweep_case(r):
            case["longitudinal_grid"] = longitudinal_grid(table_xviii)
        out.append(case)
    return out


def _is_sweep_case(row) -> bool:
    """The rolling row that holds the Table XVIII sweep: load condition 1, SBT, 10 km/h."""
    return int(row["load_condition"]) == 1 and row["track"] == "SBT" and row["speed_km_h"] == 10


def tractor_study(
    table_xv: pd.DataFrame,
    table_xvi: pd.DataFrame,
    seed: int = 5007,
    farm_class: str = "D",
    duration_s: float = 30.0,
    cases: dict | None = None,
    table_xviii: pd.DataFrame | None = None,
    recordings: dict | None = None,
) -> dict[str, pd.DataFrame]:
    """Chapter 7: MF698T on the slatted track (SBT) and a farm track (HH).

    Runs every rolling row of Table XVI with (a) the rolling and (b) the stationary
    characteristics (both Kelvin-Voigt vertical only, no longitudinal element, lift-off
    allowed, profile estimate), and compares them with (c) the recordings of the runs
    (``recordings``, :func:`with_tractor_recordings`).
    Then the Table XVIII sweep at 10 km/h, SBT, load condition 1: rear Kelvin-Voigt
    longitudinal element for the thesis' (k, c) pairs, plus Maxwell variants.

    Stationary characteristics are used as printed on both tracks (not reduced on
    SBT); Table XVII's stationary frequency ratios (1.20 SBT vs 1.14 HH ≈ 1.14/√0.9)
    suggest the thesis did the same.

    Parameters
    ----------
    table_xv, table_xvi : DataFrame
        Tractor mass properties per load condition; rolling and stationary tyre
        characteristics (:mod:`tyrelab.vehicle.published_layouts`).
    seed : int
        Seed of the tracks and estimates.
    farm_class : str
        ISO 8608 class of the farm track (HH).
    duration_s : float
        Length of a run, s.
    table_xviii : DataFrame, optional
        Thesis Table XVIII (its predicted rows give the longitudinal sweep's (k, c) pairs,
        :func:`longitudinal_grid`); default the shipped one (:mod:`tyrelab.published`).
    cases : dict of int to list, optional
        Cases computed before, by position among the rolling rows of ``table_xvi``:
        items of a previous result's ``cases`` whose inputs (:func:`tractor_case_inputs`)
        are unchanged. Only the other cases are simulated; the result is the same, to
        the bit, as simulating all of them (the batched tractor runs are independent).
        A case holds predictions only: the recordings are compared afresh each call.
    recordings : dict, optional
        The "measured" side (:func:`with_tractor_recordings`); without any, Table XVII has
        no values.

    Returns
    -------
    dict of DataFrame
        ``runs`` (per run: rms 0.5-10 Hz, peaks, ISO 2631), ``table_xvii`` (ours),
        ``table_xviii`` (ours), ``spectra`` (farm track profiles); ``cases`` (list, per
        rolling row: its runs, for a later call's ``cases``).
    """
    _validate.frame("table_xv", table_xv)
    _validate.frame("table_xvi", table_xvi)
    _validate.positive_int("seed", seed, minimum=0)
    _validate.choice("farm_class", farm_class, tuple("ABCDEFGH"))
    _validate.positive("duration_s", duration_s)
    tracks = tractor_tracks(seed, farm_class)
    hh_est, hh_true, sbt_est = tracks["HH estimate"], tracks["HH"], tracks["SBT estimate"]
    rolling = table_xvi[table_xvi["characteristics"] == "rolling"].reset_index(drop=True)
    xv, stat = _tractor_conditions(table_xv, table_xvi, rolling)
    cases = _given_cases(cases, len(rolling), "rolling-row positions", "table_xvi")

    specs = []  # per case: [(label dict, tractor kwargs, profile, radii flag)]
    for _, r in rolling.iterrows():
        case = []
        lc = int(r["load_condition"])
        g = xv.loc[lc]
        base = dict(
            mass_kg=g["mass_kg"],
            pitch_inertia_kg_m2=g["pitch_inertia_kg_m2"],
            front_distance_m=g["wheelbase_m"] - g["cg_to_rear_axle_m"],
            rear_distance_m=g["cg_to_rear_axle_m"],
            cg_height_m=g["cg_height_m"],
        )
        label = {"load_condition": lc, "track": r["track"], "speed_km_h": float(r["speed_km_h"])}
        roll_k = layouts.tractor_axles_si(r)
        stat_k = layouts.tractor_axles_si(stat.loc[lc])
        est = sbt_est if r["track"] == "SBT" else hh_est
        case.append(({**label, "characteristics": "rolling", "longitudinal": "none"}, {**base, **roll_k}, est, r["track"] != "SBT"))
        case.append(({**label, "characteristics": "stationary", "longitudinal": "none"}, {**base, **stat_k}, est, r["track"] != "SBT"))
        if _is_sweep_case(r):
            for model, pairs in longitudinal_grid(table_xviii).items():
                for k_kn, c_kn in pairs:
                    case.append(
                        (
                            {**label, "characteristics": "rolling", "longitudinal": model, "sweep": True,
                             "longitudinal_stiffness_kN_per_m": float(k_kn), "longitudinal_damping_kN_s_per_m": float(c_kn)},
                            {**base, **roll_k, "longitudinal_stiffness_N_per_m": 2 * from_kilo(k_kn),
                             "longitudinal_damping_N_s_per_m": 2 * from_kilo(c_kn), "longitudinal_model": model},
                            est,
                            False,
                        )
                    )  # fmt: skip
        specs.append(case)

    # every run in the order of the longitudinal models (a stable sort of the cases' runs)
    models = ("none", "kelvin_voigt", "maxwell")
    order = [(i, j) for model in models for i, case in enumerate(specs) for j, spec in enumerate(case)
             if spec[1].get("longitudinal_model", "none") == model]
    todo = [(i, j) for i, j in order if i not in cases]
    if todo:
        rows = _tractor_runs([specs[i][j] for i, j in todo], duration_s)
        new = {i: [None] * len(specs[i]) for i, _ in todo}
        for (i, j), row in zip(todo, rows):
            new[i][j] = row
        cases.update(new)
    results = [cases[i][j] for i, j in order]
    ordered = [cases[i] for i in range(len(specs))]
    spectra = pr.spectra_table(
        {"farm_track_estimate_left": hh_est.left_m, "farm_track_reference_left": hh_true.left_m}, hh_est.dx_m
    )
    spectra.insert(0, "track", hh_est.label)
    predicted = pd.DataFrame(results).assign(source="prediction")
    return {**with_tractor_recordings({"runs": predicted, "spectra": spectra}, recordings), "cases": ordered}


def tractor_tracks(seed: int = 5007, farm_class: str = "D") -> dict:
    """The tracks of the tractor study, each with its lead-in: ``SBT`` (the true slatted track,
    gaps resolved; the tread band is applied per axle), ``SBT estimate`` (slat tops with the
    survey error, seed ``seed + 1``), ``HH`` (the farm track driven: a realisation of ISO 8608
    class ``farm_class``, seed ``seed + 11``) and ``HH estimate`` (the survey, another
    realisation, seed ``seed + 10``: the thesis' survey was years older than the runs, §7.3).
    The predictions read the estimates; the virtual tractor that records the "measured" runs
    (:mod:`tyrelab.vehicle.study_recordings`) drives over ``SBT`` and ``HH``."""
    hh_est = pr.add_lead_in(pr.iso8608_track(farm_class, seed=seed + 10), LEAD_IN_M)
    hh_true = pr.add_lead_in(pr.iso8608_track(farm_class, seed=seed + 11), LEAD_IN_M)
    rng = np.random.default_rng(seed + 1)
    base_track = pr.slatted_track(seed=seed)
    noisy = {}
    for side in ("left", "right"):
        slats = base_track.meta[f"{side}_slats_m"] + rng.uniform(-SURVEY_ERROR_M, SURVEY_ERROR_M,
                                                                 base_track.meta["slat_x_m"].size)
        noisy[side] = np.interp(base_track.x_m, base_track.meta["slat_x_m"], slats)
    sbt_est = pr.add_lead_in(base_track.replace(left_m=noisy["left"], right_m=noisy["right"]), LEAD_IN_M)
    sbt_true = pr.add_lead_in(
        base_track.replace(left_m=pr.slat_surface(base_track, "left"), right_m=pr.slat_surface(base_track, "right")),
        LEAD_IN_M,
    )
    return {"SBT": sbt_true, "SBT estimate": sbt_est, "HH": hh_true, "HH estimate": hh_est}


def tractor_key(row: dict) -> tuple[int, str, float]:
    """The key of a tractor run (a Table XVI row or a recording): ``(load_condition, track, speed_km_h)``.

    Examples
    --------
    >>> tractor_key({"load_condition": "1", "track": "SBT", "speed_km_h": 10})
    (1, 'SBT', 10.0)
    """
    try:
        lc, track, speed = int(float(row["load_condition"])), row["track"], float(row["speed_km_h"])
    except (KeyError, TypeError, ValueError):
        lc = track = None
    if lc is None or track not in ("SBT", "HH"):
        raise ValueError(f"row: needs a load_condition number, a track SBT or HH and a speed_km_h, got {row!r:.120}")
    return lc, str(track), speed


def with_tractor_recordings(study: dict, recordings: dict | None) -> dict:
    """A tractor study's tables with its predictions compared against ``recordings``.

    Parameters
    ----------
    study : dict
        :func:`tractor_study`'s result (its ``runs`` with ``source`` ``prediction`` are kept;
        rows of earlier recordings are replaced).
    recordings : dict or None
        :func:`tractor_key` -> ``{"label": str, "vertical_m_s2", "pitch_rad_s2",
        "longitudinal_m_s2": arrays at FS_HZ}`` (any missing channel NaN-valued). Their
        rows (``characteristics`` ``reference``) are measured by the same
        :func:`run_metrics` as the predictions. Without any, Table XVII has no values.
    """
    if not isinstance(study, dict) or not {"runs", "spectra"} <= set(study):
        raise ValueError("study: expected tractor_study's result (a dict with runs and spectra)")
    if recordings is not None and not isinstance(recordings, dict):
        raise ValueError(f"recordings: expected a dict (tractor_key -> channels), got {type(recordings).__name__}")
    runs = study["runs"]
    runs = runs[runs["source"] == "prediction"]
    rows = []
    for key, rec in sorted((recordings or {}).items()):
        lc, track, speed = key
        label = {"load_condition": lc, "track": track, "speed_km_h": speed, "characteristics": "reference",
                 "longitudinal": "recorded"}
        rows.append({**run_metrics(label, rec.get("label", "recording"), rec.get("vertical_m_s2"),
                                   rec.get("pitch_rad_s2"), rec.get("longitudinal_m_s2")),
                     "method_used": "recording", "source": "recording"})
    if rows:
        runs = pd.concat([runs, pd.DataFrame(rows)], ignore_index=True)
    return {**study, **_tractor_tables(runs.reset_index(drop=True)), "spectra": study["spectra"]}


def _tractor_runs(group: list, duration_s: float) -> list[dict]:
    """The result rows of the tractor runs ``group`` (specs of :func:`tractor_study`), simulated in one batch."""
    n_steps = int(round(duration_s / DT_S)) + 1 + int(round(LEAD_IN_M / (km_h_to_m_s(10) * DT_S)))
    results = []
    input_cache: dict = {}
    input_keys = []
    for label, kw, prof, farm in group:
        v = km_h_to_m_s(label["speed_km_h"])
        wb = kw["front_distance_m"] + kw["rear_distance_m"]
        key = (id(prof), v, wb)
        if key not in input_cache:
            radii = {"front": 0.0 if farm else FRONT_7_50_18_RADIUS_M, "rear": 0.0 if farm else T4_ROLLING_RADIUS_M}
            input_cache[key] = tractor_inputs(prof, radii, {"front": 0.25, "rear": 0.45}, v, wb, n_steps)
        input_keys.append(key)
    arrs = [np.array([input_cache[key][j] for key in input_keys]) for j in range(4)]
    del input_cache
    params = {k: np.array([g[1].get(k, 0.0) for g in group], float) for k in PARAMETERS}
    models = np.array([g[1].get("longitudinal_model", "none") for g in group], dtype=object)
    sim = simulate_tractor(Tractor(**params, longitudinal_model=models), *arrs, DT_S,
                           gravity_m_s2=cm.THESIS_GRAVITY_M_S2)
    del arrs
    for i, (label, kw, prof, farm) in enumerate(group):
        wb = kw["front_distance_m"] + kw["rear_distance_m"]
        start, stop = tractor_record_window(label, wb, prof.x_m[-1], duration_s)
        row = run_metrics(label, prof.label, sim["vertical_m_s2"][i, start:stop], sim["pitch_rad_s2"][i, start:stop],
                          sim["longitudinal_m_s2"][i, start:stop])
        row.update({
            **{f"{k}_kN{unit}": to_kilo(kw.get(f"{k}_N{unit}", 0.0)) / 2  # per tyre (an axle is two)
               for k, unit in (("front_stiffness", "_per_m"), ("rear_stiffness", "_per_m"), ("front_damping", "_s_per_m"),
                               ("rear_damping", "_s_per_m"), ("longitudinal_stiffness", "_per_m"),
                               ("longitudinal_damping", "_s_per_m"))},
            "lift_off_fraction_front": float(sim["lift_off_fraction_front"][i]),
            "lift_off_fraction_rear": float(sim["lift_off_fraction_rear"][i]),
            "method_used": str(sim["method_used"][i]),
        })
        results.append(row)
    return results


def tractor_record_window(label: dict, wheelbase_m: float, track_length_m: float, duration_s: float = 30.0) -> tuple[int, int]:
    """``(start, stop)`` samples of a tractor run's record (at :data:`FS_HZ`, from the start of
    the lead-in): from when the front axle reaches the track, ``duration_s`` long (on SBT at
    most the track's length)."""
    v = km_h_to_m_s(label["speed_km_h"])
    start = int(math.ceil((LEAD_IN_M - wheelbase_m) / (v * DT_S))) if LEAD_IN_M > wheelbase_m else 0
    length = min(duration_s, (track_length_m - 2 * LEAD_IN_M) / v) if label["track"] == "SBT" else duration_s
    return start, start + int(round(length / DT_S))


def run_metrics(label: dict, profile: str, vertical_m_s2, pitch_rad_s2, longitudinal_m_s2) -> dict:
    """The chapter 7 measures of one tractor record, predicted or recorded alike (thesis §7.4):
    r.m.s. 0.5-10 Hz of the vertical and pitch accelerations from their 0.1 Hz PSDs, the two
    and three highest peaks of the vertical PSD, ISO 2631-1 values (W_k on the vertical, W_d on
    the longitudinal). A channel given as None is NaN in the row."""
    nan = float("nan")
    n = int(10 * FS_HZ)  # the 0.1 Hz PSD needs 10 s
    vert = _validate.finite_array("vertical_m_s2", vertical_m_s2, min_samples=n)
    pitch = None if pitch_rad_s2 is None else _validate.finite_array("pitch_rad_s2", pitch_rad_s2, min_samples=n)
    lon = None if longitudinal_m_s2 is None else _validate.finite_array("longitudinal_m_s2", longitudinal_m_s2,
                                                                       min_samples=n)
    fv, pv = mt.acceleration_psd(vert, FS_HZ, 0.1)
    peaks = mt.spectral_peaks(fv, pv, 3)
    two = mt.spectral_peaks(fv, pv, 2)
    if pitch is not None:
        fp, pp = mt.acceleration_psd(pitch, FS_HZ, 0.1)
    iso_z = iso2631.evaluate(vert, FS_HZ, "z")
    iso_x = iso2631.evaluate(lon, FS_HZ, "x") if lon is not None else {"weighted_rms_m_s2": nan, "a8_m_s2": nan}
    a8 = max(iso_z["a8_m_s2"], iso_x["a8_m_s2"]) if lon is not None else iso_z["a8_m_s2"]
    return {
        "sweep": bool(label.get("sweep", False)),
        **label,
        "profile": profile,
        "duration_s": vert.size / FS_HZ,
        "vertical_rms_m_s2": mt.band_rms(fv, pv, 0.5, 10.0),
        "pitch_rms_rad_s2": mt.band_rms(fp, pp, 0.5, 10.0) if pitch is not None else nan,
        "first_peak_Hz": two[0],
        "second_peak_Hz": two[1],
        "peak_1_Hz": peaks[0],
        "peak_2_Hz": peaks[1],
        "peak_3_Hz": peaks[2],
        "iso_vertical_weighted_rms_m_s2": iso_z["weighted_rms_m_s2"],
        "iso_longitudinal_weighted_rms_m_s2": iso_x["weighted_rms_m_s2"],
        "iso_vertical_vdv_m_s1_75": iso_z["vdv_m_s1_75"],
        "iso_vertical_crest_factor": iso_z["crest_factor"],
        "iso_a8_m_s2": a8,
        "iso_exceeds_action": bool(a8 > iso2631.EU_ACTION_A8_M_S2),
        "iso_exceeds_limit": bool(a8 > iso2631.EU_LIMIT_A8_M_S2),
    }


def _tractor_tables(runs: pd.DataFrame) -> dict:
    """Tables XVII, XVIII and the Table XVIII reference row (recorded) from the runs."""
    main = runs[~runs["sweep"].astype(bool)]
    keys = ["load_condition", "track", "speed_km_h"]
    ref = main[main["characteristics"] == "reference"].set_index(keys)
    rows = []
    for name in ("rolling", "stationary"):
        p = main[(main["characteristics"] == name)].set_index(keys)
        joined = p.merge(ref, left_index=True, right_index=True, how="left", suffixes=("", "_ref"))
        for track in ("SBT", "HH"):
            j = joined[joined.index.get_level_values("track") == track]
            for q, col in (
                ("vertical_rms", "vertical_rms_m_s2"),
                ("pitch_rms", "pitch_rms_rad_s2"),
                ("first_peak_frequency", "first_peak_Hz"),
                ("second_peak_frequency", "second_peak_Hz"),
            ):
                st = mt.ratio_error_statistics(j[col] / j[f"{col}_ref"])
                for stat_name, key in (("mean_ratio_error", "mean"), ("sd_ratio_error", "sd"), ("p_within_10", "p_within_10"), ("p_within_30", "p_within_30")):
                    rows.append({"track": track, "quantity": q, "statistic": stat_name, "characteristics": name, "value": st[key]})
    xvii = pd.DataFrame(rows).pivot_table(index=["track", "quantity", "statistic"], columns="characteristics", values="value", sort=False, dropna=False).reset_index()
    xvii.columns.name = None
    xvii = xvii.rename(columns={"rolling": "ours_rolling", "stationary": "ours_stationary"})
    sweep = runs[runs["sweep"].astype(bool)][
        ["longitudinal", "longitudinal_stiffness_kN_per_m", "longitudinal_damping_kN_s_per_m", "vertical_rms_m_s2",
         "pitch_rms_rad_s2", "peak_1_Hz", "peak_2_Hz", "peak_3_Hz"]
    ].reset_index(drop=True)  # fmt: skip
    ref_row = main[(main["characteristics"] == "reference") & (main["load_condition"] == 1) & (main["track"] == "SBT") & (main["speed_km_h"] == 10)]
    return {"runs": runs, "table_xvii": xvii, "table_xviii": sweep, "reference_xviii": ref_row}
