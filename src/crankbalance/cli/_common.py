"""Small helpers shared by the CLI commands: output format option and plain tables."""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from typing import Any

import click

_NUMBER = re.compile(r"^\s*([-+]?[\d.]+([eE][-+]?\d+)?%?|-|yes|no)?\s*$")


def option_name(field: str) -> str:
    """The command-line option of a settings field: ``max_mass`` -> ``--max-mass``."""
    return "--" + field.replace("_", "-")


def format_option(choices: Sequence[str]) -> Callable[[Any], Any]:
    """The ``--format`` option (stored as ``fmt``)."""
    return click.option(
        "--format",
        "fmt",
        type=click.Choice(list(choices)),
        default=choices[0],
        show_default=True,
        help="Output format.",
    )


def format_table(header: Sequence[str] | None, rows: Sequence[Sequence[str]]) -> str:
    """An aligned plain-text table: the first column and text columns left aligned, numeric
    columns right aligned; the header, when given, is underlined."""
    lines = ([list(header)] if header else []) + [list(r) for r in rows]
    widths = [max(len(str(x)) for x in column) for column in zip(*lines, strict=True)]
    numeric = [
        k > 0 and all(_NUMBER.match(str(row[k])) for row in rows) for k in range(len(widths))
    ]

    def line(cells: Sequence[str]) -> str:
        return "  ".join(
            str(c).rjust(w) if right else str(c).ljust(w)
            for c, w, right in zip(cells, widths, numeric, strict=True)
        ).rstrip()

    out = [line(cells) for cells in lines]
    if header:
        out.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(out)


def echo_table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> None:
    """Print an aligned plain-text table with an underlined header."""
    click.echo(format_table(header, rows))
