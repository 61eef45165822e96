"""The tractor assembled from parts (issue 23): one definition, checked against hand-derived answers."""

import math

import numpy as np
import pytest
from scipy import linalg

from tyrelab.vehicle import bounce_pitch
from tyrelab.vehicle.model import Axle, Chassis, Parts, SeatPoint, assemble
from tyrelab.vehicle.tractor import Tractor, tractor_parts

M, I_PITCH, I_ROLL, H = 5120.0, 6210.0, 2400.0, 0.838
A, B = 1.54, 0.896
KF, KR, CF, CR = 4.25e5, 3.3e5, 1.5e3, 1.0e3  # per tyre
TF, TR = 1.90, 1.80


def _frequencies(asm) -> dict:
    """Undamped natural frequencies (Hz) named by the coordinate that moves most."""
    k, m, names = asm.undamped()
    w2, vecs = linalg.eigh(k, m)
    out = {}
    for i in range(len(w2)):
        out[names[int(np.argmax(np.abs(vecs[:, i]) * np.sqrt(np.diag(m))))]] = math.sqrt(w2[i]) / (2 * math.pi)
    return out


def _three_d(front_mount="rigid", **front):
    return Parts(Chassis(M, I_PITCH, H, I_ROLL),
                 Axle("front", A, KF, CF, track_m=TF, mount=front_mount, **front),
                 Axle("rear", -B, KR, CR, track_m=TR), SeatPoint(-0.3, 0.35, 1.2))


def test_pitch_plane_assembly_is_the_beam_on_two_springs_of_thesis_8_2():
    asm = assemble(tractor_parts(Tractor(M, I_PITCH, A, B, H, 2 * KF, 2 * KR, 2 * CF, 2 * CR)))
    k, m, names = asm.undamped()
    assert names == ("z", "th")
    kf, kr = 2 * KF, 2 * KR
    np.testing.assert_allclose(k, [[kf + kr, kf * A - kr * B], [kf * A - kr * B, kf * A**2 + kr * B**2]], rtol=1e-15)
    np.testing.assert_allclose(m, np.diag([M, I_PITCH]))
    f = sorted(_frequencies(asm).values())
    assert f == pytest.approx(bounce_pitch.natural_frequencies(M, I_PITCH, A, B, kf, kr), rel=1e-12)
    # static tyre loads: the axle loads of a beam on two supports
    loads = asm.static_tyre_loads_N()
    assert loads["front"] == pytest.approx(M * 9.80665 * B / (A + B), rel=1e-12)
    assert loads["rear"] == pytest.approx(M * 9.80665 * A / (A + B), rel=1e-12)


def test_roll_frequency_is_that_of_the_tyres_roll_stiffness():
    """Rigid axles: roll stiffness Σ 2 k (t/2)² = k t²/2 per axle about the CG; roll decouples from
    bounce and pitch on a left/right symmetric tractor."""
    f = _frequencies(assemble(_three_d()))
    k_roll = KF * TF**2 / 2 + KR * TR**2 / 2
    assert f["phi"] == pytest.approx(math.sqrt(k_roll / I_ROLL) / (2 * math.pi), abs=0.01)
    assert sorted([f["z"], f["th"]]) == pytest.approx(
        bounce_pitch.natural_frequencies(M, I_PITCH, A, B, 2 * KF, 2 * KR), abs=0.01)


def test_a_pivoting_front_axle_passes_no_roll_moment():
    """Pivot: the body rolls on the rear tyres alone; the axle rolls on its own tyres about the pivot."""
    i_axle = 160.0
    f = _frequencies(assemble(_three_d("pivot", roll_inertia_kg_m2=i_axle)))
    assert f["phi"] == pytest.approx(math.sqrt(KR * TR**2 / 2 / I_ROLL) / (2 * math.pi), abs=0.01)
    assert f["front_axle_roll"] == pytest.approx(math.sqrt(KF * TF**2 / 2 / i_axle) / (2 * math.pi), abs=0.01)
    # static loads: a pivot axle carries the same axle load as a rigid one, split evenly
    loads = assemble(_three_d("pivot", roll_inertia_kg_m2=i_axle)).static_tyre_loads_N()
    assert loads["front_left"] == pytest.approx(M * 9.80665 * B / (A + B) / 2, rel=1e-9)
    assert loads["front_right"] == pytest.approx(loads["front_left"], rel=1e-12)


def test_named_outputs_and_a_pure_roll_input():
    """Left and right in anti-phase under both axles: no bounce, no pitch, no vertical seat motion on
    the centreline; a seat 0.35 m left of the CG moves by 0.35 φ''."""
    lm = assemble(_three_d()).linear(["vertical_m_s2", "pitch_rad_s2", "roll_rad_s2", "seat_vertical_m_s2"])
    assert lm.inputs == ("u_front_left", "du_front_left", "u_front_right", "du_front_right",
                         "u_rear_left", "du_rear_left", "u_rear_right", "du_rear_right")
    w = np.array([1.0, 0.0, -1.0, 0.0, 1.0, 0.0, -1.0, 0.0])  # a static roll input
    x = np.linalg.solve(lm.a, -lm.b @ w)
    y = lm.c @ x + lm.d @ w
    assert np.allclose(y, 0.0, atol=1e-9)  # at rest: no accelerations
    xs = dict(zip(lm.states, x))
    assert abs(xs["z"]) < 1e-12 and abs(xs["th"]) < 1e-12
    # static roll angle: tyre moments balance, φ = Σ k t u / (k_roll) with u = ±1 at ±t/2
    k_roll = KF * TF**2 / 2 + KR * TR**2 / 2
    assert xs["phi"] == pytest.approx((KF * TF + KR * TR) / k_roll, rel=1e-9)
    row = dict(zip(lm.outputs, lm.c))
    np.testing.assert_allclose(row["seat_vertical_m_s2"], row["vertical_m_s2"] - 0.3 * row["pitch_rad_s2"]
                               + 0.35 * row["roll_rad_s2"], atol=1e-12)


def test_bad_parts_are_refused_naming_the_parameter():
    with pytest.raises(ValueError, match="front_axle.roll_inertia_kg_m2"):
        assemble(_three_d("pivot"))
    with pytest.raises(ValueError, match="needs the roll model"):
        assemble(Parts(Chassis(M, I_PITCH, H), Axle("front", A, KF, CF, mount="pivot", roll_inertia_kg_m2=160.0),
                       Axle("rear", -B, KR, CR)))
    with pytest.raises(ValueError, match="chassis.mass_kg"):
        assemble(Parts(Chassis(0.0, I_PITCH, H), Axle("front", A, KF, CF), Axle("rear", -B, KR, CR)))


def test_simulate_refuses_runs_with_different_tyres_naming_assemblies():
    """A batch of a pitch-plane run (tyres front, rear) and a 3-D one (four wheels) cannot share the
    inputs array (runs, tyres, samples): refused before any work, naming the argument (the batches
    by structure would otherwise fail on the lift-off array's shape)."""
    from tyrelab.vehicle.tractor import simulate

    pitch = assemble(tractor_parts(Tractor(M, I_PITCH, A, B, H, 2 * KF, 2 * KR, 2 * CF, 2 * CR)))
    three = assemble(_three_d())
    assert tuple(pitch.tyres) != tuple(three.tyres)
    u = np.zeros((2, len(pitch.tyres), 5))
    with pytest.raises(ValueError, match=r"^assemblies: every run must have the same tyres"):
        simulate([pitch, three], u, u, 1e-3)
