"""Web app, the Balance shop's summary (issue 28 screenshot review): one cylinder, a
spread that is round-off, the V8 example's parts on another engine (findings 12, 24, 28):
the parts in no set are named in the command line's words, and before the run the tab says
whose parts the example holds and how many of its sets the engine takes."""

from __future__ import annotations

from pathlib import Path

import pytest

from crankbalance.schema.settings import ShopOptions, parse_options
from crankbalance.studies.shop import shop_study, spares_words
from crankbalance.web.tab_shop import (
    EXAMPLE,
    EXAMPLE_HEADER,
    example_name,
    fit_words,
    parts_summary,
)

from ..conftest import run_cli

PARTS = Path(__file__).resolve().parents[2] / "examples" / "v8_parts.csv"
TEXT = PARTS.read_text(encoding="utf-8")
V8 = "Parts of a 90 deg V8 (small-block, 4.030 in bore, 5.7 in rods)"


@pytest.fixture(scope="module")
def options() -> ShopOptions:
    return parse_options(ShopOptions, {})


def test_the_example_is_recognised_and_named_by_its_header() -> None:
    assert EXAMPLE == PARTS and TEXT.startswith(EXAMPLE_HEADER)
    assert example_name(TEXT) == V8
    assert example_name("part,id,mass [g]\npiston,P1,480\n") is None


def test_one_cylinder_and_the_v8_example_on_it(options: ShopOptions) -> None:
    p = shop_study("single", PARTS, options).parts
    summary = parts_summary(p, example_name(TEXT))
    assert ": 1 cylinder, matching" in summary
    assert "1 cylinder: 1 part of each kind in the sets; spares, in no set: piston " in summary
    assert f"The example is not this engine's: {V8}; paste this engine's own parts." in summary
    assert "example" not in parts_summary(p, None)  # the user's own parts


def test_the_example_on_its_own_v8_says_nothing_more(options: ShopOptions) -> None:
    p = shop_study("v8-crossplane", PARTS, options).parts
    assert spares_words(p) == ""
    assert "spares" not in parts_summary(p, example_name(TEXT))
    assert "example" not in parts_summary(p, example_name(TEXT))


def test_the_spares_are_named_as_the_command_line_names_them(
    options: ShopOptions, capsys: pytest.CaptureFixture[str]
) -> None:
    """The inline-4 takes 4 of the example's 8 sets: the 4 parts of each kind left over
    are listed, the same line in the web's summary and in ``crankbalance shop match``."""
    p = shop_study("inline4", PARTS, options).parts
    words = spares_words(p)
    assert words.startswith("4 cylinders: 4 parts of each kind in the sets; spares, in no set:")
    for kind in p.inventory.kinds:
        used = {mark for ids in p.matching.ids for mark in ids}
        spare = [mark for mark in kind.ids if mark not in used]
        assert len(spare) == 4 and f"{kind.name} {', '.join(spare)}" in words
    assert words in parts_summary(p, example_name(TEXT))
    code, out, _ = run_cli(["shop", "match", str(PARTS), "--engine", "inline4"], capsys)
    assert code == 0 and words in out.splitlines(), out
    code, out, _ = run_cli(["shop", "match", str(PARTS), "--engine", "v8-crossplane"], capsys)
    assert code == 0 and "spares" not in out


def test_before_the_run_the_tab_says_what_the_parts_make_on_this_engine() -> None:
    assert fit_words(8, 8, V8) == ""
    assert fit_words(8, 4, V8) == (
        "The example: parts of a 90 deg V8 (small-block, 4.030 in bore, 5.7 in rods). "
        "This engine has 4 cylinders: the shop matches 4 sets from parts for 8, the other "
        "parts stay spare (the result lists them); paste this engine's own parts."
    )
    assert fit_words(8, 1, None).startswith("This engine has 1 cylinder: the shop matches 1 set")
    assert fit_words(8, 12, None) == (
        "This engine has 12 cylinders: the parts make 8 sets only, too few to run."
    )


def test_a_spread_of_round_off_reads_0_g(options: ShopOptions) -> None:
    """The V6's six lightest reciprocating sets are all 863.7 g: a spread of 2.22e-13 g is
    float round-off and reads 0 g (the matching sets it to 0: tests/test_shop_matching.py)."""
    p = shop_study("v6-60", PARTS, options).parts
    assert p.matching.reciprocating_spread == 0
    assert "spread 0 g reciprocating" in parts_summary(p, example_name(TEXT))
    assert "e-" not in parts_summary(p, example_name(TEXT))
