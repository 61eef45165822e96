"""Every rig method and direction of a recorded run, into one row of ``results`` (issue 34).

Raw format v1 runs carry two optional manifest columns: ``direction`` (:data:`DIRECTIONS`,
default ``vertical``) and ``method`` (:data:`METHODS`, default ``stepped_sine``). The
channels are those of raw format v1, measured along the run's direction (the actuator and
transducers turned, thesis §3.2.5, Fig. 14; ``axle_mass_kg`` the mass moving in that
direction); a ``load_deflection`` run adds ``deflection_m`` (compression positive).

* ``stepped_sine`` — the thesis' method (§3.3.1, :mod:`tyrelab.measurement.recording`);
  not handled here, its rows are the analyse stage's as before.
* ``swept_sine``, ``random`` — the apparent mass across the band, K and C of the tyre model
  fitted over the coherent band (:mod:`tyrelab.measurement.broadband`); the frequency
  response goes to the table ``frf``.
* ``free_vibration`` — the recording's last drive stops at the release (the largest axle
  motion); the decay's extrema give the damped frequency (their spacing) and the decay rate
  σ (their logarithm, a straight line in time); the moving mass is the force per
  acceleration over the decay (in a free decay the tyre force is the inertia force of what
  moves, F/A = m at every frequency, so the apparent mass carries no damping — the envelope
  does). ``K = m (ω_d² + σ²)``, ``C = 2 m σ``: the whole suspended system, linkage
  included (thesis §3.4 b). For a rolling tyre the thesis' caveat is printed: the decay
  cannot be told from vibration the ground and the tyre's lugs keep exciting (§3.4).
* ``load_deflection`` — over the loading branch (deflection rising) the secant stiffness
  (chord from the branch's start to its end) and the tangent stiffness (straight line over
  the top quarter of the branch's deflection); over the whole loop the dissipated energy
  ``E = ∮ F dδ`` and its equivalent viscous coefficient at the test's own rate
  ``C_eq = E / ∫ δ'² dt`` (a viscous damper dissipates ``C ∫ δ'² dt``; for a sinusoidal cycle
  this is the familiar ``E / (π ω X²)``). Slow loading lets the rubber creep, so the
  stiffness is low (§3.4, Fig. 18), and the loop is the creep's, not the tyre's dynamic
  damping: "the viscous damping coefficient cannot be measured by this means" (§3.4). So
  ``C_eq`` is reported as creep, ``creep_coefficient_N_s_per_m`` (issue 44), and the run's
  ``damping_N_s_per_m`` stays null: it never enters a damping average.

Uncertainty: the type A part of each method with Student t, combined with the §3.2.9
instrument limits (:func:`tyrelab.measurement.uncertainty.limits_budget`).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
from scipy import signal
from scipy.integrate import trapezoid as _trapezoid
from scipy.stats import t as student_t

from .._validate import band, positive
from . import broadband as bb

__all__ = ["DIRECTIONS", "METHODS", "BROADBAND", "BAND_REQUIRED", "DEFLECTION", "ROLLING_CAVEAT", "FRF_COLUMNS",
           "METHOD_COLUMNS", "channel_problem", "release_index", "free_vibration_run", "load_deflection_run", "analyse_method_run"]

#: Directions a rig run can be recorded in (thesis §3.2.5, Fig. 14).
DIRECTIONS = ("vertical", "lateral", "longitudinal")
#: Methods (thesis §3.4; ``stepped_sine`` the thesis' main one).
METHODS = ("stepped_sine", "swept_sine", "random", "free_vibration", "load_deflection")
#: Methods analysed as a broadband frequency response.
BROADBAND = ("swept_sine", "random")
#: Methods whose manifest row must state ``band_low_Hz`` and ``band_high_Hz``.
BAND_REQUIRED = ("random",)
#: The deflection channel of a load-deflection run, m, compression positive.
DEFLECTION = "deflection_m"
#: Thesis §3.4 on the free-vibration method for a rolling tyre.
ROLLING_CAVEAT = ("rolling tyre: the decay cannot be distinguished from vibration excited by ground or tyre "
                  "irregularities, so free vibration is expected to be inaccurate for rolling tyres (thesis §3.4)")

#: Columns of the ``frf`` table (one row per run and frequency bin).
FRF_COLUMNS = ["run_id", "direction", "method", "frequency_Hz", "apparent_mass_real_kg", "apparent_mass_imag_kg",
               "h2_real_kg", "h2_imag_kg", "stiffness_N_per_m", "damping_N_s_per_m", "coherence",
               "stiffness_u_N_per_m", "damping_u_N_s_per_m", "in_fit"]
#: Columns a method run adds to ``results`` (beside K, C, their uncertainty and QC).
METHOD_COLUMNS = {"model": str, "series_damping_N_s_per_m": float, "series_damping_u_N_s_per_m": float,
                  "series_damping_ci95_low_N_s_per_m": float, "series_damping_ci95_high_N_s_per_m": float,
                  "fit_band_low_Hz": float, "fit_band_high_Hz": float, "fit_bins": float,
                  "kelvin_voigt_reduced_chi2": float, "maxwell_reduced_chi2": float,
                  "response_peak_Hz": float, "response_damping_ratio": float,
                  "natural_frequency_Hz": float, "damping_ratio": float, "log_decrement": float,
                  "moving_mass_kg": float, "decay_cycles": float, "secant_stiffness_N_per_m": float,
                  "tangent_stiffness_N_per_m": float, "hysteresis_energy_J": float, "method_note": str,
                  # issue 44: what a broadband estimate is worth, and the uncertainty's parts apart
                  "estimator": str, "h1_stiffness_N_per_m": float, "h1_damping_N_s_per_m": float,
                  "h2_stiffness_N_per_m": float, "h2_damping_N_s_per_m": float, "h1_h2_stiffness_spread": float,
                  "h1_h2_expected_spread": float, "model_test_p": float, "ground_motion_ratio": float,
                  "stiffness_u_a_N_per_m": float, "stiffness_u_b_N_per_m": float,
                  "damping_u_a_N_s_per_m": float, "damping_u_b_N_s_per_m": float,
                  "creep_coefficient_N_s_per_m": float, "creep_coefficient_u_N_s_per_m": float,
                  # issue 44: the ground input's effect on a rolling broadband run, tested against its own error
                  "ground_stiffness_effect_N_per_m": float, "ground_stiffness_effect_u_N_per_m": float,
                  "ground_damping_effect_N_s_per_m": float, "ground_damping_effect_u_N_s_per_m": float,
                  "qc_ground_input": str}


def channel_problem(run_id: str, method: str, channels) -> str | None:
    """The one-line reason a run's channels do not fit its method, or None.

    See Also
    --------
    analyse_method_run : analyses a run whose channels fit.

    Examples
    --------
    >>> channel_problem("R1", "load_deflection", ["time_s", "accel_left_m_s2"])
    'run R1: method load_deflection needs channel deflection_m (tyre deflection, m, compression positive), which the file lacks'
    >>> channel_problem("R1", "random", ["time_s"]) is None
    True
    """
    if method == "load_deflection" and DEFLECTION not in set(channels):
        return (f"run {run_id}: method load_deflection needs channel {DEFLECTION} (tyre deflection, m, "
                "compression positive), which the file lacks")
    return None


def _instrument(budget, k, c, omega=None):
    """§3.2.9 limits on K and C: the force gain scales both; the phase, at ω, rotates Z = K + jωC."""
    g = budget.force_gain
    if omega is None:
        return g * abs(k), g * abs(c) if np.isfinite(c) else math.nan
    return math.hypot(g * k, budget.phase_rad * omega * c), math.hypot(g * c, budget.phase_rad * k / omega)


def _refine(x, i):
    """Parabolic refinement of extremum ``i`` of ``x``: (offset in samples, value)."""
    ym, y0, yp = x[i - 1], x[i], x[i + 1]
    den = ym - 2 * y0 + yp
    d = 0.5 * (ym - yp) / den if den else 0.0
    return d, y0 - 0.25 * (ym - yp) * d


def release_index(x, sample_rate_Hz: float, noise: float) -> int:
    """Sample of the release in a free-vibration record ``x`` (offset removed): the start of the
    decay after the last forcing, found from the envelope (issue 44), whatever came before it.

    The extrema of ``|x|`` above the noise (ten times ``noise`` and 2 % of the largest) are walked
    back from the last one: an extremum belongs to the decay while the one before it is larger by at
    least half the decay rate the extrema after it give (the first three: larger at all), within
    twice the noise. A dwell at resonance before the release keeps its amplitude, so the walk stops
    at the release; the largest ``|x|`` (the old choice) could be a dwell cycle, whose constant
    amplitude made the decay look slower (C −62 % in the audit's runs).

    See Also
    --------
    free_vibration_run : the decay it finds.

    Examples
    --------
    Five seconds at constant amplitude (the dwell), then the decay (ζ = 0.1 at 4 Hz):

    >>> fs = 256.0
    >>> t = np.arange(int(12 * fs)) / fs
    >>> w, s = 2 * np.pi * 4.0, 0.1 * 2 * np.pi * 4.0
    >>> x = np.where(t < 5, np.cos(w * t), np.exp(-s * (t - 5)) * np.cos(w * t))
    >>> round(release_index(x, fs, 1e-4) / fs, 2)
    5.0
    """
    x = np.asarray(x, dtype=float)
    fs = positive("sample_rate_Hz", sample_rate_Hz)
    mag = np.abs(x)
    spec = np.abs(np.fft.rfft(x * np.hanning(x.size)))
    fq = np.fft.rfftfreq(x.size, 1 / fs)
    usable = fq > 0.3
    f_dom = float(fq[usable][np.argmax(spec[usable])]) if usable.any() and x.size > 8 else 1.0
    ext, _ = signal.find_peaks(mag, distance=max(int(0.35 * fs / f_dom), 1))
    if ext.size == 0:
        return int(np.argmax(mag))
    amp = mag[ext]
    above = np.flatnonzero(amp >= max(10 * noise, 0.02 * amp.max()))
    if above.size == 0:
        return int(np.argmax(mag))
    e = int(above[-1])
    tol = 2 * noise
    j = e
    while j > 0:
        if e - j >= 3:
            slope = float(np.polyfit(ext[j:e + 1] / fs, np.log(amp[j:e + 1]), 1)[0])
            need = math.exp(-0.5 * min(slope, 0.0) * (ext[j] - ext[j - 1]) / fs)
        else:
            need = 1.0
        if amp[j - 1] >= amp[j] * need - tol:
            j -= 1
        else:
            break
    return int(ext[j])


def free_vibration_run(time_s, accel_m_s2, force_N, *, min_cycles: int = 3, rolling: bool = False,
                       instrument=None) -> dict:
    """K, C of a free-vibration run (module docstring); ``reasons`` says why not where it fails.

    See Also
    --------
    release_index : where the decay starts.
    analyse_method_run : dispatches to it.

    Examples
    --------
    A 1000 kg mass on 400 kN/m and 4 kN s/m released from 10 mm:

    >>> fs, m, k, c = 256.0, 1000.0, 4e5, 4e3
    >>> t = np.arange(int(10 * fs)) / fs
    >>> s = c / (2 * m); wd = np.sqrt(k / m - s**2)
    >>> x = 0.01 * np.exp(-s * t) * (np.cos(wd * t) + s / wd * np.sin(wd * t))
    >>> a = -(k * x + c * np.gradient(x, t)) / m
    >>> r = free_vibration_run(t, a, m * a)
    >>> round(r["stiffness_N_per_m"] / 1e3), round(r["damping_N_s_per_m"] / 1e3, 2), r["reasons"]
    (400, 4.0, [])
    """
    from .uncertainty import limits_budget

    t = np.asarray(time_s, dtype=float)
    a = np.asarray(accel_m_s2, dtype=float)
    f = np.asarray(force_N, dtype=float)
    fs = 1.0 / float(np.median(np.diff(t)))
    out = {"reasons": [], "method_note": ROLLING_CAVEAT if rolling else ""}
    # the offset (g of a DC accelerometer) from the record's last tenth, where the decay has ended;
    # no filter: a decay that starts at the record's first sample would ring in it
    x = a - np.median(a[-max(a.size // 10, 8):])
    noise = float(np.std(x[-max(len(x) // 10, 8):]))
    i0 = release_index(x, fs, noise)
    tail = x[i0:]
    head = tail[: int(4 * fs)]
    spec = np.abs(np.fft.rfft(head * np.hanning(head.size)))
    fq = np.fft.rfftfreq(head.size, 1 / fs)
    usable = fq > 0.3
    f_dom = float(fq[usable][np.argmax(spec[usable])]) if usable.any() and head.size > 8 else 1.0
    ext, _ = signal.find_peaks(np.abs(tail), distance=max(int(0.35 * fs / f_dom), 1))
    amp0 = abs(tail[0])
    keep = []
    for e in ext:
        if abs(tail[e]) < max(10 * noise, 0.02 * amp0):
            break
        keep.append(e)
    keep = np.asarray(keep, dtype=int)
    if keep.size < 2 * min_cycles or abs(tail[keep[-1]]) > 0.6 * amp0:
        last = abs(tail[keep[-1]]) / amp0 if keep.size else 1.0
        out["reasons"].append(f"no free decay after the release: the axle motion falls to {100 * last:.0f} % of "
                              f"its largest over {keep.size} half-cycles (need {2 * min_cycles} falling below 60 %)")
        return out
    # each extremum's time and height from a parabola fitted over ±1/8 period (noise averages out;
    # the parabola's own error is the same fraction of every extremum, so the decrement keeps none of it)
    h = max(2, int(0.125 * fs / f_dom))
    tp, ap = [], []
    for e in keep:
        if e - h < 0 or e + h >= tail.size:
            continue
        c2, c1, c0 = np.polyfit(np.arange(-h, h + 1), tail[e - h : e + h + 1], 2)
        d = -c1 / (2 * c2) if c2 else 0.0
        if abs(d) > h:
            d, v = _refine(tail, e)
        else:
            v = c0 - c1**2 / (4 * c2)
        tp.append((i0 + e + d) / fs)
        ap.append(abs(v))
    tp, ap = np.asarray(tp), np.asarray(ap)
    n = np.arange(tp.size)
    (half_period, _), cov_t = np.polyfit(n, tp, 1, cov=True)
    # log-amplitude noise is ~ noise / amplitude: weights proportional to the amplitude (polyfit's w is 1/σ)
    (slope, _), cov_a = np.polyfit(tp, np.log(ap), 1, w=ap / ap.max(), cov=True)
    sigma = -float(slope)
    if not sigma > 0:
        out["reasons"].append("no free decay after the release: the extrema do not fall")
        return out
    wd = math.pi / float(half_period)
    sel = slice(i0, i0 + keep[-1] + 1)
    aa, ff = a[sel] - a[sel].mean(), f[sel] - f[sel].mean()
    m = float(np.dot(aa, ff) / np.dot(aa, aa))
    resid = ff - m * aa
    u_m = float(np.sqrt(np.dot(resid, resid) / max(aa.size - 1, 1) / np.dot(aa, aa)))
    if not m > 0:
        out["reasons"].append(f"moving mass from force per acceleration is {m:.0f} kg, not positive")
        return out
    k = m * (wd**2 + sigma**2)
    c = 2 * m * sigma
    u_sigma, u_wd = math.sqrt(cov_a[0, 0]), wd * math.sqrt(cov_t[0, 0]) / float(half_period)
    u_k = math.sqrt((k / m * u_m) ** 2 + (2 * m * wd * u_wd) ** 2 + (2 * m * sigma * u_sigma) ** 2)
    u_c = math.sqrt((c / m * u_m) ** 2 + (2 * m * u_sigma) ** 2)
    dof = max(tp.size - 2, 1)
    bk, bc = _instrument(instrument or limits_budget(), k, c)
    wn = math.hypot(wd, sigma)
    out.update(stiffness_N_per_m=k, damping_N_s_per_m=c, stiffness_u_N_per_m=math.hypot(u_k, bk),
               damping_u_N_s_per_m=math.hypot(u_c, bc), stiffness_u_a_N_per_m=u_k, stiffness_u_b_N_per_m=bk,
               damping_u_a_N_s_per_m=u_c, damping_u_b_N_s_per_m=bc, coverage_factor=float(student_t.ppf(0.975, dof)),
               uncertainty_dof=float(dof), natural_frequency_Hz=wn / (2 * math.pi), damping_ratio=sigma / wn,
               log_decrement=2 * math.pi * sigma / wd, moving_mass_kg=m, decay_cycles=tp.size / 2)
    return out


def load_deflection_run(time_s, force_N, deflection_m, *, instrument=None) -> dict:
    """Secant and tangent stiffness of the loading branch and the loop's equivalent viscous
    coefficient, the creep (module docstring). K is the secant stiffness; C is null (the loop of a
    slow cycle is creep, ``creep_coefficient_N_s_per_m``, not dynamic damping).

    See Also
    --------
    analyse_method_run : dispatches to it.
    tyrelab.measurement.methods.load_deflection_stiffness : the thesis' secant stiffness.

    Examples
    --------
    A Kelvin–Voigt tyre (300 kN/m, 2 kN s/m) cycled over 20 mm in 40 s:

    >>> t = np.arange(0, 40, 0.01)
    >>> d = 0.01 * (1 - np.cos(2 * np.pi * t / 40))
    >>> r = load_deflection_run(t, 3e5 * d + 2e3 * np.gradient(d, t), d)
    >>> round(r["secant_stiffness_N_per_m"] / 1e3), round(r["creep_coefficient_N_s_per_m"] / 1e3, 2)
    (300, 2.0)
    >>> bool(np.isnan(r["damping_N_s_per_m"]))
    True
    """
    from .uncertainty import limits_budget

    t = np.asarray(time_s, dtype=float)
    F = np.asarray(force_N, dtype=float)
    d = np.asarray(deflection_m, dtype=float)
    out = {"reasons": [], "method_note": "slow loading lets the rubber creep: the stiffness is low (thesis §3.4)"}
    fs = 1.0 / float(np.median(np.diff(t)))
    # the deflection's direction from a smoothed derivative (1 s window)
    win = max(int(fs) | 1, 5)
    ds = signal.savgol_filter(d, win if win < d.size else (d.size - 1) | 1, 2, deriv=1, delta=1 / fs)
    span = float(np.ptp(d))
    if not span > 0:
        out["reasons"].append("the deflection does not change: no loading branch")
        return out
    i_max = int(np.argmax(d))
    loading = np.flatnonzero((ds > 0) & (np.arange(d.size) <= i_max))
    if loading.size < 10:
        out["reasons"].append("no loading branch (the deflection never rises)")
        return out
    seg = slice(loading[0], i_max + 1)
    dl, Fl = d[seg], F[seg]
    n_end = max(dl.size // 20, 3)
    fit = np.polyfit(dl, Fl, 1)
    s_res = float(np.std(Fl - np.polyval(fit, dl), ddof=2))
    d0, d1 = dl[:n_end].mean(), dl[-n_end:].mean()
    f0, f1 = Fl[:n_end].mean(), Fl[-n_end:].mean()
    secant = (f1 - f0) / (d1 - d0)
    u_sec = math.sqrt(2) * s_res / math.sqrt(n_end) / abs(d1 - d0)
    top = dl >= dl.max() - 0.25 * (dl.max() - dl.min())
    tangent = float(np.polyfit(dl[top], Fl[top], 1)[0]) if top.sum() >= 5 else math.nan
    dof = max(n_end - 1, 1)
    budget = instrument or limits_budget()
    out.update(secant_stiffness_N_per_m=secant, tangent_stiffness_N_per_m=tangent, stiffness_N_per_m=secant,
               stiffness_u_N_per_m=math.hypot(u_sec, budget.force_gain * abs(secant)),
               stiffness_u_a_N_per_m=u_sec, stiffness_u_b_N_per_m=budget.force_gain * abs(secant),
               coverage_factor=float(student_t.ppf(0.975, dof)), uncertainty_dof=float(dof),
               damping_N_s_per_m=math.nan, damping_u_N_s_per_m=math.nan)
    if i_max >= d.size - 10 or float(d[-1] - d.min()) > 0.5 * span:
        out["method_note"] += "; no unloading branch: no hysteresis loop, no creep coefficient"
        return out
    # energy dissipated over the loop (trapezoid of F over the deflection) and the viscous equivalent
    energy = float(_trapezoid(F, d))
    rate2 = float(_trapezoid(ds**2, t))
    c_eq = energy / rate2
    u_e = s_res * math.sqrt(float(np.sum(np.diff(d) ** 2)))
    out.update(hysteresis_energy_J=energy, creep_coefficient_N_s_per_m=c_eq,
               creep_coefficient_u_N_s_per_m=math.hypot(u_e / rate2, budget.force_gain * abs(c_eq)))
    out["method_note"] += "; the loop's equivalent viscous coefficient is creep (creep_coefficient_N_s_per_m), not damping"
    return out


def _interval(row: dict, name: str, unit: str) -> None:
    v, u, k = row.get(f"{name}_{unit}", math.nan), row.get(f"{name}_u_{unit}", math.nan), row.get("coverage_factor")
    k = math.nan if k is None else k
    row[f"{name}_ci95_low_{unit}"] = v - k * u
    row[f"{name}_ci95_high_{unit}"] = v + k * u


def analyse_method_run(method: str, direction: str, time_s, accel_m_s2, beams_N, axle_mass_kg: float, *,
                       band_Hz=None, rolling: bool = False, deflection_m=None, run_id: str = "",
                       instrument=None) -> tuple[dict, pd.DataFrame]:
    """Analyse one run of a method other than ``stepped_sine``; return its ``results`` fields and
    its ``frf`` rows (empty but for broadband runs).

    ``accel_m_s2`` (2, n) and ``beams_N`` (4, n) are the raw-format-v1 channels along the run's
    direction; the tyre force is :func:`tyrelab.measurement.apparent_mass.tyre_force`.
    ``reasons`` in the fields (a list) says why K and C are not reported.

    Raises
    ------
    ValueError
        Naming the argument: an unknown method or direction, a missing band or deflection.

    See Also
    --------
    free_vibration_run, load_deflection_run : the methods it dispatches to.
    tyrelab.measurement.broadband.analyse_broadband : the broadband runs'.
    channel_problem : whether the run's channels fit its method.

    Examples
    --------
    A free-vibration run of a 1000 kg axle on 400 kN/m and 4 kN s/m released from 10 mm (the load
    beams carry nothing: the tyre force is the axle's ``M_a a``):

    >>> fs, m, k, c = 256.0, 1000.0, 4e5, 4e3
    >>> t = np.arange(int(10 * fs)) / fs
    >>> s = c / (2 * m); wd = np.sqrt(k / m - s**2)
    >>> x = 0.01 * np.exp(-s * t) * (np.cos(wd * t) + s / wd * np.sin(wd * t))
    >>> a = -(k * x + c * np.gradient(x, t)) / m
    >>> fields, frf = analyse_method_run("free_vibration", "vertical", t, np.stack([a, a]), np.zeros((4, t.size)), m)
    >>> round(fields["stiffness_N_per_m"] / 1e3), round(fields["damping_N_s_per_m"] / 1e3, 2), fields["reasons"], len(frf)
    (400, 4.0, [], 0)
    """
    from .apparent_mass import EXCITATION_BAND_Hz, tyre_force

    if method not in METHODS or method == "stepped_sine":
        raise ValueError(f"method must be one of {', '.join(METHODS[1:])}, got {method!r}")
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {', '.join(DIRECTIONS)}, got {direction!r}")
    mass = positive("axle_mass_kg", axle_mass_kg)
    t = np.asarray(time_s, dtype=float)
    accel = np.asarray(accel_m_s2, dtype=float)
    force = tyre_force(accel[0], accel[1], np.asarray(beams_N, dtype=float), mass)
    a = accel.mean(axis=0)
    fs = 1.0 / float(np.median(np.diff(t)))
    row = {"direction": direction, "method": method}
    frf = pd.DataFrame(columns=FRF_COLUMNS)
    if method in BROADBAND:
        if band_Hz is None and method in BAND_REQUIRED:
            raise ValueError(f"band_Hz: method {method} needs its band")
        lo, hi = band("band_Hz", band_Hz if band_Hz is not None else EXCITATION_BAND_Hz)
        r = bb.analyse_broadband(force, a, fs, (lo, hi), rolling=rolling, swept=method == "swept_sine",
                                 instrument=instrument, accel_pair_m_s2=accel[:2], axle_mass_kg=mass)
        b = (r.frequency_Hz >= lo) & (r.frequency_Hz <= hi)
        frf = pd.DataFrame({
            "run_id": run_id, "direction": direction, "method": method, "frequency_Hz": r.frequency_Hz[b],
            # the thesis' apparent mass H = -F/A (deflection-positive, §3.3.1)
            "apparent_mass_real_kg": -r.h1_kg.real[b], "apparent_mass_imag_kg": -r.h1_kg.imag[b],
            "h2_real_kg": -r.h2_kg.real[b], "h2_imag_kg": -r.h2_kg.imag[b],
            "stiffness_N_per_m": r.stiffness_N_per_m_f[b], "damping_N_s_per_m": r.damping_N_s_per_m_f[b],
            "coherence": r.coherence[b], "stiffness_u_N_per_m": r.stiffness_u_f[b],
            "damping_u_N_s_per_m": r.damping_u_f[b], "in_fit": r.in_fit[b]}, columns=FRF_COLUMNS)
        row.update(reasons=list(r.reasons) + list(r.flags), response_peak_Hz=r.response_peak_Hz,
                   response_damping_ratio=r.response_damping_ratio, estimator=r.estimator)
        if r.fit is not None:
            for name, other in (("h1", r.h1_fit), ("h2", r.h2_fit)):
                if other is not None:
                    row[f"{name}_stiffness_N_per_m"] = other.stiffness_N_per_m
                    row[f"{name}_damping_N_s_per_m"] = other.damping_N_s_per_m
            row.update(h1_h2_stiffness_spread=r.h1_h2_stiffness_spread, h1_h2_expected_spread=r.h1_h2_expected_spread,
                       model_test_p=r.model_test_p, ground_motion_ratio=r.ground_motion_ratio,
                       stiffness_u_a_N_per_m=r.stiffness_u_a_N_per_m,
                       stiffness_u_b_N_per_m=r.stiffness_u_b_N_per_m, damping_u_a_N_s_per_m=r.damping_u_a_N_s_per_m,
                       damping_u_b_N_s_per_m=r.damping_u_b_N_s_per_m)
            if r.ground_input is not None:
                row.update(ground_stiffness_effect_N_per_m=r.ground_stiffness_effect_N_per_m,
                           ground_stiffness_effect_u_N_per_m=r.ground_stiffness_effect_u_N_per_m,
                           ground_damping_effect_N_s_per_m=r.ground_damping_effect_N_s_per_m,
                           ground_damping_effect_u_N_s_per_m=r.ground_damping_effect_u_N_s_per_m,
                           qc_ground_input=r.ground_input)
            fb = r.frequency_Hz[r.in_fit]
            row.update(model=r.fit.model, stiffness_N_per_m=r.fit.stiffness_N_per_m,
                       damping_N_s_per_m=r.fit.damping_N_s_per_m,
                       series_damping_N_s_per_m=r.fit.series_damping_N_s_per_m,
                       stiffness_u_N_per_m=r.stiffness_u_N_per_m, damping_u_N_s_per_m=r.damping_u_N_s_per_m,
                       series_damping_u_N_s_per_m=r.series_damping_u_N_s_per_m,
                       coverage_factor=r.coverage_factor, uncertainty_dof=float(r.dof),
                       coherence=float(np.mean(r.coherence[r.in_fit])), fit_band_low_Hz=float(fb.min()),
                       fit_band_high_Hz=float(fb.max()), fit_bins=float(r.in_fit.sum()),
                       **{f"{m}_reduced_chi2": v.reduced_chi2 for m, v in r.alternatives.items()})
            _interval(row, "series_damping", "N_s_per_m")
    elif method == "free_vibration":
        row.update(free_vibration_run(t, a, force, rolling=rolling, instrument=instrument))
    else:
        if deflection_m is None:
            raise ValueError(f"deflection_m: method load_deflection needs the {DEFLECTION} channel")
        # compression force on the tyre: the tyre's force on the axle, upward positive
        row.update(load_deflection_run(t, force, np.asarray(deflection_m, dtype=float), instrument=instrument))
    _interval(row, "stiffness", "N_per_m")
    _interval(row, "damping", "N_s_per_m")
    return row, frf
