"""tyrelab: a measurement-data pipeline for the suspension characteristics of
agricultural tractor tyres (Lines 1991, "The Suspension Characteristics of
Agricultural Tractor Tyres", PhD thesis, Cranfield/Silsoe).

The package is organised by thesis chapter:

- :mod:`tyrelab.measurement` -- chapter 3, the apparent-mass method.
- :mod:`tyrelab.tyre`        -- chapters 4-5, stiffness and damping regressions.
- :mod:`tyrelab.vehicle`     -- chapters 6-8, simulators and ride metrics.
- :mod:`tyrelab.rig`         -- the virtual dynamic tyre test vehicle.
- :mod:`tyrelab.stages`      -- thin I/O stages that call the pure functions.
"""

__version__ = "0.1.0"
