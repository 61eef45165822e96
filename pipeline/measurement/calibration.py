"""Daily force-plate calibration check of the tyre force (thesis §3.2.9, §3.6).

The test wheel stands on a calibrated force plate while the vibrator is driven
with random noise band-limited to 1-8 Hz. The transfer function from the
force-plate force to the tyre force derived by the vehicle instrumentation
(``M_a * mean(acc) - sum(beams)``) must have magnitude 1 +- 3 % and phase
0 +- 1 degree between 2 and 6 Hz; that is +-3 % in stiffness and +-10 % in
damping for a 230 kN/m, 2.4 kNs/m tyre. Runs recorded on a day whose check
fails are flagged; optionally (§3.6) results can be corrected by the day's
transfer function.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .._validate import band, positive
from .apparent_mass import h1_spectrum

__all__ = ["CHECK_BAND_HZ", "GAIN_TOLERANCE", "PHASE_TOLERANCE_DEG", "calibration_transfer_function",
    "check_calibration", "day_summary", "CALIBRATION_REASON", "flag_failed_days", "correction_factor",
    "corrected_stiffness_damping"]

CHECK_BAND_HZ = (2.0, 6.0)  # §3.2.9
GAIN_TOLERANCE = 0.03  # §3.2.9: 1 +- 3 %
PHASE_TOLERANCE_DEG = 1.0  # §3.2.9: 0 +- 1 degree


def calibration_transfer_function(force_plate_N: np.ndarray, derived_force_N: np.ndarray, sample_rate_Hz: float,
                                  resolution_Hz: float = 0.25, band_Hz: tuple[float, float] = (1.0, 8.0),
                                  inertial_force_N: np.ndarray | None = None) -> pd.DataFrame:
    """H1 from force-plate force to derived tyre force.

    ``H1 = csd(fp, ft) / welch(fp)``, the system from x = force plate to
    y = derived force (:func:`tyrelab.measurement.apparent_mass.h1_spectrum`);
    Hann window, 50 % overlap, segments of ``1/resolution_Hz`` seconds.

    Parameters
    ----------
    force_plate_N, derived_force_N : ndarray
        Force-plate force and derived tyre force, N, upward positive.
    sample_rate_Hz : float
    resolution_Hz : float
        Frequency resolution, Hz.
    band_Hz : (float, float)
        Frequencies returned, Hz (the excitation band).
    inertial_force_N : ndarray, optional
        The axle's inertial force ``M_a * mean(acc)``, N. When given, the
        ratio ``R = M_a a / f_t`` (H1 from the force plate to it) is returned
        as ``inertial_ratio_re``, ``inertial_ratio_im``: a gain mismatch
        ``δa − δb`` between accelerometers and load beams turns the check's
        transfer function into ``1 + δb + (δa − δb) R``, so its phase moves by
        ``(δa − δb) Im R`` although the force path has no phase error
        (:func:`tyrelab.measurement.uncertainty.day_budget`).

    Returns
    -------
    DataFrame
        ``frequency_Hz``, ``gain`` (|H|), ``phase_deg`` (angle of H), ``coherence``
        (and ``inertial_ratio_re``, ``inertial_ratio_im`` with ``inertial_force_N``).

    See Also
    --------
    check_calibration : the day's pass or fail from it.
    correction_factor : the §3.6 correction from it.

    Examples
    --------
    >>> fs = 256.0; t = np.arange(0, 60, 1 / fs)
    >>> plate = np.random.default_rng(1).normal(size=t.size) * 1e3   # the force plate's force, N
    >>> tf = calibration_transfer_function(plate, 1.02 * plate, fs)   # the derived force reads 2 % high
    >>> round(float(tf["gain"].mean()), 4), round(float(tf["phase_deg"].abs().max()), 6)
    (1.02, 0.0)
    """
    sample_rate_Hz = positive("sample_rate_Hz", sample_rate_Hz)
    resolution_Hz = positive("resolution_Hz", resolution_Hz)
    band_Hz = band("band_Hz", band_Hz)
    s = h1_spectrum(force_plate_N, derived_force_N, sample_rate_Hz, int(round(sample_rate_Hz / resolution_Hz)))
    sel = (s.frequency_Hz >= band_Hz[0]) & (s.frequency_Hz <= band_Hz[1])
    h = s.h1[sel]
    out = pd.DataFrame({"frequency_Hz": s.frequency_Hz[sel], "gain": np.abs(h),
                        "phase_deg": np.degrees(np.angle(h)), "coherence": s.coherence[sel]})
    if inertial_force_N is not None:
        r = h1_spectrum(force_plate_N, inertial_force_N, sample_rate_Hz, int(round(sample_rate_Hz / resolution_Hz))).h1[sel]
        out["inertial_ratio_re"], out["inertial_ratio_im"] = r.real, r.imag
    return out


def check_calibration(tf: pd.DataFrame, band_Hz: tuple[float, float] = CHECK_BAND_HZ,
                      gain_tolerance: float = GAIN_TOLERANCE, phase_tolerance_deg: float = PHASE_TOLERANCE_DEG) -> dict:
    """Pass/fail of one calibration transfer function against §3.2.9.

    Returns
    -------
    dict
        ``pass`` (bool), ``max_gain_error_pct``, ``max_phase_error_deg``,
        ``mean_gain``, ``mean_phase_deg`` over ``band_Hz``.

    See Also
    --------
    calibration_transfer_function : the function it checks.
    day_summary : the day's verdict over its checks.

    Examples
    --------
    >>> fs = 256.0; t = np.arange(0, 60, 1 / fs)
    >>> plate = np.random.default_rng(1).normal(size=t.size) * 1e3   # the force plate's force, N
    >>> tf = calibration_transfer_function(plate, 1.02 * plate, fs)   # the derived force reads 2 % high
    >>> c = check_calibration(tf)
    >>> c["pass"], round(c["max_gain_error_pct"], 2)
    (True, 2.0)
    >>> check_calibration(calibration_transfer_function(plate, 1.05 * plate, fs))["pass"]
    False
    """
    band_Hz = band("band_Hz", band_Hz)
    gain_tolerance = positive("gain_tolerance", gain_tolerance)
    phase_tolerance_deg = positive("phase_tolerance_deg", phase_tolerance_deg)
    b = tf[(tf["frequency_Hz"] >= band_Hz[0]) & (tf["frequency_Hz"] <= band_Hz[1])]
    if b.empty:
        return {"pass": False, "max_gain_error_pct": np.nan, "max_phase_error_deg": np.nan,
                "mean_gain": np.nan, "mean_phase_deg": np.nan}
    ge = float(np.max(np.abs(b["gain"] - 1)))
    pe = float(np.max(np.abs(b["phase_deg"])))
    return {"pass": bool(ge <= gain_tolerance and pe <= phase_tolerance_deg),
            "max_gain_error_pct": 100 * ge, "max_phase_error_deg": pe,
            "mean_gain": float(b["gain"].mean()), "mean_phase_deg": float(b["phase_deg"].mean())}


def day_summary(checks: pd.DataFrame, keys: tuple[str, ...] = ("day",)) -> pd.DataFrame:
    """Per day: a day passes only if every calibration run of that day passes.

    Parameters
    ----------
    checks : DataFrame
        One row per calibration run with the ``keys`` columns and ``pass``.
    keys : tuple of str
        Columns identifying a day (e.g. ``("campaign", "day")``).

    Returns
    -------
    DataFrame
        ``keys``, ``day_pass``, ``n_calibration_runs``.

    See Also
    --------
    check_calibration : each run's check.
    flag_failed_days : flags the runs of a failed day.

    Examples
    --------
    >>> checks = pd.DataFrame({"day": ["1989-05-03", "1989-05-03", "1989-05-04"], "pass": [True, False, True]})
    >>> day_summary(checks).to_dict("records")
    [{'day': '1989-05-03', 'day_pass': False, 'n_calibration_runs': 2}, {'day': '1989-05-04', 'day_pass': True, 'n_calibration_runs': 1}]
    """
    g = checks.groupby(list(keys), sort=True)["pass"]
    out = g.agg(day_pass="all", n_calibration_runs="size").reset_index()
    out["day_pass"] = out["day_pass"].astype(bool)
    return out


CALIBRATION_REASON = "calibration failed on {day}"


def flag_failed_days(results: pd.DataFrame, days: pd.DataFrame, result_keys: tuple[str, ...] = ("recorded_on",),
                     day_keys: tuple[str, ...] = ("day",)) -> pd.DataFrame:
    """Flag runs recorded on a day whose calibration check failed.

    Appends ``calibration failed on <day>`` to ``qc_reasons`` and recomputes
    ``qc_ok`` as "no reasons". Earlier calibration reasons are removed first,
    so the function is idempotent and a day that passes after a re-check is
    cleared.

    Parameters
    ----------
    results : DataFrame
        Analysed runs with ``qc_ok``, ``qc_reasons`` (``"; "``-separated) and ``result_keys``.
    days : DataFrame
        :func:`day_summary` output with ``day_keys`` and ``day_pass``.
    result_keys, day_keys : tuple of str
        Matching columns; the last one is the date printed in the reason.

    See Also
    --------
    day_summary : the days it reads.

    Examples
    --------
    >>> runs = pd.DataFrame({"recorded_on": ["1989-05-03", "1989-05-04"], "qc_ok": [True, True], "qc_reasons": ["", ""]})
    >>> days = pd.DataFrame({"day": ["1989-05-03", "1989-05-04"], "day_pass": [False, True]})
    >>> flag_failed_days(runs, days)[["qc_ok", "qc_reasons"]].to_dict("records")
    [{'qc_ok': False, 'qc_reasons': 'calibration failed on 1989-05-03'}, {'qc_ok': True, 'qc_reasons': ''}]
    """
    out = results.copy()
    if out.empty:
        return out
    if "qc_reasons" not in out:
        out["qc_reasons"] = ""
    failed = set()
    if not days.empty:
        bad = days.loc[~days["day_pass"].astype(bool), list(day_keys)]
        failed = {tuple(str(v) for v in r) for r in bad.itertuples(index=False)}
    keys = [tuple(str(v) for v in r) for r in out[list(result_keys)].itertuples(index=False)]
    reasons = []
    for key, text in zip(keys, out["qc_reasons"].fillna("").astype(str)):
        parts = [r for r in text.split("; ") if r and not r.startswith("calibration failed on ")]
        if key in failed:
            parts.append(CALIBRATION_REASON.format(day=key[-1]))
        reasons.append("; ".join(parts))
    out["qc_reasons"] = reasons
    out["qc_ok"] = [not r for r in reasons]
    return out


def correction_factor(tf: pd.DataFrame, frequency_Hz: float) -> complex:
    """The day's calibration transfer function at ``frequency_Hz`` (complex, derived/true).

    Correction of §3.6: divide a measured tyre force (or apparent mass, or
    ``K + jωC``) by this factor. Gain and phase are interpolated linearly.

    See Also
    --------
    corrected_stiffness_damping : K and C corrected by it.

    Examples
    --------
    >>> fs = 256.0; t = np.arange(0, 60, 1 / fs)
    >>> plate = np.random.default_rng(1).normal(size=t.size) * 1e3   # the force plate's force, N
    >>> tf = calibration_transfer_function(plate, 1.02 * plate, fs)   # the derived force reads 2 % high
    >>> z = correction_factor(tf, 4.0)
    >>> round(float(z.real), 4), bool(abs(z.imag) < 1e-9)
    (1.02, True)
    """
    frequency_Hz = positive("frequency_Hz", frequency_Hz)
    if tf.empty:
        raise ValueError("tf is empty: no calibration transfer function to correct by")
    g = float(np.interp(frequency_Hz, tf["frequency_Hz"], tf["gain"]))
    p = float(np.interp(frequency_Hz, tf["frequency_Hz"], tf["phase_deg"]))
    return g * np.exp(1j * np.radians(p))


def corrected_stiffness_damping(stiffness_N_per_m: float, damping_N_s_per_m: float, frequency_Hz: float,
                                tf: pd.DataFrame) -> tuple[float, float]:
    """K and C corrected by the day's calibration transfer function (§3.6 option).

    See Also
    --------
    correction_factor : the factor it divides by.

    Examples
    --------
    >>> fs = 256.0; t = np.arange(0, 60, 1 / fs)
    >>> plate = np.random.default_rng(1).normal(size=t.size) * 1e3   # the force plate's force, N
    >>> tf = calibration_transfer_function(plate, 1.02 * plate, fs)   # the derived force reads 2 % high
    >>> k, c = corrected_stiffness_damping(1.02 * 250e3, 1.02 * 2e3, 4.0, tf)
    >>> round(k), round(c)
    (250000, 2000)
    """
    w = 2 * np.pi * frequency_Hz
    z = (stiffness_N_per_m + 1j * w * damping_N_s_per_m) / correction_factor(tf, frequency_Hz)
    return float(z.real), float(z.imag / w)
