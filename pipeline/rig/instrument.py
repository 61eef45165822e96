"""Instrument model of the virtual dynamic tyre test vehicle (thesis ch. 3).

The machine of §3.2: a test wheel (axle + wheel + tyre, mass ``M_a`` ~ 600 kg,
§3.2.8) carried through four stiff load beams (§3.2.6) by a carriage, which
is vibrated against an inertial mass of 250-400 kg (§3.2.5) and linked to the
tractor by a parallelogram linkage with some damping (§3.4: upper bound
1.2 kNs/m). Two accelerometers on the axle ends (§3.2.6).

Vertical dynamics around the static equilibrium (x upward)::

    M_a x_a'' = -K (x_a - z) - C (x_a' - z') + n + k_b (x_c - x_a) + c_b (x_c' - x_a')
    M_c' x_c'' = -k_b (x_c - x_a) - c_b (x_c' - x_a') - k_l x_c - c_l x_c' + F_d

with ``z`` the ground displacement under the tyre (surface roughness, wheel
run-out, lug passing; §2.4.5, §3.3.2), ``n`` a small non-linear tyre force
(§3.3.1 eq. 1), ``F_d`` the reaction of the accelerated inertial mass. The
experimenter holds the axle amplitude (§3.2.8 rms meter, §3.5: amplitude within
about 20 %, frequency within 0.1 Hz): the drive is chosen so that the part of
the axle motion due to the drive is the commanded slowly-wandering sinusoid;
the ground inputs add their response through the 2-DOF dynamics. The system is
solved exactly in the frequency domain over a padded, tapered record.

Recorded channels follow raw format v1 (docs/architecture.md): accelerometers
measure specific force (upward acceleration + g, as a DC accelerometer does),
load beams the force of the carriage on the axle, so that
``M_a * mean(acc) - sum(beams) = f_t = L - K (x_a - z) - C (x_a' - z') + n``
(tyre ground force on the axle, upward positive, L the static load).
Each channel then gets gain error, offset, noise, 16-bit quantisation and
clipping at its range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy import fft as sfft

from ..measurement.recording import frame_tyre_force
from ..rawformat import ACCEL_CHANNELS, BEAM_CHANNELS, OPTIONAL_CHANNELS, TIME
from ..units import STANDARD_GRAVITY_M_S2, km_h_to_m_s

__all__ = ["G", "SURFACE_ROUGHNESS_M3", "SLAT_PERIOD_M", "HUM_Hz", "NO_SCATTER", "RigConfig", "DayCalibration",
    "day_calibration", "RunSignals", "carriage_mass_kg", "ground_profile", "simulate_axle", "record",
    "derived_tyre_force"]

G = STANDARD_GRAVITY_M_S2  # m/s^2 (tyrelab.units)


#: Mains frequency of the hum artefact, Hz (UK, where the thesis' vehicle ran).
HUM_Hz = 50.0

#: ISO 8608 class geometric means G_d(n0) (m^3) used as stand-ins for the
#: surfaces of Tables V/IX (the thesis gives no profiles for them; field notes).
SURFACE_ROUGHNESS_M3 = {
    "concrete": 0.0,
    "dry_farm_track": 16e-6,  # class A
    "hard_parkland_grass": 16e-6,  # A
    "pasture_grass": 64e-6,  # B
    "dry_cultivated_land": 64e-6,  # B
    "dry_seedbed": 16e-6,  # A
    "stubble_field": 64e-6,  # B
    "artificial_rough_track": 256e-6,  # C; seeded stand-in, plus the slat passing below
}
#: §4.3.7: wooden slats 80 mm wide with 80 mm gaps -> 0.16 m period.
SLAT_PERIOD_M = 0.16


@dataclass(frozen=True)
class RigConfig:
    """Mechanical and instrumentation constants of the virtual vehicle.

    Attributes
    ----------
    axle_mass_kg : float
        Mass of axle + wheel + tyre moving with the axle, §3.2.8 "typically about 600 kg".
    inertial_mass_kg : float
        §3.2.5: 250-400 kg.
    beam_stiffness_N_per_m, beam_damping_N_s_per_m : float
        Four load beams together; axle-on-beams resonance ~ 25 Hz (§3.2.6: ten
        times stiffer than the first transducers that resonated at ~5 Hz).
    linkage_stiffness_N_per_m, linkage_damping_N_s_per_m : float
        Main linkage to the tractor (§3.2.4); damping below the 1.2 kNs/m upper
        bound of §3.4. The apparent-mass method does not see these (§3.4).
    sample_rate_Hz : float
        DAQ rate.
    noise_scale : float
        Multiplies every channel noise (benchmark: 1 and 3).
    accel_noise_m_s2, beam_noise_N, force_plate_noise_N : float
        Channel noise rms at noise_scale 1.
    accel_range_m_s2, beam_range_N, force_plate_range_N : float
        +- full scale of the 16-bit converters.
    amplitude_wander, frequency_wander_Hz, speed_wander : float
        Standard deviations of the slow wander (amplitude fraction, Hz, speed
        fraction), clipped to the §3.5 tolerances +-20 %, +-0.1 Hz.
    wander_period_s : float
        Shortest period of the wander processes.
    nonlinear_fraction : float
        Second-order tyre force, fraction of K x_rms.
    runout_m, lug_fraction : float
        Wheel run-out (first harmonic, §2.4.5) and lug excitation amplitude per
        mm of lug height.
    startup_s : float
        Stress artefact (0 = off): the vibrator starts and stops inside the
        recording; the commanded amplitude ramps up over the first and down
        over the last ``startup_s`` seconds (raised cosine).
    drive_harmonics : (float, float)
        Stress artefact: 2nd and 3rd harmonic of the commanded axle motion,
        fractions of the fundamental amplitude.
    hum_accel_m_s2, hum_beam_N : float
        Stress artefact: 50 Hz mains hum amplitude on each accelerometer and
        each load-beam channel.
    accel_drift_m_s2 : float
        Stress artefact: accelerometer offset drift over the run (each end its
        own slow random drift of about this size).
    cubic_fraction : float
        Stress artefact, non-linear tyre: a hardening force
        ``−β K d³ / d₀²`` (``d₀`` the commanded displacement amplitude); its
        first harmonic adds ``¾ β (A/d₀)²`` to the stiffness at amplitude A.
    lug_stiffness_modulation : float
        Stress artefact: the stiffness of a rolling traction tyre varies with
        the lug under the contact patch, ``K (1 + m sin θ_lug)``.
    run_scatter, day_scatter : (float, float)
        Repeatability of the tyre itself (thesis §3.6): relative standard
        deviations of K and C from run to run (each run's tyre differs from
        the truth model by a factor ``1 + sd·N(0,1)``) and from day to day (a
        factor common to the runs of a day, "variations in the ambient
        conditions"). §3.6: repeats within a few minutes "are generally
        repeatable to less than 10 kN/m in stiffness (~4 %) and to 0.2 kNs/m
        in damping (~8 %)"; read as ±2 standard deviations: 2 % and 4 %.
        Between series "the variations ... can be a little greater": a day
        factor of 1.5 % and 3 % (total 2.5 % and 5 %). ``tyrelab generate
        --no-scatter`` (:data:`NO_SCATTER`) sets both to zero for estimator
        benchmarks and truth-recovery tests. The run's recorded truth
        (``simulate_run``'s ``info``) includes the factors: it is the K and C
        the tyre had during that run.
    """

    axle_mass_kg: float = 600.0
    inertial_mass_kg: float = 300.0
    beam_stiffness_N_per_m: float = 600.0 * (2 * math.pi * 25.0) ** 2
    beam_damping_N_s_per_m: float = 2.0e3
    linkage_stiffness_N_per_m: float = 35e3
    linkage_damping_N_s_per_m: float = 0.7e3
    sample_rate_Hz: float = 256.0
    noise_scale: float = 1.0
    accel_noise_m_s2: float = 0.01
    beam_noise_N: float = 3.0
    force_plate_noise_N: float = 5.0
    accel_range_m_s2: float = 4 * G
    beam_range_N: float = 12e3
    force_plate_range_N: float = 50e3
    amplitude_wander: float = 0.07
    frequency_wander_Hz: float = 0.03
    speed_wander: float = 0.01
    wander_period_s: float = 8.0
    nonlinear_fraction: float = 0.01
    runout_m: float = 1.0e-3
    lug_fraction: float = 0.01e-3
    pad_s: float = 6.0
    startup_s: float = 0.0
    drive_harmonics: tuple[float, float] = (0.0, 0.0)
    hum_accel_m_s2: float = 0.0
    hum_beam_N: float = 0.0
    accel_drift_m_s2: float = 0.0
    cubic_fraction: float = 0.0
    lug_stiffness_modulation: float = 0.0
    run_scatter: tuple[float, float] = (0.02, 0.04)
    day_scatter: tuple[float, float] = (0.015, 0.03)


#: Overrides of :class:`RigConfig` without the tyre's run-to-run and day-to-day scatter.
NO_SCATTER = {"run_scatter": (0.0, 0.0), "day_scatter": (0.0, 0.0)}


@dataclass(frozen=True)
class DayCalibration:
    """State of the instrumentation on one day (gains, offsets).

    ``beam_gain`` of a miscalibrated day carries e.g. a 5 % error (§3.2.9 check).
    """

    accel_gain: tuple[float, float] = (1.0, 1.0)
    accel_offset_m_s2: tuple[float, float] = (0.0, 0.0)
    beam_gain: tuple[float, float, float, float] = (1.0, 1.0, 1.0, 1.0)
    beam_offset_N: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
    force_plate_gain: float = 1.0
    ambient_stiffness_factor: float = 1.0
    ambient_damping_factor: float = 1.0


def day_calibration(rng: np.random.Generator, beam_gain_error: float = 0.0,
                    gain_sd: float = 0.002, ambient_sd: tuple[float, float] = (0.0, 0.0)) -> DayCalibration:
    """Draw a day's instrument state.

    Parameters
    ----------
    rng : numpy Generator
    beam_gain_error : float
        Common gain error of the four load-beam amplifiers (0.05 = +5 %): the
        deliberately miscalibrated day.
    gain_sd : float
        Standard deviation of the per-channel gain error of a properly calibrated day
        (0.2 %: well inside the +-3 % of §3.2.9).
    ambient_sd : (float, float)
        Day-to-day factor on the tyre's K and C ("variations in the ambient
        conditions", §3.6); 0 by default.
    """
    ag = tuple(1 + gain_sd * rng.standard_normal(2))
    ao = tuple(0.02 * rng.standard_normal(2))
    bg = tuple((1 + beam_gain_error) * (1 + gain_sd * rng.standard_normal(4)))
    bo = tuple(20.0 * rng.standard_normal(4))
    fp = 1 + 0.3 * gain_sd * rng.standard_normal()
    ak = 1 + ambient_sd[0] * rng.standard_normal()
    ac = 1 + ambient_sd[1] * rng.standard_normal()
    return DayCalibration(ag, ao, bg, bo, float(fp), float(ak), float(ac))


@dataclass
class RunSignals:
    """Physical (error-free) signals of one simulated run, SI, upward positive."""

    time_s: np.ndarray
    axle_displacement_m: np.ndarray
    axle_acceleration_m_s2: np.ndarray
    ground_displacement_m: np.ndarray
    tyre_force_N: np.ndarray  # f_t, ground force on axle incl. static load
    beam_force_N: np.ndarray  # sum of the beam forces on the axle
    drive_force_N: np.ndarray = field(default_factory=lambda: np.zeros(0))
    excitation_phase_rad: np.ndarray = field(default_factory=lambda: np.zeros(0))  # commanded phase (sinusoid)


def _slow_wander(rng: np.random.Generator, t: np.ndarray, sd: float, limit: float, period_s: float) -> np.ndarray:
    """Smooth random process with standard deviation ~sd, clipped to +-limit."""
    if sd <= 0:
        return np.zeros_like(t)
    n = 6
    freqs = rng.uniform(1.0 / (8 * period_s), 1.0 / period_s, n)
    phases = rng.uniform(0, 2 * np.pi, n)
    amps = rng.rayleigh(1.0, n)
    w = (amps[:, None] * np.sin(2 * np.pi * freqs[:, None] * t[None, :] + phases[:, None])).sum(axis=0)
    w *= sd / math.sqrt(float((amps**2).sum()) / 2)
    return np.clip(w, -limit, limit)


def _taper(n: int, n_ramp: int) -> np.ndarray:
    w = np.ones(n)
    r = 0.5 - 0.5 * np.cos(np.pi * np.arange(n_ramp) / n_ramp)
    w[:n_ramp] = r
    w[n - n_ramp:] = r[::-1]
    return w


def _system(omega: np.ndarray, K: float, C: float, M_a: float, M_c: float, cfg: RigConfig):
    """2-DOF dynamic matrix entries (A11, A12, A22) and determinant."""
    jw = 1j * omega
    kb = cfg.beam_stiffness_N_per_m + jw * cfg.beam_damping_N_s_per_m
    a11 = K + jw * C + kb - omega**2 * M_a
    a12 = -kb
    a22 = kb + cfg.linkage_stiffness_N_per_m + jw * cfg.linkage_damping_N_s_per_m - omega**2 * M_c
    return a11, a12, a22, a11 * a22 - a12 * a12


def carriage_mass_kg(load_kN: float, cfg: RigConfig) -> float:
    """Carriage + inertial mass (kg) that gives the static load with the axle mass."""
    m = load_kN * 1e3 / G - cfg.axle_mass_kg
    if m <= 0:
        raise ValueError(f"load {load_kN} kN is less than the axle weight")
    return m


def ground_profile(rng: np.random.Generator, t: np.ndarray, speed_km_h: float, surface: str,
                   circumference_m: float, lug_height_mm: float, traction: bool, cfg: RigConfig) -> np.ndarray:
    """Ground/tyre displacement input z(t) (m) under the contact patch.

    Roughness with an ISO 8608 shaped spectrum (w = 2) for the surface,
    wheel run-out at the rotation frequency and its 2nd harmonic, and lug
    passing at half and full lug passing frequency for traction tyres
    (§2.4.5); all follow the slowly wandering speed, so their bands are wide.
    """
    n = t.size
    z = np.zeros(n)
    v = km_h_to_m_s(speed_km_h)
    if v <= 0:
        return z
    dt = t[1] - t[0]
    speed = v * (1 + _slow_wander(rng, t, cfg.speed_wander, 3 * cfg.speed_wander, cfg.wander_period_s))
    dist = np.cumsum(speed) * dt
    phi = 2 * np.pi * dist / circumference_m
    z += cfg.runout_m * np.sin(phi + rng.uniform(0, 2 * np.pi))
    z += 0.3 * cfg.runout_m * np.sin(2 * phi + rng.uniform(0, 2 * np.pi))
    if traction and lug_height_mm > 0:
        n_lugs = max(int(round(circumference_m / 0.2)), 8)  # lugs per side, ~0.2 m pitch
        h = cfg.lug_fraction * lug_height_mm
        z += h * np.sin(n_lugs * phi + rng.uniform(0, 2 * np.pi))  # half lug-passing (alternate sides)
        z += 0.4 * h * np.sin(2 * n_lugs * phi + rng.uniform(0, 2 * np.pi))  # lug passing
    gd = SURFACE_ROUGHNESS_M3.get(surface)
    if gd is None:
        raise ValueError(f"unknown surface {surface!r}")
    if gd > 0:
        f = sfft.rfftfreq(n, dt)
        df = f[1] - f[0]
        nsp = np.where(f > 0, f / v, np.inf)  # spatial frequency, cycles/m
        psd = np.where((nsp > 0.05) & (nsp < 10.0), gd * (nsp / 0.1) ** -2.0 / v, 0.0)  # m^2/Hz
        amp = (n / 2) * np.sqrt(2 * psd * df)
        spec = amp * np.exp(1j * rng.uniform(0, 2 * np.pi, f.size))
        spec[0] = 0
        z += sfft.irfft(spec, n)
    if surface == "artificial_rough_track":
        z += 1.0e-3 * np.sin(2 * np.pi * dist / SLAT_PERIOD_M)  # enveloped slat passing
    return z


def simulate_axle(
    stiffness_N_per_m: float,
    damping_N_s_per_m: float,
    duration_s: float,
    rng: np.random.Generator,
    cfg: RigConfig = RigConfig(),
    *,
    load_kN: float = 18.3,
    frequency_Hz: float | None = 4.0,
    amplitude_mm_pp: float = 14.0,
    speed_km_h: float = 0.0,
    surface: str = "concrete",
    circumference_m: float = 4.66,
    lug_height_mm: float = 0.0,
    traction: bool = False,
    random_band_Hz: tuple[float, float] | None = None,
    random_displacement_rms_m: float = 3e-3,
) -> RunSignals:
    """Simulate the axle of the vehicle for one run.

    Parameters
    ----------
    stiffness_N_per_m, damping_N_s_per_m : float
        The tyre's K and C for this run (truth model).
    duration_s : float
        Length of the record (s).
    rng : numpy Generator
        Seeded generator; the run is fully determined by it.
    load_kN : float
        Static tyre load (sets the carriage mass).
    frequency_Hz, amplitude_mm_pp : float
        Target sinusoidal excitation of the axle (held by the experimenter).
    random_band_Hz : (float, float) or None
        Instead of a sinusoid, band-limited random excitation (§3.2.9
        calibration: 1-8 Hz) with a flat displacement spectrum of rms
        ``random_displacement_rms_m`` (m).
    speed_km_h, surface, circumference_m, lug_height_mm, traction :
        Ground input (see :func:`ground_profile`).

    Returns
    -------
    RunSignals
    """
    fs = cfg.sample_rate_Hz
    dt = 1.0 / fs
    n_keep = int(round(duration_s * fs))
    n_pad = int(round(cfg.pad_s * fs))
    n = sfft.next_fast_len(n_keep + 2 * n_pad, real=True)
    n_pad0 = (n - n_keep) // 2
    t = np.arange(n) * dt
    omega = 2 * np.pi * sfft.rfftfreq(n, dt)
    taper = _taper(n, int(2.0 * fs))
    M_a = cfg.axle_mass_kg
    M_c = carriage_mass_kg(load_kN, cfg) - 0.0  # carriage incl. inertial mass
    K, C = stiffness_N_per_m, damping_N_s_per_m
    a11, a12, a22, det = _system(omega, K, C, M_a, M_c, cfg)

    # commanded axle motion (the drive part)
    if random_band_Hz is None:
        amp = amplitude_mm_pp / 2 * 1e-3
        lim_a = 0.2
        a_w = 1 + _slow_wander(rng, t, cfg.amplitude_wander, lim_a, cfg.wander_period_s)
        f_w = frequency_Hz + _slow_wander(rng, t, cfg.frequency_wander_Hz, 0.09, cfg.wander_period_s)
        phase = 2 * np.pi * np.cumsum(f_w) * dt + rng.uniform(0, 2 * np.pi)
        x_cmd = amp * a_w * np.sin(phase)
        if any(cfg.drive_harmonics):
            for order, h in zip((2, 3), cfg.drive_harmonics):
                x_cmd = x_cmd + h * amp * a_w * np.sin(order * phase + rng.uniform(0, 2 * np.pi))
        if cfg.startup_s > 0:
            ramp = _taper(n_keep, int(round(cfg.startup_s * fs)))
            x_cmd = x_cmd * np.concatenate([np.zeros(n_pad0), ramp, np.zeros(n - n_pad0 - n_keep)])
        X_cmd = sfft.rfft(x_cmd * taper)
    else:
        f = omega / (2 * np.pi)
        band = (f >= random_band_Hz[0]) & (f <= random_band_Hz[1])
        spec = np.where(band, np.exp(1j * rng.uniform(0, 2 * np.pi, f.size)), 0)
        xr = sfft.irfft(spec, n)
        xr *= random_displacement_rms_m / xr.std()
        X_cmd = sfft.rfft(xr * taper)
    # drive force that produces it (F_d = -X det / a12), kept for the record
    F_d = -X_cmd * det / a12

    z = ground_profile(rng, t, speed_km_h, surface, circumference_m, lug_height_mm, traction, cfg) * taper
    Z = sfft.rfft(z)
    X = X_cmd + (K + 1j * omega * C) * Z * a22 / det
    # second-order tyre force n(t) from the first-pass deflection, then its response
    d1 = sfft.irfft(X - Z, n)
    d_rms = float(np.sqrt(np.mean(d1**2))) or 1.0
    nl = -cfg.nonlinear_fraction * K * (d1**2 - np.mean(d1**2)) / d_rms * taper
    if cfg.cubic_fraction and random_band_Hz is None:
        d0 = amplitude_mm_pp / 2 * 1e-3
        nl = nl - cfg.cubic_fraction * K * d1**3 / d0**2 * taper
    if cfg.lug_stiffness_modulation and traction and lug_height_mm > 0 and speed_km_h > 0:
        n_lugs = max(int(round(circumference_m / 0.2)), 8)
        theta = 2 * np.pi * n_lugs * km_h_to_m_s(speed_km_h) * t / circumference_m + rng.uniform(0, 2 * np.pi)
        nl = nl - cfg.lug_stiffness_modulation * K * np.sin(theta) * d1 * taper
    N = sfft.rfft(nl)
    X = X + N * a22 / det
    if n % 2 == 0:  # no derivative at Nyquist
        X[-1] = 0
        Z[-1] = 0
    jw = 1j * omega
    x = sfft.irfft(X, n)
    xd = sfft.irfft(jw * X, n)
    xdd = sfft.irfft(-(omega**2) * X, n)
    zz = sfft.irfft(Z, n)
    zd = sfft.irfft(jw * Z, n)
    L = load_kN * 1e3
    f_t = L - K * (x - zz) - C * (xd - zd) + nl
    f_b = M_a * (xdd + G) - f_t
    fd = sfft.irfft(F_d, n)
    sl = slice(n_pad0, n_pad0 + n_keep)
    return RunSignals(
        time_s=np.arange(n_keep) * dt,
        axle_displacement_m=x[sl],
        axle_acceleration_m_s2=xdd[sl],
        ground_displacement_m=zz[sl],
        tyre_force_N=f_t[sl],
        beam_force_N=f_b[sl],
        drive_force_N=fd[sl],
        excitation_phase_rad=phase[sl] if random_band_Hz is None else np.zeros(0),
    )


def _adc(x: np.ndarray, full_scale: float) -> np.ndarray:
    """16-bit converter: quantise to 2*FS/65536 and clip at the rails."""
    lsb = 2 * full_scale / 65536
    counts = np.clip(np.round(x / lsb), -32768, 32767)
    return counts * lsb


def record(signals: RunSignals, day: DayCalibration, rng: np.random.Generator, cfg: RigConfig = RigConfig(),
           force_plate: bool = False, gravity_m_s2: float = G) -> pd.DataFrame:
    """Turn physical signals into a raw-format-v1 run table.

    Accelerometers: specific force ``a + g`` plus a small roll component that
    cancels in the mean of the two ends (§3.2.6); load beams: the beam force
    shared unequally between the four beams, with opposing preloads of the
    parallel pairs and a pitch component that cancels in the sum. Then gain,
    offset, noise (``cfg.noise_scale``), quantisation and clipping.
    Optional ``force_plate_N`` (calibration runs, §3.2.9). ``gravity_m_s2``: what a DC
    accelerometer adds along the run's direction (``G`` vertical, 0 lateral or longitudinal).
    """
    n = signals.time_s.size
    s = cfg.noise_scale
    acc = signals.axle_acceleration_m_s2 + gravity_m_s2
    roll = 0.03 * signals.axle_acceleration_m_s2
    out = {TIME: signals.time_s}
    for i, (sign, name) in enumerate(zip((1, -1), ACCEL_CHANNELS)):
        a = acc + sign * roll
        a = day.accel_gain[i] * a + day.accel_offset_m_s2[i] + s * cfg.accel_noise_m_s2 * rng.standard_normal(n)
        if cfg.hum_accel_m_s2:
            a = a + cfg.hum_accel_m_s2 * np.sin(2 * np.pi * HUM_Hz * signals.time_s + rng.uniform(0, 2 * np.pi))
        if cfg.accel_drift_m_s2:
            a = a + _slow_wander(rng, signals.time_s, cfg.accel_drift_m_s2, 3 * cfg.accel_drift_m_s2, 60.0)
        out[name] = _adc(a, cfg.accel_range_m_s2).astype(np.float32)
    fb = signals.beam_force_N
    fb_dyn = fb - fb.mean()
    shares = (0.26, 0.24, 0.255, 0.245)
    preload = (150.0, -150.0, 120.0, -120.0)
    pitch = (0.04, -0.04, -0.04, 0.04)
    for i in range(4):
        b = shares[i] * fb + preload[i] + pitch[i] * fb_dyn
        b = day.beam_gain[i] * b + day.beam_offset_N[i] + s * cfg.beam_noise_N * rng.standard_normal(n)
        if cfg.hum_beam_N:
            b = b + cfg.hum_beam_N * np.sin(2 * np.pi * HUM_Hz * signals.time_s + rng.uniform(0, 2 * np.pi))
        out[BEAM_CHANNELS[i]] = _adc(b, cfg.beam_range_N).astype(np.float32)
    if force_plate:
        fp = day.force_plate_gain * signals.tyre_force_N + s * cfg.force_plate_noise_N * rng.standard_normal(n)
        out[OPTIONAL_CHANNELS[0]] = _adc(fp, cfg.force_plate_range_N).astype(np.float32)
    return pd.DataFrame(out)


def derived_tyre_force(run: pd.DataFrame, axle_mass_kg: float) -> np.ndarray:
    """f_t = M_a * mean(accel_left, accel_right) - sum(load beams)  (§3.2.8, raw v1).

    :func:`tyrelab.measurement.recording.frame_tyre_force`, the one home of the equation.
    """
    return frame_tyre_force(run, axle_mass_kg)
