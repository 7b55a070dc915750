"""``crankbalance report ENGINE -o report.html|report.pdf``."""

from __future__ import annotations

import click


@click.command()
@click.argument("engine")
@click.option(
    "-o",
    "--output",
    required=True,
    help="report.html (self-contained, interactive, works offline) or report.pdf "
    "(printed by headless Chromium).",
)
@click.option("--orders", default="8", show_default=True, help="Highest harmonic order (1-64).")
@click.option(
    "--balance-factor",
    type=float,
    default=None,
    help="Override the engine file's counterweight balance factor (0 = rotating masses only).",
)
@click.option(
    "--angle",
    default=None,
    help="Override the counterweight angle: 'optimal' or an angle such as '30 deg'.",
)
@click.option(
    "--chromium",
    default=None,
    type=click.Path(dir_okay=False),
    help="Chromium executable for the PDF (default: /usr/bin/chromium or $CRANKBALANCE_CHROMIUM).",
)
def report(
    engine: str,
    output: str,
    orders: str,
    balance_factor: float | None,
    angle: str | None,
    chromium: str | None,
) -> None:
    """Balancing report of ENGINE (an engine file or a preset name): engine data, mass split,
    free forces and moments, balancing masses, residuals, figures and the settings used."""
    from ..options import AnalysisOptions, parse_options
    from ..report import write_report
    from ._common import option_name
    from .plot import check_output

    check_output(output, (".html", ".htm", ".pdf"))
    overrides: dict[str, object] = {}
    if balance_factor is not None:
        from ..errors import check_range

        check_range("--balance-factor", balance_factor, 0.0, 2.0)
        overrides["balance_factor"] = balance_factor
    if angle is not None:
        if angle.strip().lower() == "optimal":
            overrides["angle"] = "optimal"
        else:
            from ..units import parse_quantity

            overrides["angle"] = parse_quantity(angle, "angle", "--angle")
    highest = parse_options(AnalysisOptions, {"orders": orders}, option_name).orders
    path = write_report(engine, output, highest, chromium, **overrides)
    click.echo(f"wrote {path}", err=True)
