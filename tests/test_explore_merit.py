"""Figures of merit of the explorer (explore.merit), batched, against the one-engine
analysis and balancing solver and against closed forms of known engines.

The candidates are built here by hand from presets (throw angles and firing orders of
known engines) and from random cranks: the enumeration (explore.orders) is tested on its
own.
"""

from __future__ import annotations

import functools
import math
from dataclasses import replace

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.physics.balancing import CounterweightOptions, ShaftOptions, balance
from crankbalance.physics.explore import merit as merit_module
from crankbalance.physics.explore import orders as orders_module
from crankbalance.physics.explore.candidates import Candidates
from crankbalance.physics.explore.merit import (
    TORSION_ASSUMPTION,
    bank_interval_deviation,
    column_names,
    interval_deviation,
    merit,
    mode_weights,
    torsion_orders,
)
from crankbalance.physics.explore.rank import parse_filter
from crankbalance.physics.explore.work import column_count, plan
from crankbalance.physics.kinematics import harmonic_coefficients
from crankbalance.physics.model import EngineModel
from crankbalance.studies.engine import analyze, as_model

PI = math.pi


def fire_angles(model: EngineModel, order: tuple[int, ...]) -> np.ndarray:
    """Even firing: the k-th cylinder of ``order`` fires at k cycle / C."""
    n = model.cylinders
    cycle = PI * model.strokes
    fire = np.empty(n)
    fire[np.array(order) - 1] = np.arange(n) * cycle / n
    return fire


def batch(models: list[EngineModel]) -> Candidates:
    """Candidates of one topology from engine models (their cranks and firing orders)."""
    first = models[0]
    throw = np.array([np.mod(m.throw_angle - m.throw_angle[0], 2 * PI) for m in models])
    return Candidates(
        topology=first,
        throw_angle=throw,
        firing_order=np.array([m.firing_order for m in models]),
        fire_angle=np.array([fire_angles(m, m.firing_order) for m in models]),
        equivalents=np.ones(len(models), dtype=np.int64),
        index=np.arange(len(models)),
    )


def one_cylinder_force(model: EngineModel, order: int) -> float:
    """Largest force of one order of one cylinder of ``model`` (cylinder 1) [N]."""
    c = harmonic_coefficients(
        model.rod_ratio,
        order,
        model.cylinder_offset[0] / model.crank_radius,
        model.kinematics,  # type: ignore[arg-type]
    )
    return float(model.reciprocating_mass[0] * model.crank_radius * model.speed**2) * abs(
        c[order - 1]
    )


def test_inline4_flat_crank_closed_form() -> None:
    """Second-order force 4 m r w^2 lambda (first-order kinematics), nothing else free; the
    torsional excitation of the even-firing four: the major orders 2, 4, ... add, the rest
    cancel."""
    model = replace(as_model("inline4"), kinematics="first-order")
    out = merit(batch([model]), target="none")
    m, r, w = model.reciprocating_mass[0], model.crank_radius, model.speed
    assert out["F2_N"][0] == pytest.approx(4 * m * r * w**2 * model.rod_ratio, rel=1e-12)
    assert out["F2f_N"][0] == pytest.approx(out["F2b_N"][0], rel=1e-12)  # a line, not a circle
    assert out["F2_N"][0] == pytest.approx(4 * one_cylinder_force(model, 2), rel=1e-12)
    for n in range(1, 9):
        assert out[f"M{n}_Nm"][0] == 0.0
        if n != 2:
            assert out[f"F{n}_N"][0] == 0.0
    assert out["Frot_N"][0] == 0.0 and out["Mrot_Nm"][0] == 0.0
    assert out["mirror_rad"][0] == 0.0
    assert out["interval_dev_rad"][0] == 0.0
    for k in torsion_orders(4, 8):
        name = f"X{int(k)}" if k == int(k) else f"X{int(k)}p5"
        assert out[name][0] == pytest.approx(1.0 if k % 2 == 0 else 0.0, abs=1e-12), name


def test_inline4_exact_kinematics_four_times_one_cylinder() -> None:
    model = as_model("inline4")
    out = merit(batch([model]), target="none")
    for n in (2, 4, 6, 8):
        assert out[f"F{n}_N"][0] == pytest.approx(4 * one_cylinder_force(model, n), rel=1e-9)


def test_inline6_no_free_force_or_moment_of_orders_1_2() -> None:
    """The 120-degree mirror crank has none; the same six with the cylinders firing in
    turn along the crank (a star crank, not mirror-symmetric) has free moments, and the
    filter of the known result keeps the first and drops the second."""
    six = as_model("inline6")
    in_turn = replace(six, throw_angle=np.mod(-np.arange(6) * 4 * PI / 6, 2 * PI))
    in_turn = replace(in_turn, firing_order=(1, 2, 3, 4, 5, 6))
    out = merit(batch([six, in_turn]), target="none")
    for name in ("F1_N", "F2_N", "M1_Nm", "M2_Nm", "Frot_N", "Mrot_Nm", "mirror_rad"):
        assert out[name][0] == 0.0, name
    assert out["F1_N"][1] == 0.0 and out["F2_N"][1] == 0.0  # a star: forces cancel
    assert out["M1_Nm"][1] > 0 and out["M2_Nm"][1] > 0 and out["mirror_rad"][1] > 0
    keep = parse_filter("F1 == 0 and M1 == 0 and F2 == 0 and M2 == 0", out)(out)
    assert keep.tolist() == [True, False]


def test_v8_bank_firing_intervals() -> None:
    """Crossplane: even for the engine, each bank 90-180-270-180 (90 deg off even);
    flat-plane: every bank even."""
    cross, flat = as_model("v8-crossplane"), as_model("v8-flatplane")
    for model, bank in ((cross, PI / 2), (flat, 0.0)):
        out = merit(batch([model]), target="none")
        assert out["interval_dev_rad"][0] == 0.0
        assert out["bank_interval_dev_rad"][0] == pytest.approx(bank, abs=1e-12)
    out = merit(batch([cross, flat]), target="none")
    assert out["mirror_rad"][0] == pytest.approx(PI)  # throws 0 90 270 180: 1 and 4 opposite
    assert out["mirror_rad"][1] == 0.0


def test_flat_four_boxer_sides_fire_180_and_540_apart() -> None:
    """Boxer 1-3-2-4: cylinders 1, 3 on one side fire at 0 and 180 deg, 2, 4 at 360 and
    540 deg: each side 180 then 540 deg apart, 180 deg off even."""
    out = merit(batch([as_model("boxer4")]), target="none")
    assert out["interval_dev_rad"][0] == 0.0
    assert out["bank_interval_dev_rad"][0] == pytest.approx(PI, abs=1e-12)


def random_candidates(topology: EngineModel, size: int, seed: int) -> Candidates:
    """Random cranks, each cylinder firing at one of its top dead centres (uneven firing)."""
    rng = np.random.default_rng(seed)
    t, c = topology.throws, topology.cylinders
    phi = rng.uniform(0, 2 * PI, (size, t))
    phi[:, 0] = 0.0
    tdc = np.mod(topology.cylinder_bank - phi[:, topology.cylinder_throw], 2 * PI)
    fire = tdc + 2 * PI * rng.integers(0, topology.strokes // 2, (size, c))
    fire = np.mod(fire - fire[:, :1], PI * topology.strokes)
    return Candidates(
        topology,
        phi,
        np.argsort(fire, axis=1, kind="stable") + 1,
        fire,
        np.ones(size, dtype=np.int64),
        np.arange(size),
    )


@pytest.mark.parametrize("preset", ["inline5", "v6-60", "boxer4", "w12", "inline2-2stroke"])
def test_random_candidates_against_analyze_and_balance(preset: str) -> None:
    """Every column of random candidates equals the one-engine analysis and solver on an
    EngineModel built per candidate."""
    topology = as_model(preset)
    cands = random_candidates(topology, 6, seed=len(preset))
    shaft = ShaftOptions(cg_radius=0.03, length=0.2)
    cw = CounterweightOptions(cg_radius=topology.crank_radius, angle="optimal", balance_factor=0.4)
    out = merit(cands, target="secondary", shafts=shaft, balance_factor=0.4)
    scale = float(
        (topology.reciprocating_mass.sum() + topology.throw_rotating_mass.sum())
        * topology.crank_radius
        * topology.speed**2
    )
    for i in range(cands.size):
        model = replace(
            topology,
            throw_angle=cands.throw_angle[i],
            firing_order=tuple(int(c) for c in cands.firing_order[i]),
        )
        forces = analyze(model).forces
        for k, n in enumerate(forces.orders):
            assert out[f"F{n}_N"][i] == pytest.approx(forces.force_amplitude[k], abs=1e-9 * scale)
            assert out[f"F{n}f_N"][i] == pytest.approx(
                abs(forces.force_forward[k]), abs=1e-9 * scale
            )
            assert out[f"M{n}b_Nm"][i] == pytest.approx(
                abs(forces.couple_backward[k]), abs=1e-9 * scale
            )
            assert out[f"M{n}_Nm"][i] == pytest.approx(forces.moment_amplitude[k], abs=1e-9 * scale)
        assert out["Mrot_Nm"][i] == pytest.approx(abs(forces.rotating_couple), abs=1e-9 * scale)
        assert out["Frot_N"][i] == pytest.approx(abs(forces.rotating_force), abs=1e-9 * scale)
        one = balance(model, cw, shaft, shaft, 8)
        assert one.counterweights is not None
        assert out["cw_mass_kg"][i] == pytest.approx(one.counterweights.mass.sum(), rel=1e-7)
        shafts = [s for group in (one.primary, one.secondary) if group for s in group.shafts]
        assert out["shafts"][i] == sum(1 for s in shafts if s.masses and s.mass > 0)
        total = sum(x.mass for s in shafts for x in s.masses)
        assert out["shaft_mass_kg"][i] == pytest.approx(total, rel=1e-7, abs=1e-12)
        left_f = max(c.force_after for c in one.residuals)
        left_m = max(c.moment_after for c in one.residuals)
        assert out["residual_F_N"][i] == pytest.approx(left_f, rel=1e-6, abs=1e-9 * scale)
        assert out["residual_M_Nm"][i] == pytest.approx(left_m, rel=1e-6, abs=1e-9 * scale)


def test_torsional_excitation_against_a_loop() -> None:
    """X_k from the formula written cylinder by cylinder, with a mode given per cylinder."""
    topology = as_model("v6-60")
    cands = random_candidates(topology, 5, seed=3)
    shape = np.array([1.0, 0.8, 0.6, 0.9, -0.2, 0.1])
    out = merit(cands, target="none", mode_shape=shape, orders=4)
    for i in range(cands.size):
        for k in torsion_orders(4, 4):
            total = 0j
            for c in range(6):
                total += shape[c] * complex(math.cos(k * cands.fire_angle[i, c]), 0.0)
                total += shape[c] * complex(0.0, math.sin(k * cands.fire_angle[i, c]))
            name = f"X{int(k)}" if k == int(k) else f"X{int(k)}p5"
            assert out[name][i] == pytest.approx(abs(total) / 3.6, abs=1e-12)
    assert "X4" in out and "X4p5" not in out
    two = random_candidates(as_model("inline2-2stroke"), 2, seed=1)
    assert [k for k in merit(two, target="none", orders=3) if k.startswith("X")] == [
        "X1",
        "X2",
        "X3",
    ]
    assert "mode" in TORSION_ASSUMPTION and "w_c" in TORSION_ASSUMPTION


def test_linear_mode_shape() -> None:
    """1 at the free end (throw 1) down to 1/T; the cylinders of a throw share it."""
    v8 = as_model("v8-crossplane")
    assert mode_weights(v8, "linear").tolist() == [1.0, 0.75, 0.5, 0.25] * 2
    assert mode_weights(v8, "uniform").tolist() == [1.0] * 8


def test_empty_batch_has_every_column() -> None:
    model = as_model("inline4")
    full = merit(batch([model]), target="primary")
    none = batch([model])
    empty = replace(
        none,
        throw_angle=none.throw_angle[:0],
        firing_order=none.firing_order[:0],
        fire_angle=none.fire_angle[:0],
        equivalents=none.equivalents[:0],
        index=none.index[:0],
    )
    out = merit(empty, target="primary")
    assert list(out) == list(full)
    assert all(v.shape == (0,) for v in out.values())


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"target": "everything"}, "target"),
        ({"mode_shape": "parabolic"}, "mode_shape"),
        ({"mode_shape": [1.0, 2.0]}, "mode_shape"),
        ({"mode_shape": [0.0] * 4}, "mode_shape"),
        ({"mode_shape": [1.0, math.nan, 1.0, 1.0]}, "mode_shape"),
        ({"orders": 0}, "orders"),
    ],
)
def test_bad_settings_name_the_field(kwargs: dict, field: str) -> None:
    with pytest.raises(InputError) as error:
        merit(batch([as_model("inline4")]), **kwargs)
    assert error.value.field == field


@pytest.mark.parametrize("target", ["counterweights", "secondary"])
def test_a_candidates_figures_do_not_depend_on_its_batch(target: str) -> None:
    """Issue 26: every W12 broad-arrow candidate's figures, computed with all 256 and on
    their own, are the same to the last bit (the Pareto front compares them so)."""
    from crankbalance.physics.explore import orders

    problem = orders.problem("w", 12, 4, bank_angle=math.radians(60))
    cands = orders.chunk(problem, 0, orders.count(problem))
    together = merit(cands, target=target, balance_factor=0.5)  # type: ignore[arg-type]
    alone = [
        merit(cands.part(i, i + 1), target=target, balance_factor=0.5)  # type: ignore[arg-type]
        for i in range(cands.size)
    ]
    for name, column in together.items():
        assert np.array_equal(column, [one[name][0] for one in alone]), name


def test_one_bank_takes_the_whole_interval_deviation_given() -> None:
    rng = np.random.default_rng(3)
    fire = rng.uniform(0, 4 * PI, (50, 6))
    whole = interval_deviation(fire, 4 * PI)
    inline = np.zeros(6)
    given = bank_interval_deviation(fire, inline, 4 * PI, whole=whole)
    assert given.tobytes() == bank_interval_deviation(fire, inline, 4 * PI).tobytes()
    assert given is not whole
    vee = np.array([0.0, 1.0] * 3)  # two banks: each bank's own, the whole not used
    assert bank_interval_deviation(fire, vee, 4 * PI, whole=np.full(50, -1.0)).tolist() == (
        bank_interval_deviation(fire, vee, 4 * PI).tolist()
    )


# ------------------------------------------------------------- the columns, unevaluated
@pytest.mark.parametrize(
    ("layout", "cylinders", "strokes"),
    [("inline", 4, 4), ("inline", 3, 2), ("vee", 6, 4), ("boxer", 4, 4), ("radial", 5, 4)],
)
def test_column_names_are_merit_s_columns(layout: str, cylinders: int, strokes: int) -> None:
    """``column_names`` (the run's plan counts columns by it) names what ``merit`` gives,
    in its order, for every target, a few orders and mode shapes; ``column_count`` counts
    them without an evaluation for ``merit`` and by one for anything else."""
    bank = math.pi / 2 if layout == "vee" else None
    problem = orders_module.problem(layout, cylinders, strokes, bank)
    template = orders_module.template(problem)
    for target in ("none", "counterweights", "primary", "secondary"):
        for k in (1, 2, 5):
            for mode in ("uniform", "linear", [1.0] * cylinders):
                got = column_names(template.topology, target, 0.3, mode, k)
                assert got == list(merit(template, target, 0.3, mode, k))
                evaluate = functools.partial(
                    merit, target=target, balance_factor=0.3, mode_shape=mode, orders=k
                )
                assert column_count(evaluate, template) == len(got)
                assert column_count(lambda c, e=evaluate: e(c), template) == len(got)


def test_column_count_checks_as_merit_does(monkeypatch: pytest.MonkeyPatch) -> None:
    """The plan's count refuses what ``merit`` refuses, with the same line, and does not
    evaluate ``merit`` for its own keywords (but does for counterweight options)."""
    problem = orders_module.problem("inline", 4, 4)
    template = orders_module.template(problem)
    for kwargs in ({"target": "all"}, {"orders": 0}, {"mode_shape": "cubic"}):
        with pytest.raises(InputError) as by_merit:
            merit(template, **kwargs)  # type: ignore[arg-type]
        with pytest.raises(InputError) as by_count:
            plan(problem, functools.partial(merit, **kwargs))
        assert str(by_count.value) == str(by_merit.value)
    calls: list[int] = []

    def counted(candidates: Candidates, **kwargs: object) -> dict[str, np.ndarray]:
        calls.append(candidates.size)
        return merit(candidates, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(merit_module, "merit", counted)
    plan(problem, functools.partial(counted, target="primary", orders=3))
    assert calls == []
    cw = CounterweightOptions(cg_radius=0.04)
    plan(problem, functools.partial(counted, target="primary", counterweights=cw))
    assert calls == [1]
