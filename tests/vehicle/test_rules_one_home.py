"""Issue 45, Deliver 2: each rule of the vehicle's in one home, and a test that fails if a twin drifts.

- enveloping: the spectral ride's transfer function of a linear enveloping filter is that of the
  taps the filter itself averages with (:func:`tyrelab.vehicle.terrain.enveloping.window`);
- the 3-D tracks' spectra: the side spectra a 3-D run reads are :mod:`tyrelab.vehicle.terrain.profiles`'
  Welch estimates;
- lift-off: the time-domain solver's switch to RK4 and the ride's lift-off fraction judge a tyre off
  the ground by one rule (:func:`tyrelab.vehicle.solvers.time_domain.off_ground`);
- axis -> frequency weighting: one table (:data:`tyrelab.vehicle.comfort.iso2631.AXIS_WEIGHTING`)
  that the spectral ride, the measured recordings and ISO 2631-1's evaluation read.
"""

import numpy as np
import pytest

from tyrelab.vehicle.terrain import enveloping as ev


@pytest.mark.parametrize("kind, filt", [("fixed", ev.fixed_footprint), ("tapered", ev.tapered_moving_average)])
def test_the_spectral_enveloping_response_is_the_filter_s_own_gain(kind, filt):
    """A cosine of wavenumber n through the filter comes out times its transfer function H(n) (the
    taps are symmetric: H is real). A window written twice (a taper, a length rounded otherwise)
    would give another gain: 0.4 % at n = 0.9 cycles/m for a 1.25 that became 1.2."""
    from tyrelab.vehicle.run.spectral import enveloping_response

    dx, footprint = 0.01, 0.37
    x = np.arange(4000) * dx
    for n in (0.3, 0.9, 1.7):
        h = np.cos(2 * np.pi * n * x)
        out = filt(h, dx, footprint)
        gain = enveloping_response(kind, footprint, dx, [n])[0]
        mid = slice(200, -200)  # away from the padded ends
        np.testing.assert_allclose(out[mid], gain * h[mid], rtol=0, atol=1e-12)
        assert abs(gain) < 1.0  # the footprint averages: a real low-pass, not 1 by default


def test_the_window_is_the_one_both_filters_average_with():
    dx, footprint = 0.02, 0.5
    impulse = np.zeros(301)
    impulse[150] = 1.0
    for kind, filt in (("fixed", ev.fixed_footprint), ("tapered", ev.tapered_moving_average)):
        taps = ev.window(kind, footprint, dx)
        k = taps.size // 2
        np.testing.assert_array_equal(filt(impulse, dx, footprint)[150 - k:151 + k], taps[::-1])
    assert ev.window("tapered", footprint, dx).size == int(round(footprint * (1 + ev.TAPER_FRACTION / 2) / dx)) | 1


def test_the_side_spectra_are_the_profiles_welch():
    """No Welch of a profile outside terrain/profiles.py (the recordings' acceleration spectra are
    comfort/'s): a second one would drift in its detrend, window or segments. And the 3-D ride's
    side spectra are :func:`~tyrelab.vehicle.terrain.profiles.side_spectra` of its tracks."""
    import ast
    from pathlib import Path

    import tyrelab.vehicle
    from tyrelab.vehicle.terrain import profiles as pr

    root = Path(tyrelab.vehicle.__file__).parent
    homes = {"terrain/profiles.py", "comfort/metrics.py", "comfort/measured_ride.py"}
    found = []
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root).as_posix()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                    and node.func.attr in ("welch", "csd") and rel not in homes):
                found.append(f"{rel}:{node.lineno}")
    assert not found, f"a Welch spectrum outside its homes: {found}"
    rng = np.random.default_rng(4)
    left, right = rng.standard_normal(2048), rng.standard_normal(2048)
    n, g_ll, g_rr, g_lr = pr.side_spectra(left, right, 0.05, 12.8)
    n2, g = pr.profile_spectrum(left, 0.05, 12.8, detrend="constant")
    np.testing.assert_array_equal(n, n2)
    np.testing.assert_array_equal(g_ll, g)
    # E[L R*]: with R a copy of L delayed by one sample, the phase of G_LR is +2 pi n dx (L leads)
    _, _, _, g_lag = pr.side_spectra(left[1:], left[:-1], 0.05, 12.8)
    k = 20
    assert np.angle(g_lag[k]) == pytest.approx(2 * np.pi * n[k] * 0.05, abs=0.05)


def test_one_lift_off_rule_for_the_solver_and_the_ride():
    """A run whose linear tyre force comes within LIFT_OFF_RTOL of pulling (not beyond) is off the
    ground for the ride's lift-off fraction and for the solver's switch alike: it leaves the exact
    path. With two rules (the solver's exact ``<=`` against the ride's tolerance) the solver would
    keep it exact while the ride counted a lift-off."""
    from tyrelab.vehicle.model import assemble
    from tyrelab.vehicle.run import time as ride_time
    from tyrelab.vehicle.solvers import time_domain as td
    from tyrelab.vehicle.tractor import Tractor, tractor_parts

    assert ride_time.off_ground is td.off_ground and ride_time.LIFT_OFF_RTOL is td.LIFT_OFF_RTOL
    asm = assemble(tractor_parts(Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3)))
    n = 801
    t = np.arange(2 * n - 1) * 5e-4
    bump = np.where(t < 0.1, np.sin(np.pi * t / 0.1) ** 2, 0.0)  # a 1 m bump under both axles, 0.1 s
    rate = np.gradient(bump, 5e-4)
    u, du = np.stack([bump, bump])[None], np.stack([rate, rate])[None]
    unit = td.simulate([asm], u, du, 1e-3, lift_off=False, record=("front_force_N", "rear_force_N"))
    static = asm.static_tyre_loads_N()
    # scale the bump so that the deepest dip of the front force is minus its static load less half the tolerance
    j = int(np.argmin(unit["front_force_N"][0]))
    scale = -static["front"] * (1 - td.LIFT_OFF_RTOL / 2) / unit["front_force_N"][0, j]
    assert scale > 0 and (unit["rear_force_N"][0] * scale > -static["rear"] * (1 - td.LIFT_OFF_RTOL)).all()
    forces = td.simulate([asm], scale * u, scale * du, 1e-3, lift_off=False, record=("front_force_N",))
    assert td.off_ground(forces["front_force_N"][0], static["front"]).any()
    assert not (forces["front_force_N"][0] <= -static["front"]).any()  # never quite pulls
    switched = td.simulate([asm], scale * u, scale * du, 1e-3, lift_off=True, record=("front_force_N",))
    assert switched["method_used"][0] == "exact+rk4"


def test_one_table_of_axis_weightings():
    from tyrelab.vehicle.comfort import iso2631, measured_ride
    from tyrelab.vehicle.run import spectral

    assert iso2631.AXIS_WEIGHTING == {"x": "Wd", "y": "Wd", "z": "Wk"}  # ISO 2631-1 §8.2.3, Table 1
    assert spectral.AXIS_WEIGHTING is iso2631.AXIS_WEIGHTING
    for channel, (weighting, axis) in measured_ride.WEIGHTING_OF.items():
        assert weighting == iso2631.AXIS_WEIGHTING[axis] and channel.split("_")[1] == axis
    for axis, weighting in iso2631.AXIS_WEIGHTING.items():
        assert iso2631.evaluate(np.sin(np.arange(2000) / 50.0), 100.0, axis)["weighting"] == weighting


def test_one_home_for_the_hours_to_the_daily_values():
    """The ride's rows and the daily exposure give the same hours for the same A(8) (one function)."""
    from tyrelab.vehicle.comfort import daily_exposure as de
    from tyrelab.vehicle.comfort import iso2631
    from tyrelab.vehicle.run import rows

    assert "_hours_to" not in vars(de)
    day = de.daily_exposure([de.TaskExposure("one", 8.0, {"z": 0.7}, {"z": 9.0}, 600.0)])
    assert day["hours_to_eav"] == de.hours_to(iso2631.EU_ACTION_A8_M_S2, 0.7, 8.0) == 8.0 * (0.5 / 0.7) ** 2
    assert rows.de.hours_to is de.hours_to


def test_the_scenario_s_limits_read_the_daily_exposure_s():
    from tyrelab.vehicle.comfort import daily_exposure as de
    from tyrelab.vehicle.scenario import limits

    low, high, _ = limits.LIMITS["exposure.hours_per_day"]
    assert (low, high) == (de.MIN_HOURS_PER_DAY, de.MAX_HOURS_PER_DAY)
    assert limits.MIN_VERDICT_DURATION_S == de.MIN_RECORD_S


def test_the_ch7_study_builds_its_wheel_inputs_with_the_ride_s_one_construction():
    """The study's axle inputs are :func:`~tyrelab.vehicle.run.track.wheel_inputs` (pitch plane) with
    the study's enveloping, at the ride's time step; checked against the construction by hand (the
    axle mean of the enveloped tracks under each axle, the front a wheelbase ahead, the start's
    offset removed)."""
    from tyrelab.vehicle import studies
    from tyrelab.vehicle.run import track
    from tyrelab.vehicle.terrain import profiles as pr
    from tyrelab.vehicle.terrain.wheel_inputs import half_step_input

    assert studies.DT_S == track.DT_S
    prof = pr.iso8608_track("C", seed=3, length_m=60.0, dx_m=0.05)
    radii, footprints, v, wb, n = {"front": 0.4, "rear": 0.0}, {"front": 0.25, "rear": 0.45}, 3.0, 2.4, 4001
    got = studies.tractor_inputs(prof, radii, footprints, v, wb, n)
    dx = prof.dx_m
    by_hand = []
    for axle, offset in (("front", wb), ("rear", 0.0)):
        sides = [ev.tapered_moving_average(ev.rigid_tread_band(prof.track(s), dx, radii[axle]) if radii[axle]
                                           else prof.track(s), dx, footprints[axle]) for s in ("left", "right")]
        by_hand.append(half_step_input(prof.x_m, 0.5 * (sides[0] + sides[1]), v, n, x_start_m=offset, dt_s=1e-3))
    (uf, udf), (ur, udr) = by_hand
    u0 = 0.5 * (uf[0] + ur[0])
    for a, b in zip(got, (uf - u0, udf, ur - u0, udr)):
        np.testing.assert_array_equal(a, b)


def test_a_name_two_modules_export_means_one_thing():
    """``METHODS`` was the time domain's integrators in ``tractor`` and the ride's methods in
    ``scenario_limits``; ``LONGITUDINAL_MODELS`` the twelve-number tractor's and the assembled
    axle's (with ``rolling``). Each meaning has its own name now; a name two modules of a package
    export (``__all__``) must be one object, or ``tyrelab.vehicle.<name>`` cannot tell which."""
    import importlib

    from tyrelab import _lazy

    packages = ["tyrelab.vehicle"] + [f"tyrelab.vehicle.{p}" for p in ("model", "terrain", "comfort", "solvers", "scenario",
                                                                        "run", "studies", "validation")]
    twins = []
    for package in packages:
        for name, subs in _lazy.collisions(package).items():
            objects = [getattr(importlib.import_module(f"{package}.{s}"), name) for s in subs]
            if any(o is not objects[0] for o in objects):
                twins.append(f"{package}: {name} in {subs}")
    assert not twins, "one name, two meanings: " + "; ".join(twins)


def test_the_old_names_of_the_split_meanings_still_import():
    from tyrelab.vehicle import scenario_limits, tractor
    from tyrelab.vehicle.model import AXLE_LONGITUDINAL_MODELS, parts
    from tyrelab.vehicle.scenario.limits import RIDE_METHODS
    from tyrelab.vehicle.solvers.time_domain import INTEGRATION_METHODS

    assert tractor.METHODS is tractor.INTEGRATION_METHODS is INTEGRATION_METHODS == ("auto", "rk4")
    assert scenario_limits.METHODS is RIDE_METHODS == ("auto", "time", "spectral")
    assert tractor.LONGITUDINAL_MODELS is tractor.TRACTOR_LONGITUDINAL_MODELS == ("none", "kelvin_voigt", "maxwell")
    assert parts.LONGITUDINAL_MODELS is AXLE_LONGITUDINAL_MODELS == ("none", "kelvin_voigt", "maxwell", "rolling")


def test_one_simulation_step_for_the_ride_and_the_studies():
    from tyrelab.vehicle.run import records, track
    from tyrelab.vehicle.studies import shared

    assert shared.DT_S is track.DT_S and records.DT_S is track.DT_S and shared.FS_HZ is track.FS_HZ
