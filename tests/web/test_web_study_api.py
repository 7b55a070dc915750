"""Every study over real HTTP (issue 26): ``POST /api/<study>`` of a running ``crankbalance
web`` answers the command line's ``--format json`` for the same options, a light study
computed in a worker thread and a heavy one in a worker process; a file goes with the
request; a study's settings are a JSON object. The cases and the comparison are those of
tests/test_study_contract.py, which checks every study in-process."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from crankbalance.studies.registry import STUDIES

from ..test_study_contract import CASES, api_body, cli_args, run_cli, steady
from .test_web_api import post

JSON = {"Content-Type": "application/json"}
#: (study, index of its case): light and heavy studies, a file sent with the request
OVER_HTTP = [
    ("analyze", 0),
    ("balance-factor", 1),
    ("rebalance", 1),
    ("sensitivity", 0),
    ("cycle", 2),
    ("shop-plan", 1),
    ("counterweight-optimize", 0),
]


@pytest.mark.parametrize(("name", "index"), OVER_HTTP)
def test_a_study_over_http_answers_the_command_line(
    name: str, index: int, server: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from ..test_study_contract import EXAMPLES, FILES, TABLE

    for file in FILES - {"table.csv"}:
        (tmp_path / file).write_bytes((EXAMPLES / file).read_bytes())
    (tmp_path / "table.csv").write_text(TABLE)
    monkeypatch.chdir(tmp_path)
    engine, options = CASES[name][index]
    assert STUDIES[name].heavy == (name in ("sensitivity", "cycle", "counterweight-optimize"))
    status, answer = post(server, api_body(name, engine, options), JSON, f"/api/{name}")
    assert status == 200, answer
    assert steady(answer) == steady(run_cli(cli_args(name, engine, options)))


@pytest.mark.parametrize(
    ("path", "body", "headers", "status", "field"),
    [
        ("/api/friction", b"load = '25 N'", {"Content-Type": "application/toml"}, 415, None),
        ("/api/tolerance", b"[1, 2]", JSON, 422, "request body"),
        ("/api/cycle", json.dumps({"engine": "/etc/hostname"}).encode(), JSON, 422, "engine"),
        ("/api/bench", json.dumps({"kp": "1e9"}).encode(), JSON, 422, "kp"),
    ],
)
def test_a_bad_study_request_is_refused_in_one_line(
    server: str, path: str, body: bytes, headers: dict[str, str], status: int, field: Any
) -> None:
    got, answer = post(server, body, headers, path)
    assert got == status, answer
    assert set(answer) == {"error", "field"}
    if field is not None:
        assert answer["field"] == field
