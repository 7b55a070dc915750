"""Never a stale number (issue 28, item 2) in chromium: the busy bar stops when the server
has handled an action, also one that changes nothing on the page (a study setting edited,
the same preset chosen again); the preset menu says "edited" and loads the preset chosen
again; the Masses tab hides its resulting masses while the form is invalid; the balancing
card lists each part. Screenshots in ``artifacts/screenshots/fresh_*.png``.

Every wait is a wait for a state of the page (the hang guard of ``conftest.py``).
"""

from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

from crankbalance.web.project import Project  # noqa: E402

SHOTS = Path(__file__).resolve().parents[2] / "artifacts" / "screenshots"
#: the busy bar's state (BUSY_JS): every action sent was acknowledged and the bar is off
IDLE_AFTER = """(sent) => window.cbBusy && window.cbBusy.sent > sent
    && window.cbBusy.pending === 0 && window.cbBusy.timer === null
    && !document.body.classList.contains('cb-busy')"""


def sent(page) -> int:
    return int(page.evaluate("() => window.cbBusy ? window.cbBusy.sent : 0"))


def wait_idle(page, before: int) -> None:
    """Wait until an action sent after ``before`` was handled and the busy bar is off."""
    page.wait_for_function(IDLE_AFTER, arg=before)


def current(page) -> None:
    page.wait_for_function(
        "() => document.querySelector('[data-testid=status]')?.dataset.state === 'current'"
    )


def open_tab(page, name: str) -> None:
    page.get_by_role("tab", name=name, exact=True).click()
    expect(page.get_by_role("tab", name=name, exact=True)).to_have_attribute(
        "aria-selected", "true"
    )


def choose_preset(page, name: str) -> None:
    page.locator("[data-testid=preset]").first.click()
    page.get_by_role("option", name=name, exact=True).click()


def shot(page, name: str) -> None:
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / f"fresh_{name}.png"), full_page=True)


def test_busy_bar_stops_and_preset_menu(server: str, page) -> None:
    page.set_viewport_size({"width": 1280, "height": 800})
    page.goto(server + "/?preset=inline4")
    current(page)
    speed = Project.from_preset("inline4").texts["speed"]
    # a study setting edited: the server changes nothing on the page, the bar stops
    open_tab(page, "Counterweight design")
    seed = page.locator("[data-testid=setting-cw_seed]").first
    before = sent(page)
    seed.fill("7")
    wait_idle(page, before)
    # the same preset chosen again (not edited): nothing to load, the bar stops
    before = sent(page)
    choose_preset(page, "inline4")
    wait_idle(page, before)
    # an edit: the menu says so; the preset chosen again is loaded again
    open_tab(page, "Engine")
    page.locator("[data-testid=field-speed]").first.fill("3100 rpm")
    menu = page.locator("[data-testid=preset]").first
    expect(menu).to_contain_text("inline4 (edited)")
    shot(page, "preset_edited")
    before = sent(page)
    choose_preset(page, "inline4")
    expect(page.locator("[data-testid=field-speed]").first).to_have_value(speed)
    expect(menu).not_to_contain_text("edited")
    wait_idle(page, before)


def test_masses_and_balancing_card(server: str, page) -> None:
    page.set_viewport_size({"width": 1280, "height": 800})
    page.goto(server + "/?preset=paper-inline3")
    current(page)
    open_tab(page, "Results")
    table = page.locator("[data-testid=balance-table]").first
    expect(table).to_contain_text("Secondary shaft 2 (counter-rotating, 2×)")
    expect(table).to_contain_text("phase 150°")
    expect(page.locator("[data-testid=balance-left]").first).to_contain_text("What is left")
    page.locator("[data-testid=balance-table]").first.scroll_into_view_if_needed()
    shot(page, "balancing_card")
    open_tab(page, "Masses")
    masses = page.locator("[data-testid=mass-table]").first
    expect(masses).to_be_visible()
    page.locator("[data-testid=field-piston]").first.fill("-420 g")
    note = page.locator("[data-testid=masses-stale]").first
    expect(note).to_contain_text("Not computed: Piston")
    expect(masses).to_be_hidden()
    shot(page, "masses_invalid")
    open_tab(page, "Crank loads")
    expect(page.locator("[data-testid=loads-stale]").first).to_contain_text("Not computed")
    shot(page, "loads_invalid")


@pytest.mark.parametrize("preset", ["paper-inline3", "ducati-916"])
def test_dashboard_first_screen(server: str, page, preset: str) -> None:
    """Issue 28, item 1: at 1280x800 the first screen says what the tool does and shows the
    key results beside the inputs, above the fold; the detail card is folded for an engine
    that uses none of its fields (the inline-3) and open for one that does (the Ducati's
    rod positions)."""
    page.set_viewport_size({"width": 1280, "height": 800})
    page.goto(server + f"/?preset={preset}")
    current(page)
    expect(page.locator("[data-testid=tagline]").first).to_contain_text("counterweights")
    key = page.locator("[data-testid=key-results]").first
    expect(key).to_contain_text("Balanced for")
    expect(key).to_contain_text("Left after balancing")
    box = key.bounding_box()
    general = page.get_by_text("Engine general parameters").first.bounding_box()
    page.screenshot(path=str(SHOTS / f"fresh_dashboard_{preset}.png"))
    assert box["y"] + box["height"] <= 800, box  # above the fold
    assert box["x"] > general["x"] + general["width"], (box, general)  # beside the inputs
    details = page.locator("[data-testid=engine-details]").first
    rods = page.locator("[data-testid=field-rod_positions]").first
    if preset == "paper-inline3":
        expect(rods).to_be_hidden()
    else:
        expect(rods).to_be_visible()
    expect(details).to_be_visible()
    page.screenshot(path=str(SHOTS / f"fresh_dashboard_{preset}.png"))
    # an invalid form: the key results say so instead of showing old numbers
    page.locator("[data-testid=field-crank_radius]").first.fill("abc")
    expect(page.locator("[data-testid=key-stale]").first).to_contain_text("Not computed")
    expect(page.locator("[data-testid=key-lines]").first).to_be_hidden()
