"""Messages that point at the fix (issue 29): a misspelt key or table named as typed with
its closest allowed key, "did you mean" for presets and commands, the unit spellings people
use, and a spreadsheet given as an engine file explained."""

from __future__ import annotations

from pathlib import Path

import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine, preset_text
from crankbalance.units import parse_quantity

from .conftest import run_cli


def _engine(tmp_path: Path, old: str, new: str, suffix: str = ".toml") -> str:
    text = preset_text("single")
    assert old in text
    path = tmp_path / f"engine{suffix}"
    path.write_text(text.replace(old, new, 1))
    return str(path)


@pytest.mark.parametrize(
    ("old", "new", "said"),
    [
        (
            "rod_length =",
            "rod_lenght =",
            "crank_train.rod_lenght = '110 mm': unknown key; did you mean 'rod_length'?",
        ),
        ("[masses]", "[mases]", "mases: unknown key; did you mean 'masses'?"),
    ],
)
def test_a_misspelt_required_key_or_table_is_named_as_typed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], old: str, new: str, said: str
) -> None:
    code, _out, err = run_cli(["analyze", _engine(tmp_path, old, new)], capsys)
    assert code == 2
    assert err.strip() == f"error: {said}"
    assert "missing" not in err


def test_a_misspelt_preset_gets_the_closest_preset() -> None:
    with pytest.raises(InputError, match="did you mean the preset 'v8-crossplane'"):
        load_engine("v8-crosplane")
    with pytest.raises(InputError) as far:
        load_engine("nothing-like-an-engine")
    assert "did you mean" not in str(far.value)


@pytest.mark.parametrize(
    ("args", "said"),
    [
        (["analyse", "inline4"], "No such command 'analyse'; did you mean 'analyze'?"),
        (["shop", "mach"], "No such command 'mach'; did you mean 'match'?"),
        (["counterweight", "optimise"], "did you mean 'optimize'?"),
    ],
)
def test_a_misspelt_command_gets_the_closest_command(
    capsys: pytest.CaptureFixture[str], args: list[str], said: str
) -> None:
    code, _out, err = run_cli(args, capsys)
    assert code == 2
    assert said in err and err.count("\n") == 1


@pytest.mark.parametrize(
    ("typed", "kind", "written"),
    [
        ("12500 RPM", "speed", "12500 rpm"),
        ("12500 Rpm", "speed", "12500 rpm"),
        ("30 Nm", "torque", "30 N*m"),
        ("3 kNm", "torque", "3000 N*m"),
        ("30 N·m", "torque", "30 N*m"),
        ("0.1 kg·m²", "inertia", "0.1 kg*m^2"),
        ("3 g·mm", "unbalance", "3 g*mm"),
    ],
)
def test_the_unit_spellings_people_use(typed: str, kind: str, written: str) -> None:
    assert parse_quantity(typed, kind, "x") == pytest.approx(parse_quantity(written, kind, "x"))


def test_nm_is_still_the_nanometre() -> None:
    assert parse_quantity("3 nm", "length", "x") == pytest.approx(3e-9)


def test_rpm_in_capitals_in_an_engine_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code, out, _err = run_cli(["analyze", _engine(tmp_path, "9000 rpm", "12500 RPM")], capsys)
    assert code == 0 and "12500 rpm" in out


def test_a_decimal_comma_is_explained(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, _out, err = run_cli(["analyze", _engine(tmp_path, '"230 g"', '"1,5 kg"')], capsys)
    assert code == 2
    assert err.strip() == "error: masses.piston = '1,5 kg': has a decimal comma; write '1.5 kg'"


@pytest.mark.parametrize("suffix", [".csv", ".toml"])
def test_a_csv_table_given_as_an_engine_file_is_explained(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], suffix: str
) -> None:
    path = tmp_path / f"engine{suffix}"
    path.write_text("name;value\nspeed;9000 rpm\ncrank_radius;31 mm\n")
    code, _out, err = run_cli(["analyze", str(path)], capsys)
    assert code == 2
    assert "is a spreadsheet's table, not an engine file" in err
    assert 'speed = "6000 rpm"' in err and "not valid TOML" not in err


def test_a_spreadsheet_file_is_refused_before_it_is_read(tmp_path: Path) -> None:
    path = tmp_path / "engine.xlsx"
    path.write_bytes(b"PK\x03\x04\x00\x00binary")
    with pytest.raises(InputError, match="is a spreadsheet's table"):
        load_engine(path)


def test_broken_toml_is_still_called_so(tmp_path: Path) -> None:
    path = tmp_path / "engine.toml"
    path.write_text('name = "x"\n[crank_train\n')
    with pytest.raises(InputError, match="is not valid TOML"):
        load_engine(path)
