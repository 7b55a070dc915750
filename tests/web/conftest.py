"""Fixtures of the web tests: NiceGUI's simulated User (no browser) on the real page, and
``crankbalance web`` in a subprocess (``server``) for the API, load and browser tests.

The tests are async; they run on anyio's pytest plugin (installed with httpx), asyncio
backend. Each test gets a fresh NiceGUI app (``user_simulation`` resets NiceGUI's globals).

Every wait is a wait for a state of the page (or of the server) with one generous hang
guard, :data:`HANG_GUARD`: on a loaded two-core machine work takes many times longer than
on an idle one, so no wait is tuned to how long the work takes.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import subprocess
import time
from collections.abc import AsyncIterator, Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("nicegui")

from nicegui import ui  # noqa: E402
from nicegui.testing.user import User  # noqa: E402
from nicegui.testing.user_simulation import user_simulation  # noqa: E402

from crankbalance.web.app import root  # noqa: E402

#: seconds a test waits for a state before it fails as hung (not a timing target)
HANG_GUARD = 180.0
ROOT = Path(__file__).resolve().parents[2]
CHROMIUM = "/usr/bin/chromium"
#: (browser) every plotly figure visible in the open tab panel is drawn with its data and
#: laid out for the window as it is now: after a change of the window's size plotly redraws
#: a moment later, and a 3-D scene is blank until then (its canvas is cleared by the resize)
DRAWN = """() => [...document.querySelectorAll('.q-tab-panel .js-plotly-plot')]
    .filter((e) => e.offsetParent !== null)
    .every((e) => e.querySelector('.main-svg') && e.data && e.data.length > 0
                  && e._fullLayout
                  && Math.abs(e._fullLayout.width - e.getBoundingClientRect().width) < 1)"""


async def until(condition: Callable[[], Any], what: str = "the page to finish") -> None:
    """Wait until ``condition()`` is true (background work of the page or server)."""
    with hang_guard(what):
        while not condition():
            await asyncio.sleep(0.05)


@contextlib.contextmanager
def hang_guard(what: str) -> Iterator[None]:
    """Fail (not hang) when the block has not finished within :data:`HANG_GUARD`."""
    import anyio

    try:
        with anyio.fail_after(HANG_GUARD):
            yield
    except TimeoutError:
        raise AssertionError(f"waited {HANG_GUARD:g} s for {what}; hung?") from None


@pytest.fixture
def anyio_backend() -> str:
    return "asyncio"


@pytest.fixture
def hang_guard_seconds() -> float:
    """:data:`HANG_GUARD`, for tests that wait on something else than the page."""
    return HANG_GUARD


@pytest.fixture(scope="session")
def server() -> Iterator[str]:
    """``crankbalance web`` in a subprocess (log in ``artifacts/web-server.log`` when that
    folder exists); yields its URL."""
    from crankbalance.web.server import running_server

    with contextlib.ExitStack() as stack:  # the log file is closed with the server
        log = (
            stack.enter_context(open(ROOT / "artifacts" / "web-server.log", "w"))
            if (ROOT / "artifacts").is_dir()
            else subprocess.DEVNULL
        )
        with running_server(log, timeout=HANG_GUARD) as url:
            yield url


@pytest.fixture(scope="module")
def logged_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[str, Path]]:
    """``crankbalance web`` in a subprocess with its log (stdout and stderr) in a file;
    yields its URL and the log's path."""
    from crankbalance.web.server import running_server

    path = tmp_path_factory.mktemp("server") / "server.log"
    with open(path, "w") as log, running_server(log, timeout=HANG_GUARD) as url:
        # the server's "ready" line may come just after its first answer: wait for it, so
        # that a test reading the log's new lines sees only what its requests caused
        deadline = time.monotonic() + HANG_GUARD  # a hang guard, not a timing
        while "crankbalance web: ready" not in path.read_text():
            assert time.monotonic() < deadline, "no ready line from the server; hung?"
            time.sleep(0.05)
        yield url, path


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    """Debian's chromium driven by Playwright (never a downloaded browser); every wait of
    Playwright (``expect``, ``wait_for``, downloads) has the hang guard as its timeout."""
    from crankbalance.output.render import CHROMIUM_FLAGS

    sync_api = pytest.importorskip("playwright.sync_api")
    if not os.path.exists(CHROMIUM):
        pytest.skip("needs Debian's chromium")
    sync_api.expect.set_options(timeout=HANG_GUARD * 1000)
    with sync_api.sync_playwright() as p:
        chromium = p.chromium.launch(executable_path=CHROMIUM, args=list(CHROMIUM_FLAGS))
        yield chromium
        chromium.close()


@pytest.fixture
def page(browser: Any) -> Iterator[Any]:
    """A new browser page, its default timeout the hang guard."""
    page = browser.new_page(viewport={"width": 1500, "height": 1000}, accept_downloads=True)
    page.set_default_timeout(HANG_GUARD * 1000)
    yield page
    page.close()


@pytest.fixture
async def user() -> AsyncIterator[User]:
    async with user_simulation(root=root) as simulated:
        yield simulated


class Form:
    """Reach the page's elements by marker, as a person would use them."""

    def __init__(self, user: User) -> None:
        self.user = user

    def element(self, marker: str) -> Any:
        """The one element carrying ``marker``."""
        found = self.user.find(marker=marker).elements
        assert len(found) == 1, f"expected one element marked {marker!r}, found {len(found)}"
        return next(iter(found))

    def find_hidden(self, marker: str) -> Any:
        """The one element carrying ``marker``, shown or hidden (:meth:`element` finds
        only the shown ones)."""
        from nicegui import ElementFilter

        with self.user:
            found = list(ElementFilter(marker=marker, only_visible=False))
        assert len(found) == 1, f"expected one element marked {marker!r}, found {len(found)}"
        return found[0]

    def open(self, tab: str) -> None:
        """Open a tab as a click on it would: a tab other than Engine and Results is built
        when it is first opened."""
        self.user.find(marker=f"tab-{tab}").click()

    def set(self, marker: str, value: Any) -> None:
        """Set an input or select as typing/choosing would (fires its on_change)."""
        with self.user:
            self.element(marker).value = value

    def error(self, marker: str) -> str | None:
        """The message shown beside a field (Quasar's error-message), None if none."""
        return self.element(marker).error

    def text(self, marker: str) -> str:
        """Text of a label or markdown element."""
        item = self.element(marker)
        return str(getattr(item, "content", None) or getattr(item, "text", ""))

    def page_inputs(self) -> dict[str, Any]:
        """Every form field of the engine, by marker."""
        found = {}
        for item in self.user.find(ui.input).elements | self.user.find(ui.select).elements:
            for marker in item._markers:
                if marker.startswith("field-"):
                    found[marker] = item
        return found

    async def until(self, condition: Callable[[], Any], what: str = "the page") -> None:
        """Wait until background work of the page (async handlers) makes ``condition`` true."""
        await until(condition, what)

    async def see(self, text: str) -> None:
        """Wait until the page shows ``text``."""
        await self.user.should_see(text, retries=int(HANG_GUARD / 0.1))  # 0.1 s apart

    async def download(self, marker: str) -> bytes:
        """Click the button marked ``marker`` and wait for the download it sends."""
        before = len(self.user.download.http_responses)
        self.user.find(marker=marker).click()
        await until(
            lambda: len(self.user.download.http_responses) > before, f"the {marker} download"
        )
        return bytes(self.user.download.http_responses[-1].content)

    def rows(self, marker: str) -> list[dict[str, Any]]:
        return list(self.element(marker).rows)


@pytest.fixture
def form(user: User) -> Form:
    return Form(user)
