"""``tyrelab.vehicle.iso2631_5`` is :mod:`tyrelab.vehicle.comfort.iso2631_5` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .comfort import iso2631_5 as _moved

sys.modules[__name__] = _moved
