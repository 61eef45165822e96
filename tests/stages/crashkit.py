"""Helpers for the crash-safety and concurrency tests: a campaign and a `tyrelab run` subprocess."""

import subprocess
import sys

from tests.synthetic import manifest_row, spring_damper_recording, write_campaign

#: The stages these tests exercise (the ones that write the tables and the warehouse).
STAGES = ["ingest", "analyse", "calibrate", "warehouse"]  # calibrate writes results


def campaign(folder, n=24):
    """A campaign of ``n`` good runs of two lengths."""
    return write_campaign(folder, [
        (manifest_row(f"r{i:03d}", f"r{i:03d}.parquet", pressure_bar=0.8 + 0.05 * i),
         spring_damper_recording(duration_s=30.0 + 10 * (i % 2), force_noise_N=50, seed=i)) for i in range(n)])


def start_run(raw, build, *extra, stages=STAGES, repeat=1, env=None):
    """Start ``tyrelab run`` (restricted to ``stages``) in a subprocess, ``repeat`` times in a row
    (``env``: its environment, e.g. :attr:`tests.holds.Holds.env`)."""
    code = (
        "import sys, tyrelab.stages as s; s.ORDER[:] = %r\n"
        "from tyrelab.cli import main\n"
        "for _ in range(%d): rc = main(['run', '--raw', %r, '--build', %r, '--jobs', '1', *%r])\n"
        "sys.exit(rc)" % (list(stages), repeat, str(raw), str(build), list(extra))
    )
    return subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=env)
