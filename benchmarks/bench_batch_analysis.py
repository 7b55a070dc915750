"""Speed and memory of the batched analysis (issue 13, row 4), side by side in one run.

Run: python benchmarks/bench_batch_analysis.py

The batch: engines of 8 cylinders, exact kinematics, every parameter drawn per engine
(crank radius and conrod length, hence the rod ratio; speed; per cylinder the mass,
throw angle, bank angle and axial position), 8 orders; ``batch_amplitudes`` returns the
force and moment amplitude of every order of every engine.

Printed (elapsed time, ``time.perf_counter``, is the measure; the CPU time of the process,
``time.process_time``, is printed beside it for a shared machine):
- throughput on 100 000 engines, best of 3 (target >= 300 000 engines/s);
- the reference: a minimal numpy phasor sum on the same batch, in one go (no chunks):
  the same exact harmonic coefficients (``harmonic_coefficients`` on the whole batch),
  the powers of ``exp(i(phi - beta))`` by ``cumprod``, one complex matmul for the four
  sums over the cylinders, then ``|F+| + |F-|``. The pass criterion is the ratio
  library / reference <= 1.2. Both results are checked equal before timing;
- the peak memory of one call on 1 000 000 engines (target <= 300 MB), measured in a
  child process: what the call allocates (tracemalloc: results and temporaries, the
  inputs excluded, they are the caller's) and the child's peak resident size
  (``resource``, inputs and interpreter included).
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import time
import tracemalloc

import numpy as np

from crankbalance.physics.kinematics import harmonic_coefficients
from crankbalance.physics.shaking import batch_amplitudes

CYLINDERS, ORDERS = 8, 8
THROUGHPUT_ENGINES, MEMORY_ENGINES = 100_000, 1_000_000
TARGET_RATE, TARGET_RATIO, TARGET_MB = 300_000.0, 1.2, 300.0


def batch(engines: int, seed: int = 1) -> tuple[np.ndarray, ...]:
    """Random engines: crank radius, rod length, speed (E,); mass, throw angle, bank angle,
    position (E, C)."""
    rng = np.random.default_rng(seed)
    shape = (engines, CYLINDERS)
    return (
        rng.uniform(0.03, 0.06, engines),
        rng.uniform(0.12, 0.2, engines),
        rng.uniform(300, 900, engines),
        rng.uniform(0.3, 0.8, shape),
        rng.uniform(0, 2 * np.pi, shape),
        rng.uniform(-0.8, 0.8, shape),
        rng.uniform(-0.2, 0.2, shape),
    )


def reference(
    r: np.ndarray,
    l: np.ndarray,
    speed: np.ndarray,
    mass: np.ndarray,
    phi: np.ndarray,
    beta: np.ndarray,
    y: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Minimal numpy phasor sum of the whole batch at once (see the module docstring)."""
    c = harmonic_coefficients(r / l, ORDERS)  # (E, K)
    w = 0.5 * mass * (r * speed**2)[:, None] * np.exp(1j * beta)  # (E, C)
    z = np.exp(1j * (phi - beta))
    zn = np.cumprod(np.repeat(z[:, None, :], ORDERS, axis=1), axis=1)  # (E, K, C)
    s = zn @ np.stack([w, w * y, np.conj(w), np.conj(w) * y], axis=-1)  # (E, K, 4)
    force = np.abs(c * s[..., 0]) + np.abs(np.conj(c * s[..., 2]))
    moment = np.abs(c * s[..., 1]) + np.abs(np.conj(c * s[..., 3]))
    return force, moment


def best_time(func, repeat: int = 3) -> tuple[float, float]:
    """Best-of-``repeat`` time of one call [s]: elapsed (time.perf_counter, the measure)
    and this process's CPU time (time.process_time, for a shared machine)."""
    best, best_cpu = float("inf"), float("inf")
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        func()
        best = min(best, time.perf_counter() - start)
        best_cpu = min(best_cpu, time.process_time() - start_cpu)
    return best, best_cpu


def memory_child() -> None:
    """Run in a child process: one call on MEMORY_ENGINES engines, print the peaks."""
    args = batch(MEMORY_ENGINES)
    tracemalloc.start()
    batch_amplitudes(*args, orders=ORDERS)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    rss_kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB on Linux
    print(json.dumps({"traced_mb": peak / 1e6, "rss_mb": rss_kb * 1024 / 1e6}))


def main() -> None:
    args = batch(THROUGHPUT_ENGINES)
    force, moment = batch_amplitudes(*args, orders=ORDERS)
    ref_force, ref_moment = reference(*args)
    # equal to round-off of each engine's force scale (sum of m r w^2), moments times 1 m
    scale = (args[3].sum(axis=1) * args[0] * args[2] ** 2)[:, None]
    diff = max(
        float((np.abs(force - ref_force) / scale).max()),
        float((np.abs(moment - ref_moment) / scale).max()),
    )
    assert diff < 1e-12, f"library and reference differ by {diff} of the force scale"

    t, cpu = best_time(lambda: batch_amplitudes(*args, orders=ORDERS))
    t_ref, cpu_ref = best_time(lambda: reference(*args))
    rate, ratio = THROUGHPUT_ENGINES / t, t / t_ref

    child = subprocess.run(
        [sys.executable, __file__, "--memory"], check=True, capture_output=True, text=True
    )
    mem = json.loads(child.stdout)

    rows = [
        (
            f"batched analysis: {THROUGHPUT_ENGINES:,} engines, {CYLINDERS} cyl, "
            f"{ORDERS} orders, exact",
            f"{rate:,.0f} engines/s",
            f"{THROUGHPUT_ENGINES / cpu:,.0f} engines/s",
            f">= {TARGET_RATE:,.0f}",
            "PASS" if rate >= TARGET_RATE else "FAIL",
        ),
        (
            "reference: minimal numpy phasor sum, same batch",
            f"{THROUGHPUT_ENGINES / t_ref:,.0f} engines/s",
            f"{THROUGHPUT_ENGINES / cpu_ref:,.0f} engines/s",
            "",
            "",
        ),
        (
            "ratio batch time / reference time",
            f"{ratio:.2f}",
            f"{cpu / cpu_ref:.2f}",
            f"<= {TARGET_RATIO}",
            "PASS" if ratio <= TARGET_RATIO else "FAIL",
        ),
        (
            f"peak memory of one call, {MEMORY_ENGINES:,} engines (tracemalloc)",
            f"{mem['traced_mb']:,.0f} MB",
            "",
            f"<= {TARGET_MB:.0f} MB",
            "PASS" if mem["traced_mb"] <= TARGET_MB else "FAIL",
        ),
        (
            "  peak resident size of that process (inputs included)",
            f"{mem['rss_mb']:,.0f} MB",
            "",
            "",
            "",
        ),
    ]
    width = max(len(r[0]) for r in rows)
    print(f"load average (1 min) {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs")
    print(f"{'case'.ljust(width)}  {'measured':>20}  {'CPU time':>20}  {'target':>12}  result")
    print(f"{'-' * width}  {'-' * 20}  {'-' * 20}  {'-' * 12}  ------")
    for name, value, cpu_value, target, result in rows:
        print(f"{name.ljust(width)}  {value:>20}  {cpu_value:>20}  {target:>12}  {result}")


if __name__ == "__main__":
    if sys.argv[1:] == ["--memory"]:
        memory_child()
    else:
        main()
