"""Open every page of a freshly built report in headless Chromium.

Skipped, with the reason, when the ``playwright`` package or a Chromium
binary is missing (CI installs both: ``.ci/run`` apt-installs chromium and
``make test`` the ``browser`` extra); the end of the test run then says so
in a "BROWSER TESTS SKIPPED" section. No browser is downloaded: the test
drives the system Chromium. The report is the shared ``full_report``: a tiny
synthetic campaign run through every stage of :func:`tyrelab.stages.run_pipeline`,
simulate included, so chapters 6–8 are checked with real results.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from small_campaign import EVIL_TYRE

pytestmark = pytest.mark.browser

CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def chromium_path() -> str | None:
    """The system Chromium: ``$CHROMIUM``, /usr/bin/chromium, or ``chromium`` on PATH."""
    for candidate in (os.environ.get("CHROMIUM"), "/usr/bin/chromium", shutil.which("chromium"),
                      shutil.which("chromium-browser")):
        if candidate and Path(candidate).exists():
            return candidate
    return None


@pytest.fixture(scope="module")
def browser():
    sync_api = pytest.importorskip(
        "playwright.sync_api", reason="playwright is not installed (pip install -e '.[browser]')")
    exe = chromium_path()
    if exe is None:
        pytest.skip("no Chromium found (apt-get install chromium, or set $CHROMIUM)")
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=exe, args=CHROMIUM_ARGS)
        yield b
        b.close()


@pytest.fixture(scope="module")
def site(full_report) -> Path:
    """The report of the tiny campaign built through every stage (shared, tests/conftest.py)."""
    return full_report.build / "reports"


def test_every_page_opens_cleanly(browser, site, tmp_path):
    pages = sorted(site.rglob("*.html"))
    assert len(pages) >= 9  # index, 7 chapters, runs list (+ drill-downs)
    page = browser.new_page(viewport={"width": 1280, "height": 900})
    errors: list[str] = []
    requests: list[str] = []
    page.on("console", lambda m: errors.append(f"{m.type}: {m.text}") if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(f"pageerror: {e}"))
    page.on("dialog", lambda d: (errors.append(f"dialog: {d.message}"), d.dismiss()))
    page.on("request", lambda r: requests.append(r.url))
    shots = tmp_path / "screenshots"
    shots.mkdir()
    for path in pages:
        page.goto(path.as_uri())
        page.wait_for_load_state("load")
        for t in range(page.locator("table").count()):
            table = page.locator("table").nth(t)
            assert table.locator("tbody tr, tr").count() > 0, f"{path.name}: table {t} has no rows"
            if table.locator("thead").count():
                assert table.locator("tbody tr").count() > 0, f"{path.name}: table {t} has a header but no rows"
        assert page.locator("footer").inner_text().startswith("Provenance."), path.name
        shot = shots / (path.relative_to(site).as_posix().replace("/", "__") + ".png")
        page.screenshot(path=str(shot), full_page=path.name == "index.html")
        assert shot.stat().st_size > 0
    assert not errors, errors
    external = [u for u in requests if not u.startswith(("file:", "data:", "about:"))]
    assert not external, external


def test_markup_in_tyre_id_is_shown_as_text(browser, site):
    page = browser.new_page()
    dialogs: list[str] = []
    page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
    page.goto((site / "ch4-stiffness.html").as_uri())
    table_iii = page.locator("#table-iii table")
    assert table_iii.locator("tbody tr").count() > 0
    assert EVIL_TYRE in table_iii.inner_text()
    assert page.locator("script").count() == 0
    assert not dialogs
    # the thesis / ours / difference columns of Table III
    assert table_iii.locator("thead th", has_text="thesis").count() >= 2
    assert table_iii.locator("thead th", has_text="ours").count() >= 2


def test_relative_links_resolve(browser, site):
    page = browser.new_page()
    page.goto((site / "index.html").as_uri())
    page.click("nav >> text=Chapter 4")
    assert page.url.endswith("ch4-stiffness.html")
    page.click("nav >> text=Runs")
    first = page.locator("tbody a").first
    first.click()
    assert "/runs/" in page.url
    assert page.locator("svg").count() == 1
    page.click("nav >> text=Summary")
    assert page.url.endswith("index.html")


#: Thesis tables III-XX; XV and XIX are inputs of the simulations (thesis values only).
THESIS_TABLES = ["iii", "iv", "v", "vi", "vii", "viii", "ix", "x", "xi", "xii", "xiii", "xiv", "xv", "xvi",
                 "xvii", "xviii", "xix", "xx"]
#: Tables this tiny campaign can fill with our values (it has pressure sweeps at 0 and 10 km/h,
#: no amplitude, surface or torque experiments); the simulations fill chapters 6-8.
OURS_FILLED = ["iii", "vii", "xi", "xii", "xiii", "xiv", "xvi", "xvii", "xviii", "xx"]

OURS_CELLS_JS = """(sel) => {
  let n = 0;
  for (const td of document.querySelectorAll(sel + ' tbody td.thesis')) {
    const ours = td.nextElementSibling;
    if (ours && !['', '–'].includes(ours.textContent.trim())) n++;
  }
  return n;
}"""


def test_every_thesis_table_has_thesis_and_our_columns(browser, site):
    page = browser.new_page()
    seen = {}
    for path in sorted(site.glob("ch*.html")):
        page.goto(path.as_uri())
        for t in THESIS_TABLES:
            section = page.locator(f"#table-{t}")
            if not section.count():
                continue
            table = section.locator("table").first
            assert table.locator("thead th", has_text="thesis").count() >= 1, t
            assert table.locator("thead th", has_text="ours").count() >= 1, t
            assert table.locator("tbody tr").count() > 0, t
            seen[t] = page.evaluate(OURS_CELLS_JS, f"#table-{t}")
    assert sorted(seen) == sorted(THESIS_TABLES)
    assert all(seen[t] > 0 for t in OURS_FILLED), {t: seen[t] for t in OURS_FILLED}
