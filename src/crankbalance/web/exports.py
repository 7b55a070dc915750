"""Data of a figure as CSV or JSON (the numbers behind every plot of the web app).

The figures themselves come from :mod:`crankbalance.output.figures`; this only writes out the
traces a figure holds (name, x, y and z where present), so what is downloaded is exactly
what is drawn.
"""

from __future__ import annotations

import csv
import io
import json
from typing import Any

import numpy as np


def _column(values: Any) -> list[Any]:
    if values is None:
        return []
    array = np.asarray(values)
    if array.dtype.kind in "fc":
        return [None if not np.isfinite(v) else float(np.real(v)) for v in array.ravel()]
    return array.ravel().tolist()


def figure_traces(fig: Any) -> list[dict[str, Any]]:
    """The traces of a plotly figure as {name, type, x, y[, z]} with plain lists."""
    out = []
    for k, trace in enumerate(fig.data):
        item: dict[str, Any] = {"name": trace.name or f"trace {k + 1}", "type": trace.type}
        for axis in ("x", "y", "z", "r", "theta"):
            if hasattr(trace, axis) and getattr(trace, axis) is not None:
                item[axis] = _column(getattr(trace, axis))
        out.append(item)
    return out


def figure_json(fig: Any, title: str = "") -> str:
    """The traces of a figure as JSON: ``{"schema": "crankbalance.figure-data/1", ...}``."""
    return json.dumps(
        {"schema": "crankbalance.figure-data/1", "title": title, "traces": figure_traces(fig)},
        indent=1,
    )


def figure_csv(fig: Any) -> str:
    """The traces of a figure as CSV in long form: trace, point, x, y, z."""
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow(["trace", "point", "x", "y", "z"])
    for item in figure_traces(fig):
        xs, ys, zs = (
            item.get("x", item.get("theta", [])),
            item.get("y", item.get("r", [])),
            item.get("z", []),
        )
        n = max(len(xs), len(ys), len(zs))
        for i in range(n):
            writer.writerow(
                [
                    item["name"],
                    i,
                    xs[i] if i < len(xs) else "",
                    ys[i] if i < len(ys) else "",
                    zs[i] if i < len(zs) else "",
                ]
            )
    return buffer.getvalue()


def table_csv(rows: list[dict[str, Any]]) -> str:
    """Rows of dictionaries (same keys) as CSV."""
    buffer = io.StringIO()
    if rows:
        writer = csv.DictWriter(buffer, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    return buffer.getvalue()
