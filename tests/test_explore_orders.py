"""Enumeration of firing orders and their equivalences (issue 15, explore.orders).

Known results (inline-4 flat crank, the makers' V8 orders, the 270/450 twins), counts
against a brute force written here independently of the module (every permutation,
the crank from ``studies.build``, the mirror maps by hand), chunking, and the partition of
all orders into classes. The makers' maps come from crankbalance.physics.firing
(docs/engine_file.md, "Makers' numbering").
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import replace

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import parse_engine_text, preset_text
from crankbalance.physics.explore import orders
from crankbalance.physics.firing import SCHEMES
from crankbalance.physics.model import EngineModel
from crankbalance.studies.build import build_model

V90 = math.pi / 2
#: the makers' V8 numberings, from their one place (crankbalance.physics.firing, where the rules
#: and sources are): GM numbers along the crank, odd cylinders on the left bank, even on the
#: right (crankbalance's bank A); Ford bank after bank, the right bank first: its numbers
#: are crankbalance's. maker's number -> crankbalance's.
GM = dict(enumerate(SCHEMES["gm-vee"].to_crankbalance(8), start=1))
FORD = dict(enumerate(SCHEMES["ford-vee"].to_crankbalance(8), start=1))


def mapped(order: tuple[int, ...], numbering: dict[int, int]) -> tuple[int, ...]:
    """A maker's firing order in crankbalance's numbering, from cylinder 1."""
    ours = [numbering[c] for c in order]
    k = ours.index(1)
    return tuple(ours[k:] + ours[:k])


def enumerate_all(problem: orders.Problem) -> orders.Candidates:
    return orders.chunk(problem, 0, orders.count(problem))


def sequences(candidates: orders.Candidates) -> list[tuple[int, ...]]:
    return [tuple(int(c) for c in row) for row in candidates.firing_order]


def gap(a: np.ndarray) -> np.ndarray:
    return np.abs(np.remainder(np.asarray(a) + np.pi, 2 * np.pi) - np.pi)


def built(
    preset: str, order: tuple[int, ...], strokes: int | None = None, bank: float | None = None
) -> EngineModel:
    """A preset with this firing order in crankbalance's numbering (a maker's numbering
    dropped) and its crank from it (throw_angles dropped)."""
    text = re.sub(r"throw_angles = \[[^\]]*\]\n", "", preset_text(preset))
    text = re.sub(r"numbering = .*\n", "", text)
    text = re.sub(r"firing_order = \[[^\]]*\].*\n", "", text)
    text = re.sub(
        r"cylinders = \d+", f"cylinders = {len(order)}\nfiring_order = {list(order)}", text
    )
    if strokes is not None:
        text = re.sub(r"strokes = \d", f"strokes = {strokes}", text)
    if bank is not None:
        text = re.sub(
            r'bank_angle = "[^"]*"', f'bank_angle = "{math.degrees(bank):.12g} deg"', text
        )
    return build_model(parse_engine_text(text))


def brute_force(
    preset: str,
    n: int,
    strokes: int,
    bank: float | None,
    mirror_map: dict[int, int],
    reversal_map: dict[int, int] | None = None,
) -> tuple[set[tuple[int, ...]], set[tuple[int, ...]]]:
    """Every order from cylinder 1 that studies.build accepts, and the least of each class.

    Classes by hand: an order and the same sequence renumbered with ``mirror_map`` (the
    engine numbered from the other end), read again from cylinder 1; with
    ``reversal_map`` also the reversed sequence renumbered with it (run backwards, a
    vee's banks swap) and its mirror. The index order of the module with even firing is
    the lexicographic order of the sequences, so the least sequence of a class is its
    canonical candidate.
    """
    consistent: set[tuple[int, ...]] = set()
    for rest in itertools.permutations(range(2, n + 1)):
        order = (1, *rest)
        try:
            built(preset, order, strokes, bank)
        except InputError:
            continue
        consistent.add(order)

    def images(order: tuple[int, ...]) -> list[tuple[int, ...]]:
        found = [order, mapped(order, mirror_map)]
        if reversal_map is not None:
            backwards = mapped(order[::-1], reversal_map)
            found += [backwards, mapped(backwards, mirror_map)]
        return found

    least = {min(images(order)) for order in consistent}
    return consistent, least


# --------------------------------------------------------------------------- known results
def test_inline4_flat_crank_orders() -> None:
    p = orders.problem("inline", 4, 4, crank="flat")
    found = enumerate_all(p)
    # 3! = 6 orders from cylinder 1; renumbering from the other end pairs 1-2-3-4 with
    # 1-4-3-2 and 1-3-2-4 with 1-4-2-3, while 1-2-4-3 and 1-3-4-2 are their own mirror
    assert sequences(found) == [(1, 2, 3, 4), (1, 2, 4, 3), (1, 3, 2, 4), (1, 3, 4, 2)]
    assert found.equivalents.tolist() == [2, 1, 2, 1]
    assert orders.equivalent_orders(p, (1, 2, 3, 4)) == [(1, 2, 3, 4), (1, 4, 3, 2)]
    # the usual crank (outer throws up, inner down) allows exactly the two known orders
    usual = orders.problem("inline", 4, 4, fixed_throw_angles=[0, math.pi, math.pi, 0])
    assert sequences(enumerate_all(usual)) == [(1, 2, 4, 3), (1, 3, 4, 2)]
    np.testing.assert_allclose(enumerate_all(usual).throw_angle[:, 1:3], math.pi)
    # run backwards, 1-3-4-2 is 1-2-4-3: one engine when time reversal counts
    reversed_too = orders.problem("inline", 4, 4, reversal=True)
    assert orders.equivalent_orders(reversed_too, (1, 3, 4, 2)) == [(1, 2, 4, 3), (1, 3, 4, 2)]
    assert orders.equivalent_orders(p, (3, 4, 2, 1)) == [(1, 3, 4, 2)]  # any start


def test_v8_crossplane_makers_orders() -> None:
    p = orders.problem("vee", 8, 4, bank_angle=V90, crank="cross")
    found = enumerate_all(p)
    assert np.all(gap(found.fire_angle * 4) < 1e-9)  # even firing: every 90 deg
    listed = set(sequences(found))
    gm = mapped((1, 8, 4, 3, 6, 5, 7, 2), GM)
    ford_302 = mapped((1, 5, 4, 2, 6, 3, 7, 8), FORD)
    ford_351w = mapped((1, 3, 7, 2, 6, 5, 4, 8), FORD)
    assert gm == ford_302 == (1, 5, 4, 2, 6, 3, 7, 8)  # one order under two numberings
    classes = {order: orders.equivalent_orders(p, order) for order in (gm, ford_351w)}
    # the 351W's order is the 302's numbered from the other end: one engine, mirrored
    assert classes[gm] == classes[ford_351w] == [(1, 3, 7, 2, 6, 5, 4, 8), gm]
    assert len(listed & set(classes[gm])) == 1
    # counted apart when mirror images are not the same engine: which end is throw 1
    apart = orders.problem("vee", 8, 4, bank_angle=V90, crank="cross", mirror=False)
    assert {gm, ford_351w} <= set(sequences(enumerate_all(apart)))
    # both cranks are crossplane: throws 90 deg apart, not all in one plane
    for order in (gm, ford_351w):
        relative = built("v8-crossplane", order).throw_angle
        relative = relative - relative[0]
        assert np.all(gap(4 * relative) < 1e-9) and not np.all(gap(2 * relative) < 1e-9)
    # the flat-plane V8 orders are the other consistent ones
    flat = enumerate_all(orders.problem("vee", 8, 4, bank_angle=V90, crank="flat"))
    assert np.all(gap(2 * (flat.throw_angle - flat.throw_angle[:, :1])) < 1e-9)
    every = enumerate_all(orders.problem("vee", 8, 4, bank_angle=V90))
    assert sorted(sequences(every)) == sorted(sequences(flat) + sequences(found))


def test_uneven_twins_270_450() -> None:
    two_pi = 2 * math.pi
    # in-line twin: cylinder 2 fires 270 or 450 deg after cylinder 1 (crank at 90 or 270
    # deg): mirror images of one engine
    p = orders.problem("inline", 2, 4, intervals=[0.75 * two_pi, 1.25 * two_pi])
    assert orders.count(p) == 2
    found = enumerate_all(p)
    assert found.size == 1 and found.equivalents.tolist() == [2]
    np.testing.assert_allclose(found.fire_angle, [[0.0, 0.75 * two_pi]])
    ref = build_model(parse_engine_text(preset_text("inline2-270")))
    rel = ref.throw_angle - ref.throw_angle[0]
    ours = found.throw_angle[0] - found.throw_angle[0, 0]
    assert gap(ours - rel).max() < 1e-9 or gap(ours + rel).max() < 1e-9
    assert orders.equivalent_orders(p, (1, 2)) == [(1, 2), (2, 1)]
    # 90 deg vee twin on one pin: bank B must fire 90 deg (mod 360) after bank A, so 450
    vee = orders.problem("vee", 2, 4, bank_angle=V90, intervals=[1.25 * two_pi, 0.75 * two_pi])
    found = enumerate_all(vee)
    assert found.size == 1
    np.testing.assert_allclose(found.fire_angle, [[0.0, 1.25 * two_pi]])


# --------------------------------------------------------------------------- brute force
CASES = [
    # preset, layout, cylinders, strokes, bank angle, numbering from the other end
    ("inline4", "inline", 4, 4, None, {1: 4, 2: 3, 3: 2, 4: 1}),
    ("inline6", "inline", 6, 4, None, {c: 7 - c for c in range(1, 7)}),
    ("inline5", "inline", 5, 2, None, {c: 6 - c for c in range(1, 6)}),
    ("boxer6", "boxer", 6, 4, None, {c: 7 - c for c in range(1, 7)}),
    ("v8-crossplane", "vee", 8, 4, V90, {1: 4, 2: 3, 3: 2, 4: 1, 5: 8, 6: 7, 7: 6, 8: 5}),
    ("v8-crossplane", "vee", 6, 2, math.pi / 3, {1: 3, 2: 2, 3: 1, 4: 6, 5: 5, 6: 4}),
    ("w12", "w", 6, 4, math.pi / 3, {1: 2, 2: 1, 3: 4, 4: 3, 5: 6, 6: 5}),
]


@pytest.mark.parametrize(("preset", "layout", "n", "strokes", "bank", "mirror_map"), CASES)
def test_against_brute_force_and_build(
    preset: str,
    layout: str,
    n: int,
    strokes: int,
    bank: float | None,
    mirror_map: dict[int, int],
) -> None:
    p = orders.problem(layout, n, strokes, bank_angle=bank)
    assert orders.count(p) == math.factorial(n - 1)
    found = enumerate_all(p)
    consistent, least = brute_force(preset, n, strokes, bank, mirror_map)
    assert set(sequences(found)) == least
    assert int(found.equivalents.sum()) == len(consistent)
    assert np.all(np.diff(found.index) > 0)
    for k, order in enumerate(sequences(found)):
        model = built(preset, order, strokes, bank)
        assert gap(found.throw_angle[k] - model.throw_angle).max() < 1e-9, order
        # the crank puts each cylinder at its firing top dead centre at its fire angle
        tdc = found.fire_angle[k] + found.throw_angle[k][p.topology.cylinder_throw]
        assert gap(tdc - p.topology.cylinder_bank).max() < 1e-9


@pytest.mark.parametrize(
    ("preset", "layout", "n", "bank", "mirror_map", "reversal_map"),
    [
        (
            "inline6",
            "inline",
            6,
            None,
            {c: 7 - c for c in range(1, 7)},
            {c: c for c in range(1, 7)},
        ),
        ("v8-crossplane", "vee", 8, V90, CASES[4][5], {c: (c + 3) % 8 + 1 for c in range(1, 9)}),
    ],
)
def test_time_reversal_against_brute_force(
    preset: str,
    layout: str,
    n: int,
    bank: float | None,
    mirror_map: dict[int, int],
    reversal_map: dict[int, int],
) -> None:
    p = orders.problem(layout, n, 4, bank_angle=bank, reversal=True)
    found = enumerate_all(p)
    consistent, least = brute_force(preset, n, 4, bank, mirror_map, reversal_map)
    assert set(sequences(found)) == least
    assert int(found.equivalents.sum()) == len(consistent)
    # an uneven pattern whose reverse is no rotation of itself has no reversed twin
    steps = [math.radians(a) for a in (200, 240, 280)]
    one_way = orders.problem("inline", 3, 4, intervals=steps, reversal=True)
    both = orders.problem("inline", 3, 4, intervals=steps)
    np.testing.assert_array_equal(enumerate_all(one_way).index, enumerate_all(both).index)


def test_classes_partition_all_orders() -> None:
    p = orders.problem("vee", 8, 4, bank_angle=V90)
    found = enumerate_all(p)
    seen: dict[tuple[int, ...], tuple[int, ...]] = {}
    for order, size in zip(sequences(found), found.equivalents.tolist(), strict=True):
        members = orders.equivalent_orders(p, order)
        assert members[0] == order and len(members) == size
        for member in members:
            assert member not in seen, f"{member} in the classes of {seen.get(member)} and {order}"
            seen[member] = order
            assert orders.equivalent_orders(p, member) == members
    for rest in itertools.permutations(range(2, 9)):
        order = (1, *rest)
        try:
            orders.equivalent_orders(p, order)
        except InputError:
            assert order not in seen
            continue
        assert order in seen


def test_chunks_equal_the_whole() -> None:
    for p in (
        orders.problem("inline", 7, 4),
        orders.problem("vee", 8, 4, bank_angle=V90),
        orders.problem("inline", 4, 4, intervals=[math.pi, 2 * math.pi, math.pi / 2, math.pi / 2]),
    ):
        whole = enumerate_all(p)
        edges = [0, 1, 2, 17, 100, 101, orders.count(p) // 2, orders.count(p)]
        edges = sorted({min(e, orders.count(p)) for e in edges})
        parts = [orders.chunk(p, a, b) for a, b in itertools.pairwise(edges)]
        for name in ("throw_angle", "firing_order", "fire_angle", "equivalents", "index"):
            joined = np.concatenate([getattr(c, name) for c in parts])
            np.testing.assert_array_equal(joined, getattr(whole, name), err_msg=name)


@pytest.mark.parametrize(
    "p",
    [
        orders.problem("inline", 9, 4),  # 8 Lehmer digits: blocks of the table's 6
        orders.problem("inline", 5, 2, intervals=[1.0, 1.2, 1.4, 1.1, 2 * math.pi - 4.7]),
        orders.problem("inline", 3, 4),  # fewer digits than the table
        orders.problem("inline", 1, 4),
    ],
)
def test_every_order_of_pins_alone_is_the_pruned_enumeration(
    p: orders.Problem, monkeypatch: pytest.MonkeyPatch
) -> None:
    # no cylinder shares a pin: the orders come from the table of permutations, the same
    # as the enumeration digit by digit (forced here) and as each index unranked
    total = orders.count(p)
    edges = sorted({0, 1, 5, 719, 720, 721, 5039, 5041, total // 3, total - 2, total})
    edges = [e for e in edges if 0 <= e <= total]
    fast = [orders._consistent(p, a, b) for a, b in itertools.pairwise(edges)]
    monkeypatch.setattr(orders, "_pins_alone", lambda plan: False)
    for (a, b), got in zip(itertools.pairwise(edges), fast, strict=True):
        want = orders._consistent(p, a, b)
        for g, w in zip(got, want, strict=True):
            np.testing.assert_array_equal(g, w)
        slots, rot = orders._unrank(p._plan, np.arange(a, b))
        np.testing.assert_array_equal(got[1], slots)
        np.testing.assert_array_equal(got[2], rot)


def lehmer_rank(order: tuple[int, ...]) -> int:
    """Lexicographic rank of an order among the orders from cylinder 1, by hand."""
    rest = list(order[1:])
    return sum(
        sum(later < c for later in rest[k + 1 :]) * math.factorial(len(rest) - 1 - k)
        for k, c in enumerate(rest)
    )


def test_twelve_cylinders_by_chunk() -> None:
    # 11! = 39 916 800 indices: a chunk anywhere is unranked without the rest
    p = orders.problem("inline", 12, 2)
    assert orders.count(p) == 39_916_800
    start = 20_000_000  # (orders near the end are mirror images of earlier ones)
    found = orders.chunk(p, start, start + 700)
    assert found.size > 0 and found.index.min() >= start and found.index.max() < start + 700
    for order, index in zip(sequences(found), found.index.tolist(), strict=True):
        assert lehmer_rank(order) == index
    # shared pins: the W12's consistent orders, chunked and whole
    w12 = orders.problem("w", 12, 4, bank_angle=math.pi / 3)
    whole = enumerate_all(w12)
    assert whole.size == 256 and int(whole.equivalents.sum()) == 480
    step = orders.count(w12) // 7 + 1
    parts = [
        orders.chunk(w12, a, min(a + step, orders.count(w12)))
        for a in range(0, orders.count(w12), step)
    ]
    np.testing.assert_array_equal(np.concatenate([c.index for c in parts]), whole.index)
    preset = build_model(parse_engine_text(preset_text("w12")))
    assert any(
        preset.firing_order in orders.equivalent_orders(w12, order) for order in sequences(whole)
    )


def test_split_pin_v6_90() -> None:
    # a 90 deg V6 cannot fire evenly on shared pins; split pins allow every order
    assert enumerate_all(orders.problem("vee", 6, 4, bank_angle=V90)).size == 0
    p = orders.problem("vee", 6, 4, bank_angle=V90, crank="split")
    assert p.topology.throws == 6
    np.testing.assert_array_equal(p.topology.throw_position[:3], p.topology.throw_position[3:])
    found = enumerate_all(p)
    assert int(found.equivalents.sum()) == math.factorial(5)
    # GM's even-firing 90 deg V6 (odd cylinders left, even right, right bank leading as
    # in the V8), firing 1-6-5-4-3-2: the two pins of each pair are 30 deg apart
    order = mapped((1, 6, 5, 4, 3, 2), dict(enumerate(SCHEMES["gm-vee"].to_crankbalance(6), 1)))
    k = sequences(found).index(orders.equivalent_orders(p, order)[0])
    split = found.throw_angle[k, 3:] - found.throw_angle[k, :3]
    assert np.all(np.isclose(gap(split), math.radians(30)))


def test_base_masses_and_broken_symmetry() -> None:
    base = built("inline4", (1, 3, 4, 2))
    p = orders.problem("inline", 4, 4, base=base)
    np.testing.assert_array_equal(p.topology.reciprocating_mass, base.reciprocating_mass)
    np.testing.assert_array_equal(p.topology.throw_position, base.throw_position)
    # a heavier piston in cylinder 1: numbered from the other end it is another engine
    heavy = replace(base, reciprocating_mass=base.reciprocating_mass * [1.1, 1, 1, 1])
    lopsided = enumerate_all(orders.problem("inline", 4, 4, base=heavy))
    assert lopsided.size == 6 and lopsided.equivalents.tolist() == [1] * 6
    # an offset piston pin: run backwards it is offset the other way, another engine
    offset = replace(base, cylinder_offset=np.full(base.cylinders, 0.001))
    one_way = orders.problem("inline", 4, 4, base=offset, reversal=True)
    assert orders.equivalent_orders(one_way, (1, 3, 4, 2)) == [(1, 3, 4, 2)]
    topology = orders.problem("inline", 4, 4, base=offset).topology
    assert topology.cylinder_offset.tolist() == [0.001] * 4
    with pytest.raises(InputError, match="base"):
        orders.problem("inline", 6, 4, base=base)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"layout": "star", "cylinders": 4, "strokes": 4}, "layout"),
        ({"layout": "inline", "cylinders": 0, "strokes": 4}, "cylinders"),
        ({"layout": "inline", "cylinders": 21, "strokes": 4}, "cylinders"),
        ({"layout": "vee", "cylinders": 7, "strokes": 4, "bank_angle": 1.0}, "cylinders"),
        ({"layout": "inline", "cylinders": 4, "strokes": 3}, "strokes"),
        ({"layout": "vee", "cylinders": 8, "strokes": 4}, "bank_angle"),
        ({"layout": "inline", "cylinders": 4, "strokes": 4, "bank_angle": 1.0}, "bank_angle"),
        ({"layout": "inline", "cylinders": 4, "strokes": 4, "crank": "split"}, "crank"),
        ({"layout": "inline", "cylinders": 4, "strokes": 4, "crank": "bent"}, "crank"),
        ({"layout": "inline", "cylinders": 2, "strokes": 4, "intervals": [1, 2]}, "intervals"),
        ({"layout": "inline", "cylinders": 4, "strokes": 4, "fixed_throw_angles": [0]}, "fixed"),
    ],
)
def test_bad_input_names_the_field(kwargs: dict, field: str) -> None:
    with pytest.raises(InputError, match=field):
        orders.problem(**kwargs)


def test_bad_chunk_and_order() -> None:
    p = orders.problem("vee", 8, 4, bank_angle=V90)
    with pytest.raises(InputError, match="chunk"):
        orders.chunk(p, 0, orders.count(p) + 1)
    with pytest.raises(InputError, match="firing_order"):
        orders.equivalent_orders(p, (1, 2, 3))
    with pytest.raises(InputError, match="crankpin"):
        orders.equivalent_orders(p, (1, 2, 3, 4, 5, 6, 7, 8))


@pytest.mark.parametrize(
    "args",
    [
        dict(layout="inline", cylinders=6, strokes=4, reversal=True),
        dict(layout="inline", cylinders=8, strokes=4, crank="cross"),
        dict(layout="vee", cylinders=8, strokes=4, bank_angle=V90),
        dict(layout="inline", cylinders=4, strokes=4, fixed_throw_angles=[0, math.pi, math.pi, 0]),
        dict(layout="inline", cylinders=5, strokes=2, mirror=False),
    ],
)
def test_the_orbit_table_gives_what_each_range_computes(
    args: dict, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A problem of at most ORBIT_TABLE indices looks its equivalences up in a table made
    once (in pieces of ORBIT_PIECE indices): the same candidates, equivalents and order as
    computed range by range."""
    problem = orders.problem(**args)
    total = orders.count(problem)
    assert total <= orders.ORBIT_TABLE
    monkeypatch.setattr(orders, "ORBIT_PIECE", 37)  # the table made in pieces
    idx = np.unique(np.random.default_rng(0).integers(0, total, 40))
    looked_up = [
        orders.chunk(problem, 0, total),
        orders.chunk(problem, 1, total // 2),
        orders.at(problem, idx),
    ]
    monkeypatch.setattr(orders, "ORBIT_TABLE", 0)
    computed = [
        orders.chunk(problem, 0, total),
        orders.chunk(problem, 1, total // 2),
        orders.at(problem, idx),
    ]
    for a, b in zip(looked_up, computed, strict=True):
        for name in ("throw_angle", "firing_order", "fire_angle", "equivalents", "index"):
            assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert looked_up[0].size > 0
