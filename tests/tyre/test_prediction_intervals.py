"""Issue 14: the formula's prediction interval and the natural frequencies' intervals."""

import json

import numpy as np
import pytest

from tyrelab.cli import main
from tyrelab.published import read_published
from tyrelab.tyre import formula_accuracy as fa
from tyrelab.tyre.stiffness import estimate_stiffness
from tyrelab.vehicle.bounce_pitch import frequency_uncertainty, natural_frequencies, tractor_natural_frequencies

LEYLAND = ["--mass", "3235", "--pitch-inertia", "2669", "--front-distance", "1.33", "--rear-distance", "0.71",
           "--front-tyre", "7.50-16", "--front-pressure", "2.06", "--rear-tyre", "13.6-38", "--rear-pressure", "1.1"]


def test_formula_error_model_from_the_published_tables():
    m = fa.formula_error_model(read_published("table_iii"), read_published("table_ii"))
    assert m.n_tyres >= 10 and m.n >= 5 * m.n_tyres
    assert 0 < m.sd_error_percent < 30  # thesis §4.5.3: sd 10 % over 56 points
    lo, hi = m.interval(300.0)
    assert lo < 300.0 / (1 + m.mean_error_percent / 100) < hi
    # the published points themselves: most lie inside the interval of their formula value
    pred = fa.predictions_from_table(read_published("table_iii"), read_published("table_ii"))
    inside = [m.interval(f)[0] <= meas <= m.interval(f)[1]
              for f, meas in zip(pred["formula_kN_per_m"], pred["measured_kN_per_m"]) if np.isfinite(f)]
    assert 0.85 <= np.mean(inside) < 1.0
    with pytest.raises(ValueError, match="predicted_kN_per_m"):
        m.interval(-1.0)


def test_estimate_stiffness_carries_its_prediction_interval(capsys, thesis_model):
    e = estimate_stiffness("13.6R38", 1.2, 2, model=thesis_model)
    lo, hi = e.prediction_interval_kN_per_m
    assert lo < e.stiffness_kN_per_m < hi and e.stiffness_u_kN_per_m > 0
    # issue 27: the undriven front rule has an interval too (spread between tyres), not none
    front = estimate_stiffness("7.50-16", 2.0, undriven_front=True, model=thesis_model)
    flo, fhi = front.prediction_interval_kN_per_m
    assert flo < front.stiffness_kN_per_m < fhi and front.stiffness_u_kN_per_m > 0
    assert "F1" in front.prediction_interval_basis
    bare = estimate_stiffness("13.6R38", 1.2, 2)
    assert bare.prediction_interval_kN_per_m is None and bare.stiffness_kN_per_m == e.stiffness_kN_per_m
    assert main(["estimate-stiffness", "--size", "13.6R38", "--pressure", "1.2", "--age", "2"]) == 0
    assert "95 % prediction interval" in capsys.readouterr().out
    assert main(["estimate-stiffness", "--size", "13.6R38", "--pressure", "1.2", "--format", "json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert len(out["prediction_interval_kN_per_m"]) == 2 and out["stiffness_u_kN_per_m"] > 0


def test_natural_frequencies_print_intervals(capsys):
    assert main(["natural-frequencies", *LEYLAND, "--front-traction"]) == 0
    out = json.loads(capsys.readouterr().out)
    for i in (1, 2):
        lo, hi = out[f"frequency_{i}_Hz_ci95"]
        assert lo < out[f"frequency_{i}_Hz"] < hi and out[f"frequency_{i}_u_Hz"] > 0
    assert out["front_tyre_stiffness_u_kN_per_m"] > 0 and "first order" in out["frequency_interval_method"]
    # given stiffnesses without an uncertainty: no width; with one: a width
    assert main(["natural-frequencies", *LEYLAND, "--front-stiffness", "247", "--rear-stiffness", "306"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["frequency_1_u_Hz"] == 0.0 and out["frequency_1_Hz_ci95"][0] == out["frequency_1_Hz"]
    assert main(["natural-frequencies", *LEYLAND, "--front-stiffness", "247", "--rear-stiffness", "306",
                 "--rear-stiffness-u", "20"]) == 0
    assert json.loads(capsys.readouterr().out)["frequency_1_u_Hz"] > 0


def test_first_order_frequency_uncertainty_agrees_with_monte_carlo():
    args = (3235.0, 2669.0, 1.33, 0.71)
    kf, kr, uf, ur = 247.0, 306.0, 15.0, 20.0
    (u1, u2), _ = frequency_uncertainty(*args, kf, kr, uf, ur)
    rng = np.random.default_rng(1)
    samples = np.array([natural_frequencies(*args, 2e3 * a, 2e3 * b)
                        for a, b in zip(rng.normal(kf, uf, 4000), rng.normal(kr, ur, 4000))])
    assert u1 == pytest.approx(samples[:, 0].std(), rel=0.08)
    assert u2 == pytest.approx(samples[:, 1].std(), rel=0.08)
    with pytest.raises(ValueError, match="rear_stiffness_u_kN_per_m"):
        tractor_natural_frequencies(*args, "7.50-16", 2.06, "13.6-38", 1.1, rear_stiffness_u_kN_per_m=-1.0)


def test_natural_frequencies_with_undriven_fronts_carry_a_front_uncertainty(capsys):
    """Issue 27, checked by: the undriven front rule (F1 alone) is no longer certain."""
    assert main(["natural-frequencies", *LEYLAND]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["front_tyre_stiffness_u_kN_per_m"] > 0.1 * out["front_tyre_stiffness_kN_per_m"]
    lo, hi = out["frequency_2_Hz_ci95"]
    assert hi - lo > 0.1  # the front axle's mode: ±0.005 Hz when the front rule had no uncertainty
