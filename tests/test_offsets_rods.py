"""Per-cylinder offsets and rods side by side on a shared crankpin (issue 17).

References: the exact time domain (:func:`crankbalance.physics.shaking.exact_time_domain`) and a
numerical second derivative of the piston positions; a hand sum of each cylinder's closed
form; hand calculations of the rocking couple of a 90-degree L-twin with side-by-side rods;
the same engine with its pin split into two throws by hand (the issue's workaround).
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.physics.balancing import CounterweightOptions, balance
from crankbalance.physics.kinematics import harmonic_coefficients, piston_position
from crankbalance.physics.model import EngineModel
from crankbalance.physics.shaking import (
    curves,
    cylinder_coefficients,
    exact_time_domain,
    free_forces,
    phasor_curve,
    reciprocating_phasors,
)
from crankbalance.schema.engine import EngineSpec, spec_from_dict
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import analyze

from .conftest import run_cli


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


def test_batch_of_side_by_side_rods_is_the_one_engine_solver() -> None:
    """Rods side by side on a pin keep the topology's places and big ends in a batch: the
    batch gives each engine's one-engine numbers (the same solver), couples included."""
    from crankbalance.physics.balance_batch import balance_batch
    from crankbalance.physics.model import engine_batch

    m = l_twin((0.3, 0.36))
    batch = engine_batch(m, 3, speed=[500.0, 700.0, 900.0], reciprocating_mass=[0.5, 0.6])
    options = CounterweightOptions(0.03, balance_factor=0.5)
    result = balance_batch(batch, options)
    assert result.counterweights is not None
    for k in range(3):
        one = balance(batch.model(k), options)
        assert one.counterweights is not None
        np.testing.assert_allclose(
            result.counterweights.moments[k], one.counterweights.moments, rtol=1e-12
        )
        for j, name in enumerate(result.residuals.components):
            want = one.residual(name)
            assert result.residuals.moment_before[k, j] == pytest.approx(
                want.moment_before, rel=1e-12
            )
            assert result.residuals.moment_after[k, j] == pytest.approx(
                want.moment_after, rel=1e-12, abs=1e-9
            )
    assert one.residual("rotating").moment_before > 1.0, "the big ends' couple is there"


def test_batch_takes_per_cylinder_offsets() -> None:
    """EngineBatch carries each cylinder's offset: engine k of a batch is the model."""
    from crankbalance.physics.balance_batch import balance_batch
    from crankbalance.physics.model import engine_batch

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


# --------------------------------------------------------------------------- engine file
def spec_of(name: str, **crank_train: object) -> EngineSpec:
    data = load_engine(name).to_data()
    data["crank_train"].update(crank_train)
    return spec_from_dict(data)


def test_bank_offsets_go_to_the_cylinders_of_their_bank() -> None:
    """vee: bank A = cylinders 1..T, B = T+1..2T; W: bank after bank; boxer: odd cylinders
    (bank -90 deg) and even ones (+90 deg); pin and crank offsets added to every one."""
    vee = build_model(spec_of("v6-90", bank_offsets=["1 mm", "-2 mm"], pin_offset="0.5 mm"))
    np.testing.assert_allclose(vee.cylinder_offset, [1.5e-3] * 3 + [-1.5e-3] * 3, atol=1e-15)
    crank = [f"{a} deg" for a in np.degrees(build_model(load_engine("w12")).throw_angle)]
    w = build_model(spec_of("w12", bank_offsets=["1 mm", "0 mm", "-1 mm"], throw_angles=crank))
    np.testing.assert_allclose(w.cylinder_offset, np.repeat([1e-3, 0.0, -1e-3], 4), atol=1e-15)
    assert np.all(np.diff(np.degrees(w.cylinder_bank)[::4]) > 0), "banks -V, 0, +V"
    boxer = build_model(spec_of("boxer4", bank_offsets=["2 mm", "-3 mm"]))
    np.testing.assert_allclose(boxer.cylinder_offset, [2e-3, -3e-3] * 2, atol=1e-15)
    np.testing.assert_allclose(np.degrees(boxer.cylinder_bank), [-90, 90] * 2)
    each = build_model(spec_of("inline3", cylinder_offsets=["1 mm", "2 mm", "-4 mm"]))
    np.testing.assert_allclose(each.cylinder_offset, [1e-3, 2e-3, -4e-3], atol=1e-15)


@pytest.mark.parametrize(
    ("name", "fields", "field", "words"),
    [
        ("inline4", {"bank_offsets": ["1 mm"]}, "bank_offsets", "cylinder_offsets"),
        ("v6-90", {"bank_offsets": ["1 mm"]}, "bank_offsets", "one offset per bank: 2"),
        (
            "v6-90",
            {"bank_offsets": ["1 mm", "1 mm"], "cylinder_offsets": ["1 mm"] * 6},
            "cylinder_offsets",
            "not both",
        ),
        ("inline4", {"cylinder_offsets": ["1 mm"] * 3}, "cylinder_offsets", "4 for this"),
        ("v2-90", {"rod_positions": ["10 mm"]}, "rod_positions", "one length per cylinder"),
        ("inline3", {"cylinder_offsets": ["0 mm", "0 mm", "-110 mm"]}, "cylinder_offsets", "rod"),
    ],
)
def test_bad_offsets_and_rod_positions_are_refused(
    name: str, fields: dict[str, object], field: str, words: str
) -> None:
    with pytest.raises(InputError) as error:
        spec_of(name, **fields)
    assert error.value.field == f"crank_train.{field}"
    assert words in str(error.value)


def test_rod_positions_need_the_conrod_to_place_the_big_end() -> None:
    data = load_engine("v2-90").to_data()
    data["crank_train"]["rod_positions"] = ["-10 mm", "10 mm"]
    data["masses"] = {"reciprocating": "400 g", "rotating": "1.5 kg"}
    with pytest.raises(InputError) as error:
        build_model(spec_from_dict(data))
    assert error.value.field == "crank_train.rod_positions"
    assert "conrod" in str(error.value)


def tdc_crank_angles(m: EngineModel) -> np.ndarray:
    """Crank angle of each cylinder's top dead centre, found numerically: the piston
    position at its largest (no formula of the TDC angle used)."""
    out = []
    for c in range(m.cylinders):
        shift = m.cylinder_angle[c] - m.cylinder_bank[c]

        def minus_s(theta: float, shift: float = shift, c: int = c) -> float:
            return -float(
                piston_position(theta + shift, m.crank_radius, m.rod_length, m.cylinder_offset[c])
            )

        grid = np.linspace(0, 2 * np.pi, 3601)
        start = grid[np.argmin([minus_s(t) for t in grid])]
        found = minimize_scalar(
            minus_s, bracket=(start - 0.01, start, start + 0.01), tol=1e-12, method="brent"
        )
        out.append(found.x)
    return np.array(out)


@pytest.mark.parametrize(
    ("name", "fields"),
    [
        ("inline3", {"cylinder_offsets": ["0 mm", "6 mm", "-9 mm"]}),
        ("inline4", {"cylinder_offsets": ["3 mm", "0 mm", "-2 mm", "8 mm"]}),
        ("boxer4", {"bank_offsets": ["4 mm", "-7 mm"]}),
    ],
)
def test_even_firing_stays_even_with_offset_cylinders(name: str, fields: dict[str, object]) -> None:
    """The k-th cylinder to fire reaches its top dead centre k firing intervals after the
    first (modulo a turn), each piston's TDC found numerically from its position."""
    spec = spec_of(name, **fields)
    m = build_model(spec)
    n = m.cylinders
    interval = 4 * np.pi / n
    order = list(m.firing_order)
    tdc = tdc_crank_angles(m)
    for k, cylinder in enumerate(order):
        gap = tdc[cylinder - 1] - tdc[order[0] - 1] - k * interval
        assert abs(math.remainder(gap, 2 * np.pi)) < 1e-7, (name, cylinder, np.degrees(gap))
    # without the TDC correction the firing would be uneven by asin(e / (l + r))
    assert np.ptp(m.cylinder_offset) > 0


def test_offsets_on_a_shared_pin_cannot_fire_evenly() -> None:
    with pytest.raises(InputError) as error:
        build_model(spec_of("v8-flatplane", bank_offsets=["3 mm", "-3 mm"]))
    assert error.value.field == "crank_train.firing_order"
    assert "top dead centres" in str(error.value)


def test_moment_reference_moves_every_couple_by_the_force() -> None:
    r"""About a point p from the mid-point: C_p = sum (y - p) F = C - p F, each phasor and the
    rotating couple; the forces and the counterweight masses do not change."""
    p = 0.05
    mid = build_model(load_engine("v8-crossplane"))
    moved = build_model(spec_of("v8-crossplane", moment_reference="50 mm"))
    assert moved.moment_reference == pytest.approx(p, abs=1e-15)
    a, b = free_forces(mid, 6), free_forces(moved, 6)
    scale = float(mid.reciprocating_mass.sum() * mid.crank_radius * mid.speed**2)
    np.testing.assert_allclose(b.force_forward, a.force_forward, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(
        b.couple_forward, a.couple_forward - p * a.force_forward, rtol=0, atol=1e-12 * scale
    )
    np.testing.assert_allclose(
        b.couple_backward, a.couple_backward - p * a.force_backward, rtol=0, atol=1e-12 * scale
    )
    assert b.rotating_couple == pytest.approx(a.rotating_couple - p * a.rotating_force)
    for scope in ("whole", "halves"):
        options = CounterweightOptions(0.04, balance_factor=0.5, scope=scope)
        x, y = balance(mid, options).counterweights, balance(moved, options).counterweights
        assert x is not None and y is not None
        np.testing.assert_allclose(y.mass, x.mass, rtol=1e-9)
        np.testing.assert_allclose(y.position, x.position - p, atol=1e-12)
    text = analyze(moved).to_dict()["conventions"]
    assert "50 mm from the crankshaft mid-point" in text


def test_custom_positions_are_taken_from_the_crank_mid_point() -> None:
    """A custom crank measured from its nose (all positions shifted) has the moments of the
    same crank measured from its middle; moment_reference then moves the point."""
    data = load_engine("v6-60").to_data()
    for throw in data["crank_train"]["throw"]:
        throw["position"] = f"{float(throw['position'].split()[0]) + 300.0} mm"
    nose = build_model(spec_from_dict(data))
    middle = build_model(load_engine("v6-60"))
    np.testing.assert_allclose(nose.throw_position, middle.throw_position, atol=1e-12)
    a, b = free_forces(nose, 4), free_forces(middle, 4)
    np.testing.assert_allclose(a.couple_forward, b.couple_forward, atol=1e-9)


def test_ducati_and_harley_presets_by_hand() -> None:
    """Ducati 916: the first-order couple of rods 20 mm apart on a 90-degree common pin is
    a backward couple of m r w^2 a (a = 10 mm; hand calculation above); the Harley's
    knife-and-fork rods in one plane leave no couple at all."""
    d = build_model(load_engine("ducati-916"))
    np.testing.assert_allclose(d.cylinder_axial, [-0.01, 0.01])
    f = free_forces(d, 2)
    mrw2 = d.reciprocating_mass[0] * d.crank_radius * d.speed**2
    assert f.moment_amplitude[0] == pytest.approx(mrw2 * 0.01, rel=1e-12)
    assert 150 < f.moment_amplitude[0] < 250, "the issue's case: 191 N m"
    h = build_model(load_engine("harley-45"))
    assert np.all(h.cylinder_axial == 0.0)
    assert np.all(free_forces(h, 8).moment_amplitude == 0.0)
    engine = analyze("ducati-916").to_dict()["engine"]
    assert engine["cylinder_axial_m"] == [-0.01, 0.01]
    assert engine["cylinder_offset_m"] == [0.0, 0.0]


def test_explorer_merits_take_per_cylinder_offsets_and_a_moved_reference() -> None:
    """The explorer's batch columns equal the one-engine analysis and solver for a W12 whose
    cylinders have their own offsets and whose moments are taken 30 mm off its middle."""
    from crankbalance.physics.balancing import ShaftOptions
    from crankbalance.physics.explore.merit import merit

    from .test_explore_merit import random_candidates

    base = build_model(load_engine("w12"))
    topology = replace(
        base,
        cylinder_offset=np.linspace(-0.004, 0.005, base.cylinders),
        throw_position=base.throw_position - 0.03,
    )
    cands = random_candidates(topology, 4, seed=5)
    shaft = ShaftOptions(cg_radius=0.03, length=0.2)
    cw = CounterweightOptions(cg_radius=topology.crank_radius, angle="optimal", balance_factor=0.4)
    out = merit(cands, target="secondary", shafts=shaft, balance_factor=0.4)
    scale = float(topology.reciprocating_mass.sum() * topology.crank_radius * topology.speed**2)
    for i in range(cands.size):
        model = replace(topology, throw_angle=cands.throw_angle[i])
        f = free_forces(model, 8)
        for k, n in enumerate(f.orders):
            assert out[f"F{n}_N"][i] == pytest.approx(f.force_amplitude[k], abs=1e-9 * scale)
            assert out[f"M{n}_Nm"][i] == pytest.approx(f.moment_amplitude[k], abs=1e-9 * scale)
        one = balance(model, cw, shaft, shaft, 8)
        assert one.counterweights is not None
        assert out["cw_mass_kg"][i] == pytest.approx(one.counterweights.mass.sum(), rel=1e-7)
    # the offsets matter: the same cranks with one offset give other forces
    plain = merit(
        replace(cands, topology=replace(topology, cylinder_offset=np.zeros(base.cylinders))),
        target="secondary",
        shafts=shaft,
        balance_factor=0.4,
    )
    assert np.abs(plain["F1_N"] - out["F1_N"]).max() > 1e-4 * scale


def test_balance_factor_share_sits_at_the_rods_places() -> None:
    """With a balance factor b the counterweights carry the rotating masses and b times the
    reciprocating masses, each at its own axial place: their couple is, by hand,
    -r w^2 e^{i phi} [(m_b2 - m_b1) a + b (m_2 - m_1) a] for rods at -a and +a."""
    m = make_model(
        throw_angle=[30.0],
        throw_position=[0.0],
        cylinder_throw=[0, 0],
        bank_deg=[-45.0, 45.0],
        offset=[0.0, 0.0],
        axial=[-A, A],
        big_end=[0.30, 0.36],
        rotating=[2.66],
        reciprocating=[0.6, 0.7],
    )
    b = 0.5
    res = balance(m, CounterweightOptions(0.03, balance_factor=b, method="individual"))
    cw = res.counterweights
    assert cw is not None
    turn = m.crank_radius * np.exp(1j * m.throw_angle[0])
    want_c = -turn * ((0.36 - 0.30) * A + b * (0.7 - 0.6) * A)
    want_f = -turn * (2.66 + b * 1.3)
    assert (cw.moments * cw.position).sum() == pytest.approx(want_c, rel=1e-12)
    assert cw.moments.sum() == pytest.approx(want_f, rel=1e-12)


def test_cli_names_rod_positions_offsets_and_the_reference(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code, out, _ = run_cli(["analyze", "ducati-916"], capsys)
    assert code == 0
    assert "Rod position on its pin per cylinder: -10 mm, 10 mm" in out
    assert "moments about the crankshaft mid-point" in out
    data = load_engine("inline3").to_data()
    data["crank_train"].update(cylinder_offsets=["1 mm", "0 mm", "-2 mm"], moment_reference="40 mm")
    path = tmp_path / "engine.json"
    path.write_text(json.dumps(data))
    code, out, _ = run_cli(["analyze", str(path)], capsys)
    assert code == 0
    assert "Offset per cylinder: 1 mm, 0 mm, -2 mm" in out
    assert "moments about the point 40 mm from the crankshaft mid-point" in out
    data["crank_train"]["bank_offsets"] = ["1 mm"]
    path.write_text(json.dumps(data))
    code, _, err = run_cli(["analyze", str(path)], capsys)
    assert code == 2
    assert "crank_train.bank_offsets" in err
