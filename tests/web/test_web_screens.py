"""Every tab of the page on a phone (390x844) in a real browser (Playwright driving Debian's
chromium), its study run: no field overlaps another or runs past the screen, and no figure
shown is drawn with zero height (a plot squeezed to its title).

``CRANKBALANCE_SHOTS=folder`` also takes full-page screenshots of every tab at 1280x800 and
390x844 for the inline-4, crossplane V8, V12 and single-cylinder presets, for a person to
look at (not committed). Every wait is a wait for a state of the page with the hang guard
of ``conftest.py``.
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

from .conftest import DRAWN  # noqa: E402

SHOTS = os.environ.get("CRANKBALANCE_SHOTS")
TABS = (
    "Engine",
    "Masses",
    "Results",
    "Counterweight design",
    "Single cylinder",
    "Balance shaft",
    "Performance",
    "Crank loads",
)
#: the button of a tab's study and a text only its result (or its refusal) shows
ACTIONS = {
    "Counterweight design": ("Optimise", r"feasible designs"),
    "Single cylinder": ("Compute study", r"Passes:|Holes:"),
    "Balance shaft": ("Find the optimum", r"optimum mass position|does not apply|needs no"),
    "Performance": ("Run the sweep", r"Peak shaking N[\s\S]*\b0\.75\b"),
    "Crank loads": ("Run", r"Lowest peak bearing load"),
}
PHONE = {"width": 390, "height": 844}
DESKTOP = {"width": 1280, "height": 800}
#: the boxes of the visible fields and figures of the open tab panel: [name, left, top,
#: right, bottom] (a field's box is its whole Quasar field, message included; a figure's
#: left and right are those of the box it scrolls in, subplots side by side keep their
#: width) and, for a figure, the height of its plotting area (2-D axes or 3-D scene)
BOXES = """() => {
  const panel = [...document.querySelectorAll('.q-tab-panel')]
    .find((p) => p.offsetParent !== null);
  const box = (e) => { const r = e.getBoundingClientRect();
                       return [r.left, r.top, r.right, r.bottom]; };
  const fields = [...panel.querySelectorAll('[data-testid^=field-], [data-testid^=setting-]')]
    .filter((e) => e.offsetParent !== null)
    .map((e) => [e.dataset.testid, ...box(e.closest('.q-field') || e)]);
  const figures = [...panel.querySelectorAll('.js-plotly-plot')]
    .filter((e) => e.offsetParent !== null)
    .map((e) => {
      const layout = e._fullLayout || {};
      const scene = layout.scene && layout.scene.domain;
      const size = layout._size || {h: 0};
      const area = scene ? size.h * (scene.y[1] - scene.y[0]) : size.h;
      const name = (e.closest('[data-testid^=figure-]') || e).dataset.testid || 'figure';
      const [, top, , bottom] = box(e);
      const [boxLeft, , boxRight] = box(e.closest('.cb-figure-box') || e);
      return [name, boxLeft, top, boxRight, bottom, area];
    });
  return {fields, figures, width: document.documentElement.scrollWidth,
          scrollX: window.scrollX, panel: box(panel), viewport: window.innerWidth};
}"""


def _open_tab(page: Any, tab: str) -> None:
    page.get_by_role("tab", name=tab, exact=True).click()
    expect(page.get_by_role("tab", name=tab, exact=True)).to_have_attribute("aria-selected", "true")
    page.wait_for_function(SETTLED)  # the panels' slide is over
    page.wait_for_function(BUILT)  # a tab built on first opening has its content
    page.wait_for_function(SETTLED)


#: the shown tab panel holds its content, not the placeholder of a tab still being built
#: (web/app.py builds the hidden tabs when first opened)
BUILT = """() => ![...document.querySelectorAll('[data-testid$="-opening"]')]
    .some((e) => e.offsetParent !== null)"""

#: one tab panel shown, no Quasar transition running and the panel in its place (while the
#: panels slide, the old and the new one are both on the page, partly off the screen; the
#: transition's classes come a frame after the switch, so its place is checked too)
SETTLED = """() => {
    const shown = [...document.querySelectorAll('.q-tab-panel')]
        .filter((p) => p.offsetParent !== null);
    if (shown.length !== 1) return false;
    if (document.querySelector('[class*="q-transition--"][class*="-active"]')) return false;
    const panel = shown[0].getBoundingClientRect();
    const home = shown[0].parentElement.getBoundingClientRect();
    return Math.abs(panel.left - home.left) < 0.5;
}"""


#: the shown tab panel lies within the window: the page has been laid out again after the
#: window narrowed (a panel measured while still placed for the wide window was once seen at
#: 217..575 px of a 390 px window, every field "past the screen")
IN_WINDOW = """() => {
    const shown = [...document.querySelectorAll('.q-tab-panel')]
        .filter((p) => p.offsetParent !== null);
    if (shown.length !== 1) return false;
    const box = shown[0].getBoundingClientRect();
    return box.left >= -0.5 && box.right <= window.innerWidth + 0.5;
}"""


def _run_study(page: Any, tab: str) -> None:
    if tab in ACTIONS:
        button, done = ACTIONS[tab]
        page.locator(".q-tab-panel:visible").get_by_role("button", name=button).click()
        expect(page.locator(".q-tab-panel:visible").first).to_contain_text(
            re.compile(done), use_inner_text=True
        )
    page.wait_for_function(DRAWN)


def _overlaps(boxes: list[list[Any]]) -> list[str]:
    found = []
    for i, (a, al, at, ar, ab, *_) in enumerate(boxes):
        for b, bl, bt, br, bb, *_ in boxes[i + 1 :]:
            if min(ar, br) > max(al, bl) + 0.5 and min(ab, bb) > max(at, bt) + 0.5:
                found.append(f"{a} overlaps {b}")
    return found


def _check_phone(page: Any, preset: str, tab: str) -> None:
    """At 390 px: fields apart and on the screen; every figure drawn with a plotting area."""
    shown = page.evaluate(BOXES)
    where = f"{preset}, {tab}"
    assert not _overlaps(shown["fields"]), (where, _overlaps(shown["fields"]))
    # what the page was like, should a field run past (the panel's box, the sideways scroll
    # and the window's width)
    state = {k: shown[k] for k in ("panel", "scrollX", "viewport", "width")}
    for name, left, _top, right, _bottom in shown["fields"]:
        assert left >= -0.5 and right <= PHONE["width"] + 0.5, (
            f"{where}: {name} runs past ({left:.1f}..{right:.1f} px; {state})"
        )
    for name, left, top, right, bottom, area in shown["figures"]:
        assert bottom - top > 150, f"{where}: {name} is {bottom - top:.0f} px high"
        assert area > 100, f"{where}: {name} plots in {area:.0f} px (squeezed to its title)"
        assert left >= -0.5 and right <= PHONE["width"] + 0.5, f"{where}: {name} runs past"
    assert shown["width"] <= PHONE["width"], f"{where}: the page scrolls sideways"


def _shoot(page: Any, preset: str, k: int, tab: str) -> None:
    if not SHOTS:
        return
    Path(SHOTS).mkdir(parents=True, exist_ok=True)
    name = f"{preset}-{k + 1}-{tab.lower().replace(' ', '_')}"
    for size in (DESKTOP, PHONE):
        page.set_viewport_size(size)
        page.wait_for_function(DRAWN)
        page.evaluate("window.scrollTo(0, 0)")
        page.wait_for_function("() => window.scrollY === 0")
        page.screenshot(path=f"{SHOTS}/{name}-{size['width']}.png", full_page=True)


PRESETS = ("inline4", "v8-crossplane", "v12-60", "single") if SHOTS else ("v12-60", "single")


@pytest.mark.parametrize("preset", PRESETS)
def test_every_tab_fits_a_phone(server: str, browser: Any, preset: str) -> None:
    """Each tab at 390x844 with its study run: no two fields overlap, none runs past the
    screen, the page does not scroll sideways, every figure shown has a plotting area."""
    page = browser.new_page(viewport=PHONE)
    page.set_default_timeout(180_000)
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(f"{server}/?preset={preset}")
        expect(page.locator("[data-testid=status]").first).to_contain_text("Results of:")
        for k, tab in enumerate(TABS):
            _open_tab(page, tab)
            _run_study(page, tab)
            _shoot(page, preset, k, tab)
            page.set_viewport_size(PHONE)
            page.wait_for_function(DRAWN)
            page.wait_for_function(SETTLED)
            page.wait_for_function(IN_WINDOW)  # laid out again at the phone's width
            _check_phone(page, preset, tab)
    finally:
        page.close()
    assert not errors, errors
