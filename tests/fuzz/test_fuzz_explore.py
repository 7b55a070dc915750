"""Fuzzing the explorer (issue 25, item 8): hostile ``--filter`` expressions, ``--objectives``,
``--top-key`` and ``--top``, and the sizes of a problem (``--layout``, ``--cylinders``,
``--strokes``, ``--bank-angle``, ``--crank``, ``--sample``, ``--chunk``, ``--orders``,
``--mode-shape``), run in-process through ``crankbalance.cli.main`` as the option fuzzing
does (:mod:`.test_fuzz_options`: its runner, its check and its number of examples).

Each run must end in exit status 2 with one line on stderr, or in exit status 0 with no NaN
or infinity in the output, within the hang guard. Valid runs are kept cheap: at most six
cylinders with any chunk, seven or eight without one, and more only with a few random
draws (``--sample`` of at most 50) or a sample the work plan refuses: a valid run of twelve
cylinders enumerates 40 million firing orders (minutes), which tests/test_explore_bounds.py
covers with its own limits. Deterministic (``derandomize=True``, no database); ``pytest
-s`` prints the examples tried and clean per test (docs/reliability.md, "Fuzzing").
"""

from __future__ import annotations

from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ..conftest import hang_guard
from .test_fuzz_options import EXAMPLES, HANG_GUARD, assert_clean, run

#: columns of the explorer at its default orders (8), with and without their units
COLUMNS = [
    *("F1", "M1", "F2", "M2", "F1_N", "M2_Nm", "F1f", "M1b_Nm", "F8", "M8_Nm", "Frot", "Mrot"),
    *("mirror", "interval_dev_rad", "bank_interval_dev", "X1", "X2", "X0p5", "X4", "cw_mass"),
    *("shafts", "shaft_mass_kg", "residual_F", "residual_M_Nm"),
]
#: names that are no column: other orders, cases, look-alike letters, Python's names
UNKNOWN = [
    *("F9", "F64", "X65", "f1", "m1", "F01", "index", "firing_order", "throw_angle_rad"),
    *("\uff261", "F\uff11", "\u2131\u0031", "F1\u0301", "\u0130", "\u00e9", "\u65e5\u672c"),
    *("inf", "NaN", "Infinity", "nan", "abs", "__import__", "os", "True", "None", "_", "x" * 300),
]
#: numbers as a filter may write them, in and out of its bounds (1e15)
NUMBERS = [
    *("0", "1", "-0", "0.5", ".5", "5.", "1e-6", "1e15", "1e16", "1000000000000001", "1e308"),
    *("1e999", "1e-999", "9" * 400, "0x10", "0b1", "0o7", "1_000", "1j", "1e", "00", "1.2.3"),
]
#: operators between two terms: the language's (several times, so that most expressions
#: are in it), and Python's others
BINARY = [
    *(["+", "-", "*", "/", "<", "<=", ">", ">=", "==", "!=", "and", "or"] * 3),
    *("**", "//", "%", "@", "<<", ">>", "&", "|", "^", "is", "is not", "in", "not in"),
    *(":=", ",", "=", "<>", "===", "=>", "if", "else", "for", "lambda"),
]
UNARY = ["-", "-", "+", "not ", "not ", "~", "--", "*", "await ", "yield "]
#: whole texts outside the language: code, statements, other literals, control bytes
HOSTILE = [
    *("", " ", "\t", "\n", "()", "abs()", "abs(F1, M1) > 0", "F1 if M1 else F2"),
    *("__import__('os').system('true')", "[F1] == 0", "{F1} == 0", "F1.real == 0"),
    *("F1[0] == 0", "lambda: 1", "f'{F1}' == 0", "(M1 := 1) > 0", "F1 == 0 # comment"),
    *("F1 == 'a'", 'F1 == b"a"', "F1 == True", "F1 == None", "F1 == ...", "*F1 > 0"),
    *("F1, M1", "F1 == 0;", "F1 == 0\x00", "F1 ==\n0", "F1 == 0\r", "\x1b[31mF1 > 0"),
    *("F1 > 0 and", "and F1 > 0", "F1 >", "> 0", "F1 > > 0", "F1 == 0)", "(F1 == 0"),
    *("\ufeffF1 == 0", "F1\u00a0== 0", "F1 \u2264 0", "F1 \u2212 1 > 0", "\u200bF1 > 0"),
]


def _expressions() -> st.SearchStrategy[str]:
    """Expressions built from columns, unknown names and numbers with every operator,
    unary operators, brackets, ``abs`` (of one and of two arguments) and comparison
    chains: mostly within the language, often not."""
    atoms = st.one_of(st.sampled_from(COLUMNS), st.sampled_from(UNKNOWN), st.sampled_from(NUMBERS))

    def extend(inner: st.SearchStrategy[str]) -> st.SearchStrategy[str]:
        return st.one_of(
            st.tuples(inner, st.sampled_from(BINARY), inner).map(lambda t: " ".join(t)),
            st.tuples(st.sampled_from(UNARY), inner).map("".join),
            inner.map(lambda x: f"({x})"),
            inner.map(lambda x: f"abs({x})"),
            st.tuples(inner, inner).map(lambda t: f"abs({t[0]}, {t[1]})"),
            st.lists(inner, min_size=3, max_size=5).map(" < ".join),
        )

    return st.recursive(atoms, extend, max_leaves=16)


@st.composite
def long_filters(draw: Any) -> str:
    """Filters at and beyond the size limits (1 000 characters, 100 operators, 20 levels
    of brackets): chains of operators, nested brackets and ``abs``, long ``not`` and
    ``and`` chains, padding."""
    n = draw(st.sampled_from([19, 20, 21, 49, 50, 51, 99, 100, 101, 1000, 5000]))
    kind = draw(
        st.sampled_from(["sum", "minus", "brackets", "not", "and", "abs", "chain", "spaces"])
    )
    return {
        "sum": " + ".join(["F1"] * n) + " >= 0",
        "minus": "-" * n + "F1 >= 0",
        "brackets": "(" * n + "F1 >= 0" + ")" * n,
        "not": "not " * n + "F1 >= 0",
        "and": " and ".join(["F1 >= 0"] * n),
        "abs": "abs(" * n + "F1" + ")" * n + " >= 0",
        "chain": " <= ".join(["F1"] * n),
        "spaces": "F1" + " " * (10 * n) + ">= 0",
    }[kind]


FILTERS = st.one_of(
    _expressions(),
    _expressions().map(lambda x: f"{x} >= 0"),  # a number made a condition
    long_filters(),
    st.sampled_from(HOSTILE),
    st.text(max_size=60),
)
#: cheap problems for the filter and ranking examples (a few hundred candidates at most)
PROBLEMS = [
    ["--cylinders", "4"],
    ["--cylinders", "6", "--orders", "12"],
    ["--cylinders", "3", "--strokes", "2"],
    ["--layout", "vee", "--cylinders", "4", "--bank-angle", "90 deg"],
    ["--layout", "boxer", "--cylinders", "4"],
    ["--layout", "w", "--cylinders", "6", "--bank-angle", "60 deg", "--crank", "split"],
    ["--cylinders", "5", "--target", "none"],
]
FORMATS = ["table", "json", "csv"]


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


def check(test: str, args: list[str]) -> None:
    """Run ``crankbalance explore`` with ``args`` under the hang guard; it must end
    cleanly (:func:`.test_fuzz_options.assert_clean`); tallied under ``test``."""
    tally = TALLY.setdefault(test, {"tried": 0, "clean": 0, "exit 0": 0, "exit 2": 0})
    call = ["explore", "--no-progress", *args]
    tally["tried"] += 1
    with hang_guard(HANG_GUARD):
        code, out, err = run(call)
    assert_clean(call, code, out, err)
    tally["clean"] += 1
    tally[f"exit {code}"] += 1


@pytest.fixture(autouse=True)
def _print_tally(request: pytest.FixtureRequest) -> Any:
    yield
    tally = TALLY.get(request.node.name)
    if tally:
        print(
            f"\nfuzz explore {request.node.name}: tried {tally['tried']}, clean "
            f"{tally['clean']} (exit 0: {tally['exit 0']}, exit 2: {tally['exit 2']})"
        )


@fuzz(20 * EXAMPLES)
@given(
    problem=st.sampled_from(PROBLEMS),
    text=FILTERS,
    fmt=st.sampled_from(FORMATS),
)
def test_filters(problem: list[str], text: str, fmt: str) -> None:
    check("test_filters", [*problem, "--filter", text, "--format", fmt])


#: what --objectives and --top-key may name, and how names may be joined
NAMES = st.sampled_from(COLUMNS + UNKNOWN + ["", " ", "F1 ", " M1", "F1,M1", "F 1"])
SEPARATORS = st.sampled_from([",", ",", ", ", ";", " ", ",,", "\t", "\n"])


@st.composite
def name_lists(draw: Any) -> str:
    """One or many names (up to thousands), joined mostly by commas."""
    count = draw(st.one_of(st.integers(0, 6), st.sampled_from([100, 5000])))
    names = [draw(NAMES) for _ in range(min(count, 6))] * max(1, count // 6)
    return draw(SEPARATORS).join(names)


@fuzz(5 * EXAMPLES)
@given(
    problem=st.sampled_from(PROBLEMS),
    objectives=st.one_of(st.none(), name_lists()),
    key=st.one_of(st.none(), NAMES, name_lists()),
    top=st.one_of(
        st.none(), st.sampled_from(["1", "20", "100000", "100001", "0", "-1", "nan", "1e9", ""])
    ),
    fmt=st.sampled_from(FORMATS),
)
def test_objectives_and_top_key(
    problem: list[str], objectives: str | None, key: str | None, top: str | None, fmt: str
) -> None:
    args = [*problem, "--format", fmt]
    for option, value in (("--objectives", objectives), ("--top-key", key), ("--top", top)):
        if value is not None:
            args += [option, value]
    check("test_objectives_and_top_key", args)


LAYOUTS = ["inline", "vee", "boxer", "w", "vr", "radial"]
#: layouts the explorer does not take: custom throws, misspelt
OTHER_LAYOUTS = ["custom", "VEE", " w", "", "inline4"]
#: cylinders with which any chunk is cheap; seven and eight only without a chunk
CHEAP = ["1", "2", "3", "4", "5", "6"]
#: valid counts whose whole enumeration is long (12: 40 million orders): only with a sample
BIG = ["9", "10", "12", "16", "20"]
HOSTILE_COUNTS = [
    *("0", "-1", "21", "64", "65", "1000", "9" * 30, "nan", "inf", "4.0", "4.5", "1e1"),
    *("", "abc", "\u0664", " 4", "+4", "0x4"),
]
#: samples under the draws' limit (cheap: at most 50 with a big problem), and hostile ones
SMALL_SAMPLES = ["1", "10", "50"]
HOSTILE_SAMPLES = ["0", "-1", "2500001", "1000000000000", "nan", "", "50.5", "1e3"]
CHUNKS = ["1", "2", "64", "8192", "1000000000", "0", "-1", "9" * 30, "nan", "", "1.5"]
ORDERS = ["1", "2", "8", "64", "0", "65", "-1", "1e9", "nan", ""]
STROKES = ["2", "4", "4", "3", "0", "", "4.0"]
CRANKS = ["any", "any", "flat", "cross", "split", "", "Flat"]
BANK_ANGLES = ["90 deg", "60 deg", "15 deg", "72 deg", "45 deg", "120 deg"]
HOSTILE_ANGLES = [
    *("180 deg", "0 deg", "-90 deg", "720 deg", "1e-12 deg", "nan deg", "1e308 deg"),
    *("90", "90 mm", ""),
]
MODE_SHAPES = [
    *("uniform", "linear", "1,0.5,0.5,1", "1,1,1,1,1,1", "nan,1,1,1", "1e308,1,1,1"),
    *("0,0,0,0", "-1,1,1,1", "", ",".join(["1"] * 65), "Linear"),
]
SEEDS = ["0", "7", "4294967295", "4294967296", "-1", "nan", ""]


@st.composite
def sizes(draw: Any) -> list[str]:
    """A problem of a drawn layout and size; a big one only with a small or refused
    sample, a small chunk only with at most six cylinders."""
    hostile = draw(st.integers(0, 4)) == 4  # a layout it does not take, one time in five
    layout = draw(st.sampled_from(OTHER_LAYOUTS if hostile else LAYOUTS))
    args = ["--layout", layout]
    if layout in ("vee", "w") or draw(st.integers(0, 3)) == 3:
        angles = HOSTILE_ANGLES if draw(st.integers(0, 3)) == 3 else BANK_ANGLES
        args += ["--bank-angle", draw(st.sampled_from(angles))]
    kind = draw(st.sampled_from(["cheap", "cheap", "eight", "big", "hostile"]))
    if kind == "cheap":
        args += ["--cylinders", draw(st.sampled_from(CHEAP))]
    elif kind == "eight":
        args += ["--cylinders", draw(st.sampled_from(["7", "8"]))]
    elif kind == "big":
        args += ["--cylinders", draw(st.sampled_from(BIG))]
    else:
        args += ["--cylinders", draw(st.sampled_from(HOSTILE_COUNTS))]
    if kind == "big":
        args += ["--sample", draw(st.sampled_from(SMALL_SAMPLES + HOSTILE_SAMPLES))]
    elif draw(st.booleans()):
        args += ["--sample", draw(st.sampled_from(SMALL_SAMPLES + ["1000"] + HOSTILE_SAMPLES))]
    if "--sample" in args and draw(st.booleans()):
        args += ["--seed", draw(st.sampled_from(SEEDS))]
    if kind != "eight" and draw(st.booleans()):
        args += ["--chunk", draw(st.sampled_from(CHUNKS))]
    for option, values in (
        ("--orders", ORDERS),
        ("--strokes", STROKES),
        ("--crank", CRANKS),
        ("--mode-shape", MODE_SHAPES),
    ):
        if draw(st.integers(0, 2)) == 2:
            args += [option, draw(st.sampled_from(values))]
    return args


@fuzz(10 * EXAMPLES)
@given(args=sizes(), fmt=st.sampled_from(FORMATS))
def test_sizes(args: list[str], fmt: str) -> None:
    check("test_sizes", [*args, "--top", "3", "--format", fmt])


@pytest.mark.parametrize(
    ("option", "value"),
    [
        *(("--objectives", v) for v in ("", " ", ",", "F1,,M1", "F1,", ",F1")),
        *(("--top-key", v) for v in ("", " ")),
    ],
)
def test_empty_names_are_refused(option: str, value: str) -> None:
    """Found by this fuzzing: an empty name in ``--objectives`` was dropped without a word
    (``--objectives ""`` left no Pareto front: "Pareto front of 0 over nothing") and an
    empty ``--top-key`` was replaced by the default key."""
    code, _, err = run(["explore", "--cylinders", "4", option, value])
    assert code == 2 and err.startswith(f"error: {option} = {value!r}: "), err
    assert_clean([option, value], code, "", err)


@pytest.mark.parametrize(
    "args",
    [
        ["--layout", "vee", "--bank-angle", "1e-12 deg", "--cylinders", "8"],
        ["--layout", "vee", "--bank-angle", "1e-9 deg", "--cylinders", "4"],
        ["--layout", "w", "--bank-angle", "1e-12 deg", "--cylinders", "6", "--crank", "split"],
    ],
)
def test_banks_too_close_to_tell_apart_are_refused(args: list[str]) -> None:
    """Found by this fuzzing: a vee of 1e-12 deg (banks closer than the enumeration's
    tolerance of equal angles) had no symmetry at all, not even the identity, and ended in
    a ChunkError traceback (numpy: zero-size array to reduction operation minimum)."""
    code, _, err = run(["explore", *args])
    assert code == 2 and err.startswith(f"error: --bank-angle = {args[3]!r}: required"), err
    assert_clean(args, code, "", err)
