"""Fixtures of the web tests: NiceGUI's simulated User (no browser) on the real page.

The tests are async; they run on anyio's pytest plugin (installed with httpx), asyncio
backend. Each test gets a fresh NiceGUI app (``user_simulation`` resets NiceGUI's globals).
"""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator
from typing import Any

import pytest

pytest.importorskip("nicegui")

from nicegui import ui  # noqa: E402
from nicegui.testing.user import User  # noqa: E402
from nicegui.testing.user_simulation import user_simulation  # noqa: E402

from crankbalance.web.app import root  # noqa: E402


@pytest.fixture
def anyio_backend() -> str:
    return "asyncio"


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

    async def until(self, condition: Any, timeout: float = 20.0) -> None:
        """Wait until background work of the page (async handlers) makes ``condition`` true."""
        for _ in range(int(timeout / 0.05)):
            if condition():
                return
            await asyncio.sleep(0.05)
        raise AssertionError("the page did not finish in time")

    def rows(self, marker: str) -> list[dict[str, Any]]:
        return list(self.element(marker).rows)


@pytest.fixture
def form(user: User) -> Form:
    return Form(user)
