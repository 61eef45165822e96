"""tyrelab: a measurement-data pipeline for the suspension characteristics of
agricultural tractor tyres (Lines 1991, "The Suspension Characteristics of
Agricultural Tractor Tyres", PhD thesis, Cranfield/Silsoe).

The package is organised by thesis chapter:

- :mod:`tyrelab.measurement` -- chapter 3, the apparent-mass method.
- :mod:`tyrelab.tyre`        -- chapters 4-5, stiffness and damping regressions.
- :mod:`tyrelab.vehicle`     -- chapters 6-8, simulators and ride metrics.
- :mod:`tyrelab.rig`         -- the virtual dynamic tyre test vehicle.
- :mod:`tyrelab.rawformat`   -- raw recording format v1 (channels, readers, validator).
- :mod:`tyrelab.stages`      -- thin I/O stages that call the pure functions.

The library's entry points are importable from here; they and the
subpackages are imported on first use (PEP 562), so ``import tyrelab`` stays
cheap.

Examples
--------
>>> import tyrelab
>>> tyrelab.analyze_recording.__module__
'tyrelab.api'
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
        "api": ["analyse_recording", "analyze_recording", "ride"],
        "measurement.recording": ["RecordingResult", "WelchEstimate", "analyse_frame"],
        "measurement.apparent_mass": ["tyre_force", "stiffness_damping"],
        "rawformat": ["CHANNELS", "RunFileError", "read_run_file", "check_run"],
        "warehouse": ["connect_read_only", "query"],
    },
    reexport=False,
)
