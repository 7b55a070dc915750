"""Fuzzing the balance shop (issue 25, item 8): mutated parts files, CSV and TOML, through
``shop match``, ``bobweights``, ``scatter`` and ``sheet``, and hostile machine readings
through ``shop plan`` (and ``shop sheet``), in-process through ``crankbalance.cli.main``.

The parts files are ``examples/v8_parts.csv`` (docs/balance_shop.md, "The parts file")
mutated: cells that are too long, not numbers, out of range or not finite; quotes that do not
close or close early; control bytes, NUL, bytes that are not UTF-8, a byte-order mark;
missing, extra, renamed and swapped columns and units; more parts than allowed, a file over
the size limit, too few parts; duplicated, empty and overlong ids; unknown kinds and
inconsistent rods. The TOML form of the same file gets the engine-file mutations of
:mod:`.test_fuzz_engine_files` (its categories, on the parts' data). A matching has a small
``--time-limit`` (0.5 s), so a valid file is matched quickly.

Each run must end in exit status 2 with one line on stderr, or in exit status 0 with no NaN
or infinity in the output (the check and runner of :mod:`.test_fuzz_options`), within the
hang guard. Deterministic (``derandomize=True``, no database); ``pytest -s`` prints the
examples tried and clean per test (docs/reliability.md, "Fuzzing").
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from crankbalance.io.engine_file import dumps_toml
from crankbalance.io.parts_file import MAX_FILE_BYTES, MAX_PARTS

from ..conftest import hang_guard
from .test_fuzz_engine_files import CATEGORIES, PRESETS_OF
from .test_fuzz_options import (
    EXAMPLES,
    HANG_GUARD,
    NON_FINITE,
    SHOP_PLAN_BASE,
    V8_PARTS,
    assert_clean,
    run,
)

#: the example parts file: its comment lines, its header and its rows of cells
LINES = Path(V8_PARTS).read_text().splitlines()
COMMENTS = [line for line in LINES if line.startswith("#")]
HEADER, *ROWS = [line.split(",") for line in LINES if line and not line.startswith("#")]
#: the commands that read a parts file, with the options of a cheap valid call
PART_COMMANDS = {
    "match": ["shop", "match", "--engine", "v8-crossplane", "--time-limit", "0.5 s"],
    "bobweights": ["shop", "bobweights", "--engine", "v8-crossplane", "--time-limit", "0.5 s"],
    "scatter": ["shop", "scatter", "--engine", "v8-crossplane"]
    + ["--correction-planes", "-200 mm, 200 mm", "--samples", "2000"],
    "sheet": ["shop", "sheet", "--engine", "v8-crossplane", "--time-limit", "0.5 s"],
}
#: what a cell may become
CELLS = [
    *("five", "nan", "inf", "-inf", "-1", "0", "-0", "1e308", "1e-320", "1e6", "1e-9"),
    *("9" * 400, "x" * 101, "x" * 10_000, "", " ", "12 g", "12 kg", "0x10", "1_000"),
    *("\u0664\u0668\u0667", "1e", "P1", "rod", "oil", '"1,5"', '"487.0"', "487.0 ", "+487"),
]
#: bytes put into a line
BYTES = [
    *(b"\x00", b"\x1b", b"\x01", b"\x7f", b"\xff", b"\xc3", b"\xef\xbb\xbf", b"\r"),
    *(b"\t", b'"', b'""', b",", b"\n", b"#"),
]
HEADERS = [
    *("mass [parsec]", "mass [kg]", "mass [oz]", "mass", "Mass [g]", "mass [g", "mass [g][g]"),
    *("mass [1e308 g]", "mass [nan]", "part", "id", "big_end [deg]", "small_end [g]", ""),
]
Rows = list[list[str]]


def _row(rows: Rows, draw: Any) -> int:
    return draw(st.integers(0, len(rows) - 1))


def cells(header: list[str], rows: Rows, draw: Any) -> tuple[list[str], Rows]:
    """A few cells replaced by hostile values."""
    for _ in range(draw(st.integers(1, 3))):
        row = rows[_row(rows, draw)]
        if row:
            row[draw(st.integers(0, len(row) - 1))] = draw(st.sampled_from(CELLS))
    return header, rows


def quotes(header: list[str], rows: Rows, draw: Any) -> tuple[list[str], Rows]:
    """Quotes that do not close, close early, or hold a comma or a line break."""
    row = rows[_row(rows, draw)]
    k = draw(st.integers(0, len(row) - 1))
    row[k] = draw(
        st.sampled_from(
            [
                f'"{row[k]}',
                f'{row[k]}"',
                f'"{row[k]}"x',
                f'"{row[k]},1"',
                f'"{row[k]}\n"',
                f'"{row[k]}""',
                f'"{row[k]}" ',
                f'"{"x" * 200}"',
            ]
        )
    )
    return header, rows


def columns(header: list[str], rows: Rows, draw: Any) -> tuple[list[str], Rows]:
    """A column dropped, added, renamed or moved; a row made short or long."""
    k = draw(st.integers(0, len(header) - 1))
    how = draw(st.sampled_from(["drop", "add", "rename", "swap", "short row", "long row"]))
    if how == "drop":
        header = header[:k] + header[k + 1 :]
        rows = [r[:k] + r[k + 1 :] for r in rows] if draw(st.booleans()) else rows
    elif how == "add":
        header = [*header, draw(st.sampled_from(["note", "mass [g]", "id", ""]))]
    elif how == "rename":
        header = [*header]
        header[k] = draw(st.sampled_from(HEADERS))
    elif how == "swap":
        j = draw(st.integers(0, len(header) - 1))
        header = [*header]
        header[k], header[j] = header[j], header[k]
    else:
        i = _row(rows, draw)
        rows[i] = rows[i][:k] if how == "short row" else [*rows[i], "1", "2"]
    return header, rows


def counts(header: list[str], rows: Rows, draw: Any) -> tuple[list[str], Rows]:
    """Many parts (beyond the limit of 2000), or too few."""
    how = draw(st.sampled_from(["repeat", "repeat", "few", "one kind gone"]))
    if how == "repeat":
        times = draw(st.sampled_from([2, 10, MAX_PARTS // len(rows) + 1, 500]))
        return header, [list(r) for r in rows] * times
    if how == "few":
        return header, rows[: draw(st.integers(0, 7))]
    kind = draw(st.sampled_from(sorted({r[0] for r in rows})))
    return header, [r for r in rows if r[0] != kind]


def ids(header: list[str], rows: Rows, draw: Any) -> tuple[list[str], Rows]:
    """Ids duplicated, empty, overlong, with a comma or unicode."""
    i, j = _row(rows, draw), _row(rows, draw)
    how = draw(st.sampled_from(["duplicate", "empty", "overlong", "unicode", "same kind"]))
    if how == "duplicate":
        rows[j][1] = rows[i][1]
    elif how == "same kind":  # a second part of one kind with the id of the first
        rows.insert(i, list(rows[i]))
    else:
        value = {"empty": "", "overlong": "P" * 101, "unicode": "P\u0301\u200b1"}[how]
        rows[i][1] = value
    return header, rows


def kinds(header: list[str], rows: Rows, draw: Any) -> tuple[list[str], Rows]:
    """Unknown kinds, a second oil allowance, a rod without ends or whose ends do not add
    up to its mass."""
    i = _row(rows, draw)
    how = draw(st.sampled_from(["unknown", "oil twice", "rod ends", "rod sum"]))
    if how == "unknown":
        rows[i][0] = draw(st.sampled_from(["Piston", "pistons", "crank", "", "oil ", "ROD"]))
    elif how == "oil twice":
        rows.append(["oil", "", "5.0", "", ""])
    else:
        rod = next((r for r in rows if r[0] == "rod" and len(r) >= 5), None)
        if rod is not None:
            if how == "rod ends":
                rod[3] = rod[4] = ""
            else:
                rod[2] = draw(st.sampled_from(["700.0", "643.1", "1.0", "0"]))
    return header, rows


MUTATIONS = {
    "cells": cells,
    "quotes": quotes,
    "columns": columns,
    "counts": counts,
    "ids": ids,
    "kinds": kinds,
}


@st.composite
def csv_files(draw: Any) -> tuple[list[str], bytes]:
    """(mutations, bytes) of a mutated CSV parts file: one to three mutations of its cells,
    then perhaps damaged bytes or padding beyond the size limit."""
    header, rows = list(HEADER), [list(r) for r in ROWS]
    names = draw(st.lists(st.sampled_from(sorted(MUTATIONS)), min_size=1, max_size=3))
    for name in names:
        if rows and header:
            header, rows = MUTATIONS[name](header, rows, draw)
    lines = [*COMMENTS, ",".join(header), *(",".join(r) for r in rows)]
    raw = "\n".join(lines).encode("utf-8", "surrogatepass") + b"\n"
    how = draw(st.sampled_from(["none", "none", "bytes", "oversize", "crlf"]))
    if how == "bytes":
        names.append("bytes")
        for _ in range(draw(st.integers(1, 3))):
            at = draw(st.integers(0, len(raw)))
            raw = raw[:at] + draw(st.sampled_from(BYTES)) + raw[at:]
    elif how == "oversize":
        names.append("oversize")
        raw = b"# " + b"x" * MAX_FILE_BYTES + b"\n" + raw
    elif how == "crlf":
        names.append("crlf")
        raw = raw.replace(b"\n", b"\r\n")
    return names, raw


def parts_data() -> dict[str, Any]:
    """The example parts file as the data of its TOML form (docs/balance_shop.md)."""
    data: dict[str, Any] = {}
    for kind, mark, mass, big, small in ROWS:
        if kind == "oil":
            data["oil"] = f"{mass} g"
            continue
        entry = {"id": mark, "mass": f"{mass} g"}
        if kind == "rod":
            entry |= {"big_end": f"{big} g", "small_end": f"{small} g"}
        data.setdefault(kind, []).append(entry)
    return data


#: the engine-file mutations that apply to any data (not those of the crank train's keys)
TOML_MUTATIONS = {
    k: v for k, v in CATEGORIES.items() if k not in PRESETS_OF and k != "layouts and counts"
}


@st.composite
def toml_files(draw: Any) -> tuple[list[str], bytes]:
    """(mutation, bytes) of a mutated TOML parts file (JSON text where TOML cannot hold the
    mutated data: the parts reader takes it for TOML and must refuse it)."""
    name = draw(st.sampled_from(sorted(TOML_MUTATIONS)))
    text, _suffix = TOML_MUTATIONS[name](parts_data(), draw)
    raw = text if isinstance(text, bytes) else text.encode("utf-8", "surrogatepass")
    return [name], raw


def fuzz(examples: int) -> settings:
    """Deterministic hypothesis settings (no database, no deadline)."""
    return settings(
        max_examples=examples,
        derandomize=True,
        database=None,
        deadline=None,
        suppress_health_check=list(HealthCheck),
    )


TALLY: dict[str, dict[str, int]] = {}


def check(test: str, call: list[str], what: str, echoed: Iterable[str] = ()) -> None:
    """Run ``call`` under the hang guard; it must end cleanly (``echoed``: the input's texts
    the output may show); tallied under ``test``."""
    tally = TALLY.setdefault(test, {"tried": 0, "clean": 0, "exit 0": 0, "exit 2": 0})
    tally["tried"] += 1
    with hang_guard(HANG_GUARD):
        code, out, err = run(call)
    assert_clean([*call, what], code, out, err, echoed)
    tally["clean"] += 1
    tally[f"exit {code}"] += 1


@pytest.fixture(autouse=True)
def _print_tally(request: pytest.FixtureRequest) -> Any:
    yield
    tally = TALLY.get(request.node.name)
    if tally:
        print(
            f"\nfuzz shop {request.node.name}: tried {tally['tried']}, clean "
            f"{tally['clean']} (exit 0: {tally['exit 0']}, exit 2: {tally['exit 2']})"
        )


def run_parts(test: str, tmp_path: Path, command: str, case: tuple[list[str], bytes], suffix: str):
    """Write the mutated parts file and run ``command`` on it."""
    names, raw = case
    parts = tmp_path / f"parts{suffix}"
    parts.write_bytes(raw)
    call = [*PART_COMMANDS[command], str(parts)]
    if command == "sheet":
        call += ["--output", str(tmp_path / "sheet.html")]
    # a part's id is shown as written: an id "nan" is no NaN of the results
    marks = re.findall(r"[^,\s\"=]+", raw.decode("utf-8", "replace"))
    echoed = {mark for mark in marks if NON_FINITE.search(mark)}
    check(test, call, f"(mutations {names}: {raw[:300]!r})", echoed)


@fuzz(5 * EXAMPLES)
@given(command=st.sampled_from(sorted(PART_COMMANDS)), case=csv_files())
def test_csv_parts_files(tmp_path_factory: pytest.TempPathFactory, command: str, case: Any) -> None:
    run_parts("test_csv_parts_files", tmp_path_factory.mktemp("csv"), command, case, ".csv")


@fuzz(5 * EXAMPLES)
@given(command=st.sampled_from(sorted(PART_COMMANDS)), case=toml_files())
def test_toml_parts_files(
    tmp_path_factory: pytest.TempPathFactory, command: str, case: Any
) -> None:
    run_parts("test_toml_parts_files", tmp_path_factory.mktemp("toml"), command, case, ".toml")


# --------------------------------------------------------------------------- readings
AMOUNTS = [
    *("12.5", "8", "0", "-1", "nan", "inf", "1e308", "1e-320", "1e6", "9" * 400, "", "1,5"),
    *("\u00bd", "1e", "0x10"),
]
MASS_UNITS = ["g", "g", "kg", "mg", "oz", "g*mm", "mm", "", "parsec", "deg"]
RADII = ["40", "40", "0", "-40", "nan", "1e308", "1e-320", "100000", ""]
LENGTH_UNITS = ["mm", "mm", "m", "in", "um", "g", "", "deg"]
ANGLES = ["35", "200", "0", "-35", "360", "720", "721", "1e308", "nan", "inf", "", "1e-300"]
ANGLE_UNITS = ["deg", "deg", "rad", "turn", "", "mm", "%"]


def _part(valid: str, hostile: list[str], draw: Any) -> str:
    """``valid`` three times in four, else a hostile text."""
    return valid if draw(st.integers(0, 3)) < 3 else draw(st.sampled_from(hostile))


@st.composite
def readings(draw: Any) -> str:
    """A machine reading, as typed, mostly of the form '12.5 g @ 40 mm, 35 deg', often with
    a hostile number, unit or separator."""
    amount = f"{_part('12.5', AMOUNTS, draw)} {_part('g', MASS_UNITS, draw)}"
    radius = f"{_part('40', RADII, draw)} {_part('mm', LENGTH_UNITS, draw)}"
    angle = f"{_part('35', ANGLES, draw)} {_part('deg', ANGLE_UNITS, draw)}"
    form = _part(
        "{a} @ {r}, {t}",
        [
            "{a} @ {r}",
            "{a}, {t}",
            "{a} @ {r} @ {r}, {t}",
            "{a} @ {r}, {t}, {t}",
            "{a} at {r}, {t}",
            "{a}@{r},{t}",
            "{a} @ {r}; {t}",
            "@, ",
            "{a} @ {r}, {t}\x00",
            "{a} @ {r},\n{t}",
            "{a} \uff20 {r}\uff0c {t}",
        ],
        draw,
    )
    text = form.format(a=amount, r=radius, t=angle)
    if draw(st.integers(0, 9)) == 9:
        text = draw(st.sampled_from([text * 50, " " + text + " ", text.upper(), "x" * 5000]))
    return text


@fuzz(5 * EXAMPLES)
@given(
    values=st.lists(readings(), min_size=0, max_size=3),
    sheet=st.integers(0, 4),
)
def test_readings(tmp_path_factory: pytest.TempPathFactory, values: list[str], sheet: int) -> None:
    """``shop plan`` (one time in five ``shop sheet``) with the base options of the option
    fuzzing and its readings replaced: none, one, two (mostly) or three."""
    base = list(SHOP_PLAN_BASE)
    while "--reading" in base:  # the base's readings out
        at = base.index("--reading")
        del base[at : at + 2]
    if len(values) < 2 and sheet != 4:
        values = [*values, "8 g @ 40 mm, 200 deg"][:2]
    call = ["shop", "plan", *base]
    if sheet == 4:
        out = tmp_path_factory.mktemp("sheet") / "sheet.html"
        call = ["shop", "sheet", V8_PARTS, "--engine", "v8-crossplane", "--time-limit", "0.5 s"]
        call += [*base, "--output", str(out)]
    for value in values:
        call += ["--reading", value]
    check("test_readings", call, "")


def test_the_example_parts_file_is_matched(tmp_path: Path) -> None:
    """The unmutated example runs through every command (so a mutation that is refused is
    refused for what it changed), and the TOML form of it too."""
    toml = tmp_path / "parts.toml"
    toml.write_text(dumps_toml(parts_data()))
    for command in PART_COMMANDS:
        for parts in (V8_PARTS, str(toml)):
            call = [*PART_COMMANDS[command], parts]
            if command == "sheet":
                call += ["--output", str(tmp_path / "sheet.html")]
            code, _, err = run(call)
            assert code == 0, (call, err)
