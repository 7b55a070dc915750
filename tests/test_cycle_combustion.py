"""The cycle's combustion stated (issue 27, item 5): heat released or fuel, ratio of
specific heats, exhaust back-pressure and the Wiebe end-of-burn convention, checked
against the closed forms of the ideal cycles."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.physics.engine_cycle import (
    CylinderSpec,
    WiebeCombustion,
    engine_cycle,
    wiebe_burn_fraction,
)
from crankbalance.schema.settings import CycleOptions, parse_options
from crankbalance.studies.cycle import cycle

from .conftest import run_cli

CYLINDER = CylinderSpec(
    bore=0.08, crank_radius=0.04, rod_length=0.14, reciprocating_mass=0.4, crank_inertia=0.05
)
HEAT = 1000.0  # J per cycle
INSTANT = 1e-3  # rad: the shortest burn the model takes, at top dead centre


def _work(samples: int = 720, **combustion: float | str) -> float:
    wiebe = WiebeCombustion(
        **{
            "compression_ratio": 10.0,
            "ignition_angle": 0.0,
            "burn_duration": INSTANT,
            "heat_release": HEAT,
            **combustion,
        }  # fmt: skip
    )
    return engine_cycle(CYLINDER, 300.0, wiebe, 4, samples_per_revolution=samples).indicated_work


@pytest.mark.parametrize("ratio", [8.0, 12.0])
@pytest.mark.parametrize("gamma", [1.3, 1.4])
@pytest.mark.parametrize("samples", [720, 2880])
def test_instant_burn_is_the_otto_cycle(ratio: float, gamma: float, samples: int) -> None:
    """Constant-volume heat release at top dead centre between two isentropes (the Otto
    cycle): W = Q (1 - r^(1 - gamma)), against the cycle's indicated work, the integral of
    p dV over the crank angle."""
    work = _work(samples, compression_ratio=ratio, gamma=gamma)
    otto = HEAT * (1.0 - ratio ** (1.0 - gamma))
    # discretisation: trapezoidal p dV and the pressure interpolated onto the cycle's grid,
    # second order in the angle step
    discretisation = (2 * math.pi / samples) ** 2
    assert abs(work / otto - 1.0) <= discretisation, (work, otto)


def test_burn_end_stop_releases_one_minus_exp_minus_a() -> None:
    """The burn stopped at its duration releases 1 - e^-a of Q (a = 5: 99.33 %), the
    complete one all of it; both instant burns are Otto cycles of their heat."""
    otto = 1.0 - 10.0 ** (1.0 - 1.3)
    tol = (2 * math.pi / 720) ** 2
    assert _work(burn_end="complete") == pytest.approx(HEAT * otto, rel=tol)
    assert _work(burn_end="stop") == pytest.approx(HEAT * (1 - math.exp(-5.0)) * otto, rel=tol)
    angle = np.radians([10.0, 49.9, 50.0, 60.0, 120.0])
    stop = wiebe_burn_fraction(angle, 0.0, math.radians(50.0), burn_end="stop")
    complete = wiebe_burn_fraction(angle, 0.0, math.radians(50.0))
    assert stop[2:] == pytest.approx([1 - math.exp(-5.0)] * 3, abs=1e-15)
    assert complete[3] > 1 - math.exp(-5.0) and complete[4] == pytest.approx(1.0, abs=1e-12)
    assert stop[:2] == pytest.approx(complete[:2], abs=0)


def test_fuel_mass_is_its_heat() -> None:
    """Fuel m_f of heating value H at efficiency eta releases eta m_f H: the same cycle as
    that heat given."""
    fuel = WiebeCombustion(
        compression_ratio=10.0, ignition_angle=-0.3, burn_duration=0.8, fuel_mass=2e-5,
        heating_value=43e6, combustion_efficiency=0.9,
    )  # fmt: skip
    heat = WiebeCombustion(
        compression_ratio=10.0, ignition_angle=-0.3, burn_duration=0.8,
        heat_release=0.9 * 2e-5 * 43e6,
    )  # fmt: skip
    a = engine_cycle(CYLINDER, 300.0, fuel, 4)
    b = engine_cycle(CYLINDER, 300.0, heat, 4)
    assert a.indicated_work == pytest.approx(b.indicated_work, rel=1e-14)
    with pytest.raises(InputError, match="fuel_mass"):
        WiebeCombustion(10.0, 0.0, 0.5, heat_release=100.0, fuel_mass=1e-5)


def test_exhaust_back_pressure_costs_its_pumping_work() -> None:
    """A four-stroke pushing its exhaust out at p_e and drawing in at p_i loses
    (p_e - p_i) V_d per cycle, V_d the swept volume."""
    swept = CYLINDER.piston_area * CYLINDER.stroke
    free = _work()
    back = _work(exhaust_pressure=1.5e5)
    assert free - back == pytest.approx(0.5e5 * swept, rel=(2 * math.pi / 720) ** 2)


def test_the_study_states_the_combustion(capsys: pytest.CaptureFixture[str]) -> None:
    """The settings reach the model, the JSON states them and the text prints the end of
    the burn; refusals name the option."""
    settings = parse_options(
        CycleOptions, {"heat_release": "600 J", "burn_end": "stop", "gamma": "1.35"}
    )
    study = cycle(None, settings)
    combustion = study.to_dict()["combustion"]
    assert combustion["heat_release_J"] == 600.0 and combustion["burn_end"] == "stop"
    assert combustion["gamma"] == 1.35 and combustion["exhaust_pressure_Pa"] == 1e5
    plain = cycle(None, parse_options(CycleOptions, {"heat_release": "600 J", "gamma": "1.35"}))
    assert (
        study.to_dict()["summary"]["indicated_work_J"]
        < plain.to_dict()["summary"]["indicated_work_J"]
    )
    code, out, err = run_cli(["cycle", "--burn-end", "stop", "--fuel-mass", "20 mg"], capsys)
    assert code == 0, err
    assert "burn stopped at the end of the duration" in out and "0.02 g of fuel" in out
    code, out, err = run_cli(["cycle", "--format", "json"], capsys)
    assert json.loads(out)["combustion"]["burn_end"] == "complete"
    for args, option in (
        (["--heat-release", "600 J", "--fuel-mass", "20 mg"], "--fuel-mass"),
        (["--heat-release", "600 J", "--heating-value", "40 MJ/kg"], "--heating-value"),
        (["--gamma", "1.8"], "--gamma"),
        (["--burn-end", "later"], "--burn-end"),
        (["--engine", "inline2-2stroke", "--exhaust-pressure", "1.2 bar"], "--exhaust-pressure"),
    ):
        code, out, err = run_cli(["cycle", *args], capsys)
        assert code == 2 and err.startswith(f"error: {option}"), (args, err)
