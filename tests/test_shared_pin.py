"""Cylinders on a shared crankpin (V engines): the command line, the web application and
the Python API give one cylinder the same masses and bob-weight, and they are the hand
values: the throw's rotating mass shared equally among the rods on its pin
(docs/single_cylinder.md, "Cylinders on a shared crankpin")."""

from __future__ import annotations

import json

import pytest

from crankbalance.cli import main
from crankbalance.io.engine_file import load_engine
from crankbalance.studies.build import build_model
from crankbalance.studies.cylinder import cylinder_of
from crankbalance.web.project import DEFAULT_SETTINGS, Project
from crankbalance.web.studies import rebalance_study, single_study

PRESETS = ("v8-crossplane", "v2-45")
#: relative resolution of a number printed with 12 significant digits
PRINTED = 1e-11
CYLINDERS = (1, 2)


def hand(preset: str, number: int) -> tuple[float, float, int]:
    """Rotating mass (throw / rods on its pin), reciprocating mass, rods on the pin."""
    model = build_model(load_engine(preset))
    throw = int(model.cylinder_throw[number - 1])
    rods = 0
    for t in model.cylinder_throw.tolist():
        rods += int(t) == throw
    return (
        float(model.throw_rotating_mass[throw]) / rods,
        float(model.reciprocating_mass[number - 1]),
        rods,
    )


def cli(capsys, preset: str, number: int, factor: str) -> dict:
    args = ["balance-factor", "--engine", preset, "--cylinder", str(number)]
    main([*args, "--balance-factor", factor, "--format", "json"])
    return json.loads(capsys.readouterr().out)


def web(preset: str, number: int, factor: str) -> tuple[float, float]:
    """Bob-weight [kg] and reciprocating mass [kg] of the cylinder as the web page has them."""
    computed = Project.from_preset(preset).compute()
    assert computed is not None and computed.analysis is not None
    settings = dict(DEFAULT_SETTINGS, sc_cylinder=str(number), sc_balance_factor=factor)
    bob = rebalance_study(computed, settings).bob_weight  # new parts = old parts
    study = single_study(computed, settings)
    model = computed.analysis.model
    m_rec = study.primary_force / (model.crank_radius * model.speed**2)
    return bob, m_rec


@pytest.mark.parametrize("preset", PRESETS)
@pytest.mark.parametrize("number", CYLINDERS)
def test_one_cylinder_everywhere(capsys, preset: str, number: int) -> None:
    m_rot, m_rec, rods = hand(preset, number)
    assert rods == 2, f"{preset}: a V engine has two rods on each pin"
    api = cylinder_of(build_model(load_engine(preset)), number)
    assert api.rods_on_pin == rods
    assert api.rotating_mass == pytest.approx(m_rot, rel=1e-12)
    assert api.reciprocating_mass == pytest.approx(m_rec, rel=1e-12)
    for factor in ("0", "0.5", "1"):
        f = float(factor)
        bob = m_rot + f * m_rec
        printed = cli(capsys, preset, number, factor)
        # the JSON prints 12 significant digits
        assert printed["reciprocating_mass_kg"] == pytest.approx(m_rec, rel=PRINTED)
        assert printed["bob_weight"]["mass_kg"] == pytest.approx(bob, rel=PRINTED)
        web_bob, web_rec = web(preset, number, factor)
        assert web_bob == pytest.approx(bob, rel=1e-12)
        assert web_rec == pytest.approx(m_rec, rel=1e-9)
    # at f_b = 0 the bob-weight is the rotating mass itself
    assert cli(capsys, preset, number, "0")["bob_weight"]["mass_kg"] == pytest.approx(
        api.rotating_mass, rel=PRINTED
    )


@pytest.mark.parametrize("preset", PRESETS)
def test_shares_add_up_to_the_throw(preset: str) -> None:
    model = build_model(load_engine(preset))
    for throw, mass in enumerate(model.throw_rotating_mass.tolist()):
        on_pin = [k + 1 for k, t in enumerate(model.cylinder_throw.tolist()) if int(t) == throw]
        assert on_pin, f"throw {throw + 1} carries no cylinder"
        total = sum(cylinder_of(model, n).rotating_mass for n in on_pin)
        assert total == pytest.approx(mass, rel=1e-12)
