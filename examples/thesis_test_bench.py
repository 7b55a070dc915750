"""
The NTNU thesis' test rotor on the bench
========================================

The NTNU thesis' test rotor on the simulated bench.

Hoem and Røsholm (2016), chapter 5, Tables 5.5 and 5.6.

The rotor of Appendix E (disc 98 x 36.704 mm between 20 mm journals, 188 mm long, steel)
is run up to 3000, 6000 and 9000 rpm in 2 s by a PI-controlled motor and held for 1.5 s;
the bearings carry Coulomb friction with the coefficients of Table 5.5, driven by the actual
reaction forces (weight plus the rotating unbalance of the drilled holes, Table 5.2,
m_u at r = 29.3 mm). The required torque is the mean motor torque over the hold.

Run: python examples/thesis_test_bench.py
"""

from __future__ import annotations

import math

from crankbalance.physics.friction import friction_coefficient_from_torque, mean_equivalent_load
from crankbalance.physics.rotor_bench import BenchSettings, disc_rotor, run_bench

SPEEDS = (3000, 6000, 9000)
HOLE = {1: 0.0, 2: 0.0146, 3: 0.0584}
MU = {1: (0.7773, 1.2771, 1.4718), 2: (0.4044, 0.2138, 0.1027), 3: (0.1170, 0.0526, 0.0254)}
FEDEM = {1: (0.1949, 0.3204, 0.3696), 2: (0.1897, 0.3670, 0.3948), 3: (0.1988, 0.3555, 0.3861)}
MEASURED = {1: (0.1944, 0.3194, 0.3681), 2: (0.2083, 0.3715, 0.3958), 3: (0.2031, 0.3594, 0.3906)}


def main() -> None:
    print("Required torque to hold speed [N m]: this bench vs Hoem and Røsholm (2016), Table 5.6")
    print(
        f"{'case':>4} {'rpm':>5} {'bench':>8} {'FEDEM':>8} {'diff':>7} {'measured':>9} "
        f"{'diff':>7} {'f_m model':>9}"
    )
    worst = 0.0
    for case in (1, 2, 3):
        for k, rpm in enumerate(SPEEDS):
            rotor = disc_rotor(
                0.098, 0.036704, 0.020, 0.188, MU[case][k], hole_mass=HOLE[case], hole_radius=0.0293
            )
            omega = rpm * math.pi / 30
            result = run_bench(rotor, BenchSettings(speed=omega, samples=200))
            weight, force = rotor.mass * rotor.gravity, rotor.unbalance * omega**2
            model = MU[case][k] * 0.01 * float(mean_equivalent_load(weight, force))
            d_fedem = result.required_torque / FEDEM[case][k] - 1
            d_meas = result.required_torque / MEASURED[case][k] - 1
            worst = max(worst, abs(d_fedem))
            print(
                f"{case:>4} {rpm:>5} {result.required_torque:8.4f} {FEDEM[case][k]:8.4f} "
                f"{d_fedem:+7.2%} {MEASURED[case][k]:9.4f} {d_meas:+7.2%} {model:9.4f}"
            )
    print(f"largest difference to the FEDEM simulations: {worst:.2%} (issue target 5 %)")
    print("""
Why the numbers differ:
- Case 1 (balanced): the bench is 0.4-0.6 % below FEDEM. Table 5.5's mu were fitted to the
  measured torques with a rotor weight of 25.01 N; the printed geometry gives 24.98 N, and
  FEDEM itself came out 0.3-0.4 % above the measured torques (Table 5.7).
- Cases 2 and 3: the thesis fitted mu with the mean load F_m = f_m (F_w + F_u) (Eq. 4.14, a
  fit of the cubic mean used for rolling-bearing life), but Coulomb friction driven by the
  actual reaction dissipates the arithmetic mean of |F_w + F_u e^(i theta)|, which is lower.
  The 'f_m model' column shows the torque the thesis' model predicts; the bench and FEDEM
  both fall below it. The gap is largest where F_u is comparable to F_w (case 2, 3000 rpm:
  F_u = 42 N, W = 25 N; bench 0.1859 vs 0.2083 N m measured): that is FEDEM's 9.8 % miss
  in Table 5.7. Its 6.3 % at 9000 rpm is the misprint 0.3715 in Table 5.6 (the volts give
  0.3958, docs/references.md), not physics.
- Table 5.5 itself was computed with r = 29.6 mm (the radius printed under Table 5.2), while
  the holes (and FEDEM's model, which case 3 reproduces to 0.1 %) sit at 29.3 mm; in case 2
  the bench is 1-2 % below FEDEM, case 3 within 0.2 %.""")
    print("Table 5.5 back-computed with Eq. 5.1 (m = 2.546 kg, r = 29.6 mm, Table 5.6 torques):")
    weight = disc_rotor(0.098, 0.036704, 0.020, 0.188, 0.1).mass * 9.81
    for case in (1, 2, 3):
        cells = []
        for k, rpm in enumerate(SPEEDS):
            force = HOLE[case] * 0.0296 * (rpm * math.pi / 30) ** 2
            mu = float(friction_coefficient_from_torque(MEASURED[case][k], weight, force, 0.020))
            same = f"{mu:.3g}" == f"{MU[case][k]:.3g}"
            cells.append(f"{mu:.4f} ({MU[case][k]:.4f}{'' if same else ' *'})")
        print(f"  case {case}: " + "  ".join(cells))
    print(
        "  * differs at 3 significant figures: case 1 needs W = 25.01 N (all three case-1\n"
        "    entries imply it), case 2 at 3000 rpm used the 42.2 N of Table 5.2 (r = 29.3 mm)."
    )


if __name__ == "__main__":
    main()
