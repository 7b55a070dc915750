"""Study messages in the words of the form.

An :class:`~crankbalance.errors.InputError` of a study names a setting key (``sc_grade``)
or an argument of the library (``hole_diameter``); the page shows it beside the setting's
input, or in a notification that names the setting by its label, never by its key.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from nicegui import ui

from ..errors import InputError
from .studies import SETTING_FIELDS

if TYPE_CHECKING:
    from .app import Page


def in_words(error: InputError, aliases: dict[str, str] | None = None) -> tuple[str | None, str]:
    """(the setting key the message belongs to, or None; the message without the key).

    ``aliases`` maps argument names of the library to the tab's setting keys. The message
    is the value given and what is allowed; a field that is no setting keeps only that."""
    aliases = aliases or {}
    key = aliases.get(error.field, error.field)
    given = "" if error.value is None else f"{error.value!r}: "
    text = error.allowed
    for name, setting in aliases.items():  # library names inside the text, as labelled
        if setting in SETTING_FIELDS:
            text = re.sub(rf"\b{name}\b", SETTING_FIELDS[setting][0], text)
    return (key if key in SETTING_FIELDS else None), f"{given}{text}"


def show_error(page: Page, error: InputError, aliases: dict[str, str] | None = None) -> str:
    """Show a study's error beside its setting (and in a notification naming the setting's
    label, the input may be scrolled away); returns the message as shown in the tab."""
    key, text = in_words(error, aliases)
    if key is None:
        ui.notify(text, type="negative", multi_line=True)
        return text
    worded = f"{SETTING_FIELDS[key][0]}: {text}"
    if key in page.setting_inputs:
        page.show_setting_errors({key: text})
    ui.notify(worded, type="negative", multi_line=True)
    return worded
