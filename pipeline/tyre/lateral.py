"""A tyre's lateral stiffness where none is measured (issue 33): a stand-in from its vertical one.

No lateral stiffness of a rolling agricultural tyre is published in machine-readable form (the
thesis §1.9: Stayner & Boldero (1973) measured stationary tyres only; lateral stiffness about
independent of load, possibly rising with pressure). The stand-in scales the tyre's own
vertical (rolling) stiffness ``k_z`` by a ratio ``r = k_y / k_z`` taken from the published
parameter sets of the TMeasy tyre model (G. Rill, "An engineer's guess on tyre model parameter
made possible with TMeasy", 2017; as shipped with Project Chrono, BSD-3):

* ``r = 0.40``: the HMMWV 37x12.5R16.5 tyre (``data/vehicle/hmmwv/tire/HMMWV_TMeasyTire.json``:
  lateral 164.4 kN/m, vertical 411.1 kN/m);
* ``r = 0.80``: the rule of the Wheeled Vehicle Platform's TMeasy tyre (Chrono's
  ``WVP_TMeasyTire``: ``c_y = 0.8 c_z``, ``c_x = 0.9 c_z``).

:data:`RATIO` is their geometric mean, 0.57, and :data:`RATIO_95` the 95 % interval ×/÷ 2 around
it (0.28-1.13): it holds both sources with room, and spans the 50-500 kN/m per tyre that an
independent check of issue 33 found plausible for tractor tyres of 300-600 kN/m vertical
stiffness. It is a documented stand-in, flagged wherever it is used (the tyres table and
``ride.json``), as the vertical damping model's is.

Examples
--------
>>> e = estimate_lateral_stiffness(400.0)
>>> round(e["lateral_stiffness_kN_per_m"], 1), [round(x, 1) for x in e["ci95_kN_per_m"]]
(226.3, [113.1, 452.5])
"""

from __future__ import annotations

import math

from .. import _validate

__all__ = ["RATIO", "RATIO_95", "SOURCE", "estimate_lateral_stiffness"]

#: Lateral over vertical stiffness of a tyre: the geometric mean of TMeasy's 0.40 and 0.80.
RATIO = math.sqrt(0.40 * 0.80)
#: Its 95 % interval: ×/÷ 2.
RATIO_95 = (RATIO / 2.0, RATIO * 2.0)
#: Where the stand-in comes from (one line, for tables).
SOURCE = (f"stand-in k_y = {RATIO:.2f} k_z (TMeasy parameter sets, Rill 2017 / Project Chrono: 0.40-0.80; "
          f"95 % interval x/÷ 2)")


def estimate_lateral_stiffness(vertical_stiffness_kN_per_m: float) -> dict:
    """Lateral stiffness of one tyre from its vertical rolling stiffness (module docstring).

    Parameters
    ----------
    vertical_stiffness_kN_per_m : float
        The tyre's vertical stiffness, kN/m.

    Returns
    -------
    dict
        ``lateral_stiffness_kN_per_m``, ``ci95_kN_per_m`` ([low, high]), ``source``.

    See Also
    --------
    tyrelab.tyre.rolling.estimate_series_damping : the lateral element's series damper.

    Examples
    --------
    >>> e = estimate_lateral_stiffness(400.0)                 # k_y = 0.57 k_z, interval x/÷ 2
    >>> round(e["lateral_stiffness_kN_per_m"], 1), [round(v, 1) for v in e["ci95_kN_per_m"]]
    (226.3, [113.1, 452.5])
    """
    k = _validate.positive("vertical_stiffness_kN_per_m", vertical_stiffness_kN_per_m)
    return {"lateral_stiffness_kN_per_m": RATIO * k, "ci95_kN_per_m": [RATIO_95[0] * k, RATIO_95[1] * k],
            "source": SOURCE}
