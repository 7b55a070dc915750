"""The JSON API's guards (issue 12): 403 for a foreign page, 415 for a body type a foreign
page could send without asking, 413 before a large body is read, 422 for bad input and
work over the budget, 503 past the wall-clock cap, and other users answered while one
request computes. Real HTTP against ``crankbalance web`` where the server's own handling
counts (Content-Length, chunked bodies, headers), in-process where a computation must be
held (threads and events, no timing)."""

from __future__ import annotations

import http.client
import json
import threading
from collections.abc import Iterator
from typing import Any
from urllib.parse import urlsplit

import anyio
import httpx
import pytest

from crankbalance.io.engine_file import preset_text
from crankbalance.web import api

TOML = {"Content-Type": "application/toml"}


def post(
    server: str, body: bytes | Iterator[bytes], headers: dict[str, str], path: str = "/api/analyze"
) -> tuple[int, dict[str, Any]]:
    """POST over a fresh connection; (status, JSON answer)."""
    parts = urlsplit(server)
    connection = http.client.HTTPConnection(parts.hostname or "", parts.port, timeout=180)
    try:
        chunked = not isinstance(body, bytes)
        connection.request("POST", path, body=body, headers=headers, encode_chunked=chunked)
        response = connection.getresponse()
        return response.status, json.loads(response.read())
    finally:
        connection.close()


def test_body_over_the_limit_is_413_from_its_length_before_it_is_sent(server: str) -> None:
    parts = urlsplit(server)
    connection = http.client.HTTPConnection(parts.hostname or "", parts.port, timeout=180)
    try:
        connection.putrequest("POST", "/api/balance")
        connection.putheader("Content-Type", "application/toml")
        connection.putheader("Content-Length", str(10**9))
        connection.endheaders()  # headers only: the server must answer without the body
        response = connection.getresponse()
        answer = json.loads(response.read())
    finally:
        connection.close()
    assert response.status == 413, answer
    assert answer["field"] == "request body" and str(api.MAX_BODY) in answer["error"]


def test_body_without_a_length_is_cut_at_the_limit(server: str) -> None:
    chunks = (b"# " + b"x" * 1021 + b"\n" for _ in range(api.MAX_BODY // 1024 + 1))
    status, answer = post(server, chunks, TOML)
    assert status == 413 and answer["field"] == "request body", answer


@pytest.mark.parametrize(
    "content_type",
    [None, "text/plain", "application/x-www-form-urlencoded", "multipart/form-data; b=x"],
)
def test_a_body_a_foreign_page_could_send_unasked_is_415(server: str, content_type) -> None:
    headers = {} if content_type is None else {"Content-Type": content_type}
    status, answer = post(server, preset_text("inline4").encode(), headers)
    assert status == 415, answer
    assert answer["field"] == "Content-Type" and "application/toml" in answer["error"]


@pytest.mark.parametrize(
    "headers",
    [
        {"Origin": "http://evil.example"},
        {"Origin": "null"},
        {"Origin": "http://127.0.0.1:1"},  # another server of this machine
        {"Sec-Fetch-Site": "cross-site"},
        {"Sec-Fetch-Site": "same-site"},
        {"Referer": "http://evil.example/page.html"},
        {"Host": "evil.example"},  # a DNS-rebinding page: its own name, this address
    ],
)
def test_a_foreign_page_is_403(server: str, headers: dict[str, str]) -> None:
    status, answer = post(server, preset_text("inline4").encode(), {**TOML, **headers})
    assert status == 403, answer
    assert answer["field"] == next(iter(headers)), answer


@pytest.mark.parametrize(
    "headers",
    [
        {},  # curl, urllib, scripts
        {"Origin": "SERVER", "Sec-Fetch-Site": "same-origin"},  # the server's own page
        {"Referer": "SERVER/?preset=inline4"},
        {"Sec-Fetch-Site": "none"},  # typed in the address bar
    ],
)
def test_own_pages_and_scripts_are_served(server: str, headers: dict[str, str]) -> None:
    headers = {k: v.replace("SERVER", server) for k, v in headers.items()}
    status, answer = post(server, preset_text("v6-60").encode(), {**TOML, **headers})
    assert status == 200, answer
    assert answer["schema"] == "crankbalance.analysis/4" and answer["engine"]["cylinders"] == 6


def test_json_body_and_preset_name(server: str) -> None:
    body = json.dumps({"name": "x", **_file_dict("inline4")}).encode()
    status, answer = post(server, body, {"Content-Type": "application/json; charset=utf-8"})
    assert status == 200 and answer["engine"]["cylinders"] == 4, answer
    status, answer = post(server, b"boxer4\n", TOML, "/api/balance")
    assert status == 200 and answer["schema"] == "crankbalance.balance/2", answer


def test_bad_input_is_a_422_naming_the_field(server: str) -> None:
    status, answer = post(server, b'speed = "2000 kg"', TOML)
    assert status == 422
    assert answer["field"] == "speed" and "rotational speed" in answer["error"]


def test_work_over_the_budget_is_refused_before_computing(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The V12 (12 cylinders on 6 throws) is (12 + 6) x 8 orders = 144 work units: computed
    with a budget of 144, refused with one of 143 (the engine file's own caps keep every
    valid engine far below the real budget, so the budget is lowered here)."""
    body = preset_text("v12-60").encode()
    monkeypatch.setattr(api, "MAX_WORK", 144)
    status, answer = api.compute("analyze", body, "application/toml")
    assert status == 200 and answer["engine"]["cylinders"] == 12, answer
    monkeypatch.setattr(api, "MAX_WORK", 143)
    status, answer = api.compute("analyze", body, "application/toml")
    assert status == 422 and answer["field"] == "crank_train", answer
    assert "= 144 is over the API's work budget of 143" in answer["error"]


def _file_dict(preset: str) -> dict[str, Any]:
    import tomllib

    data = tomllib.loads(preset_text(preset))
    data.pop("name")
    return data


# --------------------------------------------------------------------------- in-process
def _client(held: Any, monkeypatch: pytest.MonkeyPatch) -> httpx.AsyncClient:
    """The API routes on a bare FastAPI app, ``compute`` replaced by ``held``."""
    from fastapi import FastAPI

    monkeypatch.setattr(api, "compute", held)
    app = FastAPI()
    api.register(app)
    transport = httpx.ASGITransport(app=app)
    return httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8080")


@pytest.mark.anyio
async def test_a_computing_request_does_not_hold_the_others(
    monkeypatch: pytest.MonkeyPatch, hang_guard_seconds: float
) -> None:
    """While one request computes (held in its worker thread until the test lets it go),
    /api/presets and a second computation are answered; no timing is measured."""
    started, release = threading.Event(), threading.Event()
    calls: list[str] = []

    def held(kind: str, body: bytes, content_type: str) -> tuple[int, dict[str, Any]]:
        calls.append(kind)
        if kind == "balance":
            started.set()
            if not release.wait(hang_guard_seconds):
                raise AssertionError("the held request was never let go")
        return 200, {"kind": kind}

    answers: dict[str, httpx.Response] = {}

    async def slow(http: httpx.AsyncClient) -> None:
        answers["balance"] = await http.post("/api/balance", content=b"inline4", headers=TOML)

    async with _client(held, monkeypatch) as http, anyio.create_task_group() as tasks:
        tasks.start_soon(slow, http)
        assert await anyio.to_thread.run_sync(started.wait, hang_guard_seconds)
        with anyio.fail_after(hang_guard_seconds):
            presets = await http.get("/api/presets")
            other = await http.post("/api/analyze", content=b"inline4", headers=TOML)
        assert "balance" not in answers, "the held request must still be computing"
        release.set()
    assert (
        presets.status_code == 200
        and {"name": "inline4", "title": "Inline-4, flat crank"} in presets.json()["presets"]
    )
    assert other.status_code == 200 and other.json() == {"kind": "analyze"}
    assert answers["balance"].status_code == 200 and calls == ["balance", "analyze"]


@pytest.mark.anyio
async def test_past_the_wall_clock_cap_the_answer_is_503(
    monkeypatch: pytest.MonkeyPatch, hang_guard_seconds: float
) -> None:
    """A computation that has not finished by WALL_CLOCK is answered 503 (it is held until
    the answer has arrived, so the outcome does not depend on the machine's speed)."""
    release = threading.Event()

    def held(kind: str, body: bytes, content_type: str) -> tuple[int, dict[str, Any]]:
        release.wait(hang_guard_seconds)
        return 200, {}

    monkeypatch.setattr(api, "WALL_CLOCK", 0.5)
    try:
        async with _client(held, monkeypatch) as http:
            with anyio.fail_after(hang_guard_seconds):
                response = await http.post("/api/analyze", content=b"inline4", headers=TOML)
    finally:
        release.set()
    assert response.status_code == 503 and "longer than 0.5 s" in response.json()["error"]
