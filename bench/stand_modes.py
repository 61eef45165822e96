"""The virtual stand's fitted modes against the independent reference, over seeds (issue 43).

For each seed, speed (0, 6, 11 km/h) and case (the rear left pad excited, the other pads still or
correlated), the recording of :func:`tyrelab.stand.stand_recording` through :func:`tyrelab.vehicle_frf`,
and per checked mode (bounce in ``floor_z_m_s2``, pitch in ``pitch_rad_s2``, lateral–roll in
``roll_rad_s2`` and ``floor_y_m_s2``) the fitted mode nearest the reference's root
(``tests/test_stand_rolling.py``: a rigid body on Kelvin–Voigt and rolling tyres written with numpy
alone): the error of the damped frequency (%), of the damping ratio, of the natural frequency (%),
whether the reference lies in the 95 % intervals (``!`` where not) and ``UNDET`` where the mode is
marked undetermined. Then the counts: determined modes within 2 % and 0.03, their coverage.

    PYTHONPATH=.:tests .venv/bin/python bench/stand_modes.py 1991 7 11 23 42 101

Prints one line per recording, then the summary; ``--json`` one JSON object per recording instead.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections import Counter

CHECK = (("bounce", "floor_z_m_s2"), ("pitch", "pitch_rad_s2"), ("lateral_roll", "roll_rad_s2"),
         ("lateral_roll", "floor_y_m_s2"))


def main(argv=None) -> Counter:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("seeds", nargs="+", type=int)
    ap.add_argument("--speeds", default="0,6,11")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    sys.path.insert(0, "tests")
    from test_stand_rolling import _row, reference_modes  # the independent reference

    from tyrelab import stand
    from tyrelab.api import vehicle_frf

    sc = stand.stand_scenario()
    counts = Counter()
    for seed in args.seeds:
        for speed in (float(s) for s in args.speeds.split(",")):
            truth = reference_modes(sc, speed)
            for others in ("still", "correlated"):
                rec = stand.stand_recording(sc, _row(f"stand_rear_left_{others}_{speed:g}kmh"), seed)
                r = vehicle_frf(rec, speed_km_h=speed, scenario=sc)
                cells = []
                for name, out in CHECK:
                    fd, z = truth[name]
                    fn = fd / math.sqrt(1 - z * z)
                    if not r.modes[out]:
                        cells.append({"mode": name, "output": out})
                        continue
                    m = min(r.modes[out], key=lambda m: abs(complex(-m.damping_ratio * m.frequency_Hz, m.frequency_Hz)
                                                            - complex(-z * fd, fd)))
                    cell = {"mode": name, "output": out, "frequency_error_pct": 100 * (m.frequency_Hz / fd - 1),
                            "damping_error": m.damping_ratio - z,
                            "natural_frequency_error_pct": 100 * (m.natural_frequency_Hz / fn - 1),
                            "frequency_covered": bool(m.frequency_low_Hz <= fd <= m.frequency_high_Hz),
                            "damping_covered": bool(m.damping_low <= z <= m.damping_high),
                            "determined": bool(m.determined)}
                    cells.append(cell)
                    if out != "floor_y_m_s2":  # the lateral-roll pole is shared by roll and lateral: once
                        key = f"{name} {speed:g} km/h"
                        counts[key + " cases"] += 1
                        if not m.determined:
                            counts[key + " undetermined"] += 1
                        else:
                            counts[key + " within 2 % and 0.03"] += int(abs(cell["frequency_error_pct"]) <= 2
                                                                        and abs(cell["damping_error"]) <= 0.03)
                            counts[key + " intervals covering"] += int(cell["frequency_covered"]) + int(cell["damping_covered"])
                            counts[key + " intervals"] += 2
                if args.json:
                    print(json.dumps({"seed": seed, "speed_km_h": speed, "others": others, "modes": cells}), flush=True)
                    continue
                text = []
                for c in cells:
                    if "determined" not in c:
                        text.append(f"{c['mode']}/{c['output'][:7]} none")
                        continue
                    text.append(f"{c['mode']}/{c['output'][:7]} {c['frequency_error_pct']:+5.1f}%"
                                f"{'' if c['frequency_covered'] else '!'} {c['damping_error']:+.3f}"
                                f"{'' if c['damping_covered'] else '!'} fn {c['natural_frequency_error_pct']:+5.1f}%"
                                f"{'' if c['determined'] else ' UNDET'}")
                print(f"{seed} {speed:4.1f} {others:10s} " + " | ".join(text), flush=True)
    if not args.json:
        for key in sorted(counts):
            print(f"{key}: {counts[key]}")
    return counts


if __name__ == "__main__":
    main()
