"""Old home of :mod:`tyrelab.vehicle.scenario.limits` (issue 45): its names, re-exported."""

from .scenario.limits import *  # noqa: F401,F403
from .scenario.limits import METHODS, _held_parts_problems, _known, _limit, _out, _profile_problems, _tyre_radius_m  # noqa: F401

__all__ = ["LIMITS", "RIDE_METHODS", "uses_spectral", "MAX_VARIANTS", "MAX_SPECTRAL_VARIANTS", "MAX_SAMPLES", "MIN_VERDICT_DURATION_S", "BYTES_PER_SAMPLE", "SECONDS_PER_SAMPLE", "SECONDS_PER_SPECTRAL_ROW", "MAX_TRACK_POINTS",
           "SECONDS_PER_SPECTRAL_VARIANT", "SECONDS_PER_SPECTRAL_ROW_3D", "SECONDS_PER_SPECTRAL_VARIANT_3D", "SECONDS_PER_SPECTRAL_FIGURE_ROW", "MAX_SPECTRAL_SECONDS", "BOUND_CEILINGS",
           "scenario_problems", "profile_problems", "override_problems", "track_length_m", "long_integer_problems", "work_estimate",
           "work_problems", "bound_argument"]
