"""``tyrelab.vehicle.metrics`` is :mod:`tyrelab.vehicle.comfort.metrics` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .comfort import metrics as _moved

sys.modules[__name__] = _moved
