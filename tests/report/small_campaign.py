"""A tiny campaign through the real pipeline, for the report and browser tests.

Analytic spring-damper recordings (tests/synthetic.py) in raw format v1 for a
thesis tyre (T1) and a tyre of the campaign's own ``tyres.csv`` whose id is
``<script>alert(1)</script>``, at three pressures and two speeds so that the
regress stage can fit Table III, plus one noisy run that QC flags and one
manifest row whose file is missing (quarantined).
"""

from __future__ import annotations

import logging
from pathlib import Path

from tests.synthetic import manifest_row, spring_damper_recording, write_campaign

from tyrelab.stages import Context, ORDER, run_pipeline

#: Tyre id that must render as text, never as markup.
EVIL_TYRE = "<script>alert(1)</script>"
#: Stages skipped in the fast build (simulate runs the ch. 6-8 models for ~40 s).
SLOW_STAGES = ("simulate",)


def write_small_campaign(raw: Path, duration_s: float = 12.0) -> Path:
    """Write the campaign folder ``raw/small`` and return it."""
    runs = []
    i = 0
    for tyre, k0 in (("T1", 230e3), (EVIL_TYRE, 180e3)):
        for speed, c in ((0.0, 3000.0), (10.0, 1600.0)):
            for p in (0.83, 1.38, 1.93):
                i += 1
                k = k0 + 150e3 * p - (60e3 if speed else 0.0)
                rec = spring_damper_recording(k, c + 400 * p, duration_s=duration_s, seed=i)
                runs.append((manifest_row(f"r{i:03d}", f"r{i:03d}.parquet", tyre_id=tyre, speed_km_h=speed,
                                          pressure_bar=p), rec))
    noisy = spring_damper_recording(300e3, 2000.0, duration_s=duration_s, force_noise_N=40000.0,
                                    accel_noise_m_s2=30.0, seed=99)
    runs.append((manifest_row("r_noisy", "r_noisy.parquet", tyre_id="T1", speed_km_h=5.0), noisy))
    runs.append((manifest_row("r_missing", "r_missing.parquet", tyre_id="T1"), None))
    folder = write_campaign(Path(raw) / "small", runs)
    (folder / "tyres.csv").write_text(
        "tyre_id,size,position,construction,age_years,notes\n"
        f'"{EVIL_TYRE}",13.6R38,rear_traction,radial,3,"markup in an id must stay text"\n'
    )
    return folder


def build_small_report(tmp: Path, skip: tuple[str, ...] = SLOW_STAGES) -> Context:
    """Generate the campaign under ``tmp/raw`` and run the pipeline into ``tmp/build``."""
    raw, build = Path(tmp) / "raw", Path(tmp) / "build"
    write_small_campaign(raw)
    if "simulate" not in skip:  # Tables XIII, XIV, XVII compare the predictions with recordings
        from tyrelab.generate import write_rides

        write_rides(raw, seed=1991, tractors=False)
    ctx = Context(raw=raw, build=build, jobs=1, log=logging.getLogger("tyrelab.test"))
    run_pipeline(ctx, [s for s in ORDER if s not in skip])
    return ctx
