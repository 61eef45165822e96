"""Issue 14: Table III-X lines weighted by the runs' uncertainties where they differ."""

import numpy as np
import pytest

from tyrelab.tyre.regressions import between_run_variance, fit_line


def test_equal_uncertainties_give_the_ordinary_fit():
    rng = np.random.default_rng(0)
    x = np.repeat([0.8, 1.2, 1.6, 2.0], 3)
    y = 150 + 180 * x + rng.normal(0, 5, x.size)
    ols, wls = fit_line(x, y), fit_line(x, y, u=np.full(x.size, 1.0))
    assert wls["weighting"] == "OLS" and wls["slope"] == pytest.approx(ols["slope"])


def test_between_run_scatter_is_recovered_and_noisy_runs_count_less():
    rng = np.random.default_rng(3)
    x = np.tile([0.8, 1.2, 1.6, 2.0], 40)
    u = np.where(np.arange(x.size) % 2, 2.0, 20.0)  # half the runs ten times noisier
    y = 150 + 180 * x + rng.normal(0, 6.0, x.size) + rng.normal(0, u)
    f = fit_line(x, y, u=u)
    assert f["weighting"].startswith("WLS") and f["between_run_sd"] == pytest.approx(6.0, rel=0.3)
    ols = fit_line(x, y)
    assert f["slope_se"] < ols["slope_se"]  # the weights use the information
    assert f["slope_ci_low"] < 180 < f["slope_ci_high"]
    assert 0 < f["r_squared"] < 1


def test_no_extra_scatter_when_the_uncertainties_explain_the_residuals():
    x = np.linspace(0, 1, 30)
    u = np.linspace(1, 5, 30)
    tau2 = [between_run_variance(x, 2 + 3 * x + np.random.default_rng(seed).normal(0, u), u) for seed in range(41)]
    assert np.median(tau2) < 0.05 * np.mean(u**2)  # χ² exceeds n − 2 about half the time by chance only
    assert between_run_variance(x, 2 + 3 * x + np.random.default_rng(0).normal(0, 3 * u), u) > np.mean(u**2)
