"""tyrelab: a measurement-data pipeline for the suspension characteristics of
agricultural tractor tyres (Lines 1991, "The Suspension Characteristics of
Agricultural Tractor Tyres", PhD thesis, Cranfield/Silsoe).

.. rubric:: Entry points (one question each, a result object with ``to_dict()``)

.. autosummary::

   analyse_recording -- K, C and QC of one tyre-rig recording (``analyze_recording``: the same).
   ride              -- seat vibration and daily exposure of a tractor scenario.
   ride_sweep        -- the same for every variant of a sweep (pressures, swept keys).
   road_class        -- the ISO 8608 class of each track of a road profile or OpenCRG road.
   exposure          -- a driver's daily exposure from seat recordings.

.. rubric:: Packages, by thesis chapter

.. autosummary::

   measurement       -- chapter 3: the apparent-mass method, QC, calibration, uncertainty.
   tyre              -- chapters 4-5: sizes, the stiffness formula, regressions, export.
   vehicle           -- chapters 6-8: ride prediction, exposure, the thesis' studies.
   rig               -- the virtual dynamic tyre test vehicle.
   rawformat         -- raw recording format v1 (channels, readers, validator).
   warehouse         -- the DuckDB warehouse (``query``).
   stages            -- thin I/O stages that call the pure functions.

They and the subpackages are imported on first use (PEP 562), so ``import tyrelab`` stays cheap.

Examples
--------
>>> import tyrelab
>>> tyrelab.analyze_recording.__module__
'tyrelab.api'
>>> tyrelab.analyse_recording is tyrelab.analyze_recording
True
>>> tyrelab.CHANNELS[:2]
['accel_left_m_s2', 'accel_right_m_s2']
"""

from ._lazy import attach

__version__ = "0.1.0"

__getattr__, __dir__ = attach(
    __name__,
    submodules=["api", "measurement", "tyre", "vehicle", "rig", "rawformat", "report", "stages", "resources", "watch",
                "warehouse", "export", "exposure"],
    attrs={
        "api": ["analyse_recording", "analyze_recording", "ride", "ride_sweep", "road_class", "vehicle_frf"],
        "measurement.recording": ["RecordingResult", "WelchEstimate", "analyse_frame"],
        "measurement.apparent_mass": ["tyre_force", "stiffness_damping"],
        "rawformat": ["CHANNELS", "RunFileError", "read_run_file", "check_run"],
        "warehouse": ["connect_read_only", "query"],
    },
    reexport=False,
)
