"""A split-pin vee in the Engine tab with the Pin split field (issue 28, review finding 21):
no custom throws, six pins from the vee's own fields (NiceGUI's simulated User)."""

from __future__ import annotations

import math
from typing import Any

import pytest
from nicegui.testing.user import User

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.studies.engine import analyze

pytestmark = pytest.mark.anyio


def _errors(form: Any) -> dict[str, str]:
    return {k: v.error for k, v in form.page_inputs().items() if v.error}


def _split_v6_90() -> Any:
    """The v6-90 preset with its crank given by a 30 deg pin split (even firing)."""
    spec = load_engine("v6-90")
    train = spec.crank_train.replace(
        throw_angles=None, pin_split=math.radians(30.0), firing_order=[1, 4, 2, 5, 3, 6]
    )
    return spec.replace(crank_train=train)


def _same_moments(form: Any, spec: Any) -> None:
    ref = analyze(spec).to_dict()["free_moments"]
    for row, want in zip(form.rows("orders-table"), ref, strict=False):
        moment = want["amplitude_Nm"]
        assert abs(float(row["moment"]) - moment) <= 1e-3 * max(1.0, moment), (row, want)


async def test_a_vee_takes_its_pin_split_without_custom_throws(user: User, form) -> None:
    await user.open("/?preset=v6-90")
    await form.see("Offsets, rod positions and radial rods")
    assert form.element("field-pin_split").visible, "Pin split is a vee's field"
    with user:
        form.element("editor-give-angles").value = False  # the crank from the split instead
    form.set("field-pin_split", "30 deg")
    form.set("field-firing_order", "1, 4, 2, 5, 3, 6")
    assert not _errors(form)
    assert form.element("field-layout").value == "vee"
    assert "throw-0-position" not in form.page_inputs(), "no custom throws"
    _same_moments(form, _split_v6_90())
    form.open("masses")
    assert {r["throw"] for r in form.rows("mass-table")} == {1, 2, 3, 4, 5, 6}


async def test_a_bad_pin_split_on_a_vee_is_named(user: User, form) -> None:
    await user.open("/?preset=v6-90")
    await form.see("Offsets, rod positions and radial rods")
    form.set("field-pin_split", "30 deg")  # the preset's throw angles are still given
    assert "not both" in (form.error("field-pin_split") or "")
    with user:
        form.element("editor-give-angles").value = False
    form.set("field-pin_split", "200 deg")
    assert "(-180, 180] deg for a vee" in (form.error("field-pin_split") or "")


async def test_custom_throws_from_a_split_vee_keep_the_engine(user: User, form) -> None:
    """ "Make custom throws" writes one throw per pin, each at its rod's place, and empties
    Pin split and Rod positions (the pins carry them): the engine stays the same."""
    await user.open("/?preset=v6-90")
    await form.see("Crank editor")
    with user:
        form.element("editor-give-angles").value = False
    form.set("field-pin_split", "30 deg")
    form.set("field-firing_order", "1, 4, 2, 5, 3, 6")
    form.set("field-rod_positions", "-12 mm, -12 mm, -12 mm, 12 mm, 12 mm, 12 mm")
    assert not _errors(form)
    spec = _split_v6_90()
    rods = [-0.012] * 3 + [0.012] * 3
    spec = spec.replace(crank_train=spec.crank_train.replace(rod_positions=rods))
    _same_moments(form, spec)
    user.find(marker="editor-make-custom").click()
    assert form.element("field-layout").value == "custom"
    assert form.find_hidden("field-pin_split").value == ""
    assert form.find_hidden("field-rod_positions").value == ""
    assert form.element("throw-0-position").value == "-104 mm"
    assert form.element("throw-5-position").value == "104 mm"
    assert not _errors(form)
    _same_moments(form, spec)


async def test_custom_throws_keep_a_makers_numbering(user: User, form) -> None:
    """The boxer6's firing order in Porsche's numbers: made custom throws, the named
    numbering (a boxer's) becomes the maker's numbers of the custom cylinders and the
    engine stays the same."""
    await user.open("/?preset=boxer6")
    await form.see("Crank editor")
    user.find(marker="editor-make-custom").click()
    assert form.element("field-layout").value == "custom"
    assert form.element("field-maker_numbers").value == ", ".join(
        map(str, load_engine("boxer6").crank_train.maker_map() or ())
    )
    assert form.element("field-firing_order").value == "1, 6, 2, 4, 3, 5"
    assert not _errors(form)
    _same_moments(form, load_engine("boxer6"))


def test_the_work_budget_counts_the_split_pins(monkeypatch: pytest.MonkeyPatch) -> None:
    """(cylinders + throws) x orders: a split V6 has six throws, not three."""
    from crankbalance.web import api

    monkeypatch.setattr(api, "MAX_WORK", (6 + 6) * 8 - 1)
    with pytest.raises(InputError) as err:
        api.check_work(_split_v6_90(), orders=8)
    assert "6 cylinders on 6 throws" in str(err.value)
    api.check_work(load_engine("v6-90"), orders=8)  # (6 + 3) x 8 fits
