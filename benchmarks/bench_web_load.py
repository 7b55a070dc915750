"""The web server under load (issue 8): N concurrent sessions, each opening the page and
computing M engines (analysis, counterweights, shafts, time-domain check) through the
JSON API of ``crankbalance web``; prints p50/p95/max response times and the error count.

Run: python benchmarks/bench_web_load.py [--sessions 20] [--engines 20]
The browser-level timing (input to updated page) is in benchmarks/bench_web.py.
"""

from __future__ import annotations

import argparse
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from crankbalance.web.server import running_server

# the load generator is test scaffolding (tests/web/loadgen.py), not part of the package
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "web"))
from loadgen import run_session  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--sessions", type=int, default=20)
    parser.add_argument("--engines", type=int, default=20)
    args = parser.parse_args()
    with running_server() as url:
        start = time.perf_counter()
        with ThreadPoolExecutor(args.sessions) as pool:
            results = list(
                pool.map(lambda s: run_session(url, s, args.engines), range(args.sessions))
            )
        wall = time.perf_counter() - start
    times = np.array([t for r in results for t in r.times]) * 1e3
    errors = sum(len(r.errors) for r in results)
    rows = [
        ("sessions x engines", f"{args.sessions} x {args.engines}"),
        ("requests answered", f"{times.size}"),
        ("errors", f"{errors}"),
        ("response p50", f"{np.percentile(times, 50):.1f} ms"),
        ("response p95", f"{np.percentile(times, 95):.1f} ms"),
        ("response max", f"{times.max():.1f} ms"),
        ("throughput", f"{times.size / wall:.1f} engines/s"),
    ]
    width = max(len(r[0]) for r in rows)
    for name, value in rows:
        print(f"{name.ljust(width)}  {value:>16}")


if __name__ == "__main__":
    main()
