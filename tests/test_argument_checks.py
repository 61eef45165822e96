"""Every public function of the pure packages refuses a bad argument with a ``ValueError`` naming it.

One row per (function, bad argument): a bad value of a number, an array, a band or a name must
end in one clear line naming the parameter (:mod:`tyrelab._validate`, scipy's habit), never in a
``ZeroDivisionError``, a ``KeyError``, a NaN or an infinity three functions later.

Row format — a row for each public function and each of its parameters a caller can get wrong::

    ("tyrelab.<package>.<module>.<function>", {<every argument, one of them bad>}, "<parameter named>"),

:func:`test_every_public_function_of_tyre_and_vehicle_has_a_row` walks ``__all__`` of every module of
``tyre/`` and ``vehicle/``: a public function there without a row (or a reason in :data:`EXEMPT`) fails it.

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
from pathlib import Path

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


def _results():
    """A small ``results`` table: one tyre, stationary and rolling, three pressures."""
    return pd.DataFrame({"tyre_id": "T1", "kind": "measurement", "speed_km_h": [0.0, 10.0, 15.0],
                         "pressure_bar": [1.0, 1.2, 1.4], "load_kN": 20.0, "excitation_frequency_Hz": 4.0,
                         "amplitude_mm_pp": 14.0, "torque_kNm": 0.0, "surface": "concrete",
                         "stiffness_kN_per_m": [500.0, 400.0, 420.0], "damping_kN_s_per_m": [2.0, 1.5, 1.4],
                         "qc_ok": True})


def _pub(name):
    from tyrelab.published import read_published

    return read_published(name)


def _size_points():
    from tyrelab.tyre.size_regressions import tyre_points

    return tyre_points(_pub("table_iii"), _pub("table_ii"))


def _measured_tyre():
    from tyrelab.tyre.mf_tyre import MeasuredTyre, PressureLine
    from tyrelab.tyre.sizes import parse_tyre_size

    return MeasuredTyre("MY1", parse_tyre_size("480/70R38"), PressureLine(120.0, 230.0), PressureLine(1.1, 0.4),
                        12.0, 25.0, (0.8, 1.6))


def _carriage():
    from tyrelab.vehicle.carriage import Carriage

    return Carriage(1000.0, 1e5, 1e3)


def _tractor():
    from tyrelab.vehicle.tractor import Tractor

    return Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3)


def _assembly():
    from tyrelab.vehicle.model import assemble
    from tyrelab.vehicle.tractor import tractor_parts

    return assemble(tractor_parts(_tractor()))


def _slatted():
    from tyrelab.vehicle.profiles import slatted_track

    return slatted_track(length_m=5.0)


def _scenario():
    from tyrelab.scenario_io import load_scenario

    return load_scenario(Path(__file__).resolve().parents[1] / "raw" / "scenarios" / "modern_tractor.toml")


_FIG30 = "dkp_vs_wr"


M = "tyrelab.measurement"
TY = "tyrelab.tyre"
VE = "tyrelab.vehicle"
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
    # tyre/conditions.py
    (f"{TY}.conditions.with_columns", dict(results=[1, 2]), "results"),
    (f"{TY}.conditions.usable", dict(results=None), "results"),
    (f"{TY}.conditions.on_reference_surface", dict(results="runs.csv"), "results"),
    (f"{TY}.conditions.at_nominal_torque", dict(results={"torque_kNm": 1.0}), "results"),
    (f"{TY}.conditions.at_nominal_frequency", dict(results=None), "results"),
    (f"{TY}.conditions.at_nominal_amplitude", dict(results=None), "results"),
    (f"{TY}.conditions.nominal", dict(results=_results, except_for="wind"), "except_for"),
    (f"{TY}.conditions.speed_condition", dict(speed_km_h=[10.0, -5.0]), "speed_km_h"),
    (f"{TY}.conditions.table_iii_runs", dict(results=lambda: _results().drop(columns="speed_km_h")), "results"),
    (f"{TY}.conditions.regressor", dict(results=_results, factor="wind"), "factor"),
    (f"{TY}.conditions.factor_runs", dict(results=_results, factor="wind"), "factor"),
    (f"{TY}.conditions.hold_levels", dict(runs=_results, cols=["load_kN", "nope"]), "runs"),
    (f"{TY}.conditions.hold_level", dict(x=[1.0, 2.0], keys=np.zeros((3, 1)), cols=["load_kN"], hold=["load_kN"]), "keys"),
    (f"{TY}.conditions.n_distinct", dict(values=["a", 1.0]), "values"),
    (f"{TY}.conditions.hold_constant", dict(runs=_results, x="nope", hold=["load_kN"]), "x"),
    # tyre/damping_fit.py
    (f"{TY}.damping_fit.damping_points", dict(lines=lambda: _pub("table_vii"), tyres=lambda: _pub("table_ii"), grid_bar=(0.8, -1.0)), "grid_bar"),
    (f"{TY}.damping_fit.damping_points", dict(lines=lambda: _pub("table_vii").drop(columns="speed_km_h"), tyres=lambda: _pub("table_ii")), "lines"),
    (f"{TY}.damping_fit.fit_damping", dict(points=lambda: pd.DataFrame({"tyre_id": ["T1"]})), "points"),
    (f"{TY}.damping_fit.damping_table", dict(fits=[None]), "fits"),
    # tyre/formula_accuracy.py
    (f"{TY}.formula_accuracy.p_within", dict(mean=3.0, sd=10.0, limit=0), "limit"),
    (f"{TY}.formula_accuracy.predictions_from_table", dict(table=lambda: _pub("table_iii"), tyres=lambda: _pub("table_ii"), rear_grid=(0.8, NAN)), "rear_grid"),
    (f"{TY}.formula_accuracy.predictions_from_table", dict(table=lambda: _pub("table_iii").drop(columns="condition"), tyres=None), "table"),
    (f"{TY}.formula_accuracy.predictions_from_recordings", dict(results=_results, our_table_iii=pd.DataFrame(), tyres=None), "our_table_iii"),
    (f"{TY}.formula_accuracy.accuracy_summary", dict(pred=lambda: pd.DataFrame({"tyre_id": ["T1"]}), source="ours"), "pred"),
    (f"{TY}.formula_accuracy.formula_error_model", dict(table=lambda: _pub("table_iii").iloc[:0], tyres=lambda: _pub("table_ii")), "table"),
    # tyre/formula_fit.py
    (f"{TY}.formula_fit.design_matrix", dict(sizes=["13.6R38"], age_years=[-1.0], pressure_bar=[1.2]), "age_years"),
    (f"{TY}.formula_fit.design_matrix", dict(sizes=["13.6R38"], age_years=[1.0], pressure_bar=[INF]), "pressure_bar"),
    (f"{TY}.directional.directional_tyre", dict(tyre_id="T1", direction="vertical", pressure_bar=1.0, speed_km_h=0.0), "direction"),
    (f"{TY}.directional.directional_tyre", dict(tyre_id="T1", direction="lateral", pressure_bar=1.0, speed_km_h=-1.0), "speed_km_h"),
    (f"{TY}.formula_fit.extended_design_matrix", dict(sizes=["13.6R38"], age_years=[1.0], pressure_bar=[-1.2]), "pressure_bar"),
    (f"{TY}.formula_fit.fit_formula", dict(points=lambda: pd.DataFrame({"tyre_id": ["T1"]})), "points"),
    (f"{TY}.formula_fit.leave_one_tyre_out", dict(points="points.csv"), "points"),
    (f"{TY}.formula_fit.front_rule", dict(table_iii=lambda: _pub("table_iii"), table_ii=lambda: _pub("table_ii"), front_id="F9"), "table_iii"),
    (f"{TY}.formula_fit.front_rule", dict(table_iii=lambda: _pub("table_iii"), table_ii=pd.DataFrame()), "table_ii"),
    (f"{TY}.formula_fit.fit_table", dict(fits=["fit"]), "fits"),
    # tyre/examples.py
    (f"{TY}.examples.demo_runs", dict(series="speed"), "series"),
    # tyre/mf_tyre.py
    (f"{TY}.mf_tyre.measured_tyre", dict(tyre_id="ZZ", tyres=lambda: _pub("table_ii")), "tyre_id"),
    (f"{TY}.mf_tyre.measured_tyre", dict(tyre_id="T1", tyres=lambda: _pub("table_ii"), damping_speed_km_h=0.0), "damping_speed_km_h"),
    (f"{TY}.mf_tyre.pressure_table", dict(tyre_id="T1", stiffness_by_speed=pd.DataFrame(), damping_by_speed=pd.DataFrame(), pressures_bar=[1.0], alpha=2.0), "alpha"),
    (f"{TY}.mf_tyre.pressure_table", dict(tyre_id="T1", stiffness_by_speed=pd.DataFrame(), damping_by_speed=pd.DataFrame(), pressures_bar=[-1.0]), "pressures_bar"),
    (f"{TY}.mf_tyre.property_file", dict(tyre=_measured_tyre, pressure_bar=0.0), "pressure_bar"),
    (f"{TY}.mf_tyre.property_file", dict(tyre="T1", pressure_bar=1.2), "tyre"),
    (f"{TY}.mf_tyre.tir_parameters", dict(tyre=_measured_tyre, pressure_bar=INF), "pressure_bar"),
    # tyre/models.py
    (f"{TY}.models.thesis_points", dict(table_ii=pd.DataFrame(), table_iii=lambda: _pub("table_iii")), "table_ii"),
    (f"{TY}.models.thesis_formula_fit", dict(table_ii=None, table_iii=lambda: _pub("table_iii")), "table_ii"),
    (f"{TY}.models.thesis_stiffness_model", dict(table_ii=lambda: _pub("table_ii"), table_iii=lambda: _pub("table_iii"), table_vi=None), "table_vi"),
    (f"{TY}.models.fit_row", dict(fit={"source": "ours"}), "fit"),
    (f"{TY}.models.fit_from_row", dict(row={"source": "ours"}), "row"),
    (f"{TY}.models.build_stiffness_model", dict(formula_fit_table=pd.DataFrame({"n": [1]}), thesis=None), "formula_fit_table"),
    (f"{TY}.models.build_stiffness_model", dict(formula_fit_table=pd.DataFrame({"source": ["ours"]}), thesis=None), "thesis"),
    # tyre/regressions.py
    (f"{TY}.regressions.fit_line", dict(x=[1, 2, 3], y=[1, 2, 4], alpha=2), "alpha"),
    (f"{TY}.regressions.fit_mean", dict(y=[1, 2, 3], alpha=0), "alpha"),
    (f"{TY}.regressions.measured_tyres", dict(results=None), "results"),
    (f"{TY}.regressions.pressure_regressions", dict(results=_results, response="stiffness"), "response"),
    (f"{TY}.regressions.pressure_regressions", dict(results=_results, by="tyre"), "by"),
    (f"{TY}.regressions.pressure_regressions_each", dict(results=_results, responses=("damping",), tyre_ids=["T1"]), "responses"),
    (f"{TY}.regressions.factor_regressions", dict(results=_results, factor="wind"), "factor"),
    (f"{TY}.regressions.factor_regressions_each", dict(results=_results, factor="wind", tyre_ids=["T1"]), "factor"),
    (f"{TY}.regressions.surface_effects", dict(results=_results, response="K"), "response"),
    (f"{TY}.regressions.compare_with_thesis", dict(ours=_results, thesis=None, keys=["tyre_id", "condition"], values={}), "ours"),
    (f"{TY}.regressions.table_iii", dict(fit=pd.DataFrame(), published=None), "fit"),
    (f"{TY}.regressions.table_vii", dict(fit=pd.DataFrame({"tyre_id": ["T1"]}), published=None), "fit"),
    (f"{TY}.regressions.amplitude_table", dict(rates=pd.DataFrame(), published=None, response="amplitude"), "response"),
    (f"{TY}.regressions.surface_table", dict(summary=pd.DataFrame(), published=None, response="sand"), "response"),
    (f"{TY}.regressions.summary_rates", dict(by_speed=pd.DataFrame(), rates=pd.DataFrame(), response="stiffness_kN_per_m", pressure_bar=0.0), "pressure_bar"),
    (f"{TY}.regressions.summary_rates", dict(by_speed=pd.DataFrame(), rates=pd.DataFrame(), response="stiffness_kN_per_m", rolling_min_km_h=-1.0), "rolling_min_km_h"),
    (f"{TY}.regressions.between_run_variance", dict(x=[1.0, 2.0, 3.0], y=[1.0, 2.0, 3.0], u=[0.1, 0.0, 0.1]), "u"),
    # tyre/size_regressions.py
    (f"{TY}.size_regressions.tyre_points", dict(table=pd.DataFrame({"tyre_id": ["T1"]})), "table"),
    (f"{TY}.size_regressions.select", dict(points=_size_points, spec={"x": "wr_in2"}), "spec"),
    (f"{TY}.size_regressions.selection_search", dict(points=_size_points, name="Fig. 99"), "name"),
    (f"{TY}.size_regressions.selection_search", dict(points=_size_points, name=_FIG30, max_excluded=-1), "max_excluded"),
    (f"{TY}.size_regressions.variants", dict(points=_size_points, name="wr"), "name"),
    (f"{TY}.size_regressions.size_regressions", dict(table=None, tyres=None, source="ours"), "table"),
    # tyre/sizes.py
    (f"{TY}.sizes.load_index_kg", dict(load_index=400), "load_index"),
    (f"{TY}.sizes.lugs_per_side", dict(circumference_m=NAN), "circumference_m"),
    # parse_tyre_size's message speaks of the "tyre size" (the CLI shows it to users); its parameter is `text`
    (f"{TY}.sizes.parse_tyre_size", dict(text="banana"), "size"),
    (f"{TY}.sizes.rolling_circumference_m", dict(size="13.6R38", aspect_ratio=3.0), "aspect_ratio"),
    (f"{TY}.sizes.speed_symbol_km_h", dict(symbol="Q9"), "symbol"),
    (f"{TY}.sizes.tyre_rolling_circumference_m", dict(size="banana"), "size"),
    # tyre/speed_dependence.py
    (f"{TY}.speed_dependence.at_speeds", dict(speeds_km_h=[0, 10], values=[1.0, 2.0], query_km_h=[-3.0]), "query_km_h"),
    # tyre/spoke.py
    (f"{TY}.spoke.unloaded_radius_m", dict(size="13.6R38", aspect_ratio=0), "aspect_ratio"),
    (f"{TY}.spoke.contact_half_angle", dict(h=0.7, r0=0.0), "r0"),
    (f"{TY}.spoke.spoke_rate", dict(theta=0.1, h=0.7, h_dot=0.1, wheel_rate_rad_s=NAN), "wheel_rate_rad_s"),
    (f"{TY}.spoke.vertical_force", dict(h=0.7, h_dot=0.1, wheel_rate_rad_s=3.0, r0=-0.8, c_coulomb=1.0, c_viscous=0.0), "r0"),
    (f"{TY}.spoke.vertical_force", dict(h=0.7, h_dot=0.1, wheel_rate_rad_s=3.0, r0=0.8, c_coulomb=NAN, c_viscous=0.0), "c_coulomb"),
    (f"{TY}.spoke.vertical_force_spokes", dict(h=0.7, h_dot=0.1, wheel_angle_rad=0.0, wheel_rate_rad_s=3.0, r0=0.8, c_coulomb=1.0, c_viscous=0.0, n_spokes=0), "n_spokes"),
    (f"{TY}.spoke.damping_basis", dict(speed_km_h=10.0, amplitude_m=-0.01), "amplitude_m"),
    (f"{TY}.spoke.damping_basis", dict(speed_km_h=-5.0), "speed_km_h"),
    (f"{TY}.spoke.equivalent_damping", dict(speed_km_h=10.0, frequency_Hz=0.0), "frequency_Hz"),
    (f"{TY}.spoke.equivalent_damping", dict(speed_km_h=10.0, c_viscous=NAN), "c_viscous"),
    (f"{TY}.spoke.fit_coefficients", dict(speed_km_h=[10.0, 15.0], damping=[1.0, NAN]), "damping"),
    (f"{TY}.spoke.force_curves", dict(n_points=1), "n_points"),
    (f"{TY}.spoke.speed_curves", dict(r0=0.0), "r0"),
    (f"{TY}.spoke.frequency_curves", dict(frequencies_Hz=[0.0, 4.0]), "frequencies_Hz"),
    (f"{TY}.spoke.amplitude_curves", dict(amplitudes_mm=[-2.0]), "amplitudes_mm"),
    (f"{TY}.spoke.deflection_curves", dict(deflection_percent=[8.0, 120.0]), "deflection_percent"),
    (f"{TY}.spoke.fit_tyres", dict(results=_results, min_speed_km_h=0.0), "min_speed_km_h"),
    (f"{TY}.spoke.fit_tyres_each", dict(results=_results, tyre_ids=["T1"], h_over_r0=NAN), "h_over_r0"),
    # tyre/stiffness.py
    (f"{TY}.stiffness.traction_tyre_stiffness", dict(size="13.6R38", pressure_bar=-1.0), "pressure_bar"),
    (f"{TY}.stiffness.traction_tyre_stiffness", dict(size="13.6R38", pressure_bar=1.0, age_years=NAN), "age_years"),
    (f"{TY}.stiffness.undriven_front_tyre_stiffness", dict(size="7.50-18", pressure_bar=INF), "pressure_bar"),
    (f"{TY}.stiffness.estimate_stiffness", dict(size="13.6R38", pressure_bar=-0.1), "pressure_bar"),
    (f"{TY}.stiffness.estimate_tyre_stiffness", dict(size="13.6R38", pressure_bar=1.2, age_years=-3.0), "age_years"),
    (f"{TY}.stiffness.range_warnings", dict(size="13.6R38", pressure_bar=1.0, age_years=-2), "age_years"),
    # vehicle/bounce_pitch.py
    (f"{VE}.bounce_pitch.natural_frequencies", dict(mass_kg=0.0, pitch_inertia_kg_m2=250.0, front_distance_m=1.0, rear_distance_m=1.0, front_stiffness_N_per_m_axle=1e5, rear_stiffness_N_per_m_axle=1e5), "mass_kg"),
    (f"{VE}.bounce_pitch.natural_frequencies", dict(mass_kg=1e3, pitch_inertia_kg_m2=250.0, front_distance_m=1.0, rear_distance_m=1.0, front_stiffness_N_per_m_axle=1e5, rear_stiffness_N_per_m_axle=-1e5), "rear_stiffness_N_per_m_axle"),
    (f"{VE}.bounce_pitch.mode_shapes", dict(mass_kg=1e3, pitch_inertia_kg_m2=NAN, front_distance_m=1.0, rear_distance_m=1.0, front_stiffness_N_per_m_axle=1e5, rear_stiffness_N_per_m_axle=1e5), "pitch_inertia_kg_m2"),
    (f"{VE}.bounce_pitch.tractor_natural_frequencies", dict(mass_kg=4700.0, pitch_inertia_kg_m2=5500.0, front_distance_m=1.56, rear_distance_m=0.95, front_size="380/85R28", front_pressure_bar=-1.6, rear_size="480/70R38", rear_pressure_bar=1.2), "front_pressure_bar"),
    (f"{VE}.bounce_pitch.frequency_uncertainty", dict(mass_kg=4700.0, pitch_inertia_kg_m2=5500.0, front_distance_m=1.56, rear_distance_m=0.95, front_tyre_kN_per_m=350.0, rear_tyre_kN_per_m=400.0, front_u_kN_per_m=-1.0, rear_u_kN_per_m=10.0), "front_u_kN_per_m"),
    (f"{VE}.bounce_pitch.frequency_rounding_range", dict(mass=4700.0, pitch_inertia=5500.0, front_distance=-1.56, rear_distance=0.95, front_stiffness_kN_per_m=350.0, rear_stiffness_kN_per_m=400.0), "front_distance"),
    (f"{VE}.bounce_pitch.table_xx", dict(tractors=None), "tractors"),
    (f"{VE}.bounce_pitch.table_xx_statistics", dict(table=[1, 2]), "table"),
    # vehicle/carriage.py
    (f"{VE}.carriage.damped_natural_frequency", dict(carriage=(1000.0, 1e5, 1e3)), "carriage"),
    (f"{VE}.carriage.ground_input", dict(x_m=[0.0, 1.0, 2.0], elevation_m=[0.0, 0.01, 0.0], speed_m_s=0.0, dt_s=0.001, x_start_m=0.0, x_end_m=2.0), "speed_m_s"),
    (f"{VE}.carriage.ground_input", dict(x_m=[0.0, 1.0, 2.0], elevation_m=[0.0, 0.01, 0.0], speed_m_s=1.0, dt_s=0.001, x_start_m=2.0, x_end_m=1.0), "x_end_m"),
    (f"{VE}.carriage.half_step_input", dict(x_m=[0.0, 1.0, 2.0], elevation_m=[0.0, 0.01, 0.0], speed_m_s=1.0, n_steps=10, dt_s=0.0), "dt_s"),
    (f"{VE}.carriage.carriage_state_space", dict(c=None), "c"),
    (f"{VE}.carriage.simulate_linear", dict(carriage=_carriage, u_m=[0.0] * 3, u_dot_m_s=[0.0] * 3, dt_s=-1.0), "dt_s"),
    (f"{VE}.carriage.simulate_nonlinear", dict(carriage=_carriage, u_half_m=[0.0] * 3, u_dot_half_m_s=[0.0] * 3, dt_s=0), "dt_s"),
    (f"{VE}.carriage.simulate_ivp", dict(carriage=_carriage, x_m=[0.0, 1.0, 2.0], elevation_m=[0.0] * 3, speed_m_s=1.0, t_end_s=INF), "t_end_s"),
    (f"{VE}.carriage.acceleration_response", dict(carriage=_carriage, frequency_Hz=[1.0, -2.0]), "frequency_Hz"),
    (f"{VE}.carriage.response_psd", dict(carriage=_carriage, n_cycles_per_m=[0.1], profile_psd_m3=[1e-4], speed_m_s=0.0), "speed_m_s"),
    # vehicle/daily_exposure.py
    (f"{VE}.daily_exposure.daily_exposure", dict(tasks=[]), "tasks"),
    (f"{VE}.daily_exposure.verdict", dict(a8_m_s2=NAN), "a8_m_s2"),
    (f"{VE}.daily_exposure.hours_to", dict(value_m_s2=-0.5, a8_m_s2=0.6, day_hours=8.0), "value_m_s2"),
    # vehicle/enveloping.py
    (f"{VE}.enveloping.contact_length", dict(radius_m=0.8, deflection_m=-0.01), "deflection_m"),
    (f"{VE}.enveloping.fixed_footprint", dict(heights_m=SINE, dx_m=0.0, footprint_m=0.3), "dx_m"),
    (f"{VE}.enveloping.tapered_moving_average", dict(heights_m=SINE, dx_m=0.01, footprint_m=0.3, taper_fraction=1.5), "taper_fraction"),
    (f"{VE}.enveloping.tapered_window", dict(n_samples=0), "n_samples"),
    (f"{VE}.enveloping.window", dict(kind="round", footprint_m=0.3, dx_m=0.01), "kind"),
    (f"{VE}.enveloping.rigid_tread_band", dict(heights_m=SINE, dx_m=0.01, radius_m=-0.8), "radius_m"),
    # vehicle/iso2631.py
    (f"{VE}.iso2631.weighting_response", dict(frequency_Hz=[1.0], name="Wx"), "name"),
    (f"{VE}.iso2631.weighting_ba", dict(name="Wk", fs_Hz=0.0), "fs_Hz"),
    (f"{VE}.iso2631.weighted_signal", dict(acceleration_m_s2=SINE, fs_Hz=FS, name="Wx"), "name"),
    (f"{VE}.iso2631.weighted_rms", dict(acceleration_m_s2=SINE, fs_Hz=-FS), "fs_Hz"),
    (f"{VE}.iso2631.vibration_dose_value", dict(weighted_m_s2=SINE, fs_Hz=NAN), "fs_Hz"),
    (f"{VE}.iso2631.crest_factor", dict(weighted_m_s2=[1.0, NAN]), "weighted_m_s2"),
    (f"{VE}.iso2631.daily_exposure_a8", dict(weighted_rms_m_s2=0.5, exposure_hours=-8.0), "exposure_hours"),
    (f"{VE}.iso2631.evaluate", dict(acceleration_m_s2=SINE, fs_Hz=FS, axis="w"), "axis"),
    (f"{VE}.iso2631.running_rms", dict(weighted_m_s2=SINE, fs_Hz=FS, tau_s=0.0), "tau_s"),
    (f"{VE}.iso2631.mtvv", dict(weighted_m_s2=SINE, fs_Hz=0.0), "fs_Hz"),
    (f"{VE}.iso2631.vector_sum", dict(a_wx_m_s2=0.3, a_wy_m_s2=-0.2, a_wz_m_s2=0.5), "a_wy_m_s2"),
    (f"{VE}.iso2631.method_check", dict(a_w_m_s2=1.0, crest=12.0, mtvv_m_s2=1.2, vdv_m_s1_75=10.0, duration_s=-1.0), "duration_s"),
    (f"{VE}.iso2631.impulse_response", dict(response=lambda: (lambda f: np.ones_like(f)), fs_Hz=0.0, ring_s=1.0), "fs_Hz"),
    # vehicle/iso2631_5.py
    (f"{VE}.iso2631_5.spine_response", dict(frequency_Hz=[NAN]), "frequency_Hz"),
    (f"{VE}.iso2631_5.spinal_acceleration", dict(seat_z_m_s2=SINE, fs_Hz=0.0), "fs_Hz"),
    (f"{VE}.iso2631_5.positive_peaks", dict(response_m_s2=[1.0, INF]), "response_m_s2"),
    (f"{VE}.iso2631_5.dose_from_peaks", dict(peaks_m_s2=[1.0, -1.0]), "peaks_m_s2"),
    (f"{VE}.iso2631_5.acceleration_dose", dict(seat_z_m_s2=SINE, fs_Hz=-FS), "fs_Hz"),
    (f"{VE}.iso2631_5.daily_dose", dict(doses_m_s2=2.0, exposure_s=8 * 3600, measured_s=0.0), "measured_s"),
    (f"{VE}.iso2631_5.lowpass_response", dict(frequency_Hz=[-1.0]), "frequency_Hz"),
    (f"{VE}.iso2631_5.band_response", dict(frequency_Hz=[NAN]), "frequency_Hz"),
    (f"{VE}.iso2631_5.spine_and_lowpass", dict(frequency_Hz=[NAN]), "frequency_Hz"),
    (f"{VE}.iso2631_5.highpass_sos", dict(fs_Hz=0.0), "fs_Hz"),
    (f"{VE}.iso2631_5.regime_band_sos", dict(fs_Hz=-FS), "fs_Hz"),
    (f"{VE}.iso2631_5.band_limited", dict(seat_z_m_s2=[1.0, NAN], fs_Hz=FS), "seat_z_m_s2"),
    (f"{VE}.iso2631_5.contact_regime", dict(seat_z_m_s2=SINE, fs_Hz=0.0), "fs_Hz"),
    # vehicle/lti.py
    (f"{VE}.lti.discretise", dict(a=-np.eye(1), b=np.eye(1), c=np.eye(1), d=np.zeros((1, 1)), dt_s=0.0), "dt_s"),
    # vehicle/measured_ride.py
    (f"{VE}.measured_ride.analyse_recording", dict(recording="seat.csv"), "recording"),
    (f"{VE}.measured_ride.analyse_signals", dict(signals={"seat_z_m_s2": SINE}, fs_Hz=0.0), "fs_Hz"),
    # vehicle/metrics.py
    (f"{VE}.metrics.rms", dict(x=[1.0, NAN]), "x"),
    (f"{VE}.metrics.acceleration_psd", dict(x=SINE, fs_Hz=0.0), "fs_Hz"),
    (f"{VE}.metrics.band_rms", dict(f_Hz=[1.0, 2.0], psd=[1.0, 1.0], f_low_Hz=5.0, f_high_Hz=1.0), "f_low_Hz"),
    (f"{VE}.metrics.spectral_peak", dict(f_Hz=[1.0, 2.0], psd=[1.0, 1.0], f_low_Hz=-1.0), "f_low_Hz"),
    (f"{VE}.metrics.spectral_peaks", dict(f_Hz=[1.0, 2.0], psd=[1.0, 1.0], n_peaks=0), "n_peaks"),
    (f"{VE}.metrics.envelope", dict(x=SINE, fs_Hz=FS, centre_Hz=4.0, cutoff_Hz=0.0), "cutoff_Hz"),
    (f"{VE}.metrics.envelope_similarity", dict(env_x=SINE, env_y=SINE, fs_Hz=0.0), "fs_Hz"),
    (f"{VE}.metrics.envelope_error", dict(env_predicted=SINE, env_measured=[NAN]), "env_measured"),
    (f"{VE}.metrics.compare_records", dict(predicted=SINE, measured=SINE, fs_Hz=FS, bandwidth_Hz=0.0), "bandwidth_Hz"),
    (f"{VE}.metrics.ratio_error_statistics", dict(ratios=[1.0, 1.1], tolerances=(0.1, -0.3)), "tolerances"),
    (f"{VE}.metrics.accuracy_table", dict(comparisons=lambda: pd.DataFrame({"x": [1.0]}), by="characteristics"), "comparisons"),
    # vehicle/model.py
    (f"{VE}.model.assemble", dict(parts="tractor"), "parts"),
    (f"{VE}.model.coordinate_output", dict(name=None), "name"),
    (f"{VE}.published_layouts.tractor_axles_si", dict(row={}), "row"),
    (f"{VE}.model.needs", dict(part="wheel"), "part"),
    (f"{VE}.model.scenario_key", dict(field_name=None), "field_name"),
    (f"{VE}.elements.element", dict(name="e", g=[1.0], stiffness=1.0, damping=1.0, model="coulomb"), "model"),
    # vehicle/crg.py, road_class.py, tyre/lateral.py (issue 33)
    ("tyrelab.tyre.lateral.estimate_lateral_stiffness", dict(vertical_stiffness_kN_per_m=-1.0), "vertical_stiffness_kN_per_m"),
    # tyre/rolling.py (issue 42)
    ("tyrelab.tyre.rolling.series_damping_N_s_per_m", dict(a_kN_s_per_m_km_h=NAN, speed_km_h=8.0), "a_kN_s_per_m_km_h"),
    ("tyrelab.tyre.rolling.series_damping_N_s_per_m", dict(a_kN_s_per_m_km_h=-100.0, speed_km_h=8.0), "a_kN_s_per_m_km_h"),
    ("tyrelab.tyre.rolling.series_damping_N_s_per_m", dict(a_kN_s_per_m_km_h=100.0, speed_km_h=-1.0), "speed_km_h"),
    ("tyrelab.tyre.rolling.estimate_series_damping", dict(direction="vertical"), "direction"),
    ("tyrelab.tyre.directional.rolling_coefficients", dict(direction="vertical", pressure_bar=1.0, speeds_km_h=[8.0]),
     "direction"),
    ("tyrelab.tyre.directional.rolling_coefficients", dict(direction="lateral", pressure_bar=NAN, speeds_km_h=[8.0]),
     "pressure_bar"),
    ("tyrelab.tyre.directional.rolling_coefficients", dict(direction="lateral", pressure_bar=1.0, speeds_km_h=[8.0],
                                                           given={"series_damping_kN_s_per_m_km_h": "x"},
                                                           vertical_stiffness_kN_per_m=400.0,
                                                           vertical_damping_kN_s_per_m=1.5),
     "given"),
    (f"{VE}.crg.wheel_positions", dict(lateral_offset_m=NAN, front_track_m=1.8, rear_track_m=1.9), "lateral_offset_m"),
    (f"{VE}.crg.wheel_positions", dict(lateral_offset_m=0.0, front_track_m=-1.8, rear_track_m=1.9), "front_track_m"),
    (f"{VE}.crg.crg_problems", dict(data=None, positions={}, start_m=0.0, length_m=None), "data"),
    (f"{VE}.crg.wheel_tracks", dict(data=None, positions={}), "data"),
    (f"{VE}.road_class.class_of", dict(g0_m3=-1e-6), "g0_m3"),
    (f"{VE}.road_class.road_class", dict(elevation_m=SINE, dx_m=0.0), "dx_m"),
    (f"{VE}.road_class.road_class", dict(elevation_m=[0.0] * 4, dx_m=0.05), "elevation_m"),
    (f"{VE}.run.track.crg_profile", dict(scenario=None), "scenario"),
    (f"{VE}.run.track.road_classes", dict(profile=None), "profile"),
    (f"{VE}.profiles.uniform_grid", dict(x_m=[0.0, NAN, 1.0]), "x_m"),
    # vehicle/profiles.py
    (f"{VE}.profiles.spectral_synthesis", dict(n_samples=100, dx_m=0.05, g0_m3=-1e-4, rng=lambda: np.random.default_rng(1)), "g0_m3"),
    (f"{VE}.profiles.slatted_track", dict(length_m=0.0), "length_m"),
    (f"{VE}.profiles.slat_surface", dict(track=_slatted, side="middle"), "side"),
    (f"{VE}.profiles.slat_surface", dict(track=None), "track"),
    (f"{VE}.profiles.iso8608_track", dict(dx_m=0), "dx_m"),
    (f"{VE}.profiles.iso8608_track", dict(length_m=-1), "length_m"),
    (f"{VE}.profiles.isotropic_coherence", dict(n_cycles_per_m=[0.1], track_width_m=0.0), "track_width_m"),
    (f"{VE}.profiles.profile_spectrum", dict(elevation_m=SINE, dx_m=0.05, segment_m=0.0), "segment_m"),
    (f"{VE}.profiles.profile_spectrum", dict(elevation_m=SINE, dx_m=0.05, detrend="quadratic"), "detrend"),
    (f"{VE}.profiles.side_spectra", dict(left_m=SINE, right_m=SINE, dx_m=0.05, segment_m=0.0), "segment_m"),
    (f"{VE}.profiles.add_lead_in", dict(profile=_slatted, lead_in_m=-5.0), "lead_in_m"),
    # vehicle/published_layouts.py
    (f"{VE}.published_layouts.carriage_rolling", dict(xii=pd.DataFrame({"x": [1]})), "xii"),
    (f"{VE}.published_layouts.carriage_stationary", dict(xii=None), "xii"),
    (f"{VE}.published_layouts.carriage_accuracy", dict(table=pd.DataFrame()), "table"),
    (f"{VE}.published_layouts.tractor_mass", dict(xv=pd.DataFrame()), "xv"),
    (f"{VE}.published_layouts.tractor_tyres", dict(xvi="table_xvi.csv"), "xvi"),
    (f"{VE}.published_layouts.tractor_accuracy", dict(xvii=pd.DataFrame()), "xvii"),
    (f"{VE}.published_layouts.longitudinal_sweep", dict(xviii=pd.DataFrame()), "xviii"),
    (f"{VE}.published_layouts.tractors", dict(xix=pd.DataFrame()), "xix"),
    # vehicle/ride.py
    (f"{VE}.tyres.per_speed", dict(values=[1.0, 2.0], list_speeds_km_h=[4.0], speeds_km_h=[4.0, 8.0]), "values"),
    (f"{VE}.tyres.resolve_tyres", dict(scenario="modern.toml"), "scenario"),
    (f"{VE}.tyres.build_parts", dict(scenario=_scenario, tyres={}, i=-1), "i"),
    (f"{VE}.tyres.static_tyre_loads", dict(asm="tractor"), "asm"),
    (f"{VE}.tyres.scenario_fits", dict(scenario=None, tables={}), "scenario"),
    (f"{VE}.run.track.wheel_inputs", dict(tyres=("front", "rear"), three_d=False, track=None, kind="none", footprints=(0.3, 0.4), radii=(0.6, 0.8), speed_m_s=1.0, wheelbase_m=2.5, n_steps=10), "track"),
    (f"{VE}.scenario.variants.sweep_variants", dict(scenario="modern.toml"), "scenario"),
    (f"{VE}.run.track.tyre_inputs", dict(asm=None, track=None, kind="none", footprints=(0.3, 0.4), radii=(0.6, 0.8), speed_m_s=1.0, wheelbase_m=2.5, n_steps=10), "asm"),
    (f"{VE}.run.pitch_plane.state_names", dict(tractor=None), "tractor"),
    (f"{VE}.run.pitch_plane.state_space", dict(tractor="tractor"), "tractor"),
    (f"{VE}.run.spectral.frequency_response", dict(a=-np.eye(1), b=np.eye(1), c=np.eye(1), d=np.zeros((1, 1)), frequency_Hz=[NAN]), "frequency_Hz"),
    (f"{VE}.run.spectral.enveloping_response", dict(kind="soft", footprint_m=0.3, dx_m=0.05, n_cycles_per_m=[0.1]), "kind"),
    (f"{VE}.run.track.build_profile", dict(scenario=None), "scenario"),
    (f"{VE}.run.track.axle_inputs", dict(track=_slatted, kind="none", footprints=(0.3, 0.4), radii=(0.6, 0.8), speed_m_s=-1.0, wheelbase_m=2.5, n_steps=10), "speed_m_s"),
    (f"{VE}.run.rows.exposure", dict(a_wz_m_s2=0.5, a_wx_m_s2=0.3, hours_per_day=NAN), "hours_per_day"),
    (f"{VE}.run.plan.seat_axes", dict(scenario={}), "scenario"),
    (f"{VE}.run.plan.modes", dict(asm="tractor"), "asm"),
    (f"{VE}.run.spectral.input_cross_spectra", dict(tyres=["front", "rear"], side_spectrum=None, f_Hz=[1.0], v=0.0, wheelbase_m=2.5), "v"),
    (f"{VE}.ride.ride", dict(scenario="modern.toml"), "scenario"),
    (f"{VE}.ride.ride_sweep", dict(scenario=_scenario, max_variants=0), "max_variants"),
    (f"{VE}.run.time.ride_variants", dict(scenarios=["modern.toml"]), "scenarios"),
    (f"{VE}.run.frequency.spectral_variants", dict(scenarios=["modern.toml"]), "scenarios"),
    (f"{VE}.run.time.ride_variants", dict(scenarios=lambda: [_scenario()], a8_interval=[True, False]), "a8_interval"),
    (f"{VE}.run.frequency.spectral_variants", dict(scenarios=lambda: [_scenario()], a8_interval=[]), "a8_interval"),
    (f"{VE}.ride.ride_sweep", dict(scenario=_scenario, method="fast"), "method"),
    (f"{VE}.run.sweep.expected_sweep", dict(scenario="modern.toml", front_pressures_bar=[1.0], rear_pressures_bar=[1.0]), "scenario"),
    (f"{VE}.run.sweep.expected_sweep", dict(scenario=_scenario, front_pressures_bar=[], rear_pressures_bar=[1.0]), "front_pressures_bar"),
    (f"{VE}.run.spectral.expected_weighted_rms", dict(a=np.zeros((1, 2, 2)), b=np.zeros((1, 2, 4)), c=np.zeros((1, 1, 2)), d=np.zeros((1, 1, 3)), tyres=["front", "rear"], grid={}, env={}, seat_tf=None, axes=["z"]), "a"),
    (f"{VE}.run.spectral.expected_weighted_rms", dict(a=np.zeros((1, 2, 2)), b=np.zeros((1, 2, 4)), c=np.zeros((1, 1, 2)), d=np.zeros((1, 1, 4)), tyres=["front", "rear"], grid={}, env={}, seat_tf=None, axes=["z"], chunk=0), "chunk"),
    (f"{VE}.run.output.result_json", dict(results=[]), "results"),
    (f"{VE}.run.output.results_table", dict(results=[None]), "results"),
    # vehicle/ride_validation.py
    (f"{VE}.ride_validation.track_of", dict(text=3), "text"),
    (f"{VE}.ride_validation.predicted_seat", dict(scenario=_scenario, speed_km_h=-4.0, track=None), "speed_km_h"),
    (f"{VE}.ride_validation.validation_rows", dict(measured=None, predicted_signals={}, predicted_fs_Hz=FS, known_profile=False), "measured"),
    (f"{VE}.ride_validation.validation_statistics", dict(rows=[1, 2]), "rows"),
    # vehicle/scenario.py
    ("tyrelab.scenario_io.load_scenario", dict(path=3), "path"),
    (f"{VE}.scenario.parse.parse_scenario", dict(text=b"name = 1"), "text"),
    ("tyrelab.scenario_io.read_profile_csv", dict(path=3), "path"),
    (f"{VE}.scenario.variants.with_overrides", dict(scenario=_scenario, front_pressure_bar=-1.0), "front_pressure_bar"),
    (f"{VE}.scenario.variants.with_values", dict(scenario="modern.toml", values={"tractor.mass_kg": 2.0}), "scenario"),
    (f"{VE}.scenario.parse.numeric_key", dict(key=3), "key"),
    (f"{VE}.scenario.variants.parse_sets", dict(items=[("tractor.mass_kg", 1.0)]), "items"),
    (f"{VE}.scenario.parse.scenario_from_dict", dict(doc=None), "doc"),
    (f"{VE}.daily_exposure.governing_axis", dict(k_a_w_m_s2=None), "k_a_w_m_s2"),
    # vehicle/scenario_limits.py
    (f"{VE}.scenario.limits.work_estimate", dict(scenario=_scenario, n_variants=0), "n_variants"),
    (f"{VE}.scenario.limits.bound_argument", dict(name="max_rows", value=10**400), "max_rows"),
    # vehicle/modes.py
    (f"{VE}.modes.mode_set", dict(asm="tractor"), "asm"),
    (f"{VE}.modes.mac_matrix", dict(reference=None, other=None), "reference"),
    (f"{VE}.modes.frequency_intervals", dict(asm="tractor", u_front_tyre_kN_per_m=1.0, u_rear_tyre_kN_per_m=1.0), "asm"),
    (f"{VE}.modes.follow_names", dict(reference=None, other=None), "reference"),
    (f"{VE}.modes.damped_modes", dict(asm="tractor"), "asm"),
    (f"{VE}.modes.follow_damped", dict(reference=None, other={}), "reference"),
    (f"{VE}.modes.follow_renamed", dict(reference=None, other={}), "reference"),
    (f"{VE}.solvers.roots.root_sensitivities", dict(a=[[0.0, 1.0], [-1.0, NAN]], modes={}, da=np.zeros((2, 2)), step=1.0), "a"),
    (f"{VE}.solvers.roots.root_sensitivities", dict(a=np.eye(2), modes={}, da=np.zeros((3, 3)), step=1.0), "da"),
    (f"{VE}.solvers.roots.root_sensitivities", dict(a=np.eye(2), modes=[], da=np.zeros((2, 2)), step=1.0), "modes"),
    (f"{VE}.solvers.roots.root_sensitivities", dict(a=np.eye(2), modes={}, da=np.zeros((2, 2)), step=0.0), "step"),
    # vehicle/sweeps.py
    (f"{VE}.scenario.variants.pressure_axes", dict(scenario="modern.toml", front_pressures_bar=None, rear_pressures_bar=None, keys={}), "scenario"),
    (f"{VE}.scenario.variants.unused_key_problems", dict(scenario=None, keys=[]), "scenario"),
    (f"{VE}.scenario.limits.uses_spectral", dict(scenario=_scenario, method="fast", n_variants=2), "method"),
    # vehicle/spectral_ride.py
    (f"{VE}.spectral_ride.lift_off_probability", dict(static_load_N=1e4, force_sd_N=[-1.0]), "force_sd_N"),
    (f"{VE}.spectral_ride.at_own_values", dict(scenario="modern.toml", variant=None, combo={}), "scenario"),
    (f"{VE}.spectral_ride.nominal_index", dict(scenario="modern.toml", variants=[]), "scenario"),
    (f"{VE}.spectral_ride.spectral_row", dict(speed_km_h=8.0, tyres={}, i=0, aw_m_s2={"z": 1.0}, axes=["z"], hours_per_day=8.0, duration_s=10.0, force_sd_N={"front": -1.0, "rear": 1.0}, static_load_N={"front": 1e4, "rear": 1e4}, tyres_per_element=2, exposure={}), "force_sd_N"),
    (f"{VE}.spectral_ride.lifting_speeds", dict(rows=None), "rows"),
    (f"{VE}.spectral_ride.primary_rows", dict(table=None), "table"),
    # vehicle/studies.py
    (f"{VE}.studies.carriage_case_inputs", dict(table_xii=None, stationary=pd.DataFrame()), "table_xii"),
    (f"{VE}.studies.carriage_study", dict(table_xii=pd.DataFrame(), stationary=pd.DataFrame(), seed=-1), "seed"),
    (f"{VE}.studies.tractor_case_inputs", dict(table_xv=pd.DataFrame(), table_xvi=pd.DataFrame(), farm_class="Z"), "farm_class"),
    (f"{VE}.studies.longitudinal_grid", dict(table_xviii="table_xviii.csv"), "table_xviii"),
    (f"{VE}.studies.tractor_study", dict(table_xv=pd.DataFrame(), table_xvi=pd.DataFrame(), duration_s=0.0), "duration_s"),
    (f"{VE}.studies.carriage_key", dict(row={"speed_km_h": "fast", "load_condition": "heavy"}), "row"),
    (f"{VE}.studies.tractor_key", dict(row={"load_condition": 1, "track": "road", "speed_km_h": 10}), "row"),
    (f"{VE}.studies.run_metrics", dict(label={}, profile="p", vertical_m_s2=[0.0, NAN], pitch_rad_s2=None,
                                       longitudinal_m_s2=None), "vertical_m_s2"),
    (f"{VE}.studies.with_tractor_recordings", dict(study={"runs": pd.DataFrame()}, recordings=None), "study"),
    # vehicle/study_recordings.py
    (f"{VE}.study_recordings.carriage_recordings", dict(table_xii=pd.DataFrame(), stationary=pd.DataFrame(),
                                                         surface_stiffness_factor=0.0), "surface_stiffness_factor"),
    (f"{VE}.study_recordings.tractor_recordings", dict(table_xv=pd.DataFrame(), table_xvi=pd.DataFrame(),
                                                        farm_class="Z"), "farm_class"),
    (f"{VE}.study_recordings.study_recordings", dict(pub={"table_xii": None}, seed=1), "pub"),
    # vehicle/tractor.py
    (f"{VE}.tractor.tractor_parts", dict(tractor=None), "tractor"),
    (f"{VE}.tractor.simulate", dict(assemblies=lambda: [_assembly()], u_half=np.zeros((2, 3)), du_half=np.zeros((2, 3)), dt_s=0.0), "dt_s"),
    (f"{VE}.tractor.simulate_tractor", dict(tractor=_tractor, front_half=[0.0] * 3, front_rate_half=[0.0] * 3, rear_half=[0.0] * 3, rear_rate_half=[0.0] * 3, dt_s=0), "dt_s"),
    # vehicle/virtual_rides.py
    (f"{VE}.virtual_rides.ride_plan", dict(scenarios=["modern.toml"]), "scenarios"),
    (f"{VE}.virtual_rides.virtual_recordings", dict(scenario=_scenario, key="modern", seed=-1), "seed"),
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


# --- every public function of tyre/ and vehicle/ has a row (issue 28) ------------------------------------
#: Packages whose every public function (``__all__`` of each module) needs a row in :data:`ROWS`.
CHECKED_PACKAGES = ("tyrelab.tyre", "tyrelab.vehicle")
#: ... and modules of the package that those use (the units moved below every package: issue 45).
CHECKED_MODULES = ("tyrelab.units",)

#: Public functions of those packages with no argument a caller can get wrong, each with the reason.
EXEMPT: dict[str, str] = {
    "tyrelab.vehicle.run.time.fast_element_problems": "returns its arguments' problems as lines, by design",
    "tyrelab.vehicle.scenario.limits.long_integer_problems": "returns its argument's problems as lines, by design",
    "tyrelab.vehicle.scenario.limits.track_length_m": "reads a parsed scenario's surface (checked where it is parsed)",
    "tyrelab.vehicle.scenario.parse.key_table": "takes no argument",
    "tyrelab.vehicle.model.cab_mount_problems": "returns its arguments' problems as lines, by design",
    "tyrelab.vehicle.model.pivot_problem": "writes the pivot rule's line for a section name (any text)",
    "tyrelab.units.from_kilo": "a unit conversion of any number or array (numpy's arithmetic): nothing to refuse",
    "tyrelab.units.to_kilo": "a unit conversion of any number or array (numpy's arithmetic): nothing to refuse",
    "tyrelab.units.km_h_to_m_s": "a unit conversion of any number or array (numpy's arithmetic): nothing to refuse",
    "tyrelab.units.m_s_to_km_h": "a unit conversion of any number or array (numpy's arithmetic): nothing to refuse",
    # these check arguments for a living: every problem is a returned line, so that a caller prints them all
    # at once (tyrelab ride); each line names the key and the bound (doctests of vehicle/scenario_limits.py)
    "tyrelab.vehicle.scenario.limits.scenario_problems": "returns its argument's problems as lines, by design",
    "tyrelab.vehicle.scenario.limits.override_problems": "returns its arguments' problems as lines, by design",
    "tyrelab.vehicle.scenario.limits.profile_problems": "returns its arguments' problems as lines, by design",
    "tyrelab.vehicle.scenario.limits.work_problems": "returns its arguments' problems as lines, by design",
    "tyrelab.vehicle.daily_exposure.hours_problem": "returns its argument's problem as a line, by design (doctest)",
    "tyrelab.vehicle.solvers.time_domain.off_ground": "an elementwise comparison of arrays the solver made, by design (doctest)",
}


def _public_functions() -> list[str]:
    import inspect
    import pkgutil

    out = set()
    names = [info.name for package in CHECKED_PACKAGES  # and their sub-packages (issue 45: vehicle/ in layers)
             for info in pkgutil.walk_packages(importlib.import_module(package).__path__, f"{package}.")]
    for module_name in [*names, *CHECKED_MODULES]:
        module = importlib.import_module(module_name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if inspect.isfunction(obj) and obj.__module__ == module.__name__:
                out.add(f"{module.__name__}.{name}")
    return sorted(out)


def _home(path: str) -> str:
    """A row's or exemption's function by the module that defines it: a module moved to a
    sub-package keeps its old import path (the same module), and a row may use either."""
    module, _, name = path.rpartition(".")
    try:
        obj = getattr(importlib.import_module(module), name)
    except (ImportError, AttributeError):
        return path
    return f"{obj.__module__}.{name}" if getattr(obj, "__module__", None) else path


def test_every_public_function_of_tyre_and_vehicle_has_a_row():
    public = set(_public_functions())
    rows = {_home(path) for path, _, _ in ROWS}
    exempt = {_home(path) for path in EXEMPT}
    missing = sorted(public - rows - exempt)
    assert not missing, f"{len(missing)} public functions without a row in ROWS (or a reason in EXEMPT): {missing}"
    stale = sorted(exempt - public) + sorted(exempt & rows)
    assert not stale, f"EXEMPT names functions that are not public or have rows: {stale}"
