"""Uncertainty of a run's K and C (GUM), thesis §3.2.9 and §3.6.

A run's stiffness and damping come from the complex dynamic stiffness
``Z = K + jωC = N / D``: ``N`` the demodulated, Hann-weighted tyre force and
``D`` the demodulated ``a/ω²``
(:func:`tyrelab.measurement.apparent_mass.apparent_mass_demodulation`, which
also keeps ``D`` and the residual probes). Two kinds of contribution
(docs/uncertainty.md):

Type A, the run's own data
    The force the fitted tyre does not explain (noise, ground and wheel
    inputs, hum, ...) adds ``Σ w r e^{-jφ} / D`` to Z. Its size is the
    residual's spectral density at the excitation frequency, measured by the
    same demodulation at 16 nearby frequencies (:func:`residual_uncertainty`).

Type B, the instrument (thesis §3.2.9 "1 ± 3 % and 0 ± 1°", §3.2.8 ``f_t = M_a a − Σ beams``)
    ``Z_true = Z · g_a / G`` with ``G`` the force path's transfer function
    (derived / true tyre force, what the daily force-plate check measures) and
    ``g_a`` the accelerometers' sensitivity error. A relative gain error ``δ``
    moves K and C by ``δK = K δ``, ``δC = C δ``; a phase error ``δφ`` (rad)
    rotates Z: ``δK = ωC δφ``, ``δC = −K δφ/ω``; an axle-mass error ``δM``
    adds ``δM a`` to the derived force: ``δK = ω² δM``, ``δC = 0``.
    :func:`limits_budget` is the budget of a day without a force-plate check
    (the §3.2.9 limits as rectangular distributions); :func:`day_budget` the
    budget from a day's measured calibration transfer function.

The combined standard uncertainty is the root sum of squares (the inputs are
independent), the coverage factor the Student t quantile for the effective
degrees of freedom (Welch–Satterthwaite, type B terms with infinite degrees
of freedom), the interval ``[K − k u, K + k u]``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy import stats

from .calibration import CHECK_BAND_HZ, GAIN_TOLERANCE, PHASE_TOLERANCE_DEG

__all__ = [
    "ACCEL_GAIN_U", "AXLE_MASS_U_FRACTION", "BEAM_GAIN_U", "HANN_BIN_CORRELATION", "UNCERTAINTY_COLUMNS", "GAIN_LIMIT", "PHASE_LIMIT_DEG", "LEVEL",
    "InstrumentBudget", "RunUncertainty", "residual_uncertainty", "limits_budget", "day_budget", "combine",
    "coverage_factor", "instrument_terms", "run_uncertainty",
]

#: Uncertainty columns of ``results`` (:meth:`RunUncertainty.columns`) and their source, ``uncertainty_source``.
UNCERTAINTY_COLUMNS = (
    "stiffness_u_N_per_m", "damping_u_N_s_per_m", "stiffness_u_stat_N_per_m", "damping_u_stat_N_s_per_m",
    "uncertainty_dof_stat", "uncertainty_dof", "coverage_factor", "stiffness_ci95_low_N_per_m",
    "stiffness_ci95_high_N_per_m", "damping_ci95_low_N_s_per_m", "damping_ci95_high_N_s_per_m",
)
#: Confidence level of the intervals.
LEVEL = 0.95
#: §3.2.9: the derived tyre force must match the force plate to 1 ± 3 % in gain (``GAIN_LIMIT``),
#: 0 ± 1° in phase (``PHASE_LIMIT_DEG``) over 2-6 Hz (``CHECK_BAND_Hz``): the daily check's limits,
#: whose one home is :mod:`tyrelab.measurement.calibration` (these are its values under the names
#: this module has always exported).
GAIN_LIMIT = GAIN_TOLERANCE
PHASE_LIMIT_DEG = PHASE_TOLERANCE_DEG
CHECK_BAND_Hz = CHECK_BAND_HZ
#: Standard uncertainty of each accelerometer's sensitivity after the §3.2.9 "2 g" inversion check
#: (documented choice: 0.2 %; the thesis states no figure). The two ends are averaged: 0.2 %/√2.
ACCEL_GAIN_U = 0.002 / math.sqrt(2)
#: Standard uncertainty of each load-beam amplifier's gain after the §3.2.9 "precision dummy
#: transducer" check (documented choice: 0.2 %). The four beams share the load about equally, so
#: their sum has 0.2 %/2.
BEAM_GAIN_U = 0.002 / 2
#: Correlation of the phase errors of neighbouring bins (lag 1, lag 2) of the check's Welch H1 estimate. A Hann
#: window mixes each DFT bin with its neighbours by −1/4, 1/2, −1/4, so the complex noise of neighbouring bins
#: correlates by −2/3 and of bins two apart by 1/6; a cross-spectrum (product of two such) by their squares.
HANN_BIN_CORRELATION = ((2 / 3) ** 2, (1 / 6) ** 2)
#: Standard uncertainty of the axle mass M_a as a fraction of it (documented choice: 0.5 %, ±3 kg of
#: the "typically about 600 kg" of §3.2.8). Used only without a force-plate check: the check measures
#: the derived force, ``M_a a`` included, so a passing check bounds the axle-mass error.
AXLE_MASS_U_FRACTION = 0.005


@dataclass(frozen=True)
class InstrumentBudget:
    """Type B standard uncertainties of the instrument for one run (or one day).

    Attributes
    ----------
    force_gain : float
        Relative standard uncertainty of the whole force path's gain |G| (used
        without a force-plate check: the §3.2.9 limit).
    phase_rad : float
        Standard uncertainty of the force path's phase, rad.
    accel_gain, beam_gain : float
        Relative standard uncertainties of the mean acceleration's and of the
        summed load beams' sensitivity. In ``f_t = M_a a − Σ beams`` they move
        ``Z = K + jωC`` by ``(M_a ω² − Z)(δa − δb)``: the subtraction of two
        similar quantities (§3.2.9) makes them count by ``|M_a ω² − K|``.
    axle_mass_kg : float
        Standard uncertainty of M_a, kg (0 when a force-plate check covers it).
    source : str
        Where the figures come from (``§3.2.9 limits`` or ``calibration <day>``).
    """

    force_gain: float
    phase_rad: float
    accel_gain: float = 0.0
    beam_gain: float = 0.0
    axle_mass_kg: float = 0.0
    source: str = ""


def limits_budget(axle_mass_kg: float = 600.0) -> InstrumentBudget:
    """Budget of a run without a force-plate check on its day: the §3.2.9 limits.

    The check's acceptance limits ±3 % and ±1° read as rectangular
    distributions (GUM 4.3.7: half-width/√3), plus the axle mass
    (:data:`AXLE_MASS_U_FRACTION`). The channel gains are inside the ±3 %.

    See Also
    --------
    day_budget : the budget of a day whose check passed.
    instrument_terms : K's and C's terms from a budget.

    Examples
    --------
    >>> b = limits_budget(600.0)
    >>> round(b.force_gain, 4), round(math.degrees(b.phase_rad), 3), round(b.axle_mass_kg, 1)
    (0.0173, 0.577, 3.0)
    """
    if not np.isfinite(axle_mass_kg) or axle_mass_kg <= 0:
        raise ValueError(f"axle_mass_kg must be positive, got {axle_mass_kg!r}")
    return InstrumentBudget(GAIN_LIMIT / math.sqrt(3), math.radians(PHASE_LIMIT_DEG) / math.sqrt(3),
                            0.0, 0.0, AXLE_MASS_U_FRACTION * axle_mass_kg, "§3.2.9 limits")


def _band_correlation(n: int) -> np.ndarray:
    """Correlation matrix of the check's per-bin phase errors (:data:`HANN_BIN_CORRELATION`)."""
    lag = np.abs(np.subtract.outer(np.arange(n), np.arange(n)))
    corr = np.zeros((n, n))
    corr[lag == 0] = 1.0
    for m, rho in enumerate(HANN_BIN_CORRELATION, start=1):
        corr[lag == m] = rho
    return corr


def day_budget(tf: pd.DataFrame, frequency_Hz: float, n_averages: float, corrected: bool = False,
               source: str = "calibration") -> InstrumentBudget:
    """Budget of a run on a day whose force-plate check passed (§3.2.9, §3.6).

    Parameters
    ----------
    tf : DataFrame
        ``frequency_Hz``, ``gain``, ``phase_deg``, ``coherence`` of the day's
        check (:func:`tyrelab.measurement.calibration.calibration_transfer_function`),
        optionally ``inertial_ratio_re``, ``inertial_ratio_im`` (``R = M_a a / f_t``).
    frequency_Hz : float
        The run's measured excitation frequency, Hz.
    n_averages : float
        Number of Welch segments the transfer function averaged.
    corrected : bool
        Whether the run's K, C were divided by the transfer function (§3.6
        option). If not, and the day's phase at ``frequency_Hz`` is resolved
        (below), it is an uncorrected systematic error of the force path and
        enters as an uncertainty of its own size (root sum of squares, GUM F.2.4.5).

    Returns
    -------
    InstrumentBudget
        Phase: a straight line through the day's phase over the 2–6 Hz check
        band (the force path's phase is smooth in frequency: amplifier
        filters), generalised least squares with each bin's H1 random error
        ``√(1−γ²)/(|γ|√(2 n_d))`` rad (Bendat & Piersol) and the correlation of
        neighbouring Hann-windowed bins (:data:`HANN_BIN_CORRELATION`); the
        line's standard error ``σ`` at ``frequency_Hz`` and, uncorrected and
        resolved, its value ``φ̂`` there. Resolved means ``|φ̂| > 2 √(σ² + u_g²)``:
        besides its random error, the check's phase carries the accelerometer
        and load-beam gain mismatch, ``(δa − δb) Im R`` with ``u_g =
        √(u_a² + u_b²) |Im R|`` (``R`` from ``tf``; 0 without it), which the
        budget already holds as the channel-gain terms. A phase the check
        does not resolve beyond those two is no evidence of a force-path
        phase error, and counting it would count the gains (or the noise)
        twice. Gains: the channel sensitivities :data:`ACCEL_GAIN_U`,
        :data:`BEAM_GAIN_U` (a passing check keeps their combination within
        3 %; it cannot tell the accelerometers, which also divide the force,
        from the beams). No axle-mass term (the check bounds it).

    See Also
    --------
    limits_budget : the budget of a day without a check.
    tyrelab.measurement.calibration.calibration_transfer_function : the check it reads.

    Examples
    --------
    A check whose phase is within its noise leaves the line's standard error
    (0.079°); a resolved 0.5° enters with its size:

    >>> f = np.arange(2.0, 6.01, 0.25)
    >>> tf = pd.DataFrame({"frequency_Hz": f, "gain": 1.0, "phase_deg": 0.001 * np.cos(f), "coherence": 0.999})
    >>> round(math.degrees(day_budget(tf, 4.0, 29).phase_rad), 3)
    0.079
    >>> round(math.degrees(day_budget(tf.assign(phase_deg=0.5), 4.0, 29).phase_rad), 3)
    0.506
    """
    if tf is None or len(tf) == 0:
        raise ValueError("tf must hold the day's transfer function")
    if not np.isfinite(frequency_Hz):
        raise ValueError(f"frequency_Hz must be finite, got {frequency_Hz!r}")
    if n_averages < 1:
        raise ValueError(f"n_averages must be at least 1, got {n_averages!r}")
    f = tf["frequency_Hz"].to_numpy(float)
    band = (f >= CHECK_BAND_Hz[0]) & (f <= CHECK_BAND_Hz[1])
    if band.sum() < 3:
        band = np.ones_like(f, dtype=bool)
    fb = f[band]
    phase = np.radians(tf["phase_deg"].to_numpy(float)[band])
    coh = np.clip(tf["coherence"].to_numpy(float)[band], 1e-6, 1.0)
    sd = np.sqrt(1.0 - coh) / (np.sqrt(coh) * math.sqrt(2.0 * n_averages))  # rad, per bin
    sd = np.maximum(sd, 1e-9)
    # straight line through the band by generalised least squares; its value and standard error at the run's frequency
    design = np.column_stack([np.ones_like(fb), fb - frequency_Hz])
    v_inv = np.linalg.inv(_band_correlation(fb.size) * np.outer(sd, sd))
    cov = np.linalg.inv(design.T @ v_inv @ design)
    coef = cov @ (design.T @ v_inv @ phase)
    random = math.sqrt(cov[0, 0])
    u_gain_phase = 0.0
    if {"inertial_ratio_re", "inertial_ratio_im"} <= set(tf.columns):
        im_r = tf["inertial_ratio_im"].to_numpy(float)[band]
        u_gain_phase = math.hypot(ACCEL_GAIN_U, BEAM_GAIN_U) * abs(float(np.interp(frequency_Hz, fb, im_r)))
    resolved = abs(coef[0]) > 2 * math.hypot(random, u_gain_phase)
    bias_p = float(coef[0]) if resolved and not corrected else 0.0
    return InstrumentBudget(0.0, math.sqrt(random**2 + bias_p**2), ACCEL_GAIN_U, BEAM_GAIN_U, 0.0, source)


def residual_uncertainty(residual_probes_N: np.ndarray, denominator_m: np.ndarray,
                         frequency_Hz) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Type A standard uncertainties of K and C from the force the fitted tyre leaves over.

    The estimate is ``Z = N / D`` with ``N = Σ w f e^{-jφ}``; what in ``f``
    is not the fitted tyre, the residual ``r = f − Re((K̂ + jω(t)Ĉ) ξ)``,
    adds ``δZ = Σ w r e^{-jφ} / D``. Its variance is the residual's spectral
    density at the excitation, which the probes measure: the same demodulation
    of ``r`` shifted by ``Δ_m`` (:data:`~tyrelab.measurement.apparent_mass.PROBE_OFFSETS`,
    4/T to 18/T either side, outside the Hann main lobe of the estimate).
    ``S_m`` are circular, so

        u²(K) = u²(ωC) = mean_m |S_m|² / (2 |D|²)

    Parameters
    ----------
    residual_probes_N : ndarray of complex, shape (..., n_probes)
        ``DemodulationResult.residual_probes_N``.
    denominator_m : ndarray of complex, shape (...)
        ``DemodulationResult.denominator_m``.
    frequency_Hz : float or ndarray, shape (...)
        The run's excitation frequency, Hz.

    Returns
    -------
    u_stiffness_N_per_m, u_damping_N_s_per_m, dof : ndarray, shape (...)
        Standard uncertainties and their degrees of freedom (two per probe,
        less the overlap of neighbouring Hann-weighted probes, correlation 1/6).

    See Also
    --------
    run_uncertainty : with the type B terms.
    tyrelab.measurement.apparent_mass.apparent_mass_demodulation : the probes and denominator it takes.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> s = 50.0 * (rng.standard_normal(16) + 1j * rng.standard_normal(16))
    >>> uk, uc, dof = residual_uncertainty(s, 0.5 + 0.1j, 4.0)
    >>> round(float(uk)), round(float(dof), 1)
    (80, 30.3)
    """
    s = np.asarray(residual_probes_N, dtype=complex)
    d = np.asarray(denominator_m, dtype=complex)
    if s.shape[-1] < 2:
        raise ValueError("residual_probes_N needs at least 2 probes")
    omega = 2 * np.pi * np.asarray(frequency_Hz, dtype=float)
    u = np.sqrt(np.mean(np.abs(s) ** 2, axis=-1) / 2) / np.abs(d)
    dof = 2 * s.shape[-1] / (1 + 2 * (1 / 6) ** 2)
    return u, u / omega, np.broadcast_to(dof, u.shape).astype(float)


def coverage_factor(dof, level: float = LEVEL):
    """Student t coverage factor for ``dof`` effective degrees of freedom (normal for infinite).

    See Also
    --------
    combine : the effective degrees of freedom it takes.

    Examples
    --------
    >>> round(float(coverage_factor(np.inf)), 3), round(float(coverage_factor(10)), 3)
    (1.96, 2.228)
    """
    if not 0 < level < 1:
        raise ValueError(f"level must be in (0, 1), got {level!r}")
    d = np.asarray(dof, dtype=float)
    return np.where(np.isfinite(d), stats.t.ppf(0.5 + level / 2, np.maximum(d, 1.0)), stats.norm.ppf(0.5 + level / 2))


@dataclass(frozen=True)
class RunUncertainty:
    """Combined uncertainty of runs' K and C (arrays of shape (...), SI units)."""

    stiffness_u_N_per_m: np.ndarray  #: combined standard uncertainty of K
    damping_u_N_s_per_m: np.ndarray  #: combined standard uncertainty of C
    stiffness_u_stat_N_per_m: np.ndarray  #: type A part of it (the run's own data)
    damping_u_stat_N_s_per_m: np.ndarray
    dof: np.ndarray  #: effective degrees of freedom (Welch–Satterthwaite; of K)
    coverage_factor: np.ndarray  #: k of the 95 % intervals (of K)
    stiffness_ci95_N_per_m: np.ndarray  #: (..., 2) [low, high]
    damping_ci95_N_s_per_m: np.ndarray  #: (..., 2) [low, high]

    dof_stat: np.ndarray | None = None  #: degrees of freedom of the type A part

    def columns(self) -> dict[str, np.ndarray]:
        """The ``results`` columns: standard uncertainties, type A parts, dof, k, interval bounds."""
        return {
            "stiffness_u_N_per_m": self.stiffness_u_N_per_m, "damping_u_N_s_per_m": self.damping_u_N_s_per_m,
            "stiffness_u_stat_N_per_m": self.stiffness_u_stat_N_per_m,
            "damping_u_stat_N_s_per_m": self.damping_u_stat_N_s_per_m,
            "uncertainty_dof_stat": self.dof_stat, "uncertainty_dof": self.dof, "coverage_factor": self.coverage_factor,
            "stiffness_ci95_low_N_per_m": self.stiffness_ci95_N_per_m[..., 0],
            "stiffness_ci95_high_N_per_m": self.stiffness_ci95_N_per_m[..., 1],
            "damping_ci95_low_N_s_per_m": self.damping_ci95_N_s_per_m[..., 0],
            "damping_ci95_high_N_s_per_m": self.damping_ci95_N_s_per_m[..., 1],
        }


def instrument_terms(stiffness_N_per_m, damping_N_s_per_m, frequency_Hz, budget: InstrumentBudget,
                     axle_mass_kg=600.0):
    """Type B standard uncertainties of K and C (N/m, N s/m) from an :class:`InstrumentBudget`.

    Sensitivities (module docstring): force-path gain ``K``, ``C``; phase
    ``ωC``, ``K/ω``; channel gains ``|M_a ω² − K|``, ``C``; axle mass ``ω²``, 0.

    See Also
    --------
    InstrumentBudget : the budget's terms.
    combine : adds the type A terms.

    Examples
    --------
    >>> uk, uc = instrument_terms(250e3, 2e3, 4.0, InstrumentBudget(force_gain=0.01, phase_rad=0.0))
    >>> round(float(uk), 6), round(float(uc), 6)        # 1 % of K and of C
    (2500.0, 20.0)
    >>> uk, uc = instrument_terms(250e3, 2e3, 4.0, InstrumentBudget(force_gain=0.0, phase_rad=1e-3))
    >>> round(float(uk), 2), round(float(uc), 2)        # ωC φ and K φ / ω
    (50.27, 9.95)
    """
    k = np.asarray(stiffness_N_per_m, dtype=float)
    c = np.asarray(damping_N_s_per_m, dtype=float)
    w = 2 * np.pi * np.asarray(frequency_Hz, dtype=float)
    m = np.asarray(axle_mass_kg, dtype=float)
    channels2 = budget.accel_gain**2 + budget.beam_gain**2
    u_k2 = ((budget.force_gain * k) ** 2 + (w * c * budget.phase_rad) ** 2 + (w**2 * budget.axle_mass_kg) ** 2
            + channels2 * (m * w**2 - k) ** 2)
    u_c2 = (budget.force_gain * c) ** 2 + (k * budget.phase_rad / w) ** 2 + channels2 * c**2
    return np.sqrt(u_k2), np.sqrt(u_c2)


def combine(stiffness_N_per_m, damping_N_s_per_m, frequency_Hz, u_stat_k, u_stat_c, dof_stat,
            budget: InstrumentBudget | list[InstrumentBudget], axle_mass_kg=600.0,
            level: float = LEVEL) -> RunUncertainty:
    """Combine the type A and type B terms (GUM): root sum of squares, Welch–Satterthwaite, t factor.

    ``budget`` is one :class:`InstrumentBudget` for all runs or one per run;
    ``axle_mass_kg`` (M_a, kg, scalar or per run) sets the channel gains' sensitivity.

    See Also
    --------
    instrument_terms : the type B terms.
    residual_uncertainty : the type A terms of a run.
    run_uncertainty : both for a demodulated run.

    Examples
    --------
    Type A alone (an empty budget): the interval is the t factor of its 20 degrees of freedom.

    >>> u = combine(250e3, 2e3, 4.0, 1000.0, 10.0, 20, InstrumentBudget(0.0, 0.0))
    >>> float(u.stiffness_u_N_per_m), float(u.dof), round(float(u.coverage_factor), 3), np.round(u.stiffness_ci95_N_per_m).tolist()
    (1000.0, 20.0, 2.086, [247914.0, 252086.0])
    """
    k = np.asarray(stiffness_N_per_m, dtype=float)
    c = np.asarray(damping_N_s_per_m, dtype=float)
    f = np.broadcast_to(np.asarray(frequency_Hz, dtype=float), k.shape)
    m = np.broadcast_to(np.asarray(axle_mass_kg, dtype=float), k.shape)
    if isinstance(budget, InstrumentBudget):
        bk, bc = instrument_terms(k, c, f, budget, m)
    else:
        if len(budget) != k.size:
            raise ValueError(f"budget must hold one InstrumentBudget per run ({k.size}), got {len(budget)}")
        pairs = [instrument_terms(ki, ci, fi, b, mi)
                 for ki, ci, fi, b, mi in zip(k.ravel(), c.ravel(), f.ravel(), budget, m.ravel())]
        bk = np.array([p[0] for p in pairs], dtype=float).reshape(k.shape)
        bc = np.array([p[1] for p in pairs], dtype=float).reshape(k.shape)
    ak, ac = np.asarray(u_stat_k, dtype=float), np.asarray(u_stat_c, dtype=float)
    uk, uc = np.sqrt(ak**2 + bk**2), np.sqrt(ac**2 + bc**2)
    dof_a = np.asarray(dof_stat, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        nu_k = np.where(ak > 0, uk**4 / (ak**4 / dof_a), np.inf)
        nu_c = np.where(ac > 0, uc**4 / (ac**4 / dof_a), np.inf)
    tk, tc = coverage_factor(nu_k, level), coverage_factor(nu_c, level)
    return RunUncertainty(uk, uc, ak, ac, nu_k, tk,
                          np.stack([k - tk * uk, k + tk * uk], axis=-1), np.stack([c - tc * uc, c + tc * uc], axis=-1),
                          np.broadcast_to(dof_a, k.shape).astype(float))


def run_uncertainty(demodulation, budget: InstrumentBudget | list[InstrumentBudget],
                    axle_mass_kg=600.0, level: float = LEVEL) -> RunUncertainty:
    """Combined uncertainty of the K, C of a :class:`~tyrelab.measurement.apparent_mass.DemodulationResult`.

    Type A from its residual probes (:func:`residual_uncertainty`), type B from ``budget``.

    See Also
    --------
    residual_uncertainty : its type A part.
    combine : how the parts combine.

    Examples
    --------
    >>> from tyrelab.measurement.apparent_mass import apparent_mass_demodulation
    >>> fs = 256.0; t = np.arange(0, 30, 1 / fs); w = 2 * np.pi * 3.8
    >>> x = 0.005 * np.sin(w * t); a = -w**2 * x
    >>> f = -(228e3 * x + 2.4e3 * 0.005 * w * np.cos(w * t)) + np.random.default_rng(1).normal(0, 50.0, t.size)
    >>> u = run_uncertainty(apparent_mass_demodulation(f, a, fs), limits_budget())
    >>> lo, hi = u.stiffness_ci95_N_per_m
    >>> bool(lo < 228e3 < hi), bool(u.stiffness_u_N_per_m > u.stiffness_u_stat_N_per_m > 0)
    (True, True)
    """
    uk, uc, dof = residual_uncertainty(demodulation.residual_probes_N, demodulation.denominator_m,
                                       demodulation.frequency_Hz)
    return combine(demodulation.stiffness_N_per_m, demodulation.damping_N_s_per_m, demodulation.frequency_Hz,
                   uk, uc, dof, budget, axle_mass_kg, level)
