"""The page's layout at 1280x800 and on a phone (390x844) in chromium (issue 28, review
findings 9 and 14): every tab of the tab bar within a 1280 px screen, and on a phone no card
of the Engine tab wider than the screen, on a fresh page and after a resize from 1280 px
(the key results and the 3-D crank stayed 650 px wide, their text cut at the edge).

Every wait is a wait for a state of the page (the hang guard of ``conftest.py``).
"""

from __future__ import annotations

from typing import Any

import pytest

pytest.importorskip("nicegui")
pytest.importorskip("playwright.sync_api")

from .conftest import DRAWN  # noqa: E402
from .test_web_phone import PHONE, shown_page  # noqa: E402

DESKTOP = {"width": 1280, "height": 800}
#: [label, left, right] of every tab of the tab bar
TAB_BOXES = """() => [...document.querySelectorAll('.q-tabs .q-tab')].map((t) => {
    const r = t.getBoundingClientRect(); return [t.innerText, r.left, r.right]; })"""
#: [first words, left, right] of every card shown in the open tab panel
CARD_BOXES = """() => [...document.querySelectorAll('.q-tab-panel .q-card')]
    .filter((e) => e.offsetParent !== null).map((c) => {
        const r = c.getBoundingClientRect(); return [c.innerText.slice(0, 30), r.left, r.right];
    })"""
#: the 3-D crank's scene is drawn (its WebGL container exists) and every shown plot is
#: drawn at its box's width
CRANK_DRAWN = (
    """() => !!document.querySelector('.q-tab-panel .cb-figure-box .gl-container')
    && ("""
    + DRAWN
    + ")()"
)


def engine_page(browser: Any, server: str, viewport: dict[str, int]) -> Any:
    return shown_page(browser, server, viewport, "inline4", drawn=CRANK_DRAWN)


def test_every_tab_within_1280(server: str, browser: Any) -> None:
    page = engine_page(browser, server, DESKTOP)
    try:
        boxes = page.evaluate(TAB_BOXES)
        assert len(boxes) == 11
        outside = [(label, left, right) for label, left, right in boxes if left < 0 or right > 1280]
        assert not outside, outside  # MOUNTS ran to 1344 px
    finally:
        page.close()


@pytest.mark.parametrize("resized", [False, True], ids=["fresh", "resized-from-1280"])
def test_no_card_past_the_phone_width(server: str, browser: Any, resized: bool) -> None:
    page = engine_page(browser, server, DESKTOP if resized else PHONE)
    try:
        if resized:
            page.set_viewport_size(PHONE)
            page.wait_for_function("() => window.innerWidth === 390")
            page.wait_for_function(DRAWN)
        cards = page.evaluate(CARD_BOXES)
        assert len(cards) >= 4
        past = [(words, left, right) for words, left, right in cards if right > PHONE["width"]]
        assert not past, past  # the key results and the 3-D crank ran to 652 px
    finally:
        page.close()
