"""Property tests over random valid engines: renumbering, rigid rotation, speed scaling."""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from crankbalance.schema.engine import spec_from_dict
from crankbalance.studies.engine import analyze


@st.composite
def custom_engines(draw: Any) -> dict[str, Any]:
    throws = draw(st.integers(1, 6))
    throw_list = []
    position = -0.2
    for _ in range(throws):
        position += draw(st.floats(0.02, 0.12))
        banks = draw(st.lists(st.floats(-180, 180), min_size=1, max_size=3))
        throw_list.append(
            {
                "position": f"{position * 1e3:.6f} mm",
                "angle": f"{draw(st.floats(0, 360)):.6f} deg",
                "banks": [f"{b:.6f} deg" for b in banks],
            }
        )
    r = draw(st.floats(0.02, 0.08))
    lam = draw(st.floats(0.15, 0.4))
    return {
        "speed": f"{draw(st.floats(500, 15000)):.3f} rpm",
        "crank_train": {
            "layout": "custom",
            "crank_radius": f"{r * 1e3:.6f} mm",
            "rod_length": f"{r / lam * 1e3:.6f} mm",
            "throw": throw_list,
        },
        "masses": {
            "reciprocating": f"{draw(st.floats(50, 3000)):.3f} g",
            "rotating": f"{draw(st.floats(50, 5000)):.3f} g",
        },
    }


def amplitudes(data: dict[str, Any]) -> tuple[np.ndarray, np.ndarray, float, float]:
    f = analyze(spec_from_dict(data)).forces
    return (f.force_amplitude, f.moment_amplitude, abs(f.rotating_force), abs(f.rotating_couple))


def close(a: Any, b: Any, scale: float) -> bool:
    return bool(np.allclose(a, b, rtol=1e-9, atol=1e-9 * scale))


@settings(max_examples=60, deadline=None)
@given(custom_engines())
def test_numbering_from_the_other_end(data: dict[str, Any]) -> None:
    """The same engine numbered from the other end (throw list reversed, axial
    positions measured the other way) has the same force and moment amplitudes."""
    mirrored = copy.deepcopy(data)
    throws = mirrored["crank_train"]["throw"][::-1]
    for t in throws:
        t["position"] = f"{-float(t['position'].split()[0]):.6f} mm"
    mirrored["crank_train"]["throw"] = throws
    a, b = amplitudes(data), amplitudes(mirrored)
    scale = float(np.max(a[0])) + 1.0
    for x, y in zip(a, b, strict=True):
        assert close(x, y, scale)


@settings(max_examples=60, deadline=None)
@given(custom_engines(), st.floats(0, 360))
def test_rigid_rotation_of_all_throws(data: dict[str, Any], turn: float) -> None:
    rotated = copy.deepcopy(data)
    for t in rotated["crank_train"]["throw"]:
        t["angle"] = f"{float(t['angle'].split()[0]) + turn:.6f} deg"
    a, b = amplitudes(data), amplitudes(rotated)
    scale = float(np.max(a[0])) + 1.0
    for x, y in zip(a, b, strict=True):
        assert close(x, y, scale)


@settings(max_examples=40, deadline=None)
@given(custom_engines(), st.floats(0.25, 4.0))
def test_forces_scale_with_speed_squared(data: dict[str, Any], factor: float) -> None:
    faster = copy.deepcopy(data)
    rpm = float(data["speed"].split()[0])
    faster["speed"] = f"{rpm * factor!r} rpm"
    a, b = amplitudes(data), amplitudes(faster)
    scale = float(np.max(a[0])) + 1.0
    for x, y in zip(a, b, strict=True):
        assert close(np.asarray(x) * factor**2, y, scale * factor**2)


@settings(max_examples=40, deadline=None)
@given(st.integers(2, 8), st.data())
def test_inline_renumbered_from_the_other_end(cylinders: int, data: Any) -> None:
    """An inline engine with per-cylinder masses, numbered from the other end
    (cylinder k becomes n+1-k in the firing order and the overrides)."""
    order = data.draw(st.permutations(list(range(1, cylinders + 1))))
    masses = [data.draw(st.floats(0.2, 1.5)) for _ in range(cylinders)]

    def engine(numbering: list[int]) -> dict[str, Any]:
        return {
            "speed": "3000 rpm",
            "crank_train": {
                "layout": "inline",
                "cylinders": cylinders,
                "crank_radius": "40 mm",
                "rod_length": "140 mm",
                "crank_pitch": "90 mm",
                "firing_order": [numbering[c - 1] for c in order],
            },
            "masses": {
                "reciprocating": "500 g",
                "rotating": "800 g",
                "override": [
                    {"cylinders": [numbering[c]], "reciprocating": f"{masses[c] * 1e3!r} g"}
                    for c in range(cylinders)
                ],
            },
        }

    a = amplitudes(engine(list(range(1, cylinders + 1))))
    b = amplitudes(engine(list(range(cylinders, 0, -1))))
    scale = float(np.max(a[0])) + 1.0
    for x, y in zip(a, b, strict=True):
        assert close(x, y, scale)
