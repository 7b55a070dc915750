"""Cold start of ``crankbalance analyze PRESET`` against ``python -c "import numpy"``.

Run: python benchmarks/bench_cold_start.py [--runs N] [--preset NAME] [--command analyze]

Both commands run alternately, N times each, in fresh interpreters (the same Python, the
same environment), so that a drift of the machine's speed during the run touches both;
the medians of their wall times and the ratio of the medians are printed with the target
(issue 13: the cold start at most 2.5 times the numpy import).
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time

TARGET_RATIO = 2.5


def wall(command: list[str]) -> float:
    """Wall time of one run of ``command`` [s] (its output is discarded)."""
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=15, help="runs of each command")
    parser.add_argument("--preset", default="inline4", help="engine preset")
    parser.add_argument("--command", default="analyze", choices=("analyze", "balance"))
    args = parser.parse_args()

    reference = [sys.executable, "-c", "import numpy"]
    command = [sys.executable, "-m", "crankbalance", args.command, args.preset]
    wall(reference), wall(command)  # warm the file cache
    times: dict[str, list[float]] = {"reference": [], "command": []}
    for _ in range(args.runs):
        times["reference"].append(wall(reference))
        times["command"].append(wall(command))
    ref = statistics.median(times["reference"])
    cmd = statistics.median(times["command"])
    ratio = cmd / ref
    print(f"runs: {args.runs} of each, alternately; medians (min-max)")
    for name, label in (
        ("reference", "python -c 'import numpy'"),
        ("command", " ".join(["crankbalance", args.command, args.preset])),
    ):
        t = times[name]
        print(
            f"  {label:38s} {statistics.median(t) * 1e3:7.1f} ms "
            f"({min(t) * 1e3:.1f}-{max(t) * 1e3:.1f})"
        )
    verdict = "met" if ratio <= TARGET_RATIO else "NOT met"
    print(
        f"measured {cmd * 1e3:.1f} ms = {ratio:.2f} x the numpy import; "
        f"target <= {TARGET_RATIO} x ({verdict})"
    )


if __name__ == "__main__":
    main()
