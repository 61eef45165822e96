"""``tyrelab.vehicle.bounce_pitch`` is :mod:`tyrelab.vehicle.studies.bounce_pitch` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .studies import bounce_pitch as _moved

sys.modules[__name__] = _moved
