"""``tyrelab.vehicle.ride_validation`` is :mod:`tyrelab.vehicle.validation.ride_validation` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .validation import ride_validation as _moved

sys.modules[__name__] = _moved
