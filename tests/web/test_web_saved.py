"""A saved file holds only what describes the current engine (issue 28, item 2), in
chromium: the V6 90 deg preset saved as loaded keeps its description and crank pitch; made
custom throws in the crank editor, it is saved with neither (the throws carry their
positions, and the preset's words no longer describe the engine); the file computes as the
page does.

Every wait is a wait for a state of the page (the hang guard of ``conftest.py``).
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

from crankbalance.io.engine_file import load_engine  # noqa: E402
from crankbalance.studies.engine import analyze  # noqa: E402

from .test_web_fresh_browser import current  # noqa: E402


def _save(page: Any, path: Path) -> dict[str, Any]:
    with page.expect_download() as info:
        page.get_by_role("button", name="Save TOML").click()
    info.value.save_as(path)
    return tomllib.loads(path.read_text())


def test_saved_file_drops_what_no_longer_describes_the_engine(
    server: str, page, tmp_path: Path
) -> None:
    page.set_viewport_size({"width": 1280, "height": 800})
    page.goto(server + "/?preset=v6-90")
    current(page)
    loaded = _save(page, tmp_path / "v6-90.toml")
    assert loaded["description"] == load_engine("v6-90").description
    assert "crank_pitch" in loaded["crank_train"]
    page.locator("[data-testid=editor-make-custom]").first.click()
    expect(page.locator("[data-testid=field-layout]").first).to_contain_text("custom")
    expect(page.locator("[data-testid=field-crank_pitch]").first).to_have_value("")
    current(page)
    path = tmp_path / "v6-custom.toml"
    custom = _save(page, path)
    assert custom["crank_train"]["layout"] == "custom"
    assert "crank_pitch" not in custom["crank_train"]
    assert "description" not in custom
    assert len(custom["crank_train"]["throw"]) == 3
    # the same engine: the free effects of the custom crank are the preset's
    want = analyze("v6-90").to_dict()["free_moments"]
    got = analyze(str(path)).to_dict()["free_moments"]
    for a, b in zip(got, want, strict=True):
        assert a["amplitude_Nm"] == pytest.approx(b["amplitude_Nm"], rel=1e-9, abs=1e-9)
