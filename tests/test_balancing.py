"""Balancing solver: closed forms against the general solver, degenerate cases, CLI."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.physics.balancing import (
    CounterweightOptions,
    ShaftOptions,
    balance,
    counterweight_angle_sweep,
)
from crankbalance.physics.kinematics import harmonic_coefficients
from crankbalance.schema.engine import spec_from_dict
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import balance_engine

from .conftest import EXAMPLES, run_cli


def model_of(name: str):  # noqa: ANN201
    return build_model(load_engine(name))


def test_single_cylinder_counter_rotating_shaft_and_half_balance() -> None:
    """Single cylinder: f_b = 0.5 cancels the forward half of the primary on the crank, one
    counter-rotating shaft the backward half (textbook); no primary is left."""
    m = model_of("single")
    res = balance(
        m, CounterweightOptions(0.03, balance_factor=0.5), ShaftOptions(0.03, 0.1, "pair")
    )
    co, counter = res.primary.shafts
    assert co.masses == (), "f_b = 0.5 leaves nothing co-rotating"
    p = m.reciprocating_mass[0] * m.crank_radius
    assert counter.mass * 0.03 == pytest.approx(p / 2, rel=1e-12), "shaft unbalance m r / 2"
    assert res.residual("order1").force_after == 0.0
    assert res.residual("rotating").force_after == 0.0


def test_vee90_twin_rotating_plus_one_cylinder() -> None:
    """90-degree V-twin: counterweights for all the rotating mass plus one cylinder's
    reciprocating mass (balance factor 0.5 of the pin's two) leave no primary (textbook)."""
    m = model_of("v2-90")
    res = balance(m, CounterweightOptions(0.025, balance_factor=0.5))
    assert res.residual("order1").force_before > 1000
    assert res.residual("order1").force_after == 0.0
    expected = (m.throw_rotating_mass[0] + m.reciprocating_mass[0]) * m.crank_radius / 0.025
    assert res.counterweights.mass.sum() == pytest.approx(expected, rel=1e-12)


def test_inline4_lanchester_shafts() -> None:
    """Inline-4: each Lanchester shaft carries A2 m r / 2 of unbalance (one mass mid-shaft)
    and the second order is gone (textbook, e.g. Taylor vol. 2)."""
    m = model_of("inline4")
    res = balance(m, None, None, ShaftOptions(0.02, 0.2, "pair"))
    a2 = harmonic_coefficients(m.rod_ratio, 2)[1].real
    for shaft in res.secondary.shafts:
        (mass,) = shaft.masses
        assert mass.position == 0.0
        unbalance = a2 * m.reciprocating_mass[0] * m.crank_radius / 2
        assert mass.mass * 0.02 == pytest.approx(unbalance, rel=1e-12), "A2 m r / 2"
    assert res.residual("order2").force_after == 0.0
    assert res.residual("order4").force_after > 0, "the fourth order is left (reported)"


def test_crossplane_v8_primary_couple_by_counterweights() -> None:
    m = model_of("v8-crossplane")
    res = balance(m, CounterweightOptions(0.05, balance_factor=0.5, method="individual"))
    assert res.residual("order1").moment_before > 1000
    assert res.residual("order1").moment_after == 0.0
    assert res.residual("rotating").moment_after == 0.0
    res = balance(m, CounterweightOptions(0.05, balance_factor=0.5, angle="optimal"))
    assert res.residual("order1").moment_after == 0.0


def test_single_counter_rotating_shaft_eq17_done_right() -> None:
    """A single counter-rotating primary shaft with its co-rotating half on the crank (Eq. 17
    with the same first moment and couple): no primary force or couple left."""
    spec = load_engine(EXAMPLES / "paper_inline3.toml")
    study = balance_engine(spec, primary=ShaftOptions(0.03, 0.2, "counter-rotating"))
    res = study.result
    assert res.extra_counterweights is not None
    assert res.residual("order1").moment_after == 0.0
    assert res.residual("order1").force_after == 0.0
    assert len(res.primary.shafts) == 1 and res.primary.shafts[0].sense == -1


def test_already_balanced_needs_no_mass() -> None:
    m = model_of("inline6")
    res = balance(m, CounterweightOptions(0.04, scope="whole"))
    assert np.all(res.counterweights.mass == 0.0)
    assert "already balanced" in res.counterweights.note
    res = balance(m, CounterweightOptions(0.04))  # auto: the whole crank, none needed
    assert res.counterweights.scope == "whole" and not res.counterweights.mass.any()
    assert any(note.startswith("no counterweights: ") for note in res.notes)
    assert any('scope = "halves"' in note for note in res.notes)
    res = balance(m, CounterweightOptions(0.04, scope="halves"))  # asked: each half
    assert res.counterweights.scope == "halves" and res.counterweights.mass.min() > 0
    assert res.residual("rotating").moment_after == 0.0
    assert not any(note.startswith("no counterweights: ") for note in res.notes)


def test_counterweights_in_one_plane_cannot_cancel_a_couple() -> None:
    m = model_of("paper-inline3")
    with pytest.raises(InputError, match="one plane"):
        balance(m, CounterweightOptions(0.03, webs=(1, 0, 0, 0, 0, 0)))


def test_no_nan_for_zero_targets() -> None:
    data = balance_engine(
        "boxer6", primary=ShaftOptions(0.03, 0.2), secondary=ShaftOptions(0.03, 0.2)
    ).to_dict()
    text = json.dumps(data)
    assert "NaN" not in text and "Infinity" not in text
    assert data["primary_shafts"]["mass_kg"] == 0.0


def test_angle_sweep_matches_solver() -> None:
    m = model_of("paper-inline3")
    opts = CounterweightOptions(0.03, webs=(1, 1, 0, 0, 1, 1))
    sweep = counterweight_angle_sweep(m, opts, np.radians(np.arange(0, 90.05, 0.1)))
    k = int(np.argmin(sweep.residual))
    assert math.degrees(sweep.angle[k]) == pytest.approx(30.0, abs=0.051)
    solved = balance(m, CounterweightOptions(0.03, webs=(1, 1, 0, 0, 1, 1), angle=sweep.angle[k]))
    assert solved.counterweights.mass[0] == pytest.approx(sweep.mass[k], rel=1e-12)


def test_balance_cli_json(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(
        ["balance", str(EXAMPLES / "paper_inline3.toml"), "--format", "json"], capsys
    )
    assert code == 0, err
    data = json.loads(out)
    assert data["schema"] == "crankbalance.balance/2"
    assert {"mass_kg", "angle_deg", "count"} <= set(data["counterweight"])
    assert {
        "rotating_force_N",
        "rotating_moment_Nm",
        "order1_force_N",
        "order1_moment_Nm",
        "order2_force_N",
        "order2_moment_Nm",
    } == set(data["residual"])
    code, out, err = run_cli(["balance", "inline4"], capsys)
    assert code == 0 and "Crank counterweights" in out


@pytest.mark.parametrize(
    "args,needle",
    [
        (["balance", "inline4", "--angle", "30 kg"], "--angle"),
        (["balance", "inline4", "--balance-factor", "3"], "--balance-factor"),
        (["balance", "inline4", "--scope", "thirds"], "--scope"),
        (["balance", "paper-inline3", "--scope", "halves"], "counterweights.scope"),
    ],
)
def test_balance_cli_bad_input(
    args: list[str], needle: str, capsys: pytest.CaptureFixture[str]
) -> None:
    code, _out, err = run_cli(args, capsys)
    assert code == 2 and needle in err and "Traceback" not in err


def test_spec_counterweight_options() -> None:
    data = json.loads(
        json.dumps(
            spec_from_dict(
                {
                    "speed": "3000 rpm",
                    "crank_train": {
                        "layout": "inline",
                        "cylinders": 2,
                        "crank_radius": "40 mm",
                        "rod_length": "130 mm",
                        "crank_pitch": "80 mm",
                        "firing_order": [1, 2],
                    },
                    "masses": {"reciprocating": "500 g", "rotating": "700 g"},
                    "counterweights": {
                        "cg_radius": "35 mm",
                        "angle": "optimal",
                        "method": "individual",
                        "web_offset": "15 mm",
                        "balance_factor": 0.5,
                    },
                }
            ).to_data()
        )
    )
    assert data["counterweights"]["web_offset"] == "15 mm"


def test_shaft_requirement_from_the_solver(capsys: pytest.CaptureFixture[str]) -> None:
    """The balance-shaft designer takes its unbalance from the balancing solver: inline-4
    Lanchester shafts A2 m r / 2 at 2w; the paper inline-3's single counter-rotating shaft
    sqrt(3) m r a / (2 l) at w (Kim (2018), Eq. 12)."""
    from crankbalance.physics.balance_shaft import inline3_couple_unbalance
    from crankbalance.studies.requirements import shaft_requirement

    m = model_of("inline4")
    a2 = harmonic_coefficients(m.rod_ratio, 2)[1].real
    need = shaft_requirement("inline4", 2, 0.3)
    assert need.unbalance == pytest.approx(a2 * m.reciprocating_mass[0] * m.crank_radius / 2)
    assert need.speed == pytest.approx(2 * m.speed)
    need = shaft_requirement(EXAMPLES / "paper_inline3.toml", 1, 0.2)
    assert need.unbalance == pytest.approx(inline3_couple_unbalance(0.94, 0.04, 0.09, 0.2))
    code, out, err = run_cli(
        [
            "shaft",
            "inline4",
            "--engine",
            "inline4",
            "--length",
            "300 mm",
            "--diameter",
            "25 mm",
            "--format",
            "json",
        ],
        capsys,
    )
    assert code == 0, err
    assert json.loads(out)["input"]["unbalance_kg_m"] == pytest.approx(
        a2 * m.reciprocating_mass[0] * m.crank_radius / 2
    )
    shaft = ["shaft", "inline4", "--engine", "v12-60", "--length", "300 mm", "--diameter", "25 mm"]
    code, _out, err = run_cli([*shaft, "--order", "2"], capsys)
    assert code == 2 and "--engine = 'v12-60': has no order-2 unbalance" in err
    code, _out, err = run_cli(shaft, capsys)  # the engine's order: it has none
    assert code == 2 and "no free first- or second-order force or moment" in err


def test_balance_with_one_order_still_checks_orders_1_and_2() -> None:
    data = balance_engine("inline4", 1).to_dict()
    assert data["residual"]["order2_force_N"] > 0, "inline-4 second order, no shafts"
    with pytest.raises(InputError, match="orders"):
        balance_engine("inline4", 0)
