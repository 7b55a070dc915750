"""On a phone (issue 28, item 7) in chromium at 390 x 844, the crossplane V8: a compact
header, tables that scroll sideways with a visible cue, subplots side by side stacked in
one column (and side by side again on a wide screen).

Every wait is a wait for a state of the page (the hang guard of ``conftest.py``).
"""

from __future__ import annotations

from typing import Any

import pytest

pytest.importorskip("nicegui")
pytest.importorskip("playwright.sync_api")

from plotly.subplots import make_subplots  # noqa: E402

from crankbalance.web.widgets import legend_entries, phone_stack  # noqa: E402

from .conftest import DRAWN  # noqa: E402
from .test_web_explore import connected, open_tab  # noqa: E402

PHONE = {"width": 390, "height": 844}
#: the header's largest height on a phone [px]: it took 172 of 844 px (issue 28); two
#: short lines and the status line fit in this
PHONE_HEADER = 100
#: the figures of the Results tab whose subplots stand side by side on a wide screen
SIDE_BY_SIDE = """() => [...document.querySelectorAll('.cb-figure')]
    .filter((e) => e.offsetParent !== null && e.layout?.meta?.cbStack)"""


def test_a_hidden_trace_has_no_legend_entry() -> None:
    """The phone's legend lines are counted for the traces plotly lists: a trace hidden by
    a menu (``visible=False``) has no entry, one shown in the legend only has one, and
    traces of one legend group share one."""
    data = [
        {"name": "mode 1"},
        {"name": "mode 2", "visible": False},
        {"name": "mode 3", "visible": "legendonly"},
        {"name": "order 1", "legendgroup": "o1"},
        {"name": "order 1", "legendgroup": "o1"},
        {"name": "no entry", "showlegend": False},
        {"name": ""},
    ]
    assert legend_entries(data) == 3


def test_phone_stack_moves_columns_into_rows_and_back() -> None:
    fig = make_subplots(rows=1, cols=2, subplot_titles=("Force", "Moment"))
    layout = fig.to_plotly_json()["layout"]
    stack = phone_stack(layout)
    assert stack is not None
    phone, wide = stack["phone"], stack["wide"]
    assert phone["xaxis.domain"] == phone["xaxis2.domain"] == [0.0, 1.0]
    top, bottom = phone["yaxis.domain"][1], phone["yaxis2.domain"][1]
    assert top == 1.0 and bottom == 0.5  # "Force" above "Moment"
    assert phone["yaxis2.domain"][0] < phone["yaxis2.domain"][1] <= phone["yaxis.domain"][0]
    assert (phone["annotations[0].x"], phone["annotations[0].y"]) == (0.5, 1.0)
    assert (phone["annotations[1].x"], phone["annotations[1].y"]) == (0.5, 0.5)
    assert wide["xaxis2.domain"] == list(layout["xaxis2"]["domain"])
    assert wide["annotations[1].x"] == layout["annotations"][1]["x"]
    assert phone_stack(make_subplots(rows=2, cols=1).to_plotly_json()["layout"]) is None


def shown_page(
    browser: Any,
    server: str,
    viewport: dict[str, int],
    preset: str,
    tab: str | None = None,
    drawn: str = DRAWN,
) -> Any:
    """A new page on ``preset`` at ``viewport``, connected, on ``tab`` (None: the first),
    its results current and its figures drawn (``drawn``)."""
    page = browser.new_page(viewport=viewport)
    page.goto(f"{server}/?preset={preset}")
    connected(page)
    if tab is not None:
        open_tab(page, tab)
    page.wait_for_function(
        "() => document.querySelector('[data-testid=status]')?.dataset.state === 'current'"
    )
    page.wait_for_function(drawn)
    return page


def results(browser: Any, server: str, viewport: dict[str, int]) -> Any:
    return shown_page(browser, server, viewport, "v8-crossplane", "Results")


def test_compact_header_and_table_scroll_cue(server: str, browser: Any) -> None:
    page = results(browser, server, PHONE)
    try:
        header = page.evaluate("() => document.querySelector('.q-header').offsetHeight")
        assert header <= PHONE_HEADER
        # the balancing table is wider than the phone: it scrolls, and says so
        page.wait_for_function("() => document.querySelector('.q-table__container[data-cb-more]')")
        cue = page.evaluate(
            """() => getComputedStyle(document.querySelector(
                '.q-table__container[data-cb-more]'), '::after').content"""
        )
        assert "\u2192" in cue
        count = page.evaluate("() => document.querySelectorAll('[data-cb-more]').length")
        page.evaluate(
            """() => { const m = document.querySelector('[data-cb-more] .q-table__middle');
                       m.scrollLeft = m.scrollWidth; }"""
        )  # scrolled to its end: no more to the right, no cue
        page.wait_for_function(
            f"() => document.querySelectorAll('[data-cb-more]').length === {count - 1}"
        )
    finally:
        page.close()


@pytest.mark.parametrize("viewport", [PHONE, {"width": 1280, "height": 800}])
def test_subplots_stacked_on_a_phone_side_by_side_on_a_wide_screen(
    server: str, browser: Any, viewport: dict[str, int]
) -> None:
    page = results(browser, server, viewport)
    try:
        assert page.evaluate(f"() => ({SIDE_BY_SIDE})().length") >= 1
        phone = viewport["width"] < 600
        # stacked (every x axis the full width) on a phone, side by side on a wide screen
        page.wait_for_function(
            f"""() => ({SIDE_BY_SIDE})().every((e) => {{
                const starts = new Set(Object.keys(e.layout).filter((k) => k.startsWith('xaxis'))
                    .map((k) => (e.layout[k].domain || [0, 1])[0]));
                return {"starts.size === 1" if phone else "starts.size > 1"};
            }})"""
        )
        page.wait_for_function(DRAWN)
        width = viewport["width"]
        for rights, scrolls in page.evaluate(
            f"""() => ({SIDE_BY_SIDE})().map((e) => [
                [...e.querySelectorAll('.nsewdrag')].map((r) => r.getBoundingClientRect().right),
                ((box) => box.scrollWidth > box.clientWidth + 1)(e.closest('.cb-figure-box'))
            ])"""
        ):
            assert rights and max(rights) <= width  # every subplot within the screen
            assert not scrolls
    finally:
        page.close()


def test_a_wrapped_title_moves_the_plot_down() -> None:
    """A title the card wraps into one more line gets that line's height more top margin:
    the bearing loads' title no longer sits over "bearing 1" (issue 28, item 4)."""
    from crankbalance.web.widgets import DEFAULT_TOP_MARGIN, TITLE_LINE_PX, title_layout

    text = "Main-bearing loads over the cycle (indeterminate crank)<br><sup>V8 · 5500 rpm</sup>"
    out = title_layout({"title": {"text": text}})
    assert out["title"]["text"].count("<br>") == 2
    assert out["margin"]["t"] == DEFAULT_TOP_MARGIN + TITLE_LINE_PX
    assert "margin" not in title_layout({"title": {"text": "Short<br><sup>V8</sup>"}})


#: a phone's browser as Quasar tells one (its platform detection reads the user agent)
PHONE_AGENT = (
    "Mozilla/5.0 (Linux; Android 14; Pixel 8) AppleWebKit/537.36 (KHTML, like Gecko) "
    "Chrome/120.0 Mobile Safari/537.36"
)


def test_the_tab_bar_shows_its_scroll_arrows_on_a_touch_phone(server: str, browser: Any) -> None:
    """On a touch phone Quasar hides a tab bar's scroll arrows unless asked
    (``mobile-arrows``): the tabs past the right edge then have no cue."""
    context = browser.new_context(
        viewport=PHONE, user_agent=PHONE_AGENT, is_mobile=True, has_touch=True
    )
    page = context.new_page()
    try:
        page.goto(server + "/")
        connected(page)
        assert page.evaluate("() => window.Quasar.Platform.is.mobile === true")
        page.wait_for_function(
            """() => [...document.querySelectorAll('.q-tabs__arrow--right')].some(
                (a) => a.offsetParent !== null && !a.classList.contains('q-tabs__arrow--faded'))"""
        )
    finally:
        context.close()


def test_the_3d_crank_stands_farther_out_on_a_phone() -> None:
    """The 3-D crank's camera is fitted to a wide figure; on a phone (the page's relayout
    below 600 px) it stands ``PHONE_CRANK_CAMERA`` times farther out, so that the narrow
    scene keeps its tick labels, and goes back on a wide screen."""
    from crankbalance.output.figures.crank3d import crank_3d
    from crankbalance.studies.engine import balance_engine
    from crankbalance.web.tab_engine import PHONE_CRANK_CAMERA
    from crankbalance.web.widgets import on_a_phone

    study = balance_engine("v12-60")
    figure = crank_3d(study.model, study)
    fitted = figure.layout.scene.camera.eye.to_plotly_json()
    stack = on_a_phone(figure, PHONE_CRANK_CAMERA).layout.meta["cbStack"]
    assert stack["wide"] == {"scene.camera.eye": fitted}
    assert stack["phone"]["scene.camera.eye"] == pytest.approx(
        {k: v * PHONE_CRANK_CAMERA for k, v in fitted.items()}
    )
    assert PHONE_CRANK_CAMERA > 1
