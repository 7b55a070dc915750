"""Counterweights for offset cylinders (issue 27): the balance factor is defined on the
forward-rotating first order of every cylinder, its offset included, so 0.5 cancels the
forward primary of a VR6 and a W16 from VR banks as it does of a centred engine.

Checked two ways that share nothing with the solver: an independent slider-crank sum
written here (each piston's position from the crank geometry, its first harmonic by a
discrete Fourier transform, no code of crankbalance's kinematics or shaking), and the
time-domain verification :func:`crankbalance.physics.balance_check.verify`.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from crankbalance.physics.balance_batch import balance_batch
from crankbalance.physics.balance_check import verify
from crankbalance.physics.balancing import CounterweightOptions, balance
from crankbalance.physics.model import EngineModel, stack_models
from crankbalance.studies.engine import build_model, load_engine

SAMPLES = 512


def _model(name: str) -> EngineModel:
    return build_model(load_engine(name))


def _slider_crank_first_order(model: EngineModel) -> tuple[complex, complex, complex, complex]:
    """Forward and backward first-order phasors of the reciprocating inertia force [N] and
    couple [N·m] by a plain slider-crank sum: cylinder c's piston stands on the axis at
    bank angle beta_c, the axis passing at e_c beside the crank axis on the side the pin
    moves toward after top dead centre; its distance from the crank axis along the
    cylinder axis is s = r cos(psi) + sqrt(l^2 - (r sin(psi) - e)^2), psi the pin's angle
    from the axis. The inertia force -m s'' e^{i beta} has its order-n phasor
    m (n w)^2 S_n e^{i beta}, S_n the Fourier coefficient of s."""
    theta = 2 * np.pi * np.arange(SAMPLES) / SAMPLES
    r, length, w = model.crank_radius, model.rod_length, model.speed
    pin = model.throw_angle[model.cylinder_throw]
    psi = theta[:, None] + (pin - model.cylinder_bank)[None, :]
    e = model.cylinder_offset[None, :]
    s = r * np.cos(psi) + np.sqrt(length**2 - (r * np.sin(psi) - e) ** 2)
    spectrum = np.fft.fft(s, axis=0) / SAMPLES
    weight = model.reciprocating_mass * w**2 * np.exp(1j * model.cylinder_bank)
    forward = weight * spectrum[1]
    backward = weight * spectrum[-1]
    y = model.cylinder_position
    return (
        complex(forward.sum()),
        complex(backward.sum()),
        complex((forward * y).sum()),
        complex((backward * y).sum()),
    )


def _first_order_after(model: EngineModel, moments: np.ndarray, position: np.ndarray):
    """Forward first-order force and couple of the rotating masses, the reciprocating
    masses (slider-crank sum) and counterweights of first moments ``moments`` at
    ``position``: all the crank-speed forward phasor there is."""
    w2 = model.speed**2
    turn = model.crank_radius * w2 * np.exp(1j * model.throw_angle)
    rot_f = (model.throw_rotating_mass * turn).sum()
    rot_c = (model.throw_rotating_moment * turn).sum()
    fwd, _, cfwd, _ = _slider_crank_first_order(model)
    return (
        rot_f + fwd + w2 * moments.sum(),
        rot_c + cfwd + w2 * (moments * position).sum(),
    )


@pytest.mark.parametrize("name", ["vr6", "w16", "w12-vw"])
def test_slider_crank_sum_is_the_tools_first_order(name: str) -> None:
    """The independent sum agrees with the free forces it checks (sign conventions)."""
    from crankbalance.physics.shaking import free_forces

    model = _model(name)
    forces = free_forces(model, 2)
    fwd, bwd, cfwd, cbwd = _slider_crank_first_order(model)
    scale = abs(cfwd) + abs(cbwd)
    assert scale > 100.0  # a first-order couple there is
    assert abs(cfwd - forces.couple_forward[0]) <= 1e-9 * scale
    assert abs(cbwd - forces.couple_backward[0]) <= 1e-9 * scale
    assert abs(fwd - forces.force_forward[0]) <= 1e-9 * scale / 0.1
    assert abs(bwd - forces.force_backward[0]) <= 1e-9 * scale / 0.1


@pytest.mark.parametrize("name", ["vr6", "w16"])
@pytest.mark.parametrize("method", ["pattern", "individual"])
@pytest.mark.parametrize("factor", [0.5, 0.3])
def test_balance_factor_scales_the_forward_primary_of_offset_cylinders(
    name: str, method: str, factor: float
) -> None:
    """With a balance factor f the forward first order left is (1 - 2f) times the
    reciprocating masses' own (0.5: none), the backward one untouched, in the
    slider-crank sum; the solver's residual says the same and verify agrees."""
    model = _model(name)
    assert np.any(model.cylinder_offset != 0)
    options = CounterweightOptions(
        cg_radius=model.crank_radius, balance_factor=factor, method=method, scope="whole"
    )
    result = balance(model, options)
    cw = result.counterweights
    assert cw is not None
    fwd, bwd, cfwd, cbwd = _slider_crank_first_order(model)
    force, couple = _first_order_after(model, cw.moments, cw.position)
    scale = abs(cfwd) + abs(cbwd)
    assert abs(couple - (1 - 2 * factor) * cfwd) <= 1e-9 * scale
    length = float(np.ptp(model.throw_position))
    assert abs(force - (1 - 2 * factor) * fwd) <= 1e-9 * scale / length
    # the solver's order-1 moment after is |forward left| + |backward|
    order1 = result.residual("order1")
    expected = abs((1 - 2 * factor) * cfwd) + abs(cbwd)
    assert order1.moment_after == pytest.approx(expected, rel=1e-9, abs=1e-9 * scale)
    assert not any("cannot reach" in note for note in result.notes)
    checked = verify(model, result)
    assert checked.agrees
    assert checked.residuals[1].moment_after == pytest.approx(expected, rel=1e-9, abs=1e-9 * scale)


def test_w16_at_half_leaves_no_first_order_couple() -> None:
    """The issue's W16: its first-order couple is all forward, so 0.5 leaves none (it
    grew from 310 to 632 N·m with the counterweights opposite the pins)."""
    model = _model("w16")
    result = balance(model, CounterweightOptions(cg_radius=model.crank_radius, balance_factor=0.5))
    order1 = result.residual("order1")
    assert order1.moment_before > 300.0
    assert order1.moment_after == 0.0


def test_centred_engine_unchanged_by_offset_rule() -> None:
    """A centred engine's first harmonic is exactly the pin's (c1 = 1): the same
    counterweights, to the last bit, as the paper's m_rec r e^{i phi}."""
    model = _model("vr6")
    centred = dataclasses.replace(model, cylinder_offset=np.zeros_like(model.cylinder_offset))
    options = CounterweightOptions(cg_radius=model.crank_radius, balance_factor=0.5, scope="whole")
    got = balance(centred, options).counterweights
    assert got is not None
    # by hand: the pins' reciprocating masses, half of them, with the rotating masses
    w2 = centred.speed**2
    fwd, _, cfwd, _ = _slider_crank_first_order(centred)
    force, couple = _first_order_after(centred, got.moments, got.position)
    assert abs(force) <= 1e-9 * abs(cfwd) / 0.1
    assert abs(couple) <= 1e-9 * abs(cfwd)
    assert w2 > 0


def test_batch_gives_the_one_engine_counterweights() -> None:
    """The one solver: a batch of the VR6 and its mirror gives each engine's masses."""
    model = _model("vr6")
    other = dataclasses.replace(model, cylinder_offset=-model.cylinder_offset)
    options = CounterweightOptions(cg_radius=model.crank_radius, balance_factor=0.5)
    batch = balance_batch(stack_models([model, other]), options)
    assert batch.counterweights is not None
    for i, each in enumerate((model, other)):
        one = balance(each, options).counterweights
        assert one is not None
        np.testing.assert_allclose(batch.counterweights.mass[i], one.mass, rtol=1e-12)
        np.testing.assert_allclose(batch.counterweights.direction[i], one.direction, atol=1e-12)


# --------------------------------------------------------------------------- what is left
def test_pattern_that_cannot_reach_its_target_says_so() -> None:
    """Equal counterweights at a fixed 10 deg on the VR6 at 0.5: the note says the target
    is missed and by how much, and what is left names the way to reach it."""
    model = _model("vr6")
    options = CounterweightOptions(cg_radius=model.crank_radius, balance_factor=0.5, angle=0.17)
    result = balance(model, options)
    missed = [n for n in result.notes if "cannot reach their target" in n]
    assert len(missed) == 1 and 'method = "individual"' in missed[0]
    rotating = [r for r in result.remaining if r.component == "rotating"]
    assert rotating and all("individual" in r.next_step for r in rotating)
    # the amounts are the solver's forward and backward parts, which verify measures
    order1 = result.residual("order1")
    assert order1.moment_forward_after > 0 and order1.moment_backward_after > 300.0
    checked = verify(model, result)
    assert checked.agrees
    assert checked.residuals[1].moment_forward_after == pytest.approx(
        order1.moment_forward_after, rel=1e-9
    )


def test_default_balance_factor_leaves_the_forward_primary_and_says_what_removes_it() -> None:
    from crankbalance.studies.engine import balance_engine

    study = balance_engine("v2-90")
    left = {(r.component, r.quantity, r.rotation): r for r in study.result.remaining}
    forward = left[("order1", "force", "forward")]
    assert forward.amount > 10e3 and "--balance-factor 0.5" in forward.next_step
    assert ("order1", "force", "backward") not in left  # the 90-degree twin's is all forward
    data = study.to_dict()
    assert data["remaining"][0]["text"] == forward.text
    assert data["remaining"][0]["unit"] == "N"
    half = balance_engine("v2-90", balance_factor=0.5).result
    assert not [r for r in half.remaining if r.order == 1]


@pytest.mark.parametrize("name", ["v12-60", "boxer6", "inline4"])
def test_balanced_engines_get_no_counterweights_unless_asked(name: str) -> None:
    from crankbalance.studies.engine import balance_engine

    result = balance_engine(name).result
    assert result.counterweights is not None and not result.counterweights.mass.any()
    assert any(n.startswith("no counterweights: ") for n in result.notes)
    asked = balance_engine(name, scope="halves").result
    assert asked.counterweights is not None and asked.counterweights.mass.min() > 0


def test_balance_table_says_what_is_left(capsys: pytest.CaptureFixture[str]) -> None:
    from crankbalance.cli import main

    main(["balance", "v2-90"])
    out = capsys.readouterr().out
    assert "What is left, and what would remove it:" in out
    assert "order 1 force, forward-rotating" in out and "--balance-factor 0.5" in out
    main(["balance", "v12-60"])
    out = capsys.readouterr().out
    assert "none: already balanced" in out and 'scope = "halves"' in out


def test_what_is_left_is_written_in_the_output_vocabulary() -> None:
    """Each line of ``remaining`` gives its amount as ``results.number`` writes it: four
    significant digits, 10 000 and more whole (the W12's free secondary force, 14 369 N,
    was '1.437e+04 N' on every edge that shows the line)."""
    from crankbalance.results import number
    from crankbalance.studies.engine import balance_engine

    for name in ("single", "inline4", "w12", "radial9"):
        for line in balance_engine(name).result.remaining:
            unit = "N" if line.quantity == "force" else "N·m"
            assert line.text.endswith(f": {number(line.amount)} {unit}"), line.text
            assert "e+" not in line.text, line.text
    big = [r for r in balance_engine("w12").result.remaining if r.amount >= 1e4]
    assert big, "the W12's free secondary force exceeds 10 000 N"
