"""Engine files (TOML or JSON): loading, validating, saving, and the preset library."""

from __future__ import annotations

import os
from functools import cache, lru_cache
from typing import Any

from ..errors import InputError
from ..schema.core import closest
from ..schema.engine import EngineSpec, spec_from_dict
from .files import write_atomic
from .reading import file_format, parse_json, parse_toml, read_text

#: Largest engine file read [bytes]; an engine file is a few kB of TOML or JSON.
MAX_FILE_BYTES = 2_000_000
#: the preset folder, package data beside this package's modules (a plain path: importing
#: importlib.resources, with zipfile and tempfile, cost every command more than a
#: millisecond of its cold start, issue 30)
PRESETS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "presets")


def list_presets() -> list[str]:
    """Names of the built-in engines (files ``presets/<name>.toml``)."""
    return list(_preset_names())


@cache
def _preset_names() -> tuple[str, ...]:
    """The preset folder is package data: listed once per process, not on every load."""
    return tuple(sorted(name[:-5] for name in os.listdir(PRESETS) if name.endswith(".toml")))


def preset_text(name: str) -> str:
    """The TOML text of a built-in engine."""
    if name not in _preset_names():
        raise InputError(
            "preset",
            name,
            "unknown preset; `crankbalance presets` lists them: " + ", ".join(list_presets()),
        )
    with open(os.path.join(PRESETS, f"{name}.toml"), encoding="utf-8") as file:
        return file.read()


def parse_engine_text(text: str, source: str = "engine file", fmt: str = "toml") -> EngineSpec:
    """Validate the text of an engine file (TOML, or JSON with the same structure), parsed
    with the bounds of :mod:`crankbalance.io.reading` (nesting, number length, duplicate
    JSON keys). The spec (frozen) of a text read among the last :data:`PARSE_CACHE` is
    the one made then."""
    return _parsed(text, source, fmt)


#: engine texts whose spec is kept (a spec is frozen; a text is a few kB): a preset or a
#: file read again in one process (the web application, a notebook) is not parsed again
PARSE_CACHE = 64


@lru_cache(maxsize=PARSE_CACHE)
def _parsed(text: str, source: str, fmt: str) -> EngineSpec:
    """:func:`parse_engine_text`, kept by its arguments (a refused text is not kept)."""
    if "\x00" in text:
        raise InputError(source, "binary data", "must be a text file (TOML or JSON)")
    if not text.strip():
        raise InputError(source, "empty file", "must describe an engine (see docs/engine_file.md)")
    if fmt == "json":
        return spec_from_dict(parse_json(text, source))
    try:
        data = parse_toml(text, source)
    except InputError:
        if looks_like_a_table(text):
            raise InputError(source, None, _NOT_A_TABLE) from None
        raise
    return spec_from_dict(data)


#: files a spreadsheet saves, refused with :data:`_NOT_A_TABLE` before they are read
SPREADSHEETS = (".csv", ".tsv", ".xlsx", ".xls", ".xlsm", ".ods")
_NOT_A_TABLE = (
    "is a spreadsheet's table, not an engine file; an engine file is TOML (or JSON) with "
    'one key = "value with unit" a line under [tables], e.g. speed = "6000 rpm" '
    "(docs/engine_file.md; `crankbalance presets` lists examples)"
)


def looks_like_a_table(text: str) -> bool:
    """Whether text that is not TOML reads as a CSV table a spreadsheet saved: its first
    line (not a comment) has no ``=``, no ``[`` at its start, and two or more cells
    separated by commas, semicolons or tabs."""
    for line in text.splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        if "=" in line or line.startswith("["):
            return False
        return any(len(line.split(sep)) > 1 for sep in (",", ";", "\t"))
    return False


def load_engine(source: str | os.PathLike[str]) -> EngineSpec:
    """Load an engine from a file path (``.toml`` or ``.json``) or a preset name."""
    from .reading import reading_given_files

    if reading_given_files() or not os.path.lexists(source):
        # a preset, or (for a request's files, not this machine's) a file given with it
        if str(source) in _preset_names():
            return parse_engine_text(preset_text(str(source)), f"preset {source}")
        close = closest(str(source), _preset_names())
        hint = f"; did you mean the preset '{close}'?" if close else ""
        raise InputError(
            "engine",
            str(source),
            f"is neither an engine file nor a preset{hint} "
            "(`crankbalance presets` lists the presets)",
        )
    if os.path.splitext(str(source))[1].lower() in SPREADSHEETS:
        raise InputError("engine", str(source), _NOT_A_TABLE)
    text = read_text(source, "engine", "an engine file (.toml or .json)", MAX_FILE_BYTES)
    return parse_engine_text(text, str(source), file_format(source))


def engine_to_toml(spec: EngineSpec) -> str:
    """Write an engine spec as TOML text (quantities as unit strings)."""
    return dumps_toml(spec.to_data())


def save_engine(spec: EngineSpec, path: str | os.PathLike[str]) -> None:
    """Save an engine file atomically; the format follows the suffix (.json or .toml)."""
    if file_format(path) == "json":
        import json  # here: loading an engine does not load it

        text = json.dumps(spec.to_data(), indent=2) + "\n"
    else:
        text = engine_to_toml(spec)
    write_atomic(path, text)


# --------------------------------------------------------------------------- TOML writer
def dumps_toml(data: dict[str, Any]) -> str:
    """A small TOML writer for engine files (tables, arrays of tables, scalars, lists)."""
    lines: list[str] = []
    _write_table(lines, data, [])
    return "\n".join(lines).strip() + "\n"


def _write_table(lines: list[str], table: dict[str, Any], path: list[str]) -> None:
    scalars = {k: v for k, v in table.items() if not _is_table(v) and not _is_table_list(v)}
    for key, value in scalars.items():
        lines.append(f"{_key(key)} = {_value(value)}")
    for key, value in table.items():
        if _is_table(value):
            lines.append("")
            lines.append(f"[{'.'.join(_key(p) for p in path + [key])}]")
            _write_table(lines, value, path + [key])
        elif _is_table_list(value):
            for item in value:
                lines.append("")
                lines.append(f"[[{'.'.join(_key(p) for p in path + [key])}]]")
                _write_table(lines, item, path + [key])


def _is_table(value: Any) -> bool:
    return isinstance(value, dict)


def _is_table_list(value: Any) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(v, dict) for v in value)


def _key(key: str) -> str:
    return key if key.replace("_", "").replace("-", "").isalnum() else _quoted(key, ascii=True)


def _quoted(text: str, ascii: bool = False) -> str:
    """A TOML basic string (JSON's escapes are TOML's), non-ASCII escaped if ``ascii``."""
    import json  # here: loading an engine does not load it

    return json.dumps(text, ensure_ascii=ascii)


def _value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return _quoted(value)
    if isinstance(value, list):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {type(value).__name__} to TOML")
