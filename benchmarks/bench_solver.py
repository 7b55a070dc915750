"""Speed of the one solver (issue 26 item 4, targets of issue 30), measured side by side in
one run.

Run: python benchmarks/bench_solver.py [--engines 20000]

Printed, each measured in this run (elapsed time, ``time.perf_counter``, and the CPU time
of the process, ``time.process_time``, beside it for a shared machine; best of several
repeats):

1. ``balance_engine(spec)`` (build the model, balance it: counterweights and the shafts
   the engine file asks for, the residuals) against ``free_forces(model)`` of the same
   engine, for three presets; target: at most 4 times.
2. One built model's ``free_forces`` against a minimal numpy phasor sum with the harmonic
   coefficients given (``bench_one_engine.minimal_phasor_sum``), the V12; target: at most
   2 times.
3. ``analyze(spec)`` of a spec seen before (its model kept by ``build_model``) against
   ``free_forces(model)``, the same three presets; target: at most 1.3 times (issue 30).
4. The batched balancing throughput: ``balance_batch`` on random cranks of the crossplane
   V8's topology (``random_engines``: throw angles, masses, radius, rod and speed drawn per
   engine), optimal counterweights with a balance factor of 0.5 and two shaft pairs.

The script runs on the code before issue 26 too, so one script gives before and after
(``PYTHONPATH=/tmp/base/src python benchmarks/bench_solver.py``): before issue 26 the batch
names lived in ``crankbalance.physics.balancing``.
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable
from typing import Any

import numpy as np
from bench_one_engine import minimal_phasor_sum, per_call

from crankbalance.io.engine_file import load_engine
from crankbalance.physics.balancing import CounterweightOptions, ShaftOptions
from crankbalance.physics.shaking import free_forces
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import analyze, balance_engine

try:
    from crankbalance.physics.balance_batch import balance_batch
    from crankbalance.physics.model import engine_batch
except ImportError:  # the code before issue 26
    from crankbalance.physics.balancing import (  # type: ignore[attr-defined,no-redef]
        balance_batch,
        engine_batch,
    )

PRESETS = ("inline4", "v8-crossplane", "v12-60")
TARGET_BALANCE, TARGET_FREE_FORCES, TARGET_ANALYZE = 4.0, 2.0, 1.3
CW_RADIUS, SHAFT_RADIUS, SHAFT_LENGTH = 0.045, 0.03, 0.3


def random_engines(engines: int) -> Any:
    """Random cranks of the crossplane V8's topology (an ``EngineBatch``)."""
    m = build_model(load_engine("v8-crossplane"))
    rng = np.random.default_rng(1)
    return engine_batch(
        m,
        engines,
        throw_angle=rng.uniform(0, 2 * np.pi, (engines, m.throws)),
        throw_rotating_mass=rng.uniform(0.5, 1.5, (engines, m.throws)),
        reciprocating_mass=rng.uniform(0.3, 0.8, (engines, m.cylinders)),
        crank_radius=rng.uniform(0.035, 0.05, engines),
        rod_length=rng.uniform(0.13, 0.17, engines),
        speed=rng.uniform(300, 900, engines),
    )


def best_of(func: Callable[[], object], repeat: int = 3) -> tuple[float, float]:
    """Best elapsed and best CPU time of one call of ``func`` over ``repeat`` calls [s]."""
    wall, cpu = [], []
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        func()
        wall.append(time.perf_counter() - start)
        cpu.append(time.process_time() - start_cpu)
    return min(wall), min(cpu)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--engines", type=int, default=20_000)
    args = parser.parse_args()
    rows: list[tuple[str, str, str, str]] = []

    for name in PRESETS:
        spec = load_engine(name)
        model = build_model(spec)
        balance_engine(spec)  # warm up (imports, caches)
        t_bal = per_call(lambda spec=spec: balance_engine(spec), repeat=5, number=300)
        t_ff = per_call(lambda model=model: free_forces(model, 8), repeat=5, number=2000)
        analyze(spec)  # the spec seen before
        t_an = per_call(lambda spec=spec: analyze(spec, 8), repeat=5, number=2000)
        rows += [
            (
                f"{name}: analyze(spec), seen before",
                f"{t_an[0] * 1e3:.4f} ms",
                f"{t_an[1] * 1e3:.4f} ms",
                "",
            ),
            (
                f"{name}: ratio analyze / free_forces",
                f"{t_an[0] / t_ff[0]:.2f}",
                f"{t_an[1] / t_ff[1]:.2f}",
                f"<= {TARGET_ANALYZE:g}",
            ),
            (
                f"{name}: balance_engine(spec)",
                f"{t_bal[0] * 1e3:.4f} ms",
                f"{t_bal[1] * 1e3:.4f} ms",
                "",
            ),
            (
                f"{name}: free_forces(model)",
                f"{t_ff[0] * 1e3:.4f} ms",
                f"{t_ff[1] * 1e3:.4f} ms",
                "",
            ),
            (
                f"{name}: ratio balance_engine / free_forces",
                f"{t_bal[0] / t_ff[0]:.2f}",
                f"{t_bal[1] / t_ff[1]:.2f}",
                f"<= {TARGET_BALANCE:g}",
            ),
        ]

    model = build_model(load_engine("v12-60"))
    reference = minimal_phasor_sum(model, 8)
    t_ff = per_call(lambda: free_forces(model, 8))
    t_ref = per_call(reference)
    rows += [
        ("v12-60: free_forces(model)", f"{t_ff[0] * 1e3:.4f} ms", f"{t_ff[1] * 1e3:.4f} ms", ""),
        (
            "minimal numpy phasor sum, coefficients given",
            f"{t_ref[0] * 1e3:.4f} ms",
            f"{t_ref[1] * 1e3:.4f} ms",
            "",
        ),
        (
            "ratio free_forces / minimal phasor sum",
            f"{t_ff[0] / t_ref[0]:.2f}",
            f"{t_ff[1] / t_ref[1]:.2f}",
            f"<= {TARGET_FREE_FORCES:g}",
        ),
    ]

    batch = random_engines(args.engines)
    full = (
        CounterweightOptions(CW_RADIUS, angle="optimal", balance_factor=0.5),
        ShaftOptions(SHAFT_RADIUS, SHAFT_LENGTH),
        ShaftOptions(SHAFT_RADIUS, SHAFT_LENGTH),
    )
    balance_batch(batch.take(slice(0, 100)), *full)  # warm up
    wall, cpu = best_of(lambda: balance_batch(batch, *full))
    rows.append(
        (
            f"balance_batch, {batch.size} crossplane-V8 cranks: engines/s",
            f"{batch.size / wall:,.0f}",
            f"{batch.size / cpu:,.0f}",
            "",
        )
    )

    width = max(len(r[0]) for r in rows)
    print(f"load average (1 min) {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs")
    print(f"{'case'.ljust(width)}  {'measured':>12}  {'CPU time':>12}  target")
    print(f"{'-' * width}  {'-' * 12}  {'-' * 12}  ------")
    for case, value, cpu_value, target in rows:
        print(f"{case.ljust(width)}  {value:>12}  {cpu_value:>12}  {target}")


if __name__ == "__main__":
    main()
