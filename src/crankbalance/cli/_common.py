"""Small helpers shared by the CLI commands: output format option, plain tables, the
options a user typed, and the check for an optional extra."""

from __future__ import annotations

import importlib
import re
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

import click

if TYPE_CHECKING:
    from ..schema.settings import Options

_NUMBER = re.compile(r"^\s*([-+]?[\d.]+([eE][-+]?\d+)?%?|-|yes|no)?\s*$")


def option_name(field: str) -> str:
    """The command-line option of a settings field: ``max_mass`` -> ``--max-mass``."""
    return "--" + field.replace("_", "-")


def parse_settings(model: type[Options], values: Mapping[str, Any]) -> Options:
    """A command's options validated by their schema in :mod:`crankbalance.schema.settings` (limits
    after unit conversion, finite numbers); an error names the option as typed."""
    from ..schema.settings import parse_options

    return parse_options(model, values, option_name)


def typed(values: Mapping[str, Any]) -> dict[str, Any]:
    """The options the user typed, by parameter name: an option not given (None, or an
    empty tuple for a repeatable one) is left out, so that the study's default applies; a
    repeated option's values as a list."""
    return {
        name: list(value) if isinstance(value, tuple) else value
        for name, value in values.items()
        if value is not None and value != ()
    }


def run_study(
    name: str, engine: Any, values: Mapping[str, Any], *, engine_option: bool = True, **edge: Any
) -> Any:
    """Study ``name`` of :mod:`crankbalance.studies.registry` on ``engine`` with the options
    typed (``values``: parameter name, the setting's field, -> value as typed) and the
    command's own arguments (``edge``: progress, an output file); an error names the option
    as typed (``--balance-factor``, and ``--engine`` or ``engine`` for the engine as an
    option or an argument)."""
    from ..studies.registry import run, study

    entry = study(name)

    def naming(field: str) -> str:
        if field == "engine":
            return "--engine" if engine_option else "engine"
        return "--" + entry.option(field)

    return run(name, engine, typed(values), naming=naming, **edge)


def echo_notes(engine: str) -> None:
    """Print the plausibility notes of a valid engine (unusual numbers, not errors; they are
    not part of the JSON), one ``note:`` line each."""
    from ..io.engine_file import load_engine

    for note in load_engine(engine).plausibility():
        click.echo(f"note: {note.text}")


def default_help(model: type[Options], name: str, text: str = "") -> str:
    """A help text with the setting's default as one would type it, from the settings
    schema (the one place defaults are decided): ``"Bore. [default: 76.8 mm]"``."""
    from ..schema.settings import default_text

    default = default_text(model, name)
    words = text or f"{model.FIELDS[name].title or name}."
    return f"{words} [default: {default}]" if default else words


#: the optional extras of crankbalance (pyproject.toml) and the modules each provides
EXTRAS: dict[str, tuple[str, ...]] = {
    "web": ("nicegui", "plotly", "kaleido"),
    "geometry": ("shapely", "trimesh", "pymoo"),
    "cad": ("build123d",),
    "dist": ("distributed", "pyarrow"),
}


def require_extra(extra: str, *modules: str) -> None:
    """Refuse with one line (:class:`~crankbalance.errors.InputError`, exit 2) when a module
    of an optional extra is not installed: "the web extra: needed here but not installed
    (plotly is missing): pip install 'crankbalance[web]'". ``modules`` defaults to all of
    the extra's."""
    from ..errors import InputError

    for module in modules or EXTRAS[extra]:
        assert module in EXTRAS[extra], f"{module} is not in the {extra} extra"
        try:
            importlib.import_module(module)
        except ImportError:
            raise InputError(
                f"the {extra} extra",
                None,
                f"needed here but not installed ({module} is missing): "
                f"pip install 'crankbalance[{extra}]'",
            ) from None


def given_options() -> set[str]:
    """Names of the options the user typed (not defaults) in the running command."""
    context = click.get_current_context(silent=True)
    if context is None:
        return set()
    return {
        name
        for name in context.params
        if context.get_parameter_source(name) == click.core.ParameterSource.COMMANDLINE
    }


def refuse_unused(used: dict[str, bool], reason: str, given: set[str] | None = None) -> None:
    """Refuse an option the user typed that would be ignored: ``used`` maps an option's
    parameter name to whether it acts; the first typed one that does not is named with
    ``reason`` ("only acts with --engine")."""
    from ..errors import InputError

    typed = given_options() if given is None else given
    for name, acts in used.items():
        if name in typed and not acts:
            context = click.get_current_context()
            raise InputError(option_name(name), context.params.get(name), reason)


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
