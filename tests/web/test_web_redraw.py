"""A figure is sent to the browser again only when it changes (``FigureCard.refresh``): an
edit of the speed leaves the 3-D crank as it is and does not redraw it (a 3-D scene costs
the browser a fifth of a second in software WebGL), an edit of the crank radius redraws it.

Checked in Debian's chromium. No timings: the edits' socket messages arrive in order, so
once the radius edit's redraw has come, a redraw of the speed edit would have come before.
"""

from __future__ import annotations

import pytest

pytest.importorskip("nicegui")
pytest.importorskip("playwright.sync_api")

from .conftest import DRAWN  # noqa: E402

#: count plotly's redraws of the 3-D crank with new data in window.cbRedraws (a draw after a
#: resize, which NiceGUI's resize observer asks for whenever the layout moves, keeps the
#: figure's data object and is not counted: under load such a resize came late and was)
COUNT = """() => {
    window.cbRedraws = 0;
    const figure = document.querySelector('[data-testid=figure-crank3d]');
    let drawn = figure.data;
    figure.on('plotly_afterplot', () => {
        if (figure.data !== drawn) { window.cbRedraws++; drawn = figure.data; }
    });
}"""
#: the header's count of processed edits
UPDATE = "() => Number(document.querySelector('[data-testid=status]').dataset.update)"


def test_an_edit_that_leaves_the_figure_as_it_is_redraws_nothing(server: str, page) -> None:
    page.goto(f"{server}/?preset=v12-60")
    page.wait_for_function(DRAWN)
    page.evaluate(COUNT)
    before = page.evaluate(UPDATE)
    page.locator("[data-testid=field-speed]").first.fill("5010 rpm")
    page.wait_for_function(f"() => ({UPDATE})() > {before}")
    page.locator("[data-testid=field-crank_radius]").first.fill("45.5 mm")
    page.wait_for_function("() => window.cbRedraws > 0")
    page.wait_for_function(DRAWN)
    assert page.evaluate("() => window.cbRedraws") == 1, (
        "the 3-D crank was redrawn for the speed edit (its figure did not change) or more "
        "than once for the crank radius"
    )
