"""Drilled holes with their drill point, and drilling plans (crankbalance.physics.shop.holes).

The closed forms are checked against mesh booleans (trimesh with the manifold3d engine): a
steel block minus the solid a drill cuts, from which the removed volume, its centroid and
its first moment about the crank axis follow. A mesh revolved with ``n`` sections has, in
every cross-section, the area of the inscribed n-gon, ``n sin(2 pi/n) / (2 pi)`` times the
circle's; the exact volume is scaled by that factor and the centroid is unchanged, so the
comparison holds to the boolean's round-off (1e-6) rather than to the mesh's resolution.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crankbalance.errors import InputError
from crankbalance.physics.rebalancing import DrilledHoles, rebalance
from crankbalance.physics.shop.holes import (
    DEFAULT_POINT_ANGLE,
    FLAT_BOTTOM,
    STEEL_DENSITY,
    cone_height,
    depth_for_volume,
    drilling_plan,
    hole_geometry,
    hole_mass_properties,
)

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("manifold3d")

SECTIONS = 128
#: area of the inscribed SECTIONS-gon over the circle's
POLYGON = SECTIONS * math.sin(2 * math.pi / SECTIONS) / (2 * math.pi)
#: relative tolerance of the mesh booleans (manifold3d merges vertices a little apart)
BOOLEAN = 1e-6
MM = 1e-3
GMM = 1e-6  # kg m per g mm


def drill_solid(diameter: float, depth: float, depth_to: str, point_angle: float):
    """The solid a drill cuts [mm], axis +z from the entry face z = 0, with 1 mm of air
    above the face (so no face of the boolean is coplanar)."""
    r = diameter / 2
    h = cone_height(diameter, point_angle)
    tip = depth + h if depth_to == "shoulder" else depth
    if tip >= h:
        profile = [[0, -1], [r, -1], [r, tip - h], [0, tip]]
    else:  # the point alone, a cone of height tip whose base is in the face
        base = r * tip / h
        profile = [[0, -1], [base * (1 + 1 / tip), -1], [0, tip]]
    return trimesh.creation.revolve(np.array(profile, dtype=float), sections=SECTIONS)


def removed(block, cut):
    """Volume [mm^3] and centroid [mm] of what ``cut`` takes out of ``block``."""
    rest = block.difference(cut, engine="manifold")
    assert rest.is_watertight
    volume = block.volume - rest.volume
    centroid = (block.volume * block.center_mass - rest.volume * rest.center_mass) / volume
    return volume, centroid


CASES = [
    (8.0, 10.0, "shoulder", DEFAULT_POINT_ANGLE),
    (8.0, 10.0, "tip", DEFAULT_POINT_ANGLE),
    (8.0, 1.5, "tip", DEFAULT_POINT_ANGLE),  # shallower than the point: a cone alone
    (6.0, 12.0, "shoulder", math.radians(140.0)),
    (10.0, 7.0, "tip", math.radians(90.0)),
    (8.0, 10.0, "tip", FLAT_BOTTOM),
]


@pytest.mark.parametrize(("diameter", "depth", "depth_to", "point_angle"), CASES)
def test_axial_hole_against_mesh_boolean(diameter, depth, depth_to, point_angle) -> None:
    """Axial hole at 40 mm from the crank axis (z): volume, centroid depth, first moment."""
    radius = 40.0
    block = trimesh.creation.box(extents=[30.0, 30.0, 30.0])
    block.apply_translation([radius, 0.0, 15.0])
    cut = drill_solid(diameter, depth, depth_to, point_angle)
    cut.apply_translation([radius, 0.0, 0.0])
    volume, centroid = removed(block, cut)
    exact = hole_mass_properties(
        diameter * MM, depth * MM, depth_to, "axial", radius * MM, STEEL_DENSITY, point_angle
    )
    assert volume == pytest.approx(POLYGON * float(exact.volume) / MM**3, rel=BOOLEAN)
    assert centroid[2] == pytest.approx(float(exact.centroid_depth) / MM, rel=BOOLEAN)
    moment = STEEL_DENSITY * volume * MM**3 * math.hypot(centroid[0], centroid[1]) * MM
    assert moment == pytest.approx(POLYGON * float(exact.first_moment), rel=BOOLEAN)


@pytest.mark.parametrize(("diameter", "depth", "depth_to", "point_angle"), CASES)
def test_radial_hole_against_mesh_boolean(diameter, depth, depth_to, point_angle) -> None:
    """Radial hole drilled toward the crank axis (z) from a flat face at R = 60 mm along x:
    the centroid radius is R less the centroid depth."""
    rim = 60.0
    block = trimesh.creation.box(extents=[30.0, 30.0, 30.0])
    block.apply_translation([rim - 15.0, 0.0, 0.0])
    cut = drill_solid(diameter, depth, depth_to, point_angle)
    # hole axis +z -> -x, entry face z = 0 -> x = rim
    cut.apply_transform(trimesh.transformations.rotation_matrix(-math.pi / 2, [0, 1, 0]))
    cut.apply_translation([rim, 0.0, 0.0])
    volume, centroid = removed(block, cut)
    exact = hole_mass_properties(
        diameter * MM, depth * MM, depth_to, "radial", rim * MM, STEEL_DENSITY, point_angle
    )
    assert volume == pytest.approx(POLYGON * float(exact.volume) / MM**3, rel=BOOLEAN)
    assert math.hypot(centroid[0], centroid[1]) == pytest.approx(
        float(exact.centroid_radius) / MM, rel=BOOLEAN
    )
    moment = STEEL_DENSITY * volume * MM**3 * math.hypot(centroid[0], centroid[1]) * MM
    assert moment == pytest.approx(POLYGON * float(exact.first_moment), rel=BOOLEAN)


def test_the_issues_drill_point_numbers() -> None:
    """Issue 16: four 8 mm holes, 118° point, at 40 mm radius, steel of 7850 kg/m^3: against
    flat-bottomed holes of the depth read, the points are worth +51 g mm when the depth is
    read to the shoulder and -101 g mm when read to the tip, whatever the depth."""
    assert STEEL_DENSITY == 7850.0

    def four(depth: float, depth_to: str, point_angle: float) -> float:
        hole = hole_mass_properties(8 * MM, depth, depth_to, "axial", 40 * MM, 7850.0, point_angle)
        return 4 * float(hole.first_moment) / GMM

    for depth in (5 * MM, 10 * MM, 17.3 * MM):
        flat = four(depth, "shoulder", FLAT_BOTTOM)
        assert four(depth, "tip", FLAT_BOTTOM) == pytest.approx(flat, rel=1e-12)
        shoulder = four(depth, "shoulder", DEFAULT_POINT_ANGLE) - flat
        tip = four(depth, "tip", DEFAULT_POINT_ANGLE) - flat
        assert round(shoulder) == 51 and round(tip) == -101
        # read to the shoulder the cone (pi r^2 h / 3) comes on top; read to the tip it
        # replaces a cylinder of height h, three cones: two cones less
        h = 4 * MM / math.tan(math.radians(59.0))
        cone = 4 * 7850.0 * math.pi * (4 * MM) ** 2 * h / 3 * 40 * MM / GMM
        assert shoulder == pytest.approx(cone, rel=1e-12)
        assert tip == pytest.approx(-2 * cone, rel=1e-12)


def test_four_holes_mesh_shoulder_against_flat() -> None:
    """The same +51 g mm from a mesh: a disc drilled with four pointed holes and with four
    flat-bottomed holes of the same depth to the shoulder, at 40 mm radius."""

    def drilled(point_angle: float) -> float:
        disc = trimesh.creation.cylinder(radius=60.0, height=30.0, sections=SECTIONS)
        disc.apply_translation([0.0, 0.0, 15.0])
        cuts = []
        for k in range(4):
            cut = drill_solid(8.0, 10.0, "shoulder", point_angle)
            a = math.radians(160.0 + 13.0 * k)
            cut.apply_translation([40.0 * math.cos(a), 40.0 * math.sin(a), 0.0])
            cuts.append(cut)
        rest = disc.difference(trimesh.boolean.union(cuts, engine="manifold"), engine="manifold")
        volume = disc.volume - rest.volume
        centroid = (disc.volume * disc.center_mass - rest.volume * rest.center_mass) / volume
        angles = np.radians(160.0 + 13.0 * np.arange(4))
        # first moment of the four holes' centroids, each at 40 mm: |sum| / (sum of cos) gives
        # the sum of the holes' moments about the axis
        spread = abs(np.sum(np.exp(1j * angles))) / 4
        return STEEL_DENSITY * volume * MM**3 * math.hypot(*centroid[:2]) * MM / spread

    difference = (drilled(DEFAULT_POINT_ANGLE) - drilled(FLAT_BOTTOM)) / POLYGON / GMM
    assert round(difference) == 51


def test_flat_bottom_and_point_alone() -> None:
    d = 8 * MM
    area = math.pi * d**2 / 4
    flat = hole_geometry(d, [0.0, 3 * MM, 9 * MM], "tip", FLAT_BOTTOM)
    assert flat.cone_height == 0.0
    np.testing.assert_allclose(flat.volume, area * np.array([0.0, 3, 9]) * MM, rtol=1e-15)
    np.testing.assert_allclose(flat.centroid_depth, np.array([0.0, 1.5, 4.5]) * MM, rtol=1e-15)
    h = cone_height(d)
    assert h == pytest.approx(4 * MM / math.tan(math.radians(59.0)), rel=1e-15)
    point = hole_geometry(d, h, "tip")  # exactly the point
    assert float(point.volume) == pytest.approx(area * h / 3, rel=1e-14)
    assert float(point.centroid_depth) == pytest.approx(h / 4, rel=1e-14)
    assert float(point.shoulder_depth) == 0.0
    # a depth to the shoulder of 0 is the point alone too
    assert float(hole_geometry(d, 0.0, "shoulder").volume) == pytest.approx(area * h / 3)


@settings(derandomize=True, database=None, deadline=None, max_examples=200)
@given(
    st.floats(1 * MM, 20 * MM),
    st.floats(0.0, 1e-5),
    st.sampled_from(["shoulder", "tip"]),
    st.floats(math.radians(60.0), math.pi),
)
def test_depth_for_volume_inverts_hole_geometry(diameter, volume, depth_to, point_angle) -> None:
    depth = depth_for_volume(diameter, volume, depth_to, point_angle)
    got = float(hole_geometry(diameter, depth, depth_to, point_angle).volume)
    cone = math.pi * diameter**2 / 4 * cone_height(diameter, point_angle) / 3
    if depth_to == "shoulder" and volume < cone:
        assert depth == 0.0  # the least a hole read to the shoulder removes is its point
    else:
        assert got == pytest.approx(volume, rel=1e-9, abs=1e-18)


def test_hole_input_errors() -> None:
    with pytest.raises(InputError, match="depth_to"):
        hole_geometry(8 * MM, 1 * MM, "bottom")  # type: ignore[arg-type]
    with pytest.raises(InputError, match="point_angle"):
        hole_geometry(8 * MM, 1 * MM, "tip", 4.0)
    with pytest.raises(InputError, match="depth"):
        hole_geometry(8 * MM, -1 * MM, "tip")
    with pytest.raises(InputError, match="short of the crank axis"):
        hole_mass_properties(8 * MM, 40 * MM, "tip", "radial", 40 * MM)
    with pytest.raises(InputError, match="direction"):
        hole_mass_properties(8 * MM, 4 * MM, "tip", "diagonal", 40 * MM)  # type: ignore[arg-type]


# ---------------------------------------------------------------------------------------
# drilling plans
# ---------------------------------------------------------------------------------------


def plan_correction(plan) -> complex:
    """The correction of a plan summed hole by hole from hole_mass_properties."""
    hole = hole_mass_properties(
        plan.diameter,
        plan.depth,
        plan.depth_to,
        plan.direction,
        plan.radius,
        STEEL_DENSITY,
        plan.point_angle,
    )
    return complex(float(hole.first_moment) * np.sum(np.exp(1j * plan.angles)))


def test_one_hole_when_it_fits() -> None:
    heavy = math.radians(200.0)
    plan = drilling_plan(30 * GMM, heavy, 8 * MM, 40 * MM, 12 * MM, "shoulder")
    assert plan.number == 1 and plan.angles[0] == pytest.approx(heavy)
    assert plan.residual_amount < 1e-9 * 30 * GMM
    assert plan.correction == pytest.approx(plan_correction(plan), rel=1e-12)
    # mass removed: the cylinder to the shoulder and the point
    geometry = hole_geometry(8 * MM, plan.depth, "shoulder")
    assert plan.hole_mass == pytest.approx(STEEL_DENSITY * float(geometry.volume), rel=1e-12)
    assert plan.tip_depth == pytest.approx(plan.depth + cone_height(8 * MM), rel=1e-12)


def test_split_into_holes_at_plus_minus_angles() -> None:
    """Too much for one hole 12 mm deep: equal holes symmetric about the heavy spot, the
    least pitch that leaves the spacing, and a residual from the rounded depth only."""
    heavy, spacing, step = math.radians(30.0), 2 * MM, 0.1 * MM
    plan = drilling_plan(
        200 * GMM, heavy, 8 * MM, 40 * MM, 12 * MM, "tip", spacing=spacing, depth_resolution=step
    )
    one = float(hole_mass_properties(8 * MM, 12 * MM, "tip", "axial", 40 * MM).first_moment)
    assert one < 200 * GMM  # one hole could not do it
    assert plan.number > 1
    offsets = np.angle(np.exp(1j * (plan.angles - heavy)))
    np.testing.assert_allclose(np.sort(offsets), -np.sort(offsets)[::-1], atol=1e-12)
    chord = 2 * 40 * MM * math.sin(plan.pitch / 2)
    assert chord == pytest.approx(8 * MM + spacing, rel=1e-12)
    assert np.min(np.diff(np.sort(plan.angles))) == pytest.approx(plan.pitch, rel=1e-9)
    # the fewest holes: one fewer at the same pitch would not reach at max_depth
    fewer = np.arange(plan.number - 1) - (plan.number - 2) / 2
    assert one * np.sum(np.cos(fewer * plan.pitch)) < 200 * GMM
    assert plan.depth <= 12 * MM
    assert plan.depth / step == pytest.approx(round(plan.depth / step), abs=1e-9)
    assert plan.correction == pytest.approx(plan_correction(plan), rel=1e-12)
    assert plan.residual == pytest.approx(plan.unbalance - plan.correction, abs=1e-15)
    # equal holes symmetric about the heavy spot: the residual lies on its line
    assert abs((plan.residual * np.exp(-1j * heavy)).imag) < 1e-15
    # half a depth step is the most rounding changes one hole by
    per_step = float(
        hole_mass_properties(8 * MM, plan.depth + step / 2, "tip", "axial", 40 * MM).first_moment
        - hole_mass_properties(8 * MM, plan.depth, "tip", "axial", 40 * MM).first_moment
    )
    assert plan.residual_amount <= plan.number * per_step * 1.01


def test_radial_holes_keep_the_spacing_at_the_deepest_shoulder() -> None:
    plan = drilling_plan(
        400 * GMM,
        0.0,
        8 * MM,
        60 * MM,
        10 * MM,
        "shoulder",
        direction="radial",
        spacing=3 * MM,
        depth_resolution=0.05 * MM,
    )
    assert plan.number > 1
    inner = 60 * MM - 10 * MM  # the shoulder at max_depth
    assert 2 * inner * math.sin(plan.pitch / 2) == pytest.approx(11 * MM, rel=1e-12)
    assert plan.correction == pytest.approx(plan_correction(plan), rel=1e-12)
    assert plan.residual_amount < 0.02 * 400 * GMM


def test_heavy_metal_at_the_light_spot() -> None:
    heavy = math.radians(100.0)
    plan = drilling_plan(40 * GMM, heavy, 10 * MM, 45 * MM, 15 * MM, "tip", slug_density=18000.0)
    assert plan.method == "heavy metal"
    assert np.angle(np.exp(1j * (plan.angles - heavy - math.pi))) == pytest.approx(0, abs=1e-12)
    area = math.pi * (10 * MM) ** 2 / 4
    assert plan.slug_length == pytest.approx(plan.depth - cone_height(10 * MM), rel=1e-12)
    drilled = STEEL_DENSITY * float(hole_geometry(10 * MM, plan.depth, "tip").volume)
    slug = 18000.0 * area * plan.slug_length
    assert plan.hole_mass == pytest.approx(slug - drilled, rel=1e-12)
    # the net mass added at the light spot cancels the heavy spot
    added = plan.hole_mass * 45 * MM * np.exp(1j * (heavy + math.pi))
    assert plan.unbalance + added == pytest.approx(plan.residual, abs=1e-15)
    assert plan.residual_amount < 1e-9 * 40 * GMM


@settings(derandomize=True, database=None, deadline=None, max_examples=60)
@given(
    st.floats(1 * GMM, 150 * GMM),
    st.floats(-math.pi, math.pi),
    st.sampled_from(["axial", "radial"]),
    st.sampled_from(["shoulder", "tip"]),
)
def test_plans_without_rounding_leave_no_residual(unbalance, angle, direction, depth_to) -> None:
    plan = drilling_plan(
        unbalance,
        angle,
        8 * MM,
        50 * MM,
        12 * MM,
        depth_to,
        direction=direction,
        spacing=2 * MM,
    )
    assert plan.depth <= 12 * MM
    assert plan.correction == pytest.approx(plan_correction(plan), rel=1e-12)
    if plan.residual_amount > 1e-9 * unbalance:
        # only a hole read to the shoulder can overshoot: its point alone removes too much
        assert depth_to == "shoulder" and plan.depth == 0.0
        assert abs(plan.correction) > unbalance


def test_nothing_to_correct() -> None:
    plan = drilling_plan(0.0, 1.0, 8 * MM, 40 * MM, 12 * MM, "tip")
    assert plan.number == 0 and plan.residual == 0


@pytest.mark.parametrize(
    ("kwargs", "field", "words"),
    [
        ({"unbalance": 3000 * GMM}, "unbalance", "max_depth"),
        ({"web_sector": (math.radians(250), math.radians(330))}, "web_sector", "heavy spot"),
        ({"direction": "radial", "max_depth": 40 * MM}, "max_depth", "crank axis"),
        ({"slug_density": 7000.0}, "slug_density", "denser"),
        ({"outer_radius": 43 * MM, "edge_distance": 1 * MM}, "radius", "rim"),
        (
            {"direction": "radial", "web_thickness": 9 * MM, "edge_distance": 1 * MM},
            "diameter",
            "thick",
        ),
        ({"max_holes": 0}, "max_holes", "whole number"),
    ],
)
def test_plan_input_errors(kwargs, field, words) -> None:
    args = {
        "unbalance": 30 * GMM,
        "angle": math.radians(200.0),
        "diameter": 8 * MM,
        "radius": 40 * MM,
        "max_depth": 12 * MM,
        "depth_to": "tip",
    } | kwargs
    with pytest.raises(InputError, match=words) as error:
        drilling_plan(**args)
    assert error.value.field == field


def test_web_sector_limits_the_holes() -> None:
    """A sector that holds the heavy spot but only a few holes: the plan uses them, or says
    the correction cannot be made."""
    heavy = math.radians(180.0)
    sector = (math.radians(160.0), math.radians(200.0))
    plan = drilling_plan(300 * GMM, heavy, 8 * MM, 40 * MM, 12 * MM, "tip", web_sector=sector)
    assert plan.number == 2
    edge = math.asin(4 * MM / (40 * MM))
    assert plan.angles.min() - sector[0] >= edge - 1e-12
    assert sector[1] - plan.angles.max() >= edge - 1e-12
    # pitch 2 asin(8/80) = 11.5 deg, room 20 - asin(4/40) = 14.3 deg each side: 3 holes
    with pytest.raises(InputError, match="at most 3 holes"):
        drilling_plan(600 * GMM, heavy, 8 * MM, 40 * MM, 12 * MM, "tip", web_sector=sector)


# ---------------------------------------------------------------------------------------
# the single-cylinder rebalancing with the same hole model (issue 16, item 7)
# ---------------------------------------------------------------------------------------

ARGS = (0.30, 0.40, 0.30, 0.35, 2.0, 6.2 * MM, 26.9 * MM)


@pytest.mark.parametrize(
    ("point_angle", "depth_to"),
    [(FLAT_BOTTOM, "shoulder"), (DEFAULT_POINT_ANGLE, "shoulder"), (DEFAULT_POINT_ANGLE, "tip")],
)
def test_rebalance_uses_the_hole_model(point_angle, depth_to) -> None:
    holes = DrilledHoles(
        diameter=8 * MM, radius=40 * MM, number=2, point_angle=point_angle, depth_to=depth_to
    )
    result = rebalance(*ARGS, holes, 1 * GMM)
    assert result.passed
    depth = result.iterations[-1].depth
    one = hole_mass_properties(8 * MM, depth, depth_to, "axial", 40 * MM, 7850.0, point_angle)
    assert result.iterations[-1].removed_unbalance == pytest.approx(
        4 * float(one.first_moment), rel=1e-12
    )
    assert result.iterations[-1].removed_mass == pytest.approx(4 * float(one.mass), rel=1e-12)


def test_rebalance_depth_depends_on_the_point() -> None:
    """The same unbalance off: with the point, the holes read to the shoulder are shallower
    than flat-bottomed ones by h/3 (the cone's volume over the hole's area), read to the tip
    deeper by 2h/3 (h: the height of the point)."""
    depths = {}
    for name, angle, ref in (
        ("flat", FLAT_BOTTOM, "shoulder"),
        ("shoulder", DEFAULT_POINT_ANGLE, "shoulder"),
        ("tip", DEFAULT_POINT_ANGLE, "tip"),
    ):
        holes = DrilledHoles(
            diameter=8 * MM,
            radius=40 * MM,
            number=2,
            point_angle=angle,
            depth_to=ref,
            depth_resolution=0.0,
        )
        depths[name] = rebalance(*ARGS, holes, 1e-3 * GMM).iterations[-1].depth
    h = cone_height(8 * MM)
    assert depths["flat"] - depths["shoulder"] == pytest.approx(h / 3, rel=1e-6)
    assert depths["tip"] - depths["flat"] == pytest.approx(2 * h / 3, rel=1e-6)


def test_radial_rebalance_stops_short_of_the_axis() -> None:
    holes = DrilledHoles(
        diameter=4 * MM,
        radius=20 * MM,
        direction="radial",
        number=1,
        point_angle=DEFAULT_POINT_ANGLE,
        depth_to="shoulder",
    )
    with pytest.raises(InputError, match="through the crank axis"):
        rebalance(0.3, 0.4, 0.3, 0.2, 2.0, 6.2 * MM, 26.9 * MM, holes, 1 * GMM)


def test_rebalance_file_and_command_with_a_drill_point(tmp_path, capsys) -> None:
    """The rebalance parts file takes ``point_angle`` and ``depth_to`` for holes; the
    command's JSON and table say what the depth is read to."""
    import json
    from pathlib import Path

    from crankbalance.cli import main

    example = Path(__file__).resolve().parents[1] / "examples" / "crf250r_rebalance.toml"
    text = example.read_text()
    start = text.index("[correction]")
    end = text.index("[tolerance]")
    correction = (
        '[correction]\nmethod = "holes"\nradius = "40 mm"\ndiameter = "8 mm"\nnumber = 2\n'
        'point_angle = "118 deg"\ndepth_to = "tip"\n\n'
    )
    path = tmp_path / "pointed.toml"
    path.write_text(text[:start] + correction + text[end:])
    assert main(["rebalance", "--parts", str(path), "--format", "json"]) is None
    payload = json.loads(capsys.readouterr().out)
    for case in payload["cases"]:
        assert case["correction"]["point_angle_deg"] == pytest.approx(118.0)
        assert case["correction"]["depth_to"] == "tip"
        assert case["passed"]
        last = case["iterations"][-1]
        one = hole_mass_properties(8 * MM, last["depth_m"], "tip", "axial", 40 * MM)
        assert last["removed_unbalance_kg_m"] == pytest.approx(
            4 * float(one.first_moment), rel=1e-9
        )
    assert main(["rebalance", "--parts", str(path)]) is None
    assert "depth to tip [mm]" in capsys.readouterr().out
    path.write_text(text[:start] + correction.replace("118 deg", "200 deg") + text[end:])
    with pytest.raises(SystemExit) as exit_:
        main(["rebalance", "--parts", str(path)])
    assert exit_.value.code == 2
    assert "correction.point_angle = '200 deg'" in capsys.readouterr().err
