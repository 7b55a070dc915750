"""Issue 28 item 5: drilling plans that can be made. A hole deeper than the part (the web's
thickness) or than the drill's length is refused with split holes proposed: more holes per
web, shallower, that take off the same mass (each with its drill point)."""

from __future__ import annotations

import math

import pytest

from crankbalance.errors import InputError
from crankbalance.physics.rebalancing import DrilledHoles
from crankbalance.physics.shop.holes import STEEL_DENSITY, depth_for_volume

MM = 1e-3
D = 8 * MM
POINT = math.radians(118.0)


def closed_form_volume(d: float, shoulder: float, point_angle: float) -> float:
    """V = pi d^2/4 s + the drill point's cone, pi d^2/4 h/3, h = (d/2)/tan(alpha/2)."""
    h = 0.0 if point_angle == math.pi else d / 2 / math.tan(point_angle / 2)
    return math.pi * d**2 / 4 * shoulder + math.pi * d**2 / 4 * h / 3


@pytest.mark.parametrize("depth_to", ["shoulder", "tip"])
def test_split_holes_take_off_the_single_holes_mass(depth_to: str) -> None:
    holes = DrilledHoles(
        D,
        40 * MM,
        point_angle=POINT,
        depth_to=depth_to,
        web_thickness=14 * MM,  # type: ignore[arg-type]
    )
    h = D / 2 / math.tan(POINT / 2)
    depth = 31.7 * MM  # the one hole per web
    shoulder = depth if depth_to == "shoulder" else depth - h
    single = STEEL_DENSITY * closed_form_volume(D, shoulder, POINT) * 2  # two webs
    assert holes.removed_mass(depth) == pytest.approx(single, rel=1e-12)
    n, each = holes.split(depth)
    assert n > 1
    split = holes.__class__(**{**_fields(holes), "number": n})
    assert split.removed_mass(each) == pytest.approx(single, rel=1e-12)
    tip = each + h if depth_to == "shoulder" else each
    assert tip <= 14 * MM * (1 + 1e-9)
    # one hole fewer would go deeper than the web
    fewer = depth_for_volume(D, single / STEEL_DENSITY / 2 / (n - 1), depth_to, POINT)  # type: ignore[arg-type]
    assert (fewer + h if depth_to == "shoulder" else fewer) > 14 * MM


def _fields(holes: DrilledHoles) -> dict:
    return {
        k: getattr(holes, k)
        for k in (
            "diameter",
            "radius",
            "number",
            "direction",
            "webs",
            "density",
            "depth_resolution",
            "point_angle",
            "depth_to",
            "web_thickness",
            "drill_length",
        )
    }


def test_a_hole_deeper_than_the_part_is_refused_with_the_split() -> None:
    holes = DrilledHoles(D, 40 * MM, web_thickness=14 * MM)
    with pytest.raises(InputError) as error:
        holes.check_plan(31.7 * MM, {"holes": "--holes", "web_thickness": "--web-thickness"})
    n, each = holes.split(31.7 * MM)
    message = str(error.value)
    assert "--web-thickness = 14 mm" in message
    assert f"split them: {n} per web side by side, {each * 1e3:.4g} mm deep" in message
    assert f"(--holes: {n})" in message
    # flat-bottomed: n holes of the same diameter, total depth the single hole's
    assert n * each == pytest.approx(31.7 * MM, rel=1e-12)
    holes.__class__(**{**_fields(holes), "number": n}).check_plan(each)  # fits


def test_the_drills_length_limits_the_depth() -> None:
    short = DrilledHoles(D, 40 * MM, drill_length=20 * MM)
    with pytest.raises(InputError, match=r"the drill's length, --drill-length = 20 mm"):
        short.check_plan(31.7 * MM, {"drill_length": "--drill-length"})
    DrilledHoles(D, 40 * MM).check_plan(31.7 * MM)  # a jobber drill reaches 80 mm
    assert short.split(31.7 * MM) == (2, pytest.approx(31.7 * MM / 2))
    with pytest.raises(InputError, match="drill_length"):
        DrilledHoles(D, 40 * MM, drill_length=0.0)


def test_the_cli_names_the_drill_length_and_the_split_passes(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """``rebalance --drill-length``: one 8 mm hole per web would be 119.9 mm deep, deeper
    than a 50 mm drill: refused in one line with the split (3 per web, 39.98 mm each, the
    same mass); the split typed in passes, each hole within the drill's length."""
    import json

    from .conftest import EXAMPLES, run_cli

    args = ["rebalance", "--parts", str(EXAMPLES / "crf250r_rebalance.toml")]
    args += ["--method", "holes", "--hole-diameter", "8 mm", "--drill-length", "50 mm"]
    code, out, err = run_cli(args, capsys)
    assert code == 2 and out == "" and len(err.splitlines()) == 1, err
    assert "deeper than the drill's length, --drill-length = 50 mm" in err
    depth = float(err.split("per web ")[1].split(" mm deep")[0]) * MM  # 119.9 mm, as shown
    n, each = DrilledHoles(D, 40 * MM, drill_length=50 * MM).split(depth)
    shown = float(err.split("split them: 3 per web side by side, ")[1].split(" mm")[0])
    assert n == 3 and shown == pytest.approx(each * 1e3, abs=0.02), err  # 119.9 mm / 3
    code, out, err = run_cli([*args, "--holes", str(n), "--format", "json"], capsys)
    assert code == 0, err
    for case in json.loads(out)["cases"]:
        assert case["passed"] and case["correction"]["drill_length_m"] == pytest.approx(0.05)
        assert all(it["depth_m"] <= 0.05 for it in case["iterations"])
