"""The command line's setting options come from the registry and the settings schema
(:func:`crankbalance.cli._common.study_options`): every study's command has exactly its
settings' options and its edge options, each help text shows the field's title and
default."""

from __future__ import annotations

import click
import pytest
from click.testing import CliRunner

from crankbalance.cli import cli
from crankbalance.output.format import in_output_style
from crankbalance.schema.core import default_text
from crankbalance.studies.registry import STUDIES, Study

#: the one option of a study's command that is neither a setting nor an edge option of the
#: registry: the engine, where the command does not take it as an argument
ENGINE_OPTION = "engine"


def command_of(entry: Study) -> click.Command:
    context = click.Context(cli)
    command = cli.get_command(context, entry.command[0])
    for word in entry.command[1:]:
        assert isinstance(command, click.Group)
        command = command.get_command(context, word)
    assert command is not None, entry.name
    return command


def options_of(command: click.Command) -> dict[str, click.Option]:
    return {
        opt[2:]: param
        for param in command.params
        if isinstance(param, click.Option)
        for opt in param.opts
        if opt.startswith("--") and opt != "--help"
    }


@pytest.mark.parametrize("name", sorted(STUDIES))
def test_a_study_command_has_exactly_its_settings_and_edge_options(name: str) -> None:
    entry = STUDIES[name]
    command = command_of(entry)
    settings = {entry.option(f) for f in entry.field_names() if f not in entry.arguments}
    arguments = {p.name for p in command.params if isinstance(p, click.Argument)}
    edge = set(entry.edge)
    if entry.engine != "none" and ENGINE_OPTION not in arguments:
        edge.add(ENGINE_OPTION)
    options = set(options_of(command))
    assert options == settings | edge, (name, options ^ (settings | edge))
    assert set(entry.arguments) <= arguments


@pytest.mark.parametrize("name", sorted(STUDIES))
def test_a_setting_option_shows_the_schema(name: str) -> None:
    """Each setting's option: stored under its field, default None (the schema decides),
    help with the field's title and its default as typed."""
    entry = STUDIES[name]
    model = entry.model()
    options = options_of(command_of(entry))
    for field in entry.field_names():
        if field in entry.arguments:
            continue
        option = options[entry.option(field)]
        spec = model.FIELDS[field]
        assert option.name == field, (name, field)
        assert option.default in (None, ()), (name, field, option.default)
        title, default = in_output_style(spec.title), in_output_style(default_text(spec))
        assert title and title in (option.help or ""), (name, field, option.help)
        assert default in (option.help or ""), (name, field, default, option.help)
        assert option.help and option.help.strip(), (name, field)
        assert option.is_flag == (spec.kind == "flag"), (name, field)
        assert option.multiple == (spec.kind == "list" and spec.single), (name, field)


@pytest.mark.parametrize(
    ("words", "option", "shown"),
    [
        (["balance"], "--verify", "[default: false]"),
        (["analyze"], "--orders", "[default: 8]"),
        (["bearings"], "--samples", "[default: 360]"),
        (["counterweight", "optimize"], "--density", "[default: 8000 kg/m³]"),
        (["bench"], "--inertia", "--inertia INERTIA [kg·m²]"),
        (["bench"], "--inertia", "[default: 0.00284733 kg·m²]"),
        (["bench"], "--unbalance", "--unbalance UNBALANCE [g·mm]"),
        (["bench"], "--kp", "--kp NUMBER"),
        (["bench"], "--kp", "PI proportional gain [N·m·s/rad]"),
        (["bench"], "--speed", "--speed SPEED [rpm],..."),
        (["bearings"], "--ignition", "--ignition ANGLE [°]"),
        (["bearings"], "--ignition", "[default: -25°]"),
        (["analyze"], "--orders", "--orders INTEGER"),
        (["torsional"], "--throw-stiffness", "--throw-stiffness STIFFNESS [N·m/rad]"),
        (["counterweight", "optimize"], "--segment-angle", "--segment-angle ANGLE [°]"),
        (["plot"], "--order", "--order {ORDER|rotating}"),
    ],
)
def test_help_shows_the_schema_default(words: list[str], option: str, shown: str) -> None:
    result = CliRunner().invoke(cli, [*words, "--help"], terminal_width=400)
    assert result.exit_code == 0, result.output
    line = next(line for line in result.output.splitlines() if line.strip().startswith(option))
    assert shown in line, line


#: the spellings of units the output does not use (docs: one unit style, the output's)
OTHER_STYLES = (r"\bkg\*m", r"\bg\*mm", r"\bN\*m", r"\bN m\b", r"\^\d", r"\d ?deg\b", r"\d °")


def _commands(group: click.Group, words: tuple[str, ...] = ()) -> list[tuple[str, ...]]:
    context = click.Context(group)
    found: list[tuple[str, ...]] = []
    for name in group.list_commands(context):
        command = group.get_command(context, name)
        if isinstance(command, click.Group):
            found += _commands(command, (*words, name))
        else:
            found.append((*words, name))
    return found


@pytest.mark.parametrize("words", _commands(cli), ids=" ".join)
def test_every_option_is_described_in_the_output_units(words: tuple[str, ...]) -> None:
    """Issue 29: every option of every command has a description, and the help writes units
    as the output does (N·m, kg·m², g·mm, 30°), never TEXT for a quantity."""
    import re

    result = CliRunner().invoke(cli, [*words, "--help"], terminal_width=400)
    assert result.exit_code == 0, result.output
    group: click.Group = cli
    for word in words[:-1]:
        sub = group.get_command(click.Context(group), word)
        assert isinstance(sub, click.Group)
        group = sub
    command = group.get_command(click.Context(group), words[-1])
    assert command is not None
    for parameter in command.params:
        if isinstance(parameter, click.Option) and parameter.name != "help":
            assert parameter.help, f"{' '.join(words)} {parameter.opts[0]} has no description"
    for pattern in OTHER_STYLES:
        found = re.search(pattern, result.output)
        assert found is None, f"{' '.join(words)}: {found.group(0)!r} in its help"
