"""Every error the web shows names the field as the form labels it (issue 28): no raw
schema or library name (``web_thickness``, ``correction_radius``) and no command-line
option (``--web-thickness``) in a message, and no sentence word taken for a name
(``axial holes`` is not ``axial Holes per web``).

First the simulated user: every text setting of every study tab typed invalid, its
message read; the Single cylinder's drilling plan refused by the library, its message read.
Then (last: the sync Playwright test keeps an event loop running) the same drilling-plan
message in Debian's chromium, with a screenshot.
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

import pytest
from nicegui import ui
from nicegui.testing.user import User

from crankbalance.errors import InputError
from crankbalance.web.app import RESULT_TABS
from crankbalance.web.messages import in_words
from crankbalance.web.tab_single import ALIASES

from .conftest import Form

pytestmark = pytest.mark.anyio
ROOT = Path(__file__).resolve().parents[2]
SHOTS = Path(os.environ.get("CRANKBALANCE_SHOTS") or ROOT / "artifacts" / "screenshots")
#: a raw name: a word with an underscore (a schema key, a library argument) or an option
RAW = re.compile(r"\b[a-z]+_[a-z_]+\b|--[a-z]")
#: the study tabs with settings (Results has none)
STUDY_TABS = [*(name for name in RESULT_TABS if name != "results"), "explore"]
#: the settings that make the Single cylinder's drilling plan too deep for the web: a
#: rotating mass far above the paper's inline-3's (a hole 318 mm deep) in a 10 mm web
TOO_DEEP = {
    "rb_new_reciprocating": "300 g",
    "rb_new_rotating": "900 g",
    "rb_hole_diameter": "20 mm",
    "rb_hole_radius": "40 mm",
    "rb_web_thickness": "10 mm",
}


def _label(element: Any) -> str:
    return str(element.props.get("label") or "")


def test_library_names_in_a_message_are_labels_words_stay() -> None:
    error = InputError(
        "hole_diameter",
        "80 mm",
        "is too large for axial holes at correction_radius = 40 mm (the part's depth is "
        "not given: web_thickness); split them: 3 per web (holes: 3)",
    )
    key, text = in_words(error, ALIASES)
    assert key == "rb_hole_diameter"
    assert text == (
        "Drill diameter: '80 mm' is too large for axial holes at Hole radius = 40 mm (the "
        "part's depth is not given: Web thickness at the holes); split them: 3 per web "
        "(Holes per web: 3)"
    )


@pytest.mark.parametrize("tab", STUDY_TABS)
async def test_every_setting_message_names_its_label(user: User, form: Form, tab: str) -> None:
    """Each text setting of the tab typed as ``abc``: its message starts with its label
    and holds no raw name."""
    await user.open("/")
    await form.see("Results of:")
    form.open(tab)
    await form.until(lambda: user.find(marker=f"tab-{tab}").elements, "the tab")
    if tab == "mounts":  # its settings show for an engine with a powertrain
        user.find(marker="mounts-example-mounts_inline4_car").click()
        await form.see("Results of: Inline-4")
    if tab == "shop":  # a parts file first: the tab shows one message at a time
        user.find(marker="shop-example").click()
        await form.until(lambda: form.element("shop-parts").value, "the example's parts")
    inputs = [
        element
        for element in user.find(ui.input).elements
        if any(m.startswith(("setting-", f"{tab}-")) for m in element._markers)
        and element.visible
        and _label(element)
        # a pasted file's message names its columns as the file writes them (big_end)
        and not isinstance(element, ui.textarea)
    ]
    checked = 0
    for element in inputs:
        marker = next(m for m in element._markers if m.startswith(("setting-", f"{tab}-")))
        if marker.startswith("setting-") and not _belongs(marker, tab):
            continue
        before = element.value
        form.set(marker, "abc")
        message = element.error
        form.set(marker, before)
        if message is None:  # a text setting that takes any text (a name, a list)
            continue
        checked += 1
        assert message.startswith(_label(element)), (marker, message)
        assert not RAW.search(message), (marker, message)
    assert checked >= 2, f"{tab}: {checked} settings refused 'abc'"


#: the setting prefixes of each tab that keeps its settings in the project
PREFIXES = {
    "counterweight": ("cw_",),
    "single": ("sc_", "rb_"),
    "shaft": ("bs_",),
    "performance": ("pf_",),
}


def _belongs(marker: str, tab: str) -> bool:
    return marker.removeprefix("setting-").startswith(PREFIXES.get(tab, ("-",)))


async def test_the_drilling_plan_message_names_the_web_thickness(user: User, form: Form) -> None:
    """The library refuses a hole deeper than the web: the plan's message names the web
    thickness, the drill and the holes by their labels."""
    await user.open("/")
    await form.see("Results of:")
    form.open("single")
    await form.until(lambda: user.find(marker="run-single").elements, "the tab")
    for key, value in TOO_DEEP.items():
        form.set(f"setting-{key}", value)
        assert form.error(f"setting-{key}") is None, key
    user.find(marker="run-single").click()
    await form.until(lambda: "No drilling plan" in form.text("drilling-plan"), "the refusal")
    message = form.text("drilling-plan")
    assert "Web thickness at the holes = 10 mm" in message, message
    assert "Holes per web:" in message and message.startswith("No drilling plan: Drill"), message
    assert not RAW.search(message), message


def test_the_drilling_plan_message_in_the_browser(server: str, page: Any) -> None:
    expect = pytest.importorskip("playwright.sync_api").expect
    page.goto(f"{server}/?preset=paper-inline3")
    expect(page.locator(".q-header")).to_contain_text("Results of:")
    page.get_by_role("tab", name="Single cylinder").click()
    for key, value in TOO_DEEP.items():
        field = page.locator(f"[data-testid=setting-{key}]").first
        field.fill(value)
        expect(field).to_have_value(value)
    page.get_by_role("button", name="Compute study").click()
    plan = page.locator(".q-tab-panel:visible .nicegui-markdown", has_text="No drilling plan")
    expect(plan.first).to_contain_text("deeper than the part's depth, Web thickness at the holes")
    text = plan.first.inner_text()
    assert not RAW.search(text), text
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / "single_plan_message_1280.png"), full_page=True)
