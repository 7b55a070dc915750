"""The tabs see the page through a context: the server's default preset is passed to each
page (no module global set by the server), and no tab imports the shell."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from nicegui.testing.user_simulation import user_simulation

from crankbalance.web import app
from crankbalance.web.context import TabContext

pytestmark = pytest.mark.anyio
WEB = Path(app.__file__).parent


async def test_the_server_s_default_preset_reaches_the_page_and_its_tabs() -> None:
    default = app.DEFAULT_PRESET
    async with user_simulation(root=app.page_root("v12-60")) as user:
        await user.open("/")
        name = next(iter(user.find(marker="field-name").elements)).value
        assert "V12" in name
        await user.open("/?preset=no-such-engine")  # a bad preset: the server's default
        name = next(iter(user.find(marker="field-name").elements)).value
        assert "V12" in name
        assert (
            "loaded v12-60 instead" in next(iter(user.find(marker="general-error").elements)).text
        )
    assert app.DEFAULT_PRESET == default  # nothing was set in the module


def test_the_page_is_a_tab_context_and_no_tab_imports_the_shell() -> None:
    members = {
        name
        for name in vars(TabContext)
        if not name.startswith("_") or name in TabContext.__annotations__
    } | set(TabContext.__annotations__)
    page_members = set(dir(app.Page)) | set(app.Page.__init__.__code__.co_names)
    assert members - {"project", "default_preset", "inputs", "setting_inputs"} <= page_members
    for path in WEB.glob("*.py"):
        if path.name in ("app.py", "server.py"):
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                assert node.module not in ("app", "crankbalance.web.app"), path.name
