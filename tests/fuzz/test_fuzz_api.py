"""Fuzzing the JSON API (issue 12, item 7): malformed bodies and headers, never a 5xx.

Deterministic hypothesis (the same examples on every run): mutations of every preset sent
to the in-process :func:`crankbalance.web.api.compute` (the function the server runs in its
worker threads), hostile headers against :func:`~crankbalance.web.api.check_request` (what
the server checks before it reads a body), and a few real HTTP requests to
``crankbalance web``. Every answer must be a 4xx with a one-line JSON error naming a field,
or a 200 whose numbers are all finite. A computation that does not end within the hang
guard fails the test (a guard against hanging, not a timing target).

The examples of the issue are named cases: each must be refused (4xx).
"""

from __future__ import annotations

import collections
import contextlib
import http.client
import json
import math
import select
import socket
import threading
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from crankbalance.io.engine_file import list_presets, preset_text
from crankbalance.web import api

from .test_fuzz_options import EXAMPLES

HANG_GUARD = 180.0  # seconds
PRESETS = list_presets()


def fuzz(examples: int) -> settings:
    """Deterministic hypothesis settings: the same ``examples`` examples on every run."""
    return settings(
        max_examples=examples,
        derandomize=True,
        database=None,
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
    )


#: values put in place of a key's value: wrong types, extremes, nonsense
HOSTILE = [
    "1e300 rpm",
    "1e-300 rpm",
    "1e308 km",
    "1e-320 mm",
    "-1 mm",
    "0 mm",
    "nan mm",
    "inf rpm",
    "5 parsec",
    "12 kg",
    "",
    " ",
    "x" * 2000,
    "4",
    int("9" * 400),
    2**63,
    -1,
    0,
    1e308,
    -0.0,
    float("nan"),
    float("inf"),
    True,
    None,
    [],
    [[[]]],
    {},
    {"a": 1},
    ["0 deg"] * 3000,
    list(range(3000)),
]
#: numbers put in place of a quantity's number (its unit kept) or of a plain number
EXTREMES = ["1e300", "1e-300", "-1e308", "1e308", "1e-320", "0", "-0", "nan", "inf", "-inf"]
#: tally of the in-process body fuzz: mutation -> Counter of answer statuses
TALLY: dict[str, collections.Counter[int]] = collections.defaultdict(collections.Counter)


@pytest.fixture(scope="module", autouse=True)
def _print_tally() -> Iterator[None]:
    yield
    for mutation, statuses in sorted(TALLY.items()):
        print(f"api fuzz {mutation}: {sum(statuses.values())} tried, statuses {dict(statuses)}")


def compute_guarded(kind: str, body: bytes, content_type: str | None) -> tuple[int, Any]:
    """``api.compute`` in a daemon thread: fails the test if it has not ended within the
    hang guard (a hung thread then does not hold the test process)."""
    out: list[tuple[int, Any]] = []
    worker = threading.Thread(
        target=lambda: out.append(api.compute(kind, body, content_type)), daemon=True
    )
    worker.start()
    worker.join(HANG_GUARD)
    assert out, f"api.compute did not end within {HANG_GUARD:g} s: {body[:200]!r}"
    return out[0]


def check_answer(status: int, data: Any, what: str) -> None:
    """A 4xx with a one-line JSON error naming a field, or a 200 with finite numbers."""
    text = json.dumps(data, allow_nan=False)  # what the server sends; NaN would raise
    if status == 200:
        assert isinstance(data, dict) and str(data.get("schema", "")).startswith("crankbalance."), (
            what,
            text[:300],
        )
        assert all(math.isfinite(x) for x in _numbers(data)), (what, text[:300])
        return
    assert 400 <= status < 500, (what, status, text[:500])
    assert set(data) == {"error", "field"}, (what, data)
    assert isinstance(data["error"], str) and data["error"], (what, data)
    assert "\n" not in data["error"], (what, data)
    assert isinstance(data["field"], str) and data["field"], (what, data)


def _numbers(value: Any) -> Iterator[float]:
    if isinstance(value, dict):
        for item in value.values():
            yield from _numbers(item)
    elif isinstance(value, list):
        for item in value:
            yield from _numbers(item)
    elif isinstance(value, float | int) and not isinstance(value, bool):
        yield float(value)


# --------------------------------------------------------------------------- bodies
def _paths(data: Any, prefix: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Every key path (dict keys and list indices) of a decoded engine file."""
    out = [prefix] if prefix else []
    if isinstance(data, dict):
        for key, value in data.items():
            out += _paths(value, (*prefix, key))
    elif isinstance(data, list):
        for index, value in enumerate(data):
            out += _paths(value, (*prefix, index))
    return out


def _get(data: Any, path: tuple[Any, ...]) -> Any:
    for part in path:
        data = data[part]
    return data


def _is_number(data: Any, path: tuple[Any, ...]) -> bool:
    """Whether the value at ``path`` is a number or a quantity ("40 mm")."""
    value = _get(data, path)
    if isinstance(value, str):
        value = value.partition(" ")[0]
    try:
        float(value)
    except (TypeError, ValueError):
        return False
    return not isinstance(value, bool)


def _replace(data: Any, path: tuple[Any, ...], value: Any) -> None:
    for part in path[:-1]:
        data = data[part]
    if value is _DELETE:
        del data[path[-1]]
    else:
        data[path[-1]] = value


_DELETE = object()


@st.composite
def mutated_body(draw: st.DrawFn) -> tuple[str, bytes, str, str]:
    """(mutation, body, Content-Type, kind) from a preset and one mutation."""
    preset = draw(st.sampled_from(PRESETS))
    text = preset_text(preset)
    kind = draw(st.sampled_from(["analyze", "balance"]))
    mutation = draw(
        st.sampled_from(
            [
                "value",
                "number extreme",
                "delete key",
                "unknown key",
                "truncate",
                "line dropped or doubled",
                "bytes inserted",
                "wrong content type",
                "deep nesting",
            ]
        )
    )
    if mutation in ("value", "number extreme", "delete key", "unknown key"):
        data = tomllib.loads(text)
        paths = _paths(data)
        if mutation == "number extreme":  # the number of a quantity or a plain number
            path = draw(st.sampled_from([p for p in paths if _is_number(data, p)]))
            unit = str(_get(data, path)).partition(" ")[2]
            number = draw(st.sampled_from(EXTREMES))
            _replace(data, path, f"{number} {unit}" if unit else float(number))
        elif mutation == "unknown key":
            table = draw(st.sampled_from([()] + [p for p in paths if isinstance(p[-1], str)]))
            target = data
            for part in table:
                target = target[part]
            if not isinstance(target, dict):
                target = data
            target[draw(st.sampled_from(["turbo", "Speed", "masses ", "throw", ""]))] = 1
        else:
            path = draw(st.sampled_from(paths))
            value = _DELETE if mutation == "delete key" else draw(st.sampled_from(HOSTILE))
            _replace(data, path, value)
        return mutation, json.dumps(data).encode(), "application/json", kind
    raw = text.encode()
    if mutation == "truncate":
        raw = raw[: draw(st.integers(0, len(raw) - 1))]
    elif mutation == "line dropped or doubled":
        lines = raw.splitlines(keepends=True)
        k = draw(st.integers(0, len(lines) - 1))
        lines[k : k + 1] = [] if draw(st.booleans()) else [lines[k], lines[k]]
        raw = b"".join(lines)
    elif mutation == "bytes inserted":
        at = draw(st.integers(0, len(raw)))
        raw = raw[:at] + draw(st.binary(min_size=1, max_size=16)) + raw[at:]
    elif mutation == "wrong content type":
        body = json.dumps(tomllib.loads(text)).encode()
        return mutation, body, "application/toml", kind  # JSON sent as TOML
    else:  # deep nesting, inside and outside the bounds of the readers
        depth = draw(st.sampled_from([10, 100, 500, 5000]))
        raw = b"a = " + b"[" * depth + b"]" * depth + b"\n" + raw
    return mutation, raw, "application/toml", kind


@fuzz(200)
@given(case=mutated_body())
def test_mutated_presets_never_give_a_5xx(case: tuple[str, bytes, str, str]) -> None:
    mutation, body, content_type, kind = case
    status, data = compute_guarded(kind, body, content_type)
    TALLY[mutation][status] += 1
    check_answer(status, data, f"{mutation}: {body[:300]!r}")


def _inline4(old: str, new: str) -> bytes:
    text = preset_text("inline4")
    assert old in text, old
    return text.replace(old, new, 1).encode()


def _custom(throws: int, banks: int) -> bytes:
    """A custom engine of ``throws`` throws carrying ``banks`` cylinders each."""
    rods = ", ".join(['"0 deg"'] * banks)
    body = "".join(
        f'[[crank_train.throw]]\nposition = "{k} mm"\nangle = "0 deg"\nbanks = [{rods}]\n'
        for k in range(throws)
    )
    return (
        'name = "x"\nspeed = "3000 rpm"\n[crank_train]\nlayout = "custom"\n'
        f'crank_radius = "40 mm"\nrod_length = "135 mm"\n{body}'
        '[masses]\nreciprocating = "1 kg"\nrotating = "1 kg"\n'
    ).encode()


def _throw_angles(count: int) -> bytes:
    """The crossplane V8 with ``count`` throw angles (it has 4 throws)."""
    angles = ", ".join(['"0 deg"'] * count)
    text = preset_text("v8-crossplane")
    return text.replace("[masses]", f"throw_angles = [{angles}]\n\n[masses]").encode()


#: the issue's API examples, each of which must be refused: name -> (kind, body, type)
ISSUE_EXAMPLES: dict[str, tuple[str, bytes, str]] = {
    "throw_angles x 20000": ("balance", _throw_angles(20000), "application/toml"),
    "throw_angles x 7000 (under the size limit)": (
        "balance",
        _throw_angles(7000),
        "application/toml",
    ),
    "one throw, 15000 banks": ("balance", _custom(1, 15000), "application/toml"),
    "one throw, 7000 banks (under the size limit)": (
        "balance",
        _custom(1, 7000),
        "application/toml",
    ),
    "2500 custom throws": ("balance", _custom(2500, 1), "application/toml"),
    "800 custom throws (under the size limit)": ("balance", _custom(800, 1), "application/toml"),
    "speed 1e300 rpm": ("analyze", _inline4('"6000 rpm"', '"1e300 rpm"'), "application/toml"),
    "speed 1e-300 rpm, balance": (
        "balance",
        _inline4('"6000 rpm"', '"1e-300 rpm"'),
        "application/toml",
    ),
    "rod_length 1e308 km": ("analyze", _inline4('"145 mm"', '"1e308 km"'), "application/toml"),
    "crank_pitch 1e308 km": ("balance", _inline4('"92 mm"', '"1e308 km"'), "application/toml"),
    "TOML nested 500 deep": (
        "analyze",
        b"a = " + b"[" * 500 + b"]" * 500 + b"\n",
        "application/toml",
    ),
    "5000-digit cylinders": (
        "analyze",
        _inline4("cylinders = 4", "cylinders = " + "4" * 5000),
        "application/toml",
    ),
    "JSON duplicate key": (
        "analyze",
        b'{"speed": "1000 rpm", ' + json.dumps(tomllib.loads(preset_text("inline4"))).encode()[1:],
        "application/json",
    ),
    "cylinders = true": (
        "analyze",
        _inline4("cylinders = 4", "cylinders = true"),
        "application/toml",
    ),
    'cylinders = "4"': (
        "analyze",
        _inline4("cylinders = 4", 'cylinders = "4"'),
        "application/toml",
    ),
    "conrod_rotating_fraction = true": (
        "analyze",
        _inline4("conrod_rotating_fraction = 0.67", "conrod_rotating_fraction = true"),
        "application/toml",
    ),
    "text/plain body": ("analyze", preset_text("inline4").encode(), "text/plain"),
    "no Content-Type": ("analyze", preset_text("inline4").encode(), ""),
    "binary body": ("analyze", bytes(range(256)) * 4, "application/toml"),
    "body of 1 MB": ("analyze", b"#" * 1_000_000, "application/toml"),
}


@pytest.mark.parametrize("name", list(ISSUE_EXAMPLES))
def test_issue_examples_are_refused(name: str) -> None:
    kind, body, content_type = ISSUE_EXAMPLES[name]
    status, data = compute_guarded(kind, body, content_type or None)
    check_answer(status, data, name)
    assert status != 200, f"{name} must be refused, got {json.dumps(data)[:300]}"


# --------------------------------------------------------------------------- headers
OWN = "127.0.0.1:8080"
HEADER_VALUES = {
    "host": [OWN, "localhost:8080", "[::1]:8080", "evil.example", "", "[", "127.0.0.1.evil:80"],
    "origin": [f"http://{OWN}", "http://evil.example", "null", "", "http://[", "file://"],
    "sec-fetch-site": ["same-origin", "none", "same-site", "cross-site", "", "x"],
    "referer": [f"http://{OWN}/", "http://evil.example/", "", "::", "http://["],
    "content-type": [
        "application/json",
        "APPLICATION/TOML; charset=utf-8",
        "text/plain",
        "application/x-www-form-urlencoded",
        "multipart/form-data; boundary=x",
        "",
        ";",
        "application/json+toml",
    ],
    "content-length": ["0", "10", str(api.MAX_BODY + 1), "-1", "1e3", "١٢", "9" * 40, ""],
}


@st.composite
def header_sets(draw: st.DrawFn) -> dict[str, str]:
    names = draw(st.sets(st.sampled_from(sorted(HEADER_VALUES))))
    headers = {  # this machine's value half of the time, so the later checks are reached
        name: draw(st.sampled_from(HEADER_VALUES[name][:1] * 6 + HEADER_VALUES[name]))
        for name in names
    }
    if draw(st.booleans()):
        headers[draw(st.sampled_from(sorted(HEADER_VALUES)))] = draw(
            st.text(max_size=40)
        )  # any text at all
    return headers


@fuzz(300)
@given(headers=header_sets())
def test_hostile_headers_are_refused_with_a_4xx(headers: dict[str, str]) -> None:
    """check_request either lets a request through to the body or refuses it with a 4xx
    naming the header; it never fails otherwise."""
    try:
        fmt = api.check_request(headers)
    except api.Refused as refused:
        assert 400 <= refused.status < 500
        assert refused.field in (
            "Host",
            "Origin",
            "Sec-Fetch-Site",
            "Referer",
            "Content-Type",
            "Content-Length",
            "request body",
        )
        TALLY["headers (in-process)"][refused.status] += 1
        return
    TALLY["headers (in-process)"][200] += 1
    assert fmt in ("json", "toml")
    assert headers.get("host") in HEADER_VALUES["host"][:3]  # this machine
    origin = headers.get("origin")
    assert origin is None or origin == f"http://{headers['host']}".lower()


# --------------------------------------------------------------------------- over HTTP
@pytest.fixture(scope="module")
def logged_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[str, Path]]:
    """``crankbalance web`` in a subprocess with its log in a file (as tests/web/conftest.py's
    fixture of that name); its URL and the log's path. The log must never hold a traceback."""
    pytest.importorskip("nicegui")
    from crankbalance.web.server import running_server

    path = tmp_path_factory.mktemp("server") / "server.log"
    with open(path, "w") as log, running_server(log, timeout=HANG_GUARD) as url:
        yield url, path
    assert "Traceback" not in path.read_text(), path.read_text()[-3000:]


@pytest.fixture(scope="module")
def server(logged_server: tuple[str, Path]) -> str:
    return logged_server[0]


@fuzz(30)
@given(
    headers=st.fixed_dictionaries(
        {},
        optional={
            "Origin": st.sampled_from(["SERVER", "http://evil.example", "null"]),
            "Sec-Fetch-Site": st.sampled_from(["same-origin", "cross-site", "none"]),
            "Content-Type": st.sampled_from(
                ["application/toml", "application/json", "text/plain", "text/x-toml"]
            ),
        },
    ),
    body=st.sampled_from([b"inline4", b"", b"[crank_train", b"\xff\xfe", b"x" * 70_000]),
    path=st.sampled_from(["/api/analyze", "/api/balance"]),
)
def test_over_http_never_a_5xx(
    server: str, headers: dict[str, str], body: bytes, path: str
) -> None:
    parts = urlsplit(server)
    headers = {k: v.replace("SERVER", server) for k, v in headers.items()}
    connection = http.client.HTTPConnection(parts.hostname or "", parts.port, timeout=HANG_GUARD)
    try:
        connection.request("POST", path, body=body, headers=headers)
        response = connection.getresponse()
        status, data = response.status, json.loads(response.read())
    finally:
        connection.close()
    TALLY["over HTTP"][status] += 1
    check_answer(status, data, f"{headers} {body[:40]!r}")


# --------------------------------------------------------------------------- raw HTTP
#: how a body is sent over a raw socket: those after which the server must answer, and
#: those of a broken framing or a client that goes away (an answer, a close, or nothing)
ANSWERED = ["whole", "byte-order mark", "chunked", "chunked without end"]
FRAMING = [
    "cut short, closed",
    "cut short, half-closed",
    "longer than its length",
    "length written oddly",
    "two lengths",
    "length and chunked",
    "chunk size malformed",
]
BOM = b"\xef\xbb\xbf"
#: what a byte-order mark may be put as: UTF-8's (read as the command line reads it), twice,
#: UTF-16's, in the middle of the body
MARKS = [BOM, BOM, BOM + BOM, b"\xff\xfe", b"\xfe\xff"]


def _head(port: int, path: str, content_type: str, framing: list[str]) -> bytes:
    lines = [f"POST {path} HTTP/1.1", f"Host: 127.0.0.1:{port}", f"Content-Type: {content_type}"]
    return ("\r\n".join([*lines, *framing]) + "\r\n\r\n").encode()


def _chunks(body: bytes, sizes: list[int]) -> bytes:
    """``body`` in chunks of the ``sizes`` (cycled), then the last chunk."""
    out, at, k = b"", 0, 0
    while at < len(body):
        piece = body[at : at + sizes[k % len(sizes)]]
        out += b"%x\r\n%s\r\n" % (len(piece), piece)
        at, k = at + len(piece), k + 1
    return out + b"0\r\n\r\n"


def _response(connection: socket.socket) -> tuple[int, bytes, str] | None:
    """The server's answer (status, body, content type), or None when it closed the
    connection without one."""
    response = http.client.HTTPResponse(connection)
    try:
        response.begin()
    except (http.client.RemoteDisconnected, ConnectionResetError):
        return None
    return response.status, response.read(), response.getheader("content-type") or ""


@pytest.mark.parametrize("how", ANSWERED + FRAMING)
@fuzz(EXAMPLES)  # per way of sending (CRANKBALANCE_FUZZ_EXAMPLES, default 10)
@given(
    case=mutated_body(),
    mark=st.sampled_from(MARKS),
    sizes=st.lists(st.integers(1, 5000), min_size=1, max_size=4),
    cut=st.integers(1, 1000),
)
def test_raw_http_bodies(
    logged_server: tuple[str, Path],
    how: str,
    case: tuple[str, bytes, str, str],
    mark: bytes,
    sizes: list[int],
    cut: int,
) -> None:
    """A mutated preset sent over a raw socket whole, with a byte-order mark, chunked, as a
    chunked body that never ends, cut short of its length (then closed or half-closed),
    longer than its length, with odd or conflicting lengths, with malformed chunks. The
    server answers a 4xx with a JSON error or a 200 with finite numbers, never a 5xx; where
    the framing itself is broken, the server's HTTP layer may answer a 4xx of its own (text)
    or close the connection; a client that goes away gets nothing. No traceback in the
    server's log (checked when the module ends)."""
    url, _log = logged_server
    mutation, body, content_type, kind = case
    port = urlsplit(url).port or 0
    path = f"/api/{kind}"
    if how == "byte-order mark":
        body = mark + body if mark != BOM + BOM or not body else body[:cut] + BOM + body[cut:]
    framing = [f"Content-Length: {len(body)}"]
    payload = body
    if how in ("chunked", "chunked without end", "chunk size malformed"):
        framing = ["Transfer-Encoding: chunked"]
        payload = _chunks(body, sizes)
        if how == "chunk size malformed":
            payload = payload.replace(b"\r\n", b"zz\r\n", 1)
    elif how.startswith("cut short"):
        framing = [f"Content-Length: {len(body) + cut}"]
    elif how == "longer than its length":
        framing = [f"Content-Length: {max(len(body) - cut, 0)}"]
    elif how == "length written oddly":
        written = [f"+{len(body)}", f" {len(body)} ", f"{len(body)}, {len(body)}", "0x10", "-1"]
        framing = [f"Content-Length: {written[cut % len(written)]}"]
    elif how == "two lengths":
        framing = [f"Content-Length: {len(body)}", f"Content-Length: {len(body) + cut}"]
    elif how == "length and chunked":
        framing = [f"Content-Length: {len(body)}", "Transfer-Encoding: chunked"]
    with socket.create_connection(("127.0.0.1", port), timeout=HANG_GUARD) as connection:
        connection.sendall(_head(port, path, content_type, framing))
        if how == "chunked without end":  # chunks until the server answers (413)
            chunk = b"400\r\n" + b"#" * 1024 + b"\r\n"
            for _ in range(64 * api.MAX_BODY // 1024):
                if select.select([connection], [], [], 0)[0]:
                    break
                try:
                    connection.sendall(chunk)
                except (BrokenPipeError, ConnectionResetError):
                    break
            else:
                raise AssertionError(f"no answer after {64 * api.MAX_BODY} bytes of chunks")
        else:
            with contextlib.suppress(BrokenPipeError, ConnectionResetError):
                connection.sendall(payload)
        if how == "cut short, closed":
            TALLY[f"raw HTTP {how}"][0] += 1
            return  # nothing to read: the client went away (one line in the log)
        if how == "cut short, half-closed":
            connection.shutdown(socket.SHUT_WR)
        answer = _response(connection)
    what = f"{how}, {mutation}: {framing} {payload[:200]!r}"
    if answer is None:
        assert how in FRAMING, f"closed without an answer: {what}"
        TALLY[f"raw HTTP {how}"][0] += 1
        return
    status, data, media = answer
    TALLY[f"raw HTTP {how}"][status] += 1
    assert status < 500, (status, data[:300], what)
    if how in FRAMING and "json" not in media:
        assert 400 <= status < 500, (status, data[:300], what)  # the HTTP layer's own answer
        return
    check_answer(status, json.loads(data), what)
    if how == "chunked without end":
        assert status == 413, (status, data[:300])


def test_a_body_that_stops_is_answered_408(logged_server: tuple[str, Path]) -> None:
    """Found by this fuzzing: a client that sent part of its body and then nothing more
    (its connection open) was never answered, the connection held without end; the server
    now answers 408 once :data:`crankbalance.web.api.BODY_TIMEOUT` has passed (a wait for
    the answer, under the hang guard) and closes the connection. A body with a length and
    a chunked one, sent side by side."""
    url, _log = logged_server
    port = urlsplit(url).port or 0
    partial = {
        "Content-Length: 5000": b"x" * 100,
        "Transfer-Encoding: chunked": b"5\r\nhello\r\n",
    }
    with contextlib.ExitStack() as stack:
        connections = []
        for framing, part in partial.items():
            connection = socket.create_connection(("127.0.0.1", port), timeout=HANG_GUARD)
            stack.enter_context(connection)
            connection.sendall(_head(port, "/api/analyze", "application/toml", [framing]) + part)
            connections.append(connection)
        for connection in connections:
            answer = _response(connection)
            assert answer is not None
            status, data, _media = answer
            assert status == 408, data
            error = json.loads(data)
            assert error["field"] == "request body"
            assert f"within {api.BODY_TIMEOUT:g} s" in error["error"], error
            assert connection.recv(1) == b""  # then closed by the server
