"""``tyrelab.vehicle.study_recordings`` is :mod:`tyrelab.vehicle.studies.study_recordings` (moved by issue 45; the old import path stays, the same module)."""

import sys

from .studies import study_recordings as _moved

sys.modules[__name__] = _moved
