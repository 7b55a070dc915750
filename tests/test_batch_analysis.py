"""The batched analysis against the one-engine analysis, chunk boundaries, and the cache of
the exact harmonic coefficients (issue 13)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from crankbalance.physics import kinematics
from crankbalance.physics.kinematics import (
    CACHE_SIZE,
    cached_exact_coefficients,
    exact_coefficients,
    harmonic_coefficients,
    piston_acceleration,
)
from crankbalance.physics.model import EngineModel
from crankbalance.physics.shaking import batch_amplitudes, free_forces, reciprocating_phasors

CYLINDERS = 8


def random_engines(count: int, seed: int, offset: bool = True) -> dict[str, np.ndarray]:
    """Engines of 8 cylinders, every parameter drawn per engine (rod ratio 0.15-0.45)."""
    rng = np.random.default_rng(seed)
    shape = (count, CYLINDERS)
    radius = rng.uniform(0.02, 0.08, count)
    return {
        "crank_radius": radius,
        "rod_length": radius / rng.uniform(0.15, 0.45, count),
        "speed": rng.uniform(100.0, 1000.0, count),
        "mass": rng.uniform(0.2, 1.5, shape),
        "throw_angle": rng.uniform(0.0, 2 * np.pi, shape),
        "bank": rng.uniform(-np.pi, np.pi, shape),
        "position": rng.uniform(-0.4, 0.4, shape),
        "offset": radius * rng.uniform(-0.2, 0.2, count) if offset else np.zeros(count),
    }


def one_engine(e: dict[str, np.ndarray], k: int) -> EngineModel:
    """Engine k of a batch as a model: one cylinder on each throw, no rotating masses."""
    return EngineModel(
        name=f"random {k}",
        speed=float(e["speed"][k]),
        kinematics="exact",
        crank_radius=float(e["crank_radius"][k]),
        rod_length=float(e["rod_length"][k]),
        strokes=4,
        throw_angle=e["throw_angle"][k],
        throw_position=e["position"][k],
        throw_rotating_mass=np.zeros(CYLINDERS),
        cylinder_throw=np.arange(CYLINDERS),
        cylinder_bank=e["bank"][k],
        reciprocating_mass=e["mass"][k],
        cylinder_offset=np.full(CYLINDERS, e["offset"][k]),
        cylinder_axial=np.zeros(CYLINDERS),
        cylinder_rotating_mass=np.zeros(CYLINDERS),
        firing_order=tuple(range(1, CYLINDERS + 1)),
    )


def force_scale(e: dict[str, np.ndarray]) -> np.ndarray:
    """Sum of m r w^2 of each engine [N], shape (E, 1)."""
    return (e["mass"].sum(axis=1) * e["crank_radius"] * e["speed"] ** 2)[:, None]


def batch(e: dict[str, np.ndarray], **kwargs: object) -> tuple[np.ndarray, np.ndarray]:
    return batch_amplitudes(
        e["crank_radius"],
        e["rod_length"],
        e["speed"],
        e["mass"],
        e["throw_angle"],
        e["bank"],
        e["position"],
        offset=e["offset"],
        **kwargs,  # type: ignore[arg-type]
    )


@pytest.mark.parametrize("chunk", [1, 7, 20, 1024])  # up to 16 engines: exponentials
@pytest.mark.parametrize("offset", [False, True])
def test_batch_equals_one_engine_analysis(chunk: int, offset: bool) -> None:
    """37 random engines (not a multiple of any chunk but 1): each engine's amplitudes
    from the batch equal those of free_forces on that engine alone, to 1e-12 of the
    engine's force scale, and to 1e-12 relative wherever the amplitude is not a
    cancellation (above 1e-3 of the scale)."""
    e = random_engines(37, seed=3, offset=offset)
    force, moment = batch(e, orders=8, chunk=chunk)
    assert force.shape == moment.shape == (37, 8)
    single = [free_forces(one_engine(e, k), 8) for k in range(37)]
    f1 = np.array([s.force_amplitude for s in single])
    m1 = np.array([s.moment_amplitude for s in single])
    scale = force_scale(e)
    for got, want in ((force, f1), (moment, m1)):
        assert np.all(np.abs(got - want) <= 1e-12 * scale)
        large = want > 1e-3 * scale
        assert large.sum() > 37 * 2  # orders 1 and 2 at least: the check is not empty
        assert np.all(np.abs(got - want)[large] <= 1e-12 * want[large])


def test_batch_sizes_around_the_chunk() -> None:
    """Batches of chunk - 1, chunk, chunk + 1 and 2 chunk + 3 engines give each engine
    the result it has alone and in one chunk."""
    e = random_engines(2 * 20 + 3, seed=5)
    first = {k: v[:1] for k, v in e.items()}
    alone = batch(first, chunk=20)
    for count in (19, 20, 21, 43):
        part = {k: v[:count] for k, v in e.items()}
        force, moment = batch(part, chunk=20)
        assert force.shape == (count, 8)
        scale = force_scale(part)
        ref_f, ref_m = batch(part, chunk=count)  # one chunk
        assert np.all(np.abs(force - ref_f) <= 1e-13 * scale)
        assert np.all(np.abs(moment - ref_m) <= 1e-13 * scale)
        assert np.all(np.abs(force[0] - alone[0][0]) <= 1e-13 * force_scale(first)[0])


def test_shared_cylinder_arrays_broadcast() -> None:
    """Per-cylinder arrays of shape (C,) and scalar engine parameters are shared by all
    the engines: the same result as the arrays repeated per engine."""
    e = random_engines(9, seed=7)
    tiled = dict(e)
    for key in ("mass", "throw_angle", "bank", "position"):
        tiled[key] = np.tile(e[key][0], (9, 1))
    tiled["speed"] = np.full(9, e["speed"][0])
    shared = batch_amplitudes(
        e["crank_radius"],
        e["rod_length"],
        e["speed"][0],
        e["mass"][0],
        e["throw_angle"][0],
        e["bank"][0],
        e["position"][0],
        offset=e["offset"],
        chunk=4,
    )
    full = batch(tiled, chunk=4)
    for a, b in zip(shared, full, strict=True):
        assert a.shape == (9, 8)
        assert np.allclose(a, b, rtol=1e-13, atol=0)


def test_one_engine_without_engine_axis() -> None:
    e = random_engines(1, seed=11)
    force, moment = batch_amplitudes(
        e["crank_radius"][0],
        e["rod_length"][0],
        e["speed"][0],
        e["mass"][0],
        e["throw_angle"][0],
        e["bank"][0],
        e["position"][0],
        offset=e["offset"][0],
    )
    assert force.shape == moment.shape == (8,)
    assert np.allclose(force, free_forces(one_engine(e, 0)).force_amplitude, rtol=1e-12)


def test_batch_rejects_arrays_of_more_dimensions() -> None:
    e = random_engines(4, seed=1)
    with pytest.raises(ValueError, match="per-cylinder"):
        batch_amplitudes(
            e["crank_radius"],
            e["rod_length"],
            e["speed"],
            e["mass"][None],
            e["throw_angle"],
            e["bank"],
            e["position"],
        )


@pytest.mark.parametrize("engines", [3, 200])  # one call of exponentials; powers by products
def test_batched_phasors_equal_one_engine(engines: int) -> None:
    """reciprocating_phasors on (E, C) arrays equals the call engine by engine (the
    batched balancing calls it with a batch axis)."""
    e = random_engines(engines, seed=13)
    lam = e["crank_radius"] / e["rod_length"]
    c = harmonic_coefficients(lam, 8, e["offset"] / e["crank_radius"])
    args = (e["mass"], e["throw_angle"], e["bank"], e["position"], e["crank_radius"])
    many = reciprocating_phasors(c, *args, e["speed"])
    scale = force_scale(e)
    for k in (0, engines // 2, engines - 1):
        one = reciprocating_phasors(c[k], *(a[k] for a in args), e["speed"][k])
        for a, b in zip(many, one, strict=True):
            assert np.all(np.abs(a[k] - b) <= 1e-13 * scale[k])


# --------------------------------------------------------------------------- coefficients
def fft_coefficients(lam: float, orders: int, offset: float) -> np.ndarray:
    """The exact coefficients the plain way: the FFT of the sampled exact acceleration
    (r = 1, l = 1/lambda) over a whole revolution, independent of exact_coefficients."""
    n = 256
    psi = 2 * np.pi * np.arange(n) / n
    f = -piston_acceleration(psi, 1.0, 1.0 / lam, offset)
    return 2.0 * np.fft.rfft(f)[1 : orders + 1] / n


@pytest.mark.parametrize("lam", [0.12, 0.3, 0.45])
@pytest.mark.parametrize("offset", [0.0, 0.15, -0.3])
@pytest.mark.parametrize("orders", [1, 8, 20])
def test_exact_coefficients_equal_the_fft_of_a_revolution(
    lam: float, offset: float, orders: int
) -> None:
    """Half (quarter without offset) a revolution of samples gives the coefficients of the
    whole revolution: against an FFT of 256 samples, to round-off."""
    got = harmonic_coefficients(lam, orders, offset)
    want = fft_coefficients(lam, orders, offset)
    assert got.shape == (orders,)
    assert np.abs(got - want).max() < 1e-15


def test_cache_returns_the_uncached_values() -> None:
    rng = np.random.default_rng(17)
    lams, offsets = rng.uniform(0.1, 0.45, 20), rng.uniform(-0.3, 0.3, 20)
    offsets[::4] = 0.0
    kinematics.cached_exact_coefficients.cache_clear()
    for lam, offset in zip(lams, offsets, strict=True):
        uncached = exact_coefficients(np.array([lam]), 8, np.array([offset]))[0]
        first = harmonic_coefficients(lam, 8, offset)  # computed and kept
        second = harmonic_coefficients(lam, 8, offset)  # from the cache
        assert np.array_equal(first, uncached)
        assert np.array_equal(second, uncached)
    info = kinematics.cached_exact_coefficients.cache_info()
    assert info.hits == 20 and info.misses == 20
    # the batch path computes the same numbers
    batched = exact_coefficients(lams, 8, offsets)
    for k in range(20):
        assert np.abs(batched[k] - harmonic_coefficients(lams[k], 8, offsets[k])).max() < 1e-15


def test_cache_is_keyed_by_every_parameter_and_shared_safely() -> None:
    a = harmonic_coefficients(0.3, 8, 0.0)
    assert not np.array_equal(a, harmonic_coefficients(0.31, 8, 0.0))
    assert not np.array_equal(a, harmonic_coefficients(0.3, 8, 0.1))
    assert harmonic_coefficients(0.3, 6, 0.0).shape == (6,)
    a[:] = 0.0  # the caller's copy: the cached value is not touched
    assert harmonic_coefficients(0.3, 8, 0.0)[0] == 1.0
    shared = cached_exact_coefficients(0.3, 0.0, 8)
    with pytest.raises(ValueError, match="read-only"):
        shared[0] = 2.0


def test_cache_is_bounded() -> None:
    kinematics.cached_exact_coefficients.cache_clear()
    for lam in np.linspace(0.1, 0.4, CACHE_SIZE + 50):
        harmonic_coefficients(float(lam), 4)
    info = kinematics.cached_exact_coefficients.cache_info()
    assert info.maxsize == CACHE_SIZE
    assert info.currsize == CACHE_SIZE


@pytest.mark.parametrize("preset", ["vr6", "w16", "inline3", "ducati-916", "v8-crossplane"])
def test_batch_roll_is_the_one_engine_roll(preset: str) -> None:
    """The batch path's sixth component: every engine's roll moment by order (offset
    cylinders, side-by-side rods, a reference point off the crank axis, engines with their
    own rod ratio, offsets and speed) is the one-engine analysis's roll to 1e-9."""
    from crankbalance.physics.model import stack_models, with_moment_point
    from crankbalance.physics.shaking import batch_free_forces
    from crankbalance.studies.engine import as_model

    base = with_moment_point(as_model(preset), (0.03, 0.01, -0.05))
    rng = np.random.default_rng(7)
    models = [base]
    for _ in range(3):
        models.append(
            replace(
                base,
                throw_angle=rng.uniform(0.0, 2 * np.pi, base.throws),
                rod_length=base.rod_length * rng.uniform(0.8, 1.3),
                speed=base.speed * rng.uniform(0.5, 1.5),
                cylinder_offset=base.cylinder_offset + rng.uniform(-3e-3, 3e-3),
                reciprocating_mass=base.reciprocating_mass * rng.uniform(0.8, 1.2),
            )
        )
    batch = batch_free_forces(stack_models(models), 6)
    for k, m in enumerate(models):
        one = free_forces(m, 6)
        scale = np.abs(one.roll).max()
        assert scale > 0
        np.testing.assert_allclose(batch.roll[k], one.roll, rtol=0, atol=1e-9 * scale)
        assert abs(batch.rotating_roll[k] - one.rotating_roll) <= 1e-9 * abs(one.rotating_roll)
