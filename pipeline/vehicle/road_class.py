"""``tyrelab.vehicle.road_class`` is :mod:`tyrelab.vehicle.terrain.road_class` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .terrain import road_class as _moved

sys.modules[__name__] = _moved
