"""The Crank loads tab shows the sweep's summary (``SweepStudy.summary()``): its text, the
warning highlighted on its own, the suggested case and the Pareto set marked in the table
(whose columns are the study's ``COLUMNS``). On the inline3 preset the lowest peak bearing
load (no counterweights) leaves a larger free first-order couple than the suggested case."""

from __future__ import annotations

import pytest

pytest.importorskip("nicegui")

TYPED = {"patterns": "all; none", "balance_factors": "0, 0.5, 1", "samples": "36"}


def expected() -> dict:
    from crankbalance.studies.balance_loads import bearing_sweep
    from crankbalance.web.tab_loads import SETTINGS, parse

    sweep, loads = parse({**{k: v[1] for k, v in SETTINGS.items()}, **TYPED})
    return bearing_sweep("inline3", sweep, loads).to_dict()


@pytest.mark.anyio
async def test_loads_summary_warning_and_marks(user, form) -> None:
    from crankbalance.studies.balance_loads import COLUMNS

    data = expected()
    summary = data["summary"]
    assert summary["warning"]  # the case this test is about
    await user.open("/?preset=inline3")
    await form.until(lambda: form.element("status").text.startswith("Results of"), "the engine")
    form.open("loads")
    for key, value in TYPED.items():
        form.set(f"loads-{key}", value)
    user.find(marker="loads-run").click()
    await form.until(lambda: "Suggested:" in form.text("loads-summary"), "the sweep")
    shown = form.text("loads-summary")
    for line in summary["text"]:
        if not line.startswith("Warning: "):
            assert line in shown
    assert "Warning" not in shown  # the warning stands apart, highlighted
    warning = form.element("loads-warning")
    assert warning.visible and warning.text == f"Warning: {summary['warning']}."
    assert "bg-orange-2" in warning.classes
    table = form.element("loads-cases")
    assert [c["name"] for c in table.columns] == [key for key, _ in COLUMNS] + ["mark"]
    # every short column name is explained in the line under the table ("pattern" is a word)
    note = form.text("loads-columns")
    for _, label in COLUMNS[1:]:
        assert f"{label}: " in note or f"{label}, " in note, label
    marks = [row["mark"] for row in form.rows("loads-cases")]
    for n, mark in enumerate(marks):
        assert ("suggested" in mark) == (n == summary["suggested"]), (n, mark)
        assert ("Pareto" in mark) == (n in summary["pareto"]), (n, mark)
    # another engine: the summary, the warning and the marks go with the result
    form.set("field-rod_length", "150 mm")
    await form.until(lambda: form.rows("loads-cases") == [], "the result cleared")
    await user.should_not_see(marker="loads-warning")


def test_loads_summary_in_the_browser(server: str, browser) -> None:
    """In the browser: the summary, the highlighted warning and the marked rows."""
    playwright_api = pytest.importorskip("playwright.sync_api")
    expect = playwright_api.expect
    summary = expected()["summary"]
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(server + "/?preset=inline3")
        expect(page.locator("[data-testid=status]").first).to_contain_text("Results of:")
        page.wait_for_function("() => window.socket && window.socket.connected")
        tab = page.get_by_role("tab", name="Crank loads", exact=True)
        tab.click()
        expect(tab).to_have_attribute("aria-selected", "true")
        for key, value in TYPED.items():
            page.locator(f"[data-testid=loads-{key}]").first.fill(value)
        page.locator(".q-tab-panel:visible").get_by_role("button", name="Run", exact=True).click()
        expect(page.locator("[data-testid=loads-summary]").first).to_contain_text("Suggested:")
        warning = page.locator("[data-testid=loads-warning]").first
        expect(warning).to_be_visible()
        expect(warning).to_have_text(f"Warning: {summary['warning']}.")
        rows = page.locator("[data-testid=loads-cases]").first.locator("tbody tr")
        expect(rows.nth(summary["suggested"]).locator("td").last).to_contain_text("suggested")
        for n in summary["pareto"]:
            expect(rows.nth(n).locator("td").last).to_contain_text("Pareto")
        assert not [e for e in errors if "Resize must be passed" not in e], errors
    finally:
        page.close()
