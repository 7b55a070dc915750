"""The explorer against its numpy floor (issue 30, item 4), measured side by side in one run.

Run: python benchmarks/bench_explore_floor.py [--draws 20000] [--repeat 5]

BLAS runs on one thread (set here before numpy is imported), as the explorer's tasks do
on a worker. Printed, each measured in this run (best of ``--repeat``, elapsed time with
the process's CPU time beside it):

1. the in-line 8 four-stroke, all 5 040 firing orders, end to end with counterweights
   (``studies.explore.run``: enumeration, figures of merit with the balancing, filter,
   Pareto front and top 20), against the floor: a minimal numpy computation of F1, F2, M1
   and M2 of all 5 040 firing orders, each order's crank derived from it, the harmonic
   coefficients given (``floor_all_orders``); target: at most 10 times the floor (printed
   beside: the same sums over the 2 544 candidates' cranks, given, ``floor``);
2. the in-line 16 four-stroke by random sampling (``Sample``), draws per second; target:
   at least 20 000 draws/s; the reference is an index of a range of as many indices.
"""

from __future__ import annotations

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_name] = "1"

import argparse  # noqa: E402
import functools  # noqa: E402
import itertools  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from crankbalance.physics.explore import merit, orders  # noqa: E402
from crankbalance.physics.explore.candidates import Candidates  # noqa: E402
from crankbalance.physics.kinematics import harmonic_coefficients  # noqa: E402
from crankbalance.studies.explore import Keep, Sample, run  # noqa: E402

TARGET_RATIO = 10.0
TARGET_DRAWS = 20_000.0
OBJECTIVES = ("F1_N", "M1_Nm", "F2_N", "M2_Nm")


def best(func: Callable[[], Any], repeat: int) -> tuple[float, float, Any]:
    """Best elapsed and best CPU time of one call over ``repeat`` calls [s], and its result."""
    wall, cpu, out = np.inf, np.inf, None
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        out = func()
        wall = min(wall, time.perf_counter() - start)
        cpu = min(cpu, time.process_time() - start_cpu)
    return wall, cpu, out


def floor(cands: Candidates) -> Callable[[], tuple[np.ndarray, ...]]:
    """The floor: |F1|, |F2|, |M1|, |M2| of every candidate as a minimal numpy sum, an
    in-line engine's (one bank, equal masses), the coefficients computed beforehand."""
    topo = cands.topology
    c = harmonic_coefficients(topo.rod_ratio, 2, 0.0)
    p = topo.reciprocating_mass * topo.crank_radius * topo.speed**2  # (C,)
    py = p * topo.cylinder_position
    throw = topo.cylinder_throw
    scale = np.abs(c)
    angle = cands.throw_angle

    def reference() -> tuple[np.ndarray, ...]:
        z = np.exp(1j * angle[:, throw])  # (B, C)
        z2 = z * z
        return (
            scale[0] * np.abs(z @ p),
            scale[1] * np.abs(z2 @ p),
            scale[0] * np.abs(z @ py),
            scale[1] * np.abs(z2 @ py),
        )

    return reference


def floor_all_orders(cands: Candidates) -> Callable[[], tuple[np.ndarray, ...]]:
    """The issue's floor: |F1|, |F2|, |M1|, |M2| of every firing order of the index space
    (all 7! = 5 040 sequences starting at cylinder 1, given as an integer array), each
    order's crank derived from it (cylinder k of the sequence fires at k times the even
    interval, its throw at minus that angle: magnitudes do not see the sign), the
    coefficients computed beforehand; in-line, equal masses, even firing."""
    topo = cands.topology
    c = harmonic_coefficients(topo.rod_ratio, 2, 0.0)
    p = topo.reciprocating_mass * topo.crank_radius * topo.speed**2
    py = p * topo.cylinder_position
    n = topo.cylinders
    rest = np.array(list(itertools.permutations(range(1, n))), dtype=np.int64)
    sequence = np.concatenate([np.zeros((rest.shape[0], 1), dtype=np.int64), rest], axis=1)
    step = 2 * np.pi * topo.strokes / 2 / n
    interval = step * np.arange(n)
    rows = np.arange(sequence.shape[0])[:, None]
    scale = np.abs(c)

    def reference() -> tuple[np.ndarray, ...]:
        fire = np.empty(sequence.shape)
        fire[rows, sequence] = interval  # cylinder sequence[k] fires at k intervals
        z = np.exp(1j * fire)  # its throw at minus that angle, mod 2 pi
        z2 = z * z
        return (
            scale[0] * np.abs(z @ p),
            scale[1] * np.abs(z2 @ p),
            scale[0] * np.abs(z @ py),
            scale[1] * np.abs(z2 @ py),
        )

    return reference


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=20_000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    evaluate = functools.partial(merit.merit, target="counterweights")
    keep = Keep(objectives=OBJECTIVES, key="residual_M_Nm", n=20)

    problem = orders.problem("inline", 8, 4)
    cands = orders.chunk(problem, 0, orders.count(problem))
    reference = floor(cands)
    mine = evaluate(cands)
    topo = cands.topology
    force = float(topo.reciprocating_mass.sum()) * topo.crank_radius * topo.speed**2
    for name, value in zip(OBJECTIVES[::2] + OBJECTIVES[1::2], reference(), strict=True):
        assert np.allclose(mine[name], value, rtol=1e-9, atol=1e-9 * force), name
    run(problem, evaluate, keep=keep)  # warm up
    wall, cpu, result = best(lambda: run(problem, evaluate, keep=keep), args.repeat)
    # glibc maps a large block afresh on every call (its pages faulted in each time) until
    # a freed mapping raises its threshold, which depends on what the process did before:
    # the floor's temporaries (645 kB) took 0.98 or 1.4-1.6 ms by that alone. A freed
    # 8 MB block puts them on the heap: the floor at its fastest, the stricter reference
    np.ones(2**20).sum()
    f_wall, f_cpu, _ = best(floor_all_orders(cands), max(args.repeat, 20))
    c_wall, c_cpu, _ = best(reference, max(args.repeat, 20))
    print(f"load average (1 min) {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs; BLAS 1 thread")
    print(
        f"in-line 8, {orders.count(problem)} firing orders, {cands.size} candidates, "
        f"{np.unique(cands.throw_angle, axis=0).shape[0]} distinct cranks"
    )
    print(f"  end to end, counterweights   {wall * 1e3:8.2f} ms  (CPU {cpu * 1e3:.2f} ms)")
    print(
        f"  floor: F1, F2, M1, M2 of all {orders.count(problem)} orders, cranks derived "
        f"{f_wall * 1e3:8.2f} ms  (CPU {f_cpu * 1e3:.2f} ms)"
    )
    print(
        f"  (of the {cands.size} candidates' cranks, given: {c_wall * 1e3:.2f} ms, CPU "
        f"{c_cpu * 1e3:.2f} ms; end to end is {wall / c_wall:.0f} x that)"
    )
    ratio, ratio_cpu = wall / f_wall, cpu / f_cpu
    verdict = "met" if ratio <= TARGET_RATIO else "NOT met"
    print(
        f"  measured {ratio:.1f} x the floor (CPU {ratio_cpu:.1f} x); target <= "
        f"{TARGET_RATIO:g} x ({verdict}); Pareto front {result.pareto['index'].size}"
    )

    problem = orders.problem("inline", 16, 4)
    sample = Sample(args.draws)
    run(problem, evaluate, keep=keep, sample=Sample(100))  # warm up
    s_wall, s_cpu, sampled = best(lambda: run(problem, evaluate, keep=keep, sample=sample), 1)
    r_wall, _, _ = best(lambda: run(problem, evaluate, keep=keep, span=(0, args.draws)), 1)
    rate, rate_cpu = args.draws / s_wall, args.draws / s_cpu
    verdict = "met" if rate >= TARGET_DRAWS else "NOT met"
    print(f"in-line 16, {sampled.total:,} firing orders, sample of {args.draws:,} draws")
    print(
        f"  measured {rate:,.0f} draws/s (CPU {rate_cpu:,.0f}/s); target >= "
        f"{TARGET_DRAWS:,.0f}/s ({verdict}); {sampled.candidates:,} distinct engines hit; "
        f"a draw costs {s_wall / r_wall:.1f} x an index of a range"
    )


if __name__ == "__main__":
    main()
