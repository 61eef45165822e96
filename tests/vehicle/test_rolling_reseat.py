"""Issue 42, Deliver 4: a rolling tyre's lateral element re-seats at touchdown. Off the ground its contact
point is free (no ground holds it): the unit relaxes to zero deflection (``Rolling.free_rows``), so the
tyre lands with its contact point under the patch instead of where it left the ground."""

import numpy as np
import pytest

from tyrelab.vehicle import elements
from tyrelab.vehicle.model import Axle, Chassis, Parts, SeatPoint, assemble
from tyrelab.vehicle.tractor import simulate

from .test_ride_3d import A, B, C_TYRE, H, I_PITCH, I_ROLL, K_TYRE, M, SEAT, TF, TR


def _assembly():
    kw = dict(lateral_model="rolling", lateral_series_damping_N_s_per_m=12.5e3)
    fa = Axle("front", A, 1e3 * K_TYRE["front"], 1e3 * C_TYRE["front"], TF, lateral_stiffness_N_per_m=2e5,
              lateral_damping_N_s_per_m=2e3, **kw)
    ra = Axle("rear", -B, 1e3 * K_TYRE["rear"], 1e3 * C_TYRE["rear"], TR, lateral_stiffness_N_per_m=3e5,
              lateral_damping_N_s_per_m=3e3, **kw)
    return assemble(Parts(Chassis(M, I_PITCH, H, I_ROLL, 6000.0), fa, ra,
                          SeatPoint(SEAT["ahead"], SEAT["left"], SEAT["height"]), static_load_moment=True))


def _inputs(asm):
    """A one-sided bump train under the left tyres (the body rolls and moves sideways), the ground under
    the front left wheel falling away for 0.4 s in the middle (that tyre lifts off) and coming back."""
    t = np.arange(2 * 3000 - 1) * 0.5e-3  # 1.5 s at the half step
    u = np.zeros((1, len(asm.tyres), t.size))
    for j, tyre in enumerate(asm.tyres):
        if tyre.endswith("left"):
            u[0, j] = 0.03 * np.sin(2 * np.pi * 1.5 * t)
    j = asm.tyres.index("front_left")
    drop = np.clip((t - 0.5) / 0.02, 0, 1) - np.clip((t - 0.9) / 0.02, 0, 1)
    u[0, j] -= 0.3 * drop
    du = np.gradient(u, t, axis=-1)
    return t, u, du


def test_a_lifted_rolling_tyre_re_seats_at_touchdown(monkeypatch):
    asm = _assembly()
    t, u, du = _inputs(asm)
    record = ("seat_lateral_m_s2",)
    seated = simulate([asm], u, du, method="rk4", record=record)
    assert 0.15 < seated["lift_off_fraction_front_left"][0] < 0.4
    # the same without re-seating: off the ground the unit keeps its deflection (its contact-point states
    # evolve as on the ground; only its force is gated)
    monkeypatch.setattr(elements.Rolling, "free_rows", elements.Element.free_rows)
    kept = simulate([_assembly()], u, du, method="rk4", record=record)
    a, b = seated["seat_lateral_m_s2"][0], kept["seat_lateral_m_s2"][0]
    before = t[::2] < 0.5  # before the lift-off both runs are the same, to the bit
    assert np.array_equal(a[before[:a.size]], b[before[:b.size]])
    after = t[::2][:a.size] > 0.95  # after touchdown they differ: the contact point landed elsewhere
    assert np.max(np.abs(a[after] - b[after])) > 1e-3 * np.max(np.abs(a))


def test_the_free_rows_relax_the_unit_and_a_locked_element_has_none():
    asm = _assembly()
    lay = asm.layout
    e = asm.element("front_left_lateral")
    rows = e.free_rows(lay)
    q = "q_front_left_lateral"
    assert rows[q][lay.index[q]] == pytest.approx(-1.0 / max(2e3 / 2e5, elements.RESEAT_S))
    assert np.count_nonzero(rows[q]) == 1
    locked = elements.Rolling("x", e.g, 2e5, 2e3, series_damping=np.inf)
    assert locked.free_rows(lay) == {}
