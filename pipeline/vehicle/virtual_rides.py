"""``tyrelab.vehicle.virtual_rides`` is :mod:`tyrelab.vehicle.studies.virtual_rides` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .studies import virtual_rides as _moved

sys.modules[__name__] = _moved
