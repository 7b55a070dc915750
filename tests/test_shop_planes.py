"""Two-plane balancing-machine readings (crankbalance.physics.shop.planes) against hand
calculations.

Units in the hand calculations: g, mm, g mm; the module works in kg, m, kg m
(1 g mm = 1e-6 kg m).
"""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crankbalance.errors import InputError
from crankbalance.physics.shop import planes as sp

G_MM = 1e-6  # kg m per g mm
MEASURING = (0.0, 0.400)  # machine supports, m
CORRECTION = (0.100, 0.300)  # counterweight faces, m


def test_reading_heavy_and_light_spot() -> None:
    # 10 g at 50 mm at 90 deg: 500 g mm; heavy spot at 90 deg, light spot means the
    # unbalance sits at 270 deg
    heavy = sp.reading_unbalance(0.010, 0.050, math.pi / 2, "heavy")
    light = sp.reading_unbalance(0.010, 0.050, math.pi / 2, "light")
    assert heavy == pytest.approx(500 * G_MM * 1j, abs=1e-15)
    assert light == pytest.approx(-500 * G_MM * 1j, abs=1e-15)


def test_transfer_by_hand() -> None:
    # 500 g mm at 0 deg in measuring plane A (z = 0), nothing in B (z = 400 mm);
    # correction planes at 100 and 300 mm, span 200 mm:
    # U1 = 500 (300 - 0)/200 = 750 g mm at 0 deg, U2 = 500 (0 - 100)/200 = -250 g mm
    # check: 750 - 250 = 500 (resultant); 100*750 - 300*250 = 0 = 0*500 (moment about 0)
    plan = sp.plan_correction([500 * G_MM, 0.0], MEASURING, CORRECTION, 0.050)
    assert plan.unbalance / G_MM == pytest.approx([750.0, -250.0], abs=1e-9)
    assert plan.amount / G_MM == pytest.approx([750.0, 250.0])
    assert np.degrees(plan.remove_angle) == pytest.approx([0.0, 180.0])
    assert np.degrees(plan.add_angle) == pytest.approx([180.0, 0.0])
    # at 50 mm: 15 g and 5 g
    assert plan.mass * 1e3 == pytest.approx([15.0, 5.0])
    assert plan.correction == pytest.approx(-plan.unbalance)
    assert plan.influence_method == "rigid"


def test_transfer_two_readings_by_hand() -> None:
    # A: 8 g at 50 mm at 0 deg (400 g mm), B: 6 g at 50 mm at 90 deg (300j g mm),
    # light-spot readings: the unbalances are -400 and -300j.
    # U1 = (-400 (300 - 0) - 300j (300 - 400)) / 200 = -600 + 150j
    # U2 = (-400 (0 - 100) - 300j (400 - 100)) / 200 = 200 - 450j
    reading = sp.reading_unbalance([0.008, 0.006], 0.050, [0.0, math.pi / 2], "light")
    plan = sp.plan_correction(reading, MEASURING, CORRECTION, [0.050, 0.040])
    assert plan.unbalance / G_MM == pytest.approx([-600 + 150j, 200 - 450j])
    assert plan.amount[0] / G_MM == pytest.approx(math.hypot(600, 150))
    assert math.degrees(plan.remove_angle[0]) == pytest.approx(
        180 - math.degrees(math.atan(150 / 600))
    )
    # plane 2 corrected at 40 mm: |200 - 450j| / 40 g
    assert plan.mass[1] * 1e3 == pytest.approx(math.hypot(200, 450) / 40)


def test_planes_equal_measuring_is_identity() -> None:
    reading = np.array([3e-4 + 1e-4j, -2e-4j])
    plan = sp.plan_correction(reading, CORRECTION, CORRECTION, 0.05)
    assert plan.unbalance == pytest.approx(reading)


def test_rigid_influence_inverts_the_transfer() -> None:
    a = sp.rigid_influence(MEASURING, CORRECTION)
    t = sp.transfer_matrix(MEASURING, CORRECTION)
    assert a @ t == pytest.approx(np.eye(2))
    # by hand: a unit correction in plane 1 (z = 100 mm) reads (400-100)/400 in A and
    # 100/400 in B
    assert a[:, 0] == pytest.approx([0.75, 0.25])


def test_residual_after_a_rounded_correction() -> None:
    plan = sp.plan_correction([500 * G_MM, 0.0], MEASURING, CORRECTION, 0.050)
    assert sp.predicted_residual(plan, plan.correction) == pytest.approx([0, 0], abs=1e-18)
    # holes rounded: plane 1 removes 740 g mm instead of 750 at 0 deg, plane 2 adds
    # 250 g mm one degree off; residuals 10 g mm at 0 deg and 250 (e^{i pi/180} - 1)
    applied = [-740 * G_MM, 250 * G_MM * cmath.exp(1j * math.radians(1.0))]
    residual = sp.predicted_residual(plan, applied) / G_MM
    assert residual[0] == pytest.approx(10.0)
    assert abs(residual[1]) == pytest.approx(2 * 250 * math.sin(math.radians(0.5)))
    # the machine would read the residual transferred back to the measuring planes
    reading = sp.predicted_reading(plan, applied) / G_MM
    assert reading == pytest.approx(sp.rigid_influence(MEASURING, CORRECTION) @ residual)


def test_second_reading_learns_a_calibration_error() -> None:
    # the machine reads 0.8 e^{i 10 deg} times what a rigid rotor should give (gain and
    # phase error). First plan (rigid): W1 = -U. The rotor's true unbalance U_true with
    # R0 = g A U_true; after W1 the reading is R1 = R0 + g A W1 = (1 - g) R0.
    # The rank-one update A1 = A + (dR - A W1) W1^H / |W1|^2 gives A1 W1 = g A W1, and
    # since R1 is along A W1 the next plan W2 = -A1^{-1} R1 = (1 - g)/g W1 is exact.
    g = 0.8 * cmath.exp(1j * math.radians(10.0))
    a = sp.rigid_influence(MEASURING, CORRECTION)
    true_unbalance = np.array([400 + 100j, -150 + 300j]) * G_MM
    r0 = g * a @ true_unbalance
    first = sp.plan_correction(r0, MEASURING, CORRECTION, 0.05)
    r1 = r0 + g * a @ first.correction
    assert r1 == pytest.approx((1 - g) * r0)
    second = sp.second_reading(first, first.correction, r1)
    assert second.influence_method == "rank-one update"
    assert second.correction == pytest.approx((1 - g) / g * first.correction)
    r2 = r1 + g * a @ second.correction
    assert np.abs(r2) == pytest.approx([0, 0], abs=1e-15)
    # total correction made equals minus the true unbalance
    assert first.correction + second.correction == pytest.approx(-true_unbalance)


def test_two_trial_runs_give_the_influence_matrix() -> None:
    # the classical two-plane method: a trial mass in plane 1, then one in plane 2;
    # each column of A is the reading change over the trial unbalance
    true_a = np.array([[0.9 + 0.1j, 0.3 - 0.05j], [0.2j, 1.1 + 0.2j]])
    true_u = np.array([250 - 80j, 120 + 60j]) * G_MM
    r0 = true_a @ true_u
    plan = sp.plan_correction(r0, MEASURING, CORRECTION, 0.05)
    trial1 = np.array([100 * G_MM, 0.0])
    r1 = r0 + true_a @ trial1
    plan = sp.second_reading(plan, trial1, r1)
    trial2 = np.array([0.0, 100j * G_MM])
    r2 = r1 + true_a @ trial2
    plan = sp.second_reading(plan, trial2, r2)
    assert plan.influence_method == "least squares"
    # by hand: column 1 = (r1 - r0)/100 g mm, column 2 = (r2 - r1)/(100j g mm)
    assert plan.influence[:, 0] == pytest.approx((r1 - r0) / (100 * G_MM))
    assert plan.influence[:, 1] == pytest.approx((r2 - r1) / (100j * G_MM))
    assert plan.influence == pytest.approx(true_a)
    final = r2 + true_a @ plan.correction
    assert np.abs(final) == pytest.approx([0, 0], abs=1e-15)
    assert plan.applied_runs.shape == (2, 2)


def test_iso_check_by_hand() -> None:
    # Hoem and Rosholm (2016): G 6.3, 2.7 kg, 15200 rpm -> U_per = 10.69 g mm;
    # centre of mass mid-span, correction planes at the bearings: 5.345 g mm each
    speed = 15200 * 2 * math.pi / 60
    check = sp.iso_check(
        [4.0 * G_MM, 6.0j * G_MM], "G6.3", 2.7, speed, (0.0, 0.1), 0.05, (0.0, 0.1)
    )
    assert check.tolerance / G_MM == pytest.approx([5.345, 5.345], rel=1e-3)
    assert [v.passed for v in check.verdicts] == [True, False]
    assert not check.passed
    assert check.residual / G_MM == pytest.approx([4.0, 6.0])


def test_iso_tolerance_follows_the_plane_order_given() -> None:
    # centre of mass at 20 mm of a 100 mm span: lever rule 0.8 on bearing A, held at 0.7
    # (30-70 % rule); planes at the bearings: 0.7 U_per at z = 0, 0.3 U_per at z = 0.1
    speed = 1000.0
    total = 0.0063 * 3.0 / speed
    _, forward = sp.plane_tolerances("G6.3", 3.0, speed, (0.0, 0.1), 0.02, (0.0, 0.1))
    _, reverse = sp.plane_tolerances("G6.3", 3.0, speed, (0.1, 0.0), 0.02, (0.1, 0.0))
    assert forward == pytest.approx([0.7 * total, 0.3 * total])
    assert reverse == pytest.approx([0.3 * total, 0.7 * total])


def test_bad_input_names_the_field() -> None:
    with pytest.raises(InputError, match="correction_planes"):
        sp.plan_correction([1e-4, 0], MEASURING, (0.1, 0.1), 0.05)
    with pytest.raises(InputError, match="convention"):
        sp.reading_unbalance(0.01, 0.05, 0.0, "heavy-spot")  # type: ignore[arg-type]
    with pytest.raises(InputError, match="correction_radius"):
        sp.plan_correction([1e-4, 0], MEASURING, CORRECTION, 0.0)
    with pytest.raises(InputError, match="reading"):
        sp.plan_correction([1e-4, math.nan], MEASURING, CORRECTION, 0.05)
    with pytest.raises(InputError, match="influence"):
        sp.plan_correction([1e-4, 0], MEASURING, CORRECTION, 0.05, [[1, 1], [1, 1]])
    with pytest.raises(InputError, match="mass"):
        sp.reading_unbalance(-0.01, 0.05, 0.0)


planes = st.floats(-1.0, 1.0, allow_nan=False)
parts = st.complex_numbers(max_magnitude=1e-3, allow_nan=False, allow_infinity=False)


@settings(derandomize=True, database=None, deadline=None, max_examples=100)
@given(st.lists(planes, min_size=1, max_size=6), planes, planes, st.data())
def test_transfer_keeps_resultant_and_moment(source, z1, z2, data) -> None:
    if abs(z2 - z1) < 1e-3:
        return
    u = np.array(data.draw(st.lists(parts, min_size=len(source), max_size=len(source))))
    moved = sp.transfer_matrix(source, (z1, z2)) @ u
    scale = max(1e-3, float(np.abs(u).sum()))
    assert abs(moved.sum() - u.sum()) <= 1e-9 * scale
    assert abs(z1 * moved[0] + z2 * moved[1] - np.dot(source, u)) <= 1e-9 * scale / abs(z2 - z1)
