"""The command line's setting options come from the registry and the settings schema
(:func:`crankbalance.cli._common.study_options`): every study's command has exactly its
settings' options and its edge options, each help text shows the field's title and
default."""

from __future__ import annotations

import click
import pytest
from click.testing import CliRunner

from crankbalance.cli import cli
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
        assert spec.title and spec.title in (option.help or ""), (name, field, option.help)
        default = default_text(spec)
        assert default in (option.help or ""), (name, field, default, option.help)
        assert option.is_flag == (spec.kind == "flag"), (name, field)
        assert option.multiple == (spec.kind == "list" and spec.single), (name, field)


@pytest.mark.parametrize(
    ("words", "option", "shown"),
    [
        (["balance"], "--verify", "[default: false]"),
        (["analyze"], "--orders", "[default: 8]"),
        (["bearings"], "--samples", "[default: 360]"),
        (["counterweight", "optimize"], "--density", "[default: 8000 kg/m^3]"),
    ],
)
def test_help_shows_the_schema_default(words: list[str], option: str, shown: str) -> None:
    result = CliRunner().invoke(cli, [*words, "--help"], terminal_width=400)
    assert result.exit_code == 0, result.output
    line = next(line for line in result.output.splitlines() if line.strip().startswith(option))
    assert shown in line, line
