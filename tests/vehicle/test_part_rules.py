"""Issue 35, Deliver 1: a part's rules are written once (tyrelab.vehicle.model.needs) and both the
model (on values) and the scenario file (on keys) apply them."""

import dataclasses

import pytest

from tyrelab.scenario_io import ScenarioError, parse_scenario
from tyrelab.vehicle.model import Axle, Cab, Chassis, Implement, Parts, assemble, needs, scenario_key
from tests.vehicle.golden_vehicle import _text_3d


def _problems(extra: str) -> list[str]:
    with pytest.raises(ScenarioError) as info:
        parse_scenario(_text_3d(extra))
    return info.value.problems


@pytest.mark.parametrize("section, kind, mount, head", [
    ("front_axle", "axle", "suspended", '[front_axle]\nmount = "suspended"\n'),
    ("cab", "cab", "suspended", '[cab]\nmount = "suspended"\n'),
    ("implement", "implement", "hitch_spring", '[implement]\nmount = "hitch_spring"\n'),
])
def test_the_scenario_asks_for_every_key_the_part_needs(section, kind, mount, head):
    problems = _problems(head)
    required = {p.split(" is required")[0] for p in problems if " is required" in p}
    assert required == {f"{section}.{scenario_key(f)}" for f in needs(kind, mount, three_d=True)}


def _parts(**kw):
    p = Parts(Chassis(4700.0, 5500.0, 0.95, 2400.0), Axle("front", 1.56, 5e5, 1.5e3, track_m=1.9),
              Axle("rear", -0.95, 6e5, 2e3, track_m=1.8))
    return dataclasses.replace(p, **kw)


@pytest.mark.parametrize("kind, part", [
    ("axle", Axle("front", 1.56, 5e5, 1.5e3, track_m=1.9, mount="suspended", roll_inertia_kg_m2=160.0, mass_kg=400.0,
                  suspension_stiffness_N_per_m=1.5e5)),
    ("cab", Cab(800.0, 600.0, 500.0, -0.3, 0.9, 0.5, -0.9, 1.2, 3e4, 2e3)),
    ("implement", Implement(800.0, 300.0, 300.0, 1.2, 0.8, "hitch_spring", 0.5, 0.6, 1.5e5, 1.5e4)),
])
def test_the_model_refuses_each_needed_field_that_is_not_positive(kind, part):
    where = {"axle": "front", "cab": "cab", "implement": "implement"}[kind]
    assemble(_parts(**{where: part}))  # as given: fine
    mount = "suspended" if kind in ("axle", "cab") else "hitch_spring"
    for name in needs(kind, mount, three_d=True):
        if not name.endswith(("_kg", "_kg_m2", "_N_per_m", "_N_m_per_rad", "track_m")):
            continue
        with pytest.raises(ValueError, match=name):
            assemble(_parts(**{where: dataclasses.replace(part, **{name: 0.0})}))
