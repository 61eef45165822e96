"""Old home of :mod:`tyrelab.vehicle.scenario.limits` (issue 45): its names, re-exported."""

from .scenario.limits import *  # noqa: F401,F403
from .scenario.limits import __all__  # noqa: F401
from .scenario.limits import _held_parts_problems, _known, _limit, _out, _profile_problems, _tyre_radius_m  # noqa: F401
