"""Shared test helpers."""

from __future__ import annotations

import contextlib
import copy
import signal
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from hypothesis import settings

from crankbalance.cli import main

# property tests draw the same examples on every run, so CI is repeatable; a run with
# `--hypothesis-seed=N` explores other examples
settings.register_profile("repeatable", derandomize=True, deadline=None)
settings.load_profile("repeatable")

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"


def paper_inline3_dict() -> dict[str, Any]:
    """The paper's inline-3 engine file as a dictionary (a fresh copy)."""
    return copy.deepcopy(tomllib.loads((EXAMPLES / "paper_inline3.toml").read_text()))


def run_cli(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    """Run the CLI in-process; return (exit status, stdout, stderr)."""
    try:
        result = main(args)
        code = int(result or 0)
    except SystemExit as stop:
        code = int(stop.code or 0)
    out = capsys.readouterr()
    return code, out.out, out.err


class Hang(Exception):
    """A block outlasted its hang guard."""


@contextlib.contextmanager
def hang_guard(seconds: int) -> Iterator[None]:
    """Raise :class:`Hang` in the block if it is still running after ``seconds`` (a guard
    against a hang, generous enough for a loaded machine: never a timing assertion)."""

    def stop(signum: int, frame: Any) -> None:
        raise Hang(f"still running after {seconds} s")

    previous = signal.signal(signal.SIGALRM, stop)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
