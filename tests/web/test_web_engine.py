"""Web app, Engine / Masses / Results tabs through NiceGUI's simulated User.

The paper's inline-3 typed into the form must give Table 2 of the 2021 paper on the
Results tab: counterweight 1.2413 kg, primary shaft 0.4884 kg, secondary 0.0362 kg.
"""

from __future__ import annotations

import json

import pytest
from nicegui.testing.user import User

from crankbalance.studies.engine import analyze

pytestmark = pytest.mark.anyio

PAPER_ENGINE = {  # Table 1 of the 2021 paper (docs/references.md restores the lost column)
    "field-layout": "inline",
    "field-cylinders": "3",
    "field-bank_angle": "",
    "field-firing_order": "1, 3, 2",
    "field-crank_radius": "40 mm",
    "field-rod_length": "135 mm",
    "field-crank_pitch": "90 mm",
    "field-speed": "2000 rpm",
    "field-kinematics": "first-order",
    "field-cw_webs": "1, 1, 0, 0, 1, 1",
    "field-cw_cg_radius": "30 mm",
    "field-cw_angle": "30 deg",
    "field-primary_arrangement": "pair",
    "field-primary_cg_radius": "30 mm",
    "field-primary_length": "200 mm",
    "field-secondary_arrangement": "pair",
    "field-secondary_cg_radius": "30 mm",
    "field-secondary_length": "200 mm",
}
PAPER_MASSES = {
    "field-piston": "500 g",
    "field-wrist_pin": "240 g",
    "field-conrod": "600 g",
    "field-conrod_cg_from_big_end": "45 mm",
    "field-crankpin": "400 g",
    "field-crank_web": "1800 g",
    "field-crank_web_cg_radius": "15 mm",
}


async def test_paper_inline3_typed_in_gives_table2(user: User, form) -> None:
    await user.open("/?preset=v8-crossplane")  # start from another engine
    await form.see("V8 90 deg, crossplane crank")
    for marker, value in PAPER_ENGINE.items():
        form.set(marker, value)
    user.find("Next").click()  # the Engine tab's Next leads to Masses
    with user:
        form.element("conrod-split").value = "cg"
    for marker, value in PAPER_MASSES.items():
        form.set(marker, value)
    errors = {k: v.error for k, v in form.page_inputs().items() if v.error}
    assert not errors, errors
    user.find(marker="compute").click()
    await form.see("What is left")
    masses = {row["part"].split(" (")[0]: row["mass"] for row in form.rows("balance-table")}
    # 2021 paper Table 2: counterweight 1.2413 kg, primary shaft 0.4884 kg, secondary 0.0362 kg
    assert masses["Counterweight web 1"] == "1241.3 g", masses
    assert masses["Primary shaft 1"] == masses["Primary shaft 2"] == "488.44 g", masses
    assert masses["Secondary shaft 1"] == masses["Secondary shaft 2"] == "36.181 g", masses


async def test_masses_shown_as_you_type(user: User, form) -> None:
    await user.open("/")
    form.open("masses")
    before = form.text("mass-summary")
    # paper inline-3: m_rec = 0.5 + 0.24 + 0.6/3 = 0.94 kg (2021 paper Table 1)
    assert "0.9400 kg" in before, before
    form.set("field-piston", "600 g")
    after = form.text("mass-summary")
    assert "1.0400 kg" in after, after
    rows = form.rows("mass-table")
    assert len(rows) == 3 and rows[0]["reciprocating"] == "1.0400"


async def test_results_table_matches_api(user: User, form) -> None:
    await user.open("/?preset=v8-crossplane")
    rows = form.rows("orders-table")
    api = analyze("v8-crossplane").to_dict()
    assert len(rows) == 8
    for row, ref in zip(rows, api["free_moments"], strict=True):
        assert abs(float(row["moment"]) - ref["amplitude_Nm"]) <= 1e-4 * max(
            1.0, ref["amplitude_Nm"]
        ), (row, ref)
    form.set("setting-orders", "4")
    assert len(form.rows("orders-table")) == 4
    assert list(form.element("polar-order").options) == ["rotating", "1", "2", "3", "4"]
    form.set("setting-orders", "12")
    assert list(form.element("polar-order").options)[-1] == "12", "polar menu follows the orders"


async def test_totals_mode_and_layout_change(user: User, form) -> None:
    await user.open("/")
    form.open("masses")
    with user:
        form.element("mass-mode").value = "totals"
    assert form.error("field-reciprocating"), "totals mode without totals must say so"
    form.set("field-reciprocating", "1 kg")
    form.set("field-rotating", "2 kg")
    assert form.error("field-reciprocating") is None and form.error("field-rotating") is None
    assert "1.0000 kg" in form.text("mass-summary")
    form.set("field-layout", "vee")
    assert "even number" in (form.error("field-cylinders") or ""), "3 cylinders in a vee"
    form.set("field-cylinders", "8")
    assert "Bank angle" in (form.error("field-bank_angle") or ""), "a vee needs its bank angle"
    form.set("field-bank_angle", "90 deg")
    form.set("field-cw_webs", "")
    form.set("field-firing_order", "1, 5, 4, 8, 6, 3, 7, 2")  # the crossplane V8
    errors = {k: v.error for k, v in form.page_inputs().items() if v.error}
    assert not errors, errors
    assert len(form.rows("mass-table")) == 8


async def test_downloads_are_the_api_numbers(user: User, form) -> None:
    await user.open("/")
    data = json.loads(await form.download("download-balance"))
    assert data["schema"] == "crankbalance.balance/2"
    assert abs(data["counterweight"]["mass_kg"] - 1.2413) < 1e-4, "2021 paper Table 2"
    data = json.loads(await form.download("download-analysis"))
    assert data["schema"] == "crankbalance.analysis/4"
    text = (await form.download("download-orders-csv")).decode()
    assert text.splitlines()[0].startswith("trace,point,x,y")
    data = json.loads(await form.download("download-curves-json"))
    assert data["schema"] == "crankbalance.figure-data/1" and data["traces"]


async def test_next_back_and_tabs(user: User, form) -> None:
    await user.open("/")
    panels = form.element("tab-engine").parent_slot.parent  # the ui.tabs
    assert panels.value == "engine"
    user.find(marker="next-engine").click()
    assert panels.value == "masses"
    user.find(marker="back-masses").click()
    assert panels.value == "engine"


async def test_unknown_preset_in_url_is_reported(user: User, form) -> None:
    await user.open("/?preset=no-such-engine")
    assert "no-such-engine" in form.text("general-error")
    await form.see("Inline-3, Table 1")


async def test_results_start_on_the_quantity_that_is_not_zero(user: User, form) -> None:
    """Inline-3: every free force is zero (2021 paper, Table 2 has no force to balance),
    so the curves and polar diagram start on the moment; an inline-4 (free 2nd-order
    force) starts on the force, also after switching presets."""
    await user.open("/?preset=paper-inline3")
    await form.see("Inline-3, Table 1")
    assert form.element("curve-quantity").value == "moment"
    user.find(marker="tab-results").click()
    await form.until(lambda: "title" in form.element("figure-polar").figure["layout"])
    title = str(form.element("figure-polar").figure["layout"]["title"]["text"])
    assert title.startswith("Order 1 moment: amplitude 257.1 N·m"), title
    form.set("preset", "inline4")
    assert form.element("curve-quantity").value == "force"
    form.set("preset", "paper-inline3")
    assert form.element("curve-quantity").value == "moment"
