"""docs/web.md ("JSON API") gives one body for every study of the registry; each is sent to
the API's handler and answered 200 with its study's schema (a file's ``"text": "..."`` is
the content of the file of ``examples/`` it names)."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest

from crankbalance.studies.registry import STUDIES
from crankbalance.web import api

from .conftest import hang_guard

ROOT = Path(__file__).resolve().parents[1]
ROW = re.compile(r"^\| `(?P<study>[a-z0-9-]+)` \| `(?P<body>\{.*\})` \|$")


def examples() -> dict[str, dict[str, Any]]:
    """The study -> body rows of the docs' table."""
    text = (ROOT / "docs" / "web.md").read_text()
    section = text[text.index("## JSON API") :]
    section = section[: section.index("\n## ", 1)]
    found = {}
    for line in section.splitlines():
        match = ROW.match(line)
        if match:
            found[match["study"]] = json.loads(match["body"])
    return found


def _filled(value: Any) -> Any:
    if isinstance(value, dict) and value.get("text") == "...":
        return {**value, "text": (ROOT / "examples" / value["name"]).read_text()}
    if isinstance(value, list):
        return [_filled(item) for item in value]
    return value


def test_every_study_has_an_example() -> None:
    assert set(examples()) == set(STUDIES)


@pytest.mark.parametrize("study", sorted(STUDIES))
def test_the_example_answers(study: str) -> None:
    body = {key: _filled(value) for key, value in examples()[study].items()}
    with hang_guard(300):
        status, answer = api.compute_study(study, json.dumps(body).encode(), "application/json")
    assert status == 200, answer
    assert answer["schema"].startswith("crankbalance.")
