"""Fuzzing the engine-file input (issues 12 and 25): presets mutated in 18 categories,
each file run through ``crankbalance analyze FILE`` and ``crankbalance balance FILE``
in-process. Five categories (issue 25) mutate the keys of VR and W engines (``vr_angle``,
``bore_offset``, ``pin_split``, ``w_type``), offsets and rod positions (``bank_offsets``,
``cylinder_offsets``, ``rod_positions``, ``moment_reference``), makers' numbering
(``numbering``, ``maker_numbers``), articulated rods (``[crank_train.articulated]``) and
overlapping ``[[masses.override]]`` tables, on the presets that have such keys
(:data:`NEW_KEY_PRESETS`).

Each run must end either in exit status 2 with exactly one line on stderr (``error: ...``)
and nothing on stdout, or in exit status 0 with a result that holds no NaN or infinity and
nothing on stderr; in the categories of :data:`INVALID` every file is invalid by
construction and must be refused. Warnings are errors under pytest, so a numpy overflow in
the physics counts as a failure. A run that lasts longer than :data:`HANG_GUARD` seconds is
stopped and counted as a hang (a guard against running without end, not a timing test).

The draws are deterministic (``derandomize=True``, no example database): each category
mutates :data:`FILES` presets drawn from the library (together the categories draw every
preset; ``CRANKBALANCE_FUZZ_FILES=400`` runs more). Each test prints a line
``fuzz engine-file <category>: tried N, clean M, ...``; see them with
``python3 -m pytest -p no:cacheprovider tests/fuzz -rP | grep 'fuzz engine-file'``."""

from __future__ import annotations

import contextlib
import io
import json
import os
import re
import tomllib
from collections import Counter
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from crankbalance.cli import main
from crankbalance.io.engine_file import dumps_toml, list_presets, load_engine, preset_text
from crankbalance.schema.engine import LAYOUTS

from ..conftest import hang_guard

PRESETS = list_presets()
#: Mutated files per category.
FILES = int(os.environ.get("CRANKBALANCE_FUZZ_FILES", "40"))
#: Seconds one CLI run may take before it counts as a hang.
HANG_GUARD = 60
NONFINITE = re.compile(r"\b(nan|inf|infinity)\b", re.IGNORECASE)
Draw = Callable[[st.SearchStrategy[Any]], Any]

UNITS = [
    *("mm", "m", "km", "um", "nm", "parsec", "inch", "g", "kg", "t", "mg", "rpm"),
    *("rad/s", "Hz", "deg", "rad", "turn", "kg*m^2", "g*mm^2", "N", "s", "%", "", "mm^2"),
]
NUMBERS = st.one_of(
    st.sampled_from([0, -0.0, 1, -1, 1e300, -1e300, 1e-300, 5e-324, 1.7976931348623157e308]),
    st.sampled_from([1e-320, 1e6, 1e7, 1e-7, 10**30, -(10**18), 1e15, 0.5]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(-(10**20), 10**20),
)
SCALARS = st.one_of(
    st.booleans(),
    NUMBERS,
    st.text(max_size=30),
    st.sampled_from(["4", "true", "0.5", "", "optimal", "nan", "custom", "1e300 rpm"]),
    st.lists(st.integers(-3, 70), max_size=6),
    st.dictionaries(st.text(max_size=8), st.integers(), max_size=3),
)


# --------------------------------------------------------------------------- engine data
def preset_data(name: str) -> dict[str, Any]:
    return tomllib.loads(preset_text(name))


def paths(data: Any, prefix: tuple[Any, ...] = ()) -> Iterator[tuple[Any, ...]]:
    """Every key and list index below ``data``, depth first."""
    items = data.items() if isinstance(data, dict) else enumerate(data)
    for key, value in items:
        yield prefix + (key,)
        if isinstance(value, dict | list):
            yield from paths(value, prefix + (key,))


def get(data: Any, path: tuple[Any, ...]) -> Any:
    for part in path:
        data = data[part]
    return data


def put(data: Any, path: tuple[Any, ...], value: Any) -> None:
    get(data, path[:-1])[path[-1]] = value


def quantity_paths(data: dict[str, Any]) -> list[tuple[Any, ...]]:
    return [
        p
        for p in paths(data)
        if isinstance(get(data, p), str) and re.match(r"^-?[\d.]+(e-?\d+)? \S", get(data, p))
    ]


def number_text(value: Any) -> str:
    return repr(value) if isinstance(value, float) else str(value)


def toml_or_json(data: Any, draw: Draw) -> tuple[str, str]:
    """The engine as TOML or JSON text (JSON where TOML cannot hold the data)."""
    if draw(st.booleans()):
        try:
            return dumps_toml(data), ".toml"
        except (TypeError, AttributeError, RecursionError):
            pass
    return json.dumps(data, allow_nan=True), ".json"


PLACEHOLDER = "@@FUZZ@@"


def with_text_at(data: dict[str, Any], path: tuple[Any, ...], toml: str, js: str, draw: Draw):
    """The engine as text with the raw TOML or JSON ``toml``/``js`` at ``path``."""
    put(data, path, PLACEHOLDER)
    text, suffix = toml_or_json(data, draw)
    return text.replace(json.dumps(PLACEHOLDER), toml if suffix == ".toml" else js), suffix


# --------------------------------------------------------------------------- mutations
def delete_key(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    keys = [p for p in paths(data) if isinstance(get(data, p[:-1]), dict)]
    for path in draw(st.lists(st.sampled_from(keys), min_size=1, max_size=3, unique=True)):
        with contextlib.suppress(KeyError, TypeError):
            del get(data, path[:-1])[path[-1]]
    return toml_or_json(data, draw)


def swap_type(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    for path in draw(st.lists(st.sampled_from(list(paths(data))), min_size=1, max_size=2)):
        with contextlib.suppress(KeyError, TypeError, IndexError):
            put(data, path, draw(SCALARS))
    return toml_or_json(data, draw)


def numbers(choices: st.SearchStrategy[Any]) -> Callable[..., tuple[str | bytes, str]]:
    def mutate(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
        targets = [p for p in paths(data) if not isinstance(get(data, p), dict | list)]
        quantities = quantity_paths(data)
        for path in draw(st.lists(st.sampled_from(targets), min_size=1, max_size=3)):
            value = draw(choices)
            if path in quantities and isinstance(get(data, path), str) and draw(st.booleans()):
                unit = get(data, path).split(" ", 1)[1]
                value = f"{number_text(value)} {unit}"
            put(data, path, value)
        return toml_or_json(data, draw)

    return mutate


HUGE = st.one_of(
    st.sampled_from([1e300, -1e300, 1.7976931348623157e308, 1e308, 10**30, 10**99, 1e20]),
    st.integers(10**6, 10**99),
    st.floats(1e6, 1e308),
)
TINY = st.one_of(
    st.sampled_from([0, -0.0, -1, 1e-300, 5e-324, 1e-320, 1e-9, -1e-300, -(10**6)]),
    st.floats(-1e308, 1e-6),
    st.integers(-(10**9), 0),
)
NONFINITE_NUMBERS = st.sampled_from([float("nan"), float("inf"), float("-inf")])


def quantity_strings(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    targets = quantity_paths(data) or list(paths(data))
    for path in draw(st.lists(st.sampled_from(targets), min_size=1, max_size=3)):
        number = number_text(draw(NUMBERS))
        old = get(data, path)
        own = old.split(" ", 1)[1] if isinstance(old, str) and " " in old else "mm"
        text = draw(
            st.one_of(
                st.just(f"{number} {own}"),  # the key's own unit, any number
                st.sampled_from([f"{number} {unit}" for unit in UNITS]),
                st.sampled_from(["nan mm", "inf rpm", "-inf g", "1e308 km", "5 parsec"]),
                st.sampled_from(["20..30 mm", "1 m*" * 50 + "m", "(((1 mm", "1 mm" * 40]),
                st.text(max_size=40),
            )
        )
        put(data, path, text)
    return toml_or_json(data, draw)


#: Each kind of quantity in the presets: its units, and the sizes at the edges of its
#: documented range (crankbalance.units.RANGES) and beyond them, in those units.
EDGES = {
    "length": (("mm", "m", "um"), ["1 um", "100 m", "0.001 mm", "99.99 m", "1.1 um"]),
    "mass": (("g", "kg"), ["1 mg", "1e6 kg", "0.001 g", "999999 kg", "1 kg"]),
    "angle": (("deg",), ["720 deg", "-720 deg", "1e-12 deg", "359.999999 deg"]),
    "speed": (("rpm",), ["1 rpm", "1e5 rpm", "1.0001 rpm", "99999 rpm"]),
}


def limits(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    """Quantities at the edges of their documented ranges (most such files are valid)."""
    targets = quantity_paths(data)
    for path in draw(st.lists(st.sampled_from(targets), min_size=1, max_size=4)):
        unit = get(data, path).split(" ", 1)[1]
        kind = next((k for k, (units, _) in EDGES.items() if unit in units), None)
        if kind is None:
            continue
        edge = draw(st.sampled_from(EDGES[kind][1]))
        if draw(st.booleans()):  # or the value scaled by a large or small factor
            number = float(get(data, path).split(" ", 1)[0])
            edge = f"{number * 10.0 ** draw(st.integers(-9, 9)):g} {unit}"
        put(data, path, edge)
    for key in ("conrod_rotating_fraction", "balance_factor"):
        for table in (data.get("masses", {}), data.get("counterweights", {})):
            if key in table and draw(st.booleans()):
                table[key] = draw(st.sampled_from([0, 0.0, 1, 1.0, 2.0, 1e-300, 0.999999]))
    return toml_or_json(data, draw)


def deep_nesting(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    path = draw(st.sampled_from(list(paths(data))))
    depth = draw(st.one_of(st.sampled_from([2, 31, 32, 33, 100, 500, 5000]), st.integers(1, 999)))
    if draw(st.booleans()):
        toml = js = "[" * depth + "1" + "]" * depth
    else:
        toml = "{a = " * depth + "1" + "}" * depth
        js = '{"a": ' * depth + "1" + "}" * depth
    return with_text_at(data, path, toml, js, draw)


def long_lists(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    lists = [p for p in paths(data) if isinstance(get(data, p), list)]
    path = draw(st.sampled_from(lists or list(paths(data))))
    count = draw(st.one_of(st.sampled_from([65, 129, 20_000]), st.integers(0, 5000)))
    old = get(data, path)
    item = old[0] if isinstance(old, list) and old else draw(st.sampled_from(["0 deg", 1]))
    put(data, path, [item] * count)
    return toml_or_json(data, draw)


def duplicate_keys(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    tables = [()] + [p for p in paths(data) if isinstance(get(data, p), dict)]
    path = draw(st.sampled_from(tables))
    table = get(data, path)
    if not table:
        table["name"] = "x"
    key = draw(st.sampled_from(sorted(table)))
    value = draw(st.one_of(st.just(table[key]), SCALARS))
    pairs = [*table.items(), (key, value)]
    if draw(st.booleans()):
        pairs.reverse()
    text = "{" + ", ".join(f"{json.dumps(k)}: {json.dumps(v)}" for k, v in pairs) + "}"
    if not path:
        return text, ".json"
    put(data, path, PLACEHOLDER)
    return json.dumps(data).replace(json.dumps(PLACEHOLDER), text), ".json"


def garbage_bytes(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    text, suffix = toml_or_json(data, draw)
    raw = bytearray(text.encode("utf-8"))
    for _ in range(draw(st.integers(1, 5))):
        where = draw(st.integers(0, len(raw)))
        operation = draw(st.sampled_from(["insert", "overwrite", "delete", "truncate", "all"]))
        junk = draw(
            st.one_of(
                st.binary(min_size=1, max_size=20),
                st.sampled_from([b"\x00", b"\xff\xfe", b"\xc3", b"[[", b"{", b'"""', b"\n[x]\n"]),
            )
        )
        if operation == "insert":
            raw[where:where] = junk
        elif operation == "overwrite":
            raw[where : where + len(junk)] = junk
        elif operation == "delete":
            del raw[where : where + draw(st.integers(1, 50))]
        elif operation == "truncate":
            del raw[where:]
        else:
            raw = bytearray(draw(st.binary(max_size=2000)))
    return bytes(raw), suffix


def layouts_and_counts(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    train = data["crank_train"]
    train["layout"] = draw(st.sampled_from([*LAYOUTS, "star"]))
    counts = st.one_of(
        st.sampled_from([0, 1, 2, 3, 5, 6, 12, 63, 64, 65, 100, 10**6, -1]),
        st.integers(1, 200),
    )
    if draw(st.booleans()):
        train["cylinders"] = draw(counts)
    for key in ("firing_order", "throw_angles", "bank_angle", "crank_pitch", "throw"):
        if draw(st.integers(0, 3)) == 0:
            train.pop(key, None)
    if draw(st.booleans()):
        train["bank_angle"] = f"{draw(st.integers(-400, 400))} deg"
    if draw(st.booleans()):
        n = draw(st.one_of(counts, st.just(20_000)))
        train["throw_angles"] = [f"{k * 7 % 360} deg" for k in range(min(max(n, 0), 20_000))]
    if draw(st.booleans()):
        n = draw(counts)
        order = list(range(1, min(max(n, 0), 20_000) + 1))
        train["firing_order"] = order[::-1] if draw(st.booleans()) else order
    if train["layout"] == "custom" or draw(st.integers(0, 3)) == 0:
        throws = draw(st.one_of(st.sampled_from([1, 2, 64, 65, 2_500]), st.integers(1, 100)))
        banks = draw(st.one_of(st.sampled_from([1, 2, 64, 15_000]), st.integers(1, 5)))
        banks = min(banks, max(20_000 // throws, 1))
        train["throw"] = [
            {
                "position": f"{(k - throws / 2) * 80} mm",
                "angle": f"{k * 90} deg",
                "banks": [f"{b * 45} deg" for b in range(banks)],
            }
            for k in range(throws)
        ]
    return toml_or_json(data, draw)


def unknown_keys(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    tables = [()] + [p for p in paths(data) if isinstance(get(data, p), dict)]
    for _ in range(draw(st.integers(1, 3))):
        table = get(data, draw(st.sampled_from(tables)))
        key = draw(st.one_of(st.text(min_size=1, max_size=12), st.sampled_from(["speeed", "cyl"])))
        if draw(st.booleans()) and data.get("masses"):
            moved = draw(st.sampled_from(sorted(data["masses"])))
            table[key if draw(st.booleans()) else moved] = data["masses"].pop(moved)
        else:
            table[key] = draw(SCALARS)
    return toml_or_json(data, draw)


# --------------------------------------------------------------------------- new keys
#: the presets with the keys of VR and W engines, side-by-side rods, makers' numbering,
#: articulated rods and mass overrides (the categories below draw from these only)
NEW_KEY_PRESETS = [
    *("vr6", "w8", "w12-vw", "w16", "ducati-916", "harley-45", "radial5-kinner"),
    *("radial7-scarab", "radial9-r985", "boxer6"),
]
ANGLES = [
    *("15 deg", "22 deg", "72 deg", "0 deg", "-15 deg", "90 deg", "180 deg", "359 deg"),
    *("1e-12 deg", "720 deg", "721 deg", "nan deg", "1e308 deg", "15 mm", "15", "", 15, True),
]
LENGTHS = [
    *("12.5 mm", "0 mm", "-12.5 mm", "5 mm", "-10 mm", "100 mm", "164 mm", "209 mm", "1 m"),
    *("100 m", "100.1 m", "1 um", "0.5 um", "1e308 km", "nan mm", "inf mm", "12.5 deg"),
    *("12.5", "", 12.5, True, [], {}),
]


def _set_or_delete(table: dict[str, Any], key: str, values: list[Any], draw: Draw) -> None:
    """Set ``key`` to a drawn value, or (one time in five) delete it."""
    if draw(st.integers(0, 4)) == 4:
        table.pop(key, None)
    else:
        table[key] = draw(st.sampled_from(values))


def _cylinders(train: dict[str, Any]) -> int:
    count = train.get("cylinders")
    return count if isinstance(count, int) and 0 < count <= 64 else 4


def vr_w_keys(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    """The keys of VR engines and Ws from VR banks (vr_angle, bore_offset, pin_split,
    w_type), on their own presets and on others, with the layout and bank angle."""
    train = data["crank_train"]
    keys = {
        "vr_angle": ANGLES,
        "bore_offset": LENGTHS,
        "pin_split": ANGLES,
        "w_type": ["vr", "broad-arrow", "", "VR", "v", "w", 1, True],
        "layout": ["vr", "w", "vee", "inline", "boxer", "radial"],
        "bank_angle": ANGLES,
    }
    for key in draw(st.lists(st.sampled_from(sorted(keys)), min_size=1, max_size=3)):
        _set_or_delete(train, key, keys[key], draw)
    return toml_or_json(data, draw)


def _length_list(count: int, draw: Draw) -> list[Any]:
    """A list of lengths: mostly of ``count`` entries, often of another count."""
    size = draw(st.sampled_from([count, count, count - 1, count + 1, 0, 1, 2, 3, 4, 65, 1000]))
    entries = st.one_of(st.sampled_from(LENGTHS[:8]), st.sampled_from(LENGTHS))
    return [draw(entries) for _ in range(min(max(size, 0), 8))] * max(1, size // 8)


def offsets(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    """bank_offsets, cylinder_offsets, rod_positions, moment_reference and moment_point:
    added, changed or deleted, lists of the right and wrong lengths, both offsets (and both
    points) at once."""
    train = data["crank_train"]
    n = _cylinders(train)
    for key in draw(
        st.lists(
            st.sampled_from(
                [
                    "bank_offsets",
                    "cylinder_offsets",
                    "rod_positions",
                    "moment_reference",
                    "moment_point",
                ]
            ),
            min_size=1,
            max_size=3,
        )
    ):
        if key == "moment_reference":
            _set_or_delete(train, key, [*LENGTHS, ["5 mm"]], draw)
        elif key == "moment_point":
            train[key] = _length_list(3, draw)
        elif draw(st.integers(0, 4)) == 4:
            train.pop(key, None)
        else:
            count = draw(st.sampled_from([2, 3, 4])) if key == "bank_offsets" else n
            train[key] = _length_list(count, draw)
    return toml_or_json(data, draw)


def numbering(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    """The maker's numbering: a named scheme (of this layout or another, or none such) or
    maker_numbers (a permutation, or not one), both at once, with the firing order
    reversed or shuffled."""
    train = data["crank_train"]
    n = _cylinders(train)
    if draw(st.booleans()):
        _set_or_delete(
            train,
            "numbering",
            ["porsche-boxer", "gm-vee", "ford-vee", "", "porsche", "GM-vee", 1, True],
            draw,
        )
    if draw(st.booleans()):
        order = draw(st.permutations(list(range(1, n + 1))))
        how = draw(st.sampled_from(["permutation", "duplicate", "short", "long", "out"]))
        if how == "duplicate":
            order[0] = order[-1]
        elif how == "short":
            order = order[:-1]
        elif how == "long":
            order = [*order, n + 1]
        elif how == "out":
            order[draw(st.integers(0, n - 1))] = draw(
                st.sampled_from([0, -1, n + 1, 65, 10**30, True, 1.0, "1", None])
            )
        train["maker_numbers"] = [x for x in order if x is not None]
    if draw(st.integers(0, 3)) == 3 and isinstance(train.get("firing_order"), list):
        train["firing_order"] = draw(st.permutations(train["firing_order"]))
    return toml_or_json(data, draw)


def articulated(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    """[crank_train.articulated]: its keys changed, deleted or unknown, the table put on
    engines that are no radials, or made no table."""
    train = data["crank_train"]
    n = _cylinders(train)
    table = train.setdefault(
        "articulated",
        {"master_cylinder": 1, "link_pin_radius": "30 mm", "link_rod_length": "120 mm"},
    )
    if draw(st.integers(0, 9)) == 9:
        train["articulated"] = draw(st.sampled_from([[], 1, "master", [table]]))
        return toml_or_json(data, draw)
    keys = {
        "master_cylinder": [1, 2, n, 0, n + 1, -1, 10**30, True, 1.0, "1"],
        "link_pin_radius": ["30 mm", "56 mm", "66.675 mm", "100 mm", *LENGTHS],
        "link_rod_length": ["120 mm", "197.3 mm", "254 mm", "300 mm", "40 mm", *LENGTHS],
        "master_rod": [1, "x"],
    }
    for key in draw(st.lists(st.sampled_from(sorted(keys)), min_size=1, max_size=3)):
        _set_or_delete(table, key, keys[key], draw)
    return toml_or_json(data, draw)


OVERRIDE_MASSES = {
    "piston": ["480 g", "1 kg", "0 g", "-1 g", "1e308 kg", "nan g", "480 mm", 480],
    "wrist_pin": ["130 g", "0 g", "1e7 kg"],
    "conrod": ["600 g", "2200 g", "0 g", "1e308 g"],
    "conrod_rotating_fraction": [0.75, 0.0, 1.0, 1.5, -0.1, True, "0.7"],
    "conrod_cg_from_big_end": ["40 mm", "0 mm", "1 m", "-1 mm"],
    "crankpin": ["220 g", "0 g"],
    "reciprocating": ["700 g", "0 g"],
    "rotating": ["900 g", "0 g"],
}


def overrides(data: dict[str, Any], draw: Draw) -> tuple[str | bytes, str]:
    """[[masses.override]] tables added: overlapping cylinders and throws, one number listed
    twice, both or neither of cylinders and throws, numbers out of range, many tables."""
    masses = data.setdefault("masses", {})
    if not isinstance(masses, dict):
        return toml_or_json(data, draw)
    n = _cylinders(data["crank_train"])
    tables = masses.setdefault("override", [])
    if not isinstance(tables, list):
        return toml_or_json(data, draw)
    within = st.integers(1, n)
    numbers = st.one_of(
        within, within, within, st.sampled_from([0, -1, n + 1, 65, 10**30, True, 1.5, "1"])
    )
    count = draw(st.sampled_from([1, 1, 1, 2, 2, 3, 127, 128, 129]))
    made = []
    for _ in range(min(count, 4)):
        table: dict[str, Any] = {}
        for key in draw(st.lists(st.sampled_from(["cylinders", "throws"]), min_size=1, max_size=2)):
            table[key] = draw(st.lists(numbers, min_size=1, max_size=4))
        for key in draw(st.lists(st.sampled_from(sorted(OVERRIDE_MASSES)), min_size=1, max_size=3)):
            table[key] = draw(st.sampled_from(OVERRIDE_MASSES[key]))
        made.append(table)
    tables += made * max(1, count // len(made))
    return toml_or_json(data, draw)


#: Categories whose every file is invalid by construction: each must end in exit 2.
INVALID = {"NaN and infinity", "duplicate JSON keys"}

CATEGORIES: dict[str, Callable[[dict[str, Any], Draw], tuple[str | bytes, str]]] = {
    "delete keys": delete_key,
    "swap types": swap_type,
    "huge numbers": numbers(HUGE),
    "tiny, zero and negative numbers": numbers(TINY),
    "NaN and infinity": numbers(NONFINITE_NUMBERS),
    "quantity strings": quantity_strings,
    "values at the limits": limits,
    "deep nesting": deep_nesting,
    "long lists": long_lists,
    "duplicate JSON keys": duplicate_keys,
    "garbage bytes": garbage_bytes,
    "layouts and counts": layouts_and_counts,
    "unknown and moved keys": unknown_keys,
    "VR and W keys": vr_w_keys,
    "offsets, rod positions, moment reference": offsets,
    "makers' numbering": numbering,
    "articulated rods": articulated,
    "overlapping overrides": overrides,
}
#: the presets each category mutates (all of them, but for the categories of new keys)
PRESETS_OF = {
    category: NEW_KEY_PRESETS
    for category in (
        "VR and W keys",
        "offsets, rod positions, moment reference",
        "makers' numbering",
        "articulated rods",
        "overlapping overrides",
    )
}


# --------------------------------------------------------------------------- running
def run(args: list[str]) -> tuple[int | str, str, str]:
    """Exit status (or the exception that escaped), stdout and stderr of one CLI run."""
    out, err = io.StringIO(), io.StringIO()
    code: int | str = 0
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            with hang_guard(HANG_GUARD):
                main(args)
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else 0 if stop.code is None else 1
        except Exception as error:  # a traceback, a hang: recorded, reported below
            code = f"{type(error).__name__}: {str(error)[:200]}"
    return code, out.getvalue(), err.getvalue()


def verdict(path: Path, code: int | str, out: str, err: str, invalid: bool) -> str:
    """Empty when the run ended cleanly, else what was wrong; an ``invalid`` file must be
    refused."""
    if code == 2:
        lines = err.strip().splitlines()
        if len(lines) == 1 and lines[0].startswith("error: ") and not out:
            return ""
        return f"exit 2 with stderr {err[:300]!r}"
    if code == 0:
        if invalid:
            return "exit 0: an invalid file was accepted"
        if err:
            return f"exit 0 with stderr {err[:300]!r}"
        spec = load_engine(path)
        shown = out.replace(spec.name, "").replace(spec.description, "")
        found = NONFINITE.search(shown)
        return f"exit 0 with {found.group()!r} in the output" if found else ""
    return f"ended with {code}"


@pytest.mark.parametrize("category", list(CATEGORIES))
def test_mutated_presets_end_cleanly(category: str, tmp_path: Path) -> None:
    mutate = CATEGORIES[category]
    counts: Counter[str] = Counter()
    failures: list[str] = []
    presets: set[str] = set()

    @settings(
        max_examples=FILES,
        derandomize=True,
        database=None,
        deadline=None,
        phases=[Phase.generate],
        suppress_health_check=list(HealthCheck),
    )
    @given(data=st.data())
    def one_file(data: st.DataObject) -> None:
        preset = data.draw(st.sampled_from(PRESETS_OF.get(category, PRESETS)))
        presets.add(preset)
        content, suffix = mutate(preset_data(preset), data.draw)
        path = tmp_path / f"engine{suffix}"
        if isinstance(content, str):
            content = content.encode("utf-8", "surrogatepass")
        path.write_bytes(content)
        counts["tried"] += 1
        problems = []
        for command in ("analyze", "balance"):
            code, out, err = run([command, str(path)])
            counts[f"exit {code}" if code in (0, 2) else "other"] += 1
            problem = verdict(path, code, out, err, category in INVALID)
            if problem:
                problems.append(f"{command}: {problem}")
        if problems:
            failures.append(f"{preset} -> {content[:300]!r}: {'; '.join(problems)}")
        else:
            counts["clean"] += 1

    one_file()
    print(
        f"fuzz engine-file {category}: tried {counts['tried']}, clean {counts['clean']}, "
        f"presets {len(presets)}; runs ending in exit 0: {counts['exit 0']}, "
        f"exit 2: {counts['exit 2']}"
    )
    assert counts["tried"] == FILES
    assert not failures, f"{len(failures)} of {counts['tried']} files:\n" + "\n".join(failures[:10])
