"""Issue 35, Deliver 2: a new part kind is one class, touching no solver.

A toy part (a mass on a spring and damper on top of the chassis: a vibration absorber) is
written here, outside the package, handed to :func:`tyrelab.vehicle.model.assemble` in
``Parts.extra``, and every solution path takes it as it is: its undamped frequencies are the
2-DOF system's closed form, and the exact path agrees with the RK4 path in contact.
"""

from dataclasses import dataclass

import numpy as np
import pytest

from tyrelab.vehicle.elements import SpringDamper
from tyrelab.vehicle.model import Axle, Builder, Chassis, Part, Parts, assemble
from tyrelab.vehicle.tractor import simulate

M, I, M2, K2, C2 = 5000.0, 6000.0, 300.0, 2.0e5, 1.5e3
A, B, KF = 1.2, 0.8, 4.0e5  # per tyre; rear stiffness so that KF A = KR B (bounce and pitch uncoupled)
KR = KF * A / B


@dataclass(frozen=True)
class Absorber(Part):
    """A mass on a spring and damper, vertically above the CG."""

    mass_kg: float
    stiffness_N_per_m: float
    damping_N_s_per_m: float

    def declare(self, b: Builder) -> None:
        b.coordinate("absorber_z")

    def contribute(self, b: Builder) -> None:
        at = b.chassis_point(0.0, 0.0, 0.5)
        own = {"z": b.row({"absorber_z": 1.0}), "x": at["x"], "y": at["y"]}
        b.body(self.mass_kg, 0.0, 0.0, own, None, np.zeros(b.n))
        b.element(SpringDamper("absorber", own["z"] - at["z"], self.stiffness_N_per_m, self.damping_N_s_per_m))
        b.output("absorber_m_s2", own["z"])


def _parts(extra=()):
    return Parts(Chassis(M, I, 0.9), Axle("front", A, KF, 1e3), Axle("rear", -B, KR, 1e3), extra=tuple(extra))


def test_a_toy_part_assembles_with_the_two_dof_closed_form():
    asm = assemble(_parts([Absorber(M2, K2, C2)]))
    assert asm.coordinates == ("z", "th", "absorber_z")
    k, m, names = asm.undamped()
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(m, k)).real)
    kt = 2 * (KF + KR)  # the pitch-plane element carries both tyres of an axle
    # bounce: M m w^4 - (M k2 + m (Kt + k2)) w^2 + Kt k2 = 0; pitch: (I + m h^2) w^2 = 2 (KF A^2 + KR B^2),
    # the absorber moving fore-aft with the chassis 0.5 m above the CG
    p, q = (M * K2 + M2 * (kt + K2)) / (M * M2), kt * K2 / (M * M2)
    bounce = np.array([(p - np.sqrt(p * p - 4 * q)) / 2, (p + np.sqrt(p * p - 4 * q)) / 2])
    pitch = 2 * (KF * A**2 + KR * B**2) / (I + M2 * 0.5**2)
    np.testing.assert_allclose(w2, np.sort(np.r_[bounce, pitch]), rtol=1e-12)


def test_the_solvers_take_the_toy_part_unchanged():
    asm = assemble(_parts([Absorber(M2, K2, C2)]))
    n = 4001
    t = np.arange(2 * n - 1) * 5e-4
    u = 0.01 * np.sin(np.pi * 1.5 * t) ** 2  # smooth from rest (RK4 and the exact path see the same input)
    du = 0.01 * np.pi * 1.5 * np.sin(2 * np.pi * 1.5 * t)
    uu, dd = np.stack([u, u])[None], np.stack([du, du])[None]
    record = ("absorber_m_s2", "vertical_m_s2", "absorber_z_m")
    exact = simulate([asm], uu, dd, record=record)
    rk4 = simulate([asm], uu, dd, method="rk4", record=record)
    assert exact["method_used"][0] == "exact" and rk4["method_used"][0] == "rk4"
    for key in record:
        scale = np.abs(exact[key]).max()
        assert scale > 0
        assert np.abs(exact[key] - rk4[key]).max() < 1e-4 * scale, key
    # the absorber moves the chassis: without it the body's response differs
    plain = simulate([assemble(_parts())], uu, dd, record=("vertical_m_s2",))
    assert np.abs(plain["vertical_m_s2"] - exact["vertical_m_s2"]).max() > 0.01 * np.abs(plain["vertical_m_s2"]).max()


def test_a_part_that_asks_for_a_coordinate_twice_is_refused():
    with pytest.raises(ValueError, match="absorber_z"):
        assemble(_parts([Absorber(M2, K2, C2), Absorber(M2, K2, C2)]))
