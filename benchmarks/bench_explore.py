"""Speed of the design-space explorer (issue 15, item 4), measured side by side in one run.

Run: python benchmarks/bench_explore.py [--reference 40] [--slice 400000] [--workers 2]

Printed, each measured in this run:

* the inline-8 four-stroke (5 040 firing orders): the kernel (enumeration and figures of
  merit with counterweights, one batch) and the end-to-end run (chunks, filter, Pareto
  front, top-N), candidates/s and wall time against the target 0.3 s; the reference is
  the one-engine API (``balancing.balance`` and ``shaking.free_forces`` engine by engine)
  on ``--reference`` candidates, and the speed-up over it;
* the 12-cylinder two-stroke in-line engine (39 916 800 firing orders): a slice of
  ``--slice`` indices in this process and on a dask LocalCluster of ``--workers``
  processes, indices/s of each, and the time the whole enumeration projects for a cluster
  of N workers, assuming each worker is as fast as this process (linear scaling: the
  tasks are independent; the driver only merges small Pareto sets and top-N lists);
* the random search of the in-line 16 (15! firing orders): ``--draws`` sampled indices
  against as many consecutive ones.
"""

from __future__ import annotations

import argparse
import functools
import time
from dataclasses import replace

import numpy as np

from crankbalance.physics.balancing import CounterweightOptions, balance
from crankbalance.physics.explore import merit, orders
from crankbalance.physics.shaking import free_forces
from crankbalance.studies.explore import Keep, Sample, run

TARGET = 0.3  # s, the inline-8 end to end, balancing included
OBJECTIVES = ("F1_N", "M1_Nm", "F2_N", "M2_Nm")


def timed(func, repeat: int = 3):  # noqa: ANN001, ANN201
    """Best wall time over ``repeat`` calls [s], and the last result."""
    return timed_cpu(func, repeat)[::2]


def timed_cpu(func, repeat: int = 3):  # noqa: ANN001, ANN201
    """Best wall time and best CPU time of this process over ``repeat`` calls [s], and the
    last result (the CPU time is what a busy machine's wall time hides)."""
    wall, cpu, out = np.inf, np.inf, None
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        out = func()
        wall = min(wall, time.perf_counter() - start)
        cpu = min(cpu, time.process_time() - start_cpu)
    return wall, cpu, out


def one_by_one(problem: orders.Problem, count: int) -> float:
    """Wall time [s] of the one-engine API on the first ``count`` candidates."""
    cands = orders.chunk(problem, 0, orders.count(problem))
    # the counterweights merit() takes by default
    options = CounterweightOptions(cg_radius=problem.topology.crank_radius, angle="optimal")
    start = time.perf_counter()
    for i in range(min(count, cands.size)):
        model = replace(
            problem.topology,
            throw_angle=cands.throw_angle[i].copy(),
            firing_order=tuple(int(c) for c in cands.firing_order[i]),
        )
        free_forces(model, 8)
        balance(model, counterweights=options)
    return (time.perf_counter() - start) / min(count, cands.size)


def inline8(reference: int) -> None:
    problem = orders.problem("inline", 8, 4)
    total = orders.count(problem)
    evaluate = functools.partial(merit.merit, target="counterweights")
    keep = Keep(objectives=OBJECTIVES, key="residual_M_Nm", n=20)

    def kernel() -> int:
        return len(evaluate(orders.chunk(problem, 0, total))["F1_N"])

    kernel_s, kernel_cpu, size = timed_cpu(kernel)
    end_s, end_cpu, result = timed_cpu(lambda: run(problem, evaluate, keep=keep))
    per_engine = one_by_one(problem, reference)
    print(f"inline-8 four-stroke: {total} firing orders, {size} distinct engines")
    print(
        f"  kernel      {kernel_s:8.3f} s  (CPU {kernel_cpu:.3f} s)  "
        f"{size / kernel_s:10,.0f} candidates/s"
    )
    print(
        f"  end to end  {end_s:8.3f} s  (CPU {end_cpu:.3f} s)  {size / end_s:10,.0f} "
        f"candidates/s  target {TARGET} s  ratio {end_s / TARGET:.2f}  "
        f"(Pareto front {result.pareto['index'].size})"
    )
    print(
        f"  reference   one engine at a time: {per_engine * 1e3:.2f} ms/candidate, "
        f"{per_engine * size:.1f} s for all ({reference} measured); end to end is "
        f"{per_engine * size / end_s:.0f}x faster"
    )


def two_stroke12(indices: int, workers: int) -> None:
    problem = orders.problem("inline", 12, 2)
    total = orders.count(problem)
    evaluate = functools.partial(merit.merit, target="counterweights")
    keep = Keep(objectives=OBJECTIVES, key="residual_M_Nm", n=20)
    span = (0, min(indices, total))
    local_s, local = timed(lambda: run(problem, evaluate, keep=keep, span=span), 1)
    cluster_s, there = timed(
        lambda: run(problem, evaluate, keep=keep, span=span, workers=workers), 1
    )
    same = np.array_equal(local.top["index"], there.top["index"]) and np.array_equal(
        local.pareto["index"], there.pareto["index"]
    )
    print(f"12-cylinder two-stroke in-line: {total:,} firing orders; slice of {span[1]:,}")
    print(
        f"  this process      {local_s:8.2f} s  {span[1] / local_s:10,.0f} indices/s  "
        f"({local.candidates:,} distinct engines)"
    )
    print(
        f"  LocalCluster x{workers}   {cluster_s:8.2f} s  {span[1] / cluster_s:10,.0f} "
        f"indices/s  (cluster start included; same result as in process: {same})"
    )
    per_worker = span[1] / local_s  # one worker process does what this process does
    for n in (1, workers, 16, 64, 256):
        hours = total / (per_worker * n) / 3600
        print(f"  projected, {n:4d} workers: {hours:8.2f} h for all {total:,}")


def sampled(draws: int) -> None:
    """A random search of the in-line 16 (15! firing orders): draws/s in this process."""
    problem = orders.problem("inline", 16, 4)
    evaluate = functools.partial(merit.merit, target="counterweights")
    keep = Keep(objectives=OBJECTIVES, key="residual_M_Nm", n=20)
    seconds, result = timed(lambda: run(problem, evaluate, keep=keep, sample=Sample(draws)), 1)
    range_s, ranged = timed(lambda: run(problem, evaluate, keep=keep, span=(0, draws)), 1)
    print(f"in-line 16 four-stroke: {result.total:,} firing orders")
    print(
        f"  sample of {draws:,} draws  {seconds:8.2f} s  {draws / seconds:10,.0f} draws/s  "
        f"({result.candidates:,} distinct engines hit)"
    )
    print(
        f"  range of {draws:,} indices {range_s:8.2f} s  {draws / range_s:10,.0f} indices/s  "
        f"(a draw costs {range_s and seconds / range_s:.0f}x an index of a range)"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--reference", type=int, default=40)
    parser.add_argument("--slice", type=int, default=400_000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--draws", type=int, default=5000)
    args = parser.parse_args()
    inline8(args.reference)
    two_stroke12(args.slice, args.workers)
    sampled(args.draws)


if __name__ == "__main__":
    main()
