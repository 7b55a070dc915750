"""Cold start of ``crankbalance analyze PRESET`` and ``balance PRESET`` against
``python -c "import numpy"``.

Run: python benchmarks/bench_cold_start.py [--runs N] [--preset NAME] [--as-is]

The three commands run in turn, N times each, in fresh interpreters of the same Python, so
that a drift of the machine's speed during the run touches all of them. Printed: the
median wall time and the median CPU time (user + system) of each, and each command's
ratio to the numpy import, with the target (issue 30: at most 1.5 times the numpy import;
issue 13 asked 2.5).

Python reads compiled bytecode of an installed package (pip writes it on installation).
Where ``PYTHONDONTWRITEBYTECODE`` is set, a source checkout would be compiled at every
start instead; so by default every command runs with a bytecode cache of its own in a
temporary folder (``PYTHONPYCACHEPREFIX``), filled by one warm-up run of each. ``--as-is``
keeps the environment as it is.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

TARGET_RATIO = 1.5


def run(command: list[str], env: dict[str, str]) -> tuple[float, float]:
    """Wall and CPU (user + system) time of one run of ``command`` [s]."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    return wall, cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=15, help="runs of each command")
    parser.add_argument("--preset", default="inline4", help="engine preset")
    parser.add_argument("--as-is", action="store_true", help="no bytecode cache of our own")
    args = parser.parse_args()

    commands = {
        "python -c 'import numpy'": [sys.executable, "-c", "import numpy"],
        **{
            f"crankbalance {name} {args.preset}": [
                *(sys.executable, "-m", "crankbalance", name, args.preset)
            ]
            for name in ("analyze", "balance")
        },
    }
    with tempfile.TemporaryDirectory(prefix="crankbalance-pycache-") as cache:
        env = dict(os.environ)
        if not args.as_is:
            env.pop("PYTHONDONTWRITEBYTECODE", None)
            env["PYTHONPYCACHEPREFIX"] = cache
        for command in commands.values():
            run(command, env)  # warm-up: file cache, and bytecode unless --as-is
        times: dict[str, list[tuple[float, float]]] = {name: [] for name in commands}
        for _ in range(args.runs):
            for name, command in commands.items():
                times[name].append(run(command, env))

    bytecode = "as the environment is" if args.as_is else "bytecode cached"
    print(f"{args.runs} runs of each, in turn ({bytecode}); medians, wall (min-max) and CPU")
    wall = {name: statistics.median(w for w, _ in t) for name, t in times.items()}
    cpu = {name: statistics.median(c for _, c in t) for name, t in times.items()}
    reference = next(iter(commands))
    width = max(map(len, commands)) + 2
    for name, t in times.items():
        walls = [w for w, _ in t]
        print(
            f"  {name:{width}s} wall {wall[name] * 1e3:6.0f} ms "
            f"({min(walls) * 1e3:.0f}-{max(walls) * 1e3:.0f})   cpu {cpu[name] * 1e3:6.0f} ms"
        )
    for name in list(commands)[1:]:
        ratio = wall[name] / wall[reference]
        verdict = "met" if ratio <= TARGET_RATIO else "NOT met"
        print(
            f"{name}: measured {wall[name] * 1e3:.0f} ms = {ratio:.2f} x the numpy import "
            f"(CPU {cpu[name] / cpu[reference]:.2f} x); target <= {TARGET_RATIO} x ({verdict})"
        )


if __name__ == "__main__":
    main()
