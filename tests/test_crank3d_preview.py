"""The still picture of a 3-D figure (``output/figures/crank3d_preview.py``), shown by the
web page until plotly.js has drawn the scene: every line and marker of the figure is drawn,
a line's breaks are kept, and the view is the camera's (a line along the scene's x seen
from -y is level, one along z upright)."""

from __future__ import annotations

import re

import pytest

from crankbalance.output.figures.crank3d_preview import HEIGHT, WIDTH, scene_svg

BOX = {
    "scene": {
        "xaxis": {"range": [-1, 1]},
        "yaxis": {"range": [-1, 1]},
        "zaxis": {"range": [-1, 1]},
        "aspectratio": {"x": 1, "y": 1, "z": 1},
        "camera": {"eye": {"x": 0, "y": -2, "z": 0}},
    }
}


def polylines(svg: str) -> list[list[tuple[float, float]]]:
    runs = re.findall(r'<polyline points="([^"]*)"', svg)
    return [[tuple(map(float, p.split(","))) for p in run.split()] for run in runs]


def test_a_line_along_x_seen_from_minus_y_is_level_and_one_along_z_upright() -> None:
    figure = {
        "data": [
            {"type": "scatter3d", "mode": "lines", "x": [-1, 1], "y": [0, 0], "z": [0, 0]},
            {"type": "scatter3d", "mode": "lines", "x": [0, 0], "y": [0, 0], "z": [-1, 1]},
        ],
        "layout": BOX,
    }
    across, upright = polylines(scene_svg(figure))
    assert across[0][1] == pytest.approx(across[1][1]) and across[0][0] < across[1][0]
    # SVG's y grows downwards: z up is y down the page
    assert upright[0][0] == pytest.approx(upright[1][0]) and upright[0][1] > upright[1][1]
    for x, y in across + upright:
        assert 0 <= x <= WIDTH and 0 <= y <= HEIGHT


def test_every_run_of_a_broken_line_and_every_marker_is_drawn() -> None:
    figure = {
        "data": [
            {
                "type": "scatter3d",
                "mode": "lines",
                "x": [0, 1, None, 0, 1, 1],
                "y": [0, 0, None, 1, 1, 0],
                "z": [0, 0, None, 0, 0, 1],
                "line": {"color": "#1f3b73", "width": 12},
            },
            {
                "type": "scatter3d",
                "mode": "markers",
                "x": [0, 1, 0.5],
                "y": [0, 1, 0.5],
                "z": [1, 1, 0.5],
                "marker": {"color": "#2ca02c", "size": [18, 18, 6]},
            },
        ],
        "layout": BOX,
    }
    svg = scene_svg(figure)
    assert [len(run) for run in polylines(svg)] == [2, 3]
    assert svg.count('stroke="#1f3b73"') == 2 and 'stroke-width="12"' in svg
    assert re.findall(r'r="([\d.]+)" fill="#2ca02c"', svg) == ["9", "9", "3"]


def test_a_figure_without_points_gives_an_empty_picture() -> None:
    svg = scene_svg({"data": [], "layout": BOX})
    assert svg.startswith("<svg") and "<polyline" not in svg and "<circle" not in svg


def test_the_crank_of_a_preset_is_drawn_with_all_its_parts() -> None:
    pytest.importorskip("plotly", reason="plotly is in the web/test extras")
    from crankbalance.output.figures.crank3d import crank_3d
    from crankbalance.studies.engine import balance_engine

    study = balance_engine("v8-crossplane")
    figure = crank_3d(study.model, study).to_plotly_json()
    svg = scene_svg(figure)
    markers = sum(len(t["x"]) for t in figure["data"] if t.get("mode") == "markers")
    assert svg.count("<circle") == markers == 8  # the eight counterweights
    colours = {t["line"]["color"] for t in figure["data"] if "lines" in t.get("mode", "")}
    assert all(f'stroke="{c}"' in svg for c in colours)
