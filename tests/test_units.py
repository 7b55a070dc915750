"""Quantity strings: the table of common units against pint.

``crankbalance.units`` reads the units engine files use from a small table and hands any
other unit to pint. Every spelling of the table is checked here against pint (the same
unit, the same SI value and dimension), and whole quantity strings read through the table
must give what pint gives: the same SI value, or the same error message.
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crankbalance import units
from crankbalance.errors import InputError

#: pint's base units, in the order of the table's exponents
BASE_UNITS = ("meter", "kilogram", "second", "radian")


@pytest.fixture(scope="module")
def ureg() -> Any:
    return units.registry()


def parse_with_pint(
    monkeypatch: pytest.MonkeyPatch, text: Any, kind: str
) -> float | tuple[str, str]:
    """``parse_quantity`` with the table switched off: pint reads every string and
    converts it to SI."""
    with monkeypatch.context() as patch:
        patch.setattr(units, "_table_unit", lambda unit: None)
        return outcome(text, kind)


def outcome(text: Any, kind: str) -> float | tuple[str, str]:
    """The SI value, or the error (field and message) of one quantity string."""
    try:
        return units.parse_quantity(text, kind, "field")
    except InputError as error:
        return ("error", str(error))


def same(a: float | tuple[str, str], b: float | tuple[str, str]) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-12, abs_tol=0.0)
    return a == b


@pytest.mark.parametrize("spelling", sorted(units._SPELLINGS))
def test_every_spelling_is_the_unit_pint_reads(ureg: Any, spelling: str) -> None:
    name = units._SPELLINGS[spelling]
    factor, dims = units._TABLE[name]
    quantity = ureg.Quantity(f"1 {spelling}")
    assert dict(quantity.unit_items()) == {name: 1}
    base = quantity.to_base_units()
    assert math.isclose(float(base.magnitude), factor, rel_tol=1e-12)
    assert {k: v for k, v in base.unit_items() if v} == {
        unit: e for unit, e in zip(BASE_UNITS, dims, strict=True) if e
    }


def test_every_kind_reads_and_writes_through_the_table(ureg: Any) -> None:
    for kind, (si_unit, display, example) in units.KINDS.items():
        for unit in (si_unit, display):
            assert units._table_unit(unit) is not None, f"{kind}: {unit} not in the table"
        expected = float(ureg.Quantity(1.0, si_unit).to(display).magnitude)
        assert units.format_quantity(1.0, kind).split()[0] == f"{expected:.12g}"
        assert units._table_unit(example.split(maxsplit=1)[1]) is not None


def preset_quantities() -> list[str]:
    """Every quantity string of the built-in engines."""
    found: set[str] = set()

    def walk(value: Any) -> None:
        if isinstance(value, dict):
            for item in value.values():
                walk(item)
        elif isinstance(value, list):
            for item in value:
                walk(item)
        elif isinstance(value, str) and value[:1].isdigit():
            found.add(value)

    for path in resources.files("crankbalance.presets").iterdir():
        if path.name.endswith(".toml"):
            walk(tomllib.loads(path.read_text()))
    return sorted(found)


EXAMPLES = [
    "40 mm",
    "40mm",
    " 1e3 mm ",
    ".5 mm",
    "5. mm",
    "-100 rpm",
    "+3 mm",
    "30°",
    "30 °",
    "2 um",
    "2 µm",
    "2 μm",
    "0.002 kg*m^2",
    "0.002 kg*m**2",
    "0.002 kg * m ^ 2",
    "7850 kg/m^3",
    "1 kg/m*s",
    "1 N/m/s",
    "1 m^-2",
    "1 m^02",
    "1 m^-02",
    "10 g*mm",
    "1.5 N*m",
    "50 Hz",
    "1 kHz",
    "50 Hz^2",
    "2000 rpm",
    "3 rad/s",
    "30 deg/s",
    "1 turn/min",
    "1 revolution/min",
    "3 rpm*s",
    "1 mm/m",
    "1 m/m",
    "1 mm*rad",
    "40",
    "40 kg",
    "2000 m",
    "1e400 mm",
    "1 lb",
    "1 in",
    "2 ft",
    "0.5 h",
    "1 kJ",
    "10 kW",
    "50 bar",
    "210 GPa",
    "0.01 Pa*s",
    "1e7 N/m",
    # outside the table: pint reads these on both sides
    "1 N m",
    "1 metre",
    "1 kg/(m*s^2)",
    "1 m^2.0",
    "28 %",
    "1 lbf",
    "1 rev",
    "1 mrad",
    "5 parsecs",
    "1 foo",
]


@pytest.mark.parametrize("text", EXAMPLES + preset_quantities())
def test_table_reads_as_pint_does(monkeypatch: pytest.MonkeyPatch, text: str) -> None:
    for kind in units.KINDS:
        assert same(outcome(text, kind), parse_with_pint(monkeypatch, text, kind)), kind


def test_plain_numbers_and_bad_values_name_the_field() -> None:
    for value in (40, 4.0, None, True, "", "20..30 mm", "nan mm"):
        with pytest.raises(InputError, match="crank_radius"):
            units.parse_quantity(value, "length", "crank_radius")


UNIT_TERMS = st.tuples(
    st.sampled_from(sorted(units._SPELLINGS)),
    st.sampled_from(["", "^2", "**2", "^-1", "^3", " ^ 2", "^0", "^02", "^-10"]),
)


@settings(derandomize=True, database=None, deadline=None, max_examples=300)
@given(
    number=st.sampled_from(["1", "2.5", "-3e2", ".75", "6000", "0"]),
    terms=st.lists(UNIT_TERMS, min_size=1, max_size=3),
    operators=st.lists(st.sampled_from(["*", "/", " * ", " / "]), min_size=2, max_size=2),
    kind=st.sampled_from(sorted(units.KINDS)),
)
def test_random_unit_expressions_read_as_pint_does(
    number: str, terms: list[tuple[str, str]], operators: list[str], kind: str
) -> None:
    unit = terms[0][0] + terms[0][1]
    for operator, (name, power) in zip(operators, terms[1:], strict=False):
        unit += operator + name + power
    text = f"{number} {unit}"
    with pytest.MonkeyPatch.context() as monkeypatch:
        assert same(outcome(text, kind), parse_with_pint(monkeypatch, text, kind)), text


def test_reading_the_table_loads_no_pint() -> None:
    import subprocess
    import sys

    code = (
        "import sys; from crankbalance.units import parse_quantity, format_quantity; "
        "parse_quantity('6000 rpm', 'speed', 's'); parse_quantity('40 kg', 'mass', 'm'); "
        "format_quantity(1.0, 'unbalance'); print('pint' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
