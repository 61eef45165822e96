"""Where a tyre's numbers come from (issue 45): the footprint takes the whole vehicle's static loads."""

import math

import numpy as np
import pytest

from tyrelab.resources import scenarios_dir
from tyrelab.scenario_io import load_scenario, parse_scenario
from tyrelab.vehicle import tyres
from tyrelab.vehicle.units import STANDARD_GRAVITY_M_S2 as GRAVITY_M_S2  # the assembly's gravity

IMPLEMENT = "\n[implement]\nmass_kg = 1200\nbehind_rear_axle_m = 1.2\nheight_m = 0.8\npitch_inertia_kg_m2 = 400\n"


def _modern(extra: str = ""):
    text = (scenarios_dir() / "modern_tractor.toml").read_text()
    return parse_scenario(text + extra)


def _contact_length(radius_m: float, deflection_m: float) -> float:
    """The chord of the tyre's circle at the static deflection, written out (not enveloping.contact_length)."""
    return 2.0 * math.sqrt(2.0 * radius_m * deflection_m - deflection_m**2)


def test_an_implement_changes_the_footprints():
    """The rear axle carries the implement (moments about the front axle, by hand), the front is unloaded:
    the footprints follow the static loads of the whole vehicle, not the tractor's mass alone."""
    bare, loaded = _modern(), _modern(IMPLEMENT)
    t = bare.tractor
    wb, g = t.wheelbase_m, GRAVITY_M_S2
    m_imp, behind = 1200.0, 1.2
    rear_axle_N = (t.mass_kg * g * t.front_distance_m + m_imp * g * (wb + behind)) / wb
    front_axle_N = (t.mass_kg + m_imp) * g - rear_axle_N
    for sc, (front_N, rear_N) in ((bare, (t.mass_kg * g * t.rear_distance_m / wb, t.mass_kg * g * t.front_distance_m / wb)),
                                  (loaded, (front_axle_N, rear_axle_N))):
        ty = tyres.resolve_tyres(sc)
        for axle, load_N in (("front", front_N / 2), ("rear", rear_N / 2)):
            k = ty[axle].stiffness_kN_per_m * 1e3
            want = [_contact_length(ty[axle].radius_m, load_N / kk) for kk in k]
            np.testing.assert_allclose(ty[axle].footprint_m, want, rtol=1e-12)
    before, after = tyres.resolve_tyres(bare), tyres.resolve_tyres(loaded)
    assert after["rear"].footprint_m[0] > 1.2 * before["rear"].footprint_m[0]
    assert after["front"].footprint_m[0] < before["front"].footprint_m[0]
    assert rear_axle_N / 1e3 == pytest.approx(46.04, abs=0.01)  # 28.65 kN without the implement (standard gravity)


def test_static_tyre_loads_per_tyre_in_3d_and_pitch_plane():
    """One tyre's load per axle: the pitch plane's element is the axle (two tyres); in 3-D the mean of its
    two tyres. A symmetric 3-D tractor carries what the pitch-plane one does."""
    from tyrelab.vehicle.model import assemble

    flat = _modern()
    three_d = parse_scenario((scenarios_dir() / "modern_tractor.toml").read_text().replace(
        "cg_height_m = 0.95", "cg_height_m = 0.95\nroll_inertia_kg_m2 = 2400\nfront_track_m = 1.9\nrear_track_m = 1.8"))
    assert three_d.tractor.three_d
    loads = [tyres.static_tyre_loads(assemble(tyres.build_parts(sc, tyres.resolve_tyres(sc), 0)))
             for sc in (flat, three_d)]
    for axle in ("front", "rear"):
        assert loads[1][axle] == pytest.approx(loads[0][axle], rel=1e-12)


def test_a_given_footprint_is_kept():
    sc = _modern(IMPLEMENT)
    text = (scenarios_dir() / "modern_tractor.toml").read_text().replace('pressure_bar = 1.2\n',
                                                                         'pressure_bar = 1.2\nfootprint_m = 0.5\n')
    ty = tyres.resolve_tyres(parse_scenario(text + IMPLEMENT))
    assert ty["rear"].footprint_m.tolist() == [0.5] * 4
    assert ty["front"].footprint_m[0] == tyres.resolve_tyres(sc)["front"].footprint_m[0]


def test_the_shipped_scenarios_footprints_did_not_move():
    """Without an implement, ballast or cab the whole vehicle's loads are the tractor's: m g b / L / 2."""
    sc = load_scenario(scenarios_dir() / "modern_tractor.toml")
    t = sc.tractor
    ty = tyres.resolve_tyres(sc)
    load = t.mass_kg * GRAVITY_M_S2 * t.front_distance_m / t.wheelbase_m / 2
    want = _contact_length(ty["rear"].radius_m, load / (ty["rear"].stiffness_kN_per_m[0] * 1e3))
    assert ty["rear"].footprint_m[0] == pytest.approx(want, rel=1e-12)
