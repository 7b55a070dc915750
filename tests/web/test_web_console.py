"""No console errors over a walk through every tab, and toasts that close with their tab
(issue 28, item 7, in part), in chromium.

Plotly's figures of hidden tab panels were resized by NiceGUI's own ResizeObserver, and
plotly.js refused each ("Resize must be passed a displayed plot div element", about ten per
walk); the figure cards now resize only displayed figures (``widgets.FIGURE_JS``). Every
wait is a wait for a state of the page (the hang guard of ``conftest.py``).
"""

from __future__ import annotations

from typing import Any

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

from .conftest import DRAWN  # noqa: E402
from .test_web_fresh_browser import current  # noqa: E402
from .test_web_screens import BUILT, SETTLED  # noqa: E402

PHONE = {"width": 390, "height": 844}
DESKTOP = {"width": 1280, "height": 800}


def _tabs(page: Any) -> list[str]:
    return [t.strip() for t in page.locator(".q-tabs .q-tab").all_inner_texts()]


def _open(page: Any, name: str) -> None:
    tab = page.locator(".q-tabs .q-tab", has_text=name).first
    tab.click()
    expect(tab).to_have_attribute("aria-selected", "true")
    page.wait_for_function(SETTLED)
    page.wait_for_function(BUILT)
    page.wait_for_function(DRAWN)


def test_a_walk_through_the_tabs_logs_no_error(server: str, browser: Any) -> None:
    """Every tab opened at 1280 px, the window made a phone's and every tab opened again:
    no error on the console, no uncaught error of the page (the V8's figures are drawn in
    hidden panels as the engine is computed, and resized as the window changes)."""
    page = browser.new_page(viewport=DESKTOP)
    page.set_default_timeout(180_000)
    errors: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(f"{server}/?preset=v8-crossplane")
        current(page)
        names = [n for n in _tabs(page) if n]
        assert len(names) >= 9, names
        for size in (DESKTOP, PHONE):
            page.set_viewport_size(size)
            for name in (*names[1:], names[0]):
                _open(page, name)
        assert not errors, errors
    finally:
        page.close()


def test_toasts_close_with_their_tab(server: str, page: Any) -> None:
    """A toast shown on one tab (one that stays until closed) is gone once another tab
    is opened."""
    page.set_viewport_size(PHONE)
    page.goto(f"{server}/?preset=inline4")
    current(page)
    page.wait_for_function("() => window.cbToasts && window.Quasar && Quasar.Notify")
    page.evaluate("() => Quasar.Notify.create({message: 'a toast of the Engine tab', timeout: 0})")
    toast = page.locator(".q-notification", has_text="a toast of the Engine tab")
    expect(toast).to_be_visible()
    _open(page, "Masses")
    expect(toast).to_have_count(0)
