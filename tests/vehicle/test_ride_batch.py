"""Batched sweeps (issue 23, deliver 5): variants run together give each variant's own numbers,
and the batched frequency-domain expectation is the one a single ride prints."""

import dataclasses

import numpy as np
import pytest

from tyrelab.resources import scenarios_dir
from tyrelab.vehicle import ride
from tyrelab.vehicle.model import assemble
from tyrelab.scenario_io import parse_scenario
from tyrelab.vehicle.scenario import with_overrides

COLUMNS = ["a_wz_m_s2", "a_wx_m_s2", "a_wy_m_s2", "expected_a_wz_m_s2", "expected_a_wx_m_s2", "expected_a_wy_m_s2",
           "vdv_m_s1_75", "crest_factor", "hours_to_eav"]


def _scenario(three_d: bool):
    """The shipped modern tractor on a short track (formula stiffness: the pressure matters); in 3-D
    with roll, isotropic tracks and a pivoting front axle."""
    text = (scenarios_dir() / "modern_tractor.toml").read_text().replace("length_m = 400", "length_m = 60")
    if three_d:
        text = text.replace("[tractor]\n", "[tractor]\nroll_inertia_kg_m2 = 2400\nfront_track_m = 1.9\nrear_track_m = 1.8\n")
        text = text.replace("[surface]\n", "[surface]\ntracks = \"isotropic\"\n")
        text += "\n[front_axle]\nmount = \"pivot\"\nroll_inertia_kg_m2 = 160\n"
    return with_overrides(parse_scenario(text, scenarios_dir()), [6.0, 14.0])


@pytest.mark.parametrize("three_d", [False, True])
def test_variants_together_give_each_variants_own_numbers(three_d):
    sc = _scenario(three_d)
    variants = [with_overrides(sc, None, pf, pr) for pf, pr in ((1.0, 0.8), (1.0, 1.6), (2.2, 0.8))]
    together = ride.ride_variants(variants, with_spectra=False)
    for v, got in zip(variants, together):
        alone = ride.ride(v, with_spectra=False)
        # bit for bit: a sweep's numbers do not depend on how it is cut into executor tasks (the
        # batched frequency-domain expectation of a variant does not see the others)
        np.testing.assert_array_equal(got.speeds[COLUMNS].to_numpy(float), alone.speeds[COLUMNS].to_numpy(float))
    # the variants differ (the sharing did not hand one variant's inputs to another)
    assert together[0].speeds["a_wz_m_s2"].iloc[0] != together[2].speeds["a_wz_m_s2"].iloc[0]


@pytest.mark.parametrize("three_d", [False, True])
def test_expected_sweep_is_what_ride_prints(three_d):
    sc = _scenario(three_d)
    table = ride.expected_sweep(sc, [1.0, 2.2], [0.8, 1.6])
    assert len(table) == 2 * 2 * 2
    for (pf, pr_, speed), row in table.set_index(["front_pressure_bar", "rear_pressure_bar", "speed_km_h"]).iterrows():
        one = ride.ride(with_overrides(sc, [speed], pf, pr_), with_spectra=False).speeds.iloc[0]
        for ax in ("z", "x", "y"):
            assert row[f"expected_a_w{ax}_m_s2"] == pytest.approx(one[f"expected_a_w{ax}_m_s2"], rel=1e-9, abs=1e-15)
        assert row["hours_to_eav"] == pytest.approx(ride.exposure(row["expected_a_wz_m_s2"], row["expected_a_wx_m_s2"],
                                                                  8.0, row["expected_a_wy_m_s2"])["hours_to_eav"])


def test_linear_tyres_is_the_assembly_of_each_value():
    sc = _scenario(True)
    tyres = ride.resolve_tyres(sc)
    parts = ride.build_parts(sc, tyres, 0)
    asm = assemble(parts)
    outputs = ("seat_vertical_m_s2", "seat_lateral_m_s2", "front_left_force_N")
    k = {"front": np.array([2e5, 6e5]), "rear": np.array([3e5, 3e5])}
    c = {"rear": np.array([1e3, 4e3])}
    a, b, cc, d = asm.linear_tyres(outputs, k, c)
    for v in range(2):
        p = dataclasses.replace(parts, front=dataclasses.replace(parts.front, tyre_stiffness_N_per_m=k["front"][v]),
                                rear=dataclasses.replace(parts.rear, tyre_stiffness_N_per_m=k["rear"][v],
                                                         tyre_damping_N_s_per_m=c["rear"][v]))
        for got, want in zip((a[v], b[v], cc[v], d[v]), assemble(p).linear(outputs).abcd):
            np.testing.assert_allclose(got, want, rtol=1e-10, atol=1e-9 * np.abs(want).max())


def test_linear_tyres_refuses_ragged_values():
    asm = assemble(ride.build_parts(_scenario(False), ride.resolve_tyres(_scenario(False)), 0))
    with pytest.raises(ValueError, match="stiffness_N_per_m"):
        asm.linear_tyres(("seat_vertical_m_s2",), {"front": np.ones(2), "rear": np.ones(3)})
