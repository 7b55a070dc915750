"""Issue 31 item 1, the estimate: ``[powertrain.estimate]`` (a block and a gearbox as boxes,
the crank train's masses at their places) summed with the parallel-axis theorem, checked
against the closed form of a box and against summing point masses numerically."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from crankbalance.cli import main
from crankbalance.errors import InputError
from crankbalance.io.engine_file import parse_engine_text
from crankbalance.physics import mounts_estimate as pe
from crankbalance.schema.settings import MountsOptions
from crankbalance.studies.engine import analyze
from crankbalance.studies.mounts import mounts

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "examples" / "mounts_inline4_car.toml"
GIVEN = """mass = "165 kg"                                   # engine and transaxle, filled
cg = ["40 mm", "-110 mm", "90 mm"]               # toward the gearbox (-y) and above the crank
inertia = ["8.5 kg*m^2", "4.8 kg*m^2", "7.6 kg*m^2"]
products = ["0.35 kg*m^2", "-0.40 kg*m^2", "0.55 kg*m^2"]   # tensor entries, -∫xy dm etc.
"""
ESTIMATE = """
[powertrain.estimate]
block_mass = "105 kg"
block_size = ["420 mm", "460 mm", "520 mm"]
block_center = ["20 mm", "10 mm", "110 mm"]
gearbox_mass = "48 kg"
gearbox_size = ["300 mm", "260 mm", "320 mm"]
gearbox_center = ["60 mm", "-340 mm", "20 mm"]
"""


def _estimated_text() -> str:
    text = CAR.read_text()
    assert GIVEN in text
    return text.replace(GIVEN, "").replace(
        "\n[[powertrain.mount]]", ESTIMATE + "\n[[powertrain.mount]]", 1
    )


def _points_of_box(mass: float, size: np.ndarray, centre: np.ndarray, n: int) -> tuple:
    """The box as n^3 equal point masses at the centres of its cells (the midpoint rule)."""
    axes = [(np.arange(n) + 0.5) / n * s - s / 2 + c for s, c in zip(size, centre, strict=True)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    return grid, np.full(len(grid), mass / len(grid))


def _point_sum(points: np.ndarray, masses: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """Mass, centre and inertia tensor (−∫xy dm off the diagonal) of point masses."""
    m = float(masses.sum())
    cg = (masses[:, None] * points).sum(axis=0) / m
    d = points - cg
    inertia = np.einsum(
        "k,kij->ij",
        masses,
        np.einsum("ki,ki->k", d, d)[:, None, None] * np.eye(3) - d[:, :, None] * d[:, None, :],
    )
    return m, cg, inertia


def test_a_box_and_the_parallel_axis_theorem_against_point_masses() -> None:
    size, centre = np.array([0.42, 0.46, 0.52]), np.array([0.02, 0.01, 0.11])
    a, b, c = size
    closed = 105.0 / 12 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    assert np.allclose(pe.box_inertia(105.0, size), closed)
    points, masses = _points_of_box(105.0, size, centre, 40)
    m, cg, inertia = _point_sum(points, masses)
    assert np.allclose(cg, centre)
    # the midpoint rule underestimates each square by s^2/(12 n^2)
    assert np.allclose(inertia, closed, rtol=1e-3)
    # about the origin: own inertia plus m(|d|^2 E - d d^T)
    about_origin = np.einsum(
        "k,kij->ij",
        masses,
        np.einsum("ki,ki->k", points, points)[:, None, None] * np.eye(3)
        - points[:, :, None] * points[:, None, :],
    )
    assert np.allclose(
        pe.box_inertia(105.0, size) + pe.parallel_axis(105.0, centre), about_origin, rtol=1e-3
    )


def test_the_estimate_is_the_sum_of_its_parts_as_point_masses() -> None:
    spec = parse_engine_text(_estimated_text(), str(CAR))
    model = analyze(spec).model
    result = mounts(spec, MountsOptions.parse({"speed_samples": 20}))
    parts = result.parts
    assert [p.name for p in parts][:1] == ["block"] and parts[-1].name == "gearbox"
    # every part as point masses: the boxes as grids, each throw's ring as 360 points on its
    # circle, each reciprocating mass as one point
    points, masses = [], []
    for p in parts:
        if p.name in ("block", "gearbox"):
            e = spec.powertrain.estimate
            size = e.block_size if p.name == "block" else e.gearbox_size
            xyz, m = _points_of_box(p.mass, np.array(size), p.centre, 30)
        elif "rotating" in p.name:
            t = np.linspace(0, 2 * math.pi, 360, endpoint=False)
            r = model.crank_radius
            xyz = p.centre + np.stack([r * np.sin(t), np.zeros_like(t), r * np.cos(t)], axis=1)
            m = np.full(360, p.mass / 360)
        else:
            xyz, m = p.centre[None, :], np.array([p.mass])
        points.append(xyz)
        masses.append(m)
    mass, cg, inertia = _point_sum(np.concatenate(points), np.concatenate(masses))
    pt = result.powertrain
    assert pt.mass == pytest.approx(mass, rel=1e-12)
    # 105 + 48 kg of boxes, and the crank train: 4 x (piston, pin, rod's reciprocating part)
    recip = 4 * (0.340 + 0.110 + 0.33 * 0.520)
    assert pt.mass == pytest.approx(153.0 + recip + float(model.throw_rotating_mass.sum()))
    assert np.allclose(pt.cg, cg, atol=1e-12)
    assert np.allclose(pt.inertia, inertia, rtol=2e-3, atol=1e-4)
    # the inline-4's pistons sit on the crank's z axis at the rod length, in their planes
    recips = [p for p in parts if "reciprocating" in p.name]
    assert len(recips) == 4
    assert all(p.centre[2] == pytest.approx(0.145) and p.centre[0] == 0 for p in recips)


def test_the_estimate_from_the_command_line(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    path = tmp_path / "car_estimated.toml"
    path.write_text(_estimated_text())
    code = main(["mounts", str(path), "--speed-samples", "20", "--format", "json"])
    out, err = capsys.readouterr()
    assert not code, err
    data = json.loads(out)
    names = [p["part"] for p in data["powertrain"]["estimated_from"]]
    assert names[0] == "block" and names[-1] == "gearbox" and len(names) == 2 + 4 + 4
    assert len(data["modes"]) == 6


@pytest.mark.parametrize(
    ("change", "words"),
    [
        (
            lambda t: t.replace("[powertrain]\n", '[powertrain]\nmass = "165 kg"\n'),
            "powertrain.mass = ",
        ),
        (lambda t: t.replace('gearbox_mass = "48 kg"\n', ""), "a gearbox needs gearbox_mass"),
        (lambda t: t.replace('block_size = ["420 mm", "460 mm", "520 mm"]\n', ""), "block_size"),
        (lambda t: t.replace(ESTIMATE, "\n"), "powertrain.mass"),
    ],
)
def test_bad_estimates_are_one_line_naming_the_key(change, words: str) -> None:
    with pytest.raises(InputError) as caught:
        parse_engine_text(change(_estimated_text()), str(CAR))
    assert words in str(caught.value)
