"""``crankbalance report ENGINE -o report.html|report.pdf``."""

from __future__ import annotations

import click

from ..schema.settings import AnalysisOptions, BalanceOptions
from ._common import settings_options


@click.command()
@click.argument("engine")
@click.option(
    "-o",
    "--output",
    required=True,
    help="report.html (self-contained, interactive, works offline) or report.pdf "
    "(printed by headless Chromium).",
)
@settings_options(AnalysisOptions, ("orders",))
@settings_options(BalanceOptions, ("balance_factor", "angle"))
@click.option(
    "--chromium",
    default=None,
    type=click.Path(dir_okay=False),
    help="Chromium executable for the PDF (default: /usr/bin/chromium or $CRANKBALANCE_CHROMIUM).",
)
def report(
    engine: str,
    output: str,
    orders: str | None,
    balance_factor: str | None,
    angle: str | None,
    chromium: str | None,
) -> None:
    """Balancing report of ENGINE (an engine file or a preset name): engine data, mass split,
    free forces and moments, balancing masses, residuals, figures and the settings used."""
    from ..errors import InputError
    from ..output.report import write_report
    from ._common import parse_settings, require_extra
    from .plot import check_output

    pdf = check_output(output, (".html", ".htm", ".pdf")).suffix.lower() == ".pdf"
    require_extra("web", "plotly", *(("kaleido",) if pdf else ()))
    if chromium is not None and not pdf:
        raise InputError("--chromium", chromium, "only acts on a PDF report (-o report.pdf)")
    highest = parse_settings(AnalysisOptions, {"orders": orders}).orders
    settings = parse_settings(BalanceOptions, {"balance_factor": balance_factor, "angle": angle})
    overrides = {
        key: value
        for key, value in (("balance_factor", settings.balance_factor), ("angle", settings.angle))
        if value is not None
    }
    path = write_report(engine, output, highest, chromium, **overrides)
    click.echo(f"wrote {path}", err=True)
