"""Measurement campaigns of the virtual test vehicle (thesis §3.5, ch. 4-5).

:func:`campaign_plan` builds the plan of a campaign as a DataFrame of manifest
rows (raw format v1 columns plus ``kind``, ``sample_rate_Hz``, ``notes``) and
a few private planning columns (prefixed ``plan_``) that the generator uses
and does not write. Every recording day starts with a force-plate calibration
run (§3.2.9).

``scale="full"`` mirrors the thesis programme:

* pressure x speed sweeps of every Table II tyre (§4.3.1-4.3.2, §5.3.1-5.3.2):
  five pressures (Silsoe, 12-28 psi; F1 20-38 psi) or four (Berlin, 0.8-2 bar),
  speeds 0, 1, 5, 10, 12.5, 15, 20 km/h (Silsoe) and 0, 5-50 km/h (Berlin tyres,
  Kising's speed range, §4.2);
* load 15.9, 18.3, 22.6 kN on T1-T3 (§4.3.3, Fig. 22, 35);
* amplitude 4-30 mm p-p on T1, T2, T3, F1 at 0, 1, 10, 15 km/h (Tables IV, VIII);
* frequency 2-5 Hz on T1-T3 (§4.3.5, §5.3.5, Fig. 24, 37);
* driving torque up to 4.7 kNm (T1) and 2.8 kNm (T2, T3) at 1, 8, 10, 15 km/h (§4.3.6, §5.3.6);
* the surfaces of Tables V and IX with T4 and T5 at 5 and 10 km/h (§4.3.7, §5.3.7);
* a repeatability day (T1, repeated runs, §3.6) and a deliberately
  miscalibrated day (load-beam amplifiers +5 %) repeating it;
* the other methods and directions (issue 34, :mod:`tyrelab.rig.method_runs`), on the last
  day so that every earlier run keeps its date and seed: T1 stationary at 1.38 bar and the
  nominal load by random and swept-sine excitation, free vibration and load deflection (the
  thesis' Table I case, §3.4), and lateral and longitudinal random runs over pressure and
  speed (``full`` also over load).

``scale="small"`` keeps one of each kind and enough for the Table III
regressions of every tyre (three pressures at 0 km/h and at 10 and 15 km/h).
"""

from __future__ import annotations

import datetime as _dt
import math

import numpy as np
import pandas as pd

from . import truth
from ..units import km_h_to_m_s
from .instrument import RigConfig
from .method_runs import METHOD_DURATION_S, simulate_method_run

__all__ = ["MANIFEST_COLUMNS", "TRACK_LENGTH_M", "RUN_DURATION_S", "CALIBRATION_DURATION_S",
    "CALIBRATION_BAND_HZ", "MISCALIBRATED_BEAM_GAIN_ERROR", "FIRST_DAY", "SILSOE_SPEEDS", "BERLIN_SPEEDS",
    "LOADS_KN", "AMPLITUDES_MM_PP", "FREQUENCIES_HZ", "TORQUE_SPEEDS", "SURFACE_SPEEDS", "duration_s",
    "pressures", "nominal_pressure", "campaign_plan", "population_plan", "run_seed", "plan_truth", "rms_to_pp_mm", "day_state",
    "simulate_run", "run_scatter"]

MANIFEST_COLUMNS = [
    "run_id", "file", "tyre_id", "speed_km_h", "pressure_bar", "load_kN", "excitation_frequency_Hz",
    "amplitude_mm_pp", "torque_kNm", "surface", "axle_mass_kg", "recorded_on", "kind", "sample_rate_Hz", "notes",
    "direction", "method", "band_low_Hz", "band_high_Hz",
]
#: Band of the broadband runs of the virtual campaign, Hz (the calibration band, §3.2.9).
METHOD_BAND_HZ = (1.0, 8.0)
#: Straight track length usable for one recording; §3.5: above 15 km/h there was
#: not enough track for 50 s in one run.
TRACK_LENGTH_M = 180.0
RUN_DURATION_S = 50.0  # §3.5: "about 50 seconds of data"
CALIBRATION_DURATION_S = 60.0
CALIBRATION_BAND_HZ = (1.0, 8.0)  # §3.2.9
MISCALIBRATED_BEAM_GAIN_ERROR = 0.05
FIRST_DAY = _dt.date(1989, 4, 3)

SILSOE_SPEEDS = (0.0, 1.0, 5.0, 10.0, 12.5, 15.0, 20.0)
BERLIN_SPEEDS = (0.0, 5.0, 10.0, 12.5, 15.0, 20.0, 30.0, 40.0, 50.0)
LOADS_KN = (15.9, 18.3, 22.6)  # §4.3.3
AMPLITUDES_MM_PP = (4.0, 8.0, 14.0, 20.0, 26.0, 30.0)  # §4.3.4: 4-30 mm
FREQUENCIES_HZ = (2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0)  # §4.3.5: 2-5 Hz
TORQUE_SPEEDS = (1.0, 8.0, 10.0, 15.0)  # §4.3.6
SURFACE_SPEEDS = (5.0, 10.0)  # §5.3.7


def duration_s(speed_km_h: float) -> float:
    """Recording length: 50 s, shorter when the track is too short (§3.5)."""
    if speed_km_h < 15:
        return RUN_DURATION_S
    return round(min(RUN_DURATION_S, TRACK_LENGTH_M / km_h_to_m_s(speed_km_h)), 1)


def pressures(tyre_id: str, n: int) -> tuple[float, ...]:
    """``n`` pressures evenly over the tyre's range (bar, 2 decimals)."""
    lo, hi = truth.tyre_params(tyre_id).pressure_range_bar
    return tuple(round(float(p), 2) for p in np.linspace(lo, hi, n))


def nominal_pressure(tyre_id: str) -> float:
    """Pressure used for non-pressure sets: 1.38 bar (20 psi) unless out of range."""
    lo, hi = truth.tyre_params(tyre_id).pressure_range_bar
    return float(min(max(truth.NOMINAL_PRESSURE_BAR, lo), hi))


class _Planner:
    def __init__(self, cfg: RigConfig):
        self.cfg = cfg
        self.rows: list[dict] = []
        self.day_index = -1
        self.day: _dt.date | None = None
        self.counter: dict[str, int] = {}
        self.gain_error = 0.0

    def new_day(self, tyre_id: str, gain_error: float = 0.0, note: str = "", pressure_bar: float | None = None) -> None:
        self.day_index += 1
        d = FIRST_DAY
        n = self.day_index
        while n > 0:  # working days only
            d += _dt.timedelta(days=1)
            if d.weekday() < 5:
                n -= 1
        self.day = d
        self.gain_error = gain_error
        run_id = f"cal_{d.strftime('%Y%m%d')}"
        p0 = nominal_pressure(tyre_id) if pressure_bar is None else pressure_bar
        self.rows.append(self._row(run_id, "calibration", tyre_id, 0.0, p0, truth.NOMINAL_LOAD_KN,
                                   4.5, float("nan"), 0.0, "concrete", CALIBRATION_DURATION_S,
                                   "force plate, band-limited random 1-8 Hz (§3.2.9); frequency = band centre" + note))

    def _row(self, run_id, kind, tyre_id, v, p, load, f, a, tq, surface, dur, notes):
        return {
            "run_id": run_id, "file": f"runs/{run_id}.parquet", "tyre_id": tyre_id, "speed_km_h": float(v),
            "pressure_bar": float(p), "load_kN": float(load), "excitation_frequency_Hz": float(f),
            "amplitude_mm_pp": float(a), "torque_kNm": float(tq), "surface": surface,
            "axle_mass_kg": self.cfg.axle_mass_kg, "recorded_on": self.day.isoformat(), "kind": kind,
            "sample_rate_Hz": self.cfg.sample_rate_Hz, "notes": notes,
            "plan_duration_s": float(dur), "plan_beam_gain_error": self.gain_error, "plan_set": "",
            "direction": "vertical", "method": "stepped_sine", "band_low_Hz": float("nan"), "band_high_Hz": float("nan"),
        }

    def method_run(self, method: str, direction: str, tyre_id: str, v: float, p: float,
                   load: float = truth.NOMINAL_LOAD_KN) -> None:
        set_name = f"{direction[:3]}_{method}"
        key = f"{tyre_id}_{set_name}"
        i = self.counter.get(key, 0) + 1
        self.counter[key] = i
        run_id = f"{tyre_id}_{set_name}_{i:03d}"
        row = self._row(run_id, "measurement", tyre_id, v, p, load, float("nan"), float("nan"), 0.0, "concrete",
                        METHOD_DURATION_S[method], f"{method}, {direction} (issue 34)")
        broadband = method in ("random", "swept_sine")
        row.update(plan_set=set_name, direction=direction, method=method,
                   band_low_Hz=METHOD_BAND_HZ[0] if broadband else float("nan"),
                   band_high_Hz=METHOD_BAND_HZ[1] if broadband else float("nan"))
        self.rows.append(row)

    def run(self, set_name: str, tyre_id: str, v: float, p: float, load: float = truth.NOMINAL_LOAD_KN,
            f: float = truth.NOMINAL_FREQUENCY_HZ, a: float = truth.NOMINAL_AMPLITUDE_MM_PP, tq: float = 0.0,
            surface: str = "concrete", notes: str = "") -> None:
        key = f"{tyre_id}_{set_name}"
        i = self.counter.get(key, 0) + 1
        self.counter[key] = i
        suffix = "_miscal" if self.gain_error else ""
        run_id = f"{tyre_id}_{set_name}{suffix}_{i:03d}"
        row = self._row(run_id, "measurement", tyre_id, v, p, load, f, a, tq, surface, duration_s(v), notes)
        row["plan_set"] = set_name
        self.rows.append(row)


def campaign_plan(scale: str = "small", cfg: RigConfig = RigConfig()) -> pd.DataFrame:
    """The runs of a virtual campaign, one manifest row each.

    Parameters
    ----------
    scale : {"small", "full"}
    cfg : RigConfig
        Supplies the axle mass and sample rate written to the manifest.

    Returns
    -------
    DataFrame
        :data:`MANIFEST_COLUMNS` plus ``plan_duration_s`` (s),
        ``plan_beam_gain_error`` (the day's deliberate load-beam gain error)
        and ``plan_set`` (experiment set name).
    """
    if scale not in ("small", "full"):
        raise ValueError(f"scale must be 'small' or 'full', not {scale!r}")
    full = scale == "full"
    pl = _Planner(cfg)

    # pressure x speed sweeps (Tables III, VII; Fig. 20, 21, 33, 34)
    for tid in truth.TYRES:
        berlin = tid in truth.BERLIN_TYRES
        if full:
            ps = pressures(tid, 4 if berlin else 5)
            vs = BERLIN_SPEEDS if berlin else SILSOE_SPEEDS
        else:
            ps = pressures(tid, 3)
            vs = (0.0, 10.0, 15.0)
        pl.new_day(tid)
        for p in ps:
            for v in vs:
                pl.run("sweep", tid, v, p)

    # load (§4.3.3, §5.3.3)
    for tid in (("T1", "T2", "T3") if full else ("T3",)):
        pl.new_day(tid)
        for load in LOADS_KN:
            for v in ((0.0, 1.0, 5.0, 10.0, 15.0) if full else (10.0,)):
                pl.run("load", tid, v, nominal_pressure(tid), load=load)

    # amplitude (Tables IV, VIII)
    for tid in (("T1", "T2", "T3", "F1") if full else ("F1",)):
        pl.new_day(tid)
        for v in ((0.0, 1.0, 10.0, 15.0) if full else (0.0,)):
            for a in (AMPLITUDES_MM_PP if full else (4.0, 30.0)):
                pl.run("amplitude", tid, v, nominal_pressure(tid), a=a)

    # frequency (§4.3.5, §5.3.5)
    for tid in (("T1", "T2", "T3") if full else ("T1",)):
        pl.new_day(tid)
        for v in ((0.0, 1.0, 10.0, 15.0) if full else (0.0,)):
            for f in (FREQUENCIES_HZ if full else (2.0, 5.0)):
                pl.run("frequency", tid, v, nominal_pressure(tid), f=f)

    # driving torque (§4.3.6, §5.3.6)
    torques = {"T1": (0.0, 1.2, 2.4, 3.5, 4.7), "T2": (0.0, 0.9, 1.9, 2.8), "T3": (0.0, 0.9, 1.9, 2.8)}
    for tid in (("T1", "T2", "T3") if full else ("T1",)):
        pl.new_day(tid)
        for v in (TORQUE_SPEEDS if full else (10.0,)):
            for tq in (torques[tid] if full else (0.0, 4.7)):
                pl.run("torque", tid, v, nominal_pressure(tid), tq=tq)

    # surfaces (Tables V, IX)
    for tid in (("T4", "T5") if full else ("T5",)):
        pl.new_day(tid)
        for v in (SURFACE_SPEEDS if full else (5.0,)):
            for s in (truth.SURFACES if full else ("concrete", "pasture_grass", "artificial_rough_track")):
                pl.run("surface", tid, v, nominal_pressure(tid), surface=s)

    # repeatability (§3.6), then the same on a miscalibrated day (§3.2.9)
    for gain_error in (0.0, MISCALIBRATED_BEAM_GAIN_ERROR):
        note = "; load-beam amplifiers +5 % (deliberately miscalibrated day)" if gain_error else ""
        pl.new_day("T1", gain_error=gain_error, note=note)
        for v in (0.0, 10.0):
            for _ in range(3 if full else 1):
                pl.run("repeat", "T1", v, nominal_pressure("T1"), notes=note.lstrip("; "))

    # the other methods and directions (issue 34), last so that no earlier run changes
    pl.new_day("T1")
    p0 = nominal_pressure("T1")
    for method in ("random", "swept_sine", "free_vibration", "load_deflection"):
        pl.method_run(method, "vertical", "T1", 0.0, p0)
    for direction in ("lateral", "longitudinal"):
        for p in (pressures("T1", 3) if full else (pressures("T1", 3)[0], pressures("T1", 3)[-1])):
            for v in ((0.0, 2.5, 5.0, 10.0) if full else (0.0, 5.0)):
                pl.method_run("random", direction, "T1", v, p)
        for load in (LOADS_KN if full else ()):
            pl.method_run("random", direction, "T1", 5.0, p0, load=load)

    df = pd.DataFrame(pl.rows)
    if df["run_id"].duplicated().any():
        raise AssertionError("duplicate run ids in plan")
    return df


def population_plan(population, scale: str = "small", cfg: RigConfig = RigConfig()) -> pd.DataFrame:
    """Pressure x speed sweeps of a generated tyre population (:func:`tyrelab.rig.population.tyre_population`).

    One day per tyre (force-plate calibration first); ``small``: three pressures over the
    tyre's range at 0, 10 and 15 km/h (enough for its Table III lines and the formula
    refit); ``full``: five pressures at the Silsoe speeds. Each row carries the tyre's
    :class:`~tyrelab.rig.truth.TyreParams` in ``plan_tyre`` (not written), which
    :func:`simulate_run` uses instead of the Table II catalogue.
    """
    if scale not in ("small", "full"):
        raise ValueError(f"scale must be 'small' or 'full', not {scale!r}")
    pl = _Planner(cfg)
    tyres = {}
    for member in population:
        t = member.params
        tyres[t.tyre_id] = t
        lo, hi = t.pressure_range_bar
        ps = tuple(round(float(p), 2) for p in np.linspace(lo, hi, 5 if scale == "full" else 3))
        pl.new_day(t.tyre_id, pressure_bar=float(min(max(truth.NOMINAL_PRESSURE_BAR, lo), hi)))
        for p in ps:
            for v in (SILSOE_SPEEDS if scale == "full" else (0.0, 10.0, 15.0)):
                pl.run("sweep", t.tyre_id, v, p)
    df = pd.DataFrame(pl.rows)
    df["plan_tyre"] = df["tyre_id"].map(tyres)
    return df


def run_seed(seed: int, run_id: str) -> np.random.SeedSequence:
    """Deterministic per-run seed from (campaign seed, run_id), order independent."""
    import hashlib

    h = int.from_bytes(hashlib.sha256(f"{seed}:{run_id}".encode()).digest()[:8], "little")
    return np.random.SeedSequence([int(seed) & 0xFFFFFFFF, h])


def plan_truth(plan: pd.DataFrame) -> pd.DataFrame:
    """Truth K, C (SI) of each measurement row of a plan (see :func:`truth.truth_frame`)."""
    return truth.truth_frame(plan)


def rms_to_pp_mm(x_rms_m: float) -> float:
    """Peak-to-peak (mm) of a sinusoid of rms ``x_rms_m`` (m)."""
    return 2 * math.sqrt(2) * x_rms_m * 1e3


def day_state(seed: int, recorded_on: str, beam_gain_error: float = 0.0, cfg: RigConfig = RigConfig()):
    """Instrument state of a recording day, seeded from (seed, day); ``cfg.day_scatter`` is the tyre's
    day-to-day factor (thesis §3.6, ``ambient_*_factor``)."""
    from .instrument import day_calibration

    rng = np.random.default_rng(run_seed(seed, f"day:{recorded_on}"))
    return day_calibration(rng, beam_gain_error=beam_gain_error, ambient_sd=tuple(cfg.day_scatter))


def run_scatter(seed: int, run_id: str, cfg: RigConfig = RigConfig()) -> tuple[float, float]:
    """Run-to-run factors on K and C (thesis §3.6, ``cfg.run_scatter``), from their own seed stream
    (so the recording's noise is the same with and without scatter)."""
    z = np.random.default_rng(run_seed(seed, f"scatter:{run_id}")).standard_normal(2)
    return 1.0 + cfg.run_scatter[0] * float(z[0]), 1.0 + cfg.run_scatter[1] * float(z[1])


def simulate_run(row, seed: int, cfg: RigConfig = RigConfig(), keep_signals: bool = False) -> tuple[pd.DataFrame, dict]:
    """Simulate one planned run and record it in raw format v1.

    Parameters
    ----------
    row : Mapping or namedtuple
        One row of :func:`campaign_plan`.
    seed : int
        Campaign seed; the run's generator is seeded from (seed, run_id).
    cfg : RigConfig
    keep_signals : bool
        Also return the physical signals (:class:`~tyrelab.rig.instrument.RunSignals`) as ``info["signals"]``.

    Returns
    -------
    run : DataFrame
        ``time_s``, the two accelerometers, four load beams (and
        ``force_plate_N`` for calibration runs), float32 channels.
    info : dict
        ``stiffness_N_per_m``, ``damping_N_s_per_m`` (the truth used: the
        truth model's K, C at the run's conditions times the day's and the
        run's scatter factors of ``cfg``, thesis §3.6),
        ``amplitude_mm_pp`` (of the simulated axle displacement).
    """
    from .instrument import record, simulate_axle

    get = row.get if hasattr(row, "get") else (lambda k, d=None: getattr(row, k, d))
    if get("method", "stepped_sine") not in ("stepped_sine", None) and get("kind", "measurement") == "measurement":
        rng = np.random.default_rng(run_seed(seed, get("run_id")))
        day = day_state(seed, get("recorded_on"), float(get("plan_beam_gain_error", 0.0) or 0.0), cfg)
        run, info = simulate_method_run(row, rng, day, cfg)
        info["amplitude_mm_pp"] = rms_to_pp_mm(float(info.pop("displacement_rms_m")))
        return run, info
    tyre = get("plan_tyre", None) or truth.tyre_params(get("tyre_id"))
    rng = np.random.default_rng(run_seed(seed, get("run_id")))
    day = day_state(seed, get("recorded_on"), float(get("plan_beam_gain_error", 0.0) or 0.0), cfg)
    kind = get("kind", "measurement")
    v = float(get("speed_km_h"))
    cond = dict(pressure_bar=float(get("pressure_bar")), speed_km_h=v, load_kN=float(get("load_kN")),
                torque_kNm=float(get("torque_kNm")), surface=get("surface"))
    if kind == "calibration":
        K = truth.stiffness(tyre, **cond)
        C = truth.damping(tyre, **cond)
        sig = simulate_axle(K, C, float(get("plan_duration_s", CALIBRATION_DURATION_S)), rng, cfg,
                            load_kN=cond["load_kN"], random_band_Hz=CALIBRATION_BAND_HZ,
                            speed_km_h=0.0, surface="concrete")
    else:
        f = float(get("excitation_frequency_Hz"))
        a = float(get("amplitude_mm_pp"))
        fk, fc = run_scatter(seed, get("run_id"), cfg)
        K = truth.stiffness(tyre, amplitude_mm_pp=a, frequency_Hz=f, **cond) * day.ambient_stiffness_factor * fk
        C = truth.damping(tyre, amplitude_mm_pp=a, frequency_Hz=f, **cond) * day.ambient_damping_factor * fc
        sig = simulate_axle(K, C, float(get("plan_duration_s", duration_s(v))), rng, cfg,
                            load_kN=cond["load_kN"], frequency_Hz=f, amplitude_mm_pp=a, speed_km_h=v,
                            surface=cond["surface"], circumference_m=tyre.circumference_m,
                            lug_height_mm=tyre.lug_height_mm, traction=tyre.traction)
    run = record(sig, day, rng, cfg, force_plate=(kind == "calibration"))
    x = sig.axle_displacement_m
    info = {"stiffness_N_per_m": K, "damping_N_s_per_m": C,
            "amplitude_mm_pp": rms_to_pp_mm(float(np.std(x)))}
    if keep_signals:
        info["signals"] = sig
    return run, info
