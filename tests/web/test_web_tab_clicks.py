"""A tab click is never lost (issue 28, "no step that freezes"): the tab bar switches in the
browser at once and tells the server afterwards, so clicks faster than the server's answers
all count, the last one clicked is the tab shown, and text typed right after stays.

The slow server is made deterministic: every message of the server to the page is held
(Playwright's ``route_web_socket`` between chromium and ``crankbalance web``) until the
server has handled all the clicks and sent its answers, then let through in their order.
Every wait is for a state (a message held, the page's message counter, an element), with
the hang guard of ``conftest.py``; no sleep, no timing.
"""

from __future__ import annotations

import json
import os
import re
import time
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")

from crankbalance.io.engine_file import load_engine  # noqa: E402
from crankbalance.web.app import DISMISS_TOASTS  # noqa: E402

from .conftest import DRAWN, HANG_GUARD  # noqa: E402
from .test_web_engine_fields import _field, _results_match  # noqa: E402
from .test_web_lazy_tabs import LAZY  # noqa: E402
from .test_web_screens import BUILT, SETTLED  # noqa: E402

expect = playwright_api.expect
#: screenshots for a person to look at (not committed): CRANKBALANCE_SHOTS=folder
SHOTS = os.environ.get("CRANKBALANCE_SHOTS")


class HeldServer:
    """The page's socket to the server, the server's messages held while :attr:`holding`."""

    def __init__(self, page: Any) -> None:
        self.page = page
        self.holding = False
        self.held: list[tuple[Any, Any]] = []
        page.route_web_socket(re.compile(r"/_nicegui_ws/"), self._route)

    def _route(self, ws: Any) -> None:
        server = ws.connect_to_server()
        ws.on_message(lambda message: server.send(message))  # the page's go at once
        server.on_message(lambda message: self._from_server(ws, message))

    def _from_server(self, ws: Any, message: Any) -> None:
        if self.holding:
            self.held.append((ws, message))
        else:
            ws.send(message)

    def events(self) -> list[tuple[str, Any]]:
        """The socket.io events held (name and data), in their order."""
        found = []
        for _ws, message in self.held:
            if isinstance(message, str) and message.startswith("42"):
                name, *data = json.loads(message[2:].lstrip("0123456789"))
                found.append((name, data[0] if data else None))
        return found

    def wait_for_tab_answers(self, clicks: int) -> None:
        """Wait until the server has handled ``clicks`` clicks on tabs and sent everything
        they caused: each handled click closes the toasts (``Page.on_tab``), a message the
        server sends after the element updates of the same handling."""

        def answered() -> int:
            return sum(
                1
                for name, data in self.events()
                if name == "run_javascript" and data and data.get("code") == DISMISS_TOASTS
            )

        deadline = time.monotonic() + HANG_GUARD  # a hang guard, not a timing
        while answered() < clicks:
            assert time.monotonic() < deadline, f"the server answered {answered()} of {clicks}"
            self.page.wait_for_timeout(50)  # lets Playwright deliver the socket's messages

    def release(self) -> None:
        """Let the held messages through in their order and wait until the page has taken
        them all (NiceGUI's ``window.nextMessageId`` passes the last one's ``_id``)."""
        last = max(
            (data["_id"] for _name, data in self.events() if isinstance(data, dict)),
            default=-1,
        )
        self.holding = False
        for ws, message in self.held:
            ws.send(message)
        self.held.clear()
        self.page.wait_for_function(f"() => window.nextMessageId > {last}")


def _tab(page: Any, label: str) -> Any:
    return page.get_by_role("tab", name=label, exact=True)


def _shown(page: Any, label: str) -> None:
    """The tab ``label`` is the selected one and its panel the one shown, built."""
    expect(_tab(page, label)).to_have_attribute("aria-selected", "true")
    page.wait_for_function(SETTLED)
    page.wait_for_function(BUILT)


def _open(page: Any, server: str, preset: str) -> tuple[HeldServer, list[str]]:
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    held = HeldServer(page)
    page.goto(f"{server}/?preset={preset}")
    expect(page.locator("[data-testid=status]").first).to_contain_text("Results of:")
    # the page's socket is connected (its server part answered the handshake): what is
    # held from now on are answers, not the connection itself
    page.wait_for_function("() => window.did_handshake === true")
    return held, errors


def _shoot(page: Any, name: str) -> None:
    if SHOTS:
        Path(SHOTS).mkdir(parents=True, exist_ok=True)
        page.wait_for_function(DRAWN)
        page.screenshot(path=f"{SHOTS}/{name}.png", full_page=True)


@pytest.mark.parametrize(
    "clicks",
    [("Results", "Engine"), ("Counterweight design", "Single cylinder", "Engine")],
    ids=["results-engine", "three-tabs-engine"],
)
def test_clicks_before_the_server_answers_end_on_the_last(
    server: str, page: Any, clicks: tuple[str, ...]
) -> None:
    """Tabs clicked one after the other while the server has answered none of them: each
    shows at once, the last one clicked (Engine, the tab shown when the first click was
    made) stays shown when the server's answers arrive, and text typed into an engine field
    right after the clicks, before the answers, is kept and computed."""
    held, errors = _open(page, server, "ducati-916")
    field = _field(page, "rod_positions")
    expect(field).to_have_value("-10 mm, 10 mm")
    held.holding = True
    for label in clicks:
        _tab(page, label).click()
        expect(_tab(page, label)).to_have_attribute("aria-selected", "true")  # at once
    expect(field).to_be_visible()
    field.click()
    page.keyboard.press("Control+a")
    field.press_sequentially("-30 mm, 30 mm")
    held.wait_for_tab_answers(len(clicks))
    held.release()
    _shown(page, "Engine")
    expect(field).to_be_visible()
    expect(field).to_have_value("-30 mm, 30 mm")
    spec = load_engine("ducati-916")
    _results_match(
        page, spec.replace(crank_train=spec.crank_train.replace(rod_positions=[-0.03, 0.03]))
    )
    _shown(page, "Engine")
    expect(field).to_have_value("-30 mm, 30 mm")
    _shoot(page, f"tab-clicks-{len(clicks)}")
    assert not errors, errors


def test_tabs_opened_and_left_quickly_end_built(server: str, page: Any) -> None:
    """Two tabs never opened, clicked one after the other before the server answers: the
    last one is shown with its content built (not the "Opening the tab …" placeholder), and
    the one opened and left at once is built too, with the project's values, when it is
    opened again."""
    held, errors = _open(page, server, "v8-crossplane")
    held.holding = True
    _tab(page, "Single cylinder").click()
    _tab(page, "Balance shaft").click()
    expect(_tab(page, "Balance shaft")).to_have_attribute("aria-selected", "true")
    held.wait_for_tab_answers(2)
    held.release()
    _shown(page, "Balance shaft")
    expect(page.locator(f"[data-testid={LAZY['shaft']}]").first).to_be_visible()
    _shoot(page, "tab-clicks-shaft")
    _tab(page, "Single cylinder").click()
    _shown(page, "Single cylinder")
    setting = page.locator(f"[data-testid={LAZY['single']}]").first
    expect(setting).to_be_visible()
    assert page.locator("[data-testid=single-opening]").count() == 0
    assert not errors, errors
