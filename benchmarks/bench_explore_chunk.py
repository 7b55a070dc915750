"""The explorer's chosen chunk against the best one (issue 25), measured in one run.

Run: python benchmarks/bench_explore_chunk.py [--repeat 3]

For each problem, a whole run in this process (enumeration, figures of merit with
counterweights, Pareto front and top-N) with the chunk ``explore.work.plan`` chooses, and
with chunks from a few thousand indices to the whole index space (at most
``explore.work.MAX_TASKS`` tasks, the range a user may give); printed: the time of the
chosen chunk, the best chunk and its time, the target and the ratio chosen / best. The
W12 broad arrow (39.9 million indices, 480 consistent orders) is the case of the issue:
with the former fixed chunk of 8192 indices it ran 4 873 tasks, almost all empty.
"""

from __future__ import annotations

import argparse
import functools
import math
import time

from crankbalance.physics.explore import merit, orders
from crankbalance.physics.explore.work import MAX_TASKS, plan
from crankbalance.studies.explore import Keep, run

#: the chosen chunk's run may take at most this many times the best chunk's
TARGET = 1.5
#: the former fixed chunk [indices]
FORMER = 8192
OBJECTIVES = ("F1_N", "M1_Nm", "F2_N", "M2_Nm")
PROBLEMS = {
    "W12 60 deg broad arrow": ("w", 12, math.radians(60)),
    "V12 60 deg": ("vee", 12, math.radians(60)),
    "V10 72 deg": ("vee", 10, math.radians(72)),
    "in-line 9": ("inline", 9, None),
}


def seconds(problem: orders.Problem, chunk: int, repeat: int) -> float:
    """Best wall time of a whole run with ``chunk`` [s]."""
    evaluate = functools.partial(merit.merit, target="counterweights")
    keep = Keep(objectives=OBJECTIVES, key="residual_M_Nm", n=20)
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        run(problem, evaluate, chunk=chunk, keep=keep)
        best = min(best, time.perf_counter() - start)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per chunk (best taken)")
    args = parser.parse_args()
    print(
        f"{'problem':24} {'indices':>11} {'chosen':>11} {'s':>7} {'best':>11} {'s':>7}"
        f" {'8192: s':>8} {'target':>7} {'ratio':>6}"
    )
    worst = 0.0
    for name, (layout, cylinders, bank) in PROBLEMS.items():
        problem = orders.problem(layout, cylinders, 4, bank_angle=bank)
        total = orders.count(problem)
        chosen = plan(problem, merit.merit).chunk
        least = -(-total // MAX_TASKS)
        sweep = {c for c in (2048, FORMER, 2**16, 2**19, 2**22, total) if least <= c <= total}
        times = {c: seconds(problem, c, args.repeat) for c in sorted(sweep | {chosen})}
        best = min(times, key=times.__getitem__)
        ratio = times[chosen] / times[best]
        worst = max(worst, ratio)
        former = f"{times[FORMER]:8.3f}" if FORMER in times else f"{'-':>8}"
        print(
            f"{name:24} {total:11,} {chosen:11,} {times[chosen]:7.3f} {best:11,} "
            f"{times[best]:7.3f} {former} {TARGET:7.2f} {ratio:6.2f}"
        )
    print(f"largest ratio chosen / best: {worst:.2f} (target at most {TARGET})")


if __name__ == "__main__":
    main()
