"""The tractor's switched path (exact while both axles are in contact, RK4 across lift-off)
against RK4 over the whole run (issue 15).

A row of 40 mm raised-cosine bumps (0.4 m long, every 3 m) at 4 m/s lifts the front axle
off about a sixth of the time. Tolerances from the step: RK4 at 1 ms differs from RK4 at
0.25 ms by up to ~1.5e-3 (no element) / ~1e-4 (longitudinal element) of the r.m.s. at the
touch-downs (the force clamp is a kink inside a step) and the exact path from RK4 in contact
by ~1e-5; the switched run must stay within a few times that of the RK4 run.
"""

import numpy as np
import pytest

from tyrelab.vehicle.lti import discretise
from tyrelab.vehicle.tractor import CALM_STEPS, Tractor, simulate_tractor

DT_S = 1e-3


def _bumps(t, v, height=0.04, length=0.4, pitch=3.0):
    s = np.mod(v * t, pitch)
    on = (s < length) & (t >= 0)
    u = np.where(on, 0.5 * height * (1 - np.cos(2 * np.pi * s / length)), 0.0)
    ud = np.where(on, 0.5 * height * 2 * np.pi / length * v * np.sin(2 * np.pi * s / length), 0.0)
    return u, ud


def _inputs(duration_s=3.0, v=4.0, wheelbase_m=2.436):
    t = np.arange(int(round(duration_s / (DT_S / 2))) + 1) * DT_S / 2
    return (*_bumps(t, v), *_bumps(t - wheelbase_m / v, v))


@pytest.mark.parametrize("model, kx, cx, tol", [("none", 0.0, 0.0, 5e-3), ("kelvin_voigt", 9.1e5, 6e3, 1e-3),
                                                 ("maxwell", 9.1e5, 6e3, 1e-3)])
def test_switched_run_agrees_with_rk4_across_lift_off(model, kx, cx, tol):
    tr = Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3, kx, cx, model)
    inputs = _inputs()
    sw = simulate_tractor(tr, *inputs, DT_S)
    rk4 = simulate_tractor(tr, *inputs, DT_S, method="rk4")
    assert sw["method_used"] == "exact+rk4" and rk4["method_used"] == "rk4"
    assert 0.05 < sw["lift_off_fraction_front"] < 0.5  # it does lift off, several times
    assert sw["lift_off_fraction_front"] == pytest.approx(rk4["lift_off_fraction_front"], abs=2e-3)
    for key in ("vertical_m_s2", "pitch_rad_s2", "z_m", "theta_rad") + (("longitudinal_m_s2",) if kx else ()):
        rms = np.sqrt(np.mean(rk4[key] ** 2))
        assert np.abs(sw[key] - rk4[key]).max() < tol * rms, key
        assert np.sqrt(np.mean(sw[key] ** 2)) == pytest.approx(rms, rel=1e-4), key


def test_run_in_contact_stays_exact_and_a_batch_mixes_models():
    """Inputs too small to lift a tyre: exact; models per run in one batch give each run's own result."""
    u, ud, ur, udr = (0.1 * x for x in _inputs(2.0))
    runs = [("none", 0.0, 0.0), ("maxwell", 9.1e5, 6e3), ("kelvin_voigt", 9.1e5, 6e3)]
    one = [simulate_tractor(Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3, kx, cx, m),
                            u, ud, ur, udr, DT_S) for m, kx, cx in runs]
    batch = simulate_tractor(Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3,
                                     np.array([r[1] for r in runs]), np.array([r[2] for r in runs]),
                                     np.array([r[0] for r in runs], dtype=object)),
                             *(np.tile(x, (3, 1)) for x in (u, ud, ur, udr)), DT_S)
    assert list(batch["method_used"]) == ["exact"] * 3
    for i, o in enumerate(one):
        np.testing.assert_array_equal(batch["vertical_m_s2"][i], o["vertical_m_s2"])
    with pytest.raises(ValueError, match="longitudinal_model"):
        simulate_tractor(Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3, 0, 0, "coulomb"),
                         u, ud, ur, udr, DT_S)
    assert CALM_STEPS >= 1


def test_restarted_exact_solution_continues_the_same_trajectory():
    """:class:`FohSystem` from a state reached half-way gives the one-piece solution."""
    a = np.array([[0.0, 1.0], [-400.0, -4.0]])
    b = np.array([[0.0, 0.0], [400.0, 4.0]])
    s = discretise(a, b, np.eye(2), np.zeros((2, 2)), 5e-4)
    t = np.arange(4001) * 5e-4
    w = np.vstack([np.sin(7 * t), 7 * np.cos(7 * t)])
    whole, kept = s.run(w, keep_modes=True)
    second = s.run(w[:, 2000:], x0=s.state_at(kept, 2000))
    np.testing.assert_allclose(second, whole[:, 2000:], rtol=0, atol=1e-12 * np.abs(whole).max())


def _textbook_rk4(p, models, uf, udf, ur, udr, h, g=9.80665):
    """RK4 of the module docstring's equations written out plainly (whole-batch arrays, from rest)."""
    m, inertia, a, b, hc, kf, kr, cf, cr, kx, cx = p
    kv, mw = models == "kelvin_voigt", models == "maxwell"
    wf, wr = -m * g * b / (a + b), -m * g * a / (a + b)
    rate = np.divide(kx, cx, out=np.zeros(m.size), where=cx > 0)
    active = (kx > 0) & (cx > 0)

    def rhs(y, j):
        z, th, x, vz, vth, vx, s = y
        ff = np.maximum(kf * (uf[:, j] - z - a * th) + cf * (udf[:, j] - vz - a * vth), wf)
        fr = np.maximum(kr * (ur[:, j] - z + b * th) + cr * (udr[:, j] - vz + b * vth), wr)
        d = x + hc * th
        fx = np.where(kv, -(kx * d + cx * (vx + hc * vth)), np.where(mw, -kx * (d - s) * active, 0.0)) * (fr > wr)
        ds = np.where(mw, rate * (d - s), 0.0)
        return np.array([vz, vth, vx, (ff + fr) / m, (a * ff - b * fr + hc * fx) / inertia, fx / m, ds]), ff <= wf, fr <= wr

    n = (uf.shape[1] + 1) // 2
    y, rec, off = np.zeros((7, m.size)), [], np.zeros((2, m.size))
    for i in range(n):
        k1, lf, lr = rhs(y, 2 * i)
        rec.append([k1[3], k1[4], k1[5], y[0], y[1]])
        off += [lf, lr]
        if i == n - 1:
            break
        k2 = rhs(y + 0.5 * h * k1, 2 * i + 1)[0]
        k3 = rhs(y + 0.5 * h * k2, 2 * i + 1)[0]
        k4 = rhs(y + h * k3, 2 * i + 2)[0]
        y = y + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    return np.array(rec).transpose(1, 2, 0), off / n


def test_rk4_does_the_textbook_arithmetic():
    """The RK4 on the assembled model (tyres, longitudinal element and mass matrix from the parts,
    issue 23) against the equations written out plainly, on a batch that mixes every model
    (unsorted, and a Maxwell element without its damper) and lifts tyres off: equal to rounding
    (the assembled sums run in another order: 1e-12 of the r.m.s.)."""
    models = np.array(["maxwell", "none", "kelvin_voigt", "maxwell", "kelvin_voigt"], dtype=object)
    kx = np.array([9.1e5, 0.0, 9.1e5, 9.1e5, 0.0])
    cx = np.array([6e3, 0.0, 6e3, 0.0, 2e3])
    runs = models.size
    scale = np.array([1.0, 1.2, 0.8, 1.0, 1.1])[:, None]
    uf, udf, ur, udr = (scale * x for x in _inputs(1.0))
    p = [np.full(runs, v) for v in (5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3)] + [kx, cx]
    got = simulate_tractor(Tractor(*p, longitudinal_model=models), uf, udf, ur, udr, DT_S, method="rk4")
    rec, off = _textbook_rk4(p, models, uf, udf, ur, udr, DT_S)
    assert off[0].min() > 0  # every run lifts its front axle off
    for i, key in enumerate(("vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2", "z_m", "theta_rad")):
        scale = np.sqrt(np.mean(rec[i] ** 2, axis=1, keepdims=True)) + 1e-300
        assert np.max(np.abs(got[key] - rec[i]) / scale) < 1e-9, key
    np.testing.assert_array_equal(got["lift_off_fraction_front"], off[0])
    np.testing.assert_array_equal(got["lift_off_fraction_rear"], off[1])


@pytest.mark.parametrize("method", ["rk4", "auto"])
def test_a_run_gives_the_same_bits_alone_and_in_a_batch_of_other_models(method):
    """The simulate stage reuses cached ch. 7 cases beside recomputed ones: a run's RK4 (and
    switched) arithmetic must not depend on what else is in its batch, although the batch mixes
    runs with and without a longitudinal element (other coordinates, other element slots)."""
    models = np.array(["maxwell", "none", "kelvin_voigt", "maxwell"], dtype=object)
    kx, cx = np.array([9.1e5, 0.0, 9.1e5, 9.1e5]), np.array([6e3, 0.0, 6e3, 0.0])
    scale = np.array([1.0, 1.2, 0.8, 1.1])[:, None]
    uf, udf, ur, udr = (scale * x for x in _inputs(0.6))
    p = [np.full(models.size, v) for v in (5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3)] + [kx, cx]
    batch = simulate_tractor(Tractor(*p, longitudinal_model=models), uf, udf, ur, udr, DT_S, method=method)
    assert batch["lift_off_fraction_front"].min() > 0
    for i in range(models.size):
        alone = simulate_tractor(Tractor(*(v[i] for v in p), longitudinal_model=models[i]), uf[i], udf[i], ur[i],
                                 udr[i], DT_S, method=method)
        for key, value in alone.items():
            np.testing.assert_array_equal(batch[key][i], value, err_msg=f"run {i} {key}")
