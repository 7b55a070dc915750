"""Five concurrent browser sessions on one server, each editing its own engine.

Five Playwright pages in one Debian chromium (the ``browser`` fixture) open the page on five
presets. Each edit is typed into all five pages before any page is waited for, so the
server handles the five sessions' updates side by side. At the end every page must show its
own engine ("Results of: <its name>") and the free forces and moments of its own edited
engine, as the library's ``analyze`` computes them; no page may show an error banner, log a
console error or get a 5xx from the server. Each page switches its *Live 3-D view* off first,
as the load test does: five 3-D scenes drawn in software WebGL on two busy cores would
measure chromium, not the sessions. Every wait is for a state of the page with the
hang guard of ``conftest.py`` (Playwright's default timeout there).
"""

from __future__ import annotations

import os
import tomllib
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

#: one preset per session
PRESETS = ("v12-60", "v8-crossplane", "inline4", "v6-60", "boxer4")
#: screenshots for a person to look at (not committed): CRANKBALANCE_SHOTS=folder
SHOTS = os.environ.get("CRANKBALANCE_SHOTS")
#: how often a wait looks at the page [ms] (a poll, not a timing: plotly's WebGL scene can
#: hold back the animation frames that Playwright's default polling waits for)
POLL = 100
#: the header's state and update count (every processed edit raises the count)
UPDATED = """([after]) => {
    const s = document.querySelector('[data-testid=status]');
    return s && Number(s.dataset.update) > after && s.dataset.state === 'current';
}"""
UPDATE = "() => Number(document.querySelector('[data-testid=status]')?.dataset.update || 0)"
#: the cells of the orders table of the Results tab, row by row
TABLE = """() => [...document.querySelectorAll(
        '.q-tab-panel:not([hidden]) [data-testid=orders-table] tbody tr')]
    .filter((tr) => tr.offsetParent !== null)
    .map((tr) => [...tr.querySelectorAll('td')].map((td) => td.innerText.trim()))"""


def edits(k: int) -> list[tuple[str, str, tuple[str, ...]]]:
    """The edits of session ``k``: (form field, typed text, engine-file key), different
    between sessions and from every preset's value (an unchanged value updates nothing)."""
    return [
        ("crank_radius", f"{41 + k}.5 mm", ("crank_train", "crank_radius")),
        ("speed", f"{4000 + 250 * k} rpm", ("speed",)),
        ("rod_length", f"{140 + 2 * k} mm", ("crank_train", "rod_length")),
    ]


def expected_rows(preset: str, k: int) -> tuple[str, list[list[str]]]:
    """The engine name and the orders table of session ``k``'s edited engine, from the
    library: the preset's engine file with the same edits, validated and analysed."""
    from crankbalance.io.engine_file import preset_text
    from crankbalance.output.format import number
    from crankbalance.schema.engine import spec_from_dict
    from crankbalance.studies.engine import analyze

    data = tomllib.loads(preset_text(preset))
    for _key, text, path in edits(k):
        table = data
        for part in path[:-1]:
            table = table[part]
        table[path[-1]] = text
    spec = spec_from_dict(data)
    d = analyze(spec).to_dict()
    rows = [
        [
            str(f["order"]),
            *(number(float(f[key]), 5) for key in ("amplitude_N", "forward_N", "backward_N")),
            *(number(float(m[key]), 5) for key in ("amplitude_Nm", "forward_Nm", "backward_Nm")),
        ]
        for f, m in zip(d["free_forces"], d["free_moments"], strict=True)
    ]
    return spec.name, rows


class Session:
    """One browser page on one preset, recording what would be a failure."""

    def __init__(self, browser: Any, server: str, preset: str, guard: float) -> None:
        self.preset = preset
        self.problems: list[str] = []
        self.page = browser.new_page(viewport={"width": 1280, "height": 800})
        self.page.set_default_timeout(guard * 1000)
        self.page.on("pageerror", self._page_error)
        self.page.on("console", self._console)
        self.page.on("response", self._response)
        self.page.goto(f"{server}/?preset={preset}")

    def _page_error(self, error: Any) -> None:
        self.problems.append(f"page error: {error}")

    def _console(self, message: Any) -> None:
        if message.type == "error":
            self.problems.append(f"console error: {message.text}")

    def _response(self, response: Any) -> None:
        if response.status >= 500:
            self.problems.append(f"{response.status} from {response.url}")

    def update(self) -> int:
        return int(self.page.evaluate(UPDATE))


def test_five_concurrent_sessions(server: str, browser: Any, hang_guard_seconds: float) -> None:
    sessions = [Session(browser, server, preset, hang_guard_seconds) for preset in PRESETS]
    try:
        for s in sessions:
            s.page.wait_for_function(UPDATED, arg=[0], polling=POLL)
            # five software-WebGL scenes on two busy cores would test chromium, not the server
            s.page.locator("[data-testid=show-3d]").first.click()
            expect(s.page.locator("[data-testid=show-3d]").first).to_have_attribute(
                "aria-checked", "false"
            )
        for step in range(len(edits(0))):
            before = [s.update() for s in sessions]
            for k, s in enumerate(sessions):  # typed in all five before waiting for any
                key, text, _ = edits(k)[step]
                s.page.locator(f"[data-testid=field-{key}]").first.fill(text)
            for s, n in zip(sessions, before, strict=True):
                s.page.wait_for_function(UPDATED, arg=[n], polling=POLL)
        for k, s in enumerate(sessions):
            name, rows = expected_rows(s.preset, k)
            for key, text, _ in edits(k):  # the form still holds this session's own edits
                expect(s.page.locator(f"[data-testid=field-{key}]").first).to_have_value(text)
            s.page.get_by_role("tab", name="Results", exact=True).click()
            expect(s.page.locator("[data-testid=status]").first).to_have_text(f"Results of: {name}")
            s.page.wait_for_function(
                f"(rows) => JSON.stringify(({TABLE})()) === JSON.stringify(rows)",
                arg=rows,
                polling=POLL,
            )
            assert s.page.evaluate(TABLE) == rows, s.preset
            # no error banner: no field message, no general message, no stale note
            assert s.page.locator(".q-field--error").count() == 0, s.preset
            expect(s.page.locator("[data-testid=results-stale]").first).to_be_hidden()
            expect(s.page.locator("[data-testid=general-error]").first).to_have_text("")
            assert s.page.locator(".q-notification.bg-negative").count() == 0, s.preset
            if SHOTS:
                Path(SHOTS).mkdir(parents=True, exist_ok=True)
                s.page.screenshot(path=f"{SHOTS}/session-{k + 1}-{s.preset}.png", full_page=True)
        for s in sessions:
            assert not s.problems, (s.preset, s.problems)
    finally:
        for s in sessions:
            s.page.close()
