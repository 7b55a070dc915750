"""A still picture (SVG) of a 3-D figure's scene, shown while the browser draws it.

A fresh page draws the 3-D crank (:func:`crankbalance.output.figures.crank3d.crank_3d`)
with plotly.js in WebGL, which on a machine without a GPU (software WebGL) comes seconds
after the page's first paint: plotly.js (1.35 MB) has to be loaded and run first. The web
page shows this picture in the figure's place until then (``widgets.FigureCard``), so
the user sees the crank with the page.

:func:`scene_svg` takes the figure's own traces (plotly JSON: ``scatter3d`` lines and
markers) and draws them as the 3-D view first shows them: each point is scaled into the
scene's box (each axis's range spans its ``aspectratio``), seen from the scene's camera
``eye`` (looking at the box's centre, z up) in perspective, and the scene's whole box is
fitted to the picture, as plotly.js first shows it. Nothing is computed here: every point
is one of the figure's, so both pictures show the same crank. Traces of other types are
left out (the 3-D crank has none).
"""

from __future__ import annotations

import math
from html import escape
from typing import Any

#: the picture's size [px] (the SVG scales to its element, keeping its proportions)
WIDTH, HEIGHT = 640, 400
#: the margin around the drawing [px]
MARGIN = 16
#: plotly's default camera eye (scene coordinates)
DEFAULT_EYE = (1.25, 1.25, 1.25)
#: the most points a picture draws (a bound on the work; the 3-D crank has about 100)
MAX_POINTS = 20_000


def _box(layout: dict[str, Any]) -> tuple[list[tuple[float, float]], tuple[float, ...]]:
    """Each axis's data range (x, y, z) and the scene's aspect ratios."""
    scene = layout.get("scene") or {}
    ranges = []
    for axis in ("xaxis", "yaxis", "zaxis"):
        span = (scene.get(axis) or {}).get("range")
        ranges.append((float(span[0]), float(span[1])) if span else (math.nan, math.nan))
    aspect = scene.get("aspectratio") or {}
    return ranges, tuple(float(aspect.get(a, 1.0)) for a in ("x", "y", "z"))


def _points(trace: dict[str, Any]) -> list[tuple[float, float, float] | None]:
    """A trace's points, ``None`` where a line is broken (a missing coordinate)."""
    points: list[tuple[float, float, float] | None] = []
    for p in zip(trace.get("x") or (), trace.get("y") or (), trace.get("z") or (), strict=False):
        if any(v is None or not math.isfinite(float(v)) for v in p):
            points.append(None)
        else:
            points.append((float(p[0]), float(p[1]), float(p[2])))
    return points


def scene_svg(figure: dict[str, Any]) -> str:
    """The scene of ``figure`` (plotly JSON of a 3-D figure) as an SVG picture.

    Parameters
    ----------
    figure
        ``{"data": [...], "layout": {...}}``: ``scatter3d`` traces (``x``, ``y``, ``z`` in
        the scene's data units, ``mode`` lines and/or markers, ``line.color``/``width``,
        ``marker.color``/``size``) and the layout's ``scene`` (axis ranges, aspect ratio,
        camera eye).

    Returns
    -------
    str
        An ``<svg>`` element of :data:`WIDTH` x :data:`HEIGHT` px (viewBox) that scales to
        its box; empty (no drawing) when the figure has no point.
    """
    traces = [t for t in figure.get("data", []) if t.get("type") == "scatter3d"]
    ranges, aspect = _box(figure.get("layout") or {})
    all_points = [p for t in traces for p in _points(t) if p is not None][:MAX_POINTS]
    # each axis's range (the data's where the layout gives none) spans its aspect ratio
    centre, scale = [], []
    for k, (low, high) in enumerate(ranges):
        if not math.isfinite(low) or not math.isfinite(high) or high == low:
            values = [p[k] for p in all_points] or [0.0]
            low, high = min(values), max(values)
        centre.append((low + high) / 2)
        scale.append(aspect[k] / (high - low) if high > low else 1.0)
    scene = (figure.get("layout") or {}).get("scene") or {}
    eye_d = ((scene.get("camera") or {}).get("eye")) or {}
    eye = tuple(float(eye_d.get(a, d)) for a, d in zip("xyz", DEFAULT_EYE, strict=True))
    distance = math.sqrt(sum(e * e for e in eye)) or 1.0
    back = tuple(e / distance for e in eye)  # from the centre towards the eye
    # the picture's right and up: right = forward x z-up, up = right x forward
    right = (-back[1], back[0], 0.0)
    norm = math.hypot(right[0], right[1])
    right = (right[0] / norm, right[1] / norm, 0.0) if norm > 1e-9 else (1.0, 0.0, 0.0)
    up = (
        back[1] * right[2] - back[2] * right[1],
        back[2] * right[0] - back[0] * right[2],
        back[0] * right[1] - back[1] * right[0],
    )

    def project(p: tuple[float, float, float]) -> tuple[float, float]:
        q = [(p[k] - centre[k]) * scale[k] for k in range(3)]
        depth = distance - sum(q[k] * back[k] for k in range(3))  # along the view
        f = distance / max(depth, 1e-6)
        return (
            f * sum(q[k] * right[k] for k in range(3)),
            f * sum(q[k] * up[k] for k in range(3)),
        )

    if not all_points:
        return f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {WIDTH} {HEIGHT}"></svg>'
    # fitted as plotly.js fits the scene: its whole box (every corner) in the picture
    half = [aspect[k] / 2 / scale[k] for k in range(3)]  # half of each range
    corners = [
        (centre[0] + a * half[0], centre[1] + b * half[1], centre[2] + c * half[2])
        for a in (-1, 1)
        for b in (-1, 1)
        for c in (-1, 1)
    ]
    flat = [project(p) for p in [*all_points, *corners]]
    xs, ys = [p[0] for p in flat], [p[1] for p in flat]
    span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-12)
    fit = min(
        (WIDTH - 2 * MARGIN) / max(max(xs) - min(xs), span * 1e-3),
        (HEIGHT - 2 * MARGIN) / max(max(ys) - min(ys), span * 1e-3),
    )
    mid = ((max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2)

    def px(p: tuple[float, float, float]) -> str:
        x, y = project(p)
        return f"{WIDTH / 2 + (x - mid[0]) * fit:.1f},{HEIGHT / 2 - (y - mid[1]) * fit:.1f}"

    parts = []
    for trace in traces:
        mode = str(trace.get("mode") or "lines+markers")
        points = _points(trace)
        if "lines" in mode:
            line = trace.get("line") or {}
            colour = escape(str(line.get("color") or "#444444"))
            width = float(line.get("width") or 2)
            run: list[str] = []
            for p in [*points, None]:
                if p is None:
                    if len(run) > 1:
                        parts.append(
                            f'<polyline points="{" ".join(run)}" fill="none" '
                            f'stroke="{colour}" stroke-width="{width:g}" '
                            'stroke-linecap="round" stroke-linejoin="round"/>'
                        )
                    run = []
                else:
                    run.append(px(p))
        if "markers" in mode:
            marker = trace.get("marker") or {}
            colour = escape(str(marker.get("color") or "#444444"))
            sizes = marker.get("size", 6)
            for k, p in enumerate(points):
                if p is None:
                    continue
                size = float(sizes[k] if hasattr(sizes, "__len__") else sizes)
                x, y = px(p).split(",")
                parts.append(
                    f'<circle cx="{x}" cy="{y}" r="{size / 2:g}" fill="{colour}" '
                    f'fill-opacity="{float(marker.get("opacity", 1)):g}"/>'
                )
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {WIDTH} {HEIGHT}" '
        'preserveAspectRatio="xMidYMid meet" width="100%" height="100%">'
        + "".join(parts)
        + "</svg>"
    )
