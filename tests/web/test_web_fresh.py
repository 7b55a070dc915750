"""Never a stale number (issue 28, item 2), with NiceGUI's simulated user: the Masses tab's
resulting masses, the Crank loads and Balance shop tabs while the form is invalid; the
balancing card's parts and what is left; the preset menu's "edited" entry and a preset
chosen again. The same in chromium: ``test_web_fresh_browser.py``."""

from __future__ import annotations

import pytest

pytest.importorskip("nicegui")

from nicegui.testing.user import User  # noqa: E402

from crankbalance.web.app import EDITED  # noqa: E402
from crankbalance.web.project import Project  # noqa: E402
from crankbalance.web.tab_results import balance_rows, left_lines  # noqa: E402

pytestmark = pytest.mark.anyio


@pytest.mark.parametrize("bad", ["-420 g", "abc"])
async def test_masses_hidden_while_the_form_is_invalid(user: User, form, bad: str) -> None:
    await user.open("/")
    form.open("masses")
    await form.until(lambda: form.rows("mass-table"), "the Masses tab")
    table, summary = form.element("mass-table"), form.element("mass-summary")
    note = form.find_hidden("masses-stale")
    assert table.visible and not note.visible
    form.set("field-piston", bad)
    assert form.error("field-piston")
    assert not table.visible and not summary.visible
    assert note.visible and note.text.startswith("Not computed: Piston")
    form.set("field-piston", "420 g")
    assert table.visible and summary.visible and not note.visible


async def test_loads_and_shop_say_not_computed(user: User, form) -> None:
    await user.open("/")
    for tab in ("shop", "loads"):
        form.open(tab)
        await form.until(lambda tab=tab: form.element(f"{tab}-run"), f"the {tab} tab")
    notes = [form.find_hidden(f"{tab}-stale") for tab in ("shop", "loads")]
    assert not any(note.visible for note in notes)
    radius = form.element("field-crank_radius").value
    form.set("field-crank_radius", "-3 mm")
    for note in notes:
        assert note.visible and "Not computed: Crank radius" in note.text
    form.set("field-crank_radius", radius)
    assert not any(note.visible for note in notes)


def test_balancing_card_lists_every_part_and_what_is_left() -> None:
    """The issue's split-pin case in words: each shaft's own mass (not the heaviest of the
    set), radius, phase; the counterweights' directions; what is left and its remedy."""
    b = Project.from_preset("paper-inline3").compute().study.to_dict()
    rows = balance_rows(b)
    shafts = [r for r in rows if "shaft" in r["part"]]
    # two shafts per set, two masses each, each with its own phase
    assert len(shafts) == 8
    secondary = b["secondary_shafts"]["shafts"][1]
    assert {
        "part": "Secondary shaft 2 (counter-rotating, 2×)",
        "position": "-100 mm",
        "mass": f"{secondary['masses'][0]['mass_kg'] * 1e3:.5g} g",
        "radius": "30 mm",
        "angle": "phase 150°",
    }.items() <= shafts[6].items()
    webs = [r for r in rows if r["part"].startswith("Counterweight web")]
    assert [r["angle"] for r in webs] == [
        f"{w['direction_deg']:g}°" for w in b["counterweight"]["webs"]
    ]
    assert left_lines(b)[2] == "- nothing: no free force or moment is left up to this order"
    left = left_lines(Project.from_preset("v6-60").compute().study.to_dict())
    assert left[2].startswith("- order 1 couple, forward-rotating: 1741 N·m → a balance factor")


async def test_balancing_card_on_the_page(user: User, form) -> None:
    await user.open("/?preset=v6-60")
    await form.see("What is left")
    rows = form.rows("balance-table")
    assert rows[0]["part"] == "Counterweight web 1 (throw 1)" and rows[0]["angle"] == "150°"
    assert "order 2 couple, backward-rotating" in form.text("balance-left")
    assert "Balanced for **6000 rpm**" in form.text("balance-summary")


async def test_what_is_left_names_the_form_field(user: User, form) -> None:
    """The V8 at balance factor 0: the next step names the Engine form's field, not the
    command line's option (review finding 18)."""
    await user.open("/?preset=v8-crossplane")
    await form.see("What is left")
    left = form.text("balance-left")
    assert "a balance factor of 0.5 (Balance factor 0.5; now 0)" in left, left
    assert "--balance-factor" not in left


async def test_preset_menu_says_edited_and_loads_again(user: User, form) -> None:
    await user.open("/?preset=inline4")
    menu = form.element("preset")
    assert menu.value == "inline4"
    form.set("field-speed", "3100 rpm")
    assert menu.value == EDITED.format(name="inline4")
    # typed back to the preset's value: not edited
    form.set("field-speed", Project.from_preset("inline4").texts["speed"])
    assert menu.value == "inline4"
    form.set("field-speed", "3100 rpm")
    form.set("field-name", "mine")
    assert menu.value == "inline4 (edited)"
    # the preset chosen again: loaded again, every edit gone
    form.set("preset", "inline4")
    assert form.element("field-speed").value == Project.from_preset("inline4").texts["speed"]
    assert form.element("field-name").value != "mine"
    assert menu.value == "inline4" and EDITED.format(name="inline4") not in menu.options
    # a mass mode is part of the engine too
    form.open("masses")
    await form.until(lambda: form.rows("mass-table"), "the Masses tab")
    with user:
        form.element("mass-mode").value = "totals"
    assert menu.value == "inline4 (edited)"
