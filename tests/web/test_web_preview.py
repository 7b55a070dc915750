"""A fresh page shows the 3-D crank at once (issue 28, item 8): the page the server sends
holds the crank's still picture (``FigureCard.preview``, an SVG of the figure's own lines
and markers), so the crank is seen with the page's first paint, before plotly.js is loaded
and has drawn the scene in (software) WebGL; once it has, the picture is hidden and the
interactive scene is what remains. Checked in Debian's chromium; every wait is a wait for a
state of the page (the hang guard of ``conftest.py``).
"""

from __future__ import annotations

import urllib.request

import pytest

pytest.importorskip("nicegui")
pytest.importorskip("playwright.sync_api")

from .conftest import DRAWN  # noqa: E402

PREVIEW = "[data-testid=preview-crank3d]"


def test_the_page_sent_holds_the_crank_picture(server: str) -> None:
    with urllib.request.urlopen(f"{server}/?preset=v8-crossplane", timeout=180) as response:
        html = response.read().decode()
    assert "preview-crank3d" in html
    # the picture's SVG, escaped in the page's element data: the crank's lines and the eight
    # counterweights
    assert html.count("&lt;polyline") >= 4 and html.count("&lt;circle") == 8


def test_the_picture_is_shown_until_the_scene_is_drawn_then_hidden(server: str, page) -> None:
    page.goto(f"{server}/?preset=v8-crossplane")
    page.wait_for_function(DRAWN)
    page.wait_for_function(
        "() => document.querySelector('[data-testid=figure-crank3d] .gl-container') !== null"
    )
    assert page.eval_on_selector(PREVIEW, "(e) => getComputedStyle(e).display") == "none"
    # the picture was there before: the same element, its SVG drawn with the crank's lines
    assert page.eval_on_selector(PREVIEW, "(e) => e.querySelectorAll('polyline').length") >= 4


def test_the_picture_is_displayed_while_the_scene_is_not_drawn(server: str, page) -> None:
    # plotly.js (NiceGUI's ES module of it, requested after the page's mount) is held back:
    # the picture is there meanwhile, in the figure's place, with the crank
    held: list = []
    page.route("**/_nicegui/*/esm/**", lambda route: held.append(route))
    page.goto(f"{server}/?preset=v8-crossplane")
    page.wait_for_function(
        f"() => {{ const p = document.querySelector('{PREVIEW}');"
        " return p && p.offsetParent !== null && p.querySelector('svg polyline') !== null; }"
    )
    box = page.locator(PREVIEW).bounding_box()
    assert box is not None and box["width"] > 200 and box["height"] > 100
    assert held  # plotly.js was asked for, and is still held back: no scene drawn
    assert page.locator("[data-testid=figure-crank3d] .gl-container").count() == 0
