"""Every input described once (issue 26): the reference tables of docs/engine_file.md and
docs/settings.md and the published JSON Schema docs/engine.schema.json are written from
the schemas and must be current; every preset validates against the published JSON
Schema; every field of the engine file and of every study's settings has a title and a
description, the one description the edges derive from."""

from __future__ import annotations

import json
import tomllib
from typing import Any

import pytest

from crankbalance.io.engine_file import list_presets, preset_text
from crankbalance.schema import document, settings
from crankbalance.schema.core import Schema

from .conftest import EXAMPLES, ROOT

SCHEMA = json.loads((ROOT / document.JSON_SCHEMA_DOC).read_text(encoding="utf-8"))


def test_the_documents_are_written_from_the_schemas() -> None:
    """A schema changed without `python -m crankbalance.schema.document --write` fails
    here, as a changed number fails the golden files."""
    stale = [str(path.relative_to(ROOT)) for path in document.stale(ROOT)]
    assert not stale, f"stale: {stale}; run python -m crankbalance.schema.document --write"


def test_every_engine_file_table_has_its_marker() -> None:
    text = (ROOT / document.ENGINE_FILE_DOC).read_text(encoding="utf-8")
    for name in document.ENGINE_TABLES:
        assert text.count(f"<!-- schema:begin {name} -->") == 1, name
    with pytest.raises(ValueError, match="no engine-file table 'crank_trian'"):
        document.engine_file_doc("<!-- schema:begin crank_trian -->\n<!-- schema:end -->")


def conforms(data: Any, schema: dict[str, Any], where: str = "") -> list[str]:
    """The places where ``data`` breaks ``schema`` (the parts of JSON Schema the published
    schema uses: type, enum, properties, required, additionalProperties, items, bounds)."""
    kinds = {
        "object": dict,
        "array": list,
        "string": str,
        "boolean": bool,
        "integer": int,
        "number": (int, float),
    }
    types = schema.get("type")
    if types is not None:
        names = types if isinstance(types, list) else [types]
        ok = any(
            isinstance(data, kinds[n]) and not (isinstance(data, bool) and n != "boolean")
            for n in names
        )
        if not ok:
            return [f"{where or '/'}: not {types}"]
    if "enum" in schema and not any(data == v and type(data) is type(v) for v in schema["enum"]):
        return [f"{where}: not one of {schema['enum']}"]
    problems = []
    for key in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum"):
        if key in schema and isinstance(data, (int, float)):
            bound = schema[key]
            fine = {
                "minimum": data >= bound,
                "maximum": data <= bound,
                "exclusiveMinimum": data > bound,
                "exclusiveMaximum": data < bound,
            }[key]
            if not fine:
                problems.append(f"{where}: {key} {bound}")
    if isinstance(data, str) and len(data) > schema.get("maxLength", len(data)):
        problems.append(f"{where}: too long")
    if isinstance(data, dict):
        props = schema.get("properties", {})
        problems += [f"{where}/{k}: missing" for k in schema.get("required", []) if k not in data]
        for key, value in data.items():
            if key in props:
                problems += conforms(value, props[key], f"{where}/{key}")
            elif schema.get("additionalProperties") is False:
                problems.append(f"{where}/{key}: not allowed")
    if isinstance(data, list):
        if len(data) > schema.get("maxItems", len(data)) or len(data) < schema.get("minItems", 0):
            problems.append(f"{where}: {len(data)} items")
        for k, item in enumerate(data):
            problems += conforms(item, schema.get("items", {}), f"{where}/{k}")
    return problems


def _validate(data: Any) -> list[str]:
    """The published schema's verdict: the jsonschema package where it is installed,
    else the structural walk above."""
    try:
        import jsonschema
    except ImportError:
        return conforms(data, SCHEMA)
    validator = jsonschema.Draft202012Validator(SCHEMA)
    return [error.message for error in validator.iter_errors(data)]


@pytest.mark.parametrize("name", list_presets())
def test_every_preset_validates_against_the_published_json_schema(name: str) -> None:
    assert _validate(tomllib.loads(preset_text(name))) == []


def test_the_examples_validate_and_mistakes_do_not() -> None:
    for path in EXAMPLES.glob("paper_*.toml"):
        assert _validate(tomllib.loads(path.read_text(encoding="utf-8"))) == [], path
    data = tomllib.loads(preset_text("inline4"))
    data["crank_train"]["rod_lenght"] = data["crank_train"].pop("rod_length")
    data["crank_train"]["cylinders"] = 4.5  # JSON Schema counts 4.0 as an integer
    data["kinematics"] = "exakt"
    data.pop("speed")
    assert len(_validate(data)) == 5  # unknown key, two missing, a fraction, a bad choice


def _schemas() -> list[type[Schema]]:
    found = [*document.ENGINE_TABLES.values()]
    found += [settings.StudyOptions, *settings.models()]
    return found


def test_every_field_has_a_title_and_a_description() -> None:
    """The one description the docs, the JSON Schema, the help texts and the form derive
    from: none may be left empty."""
    missing = [
        f"{schema.__name__}.{key}"
        for schema in _schemas()
        for key, spec in schema.FIELDS.items()
        if not (spec.title.strip() and spec.description.strip())
    ]
    assert not missing, f"fields without a title or a description: {missing}"
    assert sum(len(schema.FIELDS) for schema in _schemas()) > 300


def test_the_tables_say_kind_default_range_and_meaning() -> None:
    table = document.field_table(document.ENGINE_TABLES["crank_train"])
    row = next(line for line in table.splitlines() if line.startswith("| `crank_radius` |"))
    assert row.startswith("| `crank_radius` | length [mm] | required | a length with a unit")
    assert "Throw radius" in row
    settings_text = document.settings_doc()
    assert "| `iterations` | whole number | `40` | a whole number from 0 to 1000 |" in settings_text
    assert SCHEMA["properties"]["crank_train"]["properties"]["cylinders"]["maximum"] == 64
