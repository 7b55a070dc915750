"""The Explorer tab's candidate loaded as the current engine keeps its bank angle for a VR
layout (two rows a narrow angle apart) as it does for a vee and a W: without it the engine
file of a VR candidate would be refused (``crank_train.bank_angle`` is required for vr)."""

from __future__ import annotations

import math

import pytest

pytest.importorskip("nicegui")


@pytest.mark.parametrize(
    ("layout", "degrees", "throws"),
    [("vr", 15.0, (0, 240, 120, 120, 240, 0)), ("vee", 60.0, (0, 120, 240))],
)
def test_a_banked_candidate_keeps_its_bank_angle(
    layout: str, degrees: float, throws: tuple[int, ...]
) -> None:
    from crankbalance.io.engine_file import preset_text
    from crankbalance.physics.explore import orders
    from crankbalance.schema.engine import EngineSpec
    from crankbalance.web.project import Project
    from crankbalance.web.tab_explore import candidate_file

    spec = Project.from_text(preset_text("inline6"), "preset inline6").spec
    assert spec is not None
    problem = orders.problem(layout, 6, 4, math.radians(degrees))
    row = {
        "firing_order": [1, 5, 3, 6, 2, 4],
        "throw_angle_rad": [math.radians(a) for a in throws],
    }
    out = candidate_file(spec.to_data(), problem, math.radians(degrees), row)
    assert out["crank_train"]["layout"] == layout
    assert out["crank_train"]["bank_angle"] == f"{degrees:.9g} deg"
    loaded = EngineSpec.parse(out, source="candidate")
    assert loaded.crank_train.bank_angle == pytest.approx(math.radians(degrees))
