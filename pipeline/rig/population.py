"""A generated tyre population whose rolling stiffness follows known coefficients (issue 27).

The thesis' formula ``K = a + b R + c A + d W R P`` was fitted to 1980s tyres. To check
that a lab's refit (:mod:`tyrelab.tyre.formula_fit`, ``estimate-stiffness --build``)
recovers *its* tyres' behaviour, the virtual rig can measure a population of tyres whose
true rolling lines follow other coefficients, :data:`MODERN_COEFFICIENTS`, each tyre off
the formula by its own factor ``1 + e`` (``e ~ N(0, tyre_sd)``, seeded):

    K_c = (a + b R + c A) (1 + e),   ΔK_p = d W R (1 + e)

The default coefficients are a documented choice, not a measurement: the intercept is
raised so that a 13.6R38 at 1 bar sits about 12 % above the thesis' formula, the size of
the gap that a published single-wheel-tester measurement of a modern radial (2001) shows
at 1 bar (docs/regressions.md), with the pressure term left at the thesis' 0.34 (that
measurement's pressure slope agreed with the formula) and a weaker age term (3 kN/m per
year). The stationary line and the damping follow the rig's rules for a new Berlin tyre
(:mod:`tyrelab.rig.truth`): stationary ``K_c`` 1.3 × rolling and ``ΔK_p`` 0.8 × rolling
(the medians of Table III's tyres with both rows), damping as a new 6-ply tyre.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate
from ..tyre.sizes import parse_tyre_size
from . import truth

__all__ = ["MODERN_COEFFICIENTS", "POPULATION_SIZES", "PopulationTyre", "tyre_population", "catalogue_rows"]

#: (a kN/m, b kN/m/in, c kN/m/year, d kN/m/in²/bar) of the generated population (module docstring).
MODERN_COEFFICIENTS = (215.0, -2.0, 3.0, 0.34)
#: Sizes drawn in order (cycled): modern radials and inch sizes spanning R 24-42 in and W·R 330-1100 in².
POPULATION_SIZES = ("380/85R28", "420/85R34", "480/70R38", "520/85R42", "600/65R38", "540/65R34",
                    "16.9R30", "18.4R38", "14.9R28", "650/65R42", "13.6R24", "710/70R42")
#: Stationary / rolling carcass stiffness and pressure dependence (medians over Table III's tyres with both rows).
_STATIONARY_KC, _STATIONARY_DKP = 1.3, 0.8
_PRESSURE_RANGE_BAR = (0.8, 2.0)


@dataclass(frozen=True)
class PopulationTyre:
    """One generated tyre: its catalogue facts, the truth constants and its own deviation.

    Attributes
    ----------
    params : tyrelab.rig.truth.TyreParams
        What the rig simulates.
    deviation : float
        ``e``: the tyre's relative deviation from the population formula.
    """

    params: truth.TyreParams
    deviation: float

    def true_rolling_kN_per_m(self, pressure_bar: float) -> float:
        """The tyre's true rolling stiffness (10-15 km/h pool), kN/m."""
        kc, dk = self.params.k_rolling
        return kc + dk * pressure_bar


def tyre_population(n: int, seed: int = 27, coefficients=MODERN_COEFFICIENTS, tyre_sd: float = 0.04,
                    max_age_years: float = 8.0) -> tuple[PopulationTyre, ...]:
    """``n`` tyres ``P01`` … with sizes from :data:`POPULATION_SIZES` and seeded ages and deviations.

    Parameters
    ----------
    n : int
        1-99 tyres.
    seed : int
        Seed of the ages and deviations (the same seed, the same population).
    coefficients : tuple of 4 float
        True ``(a, b, c, d)``.
    tyre_sd : float
        Standard deviation of each tyre's relative deviation ``e`` (0 <= sd < 0.5).
    max_age_years : float
        Ages are drawn uniformly from whole years 0 … max_age_years.

    Examples
    --------
    >>> pop = tyre_population(3, tyre_sd=0.0)
    >>> [p.params.tyre_id for p in pop], pop[0].params.size
    (['P01', 'P02', 'P03'], '380/85R28')
    """
    if not isinstance(n, (int, np.integer)) or not 1 <= n <= 99:
        raise ValueError(f"n must be an integer from 1 to 99, got {n!r}")
    a, b, c, d = (float(x) for x in coefficients)
    if not 0 <= float(tyre_sd) < 0.5:
        raise ValueError(f"tyre_sd must be in [0, 0.5), got {tyre_sd!r}")
    max_age = _validate.non_negative("max_age_years", max_age_years)
    rng = np.random.default_rng([int(seed) & 0xFFFFFFFF, 27])
    ages = rng.integers(0, int(max_age) + 1, size=n)
    dev = rng.standard_normal(n) * float(tyre_sd)
    out = []
    for i in range(n):
        size = POPULATION_SIZES[i % len(POPULATION_SIZES)]
        s = parse_tyre_size(size)
        f = 1.0 + float(dev[i])
        kc = (a + b * s.rim_diameter_in + c * float(ages[i])) * f
        dk = d * s.width_times_rim_in2 * f
        params = truth._t(f"P{i + 1:02d}", size, "rear_traction", 6, float(ages[i]), 45.0, None, _PRESSURE_RANGE_BAR,
                          (_STATIONARY_KC * kc, _STATIONARY_DKP * dk), (kc, dk), truth._new_tyre_damping(6),
                          "generated population (tyrelab.rig.population)",
                          f"true rolling line from K = {a:g} {b:+g} R {c:+g} A {d:+g} W R P times {f:.4f}")
        out.append(PopulationTyre(params, float(dev[i])))
    return tuple(out)


def catalogue_rows(population) -> list[dict]:
    """``tyres.csv`` rows (schemas/tyres.json columns) of a population, for the campaign folder."""
    rows = []
    for t in population:
        p, s = t.params, parse_tyre_size(t.params.size)
        rows.append({"tyre_id": p.tyre_id, "size": p.size, "position": p.group, "construction": s.construction,
                     "ply_rating": p.ply_rating, "age_years": p.age_years, "age_basis": "generated",
                     "lug_height_mm": p.lug_height_mm, "source": "tyrelab.rig.population",
                     "rolling_circumference_m": round(p.circumference_m, 4), "notes": p.notes})
    return rows
