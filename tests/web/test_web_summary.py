"""The Results tab's summary card (what is unbalanced, by how much, what would cancel it)
read by a simulated user, and the study tabs' never-stale rule in a real browser
(Playwright driving Debian's chromium).

Every wait is a wait for a state of the page with the hang guard of ``conftest.py``.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

pytest.importorskip("nicegui")

from nicegui.testing.user import User  # noqa: E402

ARTIFACTS = Path(__file__).resolve().parents[2] / "artifacts" / "screenshots"


def shown(user: User, marker: str) -> bool:
    """Whether the element marked ``marker`` is on the page and visible (the simulated
    user finds visible elements only)."""
    try:
        return bool(user.find(marker=marker).elements)
    except AssertionError:
        return False


@pytest.mark.anyio
async def test_summary_crossplane_v8(user: User, form) -> None:
    """Crossplane V8: its free effect is the first-order rocking couple, forward, which
    crank counterweights (in opposition) cancel; no shaft is asked for it."""
    await user.open("/?preset=v8-crossplane")
    await form.see("What is unbalanced")
    card = form.text("summary")
    first = card.split("  \n")[0]
    assert re.match(r"\*\*Order 1 moment 4\d{3}(\.\d+)? N·m\*\* \(forward\)", first), first
    assert "crank counterweights in opposition" in first
    assert "shaft" not in first
    assert "Rotating masses" in card


@pytest.mark.anyio
async def test_summary_inline4(user: User, form) -> None:
    """Inline-4: its free effect is the second-order force, half forward and half backward:
    two balance shafts at twice crank speed, a counter-rotating pair."""
    await user.open("/?preset=inline4")
    await form.see("What is unbalanced")
    first = form.text("summary").split("  \n")[0]
    assert first.startswith("**Order 2 force"), first
    fwd, bwd = (float(x) for x in re.findall(r"(?:forward|backward) ([\d.]+) N", first))
    assert fwd == bwd > 1000
    assert "two balance shafts at 2× crank speed, a counter-rotating pair" in first
    assert "counterweights" not in first


@pytest.mark.anyio
async def test_summary_follows_the_engine(user: User, form) -> None:
    """The card is the computed engine's: a single cylinder's first order is forward
    (counterweights) and backward (a counter-rotating shaft at crank speed)."""
    await user.open("/?preset=single")
    await form.see("What is unbalanced")
    first = form.text("summary").split("  \n")[0]
    assert first.startswith("**Order 1 force"), first
    assert "crank counterweights for the forward part" in first
    assert "1× crank speed, counter-rotating for the backward part" in first


@pytest.mark.anyio
async def test_study_results_cleared_when_the_engine_changes(user: User, form) -> None:
    """Every study tab: a result computed for one engine is cleared, with "Not computed for
    this engine: re-run", once the form's engine is another; going back to the old engine
    does not bring it back, a new run does."""
    await user.open("/")
    form.open("counterweight")
    form.set("setting-cw_iterations", "3")
    form.set("setting-cw_population", "64")
    user.find(marker="optimise").click()
    await form.until(lambda: "feasible designs" in form.text("cw-summary"), "the optimiser")
    form.open("single")
    user.find(marker="run-single").click()
    await form.until(lambda: "Primary force" in form.text("single-summary"), "the study")
    form.open("performance")
    form.set("setting-pf_balance_factors", "0, 1")
    user.find(marker="run-performance").click()
    await form.until(lambda: len(form.rows("performance-table")) == 2, "the sweep")
    for tab in ("counterweight", "single", "performance"):
        assert not shown(user, f"{tab}-rerun")
    old = form.element("field-rod_length").value
    form.set("field-rod_length", "140 mm")
    await form.until(lambda: shown(user, "counterweight-rerun"), "the rerun note")
    for tab in ("counterweight", "single", "performance"):
        note = form.element(f"{tab}-rerun")
        assert "Not computed for this engine" in note.text, tab
        assert "re-run" in note.text
    assert form.text("cw-summary") == ""
    assert form.text("single-summary") == ""
    assert form.rows("performance-table") == []
    assert not shown(user, "figure-pareto")
    assert not shown(user, "figure-single-forces")
    form.set("field-rod_length", old)  # back to the engine the results were computed for
    await form.until(lambda: form.element("status").text.startswith("Results of"), "the engine")
    assert shown(user, "single-rerun")
    assert form.text("single-summary") == ""
    user.find(marker="run-single").click()  # a new run claims its result again
    await form.until(lambda: "Primary force" in form.text("single-summary"), "the study")
    assert not shown(user, "single-rerun")
    assert shown(user, "counterweight-rerun")


@pytest.mark.anyio
async def test_shaft_result_cleared_when_the_engine_changes(user: User, form) -> None:
    await user.open("/?preset=inline4")
    form.open("shaft")
    user.find(marker="run-shaft").click()
    await form.until(lambda: "optimum" in form.text("shaft-summary"), "the placement study")
    form.set("field-crank_radius", "41 mm")
    await form.until(lambda: shown(user, "shaft-rerun"), "the rerun note")
    assert form.text("shaft-summary") == ""
    assert not shown(user, "figure-shaft")


def test_study_result_marked_in_the_browser(server: str, page) -> None:
    """Chromium: the inline-4's balance-shaft result is cleared with "Not computed for this
    engine: re-run" when the crank radius is edited, and stays so after the edit is undone."""
    expect = pytest.importorskip("playwright.sync_api").expect
    import importlib.util

    spec = importlib.util.spec_from_file_location(  # its helpers (importlib import mode)
        "web_state_helpers", Path(__file__).with_name("test_web_state.py")
    )
    assert spec is not None and spec.loader is not None
    helpers = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(helpers)
    field, open_tab, state, wait_update = (
        helpers.field,
        helpers.open_tab,
        helpers.state,
        helpers.wait_update,
    )

    page.goto(server + "/?preset=inline4")
    wait_update(page, 0, "current")
    open_tab(page, "Results")
    expect(page.locator("[data-testid=summary]").first).to_contain_text(
        "two balance shafts at 2× crank speed, a counter-rotating pair"
    )
    open_tab(page, "Balance shaft")
    page.get_by_role("button", name="Find the optimum").click()
    summary = page.get_by_text("optimum mass position")
    expect(summary).to_be_visible()
    note = page.locator("[data-testid=shaft-rerun]").first
    expect(note).to_be_hidden()
    _, n = state(page)
    open_tab(page, "Engine")
    old = field(page, "crank_radius").input_value()
    field(page, "crank_radius").fill("41 mm")
    wait_update(page, n, "current")
    open_tab(page, "Balance shaft")
    expect(note).to_be_visible()
    expect(note).to_contain_text("Not computed for this engine")
    expect(summary).to_have_count(0)
    page.screenshot(path=str(ARTIFACTS / "shaft-rerun.png"), full_page=True)
    _, n = state(page)
    open_tab(page, "Engine")
    field(page, "crank_radius").fill(old)  # back to the engine of the result
    wait_update(page, n, "current")
    open_tab(page, "Balance shaft")
    expect(note).to_be_visible()
    expect(summary).to_have_count(0)
    open_tab(page, "Results")
    page.screenshot(path=str(ARTIFACTS / "results-summary-inline4.png"), full_page=True)
