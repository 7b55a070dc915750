"""Issue 28 item 5, the balance shop's sheet: every drill setting the sheet prints ("Ø8 mm,
point 118°, axial, at 45 mm; depths read to the tip") is a field of the Balance shop tab,
and what is typed there is what the sheet prints (NiceGUI's simulated User)."""

from __future__ import annotations

import pytest

from crankbalance.schema.settings import ShopOptions
from crankbalance.web.tab_shop import SETTINGS

from .test_web_shop import TYPED

pytestmark = pytest.mark.anyio

#: the settings of the sheet's hole-plan line (output/shop_sheet.py: diameter, point,
#: direction, radius, depth reference) and the web's thickness the plan is checked against
PRINTED = ("hole_diameter", "point_angle", "direction", "hole_radius", "depth_to")


def test_every_printed_drill_setting_is_a_field_of_the_tab() -> None:
    for key in (*PRINTED, "web_thickness"):
        assert key in SETTINGS, key
        assert SETTINGS[key][0] == ShopOptions.FIELDS[key].title


async def test_the_sheet_prints_what_the_tab_says(user, form) -> None:
    await user.open("/?preset=v8-crossplane")
    await form.until(lambda: form.element("status").text.startswith("Results of"), "the engine")
    form.open("shop")
    user.find(marker="shop-example").click()
    for key, value in TYPED.items():
        form.set(f"shop-{key}", value)
    form.set("shop-point_angle", "90 deg")
    form.set("shop-direction", "radial")
    user.find(marker="shop-run").click()
    await form.until(lambda: "ISO 21940-11" in form.text("shop-verdict"), "the shop study")
    sheet = (await form.download("shop-sheet")).decode()
    assert "point 90°, radial, at 45 mm; depths read to the tip" in sheet, sheet[:2000]
    assert "point 118°" not in sheet
