"""The command outputs shown in the README and ``docs/*.md`` are the commands' outputs (issue 47).

Those pages are read on GitHub and shipped beside the report, so they cannot run a command while
they are read (the site's tutorials do, with ``command-output``). Instead every shown output is a
*pair*: a fenced ``sh`` block whose last command prints it, followed by a fenced ``text`` block
holding what it prints. :func:`check` runs each pair's command in a folder laid out as a clone after
``make all`` (``raw/demo`` and ``build`` of the docs' demo build, ``raw/scenarios`` of the
repository; ``.venv/bin/tyrelab`` is the ``tyrelab`` on ``PATH``) and compares its standard output
with the block, line by line. Only the last command of a block is run (the ones before it, e.g.
``tyrelab rides …  # make all has done this``, are what the build has already done), and a
``text`` block that follows no ``sh`` block is a problem too: no output is pasted by hand.

``make docs`` runs the check (this module as a Sphinx extension: a differing block is a warning,
and Sphinx runs with ``-W``); ``make docs-outputs`` writes the commands' outputs into the blocks
(``python docs/site/_ext/tyrelab_outputs.py --update``).
"""

from __future__ import annotations

import argparse
import difflib
import os
import re
import shlex
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
#: The pages whose outputs are checked: the README and the explanation documents of docs/.
PAGES = ("README.md", "docs/*.md")
#: Longest a documented command may take, s.
TIMEOUT_S = 600

_FENCE = re.compile(r"^```(\w*)\s*$")


@dataclass
class Pair:
    """A documented command and the output shown for it."""

    page: Path
    line: int  # 1-based line of the text block's first content line
    command: str  # the block's last command, continuation lines joined
    shown: list[str]
    start: int  # 0-based index of the text block's first content line in the page's lines
    end: int  # 0-based index of its closing fence


def _blocks(lines: list[str]):
    """Fenced blocks of a page: (language, first content index, closing fence index)."""
    i = 0
    while i < len(lines):
        m = _FENCE.match(lines[i])
        if m is None:
            i += 1
            continue
        j = i + 1
        while j < len(lines) and lines[j].rstrip() != "```":
            j += 1
        yield m.group(1), i + 1, j
        i = j + 1


def last_command(block: list[str]) -> str:
    """The last command of a ``sh`` block: continuation lines joined, the trailing comment dropped.

    Examples
    --------
    >>> last_command([".venv/bin/tyrelab rides --raw raw/demo   # done", ".venv/bin/tyrelab exposure a.parquet \\\\",
    ...               "    --hours 4 --format table"])
    'tyrelab exposure a.parquet --hours 4 --format table'
    """
    commands, current = [], ""
    for line in block:
        text = line.rstrip()
        if text.endswith("\\"):
            current += text[:-1] + " "
            continue
        current += text
        if current.strip() and not current.lstrip().startswith("#"):
            commands.append(current)
        current = ""
    words = shlex.split(commands[-1], comments=True)
    if words and words[0].endswith("/tyrelab"):
        words[0] = "tyrelab"
    return shlex.join(words)


def pairs(page: Path) -> tuple[list[Pair], list[str]]:
    """The command/output pairs of a page, and its ``text`` blocks that follow no ``sh`` block."""
    lines = page.read_text(encoding="utf-8").splitlines()
    found, orphans, previous = [], [], None
    for lang, start, end in _blocks(lines):
        if lang == "text":
            between = lines[previous[2] + 1:start - 1] if previous else ["x"]
            if previous is not None and previous[0] == "sh" and not any(s.strip() for s in between):
                found.append(Pair(page, start + 1, last_command(lines[previous[1]:previous[2]]), lines[start:end],
                                  start, end))
            else:
                orphans.append(f"{page.relative_to(ROOT)}:{start}: a text block that no sh block before it prints")
        previous = (lang, start, end)
    return found, orphans


def all_pairs() -> tuple[list[Pair], list[str]]:
    found, orphans = [], []
    for pattern in PAGES:
        for page in sorted(ROOT.glob(pattern)):
            f, o = pairs(page)
            found += f
            orphans += o
    return found, orphans


def _folder(work: Path) -> Path:
    """A folder laid out as a clone after ``make all``: ``raw/demo``, ``raw/scenarios``, ``build``."""
    folder = Path(tempfile.mkdtemp(prefix="tyrelab-doc-outputs-"))
    (folder / "raw").mkdir()
    (folder / "raw" / "demo").symlink_to(work / "raw" / "demo")
    (folder / "raw" / "scenarios").symlink_to(ROOT / "raw" / "scenarios")
    (folder / "build").symlink_to(work / "build")
    return folder


def run(pair: Pair, folder: Path) -> list[str]:
    """The standard output of a pair's command, run in ``folder``, as lines."""
    env = {**os.environ, "COLUMNS": "100", "PYTHONHASHSEED": "0"}
    out = subprocess.run(pair.command, shell=True, cwd=folder, env=env, capture_output=True, text=True,
                         timeout=TIMEOUT_S)
    if out.returncode not in (0, 3):
        raise RuntimeError(f"`{pair.command}` exit {out.returncode}: {out.stderr.strip()[-500:]}")
    return out.stdout.rstrip("\n").splitlines()


def check(work: Path) -> list[str]:
    """Every problem: a shown output that differs from its command's (with a diff), an orphan block."""
    found, problems = all_pairs()
    folder = _folder(work)
    for pair in found:
        try:
            got = run(pair, folder)
        except (RuntimeError, subprocess.TimeoutExpired) as exc:
            problems.append(f"{pair.page.relative_to(ROOT)}:{pair.line}: {exc}")
            continue
        if [s.rstrip() for s in got] != [s.rstrip() for s in pair.shown]:
            diff = "\n".join(list(difflib.unified_diff(pair.shown, got, "shown", "printed", lineterm="", n=0))[:20])
            problems.append(f"{pair.page.relative_to(ROOT)}:{pair.line}: the output shown for `{pair.command}` is not "
                            f"what it prints (make docs-outputs writes it):\n{diff}")
    return problems


def update(work: Path) -> int:
    """Write every pair's command output into its page; the number of blocks changed."""
    found, orphans = all_pairs()
    for line in orphans:
        print(line, file=sys.stderr)
    folder = _folder(work)
    changed = 0
    for page in sorted({p.page for p in found}):
        lines = page.read_text(encoding="utf-8").splitlines()
        for pair in sorted((p for p in found if p.page == page), key=lambda p: -p.start):  # from the end: indices hold
            got = [s.rstrip() for s in run(pair, folder)]
            if got != [s.rstrip() for s in pair.shown]:
                lines[pair.start:pair.end] = got
                changed += 1
        page.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return changed


def setup(app):
    from sphinx.util import logging

    logger = logging.getLogger(__name__)

    def checked(app_):
        if app_.builder.name != "html":  # once per make docs
            return
        work = os.environ.get("TYRELAB_DOCS_WORK")
        if not work or not (Path(work) / "build" / "warehouse.duckdb").is_file():
            logger.warning("tyrelab_outputs: no demo build (TYRELAB_DOCS_WORK): the outputs of README.md and "
                           "docs/*.md are not checked")
            return
        for problem in check(Path(work)):
            logger.warning(problem)

    app.connect("builder-inited", checked)
    return {"parallel_read_safe": True, "parallel_write_safe": True}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--work", default=str(ROOT / "build" / "docs-work"), help="the docs' demo build (make docs makes it)")
    p.add_argument("--update", action="store_true", help="write the commands' outputs into the pages")
    a = p.parse_args(argv)
    work = Path(a.work).resolve()
    if a.update:
        print(f"{update(work)} output block(s) rewritten")
        return 0
    problems = check(work)
    for line in problems:
        print(line)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
