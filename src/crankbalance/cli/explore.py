"""``crankbalance explore``: every firing order and crank of a layout, ranked.

The enumeration is :mod:`crankbalance.physics.explore.orders`, the figures of merit
:mod:`crankbalance.physics.explore.merit`, the filter, Pareto front and top-N
:mod:`crankbalance.physics.explore.rank`, the chunked run (in this process, on a dask
LocalCluster or on an existing cluster, streaming to Parquet) :mod:`crankbalance.studies.explore`;
all imported when the command runs, dask and pyarrow only when asked for.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import click

from ..errors import InputError
from ..output.format import json_text, number
from ..schema.settings import ExploreOptions
from ._common import echo_table, format_option, require_extra, run_study, study_options, typed
from .plot import check_figure, write_figure

FORMATS = ("table", "json", "csv")
#: the module of the dist extra each option needs
DIST = {"workers": "distributed", "scheduler": "distributed", "output": "pyarrow"}


@click.command()
@click.option("--engine", help="Engine file or preset giving the masses and geometry.")
@study_options("explore")
@click.option(
    "--output",
    type=click.Path(dir_okay=False),
    help="Parquet file of every row kept (written atomically at the end).",
)
@click.option(
    "--progress/--no-progress",
    default=None,
    help="A progress line on stderr [default: when the run has more than 8 tasks].",
)
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    help="Figure of the candidates over the first two objectives, Pareto set highlighted "
    "(.png, .svg or .html; the best 50 000 by the top-N key when there are more).",
)
@format_option(FORMATS)
def explore(
    fmt: str,
    engine: str | None,
    output: str | None,
    progress: bool | None,
    plot: str | None,
    **values: Any,
) -> None:
    """Every firing order and crank of a layout: figures of merit, Pareto front, top-N."""
    given = typed(values) | ({"output": output} if output is not None else {})
    for name, module in DIST.items():
        if name in given:
            require_extra("dist", module)
    if output is not None and (
        not output.strip()
        or Path(output).is_dir()
        or not Path(os.path.realpath(output)).parent.is_dir()
    ):
        raise InputError("--output", output, "a file in an existing directory")
    points = 0
    if plot is not None:
        from ..output.figures.explore import EXPLORE_POINTS

        check_figure(plot)
        objectives = values.get("objectives") or ExploreOptions.FIELDS["objectives"].default
        if len([name for name in str(objectives).split(",") if name.strip()]) < 2:
            raise InputError("--plot", plot, "two --objectives (its axes) and a top-N key")
        points = EXPLORE_POINTS
    result = run_study(
        "explore", engine, values, output=output, progress=progress, figure_points=points
    )
    if plot is not None:
        from ..output.figures.explore import explore_points, explore_scatter

        run = result.figure
        shown = explore_points(run.top, run.pareto)
        fig = explore_scatter(
            shown, run.pareto, result.objectives[0], result.objectives[1], total=run.rows
        )
        write_figure(plot, fig)
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    records = result.top()
    names = result.names
    if fmt == "csv":
        listed = ["orders"] if result.settings.list_orders else []
        header = ["rank", "index", "firing_order", "equivalents", *listed, *names]
        lines = [",".join(header)]
        for k, r in enumerate(records, 1):
            cells = [str(k), str(r["index"]), r["firing_order"], str(r["equivalents"])]
            cells += [" ".join(r["orders"])] if listed else []  # orders: no comma
            lines.append(",".join(cells + [f"{r[n]:.9g}" for n in names]))
        click.echo("\n".join(lines))
        return
    from ..physics.explore import merit

    o, run = result.settings, result.run
    counts = result.counts()
    shown_columns = list(dict.fromkeys([*result.objectives, *([result.key] if result.key else [])]))
    sampled = f", {run.covered:,} sampled" if o.sample else ""
    click.echo(
        f"{o.layout} {o.cylinders}-cylinder {o.strokes}-stroke, crank {o.crank}"
        f"{_equivalences(o)}: "
        f"{run.total:,} firing orders{sampled}, {run.candidates:,} distinct engines, "
        f"{run.rows:,} kept, Pareto front of {counts['pareto']} over "
        f"{', '.join(result.objectives) or 'nothing'} ({number(run.seconds, 3)} s)"
    )
    listed = ["stands for"] if o.list_orders else []
    echo_table(
        ["rank", "firing order", "equiv", *listed, *shown_columns],
        [
            [
                str(k),
                r["firing_order"],
                str(r["equivalents"]),
                *([" ".join(r["orders"])] if listed else []),
                *(number(r[n]) for n in shown_columns),
            ]
            for k, r in enumerate(records, 1)
        ],
    )
    click.echo(f"Assumption: {merit.TORSION_ASSUMPTION}.")
    if output is not None:
        click.echo(f"Rows written to {output}.")


def _equivalences(o: ExploreOptions) -> str:
    """What the run counts as one engine, when not the default, and a fixed crank."""
    words = []
    if o.fixed_crank is not None:
        degrees = ", ".join(f"{math.degrees(a):g}" for a in o.fixed_crank)
        words.append(f"fixed at {degrees} deg")
    if not o.mirror:
        words.append("mirror images distinct")
    if o.reversal:
        words.append("time reversal the same")
    return f" ({'; '.join(words)})" if words else ""
