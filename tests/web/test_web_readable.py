"""Every figure readable (issue 28, item 4, in part): a value axis never stretches a
difference below the page's printed digits over the whole axis (``widgets.value_ranges``),
and a figure whose every value is 0 says so (``widgets.ALL_ZERO``): the Explorer's chosen
inline-6 candidate, balanced through the fourth order, in chromium.

Every wait is a wait for a state of the page (the hang guard of ``conftest.py``).
"""

from __future__ import annotations

from typing import Any

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

import plotly.graph_objects as go  # noqa: E402
from plotly.subplots import make_subplots  # noqa: E402

from crankbalance.output.figures.common import (  # noqa: E402
    ALL_ZERO,
    MIN_SPAN_SHARE,
    all_zero,
    value_ranges,
)

from .test_web_explore import connected, open_tab  # noqa: E402


def test_a_round_off_difference_is_drawn_flat() -> None:
    """A curve varying by 0.0004 % gets an axis of MIN_SPAN_SHARE of its magnitude, centred;
    a curve varying by 1 %, an axis with bars and a log axis keep plotly's own range."""
    fig = make_subplots(rows=1, cols=3)
    fig.add_trace(go.Scatter(x=[0, 1, 2], y=[100.0, 100.0004, 100.0002]), row=1, col=1)
    fig.add_trace(go.Scatter(x=[0, 1, 2], y=[100.0, 101.0, 100.5]), row=1, col=2)
    fig.add_trace(go.Bar(x=["a", "b"], y=[5.0, 5.0000001]), row=1, col=3)
    ranges = value_ranges(fig, fig.to_plotly_json()["layout"])
    assert list(ranges) == ["yaxis"]
    low, high = ranges["yaxis"]
    assert high - low == pytest.approx(MIN_SPAN_SHARE * 100.0004)
    assert (low + high) / 2 == pytest.approx(100.0002)
    logged = go.Figure(go.Scatter(y=[1.0, 1.0000001]), layout={"yaxis": {"type": "log"}})
    assert value_ranges(logged, logged.to_plotly_json()["layout"]) == {}


def test_all_zero_is_said_only_of_a_2d_figure_of_zeros() -> None:
    assert all_zero(go.Figure(go.Bar(x=["1", "2"], y=[0.0, 0.0])))
    assert not all_zero(go.Figure(go.Bar(x=["1", "2"], y=[0.0, 1e-9])))
    assert not all_zero(go.Figure(go.Scatter3d(x=[0], y=[0], z=[0])))
    assert not all_zero(go.Figure())


def test_a_balanced_candidate_says_0_everywhere(server: str, browser: Any) -> None:
    """The inline-6's first candidate (the least moment left) has no free force or moment
    of orders 1 to 4: its card says so above the empty bars; the inline-4's does not."""
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    try:
        page.goto(server + "/?preset=inline4")  # the explorer starts from the engine
        connected(page)
        open_tab(page, "Explorer")
        card = page.locator(".q-card", has=page.locator("[data-testid=figure-explore-candidate]"))
        page.get_by_role("button", name="Explore").click()
        summary = page.locator("[data-testid=explore-summary]").first
        expect(summary).to_contain_text("distinct engines")
        expect(card.first).not_to_contain_text(ALL_ZERO)
        field = page.locator("[data-testid=explore-cylinders]").first
        field.fill("6")
        expect(field).to_have_value("6")
        expect(summary).to_have_text("")  # the inline-4's result cleared with its settings
        page.get_by_role("button", name="Explore").click()
        expect(summary).to_contain_text("distinct engines")
        expect(card.first).to_contain_text(ALL_ZERO)
    finally:
        page.close()
