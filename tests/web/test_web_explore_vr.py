"""The Explorer tab's candidate loaded as the current engine keeps its bank angle for a VR
layout (two rows a narrow angle apart) as it does for a vee and a W: without it the engine
file of a VR candidate would be refused (``crank_train.bank_angle`` is required for vr)."""

from __future__ import annotations

import math

import pytest

pytest.importorskip("nicegui")


@pytest.mark.parametrize(
    ("layout", "degrees", "throws"),
    [("vr", 15.0, (0, 240, 120, 120, 240, 0)), ("vee", 60.0, (0, 120, 240))],
)
def test_a_banked_candidate_keeps_its_bank_angle(
    layout: str, degrees: float, throws: tuple[int, ...]
) -> None:
    from crankbalance.io.engine_file import preset_text
    from crankbalance.physics.explore import orders
    from crankbalance.schema.engine import EngineSpec
    from crankbalance.web.project import Project
    from crankbalance.web.tab_explore import candidate_file

    spec = Project.from_text(preset_text("inline6"), "preset inline6").spec
    assert spec is not None
    problem = orders.problem(layout, 6, 4, math.radians(degrees))
    row = {
        "firing_order": [1, 5, 3, 6, 2, 4],
        "throw_angle_rad": [math.radians(a) for a in throws],
    }
    out = candidate_file(spec.to_data(), problem, math.radians(degrees), row)
    assert out["crank_train"]["layout"] == layout
    assert out["crank_train"]["bank_angle"] == f"{degrees:.9g} deg"
    loaded = EngineSpec.parse(out, source="candidate")
    assert loaded.crank_train.bank_angle == pytest.approx(math.radians(degrees))


def test_a_vr_row_loads_with_its_bank_angle(server: str, browser) -> None:
    """In the browser: explore the VR-4 at 15 deg, click a row; the engine loaded is a VR
    with the bank angle explored (computed: the header names it)."""
    playwright_api = pytest.importorskip("playwright.sync_api")
    expect = playwright_api.expect
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(server + "/?preset=inline4")  # the explorer starts from its 4 cylinders
        status = page.locator("[data-testid=status]").first
        expect(status).to_contain_text("Results of:")
        page.wait_for_function("() => window.socket && window.socket.connected")
        tab = page.get_by_role("tab", name="Explorer", exact=True)
        tab.click()
        expect(tab).to_have_attribute("aria-selected", "true")
        page.locator("[data-testid=explore-layout]").first.click()
        page.get_by_role("option", name="vr", exact=True).click()
        expect(page.locator("[data-testid=explore-layout]").first).to_contain_text("vr")
        page.locator("[data-testid=explore-bank_angle]").first.fill("15 deg")
        page.get_by_role("button", name="Explore").click()
        summary = page.locator("[data-testid=explore-summary]").first
        expect(summary).to_contain_text("distinct engines")
        table = page.locator("[data-testid=explore-table]").first
        table.locator("tbody tr").first.click()
        expect(status).to_contain_text("Results of: Explorer vr-4")
        engine = page.get_by_role("tab", name="Engine", exact=True)
        engine.click()
        expect(engine).to_have_attribute("aria-selected", "true")
        expect(page.locator("[data-testid=field-layout]").first).to_contain_text("vr")
        expect(page.locator("[data-testid=field-bank_angle]").first).to_have_value("15 deg")
        assert not [e for e in errors if "Resize must be passed" not in e], errors
    finally:
        page.close()
