"""``tyrelab.vehicle.lti`` is :mod:`tyrelab.vehicle.solvers.lti` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .solvers import lti as _moved

sys.modules[__name__] = _moved
