"""Web app, the Masses tab through NiceGUI's simulated User."""

from __future__ import annotations

import pytest
from nicegui.testing.user import User

from crankbalance.web.tab_masses import CONROD_SPLIT_LABEL, MASS_MODE_LABEL

pytestmark = pytest.mark.anyio


async def test_the_two_mass_choices_are_two_labelled_rows(user: User, form) -> None:
    """ "Parts/Totals" and the conrod split are two groups: each radio on its own row, with
    its own label beside it (on one row they read as one group of four)."""
    await user.open("/")
    form.open("masses")
    rows = []
    for marker, label in (("mass-mode", MASS_MODE_LABEL), ("conrod-split", CONROD_SPLIT_LABEL)):
        row = form.element(marker).parent_slot.parent
        rows.append(row)
        assert [c.text for c in row.default_slot.children if hasattr(c, "text")] == [label]
    assert rows[0] is not rows[1]
