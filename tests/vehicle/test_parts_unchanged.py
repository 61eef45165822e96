"""Issue 35, Deliver 7: the parts refactor moves no number.

The values in ``tests/vehicle/data/golden_vehicle_*.npz`` were computed by
``tests/vehicle/golden_vehicle.py`` on the code before the refactor (main at 61de914).

Two checks (issue 46: reproducible across machines, bit-identical under the lock):

- **Everywhere** (any numpy/scipy the ranges of pyproject.toml allow, any CPU): every quantity
  within :data:`RELATIVE` of its golden value, relative to the quantity's largest magnitude. The
  tolerance is set from the conditioning of the worst-conditioned computation here, not from the
  last bits: the time integrations (~4000 steps, lift-off on RK4) of the lightly damped pitch-plane
  tractor and the 3-D pivot-axle model, whose seat spectra and pitch accelerations amplify the
  rounding of each step. Measured by running the same code and the same numpy/scipy on the three
  x86-64 kernel sets numpy and OpenBLAS dispatch to (AVX-512, AVX2, SSE: ``NPY_DISABLE_CPU_FEATURES``,
  ``OPENBLAS_CORETYPE``) — the same arithmetic, rounded differently — the quantities move by up to
  2.2e-11 relative (``tractor/auto/pitch_rad_s2`` 1.8e-11, ``3d/pivot_kv/spectra/...`` 2.2e-11;
  about 2e5 units of roundoff). :data:`RELATIVE` is 45 times that; a change of the model (a
  constant, a term, a step size) moves these numbers by 1e-6 or more.
- **Under the lock**, on the platform recorded in ``golden_vehicle_quick_bits.json`` (the numpy and
  scipy versions the lock pins, the CPU kernels they dispatch to:
  :func:`tests.vehicle.golden_vehicle.platform`): the quantities listed there to the bit. The others (the runs that cross lift-off on RK4 with a Maxwell
  element or a coordinate no spring sees: their RK4 state is now the linear model's, the Maxwell
  spring's extension ``e = d - s`` where it was the damper's ``s``) differ in their rounding only,
  by 7e-15 at most, within :data:`RELATIVE`.

Issue 45 made the standard gravity 9.80665 m/s² the vehicle model's (it was the thesis' 9.81
everywhere); the thesis' studies keep 9.81 (Tables XVII, XVIII, XX to the bit with the model's
default untouched). The stored numbers are compared with the model's gravity set back to 9.81
(:func:`before_issue_33_parts`); ``test_standard_gravity_moves_the_scenarios_by`` records how far
the standard gravity moves the rest.
"""

import contextlib
import json

import numpy as np
import pytest

from tests.vehicle import golden_vehicle as golden

#: Largest difference allowed anywhere, relative to the largest magnitude of the same quantity
#: (45 x the 2.2e-11 the three x86-64 kernel sets give: see the module's text).
RELATIVE = 1e-9


@contextlib.contextmanager
def before_issue_33_parts(thesis_gravity: bool = True):
    """The vehicle's parts and footprints as the goldens were computed (and, unless
    ``thesis_gravity`` is False, the model's gravity the thesis' 9.81 m/s² it was before issue 45).

    Before issue 33: no lateral tyre elements (the 3-D scenarios here give no ``lateral_model``, now
    ``kelvin_voigt`` by default) and no static loads' moment (which moves the shipped
    modern_tractor.toml, a Maxwell longitudinal element: docs/simulation.md). With both off the new
    code paths must move no number; the thesis' studies never had either.

    Before issue 45: the footprints from the tractor's mass alone (``m g b / L / 2`` per tyre), not
    the whole vehicle's static loads; only the 3-D runs with an implement, ballast and cab
    (``PARTS``) move with the fix (tests/vehicle/test_tyres.py checks the new loads).
    """
    import dataclasses

    import sys

    from tyrelab.vehicle import ride, tyres
    from tyrelab.vehicle.carriage import GRAVITY_M_S2, THESIS_GRAVITY_M_S2
    from tyrelab.vehicle.model import assemble
    from tyrelab.vehicle.run import plan, sweep

    holders = (ride, tyres, plan, sweep)  # every module of the ride that builds parts (issue 45's layers)
    build = tyres.build_parts
    kept = [m.build_parts for m in holders], tyres.static_tyre_loads
    model = sys.modules[assemble.__module__]
    gravity = model.STANDARD_GRAVITY_M_S2

    def old_parts(scenario, tyre_data, i):
        p = build(scenario, tyre_data, i)
        strip = {ax: dataclasses.replace(getattr(p, ax), lateral_model="none") for ax in ("front", "rear")}
        return dataclasses.replace(p, static_load_moment=False, **strip)

    def tractor_alone(asm):
        p = asm.parts
        a, b = p.front.ahead_of_cg_m, -p.rear.ahead_of_cg_m
        m_g = p.chassis.mass_kg * GRAVITY_M_S2
        return {"front": m_g * b / (a + b) / 2, "rear": m_g * a / (a + b) / 2}

    seat_axes = plan.seat_axes

    def inertial(scenario):  # issue 42 made body-fixed seat axes the 3-D default; before it they were inertial
        given = "gravity_tilt" in (scenario.doc.get("seat") or {})
        return seat_axes(scenario if given else dataclasses.replace(
            scenario, seat=dataclasses.replace(scenario.seat, gravity_tilt=False)))

    for m in holders:
        m.build_parts = old_parts
    tyres.static_tyre_loads = tractor_alone
    axes_holders = (ride, plan, sweep)
    for m in axes_holders:
        m.seat_axes = inertial
    if thesis_gravity:
        model.STANDARD_GRAVITY_M_S2 = THESIS_GRAVITY_M_S2
    try:
        yield
    finally:
        for m, f in zip(holders, kept[0]):
            m.build_parts = f
        tyres.static_tyre_loads = kept[1]
        for m in axes_holders:
            m.seat_axes = seat_axes
        model.STANDARD_GRAVITY_M_S2 = gravity


def _compare(stored, now) -> dict:
    # every stored number is still computed; quantities added since (issue 36: mtvv_m_s2) are not compared
    assert not sorted(set(stored.files) - set(now))
    report = {}
    for k in stored.files:
        a, b = stored[k], now[k]
        assert a.shape == b.shape, k
        same = np.array_equal(a, b, equal_nan=True)
        if not same:
            scale = np.nanmax(np.abs(a)) if np.isfinite(a).any() else 0.0
            diff = np.nanmax(np.abs(a - b)) if a.size else 0.0
            report[k] = diff / scale if scale else diff
    return report


def _numbers(full: bool, thesis_gravity: bool = True) -> tuple:
    stored = np.load(golden.path(full))
    with before_issue_33_parts(thesis_gravity):
        now = golden.compute(full)
    return stored, _compare(stored, now)


@pytest.fixture(scope="module")
def quick():
    return _numbers(False)


def _within_conditioning(report: dict) -> None:
    bad = {k: v for k, v in report.items() if not v <= RELATIVE}
    assert not bad, bad


def _bit_identical_under_the_lock(full: bool, report: dict) -> None:
    kept = json.loads(golden.bits_path(full).read_text())
    here = golden.platform()
    if kept["platform"] != here:
        differ = {k: (kept["platform"].get(k), v) for k, v in here.items() if kept["platform"].get(k) != v}
        pytest.skip(f"not the lock's numpy/scipy on the CPU kernels of the bit record: {differ}")
    moved = sorted(k for k in kept["bit_identical"] if k in report)
    assert not moved, f"{len(moved)} quantities moved in their last bits under the lock: {moved[:10]}"


def test_vehicle_numbers_unchanged(quick):
    _within_conditioning(quick[1])


def test_vehicle_numbers_bit_identical_under_the_lock(quick):
    _bit_identical_under_the_lock(False, quick[1])


@pytest.mark.slow  # the whole ch. 7 study and both shipped scenarios at every speed
def test_vehicle_numbers_unchanged_full():
    _within_conditioning(_numbers(True)[1])


#: Largest relative move of a quantity under the standard gravity (9.80665 for 9.81, -0.035 %),
#: by kind: the lift-off floors move by the same -0.035 %, which moves the samples counted off the
#: ground and the RK4 stretches across a lift-off (the synthetic 60 mm step of ``tractor/``, bouncing,
#: moves most); a seat reading by ~1e-4 (lift-off, gravity tilt of ``gravity_tilt = true``).
STANDARD_GRAVITY_MOVES = {"synthetic step": 1.0, "lift_off_fraction": 1e-2, "seat readings": 5e-4}


def _gravity_bound(key: str) -> float:
    if key.startswith("tractor/"):
        return STANDARD_GRAVITY_MOVES["synthetic step"]
    if "lift_off_fraction" in key:
        return STANDARD_GRAVITY_MOVES["lift_off_fraction"]
    return STANDARD_GRAVITY_MOVES["seat readings"]


def test_standard_gravity_moves_the_scenarios_by():
    """Under the standard gravity: the thesis' tables stay within the conditioning (the studies pass
    9.81), the scenarios move by at most :data:`STANDARD_GRAVITY_MOVES` and some do move."""
    _, report = _numbers(False, thesis_gravity=False)
    assert not [k for k in report if k.startswith(("study/", "table_xx/")) and not report[k] <= RELATIVE], report
    assert any(k.startswith("shipped/") and v > 1e-6 for k, v in report.items())
    too_far = {k: v for k, v in report.items() if not v <= _gravity_bound(k)}
    assert not too_far, too_far


def test_the_relative_difference_is_measured_from_the_scale():
    """The comparison fails a quantity moved by more than RELATIVE of its scale, and only that."""
    stored = {"a": np.array([1.0, -4.0]), "b": np.array([2.0])}

    class Files(dict):
        files = property(lambda self: list(self))

    assert _compare(Files(stored), {"a": np.array([1.0, -4.0 * (1 + 1e-12)]), "b": np.array([2.0])}) == \
        pytest.approx({"a": 1e-12})
    moved = _compare(Files(stored), {"a": np.array([1.0 + 4e-8, -4.0]), "b": np.array([2.0])})
    assert moved["a"] > RELATIVE
