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


def test_first_order_root_sensitivities_agree_with_the_full_solves_central_differences():
    """The ±1 % tyre stiffness intervals' derivatives by first-order perturbation against the perturbed
    models' damped modes solved in full (the path before issue 42's third session), where it answers."""
    import dataclasses

    sc = _scenario()
    tyres = resolve_tyres(sc)
    base = build_parts(sc, tyres, 0)
    asm = assemble(base)
    shapes = modes.mode_set(modes._released(asm, 0.0))
    nominal = {n: d for n, d in modes.damped_modes(asm, reference=shapes).items() if d is not None}
    assert not any(d.overdamped for d in nominal.values())
    a = asm.linear(list(asm.kinematic_outputs)[:1]).a
    compared = 0
    for axle in ("front", "rear"):
        k = getattr(base, axle).tyre_stiffness_N_per_m
        parts = {f: dataclasses.replace(base, **{axle: dataclasses.replace(getattr(base, axle), tyre_stiffness_N_per_m=f * k)})
                 for f in (1.01, 0.99)}
        lm = {f: assemble(p).linear(list(asm.kinematic_outputs)[:1]).a for f, p in parts.items()}
        slopes = modes.root_sensitivities(a, nominal, (lm[1.01] - lm[0.99]) / (0.02 * k), 0.01 * k)
        assert slopes is not None and set(slopes) == set(nominal)
        full = {f: modes.follow_damped(nominal, modes.damped_modes(assemble(p), reference=shapes)) for f, p in parts.items()}
        for n, (df, dz) in slopes.items():
            up, down = full[1.01][n], full[0.99][n]
            df_full = (up.undamped_Hz - down.undamped_Hz) / (0.02 * k)
            dz_full = (up.damping_ratio - down.damping_ratio) / (0.02 * k)
            assert df == pytest.approx(df_full, rel=1e-2, abs=1e-12), (axle, n)
            assert dz == pytest.approx(dz_full, rel=1e-2, abs=1e-12), (axle, n)
            compared += 1
    assert compared >= 2 * 8


def test_root_sensitivities_refuse_overdamped_modes_and_near_repeated_roots():
    m, k = 1000.0, 1e5
    c_crit = 2 * np.sqrt(k * m)
    da = np.array([[0.0, 0.0], [-1.0 / m, 0.0]])
    near = np.array([[0.0, 1.0], [-k / m, -0.999 * c_crit / m]])  # just below critical damping: roots close
    lam = complex(np.linalg.eigvals(near)[np.argmax(np.linalg.eigvals(near).imag)])
    mode = modes.DampedMode("bounce", lam, abs(lam) / (2 * np.pi), lam.imag / (2 * np.pi), -lam.real / abs(lam), False, 1.0)
    assert modes.root_sensitivities(near, {"bounce": mode}, da, 0.01 * k) is None
    over = modes.DampedMode("bounce", complex(-5.0), 5.0 / (2 * np.pi), 0.0, 1.0, True, 1.0)
    assert modes.root_sensitivities(near, {"bounce": over}, da, 0.01 * k) is None
