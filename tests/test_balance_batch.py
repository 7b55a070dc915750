"""Batched balancing (issue 13): engine by engine the one-engine solver's results, the
residual check that fails when a mass is wrong, and the degenerate cases handled alike."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.physics.balance_batch import BATCH_CHUNK, balance_batch, check_batch
from crankbalance.physics.balance_counterweights import _lstsq2
from crankbalance.physics.balance_types import (
    BatchBalance,
    BatchCounterweights,
    BatchShafts,
    CounterweightOptions,
    ShaftOptions,
)
from crankbalance.physics.balancing import BalanceResult, Counterweights, ShaftSet, balance
from crankbalance.physics.model import EngineBatch, EngineModel, engine_batch, stack_models, take
from crankbalance.physics.shaking import batch_free_forces
from crankbalance.studies.build import build_model

#: agreement asked of the batch with the one-engine solver
REL = 1e-9


def model_of(name: str) -> EngineModel:
    return build_model(load_engine(name))


def random_batch(
    name: str, n: int, seed: int, spread: float = math.pi, keep: int = 0
) -> EngineBatch:
    """``n`` engines of the topology of preset ``name``: throw angles turned by up to
    ``spread`` [rad], masses, crank radius, rod length and speed varied; the first ``keep``
    engines keep the preset's crank and masses (so a batch mixes cranks balanced as a whole
    and not)."""
    m = model_of(name)
    rng = np.random.default_rng(seed)
    angles = m.throw_angle + rng.uniform(-spread, spread, (n, m.throws))
    rotating = m.throw_rotating_mass * rng.uniform(0.6, 1.4, (n, m.throws))
    reciprocating = m.reciprocating_mass * rng.uniform(0.6, 1.4, (n, m.cylinders))
    angles[:keep], rotating[:keep], reciprocating[:keep] = (
        m.throw_angle,
        m.throw_rotating_mass,
        m.reciprocating_mass,
    )
    return engine_batch(
        m,
        n,
        throw_angle=angles,
        throw_rotating_mass=rotating,
        reciprocating_mass=reciprocating,
        crank_radius=m.crank_radius * rng.uniform(0.8, 1.2, n),
        rod_length=m.rod_length * rng.uniform(0.95, 1.3, n),
        speed=m.speed * rng.uniform(0.5, 1.5, n),
    )


def close(a: complex | np.ndarray, b: complex | np.ndarray, scale: float) -> bool:
    """Equal to REL of ``scale`` (the size of the quantity compared)."""
    return bool(np.all(np.abs(np.asarray(a) - np.asarray(b)) <= REL * scale))


def unbalance_scale(m: EngineModel) -> float:
    """Size of the engine's first moments [kg m]: all its masses at the crank radius."""
    return float((m.throw_rotating_mass.sum() + m.reciprocating_mass.sum()) * m.crank_radius)


def assert_counterweights(
    one: Counterweights | None, many: BatchCounterweights | None, i: int, size: float
) -> None:
    """Equal to REL; first moments at round-off of the engine's size (1e-12) count as zero:
    they are the noise of equations the counterweights cannot act on (e.g. the equal-mass
    pattern on a flat-plane crank), in both solvers."""
    assert (one is None) == (many is None)
    if one is None or many is None:
        return
    scale = np.abs(one.moments).max(initial=0.0) + 1e-3 * size
    assert close(one.moments, many.moments[i], scale), "first moments m r e^(i psi)"
    assert close(one.mass, many.mass[i], scale / one.cg_radius)
    assert np.array_equal(one.web, many.web) and np.array_equal(one.throw, many.throw)
    assert close(one.position, many.position[i], 1e-3)
    assert many.halves[i] == (one.scope == "halves")
    assert many.already_balanced[i] == ("already balanced" in one.note)
    noise = one.mass.max(initial=0.0) * one.cg_radius < 1e-12 * size
    assert noise or many.flipped[i] == ("flipped" in one.note)
    if noise:
        return
    if one.method == "pattern" and one.alpha is not None:
        turn = (one.alpha - many.alpha[i] + math.pi) % (2 * math.pi) - math.pi
        assert abs(turn) <= 1e-7, "pattern angle"
    elif one.method == "pattern":
        assert many.alpha[i] == 0.0


def assert_shafts(one: ShaftSet | None, many: BatchShafts | None, i: int) -> None:
    assert (one is None) == (many is None)
    if one is None or many is None:
        return
    assert [s.sense for s in one.shafts] == many.sense.tolist()
    for s, shaft in enumerate(one.shafts):
        assert many.layout[i, s] == len(shaft.masses), "which masses the shaft has"
        expected = np.zeros(3, complex)
        for mass in shaft.masses:
            slot = int(np.flatnonzero(np.isclose(many.position, mass.position, atol=1e-12))[0])
            expected[slot] = mass.mass * np.exp(1j * mass.phase)
        got = many.mass[i, s] * np.exp(1j * many.phase[i, s])
        assert close(expected, got, max(np.abs(expected).max(), 1e-300)), f"shaft {s}"
        assert close(shaft.mass, many.largest[i, s], max(shaft.mass, 1e-300))


def assert_residuals(one: BalanceResult, many: BatchBalance, i: int, batch: EngineBatch) -> None:
    r = many.residuals
    assert r.components == tuple(c.component for c in one.residuals)
    assert r.targeted.tolist() == [c.targeted for c in one.residuals]
    m = batch.model(i)
    force = (m.throw_rotating_mass.sum() + m.reciprocating_mass.sum()) * m.crank_radius
    force *= m.speed**2
    length = max(np.ptp(m.throw_position), m.crank_radius)
    for k, c in enumerate(one.residuals):
        assert close(c.force_before, r.force_before[i, k], force), c.component
        assert close(c.force_after, r.force_after[i, k], force), c.component
        assert close(c.moment_before, r.moment_before[i, k], force * length), c.component
        assert close(c.moment_after, r.moment_after[i, k], force * length), c.component
    # the check: every targeted component cancelled (to 1e-9 of the force scale)
    cancelled = all(
        c.force_after <= 1e-9 * force and c.moment_after <= 1e-9 * force * length
        for c in one.residuals
        if c.targeted
    )
    assert r.balanced[i] == cancelled


def assert_same_as_one_engine(
    batch: EngineBatch,
    cw: CounterweightOptions | None,
    primary: ShaftOptions | None,
    secondary: ShaftOptions | None,
    orders: int = 8,
    chunk: int = 2048,
) -> BatchBalance:
    many = balance_batch(batch, cw, primary, secondary, orders, chunk=chunk)
    assert many.size == batch.size
    for i in range(batch.size):
        one = balance(batch.model(i), cw, primary, secondary, orders)
        size = unbalance_scale(batch.model(i))
        assert_counterweights(one.counterweights, many.counterweights, i, size)
        assert_counterweights(one.extra_counterweights, many.extra_counterweights, i, size)
        assert_shafts(one.primary, many.primary, i)
        assert_shafts(one.secondary, many.secondary, i)
        assert_residuals(one, many, i, batch)
    return many


PAIR = ShaftOptions(0.03, 0.3)
SINGLE = ShaftOptions(0.03, 0.3, "counter-rotating")
SECONDARY = ShaftOptions(0.02, 0.25)
OPTIMAL = CounterweightOptions(0.045, angle="optimal", balance_factor=0.4)
INDIVIDUAL = CounterweightOptions(0.045, method="individual", balance_factor=0.5)
FIXED = CounterweightOptions(0.045, angle=0.3)

#: (topology, counterweights, primary, secondary, engines kept at the preset's crank):
#: 12 cases of 20 random engines, 240 engines in all
CASES = [
    ("inline4", OPTIMAL, None, SECONDARY, 5),
    ("inline4", INDIVIDUAL, SINGLE, SECONDARY, 5),
    ("inline4", FIXED, PAIR, None, 0),
    ("v8-crossplane", OPTIMAL, PAIR, SECONDARY, 5),
    ("v8-crossplane", INDIVIDUAL, None, SECONDARY, 0),
    ("v8-crossplane", None, PAIR, ShaftOptions(0.02, 0.25, "counter-rotating"), 0),
    ("inline3", OPTIMAL, PAIR, SECONDARY, 5),
    ("inline3", INDIVIDUAL, SINGLE, None, 0),
    ("inline3", FIXED, None, SECONDARY, 0),
    ("v6-90", OPTIMAL, SINGLE, SECONDARY, 5),  # the odd-fire 90-degree V6, cranks varied
    ("v6-90", INDIVIDUAL, PAIR, SECONDARY, 0),
    ("v6-90", FIXED, PAIR, None, 0),
]


@pytest.mark.parametrize(("name", "cw", "primary", "secondary", "keep"), CASES)
def test_batch_equals_the_one_engine_solver(
    name: str,
    cw: CounterweightOptions | None,
    primary: ShaftOptions | None,
    secondary: ShaftOptions | None,
    keep: int,
) -> None:
    """20 random engines per case, each compared with balance() to 1e-9; chunks of 7 so
    results are joined across chunks."""
    batch = random_batch(name, 20, seed=len(name) * 31 + keep, keep=keep)
    many = assert_same_as_one_engine(batch, cw, primary, secondary, chunk=7)
    if keep and cw is not None and name == "inline4":
        # the flat-plane inline-4 is balanced as a whole: no counterweights by default
        assert many.counterweights is not None
        assert not many.counterweights.halves.any()
        assert many.counterweights.already_balanced[:keep].all()
        assert not many.counterweights.already_balanced[keep:].any()


def test_batch_equals_the_one_engine_solver_with_few_orders_and_small_spread() -> None:
    batch = random_batch("v8-crossplane", 10, seed=3, spread=0.05)
    assert_same_as_one_engine(batch, OPTIMAL, PAIR, SECONDARY, orders=1)


@pytest.mark.parametrize("name", ["single", "v2-90"])
def test_single_throw_engines_of_many_web_geometries(name: str) -> None:
    """One throw: webs at half the crank radius, scaled by it; every engine has its own
    crank radius, so its own web positions (groups of equations)."""
    batch = random_batch(name, 12, seed=5)
    many = assert_same_as_one_engine(batch, INDIVIDUAL, PAIR, SECONDARY)
    assert many.counterweights is not None
    assert np.unique(many.counterweights.position[:, 0]).size == batch.size
    assert_same_as_one_engine(batch, OPTIMAL, SINGLE, None)


def test_kinematics_shared_by_the_batch() -> None:
    """The harmonic coefficients are computed once when every engine has the same rod
    ratio and offset: same results as the one-engine solver."""
    m = model_of("inline4")
    rng = np.random.default_rng(11)
    batch = engine_batch(m, 15, throw_angle=rng.uniform(0, 2 * np.pi, (15, m.throws)))
    assert_same_as_one_engine(batch, OPTIMAL, PAIR, SECONDARY)


@pytest.mark.parametrize("kinematics", ["series", "first-order"])
def test_other_kinematics(kinematics: str) -> None:
    m = dataclasses.replace(model_of("inline4"), kinematics=kinematics)
    rng = np.random.default_rng(2)
    batch = engine_batch(
        m,
        8,
        throw_angle=rng.uniform(0, 2 * np.pi, (8, m.throws)),
        rod_length=m.rod_length * rng.uniform(1, 1.3, 8),
    )
    assert_same_as_one_engine(batch, INDIVIDUAL, PAIR, SECONDARY)


def test_chunks_change_nothing_beyond_round_off() -> None:
    """numpy's vector loops depend on the array length, so the last bits may differ."""
    batch = random_batch("v6-90", 25, seed=9)
    whole = balance_batch(batch, OPTIMAL, SINGLE, SECONDARY)
    pieces = balance_batch(batch, OPTIMAL, SINGLE, SECONDARY, chunk=4)
    assert_identical(whole, pieces)


def test_forces_given_are_the_forces_computed() -> None:
    """``forces=`` (the explorer's free forces, computed once) gives the same bits as the
    forces computed inside (one chunk; in several, the forces of the whole batch differ
    from each chunk's in the last bits at most, as chunks do); forces of another batch
    or of too few orders are refused."""
    batch = random_batch("v6-90", 25, seed=9)
    forces = batch_free_forces(batch, 8)
    computed = balance_batch(batch, OPTIMAL, SINGLE, SECONDARY, 8, BATCH_CHUNK)
    assert_bits(computed, balance_batch(batch, OPTIMAL, SINGLE, SECONDARY, forces=forces))
    assert_identical(
        computed, balance_batch(batch, OPTIMAL, SINGLE, SECONDARY, 8, 4, forces=forces)
    )
    with pytest.raises(InputError, match="forces"):
        balance_batch(batch, OPTIMAL, forces=batch_free_forces(batch, 3))
    with pytest.raises(InputError, match="forces"):
        balance_batch(batch.take(slice(0, 5)), OPTIMAL, forces=batch_free_forces(batch, 8))


def assert_bits(a: object, b: object) -> None:
    """Equal dataclasses, field by field, arrays bit for bit."""
    if dataclasses.is_dataclass(a):
        assert type(a) is type(b)
        for f in dataclasses.fields(a):
            assert_bits(getattr(a, f.name), getattr(b, f.name))
    elif isinstance(a, np.ndarray):
        assert isinstance(b, np.ndarray) and (a.dtype, a.shape) == (b.dtype, b.shape)
        assert a.tobytes() == b.tobytes()
    else:
        assert a == b


def assert_identical(a: object, b: object) -> None:
    """Equal dataclasses, field by field, arrays to round-off."""
    if dataclasses.is_dataclass(a):
        for f in dataclasses.fields(a):
            assert_identical(getattr(a, f.name), getattr(b, f.name))
    elif isinstance(a, np.ndarray):
        assert isinstance(b, np.ndarray) and a.shape == b.shape
        assert np.allclose(a, b, rtol=1e-12, atol=1e-12)
    else:
        assert a == b


# --------------------------------------------------------------------------- the check
def test_residual_check_fails_when_a_mass_is_perturbed() -> None:
    batch = random_batch("inline3", 10, seed=21)
    res = balance_batch(batch, INDIVIDUAL, PAIR, SECONDARY)
    assert res.residuals.balanced.all(), "individual counterweights and shaft pairs cancel"
    again = check_batch(batch, res, chunk=3)
    # the same numbers, up to the rounding of a different chunking of the coefficients
    scale = np.abs(res.residuals.force_after).max()
    np.testing.assert_allclose(again.force_after, res.residuals.force_after, atol=1e-14 * scale)
    assert again.balanced.all()

    # one secondary shaft mass of engine 4 one per cent too heavy
    assert res.secondary is not None
    mass = res.secondary.mass.copy()
    slot = int(np.argmax(mass[4, 1]))
    mass[4, 1, slot] *= 1.01
    wrong = dataclasses.replace(res, secondary=dataclasses.replace(res.secondary, mass=mass))
    check = check_batch(batch, wrong)
    assert check.balanced.tolist() == [i != 4 for i in range(10)]
    k = check.column("order2")
    assert check.force_after[4, k] + check.moment_after[4, k] > 0
    assert check.force_after[4, check.column("order1")] == 0.0, "the other orders untouched"

    # a counterweight turned by a degree: as in the one-engine check, the counterweights
    # beyond their share that carries the rotating masses count to the first order
    assert res.counterweights is not None
    direction = res.counterweights.direction.copy()
    direction[7, 0] += math.radians(1.0)
    turned = dataclasses.replace(
        res, counterweights=dataclasses.replace(res.counterweights, direction=direction)
    )
    check = check_batch(batch, turned)
    assert check.balanced.tolist() == [i != 7 for i in range(10)]
    assert check.force_after[7, check.column("order1")] > 0


def test_residual_check_reports_what_the_pattern_cannot_cancel() -> None:
    """Equal counterweights at a fixed angle cannot balance a random crank: the residual
    is reported and the check says so, as the one-engine solver's note."""
    batch = random_batch("inline3", 6, seed=4)
    res = balance_batch(batch, FIXED)
    assert not res.residuals.balanced.any()
    for i in range(batch.size):
        one = balance(batch.model(i), FIXED)
        assert any("cannot reach their target" in note for note in one.notes)
        assert batch.size and one.counterweights is not None


# --------------------------------------------------------------------------- degenerate
def test_already_balanced_and_halves_as_the_one_engine_solver() -> None:
    batch = random_batch("inline6", 6, seed=1, keep=6)  # the preset's crank, masses varied
    res = assert_same_as_one_engine(batch, CounterweightOptions(0.04, scope="whole"), PAIR, None)
    assert res.counterweights is not None
    assert res.counterweights.already_balanced.all() and not res.counterweights.mass.any()
    assert res.primary is not None and not res.primary.layout.any(), "nothing to cancel"
    res = assert_same_as_one_engine(batch, CounterweightOptions(0.04), None, None)
    assert res.counterweights is not None and not res.counterweights.halves.any()
    assert res.counterweights.already_balanced.all(), "auto: none for a balanced crank"
    res = assert_same_as_one_engine(batch, CounterweightOptions(0.04, scope="halves"), None, None)
    assert res.counterweights is not None and res.counterweights.halves.all()


def test_zero_targets_give_no_mass_and_no_nan() -> None:
    batch = random_batch("boxer6", 5, seed=2, keep=5)
    res = assert_same_as_one_engine(batch, None, PAIR, SECONDARY)
    assert res.primary is not None and not res.primary.mass.any()
    assert res.to_dict()["primary"]["layout"] == [[0, 0]] * 5


def test_rank_deficient_webs_in_the_mid_plane() -> None:
    """Both webs of a single throw in its mid-plane (web offset 0): one plane, no couple to
    cancel, a rank-deficient system (least-norm solution) and webs on the mid-plane (the
    optimal pattern by a scan)."""
    batch = random_batch("single", 6, seed=8)
    assert_same_as_one_engine(
        batch, CounterweightOptions(0.03, method="individual", web_offset=0.0), None, None
    )
    assert_same_as_one_engine(
        batch, CounterweightOptions(0.03, angle="optimal", web_offset=0.0), None, None
    )


def test_one_plane_that_cannot_cancel_a_couple_raises_as_one_engine() -> None:
    batch = random_batch("inline3", 5, seed=3)
    opts = CounterweightOptions(0.03, webs=(1, 0, 0, 0, 0, 0))
    with pytest.raises(InputError) as one:
        balance(batch.model(0), opts)
    with pytest.raises(InputError, match=r"one plane.*\(engine 0 of the batch\)") as many:
        balance_batch(batch, opts)
    assert (many.value.field, many.value.value) == (one.value.field, one.value.value)
    # an engine that needs no counterweight does not raise; the first that does is named
    zero_mass = np.ones((5, 3))
    zero_mass[0] = 0.0
    quiet = engine_batch(
        batch.topology,
        throw_angle=batch.throw_angle,
        throw_rotating_mass=zero_mass,
        reciprocating_mass=batch.reciprocating_mass,
    )
    with pytest.raises(InputError, match=r"\(engine 1 of the batch\)"):
        balance_batch(quiet, opts, chunk=1)


def test_other_errors_as_the_one_engine_solver() -> None:
    batch = random_batch("inline4", 3, seed=1)
    for args in (
        (CounterweightOptions(0.03, webs=(1, 1)),),
        (None, SINGLE),
        (CounterweightOptions(0.03, scope="halves", webs=(1,) * 6),),
    ):
        with pytest.raises(InputError) as one:
            balance(batch.model(0), *args)  # type: ignore[arg-type]
        with pytest.raises(InputError) as many:
            balance_batch(batch, *args)  # type: ignore[arg-type]
        assert many.value.field == one.value.field
    with pytest.raises(InputError, match="halves"):
        balance_batch(
            random_batch("inline3", 2, seed=1), CounterweightOptions(0.03, scope="halves")
        )
    with pytest.raises(InputError, match="chunk"):
        balance_batch(batch, OPTIMAL, chunk=0)


def test_two_unknown_least_squares_as_numpy() -> None:
    """The stacked least squares of the optimal pattern, including parallel and zero
    columns (least-norm solutions), against numpy.linalg.lstsq."""
    rng = np.random.default_rng(0)
    matrix = rng.normal(size=(6, 4, 2))
    matrix[1, :, 1] = 3.0 * matrix[1, :, 0]  # parallel columns
    matrix[2, :, 1] = 0.0  # a zero column
    matrix[3] = 0.0  # nothing at all
    matrix[4, :, 1] = matrix[4, :, 0] * (1 + 1e-9)  # nearly parallel
    rhs = rng.normal(size=(6, 4))
    x, y = _lstsq2(matrix, rhs)
    for i in range(6):
        expected = np.linalg.lstsq(matrix[i], rhs[i], rcond=None)[0]
        assert np.allclose([x[i], y[i]], expected, rtol=1e-9, atol=1e-12), i


# --------------------------------------------------------------------------- the batch
def test_engine_batch_and_stack_models() -> None:
    m = model_of("v8-crossplane")
    models = [
        dataclasses.replace(m, throw_angle=m.throw_angle + k * 0.1, crank_radius=0.04 + k * 1e-3)
        for k in range(4)
    ]
    batch = stack_models(models)
    assert batch.size == 4 and batch.throw_angle.shape == (4, 4)
    assert batch.reciprocating_mass.shape == (4, 8)
    for k, model in enumerate(models):
        got = batch.model(k)
        assert got.crank_radius == model.crank_radius
        assert np.array_equal(got.throw_angle, model.throw_angle)
    shared = engine_batch(m, 3)
    assert shared.size == 3 and np.array_equal(shared.throw_angle[2], m.throw_angle)
    assert engine_batch(m, speed=[100.0, 200.0]).size == 2


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"speed": [1.0, 2.0], "crank_radius": [0.04] * 3}, "engine_batch"),
        ({"throw_angle": np.zeros((2, 3))}, "throw_angle"),
        ({"rod_length": [0.2, 0.03]}, r"rod_length.*engine 1"),
        ({"speed": [1.0, -1.0]}, r"speed.*engine 1"),
        ({"reciprocating_mass": [[0.5] * 8, [0.5] * 7 + [math.nan]]}, r"finite \(engine 1\)"),
    ],
)
def test_engine_batch_bad_input(kwargs: dict, match: str) -> None:
    with pytest.raises(InputError, match=match):
        engine_batch(model_of("v8-crossplane"), **kwargs)


def test_stack_models_needs_one_topology() -> None:
    with pytest.raises(InputError, match="one topology"):
        stack_models([model_of("inline4"), model_of("v8-crossplane")])
    with pytest.raises(InputError, match="at least one"):
        stack_models([])


# --------------------------------------------------------------------------- batch independence
def w12_broad_arrow() -> EngineBatch:
    """The 256 canonical cranks of the explorer's W12 broad arrow (60 deg between banks),
    the plain engine's masses (docs/explorer.md)."""
    from crankbalance.physics.explore import orders

    p = orders.problem("w", 12, 4, bank_angle=math.radians(60))
    c = orders.chunk(p, 0, orders.count(p))
    return engine_batch(c.topology, c.size, throw_angle=c.throw_angle)


#: the W12 candidate whose counterweight mass followed its batch (4.010 kg in one batch,
#: 4.062 kg in another, 4.092 kg alone): its crank turns the pattern without effect
W12_CRANK = np.radians([300.0, 120.0, 300.0, 120.0])


def assert_same_numbers(a: BatchBalance, b: BatchBalance, batch: EngineBatch) -> None:
    """Two results of the same engines equal to REL (1e-9) of each engine's scale: the
    counterweights' first moments and masses, the pattern angle where there is a mass,
    the flags, the shaft masses as m e^(i psi) and their layout, every residual."""
    size = (batch.throw_rotating_mass.sum(axis=1) + batch.reciprocating_mass.sum(axis=1)) * (
        batch.crank_radius
    )
    force = size * batch.speed**2
    length = np.maximum(np.ptp(batch.topology.throw_position), batch.crank_radius)
    for one, two in (
        (a.counterweights, b.counterweights),
        (a.extra_counterweights, b.extra_counterweights),
    ):
        assert (one is None) == (two is None)
        if one is None or two is None:
            continue
        for flag in ("halves", "flipped", "already_balanced"):
            assert np.array_equal(getattr(one, flag), getattr(two, flag)), flag
        assert np.all(np.abs(one.moments - two.moments) <= REL * size[:, None])
        assert np.all(np.abs(one.mass - two.mass) <= REL * size[:, None] / one.cg_radius)
        massive = one.mass.max(axis=1) * one.cg_radius > REL * size
        turn = np.angle(np.exp(1j * (one.alpha - two.alpha)))
        assert np.all(np.abs(turn[massive]) <= REL), "pattern angle"
    for one, two in ((a.primary, b.primary), (a.secondary, b.secondary)):
        assert (one is None) == (two is None)
        if one is None or two is None:
            continue
        assert np.array_equal(one.layout, two.layout)
        v1, v2 = one.mass * np.exp(1j * one.phase), two.mass * np.exp(1j * two.phase)
        assert np.all(np.abs(v1 - v2) <= REL * size[:, None, None] / one.cg_radius)
    r1, r2 = a.residuals, b.residuals
    assert np.array_equal(r1.balanced, r2.balanced)
    for name, scale in (
        ("force_before", force),
        ("force_after", force),
        ("moment_before", force * length),
        ("moment_after", force * length),
    ):
        assert np.all(np.abs(getattr(r1, name) - getattr(r2, name)) <= REL * scale[:, None])


@pytest.mark.parametrize(
    ("cw", "primary", "secondary"),
    [
        (CounterweightOptions(0.05, angle="optimal"), None, None),  # the explorer's default
        (CounterweightOptions(0.05, angle="optimal", balance_factor=0.5), PAIR, SECONDARY),
        (CounterweightOptions(0.05, method="individual", balance_factor=0.3), SINGLE, None),
    ],
)
def test_a_result_does_not_depend_on_its_batch(
    cw: CounterweightOptions, primary: ShaftOptions | None, secondary: ShaftOptions | None
) -> None:
    """Every W12 crank balanced in one batch, in chunks of 7, in two halves and one by one
    (a batch of one, and balance) gets the same numbers to 1e-9 relative."""
    batch = w12_broad_arrow()
    whole = balance_batch(batch, cw, primary, secondary)
    assert_same_numbers(whole, balance_batch(batch, cw, primary, secondary, chunk=7), batch)
    assert_same_numbers(whole, balance_batch(batch, cw, primary, secondary, chunk=128), batch)
    alone = [
        balance_batch(batch.take(slice(i, i + 1)), cw, primary, secondary)
        for i in range(batch.size)
    ]
    for i, one in enumerate(alone):
        assert_same_numbers(_take_one(whole, i), one, batch.take(slice(i, i + 1)))
    assert_same_as_one_engine(batch, cw, primary, secondary)


def _take_one(result: BatchBalance, i: int) -> BatchBalance:
    one: BatchBalance = take(result, slice(i, i + 1))
    return one


def test_the_w12_crank_that_turning_the_pattern_does_not_change() -> None:
    """Turning the equal-mass pattern of this crank changes neither its force nor its
    couple (the second unknown of the optimal pattern is zero, not round-off): the least
    mass is the pattern opposite the crankpins, as the one-unknown pattern at 0 deg."""
    batch = w12_broad_arrow()
    i = int(np.flatnonzero(np.all(np.isclose(batch.throw_angle, W12_CRANK), axis=1))[0])
    model = batch.model(i)
    optimal = balance(model, CounterweightOptions(0.05, angle="optimal"))
    opposite = balance(model, CounterweightOptions(0.05, angle=0.0))
    assert optimal.counterweights is not None and opposite.counterweights is not None
    assert optimal.counterweights.alpha == pytest.approx(0.0, abs=1e-12)
    np.testing.assert_allclose(
        optimal.counterweights.mass, opposite.counterweights.mass, rtol=1e-12
    )
    assert optimal.counterweights.mass.sum() == pytest.approx(4.0, rel=1e-12)
