"""What spectral rows cost (issue 46): the constants of the spectral work estimate.

A spectral row is one variant at one speed computed in the frequency domain
(:func:`tyrelab.vehicle.ride.ride_sweep` with ``method="spectral"``). The work estimate
(:func:`tyrelab.vehicle.scenario.limits.work_estimate`) prices a sweep of ``v`` variants at ``s``
speeds at ``v * V + v * s * R`` seconds: ``R`` a row (``SECONDS_PER_SPECTRAL_ROW``, or
``SECONDS_PER_SPECTRAL_ROW_3D`` of the 3-D model: roll, the rolling tyre's damped modes per speed),
``V`` what a variant costs whatever its speeds (``SECONDS_PER_SPECTRAL_VARIANT``, ``_3D``: modes,
their intervals, the 3-D model's lateral A(8) interval), and
``SECONDS_PER_SPECTRAL_FIGURE_ROW`` more for each row with figure data (seat PSD and
transmissibility: the page's variant, every row of the simulate stage). ``MAX_SPECTRAL_SECONDS`` of
that estimate bound the rows of one command.

This measures them in CPU seconds of this process (BLAS threads pinned to 1; the shared machine's
load moves wall time, less so CPU time) on the shipped ``modern_tractor.toml`` (pitch plane) and
``modern_3d_tractor.toml`` (3-D), each warmed up first: one variant at many speeds (a ``--speeds``
list; without and with figure data) and many variants (front pressures) at one speed, and solves
the two for ``R`` and ``V``. Prints JSON: CPU ms of each case per row, ``R``, ``V`` and the
figure data's ms a row, and the constants of ``limits`` beside them.

    .venv/bin/python bench/bench_spectral_rows.py [--quick]
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from tyrelab.resources import scenarios_dir  # noqa: E402
from tyrelab.scenario_io import load_scenario  # noqa: E402
from tyrelab.vehicle.ride import ride_sweep  # noqa: E402
from tyrelab.vehicle.scenario import limits  # noqa: E402


def _cpu_ms_per_row(scenario, n_variants: int, n_speeds: int, with_spectra: bool) -> float:
    """CPU ms per spectral row of ``n_variants`` front pressures x ``n_speeds`` speeds (2-30 km/h; one: 16)."""
    speeds = [float(v) for v in np.linspace(2.0, 30.0, n_speeds)] if n_speeds > 1 else [16.0]
    fronts = [float(p) for p in np.linspace(0.8, 2.0, n_variants)] if n_variants > 1 else None
    c0 = time.process_time()
    results = ride_sweep(scenario, front_pressures_bar=fronts, speeds_km_h=speeds, method="spectral",
                         with_spectra=with_spectra, max_variants=10**6, max_rows=10**9)
    return 1e3 * (time.process_time() - c0) / (len(results) * n_speeds)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="fewer rows (a check that it runs, not a measurement)")
    args = p.parse_args(argv)
    k = 10 if args.quick else 1
    out = {"load_average_1min": round(os.getloadavg()[0], 1)}
    for label, name, n in (("pitch_plane", "modern_tractor.toml", 200 // k), ("three_d", "modern_3d_tractor.toml", 40 // k)):
        sc = load_scenario(scenarios_dir() / name)
        ride_sweep(sc, speeds_km_h=[8.0], method="spectral", with_spectra=True)  # warm-up: imports, caches
        speeds = _cpu_ms_per_row(sc, 1, n, False)  # V / n + R
        figures = _cpu_ms_per_row(sc, 1, n, True)
        variants = _cpu_ms_per_row(sc, max(2, n // 2), 1, False)  # V + R
        row = (n * speeds - variants) / (n - 1)
        out[label] = {f"one_variant_{n}_speeds_ms_per_row": round(speeds, 2),
                      f"one_variant_{n}_speeds_with_figure_data_ms_per_row": round(figures, 2),
                      f"{max(2, n // 2)}_variants_one_speed_ms_per_row": round(variants, 2),
                      "row_ms": round(row, 2), "variant_ms": round(variants - row, 2),
                      "figure_data_ms_per_row": round(figures - speeds, 2)}
    out["constants_ms"] = {name: getattr(limits, name) * 1e3 for name in (
        "SECONDS_PER_SPECTRAL_ROW", "SECONDS_PER_SPECTRAL_VARIANT", "SECONDS_PER_SPECTRAL_ROW_3D",
        "SECONDS_PER_SPECTRAL_VARIANT_3D",
        "SECONDS_PER_SPECTRAL_FIGURE_ROW")}
    print(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
