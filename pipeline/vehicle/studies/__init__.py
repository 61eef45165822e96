"""The chapter 6 and 7 validation studies as pure functions (no file I/O).

**What "measured" means here.** The thesis compared simulations with vibration
recorded on the real carriage and tractor (§6.3, §7.1). Here the "measured" side is
*recordings*: arrays the caller passes (``recordings``), read by the ``simulate`` stage
from the campaign's vehicle recordings (``rides.csv`` rows with a ``study``, ingested by
the ``rides`` stage). Nothing here makes a measured number: the predictions are compared
with whatever was recorded, and a run without a recording has no comparison. The demo
campaign's recordings come from the *virtual carriage and tractor* of
:mod:`tyrelab.vehicle.study_recordings` (``tyrelab generate``), which include what the
linear prediction model leaves out (see ``docs/simulation.md``).

Predictions use the linear models and a profile *estimate*: for the carriage the
"surveyed" estimate (slat tops with ±3 mm survey error, §6.3 a) or the "recorded"
estimate (the enveloped locus plus a 1 mm noise floor and a spurious narrow-band peak at
1.35 cycles/m with 13x the power, as Fig. 51 and §6.5.1 describe; both seeded); for the
tractor the surveyed slatted track (SBT) or the farm track's (HH) survey, another
realisation of the same ISO 8608 class (the thesis' survey was years older than the runs,
§7.3). Every measure of a recording is made by the same function as the prediction's
(:func:`tyrelab.vehicle.metrics.compare_records`, :func:`run_metrics`).

Agreement statistics therefore measure how far the linear prediction is from the
recordings, not from the thesis' tractor; they are reported beside the thesis'.

The package (issue 45): :mod:`~tyrelab.vehicle.studies.chapter6` (the carriage study),
:mod:`~tyrelab.vehicle.studies.chapter7` (the tractor study), :mod:`~tyrelab.vehicle.studies.shared`
(their sampling and table checks), :mod:`~tyrelab.vehicle.studies.carriage` (the ch. 6 carriage),
:mod:`~tyrelab.vehicle.studies.bounce_pitch` (ch. 8), :mod:`~tyrelab.vehicle.studies.published_layouts`
(the digitised tables), :mod:`~tyrelab.vehicle.studies.study_recordings` and
:mod:`~tyrelab.vehicle.studies.virtual_rides` (the virtual vehicles' recordings). They import the
engine below them (model, solvers, terrain, comfort, run), never the reverse (import-linter,
``pyproject.toml``). Every name of the studies is importable from here, as before the split, and
each moved module from its old path (``tyrelab.vehicle.carriage`` is this package's ``carriage``).
"""

from ..tractor import simulate_tractor  # noqa: F401  (a name of the module before the split)
from .chapter6 import (carriage_case_inputs, carriage_key, carriage_steps, carriage_study,  # noqa: F401
                       carriage_track, profile_estimates)
from .chapter7 import (longitudinal_grid, run_metrics, tractor_case_inputs, tractor_inputs,  # noqa: F401
                       tractor_key, tractor_record_window, tractor_study, tractor_tracks, with_tractor_recordings)
from .shared import (DT_S, FRONT_7_50_18_RADIUS_M, FS_HZ, LEAD_IN_M, RECORDED_NOISE_RMS_M,  # noqa: F401
                     RECORDED_SPIKE, SURVEY_ERROR_M, T4_ROLLING_RADIUS_M, record_spectra)

__all__ = [
    "T4_ROLLING_RADIUS_M",
    "carriage_case_inputs",
    "carriage_study",
    "tractor_case_inputs",
    "longitudinal_grid",
    "tractor_study",
    "carriage_key",
    "tractor_key",
    "run_metrics",
    "with_tractor_recordings",
]
# carriage_track, carriage_steps, tractor_tracks, tractor_inputs and tractor_record_window are
# shared with tyrelab.vehicle.study_recordings (the virtual vehicles drive the studies' tracks
# and are recorded over the studies' windows); not part of the public interface.
