"""Per-cylinder offsets and rods side by side on a shared crankpin (issue 17).

References: the exact time domain (:func:`crankbalance.shaking.exact_time_domain`) and a
numerical second derivative of the piston positions; a hand sum of each cylinder's closed
form; hand calculations of the rocking couple of a 90-degree L-twin with side-by-side rods;
the same engine with its pin split into two throws by hand (the issue's workaround).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankbalance.balancing import CounterweightOptions, balance, engine_batch
from crankbalance.errors import InputError
from crankbalance.kinematics import harmonic_coefficients, piston_position
from crankbalance.model import EngineModel
from crankbalance.shaking import (
    curves,
    cylinder_coefficients,
    exact_time_domain,
    free_forces,
    phasor_curve,
    reciprocating_phasors,
)


def make_model(
    *,
    throw_angle: list[float],
    throw_position: list[float],
    cylinder_throw: list[int],
    bank_deg: list[float],
    offset: list[float],
    axial: list[float] | None = None,
    big_end: list[float] | None = None,
    rotating: list[float] | None = None,
    reciprocating: list[float] | None = None,
    kinematics: str = "exact",
) -> EngineModel:
    c = len(cylinder_throw)
    return EngineModel(
        name="test",
        speed=700.0,
        kinematics=kinematics,
        crank_radius=0.04,
        rod_length=0.13,
        strokes=4,
        throw_angle=np.radians(throw_angle),
        throw_position=np.array(throw_position, dtype=float),
        throw_rotating_mass=np.array(rotating or [1.2] * len(throw_angle), dtype=float),
        cylinder_throw=np.array(cylinder_throw, dtype=np.int64),
        cylinder_bank=np.radians(bank_deg),
        reciprocating_mass=np.array(reciprocating or [0.5 + 0.07 * k for k in range(c)]),
        cylinder_offset=np.array(offset, dtype=float),
        cylinder_axial=np.zeros(c) if axial is None else np.array(axial, dtype=float),
        cylinder_rotating_mass=np.zeros(c) if big_end is None else np.array(big_end),
        firing_order=tuple(range(1, c + 1)),
    )


def odd_v6(offset: list[float]) -> EngineModel:
    """A 60-degree-ish V6 with uneven throws, three pins of two rods each."""
    return make_model(
        throw_angle=[0.0, 113.0, 251.0],
        throw_position=[-0.09, 0.0, 0.1],
        cylinder_throw=[0, 1, 2, 0, 1, 2],
        bank_deg=[-33.0, -33.0, -33.0, 27.0, 27.0, 27.0],
        offset=offset,
    )


DIFFERENT = [0.0012, -0.0031, 0.0049, 0.0, 0.0022, -0.0009]


def test_equal_offsets_give_the_numbers_of_one_shared_offset() -> None:
    """All cylinders with one offset: the per-cylinder form gives, to the last bit, the
    phasors of the coefficients shared by every cylinder (the form before issue 17)."""
    m = odd_v6([0.0025] * 6)
    f = free_forces(m, 10)
    c = harmonic_coefficients(m.rod_ratio, 10, 0.0025 / m.crank_radius)
    shared = reciprocating_phasors(
        c,
        m.reciprocating_mass,
        m.cylinder_angle,
        m.cylinder_bank,
        m.cylinder_position,
        m.crank_radius,
        m.speed,
    )
    got = (f.force_forward, f.force_backward, f.couple_forward, f.couple_backward)
    for a, b in zip(got, shared, strict=True):
        np.testing.assert_array_equal(a, b)


def test_cylinder_coefficients_are_each_cylinders_own() -> None:
    m = odd_v6(DIFFERENT)
    rows = cylinder_coefficients(m, 8)
    assert rows.shape == (6, 8)
    for k, e in enumerate(DIFFERENT):
        want = harmonic_coefficients(m.rod_ratio, 8, e / m.crank_radius)
        np.testing.assert_allclose(rows[k], want, rtol=0, atol=1e-15)
    series = cylinder_coefficients(m, 8, "series")
    assert np.all(series == series[0]), "the series model neglects the offset"


def test_per_cylinder_offsets_against_a_hand_sum_of_closed_forms() -> None:
    r"""F_n^+ = sum_c P_c/2 c_{n,c} e^{i[n(phi-beta)+beta]} and F_n^- with conj(c_{n,c}),
    written out cylinder by cylinder (module docstring of shaking)."""
    m = odd_v6(DIFFERENT)
    k = 8
    f = free_forces(m, k)
    n = np.arange(1, k + 1)
    want = np.zeros((4, k), dtype=complex)
    for c in range(m.cylinders):
        cn = harmonic_coefficients(m.rod_ratio, k, m.cylinder_offset[c] / m.crank_radius)
        p = 0.5 * m.reciprocating_mass[c] * m.crank_radius * m.speed**2
        phi, beta, y = m.cylinder_angle[c], m.cylinder_bank[c], m.cylinder_position[c]
        fwd = p * cn * np.exp(1j * (n * (phi - beta) + beta))
        bwd = p * np.conj(cn) * np.exp(1j * (-n * (phi - beta) + beta))
        want += np.array([fwd, bwd, y * fwd, y * bwd])
    scale = float(m.reciprocating_mass.sum() * m.crank_radius * m.speed**2)
    got = np.array([f.force_forward, f.force_backward, f.couple_forward, f.couple_backward])
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-13 * scale)
    # and it is not the answer of one shared offset
    one = free_forces(odd_v6([DIFFERENT[0]] * 6), k)
    assert np.abs(one.force_forward - f.force_forward).max() > 1e-4 * scale


def test_per_cylinder_offsets_sum_of_orders_is_the_exact_time_domain() -> None:
    """Enough orders of the phasors rebuild the exact force and couple of every cylinder's
    own slider-crank, and those are the second derivative of the piston positions."""
    m = odd_v6(DIFFERENT)
    theta = np.linspace(0.0, 2 * np.pi, 97, endpoint=False)
    f = free_forces(m, 24)
    force = phasor_curve(f.force_forward, f.force_backward, f.orders, theta).sum(axis=0)
    couple = phasor_curve(f.couple_forward, f.couple_backward, f.orders, theta).sum(axis=0)
    exact_f, exact_c = exact_time_domain(m, theta)
    scale = float(m.reciprocating_mass.sum() * m.crank_radius * m.speed**2)
    assert np.abs(force - exact_f).max() < 1e-10 * scale
    assert np.abs(couple - exact_c).max() < 1e-10 * scale * 0.1
    # numerical differentiation of the piston positions (5-point stencil in the angle)
    h = 1e-2
    psi = theta[:, None] + (m.cylinder_angle - m.cylinder_bank)[None, :]

    def s(a: np.ndarray) -> np.ndarray:
        return piston_position(a, m.crank_radius, m.rod_length, m.cylinder_offset[None, :])

    d2 = (-s(psi + 2 * h) + 16 * s(psi + h) - 30 * s(psi) + 16 * s(psi - h) - s(psi - 2 * h)) / (
        12 * h * h
    )
    each = -m.reciprocating_mass * d2 * m.speed**2 * np.exp(1j * m.cylinder_bank)
    assert np.abs(each.sum(axis=1) - exact_f).max() < 1e-6 * scale
    numeric_c = (each * m.cylinder_position).sum(axis=1)
    assert np.abs(numeric_c - exact_c).max() < 1e-7 * scale
    # the curves of the analysis use the same time domain for the total
    total = curves(m, free_forces(m, 8), theta)
    np.testing.assert_allclose(total.total_fz, exact_f.real, rtol=0, atol=1e-9 * scale)


# --------------------------------------------------------------------------- side by side
A = 0.010  # rods 20 mm apart: each 10 mm from the throw centre


def l_twin(big_end: tuple[float, float] = (0.0, 0.0), offset: float = 0.0) -> EngineModel:
    """A 90-degree L-twin, one pin: cylinder 1 (bank -45 deg) at -10 mm, 2 at +10 mm."""
    return make_model(
        throw_angle=[0.0],
        throw_position=[0.0],
        cylinder_throw=[0, 0],
        bank_deg=[-45.0, 45.0],
        offset=[offset, offset],
        axial=[-A, A],
        big_end=list(big_end),
        rotating=[2.0 + sum(big_end)],
        reciprocating=[0.6, 0.6],
    )


def test_l_twin_rocking_couple_by_hand() -> None:
    r"""Rods at y = -a (bank -45) and +a (bank +45), equal masses m, no offset:
    first order C = m r w^2 a [cos(t-45)e^{i45} - cos(t+45)e^{-i45}] = m r w^2 a i e^{-it}
    (a backward couple of constant size m r w^2 a); second order
    C = m r w^2 A2 a sin(2t) (e^{i45} + e^{-i45}) = sqrt(2) m r w^2 A2 a sin 2t (along z)."""
    m = l_twin()
    mrw2 = 0.6 * m.crank_radius * m.speed**2
    f = free_forces(m, 4)
    k1, k2 = f.order(1), f.order(2)
    assert abs(f.couple_forward[k1]) < 1e-12 * mrw2
    assert f.couple_backward[k1] == pytest.approx(1j * mrw2 * A, rel=1e-13)
    a2 = harmonic_coefficients(m.rod_ratio, 2)[1].real
    assert f.moment_amplitude[k2] == pytest.approx(math.sqrt(2) * mrw2 * a2 * A, rel=1e-12)
    theta = np.linspace(0, 2 * np.pi, 36, endpoint=False)
    c2 = phasor_curve(f.couple_forward[1:2], f.couple_backward[1:2], [2], theta)[0]
    np.testing.assert_allclose(
        c2, math.sqrt(2) * mrw2 * a2 * A * np.sin(2 * theta), rtol=0, atol=1e-12 * mrw2
    )
    # the forces do not see where the rods sit
    plane = make_model(
        throw_angle=[0.0],
        throw_position=[0.0],
        cylinder_throw=[0, 0],
        bank_deg=[-45.0, 45.0],
        offset=[0.0, 0.0],
        rotating=[2.0],
        reciprocating=[0.6, 0.6],
    )
    np.testing.assert_allclose(f.force_forward, free_forces(plane, 4).force_forward, atol=1e-9)
    assert np.all(free_forces(plane, 4).moment_amplitude == 0.0)


def test_big_ends_side_by_side_give_a_rotating_couple() -> None:
    """Big ends of 0.30 and 0.36 kg at -a and +a turn with the pin: rotating couple
    r w^2 (0.36 - 0.30) a e^{i phi} by hand; equal big ends cancel."""
    m = l_twin((0.30, 0.36))
    f = free_forces(m, 2)
    rw2 = m.crank_radius * m.speed**2
    assert f.rotating_couple == pytest.approx(rw2 * 0.06 * A, rel=1e-12)
    assert f.rotating_force == pytest.approx(rw2 * m.throw_rotating_mass[0], rel=1e-15)
    assert abs(free_forces(l_twin((0.33, 0.33)), 2).rotating_couple) < 1e-15 * rw2


def test_side_by_side_rods_equal_a_pin_split_by_hand() -> None:
    """The issue's workaround: the pin split into two throws at -a and +a with one rod
    each (the crank's own rotating mass halved onto both) is the same engine."""
    m = l_twin((0.30, 0.36), offset=0.002)
    split = make_model(
        throw_angle=[0.0, 0.0],
        throw_position=[-A, A],
        cylinder_throw=[0, 1],
        bank_deg=[-45.0, 45.0],
        offset=[0.002, 0.002],
        rotating=[1.0 + 0.30, 1.0 + 0.36],
        reciprocating=[0.6, 0.6],
    )
    a, b = free_forces(m, 8), free_forces(split, 8)
    scale = 1.2 * m.crank_radius * m.speed**2
    for name in ("force_forward", "force_backward", "couple_forward", "couple_backward"):
        np.testing.assert_allclose(getattr(a, name), getattr(b, name), rtol=0, atol=1e-12 * scale)
    assert a.rotating_force == pytest.approx(b.rotating_force, rel=1e-14)
    assert a.rotating_couple == pytest.approx(b.rotating_couple, rel=1e-12)
    theta = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    for x, y in zip(exact_time_domain(m, theta), exact_time_domain(split, theta), strict=True):
        np.testing.assert_allclose(x, y, rtol=0, atol=1e-12 * scale)


def test_counterweights_carry_the_big_ends_couple() -> None:
    """Counterweights sized for the rotating masses leave no rotating force or couple, the
    big ends' couple included (balance checks it in the time domain, verify)."""
    m = make_model(
        throw_angle=[0.0, 180.0],
        throw_position=[-0.04, 0.04],
        cylinder_throw=[0, 0, 1, 1],
        bank_deg=[-45.0, 45.0, -45.0, 45.0],
        offset=[0.0] * 4,
        axial=[-A, A, -A, A],
        big_end=[0.30, 0.36, 0.30, 0.36],
        rotating=[2.0, 2.0],
    )
    f = free_forces(m, 2)
    assert abs(f.rotating_couple) > 0
    res = balance(m, CounterweightOptions(0.03))
    cw = res.counterweights
    assert cw is not None
    # the counterweights' own couple cancels the free rotating couple of free_forces
    w2 = m.speed**2
    assert abs(w2 * (cw.moments * cw.position).sum() + f.rotating_couple) < 1e-9 * abs(
        f.rotating_couple
    )
    assert abs(w2 * cw.moments.sum() + f.rotating_force) < 1e-9 * m.crank_radius * w2
    rot = res.residual("rotating")
    assert rot.moment_before > 1.0
    assert rot.moment_after < 1e-9 * rot.moment_before


def test_batch_solvers_refuse_side_by_side_rods() -> None:
    with pytest.raises(InputError, match="rod_positions"):
        engine_batch(l_twin((0.3, 0.3)), 2)


def test_batch_takes_per_cylinder_offsets() -> None:
    """EngineBatch carries each cylinder's offset: engine k of a batch is the model."""
    from crankbalance.balancing import balance_batch

    m = odd_v6(DIFFERENT)
    batch = engine_batch(m, 3, speed=[500.0, 700.0, 900.0])
    result = balance_batch(batch, CounterweightOptions(0.03))
    res = result.residuals
    for k in range(3):
        one = balance(batch.model(k), CounterweightOptions(0.03))
        np.testing.assert_allclose(batch.model(k).cylinder_offset, DIFFERENT, rtol=0, atol=0)
        for j, name in enumerate(res.components):
            want = one.residual(name)
            assert res.force_before[k, j] == pytest.approx(want.force_before, rel=1e-9, abs=1e-6)
            assert res.moment_before[k, j] == pytest.approx(want.moment_before, rel=1e-9, abs=1e-6)
        np.testing.assert_allclose(
            result.counterweights.moments[k], one.counterweights.moments, rtol=1e-9, atol=1e-15
        )
