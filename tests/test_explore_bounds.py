"""The explorer's limits (issue 25): the filter bounded before it is parsed, the work of a
run bounded before it starts, the chunk chosen from the problem, and a scheduler that does
not answer refused within its timeout. docs/explorer.md ("Limits") and docs/reliability.md
("The explorer's limits") say what each limit is.

None of these tests allocates much memory or runs long when the code is right: the
refusals come before any enumeration, and the runs are of small problems.
"""

from __future__ import annotations

import functools
import inspect
import math
import resource
import socket
import subprocess
import sys
import tracemalloc
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.physics.explore import merit, orders, rank, work
from crankbalance.physics.explore.candidates import Candidates
from crankbalance.physics.explore.rank import (
    FILTER_CHARS,
    FILTER_DEPTH,
    FILTER_NUMBER,
    FILTER_OPERATORS,
    parse_filter,
)
from crankbalance.studies.explore import Keep, evaluate_task, run, tasks

from .conftest import run_cli

COLUMNS = {
    "F1_N": np.array([0.0, 1.0, 2.0, 0.0]),
    "M1_Nm": np.array([0.0, 0.0, 3.0, 5.0]),
}
W12 = ("w", 12, 4, math.radians(60))
V12 = ("vee", 12, 4, math.radians(60))
#: a hang guard for the processes these tests start (never reached when the code is right)
GUARD = 300


def _problem(layout: str, cylinders: int, strokes: int, bank: float | None) -> Any:
    return orders.problem(layout, cylinders, strokes, bank_angle=bank)


def _one_line(code: int, out: str, err: str, named: str) -> None:
    assert code == 2 and out == "", err
    assert err.startswith(f"error: {named} = ") and err.count("\n") == 1, err
    assert "Traceback" not in err


# ------------------------------------------------------------------------------ filter
@pytest.mark.parametrize(
    ("text", "says"),
    [
        ("-" * 5000 + "F1 > 0", f"at most {FILTER_CHARS} characters"),
        ("-" * 150 + "F1 > 0", f"at most {FILTER_OPERATORS} operators"),
        (" and ".join(["F1 > 0"] * 60), f"at most {FILTER_OPERATORS} operators"),
        ("(" * 30 + "F1" + ")" * 30 + " > 0", f"nested at most {FILTER_DEPTH} deep"),
        ("F1 <= 1" + "0" * 400, "finite and at most 1e15"),
        ("F1 <= 1e999", "finite and at most 1e15"),
        ("F1 >= -1e999", "finite and at most 1e15"),
        ("F1 < inf", "finite and at most 1e15"),
        ("F1 < NaN", "finite and at most 1e15"),
        ("nonsense > 1", "unknown column 'nonsense'"),
    ],
)
def test_a_bad_filter_is_one_line_naming_the_option(
    text: str, says: str, capsys: pytest.CaptureFixture[str]
) -> None:
    code, out, err = run_cli(["explore", "--filter", text], capsys)
    _one_line(code, out, err, "--filter")
    assert says in err


def test_an_unknown_column_gives_the_closest_names_not_the_list(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # at --orders 64 the explorer has over 500 columns
    code, out, err = run_cli(["explore", "--orders", "64", "--filter", "f1 > 2"], capsys)
    _one_line(code, out, err, "--filter")
    assert "closest: F1," in err and len(err) < 250
    code, out, err = run_cli(["explore", "--orders", "64", "--objectives", "F1,M1_N"], capsys)
    _one_line(code, out, err, "--objectives")
    assert "closest: M1," in err and len(err) < 250


def _at_the_limits() -> str:
    """A filter with exactly the most operators and the deepest brackets allowed."""
    minus = FILTER_OPERATORS - FILTER_DEPTH - 1  # the brackets and >= count too
    return "(" * FILTER_DEPTH + "F1" + ")" * FILTER_DEPTH + " >= " + "-" * minus + "1"


def test_the_largest_filter_allowed_parses_and_evaluates_in_few_frames() -> None:
    text = _at_the_limits()
    assert rank._count_operators(text) == (FILTER_OPERATORS, FILTER_DEPTH)
    assert len(text) <= FILTER_CHARS
    # parsing and the recursive evaluation need a few hundred frames at most
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(len(inspect.stack()) + 400)
    try:
        kept = parse_filter(text, COLUMNS)(COLUMNS)
    finally:
        sys.setrecursionlimit(limit)
    assert kept.tolist() == [True] * 4  # F1 >= -1
    with pytest.raises(InputError, match="operators"):
        parse_filter("-" + text, COLUMNS)
    with pytest.raises(InputError, match="deep"):
        parse_filter("(" * (FILTER_DEPTH + 1) + "F1" + ")" * (FILTER_DEPTH + 1) + " > 0", COLUMNS)
    with pytest.raises(InputError, match="characters"):
        parse_filter("F1 > 0" + " " * FILTER_CHARS, COLUMNS)


@pytest.mark.parametrize(
    ("text", "counted"),
    [
        ("1e-6 >= F1", (1, 0)),  # the exponent's sign is part of the number
        ("F1 == 0 and M1 == 0", (3, 0)),
        ("abs(F1 - 2) < 0.5", (3, 1)),
        ("not (F1 > 0) or M1 < 1E+3", (5, 1)),
        ("'((((' < F1", (7, 4)),  # quotes, and brackets in a string, count (refused later)
    ],
)
def test_operators_and_brackets_are_counted_in_the_text(
    text: str, counted: tuple[int, int]
) -> None:
    assert rank._count_operators(text) == counted


@pytest.mark.parametrize(
    ("text", "allowed"),
    [
        (f"F1 < {FILTER_NUMBER:.0f}", True),
        (f"F1 > -{FILTER_NUMBER:g}", True),
        (f"F1 < {int(FILTER_NUMBER) + 1}", False),
        ("F1 < 1.0000001e15", False),
        ("F1 < 1e-300", True),
    ],
)
def test_numbers_are_bounded(text: str, allowed: bool) -> None:
    if allowed:
        assert parse_filter(text, COLUMNS)(COLUMNS).dtype == bool
    else:
        with pytest.raises(InputError, match="at most 1e15 in size"):
            parse_filter(text, COLUMNS)


def test_an_overflow_in_a_filter_warns_nothing() -> None:
    text = "F1 * " + " * ".join(["1e15"] * 30) + " >= 0"
    with np.errstate(all="raise"):  # any warning numpy would print fails the test
        assert parse_filter(text, COLUMNS)(COLUMNS).tolist() == [True] * 4


def test_the_web_tab_shows_the_same_line() -> None:
    pytest.importorskip("nicegui")
    from crankbalance.web import tab_explore

    texts = dict.fromkeys(tab_explore.SETTINGS, "") | {
        "layout": "inline",
        "cylinders": "4",
        "strokes": "4",
        "crank": "any",
        "x": "M1",
        "y": "M2",
        "top": "20",
    }
    for bad in ("-" * 5000 + "F1 > 0", "F1 <= 1e999", "nonsense > 1"):
        with pytest.raises(InputError) as web:
            tab_explore.parse(texts | {"filter": bad})
        with pytest.raises(InputError) as cli:
            parse_filter(bad, tab_explore._columns(), "--filter")
        assert web.value.field == "filter" and web.value.allowed == cli.value.allowed


# ------------------------------------------------------------------------------ work
def test_a_sample_beyond_the_budget_is_refused_at_once(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # formerly an allocation of 7.28 TiB
    args = ["explore", "--cylinders", "16", "--sample", "1000000000000"]
    code, out, err = run_cli(args, capsys)
    _one_line(code, out, err, "--sample")
    assert f"to {work.MAX_DRAWS}" in err


def _limited(args: list[str]) -> subprocess.CompletedProcess[str]:
    """The command in a process whose address space is limited to 3 GiB: a task list or
    an array that grows without bound ends in MemoryError, never on the machine."""

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))

    return subprocess.run(
        [sys.executable, "-m", "crankbalance", *args],
        capture_output=True,
        text=True,
        preexec_fn=limit,
        timeout=GUARD,
        check=False,
    )


@pytest.mark.parametrize("cylinders", ["16", "20"])
def test_an_enumeration_beyond_the_budget_is_one_line(cylinders: str) -> None:
    done = _limited(["explore", "--cylinders", cylinders])
    _one_line(done.returncode, done.stdout, done.stderr, "--cylinders")
    assert f"at most {work.MAX_CANDIDATES:,} candidates" in done.stderr
    assert "--sample" in done.stderr and "MemoryError" not in done.stderr


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (["--cylinders", "12", "--chunk", "1"], "at least 400 for this run"),
        (["--cylinders", "12", "--orders", "64", "--chunk", "100000000"], "at most"),
        (["--sample", "10", "--chunk", "0"], "from 1"),
    ],
)
def test_a_chunk_beyond_the_limits_is_one_line(
    args: list[str], says: str, capsys: pytest.CaptureFixture[str]
) -> None:
    code, out, err = run_cli(["explore", *args], capsys)
    _one_line(code, out, err, "--chunk")
    assert says in err


def test_a_layout_without_a_consistent_order_is_one_line(
    capsys: pytest.CaptureFixture[str],
) -> None:
    args = ["explore", "--layout", "vee", "--cylinders", "6", "--bank-angle", "90 deg"]
    code, out, err = run_cli(args, capsys)
    _one_line(code, out, err, "--cylinders")
    assert "none of its 120 firing orders" in err


class Counted:
    """explore.orders, counting the enumeration's calls."""

    def __init__(self) -> None:
        self.calls = 0

    def count(self, problem: Any) -> int:
        return orders.count(problem)

    def size(self, problem: Any, start: int, stop: int) -> orders.Size:
        return orders.size(problem, start, stop)

    def template(self, problem: Any) -> Candidates:
        return orders.template(problem)

    def chunk(self, problem: Any, start: int, stop: int) -> Candidates:
        self.calls += 1
        return orders.chunk(problem, start, stop)


def test_the_api_refuses_before_any_enumeration() -> None:
    source = Counted()
    problem = orders.problem("inline", 16, 4)
    with pytest.raises(InputError) as error:
        run(problem, merit.merit, source=source)
    assert error.value.field == "cylinders" and source.calls == 0
    with pytest.raises(InputError) as error:
        run(problem, merit.merit, chunk=1, span=(0, 10**6), source=source)
    assert error.value.field == "chunk" and "at least 10" in error.value.allowed
    assert source.calls == 0
    # a span within the budget runs
    result = run(problem, merit.merit, span=(0, 100), source=source)
    assert result.covered == 100 and source.calls == 1


def test_tasks_are_made_as_they_are_asked_for() -> None:
    many = tasks(orders.count(orders.problem("inline", 20, 4)), 1)
    assert len(many) == math.factorial(19)  # no list of 1.2e17 tasks was built
    assert many[0] == (0, 1) and many[-1] == (math.factorial(19) - 1, math.factorial(19))
    assert list(tasks(10, 4)) == [(0, 4), (4, 8), (8, 10)]


# ------------------------------------------------------------------------------ the chunk
def test_the_w12_broad_arrow_is_one_task(capsys: pytest.CaptureFixture[str]) -> None:
    problem = _problem(*W12)
    planned = work.plan(problem, merit.merit)
    assert planned.exact and planned.candidates == 480  # consistent orders, counted
    assert planned.chunk == orders.count(problem) and planned.tasks == 1
    args = ["explore", "--layout", "w", "--cylinders", "12", "--bank-angle", "60 deg"]
    code, out, err = run_cli([*args, "--format", "json"], capsys)
    assert code == 0, err
    assert '"distinct_engines": 256' in out and '"chunk": 39916800' in out


def test_an_inline_engine_takes_the_usual_candidates_per_task() -> None:
    planned = work.plan(orders.problem("inline", 12, 4), merit.merit)
    assert planned.chunk == work.TASK_CANDIDATES
    assert planned.tasks == -(-math.factorial(11) // work.TASK_CANDIDATES)
    given = work.plan(orders.problem("inline", 8, 4), merit.merit, chunk=100)
    assert (given.chunk, given.tasks) == (100, 51)


def test_the_chunk_changes_no_candidate() -> None:
    problem = _problem(*W12)
    keep = Keep(objectives=("F1_N", "M1_Nm"), key="F1_N", n=1000)
    chosen = run(problem, merit.merit, keep=keep)
    small = run(problem, merit.merit, keep=keep, chunk=2**19)
    assert chosen.candidates == small.candidates == 256
    assert sorted(chosen.top["index"]) == sorted(small.top["index"])


def test_the_chunk_changes_no_pareto_front() -> None:
    """Issue 26: the W12's front had 119, 104 or 109 members with the chunk. Every
    candidate's figures are computed alike in any batch (to the last bit, which the
    front's comparisons see), so the front and its numbers are the chunk's no more."""
    problem = _problem(*W12)
    keep = Keep(objectives=("F1_N", "M1_Nm", "F2_N", "M2_Nm", "cw_mass_kg"), key="F1_N", n=1)
    runs = [
        run(problem, merit.merit, keep=keep, chunk=chunk) for chunk in (None, 2**21, 2**17, 100_000)
    ]
    first = runs[0].pareto
    assert first["index"].size > 1
    for other in runs[1:]:
        assert sorted(other.pareto) == sorted(first)
        order_a, order_b = np.argsort(first["index"]), np.argsort(other.pareto["index"])
        for name in first:
            assert np.array_equal(first[name][order_a], other.pareto[name][order_b]), name


# ------------------------------------------------------------------------------ sizes
@pytest.mark.parametrize(
    "args", [W12, V12, ("vee", 8, 4, math.radians(90)), ("inline", 7, 4, None)]
)
def test_small_sizes_are_counted(args: tuple[Any, ...]) -> None:
    problem = _problem(*args)
    total = orders.count(problem)
    size = orders.size(problem, 0, total)
    assert size.exact
    assert size.orders == orders._consistent(problem, 0, total)[0].size
    part = orders.size(problem, total // 3, total // 2)
    assert part.orders == orders._consistent(problem, total // 3, total // 2)[0].size


@pytest.fixture
def narrow(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """The enumeration's levels kept small, so that a small problem takes the paths of a
    large one (the estimate, the halves)."""
    monkeypatch.setattr(orders, "SIZE_ELEMENTS", 20_000)
    monkeypatch.setattr(orders, "LEVEL_ELEMENTS", 2_000)
    orders.size.cache_clear()
    yield
    orders.size.cache_clear()


def test_a_large_size_is_estimated_near_the_count(narrow: None) -> None:
    problem = _problem(*V12)
    total = orders.count(problem)
    estimate = orders.size(problem, 0, total)
    orders.size.cache_clear()
    assert orders.size(problem, 0, total) == estimate  # the same on every call
    assert not estimate.exact
    # counted: 4 800 consistent orders and 206 672 prefixes (docs/explorer.md)
    assert 0.7 * 4800 < estimate.orders < 1.3 * 4800
    assert 0.7 * 206_672 < estimate.prefixes < 1.3 * 206_672


@pytest.mark.parametrize(
    ("args", "span"),
    [(V12, None), (W12, None), (("inline", 7, 4, None), (100, 700))],
)
def test_a_level_split_in_halves_gives_the_same_orders(
    args: tuple[Any, ...], span: tuple[int, int] | None, monkeypatch: pytest.MonkeyPatch
) -> None:
    problem = _problem(*args)
    start, stop = span or (0, orders.count(problem))
    whole = orders.chunk(problem, start, stop)
    monkeypatch.setattr(orders, "LEVEL_ELEMENTS", 500)
    halves = orders.chunk(problem, start, stop)
    for name in ("index", "firing_order", "throw_angle", "equivalents"):
        np.testing.assert_array_equal(getattr(halves, name), getattr(whole, name))


@pytest.mark.parametrize(
    ("args", "evaluate"),
    [
        (("inline", 8, 4, None), functools.partial(merit.merit, orders=64, target="secondary")),
        (("inline", 10, 4, None), merit.merit),
        (V12, merit.merit),
        (W12, merit.merit),
    ],
)
def test_a_task_stays_within_its_planned_memory(args: tuple[Any, ...], evaluate: Any) -> None:
    problem = _problem(*args)
    planned = work.plan(problem, evaluate)
    first = tasks(orders.count(problem), planned.chunk)[0]
    keep = Keep(objectives=("F1_N", "M1_Nm"), key="residual_M_Nm", n=20)
    tracemalloc.start()
    try:
        evaluate_task(problem, evaluate, None, keep, True, None, first)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak <= planned.task_bytes <= work.TASK_MEMORY


# ------------------------------------------------------------------------------ scheduler
def _explore_on(address: str) -> subprocess.CompletedProcess[str]:
    """``explore`` on the scheduler ``address``, waited for until the process ends."""
    pytest.importorskip("distributed")
    args = ["explore", "--scheduler", address, "--connect-timeout", "2 s"]
    return subprocess.run(
        [sys.executable, "-m", "crankbalance", *args],
        capture_output=True,
        text=True,
        timeout=GUARD,
        check=False,
    )


def test_a_closed_port_is_one_line() -> None:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]  # closed once the socket is
    done = _explore_on(f"tcp://127.0.0.1:{port}")
    _one_line(done.returncode, done.stdout, done.stderr, "--scheduler")
    assert "connection refused" in done.stderr


def test_a_port_that_never_answers_is_one_line() -> None:
    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen()  # accepts connections (the kernel does) and never speaks
        done = _explore_on(f"tcp://127.0.0.1:{silent.getsockname()[1]}")
    _one_line(done.returncode, done.stdout, done.stderr, "--scheduler")
    assert "answering within 2 s: it did not answer" in done.stderr


def test_seed_without_sample_is_refused(capsys: pytest.CaptureFixture[str]) -> None:
    """--seed only acts on a random search: without --sample it is refused, not ignored."""
    code, _, err = run_cli(["explore", "--cylinders", "4", "--seed", "3"], capsys)
    assert code == 2
    assert err.strip() == "error: --seed = '3': only acts with --sample"
