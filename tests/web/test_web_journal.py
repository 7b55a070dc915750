"""The Counterweight design tab's optimiser keeps the web circle clear of the main journal
(issue 28), in Debian's chromium: the paper's inline-3 (crank radius 40 mm, journal
diameter 52 mm) is optimised, the summary names the bound, and no point of the drawn
profile lies inside the drawn journal (before, the web radius was searched over
10..20 mm, inside the journal's 26 mm radius).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

from .conftest import DRAWN

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect
ROOT = Path(__file__).resolve().parents[2]
SHOTS = Path(os.environ.get("CRANKBALANCE_SHOTS") or ROOT / "artifacts" / "screenshots")

#: the profile and the journal as drawn (mm): the least distance of a profile point from
#: the crank axis and the journal's radius
PROFILE_AND_JOURNAL = """() => {
    const plot = document.querySelector('[data-testid=figure-profile]');
    const js = plot && (plot.matches('.js-plotly-plot')
        ? plot : plot.querySelector('.js-plotly-plot'));
    if (!js || !js._fullData) return null;
    const named = (start) => js._fullData.filter((t) => String(t.name || '').startsWith(start));
    const points = (t) => Array.from(t.x).map((x, i) => Math.hypot(x, t.y[i]));
    const profile = named('profile').flatMap(points);
    const journal = named('main journal').flatMap(points);
    if (!profile.length || !journal.length) return null;
    return {inner: Math.min(...profile), journal: Math.max(...journal)};
}"""


def test_the_optimised_design_clears_the_journal(server: str, page: Any) -> None:
    page.goto(f"{server}/?preset=paper-inline3")
    expect(page.locator(".q-header")).to_contain_text("Results of:")
    page.get_by_role("tab", name="Counterweight design").click()
    for key, value in (("cw_iterations", "3"), ("cw_population", "256"), ("cw_seed", "7")):
        field = page.locator(f"[data-testid=setting-{key}]").first
        field.fill(value)
        expect(field).to_have_value(value)
    page.get_by_role("button", name="Optimise").click()
    summary = page.locator(".q-tab-panel:visible .nicegui-markdown", has_text="feasible designs")
    expect(summary.first).to_contain_text(
        "Web circle radius r_cw from 26.0 mm, the main journal's radius (⌀ 52.0 mm): every "
        "design clears the journal"
    )
    page.wait_for_function(DRAWN)
    drawn = page.wait_for_function(PROFILE_AND_JOURNAL).json_value()
    assert drawn["journal"] == pytest.approx(26.0, rel=1e-6)
    assert drawn["inner"] >= drawn["journal"] - 1e-6, drawn
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / "counterweight_journal_1280.png"), full_page=True)
