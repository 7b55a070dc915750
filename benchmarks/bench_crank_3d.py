"""The 3-D crank figure (issue 13: web edit -> updated figures): ``crank_3d``.

Measured in one process, wall-clock per build of the balanced crank's figure and its
``to_plotly_json()`` (what the web page does after every edit), median and slowest of
``--builds`` builds, for the V12 preset ``v12-60`` and a 16-cylinder V (the V12 file with
16 cylinders on a cross-plane crank of eight throws and a pair of secondary balance
shafts). Reference, measured in the same run: a bare plotly figure with one 3-D line
trace holding as many points as the crank figure draws, in the same template (the least
any figure of that size costs).

    python benchmarks/bench_crank_3d.py [--builds 30]

Target: at most 50 ms per build.
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable
from typing import Any

from crankbalance.io.engine_file import parse_engine_text, preset_text
from crankbalance.output.figures.common import TEMPLATE
from crankbalance.output.figures.crank3d import crank_3d
from crankbalance.studies.engine import BalanceStudy, balance_engine

TARGET = 0.050  # s per build


def v16() -> BalanceStudy:
    """The V12 preset turned into a 16-cylinder 90-degree V with balance shafts."""
    crank = '["0 deg", "90 deg", "270 deg", "180 deg", "180 deg", "270 deg", "90 deg", "0 deg"]'
    text = (
        preset_text("v12-60")
        .replace("cylinders = 12", "cylinders = 16")
        .replace(
            "firing_order = [1, 12, 4, 10, 5, 11, 6, 7, 3, 9, 2, 8]", f"throw_angles = {crank}"
        )
        .replace('bank_angle = "60 deg"', 'bank_angle = "90 deg"')
    )
    text += (
        '\n[balance_shafts.secondary]\narrangement = "pair"\ncg_radius = "30 mm"\n'
        'length = "400 mm"\n'
    )
    study = balance_engine(parse_engine_text(text, "V16"))
    assert study.model.cylinders == 16
    return study


def timed(build: Callable[[], Any], count: int) -> list[float]:
    build()  # warm: imports, plotly's validators and templates
    times = []
    for _ in range(count):
        start = time.perf_counter()
        build().to_plotly_json()
        times.append(time.perf_counter() - start)
    return times


def bare(points: int) -> Any:
    import plotly.graph_objects as go

    xs = [float(k) for k in range(points)]
    return go.Figure(
        data=[go.Scatter3d(x=xs, y=xs, z=xs, mode="lines")],
        layout={"template": TEMPLATE},
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--builds", type=int, default=30, help="builds to time per engine")
    count = parser.parse_args().builds

    print(f"crank_3d build + to_plotly_json, {count} builds each; target {TARGET * 1e3:.0f} ms")
    for label, study in (("v12-60", balance_engine("v12-60")), ("V16", v16())):
        fig = crank_3d(study)
        points = sum(x is not None for t in fig.data for x in t.x)
        measured = timed(lambda s=study: crank_3d(s), count)
        reference = timed(lambda n=points: bare(n), count)
        median, ref = statistics.median(measured), statistics.median(reference)
        print(
            f"{label}: {len(fig.data)} traces, {points} points: median {median * 1e3:.1f} ms,"
            f" slowest {max(measured) * 1e3:.1f} ms (target {TARGET * 1e3:.0f} ms:"
            f" {'met' if median <= TARGET else 'NOT met'}); bare figure of {points} points"
            f" {ref * 1e3:.1f} ms, ratio {median / ref:.2f}"
        )


if __name__ == "__main__":
    main()
