"""
A counterweight for the paper's inline-3
========================================

Design a crankshaft counterweight for the inline-3 of the 2021 paper (Tables 1-2).

The balancing solver, run on the engine file of Table 1, asks for m_c = 1.2413 kg at
r_c = 30 mm on each of the four counterweights (Table 2), i.e. a first moment of
37.24 kg*mm: that is the requirement the shape must meet. We fix the web radius,
leave the other profile parameters free, bound the radial space and the mass, and let
the optimiser return the feasible designs, the mass-vs-radius Pareto front and the
least-mass and least-radius designs (as Table 3 does). The least-mass design is then
exported (SVG, DXF, STL) and its STL read back to check it against the requirement.

Run: python examples/counterweight_design.py
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

from crankbalance.io.cad import export_counterweight, mesh_mass_properties
from crankbalance.physics.counterweight import required_first_moment
from crankbalance.physics.counterweight_optimize import optimize_counterweight
from crankbalance.studies.engine import balance_engine

# this script's path, also when the documentation's gallery runs it (without __file__)
ENGINE = Path(sys.argv[0]).resolve().parent / "paper_inline3.toml"
REQUIRED = required_first_moment(balance_engine(ENGINE).result.counterweights)  # [kg m]
print(f"required first moment m_c r_c = {REQUIRED * 1e3:.2f} kg*mm (Table 2: 1.2413 kg x 30 mm)")

bounds = {
    "web_radius": 0.030,  # fixed by the crank web [m]
    "rectangle_height": (0.0, 0.040),
    "trapezoid_angle": (0.0, 1.3),
    "segment_radius": (0.040, 0.110),
    "segment_angle": (0.5, 3.1416),
    "thickness": (0.010, 0.035),
}


def progress(state) -> None:
    if state.iteration % 10 == 0:
        print(
            f"  iteration {state.iteration}: {state.n_feasible} feasible, "
            f"least mass {state.least_mass * 1e3:.1f} g"
        )


result = optimize_counterweight(
    REQUIRED,
    bounds,
    max_radius=0.100,
    max_mass=2.5,
    min_balance=100.0,
    rng=2021,
    iterations=30,
    callback=progress,
)
print(
    f"{len(result.designs)} feasible designs, {len(result.pareto)} on the Pareto front, "
    f"{result.elapsed:.2f} s"
)
for label, index in (("least mass", result.least_mass), ("least radius", result.least_radius)):
    row = result.row(index)
    print(
        f"{label:12s}: mass {row['mass'] * 1e3:7.1f} g, true outer radius "
        f"{row['outer_radius'] * 1e3:5.1f} mm (paper's R_min bound {row['radius_bound'] * 1e3:5.1f}"
        f" mm), t_cw {row['thickness'] * 1e3:4.1f} mm, balance {row['balance']:.2f} %"
    )

design = result.least_mass_design
with tempfile.TemporaryDirectory() as folder:
    for suffix in ("svg", "dxf", "stl"):
        export_counterweight(design, Path(folder) / f"counterweight.{suffix}")
    part = mesh_mass_properties(
        Path(folder) / "counterweight.stl", design.density, required_first_moment=REQUIRED
    )
print(
    f"STL read back: mass {part.mass * 1e3:.1f} g, r_c {part.cg_radius * 1e3:.2f} mm, "
    f"balance {part.balance:.2f} %, watertight {part.watertight}"
)
