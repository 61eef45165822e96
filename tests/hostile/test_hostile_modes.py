"""Natural-frequency intervals and mode names (issue 37): an interval is on the frequency of one mode
(followed by shape through the tyre stiffness perturbation), never below zero; a sweep's mode
columns hold the same mode in every variant."""

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from tests.scenarios import scenario_text
from tyrelab.cli import main
from tyrelab.report import ride_page
from tyrelab.scenario_io import parse_scenario
from tyrelab.vehicle import modes, ride

SHORT = 'kind = "iso8608"\nclass = "C"\nlength_m = 20'


def suspended_front(stiffness_kN_per_m: float) -> str:
    """The template tractor (formula tyres: a stiffness uncertainty) on a soft suspended front axle:
    near 92.5 kN/m its two lowest body modes trade the names bounce and pitch."""
    return scenario_text(SHORT, extra=f'[front_axle]\nmount = "suspended"\nmass_kg = 400\n'
                                      f'suspension_stiffness_kN_per_m = {stiffness_kN_per_m}\n'
                                      'suspension_damping_kN_s_per_m = 8')


@pytest.mark.parametrize("stiffness", [92.2, 92.5])
def test_intervals_are_on_one_mode_and_never_below_zero(tmp_path, capsys, stiffness):
    """Was: ``pitch 1.38 Hz [-8.59, 11.34]``, ``bounce 2.76 Hz [-7.40, 12.93]`` (the ±1 % models named
    the two modes the other way round)."""
    path = tmp_path / "s.toml"
    path.write_text(suspended_front(stiffness))
    assert main(["ride", str(path)]) == 0
    doc = json.loads(capsys.readouterr().out)
    for name, f in doc["natural_frequencies_Hz"].items():
        lo, hi = doc["natural_frequencies_Hz_ci95"][name]
        assert 0 <= lo <= f <= hi and hi - lo < 0.5 * f, (name, f, lo, hi)


def test_the_intervals_agree_with_frequencies_recomputed_at_the_interval_s_stiffness():
    """An independent check of the first-order interval: the body modes' frequencies at K ± 1.96 u
    (each axle alone, the mode picked by the nearest frequency) lie within ~10 % of the half-width."""
    sc = parse_scenario(suspended_front(92.2))
    res = ride.ride(sc, with_spectra=False)
    asm = ride.assemble(ride.build_parts(sc, res.tyres, 0))
    for name in ("bounce", "pitch"):
        f = res.natural_frequencies_Hz[name]
        lo, hi = res.natural_frequency_intervals_Hz[name]
        var = 0.0
        for axle in ("front", "rear"):
            u = 1e3 * res.tyres[axle].stiffness_u_kN_per_m
            k = getattr(asm.parts, axle).tyre_stiffness_N_per_m
            ends = []
            for sign in (1, -1):
                part = getattr(asm.parts, axle)
                scaled = replace(asm.parts, **{axle: replace(part, tyre_stiffness_N_per_m=k + sign * 1.96 * u)})
                freqs = ride.modes(ride.assemble(scaled))[0].values()
                ends.append(min(freqs, key=lambda x: abs(x - f)))
            var += ((ends[0] - ends[1]) / 2) ** 2
        assert math.sqrt(var) == pytest.approx((hi - lo) / 2, rel=0.1), name


def test_a_sweep_s_mode_columns_hold_one_mode(tmp_path):
    """Was: across 85 → 100 kN/m the lowest body mode was "pitch" in one variant and "bounce" in the
    next, so ``bounce_Hz`` jumped from 2.76 to 1.43 Hz."""
    sc = parse_scenario(suspended_front(85))
    results = ride.ride_sweep(sc, sets={"front_axle.suspension_stiffness_kN_per_m": (85, 100)}, with_spectra=False)
    table = ride.results_table(results)
    assert table["pitch_Hz"].max() < 1.6 and table["bounce_Hz"].min() > 2.5
    assert list(results[1].natural_frequencies_Hz) == list(results[0].natural_frequencies_Hz)
    alone = ride.ride(ride.with_values(sc, {"front_axle.suspension_stiffness_kN_per_m": 100}), with_spectra=False)
    assert alone.natural_frequencies_Hz["bounce"] < 1.6  # alone, by shape, the lower mode is "bounce" at 100
    assert results[1].natural_frequencies_Hz["pitch"] == alone.natural_frequencies_Hz["bounce"]
    lo, hi = results[1].natural_frequency_intervals_Hz["pitch"]
    assert [lo, hi] == alone.natural_frequency_intervals_Hz["bounce"]


def _without_first_mode(m: modes.ModeSet) -> modes.ModeSet:
    """``m`` with its first mode replaced by one of a coordinate ``m`` lacks (a mode that went away)."""
    n = len(m.coordinates)
    shapes = np.zeros((n + 1, len(m.names)))
    shapes[:n, :] = m.shapes
    shapes[:, 0] = 0.0
    shapes[n, 0] = 1.0
    mass = np.eye(n + 1)
    mass[:n, :n] = m.mass
    return modes.ModeSet(m.names, m.frequencies_Hz, (*m.coordinates, "extra"), shapes, mass, m.nodal_points_m)


def test_a_mode_that_cannot_be_followed_has_no_number_and_a_warning():
    sc = parse_scenario(scenario_text(SHORT))
    results = ride.ride_sweep(sc, sets={"tractor.mass_kg": (4700, 4800)}, with_spectra=False, method="time")
    first = results[0].natural_frequencies_Hz
    lost = next(iter(first))
    results[1].modes = _without_first_mode(results[1].modes)
    ride._follow_modes(results)
    assert math.isnan(results[1].natural_frequencies_Hz[lost]) and list(results[1].natural_frequencies_Hz) == list(first)
    assert sum("not followed from the first variant" in w for w in results[1].warnings) == 1
    doc = ride.result_json(results)
    assert doc["sweep"][1]["natural_frequencies_Hz"][lost] is None
    assert f"{lost} not followed" in ride.results_table(results)["modes_Hz"].iloc[1]
    ride_page.format_table(doc)
    html = ride_page.render_page(results)
    assert "followed by its shape" in html
