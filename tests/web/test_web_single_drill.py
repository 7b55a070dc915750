"""Web app, Single cylinder tab: the drill point of the rebalancing's holes (*Drill point
angle*, *Depth read to the*) through NiceGUI's simulated User.

The plan on the page is checked against the library's rebalancing for the same inputs
(:func:`crankbalance.studies.cylinder.rebalance_cylinder`, holes built as
:class:`~crankbalance.physics.rebalancing.DrilledHoles` with the point) and against the closed
form of a hole with a conical point (cylinder plus cone, V = A (s + h/3), h = (d/2) /
tan(alpha/2)): the mass shown per web, and the point's height between the depth to the
tip and the depth to the shoulder of the same correction."""

from __future__ import annotations

import json
import math
import re
from typing import Any

import pytest
from nicegui.elements.upload_files import SmallFileUpload
from nicegui.testing.user import User

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.physics.rebalancing import DrilledHoles, rebalance
from crankbalance.physics.single_cylinder import counterweight_moment
from crankbalance.schema.settings import (
    RebalanceOptions,
    ShopOptions,
    SingleCylinderOptions,
    parse_options,
)
from crankbalance.studies.build import build_model
from crankbalance.studies.cylinder import cylinder_of, iso_check, rebalance_cylinder

pytestmark = pytest.mark.anyio

NEW_RECIPROCATING = "359 g"  # lighter parts than the preset's: the crank needs holes
DRILL = 0.008  # the tab's default drill diameter [m]


def _reference(point_angle_deg: float, depth_to: str) -> Any:
    """The library's rebalancing of the single preset's cylinder 1 with the new
    reciprocating parts (the tab's defaults: balance factor 0.5, counterweight what that
    factor needs at the crank radius with the old parts, one hole per web at that radius),
    its holes built here with the point, not through the tab's options."""
    model = build_model(load_engine("single"))
    single = SingleCylinderOptions()
    cylinder = cylinder_of(model, single.cylinder)
    rot, rec, r = cylinder.rotating_mass, cylinder.reciprocating_mass, cylinder.crank_radius
    holes = DrilledHoles(
        diameter=DRILL,
        radius=r,
        point_angle=math.radians(point_angle_deg),
        depth_to=depth_to,  # type: ignore[arg-type]
    )
    return rebalance(
        rot,
        rec,
        rot,
        RebalanceOptions.parse({"new_reciprocating": NEW_RECIPROCATING}).new_reciprocating,
        counterweight_moment(rot, rec, single.balance_factor, r) / r,
        r,
        r,
        holes,
        iso_check(model, single).permissible,
    )


async def _plan(user: User, form: Any, **settings: str) -> str:
    """Open the Single cylinder tab of the single preset, type the settings, compute, and
    return the drilling plan as shown."""
    await user.open("/?preset=single")
    form.open("single")
    form.set("setting-rb_new_reciprocating", NEW_RECIPROCATING)
    for key, value in settings.items():
        form.set(f"setting-rb_{key}", value)
    user.find(marker="run-single").click()
    await form.until(lambda: "Holes" in form.text("drilling-plan"), "the drilling plan")
    return form.text("drilling-plan")


def _depth_mm(plan: str) -> float:
    found = re.search(r"\*\*Depth:\*\* ([0-9.]+) mm", plan)
    assert found, plan
    return float(found.group(1))


def _per_web_g(plan: str) -> float:
    found = re.search(r"\*\*Mass removed per web:\*\* ([0-9.]+) g", plan)
    assert found, plan
    return float(found.group(1))


async def test_pointed_drill_plan_equals_the_library(user: User, form) -> None:
    """118 deg, depths to the tip: the plan, its table and its drawing equal the library's
    rebalancing with those holes; the mass per web is that of a cylinder plus a cone."""
    plan = await _plan(user, form, point_angle="118 deg", depth_to="tip")
    ref = _reference(118.0, "tip")
    holes, last = ref.correction, ref.iterations[-1]
    flat = _reference(180.0, "tip").iterations[-1]
    assert last.depth > 0 and ref.passed, "the case needs holes and converges"
    assert f"**Depth:** {last.depth * 1e3:.3f} mm to the tip (118° drill point)" in plan, plan
    assert f"**Drill diameter:** {holes.diameter * 1e3:.4g} mm" in plan
    assert f"{holes.radius * 1e3:.4g} mm from the crank axis" in plan
    assert f"**Mass removed per web:** {last.removed_mass / holes.webs * 1e3:.2f} g" in plan
    assert f"**Passes:** {len(ref.iterations)} ({ref.status})" in plan
    assert f"{flat.depth * 1e3:.3f} mm" not in plan, "the point changes the depth"
    # closed form: one hole of depth t to the tip removes rho A (t - h + h/3)
    area, h = math.pi * DRILL**2 / 4, DRILL / 2 / math.tan(math.radians(59.0))
    depth = _depth_mm(plan) * 1e-3
    per_web = holes.density * area * (depth - h + h / 3) * holes.number
    assert _per_web_g(plan) == pytest.approx(per_web * 1e3, abs=0.01), (
        "mass per web against the cylinder-plus-cone volume"
    )
    # the table of the passes: its depth column says what it is read to
    table = form.element("drilling-passes")
    assert [c["label"] for c in table.columns if c["name"] == "depth"] == ["Depth to the tip [mm]"]
    assert [r["depth"] for r in table.rows] == [f"{it.depth * 1e3:.3f}" for it in ref.iterations]
    # the drawing and its downloads name the depth as read
    figure = (await form.download("download-drilling-json")).decode()
    names = [t["name"] for t in json.loads(figure)["traces"]]
    assert f"hole Ø8 mm, {last.depth * 1e3:.3f} mm deep to the tip" in names, names
    csv = (await form.download("download-drilling-csv")).decode()
    assert "deep to the tip" in csv


async def test_depth_to_the_shoulder_is_the_tip_less_the_point(user: User, form) -> None:
    """The same correction read to the shoulder: the library's depth, one point's height
    (d/2 / tan 59 deg = 2.403 mm for an 8 mm drill) less than the depth to the tip."""
    plan = await _plan(user, form, point_angle="118 deg", depth_to="shoulder")
    ref = _reference(118.0, "shoulder")
    last = ref.iterations[-1]
    assert f"**Depth:** {last.depth * 1e3:.3f} mm to the shoulder (118° drill point)" in plan
    tip = _reference(118.0, "tip").iterations[-1].depth
    h = DRILL / 2 / math.tan(math.radians(59.0))
    assert _depth_mm(plan) * 1e-3 == pytest.approx(tip - h, abs=2e-6), (
        "tip depth - shoulder depth = the point's height (cone of half-angle 59 deg)"
    )
    table = form.element("drilling-passes")
    assert "Depth to the shoulder [mm]" in [c["label"] for c in table.columns]


async def test_flat_point_gives_the_flat_plan_unchanged(user: User, form) -> None:
    """180 deg (the default) is a flat bottom: the plan of the tab without a drill point,
    whatever the depth is read to; after a pointed run the plan is cleared, not kept."""
    flat = rebalance_cylinder(
        build_model(load_engine("single")),
        SingleCylinderOptions(),
        RebalanceOptions.parse({"new_reciprocating": NEW_RECIPROCATING}),
    )
    assert flat.correction.point_angle == math.pi, "the options' default is a flat bottom"
    depth = flat.iterations[-1].depth
    assert _reference(180.0, "shoulder").iterations[-1].depth == depth, "the reference's inputs"
    plan = await _plan(user, form)
    assert form.element("setting-rb_point_angle").value == "180 deg"
    assert f"**Depth:** {depth * 1e3:.3f} mm (flat-bottomed)" in plan, plan
    table = form.element("drilling-passes")
    assert "Depth [mm]" in [c["label"] for c in table.columns]
    # a pointed run, then back to 180 deg with the depth to the shoulder: the flat plan
    form.set("setting-rb_point_angle", "118 deg")
    assert "Not computed for these settings" in form.element("single-rerun").text
    assert "Holes" not in form.text("drilling-plan"), "the old plan is cleared"
    user.find(marker="run-single").click()
    await form.until(lambda: "to the tip" in form.text("drilling-plan"), "the pointed plan")
    form.set("setting-rb_point_angle", "180 deg")
    form.set("setting-rb_depth_to", "shoulder")
    user.find(marker="run-single").click()
    await form.until(lambda: "flat-bottomed" in form.text("drilling-plan"), "the flat plan")
    assert f"**Depth:** {depth * 1e3:.3f} mm (flat-bottomed)" in form.text("drilling-plan")


async def test_depth_reference_edit_clears_the_result(user: User, form) -> None:
    """Never stale: choosing the other depth reference clears the plan and says to re-run."""
    await _plan(user, form, point_angle="118 deg")
    form.set("setting-rb_depth_to", "shoulder")
    assert "Not computed for these settings" in form.element("single-rerun").text
    assert "Holes" not in form.text("drilling-plan")
    passes = [e for e in user.client.elements.values() if "drilling-passes" in e._markers]
    assert [(t.rows, t.visible) for t in passes] == [([], False)], "the passes are cleared"


@pytest.mark.parametrize("typed", ["200 deg", "abc", "118", "0 deg"])
async def test_bad_point_angle_is_named_beside_the_field(user: User, form, typed: str) -> None:
    """A bad point angle: the message under the field names it by its label, quotes the
    value and says what is allowed in the words of the options schema (those of the
    command line and of the Balance shop tab); Compute study then plans no holes."""
    await user.open("/?preset=single")
    form.open("single")
    form.set("setting-rb_point_angle", typed)
    shown = form.error("setting-rb_point_angle") or ""
    with pytest.raises(InputError) as same:  # the Balance shop's (and the CLI's) words
        parse_options(ShopOptions, {"point_angle": typed})
    assert shown == f"Drill point angle: {typed!r} {same.value.allowed}", shown
    assert "rb_" not in shown
    user.find(marker="run-single").click()
    await form.until(lambda: "No drilling plan" in form.text("drilling-plan"), "the refusal")
    assert "Drill point angle" in form.text("drilling-plan")


async def test_project_round_trip_keeps_the_drill_point(user: User, form) -> None:
    """Save the project as TOML with a pointed drill read to the shoulder, load another
    preset, load the file: both settings come back in their inputs and the plan with them."""
    await user.open("/?preset=single")
    form.open("single")
    form.set("setting-rb_new_reciprocating", NEW_RECIPROCATING)
    form.set("setting-rb_point_angle", "118 deg")
    form.set("setting-rb_depth_to", "shoulder")
    saved = await form.download("save-toml")
    line = saved.decode().splitlines()[0]
    assert '"rb_point_angle":"118 deg"' in line and '"rb_depth_to":"shoulder"' in line, line
    with user:
        form.element("preset").value = "inline4"
    await form.until(lambda: form.element("setting-rb_point_angle").value == "180 deg")
    assert form.element("setting-rb_depth_to").value == "tip"
    with user:
        await form.element("upload").handle_uploads(
            [SmallFileUpload("mine.toml", "text/plain", saved)]
        )
    await form.until(lambda: form.element("setting-rb_point_angle").value == "118 deg")
    assert form.element("setting-rb_depth_to").value == "shoulder"
    user.find(marker="run-single").click()
    await form.until(lambda: "Holes" in form.text("drilling-plan"), "the drilling plan")
    last = _reference(118.0, "shoulder").iterations[-1]
    assert f"{last.depth * 1e3:.3f} mm to the shoulder" in form.text("drilling-plan")


def test_radial_hole_drawing_shows_the_point() -> None:
    """figures.drilling_plan, radial holes: the outline reaches the tip (rim - depth to the
    tip) and is full width down to the shoulder, the point's height (cone of half-angle
    59 deg) above the tip; a flat bottom is full width to its one depth."""
    from crankbalance.output.figures.single import drilling_plan

    model = build_model(load_engine("single"))
    single = SingleCylinderOptions()
    cylinder = cylinder_of(model, single.cylinder)
    h = DRILL / 2 / math.tan(math.radians(59.0))
    for angle, depth_to, to_tip, named in (  # to_tip: from the depth as read to the tip
        (118.0, "tip", 0.0, " deep to the tip"),
        (118.0, "shoulder", h, " deep to the shoulder"),
        (180.0, "tip", 0.0, " deep"),
    ):
        holes = DrilledHoles(
            diameter=DRILL,
            radius=0.04,
            direction="radial",
            point_angle=math.radians(angle),
            depth_to=depth_to,  # type: ignore[arg-type]
        )
        rot, rec, r = cylinder.rotating_mass, cylinder.reciprocating_mass, cylinder.crank_radius
        cw_mass = counterweight_moment(rot, rec, single.balance_factor, r) / r
        result = rebalance(rot, rec, rot, rec - 0.01, cw_mass, r, r, holes, 1e-7)
        depth = result.iterations[-1].depth
        assert depth > h
        trace = next(t for t in drilling_plan(result, 0.03).data if t.legendgroup == "holes")
        y, x = list(trace.y), list(trace.x)
        assert trace.name.endswith(named), trace.name
        tip = depth + to_tip  # depth to the tip [m]
        assert max(x) - min(x) == pytest.approx(DRILL * 1e3)
        assert max(y) == pytest.approx(-(0.04 - tip) * 1e3), "the tip, towards the axis"
        assert min(y) == pytest.approx(-40.0), "drilled from the rim"
        full = [yy for xx, yy in zip(x, y, strict=True) if abs(abs(xx) - DRILL * 500) < 1e-9]
        shoulder = tip - (h if angle < 180 else 0.0)
        assert max(full) == pytest.approx(-(0.04 - shoulder) * 1e3), "full width to the shoulder"
