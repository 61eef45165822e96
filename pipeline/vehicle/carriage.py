"""``tyrelab.vehicle.carriage`` is :mod:`tyrelab.vehicle.studies.carriage` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .studies import carriage as _moved

sys.modules[__name__] = _moved
