"""Figures of the design-space explorer (:mod:`crankbalance.physics.explore`, rows of its
run, :mod:`crankbalance.studies.explore`).

Public functions
----------------
- ``explore_scatter(rows, pareto, x, y, title="Candidates", total=None) -> Figure``
    candidates over two objectives, the Pareto set highlighted, hover text per candidate
- ``explore_candidate(row, orders=4) -> Figure``    one candidate's free forces and moments
- ``explore_points(*parts) -> dict``                the rows a scatter draws, each once
- ``explore_hover(rows, names) -> list[str]``       the hover text of each row
- ``column_words(name) -> str``                     an explorer column in words with its unit
"""

from __future__ import annotations

import math
import re
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from .common import COLORS, TEMPLATE, figure_title, make_subplots, note_if_zero, plotly_go

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go


#: most candidates an explorer scatter draws (the best by the top-N key and the Pareto set)
EXPLORE_POINTS = 50_000
#: what :func:`explore_candidate` writes over its bars when every one is zero
BALANCED = (
    "0 everywhere: no free force or moment of orders 1 to {orders}<br>"
    "(this crank is balanced in them: nothing to draw)"
)


#: the explorer's columns without an order, in words (docs/explorer.md's table of columns)
COLUMN_WORDS = {
    "Frot_N": "force of the rotating masses (no counterweights)",
    "Mrot_Nm": "couple of the rotating masses (no counterweights)",
    "cw_mass_kg": "counterweight mass",
    "shafts": "balance shafts needed",
    "shaft_mass_kg": "balance-shaft mass",
    "residual_F_N": "largest force left after balancing",
    "residual_M_Nm": "largest moment left after balancing",
    "mirror_rad": "distance of the crank from its mirror image",
    "interval_dev_rad": "firing intervals' deviation from even",
    "bank_interval_dev_rad": "worst bank's firing intervals' deviation from even",
}
#: an explorer column's unit suffix -> its unit as shown
UNITS = (("_Nm", "N·m"), ("_N", "N"), ("_kg", "kg"), ("_rad", "rad"))
#: a free force's or moment's column: ``F2_N``, ``M1f_Nm`` (f forward, b backward)
FREE_COLUMN = re.compile(r"^([FM])(\d+)([fb]?)_(N|Nm)$")


def column_words(name: str) -> str:
    """An explorer column in words with its unit: ``M1_Nm`` -> ``free moment, order 1
    [N·m]``, ``X1p5`` -> ``torsional excitation, order 1.5``."""
    unit = next((u for suffix, u in UNITS if name.endswith(suffix)), "")
    free = FREE_COLUMN.match(name)
    if free:
        kind, order, part, _ = free.groups()
        what = "free force" if kind == "F" else "free moment"
        part = {"f": ", forward", "b": ", backward", "": ""}[part]
        words = f"{what}, order {order}{part}"
    elif re.fullmatch(r"X\d+(p\d+)?", name):
        words = f"torsional excitation, order {name[1:].replace('p', '.')}"
    else:
        words = COLUMN_WORDS.get(name, name)
    return f"{words} [{unit}]" if unit else words


def explore_points(*parts: dict[str, Any]) -> dict[str, NDArray[Any]]:
    """The rows of explorer results (a run's top-N list, its Pareto set), each candidate
    once (by its enumeration index), by increasing index: the points of
    :func:`explore_scatter`."""
    parts = tuple(p for p in parts if p and np.asarray(p["index"]).size)
    if not parts:
        return {}
    joined = {name: np.concatenate([np.asarray(p[name]) for p in parts]) for name in parts[0]}
    _, first = np.unique(joined["index"], return_index=True)
    return {name: values[first] for name, values in joined.items()}


def explore_hover(rows: dict[str, Any], names: tuple[str, ...]) -> list[str]:
    """One hover text per row: the firing order, the throw angles [deg], the values of
    ``names``."""
    out = []
    for i in range(np.asarray(rows["index"]).size):
        order = "-".join(str(int(c)) for c in rows["firing_order"][i])
        throws = ", ".join(f"{math.degrees(a) % 360:.0f}" for a in rows["throw_angle_rad"][i])
        values = "<br>".join(f"{n} = {float(rows[n][i]):.5g}" for n in names)
        out.append(f"firing order {order}<br>throws [deg]: {throws}<br>{values}")
    return out


def explore_scatter(
    rows: dict[str, Any],
    pareto: dict[str, Any],
    x: str,
    y: str,
    title: str = "Candidates",
    total: int | None = None,
) -> go.Figure:
    """Explorer candidates over two objectives (columns of
    :func:`crankbalance.physics.explore.merit.merit`), the Pareto set highlighted.

    ``rows`` are the candidates drawn (each with ``index``, ``firing_order``,
    ``throw_angle_rad`` and the columns ``x`` and ``y``), ``pareto`` the run's Pareto set
    (drawn over them), ``total`` the candidates the run kept (said in the legend when more
    than drawn). Each point carries its enumeration index as ``customdata`` (what a click
    gives) and a hover text with its firing order, throw angles and values.
    """
    go = plotly_go()
    fig = go.Figure()
    names = tuple(dict.fromkeys((x, y)))
    for part, label, color, size in (
        (rows, "candidates", COLORS["before"], 6),
        (pareto, "Pareto set", COLORS["after"], 10),
    ):
        n = np.asarray(part.get("index", ())).size if part else 0
        if not n:
            continue
        shown = f"{label} ({n}" + (f" of {total})" if label == "candidates" and total else ")")
        scatter = go.Scattergl if n > 5000 else go.Scatter  # SVG slows down past that
        fig.add_trace(
            scatter(
                x=np.asarray(part[x], dtype=float),
                y=np.asarray(part[y], dtype=float),
                mode="markers",
                name=shown,
                customdata=np.asarray(part["index"], dtype=np.int64),
                hovertext=explore_hover(part, names),
                hoverinfo="text",
                marker={"color": color, "size": size, "line": {"width": 0}},
            )
        )
    fig.update_xaxes(title_text=column_words(x))
    fig.update_yaxes(title_text=column_words(y))
    fig.update_layout(
        template=TEMPLATE,
        legend={"orientation": "h", "y": -0.2},
        title=figure_title(title, note="both objectives minimised"),
    )
    return fig


def explore_candidate(row: dict[str, Any], orders: int = 4) -> go.Figure:
    """One explorer candidate's leading figures: free force and free moment of orders 1 to
    ``orders`` (forward and backward stacked), the firing order in the title; a crank
    balanced in all of them gets :data:`BALANCED` written over its empty axes, one balanced
    in its forces or its moments only gets "0 N everywhere" (or N·m) in that subplot
    (:func:`~crankbalance.output.figures.common.note_if_zero`). ``row`` is one row of the
    explorer's columns (scalars, or arrays of one element)."""
    go = plotly_go()
    fig = make_subplots(rows=1, cols=2, subplot_titles=("free force [N]", "free moment [N·m]"))

    def value(name: str) -> float:
        return float(np.asarray(row.get(name, np.nan)).reshape(-1)[0])

    found = [n for n in range(1, orders + 1) if f"F{n}f_N" in row]
    labels = [str(n) for n in found]
    for col, (letter, unit) in enumerate((("F", "N"), ("M", "Nm")), start=1):
        for part, name in (("f", "forward"), ("b", "backward")):
            fig.add_trace(
                go.Bar(
                    x=labels,
                    y=[value(f"{letter}{n}{part}_{unit}") for n in found],
                    name=name,
                    marker_color=COLORS[name],
                    showlegend=col == 1,
                ),
                row=1,
                col=col,
            )
    fig.update_xaxes(title_text="order")
    if any(v for trace in fig.data for v in trace.y):  # an empty subplot says why
        for col, unit in ((1, "N"), (2, "N·m")):
            bars = [v for trace in fig.data[2 * col - 2 : 2 * col] for v in trace.y]
            note_if_zero(fig, bars, unit, 1, col, "" if col == 1 else "2")
    else:  # a balanced crank: say why empty
        fig.add_annotation(
            text=BALANCED.format(orders=found[-1] if found else orders),
            xref="paper",
            yref="paper",
            x=0.5,
            y=0.5,
            showarrow=False,
            bgcolor="white",
        )
    order = "-".join(str(int(c)) for c in np.asarray(row["firing_order"]).reshape(-1))
    fig.update_layout(
        template=TEMPLATE,
        barmode="stack",
        legend={"orientation": "h", "y": -0.2},
        title=figure_title("Leading figures of merit", note=f"firing order {order}"),
    )
    return fig
