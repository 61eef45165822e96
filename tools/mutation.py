"""Mutation testing of the pure physics and statistics with cosmic-ray (``make mutation``).

cosmic-ray mutates a source file *on disk*, runs a test command, and restores the file.
So that it never touches the working tree (and an interrupted run cannot leave a mutant
behind in it), the package is copied to ``<workdir>/tree/tyrelab``, and the tests run with
``PYTHONPATH=<workdir>/tree``: the import package is ``tyrelab`` while its source folder is
``pipeline/`` (setuptools ``package-dir``), and a folder on ``PYTHONPATH`` comes before the
editable install's finder, so the tests import the copy, the files cosmic-ray mutates.
``tyrelab.schemas``/``templates``/``data`` (not mutated) still resolve through the
editable install.

Each module is its own session (``<workdir>/<name>.sqlite``) with the test files that
exercise it as the test command (``pytest -x``), so one module can be run, resumed or
re-run alone::

    python tools/mutation.py                         # every module (hours on 2 cores)
    python tools/mutation.py vehicle/comfort/iso2631.py      # one module
    python tools/mutation.py --report                # scores of the sessions run so far

The score of a module is ``killed / (mutants - equivalent)``; the equivalent mutants are
listed, each with the reason, in ``tools/mutation_equivalents.toml`` (and
``docs/testing.md``) and matched by operator and the text of the mutated line, so that
they survive unrelated edits that move lines. Operators: cosmic-ray's core set minus
the ones that only produce noise on numeric code (bitwise and shift operators, ``%`` and
``//`` as replacements, exception/decorator removal and the variable inserter/replacer,
see ``EXCLUDED_OPERATORS``).
"""

from __future__ import annotations

import argparse
import json
import random
import re
import os
import shutil
import sqlite3
import subprocess
import sys
import time
import tomllib
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]

#: Module (relative to pipeline/) -> test files that exercise it.
MODULES: dict[str, list[str]] = {
    "measurement/apparent_mass.py": ["tests/measurement/test_apparent_mass.py", "tests/measurement/test_qc.py",
                                     "tests/measurement/test_uncertainty.py"],  # the residual probes
    "measurement/calibration.py": ["tests/measurement/test_calibration.py", "tests/stages/test_calibrate.py"],
    "measurement/methods.py": ["tests/measurement/test_methods.py"],
    "measurement/qc.py": ["tests/measurement/test_qc.py"],
    "tyre/conditions.py": ["tests/tyre/test_conditions.py", "tests/tyre/test_regressions.py"],
    "tyre/formula_accuracy.py": ["tests/tyre/test_formula_accuracy.py"],
    "tyre/regressions.py": ["tests/tyre/test_regressions.py", "tests/stages/test_regress.py::"
                            "test_every_comparison_table_gives_ours_minus_thesis_on_non_zero_differences"],
    "tyre/size_regressions.py": ["tests/tyre/test_size_regressions.py"],
    "tyre/sizes.py": ["tests/tyre/test_sizes.py"],
    "tyre/spoke.py": ["tests/tyre/test_spoke.py"],
    "tyre/stiffness.py": ["tests/tyre/test_stiffness.py", "tests/tyre/test_stiffness_estimate.py"],
    "vehicle/comfort/iso2631.py": ["tests/vehicle/test_iso2631.py"],
    "vehicle/studies/bounce_pitch.py": ["tests/vehicle/test_bounce_pitch.py"],
    "vehicle/studies/carriage.py": ["tests/vehicle/test_carriage.py"],
    "vehicle/tractor.py": ["tests/vehicle/test_metrics_tractor.py"],
    "vehicle/ride.py": ["tests/vehicle/test_ride.py"],
    # issue 45: the ride's layers (ride.py runs a scenario or a sweep with them)
    "vehicle/tyres.py": ["tests/vehicle/test_tyres.py", "tests/vehicle/test_ride.py"],
    "vehicle/run/spectral.py": ["tests/vehicle/test_ride.py", "tests/vehicle/test_spectral_ride.py"],
    "vehicle/run/time.py": ["tests/vehicle/test_ride.py", "tests/vehicle/test_ride_batch.py"],
    "vehicle/run/track.py": ["tests/vehicle/test_run_layers.py", "tests/vehicle/test_ride.py"],
}

#: Operators kept (cosmic-ray operator names). One mutant per site and kind, in the spirit
#: of Offutt's "sufficient" operator set: arithmetic swapped for its sibling (+ -, * /,
#: ** -> *), comparisons moved across the boundary or negated, a unary minus or a
#: ``not`` dropped, ``not`` added, constants +-1, boolean constants and ``and``/``or``
#: swapped, loops emptied, ``break``/``continue`` swapped. cosmic-ray's full set (every
#: operator to every other, bitwise and shift operators, exception/decorator removal,
#: variable insertion) multiplies the count by ~5 with mutants that numeric code kills at
#: import or on the first call.
KEPT_OPERATORS = re.compile(
    r"core/(ReplaceBinaryOperator_(Add_Sub|Sub_Add|Mul_Div|Div_Mul|Pow_Mul|FloorDiv_Div|Mod_FloorDiv)"
    r"|ReplaceComparisonOperator_(Lt_LtE|LtE_Lt|Gt_GtE|GtE_Gt|Eq_NotEq|NotEq_Eq|Is_IsNot|IsNot_Is|In_NotIn|NotIn_In)"
    r"|ReplaceUnaryOperator_(Delete_USub|Delete_Not)"
    r"|AddNot|NumberReplacer|ReplaceTrueWithFalse|ReplaceFalseWithTrue|ReplaceAndWithOr|ReplaceOrWithAnd"
    r"|ReplaceBreakWithContinue|ReplaceContinueWithBreak|ZeroIterationForLoop)$"
)

#: Seconds a mutant's test run may take, as a multiple of the unmutated run (plus a floor).
TIMEOUT_FACTOR, TIMEOUT_FLOOR_S = 4.0, 120.0


def _copy_tree(tree: Path) -> Path:
    """Fresh copy of pipeline/ as ``<tree>/tyrelab``; returns ``tree``."""
    if tree.exists():
        shutil.rmtree(tree)
    shutil.copytree(REPO / "pipeline", tree / "tyrelab", ignore=shutil.ignore_patterns("__pycache__"))
    return tree


def _env(tree: Path) -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(tree)] + ([env["PYTHONPATH"]] if env.get("PYTHONPATH") else []))
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    return env


def _test_command(tests: list[str]) -> str:
    return f"{sys.executable} -m pytest -x -q -p no:cacheprovider -p no:randomly -m 'not slow' " + " ".join(tests)


def _check_copy_is_imported(tree: Path, env: dict[str, str]) -> None:
    out = subprocess.run([sys.executable, "-c", "import tyrelab; print(tyrelab.__file__)"],
                         env=env, cwd=REPO, capture_output=True, text=True, check=True).stdout.strip()
    if not Path(out).resolve().is_relative_to(tree.resolve()):
        raise SystemExit(f"mutation: the tests import {out}, not the copy under {tree}")


def _name(module: str) -> str:
    return module.replace("/", ".").removesuffix(".py")


def _mutant_key(work_item) -> tuple:
    """Sort key of a work item that does not depend on its (random) job id."""
    return tuple((tuple(m.start_pos), tuple(m.end_pos), m.operator_name, m.occurrence) for m in work_item.mutations)


def select(session: Path, sample: int | None, seed: int = 2631) -> None:
    """Skip the mutants of operators not in ``KEPT_OPERATORS`` and, with ``sample``, all but a
    seeded random sample of ``sample`` of the rest (cosmic-ray's own filters do the same:
    a result with outcome ``skipped``)."""
    from cosmic_ray.work_db import WorkDB, use_db
    from cosmic_ray.work_item import WorkerOutcome, WorkResult

    with use_db(str(session), WorkDB.Mode.open) as db:
        # job ids are random uuids: order by what the mutant is, so that the same seed picks the
        # same mutants in every session of the same source
        items = sorted(db.pending_work_items, key=_mutant_key)
        kept = [w for w in items if all(KEPT_OPERATORS.match(m.operator_name) for m in w.mutations)]
        kept_ids = {w.job_id for w in kept}
        chosen = set(kept_ids)
        if sample is not None and sample < len(kept):
            chosen = {w.job_id for w in random.Random(seed).sample(kept, sample)}
        for w in items:
            if w.job_id not in chosen:
                reason = "not in the sample" if w.job_id in kept_ids else "operator not kept"
                db.set_result(w.job_id, WorkResult(output=reason, worker_outcome=WorkerOutcome.SKIPPED))


def rerun_survivors(session: Path) -> int:
    """Forget the survivors' results so that ``cosmic-ray exec`` runs them again (new tests)."""
    con = sqlite3.connect(session)
    n = con.execute("DELETE FROM work_results WHERE lower(test_outcome) = 'survived'").rowcount
    con.commit()
    con.close()
    return n


def run_module(module: str, workdir: Path, resume: bool, sample: int | None = None) -> None:
    """Copy the package, init and filter the session (unless resuming), execute it.

    Each module has its own copy (``<workdir>/<name>.tree``), so sessions of different
    modules can run side by side and a resumed session mutates the source it was made from.
    """
    name = _name(module)
    session, config, tree = (workdir / f"{name}.{ext}" for ext in ("sqlite", "toml", "tree"))
    resume = resume and session.exists() and tree.exists()
    if resume and (tree / "tyrelab" / module).read_bytes() == (REPO / "pipeline" / module).read_bytes():
        _copy_tree(tree)  # the module is as the session knows it: the rest of the package may be newer
    elif resume:
        print(f"mutation: {module} changed since its session began: starting it afresh", flush=True)
        resume = False
        if sample is None:  # as many as the old session tested, not the whole module
            with sqlite3.connect(session) as con:
                sample = con.execute("SELECT count(*) FROM work_results WHERE lower(worker_outcome) != 'skipped'"
                                     ).fetchone()[0] or None
    if not resume:
        session.unlink(missing_ok=True)
        _copy_tree(tree)
    env = _env(tree)
    _check_copy_is_imported(tree, env)
    tests = MODULES[module]
    t0 = time.perf_counter()
    base = subprocess.run(_test_command(tests), shell=True, env=env, cwd=REPO, capture_output=True, text=True)
    if base.returncode != 0:
        raise SystemExit(f"mutation: {module}: the tests fail without a mutant:\n{base.stdout[-2000:]}")
    timeout = max(TIMEOUT_FACTOR * (time.perf_counter() - t0), TIMEOUT_FLOOR_S)
    config.write_text(
        "[cosmic-ray]\n"
        f"module-path = {json.dumps(str(tree / 'tyrelab' / module))}\n"
        f"timeout = {timeout:.0f}\n"
        "excluded-modules = []\n"
        f"test-command = {json.dumps(_test_command(tests))}\n"
        "[cosmic-ray.distributor]\nname = \"local\"\n"
    )
    bin_ = Path(sys.executable).parent
    if not resume:
        subprocess.run([bin_ / "cosmic-ray", "init", config, session], env=env, cwd=REPO, check=True)
        select(session, sample)
    print(f"mutation: {module}: timeout {timeout:.0f} s per mutant, tests: {' '.join(tests)}", flush=True)
    subprocess.run([bin_ / "cosmic-ray", "exec", config, session], env=env, cwd=REPO, check=True)


def load_equivalents() -> list[dict]:
    path = REPO / "tools" / "mutation_equivalents.toml"
    return tomllib.loads(path.read_text())["equivalent"] if path.exists() else []


def survivors(session: Path) -> list[dict]:
    """Surviving mutants of a session: operator, line number, source line, diff."""
    con = sqlite3.connect(session)
    rows = con.execute(
        "SELECT m.operator_name, m.start_pos_row, m.module_path, r.diff FROM mutation_specs m "
        "JOIN work_results r ON r.job_id = m.job_id WHERE lower(r.test_outcome) = 'survived' "
        "ORDER BY m.start_pos_row").fetchall()
    con.close()
    out = []
    for op, row, path, diff in rows:
        lines = Path(path).read_text().splitlines() if Path(path).exists() else []
        text = lines[row - 1].strip() if 0 < row <= len(lines) else ""
        plus = [d[1:].strip() for d in (diff or "").splitlines() if d.startswith("+") and not d.startswith("+++")]
        out.append({"operator": op, "line": row, "source": text, "mutant": plus[0] if plus else "", "diff": diff or ""})
    return out


def counts(session: Path) -> dict[str, int]:
    """Work items per outcome: killed, survived, incompetent, skipped (filtered), pending."""
    con = sqlite3.connect(session)
    rows = con.execute(
        "SELECT lower(coalesce(r.test_outcome, r.worker_outcome, 'pending')), count(*) FROM work_items w "
        "LEFT JOIN work_results r ON r.job_id = w.job_id GROUP BY 1").fetchall()
    con.close()
    return {k: n for k, n in rows}


def report(workdir: Path, modules: list[str], verbose: bool) -> int:
    """Print the score per module; return 1 if any module is below 90 %."""
    equivalents = load_equivalents()
    print(f"{'module':34s} {'mutants':>7s} {'killed':>6s} {'surv.':>5s} {'equiv.':>6s} {'pending':>7s} {'score':>6s}")
    worst = 100.0
    for module in modules:
        session = workdir / f"{_name(module)}.sqlite"
        if not session.exists():
            print(f"{module:34s} (not run)")
            continue
        c = counts(session)
        surv = survivors(session)
        eq = [s for s in surv if any(e["module"] == module and e["operator"] == s["operator"]
                                      and e["mutant"] == s["mutant"] for e in equivalents)]
        killed = c.get("killed", 0) + c.get("incompetent", 0)
        pending = c.get("pending", 0)
        total = killed + len(surv)
        scored = total - len(eq)
        score = 100.0 * killed / scored if scored else 100.0
        worst = min(worst, score)
        print(f"{module:34s} {total:7d} {killed:6d} {len(surv) - len(eq):5d} {len(eq):6d} {pending:7d} {score:5.1f}%")
        if verbose:
            for s in surv:
                if s not in eq:
                    print(f"    SURVIVED {s['operator']} line {s['line']}: {s['source']}")
                    print(f"      -> {s['mutant']}")
    return 0 if worst >= 90.0 else 1


def markdown(workdir: Path, modules: list[str]) -> str:
    """The scores and the equivalent mutants as Markdown tables (for docs/testing.md)."""
    equivalents = load_equivalents()
    lines = ["| module | mutants tested | killed | survived | equivalent | score |", "|---|---|---|---|---|---|"]
    for module in modules:
        session = workdir / f"{_name(module)}.sqlite"
        if not session.exists():
            lines.append(f"| `{module}` | not run | | | | |")
            continue
        c, surv = counts(session), survivors(session)
        eq = [s for s in surv if any(e["module"] == module and e["operator"] == s["operator"]
                                      and e["mutant"] == s["mutant"] for e in equivalents)]
        killed = c.get("killed", 0) + c.get("incompetent", 0)
        scored = killed + len(surv) - len(eq)
        score = f"{100.0 * killed / scored:.0f} %" if scored else "–"
        lines.append(f"| `{module}` | {killed + len(surv)} | {killed} | {len(surv) - len(eq)} | {len(eq)} | {score} |")
    lines += ["", "| module | line | surviving mutant (operator: mutated line) |", "|---|---|---|"]
    for module in modules:
        session = workdir / f"{_name(module)}.sqlite"
        if not session.exists():
            continue
        for sv in survivors(session):
            if not any(e["module"] == module and e["operator"] == sv["operator"] and e["mutant"] == sv["mutant"]
                       for e in equivalents):
                lines.append(f"| `{module}` | {sv['line']} | {sv['operator'].removeprefix('core/')}: "
                             f"`{sv['mutant'].replace('|', '¦')}` |")
    lines += ["", "| module | mutant (operator: mutated line) | why equivalent |", "|---|---|---|"]
    for e in equivalents:
        lines.append(f"| `{e['module']}` | {e['operator'].removeprefix('core/')}: `{e['mutant']}` | {e['why']} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("modules", nargs="*", help="modules relative to pipeline/ (default: all)")
    ap.add_argument("--workdir", type=Path, default=REPO / "build" / "mutation")
    ap.add_argument("--report", action="store_true", help="only print the scores of existing sessions")
    ap.add_argument("--resume", action="store_true", help="continue existing sessions instead of starting afresh")
    ap.add_argument("--survivors", action="store_true",
                    help="run the surviving mutants of existing sessions again (after adding tests)")
    ap.add_argument("--sample", type=int, default=None,
                    help="test a seeded random sample of N mutants per module instead of all of them")
    ap.add_argument("-v", "--verbose", action="store_true", help="list the surviving mutants")
    ap.add_argument("--markdown", action="store_true", help="print scores and equivalents as Markdown tables")
    args = ap.parse_args(argv)
    unknown = [m for m in args.modules if m not in MODULES]
    if unknown:
        ap.error(f"unknown module(s) {unknown}; known: {sorted(MODULES)}")
    modules = args.modules or list(MODULES)
    args.workdir.mkdir(parents=True, exist_ok=True)
    if args.markdown:
        print(markdown(args.workdir, modules))
        return 0
    if not args.report:
        for module in modules:
            session = args.workdir / f"{_name(module)}.sqlite"
            if args.survivors and session.exists():
                print(f"mutation: {module}: {rerun_survivors(session)} survivors to run again", flush=True)
            run_module(module, args.workdir, args.resume or args.survivors, args.sample)
    return report(args.workdir, modules, args.verbose)


if __name__ == "__main__":
    sys.exit(main())
