"""Tyre stiffness and damping, thesis chapters 4-5: sizes, the formula, regressions, export.

Every public name of the submodules below (their ``__all__``) is importable from here; a submodule
is imported on first use (:mod:`tyrelab._lazy`). One tyre run's K and C is
:func:`tyrelab.analyse_recording`.

.. rubric:: Sizes and the empirical formula

.. autosummary::

   sizes             -- tyre size designations, inch and metric (``parse_tyre_size``, rolling circumference).
   stiffness         -- rolling stiffness from size, age and pressure, with its interval (``estimate_stiffness``).
   formula_fit       -- the formula K = a + b R + c A + d W R P as a fitted model (the thesis' or your lab's).
   formula_accuracy  -- how well the formula predicts rolling stiffness (§4.5.3).
   models            -- the stiffness models from tables: the thesis' and a build's.

.. rubric:: Regressions of chapters 4 and 5

.. autosummary::

   conditions        -- which runs count for which thesis regression: the one place for the convention.
   regressions       -- stiffness and damping on pressure, speed, load, amplitude, frequency (Tables III-X).
   size_regressions  -- across-tyre regressions the formula's coefficients rest on (§4.4.4, §4.5.3).
   speed_dependence  -- a measured tyre's K or C at any speed from its per-speed fits.
   damping_fit       -- damping of an unmeasured tyre from the Table VII lines.
   spoke             -- the rotating-spoke damping model (§5.5.2).

.. rubric:: Lateral and longitudinal

.. autosummary::

   lateral           -- a tyre's lateral stiffness where none is measured (a stand-in from its vertical one).
   rolling           -- a rolling tyre's series damper c2 = a / v and its stand-in (§2.5).
   directional       -- a tyre's lateral and longitudinal coefficients: scenario, build, catalogue, stand-in.

.. rubric:: Export

.. autosummary::

   mf_tyre           -- a measured tyre as MF-Tyre ``.tir`` files and K(P), C(P) tables.

.. rubric:: Example data

.. autosummary::

   examples          -- one made-up tyre's runs, the data of this package's Examples (``demo_runs``).
"""

from .._lazy import attach

__getattr__, __dir__ = attach(__name__)
