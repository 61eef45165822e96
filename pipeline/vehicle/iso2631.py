"""``tyrelab.vehicle.iso2631`` is :mod:`tyrelab.vehicle.comfort.iso2631` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .comfort import iso2631 as _moved

sys.modules[__name__] = _moved
