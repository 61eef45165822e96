"""tyre/: a bad argument is a ValueError naming the parameter (tyrelab._validate; issues 27, 28)."""

import pytest

from tyrelab.tyre import damping_fit, formula_accuracy, regressions, speed_dependence, spoke, stiffness
from tyrelab.tyre.formula_fit import FormulaFit, FrontRule

_FIT = FormulaFit("x", (172.0, -1.77, 5.6, 0.34), tuple(tuple(0.0 for _ in range(4)) for _ in range(4)), 0.1, 30.0,
                  0.9, 14, 56)
_DAMPING = damping_fit.DampingFit("x", (0.9, 0.1, -0.06, 0.42), tuple(tuple(0.0 for _ in range(4)) for _ in range(4)),
                                  0.2, 0.9, 5, 55)

CASES = [
    ("alpha", lambda: regressions.fit_line([1, 2, 3], [1, 2, 4], alpha=2)),
    ("alpha", lambda: regressions.fit_mean([1, 2, 3], alpha=0)),
    ("pressure_bar", lambda: stiffness.traction_tyre_stiffness("13.6R38", -1.0)),
    ("age_years", lambda: stiffness.traction_tyre_stiffness("13.6R38", 1.0, float("nan"))),
    ("pressure_bar", lambda: stiffness.undriven_front_tyre_stiffness("7.50-18", float("inf"))),
    ("pressure_bar", lambda: stiffness.estimate_stiffness("13.6R38", -0.1)),
    ("age_years", lambda: stiffness.range_warnings("13.6R38", 1.0, -2)),
    ("limit", lambda: formula_accuracy.p_within(3.0, 10.0, limit=0)),
    ("aspect_ratio", lambda: spoke.unloaded_radius_m("13.6R38", aspect_ratio=0)),
    ("frequency_Hz", lambda: spoke.equivalent_damping(10.0, frequency_Hz=0.0)),
    ("amplitude_m", lambda: spoke.damping_basis(10.0, amplitude_m=-0.01)),
    ("speed_km_h", lambda: spoke.damping_basis(-5.0)),
    ("pressure_bar", lambda: _FIT.predict("13.6R38", -1.0)),
    ("level", lambda: _FIT.coverage_factor(1.0)),
    ("pressure_bar", lambda: FrontRule(1.0, 0.1, 10).predict("7.50-18", -1.0)),
    ("speed_km_h", lambda: _DAMPING.predict(1.2, float("nan"))),
    ("query_km_h", lambda: speed_dependence.at_speeds([0, 10], [1.0, 2.0], [-3.0])),
]


@pytest.mark.parametrize("name,call", CASES, ids=[f"{i}-{c[0]}" for i, c in enumerate(CASES)])
def test_bad_argument_names_the_parameter(name, call):
    with pytest.raises(ValueError, match=name):
        call()
