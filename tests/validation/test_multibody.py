"""Issue 17 item 6: crankbalance's free forces and moments against a multibody simulation.

``validation/multibody.py`` builds each engine in EXUDYN (rigid crank, rods with the
two-mass-equivalent inertia, pistons on prismatic joints with their offsets and axial
positions), drives the crank, sums the ground reactions and takes their Fourier series;
every order's force and moment phasor must agree with
:func:`crankbalance.physics.shaking.free_forces` within 0.5 % of the order's amplitude or 1e-4 of
the largest first-order amplitude (``docs/validation.md``).

EXUDYN is in the ``validation`` extra, which ``.ci/run`` installs: where it is missing the
test fails (it is not skipped), saying how to install it.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib.util
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
HARNESS = ROOT / "validation" / "multibody.py"


def _load() -> ModuleType:
    spec = importlib.util.spec_from_file_location("crankbalance_validation_multibody", HARNESS)
    assert spec is not None and spec.loader is not None, f"cannot load {HARNESS}"
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up by name
    spec.loader.exec_module(module)
    return module


multibody = _load()


def _require_exudyn() -> None:
    try:
        import exudyn  # noqa: F401
    except ImportError as missing:
        pytest.fail(
            f"EXUDYN is not installed ({missing}); the multibody cross-check needs the "
            "validation extra: pip install -e .[validation]  (.ci/run installs it)"
        )


@functools.cache
def _run(engine: str) -> tuple[Any, list]:
    return multibody.run(engine)


def _failures(rows: list) -> str:
    return "\n".join(
        f"{r.engine} {r.quantity} order {r.order}: crankbalance {r.crankbalance:.6g}, EXUDYN "
        f"{r.exudyn:.6g}, amplitude difference {r.difference:.3g}, phasor difference "
        f"{r.phasor_error:.3g}, limit {r.limit:.3g}"
        for r in rows
        if not r.passed
    )


@pytest.mark.parametrize("engine", multibody.TEST_ENGINES)
def test_every_order_agrees_with_exudyn(engine: str) -> None:
    _require_exudyn()
    sim, rows = _run(engine)
    assert len(rows) == 3 * multibody.ORDERS  # force, moment and roll
    assert not _failures(rows), (
        f"{engine}: crankbalance against EXUDYN (issue 17 acceptance: 0.5 % of the order's "
        f"amplitude or 1e-4 of the largest first-order amplitude):\n{_failures(rows)}"
    )
    # the single run with the finest step passes too: the extrapolation only sharpens it
    raw = multibody.compare(engine, multibody.ENGINES[engine][1](), sim.raw)
    assert not _failures(raw), f"{engine}, without the extrapolation:\n{_failures(raw)}"
    # the engine has a load far above its limit, which the simulation reproduced: not
    # zeros that pass everywhere
    biggest = max(rows, key=lambda r: r.crankbalance / r.limit)
    assert biggest.crankbalance > 100 * biggest.limit, f"{engine}: no load above the floor"


def test_the_roll_moment_is_the_simulations() -> None:
    """Issue 27: the roll moment about the crank axis (the reaction of the inertia torque
    and the offset cylinders' side forces) against the simulation's ground reactions
    without the drive: the offset single's every order, and the VR6's third (its six
    cylinders' inertia torques add in the third order) with its first two cancelled; the
    same engines without the offsets' moment arm fail."""
    _require_exudyn()
    for engine in ("single-desaxe", "vr6"):
        sim, rows = _run(engine)
        roll = [r for r in rows if r.quantity == "roll"]
        assert len(roll) == multibody.ORDERS and not _failures(roll), _failures(roll)
        biggest = max(roll, key=lambda r: r.crankbalance / r.limit)
        assert biggest.exudyn > 100 * biggest.limit, f"{engine}: no roll above the floor"
        model = multibody.ENGINES[engine][1]()
        centred = dataclasses.replace(model, cylinder_offset=0 * model.cylinder_offset)
        wrong = [r for r in multibody.compare(engine, centred, sim.phasors) if r.quantity == "roll"]
        assert _failures(wrong), f"{engine}: the roll without offsets passed"


def test_the_comparison_sees_a_one_percent_change() -> None:
    """The same simulation against a model with 1 % more reciprocating mass, or its pistons'
    offset reversed, fails: the limits are tight enough to see a real error."""
    _require_exudyn()
    sim, _rows = _run("single-desaxe")
    model = multibody.ENGINES["single-desaxe"][1]()
    heavier = dataclasses.replace(model, reciprocating_mass=1.01 * model.reciprocating_mass)
    mirrored = dataclasses.replace(model, cylinder_offset=-model.cylinder_offset)
    for wrong, what in ((heavier, "1 % heavier pistons"), (mirrored, "offset reversed")):
        rows = multibody.compare("single-desaxe", wrong, sim.phasors)
        assert _failures(rows), f"a model with {what} passed the comparison"


def test_master_and_link_rods_are_not_the_simple_radial() -> None:
    """The articulated radial's simulation (master rod carrying the link rods) agrees with
    crankbalance's articulated model and not with the simple one (every rod on the pin),
    whose second order is a tenth of it: the multibody model sees the articulation."""
    _require_exudyn()
    sim, rows = _run("radial5-kinner")
    assert not _failures(rows)
    model = multibody.ENGINES["radial5-kinner"][1]()
    assert model.articulation is not None
    simple = multibody.compare(
        "radial5-kinner", dataclasses.replace(model, articulation=None), sim.phasors
    )
    second = next(r for r in simple if r.quantity == "force" and r.order == 2)
    assert not second.passed, "the simple radial's second order matched the articulated one"


def test_the_vr6_rows_offsets_are_seen() -> None:
    """The VR6's third-order force comes from its rows' bore offsets (-/+12.5 mm): the
    simulation agrees with crankbalance's model of them and not with the same engine
    without offsets (no third order) or with one offset for both rows."""
    _require_exudyn()
    sim, rows = _run("vr6")
    assert not _failures(rows)
    model = multibody.ENGINES["vr6"][1]()
    assert np.ptp(model.cylinder_offset) > 0, "the VR6 preset lost its row offsets"
    third = next(r for r in rows if r.quantity == "force" and r.order == 3)
    assert third.exudyn > 10 * third.limit, "the third order is not above the floor"
    for wrong in (0 * model.cylinder_offset, np.abs(model.cylinder_offset)):
        other = multibody.compare(
            "vr6", dataclasses.replace(model, cylinder_offset=wrong), sim.phasors
        )
        third = next(r for r in other if r.quantity == "force" and r.order == 3)
        assert not third.passed, f"offsets {wrong} passed the third order"


def test_side_by_side_rods_and_the_moment_reference() -> None:
    """The side-by-side twin's rocking couple (rods 20 mm apart by the engine file's
    rod_positions) is in the simulation and missing from the same twin with its rods in one
    plane; and crankbalance's moments about a point moved by ``moment_reference`` are the
    simulation's moments taken about that point."""
    _require_exudyn()
    sim, rows = _run("v2-45-side-by-side")
    assert not _failures(rows)
    model = multibody.ENGINES["v2-45-side-by-side"][1]()
    np.testing.assert_allclose(model.cylinder_axial, [-0.010, 0.010])
    first = next(r for r in rows if r.quantity == "moment" and r.order == 1)
    assert first.exudyn > 10 * first.limit, "no rocking couple above the floor"
    flat = dataclasses.replace(model, cylinder_axial=np.zeros(2))
    assert _failures(multibody.compare("flat", flat, sim.phasors)), "rods in one plane passed"

    text = multibody.preset_text("v2-45").replace(
        'bank_angle = "45 deg"',
        'bank_angle = "45 deg"\nrod_positions = ["-10 mm", "10 mm"]\nmoment_reference = "35 mm"',
    )
    moved = multibody._engine(text)
    assert not _failures(multibody.compare("moved", moved, multibody.about(sim.phasors, 0.035)))
    assert _failures(multibody.compare("moved", moved, sim.phasors)), "the reference did not move"


def test_the_fourier_analysis_reads_a_known_curve_back() -> None:
    """The harness's sampling and sign conventions on a curve whose phasors are known:
    z + i x = F+ e^{i n theta} + F- e^{-i n theta}, couple C = -i (M_z + i M_x)."""
    speed = 100.0
    period = 2 * np.pi / speed
    times = np.arange(0, 2 * 240 + 1) * period / 240
    theta = np.array([multibody.crank_angle(t, speed) for t in times])
    f_plus, f_minus, c_plus = 3.0 - 1.0j, 0.5 + 2.0j, 1.5 + 0.25j
    z_ix = f_plus * np.exp(2j * theta) + f_minus * np.exp(-2j * theta)
    couple = c_plus * np.exp(1j * theta)
    moment_c = 1j * couple  # M_z + i M_x
    force = np.column_stack([z_ix.imag, np.zeros_like(theta), z_ix.real])
    moment = np.column_stack([moment_c.imag, np.zeros_like(theta), moment_c.real])
    found = multibody._fourier(times, force, moment, speed, 3)
    np.testing.assert_allclose(found.force_forward, [0, f_plus, 0], atol=1e-12)
    np.testing.assert_allclose(found.force_backward, [0, f_minus, 0], atol=1e-12)
    np.testing.assert_allclose(found.couple_forward, [c_plus, 0, 0], atol=1e-12)
    np.testing.assert_allclose(found.couple_backward, [0, 0, 0], atol=1e-12)
    # the prescribed crank angle: at rest at 0, speed w after one revolution's time
    assert multibody.crank_angle(0.0, speed) == 0.0
    h = 1e-7
    rate = multibody.crank_angle(period + h, speed) - multibody.crank_angle(period - h, speed)
    assert rate / (2 * h) == pytest.approx(speed, rel=1e-6)
    assert multibody.crank_angle(period, speed) == pytest.approx(np.pi)


@pytest.mark.parametrize("engine", ["vr6", "w16"])
def test_counterweights_at_half_cancel_the_forward_primary_exudyn_sees(engine: str) -> None:
    """Issue 27: crankbalance's counterweights at a balance factor of 0.5, added to the
    simulated crank train as the point masses they are (a mass m at radius rho turning
    with the crank adds m rho w^2 e^{i psi} to the forward first order, y times that to
    the couple), cancel the forward first-order force and couple of the simulation (the
    rotating masses and the offset pistons together) within the acceptance; the
    counterweights opposite each crankpin (the rule before issue 27) do not."""
    _require_exudyn()
    from crankbalance.physics.balancing import CounterweightOptions, balance

    sim, rows = _run(engine)
    assert not _failures(rows)
    model = multibody.ENGINES[engine][1]()
    options = CounterweightOptions(cg_radius=model.crank_radius, balance_factor=0.5)
    cw = balance(model, options).counterweights
    assert cw is not None
    w2 = model.speed**2
    force_scale, moment_scale = multibody.first_order_scales(model, multibody.reference(model))
    simulated = sim.phasors
    force = simulated.force_forward[0] + w2 * cw.moments.sum()
    couple = simulated.couple_forward[0] + w2 * (cw.moments * cw.position).sum()
    assert abs(force) <= multibody.FLOOR * force_scale
    assert abs(couple) <= multibody.FLOOR * moment_scale
    # the old rule: half of each pin's reciprocating mass opposite the pin, on top of the
    # share that carries the rotating masses
    share = balance(model, dataclasses.replace(options, balance_factor=0.0)).counterweights
    assert share is not None
    pins = np.exp(1j * model.throw_angle[model.cylinder_throw])
    old = 0.5 * model.reciprocating_mass * model.crank_radius * pins
    old_couple = simulated.couple_forward[0] + w2 * (
        (share.moments * share.position).sum() - (old * model.cylinder_position).sum()
    )
    assert abs(old_couple) > 100 * multibody.FLOOR * moment_scale
