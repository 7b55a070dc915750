"""The counterweight optimiser keeps the web circle clear of the main journal (issue 28):
the profile leaves out the web circle of radius r_cw about the crank axis, where the main
journal sits, so r_cw is searched from the journal's radius up; a given web radius below
it is refused. Checked on the designs' polygons with shapely against the journal and the
crankpin as :func:`crankbalance.studies.counterweight.crank_outline` draws them.
"""

from __future__ import annotations

from typing import Any

import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.physics.counterweight import CounterweightDesign
from crankbalance.physics.counterweight_optimize import DEFAULT_BOUNDS, clear_of_journal
from crankbalance.schema.settings import CounterweightOptimizeOptions
from crankbalance.studies.counterweight import CrankOutline, crank_outline, optimize

shapely = pytest.importorskip("shapely")
from shapely.geometry import Point, Polygon  # noqa: E402

#: chord error of the polygonised outlines [m]; the parts are shrunk by twice it, so a
#: design touching the journal (r_cw at its bound) is not counted as overlapping it
CHORD = 1e-6
RUN = {"iterations": 3, "population": 256, "seed": 7}


def _overlaps(design: CounterweightDesign, crank: CrankOutline) -> dict[str, float]:
    """The areas [m^2] by which ``design`` overlaps the journal (about the crank axis) and
    the crankpin (at -y, opposite the counterweight), as the drawing places them."""
    loops = design.outline(CHORD)
    profile = Polygon(loops[0]).buffer(0)
    for loop in loops[1:]:
        profile = profile.union(Polygon(loop).buffer(0))
    journal = Point(0.0, 0.0).buffer(crank.journal_diameter / 2 - 2 * CHORD, 1024)
    pin = Point(0.0, -crank.crank_radius).buffer(crank.pin_diameter / 2 - 2 * CHORD, 1024)
    return {
        "journal": profile.intersection(journal).area,
        "crankpin": profile.intersection(pin).area,
    }


def _designs(result: Any) -> list[CounterweightDesign]:
    res = result.optimum
    return [res.least_mass_design, res.least_radius_design] + [res.design(i) for i in result.listed]


def test_the_check_finds_an_overlap() -> None:
    """The polygon check sees a web circle smaller than the journal (the old default range,
    10..20 mm, on the paper's inline-3: journal radius 26 mm)."""
    crank = crank_outline(load_engine("paper-inline3"))
    assert crank.journal_diameter / 2 == pytest.approx(0.026)
    design = CounterweightDesign(0.015, 0.02, 0.35, 0.05, 2.1, 0.01)
    assert _overlaps(design, crank)["journal"] > 1e-5


@pytest.mark.parametrize("preset", ["paper-inline3", "inline4", "v8-crossplane", "single"])
def test_an_optimised_design_clears_the_journal(preset: str) -> None:
    """Every listed design of an optimisation for the engine clears its journal and its
    crankpin; every feasible design has r_cw at least the journal's radius."""
    engine = load_engine(preset)
    crank = crank_outline(engine)
    result = optimize(engine, CounterweightOptimizeOptions(**RUN))
    rj = crank.journal_diameter / 2
    assert result.optimum.designs[:, 0].min() >= rj
    low, _high = result.bounds["web_radius"]  # type: ignore[misc]
    assert low == pytest.approx(max(rj, DEFAULT_BOUNDS["web_radius"][0]))
    for design in _designs(result):
        areas = _overlaps(design, crank)
        assert areas == {"journal": 0.0, "crankpin": 0.0}, (design, areas)


def test_a_typed_journal_diameter_bounds_the_web_radius() -> None:
    """Without an engine, ``journal_diameter`` sets the bound (here 40 mm: r_cw >= 20 mm)."""
    settings = CounterweightOptimizeOptions(first_moment=0.00788, journal_diameter=0.04, **RUN)
    result = optimize(None, settings)
    assert result.bounds["web_radius"] == pytest.approx((0.020, 0.030))
    assert result.optimum.designs[:, 0].min() >= 0.020
    plain = optimize(None, CounterweightOptimizeOptions(first_moment=0.00788, **RUN))
    assert plain.bounds["web_radius"] == DEFAULT_BOUNDS["web_radius"]  # no limit given


def test_a_web_radius_inside_the_journal_is_refused() -> None:
    engine = load_engine("paper-inline3")
    with pytest.raises(InputError) as raised:
        optimize(engine, CounterweightOptimizeOptions(web_radius="10..30 mm", **RUN))
    assert raised.value.field == "web_radius" and raised.value.value == "10..30 mm"
    assert "main journal's radius, 26 mm" in str(raised.value)
    kept = optimize(engine, CounterweightOptimizeOptions(web_radius="27 mm", **RUN))
    assert kept.bounds["web_radius"] == pytest.approx(0.027)


def test_clear_of_journal() -> None:
    lo, hi = DEFAULT_BOUNDS["web_radius"]
    assert clear_of_journal(None, lo / 2)["web_radius"] == (lo, hi)  # a small journal
    assert clear_of_journal({}, 0.026)["web_radius"] == pytest.approx((0.026, 0.036))
    assert clear_of_journal({"thickness": 0.01}, 0.012) == {
        "thickness": 0.01,
        "web_radius": pytest.approx((0.012, 0.022)),
    }
    assert clear_of_journal({"web_radius": (0.03, 0.04)}, 0.026)["web_radius"] == (0.03, 0.04)
    for bad in (0.02, (0.02, 0.04)):
        with pytest.raises(InputError, match="overlaps the journal"):
            clear_of_journal({"web_radius": bad}, 0.026)
    with pytest.raises(InputError):
        clear_of_journal(None, 0.0)
