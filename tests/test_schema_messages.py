"""Messages that point at the fix (issues 26 and 29), through the command line: an unknown
key with its closest allowed key, reported before a missing key; a key in the wrong table
with its table; a misspelt table; an unknown choice; a decimal comma; and the
plausibility notes of a valid engine (``note:`` lines of ``analyze`` and ``balance``, the
web form's warnings), which are not errors and not in the JSON."""

from __future__ import annotations

import json
import tomllib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine, preset_text
from crankbalance.schema.engine import MAX_PISTON_SPEED, ROD_RATIO, spec_from_dict
from crankbalance.schema.settings import AnalysisOptions, CounterweightOptions, parse_options

from .conftest import run_cli


def inline4() -> dict[str, Any]:
    return tomllib.loads(preset_text("inline4"))


def rename(table: str, key: str, new: str) -> Callable[[dict[str, Any]], None]:
    def change(data: dict[str, Any]) -> None:
        node = data[table] if table else data
        node[new] = node.pop(key)

    return change


def move(key: str, source: str, target: str) -> Callable[[dict[str, Any]], None]:
    def change(data: dict[str, Any]) -> None:
        (data[target] if target else data)[key] = (data[source] if source else data).pop(key)

    return change


#: an engine file's mistake -> the one line that names it and says the fix
MISTAKES = [
    (
        "misspelt key",
        rename("crank_train", "rod_length", "rod_lenght"),
        "crank_train.rod_lenght = '145 mm': unknown key; did you mean 'rod_length'?",
    ),
    ("misspelt table", rename("", "masses", "mases"), "mases: unknown key; did you mean 'masses'?"),
    (
        "misspelt key in a list of tables",
        lambda d: d["masses"].update(override=[{"cylinders": [1], "pistn": "300 g"}]),
        "masses.override[0].pistn = '300 g': unknown key; did you mean 'piston'?",
    ),
    (
        "key above its table",
        move("rod_length", "crank_train", ""),
        "rod_length = '145 mm': unknown key here; rod_length belongs in [crank_train]",
    ),
    (
        "top-level key inside a table",
        move("speed", "", "crank_train"),
        "crank_train.speed = '6000 rpm': unknown key here; speed belongs at the top level, "
        "before any [table]",
    ),
    (
        "misspelt choice",
        lambda d: d.update(kinematics="exakt"),
        "kinematics = 'exakt': must be one of exact, series, first-order; did you mean 'exact'?",
    ),
    (
        "misspelt layout",
        lambda d: d["crank_train"].update(layout="inlin"),
        "crank_train.layout = 'inlin': must be one of inline, vee, boxer, w, radial, vr, "
        "custom; did you mean 'inline'?",
    ),
    (
        "decimal comma",
        lambda d: d["masses"].update(piston="0,34 kg"),
        "masses.piston = '0,34 kg': has a decimal comma; write '0.34 kg'",
    ),
    (
        "misspelt numbering",
        lambda d: d["crank_train"].update(numbering="porsche-boxr"),
        "crank_train.numbering = 'porsche-boxr': must be one of porsche-boxer, gm-vee, "
        "ford-vee; did you mean 'porsche-boxer'?",
    ),
]


@pytest.mark.parametrize("name,change,line", MISTAKES, ids=[m[0] for m in MISTAKES])
def test_engine_file_mistakes_point_at_the_fix(
    name: str,
    change: Callable[[dict[str, Any]], None],
    line: str,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    data = inline4()
    change(data)
    path = tmp_path / "engine.json"
    path.write_text(json.dumps(data))
    code, out, err = run_cli(["analyze", str(path)], capsys)
    assert (code, out, err) == (2, "", f"error: {line}\n")


def test_a_typo_is_named_before_the_key_it_misspells_is_missing() -> None:
    """`rod_lenght` leaves `rod_length` missing: the typo is the message, not the missing
    key (which pydantic named first)."""
    data = inline4()
    data["crank_train"]["rod_lenght"] = data["crank_train"].pop("rod_length")
    data["masses"].pop("piston")  # a second problem, further on: the typo still comes first
    with pytest.raises(InputError) as caught:
        spec_from_dict(data)
    assert caught.value.field == "crank_train.rod_lenght"
    assert "did you mean 'rod_length'" in caught.value.allowed


def test_settings_name_the_closest_setting_and_a_decimal_comma(
    capsys: pytest.CaptureFixture[str],
) -> None:
    with pytest.raises(InputError) as caught:
        parse_options(AnalysisOptions, {"order": "3"})
    assert str(caught.value) == "order = '3': unknown setting; did you mean 'orders'?"
    with pytest.raises(InputError) as caught:
        parse_options(CounterweightOptions, {"max_mass": "0,4 kg"}, lambda f: "--" + f)
    assert str(caught.value) == "--max_mass = '0,4 kg': has a decimal comma; write '0.4 kg'"
    code, out, err = run_cli(["balance", "inline4", "--balance-factor", "0,5"], capsys)
    assert (code, out) == (2, "")
    assert err == "error: --balance-factor = '0,5': has a decimal comma; write '0.5'\n"


# --------------------------------------------------------------------------- plausibility
def unusual(tmp_path: Path) -> Path:
    """The inline-4 preset at 12000 rpm with a 250 mm rod: 2 r omega / pi = 34.4 m/s and
    250 / 43 = 5.81 crank radii."""
    data = inline4()
    data["speed"] = "12000 rpm"
    data["crank_train"]["rod_length"] = "250 mm"
    path = tmp_path / "unusual.json"
    path.write_text(json.dumps(data))
    return path


def test_the_schema_says_what_is_unusual(tmp_path: Path) -> None:
    notes = load_engine(unusual(tmp_path)).plausibility()
    assert [note.field for note in notes] == ["speed", "crank_train.rod_length"]
    assert notes[0].text.startswith("mean piston speed 34.4 m/s, above about 30 m/s")
    assert notes[1].text.startswith("the rod is 5.81 crank radii long, outside the usual 2.8-4.5")
    assert load_engine("inline4").plausibility() == []
    assert MAX_PISTON_SPEED == 30.0 and ROD_RATIO == (2.8, 4.5)


@pytest.mark.parametrize("command", ["analyze", "balance"])
def test_notes_in_the_table_not_in_the_json(
    command: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = str(unusual(tmp_path))
    code, out, err = run_cli([command, path], capsys)
    assert code == 0 and err == "", err
    notes = [line for line in out.splitlines() if line.startswith("note: ")]
    assert "note: mean piston speed 34.4 m/s, above about 30 m/s; check the speed and " in out
    assert any(line.startswith("note: the rod is 5.81 crank radii long") for line in notes)
    code, out, err = run_cli([command, path, "--format", "json"], capsys)
    assert code == 0 and "piston speed" not in out and "crank radii" not in out
    code, out, err = run_cli([command, "inline4"], capsys)
    assert code == 0 and "piston speed" not in out


def test_the_web_form_warns_with_the_schema_s_notes() -> None:
    from crankbalance.web.project import Project

    project = Project.from_preset("inline4")
    assert project.warnings == {}
    project.set("speed", "12000 rpm")
    assert project.warnings["speed"].startswith("Warning: mean piston speed 34.4 m/s")
    project.set("rod_length", "250 mm")
    assert project.warnings["rod_length"].startswith("Warning: the rod is 5.81 crank radii")
    assert project.spec is not None and not project.errors  # a warning is not an error


#: every field of three lengths x, y, z (a point or a box's edges): one declaration
#: (schema.core.three_lengths), so one set of words and messages
THREE_LENGTHS = [
    ("CrankTrain", "moment_point"),
    ("Mount", "position"),
    ("PowertrainEstimate", "block_size"),
    ("PowertrainEstimate", "block_center"),
    ("PowertrainEstimate", "gearbox_size"),
    ("PowertrainEstimate", "gearbox_center"),
    ("Powertrain", "cg"),
    ("AnalysisOptions", "moment_point"),
    ("MountsOptions", "point"),
]


@pytest.mark.parametrize(("schema", "name"), THREE_LENGTHS)
def test_fields_of_three_lengths_are_one_declaration(schema: str, name: str) -> None:
    from crankbalance.schema import engine, settings
    from crankbalance.schema.core import allowed, three_lengths

    spec = getattr(engine, schema, None) or getattr(settings, schema)
    got = spec.FIELDS[name]
    edges = {"gt": 0.0} if name.endswith("_size") else {}  # a box's edges: above zero
    made = three_lengths(got.title, got.description, default=got.default, hint=got.hint, **edges)
    assert repr(got) == repr(made)
    assert got.hint.startswith("x, y, z, e.g. ")
    assert allowed(got).startswith("3 values, each ")


@pytest.mark.parametrize(
    ("where", "value", "message"),
    [
        ("option", "1 mm, 2 mm", "--moment-point = ['1 mm', '2 mm']: needs exactly 3 entries"),
        ("option", "1 mm, 2 mm, 3 mm, 4 mm", "--moment-point = '4 entries': takes exactly 3"),
        ("option", "1 mm, 2 kg, 3 mm", "--moment-point = '2 kg': has the wrong unit for a length"),
        ("file", ["1 mm", "2 mm"], "crank_train.moment_point = ['1 mm', '2 mm']: needs exactly 3"),
        ("file", ["1 mm", "2 kg", "0"], "crank_train.moment_point[1] = '2 kg': has the wrong unit"),
    ],
)
def test_a_point_of_three_lengths_is_named_as_written(
    where: str, value: Any, message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    if where == "option":
        code, _, err = run_cli(["analyze", "inline4", "--moment-point", value], capsys)
    else:
        data = inline4()
        data["crank_train"]["moment_point"] = value
        with pytest.raises(InputError) as error:
            spec_from_dict(data)
        code, err = 2, f"error: {error.value}\n"
    assert code == 2 and err.startswith(f"error: {message}"), err
    assert err.count("\n") == 1
