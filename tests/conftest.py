import fcntl
import logging
import os
import signal

import pytest

from tests.report.small_campaign import build_small_report
from tyrelab.stages import Context


def pytest_configure(config):
    """Ctrl-C as a terminal sends it, even when the suite was started ignoring SIGINT.

    A shell starts a background job (``make test &`` in a script, a queue daemon under ``nohup``)
    with SIGINT ignored, and a child inherits an ignored signal across ``exec``: every test that
    sends SIGINT to a ``tyrelab`` subprocess would then wait out its hang guard (600 s) for a
    command that never saw the signal. A handled signal is reset to the default across ``exec``, so
    Python's own handler here gives the subprocesses the SIGINT a user's terminal gives them.
    """
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)


@pytest.fixture(scope="session")
def full_report(tmp_path_factory) -> Context:
    """The tiny seeded campaign of ``tests/report/small_campaign.py`` through *every* stage.

    Ingest to report, simulate included, so that the report's chapters 6-8 hold our
    values. Built once per test session and shared read-only: under pytest-xdist every
    worker would otherwise build its own, so the first worker to take the lock builds
    into the session's common temporary folder and the others wait and reuse it.
    """
    base = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        base = base.parent  # shared by the workers of this session
    root = base / "full_report"
    root.mkdir(exist_ok=True)
    with open(base / "full_report.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            if not (root / "built").exists():
                build_small_report(root, skip=())
                (root / "built").write_text("ok\n")
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
    return Context(raw=root / "raw", build=root / "build", jobs=1, log=logging.getLogger("tyrelab.test"))


def pytest_collection_modifyitems(config, items):
    """Collect the tests marked ``long`` (``pytestmark = pytest.mark.long`` in a file whose tests take
    many seconds in the default run) first, so that pytest-xdist, which hands out tests
    round-robin in collection order, starts them at once on different workers instead of leaving
    one for the end of the run. A stable sort: the rest keep their order."""
    items.sort(key=lambda item: item.get_closest_marker("long") is None)


_skipped_browser: list[str] = []


def pytest_runtest_logreport(report):
    if report.skipped and "browser" in report.keywords:
        reason = report.longrepr[-1] if isinstance(report.longrepr, tuple) else str(report.longrepr)
        _skipped_browser.append(f"{report.nodeid}: {reason}")


def pytest_terminal_summary(terminalreporter):
    """Say loudly when the browser tests did not run: the report was then not opened in Chromium."""
    if _skipped_browser:
        tr = terminalreporter
        tr.section("BROWSER TESTS SKIPPED", sep="!", red=True, bold=True)
        tr.write_line(f"{len(_skipped_browser)} browser test(s) skipped: the report was NOT opened in Chromium.",
                      red=True, bold=True)
        for line in sorted(set(_skipped_browser)):
            tr.write_line(f"  {line}", red=True)
        tr.write_line("Install the 'browser' extra (make install) and Chromium (apt-get install chromium).", red=True)
