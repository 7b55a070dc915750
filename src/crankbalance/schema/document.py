"""The documentation written from the schemas: the reference tables of the engine file
(``docs/engine_file.md``), of every study's settings (``docs/settings.md``) and the
published JSON Schema of the engine file (``docs/engine.schema.json``).

Each table of ``docs/engine_file.md`` sits between ``<!-- schema:begin TABLE -->`` and
``<!-- schema:end -->``, TABLE the engine-file table it describes (``top``,
``crank_train``, ``masses.override``, ...); the text around the markers is written by
hand. ``docs/settings.md`` is written whole. ``python -m crankbalance.schema.document
--write`` writes all three; without ``--write`` it names the files that are stale and
exits 1 (``tests/test_schema_document.py`` fails on a stale file, as the golden files do).
"""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path
from typing import Any

from ..units import KINDS
from . import settings
from .core import REQUIRED, Field, Schema, allowed, default_text, json_schema
from .engine import (
    Articulated,
    BalanceShafts,
    Counterweights,
    CrankTrain,
    EngineSpec,
    Masses,
    MassOverride,
    Mount,
    Powertrain,
    PowertrainEstimate,
    ShaftSet,
    Throw,
)

#: the tables of the engine file, by the name of their marker, with their schema
ENGINE_TABLES: dict[str, type[Schema]] = {
    "top": EngineSpec,
    "crank_train": CrankTrain,
    "crank_train.throw": Throw,
    "crank_train.articulated": Articulated,
    "masses": Masses,
    "masses.override": MassOverride,
    "counterweights": Counterweights,
    "balance_shafts": BalanceShafts,
    "balance_shafts.primary": ShaftSet,
    "powertrain": Powertrain,
    "powertrain.mount": Mount,
    "powertrain.estimate": PowertrainEstimate,
}
#: the documents written, relative to the repository's root
ENGINE_FILE_DOC = "docs/engine_file.md"
SETTINGS_DOC = "docs/settings.md"
JSON_SCHEMA_DOC = "docs/engine.schema.json"
_BEGIN = re.compile(r"<!-- schema:begin ([\w.]+) -->\n.*?<!-- schema:end -->", re.DOTALL)


def kind_words(spec: Field) -> str:
    """The kind of a field and its display unit, as a table shows it ("length [mm]")."""
    if spec.quantity is not None:
        return f"{spec.kind} [{KINDS[spec.kind][1].replace('**', '^')}]"
    if spec.kind == "list":
        assert spec.item is not None
        if spec.item.kind == "table":
            return "list of tables"
        words = kind_words(spec.item).split(" [")
        return f"list of {words[0]}s" + (f" [{words[1]}" if len(words) > 1 else "")
    return {
        "whole": "whole number",
        "factor": "number or %",
        "flag": "true/false",
        "any": "text",
    }.get(spec.kind, spec.kind)


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def field_table(schema: type[Schema], header: str = "key") -> str:
    """The Markdown table of a schema: key, kind and unit, default, allowed, meaning."""
    rows = [
        f"| {header} | kind [unit] | default | allowed | meaning |",
        "|---|---|---|---|---|",
    ]
    for key, spec in schema.FIELDS.items():
        if spec.default is REQUIRED:
            default = "required"
        else:
            default = f"`{default_text(spec)}`" if default_text(spec) else "—"
        table = spec.kind == "table" or (spec.item is not None and spec.item.kind == "table")
        words = "see below" if table else allowed(spec)
        if table and spec.max_items is not None:
            words = f"at most {spec.max_items} tables, see below"
        meaning = spec.description or spec.title
        rows.append(
            f"| `{key}` | {kind_words(spec)} | {_cell(default)} | {_cell(words)} | "
            f"{_cell(meaning)} |"
        )
    return "\n".join(rows)


def engine_file_doc(text: str) -> str:
    """``docs/engine_file.md`` with its tables written from the schema (the text between
    the markers replaced; a marker of an unknown table is an error)."""

    def table(found: re.Match[str]) -> str:
        name = found.group(1)
        if name not in ENGINE_TABLES:
            raise ValueError(f"{ENGINE_FILE_DOC}: no engine-file table {name!r}")
        generated = "<!-- generated from crankbalance.schema.engine: do not edit -->"
        body = field_table(ENGINE_TABLES[name])
        return f"<!-- schema:begin {name} -->\n{generated}\n\n{body}\n\n<!-- schema:end -->"

    return _BEGIN.sub(table, text)


def _studies() -> list[type[settings.StudyOptions]]:
    """The settings schemas, in the order of :data:`crankbalance.schema.settings.MODELS`."""
    return settings.models()


def settings_doc() -> str:
    """``docs/settings.md``: every study's settings, one table each."""
    out = [
        "# Settings of the studies",
        "",
        "<!-- generated from crankbalance.schema.settings by "
        "`python -m crankbalance.schema.document --write`: do not edit -->",
        "",
        "Every study and every command validates its settings through one schema of",
        "`crankbalance.schema.settings`: the command line (a setting `max_mass` is the option",
        "`--max-mass`), the web form (the setting's key with its study's prefix, `cw_max_mass`)",
        "and the Python API take the same names, defaults and limits, and a refusal names the",
        "setting as it was written. A quantity is a text with a unit (`'400 g'`), read in any",
        "unit of its kind and checked after conversion; `—` as a default means the study",
        "derives the value (from the engine, or leaves the feature out), as the meaning says.",
        "An unknown setting is refused and named with the closest known one.",
        "",
    ]
    for schema in _studies():
        first = (schema.__doc__ or schema.__name__).split("\n\n")[0]
        out += [
            f"## {schema.__name__}",
            "",
            " ".join(first.split()),
            "",
            field_table(schema, "setting"),
            "",
        ]
    return "\n".join(out)


def engine_json_schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of the engine file."""
    return json_schema(EngineSpec, title="crankbalance engine file")


def documents(root: Path) -> dict[Path, str]:
    """Every document written from the schemas, by path, as it should read."""
    engine_doc = root / ENGINE_FILE_DOC
    schema_text = json.dumps(engine_json_schema(), indent=2, ensure_ascii=False) + "\n"
    return {
        engine_doc: engine_file_doc(engine_doc.read_text(encoding="utf-8")),
        root / SETTINGS_DOC: settings_doc(),
        root / JSON_SCHEMA_DOC: schema_text,
    }


def stale(root: Path) -> list[Path]:
    """The documents that do not read as the schemas write them."""
    return [
        path
        for path, text in documents(root).items()
        if not path.exists() or path.read_text(encoding="utf-8") != text
    ]


def main(argv: list[str] | None = None) -> int:
    """``python -m crankbalance.schema.document [--write] [ROOT]``: write the documents
    (``--write``), or name the stale ones and return 1."""
    args = list(sys.argv[1:] if argv is None else argv)
    write = "--write" in args
    rest = [a for a in args if a != "--write"]
    root = Path(rest[0]) if rest else Path(__file__).resolve().parents[3]
    if write:
        from ..io.files import write_atomic

        for path, text in documents(root).items():
            write_atomic(path, text)
            print(f"wrote {path.relative_to(root)}")
        return 0
    old = stale(root)
    for path in old:
        print(f"stale: {path.relative_to(root)} (python -m crankbalance.schema.document --write)")
    return 1 if old else 0


if __name__ == "__main__":
    raise SystemExit(main())
