"""``tyrelab.vehicle.enveloping`` is :mod:`tyrelab.vehicle.terrain.enveloping` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .terrain import enveloping as _moved

sys.modules[__name__] = _moved
