"""The damped modes' release path builds each step's state matrix from rows kept between the steps
(issue 42, Cost): the same matrix, to the bit, as the assembly's own rows of the released model."""

from __future__ import annotations

import numpy as np
import pytest

from tyrelab.resources import scenarios_dir
from tyrelab.scenario_io import parse_scenario
from tyrelab.vehicle.elements import Rolling
from tyrelab.vehicle.model import assemble
from tyrelab.vehicle.solvers import modes
from tyrelab.vehicle.tyres import build_parts, resolve_tyres

SHARES = (1e-4, 3e-3, 0.1, 0.5, 1.0)


def _scenario(lateral: str = "rolling", longitudinal: str = "maxwell"):
    text = (scenarios_dir() / "modern_3d_tractor.toml").read_text()
    text = text.replace('longitudinal_model = "maxwell"', f'longitudinal_model = "{longitudinal}"')
    text = text.replace("[tractor]\n", f'[tractor]\nlateral_model = "{lateral}"\n', 1)
    text = text.replace("speeds_km_h = [4, 8, 12, 16, 20]", "speeds_km_h = [4, 16]")
    return parse_scenario(text, scenarios_dir())


@pytest.mark.parametrize("lateral, longitudinal", [("rolling", "maxwell"), ("maxwell", "rolling"), ("rolling", "none")])
def test_each_step_has_the_released_models_rows_to_the_bit(lateral, longitudinal):
    sc = _scenario(lateral, longitudinal)
    tyres = resolve_tyres(sc)
    checked = 0
    for i in range(len(sc.exposure.speeds_km_h)):
        asm = assemble(build_parts(sc, tyres, i))
        assert modes._released_by(asm)
        one = modes._released(asm, 1.0)
        lay = one.layout
        known, _, _ = one.state_rows(lay, [e for e in one.elements if not isinstance(e, Rolling)])
        path = modes._release_path(asm, None, ("z", "th"))
        for share in SHARES:
            _, _, rows = one.state_rows(lay, modes._released(asm, share).elements, known)
            assert np.array_equal(path.rows_at(share), rows), (lateral, longitudinal, i, share)
            checked += 1
    assert checked == 2 * len(SHARES)
