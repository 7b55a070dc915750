"""Issue 28 item 5 in the web app (Single cylinder tab, NiceGUI's simulated User): the
drilling plan is checked against the web's thickness and the drill's length, fields of the
tab (*Web thickness at the holes*, *Drill length*); a hole deeper than either is refused with
split holes proposed, the library's (:meth:`~crankbalance.physics.rebalancing.DrilledHoles.split`),
and the proposal, typed in, gives a plan that states the limit it was checked against."""

from __future__ import annotations

from typing import Any

import pytest
from nicegui.testing.user import User

from crankbalance.io.engine_file import load_engine
from crankbalance.physics.rebalancing import DrilledHoles
from crankbalance.schema.settings import RebalanceOptions, SingleCylinderOptions
from crankbalance.studies.build import build_model
from crankbalance.studies.cylinder import rebalance_cylinder

pytestmark = pytest.mark.anyio

NEW_RECIPROCATING = "359 g"  # lighter parts: one 8 mm hole per web 19.0 mm deep


async def _plan(user: User, form: Any, words: str, **settings: str) -> str:
    await user.open("/?preset=single")
    form.open("single")
    form.set("setting-rb_new_reciprocating", NEW_RECIPROCATING)
    for key, value in settings.items():
        form.set(f"setting-rb_{key}", value)
    user.find(marker="run-single").click()
    await form.until(lambda: words in form.text("drilling-plan"), "the drilling plan")
    return form.text("drilling-plan")


def _library(**settings: Any) -> Any:
    options = RebalanceOptions.parse({"new_reciprocating": NEW_RECIPROCATING, **settings})
    model = build_model(load_engine("single"))
    return rebalance_cylinder(model, SingleCylinderOptions(), options)


async def test_a_hole_deeper_than_the_web_is_refused_with_split_holes(user: User, form) -> None:
    one = _library()  # without the web's thickness: one hole, within the drill's reach
    depth = one.iterations[-1].depth
    assert 0.014 < depth < 0.080
    web = DrilledHoles(one.correction.diameter, one.correction.radius, web_thickness=0.014)
    n, each = web.split(depth)
    assert n == 2
    plan = await _plan(user, form, "No drilling plan", web_thickness="14 mm")
    assert "deeper than the part's depth" in plan and "14 mm" in plan, plan
    assert f"split them: {n} per web side by side, {each * 1e3:.4g} mm deep" in plan, plan
    # the split typed in: a plan, checked against the web
    plan = await _plan(user, form, "Holes", web_thickness="14 mm", holes=str(n))
    assert f"{n} per web on 2 webs" in plan, plan
    assert "**Deepest possible:** 14 mm to the tip (the part's depth, Web thickness" in plan
    ref = _library(web_thickness="14 mm", holes=n)
    assert f"**Depth:** {ref.iterations[-1].depth * 1e3:.3f} mm" in plan
    assert ref.iterations[-1].depth <= 0.014


async def test_the_drills_length_is_a_field(user: User, form) -> None:
    plan = await _plan(user, form, "No drilling plan", drill_length="15 mm")
    assert "the drill's length, Drill length = 15 mm" in plan or "drill_length = 15 mm" in plan
    assert "split them: 2 per web side by side" in plan, plan
