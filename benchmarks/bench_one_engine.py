"""Speed of one analysis of a built model (issue 13, row 3), measured side by side in one run.

Run: python benchmarks/bench_one_engine.py

Times ``free_forces(model, 8)`` of the V12 preset (12 cylinders, 8 orders: the phasors of
force and couple of every order and of the rotating masses), best of several repeats.
The pass criterion is the target (0.05 ms per analysis) on the elapsed time
(``time.perf_counter``); the CPU time of the process (``time.process_time``) is printed
beside it, since on a shared machine the elapsed time also counts the other processes.
The reference is a minimal numpy phasor sum of the same engine with its harmonic
coefficients computed beforehand (``c * exp(i n theta) @ w``, no caching, no
dataclass): the floor any analysis that builds the phasors pays in numpy, so the ratio
says how much the library adds.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable

import numpy as np

from crankbalance.io.engine_file import load_engine
from crankbalance.physics.kinematics import harmonic_coefficients
from crankbalance.physics.model import EngineModel
from crankbalance.physics.shaking import free_forces
from crankbalance.studies.build import build_model

TARGET = 0.05e-3  # s per analysis


def per_call(func, repeat: int = 7, number: int = 2000) -> tuple[float, float]:
    """Best-of-``repeat`` mean time of one call [s]: elapsed (time.perf_counter, the
    measure) and this process's CPU time (time.process_time, for a shared machine)."""
    best, best_cpu = float("inf"), float("inf")
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        for _ in range(number):
            func()
        best = min(best, (time.perf_counter() - start) / number)
        best_cpu = min(best_cpu, (time.process_time() - start_cpu) / number)
    return best, best_cpu


def minimal_phasor_sum(model: EngineModel, orders: int = 8) -> Callable[[], tuple[np.ndarray, ...]]:
    """The reference: the forward and backward phasors of force and couple of ``model`` as a
    minimal numpy sum, ``c * (exp(i n theta) @ w)``, its harmonic coefficients computed here,
    before any timing (one offset for every cylinder, as the presets have)."""
    e = model.cylinder_offset[0]
    c = harmonic_coefficients(model.rod_ratio, orders, e / model.crank_radius)
    phi, beta = model.cylinder_angle, model.cylinder_bank
    y, mass = model.cylinder_position, model.reciprocating_mass
    n = np.arange(1, orders + 1)[:, None]

    def reference() -> tuple[np.ndarray, ...]:
        w = 0.5 * mass * model.crank_radius * model.speed**2 * np.exp(1j * beta)
        turn = np.exp(1j * n * (phi - beta))  # (K, C)
        fwd, cfwd = c * (turn @ w), c * (turn @ (w * y))
        bwd, cbwd = np.conj(c * (turn @ np.conj(w))), np.conj(c * (turn @ np.conj(w * y)))
        return fwd, bwd, cfwd, cbwd

    return reference


def main() -> None:
    model = build_model(load_engine("v12-60"))
    orders = 8
    mass = model.reciprocating_mass
    reference = minimal_phasor_sum(model, orders)

    ours = free_forces(model, orders)
    ref = reference()
    scale = float(mass.sum()) * model.crank_radius * model.speed**2
    diff = max(
        float(np.abs(a - b).max())
        for a, b in zip(
            (ours.force_forward, ours.force_backward, ours.couple_forward, ours.couple_backward),
            ref,
            strict=True,
        )
    )
    assert diff < 1e-12 * scale, f"library and reference differ by {diff} N"

    t, cpu = per_call(lambda: free_forces(model, orders))
    t_ref, cpu_ref = per_call(reference)
    rows = [
        (
            "analysis of one built model (V12, 8 orders): free_forces",
            f"{t * 1e3:.4f} ms",
            f"{cpu * 1e3:.4f} ms",
            f"<= {TARGET * 1e3:.2f} ms",
            "PASS" if t <= TARGET else "FAIL",
        ),
        (
            "reference: minimal numpy phasor sum, coefficients given",
            f"{t_ref * 1e3:.4f} ms",
            f"{cpu_ref * 1e3:.4f} ms",
            "",
            "",
        ),
        ("ratio analysis / reference", f"{t / t_ref:.2f}", f"{cpu / cpu_ref:.2f}", "", ""),
    ]
    width = max(len(r[0]) for r in rows)
    print(f"load average (1 min) {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs")
    print(f"{'case'.ljust(width)}  {'measured':>12}  {'CPU time':>12}  {'target':>10}  result")
    print(f"{'-' * width}  {'-' * 12}  {'-' * 12}  {'-' * 10}  ------")
    for name, value, cpu_value, target, result in rows:
        print(f"{name.ljust(width)}  {value:>12}  {cpu_value:>12}  {target:>10}  {result}")


if __name__ == "__main__":
    main()
