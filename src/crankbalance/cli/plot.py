"""``crankbalance plot KIND ENGINE -o FILE``: one figure of an engine as PNG, SVG or HTML."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click

KINDS = ("orders", "curves", "polar", "crank", "residuals", "single")
SUFFIXES = {".png": "png", ".svg": "svg", ".html": "html", ".htm": "html"}


def build_figure(kind: str, engine: str, order: str = "1", quantity: str = "force",
                 balance: bool = True, cylinder: int = 1,
                 balance_factor: float = 0.5) -> Any:
    """The figure ``kind`` of ``engine`` (preset name or engine file)."""
    from .. import plots
    from ..analysis import analyze, balance_engine
    from ..errors import InputError

    if kind not in KINDS:
        raise InputError("KIND", kind, f"one of {', '.join(KINDS)}")
    if kind in ("residuals", "crank") or (kind == "curves" and balance):
        study = balance_engine(engine)
        if kind == "residuals":
            return plots.residuals_bar(study)
        if kind == "crank":
            return plots.crank_3d(study.model, study if balance else None)
        return plots.curves_figure(analyze(study.model), study, quantity)  # type: ignore[arg-type]
    analysis = analyze(engine)
    if kind == "orders":
        return plots.orders_bar(analysis)
    if kind == "curves":
        return plots.curves_figure(analysis, None, quantity)  # type: ignore[arg-type]
    if kind == "polar":
        chosen: int | str = order
        if order.strip().lstrip("+").isdigit():
            chosen = int(order)
        return plots.polar_figure(analysis, chosen, quantity)  # type: ignore[arg-type]
    from ..single_cylinder import cylinder_balance_factor_study

    count = analysis.model.cylinders
    if not 1 <= cylinder <= count:
        raise InputError("--cylinder", cylinder, f"a cylinder number from 1 to {count}")
    single = cylinder_balance_factor_study(analysis.model, cylinder - 1, balance_factor)
    fig = plots.single_cylinder_forces(single)
    fig.update_layout(title=f"{analysis.model.name}, cylinder {cylinder} alone: "
                            f"{fig.layout.title.text}")
    return fig


@click.command()
@click.argument("kind", type=click.Choice(KINDS))
@click.argument("engine")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False),
              help="Output file: .png, .svg or .html (self-contained, works offline).")
@click.option("--order", default="1", show_default=True,
              help="polar: the harmonic order, or 'rotating' for the bare crank's masses.")
@click.option("--quantity", type=click.Choice(["force", "moment"]), default="force",
              show_default=True, help="curves/polar: force or moment.")
@click.option("--balance/--no-balance", default=True, show_default=True,
              help="curves/crank: include the engine after balancing (counterweights, shafts "
                   "as the engine file asks).")
@click.option("--cylinder", type=int, default=1, show_default=True,
              help="single: cylinder number (1-based).")
@click.option("--balance-factor", type=float, default=0.5, show_default=True,
              help="single: balance factor (0 = rotating mass only, 0.5 = 50 %).")
@click.option("--width", type=click.IntRange(100, 8000), default=None,
              help="Image width [px] (PNG/SVG).")
@click.option("--height", type=click.IntRange(100, 8000), default=None,
              help="Image height [px] (PNG/SVG).")
def plot(kind: str, engine: str, output: str, order: str, quantity: str, balance: bool,
         cylinder: int, balance_factor: float, width: int | None,
         height: int | None) -> None:
    """Draw figure KIND of ENGINE (an engine file or a preset name).

    KIND: orders (free forces/moments by order), curves (versus crank angle, before and
    after balancing), polar (rotating-vector diagram of one order), crank (3-D crankshaft
    with counterweights and balance shafts), residuals (before/after balancing),
    single (one cylinder's shaking forces for a balance factor).
    """
    from ..errors import InputError
    from ..io import write_atomic

    suffix = Path(output).suffix.lower()
    if suffix not in SUFFIXES:
        raise InputError("--output", output, "a file name ending in .png, .svg or .html")
    fmt = SUFFIXES[suffix]
    fig = build_figure(kind, engine, order, quantity, balance, cylinder, balance_factor)
    from .. import plots

    if fmt == "html":
        write_atomic(output, plots.to_html(fig))
    else:
        write_atomic(output, plots.to_image(fig, fmt, width=width, height=height))  # type: ignore[arg-type]
    click.echo(f"wrote {output}", err=True)
