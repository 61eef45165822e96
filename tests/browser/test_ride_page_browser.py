"""The ride page leads with the answer (issue 38), looked at in headless Chromium at 1400 and 800 px:
a 3-D scenario's verdict, governing axis and hours per speed come before any figure, its warnings
are one collapsed block, headers wrap only between words, figures use the page's width."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.browser.test_report_browser import browser  # noqa: F401  (the module's Chromium fixture)

pytestmark = pytest.mark.browser

SCENARIO = (Path(__file__).parents[2] / "raw" / "scenarios" / "modern_tractor.toml").read_text()
THREE_D = SCENARIO.replace("cg_height_m = 0.95", "cg_height_m = 0.95\nroll_inertia_kg_m2 = 2400\n"
                           "front_track_m = 1.9\nrear_track_m = 1.8", 1).replace("length_m = 400", "length_m = 120")

LOOK_JS = """() => {
  const box = e => e.getBoundingClientRect();
  const answer = document.querySelector('#answer');
  const figures = [...document.querySelectorAll('figure')];
  const content = box(document.querySelector('h1')).width;
  const ths = [...document.querySelectorAll('thead th')];
  return {
    answerTop: box(answer).top, answerBottom: box(answer).bottom,
    answerText: answer.innerText,
    firstFigureTop: figures.length ? box(figures[0]).top : null,
    figureWidths: figures.map(f => box(f.querySelector('svg')).width / content),
    details: [...document.querySelectorAll('details.warnings')].map(d => ({open: d.open, summary: d.querySelector('summary').innerText,
                                                                         items: d.querySelectorAll('li').length})),
    loose: document.querySelectorAll('p.warn').length,
    overflowingHeaders: ths.filter(th => th.scrollWidth > th.clientWidth + 1).map(th => th.innerText),
    captions: [...document.querySelectorAll('figcaption')].map(c => c.innerText),
  };
}"""


@pytest.fixture(scope="module")
def page_path(tmp_path_factory):
    from tyrelab.cli import main

    folder = tmp_path_factory.mktemp("ride3d")
    (folder / "s.toml").write_text(THREE_D)
    assert main(["-q", "ride", str(folder / "s.toml"), "--speeds", "4", "8", "12", "--front-pressure", "1.2", "1.6",
                 "--rear-pressure", "0.8", "1.2", "--out", str(folder / "out")]) == 0
    return folder / "out" / "ride.html"


@pytest.mark.parametrize("width", [1400, 800])
def test_a_3d_ride_page_leads_with_the_answer(browser, page_path, width):  # noqa: F811
    page = browser.new_page(viewport={"width": width, "height": 900})
    errors: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.goto(page_path.as_uri())
    r = page.evaluate(LOOK_JS)
    assert not errors
    # the answer on the first screen, before any figure: verdict, governing axis, hours per speed
    assert r["answerTop"] < 900 and r["firstFigureTop"] is not None and r["answerBottom"] < r["firstFigureTop"]
    assert "Verdict over 8 h a day:" in r["answerText"] and "Governing axis of A(8):" in r["answerText"]
    for speed in ("4", "8 (working)", "12"):
        assert f"\n{speed}\t" in r["answerText"]
    assert page.locator("#answer .axis").first.is_visible()
    # warnings: one collapsed block with their count, grouped by tyre; none loose on the page
    assert len(r["details"]) == 1 and not r["details"][0]["open"] and r["loose"] == 0
    summary = r["details"][0]["summary"]
    assert summary.startswith(f"{r['details'][0]['items']} warnings (") and "front tyre:" in summary
    assert not page.locator("details.warnings li").first.is_visible()
    # the heatmap at the working speed (the middle speed, said), small multiples for the others
    assert any("at the working speed, 8 km/h" in c for c in r["captions"])
    assert any(c.startswith("The same at the other speeds") for c in r["captions"])
    assert any("the scenario's own values (1.6/1.2 bar)" in c for c in r["captions"])  # the spectra's variant
    # headers wrap between words only (a word never overflows its cell) and figures use the width
    assert r["overflowingHeaders"] == []
    assert min(r["figureWidths"]) > 0.9
    page.close()


#: What a reader cannot see: an element whose content is cut by ``overflow: hidden``/``clip``, or that
#: reaches past the window with no scrolling container around it (issue 47; a table that scrolls
#: inside its own box is fine).
CLIPPED_JS = """() => {
  const out = [], win = document.documentElement.clientWidth;
  if (document.documentElement.scrollWidth > win + 1) out.push('the page is wider than the window');
  for (const e of document.querySelectorAll('body *')) {
    const cs = getComputedStyle(e);
    if (e.clientWidth > 0 && e.scrollWidth > e.clientWidth + 1 && (cs.overflowX === 'hidden' || cs.overflowX === 'clip'))
      out.push('cut: ' + e.tagName + ' ' + (e.innerText || '').slice(0, 40));
    if (e.getBoundingClientRect().right > win + 1) {
      let p = e.parentElement, scrolls = false;
      for (; p; p = p.parentElement) { const o = getComputedStyle(p).overflowX; if (o === 'auto' || o === 'scroll') { scrolls = true; break; } }
      if (!scrolls) out.push('past the window: ' + e.tagName + ' ' + (e.innerText || '').slice(0, 40));
    }
  }
  return out;
}"""


@pytest.mark.parametrize("width", [1400, 800])
def test_nothing_on_a_sweeps_ride_page_is_cut(browser, page_path, width):  # noqa: F811
    page = browser.new_page(viewport={"width": width, "height": 900})
    page.goto(page_path.as_uri())
    assert page.evaluate(CLIPPED_JS) == []
    page.close()
