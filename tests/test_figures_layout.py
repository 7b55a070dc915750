"""The axes of figures as a designer reads them (issue 28, review findings 11 and 14): a
to-scale drawing keeps exactly its drawing's range and narrow side margins (on a phone it
was drawn in 158 of 318 px, and a wide plot widened its x range to ±250 mm around a
±112 mm drawing)."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("plotly")

from crankbalance.output.figures.common import DRAWING_MARGIN, plotly_go, web_drawing  # noqa: E402


def test_a_drawing_keeps_its_range_on_any_plot_shape() -> None:
    go = plotly_go()
    ring = np.linspace(0, 2 * np.pi, 91)
    fig = go.Figure(go.Scatter(x=50 * np.cos(ring), y=50 * np.sin(ring), mode="lines"))
    out = web_drawing(fig, 55.0, "A web")
    layout = out.layout
    assert list(layout.xaxis.range) == list(layout.yaxis.range) == [-55.0, 55.0]
    assert (layout.yaxis.scaleanchor, layout.yaxis.scaleratio) == ("x", 1)
    # the plot shrinks to a square instead of widening the range of one axis
    assert layout.xaxis.constrain == layout.yaxis.constrain == "domain"
    assert (layout.margin.l, layout.margin.r) == (DRAWING_MARGIN["l"], DRAWING_MARGIN["r"])
    assert DRAWING_MARGIN["l"] + DRAWING_MARGIN["r"] < 160  # plotly's default: 80 + 80
