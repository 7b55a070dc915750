"""The figures of the mount study (:mod:`crankbalance.physics.mounts`): the Campbell diagram
of the six rigid-body modes and the force every mount transmits over speed.

Public functions
----------------
- ``mounts_figure(result) -> Figure``               (studies.mounts.MountsResult)
- ``mounts_layout_figure(result) -> Figure``        (studies.mounts.MountsResult)
- ``mode_shapes_figure(result) -> Figure``          (studies.mounts.MountsResult)
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from ...physics.mounts import point_map, rotation
from .common import COLORS, ORDER_COLORS, TEMPLATE, make_subplots, plotly_go

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...studies.mounts import MountsResult

_DASHES = ("solid", "dash", "dot", "dashdot", "longdash", "longdashdot")
#: the largest displacement of a drawn mode shape, as a share of the layout's size (the
#: mounts, the centre of gravity and the reference point): shapes are drawn to scale, not
#: to size (a mode has no amplitude of its own)
MODE_DRAWN = 0.2
#: frames of one cycle of a mode's motion in the animated mode shapes (the web app)
MODE_FRAMES = 24
#: cycles the animation's Play button runs, and each frame's duration [ms]
MODE_CYCLES = 4
MODE_FRAME_MS = 60
#: length of a mount's compression-axis stroke in the layout, as a share of its size
AXIS_DRAWN = 0.12
_MM = 1000.0
#: one colour per rigid-body mode (the Campbell diagram and the mode shapes), apart from
#: the orders' colours (:data:`~.common.ORDER_COLORS`) of the same figure
MODE_COLORS = ("#1b9e77", "#7570b3", "#e7298a", "#e6ab02", "#a6761d", "#666666")
#: the Campbell diagram's range of frequencies: up to this times the highest mode
CAMPBELL_TOP = 1.6
#: the height of each row of :func:`mounts_figure` and the gap between rows, which holds
#: the row's title [px]
ROW_PX = 300
ROW_GAP_PX = 60
#: the top and bottom margins of :func:`mounts_figure` (the title; the speed axis) [px]
MARGIN_TOP = 110
MARGIN_BOTTOM = 70
#: the side margins of the 3-D figures [px]: the mode menu and the phase slider's end
#: labels inside the figure
SIDE_PX = 20
#: the leader of a name in the layout figure: its run up and aside [px]
LABEL_PX = 28


def mounts_figure(result: MountsResult) -> go.Figure:
    """Top, the Campbell diagram: the six natural frequencies [Hz] of the powertrain on its
    mounts (one colour and legend entry per mode, :data:`MODE_COLORS`) and the engine-order
    lines f = n · rpm / 60 over the speed range (each in its order's colour of the forces
    below, labelled "order n" at its end, cut where it leaves the diagram's range: up to
    :data:`CAMPBELL_TOP` times the highest mode; an order above that range over the whole
    speed range is named in the diagram's title instead), a marker at every crossing;
    middle, the largest force of each mount over a cycle [N] against speed, one line per
    mount (dash) and order (colour); with a comparison of balancing choices or an
    optimisation, a third row: the largest force of any mount and order against speed, for
    the mounts as given, each choice and the optimised mounts. Each row is :data:`ROW_PX`
    high, the rows :data:`ROW_GAP_PX` apart (their titles clear of the row above)."""
    go = plotly_go()
    response, modes = result.response, result.modes
    rpm = np.asarray(response.speeds) * 30 / math.pi
    extra = bool(result.comparison) or result.optimum_response is not None
    top = float(max(modes.frequencies.max(), 1.0)) * CAMPBELL_TOP
    lines = {n: order_line(float(n), float(rpm[0]), float(rpm[-1]), top) for n in response.orders}
    above = [f"{n:g}" for n, line in lines.items() if line is None]
    campbell = "Campbell diagram"  # short enough for a phone; the modes are in the legend
    if above:
        orders = f"order{'s' if len(above) > 1 else ''} {', '.join(above)}"
        campbell += f"<br><sub>{orders} above every mode</sub>"
    rows = 3 if extra else 2
    plot = rows * ROW_PX + (rows - 1) * ROW_GAP_PX
    fig = make_subplots(
        rows=rows,
        cols=1,
        shared_xaxes=True,
        vertical_spacing=ROW_GAP_PX / plot,
        subplot_titles=(
            campbell,
            "Force transmitted by each mount",
            *(["Largest force of any mount and order"] if extra else []),
        ),
    )
    for k, n in enumerate(response.orders):
        line = lines[n]
        if line is None:
            continue
        (x0, y0), (x1, y1) = line
        fig.add_trace(
            go.Scatter(
                x=[x0, x1],
                y=[y0, y1],
                mode="lines+text",
                name=f"order {n:g}",
                showlegend=False,
                text=["", f"order {n:g}"],
                textposition=_order_label(x1, y1, float(rpm[0]), float(rpm[-1]), top),
                textfont={"color": ORDER_COLORS[k % len(ORDER_COLORS)]},
                line={"color": ORDER_COLORS[k % len(ORDER_COLORS)], "width": 1.5},
                hovertemplate=f"order {n:g}<extra></extra>",
            ),
            row=1,
            col=1,
        )
    for r, f in enumerate(modes.frequencies):
        fig.add_trace(
            go.Scatter(
                x=[rpm[0], rpm[-1]],
                y=[f, f],
                mode="lines",
                name=f"mode {r + 1}: {f:.3g} Hz, {_most(modes.energy[r])}",
                line={"color": MODE_COLORS[r % len(MODE_COLORS)], "width": 2},
                hovertemplate=f"mode {r + 1}: {f:.2f} Hz<extra></extra>",
            ),
            row=1,
            col=1,
        )
    if result.crossings:
        fig.add_trace(
            go.Scatter(
                x=[c.speed * 30 / math.pi for c in result.crossings],
                y=[modes.frequencies[c.mode] for c in result.crossings],
                mode="markers",
                name="crossings",
                showlegend=False,
                marker={"color": COLORS["total"], "size": 8},
                text=[f"mode {c.mode + 1}, order {c.order:g}" for c in result.crossings],
                hovertemplate="%{text}: %{x:.0f} rpm<extra></extra>",
            ),
            row=1,
            col=1,
        )
    fig.update_yaxes(title_text="frequency [Hz]", range=[0, top], row=1, col=1)
    for k, n in enumerate(response.orders):
        color = ORDER_COLORS[k % len(ORDER_COLORS)]
        for i, mount in enumerate(result.powertrain.mounts):
            fig.add_trace(
                go.Scatter(
                    x=rpm,
                    y=response.mount_peak[:, k, i],
                    mode="lines",
                    name=f"{mount.name}, order {n:g}",
                    line={"color": color, "dash": _DASHES[i % len(_DASHES)]},
                ),
                row=2,
                col=1,
            )
    fig.update_yaxes(title_text="force [N]", row=2, col=1)
    if extra:
        _largest(fig, result, rpm)
    fig.update_xaxes(range=[rpm[0], rpm[-1]])
    fig.update_xaxes(title_text="speed [rpm]", row=rows, col=1)
    fig.update_layout(
        template=TEMPLATE,
        title=f"{result.name}: the powertrain on its mounts",
        height=plot + MARGIN_TOP + MARGIN_BOTTOM,
        margin={"l": 70, "r": 30, "t": MARGIN_TOP, "b": MARGIN_BOTTOM},
    )
    return fig


def order_line(
    order: float, low: float, high: float, top: float
) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The engine-order line f = n · rpm / 60 [Hz] of the Campbell diagram from ``low`` to
    ``high`` [rpm], cut where it reaches the diagram's ``top`` [Hz]: its two ends (rpm, Hz),
    or None when the line lies above ``top`` over the whole range."""
    start = order * low / 60
    if start >= top:
        return None
    end = min(high, 60 * top / order) if order > 0 else high
    return (low, start), (end, order * end / 60)


def _order_label(x: float, y: float, low: float, high: float, top: float) -> str:
    """Where an order line's label goes from its end (``x`` rpm, ``y`` Hz), inside the
    diagram and off the line: below and right of an end at the top (below and left near
    the highest speed), above and left of an end at the highest speed."""
    if y < top * (1 - 1e-9):
        return "top left"
    return "bottom right" if x < low + 0.8 * (high - low) else "bottom left"


def _most(energy: np.ndarray) -> str:
    """The coordinate that holds the most of a mode's kinetic energy."""
    return ("x", "y", "z", "roll", "pitch", "yaw")[int(np.argmax(energy))]


def _layout_points(result: MountsResult) -> np.ndarray:
    """The mounts, the centre of gravity and the reference point (N + 2, 3) [m]."""
    pt = result.powertrain
    return np.array(
        [*(m.position for m in pt.mounts), pt.cg, result.model.moment_point], dtype=float
    )


def _size(points: np.ndarray) -> float:
    """The layout's size: its largest extent along an axis [m] (at least 1 mm)."""
    return float(max(np.ptp(points, axis=0).max(), 1e-3))


def _line(go: Any, a: np.ndarray, b: np.ndarray, name: str, **style: Any) -> Any:
    """A 3-D segment from ``a`` to ``b`` [m], drawn in mm."""
    return go.Scatter3d(
        x=[a[0] * _MM, b[0] * _MM],
        y=[a[1] * _MM, b[1] * _MM],
        z=[a[2] * _MM, b[2] * _MM],
        mode="lines",
        name=name,
        **style,
    )


def _scene() -> dict[str, Any]:
    return {
        "xaxis_title": "x [mm]",
        "yaxis_title": "y, crank axis [mm]",
        "zaxis_title": "z [mm]",
        "aspectmode": "data",
    }


def mounts_layout_figure(result: MountsResult) -> go.Figure:
    """The mount layout drawn with the powertrain (3-D, engine axes, mm): each mount (its
    name, its compression axis as a short stroke), the centre of gravity, the crank axis
    through the reference point, the torque-roll axis and the roll mode's axis of rotation
    through the centre of gravity, and the lines from the centre of gravity to the mounts."""
    go = plotly_go()
    pt, modes = result.powertrain, result.modes
    points = _layout_points(result)
    size = _size(points)
    cg, ref = np.asarray(pt.cg, dtype=float), np.asarray(result.model.moment_point, dtype=float)
    fig = go.Figure()
    ys = points[:, 1]
    reach = 0.15 * size
    fig.add_trace(
        _line(
            go,
            np.array([ref[0], ys.min() - reach, ref[2]]),
            np.array([ref[0], ys.max() + reach, ref[2]]),
            "crank axis",
            line={"color": COLORS["crank"], "width": 6},
        )
    )
    for m in pt.mounts:
        fig.add_trace(
            _line(
                go,
                np.asarray(m.position, dtype=float),
                cg,
                f"{m.name} to G",
                showlegend=False,
                line={"color": COLORS["before"], "width": 2, "dash": "dot"},
                hoverinfo="skip",
            )
        )
    half = 0.5 * AXIS_DRAWN * size
    for k, m in enumerate(pt.mounts):
        axis = rotation(m.orientation)[:, 2]
        p = np.asarray(m.position, dtype=float)
        fig.add_trace(
            _line(
                go,
                p - half * axis,
                p + half * axis,
                "compression axes",
                legendgroup="compression",
                showlegend=k == 0,
                line={"color": COLORS["forward"], "width": 5},
                hoverinfo="skip",
            )
        )
    fig.add_trace(
        go.Scatter3d(
            x=[m.position[0] * _MM for m in pt.mounts],
            y=[m.position[1] * _MM for m in pt.mounts],
            z=[m.position[2] * _MM for m in pt.mounts],
            mode="markers",
            name="mounts",
            text=[m.name for m in pt.mounts],
            marker={"size": 6, "color": COLORS["forward"]},
            hovertemplate="%{text}: %{x:.0f}, %{y:.0f}, %{z:.0f} mm<extra></extra>",
        )
    )
    fig.add_trace(
        go.Scatter3d(
            x=[cg[0] * _MM],
            y=[cg[1] * _MM],
            z=[cg[2] * _MM],
            mode="markers",
            name=f"centre of gravity ({pt.mass:.4g} kg)",
            text=["G"],
            marker={"size": 7, "color": COLORS["total"], "symbol": "diamond"},
            hovertemplate="G: %{x:.0f}, %{y:.0f}, %{z:.0f} mm<extra></extra>",
        )
    )
    roll = modes.shapes[3:, modes.roll_mode]
    roll = roll / max(float(np.linalg.norm(roll)), 1e-300)
    for axis, name, color in (
        (modes.torque_roll_axis, "torque-roll axis", COLORS["after"]),
        (roll, f"roll mode {modes.roll_mode + 1}: its axis of rotation", COLORS["counterweight"]),
    ):
        fig.add_trace(
            _line(
                go,
                cg - 0.6 * size * axis,
                cg + 0.6 * size * axis,
                name,
                line={"color": color, "width": 4, "dash": "dash"},
            )
        )
    fig.update_layout(
        template=TEMPLATE,
        title=f"{result.name}: mounts, centre of gravity, crank axis",
        scene={**_scene(), "annotations": _labels(pt)},
        height=560,
        margin={"l": SIDE_PX, "r": SIDE_PX, "t": 60, "b": 0},
    )
    return fig


def _labels(pt: Any) -> list[dict[str, Any]]:
    """The names of the mounts and G as the scene's annotations: drawn over the scene (a
    text of the scene itself is hidden behind any line in front of it), each on a short
    leader above its point, alternately left and right so that neighbours' names part."""
    points = [(m.name, m.position) for m in pt.mounts] + [("G", pt.cg)]
    return [
        {
            "x": p[0] * _MM,
            "y": p[1] * _MM,
            "z": p[2] * _MM,
            "text": name,
            "showarrow": True,
            "arrowhead": 0,
            "arrowwidth": 1,
            "arrowcolor": COLORS["before"],
            "ax": LABEL_PX if k % 2 else -LABEL_PX,
            "ay": -LABEL_PX,
            "bgcolor": "rgba(255, 255, 255, 0.85)",
            "font": {"size": 12},
        }
        for k, (name, p) in enumerate(points)
    ]


def mode_shapes_figure(result: MountsResult, animate: bool = False) -> go.Figure:
    """The six rigid-body modes drawn (3-D, engine axes, mm): the layout at rest (grey) and
    displaced by each mode (the mounts and the centre of gravity joined as in
    :func:`mounts_layout_figure`, a stroke from rest to the displaced point at each), one mode at a
    time (a menu picks it; the roll mode first). Displacements are to scale, not to size:
    the largest of each mode is :data:`MODE_DRAWN` of the layout's size.

    With ``animate`` (the web app) the chosen mode also moves: :data:`MODE_FRAMES` frames
    of one cycle of the motion (the displacement times cos 2πk/N, frame 0 the static
    drawing), a slider of the phase, and the scene's axes fixed to the largest excursion of
    every mode (a moving shape does not rescale it); the page's *Play* and *Pause* run the
    frames (:func:`mode_play_script`). Without it (reports, ``--plot``) the drawing is
    static.
    """
    go = plotly_go()
    pt, modes = result.powertrain, result.modes
    cg = np.asarray(pt.cg, dtype=float)
    body = np.array([*(m.position for m in pt.mounts), cg], dtype=float)  # mounts, then G
    size = _size(_layout_points(result))
    names = [m.name for m in pt.mounts] + ["G"]
    # each mode's displacement of the mounts and G as drawn [m] (the largest MODE_DRAWN of
    # the layout's size)
    drawn = []
    for r in range(6):
        moved = np.array([point_map(cg, p) @ modes.shapes[:, r] for p in body])
        largest = float(np.linalg.norm(moved, axis=1).max())
        drawn.append(moved * (MODE_DRAWN * size / largest if largest > 0 else 0.0))

    fig = go.Figure()
    x0, y0, z0 = _mode_frame(body)
    fig.add_trace(
        go.Scatter3d(
            x=x0, y=y0, z=z0, mode="lines", name="at rest", line={"color": "#bbbbbb", "width": 4}
        )
    )
    traces_per_mode = 2
    first = modes.roll_mode
    for r in range(6):
        frame, strokes = _mode_lines(body, body + drawn[r])
        label = f"mode {r + 1}: {modes.frequencies[r]:.3g} Hz"
        fig.add_trace(
            go.Scatter3d(
                **frame,
                mode="lines",
                name=label,
                visible=r == first,
                showlegend=r == first,
                line={"color": MODE_COLORS[r % len(MODE_COLORS)], "width": 6},
                hoverinfo="skip",
            )
        )
        fig.add_trace(
            go.Scatter3d(
                **strokes,
                mode="lines+markers",
                name=f"mode {r + 1}: motion of the mounts and G",
                visible=r == first,
                showlegend=r == first,
                line={"color": COLORS["total"], "width": 3},
                marker={"size": [0, 5, 0] * len(body), "color": COLORS["total"]},
                text=[n for n in names for _ in range(3)],
                hovertemplate="%{text}<extra></extra>",
            )
        )
    buttons = []
    for r in range(6):
        visible = [True] + [k // traces_per_mode == r for k in range(traces_per_mode * 6)]
        energy = modes.energy[r]
        most = _most(energy)
        buttons.append(
            {
                "label": f"mode {r + 1}: {modes.frequencies[r]:.3g} Hz, {most}",
                "method": "update",
                # the legend names the mode shown only (a phone makes room for each entry)
                "args": [
                    {"visible": visible, "showlegend": visible},
                    {"title.text": f"{result.name}: mode {r + 1} ({most} {energy.max():.0f} %)"},
                ],
            }
        )
    energy = modes.energy[first]
    most = _most(energy)
    fig.update_layout(
        template=TEMPLATE,
        title=f"{result.name}: mode {first + 1} ({most} {energy.max():.0f} %)",
        scene=_scene(),
        height=560,
        margin={"l": SIDE_PX, "r": SIDE_PX, "t": 90, "b": 0},
        updatemenus=[
            {
                "buttons": buttons,
                "active": first,
                "x": 1,
                "xanchor": "right",
                "y": 1,
                "yanchor": "bottom",
            }
        ],
    )
    if animate:
        _animate_modes(fig, body, drawn)
    return fig


def mode_play_script(element: int, play: bool) -> str:
    """The JavaScript that plays (:data:`MODE_CYCLES` cycles of :data:`MODE_FRAME_MS` ms
    frames) or pauses the animated mode shapes drawn by NiceGUI's plotly element of id
    ``element``. Plotly rejects the promise of an animation that another one interrupts
    (*Pause*, the slider, a new figure); the script catches it, so that no unhandled
    rejection reaches the page."""
    if play:
        frames = (
            f"[...Array({MODE_CYCLES})].flatMap(() => el._transitionData._frames.map((f) => "
            "f.name))"
        )
        options = (
            f"{{mode: 'immediate', frame: {{duration: {MODE_FRAME_MS}, redraw: true}}, "
            "transition: {duration: 0}}"
        )
    else:
        frames, options = "[null]", "{mode: 'immediate', frame: {duration: 0}}"
    return (
        f"const plot = getElement({int(element)}); const el = plot && plot.$el; "
        "if (plot && plot.Plotly && el._transitionData && el._transitionData._frames.length) "
        f"plot.Plotly.animate(el, {frames}, {options}).catch(() => {{}});"
    )


def _mode_frame(p: np.ndarray) -> tuple[list[float | None], ...]:
    """Lines from G (the last point) to each mount, in mm (None breaks the line)."""
    xs: list[float | None] = []
    ys: list[float | None] = []
    zs: list[float | None] = []
    for i in range(len(p) - 1):
        for q in (p[-1], p[i]):
            xs.append(q[0] * _MM)
            ys.append(q[1] * _MM)
            zs.append(q[2] * _MM)
        xs.append(None)
        ys.append(None)
        zs.append(None)
    return xs, ys, zs


def _mode_lines(
    body: np.ndarray, shown: np.ndarray
) -> tuple[dict[str, list[float | None]], dict[str, list[float | None]]]:
    """The coordinates [mm] of a mode's two traces: the layout displaced to ``shown`` and
    the strokes from rest (``body``) to it."""
    xs, ys, zs = _mode_frame(shown)
    ax: list[float | None] = []
    ay: list[float | None] = []
    az: list[float | None] = []
    for p, q in zip(body, shown, strict=True):
        ax += [p[0] * _MM, q[0] * _MM, None]
        ay += [p[1] * _MM, q[1] * _MM, None]
        az += [p[2] * _MM, q[2] * _MM, None]
    return {"x": xs, "y": ys, "z": zs}, {"x": ax, "y": ay, "z": az}


def _animate_modes(fig: go.Figure, body: np.ndarray, drawn: list[np.ndarray]) -> None:
    """Frames of one cycle of every mode's motion (:func:`mode_shapes_figure`), the phase
    slider and the scene's fixed axes."""
    go = plotly_go()
    frames, steps = [], []
    for k in range(MODE_FRAMES):
        phase = 2 * math.pi * k / MODE_FRAMES
        data = []
        for moved in drawn:
            frame, strokes = _mode_lines(body, body + math.cos(phase) * moved)
            data += [go.Scatter3d(**frame), go.Scatter3d(**strokes)]
        name = f"{math.degrees(phase):.0f}"
        frames.append(go.Frame(data=data, traces=list(range(1, 1 + len(data))), name=name))
        steps.append(
            {
                "label": f"{name}°",
                "method": "animate",
                "args": [[name], {"mode": "immediate", "frame": {"duration": 0, "redraw": True}}],
            }
        )
    fig.frames = frames
    fig.update_layout(
        sliders=[
            {
                "steps": steps,
                "currentvalue": {"prefix": "phase of the motion "},
                # the end ticks' labels inside the figure
                "x": 0.02,
                "len": 0.94,
                "y": 0,
                "yanchor": "top",
                "pad": {"t": 10},
            }
        ],
        margin={"l": SIDE_PX, "r": SIDE_PX, "t": 90, "b": 90},
        height=640,
    )
    # the scene's axes fixed to every mode's largest excursion (mm), in proportion
    points = np.concatenate([body, *(body + m for m in drawn), *(body - m for m in drawn)])
    low, high = points.min(axis=0) * _MM, points.max(axis=0) * _MM
    pad = 0.05 * float(max((high - low).max(), 1.0))
    low, high = low - pad, high + pad
    span = high - low
    fig.update_layout(
        scene={
            **{f"{a}axis": {"range": [low[i], high[i]]} for i, a in enumerate("xyz")},
            "aspectmode": "manual",
            "aspectratio": dict(zip("xyz", span / span.max(), strict=True)),
        }
    )


def _largest(fig: go.Figure, result: MountsResult, rpm: np.ndarray) -> None:
    """Third row: the largest force of any mount and order over speed, for the mounts as
    given, each balancing choice compared and the optimised mounts."""
    go = plotly_go()
    lines = [("mounts as given", result.response.mount_peak, "solid")]
    lines += [(label, r.response.mount_peak, "solid") for label, r in result.comparison]
    if result.optimum_response is not None:
        lines.append(("optimised mounts", result.optimum_response.mount_peak, "dash"))
    for k, (label, peak, dash) in enumerate(lines):
        fig.add_trace(
            go.Scatter(
                x=rpm,
                y=peak.max(axis=(1, 2)),
                mode="lines",
                name=label,
                line={"color": ORDER_COLORS[k % len(ORDER_COLORS)], "dash": dash},
            ),
            row=3,
            col=1,
        )
    fig.update_yaxes(title_text="force [N]", row=3, col=1)
