"""
Inline-4 second-order balance shaft
===================================

Inline-4 second-order balance shaft: where to put the unbalance mass (Kim 2018).

Takes the built-in "inline4" engine, works out the first moment each shaft of the
counter-rotating pair must carry, finds the optimum mass position along a shaft on end
bearings for w = 2 (paper: 67 %), sweeps the weight w, and checks the optimum layout.

Run: python examples/balance_shaft_inline4.py
"""

import numpy as np

from crankbalance.io.engine_file import load_engine
from crankbalance.physics.balance_shaft import (
    BalanceShaft,
    design_checks,
    inline4_secondary_unbalance,
    inline4_study,
    shaft_response,
)
from crankbalance.physics.beam import ShaftSection
from crankbalance.studies.build import build_model

engine = build_model(load_engine("inline4"))
unbalance = inline4_secondary_unbalance(
    float(engine.reciprocating_mass[0]), engine.crank_radius, engine.rod_length
)
max_shaft_speed = 2 * 6500 * 2 * np.pi / 60  # shafts turn at twice crank speed; 6500 rpm crank
length = 0.30
section = ShaftSection(outer_diameter=0.028)  # steel

print(
    f"{engine.name}: each shaft needs m*e = {1e6 * unbalance:.0f} g*mm "
    f"at {max_shaft_speed * 60 / (2 * np.pi):.0f} rpm shaft speed"
)

study = inline4_study(unbalance, max_shaft_speed, length, section, weight=2.0)
print(
    f"optimum unbalance-mass position (w = 2): {100 * study.optimum_position:.1f} % "
    f"of the length (paper: 67 %)"
)
print(" w     optimum")
for w, x in zip(study.weights, study.optimum_positions, strict=True):
    print(f"{w:4.1f}  {100 * x:6.1f} %")

shaft = BalanceShaft(
    length,
    section,
    (0.0, length),
    (study.optimum_position * length,),
    (unbalance,),
    max_shaft_speed,
    unbalance_radius=0.02,
)
response = shaft_response(shaft)
checks = design_checks(response, bearing_capacity=6000.0, deflection_limit=0.5e-3)
print(
    f"at the optimum: bearing loads {response.reactions.round(0)} N, "
    f"max deflection {1e6 * response.max_deflection:.0f} um, "
    f"stress {response.max_stress / 1e6:.0f} MPa, first bending frequency "
    f"{response.first_frequency:.0f} Hz"
)
print(
    f"critical speed / max speed = {checks.critical_speed_ratio:.2f} "
    f"({'ok' if checks.critical_speed_ok else 'too close'}), bearings "
    f"{'ok' if checks.bearing_ok else 'overloaded'}, deflection "
    f"{'ok' if checks.deflection_ok else 'too large'}"
)
