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


class SuggestingGroup(click.Group):
    """A click group that answers a misspelt command with the closest one: ``No such
    command 'analyse'; did you mean 'analyze'?``."""

    def resolve_command(
        self, ctx: click.Context, args: list[str]
    ) -> tuple[str | None, click.Command | None, list[str]]:
        name = click.utils.make_str(args[0]) if args else ""
        known = self.list_commands(ctx)
        if name and not name.startswith("-") and name not in known:
            from ..schema.core import closest

            close = closest(name, known)
            if close is not None:
                ctx.fail(f"No such command {name!r}; did you mean {close!r}?")
        return super().resolve_command(ctx, args)


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


#: the file settings click checks before the study runs (``click.Path``: "File 'p.csv'
#: does not exist"), as these options always did; the other file settings (``--parts``) are
#: read by the study, whose message says why a file cannot be read
CLICK_PATHS = frozenset({"pressure_csv"})


def study_options(
    name: str, *, only: Sequence[str] = ()
) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Add a click parameter for every setting of study ``name`` of the registry
    (:mod:`crankbalance.studies.registry`), from its settings schema alone: the option
    ``--`` + :meth:`Study.option <crankbalance.studies.registry.Study.option>`, stored under
    the field's name; its help the field's title, description and choices, then its
    default as one would type it or, without a default, its hint (:func:`setting_help`).

    Every option's default is None (not given): the schema decides every default. A
    ``flag`` is a boolean flag (``--gas/--no-gas`` when it is on by default), a list that
    may be given once or several times (``single``) a repeatable option, a choice a text
    option (the schema reads it, with its did-you-mean message); the settings of
    :attr:`Study.arguments` are arguments instead. The edge's options (``--format``,
    ``--plot``, the engine) are the command's own. ``only``: the settings a command takes
    when it takes only some of the study's (``counterweight check``: the requirement and the
    density of ``counterweight show``)."""
    from ..studies.registry import study

    entry = study(name)
    return settings_options(
        entry.model(),
        [f for f in entry.field_names() if not only or f in only],
        entry.option,
        arguments=entry.arguments,
    )


def settings_options(
    model: type[Options],
    fields: Sequence[str] = (),
    option: Callable[[str], str] | None = None,
    *,
    arguments: Sequence[str] = (),
) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """:func:`study_options` for the settings ``fields`` (default: all) of a settings
    model, for the commands that are no study of the registry (``plot``, ``report``):
    ``option(field)`` is the option without dashes (default: the field with dashes)."""
    named = option or (lambda field: field.replace("_", "-"))

    def decorate(function: Callable[..., Any]) -> Callable[..., Any]:
        for field in reversed(fields or list(model.FIELDS)):
            spec = model.FIELDS[field]
            if field in arguments:
                function = click.argument(field)(function)
                continue
            flag = "--" + named(field)
            kinds: dict[str, Any] = {}
            if spec.kind == "flag":
                kinds["is_flag"] = True
                if spec.default is True:
                    flag += f"/--no-{named(field)}"
            if spec.kind == "list" and spec.single:
                kinds["multiple"] = True
            if field in CLICK_PATHS:
                kinds["type"] = click.Path(exists=True, dir_okay=False)
            elif field not in CLICK_PATHS:
                kinds["metavar"] = setting_metavar(model, field)
            function = click.option(
                flag, field, default=None, help=setting_help(model, field), **kinds
            )(function)
        return function

    return decorate


#: the metavar of a setting of each plain kind (a quantity's is its kind and unit)
METAVARS = {
    "number": "NUMBER",
    "whole": "INTEGER",
    "factor": "FRACTION",
    "choice": "CHOICE",
    "text": "TEXT",
}
#: choices a metavar lists in full (more are "CHOICE", listed in the help)
METAVAR_CHOICES = 5


def setting_metavar(model: type[Options], name: str) -> str:
    """What ``--help`` shows after a setting's option: a quantity's kind and display unit
    (``LENGTH [mm]``, ``INERTIA [kg·m²]``), a number's kind (``NUMBER``, ``INTEGER``,
    ``FRACTION``: 0.5 or 50%), a few choices (``{exact|series}``), a list's item with
    ``,...``."""
    from ..output.format import in_output_style
    from ..units import KINDS

    spec = model.FIELDS[name]
    if spec.kind == "list" and spec.item is not None:
        return f"{_metavar(spec.item, KINDS, in_output_style)},..."
    return _metavar(spec, KINDS, in_output_style)


def _metavar(spec: Any, kinds: Mapping[str, Any], style: Callable[[str], str]) -> str:
    if spec.metavar:
        return str(spec.metavar)
    if spec.quantity is not None and spec.kind in kinds:
        unit = kinds[spec.kind][1]
        return f"{spec.kind.upper()} [{'°' if unit == 'deg' else style(unit)}]"
    if spec.choices and len(spec.choices) <= METAVAR_CHOICES:
        return "{" + "|".join(map(str, spec.choices)) + "}"
    return METAVARS.get(spec.kind, "TEXT")


def setting_help(model: type[Options], name: str) -> str:
    """The help text of a setting from its schema: ``"Bore. Cylinder bore, for the gas
    force. [default: 76.8 mm]"``; without a default, its hint in brackets instead, or for
    a quantity an example of it as typed (``[e.g. '40 mm']``)."""
    from ..output.format import in_output_style
    from ..schema.core import default_text
    from ..units import KINDS

    spec = model.FIELDS[name]
    title = spec.title or name.replace("_", " ").capitalize()
    words = [title if title.endswith((".", "?")) else title + "."]
    if spec.description:
        words.append(spec.description)
    if spec.choices:
        words.append("One of: " + ", ".join(map(str, spec.choices)) + ".")
    default = default_text(spec)
    if default:
        words.append(f"[default: {default}]")
    elif spec.hint:
        words.append(f"[{spec.hint}]")
    elif spec.quantity is not None:
        words.append(f"[e.g. '{spec.example or KINDS[spec.kind][2]}']")
    return in_output_style(" ".join(words))


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
