"""One engine, one answer (issue 28, review findings 10 and 30): the one-cylinder sweep
(``sensitivity``, the web's Performance tab) and the bearing-load studies (``bearings``,
``bearings-sweep``, the web's Crank loads) take the same bore, main journal and peak
cylinder pressure from the engine where their settings are empty, and say so."""

from __future__ import annotations

import pytest

from crankbalance.studies.engine import as_model
from crankbalance.studies.loads import assumed_text
from crankbalance.studies.performance import assumption_text, engine_estimate
from crankbalance.studies.registry import run


@pytest.mark.parametrize("engine", ["inline4", "single"])
def test_performance_and_crank_loads_assume_the_same_cylinder(engine: str) -> None:
    sweep = run("sensitivity", engine, {"balance_factors": ["0"]})
    loads = run("bearings", engine, {"balance_factor": "0"})
    a, s = sweep.to_dict()["assumed"], loads.to_dict()["settings"]
    estimate = engine_estimate(as_model(engine))
    r = as_model(engine).crank_radius
    assert estimate.bore == pytest.approx(2 * r) and estimate.journal_diameter == pytest.approx(
        1.3 * r
    )
    assert a["bore_m"] == pytest.approx(s["bore_m"]) == pytest.approx(estimate.bore)
    assert a["journal_diameter_m"] == pytest.approx(s["journal_diameter_m"])
    assert a["journal_diameter_m"] == pytest.approx(estimate.journal_diameter)
    # the same Wiebe combustion in the same cylinder: the same peak pressure (the two
    # cycles sample it at different steps)
    assert a["peak_pressure_Pa"] == pytest.approx(s["peak_pressure_Pa"], rel=2e-3)
    assert sorted(a["estimated"]) == ["bore", "journal_diameter"]
    # both say it in the same words, marked as the engine's estimate
    words = assumption_text(a["bore_m"], a["peak_pressure_Pa"], a["journal_diameter_m"], ["bore"])
    assert f"bore {estimate.bore * 1e3:.4g} mm*" in words
    assert f"bore {estimate.bore * 1e3:.4g} mm*" in sweep.assumption()
    assert f"main journal {estimate.journal_diameter * 1e3:.4g} mm*" in sweep.assumption()
    assert f"bore {estimate.bore * 1e3:.4g} mm*" in assumed_text(s)
    assert f"main journal {estimate.journal_diameter * 1e3:.4g} mm*" in assumed_text(s)
    assert f"peak pressure {a['peak_pressure_Pa'] / 1e5:.4g} bar" in assumed_text(s)


def test_single_peak_bearing_load_is_the_two_main_bearings_together() -> None:
    """The single's one crank throw between two main bearings: the one-cylinder study puts
    its whole load on one bearing, the bearing-load study shares it between the two (half
    each, the determinate crank): the same quantity, once the cylinder is the same."""
    sweep = run("sensitivity", "single", {"balance_factors": ["0"]})
    loads = run("bearings", "single", {"balance_factor": "0"}).to_dict()
    bearings = [b["max_load_N"] for b in loads["models"]["determinate"]["bearings"]]
    assert len(bearings) == 2
    assert float(sweep.result.peak_bearing_load[0, 0]) == pytest.approx(sum(bearings), rel=2e-3)


def test_typed_settings_are_not_estimates() -> None:
    sweep = run("sensitivity", "inline4", {"bore": "80 mm", "journal_diameter": "30 mm"})
    a = sweep.to_dict()["assumed"]
    assert a["bore_m"] == pytest.approx(0.08) and a["journal_diameter_m"] == pytest.approx(0.03)
    assert a["estimated"] == [] and "*" not in sweep.assumption()
    loads = run("bearings", "inline4", {"bore": "80 mm"}).to_dict()["settings"]
    assert "bore 80 mm," in assumed_text(loads)
    # without an engine: the thesis' single, nothing estimated
    alone = run("sensitivity", None, {}).to_dict()["assumed"]
    assert alone["bore_m"] == pytest.approx(0.0768) and alone["estimated"] == []


@pytest.mark.parametrize(
    "words",
    [
        ["sensitivity", "--engine", "single", "--balance-factors", "0"],
        ["cycle", "--engine", "single", "--cylinder", "1"],
    ],
)
def test_the_command_line_says_what_it_assumed(words: list[str]) -> None:
    """The text output of ``sensitivity`` and ``cycle --cylinder`` prints the line the web's
    Performance tab prints: the same words from the same values."""
    from click.testing import CliRunner

    from crankbalance.cli import cli
    from crankbalance.studies.cycle import assumption_words

    result = CliRunner().invoke(cli, words)
    assert result.exit_code == 0, result.output
    expected = assumption_words(
        run("sensitivity", "single", {"balance_factors": ["0"]}).to_dict()["assumed"]
    )
    assert f"Assumed: {expected}" in result.output.splitlines()
