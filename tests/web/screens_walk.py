"""A screenshot set of every tab of the web app, for a person to look at (issue 28, "Show").

Run as ``python tests/web/screens_walk.py OUTDIR`` (not collected by pytest): starts
``crankbalance web`` on a free port and Debian's chromium as ``tests/web/conftest.py`` does,
and for each preset of :data:`PRESETS` opens every tab, runs the tab's study with its
default settings where the tab has a run button (the Balance shop with its example parts
and the two readings of ``examples/v8_shop.py``, the Mounts tab with its worked example),
and saves full-page PNGs ``OUTDIR/<preset>_<tab>_<width>.png`` at 1280x800 and 390x844, plus
``OUTDIR/console.log``: every console error and page error, with the preset and tab it came
in, and every wait that ran into the hang guard. Every wait is a wait for a state of the page
(never a sleep); a wait that runs into the guard is logged and the walk goes on.
"""

from __future__ import annotations

import argparse
import re
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))  # the helpers of the browser tests, reused

from tests.web.conftest import CHROMIUM  # noqa: E402
from tests.web.test_web_screens import (  # noqa: E402
    ACTIONS,
    DESKTOP,
    DRAWN,
    IN_WINDOW,
    PHONE,
    SETTLED,
    _open_tab,
)
from tests.web.test_web_shop import TYPED as SHOP_READINGS  # noqa: E402

#: the presets walked: an inline-4, the crossplane V8, the split-pin V6, a single cylinder
PRESETS = ("inline4", "v8-crossplane", "v6-60", "single")
#: the tabs, in the page's order: (label, short name used in the file names)
TABS = (
    ("Engine", "engine"),
    ("Masses", "masses"),
    ("Results", "results"),
    ("Counterweight design", "counterweight"),
    ("Single cylinder", "single"),
    ("Balance shaft", "shaft"),
    ("Performance", "performance"),
    ("Explorer", "explore"),
    ("Balance shop", "shop"),
    ("Crank loads", "loads"),
    ("Mounts", "mounts"),
)
#: the run button of each study tab and a text only its result (or its refusal) shows in
#: the tab panel
RUNS = {
    **ACTIONS,
    "Explorer": ("Explore", r"distinct engines|Not run|too many|at most"),
    "Balance shop": ("Run", ""),  # its summary, below
    "Crank loads": ("Run", r"Lowest peak|Not run"),
}
#: where a tab's result shows when it is not a text of its own: the element and a pattern
#: of its finished result (the shop's summary says "running …" while it runs, and its
#: field labels name ISO 21940 too)
RESULT_IN = {"Balance shop": ("[data-testid=shop-summary]", r"^(?![\s\S]*running)[\s\S]*\S")}
#: the Mounts tab's worked example for each preset (a button of web/tab_mounts.py)
MOUNTS_EXAMPLE = "Inline-4 car, three mounts"
#: seconds a wait lasts before the walk logs it and goes on (a hang guard, not a timing)
GUARD = 240.0
#: (browser) the shown tab panel shows a text matching the pattern given (a study's result
#: or its refusal) or a field's error message (settings refused)
DONE = """([pattern, selector]) => {
    const panel = [...document.querySelectorAll('.q-tab-panel')]
        .find((p) => p.offsetParent !== null);
    const shown = panel && (selector ? panel.querySelector(selector) : panel);
    return !!shown && (new RegExp(pattern).test(shown.innerText)
        || [...panel.querySelectorAll('.q-field--error')].some((e) => e.offsetParent !== null));
}"""


class Walk:
    """One browser page walking the tabs of one preset; logs what went wrong."""

    def __init__(self, browser: Any, url: str, preset: str, out: Path, log: list[str]) -> None:
        self.page = browser.new_page(viewport=DESKTOP)
        self.page.set_default_timeout(GUARD * 1000)
        self.preset, self.out, self.log, self.tab = preset, out, log, "start"
        self.page.on("console", self.console)
        self.page.on("pageerror", lambda e: self.note(f"page error: {e}"))
        self.page.goto(f"{url}/?preset={preset}")
        self.expect(self.status()).to_contain_text("Results of:")
        self.page.wait_for_function("() => window.socket && window.socket.connected")

    def note(self, line: str) -> None:
        self.log.append(f"{self.preset} | {self.tab} | {line}")

    def console(self, message: Any) -> None:
        if message.type in ("error", "warning"):
            self.note(f"console {message.type}: {message.text}")

    def status(self) -> Any:
        return self.page.locator("[data-testid=status]").first

    @property
    def expect(self) -> Any:
        from playwright.sync_api import expect

        return expect

    def panel(self) -> Any:
        return self.page.locator(".q-tab-panel:visible").first

    def wait(self, what: str, step: Any) -> bool:
        """Run the wait ``step``; on the hang guard log it and go on."""
        try:
            step()
        except Exception as error:  # Playwright's TimeoutError and assertion errors
            self.note(f"waited for {what}: {type(error).__name__}: {str(error)[:300]}")
            return False
        return True

    def result_or_refusal(self, pattern: str, selector: str = "") -> None:
        self.page.wait_for_function(DONE, arg=[pattern, selector])

    def run(self, label: str) -> None:
        """Run the tab's study (its example loaded first where it has one)."""
        panel = self.panel()
        if label == "Balance shop":
            panel.get_by_role("button", name="Load example").click()
            parts = self.page.locator("[data-testid=shop-parts]").first
            self.wait(
                "the example parts", lambda: self.expect(parts).to_have_value(re.compile("."))
            )
            for key, value in SHOP_READINGS.items():
                self.page.locator(f"[data-testid=shop-{key}]").first.fill(value)
        button, done = RUNS[label]
        selector, done = RESULT_IN.get(label, ("", done))
        panel.get_by_role("button", name=button, exact=True).click()
        self.wait("the study's result", lambda: self.result_or_refusal(done, selector))

    def mounts_example(self) -> None:
        """The Mounts tab's worked example (it replaces the engine) and its run."""
        self.tab = "mounts-example"
        self.page.get_by_role("button", name=MOUNTS_EXAMPLE).click()
        self.wait(
            "the example engine",
            lambda: self.expect(self.status()).to_contain_text("Inline-4 transverse"),
        )
        self.panel().get_by_role("button", name="Run", exact=True).click()
        self.wait("the mounts study", lambda: self.result_or_refusal(r"Torque-roll axis|Not run"))
        self.shoot("mounts-example")

    def shoot(self, name: str) -> None:
        for size in (DESKTOP, PHONE):
            self.page.set_viewport_size(size)
            self.wait("the figures drawn", lambda: self.page.wait_for_function(DRAWN))
            self.wait("the panel laid out", lambda: self.page.wait_for_function(IN_WINDOW))
            self.page.evaluate("window.scrollTo(0, 0)")
            self.page.wait_for_function("() => window.scrollY === 0")
            path = self.out / f"{self.preset}_{name}_{size['width']}.png"
            self.page.screenshot(path=str(path), full_page=True)
        self.page.set_viewport_size(DESKTOP)
        self.wait("the figures drawn", lambda: self.page.wait_for_function(DRAWN))

    def every_tab(self) -> None:
        for label, name in TABS:
            self.tab = name
            self.wait("the tab", lambda label=label: _open_tab(self.page, label))
            if label in RUNS:
                self.run(label)
            self.wait("the tab settled", lambda: self.page.wait_for_function(SETTLED))
            self.shoot(name)
        self.mounts_example()
        self.page.close()


def browser() -> Iterator[Any]:
    from playwright.sync_api import expect, sync_playwright

    from crankbalance.output.render import CHROMIUM_FLAGS

    expect.set_options(timeout=GUARD * 1000)  # Playwright's own is 5 s
    with sync_playwright() as p:
        chromium = p.chromium.launch(executable_path=CHROMIUM, args=list(CHROMIUM_FLAGS))
        yield chromium
        chromium.close()


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("outdir", type=Path)
    parser.add_argument("--presets", nargs="+", default=list(PRESETS))
    args = parser.parse_args()
    from crankbalance.web.server import running_server

    out: Path = args.outdir
    out.mkdir(parents=True, exist_ok=True)
    log: list[str] = []
    started = time.monotonic()
    with open(out / "server.log", "w") as server_log, running_server(server_log) as url:
        for chromium in browser():
            for preset in args.presets:
                begun = time.monotonic()
                Walk(chromium, url, preset, out, log).every_tab()
                log.append(f"{preset} | - | walked in {time.monotonic() - begun:.0f} s")
                (out / "console.log").write_text("\n".join(log) + "\n", encoding="utf-8")
    log.append(f"- | - | whole walk {time.monotonic() - started:.0f} s")
    (out / "console.log").write_text("\n".join(log) + "\n", encoding="utf-8")
    print("\n".join(log))
    return 0


if __name__ == "__main__":
    sys.exit(main())
