"""Shared test helpers."""

from __future__ import annotations

import copy
import tomllib
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
