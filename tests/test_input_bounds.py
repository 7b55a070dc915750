"""Bounded input (issue 12): every engine-file example of the issue as a test.

Files are read with a size cap and only when they are regular files; TOML and JSON are
parsed with bounded nesting and number length, duplicate JSON keys refused; counts and
flags take whole numbers only; the work an engine file asks for is capped; quantities are
checked after unit conversion against a documented physical range. Each refusal is one
line naming the field as written, exit status 2.
"""

from __future__ import annotations

import json
import os
import re
import socket
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine, parse_engine_text, preset_text
from crankbalance.io.pressure_csv import read_pressure_csv
from crankbalance.io.reading import MAX_DEPTH, parse_json, parse_toml, read_text
from crankbalance.schema import core as schema_core
from crankbalance.schema.engine import MAX_CYLINDERS, MAX_THROWS, parse_in_range
from crankbalance.units import RANGES

from .conftest import hang_guard, run_cli

#: Seconds a test may wait on a read before it counts as hung (a guard, not a timing test).
HANG_GUARD = 60


def one_line_error(code: int, out: str, err: str, *needles: str) -> str:
    """The one error line of a refused run, checked to name each of ``needles``."""
    assert code == 2, (code, out, err)
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    assert "Traceback" not in err and out == ""
    for needle in needles:
        assert needle in lines[0], (needle, lines[0])
    return lines[0]


def inline4() -> dict[str, Any]:
    import tomllib

    return tomllib.loads(preset_text("inline4"))


def write_json(tmp_path: Path, data: Any) -> Path:
    path = tmp_path / "engine.json"
    path.write_text(json.dumps(data, allow_nan=True))
    return path


# --------------------------------------------------------------------------- files
DEVICES = [p for p in ("/dev/zero", "/dev/urandom", "/dev/null") if os.path.exists(p)]


@pytest.mark.parametrize("device", DEVICES)
@pytest.mark.parametrize("command", ["analyze", "balance"])
def test_devices_are_refused_without_reading(
    device: str, command: str, capsys: pytest.CaptureFixture[str]
) -> None:
    """`crankbalance analyze /dev/zero` read without bound until a MemoryError;
    /dev/urandom hung."""
    with hang_guard(HANG_GUARD):
        code, out, err = run_cli([command, device], capsys)
    one_line_error(code, out, err, f"engine = '{device}'", "is a device")


def test_fifo_is_refused_without_waiting_for_a_writer(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    fifo = tmp_path / "engine.toml"
    os.mkfifo(fifo)
    with hang_guard(HANG_GUARD):
        code, out, err = run_cli(["analyze", str(fifo)], capsys)
        one_line_error(code, out, err, "engine = ", "pipe")
        with pytest.raises(InputError, match="pipe"):
            read_pressure_csv(fifo)


def test_socket_and_folder_and_symlink_to_a_device_are_refused(tmp_path: Path) -> None:
    with socket.socket(socket.AF_UNIX) as server:
        server.bind(str(tmp_path / "s"))
        with pytest.raises(InputError, match="socket"):
            load_engine(tmp_path / "s")
    with pytest.raises(InputError, match="folder"):
        load_engine(tmp_path)
    if DEVICES:
        (tmp_path / "zero.toml").symlink_to(DEVICES[0])
        with hang_guard(HANG_GUARD), pytest.raises(InputError, match="device"):
            load_engine(tmp_path / "zero.toml")


@pytest.mark.parametrize("target", ["folder", *DEVICES])
def test_rebalance_parts_must_be_a_file(
    target: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`rebalance --parts SOME_DIRECTORY` ended in a traceback."""
    path = str(tmp_path) if target == "folder" else target
    with hang_guard(HANG_GUARD):
        code, out, err = run_cli(["rebalance", "--parts", path], capsys)
    one_line_error(code, out, err, "parts = ", "folder" if target == "folder" else "device")


def test_read_text_bounds(tmp_path: Path) -> None:
    path = tmp_path / "f.toml"
    path.write_bytes(b"a" * 101)
    with pytest.raises(InputError, match="larger than 100 bytes"):
        read_text(path, "engine", "an engine file", 100)
    path.write_bytes(b"\xef\xbb\xbfname = 'x'\n")  # a byte-order mark is dropped
    assert read_text(path, "engine", "an engine file", 100) == "name = 'x'\n"
    for raw in (b"\xff\xfe", b"a\x00b"):
        path.write_bytes(raw)
        with pytest.raises(InputError, match="UTF-8 text, not binary"):
            read_text(path, "engine", "an engine file", 100)
    with pytest.raises(InputError, match="cannot be read"):
        read_text(tmp_path / "missing.toml", "engine", "an engine file", 100)


# --------------------------------------------------------------------------- TOML and JSON
NESTED = [
    ("TOML arrays 500 deep", "engine.toml", "speed = " + "[" * 500 + "]" * 500),
    ("TOML inline tables 500 deep", "engine.toml", "speed = " + "{a = " * 500 + "1" + "}" * 500),
    ("TOML dotted key 500 deep", "engine.toml", "a" + ".a" * 500 + " = 1"),
    ("TOML table header 500 deep", "engine.toml", "[" + ".".join(["a"] * 500) + "]"),
    ("JSON 500 deep", "engine.json", '{"speed": ' + "[" * 500 + "]" * 500 + "}"),
]


@pytest.mark.parametrize("name,filename,text", NESTED, ids=[c[0] for c in NESTED])
def test_deep_nesting_is_refused(
    name: str, filename: str, text: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """TOML nested 500 deep ended in a RecursionError, in the CLI and the web upload."""
    path = tmp_path / filename
    path.write_text(text)
    code, out, err = run_cli(["analyze", str(path)], capsys)
    one_line_error(code, out, err, str(path), f"deeper than {MAX_DEPTH} levels")
    fmt = "json" if filename.endswith(".json") else "toml"
    with pytest.raises(InputError, match="deeper than"):
        parse_engine_text(text, "upload.toml", fmt)  # the parser of the web upload and API


def test_nesting_up_to_the_cap_is_read() -> None:
    depth = MAX_DEPTH
    assert parse_toml("a = " + "[" * depth + "]" * depth, "f")["a"] is not None
    assert parse_json("[" * depth + "]" * depth, "f") is not None
    # brackets and dots inside strings and comments are not nesting
    text = 'a = "[[[[{{{{" # ]]]]]]]]\nb = """\n' + "[" * 100 + '"""\n"x.y.z" = 1\n'
    assert parse_toml(text, "f")["b"] == "[" * 100


@pytest.mark.parametrize("suffix", [".toml", ".json"])
def test_5000_digit_cylinders_is_refused(
    suffix: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A 5000-digit `cylinders` ended in a ValueError (Python's integer string limit)."""
    digits = "9" * 5000
    if suffix == ".toml":
        text = preset_text("inline4").replace("cylinders = 4", f"cylinders = {digits}")
    else:
        text = json.dumps(inline4()).replace('"cylinders": 4', f'"cylinders": {digits}')
    assert digits in text
    path = tmp_path / f"engine{suffix}"
    path.write_text(text)
    code, out, err = run_cli(["analyze", str(path)], capsys)
    one_line_error(code, out, err, str(path), "longer than 100 characters")
    with pytest.raises(InputError, match="longer than"):
        parse_engine_text(text, "upload", suffix[1:])
    hexadecimal = preset_text("inline4").replace("cylinders = 4", "cylinders = 0x" + "f" * 4000)
    with pytest.raises(InputError, match="longer than"):
        parse_engine_text(hexadecimal, "upload")


def test_duplicate_json_key_is_refused_naming_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """JSON with a duplicate key was read with the first value dropped."""
    text = json.dumps(inline4())
    text = text.replace('"speed": "6000 rpm"', '"speed": "2000 rpm", "speed": "6000 rpm"')
    path = tmp_path / "engine.json"
    path.write_text(text)
    code, out, err = run_cli(["analyze", str(path)], capsys)
    one_line_error(code, out, err, str(path), "'speed' twice")
    nested = json.dumps(inline4()).replace('"cylinders": 4', '"cylinders": 4, "cylinders": 4')
    with pytest.raises(InputError, match="'cylinders' twice"):
        parse_engine_text(nested, "upload", "json")


# --------------------------------------------------------------------------- strict types
def ct(**changes: Any) -> Callable[[dict[str, Any]], None]:
    return lambda d: d["crank_train"].update(changes)


def ms(**changes: Any) -> Callable[[dict[str, Any]], None]:
    return lambda d: d["masses"].update(changes)


STRICT = [
    ("cylinders = true", ct(cylinders=True, firing_order=[1]), "crank_train.cylinders"),
    ('cylinders = "4"', ct(cylinders="4"), "crank_train.cylinders"),
    ("cylinders = 4.0", ct(cylinders=4.0), "crank_train.cylinders"),
    ("conrod_rotating_fraction = true", ms(conrod_rotating_fraction=True), "conrod_rotating"),
    ('conrod_rotating_fraction = "0.67"', ms(conrod_rotating_fraction="0.67"), "conrod_rotating"),
    ("strokes = true", ct(strokes=True), "crank_train.strokes"),
    ('strokes = "4"', ct(strokes="4"), "crank_train.strokes"),
    ("firing order of booleans", ct(firing_order=[True, 3, 4, 2]), "crank_train.firing_order"),
    ('firing order of "1"', ct(firing_order=["1", 3, 4, 2]), "crank_train.firing_order"),
    (
        "web flag true",
        lambda d: d.update(counterweights={"cg_radius": "30 mm", "webs": [True] * 8}),
        "counterweights.webs",
    ),
    (
        "override cylinders true",
        ms(override=[{"cylinders": [True], "piston": "300 g"}]),
        "masses.override[0].cylinders",
    ),
    (
        "balance factor as text",
        lambda d: d.update(counterweights={"cg_radius": "30 mm", "balance_factor": "0.5"}),
        "counterweights.balance_factor",
    ),
]


@pytest.mark.parametrize("name,change,field", STRICT, ids=[c[0] for c in STRICT])
def test_counts_and_flags_take_whole_numbers_only(
    name: str,
    change: Callable[[dict[str, Any]], None],
    field: str,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    """`cylinders = true` was read as a one-cylinder engine, `cylinders = "4"` as 4 and
    `conrod_rotating_fraction = true` as 1."""
    data = inline4()
    change(data)
    code, out, err = run_cli(["analyze", str(write_json(tmp_path, data))], capsys)
    one_line_error(code, out, err, field)


def test_plain_numbers_stay_accepted(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Whole numbers where a fraction is expected, and the presets, are read as before."""
    data = inline4()
    data["masses"]["conrod_rotating_fraction"] = 1
    data["counterweights"] = {"cg_radius": "30 mm", "balance_factor": 1, "webs": [1, 0] * 4}
    code, _out, err = run_cli(["balance", str(write_json(tmp_path, data))], capsys)
    assert code == 0, err


# --------------------------------------------------------------------------- bounded work
def custom(throws: int, banks: int) -> dict[str, Any]:
    data = inline4()
    train = data["crank_train"]
    for key in ("cylinders", "firing_order", "crank_pitch"):
        train.pop(key)
    train["layout"] = "custom"
    train["throw"] = [
        {"position": f"{k * 90} mm", "angle": "0 deg", "banks": ["0 deg"] * banks}
        for k in range(throws)
    ]
    return data


@pytest.fixture
def parse_count(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """How many quantity strings the engine file's validation parsed."""
    calls = [0]
    parse = schema_core.parse_quantity

    def counting(*args: Any, **kwargs: Any) -> float:
        calls[0] += 1
        return parse(*args, **kwargs)

    monkeypatch.setattr(schema_core, "parse_quantity", counting)
    return calls


BIG_BODIES = [
    ("throw_angles with 20000 entries", "throw_angles", "crank_train.throw_angles"),
    ("one custom throw with 15000 banks", "banks", "crank_train.throw[0].banks"),
    ("2500 custom throws", "throws", "crank_train.throw"),
]


@pytest.mark.parametrize("name,kind,field", BIG_BODIES, ids=[c[0] for c in BIG_BODIES])
def test_large_bodies_are_refused_before_the_work(
    name: str, kind: str, field: str, parse_count: list[int]
) -> None:
    """Bodies under the 200 kB limit took 20-55 s: they are refused after at most a cap's
    worth of quantities is parsed (a count of the work, not a timing)."""
    if kind == "throw_angles":
        data = inline4()
        data["crank_train"]["throw_angles"] = ["0 deg"] * 20_000
    else:
        data = custom(1, 15_000) if kind == "banks" else custom(2_500, 1)
    text = json.dumps(data)
    assert len(text) < 200_000 * 2
    with pytest.raises(InputError) as error:
        parse_engine_text(text, "upload", "json")
    assert str(error.value).startswith(f"{field} = ") and "at most" in str(error.value)
    assert parse_count[0] < 4 * MAX_CYLINDERS


def test_throw_angles_count_must_match_the_throws() -> None:
    data = inline4()
    data["crank_train"]["throw_angles"] = ["0 deg"] * 5
    with pytest.raises(InputError, match="one angle per throw; this engine has 4 throws"):
        parse_engine_text(json.dumps(data), "upload", "json")


def test_caps_on_cylinders_throws_and_banks() -> None:
    assert load_engine_dict(custom(MAX_THROWS, 1)).crank_train.cylinder_count == MAX_THROWS
    assert load_engine_dict(custom(1, MAX_CYLINDERS)).crank_train.cylinder_count == 64
    with pytest.raises(InputError, match=f"cylinders; at most {MAX_CYLINDERS}"):
        load_engine_dict(custom(2, MAX_CYLINDERS))
    with pytest.raises(InputError, match="crank_train.throw = '65 entries'"):
        load_engine_dict(custom(MAX_THROWS + 1, 1))
    data = inline4()
    data["crank_train"].update(cylinders=MAX_CYLINDERS + 1)
    data["crank_train"].pop("firing_order")
    with pytest.raises(InputError, match="crank_train.cylinders"):
        load_engine_dict(data)
    data["masses"]["override"] = [{"cylinders": [1], "piston": "300 g"}] * 200
    data["crank_train"].update(cylinders=4)
    with pytest.raises(InputError, match="masses.override = '200 entries'"):
        load_engine_dict(data)
    data = inline4()
    data["name"] = "x" * 10_000
    with pytest.raises(InputError, match="at most 200 characters"):
        load_engine_dict(data)


def load_engine_dict(data: dict[str, Any]) -> Any:
    return parse_engine_text(json.dumps(data), "upload", "json")


# --------------------------------------------------------------------------- ranges
RANGE_CASES = [
    ("speed = 1e300 rpm", "balance", lambda d: d.update(speed="1e300 rpm"), "speed"),
    ("speed = 1e-300 rpm", "balance", lambda d: d.update(speed="1e-300 rpm"), "speed"),
    ("rod_length = 1e308 km", "analyze", ct(rod_length="1e308 km"), "crank_train.rod_length"),
    ("crank_pitch = 1e308 km", "balance", ct(crank_pitch="1e308 km"), "crank_train.crank_pitch"),
    ("crank_radius = 1e-320 mm", "analyze", ct(crank_radius="1e-320 mm"), "crank_radius"),
    ("piston = 1e30 kg", "analyze", ms(piston="1e30 kg"), "masses.piston"),
    ("conrod_inertia = 1e9", "analyze", ms(conrod_inertia="1e9 kg*m^2"), "masses.conrod_inertia"),
    ("bank angle = 1e20 deg", "analyze", ct(throw_angles=["1e20 deg"] * 4), "throw_angles[0]"),
    ("pin_offset = -1e10 m", "analyze", ct(pin_offset="-1e10 m"), "crank_train.pin_offset"),
    ("quantity of 200 chars", "analyze", ct(crank_radius="4" * 197 + " mm"), "crank_radius"),
]


@pytest.mark.parametrize("name,command,change,field", RANGE_CASES, ids=[c[0] for c in RANGE_CASES])
def test_values_are_checked_after_unit_conversion(
    name: str,
    command: str,
    change: Callable[[dict[str, Any]], None],
    field: str,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    """`speed = "1e300 rpm"` gave an OverflowError, `"1e-300 rpm"` with `balance` a
    ZeroDivisionError, `rod_length = "1e308 km"` a NaN error and `crank_pitch = "1e308 km"`
    a LinAlgError: values were checked before unit conversion, not after."""
    data = inline4()
    change(data)
    code, out, err = run_cli([command, str(write_json(tmp_path, data))], capsys)
    line = one_line_error(code, out, err, field)
    assert "must" in line


def test_range_message_names_the_field_and_the_range(tmp_path: Path) -> None:
    data = inline4()
    data["speed"] = "1e300 rpm"
    with pytest.raises(InputError) as error:
        load_engine(write_json(tmp_path, data))
    assert str(error.value) == "speed = '1e300 rpm': must lie between 1 rpm and 1e5 rpm"


@pytest.mark.parametrize("kind", sorted(RANGES))
def test_range_edges(kind: str) -> None:
    """The edges of each documented range are accepted, beyond them refused; zero is left
    to each field's own rule."""
    low, high = RANGES[kind]
    assert parse_in_range(low, kind) <= parse_in_range(high, kind)
    assert parse_in_range("-" + high, kind) == -parse_in_range(high, kind)
    number, unit = high.split(" ", 1)
    with pytest.raises(InputError, match=re.escape(f"must lie between {low} and {high}")):
        parse_in_range(f"{float(number) * 1.01} {unit}", kind, "x")
    number, unit = low.split(" ", 1)
    if float(number) > 0:
        with pytest.raises(InputError, match="must lie between"):
            parse_in_range(f"{float(number) * 0.99} {unit}", kind, "x")
    assert parse_in_range(f"0 {unit}", kind) == 0.0


def test_presets_and_examples_lie_within_the_ranges() -> None:
    """Every preset loads (their quantities lie within the documented ranges)."""
    from crankbalance.io.engine_file import list_presets

    for name in list_presets():
        assert load_engine(name).speed > 0
    root = Path(__file__).resolve().parents[1]
    for path in (root / "examples").glob("paper_*.toml"):
        assert load_engine(path).speed > 0


def test_a_key_with_control_characters_is_quoted_in_the_message(tmp_path: Path) -> None:
    """An unknown key is named as written, but a line break in it never reaches the
    terminal: the message stays one line."""
    data = inline4()
    data["crank_train"]["bad\nkey\x1b[2J"] = 1
    with pytest.raises(InputError) as error:
        load_engine(write_json(tmp_path, data))
    message = str(error.value)
    assert message.startswith('crank_train."bad\\nkey\\u001b[2J"') and "\n" not in message


# --------------------------------------------------------------------------- overrides
def with_overrides(*tables: dict[str, Any]) -> dict[str, Any]:
    data = inline4()
    data["masses"]["override"] = list(tables)
    return data


def test_two_overrides_giving_a_cylinder_the_same_mass_are_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Issue 25: two [[masses.override]] tables for cylinder 3; the later one used to win
    without a word. One line names both tables."""
    data = with_overrides(
        {"cylinders": [3], "piston": "480 g"},
        {"throws": [2], "crankpin": "420 g"},
        {"cylinders": [1, 3], "piston": "490 g"},
    )
    code, out, err = run_cli(["analyze", str(write_json(tmp_path, data))], capsys)
    one_line_error(
        code,
        out,
        err,
        "masses.override[0] and masses.override[2] both give cylinder 3 its piston",
        "give it once",
    )


@pytest.mark.parametrize(
    ("tables", "words"),
    [
        (
            ({"throws": [2], "crankpin": "420 g"}, {"throws": [4, 2], "crankpin": "410 g"}),
            "masses.override[0] and masses.override[1] both give throw 2 its crankpin",
        ),
        (  # the conrod's split given two ways: the later would replace the earlier
            (
                {"cylinders": [2], "conrod_rotating_fraction": 0.7},
                {"cylinders": [2], "conrod_cg_from_big_end": "40 mm"},
            ),
            "masses.override[0] and masses.override[1] both give cylinder 2 its "
            "conrod_cg_from_big_end",
        ),
        (({"cylinders": [3, 3], "piston": "480 g"},), "lists cylinder 3 twice"),
        (({"throws": [1, 2, 1], "crankpin": "420 g"},), "lists throw 1 twice"),
    ],
)
def test_overlapping_overrides_name_both_places(tables: tuple[Any, ...], words: str) -> None:
    with pytest.raises(InputError, match=re.escape(words)):
        load_engine_dict(with_overrides(*tables))


def test_overrides_of_different_masses_for_one_cylinder_combine() -> None:
    """Two tables that give one cylinder different masses lose nothing (the web's crank
    editor writes one table per row): both apply."""
    from crankbalance.studies.build import build_model

    split = load_engine_dict(
        with_overrides(
            {"cylinders": [3], "piston": "480 g"}, {"cylinders": [3], "wrist_pin": "90 g"}
        )
    )
    together = load_engine_dict(
        with_overrides({"cylinders": [3], "piston": "480 g", "wrist_pin": "90 g"})
    )
    masses = build_model(split).reciprocating_mass
    assert masses[2] != masses[0]  # the overrides apply to cylinder 3
    assert masses.tolist() == pytest.approx(build_model(together).reciprocating_mass.tolist())
