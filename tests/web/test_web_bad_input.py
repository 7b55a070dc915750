"""Bad input in every field shows a message beside that field and never a server error;
a malformed project upload is refused with a clear message and the project is kept;
several users keep their own projects."""

from __future__ import annotations

import logging

import pytest
from nicegui.elements.upload_files import SmallFileUpload
from nicegui.testing.user import User
from nicegui.testing.user_simulation import user_simulation

from crankbalance.io.engine_file import preset_text
from crankbalance.web.app import root
from crankbalance.web.form import FIELDS
from crankbalance.web.project import MAX_BYTES, SETTINGS_TAG

pytestmark = pytest.mark.anyio

BAD_BY_KIND = {
    "quantity": "12 parsecs per",
    "int": "three",
    "float": "half",
    "intlist": "1, x, 3",
    "quantitylist": "1 mm, 12 parsecs",
    "choice": "sideways",
    "angle_or_optimal": "steep",
}
BAD_VALUES = {  # values that parse but the spec refuses
    "cylinders": "0",
    "crank_radius": "0 mm",
    "rod_length": "20 mm",
    "speed": "-5 rpm",
    "firing_order": "1, 1, 2",
    "crank_pitch": "-9 mm",
    "bank_angle": "30 deg",
    "cw_balance_factor": "3",
    "cw_webs": "0, 0, 0, 0, 0, 0",
    "cw_cg_radius": "-3 mm",
    "piston": "-1 g",
    "conrod": "0 g",
    "conrod_rotating_fraction": "1.5",
    "crank_web_cg_radius": "-2 mm",
    "primary_length": "0 mm",
    "secondary_cg_radius": "0 m",
    "reciprocating": "-1 kg",
    "rotating": "-1 kg",
}


def _mode_for(user: User, form, key: str) -> None:
    group = next(f.group for f in FIELDS if f.key == key)
    with user:
        form.element("mass-mode").value = "totals" if group == "totals" else "parts"
        if group in ("fraction", "cg"):
            form.element("conrod-split").value = group
    if group == "totals":
        for marker, value in (("field-reciprocating", "1 kg"), ("field-rotating", "2 kg")):
            if not form.element(marker).value:
                form.set(marker, value)


async def test_bad_input_in_every_field(user: User, form, caplog) -> None:
    await user.open("/")
    form.open("masses")  # the mass fields (built when their tab is first opened)
    checked = 0
    for f in FIELDS:
        if f.kind == "text":
            continue  # the engine name takes any text
        if f.layouts:
            continue  # hidden on this engine's layout: tests/web/test_web_engine_fields.py
        _mode_for(user, form, f.key)
        marker = f"field-{f.key}"
        element = form.element(marker)
        good = element.value
        for bad in filter(None, (BAD_BY_KIND[f.kind], BAD_VALUES.get(f.key))):
            if f.kind == "choice":
                with user:
                    element.set_options([*element.options, bad])
            form.set(marker, bad)
            message = form.error(marker)
            assert message, f"{f.key} = {bad!r} shows no message beside the field"
            assert message.startswith(f.label), (f.key, message)  # in the words of the form
            assert "crank_train" not in message and "docs/" not in message, message
            assert (
                "results below are those of the last valid engine" in form.text("results-stale")
                and form.element("results-stale").visible
            )
            checked += 1
            form.set(marker, good)
            assert form.error(marker) is None, (f.key, form.error(marker))
    assert checked >= 40
    assert not [r for r in caplog.records if r.levelno >= logging.ERROR]


def _with_settings(line: str) -> bytes:
    return (SETTINGS_TAG + line + "\n" + preset_text("inline4")).encode()


#: uploads that must be refused at load: (file name, content, a word the message must hold)
BAD_UPLOADS = [
    ("broken.toml", b"name = 'x'\n[crank_train\nlayout = 'inline'", "TOML"),
    ("unknown.toml", preset_text("inline4").encode() + b"\nturbo = true\n", "turbo"),
    ("binary.toml", bytes(range(256)), "UTF-8"),
    ("empty.json", b"", "empty"),
    ("wrong.json", b'{"speed": "fast"}', "speed"),
    ("deep.toml", b"a = " + b"[" * 500 + b"]" * 500, "deep"),
    ("digits.toml", preset_text("inline4").replace("= 4", "= " + "4" * 5000).encode(), "digit"),
    ("huge.toml", b"#" * (MAX_BYTES + 1), str(MAX_BYTES)),
    ("orders.toml", _with_settings('{"orders": "abc"}'), "orders = 'abc'"),
    ("unknown-setting.toml", _with_settings('{"turbo": 1}'), "unknown setting"),
    ("broken-settings.toml", _with_settings('{"orders": '), "JSON object"),
    ("list-settings.toml", _with_settings("[8]"), "JSON object"),
    ("typed-setting.toml", _with_settings('{"cw_seed": [1]}'), "text or a number"),
    ("mode-setting.toml", _with_settings('{"mass_mode": "both"}'), "parts, totals"),
    ("polar-setting.toml", _with_settings('{"polar_order": "0"}'), "polar_order"),
    ("seed-setting.toml", _with_settings('{"cw_seed": -1}'), "cw_seed"),
]


async def test_malformed_upload_is_refused_and_project_kept(user: User, form, caplog) -> None:
    """Every bad upload says, on the page, which file was refused and why; the project is
    kept; the server logs no error and no traceback."""
    await user.open("/?preset=v8-crossplane")
    upload = form.element("upload")
    for name, data, word in BAD_UPLOADS:
        with user:
            await upload.handle_uploads([SmallFileUpload(name, "text/plain", data)])
        await form.until(lambda: form.text("general-error"), f"the refusal of {name}")
        message = form.text("general-error")
        with user:
            form.element("general-error").set_text("")
        assert message.startswith(f"Upload of {name} refused, the current project is kept")
        assert word in message, (name, message)  # says what is wrong
        assert "\n" not in message, message  # one line
        assert form.element("field-name").value == "V8 90 deg, crossplane crank"
        assert form.element("field-cylinders").value == "8"
    assert not [r for r in caplog.records if r.exc_info or r.levelno >= logging.ERROR]


async def test_file_the_browser_refuses_is_reported(user: User, form) -> None:
    """A file over the size limit is refused by the browser before it is sent; the page
    says so."""
    await user.open("/?preset=v8-crossplane")
    user.find(marker="upload").trigger("rejected")
    await form.until(lambda: form.text("general-error"), "the refusal")
    assert f"larger than {MAX_BYTES} bytes" in form.text("general-error")
    assert form.element("field-cylinders").value == "8"


async def test_save_then_load_round_trip(user: User, form) -> None:
    await user.open("/")
    form.set("field-speed", "3000 rpm")
    form.set("setting-orders", "6")
    saved = await form.download("save-toml")
    assert b"crankbalance-web settings" in saved and b'speed = "3000 rpm"' in saved
    with user:
        form.element("preset").value = "inline4"
    assert form.element("field-cylinders").value == "4"
    with user:
        await form.element("upload").handle_uploads(
            [SmallFileUpload("mine.toml", "text/plain", saved)]
        )
    await form.until(lambda: form.element("field-cylinders").value == "3")
    assert form.element("field-speed").value == "3000 rpm"
    assert form.element("field-cylinders").value == "3"
    assert len(form.rows("orders-table")) == 6
    assert form.text("general-error") == ""
    # the preset selector names no preset once the form holds an uploaded project, and the
    # preset chosen before can be chosen again
    assert form.element("preset").value is None, "the selector still names inline4"
    with user:
        form.element("preset").value = "inline4"
    assert form.element("field-cylinders").value == "4"


async def test_two_users_keep_their_own_projects() -> None:
    async with user_simulation(root=root) as first:
        await first.open("/")
        second = User(first.http_client)  # a second browser on the same server
        await second.open("/?preset=v12-60")
        assert second.client is not first.client
        first_speed = next(iter(first.find(marker="field-speed").elements))
        second_speed = next(iter(second.find(marker="field-speed").elements))
        with first:
            first_speed.value = "1234 rpm"
        assert second_speed.value != "1234 rpm"
        first_name = next(iter(first.find(marker="field-name").elements)).value
        second_name = next(iter(second.find(marker="field-name").elements)).value
        assert "Inline-3" in first_name and "V12" in second_name
