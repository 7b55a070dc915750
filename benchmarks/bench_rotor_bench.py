"""Rotor bench, 3.5 s simulated (issue 13): CPU time of one run against its target.

The thesis' test rotor, case 3 (unbalance from the drilled holes), at 3000, 6000 and 9000
rpm with the default 2 s ramp and 1.5 s hold. Measured: ``run_bench`` (a Dormand-Prince
5(4) pair stepping plain floats). Reference, measured in the same run: the same equations,
tolerances and step limit integrated by scipy's ``solve_ivp`` (DOP853), which is how
``run_bench`` integrated before issue 13. CPU time (``time.process_time``), best of a few
runs, so that other processes on the machine count less.

    python benchmarks/bench_rotor_bench.py

Target: at most 0.2 s of CPU per run on an idle machine.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np

from crankbalance.physics.rotor_bench import (
    BenchRotor,
    BenchSettings,
    _bench_model,
    disc_rotor,
    run_bench,
)

TARGET = 0.2  # s of CPU per run


def cpu_time(function: Callable[[], object], repeat: int = 3) -> float:
    """Best-of-``repeat`` CPU time of one call [s]."""
    times = []
    for _ in range(repeat):
        start = time.process_time()
        function()
        times.append(time.process_time() - start)
    return min(times)


def solve_ivp_bench(rotor: BenchRotor, settings: BenchSettings) -> float:
    """The required torque by scipy's DOP853 on the same equations [N m]."""
    from scipy.integrate import solve_ivp

    equations = _bench_model(rotor, settings)

    def rhs(t: float, y: np.ndarray) -> list[float]:
        reference, motor, friction, alpha, _, _ = equations(t, y[0], y[1], y[2])
        return [y[1], alpha, reference - y[1], motor, friction]

    t_ramp = settings.ramp_time
    options = dict(
        method="DOP853",
        rtol=settings.rtol,
        atol=[1e-6, 1e-6 * settings.speed, 1e-8, 1e-8, 1e-8],
        max_step=2 * math.pi / settings.speed / 8,
    )
    ramp = solve_ivp(rhs, (0.0, t_ramp), np.zeros(5), **options)
    hold = solve_ivp(rhs, (t_ramp, t_ramp + settings.hold_time), ramp.y[:, -1], **options)
    return float((hold.y[3, -1] - hold.y[3, 0]) / settings.hold_time)


def main() -> None:
    rotor = disc_rotor(0.098, 0.036704, 0.020, 0.188, 0.0526, hole_mass=0.0584, hole_radius=0.0293)
    print(
        f"{'case 3, 3.5 s simulated':<24} {'measured':>9} {'target':>7} "
        f"{'solve_ivp':>10} {'ratio':>6} {'torque rel. diff':>17}  ok"
    )
    for rpm in (3000, 6000, 9000):
        settings = BenchSettings(speed=rpm * math.pi / 30)
        measured = cpu_time(lambda s=settings: run_bench(rotor, s))
        reference = cpu_time(lambda s=settings: solve_ivp_bench(rotor, s))
        difference = run_bench(rotor, settings).required_torque / solve_ivp_bench(rotor, settings)
        print(
            f"{f'{rpm} rpm':<24} {measured:8.3f}s {TARGET:6.1f}s {reference:9.3f}s "
            f"{measured / reference:6.3f} {abs(difference - 1):17.1e}  "
            f"{'yes' if measured <= TARGET else 'NO'}"
        )


if __name__ == "__main__":
    main()
