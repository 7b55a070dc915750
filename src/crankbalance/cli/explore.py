"""``crankbalance explore``: every firing order and crank of a layout, ranked.

The enumeration is :mod:`crankbalance.physics.explore.orders`, the figures of merit
:mod:`crankbalance.physics.explore.merit`, the filter, Pareto front and top-N
:mod:`crankbalance.physics.explore.rank`, the chunked run (in this process, on a dask
LocalCluster or on an existing cluster, streaming to Parquet) :mod:`crankbalance.studies.explore`;
all imported when the command runs, dask and pyarrow only when asked for.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import os
import re
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from ..errors import InputError
from ..output.format import json_text, number
from ..physics.explore.work import CONNECT_TIMEOUT, MAX_DRAWS, TASK_CANDIDATES, TASK_MEMORY
from ._common import (
    echo_table,
    format_option,
    named_as_typed,
    parse_settings,
    refuse_unused,
    require_extra,
)

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from ..schema.settings import ExploreOptions

FORMATS = ("table", "json", "csv")
#: a dask scheduler's address, ``tcp://10.0.0.5:8786``
SCHEDULER = re.compile(r"^[a-z]+://[^\s/:]+(:\d+)?$")
#: the module of the dist extra each option needs
DIST = {"workers": "distributed", "scheduler": "distributed", "output": "pyarrow"}


def _problem(o: ExploreOptions, typed: Mapping[str, Any]) -> Any:
    """The problem of the options; an error names the option as typed."""
    from ..physics.explore import orders

    base = None
    if o.engine is not None:
        from ..io.engine_file import load_engine
        from ..studies.build import build_model

        spec = load_engine(o.engine)
        if spec.crank_train.has_vr_rows:
            raise InputError("--engine", o.engine, orders.VR_REFUSED)
        base = build_model(spec)
    try:
        with named_as_typed(typed):
            return orders.problem(
                o.layout,
                o.cylinders,
                o.strokes,
                bank_angle=o.bank_angle,
                crank=o.crank,
                base=base,
            )
    except InputError as error:
        if error.field != "base":
            raise
        raise InputError("--engine", o.engine, error.allowed) from None


def _mode_shape(text: str) -> str | list[float]:
    """``uniform``, ``linear`` or one weight per cylinder, comma separated."""
    from ..physics.explore.merit import MODE_SHAPES

    if text.strip() in MODE_SHAPES:
        return text.strip()
    try:
        weights = [float(w) for w in text.split(",")]
    except ValueError:
        weights = []
    if not weights or not all(math.isfinite(w) for w in weights):
        raise InputError(
            "--mode-shape", text, f"{' or '.join(MODE_SHAPES)}, or one number per cylinder"
        )
    return weights


def _order_text(order: NDArray[Any]) -> str:
    return "-".join(str(int(c)) for c in order)


def _records(rows: Mapping[str, NDArray[Any]], names: list[str]) -> list[dict[str, Any]]:
    """Rows as dictionaries: the firing order as text, the throw angles as a list."""
    out = []
    for i in range(rows["index"].size):
        record: dict[str, Any] = {
            "index": int(rows["index"][i]),
            "firing_order": _order_text(rows["firing_order"][i]),
            "equivalents": int(rows["equivalents"][i]),
            "throw_angle_rad": [float(a) for a in rows["throw_angle_rad"][i]],
        }
        record.update({name: float(rows[name][i]) for name in names})
        out.append(record)
    return out


def _write_plot(plot: str, result: Any, objectives: tuple[str, ...]) -> None:
    """The scatter of the run's candidates (its top-N list and Pareto set) over the first
    two objectives, written atomically (png, svg or html by the suffix)."""
    from ..io.files import write_atomic
    from ..output import render
    from ..output.figures.explore import explore_points, explore_scatter

    points = explore_points(result.top, result.pareto)
    fig = explore_scatter(points, result.pareto, objectives[0], objectives[1], total=result.rows)
    fmt = Path(plot).suffix.lower().lstrip(".")
    write_atomic(plot, render.to_html(fig) if fmt == "html" else render.to_image(fig, fmt))  # type: ignore[arg-type]
    click.echo(f"wrote {plot}", err=True)


@click.command()
@click.option(
    "--layout", default="inline", show_default=True, help="inline, vee, boxer or w (broad arrow)."
)
@click.option("--cylinders", default="4", show_default=True, help="Number of cylinders.")
@click.option("--strokes", default="4", show_default=True, help="2 or 4.")
@click.option("--bank-angle", help="Vee angle, or the angle between W banks, e.g. '90 deg'.")
@click.option(
    "--crank", default="any", show_default=True, help="any, flat, cross or split (split pins)."
)
@click.option("--engine", help="Engine file or preset giving the masses and geometry.")
@click.option(
    "--target",
    default="counterweights",
    show_default=True,
    help="Balancing target: none, counterweights, primary or secondary (shaft pairs).",
)
@click.option("--balance-factor", default="0", show_default=True, help="e.g. 0.5 or 50%.")
@click.option(
    "--mode-shape",
    default="uniform",
    show_default=True,
    help="Torsional mode shape: uniform, linear, or one weight per cylinder '1,0.8,...'.",
)
@click.option("--orders", default="8", show_default=True, help="Highest order (1-64).")
@click.option(
    "--objectives",
    default="F1,M1,F2,M2",
    show_default=True,
    help="Columns of the Pareto front, all minimised, comma separated.",
)
@click.option("--filter", "filter_text", help="Rows kept, e.g. 'F1 == 0 and M1 == 0'.")
@click.option("--top", default="20", show_default=True, help="Rows of the top-N table.")
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
    default=f"{CONNECT_TIMEOUT:g} s",
    show_default=True,
    help="Time the --scheduler has to answer (0.1 s to 120 s).",
)
@click.option(
    "--sample",
    help=f"Random search: draw N indices instead of enumerating all (at most {MAX_DRAWS:,}).",
)
@click.option("--seed", default="0", show_default=True, help="Seed of --sample.")
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
    filter_text: str | None,
    output: str | None,
    progress: bool | None,
    plot: str | None,
    **options: Any,
) -> None:
    """Every firing order and crank of a layout: figures of merit, Pareto front, top-N."""
    import numpy as np

    from ..physics.explore import merit, orders, rank
    from ..physics.explore.work import plan
    from ..results import require_finite
    from ..schema.settings import ExploreOptions
    from ..studies.explore import Keep, Sample, progress_line, run

    if options.get("layout") == "vr":
        raise InputError("--layout", "vr", orders.VR_REFUSED)
    o = parse_settings(ExploreOptions, {**options, "filter": filter_text})
    if o.scheduler is not None and o.workers is not None:
        raise InputError("--workers", options["workers"], "not with --scheduler")
    refuse_unused({"connect_timeout": o.scheduler is not None}, "only acts with --scheduler")
    refuse_unused({"seed": o.sample is not None}, "only acts with --sample")
    given = {"output": output, "workers": o.workers, "scheduler": o.scheduler}
    for name, module in DIST.items():
        if given[name] is not None:
            require_extra("dist", module)
    if output is not None and (
        not output.strip()
        or Path(output).is_dir()
        or not Path(os.path.realpath(output)).parent.is_dir()
    ):
        raise InputError("--output", output, "a file in an existing directory")
    if o.scheduler is not None and not SCHEDULER.match(o.scheduler):
        raise InputError("--scheduler", o.scheduler, "an address PROTOCOL://HOST:PORT")
    if plot is not None:
        from .plot import check_output

        check_output(plot, (".png", ".svg", ".html"), "--plot")
        require_extra("web", "plotly", *(() if plot.lower().endswith(".html") else ("kaleido",)))
    typed = {k: options[k] for k in ("layout", "cylinders", "strokes", "crank")}
    typed |= {"bank_angle": options["bank_angle"]}
    problem = _problem(o, typed)
    evaluate = functools.partial(
        merit.merit,
        target=o.target,
        balance_factor=o.balance_factor,
        mode_shape=_mode_shape(o.mode_shape),
        orders=o.orders,
    )
    with named_as_typed({"mode_shape": o.mode_shape, "orders": options["orders"]}):
        columns = list(evaluate(orders.template(problem)))
    names = [name.strip() for name in o.objectives.split(",")]
    if not all(names):  # an empty name was dropped without a word ("" left no front at all)
        raise InputError(
            "--objectives", o.objectives, "column names separated by commas, none empty"
        )
    objectives = tuple(rank.column_name(name, columns, "--objectives") for name in names)
    # an empty --top-key is refused as an unknown column, not replaced by the default
    key = None if o.top_key is None else rank.column_name(o.top_key, columns, "--top-key")
    if key is None:  # the largest moment left after balancing, else the first objective
        key = "residual_M_Nm" if "residual_M_Nm" in columns else next(iter(objectives), None)
    if plot is not None and (len(objectives) < 2 or key is None):
        raise InputError("--plot", plot, "two --objectives (its axes) and a top-N key")
    keep = Keep(objectives=objectives, key=key, n=o.top)
    if plot is not None:  # the figure's candidates: the best by the key, up to its limit
        from ..output.figures.explore import EXPLORE_POINTS

        keep = Keep(objectives=objectives, key=key, n=max(o.top, EXPLORE_POINTS))
    select = None if o.filter is None else rank.parse_filter(o.filter, columns, "--filter")
    sample = None if o.sample is None else Sample(draws=o.sample, seed=o.seed)
    # the work of the run, before any enumeration, draw or task list (explore.work)
    sizes = {"cylinders": options["cylinders"], "sample": options["sample"]}
    with named_as_typed(sizes | {"chunk": options["chunk"]}):
        work = plan(problem, evaluate, chunk=o.chunk, sample=sample)
    if sample is None and work.exact and work.candidates == 0:
        raise InputError(
            "--cylinders",
            options["cylinders"],
            f"a layout with a firing order: none of its {work.indices:,} firing orders puts "
            "the cylinders sharing a crankpin at one angle (try another --bank-angle, or "
            "--crank split)",
        )
    show = progress if progress is not None else work.tasks > 8
    with named_as_typed({"scheduler": o.scheduler}):
        result = run(
            problem,
            evaluate,
            chunk=work.chunk,
            select=select,
            keep=keep,
            output=output,
            scheduler=o.scheduler,
            workers=o.workers,
            sample=sample,
            progress=progress_line() if show else None,
            connect_timeout=o.connect_timeout,
        )
    if plot is not None:
        _write_plot(plot, result, objectives)
        result = dataclasses.replace(result, top={k: v[: o.top] for k, v in result.top.items()})
    names = [n for n in columns if n in result.top or n in result.pareto]
    shown = list(dict.fromkeys([*objectives, *([keep.key] if keep.key else [])]))
    for part in (result.top, result.pareto):
        require_finite({n: np.asarray(part[n], dtype=float) for n in names if n in part})
    counts = {
        "orders": result.total,
        "looked_at": result.covered,
        "distinct_engines": result.candidates,
        "kept_by_filter": result.rows,
        "pareto": int(result.pareto["index"].size) if result.pareto else 0,
        "seconds": result.seconds,
    }
    if fmt == "json":
        payload = {
            "schema": "crankbalance.explore/1",
            "problem": {
                k: v for k, v in o.values().items() if k not in ("scheduler", "connect_timeout")
            }
            | {"chunk": work.chunk},
            "counts": counts,
            "objectives": list(objectives),
            "top_key": keep.key,
            "torsion_assumption": merit.TORSION_ASSUMPTION,
            "top": _records(result.top, names) if result.top else [],
            "pareto": _records(result.pareto, names) if result.pareto else [],
            "output": output,
        }
        click.echo(json_text(payload))
        return
    records = _records(result.top, names) if result.top else []
    if fmt == "csv":
        header = ["rank", "index", "firing_order", "equivalents", *names]
        lines = [",".join(header)]
        for k, r in enumerate(records, 1):
            values = [str(k), str(r["index"]), r["firing_order"], str(r["equivalents"])]
            lines.append(",".join(values + [f"{r[n]:.9g}" for n in names]))
        click.echo("\n".join(lines))
        return
    sampled = f", {result.covered:,} sampled" if sample else ""
    click.echo(
        f"{o.layout} {o.cylinders}-cylinder {o.strokes}-stroke, crank {o.crank}: "
        f"{result.total:,} firing orders{sampled}, {result.candidates:,} distinct engines, "
        f"{result.rows:,} kept, Pareto front of {counts['pareto']} over "
        f"{', '.join(objectives) or 'nothing'} ({number(result.seconds, 3)} s)"
    )
    echo_table(
        ["rank", "firing order", "equiv", *shown],
        [
            [str(k), r["firing_order"], str(r["equivalents"]), *(number(r[n]) for n in shown)]
            for k, r in enumerate(records, 1)
        ],
    )
    click.echo(f"Assumption: {merit.TORSION_ASSUMPTION}.")
    if output is not None:
        click.echo(f"Rows written to {output}.")
