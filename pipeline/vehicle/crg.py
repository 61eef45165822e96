"""``tyrelab.vehicle.crg`` is :mod:`tyrelab.vehicle.terrain.crg` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .terrain import crg as _moved

sys.modules[__name__] = _moved
