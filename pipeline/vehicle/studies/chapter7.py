"""The chapter 7 study: the MF698T on the slatted and farm tracks, the Table XVIII sweep of the rear
tyres' longitudinal elements and Tables XVII/XVIII (ours) against the recordings
(:mod:`tyrelab.vehicle.studies`)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ... import _validate
from . import carriage as cm
from . import published_layouts as layouts
from ..comfort import iso2631
from ..comfort import metrics as mt
from ..terrain import enveloping as ev
from ..terrain import profiles as pr
from ..tractor import PARAMETERS, Tractor, simulate_tractor
from ..run.track import wheel_inputs
from ..units import from_kilo, km_h_to_m_s, to_kilo
from .shared import (DT_S, FRONT_7_50_18_RADIUS_M, FS_HZ, LEAD_IN_M, SURVEY_ERROR_M, T4_ROLLING_RADIUS_M,
                     _by_condition, _given_cases, _plain, _refuse)

__all__ = ["tractor_case_inputs", "longitudinal_grid", "tractor_study", "tractor_key", "run_metrics",
           "with_tractor_recordings"]
# tractor_tracks, tractor_inputs and tractor_record_window are shared with
# tyrelab.vehicle.study_recordings (the virtual tractor drives the study's tracks and is recorded over
# its windows); not part of the public interface.


def tractor_inputs(profile: pr.Profile, radii, footprints, speed, wheelbase, n_steps):
    """Axle inputs (mean of left/right enveloped tracks), rear delayed by wheelbase/speed: the ride's
    one construction of wheel inputs (:func:`tyrelab.vehicle.run.track.wheel_inputs`, the pitch
    plane) with the study's enveloping, the rigid tread band (``radii``, 0: none) then the tapered
    moving average over the footprint (§7.3)."""
    dx = profile.dx_m

    def enveloped(side, axle, footprint_m, radius_m):  # the axle mean of the two enveloped tracks
        tracks = [ev.tapered_moving_average(ev.rigid_tread_band(profile.track(s), dx, radius_m) if radius_m
                                            else profile.track(s), dx, footprint_m) for s in ("left", "right")]
        return 0.5 * (tracks[0] + tracks[1])

    (uf, ur), (udf, udr) = wheel_inputs(("front", "rear"), False, profile, "tapered",
                                        (footprints["front"], footprints["rear"]), (radii["front"], radii["rear"]),
                                        speed, wheelbase, n_steps, enveloped=enveloped)
    return uf, udf, ur, udr


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

    See Also
    --------
    tractor_study : sweeps these elements.

    Examples
    --------
    >>> g = longitudinal_grid()
    >>> g["kelvin_voigt"][:3], g["maxwell"]
    ([(0.0, 0.0), (455.0, 0.0), (455.0, 1.0)], [(455.0, 1.0), (455.0, 3.0), (455.0, 5.0)])
    """
    if table_xviii is not None:
        _validate.frame("table_xviii", table_xviii)
    if table_xviii is None:
        from ... import published

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

    See Also
    --------
    tractor_study : the study of these cases.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> from tyrelab.vehicle.published_layouts import tractor_mass, tractor_tyres
    >>> cases = tractor_case_inputs(tractor_mass(read_published("table_xv")), tractor_tyres(read_published("table_xvi")))
    >>> len(cases), tractor_key(cases[0]["row"]), cases[0]["farm_class"], cases[0]["duration_s"]
    (28, (1, 'SBT', 10.0), 'D', 30.0)
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

    See Also
    --------
    tractor_case_inputs : what each case reads.
    with_tractor_recordings : compares it with recordings.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> from tyrelab.vehicle.published_layouts import tractor_mass, tractor_tyres
    >>> mass, tyres = tractor_mass(read_published("table_xv")), tractor_tyres(read_published("table_xvi"))
    >>> rolling = tyres["characteristics"] == "rolling"
    >>> one = tyres.loc[~rolling | (tyres.index == tyres.index[rolling][0])]   # the first rolling run, for speed
    >>> s = tractor_study(mass, one)
    >>> s["runs"][["characteristics", "sweep"]].drop_duplicates().values.tolist()    # the run, its stationary twin, the sweep
    [['rolling', False], ['stationary', False], ['rolling', True]]
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

    See Also
    --------
    tractor_study : keys its runs and recordings by it.

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

    See Also
    --------
    tractor_study : the study it completes.
    tyrelab.vehicle.study_recordings.tractor_recordings : the virtual recordings.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> from tyrelab.vehicle.published_layouts import tractor_mass, tractor_tyres
    >>> mass, tyres = tractor_mass(read_published("table_xv")), tractor_tyres(read_published("table_xvi"))
    >>> rolling = tyres["characteristics"] == "rolling"
    >>> one = tyres.loc[~rolling | (tyres.index == tyres.index[rolling][0])]   # the first rolling run, for speed
    >>> from tyrelab.vehicle.study_recordings import tractor_recordings
    >>> s = with_tractor_recordings(tractor_study(mass, one), tractor_recordings(mass, one))
    >>> s["runs"]["source"].value_counts().to_dict()
    {'prediction': 13, 'recording': 1}
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
    the longitudinal). A channel given as None is NaN in the row.

    See Also
    --------
    tyrelab.vehicle.metrics.spectral_peaks : the peaks it reads.

    Examples
    --------
    >>> t = np.arange(0, 60, 1 / FS_HZ)
    >>> m = run_metrics({"speed_km_h": 10.0}, "SBT", np.sin(2 * np.pi * 2 * t) + 0.5 * np.sin(2 * np.pi * 3.5 * t),
    ...                 0.1 * np.sin(2 * np.pi * 3.5 * t), None)
    >>> round(m["vertical_rms_m_s2"], 4), m["first_peak_Hz"], m["second_peak_Hz"], m["iso_longitudinal_weighted_rms_m_s2"]
    (0.7906, 2.0, 3.5, nan)
    """
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
