"""Issue 45, Deliver 2: gravity and km/h each written once in tyrelab (:mod:`tyrelab.units`).

The standard gravity 9.80665 m/s² is :data:`tyrelab.units.STANDARD_GRAVITY_M_S2`; the thesis' 9.81,
which the chapter 6 and 7 studies need to reproduce the printed tables, is
:data:`~tyrelab.vehicle.studies.carriage.THESIS_GRAVITY_M_S2`. :mod:`tyrelab.units` sits below every
package (the raw format, the rig, the measurement methods and the tyre package import it as the
vehicle model does), so the whole package is checked, not only ``vehicle/``.
"""

import ast
from pathlib import Path

import numpy as np

import tyrelab
from tyrelab import units

#: Gravity written as a number.
GRAVITY_VALUES = (9.81, 9.80665)
#: The units' one home, and the thesis' 9.81 of the chapter 6 study (a named constant).
GRAVITY_HOMES = {"units.py", "vehicle/studies/carriage.py"}


def _numbers(tree):
    """(line, kind) of each gravity literal and each ``x / 3.6``, ``x * 3.6`` or ``3.6 * x`` in the code."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and type(node.value) is float and node.value in GRAVITY_VALUES:
            yield node.lineno, "gravity"
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Div, ast.Mult)):
            sides = (node.right,) if isinstance(node.op, ast.Div) else (node.left, node.right)
            if any(isinstance(x, ast.Constant) and x.value == 3.6 for x in sides):
                yield node.lineno, "km/h"


def _found(kind: str, allowed) -> list[str]:
    root = Path(tyrelab.__file__).parent
    out = []
    for path in sorted(root.rglob("*.py")):
        if path.relative_to(root).as_posix() in allowed:
            continue
        text = path.read_text(encoding="utf-8")
        for no, k in _numbers(ast.parse(text)):
            if k == kind:
                out.append(f"{path.relative_to(root)}:{no}: {text.splitlines()[no - 1].strip()}")
    return out


def test_one_gravity_in_the_package():
    found = _found("gravity", GRAVITY_HOMES)
    assert not found, "gravity written by hand (use tyrelab.units.STANDARD_GRAVITY_M_S2):\n" + "\n".join(found)


def test_one_km_h_conversion_in_the_package():
    found = _found("km/h", {"units.py"})
    assert not found, "km/h converted by hand (use tyrelab.units.km_h_to_m_s):\n" + "\n".join(found)


def test_the_check_finds_what_it_should():
    def kinds(text):
        return [k for _, k in _numbers(ast.parse(text))]

    for text in ("g = 9.81", "x * 9.80665", "v = s / 3.6", "v / 3.6 * dt", "a = 3.6 * v", "a = v*3.6"):
        assert kinds(text), text
    for text in ("x = 19.81", "y = 9.812", "'9.81'", "'13.6-38'", "k = 3.65 * x", "t = 3.6 / v", "f(3.6)"):
        assert not kinds(text), text


def test_the_gravity_copies_below_the_vehicle_package_are_the_standard_one():
    from tyrelab.measurement import methods
    from tyrelab.rawformat import rides
    from tyrelab.rig import instrument
    from tyrelab.vehicle import virtual_rides

    assert units.STANDARD_GRAVITY_M_S2 == 9.80665
    for copy in (rides.GRAVITY_M_S2, instrument.G, methods._G, virtual_rides.GRAVITY_M_S2):
        assert copy == units.STANDARD_GRAVITY_M_S2


def test_the_thesis_studies_keep_the_thesis_gravity_and_the_model_the_standard_one():
    from tyrelab.vehicle import carriage
    from tyrelab.vehicle.model import Assembly, assemble
    from tyrelab.vehicle.tractor import Tractor, tractor_parts

    assert carriage.THESIS_GRAVITY_M_S2 == 9.81 and carriage.GRAVITY_M_S2 == 9.81
    t = Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3)
    standard, thesis = assemble(tractor_parts(t)), assemble(tractor_parts(t), carriage.THESIS_GRAVITY_M_S2)
    assert isinstance(standard, Assembly) and standard.gravity_m_s2 == units.STANDARD_GRAVITY_M_S2
    # the static loads (the lift-off floors) scale with the assembly's gravity: the whole weight
    total = sum(standard.static_tyre_loads_N().values())
    np.testing.assert_allclose(total, 5120.0 * units.STANDARD_GRAVITY_M_S2, rtol=1e-12)
    np.testing.assert_allclose(sum(thesis.static_tyre_loads_N().values()), 5120.0 * 9.81, rtol=1e-12)
    floors = {e.name: e.floor_N for e in thesis.elements if e.input is not None}
    assert floors == {k: -v for k, v in thesis.static_tyre_loads_N().items()}


def test_the_time_domain_solver_refuses_a_gravity_not_its_assemblies():
    import pytest

    from tyrelab.vehicle.model import assemble
    from tyrelab.vehicle.tractor import Tractor, simulate, tractor_parts

    asm = assemble(tractor_parts(Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3)))
    u = np.zeros((1, 2, 21))
    with pytest.raises(ValueError, match="gravity_m_s2"):
        simulate([asm], u, u, gravity_m_s2=9.81)
    assert simulate([asm], u, u, gravity_m_s2=units.STANDARD_GRAVITY_M_S2)["method_used"][0] == "exact"


def test_km_h_to_m_s_is_the_division_it_replaced():
    speeds = np.array([0.5, 7.0, 10.0, 12.3, 16.0, 40.0])
    assert np.array_equal(units.km_h_to_m_s(speeds), speeds / 3.6)
    assert units.km_h_to_m_s(36.0) == 10.0
