"""One rule for readable figures at every edge (issue 28, item 4): the minimum span of a
value axis and the "0 everywhere" note live in ``output/figures/common.py``; the command
line's and the reports' figures get them through ``output/render.py``, the web's figure
cards through the same functions."""

from __future__ import annotations

import pytest

go = pytest.importorskip("plotly.graph_objects")

from crankbalance.output import render  # noqa: E402
from crankbalance.output.figures.common import (  # noqa: E402
    ALL_ZERO,
    MIN_SPAN_SHARE,
    readable,
)


def round_off_curve() -> go.Figure:
    return go.Figure(go.Scatter(x=[0, 1, 2], y=[100.0, 100.0004, 100.0002]))


def test_a_round_off_difference_gets_the_minimum_span() -> None:
    fig = round_off_curve()
    shown = readable(fig)
    low, high = shown.layout.yaxis.range
    assert high - low == pytest.approx(MIN_SPAN_SHARE * 100.0004)
    assert (low + high) / 2 == pytest.approx(100.0002)
    assert fig.layout.yaxis.range is None  # the figure given is left as it is
    varied = go.Figure(go.Scatter(y=[100.0, 101.0]))
    assert readable(varied) is varied


def test_the_command_lines_and_reports_html_has_the_span_and_the_zero_note() -> None:
    html = render.to_html(round_off_curve(), include_plotlyjs=False, full_html=False)
    assert '"range":[' in html.replace(" ", "")
    zeros = go.Figure(go.Bar(x=["1", "2"], y=[0.0, 0.0]))
    assert ALL_ZERO in render.to_html(zeros, include_plotlyjs=False, full_html=False)
    assert ALL_ZERO not in render.to_html(
        go.Figure(go.Bar(x=["1", "2"], y=[0.0, 1.0])), include_plotlyjs=False, full_html=False
    )


def test_the_zero_note_is_not_said_twice() -> None:
    """A figure that already says "... everywhere" (``note_if_zero``) gets no second note."""
    fig = go.Figure(go.Bar(x=["1"], y=[0.0]))
    fig.add_annotation(text="0 N everywhere<br>(balanced)", showarrow=False)
    assert len(readable(fig).layout.annotations) == 1


def test_a_scatter_of_values_is_not_zero_while_its_x_is_not() -> None:
    """Candidates at M1 = 0, 1974 and 3948 N·m with M2 = 0 each (the explorer's inline-4
    over M1, M2) are not "0 everywhere"; a line at 0 over its crank angle is, and so is a
    scatter of values at (0, 0)."""
    from crankbalance.output.figures.common import all_zero

    candidates = go.Scatter(x=[0.0, 1973.9, 3947.8], y=[0.0, 0.0, 0.0], mode="markers")
    assert not all_zero(go.Figure(candidates))
    assert all_zero(go.Figure(go.Scatter(x=[0.0, 360.0, 720.0], y=[0.0, 0.0, 0.0])))
    assert all_zero(go.Figure(go.Scatter(x=[0.0], y=[0.0], mode="markers")))
