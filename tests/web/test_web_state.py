"""The page's state in a real browser (Playwright driving Debian's chromium): results are
never shown as current for a form that cannot be computed, every selector redraws what it
controls, and the page fits a phone.

Every wait is a wait for a state of the page with the hang guard of ``conftest.py``.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

STATUS = "[data-testid=status]"


def field(page, key: str):
    return page.locator(f"[data-testid=field-{key}]").first


def choose(page, key: str, option: str) -> None:
    """Pick ``option`` in the select of the form field ``key``."""
    field(page, key).click()
    page.get_by_role("option", name=option, exact=True).click()


def open_tab(page, name: str) -> None:
    page.get_by_role("tab", name=name, exact=True).click()
    expect(page.get_by_role("tab", name=name, exact=True)).to_have_attribute(
        "aria-selected", "true"
    )


def state(page) -> tuple[str, int]:
    """The header's state (``current``/``error``) and its update count."""
    status = page.locator(STATUS).first
    return str(status.get_attribute("data-state")), int(status.get_attribute("data-update") or 0)


def wait_update(page, after: int, wanted: str) -> None:
    """Wait until the page has shown an update later than ``after`` in state ``wanted``."""
    page.wait_for_function(
        """([after, wanted]) => {
            const s = document.querySelector('[data-testid=status]');
            return s && Number(s.dataset.update) > after && s.dataset.state === wanted;
        }""",
        arg=[after, wanted],
    )


def test_never_stale_v10_odd_fire_with_shafts(server: str, page) -> None:
    """The issue's case: V10-72 changed to a V10 at 90 deg with primary shafts, which the
    solver refuses. Nothing may claim that the old V10-72's results are current."""
    page.goto(server + "/?preset=v10-72")
    wait_update(page, 0, "current")
    header = page.locator(".q-header").first
    expect(header).to_contain_text("Results of: V10 72 deg")
    _, n = state(page)
    field(page, "bank_angle").fill("90 deg")
    wait_update(page, n, "error")
    _, n = state(page)
    choose(page, "primary_arrangement", "pair")
    field(page, "primary_cg_radius").fill("30 mm")
    field(page, "primary_length").fill("400 mm")
    wait_update(page, n, "error")
    expect(field(page, "primary_length")).to_have_value("400 mm")
    expect(header).to_contain_text("Not computed")
    assert "computed in" not in header.inner_text()
    assert "Results of" not in header.inner_text()
    # the reason is the solver's, beside the firing order
    expect(page.locator(".q-field--error").first).to_contain_text("throw angles (crank editor)")
    # every result tab says so, with the reason, and greys what it still shows
    for tab, name in (
        ("Results", "results"),
        ("Counterweight design", "counterweight"),
        ("Single cylinder", "single"),
        ("Balance shaft", "shaft"),
        ("Performance", "performance"),
    ):
        open_tab(page, tab)
        note = page.locator(f"[data-testid={name}-stale]").first
        expect(note).to_be_visible()
        expect(note).to_contain_text("Not computed")
        expect(note).to_contain_text("throw angles (crank editor)")
        expect(note).to_contain_text("not of the form")
    # a download of the old engine's numbers is refused
    open_tab(page, "Results")
    page.get_by_role("button", name="Balance JSON").click()
    expect(page.locator(".q-notification").last).to_contain_text("Not computed")
    # back to the preset's bank angle: current again, the banners gone
    _, n = state(page)
    open_tab(page, "Engine")
    choose(page, "primary_arrangement", "none")
    field(page, "bank_angle").fill("72 deg")
    wait_update(page, n, "current")
    open_tab(page, "Results")
    expect(page.locator("[data-testid=results-stale]").first).to_be_hidden()
    with page.expect_download() as info:
        page.get_by_role("button", name="Balance JSON").click()
    balance = json.loads(Path(info.value.path()).read_text())
    assert balance["primary_shafts"] is None
    assert re.search("V10 72", page.locator(STATUS).first.inner_text())


def figure_title(page, name: str) -> str:
    """The title of the plotly figure marked ``figure-<name>`` as drawn in the browser."""
    return str(
        page.evaluate(
            """(name) => {
                const gd = document.querySelector(`[data-testid=figure-${name}] .js-plotly-plot`)
                    || document.querySelector(`[data-testid=figure-${name}]`);
                return gd && gd.layout && gd.layout.title ? gd.layout.title.text : '';
            }""",
            name,
        )
    )


def wait_title(page, name: str, pattern: str) -> None:
    """Wait until the figure ``name`` is drawn with a title matching ``pattern``."""
    page.wait_for_function(
        """([name, pattern]) => {
            const gd = document.querySelector(`[data-testid=figure-${name}] .js-plotly-plot`)
                || document.querySelector(`[data-testid=figure-${name}]`);
            return gd && gd.layout && gd.layout.title
                && new RegExp(pattern).test(gd.layout.title.text);
        }""",
        arg=[name, pattern],
    )


def pick(page, marker: str, option: str) -> None:
    page.locator(f"[data-testid={marker}]").first.click()
    page.get_by_role("option", name=option, exact=True).click()


def test_selectors_redraw_and_polar_opens_on_the_leading_component(server: str, page) -> None:
    """Crossplane V8: the polar diagram opens on its first-order rocking couple (its
    forces are zero but for a small fourth order); each selector redraws its figures at
    once, with no edit of the engine."""
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(server + "/?preset=v8-crossplane")
    wait_update(page, 0, "current")
    _, n = state(page)
    open_tab(page, "Results")
    wait_title(page, "polar", r"^Order 1 moment: amplitude 4\d{3}(\.\d)? N·m")
    wait_title(page, "curves", r"^Free moments")
    expect(page.locator("[data-testid=curve-quantity]").first).to_contain_text("moment")
    pick(page, "curve-quantity", "force")
    wait_title(page, "curves", r"^Free forces")
    wait_title(page, "polar", r"^Order 1 force: amplitude 0 N")
    pick(page, "polar-order", "4")
    wait_title(page, "polar", r"^Order 4 force: amplitude [1-9]")
    wait_title(page, "curves", r"^Free forces")
    pick(page, "curve-quantity", "moment")
    wait_title(page, "polar", r"^Order 4 moment")
    wait_title(page, "curves", r"^Free moments")
    assert state(page) == ("current", n), "a selector is not an edit of the engine"
    assert not errors, errors


def test_phone_one_column_no_overlap(server: str, browser) -> None:
    """At 390x844 the form is one column: no two visible fields overlap and none runs past
    the screen; a long message under a field pushes the next field down."""
    page = browser.new_page(viewport={"width": 390, "height": 844})
    try:
        page.goto(server + "/?preset=v10-72")
        wait_update(page, 0, "current")
        _, n = state(page)
        field(page, "bank_angle").fill("90 deg")  # the solver's long message
        wait_update(page, n, "error")
        boxes = page.evaluate(
            """() => [...document.querySelectorAll('.q-tab-panel [data-testid^=field-]')]
                .filter((e) => e.offsetParent !== null)
                .map((e) => { const f = e.closest('.q-field') || e;
                              const r = f.getBoundingClientRect();
                              return [e.dataset.testid, r.left, r.top, r.right, r.bottom]; })"""
        )
        assert len(boxes) >= 10, boxes
        for name, left, _top, right, _bottom in boxes:
            assert left >= 0 and right <= 390, f"{name} runs past the screen: {left}..{right}"
        for i, (a, al, at, ar, ab) in enumerate(boxes):
            for b, bl, bt, br, bb in boxes[i + 1 :]:
                overlap = min(ar, br) > max(al, bl) and min(ab, bb) > max(at, bt)
                assert not overlap, f"{a} and {b} overlap"
        # one column: every field starts at the same left edge
        assert len({round(left) for _, left, *_ in boxes}) <= 2, boxes
    finally:
        page.close()
