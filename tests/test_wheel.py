"""The built wheel installs in a clean virtualenv and works from an empty folder (issue 10).

Slow (builds the sdist and the wheel, installs tyrelab and its dependencies
from the package index or pip's cache, runs the small campaign through every
stage): ``make test-package`` runs it, and so does ``.ci/run``.
"""

import os
import subprocess
import sys
import venv
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]

pytestmark = pytest.mark.slow


def run(argv, cwd, env=None, timeout=1800):
    p = subprocess.run([str(a) for a in argv], cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    out = p.stdout + p.stderr
    assert "Traceback" not in out, f"{argv}: traceback\n{out[-4000:]}"
    return p


def test_wheel_in_a_fresh_venv_runs_generate_run_sql_report(tmp_path):
    dist = tmp_path / "dist"
    # sdist first, then the wheel built from the sdist: both must carry the shipped data
    p = run([sys.executable, "-m", "build", "--outdir", dist, REPO], cwd=tmp_path)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    wheel = next(dist.glob("tyrelab-*.whl"))

    env_dir = tmp_path / "venv"
    venv.create(env_dir, with_pip=True)
    py, tyrelab = env_dir / "bin" / "python", env_dir / "bin" / "tyrelab"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    p = run([py, "-m", "pip", "install", "--quiet", wheel], cwd=tmp_path, env=env)
    assert p.returncode == 0, p.stderr[-3000:]

    empty = tmp_path / "empty"
    empty.mkdir()
    p = run([py, "-c", "import tyrelab; print(tyrelab.__file__)"], cwd=empty, env=env)
    assert p.returncode == 0 and str(env_dir) in p.stdout
    p = subprocess.run([str(py), "-c", "import pipeline"], cwd=empty, env=env, capture_output=True, text=True)
    assert p.returncode != 0 and "No module named 'pipeline'" in p.stderr

    for argv in (["generate", "--out", "raw", "--scale", "small"], ["run", "--raw", "raw", "--build", "build"]):
        p = run([tyrelab, *argv], cwd=empty, env=env)
        assert p.returncode == 0, f"{argv}: exit {p.returncode}\n{p.stderr[-3000:]}"
    p = run([tyrelab, "sql", "select count(*) as n from results", "--format", "json"], cwd=empty, env=env)
    # 169 stepped-sine runs and issue 34's 12 runs of the other methods and directions
    assert p.returncode == 0 and '"n":181' in p.stdout.replace(" ", ""), p.stdout + p.stderr
    report = empty / "build" / "reports" / "index.html"
    assert report.is_file() and "tyrelab" in report.read_text(encoding="utf-8").lower()
    # the documents the chapters link to are shipped (tyrelab.docs) and rendered beside them
    assert 'id="chapter-3"' in (empty / "build" / "reports" / "docs" / "findings.html").read_text(encoding="utf-8")
    # the library, from the same venv, on one of the generated runs
    code = ("import csv, tyrelab; row = next(r for r in csv.DictReader(open('raw/manifest.csv')) "
            "if r['kind'] == 'measurement'); res = tyrelab.analyze_recording('raw/' + row['file'], "
            "float(row['axle_mass_kg'])); print(100 < res.stiffness_kN_per_m < 1000)")
    p = run([py, "-c", code], cwd=empty, env=env)
    assert p.returncode == 0 and p.stdout.strip() == "True", p.stderr
