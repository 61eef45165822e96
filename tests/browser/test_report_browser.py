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
from tests.report.small_campaign import EVIL_TYRE

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


# --- Every page as a reader sees it at 1400 px (issue 26) -----------------------------------------

#: The width the pages are checked at, and the narrowest a column of numbers needs (px: "1,234.5" at
#: the tables' 0.82 em plus padding is ~55 px): a table
#: with no more columns than the page has room for at this width must fit without scrolling.
VIEWPORT_PX = 1400
MIN_COLUMN_PX = 56

#: Per page: every table's scroll box and width, its column count, and its cells as text.
READ_PAGE_JS = """() => {
  const tables = [];
  for (const t of document.querySelectorAll('table')) {
    const box = t.closest('.scroll') || t.parentElement;
    const head = t.querySelector('thead tr:last-child') ? t.tHead : null;
    const rows = [...t.querySelectorAll('tbody:not(.not-compared) tr')].map(tr => [...tr.cells].map(td => td.innerText.split('\\n')[0].trim()));
    const ncols = Math.max(0, ...[...t.rows].map(r => [...r.cells].reduce((n, c) => n + c.colSpan, 0)));
    const caption = t.caption ? t.caption.innerText : (t.closest('section') ? t.closest('section').id : '');
    tables.push({caption, ncols, rows, boxWidth: box.clientWidth, boxScroll: box.scrollWidth,
                 keys: [...t.querySelectorAll('thead th.text')].length});
  }
  const code = [...document.querySelectorAll('code')].map(c => c.innerText);
  return {tables, code, text: document.body.innerText, pageScroll: document.documentElement.scrollWidth,
          pageWidth: document.documentElement.clientWidth};
}"""


@pytest.fixture(scope="module")
def read_pages(browser, site):
    """Every page at 1400 px: tables, code, text, and the console errors raised while loading it."""
    page = browser.new_page(viewport={"width": VIEWPORT_PX, "height": 1000})
    errors: list[str] = []
    page.on("console", lambda m: errors.append(f"{m.type}: {m.text}") if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(f"pageerror: {e}"))
    seen = {}
    for path in sorted(site.rglob("*.html")):
        errors.clear()
        page.goto(path.as_uri())
        page.wait_for_load_state("load")
        seen[path.relative_to(site).as_posix()] = {**page.evaluate(READ_PAGE_JS), "errors": list(errors)}
    page.close()
    return seen


def test_no_console_errors_at_1400px(read_pages):
    assert {p: r["errors"] for p, r in read_pages.items() if r["errors"]} == {}


def test_no_horizontal_scrollbar_on_a_table_that_could_fit(read_pages):
    """A table scrolls sideways at 1400 px only when it has more columns than the page has room for
    (``MIN_COLUMN_PX`` each); a long text cell or an unbreakable value must not push it off-screen."""
    bad = []
    for name, r in read_pages.items():
        if r["pageScroll"] > r["pageWidth"]:
            bad.append(f"{name}: the page itself scrolls sideways ({r['pageScroll']} > {r['pageWidth']} px)")
        for t in r["tables"]:
            if t["boxScroll"] > t["boxWidth"] + 1 and t["ncols"] * MIN_COLUMN_PX <= t["boxWidth"]:
                bad.append(f"{name}: table {t['caption']!r} ({t['ncols']} columns) is {t['boxScroll']} px wide "
                           f"in {t['boxWidth']} px")
    assert bad == []


def _shown_queries(r: dict) -> list[str]:
    """The SQL a page shows: ``SELECT ...`` in code elements, and ``tyrelab sql "..."`` anywhere."""
    import re

    queries = [c.strip() for c in r["code"] if re.match(r"(?is)\s*(SELECT|WITH)\b", c)]
    queries += re.findall(r'tyrelab sql "([^"]+)"', r["text"])
    return queries


def test_every_query_shown_runs_in_tyrelab_sql(read_pages, full_report, capsys):
    """Each query a page shows runs, as shown, through ``tyrelab sql`` on the build it describes."""
    from tyrelab.cli import main

    queries = sorted({q for r in read_pages.values() for q in _shown_queries(r)})
    assert len(queries) > 20
    failed = {}
    for q in queries:
        capsys.readouterr()
        code = main(["sql", "--build", str(full_report.build), "--format", "csv", q.replace("…", "r001")])
        if code != 0:
            failed[q] = capsys.readouterr().err.strip()
    assert failed == {}


def _number(text: str) -> float | None:
    import re

    m = re.fullmatch(r"[−-]?[\d,]*\.?\d+(e[+-]?\d+)?", text.strip().replace("\u2009", ""))
    return float(m.group(0).replace(",", "").replace("−", "-")) if m else None


def _text_not_numeric_order(rows: list[list[str]]) -> list[str]:
    """Columns ordered as text where they hold numbers: within each group of rows that agree on the
    columns to the left, the numbers follow string order and not numeric order. Only the leading
    sorted columns (the table's row order) are looked at."""
    problems = []
    width = min((len(r) for r in rows), default=0)
    for j in range(width):
        groups: dict[tuple, list[str]] = {}
        for row in rows:
            groups.setdefault(tuple(row[:j]), []).append(row[j])
        sorted_somehow = True
        for key, cells in groups.items():
            nums = [_number(c) for c in cells]
            if len(cells) < 3 or any(n is None for n in nums):
                continue
            if nums == sorted(nums):
                continue
            if cells == sorted(cells):
                problems.append(f"column {j + 1} after {list(key)}: {cells}")
            else:
                sorted_somehow = False
        if not sorted_somehow:
            break
    return problems


def test_numeric_columns_are_ordered_as_numbers(read_pages):
    bad = {f"{name}: {t['caption']}": p for name, r in read_pages.items() for t in r["tables"]
           if (p := _text_not_numeric_order(t["rows"]))}
    assert bad == {}


def test_text_order_detector():
    assert _text_not_numeric_order([["a", "10"], ["a", "12.5"], ["a", "5"], ["a", "7.5"]])
    assert not _text_not_numeric_order([["a", "5"], ["a", "7.5"], ["a", "10"], ["a", "12.5"]])
    assert not _text_not_numeric_order([["a", "5"], ["b", "10"], ["b", "7.5"], ["b", "2"]])


def test_the_ride_page_of_a_pressure_sweep_fits_at_1400px(browser, tmp_path):
    """``tyrelab ride --out`` (a sweep: the widest table) as a reader sees it: no sideways scrolling,
    no console errors, numeric columns in numeric order, the PSD's drop explained."""
    from tyrelab.cli import main

    scenario = Path(__file__).parents[2] / "raw" / "scenarios" / "modern_tractor.toml"
    assert main(["-q", "ride", str(scenario), "--speeds", "4", "8", "--front-pressure", "1.0", "1.4",
                 "--rear-pressure", "0.8", "1.2", "--out", str(tmp_path)]) == 0
    page = browser.new_page(viewport={"width": VIEWPORT_PX, "height": 1000})
    errors: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.goto((tmp_path / "ride.html").as_uri())
    r = page.evaluate(READ_PAGE_JS)
    assert not errors
    wide = [t for t in r["tables"] if t["boxScroll"] > t["boxWidth"] + 1 and t["ncols"] * MIN_COLUMN_PX <= t["boxWidth"]]
    assert wide == [] and r["pageScroll"] <= r["pageWidth"]
    assert all(not _text_not_numeric_order(t["rows"]) for t in r["tables"])
    assert "Each curve drops where the track's unevenness ends" in r["text"]
