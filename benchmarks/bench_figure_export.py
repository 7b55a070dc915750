"""Figure PNG export (issue 13): the first export of a process against the later ones.

``render.to_image`` keeps one headless Chromium open for the whole process: the first
export starts it, later exports reuse it. Measured in one process, wall-clock time (the
work is done in Chromium's processes, so CPU time of this one would say little):

- the first export (starts Chromium and loads plotly.js into its page);
- ``--exports`` later exports of four different figures (median and slowest);
- reference, measured in the same run: one export the way kaleido does it without a kept
  browser (``kaleido.calc_fig_sync`` with no server: a Chromium started and closed per
  call), which is what every export cost before.

    python benchmarks/bench_figure_export.py [--exports 12]

Target: every export after the first at most 1 s.
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

from crankbalance.output import render
from crankbalance.output.figures.engine import curves_figure, orders_bar, polar_figure
from crankbalance.studies.engine import analyze

TARGET = 1.0  # s per export after the first


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exports", type=int, default=12, help="later exports to time")
    count = parser.parse_args().exports

    result = analyze("v12-60")
    kinds = [
        orders_bar(result),
        curves_figure(result),
        polar_figure(result, 1),
        orders_bar(analyze("inline4")),
    ]

    start = time.perf_counter()
    render.to_image(kinds[0], "png")
    first = time.perf_counter() - start

    later = []
    for k in range(count):
        start = time.perf_counter()
        data = render.to_image(kinds[k % len(kinds)], "png")
        later.append(time.perf_counter() - start)
        assert data[:4] == b"\x89PNG"

    import kaleido

    opts = {"format": "png", "width": 1000, "height": 600}
    start = time.perf_counter()
    kaleido.calc_fig_sync(
        kinds[0].to_dict(), opts=opts, kopts={"path": render.find_chromium(), "mathjax": False}
    )
    one_shot = time.perf_counter() - start

    launcher = render.EXPORTER.pid()
    children = Path(f"/proc/{launcher}/task/{launcher}/children")
    if launcher is not None and children.exists():
        browser = children.read_text().split()[0]
        command = Path(f"/proc/{browser}/cmdline").read_bytes().decode().split("\0")
        flags = [a for a in command if a in render.CHROMIUM_FLAGS]
        print(f"browser: {render.find_chromium()} -> {command[0]}, with {' '.join(flags)}")

    median, slowest = statistics.median(later), max(later)
    print(f"{'figure PNG export':<36} {'measured':>9} {'target':>7} {'ratio':>22}  ok")
    print(f"{'first export (starts Chromium)':<36} {first:8.2f}s {'-':>7} {'':>22}")
    print(
        f"{f'later exports, median of {count}':<36} {median:8.2f}s {TARGET:6.1f}s "
        f"{median / first:8.3f} of the first  {'yes' if median <= TARGET else 'NO'}"
    )
    print(
        f"{'later exports, slowest':<36} {slowest:8.2f}s {TARGET:6.1f}s "
        f"{slowest / first:8.3f} of the first  {'yes' if slowest <= TARGET else 'NO'}"
    )
    print(
        f"{'reference: Chromium per export':<36} {one_shot:8.2f}s {'-':>7} "
        f"{median / one_shot:8.3f} later/this"
    )


if __name__ == "__main__":
    main()
