"""Load generator for the web server: sessions that open the page and compute engines
through the JSON API. Shared by ``tests/web/test_web_load.py`` and
``benchmarks/bench_web_load.py``; plain ``http.client``, no browser."""

from __future__ import annotations

import http.client
import json
import time
from dataclasses import dataclass, field
from typing import Any
from urllib.parse import urlsplit

from crankbalance.io.engine_file import list_presets, preset_text

#: presets cycled through by the sessions (2 to 12 cylinders, every layout)
PRESETS = [p for p in list_presets() if not p.startswith("paper")]


def engine_text(session: int, index: int) -> str:
    """A distinct engine file for each (session, index): a preset at its own speed."""
    name = PRESETS[(7 * session + index) % len(PRESETS)]
    rpm = 1000 + 37 * session + 211 * index
    lines = preset_text(name).splitlines()
    return "\n".join(f'speed = "{rpm} rpm"' if ln.startswith("speed =") else ln for ln in lines)


@dataclass
class SessionResult:
    answers: list[dict[str, Any]] = field(default_factory=list)
    times: list[float] = field(default_factory=list)  # seconds per engine
    errors: list[str] = field(default_factory=list)


def run_session(url: str, session: int, engines: int, timeout: float = 120.0) -> SessionResult:
    """One session: open the web page, then compute ``engines`` engines on its own
    connection; every answer and every error is kept."""
    out = SessionResult()
    parts = urlsplit(url)
    if not parts.hostname:
        raise ValueError(f"server url {url!r} has no host name (expected http://host:port)")
    connection = http.client.HTTPConnection(parts.hostname, parts.port, timeout=timeout)
    try:
        connection.request("GET", "/?preset=inline4")
        page = connection.getresponse()
        page.read()
        if page.status != 200:
            out.errors.append(f"session {session}: page answered {page.status}")
        for index in range(engines):
            body = engine_text(session, index).encode()
            start = time.perf_counter()
            connection.request(
                "POST", "/api/balance", body=body, headers={"Content-Type": "application/toml"}
            )
            response = connection.getresponse()
            data = response.read()
            out.times.append(time.perf_counter() - start)
            if response.status != 200:
                out.errors.append(
                    f"session {session} engine {index}: {response.status} {data[:200]!r}"
                )
                continue
            out.answers.append(json.loads(data))
    except OSError as error:
        out.errors.append(f"session {session}: {error}")
    finally:
        connection.close()
    return out
