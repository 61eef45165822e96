"""``tyrelab.vehicle.published_layouts`` is :mod:`tyrelab.vehicle.studies.published_layouts` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .studies import published_layouts as _moved

sys.modules[__name__] = _moved
