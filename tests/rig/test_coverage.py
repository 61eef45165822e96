"""Issue 14: do the per-run 95 % intervals hold the truth on the stress campaign of the virtual rig?

The full figure (30 runs per artefact x noise cell, 480 runs) is in docs/benchmarks.md, from
``bench/bench_uncertainty.py``; the default test runs a small sample of every cell, the
slow one the issue's criterion (93-97 %) on 480 runs.
"""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))

from bench_uncertainty import evaluate, summarise  # noqa: E402


def test_intervals_hold_the_truth_on_a_small_stress_sample():
    df = evaluate(runs_per_cell=2, seed=7)
    assert len(df) == 32 and set(df["artefact"]) >= {"startup", "harmonics", "hum", "drift", "nonlinear",
                                                       "lug_modulation", "all"}
    assert df["K_in"].mean() >= 0.85 and df["C_in"].mean() >= 0.85
    # not uselessly wide: a day-checked run's interval is a small fraction of K and C
    assert df["K_width_pct"].median() < 2.0 and df["C_width_pct"].median() < 15.0
    table = summarise(df)
    assert {"K coverage %", "C coverage %", "median K width %", "median C width %"} <= set(table.columns)


@pytest.mark.slow
def test_coverage_within_93_to_97_percent():
    # the criterion on the benchmark's 480 runs (~100 s on 2 cores): measured K 96.0 %, C 96.7 %.
    # Not at a smaller size: with n runs the coverage's binomial standard error is sqrt(0.95 * 0.05 / n), 1.0 % at
    # 480 and 1.7 % at 160 runs, against a band of 4 % (160 runs measured K 92.5 %, 240 runs C 97.5 %).
    df = evaluate(runs_per_cell=30, seed=1991, jobs=2)
    assert len(df) == 480
    assert 0.93 <= df["K_in"].mean() <= 0.97
    assert 0.93 <= df["C_in"].mean() <= 0.97
