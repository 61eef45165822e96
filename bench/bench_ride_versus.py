"""The ride's speed before and after a change, both in one process (issue 35, Deliver 6).

The code of another revision (``--old``, default ``main``) is checked out beside this one
(``git archive`` of its ``pipeline/`` into a temporary folder, imported as ``tyrelab_old``)
and the same three jobs are timed with each, alternating, in CPU seconds (BLAS threads
pinned to 1), the median of ``--repeat`` rounds:

* ``one_scenario`` — :func:`tyrelab.vehicle.ride.ride` of the shipped ``modern_tractor.toml``
  (4 speeds, 750 s of driving at 1 ms), without figure data;
* ``rk4_baseline`` — the nonlinear RK4 pitch-plane tractor
  (:func:`tyrelab.vehicle.tractor.simulate_tractor`, ``method="rk4"``) on that scenario's
  16 km/h run (the inputs built once, by the new code, for both);
* ``fd_10000`` — :func:`tyrelab.vehicle.ride.expected_sweep`, 50 x 50 pressure pairs x 4
  speeds = 10,000 frequency-domain variant-speeds.

Prints JSON: per job the old and new CPU seconds and ``new/old`` (target <= 1.1), and whether
the numbers agree (the largest relative difference).

    .venv/bin/python bench/bench_ride_versus.py [--old REV] [--repeat 3] [--skip-fd]
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import importlib  # noqa: E402
import io  # noqa: E402
import json  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tarfile  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def old_package(rev: str, where: Path) -> str:
    """Extract ``pipeline/`` of ``rev`` to ``where/tyrelab_old`` and put it on the path."""
    blob = subprocess.run(["git", "-C", str(ROOT), "archive", rev, "pipeline"], check=True, capture_output=True).stdout
    with tarfile.open(fileobj=io.BytesIO(blob)) as tar:
        tar.extractall(where, filter="data")
    (where / "pipeline").rename(where / "tyrelab_old")
    sys.path.insert(0, str(where))
    return subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", rev], check=True, capture_output=True,
                          text=True).stdout.strip()


def _cpu(fn, *args, **kw):
    c0 = time.process_time()
    out = fn(*args, **kw)
    return out, time.process_time() - c0


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--old", default="main", help="the revision to compare with (default main)")
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--skip-fd", action="store_true", help="leave out the 10,000 frequency-domain variant-speeds")
    args = p.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        rev = old_package(args.old, Path(tmp))
        mods = {}
        for name, pkg in (("old", "tyrelab_old"), ("new", "tyrelab")):
            mods[name] = {m: importlib.import_module(f"{pkg}.{m}") for m in ("vehicle.ride", "vehicle.tractor",
                                                                               "scenario_io", "resources")}
        return _run(mods, rev, args)


def _run(mods: dict, rev: str, args) -> int:
    new = mods["new"]
    path = new["resources"].scenarios_dir() / "modern_tractor.toml"
    sc = {k: m["scenario_io"].load_scenario(path) for k, m in mods.items()}
    ride = new["vehicle.ride"]
    s = sc["new"]
    tyres = ride.resolve_tyres(s)
    track = ride.build_profile(s)
    i = list(s.exposure.speeds_km_h).index(16.0)
    tr = new["vehicle.tractor"].Tractor.of_parts(ride.build_parts(s, tyres, i))
    v, wb = 16.0 / 3.6, s.tractor.wheelbase_m
    _, stop = ride._record_window(track, wb, v, None)
    fp = (float(tyres["front"].footprint_m[i]), float(tyres["rear"].footprint_m[i]))
    inputs = ride.axle_inputs(track.profile, s.surface.enveloping, fp, (tyres["front"].radius_m, tyres["rear"].radius_m),
                              v, wb, stop)
    fronts = [round(0.8 + 1.6 * i / 49, 4) for i in range(50)]
    rears = [round(0.6 + 1.4 * i / 49, 4) for i in range(50)]

    def jobs(k):
        m = mods[k]
        t = m["vehicle.tractor"]
        tractor = t.Tractor(**{f: getattr(tr, f) for f in t.PARAMETERS}, longitudinal_model=tr.longitudinal_model)
        out = {"one_scenario": lambda: m["vehicle.ride"].ride(sc[k], with_spectra=False).speeds,
               "rk4_baseline": lambda: t.simulate_tractor(tractor, *inputs, lift_off=True, method="rk4")}
        if not args.skip_fd:
            out["fd_10000"] = lambda: m["vehicle.ride"].expected_sweep(sc[k], fronts, rears)
        return out

    for k in mods:  # warm-up: imports, caches
        m = mods[k]
        m["vehicle.ride"].ride(m["scenario_io"].load_scenario(path), with_spectra=False)
    times = {k: {} for k in mods}
    results = {}
    for _ in range(args.repeat):
        for k in ("old", "new"):
            for job, fn in jobs(k).items():
                res, cpu = _cpu(fn)
                times[k].setdefault(job, []).append(cpu)
                results[(k, job)] = res
    report = {"old": rev, "new": "this checkout", "repeat": args.repeat,
              "load_average_1min": round(os.getloadavg()[0], 1), "jobs": {}}
    for job in times["new"]:
        o, n = float(np.median(times["old"][job])), float(np.median(times["new"][job]))
        report["jobs"][job] = {"old_cpu_s": round(o, 3), "new_cpu_s": round(n, 3), "new_over_old": round(n / o, 3),
                               "max_relative_difference": _difference(results[("old", job)], results[("new", job)])}
    print(json.dumps(report, indent=2))
    return 0


def _difference(a, b) -> float:
    """Largest difference relative to each quantity's largest magnitude (0.0: the same bits)."""
    if isinstance(a, dict):
        pairs = [(a[k], b[k]) for k in a if k != "method_used"]
    else:
        cols = [c for c in a.columns if pd.api.types.is_numeric_dtype(a[c]) and not pd.api.types.is_bool_dtype(a[c])]
        pairs = [(a[c].to_numpy(float), b[c].to_numpy(float)) for c in cols]
    worst = 0.0
    for x, y in pairs:
        x, y = np.asarray(x, float), np.asarray(y, float)
        scale = np.nanmax(np.abs(x)) if np.isfinite(x).any() else 0.0
        d = np.nanmax(np.abs(x - y)) if x.size else 0.0
        worst = max(worst, float(d / scale) if scale else float(d))
    return float(f"{worst:.3g}")


if __name__ == "__main__":
    raise SystemExit(main())
