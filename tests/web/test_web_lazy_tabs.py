"""The page builds the hidden tabs only when they are first opened (issue 14, item 9: the
first load). The Engine and Results tabs (the first screen) are built with the page; every
other tab's elements do not exist until the tab is opened, and exist after, showing the
project as it is (its settings, the computed engine's numbers). A tab never opened still
keeps its settings in the project: they are loaded and saved with it.

Checked in Debian's chromium (``crankbalance web`` in a subprocess, Playwright) and with
NiceGUI's simulated user. No timings: every wait is for a state of the page.
"""

from __future__ import annotations

import json
from typing import Any

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")

from crankbalance.web.app import FIRST_SCREEN, TABS  # noqa: E402
from crankbalance.web.project import SETTINGS_TAG, Project  # noqa: E402

#: one element of each tab built on opening (its data-testid), and the tab's label
LAZY = {
    "masses": "field-piston",
    "counterweight": "setting-cw_density",
    "single": "setting-sc_grade",
    "shaft": "setting-bs_length",
    "performance": "setting-pf_journal_diameter",
    "explore": "explore-table",
    "shop": "shop-summary",
    "loads": "loads-summary",
    "mounts": "mounts-summary",
}
LABELS = dict(TABS)


def _count(page: Any, testid: str) -> int:
    return int(page.locator(f"[data-testid={testid}]").count())


def _settings_of(toml_text: str) -> dict[str, Any]:
    """The settings line of a saved project."""
    line = next(line for line in toml_text.splitlines() if line.startswith(SETTINGS_TAG))
    return dict(json.loads(line[len(SETTINGS_TAG) :]))


def test_hidden_tabs_are_built_when_first_opened(server: str, page: Any) -> None:
    """Before a tab is opened its elements are not in the page; after, they are, with the
    project's values; the first screen is there at once."""
    assert set(LAZY) | set(FIRST_SCREEN) == set(LABELS), "every tab is checked"
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    response = page.goto(f"{server}/?preset=v8-crossplane")
    served = response.text()  # the page as the server sends it: every element it holds
    playwright_api.expect(page.locator(".q-header")).to_contain_text("Results of:")
    assert "field-crank_radius" in served, "the Engine tab is built with the page"
    assert _count(page, "field-crank_radius") == 1
    for name, testid in LAZY.items():
        assert testid not in served, f"the {name} tab is not built before it is opened"
        assert f"{name}-opening" in served, f"the {name} tab's panel says it is opening"
        assert _count(page, testid) == 0
    for name, testid in LAZY.items():
        page.get_by_role("tab", name=LABELS[name]).click()
        playwright_api.expect(page.locator(f"[data-testid={testid}]").first).to_be_attached()
        assert _count(page, f"{name}-opening") == 0, f"the {name} tab's placeholder is gone"
    # the Masses tab shows the form's values; a field typed there is checked like any other
    project = Project.from_preset("v8-crossplane")
    page.get_by_role("tab", name=LABELS["masses"]).click()
    piston = page.locator("[data-testid=field-piston]").first
    playwright_api.expect(piston).to_have_value(project.texts["piston"])
    piston.fill("not a mass")
    playwright_api.expect(page.locator("[data-testid=status]").first).to_contain_text(
        "Not computed: see Piston"
    )
    piston.fill(project.texts["piston"])
    playwright_api.expect(page.locator(".q-header")).to_contain_text("Results of:")
    # the tabs opened show the project: the counterweight tab its setting and requirement
    page.get_by_role("tab", name=LABELS["counterweight"]).click()
    density = page.locator("[data-testid=setting-cw_density]").first
    playwright_api.expect(density).to_have_value("8000 kg/m^3")
    playwright_api.expect(page.locator(".q-tab-panel:visible").first).to_contain_text(
        "Required first moment"
    )
    assert not errors, errors


def test_settings_of_a_tab_never_opened_survive_load_and_save(
    server: str, page: Any, tmp_path: Any
) -> None:
    """A project whose counterweight and balance-shaft settings differ from the defaults is
    uploaded and saved again without those tabs ever being opened: the saved file keeps
    them; opened afterwards, the tabs show them."""
    project = Project.from_preset("v8-crossplane")
    project.settings.update({"cw_density": "7800 kg/m^3", "bs_length": "280 mm"})
    text = project.to_toml()
    page.goto(f"{server}/?preset=inline4")
    playwright_api.expect(page.locator(".q-header")).to_contain_text("Results of:")
    page.get_by_text("Load a project file").click()
    page.locator("input[type=file]").set_input_files(
        files=[{"name": "v8.toml", "mimeType": "application/toml", "buffer": text.encode()}]
    )
    playwright_api.expect(page.locator(".q-header")).to_contain_text(
        f"Results of: {project.spec.name if project.spec else ''}"
    )
    assert _count(page, "setting-cw_density") == 0, "the counterweight tab is not opened"
    with page.expect_download() as info:
        page.get_by_role("button", name="Save TOML").click()
    path = tmp_path / "saved.toml"
    info.value.save_as(path)
    saved = _settings_of(path.read_text(encoding="utf-8"))
    assert saved["cw_density"] == "7800 kg/m^3", saved
    assert saved["bs_length"] == "280 mm", saved
    assert _count(page, "setting-cw_density") == 0, "saving does not build the tab"
    page.get_by_role("tab", name=LABELS["counterweight"]).click()
    density = page.locator("[data-testid=setting-cw_density]").first
    playwright_api.expect(density).to_have_value("7800 kg/m^3")
    page.get_by_role("tab", name=LABELS["shaft"]).click()
    length = page.locator("[data-testid=setting-bs_length]").first
    playwright_api.expect(length).to_have_value("280 mm")
