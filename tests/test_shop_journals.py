"""Which matched sets share a journal (crankbalance.physics.shop.journals, issue 27): the
pairing against brute force over every assignment of sets to cylinders, the joint matching
against the exhaustive search, the oil per journal or per rod, and the study's output."""

from __future__ import annotations

import itertools
import json
from pathlib import Path

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.parts_file import load_parts_file
from crankbalance.physics.shop.journals import MAX_GROUPINGS, groupings, pair_journals
from crankbalance.physics.shop.matching import Inventory, match_parts
from crankbalance.schema.settings import ShopOptions
from crankbalance.studies.shop import parts_study

from .conftest import EXAMPLES, run_cli
from .test_shop_matching import G, engine, random_inventory


def brute_force_spread(weight: np.ndarray, throw: np.ndarray) -> float:
    """The least spread of the journals' sums over every assignment of the sets to the
    cylinders (all C! of them), independent of the groupings the module enumerates."""
    best = np.inf
    for order in itertools.permutations(range(weight.size)):
        sums = np.bincount(throw, weights=weight[list(order)])
        best = min(best, float(np.ptp(sums)))
    return best


V8 = np.array([0, 1, 2, 3, 0, 1, 2, 3])  # the v8-crossplane preset's cylinder_throw


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_v8_pairing_milp_and_exhaustive_equal_brute_force(seed: int) -> None:
    """On a V8 (8 sets, 4 journals of 2: 105 groupings, 40 320 assignments) the MILP and
    the exhaustive pairing both reach the brute-force least spread, proven."""
    weight = np.random.default_rng(seed).normal(0.9, 0.002, 8)
    expected = brute_force_spread(weight, V8)
    for method in ("milp", "exhaustive"):
        paired = pair_journals(weight, V8, 4, method)
        assert paired.optimal and paired.status == "proven optimal"
        assert paired.spread == pytest.approx(expected, abs=1e-12)
        # what it reports is what it did: the journals' sums of the sets it placed
        sums = np.bincount(V8, weights=weight[paired.set_of_cylinder])
        assert paired.bob_weight == pytest.approx(sums, abs=1e-15)
        assert sorted(paired.set_of_cylinder.tolist()) == list(range(8))
    listed = pair_journals(weight, V8, 4, "as-listed")
    assert listed.spread == pytest.approx(np.ptp(np.bincount(V8, weights=weight)))
    assert listed.spread == paired.as_listed_spread >= paired.spread


def test_w12_pairing_of_three_rods_per_journal() -> None:
    """Journals of three rods (the broad-arrow W12: 15 400 groupings): the MILP equals the
    exhaustive pairing."""
    throw = np.repeat(np.arange(4), 3)
    weight = np.random.default_rng(4).normal(0.7, 0.003, 12)
    milp = pair_journals(weight, throw, 4, "milp")
    full = pair_journals(weight, throw, 4, "exhaustive")
    assert milp.optimal and full.optimal
    assert milp.spread == pytest.approx(full.spread, abs=1e-12)
    assert all(len(sets) == 3 for sets in milp.journal_sets)


def test_groupings_and_their_bound() -> None:
    assert groupings([2, 2, 2, 2]) == 105
    assert groupings([2] * 6) == 10_395
    assert groupings([2] * 8) == 2_027_025 > MAX_GROUPINGS
    with pytest.raises(InputError, match="2027025 groupings"):
        pair_journals(np.ones(16), np.tile(np.arange(8), 2), 8, "exhaustive")
    # one rod per journal (an in-line engine, split pins): nothing to pair
    single = pair_journals([0.5, 0.6, 0.4], [0, 1, 2], 3)
    assert single.optimal and "nothing to pair" in single.status
    assert single.set_of_cylinder.tolist() == [0, 1, 2]
    with pytest.raises(InputError, match="method"):
        pair_journals([0.5, 0.6], [0, 0], 1, "greedy")


@pytest.mark.parametrize(("seed", "counts"), [(31, (4, 4)), (32, (5, 4)), (33, (4, 4, 4))])
def test_joint_milp_equals_exhaustive_on_a_v4(seed: int, counts: tuple[int, ...]) -> None:
    """The joint objective (the sets' weighted spread plus the journals' spread) on the
    90 deg V4 (two journals of two rods): the MILP reaches the exhaustive optimum over
    every ordered assignment, and is no worse than matching first and pairing after."""
    model = engine("v4-90")
    inventory = random_inventory(seed, counts, 4)
    if len(counts) == 3:  # 3 kinds of 4: 4!^3 = 13 824 assignments
        inventory = Inventory(inventory.kinds, inventory.reciprocating_allowance, 4.0 * G)
    joint = match_parts(inventory, 4, "milp", "journal", model=model, fraction=0.5)
    full = match_parts(inventory, 4, "exhaustive", "journal", model=model, fraction=0.5)
    assert joint.optimal
    assert joint.objective_value == pytest.approx(full.objective_value, rel=1e-9, abs=1e-12)
    throw = np.asarray(model.cylinder_throw)
    bob = np.bincount(throw, weights=joint.rotating + 0.5 * joint.reciprocating)
    expected = joint.reciprocating_spread + joint.rotating_spread + np.ptp(bob)
    assert joint.objective_value == pytest.approx(expected, rel=1e-12)
    first = match_parts(inventory, 4, "milp")  # matched first, then paired
    paired = pair_journals(first.rotating + 0.5 * first.reciprocating, throw, model.throws)
    sequential = first.reciprocating_spread + first.rotating_spread + paired.spread
    assert joint.objective_value <= sequential + 1e-12


def test_joint_needs_the_engine() -> None:
    inventory = random_inventory(34, (4, 4), 4)
    with pytest.raises(InputError, match="needs the engine"):
        match_parts(inventory, 4, "milp", "journal")
    with pytest.raises(InputError, match="pairing"):
        match_parts(inventory, 4, "pairing", "journal", model=engine("v4-90"))


def with_oil(tmp_path: Path, line: str) -> Path:
    """The V8 example's parts with its oil line replaced by ``line``."""
    text = (EXAMPLES / "v8_parts.csv").read_text(encoding="utf-8")
    lines = [row for row in text.splitlines() if not row.startswith("oil,")]
    path = tmp_path / f"{line.split(',')[0]}.csv"
    path.write_text("\n".join([*lines, line]) + "\n", encoding="utf-8")
    return path


def test_oil_per_journal_or_per_rod_the_same_total(tmp_path: Path) -> None:
    """8 g of oil per journal on a V8 (two rods a journal) is 4 g per rod: the same
    total (32 g), the same sets and the same bob-weights either way."""
    per_rod = load_parts_file(with_oil(tmp_path, "oil,,4.0,,"))
    per_journal = load_parts_file(with_oil(tmp_path, "journal_oil,,8.0,,"))
    assert per_rod.rotating_allowance == pytest.approx(4 * G)
    assert per_journal.journal_allowance == pytest.approx(8 * G)
    assert per_journal.rotating_allowance == 0.0
    model = engine("v8-crossplane")
    shared = per_journal.per_rod(model.cylinder_throw)
    assert 8 * shared.rotating_allowance == pytest.approx(4 * per_journal.journal_allowance)
    assert 8 * shared.rotating_allowance == pytest.approx(8 * per_rod.rotating_allowance)
    options = ShopOptions(method="as-listed", journals="as-listed")
    a = parts_study("v8-crossplane", per_rod, options)
    b = parts_study("v8-crossplane", per_journal, options)
    assert b.bob_weights.bob_weight == pytest.approx(a.bob_weights.bob_weight, abs=1e-15)
    assert b.matching.rotating == pytest.approx(a.matching.rotating, abs=1e-15)
    assert b.bob_weights.rotating.sum() == pytest.approx(
        a.bob_weights.rotating.sum(), abs=1e-15
    )  # the oil of the engine: 32 g either way, in the journals' rotating shares
    options = ShopOptions(method="as-listed")  # paired on the journals
    a, b = (parts_study("v8-crossplane", x, options) for x in (per_rod, per_journal))
    assert b.journals.spread == pytest.approx(a.journals.spread, abs=1e-12)
    # unshared, nothing matches it: a per-journal allowance is never silently dropped
    with pytest.raises(InputError, match="per journal"):
        match_parts(per_journal, 8, "as-listed")
    # journals of different numbers of rods cannot share it evenly
    with pytest.raises(InputError, match="give the oil per rod"):
        per_journal.per_rod([0, 0, 1])
    toml = tmp_path / "oil.toml"
    toml.write_text('journal_oil = "8 g"\n[[piston]]\nmass = "500 g"\n', encoding="utf-8")
    assert load_parts_file(toml).journal_allowance == pytest.approx(8 * G)
    both = tmp_path / "both.csv"
    both.write_text("part,id,mass [g]\npiston,P1,500\noil,,4\njournal_oil,,8\n", encoding="utf-8")
    with pytest.raises(InputError, match="oil allowance twice"):
        load_parts_file(both)


def test_the_study_pairs_the_sets_on_the_journals(capsys: pytest.CaptureFixture[str]) -> None:
    """shop match on the V8 example (the sets as listed, to be quick): the sets paired on
    the journals (proven), the journals' bob-weights those of the bob-weight table, their
    spread at most as listed; --journals as-listed keeps set c in cylinder c; joint refuses
    the method pairing."""
    parts = str(EXAMPLES / "v8_parts.csv")
    args = ["shop", "match", parts, "--engine", "v8-crossplane", "--method", "as-listed"]
    code, text, err = run_cli([*args, "--format", "json"], capsys)
    assert code == 0, err
    study = json.loads(text)["result"]
    journals = study["journals"]
    assert journals["method"] == "milp" and journals["optimal"]
    assert journals["spread_kg"] <= journals["as_listed_spread_kg"]
    code, text, err = run_cli(["shop", "bobweights", *args[2:], "--format", "json"], capsys)
    assert code == 0, err
    bob = json.loads(text)["result"]["bob_weight_kg"]
    assert bob == pytest.approx(journals["bob_weight_kg"], abs=1e-12)
    assert journals["spread_kg"] == pytest.approx(np.ptp(bob), abs=1e-12)
    # the sets of the matching are the same sets, moved between cylinders
    code, text, err = run_cli([*args, "--journals", "as-listed", "--format", "json"], capsys)
    assert code == 0, err
    listed = json.loads(text)["result"]
    assert sorted(map(tuple, listed["matching"]["ids"])) == sorted(
        map(tuple, study["matching"]["ids"])
    )
    assert listed["journals"]["spread_kg"] == pytest.approx(journals["as_listed_spread_kg"])
    code, table, err = run_cli(args, capsys)
    assert code == 0, err
    assert "spread of the journals' bob-weights" in table and "pin 1: cylinders 1, 5" in table
    code, _, err = run_cli([*args[:-1], "pairing", "--journals", "joint"], capsys)
    assert code == 2 and "--journals" in err and "milp or exhaustive" in err


def test_the_shop_sheet_shows_the_journals() -> None:
    """The sheet names how the sets went on the journals, the cylinders of each crankpin
    with its bob-weight, and the spread against the sets as listed."""
    from crankbalance.output.shop_sheet import sheet_html
    from crankbalance.studies.shop import shop_study

    study = shop_study("v8-crossplane", EXAMPLES / "v8_parts.csv", ShopOptions(method="as-listed"))
    page = sheet_html(study, static=True)
    assert "<h2>Sets on the journals</h2>" in page
    assert "paired for the least spread of the journals&#x27; bob-weights (proven optimal)" in page
    pairing = study.parts.journals
    for t, weight in enumerate(pairing.bob_weight):
        cylinders = ", ".join(str(c + 1) for c in np.flatnonzero(pairing.cylinder_throw == t))
        assert f"<td>{t + 1}</td><td>{cylinders}</td><td>{weight * 1e3:.5g} g</td>" in page.replace(
            "\n", ""
        )
