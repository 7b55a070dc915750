"""End-to-end: ``crankbalance web`` in a subprocess, driven by Playwright in Debian's
chromium (never a downloaded browser). Load a preset, change an input, compute, download
the report and check its numbers against the API; screenshots of every tab go to
``artifacts/screenshots/``. The load test is in ``test_web_load.py``.
"""

from __future__ import annotations

import json
import math
import re
import time
from pathlib import Path

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")

ROOT = Path(__file__).resolve().parents[2]
SHOTS = ROOT / "artifacts" / "screenshots"
TABS = [
    "Engine",
    "Masses",
    "Results",
    "Counterweight design",
    "Single cylinder",
    "Balance shaft",
    "Performance",
]
#: true once every plotly figure visible in the open tab panel is drawn with its data
DRAWN = """() => [...document.querySelectorAll('.q-tab-panel .js-plotly-plot')]
    .filter((e) => e.offsetParent !== null)
    .every((e) => e.querySelector('.main-svg') && e.data && e.data.length > 0)"""


def _field(page, key: str):
    return page.locator(f"[data-testid=field-{key}]").first


def _wait_text(page, selector: str, pattern: str) -> str:
    """Wait (the page's hang guard, see conftest) until ``selector`` shows ``pattern``."""
    locator = page.locator(selector).first
    playwright_api.expect(locator).to_contain_text(re.compile(pattern), use_inner_text=True)
    return str(locator.inner_text())


def test_preset_change_compute_report(server: str, page, tmp_path: Path) -> None:
    from crankbalance.io.engine_file import load_engine
    from crankbalance.studies.engine import analyze, balance_engine

    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(server + "/?preset=v8-crossplane")
    page.get_by_text("V8 90 deg, crossplane crank").first.wait_for()
    speed = _field(page, "speed")
    assert speed.input_value() == "5500 rpm"
    _wait_text(page, ".q-header", r"Results of: V8 90 deg")  # the preset, shown
    t0 = time.perf_counter()
    speed.fill("6000 rpm")
    page.wait_for_function(  # the header's update count after the preset's first update
        "() => Number(document.querySelector('[data-testid=status]').dataset.update) >= 2"
    )
    status = _wait_text(page, ".q-header", r"Results of: V8 90 deg")  # 6000 rpm
    latency = time.perf_counter() - t0
    page.get_by_role("tab", name="Masses").click()
    page.get_by_role("button", name="Compute results").click()
    _wait_text(page, "body", r"Counterweight web 1")
    # the same engine through the API
    spec = load_engine("v8-crossplane").replace(speed=6000 * 3.141592653589793 / 30)
    api = analyze(spec).to_dict()
    study = balance_engine(spec).to_dict()
    with page.expect_download() as info:
        page.get_by_role("button", name="Report HTML").click()
    path = tmp_path / "report.html"
    info.value.save_as(path)
    text = path.read_text()
    # the numbers the report embeds (and prints) against the API's
    embedded = re.search(
        r'<script type="application/json" id="crankbalance-data">(.*?)</script>', text, re.S
    )
    assert embedded, "the report embeds its numbers as JSON"
    report = json.loads(embedded.group(1).replace("<\\/", "</"))
    assert abs(report["analysis"]["engine"]["speed_rad_s"] * 30 / math.pi - 6000) < 1e-9, (
        "the changed engine"
    )
    for got, ref in zip(report["analysis"]["free_moments"], api["free_moments"], strict=True):
        assert abs(got["amplitude_Nm"] - ref["amplitude_Nm"]) <= 1e-9 * max(1, ref["amplitude_Nm"])
    cw = study["counterweight"]["mass_kg"]
    assert abs(report["balance"]["counterweight"]["mass_kg"] - cw) <= 1e-12 * max(1, cw)
    moment1 = api["free_moments"][0]["amplitude_Nm"]
    assert f"<td>{moment1:.5g}</td>" in text, f"first-order moment {moment1:.5g} N·m printed"
    with page.expect_download() as info:
        page.get_by_role("button", name="Analysis JSON").click()
    info.value.save_as(tmp_path / "analysis.json")
    data = json.loads((tmp_path / "analysis.json").read_text())
    for got, ref in zip(data["free_moments"], api["free_moments"], strict=True):
        assert abs(got["amplitude_Nm"] - ref["amplitude_Nm"]) <= 1e-9 * max(1, ref["amplitude_Nm"])
    assert abs(data["engine"]["speed_rad_s"] * 30 / math.pi - 6000) < 1e-9
    assert not errors, errors
    print(f"input-to-update latency in the browser: {latency * 1e3:.0f} ms ({status})")


def test_screenshots_of_every_tab(server: str, page) -> None:
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.goto(server + "/")
    page.get_by_text("Inline-3, Table 1").first.wait_for()
    _field(page, "rod_length").fill("30 mm")  # a bad value: message beside the field
    # beside the field, once Quasar's hint-to-message transition is over
    playwright_api.expect(page.locator(".q-field--error .q-field__bottom").first).to_contain_text(
        "Rod length = 30 mm: must exceed crank radius"
    )
    page.screenshot(path=str(SHOTS / "engine_bad_input.png"))
    _field(page, "rod_length").fill("135 mm")
    _wait_text(page, ".q-header", r"Results of:")
    # button of the tab's study and a text that only its result shows
    actions = {
        "Counterweight design": ("Optimise", r"feasible designs"),
        "Single cylinder": ("Compute study", r"Least peak at"),
        # the paper's inline-3 has free moments only: the tab says the study does not apply
        "Balance shaft": ("Find the optimum", r"does not apply"),
        "Performance": ("Run the sweep", r"Peak shaking N[\s\S]*\b0\.75\b"),
    }
    for k, tab in enumerate(TABS):
        page.get_by_role("tab", name=tab).click()
        playwright_api.expect(page.get_by_role("tab", name=tab)).to_have_attribute(
            "aria-selected", "true"
        )
        if tab in actions:
            button, done = actions[tab]
            page.get_by_role("button", name=button).click()
            _wait_text(page, ".q-tab-panel:visible", done)
        # every figure shown in the tab has been drawn with its data
        page.wait_for_function(DRAWN)
        # the header is fixed: scrolled (after clicking a button low on the page) it would
        # be drawn across the middle of a full-page screenshot
        page.evaluate("window.scrollTo(0, 0)")
        page.wait_for_function("() => window.scrollY === 0")
        page.screenshot(
            path=str(SHOTS / f"{k + 1}_{tab.lower().replace(' ', '_')}.png"), full_page=True
        )
    assert len(list(SHOTS.glob("*.png"))) >= len(TABS)
