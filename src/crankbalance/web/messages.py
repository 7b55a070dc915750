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
from .studies import SETTING_FIELDS, worded

if TYPE_CHECKING:
    from .context import TabContext


#: library arguments whose value is no number the user typed (a correction's kind)
UNTYPED = frozenset({"correction"})


def named(name: str) -> str:
    """The pattern of a library argument ``name`` where a message names it: a name with an
    underscore anywhere (``web_thickness``), a plain word only as a name is written in a
    message, before ``=`` or ``:`` (``holes: 25``), so that the words of a sentence stay
    (``axial holes at ...`` is not ``axial Holes per web at ...``)."""
    return rf"\b{name}\b" if "_" in name else rf"\b{name}\b(?=\s*[=:])"


def in_words(error: InputError, aliases: dict[str, str] | None = None) -> tuple[str | None, str]:
    """(the setting key the message belongs to, or None; the message in the form's words).

    ``aliases`` maps argument names of the library to the tab's setting keys. A message of
    a setting names it by its label (:func:`~.studies.worded`); one of no setting is the
    value given and what is wrong."""
    aliases = aliases or {}
    key = aliases.get(error.field, error.field)
    value = None if error.field in UNTYPED else error.value
    text = error.allowed
    for name, setting in aliases.items():  # library names inside the text, as labelled
        if setting in SETTING_FIELDS:
            text = re.sub(named(name), SETTING_FIELDS[setting][0], text)
    if key in SETTING_FIELDS:
        return key, worded(key, value, text)
    return None, text if value is None else f"{value!r}: {text}"


def show_error(page: TabContext, error: InputError, aliases: dict[str, str] | None = None) -> str:
    """Show a study's error beside its setting (and in a notification, the input may be
    scrolled away); returns the message as shown in the tab."""
    key, text = in_words(error, aliases)
    if key is not None and key in page.setting_inputs:
        page.show_setting_errors({key: text})
    ui.notify(text, type="negative", multi_line=True)
    return text
