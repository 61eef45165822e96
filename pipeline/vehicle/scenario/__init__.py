"""Ride scenarios: what a scenario file says, how it is read and checked, its limits and its variants
(issue 13; a package since issue 45).

- :mod:`~tyrelab.vehicle.scenario.specs`: the scenario's tables as frozen dataclasses
  (:class:`Scenario`, :meth:`Scenario.parts`);
- :mod:`~tyrelab.vehicle.scenario.parse`: TOML text or a dict to a checked :class:`Scenario`
  (every problem at once, :class:`ScenarioError`), the key table;
- :mod:`~tyrelab.vehicle.scenario.limits`: each number's range and the work a sweep may create;
- :mod:`~tyrelab.vehicle.scenario.variants`: other speeds, pressures and key values, ``--set``, a
  sweep's variants and what it may sweep.

Every name that ``tyrelab.vehicle.scenario`` held as a module is importable from here.
"""

from .specs import (AxleSpec, BallastSpec, CabSpec, ExposureSpec, ImplementSpec, Scenario, ScenarioError, SeatSpec,
                    SimulationSpec, SurfaceSpec, SweepSpec, TractorSpec, TyreSpec)
from .parse import key_table, numeric_key, parse_scenario, scenario_from_dict
from .parse import (_build, _check_value, _control_characters, _crg_problems, _float_or_none, _floats,  # noqa: F401
                    _from_document, _given, _is_number, _missing, _parts_problems, _plain, _profile_problems,
                    _resolve_inside, _section_values, _sections, _speed_values, _sweep_key_problems, _validate)
from .variants import MAX_SET_COMBINATIONS, parse_sets, sweep_variants, with_overrides, with_values

#: The module's old name of :data:`~tyrelab.vehicle.scenario.variants.MAX_SET_COMBINATIONS` (``--set``'s
#: combinations; a sweep's variants are bounded by :data:`tyrelab.vehicle.scenario.limits.MAX_VARIANTS`).
MAX_VARIANTS = MAX_SET_COMBINATIONS

__all__ = [
    "Scenario",
    "TractorSpec",
    "SeatSpec",
    "TyreSpec",
    "SurfaceSpec",
    "ExposureSpec",
    "SimulationSpec",
    "SweepSpec",
    "AxleSpec",
    "CabSpec",
    "ImplementSpec",
    "BallastSpec",
    "ScenarioError",
    "parse_scenario",
    "scenario_from_dict",
    "key_table",
    "with_overrides",
    "with_values",
    "numeric_key",
    "parse_sets",
    "sweep_variants",
]
