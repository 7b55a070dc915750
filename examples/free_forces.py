"""
Free forces and moments of classic engines
==========================================

Free forces and moments of a few classic engines, through the Python API.

Run: python examples/free_forces.py
"""

from crankbalance.studies.engine import analyze

for preset in ("paper-inline3", "inline4", "v8-crossplane", "boxer4"):
    result = analyze(preset, orders=4)
    f = result.forces
    print(f"{result.model.name}")
    for k, order in enumerate(f.orders):
        print(
            f"  order {order}: force {f.force_amplitude[k]:10.1f} N "
            f"(forward {abs(f.force_forward[k]):9.1f}, backward {abs(f.force_backward[k]):9.1f}), "
            f"moment {f.moment_amplitude[k]:9.2f} N m"
        )
    print(
        f"  rotating masses: force {abs(f.rotating_force):.1f} N, "
        f"moment {abs(f.rotating_couple):.2f} N m"
    )
