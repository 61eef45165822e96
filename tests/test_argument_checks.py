"""Every public function of the pure packages refuses a bad argument with a ``ValueError`` naming it.

One row per (function, bad argument): a bad value of a number, an array, a band or a name must
end in one clear line naming the parameter (:mod:`tyrelab._validate`, scipy's habit), never in a
``ZeroDivisionError``, a ``KeyError``, a NaN or an infinity three functions later.

Row format — add a row for each public function and each of its parameters a caller can get
wrong; the engineers of ``tyre/`` and ``vehicle/`` add theirs to :data:`ROWS` in the same form::

    ("tyrelab.<package>.<module>.<function>", {<every argument, one of them bad>}, "<parameter named>"),

- the first field is the function's import path (imported when the test runs);
- the second is the keyword arguments of the call: valid values for all but the one under test
  (``SINE``, ``T``, ``FS`` are a valid 20 s, 4 Hz signal, its time base and sample rate; a value may
  be a zero-argument callable such as ``_tf`` or ``_run``, called when the row runs, for inputs that
  must be fresh);
- the third is the parameter the ``ValueError`` message must name (as a whole word).
"""

from __future__ import annotations

import importlib
import math
import re

import numpy as np
import pandas as pd
import pytest

FS = 256.0
T = np.arange(0, 20, 1 / FS)
SINE = np.sin(2 * np.pi * 4.0 * T)
NAN, INF = math.nan, math.inf


def _tf():
    f = np.arange(1.0, 8.25, 0.25)
    return pd.DataFrame({"frequency_Hz": f, "gain": np.ones_like(f), "phase_deg": np.zeros_like(f),
                         "coherence": np.ones_like(f)})


def _run():
    from tyrelab.rawformat import CHANNELS

    return pd.DataFrame({"time_s": T, **{c: SINE for c in CHANNELS}})



M = "tyrelab.measurement"
ROWS = [
    # measurement/apparent_mass.py
    (f"{M}.apparent_mass.tyre_force", dict(accel_left_m_s2=SINE, accel_right_m_s2=SINE, load_beams_N=np.zeros((4, SINE.size)), axle_mass_kg=-1.0), "axle_mass_kg"),
    (f"{M}.apparent_mass.stiffness_damping", dict(apparent_mass_kg=-400 - 100j, frequency_Hz=0.0), "frequency_Hz"),
    (f"{M}.apparent_mass.apparent_mass_from_kc", dict(stiffness_N_per_m=4e5, damping_N_s_per_m=2e3, frequency_Hz=-4.0), "frequency_Hz"),
    (f"{M}.apparent_mass.excitation_frequency", dict(accel_m_s2=SINE, sample_rate_Hz=0.0), "sample_rate_Hz"),
    (f"{M}.apparent_mass.excitation_frequency", dict(accel_m_s2=SINE, sample_rate_Hz=FS, band_Hz=(8.0, 1.0)), "band_Hz"),
    (f"{M}.apparent_mass.apparent_mass_demodulation", dict(force_N=SINE, accel_m_s2=SINE, sample_rate_Hz=NAN), "sample_rate_Hz"),
    (f"{M}.apparent_mass.apparent_mass_demodulation", dict(force_N=SINE, accel_m_s2=SINE, sample_rate_Hz=FS, half_band_Hz=0.0), "half_band_Hz"),
    (f"{M}.apparent_mass.apparent_mass_welch", dict(force_N=SINE, accel_m_s2=SINE, sample_rate_Hz=FS, resolution_Hz=0.0), "resolution_Hz"),
    (f"{M}.apparent_mass.h1_spectrum", dict(x=SINE, y=SINE, sample_rate_Hz=FS, nperseg=0), "nperseg"),
    # measurement/calibration.py
    (f"{M}.calibration.calibration_transfer_function", dict(force_plate_N=SINE, derived_force_N=SINE, sample_rate_Hz=-FS), "sample_rate_Hz"),
    (f"{M}.calibration.calibration_transfer_function", dict(force_plate_N=SINE, derived_force_N=SINE, sample_rate_Hz=FS, resolution_Hz=0.0), "resolution_Hz"),
    (f"{M}.calibration.check_calibration", dict(tf=_tf, gain_tolerance=-0.03), "gain_tolerance"),
    (f"{M}.calibration.check_calibration", dict(tf=_tf, phase_tolerance_deg=NAN), "phase_tolerance_deg"),
    (f"{M}.calibration.check_calibration", dict(tf=_tf, band_Hz=(6.0, 2.0)), "band_Hz"),
    (f"{M}.calibration.correction_factor", dict(tf=_tf, frequency_Hz=0.0), "frequency_Hz"),
    (f"{M}.calibration.corrected_stiffness_damping", dict(stiffness_N_per_m=4e5, damping_N_s_per_m=2e3, frequency_Hz=-1.0, tf=_tf), "frequency_Hz"),
    # measurement/methods.py
    (f"{M}.methods.load_deflection_stiffness", dict(force_N=SINE, deflection_m=SINE, fraction=(0.9, 0.2)), "fraction"),
    (f"{M}.methods.free_vibration", dict(time_s=T, response=SINE, mass_kg=0.0), "mass_kg"),
    (f"{M}.methods.free_vibration", dict(time_s=T, response=SINE, mass_kg=1e3, n_cycles=0), "n_cycles"),
    (f"{M}.methods.half_power", dict(force_N=SINE, accel_m_s2=SINE, sample_rate_Hz=FS, mass_kg=-1.0), "mass_kg"),
    # measurement/qc.py
    (f"{M}.qc.clipped", dict(x=SINE, min_run=0), "min_run"),
    (f"{M}.qc.clipped", dict(x=SINE, min_count=2.5), "min_count"),
    (f"{M}.qc.interference_frequencies_Hz", dict(speed_km_h=-5.0, circumference_m=5.0), "speed_km_h"),
    (f"{M}.qc.interference_frequencies_Hz", dict(speed_km_h=5.0, circumference_m=-1.0), "circumference_m"),
    (f"{M}.qc.interference_frequencies_Hz", dict(speed_km_h=5.0, circumference_m=5.0, harmonics=-1), "harmonics"),
    # measurement/recording.py
    (f"{M}.recording.analyse_batch", dict(accel=np.zeros((1, 2, 1024)), beams=np.zeros((1, 4, 1024)), axle_mass_kg=np.ones(1), sample_rate_Hz=0.0), "sample_rate_Hz"),
    (f"{M}.recording.dominant_frequency_Hz", dict(accel_m_s2=SINE, sample_rate_Hz=INF), "sample_rate_Hz"),
    (f"{M}.recording.dominant_frequency_Hz", dict(accel_m_s2=SINE, sample_rate_Hz=FS, low_Hz=10.0, high_Hz=1.0), "low_Hz"),
    # measurement/uncertainty.py
    (f"{M}.uncertainty.limits_budget", dict(axle_mass_kg=0.0), "axle_mass_kg"),
    (f"{M}.uncertainty.day_budget", dict(tf=_tf, frequency_Hz=4.0, n_averages=0), "n_averages"),
    (f"{M}.uncertainty.coverage_factor", dict(dof=5, level=1.5), "level"),
    # rawformat
    ("tyrelab.rawformat.check_run", dict(df=lambda: _run(), excitation_frequency_Hz=-4.0), "excitation_frequency_Hz"),
    ("tyrelab.rawformat.check_run", dict(df=lambda: _run(), excitation_frequency_Hz=NAN), "excitation_frequency_Hz"),
    ("tyrelab.rawformat.check_run", dict(df=lambda: _run(), excitation_frequency_Hz=4.0, sample_rate_Hz=0.0), "sample_rate_Hz"),
]


def _call(path: str, kwargs: dict):
    module, _, name = path.rpartition(".")
    fn = getattr(importlib.import_module(module), name)
    return fn(**{k: (v() if callable(v) and not isinstance(v, type) else v) for k, v in kwargs.items()})


@pytest.mark.parametrize("path, kwargs, parameter", ROWS, ids=[f"{p.rpartition('.')[2]}-{n}" for p, _, n in ROWS])
def test_a_bad_argument_is_a_value_error_naming_it(path, kwargs, parameter):
    with pytest.raises(ValueError) as info:
        _call(path, kwargs)
    assert re.search(rf"\b{re.escape(parameter)}\b", str(info.value)), str(info.value)
