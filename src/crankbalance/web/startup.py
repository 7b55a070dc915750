"""NiceGUI imported without the socket.io *client* libraries (a fresh server's start).

NiceGUI imports python-socketio, whose package imports its clients, and their transports
import aiohttp, requests and websocket-client when installed (each in a ``try``; the
client then says it needs them when used). The server only answers socket.io, never
connects as a client, and nothing else of the server imports them: about 0.4 s of a fresh
``crankbalance web``'s 1.4 s of NiceGUI's imports on this machine (docs/web.md, "A freshly
started server"). Likewise python-engineio imports its Tornado driver when Tornado is
installed (Jupyter brings it); NiceGUI's server runs engine.io on ASGI
(``async_mode='asgi'``), never on Tornado: about 25 ms more.
"""

from __future__ import annotations

import importlib
import sys

#: the socket.io clients' transports and engine.io's Tornado driver's library, never used by
#: the server (see the module's text)
CLIENT_MODULES = ("aiohttp", "requests", "websocket", "tornado")


def import_nicegui() -> None:
    """Import NiceGUI with :data:`CLIENT_MODULES` held back: each is marked "not
    installed" in ``sys.modules`` while NiceGUI imports, and unmarked after (a later
    ``import requests`` works as usual). Does nothing once NiceGUI is imported."""
    if "nicegui" in sys.modules:
        return
    held = [name for name in CLIENT_MODULES if name not in sys.modules]
    for name in held:
        sys.modules[name] = None  # type: ignore[assignment]  # Python's "import blocked"
    try:
        importlib.import_module("nicegui")
    finally:
        for name in held:
            if sys.modules.get(name, 0) is None:
                del sys.modules[name]
