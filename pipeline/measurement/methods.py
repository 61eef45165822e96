"""Alternative methods of measuring tyre stiffness and damping (thesis §3.4, Table I).

a) load-deflection: slope of the slow load-deflection curve (no damping);
b) free vibration: natural frequency and logarithmic decrement of the decay;
c) forced vibration: peak frequency and half-power bandwidth of the response
   to random (or swept) force.

The response-based methods b) and c) measure the whole suspended system, so
they include the linkage between tractor and carriage (damping upper bound
1.2 kNs/m, §3.4) which the apparent-mass method excludes; slow loading lets
the rubber creep, which makes the load-deflection stiffness low (§3.4).
:func:`tyrelab.rig.experiments.table_i` reproduces the structure of Table I by applying these
methods to virtual experiments on the stationary tyre T1 at 1.38 bar (the rig runs the
experiments and calls the methods here; this module never runs the rig).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from scipy import signal

from .._validate import band, positive, positive_int, same_last_axis
from ..units import STANDARD_GRAVITY_M_S2
from .apparent_mass import h1_spectrum

__all__ = ["METHODS", "TABLE_I_SOURCE", "TABLE_I_RECORDINGS_SOURCE", "THESIS_DIRECTION", "THESIS_METHOD",
           "DIRECTIONS", "load_deflection_stiffness", "free_vibration", "half_power", "direction_runs", "thesis_runs",
           "table_i_runs", "table_i_from_results"]

#: The methods of Table I (§3.4), as named in ``raw/published/table_i.csv``.
METHODS = ("apparent_mass", "load_deflection", "free_vibration", "forced_vibration")
#: Where our Table I comes from: virtual experiments, not the campaign's recordings.
TABLE_I_SOURCE = "virtual experiments on the truth-model tyre (tyrelab.rig.experiments)"
#: ... or the campaign's recordings of several methods on one tyre and condition (issue 34).
#: ``source`` of a Table I from recordings: ``runs`` the runs its rows are the means of (``n_runs`` summed),
#: ``methods`` how many of them each method's row has (issue 44: it said the case's runs of every method
#: and frequency, "8 runs" where the rows rest on 1-2 each).
TABLE_I_RECORDINGS_SOURCE = "recordings: {tyre} at {pressure:g} bar, {load:g} kN, stationary ({runs} runs: {methods})"
_G = STANDARD_GRAVITY_M_S2
#: The direction and method of the runs the thesis' tables and figures rest on (chapters 4-5: the
#: vertical apparent mass by stepped sine, §3.2); the other directions have tables of their own (issue 44).
THESIS_DIRECTION, THESIS_METHOD = "vertical", "stepped_sine"
#: The directions a rig run may have (raw format v1's ``direction``).
DIRECTIONS = ("vertical", "lateral", "longitudinal")


def direction_runs(results: pd.DataFrame, direction: str) -> pd.DataFrame:
    """The rows of ``results`` of one ``direction`` (a row without one is vertical: a build from
    before issue 34); every column kept.

    See Also
    --------
    thesis_runs : the vertical stepped-sine runs.

    Examples
    --------
    >>> r = pd.DataFrame({"run_id": ["a", "b", "c"], "direction": ["vertical", "lateral", None]})
    >>> list(direction_runs(r, "vertical")["run_id"]), list(direction_runs(r, "lateral")["run_id"])
    (['a', 'c'], ['b'])
    """
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {DIRECTIONS}, got {direction!r}")
    if results is None or "direction" not in results.columns:
        return results if direction == THESIS_DIRECTION or results is None else results.iloc[0:0]
    return results.loc[results["direction"].fillna(THESIS_DIRECTION).astype(str) == direction]


def thesis_runs(results: pd.DataFrame) -> pd.DataFrame:
    """The runs the thesis' tables and figures rest on: vertical stepped-sine runs (issue 34; issue 44:
    a lateral or longitudinal run never enters a vertical table or figure). A build without the
    ``direction``/``method`` columns is all of them.

    See Also
    --------
    direction_runs : the runs of one direction.

    Examples
    --------
    >>> r = pd.DataFrame({"direction": ["vertical", "lateral", "vertical"],
    ...                   "method": ["stepped_sine", "stepped_sine", "random"]})
    >>> thesis_runs(r).index.tolist()
    [0]
    """
    keep = pd.Series(True, index=results.index)
    for name, value in (("direction", THESIS_DIRECTION), ("method", THESIS_METHOD)):
        if name in results:
            keep &= results[name].fillna(value).astype(str) == value
    return results.loc[keep] if not keep.all() else results


def load_deflection_stiffness(force_N: np.ndarray, deflection_m: np.ndarray, fraction: tuple[float, float] = (0.2, 0.9)) -> float:
    """Stiffness (N/m) from the loading branch of a load-deflection test.

    Straight line of force on deflection over the loading branch between
    ``fraction`` of the maximum force (the unloading branch differs by the
    hysteresis, §3.4).

    See Also
    --------
    free_vibration, half_power : the dynamic methods.

    Examples
    --------
    >>> d = np.r_[np.linspace(0, 0.02, 50), np.linspace(0.02, 0, 50)]       # loading, then unloading
    >>> F = np.r_[250e3 * d[:50], 250e3 * d[50:] - 800.0]                      # hysteresis on the way back
    >>> round(load_deflection_stiffness(F, d))
    250000
    """
    F = np.asarray(force_N, dtype=float)
    d = np.asarray(deflection_m, dtype=float)
    same_last_axis(force_N=F, deflection_m=d)
    if not 0 <= fraction[0] < fraction[1] <= 1:
        raise ValueError(f"fraction must satisfy 0 <= low < high <= 1, got {fraction!r}")
    i_max = int(np.argmax(F))
    F, d = F[: i_max + 1], d[: i_max + 1]
    sel = (F >= fraction[0] * F.max()) & (F <= fraction[1] * F.max())
    return float(np.polyfit(d[sel], F[sel], 1)[0])


def free_vibration(time_s: np.ndarray, response: np.ndarray, mass_kg: float, n_cycles: int = 5) -> dict:
    """K and C from a free decay: damped frequency and logarithmic decrement.

    Positive peaks of the (mean-removed) response; ``delta = ln(x_0/x_n)/n``,
    ``zeta = delta/sqrt(4 pi^2 + delta^2)``, damped frequency from the peak
    spacing, ``w_n = w_d/sqrt(1 - zeta^2)``, ``K = m w_n^2``, ``C = 2 zeta m w_n``.

    Returns
    -------
    dict
        ``stiffness_N_per_m``, ``damping_N_s_per_m``, ``natural_frequency_Hz``, ``damping_ratio``.

    See Also
    --------
    half_power : the forced-vibration method.
    table_i_from_results : the methods side by side.

    Examples
    --------
    >>> m, k, zeta = 1000.0, 250e3, 0.1                  # a 2.52 Hz mode, 10 % damped
    >>> wn = np.sqrt(k / m); wd = wn * np.sqrt(1 - zeta**2); t = np.arange(0, 4, 1 / 1000)
    >>> r = free_vibration(t, np.exp(-zeta * wn * t) * np.cos(wd * t), m)
    >>> round(float(r["stiffness_N_per_m"]), -3), round(float(r["damping_ratio"]), 3), round(float(r["natural_frequency_Hz"]), 2)
    (250000.0, 0.1, 2.52)
    """
    mass_kg = positive("mass_kg", mass_kg)
    n_cycles = positive_int("n_cycles", n_cycles, minimum=2)  # a decrement needs two cycles
    t = np.asarray(time_s, dtype=float)
    x = np.asarray(response, dtype=float)
    same_last_axis(time_s=t, response=x)
    x = x - x[-len(x) // 10:].mean()
    fs = 1.0 / (t[1] - t[0])
    peaks, _ = signal.find_peaks(x, height=0.05 * np.abs(x).max(), distance=max(int(0.12 * fs), 1))
    peaks = peaks[: n_cycles + 1]
    if peaks.size < 3:
        raise ValueError("too few decay cycles")
    # parabolic refinement of each peak's time and height
    tp, xp = [], []
    dt = t[1] - t[0]
    for p in peaks:
        ym, y0, yp = x[p - 1], x[p], x[p + 1]
        den = ym - 2 * y0 + yp
        delta = 0.5 * (ym - yp) / den if den else 0.0
        tp.append(t[p] + delta * dt)
        xp.append(y0 - 0.25 * (ym - yp) * delta)
    tp, xp = np.asarray(tp), np.asarray(xp)
    n = len(xp) - 1
    log_dec = float(np.log(xp[0] / xp[-1]) / n)
    zeta = log_dec / np.sqrt(4 * np.pi**2 + log_dec**2)
    wd = 2 * np.pi * n / (tp[-1] - tp[0])
    wn = wd / np.sqrt(1 - zeta**2)
    return {"stiffness_N_per_m": mass_kg * wn**2, "damping_N_s_per_m": 2 * zeta * mass_kg * wn,
            "natural_frequency_Hz": wn / (2 * np.pi), "damping_ratio": zeta}


def half_power(force_N: np.ndarray, accel_m_s2: np.ndarray, sample_rate_Hz: float, mass_kg: float,
               resolution_Hz: float = 0.01, band_Hz: tuple[float, float] = (1.0, 8.0)) -> dict:
    """K and C from the forced response: resonance peak and half-power bandwidth.

    Receptance ``X/F = -H1/w^2`` with ``H1 = csd(F, a)/welch(F)`` (system from
    force to acceleration, :func:`tyrelab.measurement.apparent_mass.h1_spectrum`);
    peak frequency ``f_n`` and the -3 dB points (linear interpolation) give
    ``zeta = (f2 - f1)/(2 f_n)``; ``K = m (2 pi f_n)^2``, ``C = 2 zeta m 2 pi f_n``.

    Raises
    ------
    ValueError
        Naming a non-positive rate, mass or resolution, a bad band, or force
        and acceleration of different lengths.

    See Also
    --------
    free_vibration : the free-decay method.
    tyrelab.measurement.apparent_mass.h1_spectrum : the H1 it reads.

    Examples
    --------
    >>> fs, n = 100.0, 100 * 600                                   # 10 min of random force
    >>> f = np.fft.rfftfreq(n, 1 / fs); w = 2 * np.pi * f
    >>> F = np.array([1, 1j]) @ np.random.default_rng(1).normal(size=(2, f.size)); F[0] = 0
    >>> m, k, c = 1000.0, 250e3, 2000.0                              # a 2.52 Hz mode, 6.3 % damped
    >>> a = np.fft.irfft(-w**2 * F / (k - m * w**2 + 1j * w * c), n)
    >>> r = half_power(np.fft.irfft(F, n), a, fs, m)
    >>> round(float(r["stiffness_N_per_m"]), -3), round(float(r["natural_frequency_Hz"]), 2), round(float(r["damping_N_s_per_m"]), -2)
    (251000.0, 2.52, 2000.0)
    """
    sample_rate_Hz = positive("sample_rate_Hz", sample_rate_Hz)
    mass_kg = positive("mass_kg", mass_kg)
    resolution_Hz = positive("resolution_Hz", resolution_Hz)
    band_Hz = band("band_Hz", band_Hz)
    s = h1_spectrum(force_N, accel_m_s2, sample_rate_Hz, int(round(sample_rate_Hz / resolution_Hz)))
    sel = (s.frequency_Hz >= band_Hz[0]) & (s.frequency_Hz <= band_Hz[1])
    f, h = s.frequency_Hz[sel], s.h1[sel]
    r = np.abs(h) / (2 * np.pi * f) ** 2
    k = int(np.argmax(r))
    # parabolic refinement of the peak
    ym, y0, yp = r[k - 1], r[k], r[k + 1]
    den = ym - 2 * y0 + yp
    dk = 0.5 * (ym - yp) / den if den else 0.0
    fn = f[k] + dk * (f[1] - f[0])
    peak = y0 - 0.25 * (ym - yp) * dk
    level = peak / np.sqrt(2)
    i1 = k
    while i1 > 0 and r[i1] > level:
        i1 -= 1
    i2 = k
    while i2 < r.size - 1 and r[i2] > level:
        i2 += 1
    f1 = np.interp(level, [r[i1], r[i1 + 1]], [f[i1], f[i1 + 1]])
    f2 = np.interp(level, [r[i2], r[i2 - 1]], [f[i2], f[i2 - 1]])
    zeta = (f2 - f1) / (2 * fn)
    wn = 2 * np.pi * fn
    return {"stiffness_N_per_m": mass_kg * wn**2, "damping_N_s_per_m": 2 * zeta * mass_kg * wn,
            "natural_frequency_Hz": fn, "damping_ratio": zeta}


def table_i_runs(results: pd.DataFrame) -> pd.DataFrame:
    """Vertical stationary runs grouped by tyre and condition, with the Table I method each gives
    (``table_i_method``; None where none): stepped sine → apparent mass, swept sine and random →
    forced vibration, free vibration, load deflection. Only runs whose QC passed.

    See Also
    --------
    table_i_from_results : Table I from these runs.

    Examples
    --------
    >>> r = pd.DataFrame({"tyre_id": "T1", "pressure_bar": 1.38, "load_kN": 18.3, "speed_km_h": [0.0, 0.0, 10.0],
    ...                   "method": ["random", "free_vibration", "stepped_sine"], "direction": "vertical", "qc_ok": True})
    >>> table_i_runs(r)["table_i_method"].tolist()     # the rolling run is not a Table I run
    ['forced_vibration', 'free_vibration']
    """
    need = {"tyre_id", "pressure_bar", "load_kN", "speed_km_h", "method", "direction", "qc_ok"}
    if results is None or results.empty or not need <= set(results.columns):
        return pd.DataFrame(columns=[*need, "table_i_method"])
    r = results.loc[(results["direction"].fillna("vertical") == "vertical") & (results["speed_km_h"] == 0)
                    & results["qc_ok"].fillna(False).astype(bool)].copy()
    r["table_i_method"] = r["method"].fillna("stepped_sine").map(
        {"stepped_sine": "apparent_mass", "swept_sine": "forced_vibration", "random": "forced_vibration",
         "free_vibration": "free_vibration", "load_deflection": "load_deflection"})
    r["pressure_bar"] = r["pressure_bar"].round(2)
    r["load_kN"] = r["load_kN"].round(1)
    return r


def table_i_from_results(results: pd.DataFrame, thesis: pd.DataFrame) -> pd.DataFrame | None:
    """Table I from a campaign's recordings (issue 34), or None where no tyre and condition has a
    stepped-sine run and a run of another method.

    The case with the most methods (ties: most runs, then tyre, pressure, load) is taken. Per
    method the mean over its runs: apparent mass K and C of the stepped-sine runs (those at
    4 ± 0.5 Hz where there are any, the thesis' frequency); forced
    vibration from the broadband runs' response peak and half-power width, free vibration
    from the decay's natural frequency and damping ratio, both with the suspended mass L/g as
    the thesis computes them (§3.4; :func:`tyrelab.rig.experiments.suspended_mass_kg`);
    load deflection the secant stiffness (no damping: "the viscous damping coefficient cannot
    be measured by this means", §3.4). Columns as :func:`tyrelab.rig.experiments.table_i`
    (``truth_*`` null) and ``source`` naming the case.

    See Also
    --------
    table_i_runs : the runs it groups.
    tyrelab.rig.experiments.table_i : the same from virtual experiments.

    Examples
    --------
    A stepped-sine run and a free decay of one tyre at 18.3 kN: the decay's 2.3 Hz and 10 % with the
    suspended mass L/g = 1866 kg give K = m ω² = 389.7 kN/m and C = 2 ζ m ω = 5.39 kN s/m:

    >>> from tyrelab.published import read_published
    >>> r = pd.DataFrame({"tyre_id": "T1", "pressure_bar": 1.38, "load_kN": 18.3, "speed_km_h": 0.0, "direction": "vertical",
    ...                   "qc_ok": True, "method": ["stepped_sine", "free_vibration"], "excitation_frequency_Hz": [4.0, np.nan],
    ...                   "stiffness_N_per_m": [400e3, np.nan], "damping_N_s_per_m": [2.0e3, np.nan],
    ...                   "natural_frequency_Hz": [np.nan, 2.3], "damping_ratio": [np.nan, 0.1]})
    >>> t = table_i_from_results(r, read_published("table_i")).set_index("method")
    >>> t.loc[["apparent_mass", "free_vibration"], ["stiffness_kN_per_m", "damping_kN_s_per_m"]].round(2).values.tolist()
    [[400.0, 2.0], [389.71, 5.39]]
    """
    runs = table_i_runs(results)
    runs = runs.loc[runs["table_i_method"].notna()]
    if runs.empty:
        return None
    keys = ["tyre_id", "pressure_bar", "load_kN"]
    best = None
    for key, g in runs.groupby(keys, sort=True):
        methods = set(g["table_i_method"])
        if "apparent_mass" not in methods or len(methods) < 2:
            continue
        score = (len(methods), len(g))
        if best is None or score > best[0]:
            best = (score, key, g)
    if best is None:
        return None
    (_, (tyre, pressure, load), g) = best
    m = load * 1e3 / _G
    ours = {}
    at4_of = 0  # the stepped-sine runs of the case, of which those at 4 Hz are used where there are any
    for method, sub in g.groupby("table_i_method"):
        if method == "apparent_mass":
            at4_of = len(sub)
            at4 = (sub["excitation_frequency_Hz"] - 4.0).abs() <= 0.5  # the thesis' 4 Hz where there are such runs
            sub = sub.loc[at4] if at4.any() else sub
            k, c = sub["stiffness_N_per_m"].mean(), sub["damping_N_s_per_m"].mean()
        elif method == "load_deflection":
            k, c = sub["secant_stiffness_N_per_m"].mean(), np.nan
        else:
            f, z = (("response_peak_Hz", "response_damping_ratio") if method == "forced_vibration"
                    else ("natural_frequency_Hz", "damping_ratio"))
            wn = 2 * np.pi * sub[f].to_numpy(float)
            k = float(np.nanmean(m * wn**2))
            c = float(np.nanmean(2 * sub[z].to_numpy(float) * m * wn))
        ours[method] = (float(k), float(c), len(sub))
    th = thesis.set_index("method")
    used = {method: ours[method][2] for method in METHODS if method in ours}
    each = ", ".join(f"{method.replace('_', ' ')} {n}" + (" at 4 Hz" if method == "apparent_mass" and n < at4_of else "")
                     for method, n in used.items())
    source = TABLE_I_RECORDINGS_SOURCE.format(tyre=tyre, pressure=pressure, load=load, runs=sum(used.values()), methods=each)
    k0, c0, _ = ours["apparent_mass"]
    tk0, tc0 = (float(th.loc["apparent_mass", c]) for c in ("stiffness_kN_per_m", "damping_kN_s_per_m"))
    rows = []
    for method in METHODS:
        tk, tc = (float(th.loc[method, c]) for c in ("stiffness_kN_per_m", "damping_kN_s_per_m"))
        k, c, n = ours.get(method, (np.nan, np.nan, 0))
        rows.append({
            "method": method, "method_label": th.loc[method, "method_label"], "source": source,
            "thesis_stiffness_kN_per_m": tk, "thesis_damping_kN_s_per_m": tc,
            "stiffness_kN_per_m": k / 1e3, "damping_kN_s_per_m": c / 1e3,
            "stiffness_difference_kN_per_m": k / 1e3 - tk, "damping_difference_kN_s_per_m": c / 1e3 - tc,
            "thesis_stiffness_ratio": tk / tk0, "stiffness_ratio": k / k0,
            "thesis_damping_excess_kN_s_per_m": tc - tc0, "damping_excess_kN_s_per_m": (c - c0) / 1e3,
            "truth_stiffness_kN_per_m": np.nan, "truth_damping_kN_s_per_m": np.nan,
            "tyre_id": tyre, "pressure_bar": pressure, "load_kN": load, "n_runs": n,
        })
    return pd.DataFrame(rows)
