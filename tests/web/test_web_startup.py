"""A fresh server's start (issue 28, item 8): NiceGUI imported without the socket.io
clients' libraries and engine.io's Tornado driver (``web/startup.py``), the worker pool's
fork server started at the first browser's connection (``server.pool_starter``).
docs/web.md, "A freshly started server"."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
import threading

import pytest

pytest.importorskip("nicegui")

from crankbalance.web import pool, server, startup  # noqa: E402

from .conftest import HANG_GUARD  # noqa: E402


def test_the_server_imports_nicegui_without_the_socketio_clients() -> None:
    held = [m for m in startup.CLIENT_MODULES if importlib.util.find_spec(m) is not None]
    if not held:
        pytest.skip(f"none of {startup.CLIENT_MODULES} is installed: nothing to hold back")
    code = (
        "import sys; import crankbalance.web.server; "
        f"print(sorted(m for m in {held!r} if m in sys.modules)); "
        f"[__import__(m) for m in {held!r}]; print('imported')"  # unmarked after
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=HANG_GUARD
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["[]", "imported"]


def test_the_pool_starts_at_the_first_connection_only(monkeypatch) -> None:
    calls: list[int] = []
    monkeypatch.setattr(pool, "warm_up", lambda: calls.append(1))
    before = set(threading.enumerate())
    on_connect = server.pool_starter()
    assert calls == []  # not before a browser connects
    for _ in range(3):
        on_connect()
    for thread in set(threading.enumerate()) - before:
        thread.join(HANG_GUARD)
    assert calls == [1]
