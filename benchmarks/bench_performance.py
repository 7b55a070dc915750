"""Timings of the friction/performance hot paths (issue 7); prints a table.

Targets: bench run (3.5 s simulated) < 1 s; one engine cycle < 50 ms;
50-point balance-factor sweep < 5 s.

Run: python benchmarks/bench_performance.py
"""

from __future__ import annotations

import math
import time

import numpy as np

from crankbalance.physics.engine_cycle import (
    CylinderSpec,
    WiebeCombustion,
    balance_sensitivity,
    engine_cycle,
)
from crankbalance.physics.rotor_bench import BenchSettings, disc_rotor, run_bench


def best_of(function, repeat: int = 3) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    rows = []
    for rpm in (3000, 6000, 9000):
        rotor = disc_rotor(
            0.098, 0.036704, 0.020, 0.188, 0.0526, hole_mass=0.0584, hole_radius=0.0293
        )
        settings = BenchSettings(speed=rpm * math.pi / 30)
        rows.append(
            (
                f"bench, case 3, {rpm} rpm (3.5 s simulated)",
                best_of(lambda r=rotor, s=settings: run_bench(r, s)),
                1.0,
            )
        )
    cylinder = CylinderSpec(
        bore=0.0768,
        crank_radius=0.0269,
        rod_length=0.1035,
        reciprocating_mass=0.282,
        crank_inertia=6e-3,
        balance_factor=0.5,
        journal_diameter=0.03,
        friction_coefficient=0.005,
    )
    combustion = WiebeCombustion(
        compression_ratio=13.5, ignition_angle=np.radians(-25), burn_duration=np.radians(50)
    )
    speed = 9000 * math.pi / 30
    rows.append(
        (
            "engine cycle, 4-stroke, 720 samples/rev",
            best_of(lambda: engine_cycle(cylinder, speed, combustion), 10),
            0.05,
        )
    )
    factors = np.linspace(0.0, 1.0, 50)
    rows.append(
        (
            "sensitivity sweep, 50 balance factors",
            best_of(lambda: balance_sensitivity(cylinder, speed, combustion, factors)),
            5.0,
        )
    )
    width = max(len(r[0]) for r in rows)
    print(f"{'case'.ljust(width)}  {'time [ms]':>10}  {'target [ms]':>11}  ok")
    print("-" * (width + 30))
    for name, seconds, target in rows:
        print(
            f"{name.ljust(width)}  {seconds * 1e3:10.1f}  {target * 1e3:11.0f}  "
            f"{'yes' if seconds < target else 'NO'}"
        )


if __name__ == "__main__":
    main()
