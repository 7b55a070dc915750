"""Web app, the Balance shop's summary (issue 28 screenshot review): one cylinder, a
spread that is round-off, the V8 example's parts on another engine."""

from __future__ import annotations

from pathlib import Path

import pytest

from crankbalance.schema.settings import ShopOptions, parse_options
from crankbalance.studies.shop import shop_study
from crankbalance.web.tab_shop import EXAMPLE, EXAMPLE_HEADER, parts_summary

PARTS = Path(__file__).resolve().parents[2] / "examples" / "v8_parts.csv"


@pytest.fixture(scope="module")
def options() -> ShopOptions:
    return parse_options(ShopOptions, {})


def test_the_example_is_recognised_by_its_header() -> None:
    assert EXAMPLE == PARTS and PARTS.read_text(encoding="utf-8").startswith(EXAMPLE_HEADER)


def test_one_cylinder_and_the_v8_example_on_it(options: ShopOptions) -> None:
    p = shop_study("single", PARTS, options).parts
    summary = parts_summary(p, example=True)
    assert ": 1 cylinder, matching" in summary
    assert "The example's parts are a V8's: 1 of its 8 sets used" in summary
    assert "V8's" not in parts_summary(p, example=False)  # the user's own parts


def test_the_example_on_its_own_v8_says_nothing_more(options: ShopOptions) -> None:
    p = shop_study("v8-crossplane", PARTS, options).parts
    assert "sets used" not in parts_summary(p, example=True)


def test_a_spread_of_round_off_reads_0_g(options: ShopOptions) -> None:
    """The V6's six lightest reciprocating sets are all 863.7 g: a spread of 2.22e-13 g is
    float round-off and reads 0 g."""
    p = shop_study("v6-60", PARTS, options).parts
    assert 0 < p.matching.reciprocating_spread < 1e-12
    assert "spread 0 g reciprocating" in parts_summary(p, example=True)
    assert "e-" not in parts_summary(p, example=True)
