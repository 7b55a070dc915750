"""The Mounts tab's figures read on their own (issue 28, item 4; the screenshot review's
findings 13 and 23): a legend entry per mode, every order line labelled and inside the
Campbell diagram, no title over another or over a plot, the 3-D names never hidden, the
mode menu and the phase slider inside the figure, and the 3-D figures' phone layout."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest

from crankbalance.output.figures.mounts import (
    MODE_COLORS,
    mode_shapes_figure,
    mounts_figure,
    mounts_layout_figure,
    order_line,
)

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "examples" / "mounts_inline4_car.toml"
BIKE = ROOT / "examples" / "mounts_vtwin_motorcycle.toml"
#: plotly's defaults where a figure sets none: height, top and bottom margins [px]
HEIGHT, TOP, BOTTOM = 450, 100, 80
#: the height of a line of text as a share of its font size, and a title's free space [px]
LINE, PAD = 1.3, 4


@pytest.fixture(scope="module")
def result() -> Any:
    from crankbalance.studies.registry import run

    return run("mounts", str(CAR), {"speed_samples": "60", "orders": "4"}, naming=str)


def _campbell(fig: Any) -> list[Any]:
    return [t for t in fig.data if t.xaxis in (None, "x") and t.yaxis in (None, "y")]


def test_every_mode_has_its_colour_and_legend_entry(result: Any) -> None:
    fig = mounts_figure(result)
    modes = [t for t in _campbell(fig) if (t.name or "").startswith("mode ")]
    assert [t.name.split(":")[0] for t in modes] == [f"mode {r}" for r in range(1, 7)]
    assert all(t.showlegend is not False for t in modes)
    assert [t.line.color for t in modes] == list(MODE_COLORS)
    freqs = result.modes.frequencies
    for t, f in zip(modes, freqs, strict=True):
        assert f"{f:.3g} Hz" in t.name


def test_every_order_line_is_labelled_in_its_orders_colour(result: Any) -> None:
    fig = mounts_figure(result)
    orders = [t for t in _campbell(fig) if (t.name or "").startswith("order ")]
    assert orders, "an order crosses the diagram"
    forces = {t.name: t.line.color for t in fig.data if t.xaxis == "x2"}
    mount = result.powertrain.mounts[0].name
    for t in orders:
        assert t.text[-1] == t.name  # "order 1" at the line's end, not "order 1.0"
        assert not t.name.endswith(".0")
        assert t.line.color == forces[f"{mount}, {t.name}"]


def test_order_lines_stay_inside_the_campbell_diagram(result: Any) -> None:
    fig = mounts_figure(result)
    low, top = fig.layout.yaxis.range
    rpm = [s * 30 / math.pi for s in (result.response.speeds[0], result.response.speeds[-1])]
    drawn = set()
    for t in _campbell(fig):
        assert all(low <= y <= top * (1 + 1e-12) for y in t.y), t.name
        assert all(rpm[0] - 1e-9 <= x <= rpm[1] + 1e-9 for x in t.x), t.name
        drawn.add(t.name)
    above = [n for n in result.response.orders if f"order {n:g}" not in drawn]
    title = fig.layout.annotations[0].text
    for n in above:  # an order above every mode is named, not drawn off the diagram
        assert order_line(float(n), rpm[0], rpm[1], top) is None
        assert f"{n:g}" in title


def test_order_line_is_cut_at_the_top() -> None:
    assert order_line(2.0, 600.0, 6000.0, 30.0) == ((600.0, 20.0), (900.0, 30.0))
    assert order_line(1.0, 600.0, 1200.0, 30.0) == ((600.0, 10.0), (1200.0, 20.0))
    assert order_line(4.0, 600.0, 6000.0, 30.0) is None


def _boxes(fig: Any) -> tuple[list[tuple[str, float, float]], list[tuple[str, float, float]]]:
    """The titles' boxes and the plots' boxes, each (name, bottom, top) in px from the
    figure's bottom: a subplot title sits on the top of its plot (plotly's ``yanchor``
    bottom), the figure's title is centred on its first line's baseline halfway down the
    top margin (plotly's ``y`` auto)."""
    layout = fig.layout
    height = layout.height or HEIGHT
    top = TOP if layout.margin.t is None else layout.margin.t
    bottom = BOTTOM if layout.margin.b is None else layout.margin.b
    plot = height - top - bottom
    titles = []
    for note in layout.annotations:
        lines = note.text.count("<br>") + 1
        base = bottom + note.y * plot
        titles.append((note.text, base, base + lines * LINE * note.font.size + PAD))
    size = 17  # plotly's title font
    lines = layout.title.text.count("<br>") + 1
    baseline = height - top / 2
    titles.append(("title", baseline - (lines - 1) * LINE * size - 0.3 * size, baseline + size))
    plots = [
        (key, bottom + axis.domain[0] * plot, bottom + axis.domain[1] * plot)
        for key in layout
        if key.startswith("yaxis")
        for axis in [layout[key]]
    ]
    return titles, plots


@pytest.mark.parametrize("compared", [False, True])
def test_no_title_overlaps_another_or_a_plot(result: Any, compared: bool) -> None:
    """Two rows, and three with a comparison of balancing choices."""
    if compared:
        from crankbalance.studies.registry import run

        settings = {"speed_samples": "40", "orders": "2", "compare_balance_factors": "0,0.5"}
        result = run("mounts", str(BIKE), settings, naming=str)
    fig = mounts_figure(result)
    titles, plots = _boxes(fig)
    assert len(plots) == (3 if compared else 2)
    height = fig.layout.height or HEIGHT
    for k, (name, low, high) in enumerate(titles):
        assert 0 <= low < high <= height, name
        for other, b, t in titles[k + 1 :]:
            assert high <= b or t <= low, (name, other)
        for axis, b, t in plots:
            assert high <= b or t <= low + 1e-9, (name, axis)


def test_the_layouts_names_are_drawn_over_the_scene(result: Any) -> None:
    """A name as the scene's text hid behind a line in front of it ("torque ro")."""
    fig = mounts_layout_figure(result)
    assert not any("text" in (t.mode or "") for t in fig.data)
    names = [a.text for a in fig.layout.scene.annotations]
    assert names == [m.name for m in result.powertrain.mounts] + ["G"]
    assert fig.layout.margin.r > 0 and fig.layout.margin.l > 0


def test_mode_shapes_legend_names_the_mode_shown_and_stays_inside(result: Any) -> None:
    fig = mode_shapes_figure(result, animate=True)
    shown = [t.name for t in fig.data if t.showlegend is not False]
    first = result.modes.roll_mode + 1
    assert shown == ["at rest", *(n for n in shown[1:] if n.startswith(f"mode {first}:"))]
    assert len(shown) == 3
    for button in fig.layout.updatemenus[0].buttons:
        visible = button.args[0]["visible"]
        assert button.args[0]["showlegend"] == visible
    slider = fig.layout.sliders[0]
    assert slider.x > 0 and slider.x + slider.len < 1  # "0°" and "345°" not cut
    assert fig.layout.margin.r > 0  # the mode menu inside the figure's right edge


def test_the_3d_figures_on_a_phone(result: Any) -> None:
    pytest.importorskip("nicegui")
    from crankbalance.web.tab_mounts import PHONE_CAMERA
    from crankbalance.web.widgets import PHONE_LEGEND_LINE, PLOTLY_EYE, on_a_phone

    fig = on_a_phone(
        mode_shapes_figure(result, animate=True), PHONE_CAMERA["modes"], legend_below=True
    )
    stack = fig.layout.meta["cbStack"]
    assert stack["wide"]["scene.camera.eye"] == PLOTLY_EYE
    assert stack["phone"]["scene.camera.eye"]["x"] > PLOTLY_EYE["x"]
    # the legend (three lines on a phone) below the phase slider
    assert stack["phone"]["margin.b"] == fig.layout.margin.b + 3 * PHONE_LEGEND_LINE
    assert stack["wide"]["margin.b"] == fig.layout.margin.b
