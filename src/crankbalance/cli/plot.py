"""``crankbalance plot KIND ENGINE -o FILE``: one figure of an engine as PNG, SVG or HTML."""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import click

from ..schema.settings import PlotOptions
from ._common import settings_options

KINDS = ("orders", "curves", "polar", "crank", "residuals", "single")
SUFFIXES = {".png": "png", ".svg": "svg", ".html": "html", ".htm": "html"}
#: the options that change each kind of figure (any other one given is refused, not ignored)
KIND_OPTIONS = {
    "orders": (),
    "curves": ("quantity", "balance"),
    "polar": ("order", "quantity"),
    "crank": ("balance",),
    "residuals": (),
    "single": ("cylinder", "balance_factor"),
}


def check_output(output: str, suffixes: Sequence[str], field: str = "--output") -> Path:
    """The output file, refused (InputError) before any work when it cannot be written: a
    suffix not in ``suffixes``, a directory, or a folder that is missing or read-only."""
    from ..errors import InputError

    target = Path(output)
    if target.suffix.lower() not in suffixes:
        raise InputError(field, output, "a file name ending in " + ", ".join(suffixes))
    folder = target.parent
    if target.is_dir():
        raise InputError(field, output, "a file name, not a directory")
    if not folder.is_dir():
        raise InputError(field, output, f"a file in an existing directory (no {folder}/)")
    if not os.access(folder, os.W_OK | os.X_OK) or (
        target.exists() and not os.access(target, os.W_OK)
    ):
        raise InputError(field, output, "a file that can be written (permission denied)")
    return target


#: the files a study's ``--plot`` writes
FIGURE_SUFFIXES = (".png", ".svg", ".html")


def check_figure(plot: str) -> None:
    """Refuse a study's ``--plot`` file before any work: another kind of file, or a missing
    extra to draw it (plotly; kaleido for an image)."""
    from ._common import require_extra

    check_output(plot, FIGURE_SUFFIXES, "--plot")
    require_extra("web", "plotly", *(() if plot.lower().endswith(".html") else ("kaleido",)))


def write_figure(plot: str, fig: Any) -> None:
    """Write a study's figure atomically, PNG, SVG or HTML by the file's suffix."""
    from ..io.files import write_atomic
    from ..output import render

    fmt = Path(plot).suffix.lower().lstrip(".")
    write_atomic(plot, render.to_html(fig) if fmt == "html" else render.to_image(fig, fmt))  # type: ignore[arg-type]
    click.echo(f"wrote {plot}", err=True)


def build_figure(
    kind: str,
    engine: str,
    order: str = "1",
    quantity: str = "force",
    balance: bool = True,
    cylinder: int = 1,
    balance_factor: float = 0.5,
) -> Any:
    """The figure ``kind`` of ``engine`` (preset name or engine file)."""
    from ..errors import InputError
    from ..output.figures.balancing import residuals_bar
    from ..output.figures.crank3d import crank_3d
    from ..output.figures.engine import curves_figure, orders_bar, polar_figure
    from ..output.figures.single import single_cylinder_forces
    from ..studies.engine import analyze, balance_engine

    if kind not in KINDS:
        raise InputError("KIND", kind, f"one of {', '.join(KINDS)}")
    if kind == "residuals" or (kind in ("crank", "curves") and balance):
        study = balance_engine(engine)
        if kind == "residuals":
            return residuals_bar(study)
        if kind == "crank":
            return crank_3d(study.model, study)
        return curves_figure(analyze(study.model), study, quantity)  # type: ignore[arg-type]
    analysis = analyze(engine)
    if kind == "crank":
        return crank_3d(analysis.model)
    if kind == "orders":
        return orders_bar(analysis)
    if kind == "curves":
        return curves_figure(analysis, None, quantity)  # type: ignore[arg-type]
    if kind == "polar":
        chosen: int | str = order.strip()
        if order.strip().isdigit():
            chosen = int(order)
            if chosen < 1:  # polar_figure takes 0 for the rotating masses
                raise InputError("--order", order, "a harmonic order from 1, or 'rotating'")
        return polar_figure(analysis, chosen, quantity)  # type: ignore[arg-type]
    from ..studies.cylinder import cylinder_study

    count = analysis.model.cylinders
    if not 1 <= cylinder <= count:
        raise InputError("--cylinder", cylinder, f"a cylinder number from 1 to {count}")
    single = cylinder_study(analysis.model, cylinder, balance_factor)
    fig = single_cylinder_forces(single)
    fig.update_layout(
        title=f"{analysis.model.name}, cylinder {cylinder} alone: {fig.layout.title.text}"
    )
    return fig


@click.command()
@click.argument("kind", metavar="KIND")
@click.argument("engine")
@click.option(
    "-o",
    "--output",
    required=True,
    help="Output file: .png, .svg or .html (self-contained, works offline).",
)
@click.option(
    "--quantity",
    type=click.Choice(["force", "moment"]),
    default="force",
    show_default=True,
    help="curves/polar: force or moment.",
)
@click.option(
    "--balance/--no-balance",
    default=True,
    show_default=True,
    help="curves/crank: include the engine after balancing (counterweights, shafts "
    "as the engine file asks).",
)
@settings_options(PlotOptions)
@click.option(
    "--width", type=click.IntRange(100, 8000), default=None, help="Image width [px] (PNG/SVG)."
)
@click.option(
    "--height", type=click.IntRange(100, 8000), default=None, help="Image height [px] (PNG/SVG)."
)
@click.pass_context
def plot(
    ctx: click.Context,
    kind: str,
    engine: str,
    output: str,
    quantity: str,
    balance: bool,
    order: str | None,
    cylinder: str | None,
    balance_factor: str | None,
    width: int | None,
    height: int | None,
) -> None:
    """Draw figure KIND of ENGINE (an engine file or a preset name).

    KIND: orders (free forces/moments by order), curves (versus crank angle, before and
    after balancing), polar (rotating-vector diagram of one order), crank (3-D crankshaft
    with counterweights and balance shafts), residuals (before/after balancing),
    single (one cylinder's shaking forces for a balance factor).
    """
    from click.core import ParameterSource

    from ..errors import InputError
    from ._common import parse_settings, require_extra

    if kind not in KINDS:
        raise InputError("KIND", kind, f"one of {', '.join(KINDS)}")
    fmt = SUFFIXES[check_output(output, tuple(SUFFIXES)).suffix.lower()]
    given = [
        name
        for name in (
            "order",
            "quantity",
            "balance",
            "cylinder",
            "balance_factor",
            "width",
            "height",
        )
        if ctx.get_parameter_source(name) is not ParameterSource.DEFAULT
    ]
    for name in given:
        if name in ("width", "height"):
            if fmt == "html":
                raise InputError(
                    f"--{name}",
                    ctx.params[name],
                    "only for .png/.svg output (HTML figures fill the window)",
                )
        elif name not in KIND_OPTIONS[kind]:
            used = " or ".join(k for k, v in KIND_OPTIONS.items() if name in v)
            raise InputError(
                "--" + name.replace("_", "-"),
                ctx.params[name],
                f"only for the {used} figure, not {kind}",
            )
    require_extra("web", "plotly", *(() if fmt == "html" else ("kaleido",)))
    o = parse_settings(
        PlotOptions, {"order": order, "cylinder": cylinder, "balance_factor": balance_factor}
    )
    fig = build_figure(kind, engine, str(o.order), quantity, balance, o.cylinder, o.balance_factor)
    from ..io.files import write_atomic
    from ..output import render

    if fmt == "html":
        write_atomic(output, render.to_html(fig))
    else:
        write_atomic(output, render.to_image(fig, fmt, width=width, height=height))  # type: ignore[arg-type]
    click.echo(f"wrote {output}", err=True)
