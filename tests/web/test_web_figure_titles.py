"""A figure card does not repeat its title in the figure (issue 28 review, finding 8): the
card shows its title, the figure keeps only its second line (the engine, a note); the
command line's and the reports' figures keep their whole titles."""

from __future__ import annotations

import pytest

pytest.importorskip("nicegui")

from crankbalance.web.widgets import without_card_title  # noqa: E402


def test_the_card_title_is_not_repeated() -> None:
    sub = "<br><sup>inline4 · 6000 rpm</sup>"
    same = "Free forces and moments by order"
    assert without_card_title(same + sub, same) == "<sup>inline4 · 6000 rpm</sup>"
    assert without_card_title(same, same) == ""
    both = "Residuals before and after balancing"
    assert without_card_title(both, "Residuals before/after balancing") == ""
    assert without_card_title("Drilling plan" + sub, "Drilling plan to scale") == sub[4:]
    other = "Main-bearing loads over the cycle" + sub
    assert without_card_title(other, "Polar load diagrams (middle balance factor)") == other


@pytest.mark.anyio
async def test_the_orders_card_drops_its_figure_title(user, form) -> None:
    """The Results tab's orders card: its figure has the engine's name as its title, not
    "Free forces and moments by order" a second time (the figure itself keeps it)."""
    await user.open("/?preset=inline4")
    await form.until(lambda: form.element("status").text.startswith("Results of"), "the engine")
    user.find(marker="tab-results").click()
    await form.until(lambda: "title" in form.element("figure-orders").figure["layout"])
    shown = form.element("figure-orders").figure["layout"]["title"]["text"]
    assert "Free forces and moments by order" not in shown
    assert shown.startswith("<sup>") and "inline" in shown.lower()
