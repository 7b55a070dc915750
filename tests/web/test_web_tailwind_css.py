"""The page's static Tailwind stylesheet (web/static/tailwind.css) against NiceGUI's Tailwind
runtime, in a real browser (Playwright driving Debian's chromium).

The page is served without the runtime (``ui.run(tailwind=False)``) and with the stylesheet
that ``tests/web/tailwind_css.py`` captured from it. Checked against a second server with
the runtime on (``serve(tailwind=True)``, NiceGUI's own compiler and configuration):

- every rule the runtime generates for the page (every tab at both widths, Quasar's
  popups, every class written in the code) is in the shipped stylesheet: a class added to
  the code without regenerating the stylesheet fails here;
- the page looks the same: every tab at 1280x800 and 390x844 has every element of the
  page in the same place and size, with the same font and colours, as with the runtime.
  Screenshots of both go to ``artifacts/tailwind/`` when that folder's parent exists.

Every wait is a wait for a state of the page with the hang guard of ``conftest.py``.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("nicegui")
pytest.importorskip("playwright.sync_api")

from . import tailwind_css  # noqa: E402
from .conftest import DRAWN, HANG_GUARD, ROOT  # noqa: E402

SHOTS = ROOT / "artifacts" / "tailwind"
#: every element of the page a person sees (a figure's inside is plotly's, drawn for the
#: figure's box; a click's ripple is left out): its name (tag, test id, classes), box [px,
#: page coordinates] and the computed font, colour and background
LAYOUT = """() => {
  const seen = (e) => e.getClientRects().length > 0
      && getComputedStyle(e).visibility !== 'hidden';
  const items = [];
  for (const e of document.querySelectorAll('#app *')) {
    if (e.closest('svg') || e.parentElement.closest('.js-plotly-plot')) continue;
    if (e.id === 'cb-busy' || e.closest('.q-ripple') || !seen(e)) continue;
    const r = e.getBoundingClientRect();
    const s = getComputedStyle(e);
    const name = [e.tagName.toLowerCase(), e.dataset.testid || '',
                  (e.getAttribute('class') || '').trim()].join(' ');
    items.push([name, ...[r.left, r.top + scrollY, r.width, r.height]
                .map((v) => Math.round(v * 2) / 2),
                s.font, s.color, s.backgroundColor]);
  }
  return items;
}"""


@pytest.fixture(scope="module")
def runtime_server() -> Iterator[str]:
    """``serve(tailwind=True)``: the page with NiceGUI's Tailwind runtime."""
    from crankbalance.web.server import running_server

    with running_server(timeout=HANG_GUARD, tailwind=True) as url:
        yield url


def test_shipped_stylesheet_has_every_rule_of_the_runtime(
    runtime_server: str, browser: Any
) -> None:
    """What the runtime generates for the page now is all in web/static/tailwind.css."""
    captured = tailwind_css.capture(browser, runtime_server)
    assert "@layer utilities" in captured and ".w-full" in captured, captured[:500]
    lacking = tailwind_css.missing(captured, tailwind_css.shipped())
    assert not lacking, (
        f"web/static/tailwind.css lacks {len(lacking)} rule(s) that NiceGUI's Tailwind "
        f"runtime generates for the page (a class added to the code?); run "
        f"{tailwind_css.REGENERATE}\n" + "\n".join(lacking[:40])
    )


def test_rules_reader() -> None:
    """:func:`tailwind_css.rules` sees the same rules in another order and layout, and each
    declaration with the at-rules and selector around it."""
    one = "@layer a, b;\n@layer b { .x { width: 1px; color: red } /* c { */ }\n.y{content: '}'}"
    two = ".y {\n  content: '}';\n}\n@layer a, b;\n@layer b {\n .x { color: red;\n width: 1px; } }"
    assert (
        tailwind_css.rules(one)
        == tailwind_css.rules(two)
        == {
            ("@layer a, b",),
            ("@layer b", ".x", "width: 1px"),
            ("@layer b", ".x", "color: red"),
            (".y", "content: '}'"),
        }
    )
    assert tailwind_css.missing("@layer b { .x { width: 2px } }", one) == [
        "@layer b { .x { width: 2px"
    ]


def test_class_tokens(tmp_path: Path) -> None:
    """:func:`tailwind_css.class_tokens` reads the classes written in the code: literal,
    added or removed, passed as ``classes=``, and a parameter's default and the strings
    its callers pass; a dict's keys and other strings are no classes."""
    (tmp_path / "page.py").write_text(
        "class A:\n"
        "    def cell(self, key, width='w-32'):\n"
        "        ui.input(key).classes(width).props('dense')\n"
        "    def build(self):\n"
        "        self.cell('a', 'w-28')\n"
        "        self.cell('b', width='md:w-56')\n"
        "        ui.row().classes('w-full\\n gap-2').classes(add='x-1', remove='x-2')\n"
        "        ui.element('div', classes='min-w-[3px]')\n"
        "class B:\n"
        "    def build(self, on):\n"
        "        ui.label('not a class').classes(**{'add' if on else 'remove': 'cb-y'})\n"
    )
    assert tailwind_css.class_tokens(tmp_path) == [
        *("cb-y", "gap-2", "md:w-56", "min-w-[3px]", "w-28", "w-32", "w-full", "x-1", "x-2")
    ]


def _open(page: Any, label: str) -> None:
    tailwind_css.open_tab(page, label)
    page.mouse.move(0, 0)  # the tab is not hovered in the screenshot
    page.wait_for_function(DRAWN)
    page.wait_for_function(tailwind_css.SETTLED)
    page.wait_for_function(STILL)
    page.wait_for_function(TABS_MEASURED)


#: every tab bar shown shows the scroll arrows exactly when its tabs overflow it, Quasar's rule
#: (QTabs.updateContainer); after a change of the window's size Quasar applies it through a
#: debounced resize observer, so a bar measured at once may still have the old width's state
TABS_MEASURED = """() => [...document.querySelectorAll('.q-tabs')].every((bar) => {
    const content = bar.querySelector('.q-tabs__content');
    if (!content || bar.offsetParent === null) return true;  // a bar not shown
    const tabs = [...content.children].reduce((sum, el) => sum + (el.offsetWidth || 0), 0);
    const overflow = bar.offsetWidth > 0 && Math.min(content.scrollWidth, tabs) > bar.offsetWidth;
    return bar.classList.contains('q-tabs--scrollable') === overflow; })"""


#: no animation or transition of the page is running (the tab bar's indicator slides to
#: the tab opened), endless ones (the busy bar) aside
STILL = """() => document.getAnimations().every((a) => a.playState !== 'running'
    || a.effect.getComputedTiming().endTime === Infinity)"""


@contextlib.contextmanager
def _pages(browser: Any, urls: dict[str, str]) -> Iterator[dict[str, Any]]:
    pages = {}
    try:
        for mode, url in urls.items():
            pages[mode] = tailwind_css.open_page(browser, url)
        yield pages
    finally:
        for page in pages.values():
            page.close()


def _differences(runtime: list[list[Any]], static: list[list[Any]]) -> list[str]:
    if [item[0] for item in runtime] != [item[0] for item in static]:
        names = sorted({item[0] for item in runtime} ^ {item[0] for item in static})
        return [f"other elements shown: {names[:10]} (of {len(runtime)} and {len(static)})"]
    found = []
    for a, b in zip(runtime, static, strict=True):
        boxes = max(abs(u - v) for u, v in zip(a[1:5], b[1:5], strict=True))
        if boxes > 1 or a[5:] != b[5:]:
            found.append(f"{a[0]!r}: runtime {a[1:]} static {b[1:]}")
    return found


def test_layout_same_as_with_the_runtime(server: str, runtime_server: str, browser: Any) -> None:
    """Every tab at 1280x800 and 390x844: with the static stylesheet every element shown
    has the box, font and colours it has with the runtime; the static page loads no
    runtime and has the stylesheet."""
    from crankbalance.web.app import TABS
    from crankbalance.web.server import TAILWIND_URL

    shots = SHOTS.parent.is_dir()
    if shots:
        SHOTS.mkdir(exist_ok=True)
    problems: list[str] = []
    with _pages(browser, {"runtime": runtime_server, "static": server}) as pages:
        static = pages["static"]
        assert static.evaluate(tailwind_css.RUNTIME_CSS) is None, "the runtime is loaded"
        assert static.evaluate(
            "(u) => [...document.styleSheets].some((s) => (s.href || '').includes(u)"
            " && s.cssRules.length > 0)",
            TAILWIND_URL,
        ), f"the page has no stylesheet from {TAILWIND_URL}"
        for size in (tailwind_css.DESKTOP, tailwind_css.PHONE):
            for _name, label in TABS:
                layouts = {}
                for mode, page in pages.items():
                    page.set_viewport_size(size)
                    _open(page, label)
                    page.evaluate("window.scrollTo(0, 0)")
                    page.wait_for_function("() => window.scrollY === 0")
                    layouts[mode] = page.evaluate(LAYOUT)
                    if shots:
                        tab = label.lower().replace(" ", "_")
                        page.screenshot(
                            path=str(SHOTS / f"{tab}-{size['width']}-{mode}.png"), full_page=True
                        )
                found = _differences(layouts["runtime"], layouts["static"])
                problems += [f"{label} at {size['width']} px: {d}" for d in found[:5]]
    assert not problems, "the page looks different without the runtime:\n" + "\n".join(
        problems[:40]
    )
