"""Malformed engine files and CLI calls: one clear message naming the field, exit 2,
no traceback (issue 2)."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from crankbalance.io.engine_file import dumps_toml

from .conftest import paper_inline3_dict, run_cli


def edit(change: Callable[[dict[str, Any]], None]) -> dict[str, Any]:
    data = paper_inline3_dict()
    change(data)
    return data


def ct(**kw: Any) -> Callable[[dict[str, Any]], None]:
    return lambda d: d["crank_train"].update(kw)


def ms(**kw: Any) -> Callable[[dict[str, Any]], None]:
    return lambda d: d["masses"].update(kw)


def drop(*path: str) -> Callable[[dict[str, Any]], None]:
    def change(d: dict[str, Any]) -> None:
        for p in path[:-1]:
            d = d[p]
        del d[path[-1]]

    return change


CASES: list[tuple[str, Callable[[dict[str, Any]], None], str]] = [
    ("negative mass", ms(piston="-500 g"), "masses.piston"),
    ("zero conrod", ms(conrod="0 g"), "masses.conrod"),
    ("rod shorter than crank", ct(rod_length="30 mm"), "crank_train.rod_length"),
    ("firing order repeats", ct(firing_order=[1, 1, 2]), "crank_train.firing_order"),
    ("firing order too short", ct(firing_order=[1, 2]), "crank_train.firing_order"),
    ("firing order not integers", ct(firing_order=["a", 2, 3]), "crank_train.firing_order"),
    ("zero cylinders", ct(cylinders=0), "crank_train.cylinders"),
    ("odd vee", ct(layout="vee", bank_angle="90 deg"), "crank_train.cylinders"),
    ("unknown layout", ct(layout="star"), "crank_train.layout"),
    (
        "bank angle out of range",
        lambda d: d["crank_train"].update(
            layout="vee", cylinders=4, bank_angle="200 deg", firing_order=None
        ),
        "crank_train.bank_angle",
    ),
    (
        "bank angle missing",
        lambda d: (
            d["crank_train"].update(layout="vee", cylinders=4),
            d["crank_train"].pop("firing_order"),
        ),
        "crank_train.bank_angle",
    ),
    ("bank angle on inline", ct(bank_angle="60 deg"), "crank_train.bank_angle"),
    ("missing unit (number)", ct(crank_radius=40), "crank_train.crank_radius"),
    ("missing unit (string)", ct(crank_radius="40"), "crank_train.crank_radius"),
    ("mass for a length", ct(crank_radius="40 kg"), "crank_train.crank_radius"),
    ("length for a mass", ms(piston="500 mm"), "masses.piston"),
    ("NaN quantity", ct(crank_radius="nan mm"), "crank_train.crank_radius"),
    (
        "NaN fraction",
        lambda d: (
            d["masses"].pop("conrod_cg_from_big_end"),
            d["masses"].update(conrod_rotating_fraction=float("nan")),
        ),
        "masses.conrod_rotating_fraction",
    ),
    (
        "fraction above one",
        lambda d: (
            d["masses"].pop("conrod_cg_from_big_end"),
            d["masses"].update(conrod_rotating_fraction=1.5),
        ),
        "masses.conrod_rotating_fraction",
    ),
    ("unknown top-level key", lambda d: d.update(colour="red"), "colour"),
    ("misspelt nested key", ms(pistn="500 g"), "masses.pistn"),
    ("missing speed", drop("speed"), "speed"),
    ("speed in metres", lambda d: d.update(speed="2000 m"), "speed"),
    ("negative speed", lambda d: d.update(speed="-100 rpm"), "speed"),
    ("unknown kinematics", lambda d: d.update(kinematics="approx"), "kinematics"),
    ("three strokes", ct(strokes=3), "crank_train.strokes"),
    ("throw angles count", ct(throw_angles=["0 deg"]), "crank_train.throw_angles"),
    (
        "web pattern length",
        lambda d: d["counterweights"].update(webs=[1, 1]),
        "counterweights.webs",
    ),
    ("conrod without split", drop("masses", "conrod_cg_from_big_end"), "masses.conrod"),
    ("conrod CG beyond rod", ms(conrod_cg_from_big_end="200 mm"), "masses.conrod_cg_from_big_end"),
    (
        "override of a missing cylinder",
        ms(override=[{"cylinders": [7], "piston": "400 g"}]),
        "masses.override[0].cylinders",
    ),
    (
        "custom without throws",
        lambda d: d["crank_train"].update(layout="custom"),
        "crank_train.throw",
    ),
    (
        "custom with an unused crank pitch",
        lambda d: (
            d["crank_train"].update(
                layout="custom",
                throw=[
                    {"position": f"{k * 90} mm", "angle": "0 deg", "banks": ["0 deg"]}
                    for k in range(4)
                ],
            ),
            d["crank_train"].pop("cylinders"),
            d["crank_train"].pop("firing_order"),
        ),
        "crank_train.crank_pitch",
    ),
    (
        "radial with two cylinders",
        lambda d: d["crank_train"].update(layout="radial", cylinders=2, firing_order=None),
        "crank_train.cylinders",
    ),
    ("missing crank pitch", drop("crank_train", "crank_pitch"), "crank_train.crank_pitch"),
    ("missing piston", drop("masses", "piston"), "masses.piston"),
    (
        "inconsistent vee firing order",
        lambda d: (
            d.pop("counterweights"),
            d["crank_train"].update(
                layout="vee", cylinders=8, bank_angle="90 deg", firing_order=list(range(1, 9))
            ),
        ),
        "crank_train.firing_order",
    ),
    (
        "counterweight radius zero",
        lambda d: d["counterweights"].update(cg_radius="0 mm"),
        "counterweights.cg_radius",
    ),
    (
        "shaft length negative",
        lambda d: d["balance_shafts"]["primary"].update(length="-2 mm"),
        "balance_shafts.primary.length",
    ),
    ("string for a number", ct(cylinders="three"), "crank_train.cylinders"),
]


def check_message(code: int, err: str, field: str) -> None:
    assert code == 2, err
    assert "Traceback" not in err
    lines = [line for line in err.strip().splitlines() if line]
    assert len(lines) == 1, f"one message, got: {err!r}"
    assert lines[0].startswith("error: ")
    assert field in lines[0], f"the message names {field}: {lines[0]!r}"


@pytest.mark.parametrize("name,change,field", CASES, ids=[c[0] for c in CASES])
def test_malformed_engine_file(
    name: str,
    change: Callable[[dict[str, Any]], None],
    field: str,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    data = edit(change)
    data = json.loads(json.dumps(data, allow_nan=True))  # drop None values below
    for section in data.values():
        if isinstance(section, dict):
            for k in [k for k, v in section.items() if v is None]:
                del section[k]
    path = tmp_path / "engine.json"
    path.write_text(json.dumps(data, allow_nan=True))
    code, out, err = run_cli(["analyze", str(path)], capsys)
    check_message(code, err, field)
    assert out == ""


RAW_FILES = [
    ("empty file", b"", "engine.toml"),
    ("only whitespace", b"  \n\n", "engine.toml"),
    ("binary file", bytes(range(256)), "engine.toml"),
    ("TOML syntax error", b'name = "x"\nspeed = 2000 rpm\n', "engine.toml"),
    ("JSON syntax error", b'{"speed": }', "engine.json"),
    ("JSON list", b"[1, 2, 3]", "engine.json"),
]


@pytest.mark.parametrize("name,raw,filename", RAW_FILES, ids=[c[0] for c in RAW_FILES])
def test_unreadable_files(
    name: str, raw: bytes, filename: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / filename
    path.write_bytes(raw)
    code, _out, err = run_cli(["analyze", str(path)], capsys)
    # a binary file is refused by the reader: `engine = 'PATH'` (a long PATH is shortened)
    field = {"JSON list": "engine file", "binary file": "engine = "}.get(name, str(path))
    check_message(code, err, field)


@pytest.mark.parametrize(
    "args,needle",
    [
        (["analyze", "no-such-engine"], "engine"),
        (["analyze", "inline4", "--orders", "0"], "--orders"),
        (["analyze", "inline4", "--format", "xml"], "--format"),
        (["analyze"], "ENGINE"),
        (["frobnicate"], "frobnicate"),
    ],
)
def test_bad_cli_calls(args: list[str], needle: str, capsys: pytest.CaptureFixture[str]) -> None:
    code, _out, err = run_cli(args, capsys)
    assert code == 2
    assert "Traceback" not in err
    assert needle in err


def test_folder_instead_of_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, _out, err = run_cli(["analyze", str(tmp_path)], capsys)
    check_message(code, err, "engine")


def test_toml_writer_roundtrip() -> None:
    import tomllib

    data = paper_inline3_dict()
    assert tomllib.loads(dumps_toml(data)) == data


def test_atomic_write_keeps_normal_permissions(tmp_path: Path) -> None:
    import os
    import stat

    from crankbalance.io.files import write_atomic

    target = tmp_path / "report.html"
    write_atomic(target, "x")
    umask = os.umask(0)
    os.umask(umask)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~umask
    os.chmod(target, 0o640)
    write_atomic(target, "y")
    assert stat.S_IMODE(target.stat().st_mode) == 0o640 and target.read_text() == "y"


@pytest.mark.parametrize("text", ["20..30 mm", "20 30 mm", "2 * 3 mm", "40 mm*2", "nan mm"])
def test_quantity_must_be_one_number_and_a_unit(text: str) -> None:
    """pint reads '20..30 mm' as 20. x .30 mm = 6 mm and '20 30 mm' as 600 mm; a quantity
    field takes one number and a unit, anything else is refused."""
    from crankbalance.errors import InputError
    from crankbalance.units import parse_quantity

    with pytest.raises(InputError, match="crank_radius"):
        parse_quantity(text, "length", "crank_radius")


def test_a_long_value_keeps_its_start_and_its_end() -> None:
    """A value longer than a message can show keeps its start and end: a long path keeps
    its file name (it was cut at 77 characters, losing the name in a deep folder)."""
    from crankbalance.errors import InputError

    path = "/tmp/" + "deep/" * 30 + "parts.csv"
    message = str(InputError("parts", path, "must be UTF-8 text"))
    shown = message.split(" = ", 1)[1].split(": must", 1)[0]
    assert len(shown) == 80 and shown.startswith("'/tmp/deep/") and shown.endswith("parts.csv'")
    assert str(InputError("x", "short", "bad")) == "x = 'short': bad"
