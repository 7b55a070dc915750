"""Hoem and Røsholm (2016) chapter 5: the simplified test rotor on the simulated bench.

Rotor (Appendix E, Table 7.2 as printed): disc d1 = 98 mm, t = 36.704 mm, journals d2 = 20 mm,
overall L1 = 188 mm, steel 7850 kg/m^3 -> m = 2.546 kg. (t = 36.704 mm follows from the inertia
with d1 = 100 mm, docs/references.md; the thesis' Table 5.5 is reproduced with the printed 98 mm.)
Unbalance (Table 5.2): 14.6 g (case 2) and 58.4 g (case 3) drilled out at r = 29.3 mm
(docs/references.md: the radius Table 5.2's forces were computed with).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankbalance.physics.friction import (
    friction_coefficient_from_torque,
    mean_equivalent_load,
    torque_from_transducer_voltage,
)
from crankbalance.physics.rotor_bench import BenchSettings, disc_rotor, run_bench

SPEEDS_RPM = (3000, 6000, 9000)
HOLE_MASS = {1: 0.0, 2: 0.0146, 3: 0.0584}
# Table 5.5: friction coefficients from the physical test
MU_TABLE_5_5 = {
    1: (0.7773, 1.2771, 1.4718),
    2: (0.4044, 0.2138, 0.1027),
    3: (0.1170, 0.0526, 0.0254),
}
# Table 5.6, bottom: required torque of the FEDEM simulations [N m]
FEDEM_TABLE_5_6 = {
    1: (0.1949, 0.3204, 0.3696),
    2: (0.1897, 0.3670, 0.3948),
    3: (0.1988, 0.3555, 0.3861),
}
# Table 5.6, top: measured torques; case 2 at 9000 rpm corrected to 0.3958 (docs/references.md)
MEASURED_TABLE_5_6 = {
    1: (0.1944, 0.3194, 0.3681),
    2: (0.2083, 0.3715, 0.3958),
    3: (0.2031, 0.3594, 0.3906),
}
# Table 5.3 in volts (case 3 run 1 omitted as in the thesis)
VOLTS_TABLE_5_3 = {
    1: ((0.40, 0.38, 0.38), (0.49, 0.52, 0.51), (0.56, 0.55, 0.55)),
    2: ((0.40, 0.40, 0.40), (0.57, 0.55, 0.55), (0.58, 0.58, 0.58)),
    3: ((0.39, 0.40), (0.53, 0.56), (0.57, 0.58)),
}
GEOMETRY = dict(disc_diameter=0.098, disc_thickness=0.036704, journal_diameter=0.020, length=0.188)
RADIUS = 0.0293
G = 9.81


def _rotor(case: int, mu: float):
    return disc_rotor(
        **GEOMETRY, friction_coefficient=mu, hole_mass=HOLE_MASS[case], hole_radius=RADIUS
    )


def test_rotor_mass_and_inertia_appendix_e():
    rotor = _rotor(1, 0.1)
    assert rotor.mass == pytest.approx(2.5464, abs=1e-4), (
        "Hoem and Røsholm (2016), App. E geometry as printed"
    )
    wide = disc_rotor(0.100, 0.036704, 0.020, 0.188, 0.1)
    assert wide.inertia == pytest.approx(2847.335e-6, rel=2e-5), (
        "Hoem and Røsholm (2016), App. E Eq. 7.7: I = 2847.335 kg mm^2 with d1 = 100 mm "
        "(docs/references.md)"
    )


def test_table_5_6_measured_torques_from_volts():
    for case, rows in VOLTS_TABLE_5_3.items():
        for k, volts in enumerate(rows):
            torque = torque_from_transducer_voltage(np.mean(volts))
            assert torque == pytest.approx(MEASURED_TABLE_5_6[case][k], abs=6e-5), (
                f"Hoem and Røsholm (2016), Table 5.6 top, case {case}, {SPEEDS_RPM[k]} rpm: "
                "(V - 0.2) 5/4.8"
            )


@pytest.mark.parametrize("case", [1, 2, 3])
def test_bench_required_torque_against_table_5_6(case):
    for k, rpm in enumerate(SPEEDS_RPM):
        rotor = _rotor(case, MU_TABLE_5_5[case][k])
        result = run_bench(rotor, BenchSettings(speed=rpm * math.pi / 30, samples=200))
        reference = FEDEM_TABLE_5_6[case][k]
        assert result.required_torque == pytest.approx(reference, rel=0.05), (
            f"Hoem and Røsholm (2016), Table 5.6 (FEDEM), case {case}, {rpm} rpm, within 5 %"
        )
        # tighter: the bench reproduces the FEDEM values within 2.1 % in all nine runs
        assert result.required_torque == pytest.approx(reference, rel=0.021)
        # and its mean friction is the Coulomb mean of the actual reaction (no f_m fit)
        arithmetic = (
            MU_TABLE_5_5[case][k]
            * 0.01
            * mean_equivalent_load(
                rotor.mass * rotor.gravity,
                rotor.unbalance * (rpm * math.pi / 30) ** 2,
                "arithmetic",
            )
        )
        assert result.mean_friction_torque == pytest.approx(arithmetic, rel=2e-3)


def test_table_5_5_friction_coefficients_back_computed():
    """Eq. 5.1 with the thesis' inputs: the printed rotor (m = 2.546 kg), r = 29.6 mm as the
    thesis text gives it, F_m from Eq. 4.14 and the Table 5.6 torques. Seven of nine agree
    to three significant figures; the two 3000 rpm entries of cases 1 and 2 do not."""
    weight = _rotor(1, 0.1).mass * G
    matches = []
    for case in (1, 2, 3):
        for k, rpm in enumerate(SPEEDS_RPM):
            force = HOLE_MASS[case] * 0.0296 * (rpm * math.pi / 30) ** 2
            mu = friction_coefficient_from_torque(MEASURED_TABLE_5_6[case][k], weight, force, 0.020)
            matches.append(f"{mu:.3g}" == f"{MU_TABLE_5_5[case][k]:.3g}")
            assert mu == pytest.approx(MU_TABLE_5_5[case][k], rel=0.008), (
                f"Hoem and Røsholm (2016), Table 5.5 case {case} {rpm} rpm"
            )
    assert sum(matches) == 7, (
        "Hoem and Røsholm (2016), Table 5.5: seven of nine to three significant figures"
    )
    assert not matches[0] and not matches[3], "the misfits are case 1 and case 2 at 3000 rpm"


# Case 1 of Table 5.5: the three entries all imply T / (mu d/2) = W = 25.01 N (the implied
# weights are 25.0096, 25.0098, 25.0102 N: m = 2.549 kg, 0.12 % more than the printed
# geometry); 0.7773 sits just below the rounding edge 0.7775. These are readings of the
# thesis' own numbers (no library call), so they are data here, not an assertion.
CASE_1_IMPLIED_WEIGHT = 25.01


def test_table_5_5_misfits_explained():
    # Case 1: with W = 25.01 N and no unbalance, Eq. 5.1 gives the three printed
    # coefficients to their four decimals.
    for k, rpm in enumerate(SPEEDS_RPM):
        mu = friction_coefficient_from_torque(
            MEASURED_TABLE_5_6[1][k], CASE_1_IMPLIED_WEIGHT, 0.0, 0.020
        )
        assert mu == pytest.approx(MU_TABLE_5_5[1][k], abs=5e-5), (
            f"Hoem and Røsholm (2016), Table 5.5 case 1, {rpm} rpm, with W = 25.01 N"
        )
    # Case 2 at 3000 rpm: the printed 0.4044 follows with the Table 5.2 force 42.2 N
    # (r = 29.3 mm), while the other unbalanced entries need r = 29.6 mm.
    mu = friction_coefficient_from_torque(0.2083, CASE_1_IMPLIED_WEIGHT, 42.2, 0.020)
    assert mu == pytest.approx(0.4044, abs=2e-4), (
        "Hoem and Røsholm (2016), Table 5.5 case 2, 3000 rpm, with 42.2 N"
    )
