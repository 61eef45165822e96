"""A run of a ride scenario or a sweep, in layers (issue 45).

- :mod:`~tyrelab.vehicle.run.records`: the typed record of a run (:class:`~.records.VariantPlan`,
  :class:`~.records.SpeedRun`, :class:`~.records.RideResult`, the shared :class:`~.records.RideCache`);
- :mod:`~tyrelab.vehicle.run.rows`: one :class:`~.rows.SpeedRow` for time and spectral rows, and
  the Directive's exposure of a row;
- :mod:`~tyrelab.vehicle.run.track`: the track, its spectrum and the wheel inputs;
- :mod:`~tyrelab.vehicle.run.plan`: a variant's plan, each speed's linear model, the result;
- :mod:`~tyrelab.vehicle.run.time`, :mod:`~tyrelab.vehicle.run.frequency`: time and spectral runs;
- :mod:`~tyrelab.vehicle.run.spectral`: the frequency-domain core;
- :mod:`~tyrelab.vehicle.run.sweep`: sweeps and the expected-value pressure study;
- :mod:`~tyrelab.vehicle.run.output`: the JSON document and the results table.

:mod:`tyrelab.vehicle.ride` runs a scenario or a sweep with these and keeps every old name.
"""

__all__ = []  # the layers' names are their modules' (tyrelab.vehicle.ride re-exports them)
