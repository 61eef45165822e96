"""Vehicles on their tyres, thesis chapters 6-8 and beyond: ride prediction, exposure, validation.

Every public name of the submodules below (their ``__all__``) is importable from here; a submodule
is imported on first use (:mod:`tyrelab._lazy`). The entry points a user needs first are
:func:`tyrelab.ride` and :func:`tyrelab.exposure`.

The modules live in layers (issue 45; docs/architecture.md): ``units``; ``model`` and ``elements``;
the sub-packages ``terrain`` (ground input), ``comfort`` (exposure and its standards), ``solvers``
(LTI, the time domain, modes, the beam) and ``validation``; the scenario run; the thesis' studies on top
(``studies``: chapters 6-8, their published layouts and virtual recordings). A module
moved into a sub-package keeps its old name here (``tyrelab.vehicle.profiles`` is
``tyrelab.vehicle.terrain.profiles``, ``tyrelab.vehicle.carriage`` is ``tyrelab.vehicle.studies.carriage``).

.. rubric:: Ride prediction

.. autosummary::

   ride              -- a tractor scenario per speed and variant: seat a_w, A(8), hours (``ride``, ``ride_sweep``).
   scenario          -- scenario files in TOML: parsing, checks, overrides, sweeps (``parse_scenario``).
   scenario_limits   -- each scenario number's range and the work a sweep may create.
   model             -- the tractor as parts (chassis, axles, cab, implement, seat), assembled once.
   tractor           -- the ch. 7 tractor as twelve numbers on the time domain (solvers.time_domain: exact in contact, RK4 across lift-off).
   lti               -- exact first-order-hold solution of linear time-invariant systems.
   bounce_pitch      -- bounce and pitch natural frequencies of an unsuspended tractor (ch. 8).

.. rubric:: Ground input

.. autosummary::

   profiles          -- ground profiles: the slatted track stand-in, ISO 8608 tracks, spectra.
   enveloping        -- tyre enveloping filters of the ground input (§1.5, §6.3).
   crg               -- measured roads in OpenCRG files.
   road_class        -- the ISO 8608 class of a measured road profile.

.. rubric:: Exposure and its standards

.. autosummary::

   iso2631           -- ISO 2631-1:1997 frequency weighting, a_w, VDV, MTVV, crest factor, A(8).
   iso2631_5         -- ISO 2631-5:2018 spinal dose D_z of multiple shocks.
   daily_exposure    -- a driver's day of tasks: A(8) of the highest axis, ``governing_axis``, hours, HSE points.
   measured_ride     -- one streamed analysis of a recording (or of predicted signals).
   metrics           -- accuracy measures of thesis §6.4 and §7.4.

.. rubric:: The thesis' studies and validation

.. autosummary::

   carriage          -- the single-wheel carriage over a rough track (ch. 6).
   studies           -- the chapter 6 and 7 validation studies as pure functions.
   published_layouts -- the digitised Tables XII-XX in the layouts the studies use.
   study_recordings  -- recordings of the thesis' carriage and MF698T from virtual vehicles.
   virtual_rides     -- seeded recordings of virtual tractors (``tyrelab generate``).
   ride_validation   -- predictions checked against recordings (§6.4, §7.4).
"""

from .._lazy import attach

__getattr__, __dir__ = attach(__name__)
