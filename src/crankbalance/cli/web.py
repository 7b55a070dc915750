"""``crankbalance web``: serve the web application on 127.0.0.1."""

from __future__ import annotations

import click

from ..errors import InputError
from ._common import require_extra


@click.command()
@click.option(
    "--port",
    type=click.IntRange(1, 65535),
    default=8080,
    show_default=True,
    help="TCP port on 127.0.0.1.",
)
@click.option(
    "--preset",
    default="paper-inline3",
    show_default=True,
    help="Engine loaded when a page opens without ?preset=NAME.",
)
@click.option("--show/--no-show", default=False, show_default=True, help="Open a browser window.")
def web(port: int, preset: str, show: bool) -> None:
    """Serve the web application (NiceGUI) on http://127.0.0.1:PORT.

    Each browser tab keeps its own project; ``/?preset=v8-crossplane`` opens a preset.
    """
    from ..io.engine_file import list_presets

    if preset not in list_presets():
        raise InputError("--preset", preset, "unknown preset; `crankbalance presets` lists them")
    import importlib.util

    from ..web.startup import import_nicegui

    try:
        import_nicegui()  # first, without the socket.io clients (web/startup.py)
    except ImportError:
        pass  # said by require_extra below
    # kaleido is looked for, not imported: the server imports it when a PDF is asked for
    require_extra("web", "nicegui", "plotly")
    if importlib.util.find_spec("kaleido") is None:
        require_extra("web", "kaleido")
    from ..web.server import serve

    serve(port=port, preset=preset, show=show)
