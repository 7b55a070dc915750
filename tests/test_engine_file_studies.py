"""Studies that take their data from an engine file or preset (--engine)."""

from __future__ import annotations

import json
import math

import pytest

from crankbalance.errors import InputError
from crankbalance.physics.engine_cycle import CylinderSpec, WiebeCombustion, engine_cycle
from crankbalance.studies.engine import as_model

from .conftest import run_cli


def test_cycle_from_engine_file(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(
        ["cycle", "--engine", "single", "--cylinder", "1", "--format", "json"]
        + ["--balance-factor", "0.5"],
        capsys,
    )
    assert code == 0, err
    data = json.loads(out)
    assert "engine" not in data, "one cylinder"
    model = as_model("single")
    assert data["cylinder"]["reciprocating_mass_kg"] == pytest.approx(model.reciprocating_mass[0])
    assert data["cylinder"]["crank_radius_m"] == pytest.approx(model.crank_radius)
    assert data["speed_rad_s"] * 30 / math.pi == pytest.approx(9000.0)
    code, _out, err = run_cli(["cycle", "--engine", "single", "--cylinder", "2"], capsys)
    assert code == 2 and "--cylinder" in err


def test_too_small_crank_inertia_is_refused() -> None:
    """A crank inertia far too small for the cycle would make the speed swing through zero:
    refused with a message naming the field instead of a meaningless result."""
    cylinder = CylinderSpec(
        bore=0.08,
        crank_radius=0.04,
        rod_length=0.135,
        reciprocating_mass=0.94,
        crank_inertia=0.0005,
    )
    with pytest.raises(InputError, match="crank_inertia"):
        engine_cycle(
            cylinder,
            2000 * 3.14159 / 30,
            WiebeCombustion(compression_ratio=12.0, ignition_angle=-0.4, burn_duration=0.9),
        )
