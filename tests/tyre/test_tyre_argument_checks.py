"""tyre/: a bad argument of a result object's method is a ValueError naming the parameter (issues 27, 28).

The module functions of ``tyre/`` have their rows in ``tests/test_argument_checks.py`` (one table; a new public
function without a row fails there); the methods of the fitted models are checked here.
"""

import pytest

from tyrelab.tyre import damping_fit
from tyrelab.tyre.formula_fit import FormulaFit, FrontRule

_FIT = FormulaFit("x", (172.0, -1.77, 5.6, 0.34), tuple(tuple(0.0 for _ in range(4)) for _ in range(4)), 0.1, 30.0,
                  0.9, 14, 56)
_DAMPING = damping_fit.DampingFit("x", (0.9, 0.1, -0.06, 0.42), tuple(tuple(0.0 for _ in range(4)) for _ in range(4)),
                                  0.2, 0.9, 5, 55)

CASES = [
    ("pressure_bar", lambda: _FIT.predict("13.6R38", -1.0)),
    ("level", lambda: _FIT.coverage_factor(1.0)),
    ("wr_in2", lambda: _FIT.predict_terms(38.0, 0.0, 1.2)),
    ("pressure_bar", lambda: FrontRule(1.0, 0.1, 10).predict("7.50-18", -1.0)),
    ("level", lambda: FrontRule(1.0, 0.1, 10).predict("7.50-18", 1.0, level=0.0)),
    ("speed_km_h", lambda: _DAMPING.predict(1.2, float("nan"))),
    ("age_years", lambda: _DAMPING.predict(1.2, 10.0, -1.0)),
]


@pytest.mark.parametrize("name,call", CASES, ids=[f"{i}-{c[0]}" for i, c in enumerate(CASES)])
def test_bad_argument_names_the_parameter(name, call):
    with pytest.raises(ValueError, match=rf"\b{name}\b"):
        call()
