"""The time-domain verification of a balancing result (issue 26): separate from the
solver, optional, and in agreement with the solver's phasor residuals to round-off."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import list_presets, load_engine
from crankbalance.physics.balance_check import verify
from crankbalance.physics.balancing import CounterweightOptions, ShaftOptions, balance
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import balance_engine

from .conftest import run_cli


@pytest.mark.parametrize("name", list_presets())
def test_verification_agrees_with_the_solver_on_every_preset(name: str) -> None:
    """The engine file's own balancing, and a harder one (individual counterweights with a
    balance factor, a single counter-rotating primary shaft: the Eq. 17 extra set, and a
    secondary pair): every component before and after within round-off of the solver."""
    study = balance_engine(name, verify=True)
    assert study.verification is not None and study.verification.agrees, study.verification
    model = build_model(load_engine(name))
    result = balance(
        model,
        CounterweightOptions(model.crank_radius, method="individual", balance_factor=0.5),
        ShaftOptions(0.03, 0.3, "counter-rotating"),
        ShaftOptions(0.02, 0.25),
    )
    check = verify(model, result)
    assert check.agrees, check
    assert [c.component for c in check.residuals] == [c.component for c in result.residuals]
    # what the solver targeted, the time domain finds cancelled too
    for measured in check.residuals:
        if measured.targeted and measured.component != "order1":
            assert measured.force_after == 0.0 and measured.moment_after == 0.0, measured


def test_verification_finds_a_wrong_mass() -> None:
    """One counterweight a per cent too heavy, one shaft mass turned by a degree: the time
    domain measures what they leave, which the result does not report."""
    model = build_model(load_engine("inline4"))  # a secondary force for the shafts
    result = balance(
        model,
        CounterweightOptions(0.045, angle="optimal", scope="halves"),
        None,
        ShaftOptions(0.03, 0.3),
    )
    assert verify(model, result).agrees
    cw = result.counterweights
    assert cw is not None
    mass = cw.mass.copy()
    mass[2] *= 1.01
    heavy = dataclasses.replace(
        result,
        counterweights=dataclasses.replace(cw, mass=mass),
        rotating_share=cw.moments * np.where(np.arange(cw.count) == 2, 1.01, 1.0),
    )
    check = verify(model, heavy)
    assert not check.agrees
    assert check.residuals[0].force_after > 1.0, "the rotating force left by the extra 1 %"
    secondary = result.secondary
    assert secondary is not None
    shaft = secondary.shafts[1]
    assert shaft.masses, "a counter-rotating secondary mass"
    turned = dataclasses.replace(
        shaft,
        masses=tuple(dataclasses.replace(m, phase=m.phase + np.radians(1.0)) for m in shaft.masses),
    )
    wrong = dataclasses.replace(
        result, secondary=dataclasses.replace(secondary, shafts=(secondary.shafts[0], turned))
    )
    check = verify(model, wrong)
    assert not check.agrees
    assert check.residuals[2].force_after > 0.0 or check.residuals[2].moment_after > 0.0


def test_samples_must_exceed_twice_the_orders() -> None:
    model = build_model(load_engine("inline4"))
    result = balance(model, CounterweightOptions(0.04), orders=8)
    with pytest.raises(InputError, match="samples"):
        verify(model, result, samples=16)
    assert verify(model, result, samples=64).agrees


def test_verification_only_when_asked(capsys: pytest.CaptureFixture[str]) -> None:
    """The JSON gets ``verification`` with --verify only; its components are the
    result's, measured in the time domain; the table prints the agreement."""
    plain = balance_engine("inline6").to_dict()
    assert "verification" not in plain
    code, out, err = run_cli(["balance", "inline6", "--format", "json"], capsys)
    assert code == 0, err and "verification" not in json.loads(out)
    code, out, err = run_cli(["balance", "inline6", "--verify", "--format", "json"], capsys)
    assert code == 0, err
    data = json.loads(out)
    check = data["verification"]
    assert check["agrees"] is True and check["samples"] == 256
    assert [c["component"] for c in check["components"]] == [
        c["component"] for c in data["components"]
    ]
    for measured, solved in zip(check["components"], data["components"], strict=True):
        for key in ("force_before_N", "force_after_N"):
            assert abs(measured[key] - solved[key]) <= check["force_round_off_N"]
        for key in ("moment_before_Nm", "moment_after_Nm"):
            assert abs(measured[key] - solved[key]) <= check["moment_round_off_Nm"]
    code, out, err = run_cli(["balance", "inline6", "--verify"], capsys)
    assert code == 0, err
    assert "Time-domain verification" in out and "agree to round-off" in out
    code, out, err = run_cli(["balance", "inline6"], capsys)
    assert code == 0 and "Time-domain verification" not in out
