"""Command line: ``crankbalance COMMAND ...``.

Each command lives in its own module of this package and is imported only when it
runs, so that ``crankbalance --help`` and every command start fast. To add a command,
add one line to :data:`COMMANDS` (name -> "module:function" of a ``click.Command``).
Commands raise :class:`crankbalance.errors.InputError` for bad input,
:class:`crankbalance.errors.ResultError` when a result is not finite (every output is
checked before it is printed) and :class:`crankbalance.io.files.WriteError` for a file
that cannot be written (a full disk); :func:`main` prints the message on one line without
a traceback and exits with status 2.
"""

from __future__ import annotations

import gc
import importlib
import sys
from typing import Any

import click

from ..errors import InputError, ResultError
from ..io.files import WriteError
from ._common import SuggestingGroup

COMMANDS: dict[str, tuple[str, str]] = {
    # name: ("module:attribute", one-line help)
    "analyze": ("crankbalance.cli.analyze:analyze", "Free forces and moments of an engine."),
    "balance": (
        "crankbalance.cli.balance:balance",
        "Counterweights and balance shafts of an engine.",
    ),
    "counterweight": (
        "crankbalance.cli.counterweight:counterweight",
        "Counterweight shape: optimise, show, export, check a CAD part.",
    ),
    "presets": ("crankbalance.cli.analyze:presets", "List the built-in engine library."),
    "shaft": ("crankbalance.cli.shaft:shaft", "Balance-shaft bearing and unbalance-mass layout."),
    "balance-factor": (
        "crankbalance.cli.single:balance_factor",
        "Single-cylinder balance factor, bob-weight and force study.",
    ),
    "rebalance": (
        "crankbalance.cli.single:rebalance_command",
        "Rebalance a single-cylinder crank after new parts.",
    ),
    "tolerance": (
        "crankbalance.cli.single:tolerance_command",
        "ISO 21940-11 permissible residual unbalance and verdict.",
    ),
    "friction": (
        "crankbalance.cli.performance:friction",
        "Bearing friction torque with unbalance.",
    ),
    "bench": ("crankbalance.cli.performance:bench", "Simulated rotor test bench (PI spin-up)."),
    "cycle": ("crankbalance.cli.performance:cycle", "Engine-cycle torque and bearing loads."),
    "sensitivity": (
        "crankbalance.cli.performance:sensitivity",
        "Performance against the balance factor.",
    ),
    "web": ("crankbalance.cli.web:web", "Serve the web application on 127.0.0.1."),
    "plot": ("crankbalance.cli.plot:plot", "Draw a figure of an engine (PNG, SVG, HTML)."),
    "report": ("crankbalance.cli.report:report", "Engine balancing report (HTML or PDF)."),
    "explore": (
        "crankbalance.cli.explore:explore",
        "Every firing order and crank of a layout, ranked.",
    ),
    "torsional": (
        "crankbalance.cli.torsional:torsional",
        "Torsional vibration of the crank train: modes, resonances, damper.",
    ),
    "mounts": (
        "crankbalance.cli.mounts:mounts",
        "The powertrain on its mounts: statics, modes, mount forces over speed.",
    ),
    "shop": ("crankbalance.cli.shop:shop", "Balance shop: parts, bob-weights, hole plan, sheet."),
    "bearings": (
        "crankbalance.cli.bearings:bearings",
        "Main-bearing loads and crank bending over the engine cycle.",
    ),
    "bearings-sweep": (
        "crankbalance.cli.bearings_sweep:bearings_sweep",
        "Bearing loads, friction and crank bending against counterweights and balance factor.",
    ),
}


class _NotWritten(click.ClickException):
    """A :class:`WriteError` on its way through click (see :meth:`LazyGroup.invoke`)."""

    exit_code = 2


class LazyGroup(SuggestingGroup):
    """A click group whose commands are imported on first use."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(COMMANDS)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in COMMANDS:
            return None
        target, _help = COMMANDS[cmd_name]
        module_name, attribute = target.split(":")
        command = getattr(importlib.import_module(module_name), attribute)
        assert isinstance(command, click.Command)
        return command

    def invoke(self, ctx: click.Context) -> Any:
        # click's own main() takes every OSError of errno EPIPE for its standard output
        # closing and exits 1 without a word; a WriteError (the reader of a FIFO went away)
        # leaves click as a click error, which main() prints as its one line (exit 2)
        try:
            return super().invoke(ctx)
        except WriteError as error:
            raise _NotWritten(str(error)) from None

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        rows = [(name, COMMANDS[name][1]) for name in sorted(COMMANDS)]
        with formatter.section("Commands"):
            formatter.write_dl(rows)


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="crankbalance")
def cli() -> None:
    """crankbalance: balancing design of reciprocating-engine crank trains."""


def main(argv: list[str] | None = None) -> Any:
    """Entry point of the ``crankbalance`` console script.

    ``argv`` None reads the process's own command line: the process exits after the
    command, so its objects are frozen first (:func:`_exiting`). A caller that passes
    ``argv`` (a test, a script) keeps its process as it was."""
    try:
        return cli.main(args=argv, prog_name="crankbalance", standalone_mode=False)
    except (InputError, ResultError, WriteError) as error:
        click.echo(f"error: {_one_line(str(error))}", err=True)
        sys.exit(2)
    except click.exceptions.Abort:
        click.echo("aborted", err=True)
        sys.exit(1)
    except click.ClickException as error:  # usage errors: one line, like InputError
        click.echo(f"error: {_one_line(error.format_message())}", err=True)
        sys.exit(error.exit_code)
    finally:
        if argv is None:
            _exiting()


def _exiting() -> None:
    """Move every object to the collector's permanent generation (:func:`gc.freeze`) as
    the command's process is about to exit: the interpreter's last collection at exit then
    walks none of them. That collection has nothing of a command's to finalise (every file
    a command writes is closed by then; the ``atexit`` handlers run before it) but took
    about 10 ms of every command's cold start, most of it over numpy's objects (issue 30,
    docs/performance.md, "Round nine"). The memory goes back to the system with the
    process."""
    gc.freeze()


def _one_line(message: str) -> str:
    """A message on one line (a value or a reason may hold line breaks)."""
    return " ".join(message.split())


if __name__ == "__main__":  # pragma: no cover
    main()
