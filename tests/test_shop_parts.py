"""The balance shop's parts file (crankbalance.io.parts_file): CSV and TOML read to the
same inventory, units from the header, and one clear message per mistake, naming the
file, line and column (or key), the value and what is allowed."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.parts_file import load_parts_file

from .conftest import EXAMPLES

CSV = """\
# two cylinders
part,id,mass [g],big_end [g],small_end [g]
piston,P1,512.4,,
piston,P2,513.0,,
pin,,140.0,,
pin,,140.6,,
rod,R1,638.2,452.0,186.3
rod,R2,637.0,451.1,185.8
shell,S1,48.1,,
shell,S2,48.3,,
oil,,4.0,,
"""

TOML = """\
oil = "4 g"
[[piston]]
id = "P1"
mass = "512.4 g"
[[piston]]
id = "P2"
mass = "0.513 kg"
[[pin]]
mass = "140 g"
[[pin]]
mass = "140.6 g"
[[rod]]
id = "R1"
big_end = "452.0 g"
small_end = "186.3 g"
mass = "638.2 g"
[[rod]]
id = "R2"
big_end = "451.1 g"
small_end = "185.8 g"
[[shell]]
id = "S1"
mass = "48.1 g"
[[shell]]
id = "S2"
mass = "48.3 g"
"""


def write(tmp_path: Path, text: str, name: str = "parts.csv") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def test_csv_shares_and_allowance(tmp_path: Path) -> None:
    inventory = load_parts_file(write(tmp_path, CSV))
    assert inventory.names == ("piston", "pin", "rod", "shell")
    piston, pin, rod, shell = inventory.kinds
    assert piston.ids == ("P1", "P2")
    assert pin.ids == ("pin 1", "pin 2")  # no mark given
    assert piston.reciprocating == pytest.approx([0.5124, 0.513])
    assert piston.rotating.tolist() == [0.0, 0.0]
    assert rod.reciprocating == pytest.approx([0.1863, 0.1858])  # small ends
    assert rod.rotating == pytest.approx([0.452, 0.4511])  # big ends
    assert shell.rotating == pytest.approx([0.0481, 0.0483])
    assert shell.reciprocating.tolist() == [0.0, 0.0]
    assert inventory.rotating_allowance == pytest.approx(0.004)
    assert inventory.reciprocating_allowance == 0.0


def test_toml_reads_as_the_csv(tmp_path: Path) -> None:
    csv = load_parts_file(write(tmp_path, CSV))
    toml = load_parts_file(write(tmp_path, TOML, "parts.toml"))
    assert toml.names == csv.names
    assert toml.rotating_allowance == pytest.approx(csv.rotating_allowance)
    for a, b in zip(toml.kinds, csv.kinds, strict=True):
        assert a.ids == b.ids
        assert a.reciprocating == pytest.approx(b.reciprocating)
        assert a.rotating == pytest.approx(b.rotating)


def test_header_units_and_column_order(tmp_path: Path) -> None:
    """Any mass unit in the header; columns in any order; kinds in any case."""
    text = (
        "small_end [kg],id,part,mass [kg],big_end [kg]\n"
        "0.1863,R1,Rod,0.6382,0.452\n"
        ",P1,piston,0.5124,\n"
    )
    inventory = load_parts_file(write(tmp_path, text))
    assert inventory.kinds[0].rotating == pytest.approx([0.452])
    assert inventory.kinds[1].reciprocating == pytest.approx([0.5124])
    ounces = load_parts_file(write(tmp_path, "part,mass [oz]\npiston,16\n"))
    assert ounces.kinds[0].reciprocating == pytest.approx([0.45359237], rel=1e-9)


def test_v8_example() -> None:
    inventory = load_parts_file(EXAMPLES / "v8_parts.csv")
    assert inventory.names == ("piston", "pin", "rings", "locks", "rod", "shell")
    assert all(kind.count == 8 for kind in inventory.kinds)
    rod = inventory.kinds[4]
    assert np.all((rod.rotating > 0.4) & (rod.rotating < 0.5))
    assert inventory.rotating_allowance == pytest.approx(0.004)


HEADER = "part,id,mass [g],big_end [g],small_end [g]\n"


@pytest.mark.parametrize(
    ("text", "field", "message"),
    [
        ("part,id,mass\npiston,P1,500\n", "line 1 (header)", "needs its unit in brackets"),
        ("part,id,mass [mm]\npiston,P1,500\n", "line 1 (header), mass [mm]", "wrong unit"),
        ("part,weight [g]\npiston,500\n", "line 1 (header)", "is not a column"),
        ("part,id\npiston,P1\n", "line 1 (header)", "has no 'mass' column"),
        ("part [g],mass [g]\npiston,500\n", "line 1 (header)", "takes no unit"),
        ("part,mass [g],mass [g]\npiston,500,500\n", "line 1 (header)", "names a column twice"),
        (HEADER + "pistn,P1,500,,\n", "line 2, part", "must be a kind of part: piston"),
        (HEADER + "piston,P1,five,,\n", "line 2, mass [g]", "must be a number"),
        (HEADER + "piston,P1,nan,,\n", "line 2, mass [g]", "must be a finite number"),
        (HEADER + "piston,P1,-500,,\n", "line 2, mass", "must be greater than zero"),
        (HEADER + "piston,P1,0,,\n", "line 2, mass", "must be greater than zero"),
        (HEADER + "piston,P1,1e12,,\n", "line 2, mass [g]", "must lie between"),
        (HEADER + "piston,P1,,,\n", "line 2, mass", "is missing"),
        (HEADER + "piston,P1,500,400,\n", "line 2, big_end", "applies to rods only"),
        (HEADER + "rod,R1,640,452,\n", "line 2, small_end", "a rod needs both ends"),
        (HEADER + "rod,R1,660,452,186\n", "line 2, mass", "re-weigh the rod"),
        (HEADER + "piston,P1,500,,\npiston,P1,501,,\n", "line 3, id", "given to two pistons"),
        (HEADER + "oil,,4,,\noil,,3,,\npiston,P1,500,,\n", "line 3", "oil allowance twice"),
        (HEADER + "piston,P1,500,,,7\n", "line 2", "has 6 cells"),
        (HEADER + "oil,,4,,\n", "parts", "lists no part"),
        ("# only a comment\n", "parts", "holds no header"),
    ],
)
def test_csv_mistakes(tmp_path: Path, text: str, field: str, message: str) -> None:
    path = write(tmp_path, text)
    with pytest.raises(InputError, match=message) as caught:
        load_parts_file(path)
    assert field in caught.value.field
    if field != "parts":
        assert str(path) in caught.value.field  # the file is named


@pytest.mark.parametrize(
    ("text", "field", "message"),
    [
        ('[[piston]]\nid = "P1"\nmass = "500"\n', "piston[1].mass", "needs a unit"),
        ('[[piston]]\nmass = "500 g"\ncolour = "red"\n', "piston[1].colour", "unknown key"),
        ('[[piston]]\nmass = "500 mm"\n', "piston[1].mass", "wrong unit"),
        ('[[rod]]\nbig_end = "450 g"\n', "rod[1].small_end", "a rod needs both ends"),
        ('[[piston]]\nid = true\nmass = "500 g"\n', "piston[1].id", "text or a whole number"),
        ('piston = "500 g"\n', "piston", "array of tables"),
        ('[[pistons]]\nmass = "500 g"\n', "key", "must be a kind of part"),
        ('oil = "4 g"\n', "parts", "lists no part"),
    ],
)
def test_toml_mistakes(tmp_path: Path, text: str, field: str, message: str) -> None:
    path = write(tmp_path, text, "parts.toml")
    with pytest.raises(InputError, match=message) as caught:
        load_parts_file(path)
    assert field in caught.value.field


def test_file_bounds(tmp_path: Path) -> None:
    """Read through io.reading: a folder or binary data is refused, naming 'parts'."""
    with pytest.raises(InputError, match="is a folder") as caught:
        load_parts_file(tmp_path)
    assert caught.value.field == "parts"
    binary = tmp_path / "parts.csv"
    binary.write_bytes(b"part,mass [g]\x00\n")
    with pytest.raises(InputError, match="binary"):
        load_parts_file(binary)
