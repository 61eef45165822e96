"""``tyrelab.vehicle.measured_ride`` is :mod:`tyrelab.vehicle.comfort.measured_ride` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .comfort import measured_ride as _moved

sys.modules[__name__] = _moved
