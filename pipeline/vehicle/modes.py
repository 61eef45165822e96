"""``tyrelab.vehicle.modes`` is :mod:`tyrelab.vehicle.solvers.modes` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .solvers import modes as _moved

sys.modules[__name__] = _moved
