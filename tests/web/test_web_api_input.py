"""Issue 25, the JSON API: an engine file with a UTF-8 byte-order mark is read as the
command line reads it (``io.reading.decode_text``, the one rule), as a JSON body of
``/api/analyze`` and a TOML body of ``/api/balance``; a client that closes its connection
in the middle of its body leaves one line in the server's log, no traceback. Real HTTP
against ``crankbalance web`` in a subprocess; the log is the one the fixture captures."""

from __future__ import annotations

import json
import socket
import time
from pathlib import Path
from urllib.parse import urlsplit

from crankbalance.cli import main as cli
from crankbalance.io.engine_file import engine_to_toml, load_engine, preset_text

from .conftest import HANG_GUARD
from .test_web_api import post

BOM = b"\xef\xbb\xbf"


def test_bom_json_body_of_analyze_as_the_cli_reads_it(server: str, tmp_path: Path, capsys) -> None:
    body = json.dumps(load_engine("v8-crossplane").to_data()).encode()
    headers = {"Content-Type": "application/json"}
    status, with_bom = post(server, BOM + body, headers, "/api/analyze")
    assert status == 200, with_bom
    assert post(server, body, headers, "/api/analyze") == (200, with_bom)
    # the command line reads the same file (docs/engine_file.md: the mark is dropped)
    path = tmp_path / "engine.json"
    path.write_bytes(BOM + body)
    try:
        cli(["analyze", str(path), "--format", "json"])
    except SystemExit as exit_:
        assert not exit_.code, capsys.readouterr().err
    assert json.loads(capsys.readouterr().out) == with_bom


def test_bom_toml_body_of_balance(server: str) -> None:
    body = preset_text("inline4").encode()
    headers = {"Content-Type": "application/toml"}
    status, with_bom = post(server, BOM + body, headers, "/api/balance")
    assert status == 200, with_bom
    assert post(server, body, headers, "/api/balance") == (200, with_bom)
    # and a TOML written by crankbalance itself, with the mark
    toml = engine_to_toml(load_engine("w12")).encode()
    assert post(server, BOM + toml, headers, "/api/balance")[0] == 200


def test_binary_body_still_refused_in_one_line(server: str) -> None:
    status, answer = post(server, bytes(range(256)), {"Content-Type": "application/toml"})
    assert status == 422 and "UTF-8" in answer["error"], answer


def _closed_mid_body(url: str) -> None:
    """Send the headers of a 5000-byte body, 100 bytes of it, and close the connection."""
    port = urlsplit(url).port
    with socket.create_connection(("127.0.0.1", port), timeout=HANG_GUARD) as connection:
        connection.sendall(
            b"POST /api/analyze HTTP/1.1\r\nHost: 127.0.0.1:%d\r\n"
            b"Content-Type: application/toml\r\nContent-Length: 5000\r\n\r\n" % port + b"x" * 100
        )


def test_client_closing_mid_body_leaves_one_log_line(
    logged_server: tuple[str, Path], hang_guard_seconds: float
) -> None:
    url, log = logged_server
    before = log.read_text()
    _closed_mid_body(url)
    deadline = time.monotonic() + hang_guard_seconds  # a hang guard, not a timing
    while "closed the connection" not in log.read_text()[len(before) :]:
        assert time.monotonic() < deadline, "no log line about the closed connection; hung?"
        time.sleep(0.05)
    # a complete request after it: anything the first one would log is logged by now
    assert (
        post(url, preset_text("inline4").encode(), {"Content-Type": "application/toml"})[0] == 200
    )
    added = log.read_text()[len(before) :]
    lines = [line for line in added.splitlines() if line.strip()]
    assert len(lines) == 1, added
    assert "Traceback" not in added and "ClientDisconnect" not in added
    assert lines[0].startswith("POST /api/analyze: request body = ")
    assert "of 5000 bytes received" in lines[0]


def test_a_request_head_that_stalls_is_closed(tmp_path: Path) -> None:
    """A client that sends part of a request's head and then stalls (slowloris) is closed
    after the head deadline, with one log line; a whole request on another connection is
    answered as before. The test waits for the server to close the socket (recv returns
    b""); the socket's timeout is only the hang guard."""
    from crankbalance.web.server import running_server

    path = tmp_path / "server.log"
    with open(path, "w") as log, running_server(log, timeout=HANG_GUARD, head_timeout=1.0) as url:
        port = int(urlsplit(url).port or 0)
        with socket.create_connection(("127.0.0.1", port), timeout=HANG_GUARD) as stalled:
            stalled.sendall(b"GET /api/presets HTTP/1.1\r\nHost: 127.0.0.1\r\n")
            assert stalled.recv(100) == b""  # closed by the server, not answered
        with socket.create_connection(("127.0.0.1", port), timeout=HANG_GUARD) as whole:
            whole.sendall(b"GET /api/presets HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
            assert whole.recv(20).startswith(b"HTTP/1.1 200")
    lines = [line for line in path.read_text().splitlines() if "did not arrive" in line]
    assert len(lines) == 1 and "(44 bytes came); connection closed" in lines[0], lines
    assert "Traceback" not in path.read_text()
