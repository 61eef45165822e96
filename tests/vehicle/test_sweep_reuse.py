"""A sweep's cost cuts (issue 42, Deliver 7) leave its numbers as they were: every variant of a sweep
against the same variant computed alone (fresh caches, nothing shared, nothing skipped).

Tolerance: the sweep and the lone runs make the same floating-point operations on the same models
(the sweep takes a model's damped modes from the one computed for an equal model, and batches the
expectations of variants that share a speed, elementwise); 1e-12 relative leaves room for BLAS'
rounding with the batch's memory layout and nothing more (a changed model or mode moves these
numbers by far more).
"""

from __future__ import annotations

import math

import pytest

from tyrelab.resources import scenarios_dir
from tyrelab.scenario_io import load_scenario
from tyrelab.vehicle import ride
from tyrelab.vehicle.run import frequency, sweep, time as time_run
from tyrelab.vehicle.scenario import with_overrides

RTOL = 1e-12


def _same(a, b, path=""):
    """``a`` equals ``b`` (nested JSON), numbers within :data:`RTOL`."""
    if isinstance(a, dict):
        assert set(a) == set(b), path
        for k in a:
            _same(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), path
        for k, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{path}[{k}]")
    elif isinstance(a, float) and isinstance(b, float):
        assert (math.isnan(a) and math.isnan(b)) or a == pytest.approx(b, rel=RTOL, abs=0.0), path
    else:
        assert a == b, path


def _alone(results, run):
    """Each variant of ``results`` run alone by ``run`` (a fresh cache each), its modes then followed
    from the first variant's as a sweep follows them."""
    alone = [run([r.scenario])[0] for r in results]
    for a, r in zip(alone, results):
        a.variant, a.nominal = r.variant, r.nominal
    sweep._follow_modes(alone)
    return alone


@pytest.fixture(scope="module")
def three_d():
    sc = load_scenario(scenarios_dir() / "modern_3d_tractor.toml")
    assert sc.tractor.three_d and sc.tractor.lateral_model == "rolling"
    return sc


@pytest.mark.parametrize("method", ["spectral", pytest.param("time", marks=pytest.mark.slow)])
def test_a_3d_rolling_sweep_equals_its_variants_alone(three_d, method):
    speeds = [6.0, 12.0] if method == "spectral" else [12.0]
    results = ride.ride_sweep(three_d, [1.0, 1.6], [1.2], speeds, with_spectra=False, method=method,
                              max_samples=10**9)
    run = ((lambda s: frequency.spectral_variants(s, with_spectra=False)) if method == "spectral"
           else (lambda s: time_run.ride_variants(s, with_spectra=False)))
    alone = _alone(results, run)
    assert all(r.modes_by_speed for r in results)  # the damped modes of every variant, per speed
    got, want = ride.result_json(results), ride.result_json(alone)
    _same(got, want)  # every block: rows, modes with damping, their intervals; the top A(8) interval
    assert want["a8_lateral_ci95_m_s2"], "the stand-in's A(8) interval is reported for the first variant"
    # the A(8) interval is the first variant's alone (what result_json reports); the others' skipped
    assert results[0].a8_lateral_ci95_m_s2 == alone[0].a8_lateral_ci95_m_s2
    assert [r.a8_lateral_ci95_m_s2 for r in results[1:]] == [{}] * (len(results) - 1)
    assert all(a.a8_lateral_ci95_m_s2 for a in alone)


def test_variants_of_one_model_share_its_damped_modes(three_d):
    """A swept key the model does not read (the hours of exposure): every variant the same model, its
    damped modes computed once (the cache holds one entry per speed and one of intervals), and each
    variant's equal to the model's alone."""
    sc = with_overrides(three_d, [8.0])
    results = ride.ride_sweep(sc, sets={"exposure.hours_per_day": [4.0, 10.0]}, with_spectra=False,
                              method="spectral")
    assert len(results) == 2 and results[0].speeds["a8_m_s2"].iloc[0] != results[1].speeds["a8_m_s2"].iloc[0]
    cache = ride.RideCache()
    frequency.spectral_variants([r.scenario for r in results], with_spectra=False, cache=cache)
    assert sorted(k[0] for k in cache.modes) == ["damped", "intervals"]
    alone = _alone(results, lambda s: frequency.spectral_variants(s, with_spectra=False))
    _same(ride.result_json(results), ride.result_json(alone))


def test_pitch_plane_sweep_equals_its_variants_alone():
    sc = load_scenario(scenarios_dir() / "modern_tractor.toml")
    results = ride.ride_sweep(sc, [1.0, 1.6], [0.8, 1.2], [6.0, 12.0], with_spectra=False, method="spectral")
    alone = _alone(results, lambda s: frequency.spectral_variants(s, with_spectra=False))
    _same(ride.result_json(results), ride.result_json(alone))


def test_the_release_path_gives_the_roots_of_the_released_models(three_d):
    """:func:`damped_modes`' steps (the series dampers released by ``share``) from one layout and the
    fixed elements' rows computed once: the same roots and shapes as assembling each released model
    (the same operations: equal to the last bit)."""
    import numpy as np

    from tyrelab.vehicle.model import assemble
    from tyrelab.vehicle.solvers import modes as m
    from tyrelab.vehicle.tyres import build_parts, resolve_tyres

    sc = with_overrides(three_d, [4.0, 20.0])
    tyres = resolve_tyres(sc)
    for i in range(2):
        asm = assemble(build_parts(sc, tyres, i))
        ref = m.mode_set(m._released(asm, 0.0))
        path = m._release_path(asm, None, ref.coordinates)
        for share in (1e-4, 0.01, 0.3, 1.0):
            roots, shapes = m._roots(m._released(asm, share), None, ref.coordinates)
            got_roots, got_shapes = path(share)
            assert np.array_equal(got_roots, roots) and np.array_equal(got_shapes, shapes), (i, share)


@pytest.mark.parametrize("kind", ["fixed", "tapered", "none"])
def test_the_envelope_table_is_each_footprints_response(kind):
    """The expectation's enveloping table (the cosines of a window length computed once for the
    footprints that share it) equals :func:`enveloping_response` of each footprint, to the last bit."""
    import numpy as np

    from tyrelab.vehicle.run import spectral

    n = np.geomspace(0.01, 10.0, 500)
    fps = [0.30, 0.30 + 1e-16, 0.3049, 0.41, 0.62, 0.0]
    table = spectral._envelope_table(kind, fps, 0.05, n)
    assert table.shape == (len(fps), n.size)
    for row, fp in zip(table, fps):
        assert np.array_equal(row, spectral.enveloping_response(kind, fp, 0.05, n))
