"""Unit tests of crankbalance.physics.tolerance (ISO 21940-11 grades and plane allocation)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.physics import tolerance as tl


def test_grade_series() -> None:
    values = [g.value * 1000 for g in tl.GRADES]
    assert values == [4000, 1600, 630, 250, 100, 40, 16, 6.3, 2.5, 1, 0.4]
    # ISO grades step by a factor of about 2.5
    ratios = np.array(values[:-1]) / np.array(values[1:])
    assert np.all((ratios > 2.3) & (ratios < 2.7))
    assert all(g.crank_drive for g in tl.GRADES if g.value >= 0.0063)


@pytest.mark.parametrize("text", ["G6.3", "g 6.3", "6.3", 6.3, " G6.30 "])
def test_grade_lookup(text) -> None:
    assert tl.balance_grade(text).name == "G 6.3"


@pytest.mark.parametrize("bad", ["G7", "H6.3", "", 5, True])
def test_unknown_grade(bad) -> None:
    with pytest.raises(InputError) as info:
        tl.balance_grade(bad)
    assert info.value.field == "grade" and "G6.3" in str(info.value)


def test_permissible_unbalance_formula() -> None:
    omega = 3000 * 2 * math.pi / 60
    u = tl.permissible_unbalance("G2.5", 10.0, omega)
    # U [g mm] = 1000 G [mm/s] m [kg] / Omega [rad/s]
    assert u * 1e6 == pytest.approx(1000 * 2.5 * 10.0 / omega, rel=1e-12)
    assert tl.specific_unbalance("G2.5", omega) == pytest.approx(u / 10.0, rel=1e-12)
    with pytest.raises(InputError, match="rotor_mass"):
        tl.permissible_unbalance("G2.5", -1.0, omega)
    with pytest.raises(InputError, match="speed"):
        tl.permissible_unbalance("G2.5", 1.0, 0.0)


def test_allocation_planes_at_bearings_symmetric() -> None:
    a = tl.allocate_to_planes(1.0, 0.0, 0.2, 0.1)
    assert (a.bearing_a, a.bearing_b, a.plane_1, a.plane_2) == pytest.approx((0.5,) * 4)


def test_allocation_lever_rule_and_limits() -> None:
    a = tl.allocate_to_planes(1.0, 0.0, 0.2, 0.08)
    assert a.bearing_a == pytest.approx(0.6) and a.bearing_b == pytest.approx(0.4)
    far = tl.allocate_to_planes(1.0, 0.0, 0.2, 0.01)
    assert far.bearing_a == pytest.approx(0.7) and far.bearing_b == pytest.approx(0.3), (
        "ISO 21940-11 cl. 7: each bearing share within 30-70 % of U_per"
    )


def test_allocation_inboard_symmetric_is_half() -> None:
    a = tl.allocate_to_planes(1.0, 0.0, 0.3, 0.15, 0.05, 0.25)
    assert a.plane_1 == pytest.approx(0.5) and a.plane_2 == pytest.approx(0.5)


def test_allocation_outboard_symmetric_reduced_by_l_over_b() -> None:
    # bearings 0..0.2 m, planes at -0.05 and 0.25 m: b = 0.3 m
    a = tl.allocate_to_planes(1.0, 0.0, 0.2, 0.1, -0.05, 0.25)
    assert a.plane_1 == pytest.approx(0.5 * 0.2 / 0.3)
    assert a.plane_2 == pytest.approx(0.5 * 0.2 / 0.3)


@pytest.mark.parametrize(
    "geometry",
    [(0.0, 0.2, 0.07, -0.03, 0.12), (0.0, 0.25, 0.15, 0.05, 0.3), (0.1, 0.4, 0.2, 0.0, 0.5)],
)
def test_allocation_worst_phase_by_brute_force(geometry) -> None:
    za, zb, zc, z1, z2 = geometry
    a = tl.allocate_to_planes(1.0, za, zb, zc, z1, z2)
    span = zb - za
    phase = np.linspace(0, 2 * np.pi, 3601)
    u1, u2 = a.plane_1, a.plane_2 * np.exp(1j * phase)
    # rigid-body statics: reactions equivalent to the two plane unbalances
    at_a = np.abs(u1 * (zb - z1) / span + u2 * (zb - z2) / span)
    at_b = np.abs(u1 * (z1 - za) / span + u2 * (z2 - za) / span)
    assert at_a.max() <= a.bearing_a * (1 + 1e-9)
    assert at_b.max() <= a.bearing_b * (1 + 1e-9)
    # and the rule is tight: one of the bearings reaches its share
    assert max(at_a.max() / a.bearing_a, at_b.max() / a.bearing_b) == pytest.approx(1, rel=1e-5)


def test_allocation_bad_geometry() -> None:
    with pytest.raises(InputError, match="bearing_b"):
        tl.allocate_to_planes(1.0, 0.2, 0.1, 0.15)
    with pytest.raises(InputError, match="plane_2"):
        tl.allocate_to_planes(1.0, 0.0, 0.2, 0.1, 0.1, 0.05)


def test_verdict() -> None:
    v = tl.check_residual(7.39e-6, 10.69e-6)
    assert v.passed and v.ratio == pytest.approx(7.39 / 10.69)
    assert not tl.check_residual(11e-6, 10.69e-6).passed
    with pytest.raises(InputError, match="residual"):
        tl.check_residual(-1e-6, 10.69e-6)
