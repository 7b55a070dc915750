"""The Mounts tab (issue 31 item 6; docs/web.md "Mounts"): an engine without a [powertrain]
table is told so and offered the worked examples; the inline-4 car example's run shows the
numbers of ``crankbalance mounts --format json`` (the modes, the torque-roll axis and the
roll mode's angle, the largest mount force per order) and draws the layout, the mode shapes
and the forces over speed; a bad setting is named beside its field and clears the result;
an engine form that cannot be computed clears it too and the tab says why.

The browser test (Playwright driving Debian's chromium) takes screenshots at 1280x800 and
390x844 into ``artifacts/screenshots/`` (ignored by git). Every wait is a wait for a state
of the page with the hang guard of ``conftest.py``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from crankbalance.output.format import number

pytest.importorskip("nicegui")

ROOT = Path(__file__).resolve().parents[2]
SHOTS = Path(os.environ.get("CB_MOUNTS_SHOTS", ROOT / "artifacts" / "screenshots"))
CAR = ROOT / "examples" / "mounts_inline4_car.toml"
#: the tab's settings as typed in the tests (the rest at the schema's defaults)
TYPED = {"speed_samples": "120", "orders": "4"}


def cli_json(*options: str) -> dict[str, Any]:
    """``crankbalance mounts --format json`` of the car example, as the command line gives it."""
    out = subprocess.run(
        [sys.executable, "-m", "crankbalance", "mounts", str(CAR), "--format", "json", *options],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, "PYTHONPATH": str(ROOT / "src")},
    )
    data = json.loads(out.stdout)
    assert isinstance(data, dict)
    return data


def cli_cells() -> tuple[list[list[str]], list[list[str]], str]:
    """The modes table's and the orders table's cells and the roll mode's angle, from the
    command line's JSON with the tests' settings."""
    data = cli_json("--speed-samples", TYPED["speed_samples"], "--orders", TYPED["orders"])
    modes = [
        [str(m["mode"]), number(m["frequency_Hz"], 5)]
        + [number(m["energy_percent"][k], 3) for k in ("x", "y", "z", "roll", "pitch", "yaw")]
        for m in data["modes"]
    ]
    orders = [
        [str(o["order"]), o["largest"]["mount"], number(o["largest"]["force_N"], 5)]
        for o in data["orders"]
    ]
    return modes, orders, number(data["roll_mode_angle_to_torque_roll_axis_deg"], 3)


def test_parse_names_the_field() -> None:
    """The tab's settings are checked by the registry's study and refused on their field."""
    from crankbalance.errors import InputError
    from crankbalance.web.tab_mounts import SETTINGS, parse

    defaults = {k: v[1] for k, v in SETTINGS.items()}
    cases = {
        "speed_min": {"speed_min": "600 kg"},
        "speed_max": {"speed_max": "300 rpm"},  # below the lowest speed
        "speed_samples": {"speed_samples": "1"},
        "orders": {"orders": "0"},
        "rotating": {"rotating": "maybe"},
        "point": {"point": "1 mm, 2 mm"},
    }
    for field, texts in cases.items():
        with pytest.raises(InputError) as error:
            parse({**defaults, **texts})
        assert error.value.field == field, (field, error.value)
    assert parse({**defaults, "point": "0 mm, 0 mm, 100 mm"})[0]["point"] == [
        "0 mm",
        "0 mm",
        "100 mm",
    ]


def test_tables_are_the_studys_json() -> None:
    """The tab's tables and summary read the study's JSON (the command line's)."""
    from crankbalance.web.tab_mounts import mode_rows, mounts_study, order_rows, summary_text

    data = mounts_study(str(CAR), dict(TYPED)).to_dict()
    modes, orders, angle = cli_cells()
    assert [list(row.values()) for row in mode_rows(data)] == modes
    assert [list(row.values())[:3] for row in order_rows(data)] == orders
    assert f"**{angle} deg**" in summary_text(data)


def test_mode_shapes_animate_in_the_web_and_stay_static_for_reports() -> None:
    """The web's mode shapes move (issue 28, item 4): one frame per phase of a cycle, frame
    0 the static drawing, half a cycle the mirror image through the layout at rest; a phase
    slider, the page's Play runs them; the static figure (reports, ``--plot``) has no
    frames."""
    import numpy as np

    from crankbalance.output.figures.mounts import (
        MODE_CYCLES,
        MODE_FRAMES,
        mode_play_script,
        mode_shapes_figure,
    )
    from crankbalance.web.tab_mounts import mounts_study

    result = mounts_study(str(CAR), dict(TYPED))
    static = mode_shapes_figure(result)
    assert not static.frames and not static.layout.sliders
    moving = mode_shapes_figure(result, animate=True)
    assert len(moving.frames) == MODE_FRAMES == len(moving.layout.sliders[0].steps)
    assert len(moving.layout.updatemenus) == 1  # the mode menu; Play is the page's
    assert f"Array({MODE_CYCLES})" in mode_play_script(7, True)
    assert "[null]" in mode_play_script(7, False)

    def coords(trace) -> np.ndarray:
        return np.array([v for v in trace.x if v is not None], dtype=float)

    rest = coords(static.data[0])
    half = moving.frames[MODE_FRAMES // 2]
    for k in range(1, 13):  # two traces per mode, six modes
        assert coords(moving.frames[0].data[k - 1]) == pytest.approx(coords(static.data[k]))
    shown = coords(static.data[1])
    assert coords(half.data[0]) == pytest.approx(2 * rest - shown)
    assert list(moving.frames[0].traces) == list(range(1, 13))


@pytest.mark.anyio
async def test_mounts_tab_needs_a_powertrain_then_runs(user, form) -> None:
    """The default preset has no [powertrain]: the tab says so; the example's button loads
    the car; a run shows the study; a bad setting and an engine form that cannot be computed
    each clear the result, and the tab says why. (Simulated user, before the browser tests:
    sync Playwright's loop would be running.)"""
    await user.open("/")
    await form.until(lambda: form.element("status").text.startswith("Results of"), "the engine")
    form.open("mounts")  # built when first opened
    await form.until(lambda: form.element("mounts-needs").visible, "the powertrain note")
    assert "[powertrain]" in form.text("mounts-needs")
    user.find(marker="mounts-example-mounts_inline4_car").click()
    await form.until(
        lambda: (
            form.element("status").text == "Results of: Inline-4 transverse in a car, three mounts"
        ),
        "the car example",
    )
    await user.should_not_see(marker="mounts-needs")
    for key, value in TYPED.items():
        form.set(f"mounts-{key}", value)
    user.find(marker="mounts-run").click()
    await form.until(lambda: "Torque-roll axis" in form.text("mounts-summary"), "the study")
    modes, orders, angle = cli_cells()
    assert [list(row.values()) for row in form.rows("mounts-modes-table")] == modes
    assert [list(row.values())[:3] for row in form.rows("mounts-orders-table")] == orders
    assert f"{angle} deg" in form.text("mounts-summary")
    # a bad setting: named beside its field, the result gone
    form.set("mounts-speed_samples", "1")
    await form.until(lambda: form.rows("mounts-modes-table") == [], "the result cleared")
    assert "Speeds of the sweep" in str(form.error("mounts-speed_samples"))
    assert "these settings" in form.element("mounts-rerun").text
    user.find(marker="mounts-run").click()
    await form.until(lambda: "Not run" in form.text("mounts-summary"), "the refusal")
    # more work than the study's budget: refused before it starts, beside the field
    form.set("mounts-speed_samples", "10001")
    form.set("mounts-orders", "8")
    user.find(marker="mounts-run").click()
    await form.until(lambda: "at most 50000" in form.text("mounts-summary"), "the budget")
    assert "at most 50000" in str(form.error("mounts-speed_samples"))
    form.set("mounts-speed_samples", TYPED["speed_samples"])
    form.set("mounts-orders", TYPED["orders"])
    user.find(marker="mounts-run").click()
    await form.until(lambda: len(form.rows("mounts-modes-table")) == 6, "the study again")
    # an engine form that cannot be computed: no number left, the tab says why
    form.set("field-rod_length", "x")
    await form.until(lambda: form.rows("mounts-modes-table") == [], "the result cleared")
    assert form.element("mounts-rerun").text.startswith("Not computed: ")
    assert form.text("mounts-summary") == ""
    form.set("field-rod_length", "145 mm")
    await form.until(lambda: "re-run" in form.element("mounts-rerun").text, "the form valid")


playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect


#: (browser) the plot drawn at its box's width (after a resize: the page's phone relayouts
#: come first, FIGURE_JS)
REDRAWN = """(el) => new Promise((done) => {
    const drawn = () => el._fullLayout
        && Math.abs(el._fullLayout.width - el.getBoundingClientRect().width) < 1;
    if (drawn()) return done();
    el.on('plotly_afterplot', () => drawn() && done());
})"""
#: (browser) the mode shapes' legend below the phase slider, the slider and the mode menu
#: inside the figure
APART = """(el) => {
    const box = (s) => el.querySelector(s).getBoundingClientRect();
    const figure = el.getBoundingClientRect();
    const legend = box('.legend'), slider = box('.slider-container');
    const menu = box('.updatemenu-container');
    return legend.top >= slider.bottom - 1 && slider.left >= figure.left
        && slider.right <= figure.right && menu.right <= figure.right;
}"""


@pytest.mark.parametrize(("width", "height"), [(1280, 800), (390, 844)])
def test_mounts_tab_in_the_browser(server: str, browser, width: int, height: int) -> None:
    """The car example loaded from the tab, run, its tables equal to the command line's
    JSON, its three figures drawn; screenshots of the tab."""
    modes, orders, angle = cli_cells()
    page = browser.new_page(viewport={"width": width, "height": height})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(server + "/")
        expect(page.locator("[data-testid=status]").first).to_contain_text("Results of:")
        page.wait_for_function("() => window.socket && window.socket.connected")
        tab = page.get_by_role("tab", name="Mounts", exact=True)
        tab.click()
        expect(tab).to_have_attribute("aria-selected", "true")
        expect(page.locator("[data-testid=mounts-needs]").first).to_be_visible()
        page.get_by_role("button", name="Inline-4 car, three mounts").click()
        expect(page.locator("[data-testid=status]").first).to_contain_text("Inline-4 transverse")
        for key, value in TYPED.items():
            page.locator(f"[data-testid=mounts-{key}]").first.fill(value)
        play = page.locator("[data-testid=mounts-modes-play]").first
        expect(play).to_be_hidden()  # nothing to play before a run
        page.locator(".q-tab-panel:visible").get_by_role("button", name="Run", exact=True).click()
        summary = page.locator("[data-testid=mounts-summary]").first
        expect(summary).to_contain_text(f"{angle} deg")
        table = page.locator("[data-testid=mounts-modes-table]").first
        expect(table.locator("tbody tr")).to_have_count(6)
        for n, row in enumerate(modes):
            cells = table.locator("tbody tr").nth(n).locator("td")
            for k, cell in enumerate(row):
                expect(cells.nth(k)).to_have_text(cell)
        table = page.locator("[data-testid=mounts-orders-table]").first
        for n, row in enumerate(orders):
            cells = table.locator("tbody tr").nth(n).locator("td")
            for k, cell in enumerate(row):
                expect(cells.nth(k)).to_have_text(cell)
        for name in ("mounts-layout", "mounts-modes", "mounts-forces"):
            figure = page.locator(f"[data-testid=figure-{name}]").first
            expect(figure.locator(".main-svg").first).to_be_attached()
        page.wait_for_function(
            """() => [...document.querySelectorAll('.q-tab-panel .js-plotly-plot')]
                .filter((e) => e.offsetParent !== null)
                .every((e) => e.querySelector('.main-svg') && e.data && e.data.length > 0)"""
        )
        # the chosen mode moves (issue 28, item 4): Play changes its drawn coordinates
        modes_plot = page.locator("[data-testid=figure-mounts-modes]").first
        first = modes_plot.evaluate(
            "el => JSON.stringify(el.data.find((t, i) => i > 0 && t.visible === true).x)"
        )
        expect(modes_plot.locator(".slider-container")).to_have_count(1)
        play.click()
        modes_plot.evaluate(
            """(el, first) => new Promise((done) => {
                const moved = () =>
                    JSON.stringify(el.data.find((t, i) => i > 0 && t.visible === true).x)
                    !== first;
                if (moved()) return done();
                el.on('plotly_animated', () => moved() && done());
                el.on('plotly_animatingframe', () => moved() && done());
            })""",
            first,
        )
        page.locator("[data-testid=mounts-modes-pause]").first.click()
        # the legend below the phase slider's ticks, the slider and the mode menu inside the
        # figure (review findings 13 and 23; on a phone the page's relayouts of on_a_phone),
        # at this width, after a change to the other width and back
        other = {"width": 390, "height": 844} if width > 600 else {"width": 1280, "height": 800}
        for size in (None, other, {"width": width, "height": height}):
            if size is not None:
                page.set_viewport_size(size)
            modes_plot.evaluate(REDRAWN)
            assert modes_plot.evaluate(APART), size
        SHOTS.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(SHOTS / f"mounts_{width}x{height}.png"), full_page=True)
        # a bad setting: beside its field in the field's words; the result is gone
        page.locator("[data-testid=mounts-speed_samples]").first.fill("1")
        message = page.locator(".q-field--error", has_text="Speeds of the sweep").first
        expect(message).to_contain_text("from 2")
        expect(page.locator("[data-testid=mounts-rerun]").first).to_be_visible()
        expect(
            page.locator("[data-testid=mounts-modes-table]").first.locator("tbody tr")
        ).to_have_count(0)
        expect(play).to_be_hidden()  # cleared with the result
        assert not [e for e in errors if "Resize must be passed" not in e], errors
    finally:
        page.close()
