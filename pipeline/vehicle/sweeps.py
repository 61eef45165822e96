"""Old home of the sweep rules, now in :mod:`tyrelab.vehicle.scenario.variants` (issue 45): its names, re-exported."""

from .scenario.variants import PRESSURE_KEYS, pressure_axes, unused_key_problems  # noqa: F401
from .scenario.variants import _reason, _tyre_reason  # noqa: F401

__all__ = ["PRESSURE_KEYS", "pressure_axes", "unused_key_problems"]
