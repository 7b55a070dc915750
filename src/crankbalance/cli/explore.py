"""``crankbalance explore``: every firing order and crank of a layout, ranked.

The enumeration is :mod:`crankbalance.physics.explore.orders`, the figures of merit
:mod:`crankbalance.physics.explore.merit`, the filter, Pareto front and top-N
:mod:`crankbalance.physics.explore.rank`, the chunked run (in this process, on a dask
LocalCluster or on an existing cluster, streaming to Parquet) :mod:`crankbalance.studies.explore`;
all imported when the command runs, dask and pyarrow only when asked for.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import click

from ..errors import InputError
from ..output.format import json_text, number
from ..physics.explore.work import CONNECT_TIMEOUT, MAX_DRAWS, TASK_CANDIDATES, TASK_MEMORY
from ..schema.settings import ExploreOptions
from ._common import default_help, echo_table, format_option, require_extra, run_study, typed
from .plot import check_figure, write_figure

FORMATS = ("table", "json", "csv")
#: the module of the dist extra each option needs
DIST = {"workers": "distributed", "scheduler": "distributed", "output": "pyarrow"}


def _shown(name: str, words: str) -> str:
    return default_help(ExploreOptions, name, words)


@click.command()
@click.option(
    "--layout", default=None, help=_shown("layout", "inline, vee, boxer or w (broad arrow).")
)
@click.option("--cylinders", default=None, help=_shown("cylinders", "Number of cylinders."))
@click.option("--strokes", default=None, help=_shown("strokes", "2 or 4."))
@click.option("--bank-angle", help="Vee angle, or the angle between W banks, e.g. '90 deg'.")
@click.option(
    "--crank", default=None, help=_shown("crank", "any, flat, cross or split (split pins).")
)
@click.option("--engine", help="Engine file or preset giving the masses and geometry.")
@click.option(
    "--target",
    default=None,
    help=_shown(
        "target", "Balancing target: none, counterweights, primary or secondary (shaft pairs)."
    ),
)
@click.option("--balance-factor", default=None, help=_shown("balance_factor", "e.g. 0.5 or 50%."))
@click.option(
    "--mode-shape",
    default=None,
    help=_shown(
        "mode_shape",
        "Torsional mode shape: uniform, linear, or one weight per cylinder '1,0.8,...'.",
    ),
)
@click.option("--orders", default=None, help=_shown("orders", "Highest order (1-64)."))
@click.option(
    "--objectives",
    default=None,
    help=_shown("objectives", "Columns of the Pareto front, all minimised, comma separated."),
)
@click.option("--filter", help="Rows kept, e.g. 'F1 == 0 and M1 == 0'.")
@click.option("--top", default=None, help=_shown("top", "Rows of the top-N table."))
@click.option(
    "--top-key",
    help="Column of the top-N table [default: residual_M, the largest moment left after "
    "balancing; with --target none the first objective].",
)
@click.option(
    "--chunk",
    help=f"Indices per task [default: chosen from the problem, about {TASK_CANDIDATES} "
    f"candidates per task; at most what a task's {TASK_MEMORY // 2**20} MiB hold].",
)
@click.option("--workers", help="Run on a dask LocalCluster of N worker processes.")
@click.option("--scheduler", help="Run on an existing dask cluster, tcp://HOST:PORT.")
@click.option(
    "--connect-timeout",
    default=None,
    help=f"Time the --scheduler has to answer (0.1 s to 120 s). [default: {CONNECT_TIMEOUT:g} s]",
)
@click.option(
    "--sample",
    help=f"Random search: draw N indices instead of enumerating all (at most {MAX_DRAWS:,}).",
)
@click.option("--seed", default=None, help=_shown("seed", "Seed of --sample."))
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
        header = ["rank", "index", "firing_order", "equivalents", *names]
        lines = [",".join(header)]
        for k, r in enumerate(records, 1):
            cells = [str(k), str(r["index"]), r["firing_order"], str(r["equivalents"])]
            lines.append(",".join(cells + [f"{r[n]:.9g}" for n in names]))
        click.echo("\n".join(lines))
        return
    from ..physics.explore import merit

    o, run = result.settings, result.run
    counts = result.counts()
    shown_columns = list(dict.fromkeys([*result.objectives, *([result.key] if result.key else [])]))
    sampled = f", {run.covered:,} sampled" if o.sample else ""
    click.echo(
        f"{o.layout} {o.cylinders}-cylinder {o.strokes}-stroke, crank {o.crank}: "
        f"{run.total:,} firing orders{sampled}, {run.candidates:,} distinct engines, "
        f"{run.rows:,} kept, Pareto front of {counts['pareto']} over "
        f"{', '.join(result.objectives) or 'nothing'} ({number(run.seconds, 3)} s)"
    )
    echo_table(
        ["rank", "firing order", "equiv", *shown_columns],
        [
            [
                str(k),
                r["firing_order"],
                str(r["equivalents"]),
                *(number(r[n]) for n in shown_columns),
            ]
            for k, r in enumerate(records, 1)
        ],
    )
    click.echo(f"Assumption: {merit.TORSION_ASSUMPTION}.")
    if output is not None:
        click.echo(f"Rows written to {output}.")
