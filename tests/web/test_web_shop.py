"""The Balance shop tab in a real browser (Playwright driving Debian's chromium): the
v8-crossplane preset, the example parts loaded, two balancing-machine readings, a run; the
bob-weights and the ISO verdict are those :mod:`crankbalance.studies.shop` computes for the
same inputs; a bad reading is named beside its field and clears the result.

Screenshots at 1280x800 and 390x844 go to ``artifacts/screenshots/`` (ignored by git).
Every wait is a wait for a state of the page with the hang guard of ``conftest.py``.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from crankbalance.output.format import text
from crankbalance.schema.settings import ShopOptions, parse_options
from crankbalance.studies.shop import shop_study

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

ROOT = Path(__file__).resolve().parents[2]
SHOTS = ROOT / "artifacts" / "screenshots"  # ignored by git
PARTS = ROOT / "examples" / "v8_parts.csv"
#: the tab's settings as typed (those of examples/v8_shop.py)
TYPED = {
    "reading_1": "12.5 g @ 40 mm, 35 deg",
    "reading_2": "8 g @ 40 mm, 200 deg",
    "measuring_planes": "0 mm, 400 mm",
    "correction_planes": "50 mm, 350 mm",
    "hole_radius": "45 mm",
    "rotor_mass": "25 kg",
    "bearings": "-20 mm, 420 mm",
}


def expected() -> tuple[list[str], str]:
    """The bob-weights and the ISO verdict's words from the study itself (the tab's
    defaults: fraction 0.5, 8 mm drill, 15 mm deepest, depth to the tip, G6.3)."""
    values = {k: v for k, v in TYPED.items() if not k.startswith("reading")}
    values["reading"] = [TYPED["reading_1"], TYPED["reading_2"]]
    options = parse_options(ShopOptions, {**values, "depth_to": "tip", "fraction": "0.5"})
    study = shop_study("v8-crossplane", PARTS, options)
    bobs = [text(w, "mass", 5) for w in study.parts.bob_weights.bob_weight]
    assert study.holes is not None
    verdict = f"ISO 21940-11 {study.holes.grade}: {'PASS' if study.holes.check.passed else 'FAIL'}"
    return bobs, verdict


def _overlap(a: dict[str, float], b: dict[str, float]) -> bool:
    """Whether two bounding boxes (Playwright's x, y, width, height) intersect."""
    apart_x = a["x"] + a["width"] <= b["x"] or b["x"] + b["width"] <= a["x"]
    apart_y = a["y"] + a["height"] <= b["y"] or b["y"] + b["height"] <= a["y"]
    return not (apart_x or apart_y)


def panel_titles_stay_apart(figure) -> None:  # type: ignore[no-untyped-def]
    """The hole plan's two panel titles, as the browser lays them out, neither intersect
    each other nor the figure's title, and lie inside the figure."""
    titles = figure.locator(".annotation-text", has_text="plane")
    expect(titles).to_have_count(2)
    boxes = [titles.nth(k).bounding_box() for k in range(2)]
    main = figure.locator(".gtitle").first.bounding_box()
    whole = figure.locator(".main-svg").first.bounding_box()
    assert None not in (*boxes, main, whole)
    assert not _overlap(boxes[0], boxes[1]), boxes
    for box in boxes:
        assert not _overlap(box, main), (box, main)
        assert whole["x"] <= box["x"] and box["x"] + box["width"] <= whole["x"] + whole["width"]
        assert whole["y"] <= box["y"]


def labels_stay_apart(figure) -> None:  # type: ignore[no-untyped-def]
    """No two texts of the hole plan (panel titles with the holes' angles, the "0° (crankpin
    1)" marks, the figure's title) intersect as the browser lays them out (review findings
    12 and 23: "213.3°" was drawn over "26.5°"), and the x axis ticks stay within ±100 mm
    for the example's 45 mm hole circle (they ran to ±250 mm)."""
    texts = figure.locator(".annotation-text, .textpoint text, .gtitle")
    boxes = [texts.nth(k).bounding_box() for k in range(texts.count())]
    assert len(boxes) >= 5 and None not in boxes, boxes
    for k, a in enumerate(boxes):
        for b in boxes[k + 1 :]:
            assert not _overlap(a, b), (a, b)
    ticks = figure.locator(".xtick text").all_text_contents()
    assert ticks and all(abs(float(t.replace("\u2212", "-"))) <= 100 for t in ticks), ticks


def open_tab(page, name: str) -> None:
    """Open a tab and wait until its panel has slid into place (a click during the slide,
    on "Load example", was lost once under load)."""
    from .test_web_screens import SETTLED

    page.get_by_role("tab", name=name, exact=True).click()
    expect(page.get_by_role("tab", name=name, exact=True)).to_have_attribute(
        "aria-selected", "true"
    )
    page.wait_for_function(SETTLED)


@pytest.mark.anyio
async def test_shop_result_cleared_when_the_engine_changes(user, form) -> None:
    """The result belongs to the engine it was run for: another rod length clears it.
    (Simulated user, before the browser tests: sync Playwright's loop would be running.)"""
    await user.open("/?preset=v8-crossplane")
    await form.until(lambda: form.element("status").text.startswith("Results of"), "the engine")
    form.open("shop")
    user.find(marker="shop-example").click()
    for key, value in TYPED.items():
        form.set(f"shop-{key}", value)
    user.find(marker="shop-run").click()
    await form.until(lambda: "ISO 21940-11" in form.text("shop-verdict"), "the shop study")
    assert len(form.rows("shop-bobweights")) == 4
    form.set("field-rod_length", "150 mm")
    await form.until(lambda: form.rows("shop-bobweights") == [], "the result cleared")
    assert "Not computed for this engine" in form.element("shop-rerun").text
    assert form.text("shop-verdict") == ""


@pytest.mark.anyio
async def test_the_example_on_an_inline_4_says_whose_parts_and_which_are_spare(user, form) -> None:
    """Review findings 12 and 28: "Load example" filled a V8's parts into any engine and the
    inline-4 ran on 4 of its 8 sets without a word. Below the parts, before the run, the tab
    names the example's V8 and says the engine takes 4 sets; the result names the spares in
    the command line's words (studies.shop.spares_words)."""
    from crankbalance.studies.shop import spares_words

    await user.open("/?preset=inline4")
    await form.until(lambda: form.element("status").text.startswith("Results of"), "the engine")
    form.open("shop")
    note = form.find_hidden("shop-fit")
    assert not note.visible  # no parts yet
    user.find(marker="shop-example").click()
    await form.until(lambda: note.visible, "the note on the example")
    assert note.text.startswith("The example: parts of a 90 deg V8 (small-block")
    assert "This engine has 4 cylinders: the shop matches 4 sets from parts for 8" in note.text
    card = form.element("shop-parts").parent_slot.parent
    children = card.default_slot.children
    assert children.index(note) == children.index(form.element("shop-parts")) + 1
    user.find(marker="shop-run").click()
    await form.until(lambda: "spares, in no set" in form.text("shop-summary"), "the shop study")
    options = parse_options(ShopOptions, {"fraction": "0.5"})
    spares = spares_words(shop_study("inline4", PARTS, options).parts)
    assert spares in form.text("shop-summary")
    assert "The example is not this engine's: Parts of a 90 deg V8" in form.text("shop-summary")
    # the engine's own count of parts: the note goes
    own = "part,id,mass [g]\n" + "".join(f"piston,P{k},480\n" for k in range(1, 5))
    form.set("shop-parts", own)
    await form.until(lambda: not note.visible, "the note gone")


@pytest.mark.parametrize(("width", "height"), [(1280, 800), (390, 844)])
def test_shop_bobweights_holes_and_verdict(server: str, browser, width: int, height: int) -> None:
    bobs, verdict = expected()
    page = browser.new_page(viewport={"width": width, "height": height})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(server + "/?preset=v8-crossplane")
        expect(page.locator("[data-testid=status]").first).to_contain_text("Results of:")
        page.wait_for_function("() => window.socket && window.socket.connected")
        open_tab(page, "Balance shop")
        page.get_by_role("button", name="Load example").click()
        expect(page.locator("[data-testid=shop-parts]").first).to_have_value(
            PARTS.read_text(encoding="utf-8")
        )
        for key, value in TYPED.items():
            page.locator(f"[data-testid=shop-{key}]").first.fill(value)
        page.get_by_role("button", name="Run", exact=True).click()
        shown = page.locator("[data-testid=shop-verdict]").first
        expect(shown).to_contain_text(verdict)
        table = page.locator("[data-testid=shop-bobweights]").first
        expect(table.locator("tbody tr")).to_have_count(len(bobs))
        for row, bob in enumerate(bobs):
            expect(table.locator("tbody tr").nth(row).locator("td").last).to_have_text(bob)
        holes = page.locator("[data-testid=figure-shop-holes]").first
        expect(holes.locator(".main-svg").first).to_be_attached()
        panel_titles_stay_apart(holes)
        labels_stay_apart(holes)
        SHOTS.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(SHOTS / f"shop-{width}x{height}.png"), full_page=True)
        with page.expect_download() as download:
            page.get_by_role("button", name="Shop sheet HTML").click()
        sheet = Path(download.value.path()).read_text(encoding="utf-8")
        assert "Balance shop sheet: V8" in sheet and bobs[0] in sheet
        # the embedded study: schema /2, every key with its unit (docs/json.md)
        data = sheet.split('id="crankbalance-data">', 1)[1].split("</script>", 1)[0]
        study = json.loads(data.replace("<\\/", "</"))["study"]
        assert '"schema":"crankbalance.shop-sheet/2"' in data.replace(" ", "")
        assert len(study["parts"]["bob_weights"]["bob_weight_kg"]) == len(bobs)
        assert all(0 <= a < 360 for h in study["holes"]["holes"] for a in h["angles_deg"])
        # a bad reading: named beside its field in the field's words; the result is gone
        page.locator("[data-testid=shop-reading_2]").first.fill("8 g")
        message = page.locator(".q-field--error", has_text="Reading, plane 2").first
        expect(message).to_contain_text("an amount at a radius and an angle")
        expect(page.locator("[data-testid=shop-rerun]").first).to_be_visible()
        expect(table.locator("tbody tr")).to_have_count(0)
        page.screenshot(path=str(SHOTS / f"shop-bad-{width}x{height}.png"), full_page=True)
        assert not errors, errors
    finally:
        page.close()


def test_parse_names_the_field() -> None:
    """The tab's settings are refused on the field that holds the mistake."""
    from crankbalance.errors import InputError
    from crankbalance.web.tab_shop import parse

    parts = PARTS.read_text(encoding="utf-8")
    inventory, options = parse({"parts": parts})  # no readings: the parts study only
    assert options.reading == [] and len(inventory.kinds) > 1
    cases = {
        "parts": {"parts": "part,id\npiston,P1"},
        "reading_2": {"parts": parts, "reading_1": TYPED["reading_1"]},
        "rotor_mass": {"parts": parts, **{k: v for k, v in TYPED.items() if k != "rotor_mass"}},
        "hole_radius": {"parts": parts, **TYPED, "hole_radius": "45"},
    }
    for field, texts in cases.items():
        with pytest.raises(InputError) as error:
            parse(texts)
        assert error.value.field == field, (field, error.value)
