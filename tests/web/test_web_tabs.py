"""Browser tests of the study tabs (Single cylinder, Counterweight design, Balance shaft):
``crankbalance web`` in a subprocess driven by Playwright in Debian's chromium. Every wait
is for a state of the page with the hang guard of ``conftest.py``; the numbers on screen
are checked against the library's own results for the same engine and settings.
"""

from __future__ import annotations

import math
import os
import re
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")

#: screenshots for a person to look at (not committed): CRANKBALANCE_SHOTS=folder
from .conftest import DRAWN  # noqa: E402

SHOTS = os.environ.get("CRANKBALANCE_SHOTS")


def _open(page: Any, server: str, preset: str, tab: str) -> list[str]:
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(f"{server}/?preset={preset}")
    playwright_api.expect(page.locator(".q-header")).to_contain_text("Results of:")
    page.get_by_role("tab", name=tab).click()
    playwright_api.expect(page.get_by_role("tab", name=tab)).to_have_attribute(
        "aria-selected", "true"
    )
    return errors


def _setting(page: Any, key: str) -> Any:
    return page.locator(f"[data-testid=setting-{key}]").first


def _text(page: Any, marker_text: str, pattern: str) -> str:
    """Wait until the element of the tab that shows ``marker_text`` matches ``pattern``."""
    locator = page.locator(".q-tab-panel:visible .nicegui-markdown", has_text=marker_text).first
    playwright_api.expect(locator).to_contain_text(re.compile(pattern), use_inner_text=True)
    return str(locator.inner_text())


def _shoot(page: Any, name: str) -> None:
    if not SHOTS:
        return
    Path(SHOTS).mkdir(parents=True, exist_ok=True)
    page.wait_for_function(DRAWN)
    for width, height in ((1280, 800), (390, 844)):
        page.set_viewport_size({"width": width, "height": height})
        page.wait_for_function(DRAWN)  # redrawn for the new width
        page.evaluate("window.scrollTo(0, 0)")
        page.screenshot(path=f"{SHOTS}/{name}-{width}.png", full_page=True)
    page.set_viewport_size({"width": 1500, "height": 1000})


def _single_reference(new_reciprocating: str) -> tuple[Any, Any]:
    """The library's rebalancing and ISO check of the single preset's cylinder 1."""
    from crankbalance.io.engine_file import load_engine
    from crankbalance.schema.settings import RebalanceOptions, SingleCylinderOptions
    from crankbalance.studies.build import build_model
    from crankbalance.studies.cylinder import iso_check, rebalance_cylinder

    model = build_model(load_engine("single"))
    single = SingleCylinderOptions()
    new = RebalanceOptions.parse({"new_reciprocating": new_reciprocating})
    reb = rebalance_cylinder(model, single, new)
    return reb, iso_check(model, single)


def test_single_cylinder_drilling_plan(server: str, page: Any) -> None:
    """New lighter reciprocating parts: the plan on screen (count, diameter, depth, radius,
    angle, mass per web, passes) and its drawing equal the library's rebalancing; the
    rotor mass left empty is named as a stand-in beside the ISO result."""
    errors = _open(page, server, "single", "Single cylinder")
    _setting(page, "rb_new_reciprocating").fill("359 g")
    page.get_by_role("button", name="Compute study").click()
    plan = _text(page, "Holes:", r"Passes:")
    reb, iso = _single_reference("359 g")
    holes, last = reb.correction, reb.iterations[-1]
    assert last.depth > 0 and reb.passed, "the case needs holes and converges"
    assert f"{holes.number} per web on {holes.webs} webs" in plan
    assert f"Drill diameter: {holes.diameter * 1e3:.4g} mm" in plan
    assert f"Depth: {last.depth * 1e3:.3f} mm" in plan
    assert f"{holes.radius * 1e3:.4g} mm from the crank axis" in plan
    assert "180° from the crankpin" in plan
    assert f"Mass removed per web: {last.removed_mass / holes.webs * 1e3:.2f} g" in plan
    assert f"Passes: {len(reb.iterations)} (converged)" in plan
    assert "PASS" in plan
    rows = page.locator(".q-tab-panel:visible .q-table tbody tr")
    playwright_api.expect(rows).to_have_count(len(reb.iterations))
    assert f"{last.depth * 1e3:.3f}" in rows.last.inner_text()
    # the drawing: its hole at the plan's radius, straight below the crank axis
    page.wait_for_function(DRAWN)
    hole = page.evaluate(
        """() => [...document.querySelectorAll('.js-plotly-plot')]
        .flatMap((e) => e._fullData || []).filter((t) => (t.name || '').startsWith('hole'))
        .map((t) => ({x: Array.from(t.x), y: Array.from(t.y)}))[0]"""
    )
    assert hole is not None, "the drawing shows the hole"
    cx = (max(hole["x"]) + min(hole["x"])) / 2
    cy = (max(hole["y"]) + min(hole["y"])) / 2
    assert abs(cx) < 1e-6 and abs(cy + holes.radius * 1e3) < 1e-6
    assert abs((max(hole["x"]) - min(hole["x"])) - holes.diameter * 1e3) < 1e-6
    # the ISO rotor mass: left empty, its stand-in is named beside the result
    note = _text(page, "Rotor mass", r"stand in")
    assert f"({iso.rotor_mass:.3f} kg)" in note
    _shoot(page, "single-drilling")
    _setting(page, "sc_rotor_mass").fill("2.7 kg")
    page.get_by_role("button", name="Compute study").click()
    _text(page, "Rotor mass", r"2\.700 kg, as given")
    assert not errors, errors


def test_single_cylinder_no_holes_and_worded_error(server: str, page: Any) -> None:
    """Unchanged parts need no hole (said so); a balance factor the holes cannot reach is
    shown in the words of the form, never by an internal key."""
    errors = _open(page, server, "single", "Single cylinder")
    page.get_by_role("button", name="Compute study").click()
    _text(page, "Holes:", r"none: the unbalance to remove is within the tolerance")
    _setting(page, "rb_new_reciprocating").fill("450 g")  # heavier: holes cannot do it
    page.get_by_role("button", name="Compute study").click()
    plan = _text(page, "No drilling plan", r"Balance factor: .*removing material")
    for internal in ("target_balance_factor", "sc_", "rb_", "crank_train."):
        assert internal not in plan
    assert not errors, errors


def test_drilling_drawing_radial_holes_reach_the_depth() -> None:
    """Radial holes are drawn as the slot the drill leaves, from the rim inward by the
    plan's depth; a rebalancing without holes draws none."""
    from dataclasses import replace

    from crankbalance.output.figures.single import drilling_plan
    from crankbalance.physics.rebalancing import DrilledHoles, rebalance

    holes = DrilledHoles(diameter=0.006, radius=0.05, number=2, direction="radial")
    reb = rebalance(0.8, 0.4, 0.8, 0.39, 1.2, 0.031, 0.031, holes, 1e-9)
    depth = reb.iterations[-1].depth * 1e3
    assert depth > 0
    fig = drilling_plan(reb, 0.031)
    drawn = [t for t in fig.data if (t.name or "").startswith("hole") or t.legendgroup == "holes"]
    assert len(drawn) == holes.number
    for trace in drawn:
        reach = [float((x * x + y * y) ** 0.5) for x, y in zip(trace.x, trace.y, strict=True)]
        # corners of the slot: half the diameter (3 mm) beside the hole's axis
        assert min(reach) == pytest.approx(math.hypot(50 - depth, 3), rel=1e-9)
        assert max(reach) == pytest.approx(math.hypot(50, 3), rel=1e-9)
    none = drilling_plan(replace(reb, iterations=[]), 0.031)
    assert not [t for t in none.data if t.legendgroup == "holes"]
    assert "no hole needed" in none.layout.title.text


@pytest.mark.parametrize(
    ("preset", "says"),
    [
        ("v10-72", r"does not apply to this engine[\s\S]*second-order effect is a moment"),
        ("inline6", r"needs no balance shaft"),
        ("radial5", r"does not apply to this engine[\s\S]*counterweights cancel it"),
    ],
)
def test_balance_shaft_says_when_it_does_not_apply(
    server: str, page: Any, preset: str, says: str
) -> None:
    """No silent fallback: an engine whose shaft would carry a moment, one without free
    first- or second-order effects and one whose counterweights cancel its free force are
    told so, and no placement result or figure is shown."""
    errors = _open(page, server, preset, "Balance shaft")
    page.get_by_role("button", name="Find the optimum").click()
    panel = page.locator(".q-tab-panel:visible").first
    playwright_api.expect(panel).to_contain_text(re.compile(says), use_inner_text=True)
    assert "optimum mass position" not in panel.inner_text()
    playwright_api.expect(panel.locator(".js-plotly-plot:visible")).to_have_count(0)
    if preset == "v10-72":
        _shoot(page, "shaft-v10")
    assert not errors, errors


def test_balance_shaft_inline4_secondary_force(server: str, page: Any) -> None:
    """The inline-4's free second-order force: the study applies and finds the 67 % of Kim
    (2018), Fig. 7, with w = 2."""
    errors = _open(page, server, "inline4", "Balance shaft")
    _text(page, "For this engine", r"free second-order force of \d")
    page.get_by_role("button", name="Find the optimum").click()
    _text(page, "optimum mass position", r"66\.7 %")
    _shoot(page, "shaft-inline4")
    assert not errors, errors


def _outer_radii(summary: str) -> list[float]:
    return [float(x) for x in re.findall(r"outer radius ([\d.]+) mm, balance", summary)]


def test_counterweight_radial_space_from_the_engine(server: str, page: Any) -> None:
    """Largest radial space left empty: the optimiser keeps within the engine's space
    (rod length - crank radius, 155 - 47 = 108 mm for the crossplane V8); a larger limit
    typed in lets bigger designs through, each warned about."""
    errors = _open(page, server, "v8-crossplane", "Counterweight design")
    _text(page, "Largest radial space", r"the engine's 108\.0 mm")
    page.get_by_role("button", name="Optimise").click()
    summary = _text(page, "feasible designs", r"Least radius:.*outer radius")
    radii = _outer_radii(summary)
    assert len(radii) == 2 and max(radii) <= 108.0 + 0.05, summary
    assert "Warning" not in summary
    _setting(page, "cw_max_radius").fill("300 mm")
    page.get_by_role("button", name="Optimise").click()
    # the new result (the old one had no warning): without the engine's limit the
    # least-mass design is larger than the space
    summary = _text(page, "feasible designs", r"larger than the space")
    radii = _outer_radii(summary)
    assert max(radii) > 108.0
    for radius in radii:
        assert (f"outer radius {radius:.1f} mm is larger than the space" in summary) == (
            radius > 108.0
        )
    _shoot(page, "counterweight-space")
    assert not errors, errors


def _rerun(page: Any, tab: str) -> Any:
    return page.locator(f"[data-testid={tab}-rerun]").first


def test_study_result_belongs_to_its_settings(server: str, page: Any) -> None:
    """A study's result belongs to (engine, that study's settings): editing one of its
    settings after a run clears it and says so; typing the old value back does not bring
    it back, only a new run does. Another study's setting leaves it alone."""
    errors = _open(page, server, "single", "Single cylinder")
    page.get_by_role("button", name="Compute study").click()
    _text(page, "Holes:", r"Passes:|none")
    # the optimiser's settings are not this study's: its result stays
    page.get_by_role("tab", name="Counterweight design").click()
    _setting(page, "cw_iterations").fill("2")
    _setting(page, "cw_population").fill("64")
    playwright_api.expect(_setting(page, "cw_population")).to_have_value("64")
    page.get_by_role("tab", name="Single cylinder").click()
    _text(page, "Primary force", r"Least peak at")
    note = _rerun(page, "single")
    playwright_api.expect(note).to_be_hidden()
    _setting(page, "sc_balance_factor").fill("0.6")
    playwright_api.expect(note).to_contain_text("Not computed for these settings: re-run")
    panel = page.locator(".q-tab-panel:visible").first
    playwright_api.expect(panel).to_contain_text("Compute the study for the drilling plan.")
    playwright_api.expect(panel.locator(".js-plotly-plot:visible")).to_have_count(0)
    assert "Least peak at" not in panel.inner_text()
    _setting(page, "sc_balance_factor").fill("0.5")  # the old value: still not computed
    playwright_api.expect(_setting(page, "sc_balance_factor")).to_have_value("0.5")
    playwright_api.expect(note).to_be_visible()
    assert "Least peak at" not in panel.inner_text()
    page.get_by_role("button", name="Compute study").click()
    _text(page, "Primary force", r"Least peak at")
    playwright_api.expect(note).to_be_hidden()
    # the counterweight optimiser: its density edited after a run
    page.get_by_role("tab", name="Counterweight design").click()
    page.get_by_role("button", name="Optimise").click()
    _text(page, "feasible designs", r"Least mass:")
    _setting(page, "cw_density").fill("2700 kg/m^3")
    playwright_api.expect(_rerun(page, "counterweight")).to_contain_text(
        "Not computed for these settings: re-run"
    )
    panel = page.locator(".q-tab-panel:visible").first
    assert "feasible designs" not in panel.inner_text()
    playwright_api.expect(panel.locator(".js-plotly-plot:visible")).to_have_count(0)
    assert not errors, errors


def _field_of(page: Any, key: str) -> Any:
    """The Quasar field of the setting ``key`` (its label, input and message)."""
    return page.locator(
        f".q-field:has([data-testid=setting-{key}]), .q-field[data-testid=setting-{key}]"
    ).first


#: tab, setting, text typed, message shown under it
TYPED = (
    (
        "Single cylinder",
        "sc_balance_factor",
        "3",
        "Balance factor: '3' must be a number from 0 to 2",
    ),
    ("Single cylinder", "rb_holes", "0", "Holes per web: '0' must be a whole number from 1 to 12"),
    (
        "Single cylinder",
        "rb_hole_diameter",
        "8 kg",
        "Drill diameter: '8 kg' has the wrong unit for a length; write e.g. '40 mm'",
    ),
    (
        "Counterweight design",
        "cw_density",
        "8000",
        "Density: '8000' needs a unit, e.g. '7850 kg/m^3'",
    ),
    (
        "Counterweight design",
        "cw_min_balance",
        "nan",
        "Smallest balance [%]: 'nan' must be a finite number from 1 to 1000",
    ),
    (
        "Counterweight design",
        "cw_max_radius",
        "1e9 mm",
        "Largest radial space: '1e9 mm' must be a length with a unit, e.g. '40 mm', from "
        "0.001 mm to 100000 mm",
    ),
)


def test_setting_messages_in_the_words_of_the_form(server: str, page: Any) -> None:
    """A wrong unit, a missing unit, a NaN, a value out of range typed into settings: the
    message under each field names it by its label and reads as a sentence (no key, no
    "must be has the wrong unit")."""
    errors = _open(page, server, "single", "Single cylinder")
    for tab, key, typed, shown in TYPED:
        page.get_by_role("tab", name=tab).click()
        _setting(page, key).fill(typed)
        field = _field_of(page, key)
        playwright_api.expect(field).to_contain_text(shown)
        text = field.inner_text()
        for internal in ("sc_", "rb_", "cw_", "must be has", "must be a density"):
            assert internal not in text, text
    _shoot(page, "setting-messages")
    assert not errors, errors


def test_holes_per_web_in_the_drilling_plan(server: str, page: Any) -> None:
    """*Holes per web*: three holes per web drill a third as deep as one (axial holes at the
    same radius); the plan, its table and its drawing equal the library's rebalancing."""
    from crankbalance.io.engine_file import load_engine
    from crankbalance.schema.settings import RebalanceOptions, SingleCylinderOptions
    from crankbalance.studies.build import build_model
    from crankbalance.studies.cylinder import rebalance_cylinder

    model = build_model(load_engine("single"))
    one, three = (
        rebalance_cylinder(
            model,
            SingleCylinderOptions(),
            RebalanceOptions.parse({"new_reciprocating": "359 g", "holes": n}),
        )
        for n in (1, 3)
    )
    assert three.iterations[-1].depth == pytest.approx(one.iterations[-1].depth / 3, rel=0.02)
    errors = _open(page, server, "single", "Single cylinder")
    _setting(page, "rb_new_reciprocating").fill("359 g")
    _setting(page, "rb_holes").fill("3")
    page.get_by_role("button", name="Compute study").click()
    plan = _text(page, "Holes:", r"3 per web on 2 webs \(6 in all\)")
    depth = three.iterations[-1].depth
    assert f"Depth: {depth * 1e3:.3f} mm" in plan
    assert f"{one.iterations[-1].depth * 1e3:.3f} mm" not in plan
    removed = three.iterations[-1].removed_mass
    assert f"Mass removed per web: {removed / 2 * 1e3:.2f} g" in plan
    page.wait_for_function(DRAWN)
    holes = page.evaluate(
        """() => [...document.querySelectorAll('.js-plotly-plot')]
        .flatMap((e) => e._fullData || []).filter((t) => t.legendgroup === 'holes').length"""
    )
    assert holes == 3
    _shoot(page, "single-three-holes")
    assert not errors, errors
