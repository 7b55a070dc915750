"""Web app, the Explorer tab's problem from the page's engine, through NiceGUI's simulated
User (no browser): the tab opens on the engine's layout, cylinders, strokes and bank angle
where the explorer can explore them, else on its defaults with a line saying why."""

from __future__ import annotations

import pytest
from nicegui.testing.user import User

pytestmark = pytest.mark.anyio


async def test_the_explorer_starts_from_the_engine(user: User, form) -> None:
    await user.open("/?preset=v8-crossplane")
    form.open("explore")
    values = {k: form.element(f"explore-{k}").value for k in ("layout", "cylinders", "strokes")}
    assert values == {"layout": "vee", "cylinders": "8", "strokes": "4"}
    assert form.element("explore-bank_angle").value == "90 deg"
    line = form.text("explore-problem")
    assert "vee, 8 cylinders, 4-stroke, bank angle 90 deg" in line, line
    assert "the crank of this page's engine" in line, line
    form.set("explore-cylinders", "6")
    line = form.text("explore-problem")
    assert "vee, 6 cylinders" in line and "not this page's engine" in line, line
    assert "vee, 8 cylinders" in line, line  # the engine's own problem, to go back to


async def test_the_explorer_says_why_it_does_not_take_the_engine(user: User, form) -> None:
    """The split-crankpin V6 preset has custom throws: the explorer keeps its defaults."""
    await user.open("/?preset=v6-60")
    form.open("explore")
    assert form.element("explore-layout").value == "inline"
    assert form.element("explore-cylinders").value == "4"
    line = form.text("explore-problem")
    assert "inline, 4 cylinders" in line and "not this page's engine" in line, line
    assert "not a custom one" in line, line
