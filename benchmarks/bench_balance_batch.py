"""Speed of the batched balancing solver (issue 13 row "batched balancing"), measured side
by side in one run.

Run: python benchmarks/bench_balance_batch.py [--engines 20000] [--reference 200]

The batch: crossplane V8 topology (8 cylinders, 4 throws), every engine with its own random
throw angles, rod ratio, masses, crank radius and speed, exact kinematics, 8 orders. The
full problem: optimal-angle counterweights with a balance factor, primary and secondary
shaft pairs, residuals and the residual check. Printed, each measured in this run:

* engines/s of :func:`balance_batch`, the target 50 000/s and their ratio;
* the one-engine solver :func:`balance` on the first ``--reference`` engines, and the
  speed-up of the batch over it;
* a minimal numpy version of the same algebra (phasor sum, least-norm counterweights by one
  pseudo-inverse, two-mass shafts, residual amplitudes; no options, no checks, no chunks)
  against :func:`balance_batch` with the same options (individual counterweights);
* the peak memory of :func:`balance_batch` above its result (tracemalloc), which the
  chunks bound.
"""

from __future__ import annotations

import argparse
import time
import tracemalloc

import numpy as np
from bench_solver import random_engines

from crankbalance.physics.balance_batch import balance_batch
from crankbalance.physics.balancing import CounterweightOptions, ShaftOptions, balance
from crankbalance.physics.kinematics import harmonic_coefficients
from crankbalance.physics.model import EngineBatch

TARGET = 50_000.0  # engines/s
CW_RADIUS, SHAFT_RADIUS, SHAFT_LENGTH = 0.045, 0.03, 0.3


def best(func, repeat: int = 3) -> tuple[float, float]:
    """Best wall time and best CPU time of this process over ``repeat`` calls [s]."""
    wall, cpu = [], []
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        func()
        wall.append(time.perf_counter() - start)
        cpu.append(time.process_time() - start_cpu)
    return min(wall), min(cpu)


def minimal_numpy(b: EngineBatch, orders: int = 8) -> tuple[np.ndarray, ...]:
    """The algebra of individual counterweights (balance factor 0) and two-mass shaft pairs
    with nothing else: no options, no degenerate cases, no chunks."""
    topo = b.topology
    r, w = b.crank_radius, b.speed
    coeff = harmonic_coefficients(r / b.rod_length, orders, b.cylinder_offset[:, 0] / r)
    delta = b.throw_angle[:, topo.cylinder_throw] - topo.cylinder_bank
    load = 0.5 * b.reciprocating_mass * (r * w**2)[:, None] * np.exp(1j * topo.cylinder_bank)
    turn = np.exp(1j * np.arange(1, orders + 1)[None, :, None] * delta[:, None, :])
    y = topo.cylinder_position
    fwd = coeff * np.einsum("ekc,ec->ek", turn, load)
    cfwd = coeff * np.einsum("ekc,ec->ek", turn, load * y)
    bwd = np.conj(coeff * np.einsum("ekc,ec->ek", turn, np.conj(load)))
    cbwd = np.conj(coeff * np.einsum("ekc,ec->ek", turn, np.conj(load) * y))
    # counterweights: least-norm first moments on every web
    rot = b.throw_rotating_mass * r[:, None] * np.exp(1j * b.throw_angle)
    yt = topo.throw_position
    offset = np.diff(yt).min() / 4
    yw = np.repeat(yt, 2) + np.tile([-offset, offset], topo.throws)
    length = max(np.ptp(yt), r.max())
    a = np.array([np.ones_like(yw), yw / length])
    target = np.stack([-rot.sum(axis=1), -(rot * yt).sum(axis=1) / length], axis=1)
    v = target @ np.linalg.pinv(a).T
    cw_mass = np.abs(v) / CW_RADIUS
    rotating_left = np.abs(w**2 * (rot.sum(axis=1) + v.sum(axis=1)))
    # shafts: two masses at +-l/2 cancelling force and couple of orders 1 and 2, and what
    # their forces leave (rebuilt from the masses' first moments)
    half = SHAFT_LENGTH / 2
    after_f, after_c = [fwd.copy(), bwd.copy()], [cfwd.copy(), cbwd.copy()]
    masses = []
    for k in (0, 1):
        gain = SHAFT_RADIUS * ((k + 1) * w) ** 2
        for s, (force, couple) in enumerate(((fwd, cfwd), (bwd, cbwd))):
            v2 = (-force[:, k] / gain - couple[:, k] / (gain * half)) / 2
            v1 = -force[:, k] / gain - v2
            masses.append(np.abs(np.stack([v1, v2], axis=1)))
            after_f[s][:, k] += gain * (v1 + v2)
            after_c[s][:, k] += gain * half * (v2 - v1)
    residual_force = np.abs(after_f[0]) + np.abs(after_f[1])
    residual_moment = np.abs(after_c[0]) + np.abs(after_c[1])
    return cw_mass, rotating_left, *masses, residual_force, residual_moment


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--engines", type=int, default=20_000)
    parser.add_argument("--reference", type=int, default=200)
    args = parser.parse_args()

    batch = random_engines(args.engines)
    full = (
        CounterweightOptions(CW_RADIUS, angle="optimal", balance_factor=0.5),
        ShaftOptions(SHAFT_RADIUS, SHAFT_LENGTH),
        ShaftOptions(SHAFT_RADIUS, SHAFT_LENGTH),
    )
    simple = (CounterweightOptions(CW_RADIUS, method="individual"), *full[1:])

    balance_batch(batch.take(slice(0, 100)), *full)  # warm up
    t_full = best(lambda: balance_batch(batch, *full))
    models = [batch.model(i) for i in range(min(args.reference, batch.size))]
    t_one = best(lambda: [balance(m, *full) for m in models], repeat=1)
    t_simple = best(lambda: balance_batch(batch, *simple))
    t_minimal = best(lambda: minimal_numpy(batch))

    result = balance_batch(batch, *full)
    kept = sum(v.nbytes for v in _arrays(result))  # the result itself, the floor
    tracemalloc.start()
    balance_batch(batch, *full)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()

    print(
        f"batched balancing, crossplane V8 topology, {batch.size} random engines, "
        "exact kinematics, 8 orders (engines/s by wall-clock and by CPU time of this process;"
        " they differ when other processes share the cores)"
    )
    rows = [
        ("balance_batch: optimal counterweights + 2 shaft pairs + check", batch.size, t_full),
        ("balance (one engine at a time), same problem", len(models), t_one),
        ("balance_batch: individual counterweights + 2 shaft pairs + check", batch.size, t_simple),
        ("minimal numpy algebra of that problem (no options, no checks)", batch.size, t_minimal),
    ]
    width = max(len(r[0]) for r in rows)
    print(f"{'case'.ljust(width)}  {'wall /s':>10}  {'CPU /s':>10}")
    for name, count, (wall, cpu) in rows:
        print(f"{name.ljust(width)}  {count / wall:>10,.0f}  {count / cpu:>10,.0f}")
    for label, k in (("wall", 0), ("CPU", 1)):
        rate = batch.size / t_full[k]
        print(
            f"{label:>4}: measured {rate:,.0f} engines/s, target {TARGET:,.0f}, "
            f"measured/target {rate / TARGET:.2f}; speed-up over the one-engine solver "
            f"{rate / (len(models) / t_one[k]):.0f}x; balance_batch / minimal numpy "
            f"(time, same problem) {t_simple[k] / t_minimal[k]:.2f}"
        )
    print(
        f"peak memory of balance_batch above its result: {(peak - kept) / 1e6:.1f} MB "
        f"(result {kept / 1e6:.1f} MB, {kept / batch.size:.0f} B per engine)"
    )


def _arrays(obj: object) -> list[np.ndarray]:
    """Every array of a result dataclass, recursively."""
    import dataclasses

    if isinstance(obj, np.ndarray):
        return [obj]
    if dataclasses.is_dataclass(obj):
        return [a for f in dataclasses.fields(obj) for a in _arrays(getattr(obj, f.name))]
    return []


if __name__ == "__main__":
    main()
