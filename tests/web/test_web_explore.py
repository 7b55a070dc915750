"""The Explorer tab in a real browser (Playwright driving Debian's chromium): explore the
inline-4 4-stroke, see the scatter and the table, load a candidate as the current engine
and find it on the Engine and Results tabs; a bad filter is named beside its field.

Screenshots at 1280x800 and 390x844 go to ``artifacts/screenshots/`` (ignored by git).
Every wait is a wait for a state of the page with the hang guard of ``conftest.py``.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from crankbalance.physics.explore import orders

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

SHOTS = Path(__file__).resolve().parents[2] / "artifacts" / "screenshots"  # ignored by git


def open_tab(page, name: str) -> None:
    page.get_by_role("tab", name=name, exact=True).click()
    expect(page.get_by_role("tab", name=name, exact=True)).to_have_attribute(
        "aria-selected", "true"
    )


def shoot(page, name: str) -> None:
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / f"{name}.png"), full_page=True)


def connected(page) -> None:
    """Wait until the page's websocket is connected (a click before it would be lost)."""
    page.wait_for_function("() => window.socket && window.socket.connected")


def explore_inline4(page) -> None:
    connected(page)
    open_tab(page, "Explorer")
    page.get_by_role("button", name="Explore").click()
    expect(page.locator("[data-testid=explore-summary]").first).to_contain_text("distinct engines")


@pytest.mark.parametrize(("width", "height"), [(1280, 800), (390, 844)])
def test_explore_and_load_a_candidate(server: str, browser, width: int, height: int) -> None:
    page = browser.new_page(viewport={"width": width, "height": height})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(server + "/?preset=inline4")  # the explorer starts from the engine
        expect(page.locator("[data-testid=status]").first).to_contain_text("Results of:")
        explore_inline4(page)
        problem = orders.problem("inline", 4, 4)
        engines = orders.chunk(problem, 0, orders.count(problem))
        table = page.locator("[data-testid=explore-table]").first
        # one row per distinct engine of the inline-4 (4 of the 6 orders from cylinder 1)
        expect(table.locator("tbody tr")).to_have_count(engines.size)
        for order in engines.firing_order:
            expect(table).to_contain_text("-".join(str(c) for c in order))
        scatter = page.locator("[data-testid=figure-explore-scatter]").first
        expect(scatter.locator(".scatterlayer .point").first).to_be_attached()
        expect(scatter).to_contain_text("Pareto set")
        shoot(page, f"explore-{width}x{height}")
        # a click on the row of 1-3-4-2 loads it as the current engine
        table.locator("tbody tr", has_text="1-3-4-2").first.click()
        status = page.locator("[data-testid=status]").first
        expect(status).to_contain_text("Explorer inline-4 1-3-4-2")
        open_tab(page, "Engine")
        order = page.locator("[data-testid=field-firing_order]").first
        expect(order).to_have_value(re.compile(r"^1\D+3\D+4\D+2$"))
        expect(page.locator("[data-testid=field-cylinders]").first).to_have_value("4")
        shoot(page, f"explore-engine-{width}x{height}")
        open_tab(page, "Results")
        expect(page.locator("[data-testid=results-stale]").first).to_be_hidden()
        expect(status).to_contain_text("Results of: Explorer inline-4 1-3-4-2")
        # the explorer keeps its result; a bad filter is named beside the field and the
        # result, which belongs to the settings, is cleared
        open_tab(page, "Explorer")
        expect(table.locator("tbody tr")).to_have_count(engines.size)
        page.locator("[data-testid=explore-filter]").first.fill("F1 <")
        message = page.locator(".q-field--error", has_text="filter").first
        expect(message).to_contain_text("F1 <")
        expect(page.locator("[data-testid=explore-rerun]").first).to_be_visible()
        expect(table.locator("tbody tr")).to_have_count(0)
        shoot(page, f"explore-bad-filter-{width}x{height}")
        assert not errors, errors
    finally:
        page.close()


def test_a_large_problem_points_to_the_command_line(server: str, browser) -> None:
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    try:
        page.goto(server + "/")
        connected(page)
        open_tab(page, "Explorer")
        page.locator("[data-testid=explore-cylinders]").first.fill("10")
        message = page.locator(".q-field--error", has_text="--workers").first
        expect(message).to_contain_text("362,880")
    finally:
        page.close()


def test_pareto_ties_within_round_off_are_kept_as_the_command_line_keeps_them(
    server: str, browser
) -> None:
    """The inline-5's Pareto set over M1 and M2 holds orders whose moments differ by
    round-off only: the tab keeps them with the round-off tolerance
    (``rank.tolerances``) as ``crankbalance explore`` does (the tab runs its study), not the
    fewer of an exact comparison."""
    from crankbalance.physics.explore import merit
    from crankbalance.schema.settings import ExploreOptions, parse_options
    from crankbalance.studies.explore import Keep, run
    from crankbalance.studies.explorer import explore

    options = {"layout": "inline", "cylinders": 5, "objectives": "M1,M2"}
    want = len(explore(None, parse_options(ExploreOptions, options)).to_dict()["pareto"])
    # an exact comparison (no tolerance) drops some of them
    exact = run(orders.problem("inline", 5, 4), merit.merit, keep=Keep(("M1_Nm", "M2_Nm")))
    assert exact.pareto["index"].size < want
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    try:
        page.goto(server + "/")
        connected(page)
        open_tab(page, "Explorer")
        # the tab has taken its problem from the page's engine (the paper's inline-3)
        problem = page.locator("[data-testid=explore-problem]").first
        expect(problem).to_contain_text("inline, 3 cylinders")
        for key, value in (("cylinders", "5"), ("x", "M1"), ("y", "M2")):
            field = page.locator(f"[data-testid=explore-{key}]").first
            field.fill(value)
            expect(field).to_have_value(value)
        page.get_by_role("button", name="Explore").click()
        summary = page.locator("[data-testid=explore-summary]").first
        expect(summary).to_contain_text(f"Pareto set of {want} over")
    finally:
        page.close()


def test_every_explorer_column_has_words() -> None:
    """The table names its columns in words with their unit, never the raw name."""
    from crankbalance.output.figures.explore import column_words
    from crankbalance.web.tab_explore import _columns

    for name in _columns():
        assert column_words(name) != name, name
    assert column_words("M1_Nm") == "free moment, order 1 [N·m]"
    assert column_words("F2b_N") == "free force, order 2, backward [N]"
    assert column_words("X1p5") == "torsional excitation, order 1.5"


def test_the_table_names_its_columns_in_words(server: str, browser) -> None:
    """The inline-4's table heads its columns in words (not ``M1_Nm`` or
    ``residual_M_Nm``) and says what the count of orders giving the same engine is."""
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    try:
        page.goto(server + "/?preset=inline4")  # the explorer starts from the engine
        expect(page.locator("[data-testid=status]").first).to_contain_text("Results of:")
        explore_inline4(page)
        head = page.locator("[data-testid=explore-table] thead").first
        for words in (
            "free moment, order 1 [N·m]",
            "free moment, order 2 [N·m]",
            "largest moment left after balancing [N·m]",
            "orders giving it",
        ):
            expect(head).to_contain_text(words)
        for raw in ("M1_Nm", "residual_M_Nm", "equiv"):
            expect(head).not_to_contain_text(raw)
        note = page.locator(".q-tab-panel:visible", has_text="Orders giving it").first
        expect(note).to_contain_text("give this same engine")
    finally:
        page.close()


def test_ties_are_told_apart_by_what_differs() -> None:
    """The inline-6's eight orders without free forces or moments tie (issue 28, item 4):
    :func:`tied` finds them, :func:`tie_columns` gives what differs (successive firings on
    neighbouring throws, the linear mode's torsional excitation of orders 0.5 to 2.5), and
    the V8's per bank; the inline-4's two tied orders differ in nothing computed."""
    from crankbalance.schema.settings import ExploreOptions, parse_options
    from crankbalance.studies.explorer import explore
    from crankbalance.web.tab_explore import tie_columns, tied

    def top(**given):
        o = parse_options(ExploreOptions, {"top": 20, **given})
        rows = explore(None, o, figure_points=1000).figure.top
        problem = orders.problem(o.layout, o.cylinders, o.strokes, o.bank_angle)
        return rows, problem

    rows, problem = top(layout="inline", cylinders=6)
    assert tied(rows, problem, 20) == 8
    apart = tie_columns(rows, problem, 8)
    sequences = ["-".join(map(str, rows["firing_order"][k])) for k in range(8)]
    neighbours = dict(zip(sequences, apart["neighbours"], strict=True))
    assert neighbours["1-5-3-6-2-4"] == "0" and neighbours["1-2-3-6-5-4"] == "4"
    assert set(apart) == {"neighbours", "X0.5", "X1.5", "X2.5"}
    assert "banks" not in apart  # one bank
    rows, problem = top(layout="vee", cylinders=8, bank_angle="90 deg")
    n = tied(rows, problem, 20)
    assert n > 1 and len(set(tie_columns(rows, problem, n)["banks"])) == n
    rows, problem = top(layout="inline", cylinders=4)
    assert tied(rows, problem, 20) == 2 and tie_columns(rows, problem, 2) == {}
    assert tied(rows, problem, 1) == 1


def test_a_balanced_candidate_says_why_its_plot_is_empty() -> None:
    """explore_candidate of a crank with no free force or moment writes why it is empty."""
    from crankbalance.output.figures.explore import BALANCED, explore_candidate

    row = {"firing_order": [1, 5, 3, 6, 2, 4]}
    row |= {
        f"{k}{n}{p}_{u}": 0.0
        for k, u in (("F", "N"), ("M", "Nm"))
        for n in (1, 2, 3, 4)
        for p in "fb"
    }
    texts = [a.text for a in explore_candidate(row).layout.annotations]
    assert BALANCED.format(orders=4) in texts
    row["M1f_Nm"] = 3.0
    assert BALANCED.format(orders=4) not in [
        a.text for a in explore_candidate(row).layout.annotations
    ]


@pytest.mark.parametrize(("width", "height"), [(1280, 800), (390, 844)])
def test_inline6_ties_are_explained_in_the_page(
    server: str, browser, width: int, height: int
) -> None:
    """The inline-6's tied orders in the page: the note says they are equivalent in free
    forces and moments and names what tells them apart; the table has those columns (the
    classic 1-5-3-6-2-4 fires no neighbouring throws in succession); the chosen balanced
    candidate's figure says why it is empty."""
    page = browser.new_page(viewport={"width": width, "height": height})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(server + "/")
        expect(page.locator("[data-testid=status]").first).to_contain_text("Results of:")
        connected(page)
        open_tab(page, "Explorer")
        field = page.locator("[data-testid=explore-cylinders]").first
        field.fill("6")
        expect(field).to_have_value("6")
        page.get_by_role("button", name="Explore").click()
        summary = page.locator("[data-testid=explore-summary]").first
        expect(summary).to_contain_text("64 distinct engines")
        ties = page.locator("[data-testid=explore-ties]").first
        expect(ties).to_contain_text("Rows 1 to 8 tie")
        expect(ties).to_contain_text("equivalent in free forces and moments")
        expect(ties).to_contain_text("main-bearing load proxy")
        head = page.locator("[data-testid=explore-table] thead").first
        expect(head).to_contain_text("successive firings on neighbouring throws")
        expect(head).to_contain_text("torsional excitation, order 1.5, linear mode [-]")
        row = page.locator("[data-testid=explore-table] tbody tr", has_text="1-5-3-6-2-4").first
        expect(row.locator("td").nth(4)).to_have_text("0")  # after "orders giving it"
        card = page.locator(".q-card", has_text="Chosen candidate").first
        expect(card).to_contain_text("0 everywhere")
        figure = page.locator("[data-testid=figure-explore-candidate]").first
        expect(figure.locator(".annotation-text", has_text="balanced in them")).to_have_count(1)
        shoot(page, f"explore-ties-{width}x{height}")
        assert not errors, errors
    finally:
        page.close()
