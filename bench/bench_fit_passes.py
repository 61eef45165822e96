"""Regress's per-tyre fits in one pass against several passes (the progress steps of the stage).

Usage::

    python bench/bench_fit_passes.py --build BUILD [--repeats 5]

``BUILD`` is a build folder with ``parquet/results.parquet`` and ``parquet/tyres.parquet``
(e.g. ``tyrelab generate --out /tmp/x/raw --scale full --seed 1991`` then ``tyrelab run``).
:func:`tyrelab.stages.regress.tyre_fits_each` fits every measured tyre in 1 pass, in
:data:`~tyrelab.stages.regress.FIT_PASSES` passes, in 8 and in one pass per tyre; the passes are
interleaved, each ``--repeats`` times, in this process. CPU seconds (``time.process_time``,
min over the repeats) and their ratio to one pass. Prints one JSON object.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

import numpy as np
import pandas as pd


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", type=Path, required=True)
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    from tyrelab.stages import regress
    from tyrelab.tyre.regressions import measured_tyres

    results = pd.read_parquet(args.build / "parquet" / "results.parquet")
    results["tyre_id"] = results["tyre_id"].astype(str)
    tyres = pd.read_parquet(args.build / "parquet" / "tyres.parquet")
    results = results[[c for c in regress.FIT_INPUT_COLUMNS if c in results.columns]]
    ids = measured_tyres(results)
    rows_of = results.groupby("tyre_id", sort=False).indices

    def fit(passes: int) -> None:
        size = -(-len(ids) // passes)
        for start in range(0, len(ids), size):
            some = ids[start:start + size]
            regress.tyre_fits_each(results.iloc[np.sort(np.concatenate([rows_of[t] for t in some]))], some, tyres)

    variants = {"one_pass": 1, **{f"{n}_passes": n for n in sorted({regress.FIT_PASSES, 8})}, "pass_per_tyre": len(ids)}
    cpu = {name: [] for name in variants}
    load = os.getloadavg()[0]
    for _ in range(args.repeats):
        for name, passes in variants.items():
            t = time.process_time()
            fit(passes)
            cpu[name].append(time.process_time() - t)
    best = {name: min(v) for name, v in cpu.items()}
    print(json.dumps({"tyres": len(ids), "runs": len(results), "load_at_start": round(load, 2),
                      "cpu_s": {k: round(v, 3) for k, v in best.items()},
                      "ratio_to_one_pass": {k: round(v / best["one_pass"], 2) for k, v in best.items()}}, indent=1))


if __name__ == "__main__":
    main()
