"""K, C and QC of recordings in raw format v1, without the stage machinery.

The library face of the analyse stage, pure (no file I/O): :func:`analyse_frame`
takes one recording as a DataFrame with the raw-format-v1 channels and the
axle mass and returns a :class:`RecordingResult`; :func:`analyse_batch` does
the same work on a batch of equal-length runs in one vectorised call (the
analyse stage and ``tyrelab analyze-run`` both call it).
:func:`tyrelab.analyze_recording` (:mod:`tyrelab.api`) reads a run file first.

Both estimators are computed: the phase-locked synchronous demodulation
(K and C used downstream) and the thesis' Welch H1 read at the excitation bin
(:mod:`tyrelab.measurement.apparent_mass`); QC follows thesis §3.5
(:mod:`tyrelab.measurement.qc`).

Examples
--------
A spring-damper tyre of 250 kN/m and 2 kN s/m under a 600 kg axle, excited
at 4 Hz, 14 mm peak to peak, sampled at 256 Hz for 30 s:

>>> import numpy as np, pandas as pd
>>> fs, f0, K, C, M = 256.0, 4.0, 250e3, 2e3, 600.0
>>> t = np.arange(int(30 * fs)) / fs
>>> w = 2 * np.pi * f0
>>> x = 7e-3 * np.sin(w * t)                    # axle displacement, m, upward
>>> a = -w**2 * x                               # axle acceleration, m/s²
>>> f_t = -(K * x + C * w * 7e-3 * np.cos(w * t))  # tyre force on the axle, N
>>> beams = (M * a - f_t) / 4                   # each load beam carries a quarter
>>> rec = pd.DataFrame({"time_s": t, "accel_left_m_s2": a, "accel_right_m_s2": a,
...                     **{f"load_beam_{i}_N": beams for i in range(1, 5)}})
>>> r = analyse_frame(rec, axle_mass_kg=M)
>>> round(r.stiffness_kN_per_m), round(r.damping_kN_s_per_m, 2), round(r.excitation_frequency_Hz, 2)
(250, 2.0, 4.0)
>>> r.qc_ok, r.qc_reasons
(True, ())
>>> sorted(r.to_dict())[:3]
['amplitude_mm_pp', 'amplitude_rms_mm', 'apparent_mass_imag_kg']
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .._validate import band, positive, positive_array
from ..rawformat import ACCEL_CHANNELS, BEAM_CHANNELS, CHANNELS, TIME, check_run
from . import apparent_mass as am
from . import qc
from . import uncertainty as unc

__all__ = ["WelchEstimate", "RecordingResult", "analyse_frame", "analyse_batch", "recording_arrays",
           "frame_tyre_force", "dominant_frequency_Hz"]

#: How :class:`RecordingResult` names the estimator of K and C.
ESTIMATOR = "phase-locked synchronous demodulation"


@dataclass(frozen=True)
class WelchEstimate:
    """K and C the thesis' way (Welch H1 at the excitation bin, §3.3.1)."""

    frequency_Hz: float  #: frequency of the bin read, Hz
    stiffness_N_per_m: float  #: K, N/m
    damping_N_s_per_m: float  #: C, N s/m


@dataclass(frozen=True)
class RecordingResult:
    """Stiffness, damping and QC of one recording (thesis ch. 3).

    Values are NaN where the excitation was not found. ``apparent_mass_kg``
    is H in the thesis convention (deflection-positive, §3.5).
    """

    sample_rate_Hz: float  #: sampling rate, Hz
    duration_s: float  #: length of the recording, s
    axle_mass_kg: float  #: M_a used for the tyre force, kg
    excitation_frequency_Hz: float  #: measured excitation frequency, Hz
    stiffness_N_per_m: float  #: K, N/m (synchronous demodulation)
    damping_N_s_per_m: float  #: C, N s/m (synchronous demodulation)
    apparent_mass_kg: complex  #: H at the excitation frequency, kg
    amplitude_mm_pp: float  #: measured axle displacement amplitude, mm peak to peak
    acceleration_amplitude_m_s2: float  #: axle acceleration amplitude (peak), m/s²
    coherence: float  #: magnitude-squared coherence of force and acceleration at the excitation
    welch: WelchEstimate  #: the thesis-method estimate, for comparison
    qc_reasons: tuple[str, ...] = ()  #: why the run should not be used (empty: QC passed)
    file: str | None = None  #: the run file, when read from one
    estimator: str = field(default=ESTIMATOR)
    #: standard uncertainties of K (N/m) and C (N s/m) and their 95 % intervals [low, high]
    #: (issue 14; one recording has no day check: the §3.2.9 limits, docs/uncertainty.md)
    stiffness_u_N_per_m: float = math.nan
    damping_u_N_s_per_m: float = math.nan
    stiffness_ci95_N_per_m: tuple[float, float] = (math.nan, math.nan)
    damping_ci95_N_s_per_m: tuple[float, float] = (math.nan, math.nan)
    #: the budget: type A parts, degrees of freedom, coverage factor, level, instrument source
    uncertainty: dict = field(default_factory=dict)

    @property
    def qc_ok(self) -> bool:
        """True when QC found nothing wrong."""
        return not self.qc_reasons

    @property
    def stiffness_kN_per_m(self) -> float:
        """K, kN/m."""
        return self.stiffness_N_per_m / 1e3

    @property
    def damping_kN_s_per_m(self) -> float:
        """C, kN s/m."""
        return self.damping_N_s_per_m / 1e3

    @property
    def amplitude_rms_mm(self) -> float:
        """Axle displacement amplitude, mm rms (the thesis' rms meter, §3.2.8)."""
        return self.amplitude_mm_pp / 2 / math.sqrt(2)

    def to_dict(self) -> dict:
        """JSON-ready dict (NaN as ``None``) with the keys of ``tyrelab analyze-run`` (a contract)."""
        num = lambda v: float(v) if math.isfinite(v) else None  # noqa: E731
        return {
            "file": self.file,
            "sample_rate_Hz": self.sample_rate_Hz,
            "duration_s": self.duration_s,
            "axle_mass_kg": self.axle_mass_kg,
            "excitation_frequency_Hz": num(self.excitation_frequency_Hz),
            "stiffness_N_per_m": num(self.stiffness_N_per_m),
            "damping_N_s_per_m": num(self.damping_N_s_per_m),
            "stiffness_kN_per_m": num(self.stiffness_kN_per_m),
            "damping_kN_s_per_m": num(self.damping_kN_s_per_m),
            "apparent_mass_real_kg": num(self.apparent_mass_kg.real),
            "apparent_mass_imag_kg": num(self.apparent_mass_kg.imag),
            "amplitude_mm_pp": num(self.amplitude_mm_pp),
            "amplitude_rms_mm": num(self.amplitude_rms_mm),
            "coherence": num(self.coherence),
            "estimator": self.estimator,
            "welch": {
                "frequency_Hz": num(self.welch.frequency_Hz),
                "stiffness_N_per_m": num(self.welch.stiffness_N_per_m),
                "damping_N_s_per_m": num(self.welch.damping_N_s_per_m),
            },
            "stiffness_u_N_per_m": num(self.stiffness_u_N_per_m),
            "damping_u_N_s_per_m": num(self.damping_u_N_s_per_m),
            "stiffness_ci95_N_per_m": [num(v) for v in self.stiffness_ci95_N_per_m],
            "damping_ci95_N_s_per_m": [num(v) for v in self.damping_ci95_N_s_per_m],
            "uncertainty": {k: (num(v) if isinstance(v, float) else v) for k, v in self.uncertainty.items()},
            "qc_ok": self.qc_ok,
            "qc_reasons": list(self.qc_reasons),
        }


def recording_arrays(frame: pd.DataFrame) -> tuple[np.ndarray, np.ndarray]:
    """Accelerations ``(2, n)`` (m/s²) and load beams ``(4, n)`` (N) of a raw-format-v1 frame.

    See Also
    --------
    frame_tyre_force : the tyre force of a frame.

    Examples
    --------
    >>> frame = pd.DataFrame({"time_s": [0.0, 0.01], "accel_left_m_s2": [1.0, 2.0], "accel_right_m_s2": [3.0, 4.0],
    ...                       **{f"load_beam_{i}_N": [10.0 * i, 0.0] for i in range(1, 5)}})
    >>> accel, beams = recording_arrays(frame)
    >>> accel.tolist(), beams[:, 0].tolist()
    ([[1.0, 2.0], [3.0, 4.0]], [10.0, 20.0, 30.0, 40.0])
    """
    missing = [c for c in CHANNELS if c not in frame.columns]
    if missing:
        raise ValueError(f"frame lacks channel(s) {', '.join(missing)}")
    accel = np.stack([pd.to_numeric(frame[c]).to_numpy(float) for c in ACCEL_CHANNELS])
    beams = np.stack([pd.to_numeric(frame[c]).to_numpy(float) for c in BEAM_CHANNELS])
    return accel, beams


def frame_tyre_force(frame: pd.DataFrame, axle_mass_kg: float) -> np.ndarray:
    """Tyre force (N, upward positive) of a raw-format-v1 frame: :func:`~tyrelab.measurement.apparent_mass.tyre_force`.

    See Also
    --------
    recording_arrays : the frame's arrays.
    tyrelab.measurement.apparent_mass.tyre_force : the force from arrays.

    Examples
    --------
    >>> import pandas as pd
    >>> frame = pd.DataFrame({"accel_left_m_s2": [1.0], "accel_right_m_s2": [1.0],
    ...                       **{f"load_beam_{i}_N": [25.0] for i in range(1, 5)}})
    >>> frame_tyre_force(frame, 600.0)
    array([500.])
    """
    accel, beams = recording_arrays(frame)
    return am.tyre_force(accel[0], accel[1], beams, axle_mass_kg)


def analyse_batch(
    accel: np.ndarray,
    beams: np.ndarray,
    axle_mass_kg: np.ndarray,
    sample_rate_Hz: float,
    interference_Hz: list[list[float]] | None = None,
) -> pd.DataFrame:
    """Analyse equal-length runs sampled at one rate.

    Parameters
    ----------
    accel : ndarray, shape (runs, 2, n)
        Left and right axle accelerations, m/s², upward positive.
    beams : ndarray, shape (runs, 4, n)
        Load-beam forces on the axle, N, upward positive.
    axle_mass_kg : ndarray, shape (runs,)
        Axle mass M_a, kg.
    sample_rate_Hz : float
        Sampling rate, Hz.
    interference_Hz : list of list of float, optional
        Per run, frequencies of the wheel's own excitation (rotation, lug
        passing) that would bias K and C if they met the excitation
        (:func:`tyrelab.measurement.qc.interference_frequencies_Hz`).

    Returns
    -------
    DataFrame
        One row per run: measured frequency, H, K, C (both estimators),
        measured amplitude, coherence and QC (``qc_ok``, ``qc_reasons``), in
        thesis units.

    Raises
    ------
    ValueError
        Naming the argument whose shape or value is wrong.

    See Also
    --------
    analyse_frame : one recording given as a DataFrame.
    recording_arrays : the arrays of a frame.

    Examples
    --------
    >>> fs = 256.0; t = np.arange(0, 30, 1 / fs); w = 2 * np.pi * 3.8
    >>> x = 0.005 * np.sin(w * t); a = -w**2 * x               # 10 mm p-p at 3.8 Hz
    >>> f = -(228e3 * x + 2.4e3 * 0.005 * w * np.cos(w * t))  # a Kelvin-Voigt tyre's force, N
    >>> beams = np.stack([(600.0 * a - f) / 4] * 4)            # what the load beams carry of it, M_a = 600 kg
    >>> r = analyse_batch(np.stack([a, a])[None], beams[None], np.array([600.0]), fs)
    >>> r[["stiffness_kN_per_m", "damping_kN_s_per_m", "qc_ok"]].round(3).to_dict("records")
    [{'stiffness_kN_per_m': 228.0, 'damping_kN_s_per_m': 2.4, 'qc_ok': True}]
    """
    sample_rate_Hz = positive("sample_rate_Hz", sample_rate_Hz)
    accel, beams = np.asarray(accel), np.asarray(beams)
    if accel.ndim != 3 or accel.shape[1] != 2:
        raise ValueError(f"accel must have shape (runs, 2, n), got {accel.shape}")
    if beams.shape != (accel.shape[0], 4, accel.shape[2]):
        raise ValueError(f"beams must have shape {(accel.shape[0], 4, accel.shape[2])}, got {beams.shape}")
    mass = positive_array("axle_mass_kg", axle_mass_kg)
    if mass.shape != (accel.shape[0],):
        raise ValueError(f"axle_mass_kg must have shape ({accel.shape[0]},), got {mass.shape}")
    if interference_Hz is not None and len(interference_Hz) != accel.shape[0]:
        raise ValueError(f"interference_Hz must have one list per run ({accel.shape[0]}), got {len(interference_Hz)}")
    if accel.shape[0] == 1:
        # One run is analysed as two copies of itself: numpy's reductions over a (1, n) batch take
        # another summation path than over (runs >= 2, n), which moved the last bit of the type A
        # uncertainty, so a run analysed alone (an added run, analyze-run) must give the numbers
        # it gives in any batch.
        twice = analyse_batch(np.repeat(accel, 2, axis=0), np.repeat(beams, 2, axis=0), np.repeat(mass, 2),
                              sample_rate_Hz, None if interference_Hz is None else list(interference_Hz) * 2)
        return twice.iloc[:1].reset_index(drop=True)
    force = am.tyre_force(accel[:, 0], accel[:, 1], beams, mass)
    a = accel.mean(axis=1, dtype=float)
    fe = am.excitation_frequency(a, sample_rate_Hz)
    found = np.isfinite(fe)
    cols = {k: np.full(len(fe), np.nan) for k in (
        "excitation_frequency_measured_Hz",
        "apparent_mass_real_kg", "apparent_mass_imag_kg", "stiffness_N_per_m", "damping_N_s_per_m",
        "welch_stiffness_N_per_m", "welch_damping_N_s_per_m", "welch_frequency_Hz", "coherence",
        "amplitude_measured_mm_pp", "amplitude_measured_rms_mm", "acceleration_amplitude_m_s2",
        *unc.UNCERTAINTY_COLUMNS,
    )}
    if found.any():
        d = am.apparent_mass_demodulation(force[found], a[found], sample_rate_Hz, fe[found])
        w = am.apparent_mass_welch(force[found], a[found], sample_rate_Hz, fe[found])
        cols["excitation_frequency_measured_Hz"][found] = d.frequency_Hz
        cols["apparent_mass_real_kg"][found] = d.apparent_mass_kg.real
        cols["apparent_mass_imag_kg"][found] = d.apparent_mass_kg.imag
        cols["stiffness_N_per_m"][found] = d.stiffness_N_per_m
        cols["damping_N_s_per_m"][found] = d.damping_N_s_per_m
        cols["welch_stiffness_N_per_m"][found] = w.stiffness_N_per_m
        cols["welch_damping_N_s_per_m"][found] = w.damping_N_s_per_m
        cols["welch_frequency_Hz"][found] = w.frequency_Hz
        cols["coherence"][found] = w.coherence
        cols["amplitude_measured_mm_pp"][found] = 2e3 * d.displacement_amplitude_m
        cols["amplitude_measured_rms_mm"][found] = 1e3 * d.displacement_amplitude_m / np.sqrt(2)
        cols["acceleration_amplitude_m_s2"][found] = d.acceleration_amplitude_m_s2
        # per-run uncertainty (issue 14): the run's own residual near the excitation and the §3.2.9
        # limits (the calibrate stage replaces the limits by the day's check where there is one)
        u = unc.run_uncertainty(d, [unc.limits_budget(m) for m in mass[found]], mass[found])
        for name, values in u.columns().items():
            cols[name][found] = values
    for q in ("stiffness", "damping", "welch_stiffness", "welch_damping"):
        unit = "N_per_m" if q.endswith("stiffness") else "N_s_per_m"
        cols[f"{q}_k{unit}"] = cols[f"{q}_{unit}"] / 1e3
    t = np.arange(a.shape[-1]) / sample_rate_Hz
    blocks = [None] * len(fe)
    if found.any():
        amp_blocks, freq_blocks = am.excitation_blocks(d.envelope_m_s2, d.angular_frequency_rad_s, sample_rate_Hz)
        for j, i in enumerate(np.flatnonzero(found)):
            blocks[i] = (amp_blocks[j], freq_blocks[j])
    # (runs, 6) in CHANNELS order; each row is screened on its own, so no (runs, 6, n) copy is needed
    flags = np.concatenate([qc.clipped(x.reshape(-1, x.shape[-1])).reshape(x.shape[:2]) for x in (accel, beams)],
                           axis=1)
    reasons = []
    for i in range(len(fe)):
        reasons.append(qc.qc_reasons(
            t, a[i], force[i], cols["excitation_frequency_measured_Hz"][i], cols["coherence"][i],
            interference_Hz=interference_Hz[i] if interference_Hz else None, blocks=blocks[i],
            clipped_channels=[c for c, flag in zip(CHANNELS, flags[i]) if flag],
        ) + qc.plausibility_reasons(cols["stiffness_N_per_m"][i], cols["damping_N_s_per_m"][i]))
    cols["qc_ok"] = np.array([not r for r in reasons], dtype=bool)
    cols["qc_reasons"] = ["; ".join(r) for r in reasons]
    cols["uncertainty_source"] = np.where(found, unc.limits_budget().source, "")
    return pd.DataFrame(cols)


def dominant_frequency_Hz(accel_m_s2: np.ndarray, sample_rate_Hz: float, low_Hz: float = 0.25,
                          high_Hz: float = 50.0) -> float:
    """Frequency of the strongest axle motion between ``low_Hz`` and ``high_Hz`` (or Nyquist), Hz.

    The Hann-windowed acceleration spectrum divided by f² (the velocity spectrum), so that
    neither low-frequency drift nor the wheel's lug vibration outweighs a vibrator excitation.
    :func:`analyse_frame` uses it to refuse an excitation outside
    :data:`tyrelab.measurement.apparent_mass.EXCITATION_BAND_Hz`, whose own peak would then be noise.

    See Also
    --------
    tyrelab.measurement.apparent_mass.excitation_frequency : the drive's frequency within its band.

    Examples
    --------
    >>> t = np.arange(4096) / 256.0
    >>> round(dominant_frequency_Hz(np.sin(2 * np.pi * 12.0 * t), 256.0), 2)
    12.0
    """
    positive("sample_rate_Hz", sample_rate_Hz)
    band("low_Hz, high_Hz", (low_Hz, high_Hz))
    a = np.asarray(accel_m_s2, dtype=float)
    a = a - a.mean()
    power = np.abs(np.fft.rfft(a * np.hanning(a.size))) ** 2
    f = np.fft.rfftfreq(a.size, 1.0 / sample_rate_Hz)
    sel = (f >= low_Hz) & (f <= min(high_Hz, sample_rate_Hz / 2))
    if not sel.any() or not power[sel].any():
        return float("nan")
    return float(f[sel][np.argmax(power[sel] / f[sel] ** 2)])


def analyse_frame(
    frame: pd.DataFrame,
    axle_mass_kg: float,
    *,
    sample_rate_Hz: float | None = None,
    interference_Hz: list[float] | None = None,
    file: str | None = None,
) -> RecordingResult:
    """Stiffness K, damping C and QC of one recording given as a DataFrame (thesis ch. 3, §3.5).

    Parameters
    ----------
    frame : DataFrame
        The raw-format-v1 channels (:data:`tyrelab.rawformat.CHANNELS`;
        accelerations upward positive, m/s²; load-beam forces on the axle, N)
        and ``time_s``; without ``time_s``, ``sample_rate_Hz`` makes one.
    axle_mass_kg : float
        Mass of axle, wheel and tyre below the load beams M_a, kg (§3.2.8).
    sample_rate_Hz : float, optional
        Expected sampling rate, Hz, checked against the time base.
    interference_Hz : list of float, optional
        Frequencies of the wheel's own excitation (rotation, lug passing) for
        the QC of rolling runs (:func:`tyrelab.measurement.qc.interference_frequencies_Hz`).
    file : str, optional
        Where the frame was read from, kept in the result.

    Returns
    -------
    RecordingResult

    Raises
    ------
    ValueError
        If ``axle_mass_kg`` or ``sample_rate_Hz`` is not finite and positive,
        ``frame`` is not a DataFrame, or it has no ``time_s`` and no ``sample_rate_Hz``.
    tyrelab.rawformat.RunFileError
        If the channels fail the raw-format checks (missing channel, NaN,
        irregular or out-of-range sampling, too short).

    See Also
    --------
    analyse_batch : many runs of one length at once.
    tyrelab.measurement.analyse_method_run : a run of the other methods.

    Examples
    --------
    >>> analyse_frame(pd.DataFrame(), axle_mass_kg=-600.0)
    Traceback (most recent call last):
    ...
    ValueError: axle_mass_kg must be finite and positive, got -600.0
    """
    mass = positive("axle_mass_kg", axle_mass_kg)
    if sample_rate_Hz is not None:
        sample_rate_Hz = positive("sample_rate_Hz", sample_rate_Hz)
    if not isinstance(frame, pd.DataFrame):
        raise ValueError(f"frame must be a pandas DataFrame, got {type(frame).__name__}")
    if isinstance(frame.columns, pd.MultiIndex):
        raise ValueError(f"frame must have one level of column names (the channels), got {frame.columns.nlevels} levels")
    duplicated = sorted({str(c) for c in frame.columns[frame.columns.duplicated()]})
    if duplicated:
        raise ValueError(f"frame has duplicated columns: {', '.join(duplicated)}")
    if TIME not in frame.columns:
        if sample_rate_Hz is None:
            raise ValueError("sample_rate_Hz is needed for a recording without a time_s column")
        frame = frame.assign(**{TIME: np.arange(len(frame)) / sample_rate_Hz})
    info = check_run(frame, excitation_frequency_Hz=0.0, sample_rate_Hz=sample_rate_Hz)
    accel, beams = recording_arrays(frame)
    row = analyse_batch(accel[np.newaxis], beams[np.newaxis], np.array([mass]), info.sample_rate_Hz,
                        [list(interference_Hz)] if interference_Hz else None).iloc[0]
    lo, hi = am.EXCITATION_BAND_Hz
    dominant = dominant_frequency_Hz(accel.mean(axis=0), info.sample_rate_Hz)
    if np.isfinite(dominant) and not lo <= dominant <= hi:
        # The band's own peak would be noise: no K, C or H, and the reason names the band.
        row = row.copy()
        row[[c for c in row.index if c not in ("qc_ok", "qc_reasons")]] = np.nan
        row["excitation_frequency_measured_Hz"] = dominant
        row["qc_reasons"] = (f"excitation at {dominant:.2f} Hz is outside the analysis band {lo:g}-{hi:g} Hz: "
                             "K and C are not estimated")
    return RecordingResult(
        sample_rate_Hz=info.sample_rate_Hz,
        duration_s=info.duration_s,
        axle_mass_kg=mass,
        excitation_frequency_Hz=float(row["excitation_frequency_measured_Hz"]),
        stiffness_N_per_m=float(row["stiffness_N_per_m"]),
        damping_N_s_per_m=float(row["damping_N_s_per_m"]),
        apparent_mass_kg=complex(row["apparent_mass_real_kg"], row["apparent_mass_imag_kg"]),
        amplitude_mm_pp=float(row["amplitude_measured_mm_pp"]),
        acceleration_amplitude_m_s2=float(row["acceleration_amplitude_m_s2"]),
        coherence=float(row["coherence"]),
        welch=WelchEstimate(float(row["welch_frequency_Hz"]), float(row["welch_stiffness_N_per_m"]),
                            float(row["welch_damping_N_s_per_m"])),
        qc_reasons=tuple(r for r in row["qc_reasons"].split("; ") if r),
        file=file,
        stiffness_u_N_per_m=float(row["stiffness_u_N_per_m"]),
        damping_u_N_s_per_m=float(row["damping_u_N_s_per_m"]),
        stiffness_ci95_N_per_m=(float(row["stiffness_ci95_low_N_per_m"]), float(row["stiffness_ci95_high_N_per_m"])),
        damping_ci95_N_s_per_m=(float(row["damping_ci95_low_N_s_per_m"]), float(row["damping_ci95_high_N_s_per_m"])),
        uncertainty={
            "stiffness_u_stat_N_per_m": float(row["stiffness_u_stat_N_per_m"]),
            "damping_u_stat_N_s_per_m": float(row["damping_u_stat_N_s_per_m"]),
            "dof_stat": float(row["uncertainty_dof_stat"]), "dof": float(row["uncertainty_dof"]),
            "coverage_factor": float(row["coverage_factor"]), "level": unc.LEVEL,
            "instrument": str(row["uncertainty_source"]),
        },
    )
