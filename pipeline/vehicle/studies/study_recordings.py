"""Recordings of the thesis' carriage and MF698T from virtual vehicles (chapters 6-7; issue 24).

The thesis compared its predictions with accelerations *recorded* on the carriage (ch. 6) and
the MF698T (ch. 7) and "subjected to exactly the same analysis" (§6.3). We have no such tapes,
so ``tyrelab generate`` writes recordings in the raw ride format (:mod:`tyrelab.rawformat.rides`)
made by *virtual* vehicles that include what the linear prediction models leave out; the
``simulate`` stage then compares its predictions with the recordings it is given, as it would
with a lab's own (:mod:`tyrelab.vehicle.studies`). Nothing of this module runs in the pipeline.

virtual carriage (ch. 6, one recording per Table XII rolling row)
    tyre stiffness 0.9 x rolling (the slat-surface drop of Table V) and rolling damping;
    linkage friction as Coulomb friction (:data:`CARRIAGE_COULOMB_FRICTION_N`) instead of the
    1 kN s/m viscous damper the thesis assumed (§6.5.2 names it as the likely error); tyre
    lift-off; the true slat surface, gaps included, enveloped by a rigid tread band then the
    tapered moving average (:func:`tyrelab.vehicle.studies.carriage_track`). Channel
    ``floor_z_m_s2``: the carriage body's vertical acceleration.
virtual MF698T (ch. 7, one recording per Table XVI rolling row)
    the rolling Table XVI characteristics, a Maxwell rear longitudinal element
    (:data:`TRACTOR_LONGITUDINAL`, §7.5's proposal), lift-off, the true slatted track (SBT) or,
    for the farm track (HH), the realisation driven, not the one surveyed
    (:func:`tyrelab.vehicle.studies.tractor_tracks`). Channels ``floor_z_m_s2`` (vertical),
    ``pitch_rad_s2`` and ``floor_x_m_s2`` (fore-aft) at the body's reference point.

Each recording starts where the study's record starts (the end of the carriage's lead-in, the
front axle reaching the tractor's track), at the studies' 1 kHz, and carries seeded
accelerometer noise (:data:`NOISE_M_S2`, :data:`PITCH_NOISE_RAD_S2`, white, seeded from
(seed, ride_id)), stored as float32 as a 24-bit logger would: the studies' numbers move by
this noise only (``docs/simulation.md`` says by how much). The tracks are the studies' own
(seeded by :data:`TRACK_SEED`, the ``simulate`` stage's seed): the vehicle and the prediction
share the track, as the thesis' did; only the noise follows the campaign's seed.
"""

from __future__ import annotations

import zlib

import numpy as np
import pandas as pd

from ... import _validate
from . import carriage as cm
from . import published_layouts as layouts
from .. import studies
from ..tractor import PARAMETERS, Tractor, simulate_tractor
from ..units import KILO, from_kilo, km_h_to_m_s

__all__ = ["TRACK_SEED", "CARRIAGE_COULOMB_FRICTION_N", "TRACTOR_LONGITUDINAL", "NOISE_M_S2",
           "PITCH_NOISE_RAD_S2", "carriage_recordings", "tractor_recordings", "study_recordings"]

#: Seed of the studies' tracks (the ``simulate`` stage's ``SEED``): the recorded and predicted
#: runs drive the same track.
TRACK_SEED = 5007
#: Linkage friction of the virtual carriage, N.
CARRIAGE_COULOMB_FRICTION_N = 150.0
#: Rear longitudinal Maxwell element per tyre of the virtual MF698T (N/m, N s/m; §7.5).
TRACTOR_LONGITUDINAL = (455e3, 3e3)
#: Accelerometer noise, r.m.s., m/s² (as :data:`tyrelab.vehicle.virtual_rides.SENSOR_NOISE_M_S2`).
NOISE_M_S2 = 0.02
#: Pitch channel noise, r.m.s., rad/s² (two vertical accelerometers 2 m apart, each 0.02 m/s²,
#: differenced: 0.02·√2 / 2 ≈ 0.014).
PITCH_NOISE_RAD_S2 = 0.014
#: Nominal recording dates (the thesis gives none per run).
CARRIAGE_DAY, TRACTOR_DAY = "1990-06-20", "1990-09-12"


def carriage_recordings(table_xii: pd.DataFrame, stationary: pd.DataFrame, seed: int = TRACK_SEED,
                        surface_stiffness_factor: float = 0.9) -> dict:
    """The virtual carriage's record of every Table XII rolling row (noise-free).

    Parameters
    ----------
    table_xii, stationary : DataFrame
        As :func:`tyrelab.vehicle.studies.carriage_study` reads them.
    seed : int
        Seed of the track.
    surface_stiffness_factor : float
        Stiffness factor on the slatted track (thesis §6.3: 0.9).

    Returns
    -------
    dict
        :func:`~tyrelab.vehicle.studies.carriage_key` -> vertical acceleration, m/s², at
        :data:`tyrelab.vehicle.studies.FS_HZ` from the end of the lead-in.

    See Also
    --------
    tractor_recordings : the tractor study's.
    tyrelab.vehicle.studies.carriage_study : the study that reads them.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> from tyrelab.vehicle.published_layouts import carriage_rolling, carriage_stationary
    >>> xii = carriage_rolling(read_published("table_xii")).head(2)      # two of Table XII's runs, for speed
    >>> stationary = carriage_stationary(read_published("table_xii"))
    >>> rec = carriage_recordings(xii, stationary)
    >>> list(rec)
    [(17.5, 'light'), (17.5, 'heavy')]
    """
    _validate.frame("table_xii", table_xii)
    _validate.frame("stationary", stationary)
    _validate.positive_int("seed", seed, minimum=0)
    _validate.positive("surface_stiffness_factor", surface_stiffness_factor)
    conds = table_xii.reset_index(drop=True)
    track, lead, est_by_load, x = studies.carriage_track(conds, seed, surface_stiffness_factor)
    speeds = conds["actual_speed_m_s"].to_numpy(float)
    starts, stops = studies.carriage_steps(speeds, track.x_m[-1])
    n_max = int(stops.max())
    uh = np.empty((len(conds), 2 * n_max - 1))
    udh = np.empty_like(uh)
    for i, c in enumerate(conds.to_dict("records")):
        u, ud = cm.half_step_input(x, est_by_load[c["load_condition"]]["true"], speeds[i], n_max, dt_s=studies.DT_S)
        uh[i], udh[i] = u - u[0], ud
    car = cm.Carriage(
        mass_kg=conds["load_kg"].to_numpy(float),
        stiffness_N_per_m=surface_stiffness_factor * KILO * conds["stiffness_kN_per_m"].to_numpy(float),
        damping_N_s_per_m=from_kilo(conds["damping_kN_s_per_m"].to_numpy(float)),
        parasitic_damping_N_s_per_m=0.0,
        coulomb_friction_N=CARRIAGE_COULOMB_FRICTION_N,
    )
    ref = cm.simulate_nonlinear(car, uh, udh, studies.DT_S, lift_off=True, n_steps=stops)
    return {studies.carriage_key(c): ref["a_m_s2"][i, int(starts[i]):int(stops[i])].copy()
            for i, c in enumerate(conds.to_dict("records"))}


def tractor_recordings(table_xv: pd.DataFrame, table_xvi: pd.DataFrame, seed: int = TRACK_SEED,
                       farm_class: str = "D", duration_s: float = 30.0) -> dict:
    """The virtual MF698T's record of every Table XVI rolling row (noise-free).

    Returns
    -------
    dict
        :func:`~tyrelab.vehicle.studies.tractor_key` -> ``{"vertical_m_s2", "pitch_rad_s2",
        "longitudinal_m_s2"}`` at :data:`tyrelab.vehicle.studies.FS_HZ`, the study's record
        window (:func:`~tyrelab.vehicle.studies.tractor_record_window`).

    See Also
    --------
    carriage_recordings : the carriage study's.
    tyrelab.vehicle.studies.tractor_study : the study that reads them.

    Examples
    --------
    >>> from tyrelab.published import read_published
    >>> from tyrelab.vehicle.published_layouts import tractor_mass, tractor_tyres
    >>> mass, tyres = tractor_mass(read_published("table_xv")), tractor_tyres(read_published("table_xvi"))
    >>> rolling = tyres["characteristics"] == "rolling"
    >>> one = tyres.loc[~rolling | (tyres.index == tyres.index[rolling][0])]   # the first rolling run, for speed
    >>> rec = tractor_recordings(mass, one)
    >>> list(rec), sorted(rec[(1, "SBT", 10.0)])
    ([(1, 'SBT', 10.0)], ['longitudinal_m_s2', 'pitch_rad_s2', 'vertical_m_s2'])
    """
    _validate.frame("table_xv", table_xv)
    _validate.frame("table_xvi", table_xvi)
    _validate.positive_int("seed", seed, minimum=0)
    _validate.choice("farm_class", farm_class, tuple("ABCDEFGH"))
    _validate.positive("duration_s", duration_s)
    tracks = studies.tractor_tracks(seed, farm_class)
    rolling = table_xvi[table_xvi["characteristics"] == "rolling"].reset_index(drop=True)
    xv = table_xv.set_index(table_xv["load_condition"].astype(int))
    kx, cx = TRACTOR_LONGITUDINAL
    n_steps = int(round(duration_s / studies.DT_S)) + 1 + int(round(studies.LEAD_IN_M / (km_h_to_m_s(10) * studies.DT_S)))
    runs, inputs = [], []
    for r in rolling.to_dict("records"):
        g = xv.loc[int(r["load_condition"])]
        kw = {"mass_kg": g["mass_kg"], "pitch_inertia_kg_m2": g["pitch_inertia_kg_m2"],
              "front_distance_m": g["wheelbase_m"] - g["cg_to_rear_axle_m"], "rear_distance_m": g["cg_to_rear_axle_m"],
              "cg_height_m": g["cg_height_m"],
              **layouts.tractor_axles_si(r),
              "longitudinal_stiffness_N_per_m": 2 * kx, "longitudinal_damping_N_s_per_m": 2 * cx}
        farm = r["track"] != "SBT"
        prof = tracks["HH" if farm else "SBT"]
        radii = {"front": 0.0 if farm else studies.FRONT_7_50_18_RADIUS_M,
                 "rear": 0.0 if farm else studies.T4_ROLLING_RADIUS_M}
        wb = kw["front_distance_m"] + kw["rear_distance_m"]
        inputs.append(studies.tractor_inputs(prof, radii, {"front": 0.25, "rear": 0.45}, km_h_to_m_s(float(r["speed_km_h"])),
                                             wb, n_steps))
        runs.append((r, kw, prof, wb))
    arrs = [np.array([inp[j] for inp in inputs]) for j in range(4)]
    params = {k: np.array([kw.get(k, 0.0) for _, kw, _, _ in runs], float) for k in PARAMETERS}
    sim = simulate_tractor(Tractor(**params, longitudinal_model=np.array(["maxwell"] * len(runs), dtype=object)),
                           *arrs, studies.DT_S, gravity_m_s2=cm.THESIS_GRAVITY_M_S2)
    out = {}
    for i, (r, kw, prof, wb) in enumerate(runs):
        start, stop = studies.tractor_record_window({"speed_km_h": float(r["speed_km_h"]), "track": r["track"]}, wb,
                                                    prof.x_m[-1], duration_s)
        out[studies.tractor_key(r)] = {c: sim[c][i, start:stop].copy()
                                       for c in ("vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2")}
    return out


def _rng(seed: int, key: str) -> np.random.Generator:
    return np.random.default_rng([int(seed), zlib.crc32(key.encode())])


def _frame(seed: int, ride_id: str, channels: dict) -> pd.DataFrame:
    """A recording: ``time_s`` and each channel plus its seeded noise, as float32."""
    rng = _rng(seed, ride_id)
    n = next(iter(channels.values())).size
    cols = {"time_s": np.arange(n) * studies.DT_S}
    for name, x in channels.items():
        sd = PITCH_NOISE_RAD_S2 if name.endswith("rad_s2") else NOISE_M_S2
        cols[name] = (x + sd * rng.standard_normal(n)).astype(np.float32)
    return pd.DataFrame(cols)


def study_recordings(pub: dict, seed: int) -> tuple[pd.DataFrame, dict, pd.DataFrame]:
    """The recordings ``tyrelab generate`` writes for chapters 6 and 7.

    Parameters
    ----------
    pub : dict
        The published tables ``table_xii``, ``table_xv``, ``table_xvi`` (as read by
        :func:`tyrelab.published.read_published`).
    seed : int
        The campaign's seed (of the noise only).

    Returns
    -------
    rows : DataFrame
        ``rides.csv`` rows (``study``, ``load_condition``, ``study_track`` name the study's run).
    frames : dict
        ``file`` -> recording DataFrame.
    track : DataFrame
        The slatted track's slat tops (``x_m, left_m, right_m``), the ``track`` of every
        slatted-track row (``rides/slatted_track.csv``).
    """
    from . import published_layouts as layouts

    if not isinstance(pub, dict) or not {"table_xii", "table_xv", "table_xvi"} <= set(pub):
        raise ValueError("pub: expected a dict of the published tables table_xii, table_xv and table_xvi")
    _validate.positive_int("seed", seed, minimum=0)
    xii = layouts.carriage_rolling(pub["table_xii"])
    rows, frames = [], {}

    def add(ride_id, vehicle, speed, track, day, study, load, study_track, channels):
        file = f"rides/{ride_id}.parquet"
        rows.append({"ride_id": ride_id, "file": file, "vehicle": vehicle, "speed_km_h": float(speed), "track": track,
                     "recorded_on": day, "notes": "virtual recording of the thesis' vehicle (tyrelab generate)",
                     "study": study, "load_condition": str(load), "study_track": study_track})
        frames[file] = _frame(seed, ride_id, channels)

    slatted = "rides/slatted_track.csv"
    for (speed, load), a in carriage_recordings(xii, layouts.carriage_stationary(pub["table_xii"])).items():
        add(f"ch6_carriage_{load}_{speed:g}kmh".replace(".", "p"), "thesis carriage, T4 13.6R38 (virtual, ch. 6)",
            speed, slatted, CARRIAGE_DAY, "carriage", load, "SBT", {"floor_z_m_s2": a})
    for (lc, track, speed), r in tractor_recordings(layouts.tractor_mass(pub["table_xv"]),
                                                    layouts.tractor_tyres(pub["table_xvi"])).items():
        add(f"ch7_mf698t_lc{lc}_{track}_{speed:g}kmh".replace(".", "p"), "MF698T (virtual, ch. 7)", speed,
            slatted if track == "SBT" else "ISO 8608 class D", TRACTOR_DAY, "tractor", lc, track,
            {"floor_z_m_s2": r["vertical_m_s2"], "pitch_rad_s2": r["pitch_rad_s2"],
             "floor_x_m_s2": r["longitudinal_m_s2"]})
    from ..terrain.profiles import slatted_track

    t = slatted_track(seed=TRACK_SEED)
    return pd.DataFrame(rows), frames, pd.DataFrame({"x_m": t.x_m, "left_m": t.left_m, "right_m": t.right_m})
