"""The Crank loads tab in a real browser (Playwright driving Debian's chromium): the inline4
preset, eight and four counterweights and none at two balance factors, a run; the table's
rows are those :func:`crankbalance.studies.balance_loads.bearing_sweep` computes for the
same settings; both figures are drawn; a bad pattern is named beside its field and clears
the result; another engine clears it too; the sweep figure's peak loads are grouped per
balance factor, one bar per bearing (issue 28, item 4).

Screenshots at 1280x800 and 390x844 go to ``artifacts/screenshots/`` (ignored by git).
Every wait is a wait for a state of the page with the hang guard of ``conftest.py``.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from crankbalance.output.format import number
from crankbalance.studies.balance_loads import bearing_sweep, case_rows

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

ROOT = Path(__file__).resolve().parents[2]
SHOTS = ROOT / "artifacts" / "screenshots"  # ignored by git
#: the tab's settings as typed (the rest at the tab's defaults)
TYPED = {
    "patterns": "all; 1,0,0,1,1,0,0,1; none",
    "balance_factors": "0, 0.5",
    "samples": "72",
}


def expected() -> list[list[str]]:
    """The table's cells from the study itself, with the tab's defaults."""
    from crankbalance.web.tab_loads import SETTINGS, parse

    sweep, loads = parse({**{k: v[1] for k, v in SETTINGS.items()}, **TYPED})
    data = bearing_sweep("inline4", sweep, loads).to_dict()
    return [
        ["–" if v is None else (v if isinstance(v, (str, int)) else number(v, 5)) for v in row]
        for row in case_rows(data)
    ]


def open_tab(page, name: str) -> None:
    page.get_by_role("tab", name=name, exact=True).click()
    expect(page.get_by_role("tab", name=name, exact=True)).to_have_attribute(
        "aria-selected", "true"
    )


@pytest.mark.anyio
async def test_loads_result_cleared_when_the_engine_changes(user, form) -> None:
    """The result belongs to the engine it was run for: another rod length clears it; so
    does an edit of the tab's own settings. (Simulated user, before the browser tests:
    sync Playwright's loop would be running.)"""
    await user.open("/?preset=inline4")
    await form.until(lambda: form.element("status").text.startswith("Results of"), "the engine")
    form.open("loads")  # built when first opened
    for key, value in TYPED.items():
        form.set(f"loads-{key}", value)
    user.find(marker="loads-run").click()
    await form.until(lambda: "Lowest peak" in form.text("loads-summary"), "the sweep")
    assert len(form.rows("loads-cases")) == 5  # two patterns at two factors, none once
    # what was assumed: the engine's crank + flywheel inertia, as every study takes it
    from crankbalance.studies.crank import rotating_inertia
    from crankbalance.studies.engine import as_model

    inertia = rotating_inertia(as_model("inline4"))
    assert f"Assumed: crank + flywheel {inertia:.4g}" in form.text("loads-summary")
    form.set("field-rod_length", "150 mm")
    await form.until(lambda: form.rows("loads-cases") == [], "the result cleared")
    assert "Not computed for this engine" in form.element("loads-rerun").text
    user.find(marker="loads-run").click()
    await form.until(lambda: len(form.rows("loads-cases")) == 5, "the sweep again")
    form.set("loads-balance_factors", "0.5")
    await form.until(lambda: form.rows("loads-cases") == [], "the result cleared")
    assert "these settings" in form.element("loads-rerun").text


def test_parse_names_the_field() -> None:
    """The tab's settings are refused on the field that holds the mistake."""
    from crankbalance.errors import InputError
    from crankbalance.web.tab_loads import SETTINGS, parse

    defaults = {k: v[1] for k, v in SETTINGS.items()}
    cases = {
        "patterns": {"patterns": "all; 2,0"},
        "balance_factors": {"balance_factors": "0.5, x"},
        "samples": {"samples": "10"},
        "gas": {"gas": "maybe"},
        "bearing_stiffness": {"bearing_stiffness": "5e8 kg"},
    }
    for field, texts in cases.items():
        with pytest.raises(InputError) as error:
            parse({**defaults, **texts})
        assert error.value.field == field, (field, error.value)


@pytest.mark.parametrize(("width", "height"), [(1280, 800), (390, 844)])
def test_loads_table_and_figures(server: str, browser, width: int, height: int) -> None:
    rows = expected()
    page = browser.new_page(viewport={"width": width, "height": height})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(server + "/?preset=inline4")
        expect(page.locator("[data-testid=status]").first).to_contain_text("Results of:")
        page.wait_for_function("() => window.socket && window.socket.connected")
        open_tab(page, "Crank loads")
        for key, value in TYPED.items():
            page.locator(f"[data-testid=loads-{key}]").first.fill(value)
        page.locator(".q-tab-panel:visible").get_by_role("button", name="Run", exact=True).click()
        expect(page.locator("[data-testid=loads-summary]").first).to_contain_text("Lowest peak")
        table = page.locator("[data-testid=loads-cases]").first
        expect(table.locator("tbody tr")).to_have_count(len(rows))
        for n, row in enumerate(rows):
            cells = table.locator("tbody tr").nth(n).locator("td")
            expect(cells.nth(0)).to_have_text(row[0])
            expect(cells.nth(4)).to_have_text(row[4])  # the largest bearing load
            expect(cells.nth(8)).to_have_text(row[8])  # the friction power
        for name in ("loads-polar", "loads-sweep"):
            figure = page.locator(f"[data-testid=figure-{name}]").first
            expect(figure.locator(".main-svg").first).to_be_attached()
        # the peak loads grouped per balance factor (issue 28, item 4): the factor on the
        # axis under its pattern, one bar per bearing named in the legend, axes in words
        sweep = page.locator("[data-testid=figure-loads-sweep]").first
        expect(sweep.locator(".legendtext", has_text="bearing 5")).to_have_count(1)
        bars = sweep.evaluate(
            "el => el.data.filter(t => t.type === 'bar').map(t => [t.name, t.x[1]])"
        )
        assert [b[0] for b in bars] == [f"bearing {k}" for k in range(1, 6)]
        assert bars[0][1] == ["f_b 0", "f_b 0.5", "f_b 0", "f_b 0.5", "no counterweights"]
        titles = sweep.evaluate(
            "el => Array.from(el.querySelectorAll('.g-xtitle text, .g-ytitle text, "
            "[class*=title] text')).map(t => t.textContent)"
        )
        assert any("balance factor f_b [-]" in t for t in titles), titles
        assert "peak bearing load [N]" in titles, titles
        SHOTS.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(SHOTS / f"loads-{width}x{height}.png"), full_page=True)
        # a bad pattern: named beside its field in the field's words; the result is gone
        page.locator("[data-testid=loads-patterns]").first.fill("all; 2,0")
        message = page.locator(".q-field--error", has_text="Counterweight patterns").first
        expect(message).to_contain_text("0/1 per web")
        expect(page.locator("[data-testid=loads-rerun]").first).to_be_visible()
        expect(table.locator("tbody tr")).to_have_count(0)
        assert not errors, errors
    finally:
        page.close()
