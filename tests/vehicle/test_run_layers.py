"""The ride in layers (issue 45): one row record, one wheel-input construction, the size of the files."""

from pathlib import Path

import numpy as np
import pytest

from tyrelab.resources import package_dir, scenarios_dir
from tyrelab.scenario_io import load_scenario
from tyrelab.vehicle import profiles as pr
from tyrelab.vehicle import ride
from tyrelab.vehicle.carriage import half_step_input
from tyrelab.vehicle.run import records, track
from tyrelab.vehicle.run.rows import SPECTRAL_ONLY, SpeedRow
from tyrelab.vehicle.scenario import with_overrides

#: The ``speeds`` columns of a time row, in order (``tyrelab ride``'s JSON before issue 45).
TIME_COLUMNS = [
    "speed_km_h", "front_pressure_bar", "rear_pressure_bar", "front_stiffness_kN_per_m", "rear_stiffness_kN_per_m",
    "front_damping_kN_s_per_m", "rear_damping_kN_s_per_m", "a_wz_m_s2", "a_wx_m_s2", "a_wy_m_s2",
    "expected_a_wz_m_s2", "expected_a_wx_m_s2", "expected_a_wy_m_s2", "vdv_m_s1_75", "vdv_daily_m_s1_75",
    "crest_factor", "mtvv_m_s2", "lift_off_fraction_front", "lift_off_fraction_rear", "a_v_m_s2", "a8_m_s2",
    "a8_axis", "hours_to_eav", "hours_to_elv", "verdict", "hours_per_day", "duration_s", "simulation", "method"]


def test_one_speed_row_gives_the_time_and_the_spectral_columns():
    sc = with_overrides(load_scenario(scenarios_dir() / "modern_tractor.toml"), [8.0])
    time_row = ride.ride(sc, with_spectra=False).speeds
    spectral = ride.spectral_variants([sc], with_spectra=False)[0].speeds
    assert list(time_row.columns) == TIME_COLUMNS
    assert [c for c in spectral.columns if c not in SPECTRAL_ONLY] == TIME_COLUMNS
    assert set(SPECTRAL_ONLY) <= set(spectral.columns)
    assert spectral.iloc[0]["a_wz_m_s2"] == pytest.approx(time_row.iloc[0]["expected_a_wz_m_s2"], rel=1e-12)
    assert [f for f in SpeedRow.__dataclass_fields__ if f not in SPECTRAL_ONLY] == TIME_COLUMNS


def _profile_with_rear_tracks() -> pr.Profile:
    rng = np.random.default_rng(45)
    x = np.arange(0.0, 40.0, 0.05)
    front_l, front_r, rear_l, rear_r = (np.cumsum(rng.normal(0, 1e-3, x.size)) for _ in range(4))
    return pr.Profile(x, front_l, front_r, "four tracks", {"kind": "crg"}, rear_l, rear_r)


def test_the_rear_wheels_run_on_the_rear_tracks_on_both_paths():
    """The exact linear path's cached wheel tracks (RideCache.envelope) and the RK4 path's
    (envelope_side) are one construction: a road with rear tracks of its own gives the rear wheels
    those tracks on both (before issue 45 the cached path put them on the front tracks)."""
    prof = _profile_with_rear_tracks()
    tyres = ("front_left", "front_right", "rear_left", "rear_right")
    fp, radii, v, wb, n = (0.3, 0.4), (0.6, 0.8), 3.0, 2.5, 4000
    cache = records.RideCache()
    cached = track.wheel_inputs(tyres, True, prof, "tapered", fp, radii, v, wb, n, half_steps=False,
                                enveloped=lambda side, axle, f, r: cache.envelope("k", prof, side, "tapered", f, r, axle))
    direct = track.wheel_inputs(tyres, True, prof, "tapered", fp, radii, v, wb, n, half_steps=False)
    np.testing.assert_array_equal(cached[0], direct[0])
    np.testing.assert_array_equal(cached[1], direct[1])
    half = track.wheel_inputs(tyres, True, prof, "tapered", fp, radii, v, wb, n)
    np.testing.assert_array_equal(half[0][:, ::2], direct[0])  # the full steps are every other half step
    # by hand: the rear left wheel on the rear left track, enveloped with the rear footprint
    from tyrelab.vehicle import enveloping as ev

    u_fl, _ = half_step_input(prof.x_m, ev.tapered_moving_average(prof.left_m, prof.dx_m, fp[0]), v, n, wb,
                              track.DT_S, half_steps=False)
    u_rl, _ = half_step_input(prof.x_m, ev.tapered_moving_average(prof.rear_left_m, prof.dx_m, fp[1]), v, n, 0.0,
                              track.DT_S, half_steps=False)
    u0 = 0.5 * (u_fl[0] + u_rl[0])
    np.testing.assert_allclose(direct[0][2], u_rl - u0, rtol=0, atol=1e-15)


def test_the_pitch_plane_inputs_are_the_axle_mean():
    prof = _profile_with_rear_tracks()
    u, du = track.wheel_inputs(("front", "rear"), False, prof, "none", (0.3, 0.4), (0.6, 0.8), 3.0, 2.5, 1000)
    uf, udf, ur, udr = track.axle_inputs(prof, "none", (0.3, 0.4), (0.6, 0.8), 3.0, 2.5, 1000)
    np.testing.assert_array_equal(u, [uf, ur])
    mean_rear, _ = half_step_input(prof.x_m, prof.track("mean", "rear"), 3.0, 1000, 0.0, track.DT_S)
    mean_front, _ = half_step_input(prof.x_m, prof.track("mean"), 3.0, 1000, 2.5, track.DT_S)
    np.testing.assert_allclose(ur, mean_rear - 0.5 * (mean_front[0] + mean_rear[0]), rtol=0, atol=1e-15)


def test_ride_runs_a_scenario_or_a_sweep_and_no_file_of_the_vehicle_is_long():
    root = Path(package_dir()) / "vehicle"
    assert len((root / "ride.py").read_text().splitlines()) <= 300
    paths = sorted(root.rglob("*.py"))
    assert len(paths) > 60 and root / "studies" / "carriage.py" in paths
    long = [f"{p.relative_to(root)}: {n}" for p in paths if (n := len(p.read_text().splitlines())) > 700]
    assert not long, long


def test_the_chapter_studies_live_in_studies_and_their_old_paths_are_the_same_modules():
    import importlib

    for name in ("carriage", "bounce_pitch", "study_recordings", "published_layouts", "virtual_rides"):
        old, new = (importlib.import_module(f"tyrelab.vehicle.{p}{name}") for p in ("", "studies."))
        assert old is new and new.__file__.endswith(f"studies/{name}.py"), name
