"""``tyrelab.vehicle.profiles`` is :mod:`tyrelab.vehicle.terrain.profiles` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .terrain import profiles as _moved

sys.modules[__name__] = _moved
