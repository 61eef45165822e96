"""``tyrelab.vehicle.daily_exposure`` is :mod:`tyrelab.vehicle.comfort.daily_exposure` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .comfort import daily_exposure as _moved

sys.modules[__name__] = _moved
