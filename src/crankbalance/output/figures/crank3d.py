"""The 3-D view of the crankshaft (engine analysis and balancing,
:mod:`crankbalance.studies.engine`) and its framing: the scene's ranges, tick labels and
the camera distance at which the whole crank fits the view.

Public functions
----------------
- ``crank_3d(model, balance_study=None) -> Figure``
    3-D view of the crankshaft: journals, throws, webs, cylinder axes, counterweights
    (marker size from mass), balance shafts with their masses (schematic positions).
- ``crank_3d_scene(traces) -> dict``
    The plotly scene that frames the traces (ranges, aspect, ticks, camera).
- ``scene_box_fits(ratios, eye) -> bool``
    Whether a scene box seen from ``eye`` fits the view.
- ``clean_tick(value) -> float``
    A tick value without float noise.

The 3-D view puts the crank axis y horizontally; lengths in mm.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .common import COLORS, TEMPLATE, figure_title, plotly_go

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...physics.model import EngineModel
    from ...studies.engine import Analysis, BalanceStudy


#: the 3-D crank's frame: room around the drawing on every side, as a share of its largest
#: extent; the shortest axis drawn at least this share of the longest (a single's crank is
#: a few mm long, a radial's cylinders reach 400 mm: the short axis keeps its scale and
#: gets empty room, so its tick labels do not crowd); tick labels per axis of full length;
#: the camera's direction (from the front, a little from the right and above)
SCENE_MARGIN = 0.08
SCENE_MIN_ASPECT = 0.4
SCENE_TICKS = 8
SCENE_EYE = (0.7, -1.9, 0.6)
#: the view the camera's distance is fitted to: plotly's vertical field of view [rad], the
#: width / height of the scene it must fit (a half-width web card; a wider figure only
#: gains room), and the share of that view the box may fill
SCENE_FOV = math.pi / 4
SCENE_VIEW_ASPECT = 1.25
SCENE_FILL = 0.7


def scene_box_fits(ratios: ArrayLike, eye: ArrayLike) -> bool:
    """Whether the eight corners of a plotly scene box (sides ``ratios``, the aspect
    ratios, centred on the origin) seen in perspective from ``eye`` (looking at the
    centre, z up, vertical field of view :data:`SCENE_FOV`) lie within
    :data:`SCENE_FILL` of a view :data:`SCENE_VIEW_ASPECT` times as wide as high."""
    position = np.asarray(eye, dtype=float)
    forward = -position / np.linalg.norm(position)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half = np.asarray(ratios, dtype=float) / 2
    corners = np.array(np.meshgrid(*[(-h, h) for h in half])).reshape(3, -1).T
    relative = corners - position
    depth = relative @ forward
    if np.any(depth <= 0):
        return False
    tangent = math.tan(SCENE_FOV / 2) * SCENE_FILL
    across = np.abs(relative @ right) / depth
    high = np.abs(relative @ up) / depth
    return bool(np.all(across <= tangent * SCENE_VIEW_ASPECT) and np.all(high <= tangent))


def _fitted_eye(ratios: Sequence[float]) -> NDArray[np.float64]:
    """The camera along :data:`SCENE_EYE` at the least distance (to 1 %) from which the
    box of ``ratios`` fits the view (:func:`scene_box_fits`)."""
    direction = np.asarray(SCENE_EYE, dtype=float)
    direction /= np.linalg.norm(direction)
    near, far = 0.1, 50.0
    while far / near > 1.01:
        middle = math.sqrt(near * far)
        near, far = (near, middle) if scene_box_fits(ratios, middle * direction) else (middle, far)
    return far * direction


#: no tick label within this share of an axis' length from its ends, where three axes meet
#: and their labels would run into each other
SCENE_TICK_EDGE = 0.1


def _scene_ticks(span: Sequence[float], count: int) -> list[float]:
    """At most about ``count`` round tick values (1, 2 or 5 times a power of ten apart) in
    ``span``, none within :data:`SCENE_TICK_EDGE` of its ends."""
    low, high = float(span[0]), float(span[1])
    edge = SCENE_TICK_EDGE * (high - low)
    raw = (high - low) / max(count, 1)
    power = 10.0 ** math.floor(math.log10(raw))
    step = next(f * power for f in (1.0, 2.0, 5.0, 10.0) if f * power >= raw)
    first = math.ceil((low + edge) / step)
    last = math.floor((high - edge) / step)
    return [clean_tick(k * step) for k in range(first, last + 1)]


def clean_tick(value: float) -> float:
    """A tick value without float noise (``3 * 0.1`` -> ``0.3``, no ``-0.0``)."""
    return float(f"{value:.12g}") + 0.0


def crank_3d_scene(traces: list[dict[str, Any]]) -> dict[str, Any]:
    """The scene of the 3-D crank that frames every trace: per axis a range holding every
    point of ``traces`` (plotly ``scatter3d`` dictionaries, ``None`` breaks skipped) with
    :data:`SCENE_MARGIN` of room, widened about its centre to at least
    :data:`SCENE_MIN_ASPECT` of the longest; the box to scale (aspect ratio of the
    ranges), at most :data:`SCENE_TICKS` tick labels on the longest axis and fewer on the
    shorter ones, and the camera along :data:`SCENE_EYE` as near as the whole box fits
    the view (:func:`scene_box_fits`)."""
    lows, highs = [], []
    for key in ("x", "y", "z"):
        values = [float(v) for t in traces for v in t.get(key, []) if v is not None]
        lows.append(min(values, default=-1.0))
        highs.append(max(values, default=1.0))
    largest = max(max(h - lo for lo, h in zip(lows, highs, strict=True)), 1.0)
    pad = SCENE_MARGIN * largest
    ranges = []
    for lo, h in zip(lows, highs, strict=True):
        half = max((h - lo) / 2 + pad, SCENE_MIN_ASPECT * (largest / 2 + pad))
        centre = (lo + h) / 2
        ranges.append([centre - half, centre + half])
    longest = max(h - lo for lo, h in ranges)
    ratios = [(h - lo) / longest for lo, h in ranges]
    eye = _fitted_eye(ratios)
    # tick labels by the length an axis shows: its share of the box, foreshortened by the
    # angle it makes with the line of sight (an axis seen end-on would crowd its labels)
    sight = eye / np.linalg.norm(eye)
    shown = [ratio * math.sqrt(max(0.0, 1.0 - sight[k] ** 2)) for k, ratio in enumerate(ratios)]
    axes = {
        f"{key}axis": {
            "range": span,
            "tickmode": "array",
            "tickvals": _scene_ticks(span, max(2, round(SCENE_TICKS * length))),
        }
        for key, span, length in zip(("x", "y", "z"), ranges, shown, strict=True)
    }
    return {
        **axes,
        "aspectmode": "manual",
        "aspectratio": dict(zip(("x", "y", "z"), ratios, strict=True)),
        "camera": {"eye": dict(zip(("x", "y", "z"), (float(v) for v in eye), strict=True))},
    }


def crank_3d(
    model: EngineModel | Analysis | BalanceStudy, balance_study: BalanceStudy | None = None
) -> go.Figure:
    """3-D view of the crankshaft at crank angle 0 (lengths in mm).

    Crank axis y drawn horizontally. Main journals on the axis, each throw's crankpin at
    the crank radius in its direction, two webs per throw (a quarter pitch from the throw
    mid-plane, as the balancing solver assumes), the cylinder axes as thin lines, and with
    ``balance_study`` the counterweights (at their CG radius and direction; marker size
    grows with the square root of the mass) and the balance-shaft masses. Shafts are drawn
    beside the crank at a schematic distance (their position across the crank does not
    enter the balance).
    """
    from ...physics.balancing import default_web_offset
    from ...physics.model import EngineModel

    go = plotly_go()
    if isinstance(model, EngineModel):
        m = model
    else:  # an analysis or a balancing study: its engine (and the study's balancing)
        from ...studies.engine import BalanceStudy

        if balance_study is None and isinstance(model, BalanceStudy):
            balance_study = model
        m = model.model
    mm = 1e3
    r = m.crank_radius
    web = default_web_offset(m)
    pos = m.throw_position
    span = float(np.ptp(pos)) if m.throws > 1 else 0.0
    end = span / 2 + 2 * web
    middle = -m.moment_reference  # the crank's mid-point, from the moment reference point
    # one trace per legend entry, kind (lines or markers) and style: segments joined with
    # None breaks, hover text and marker size per point (a few traces build and draw much
    # faster than one per segment: plotly validates every trace)
    traces: dict[tuple[str, str, str], dict[str, Any]] = {}

    def trace(mode: str, name: str, show: bool, **style: Any) -> dict[str, Any]:
        key = (mode, name, repr(style))
        if key not in traces:
            traces[key] = {
                "type": "scatter3d",
                "mode": mode,
                "name": name,
                "legendgroup": style.pop("group", name),
                "showlegend": show,
                "x": [],
                "y": [],
                "z": [],
                "text": [],
                **style,
            }
        t = traces[key]
        t["showlegend"] = t["showlegend"] or show
        return t

    def line(
        ys: tuple[float, float],
        xs: tuple[float, float],
        zs: tuple[float, float],
        name: str,
        color: str,
        width: float,
        group: str,
        show: bool,
        dash: str = "solid",
        text: str | None = None,
    ) -> None:
        t = trace(
            "lines",
            name,
            show,
            group=group,
            line={"color": color, "width": width, "dash": dash},
            hoverinfo="text" if text else "name",
        )
        for out, values in ((t["x"], ys), (t["y"], xs), (t["z"], zs)):
            if out:
                out.append(None)
            out.extend(v * mm for v in values)
        t["text"].extend(([None] if len(t["text"]) else []) + [text, text])

    def marker(
        y: float, x: float, z: float, name: str, color: str, size: float, show: bool, text: str
    ) -> None:
        t = trace("markers", name, show, marker={"color": color, "opacity": 0.9}, hoverinfo="text")
        t["marker"].setdefault("size", []).append(size)
        for out, v in ((t["x"], y), (t["y"], x), (t["z"], z)):
            out.append(v * mm)
        t["text"].append(text)

    # main journals: the crank axis between and beyond the throws
    line(
        (middle - end, middle + end),
        (0, 0),
        (0, 0),
        "crank axis / main journals",
        COLORS["crank"],
        8,
        "axis",
        True,
    )
    for t in range(m.throws):
        phi = m.throw_angle[t]
        px, pz = r * math.sin(phi), r * math.cos(phi)
        y0, y1 = pos[t] - web, pos[t] + web
        text = (
            f"throw {t + 1}: angle {math.degrees(phi) % 360:.1f} deg, y {pos[t] * mm:.1f} mm,"
            f" rotating mass {m.throw_rotating_mass[t]:.3f} kg"
        )
        line((y0, y1), (px, px), (pz, pz), "crankpins", "#1f3b73", 12, "pin", True, text=text)
        for yw in (y0, y1):
            line((yw, yw), (0, px), (0, pz), "webs", "#6b6b6b", 6, "web", True)
    # cylinder axes from the crankpin's top-dead-centre circle outward
    for c in range(m.cylinders):
        beta = m.cylinder_bank[c]
        y = m.cylinder_position[c]
        r0, r1 = r + m.rod_length, r + m.rod_length + 2 * r
        line(
            (y, y),
            (r0 * math.sin(beta), r1 * math.sin(beta)),
            (r0 * math.cos(beta), r1 * math.cos(beta)),
            "cylinder axes (stroke)",
            "#c7c7c7",
            10,
            "cyl",
            True,
            text=f"cylinder {c + 1}: bank {math.degrees(beta):.1f} deg",
        )
    if balance_study is not None:
        res = balance_study.result
        masses = [
            cw.mass for cw in (res.counterweights, res.extra_counterweights) if cw is not None
        ]
        for group in (res.primary, res.secondary):
            if group is not None:
                masses += [np.array([x.mass for s in group.shafts for x in s.masses])]
        biggest = max((float(np.max(a, initial=0.0)) for a in masses), default=0.0)

        def size(mass: float) -> float:
            return 4.0 + 14.0 * math.sqrt(mass / biggest) if biggest > 0 else 4.0

        for label, cw, color in (
            ("counterweights", res.counterweights, COLORS["counterweight"]),
            ("extra counterweights (Eq. 17)", res.extra_counterweights, "#98df8a"),
        ):
            if cw is None or cw.count == 0:
                continue
            for j in range(cw.count):
                d, rho = float(cw.direction[j]), cw.cg_radius
                cx, cz, y = rho * math.sin(d), rho * math.cos(d), float(cw.position[j])
                line((y, y), (0, cx), (0, cz), label, color, 5, label, False)
                marker(
                    y,
                    cx,
                    cz,
                    label,
                    color,
                    size(float(cw.mass[j])),
                    True,
                    f"{label}: web {int(cw.web[j])}, {cw.mass[j]:.4g} kg at "
                    f"{rho * mm:.1f} mm, {math.degrees(d) % 360:.1f} deg",
                )
        # balance shafts beside the crank (schematic): primary left/right of the crank at
        # the height of the axis, secondary below; co-rotating on one side
        gap = 2.5 * r + 0.02
        for group, zc, color in (
            (res.primary, 0.0, COLORS["shaft1"]),
            (res.secondary, -(r + 0.5 * m.rod_length), COLORS["shaft2"]),
        ):
            if group is None:
                continue
            half = group.length / 2
            for s in group.shafts:
                xc = -gap if s.sense > 0 else gap
                sense = "co-rotating" if s.sense > 0 else "counter-rotating"
                label = f"order-{group.order} shaft, {sense}"
                line(
                    (-half, half),
                    (xc, xc),
                    (zc, zc),
                    label,
                    color,
                    6,
                    label,
                    True,
                    dash="solid" if s.sense > 0 else "dash",
                )
                for x in s.masses:
                    rho = s.cg_radius
                    mx, mz = xc + rho * math.sin(x.phase), zc + rho * math.cos(x.phase)
                    arm = (x.position, x.position), (xc, mx), (zc, mz)
                    line(*arm, label, color, 4, label, False)
                    marker(
                        x.position,
                        mx,
                        mz,
                        label,
                        color,
                        size(x.mass),
                        False,
                        f"{label}: {x.mass:.4g} kg at {rho * mm:.1f} mm, y "
                        f"{x.position * mm:.1f} mm, phase {math.degrees(x.phase):.1f} deg",
                    )
    for drawn in traces.values():
        if not any(drawn["text"]):
            del drawn["text"]
    scene = crank_3d_scene(list(traces.values()))
    scene["xaxis"]["title"] = {"text": "y, crank axis [mm]"}
    scene["yaxis"]["title"] = {"text": "x [mm]"}
    scene["zaxis"]["title"] = {"text": "z [mm]"}
    layout = {
        "template": TEMPLATE,
        "title": {"text": figure_title("Crankshaft at crank angle 0", m.name)},
        "scene": scene,
        "legend": {"orientation": "h", "y": -0.05},
        "margin": {"l": 0, "r": 0, "t": 50, "b": 0},
    }
    # one validated construction (update_layout afterwards would validate the template twice)
    return go.Figure(data=list(traces.values()), layout=layout)
