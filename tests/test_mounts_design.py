"""Issue 31 item 5 for the user: the comparison of balancing choices from the settings
(``--compare-pattern``, ``--compare-balance-factors``, ``--compare-shafts``) and the mount
optimiser (``--optimize``), checked against the Python loop of :func:`compare` and against a
brute-force grid."""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path

import numpy as np
import pytest

from crankbalance.cli import main
from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine, parse_engine_text
from crankbalance.physics import mounts as pm
from crankbalance.physics import mounts_optimize as po
from crankbalance.physics.balance_types import CounterweightOptions
from crankbalance.schema.engine import EngineSpec
from crankbalance.schema.settings import MountsOptions
from crankbalance.studies.mounts import Choice, compare, comparison_table, mounts

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "examples" / "mounts_inline4_car.toml"
BIKE = ROOT / "examples" / "mounts_vtwin_motorcycle.toml"


def _run(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    try:
        code = int(main(args) or 0)
    except SystemExit as stop:
        code = int(stop.code or 0)
    out, err = capsys.readouterr()
    return code, out, err


# ------------------------------------------------------------------------------- comparison
def test_compare_settings_give_the_table_of_the_python_loop(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code, out, err = _run(
        [
            "mounts",
            str(BIKE),
            "--orders",
            "2",
            "--speed-samples",
            "60",
            "--compare-pattern",
            "file",
            "--compare-pattern",
            "none",
            "--compare-balance-factors",
            "0,0.5",
            "--format",
            "json",
        ],
        capsys,
    )
    assert code == 0, err
    rows = json.loads(out)["comparison"]
    assert [r["choice"] for r in rows] == ["file bf 0", "file bf 0.5", "no counterweights"]
    # the same choices written by hand: the bike's file has no [counterweights], so its
    # counterweights are the default ones (every web, crank radius, optimal angle)
    settings = MountsOptions.parse({"orders": 2, "speed_samples": 60})
    radius = load_engine(BIKE).crank_train.crank_radius
    by_hand = comparison_table(
        compare(
            BIKE,
            settings,
            [
                Choice("a", CounterweightOptions(radius, angle="optimal", balance_factor=0.0)),
                Choice("b", CounterweightOptions(radius, angle="optimal", balance_factor=0.5)),
                Choice("c", None),
            ],
        )
    )
    for row, hand in zip(rows, by_hand, strict=True):
        assert row["order_1_N"] == pytest.approx(hand["order_1_N"], rel=1e-9)
        assert row["order_2_N"] == pytest.approx(hand["order_2_N"], rel=1e-9)
    # a 90 degree V-twin's primary is a force of constant size turning with the crank: half
    # the reciprocating mass on the counterweights cancels it (docs/theory.md)
    assert rows[1]["order_1_N"] < 0.1 * rows[0]["order_1_N"]
    assert rows[2]["order_1_N"] > rows[0]["order_1_N"]


def test_compare_shafts_adds_the_files_shafts_and_needs_them(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code, _, err = _run(["mounts", str(BIKE), "--compare-shafts", "--speed-samples", "20"], capsys)
    assert code == 2
    assert "error: --compare-shafts" in err
    assert "[balance_shafts]" in err
    text = CAR.read_text() + (
        '\n[balance_shafts.secondary]\ncg_radius = "30 mm"\nlength = "200 mm"\n'
        'arrangement = "pair"\n'
    )
    result = mounts(
        _engine_from(text),
        MountsOptions.parse({"speed_samples": 30, "compare_shafts": True}),
    )
    labels = [label for label, _ in result.comparison]
    assert len(labels) == 2 and labels[1].endswith("shafts")
    without, with_shafts = (r for _, r in result.comparison)
    # the secondary shafts cancel the second-order force: less reaches the mounts
    assert with_shafts.response.mount_peak[:, 1].max() < without.response.mount_peak[:, 1].max()


def _engine_from(text: str) -> EngineSpec:
    return parse_engine_text(text, str(CAR))


def test_too_many_balancing_choices_are_refused_before_work(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code, _, err = _run(
        [
            "mounts",
            str(BIKE),
            "--compare-pattern",
            "all",
            "--compare-pattern",
            "file",
            "--compare-balance-factors",
            "0:1:0.05",
        ],
        capsys,
    )
    assert code == 2
    assert "at most 32 balancing choices: here 42" in err


# ------------------------------------------------------------------------------- optimiser
def _car_case(samples: int = 12) -> tuple[pm.Powertrain, np.ndarray, np.ndarray, float, np.ndarray]:
    r = mounts(CAR, MountsOptions.parse({"speed_samples": 20}))
    speeds = np.linspace(r.response.speeds[0], r.response.speeds[-1], samples)
    return r.powertrain, r.loads, r.response.orders, r.model.speed, speeds


def test_the_optimiser_beats_a_brute_force_grid_and_meets_its_goals() -> None:
    pt, loads, orders, speed, speeds = _car_case()
    goals = po.MountGoals(("stiffness",), band=(5.0, 14.0), iterations=20)
    found = po.optimize_mounts(pt, goals, loads, orders, speed, speeds)
    grid = np.linspace(math.log(0.5), math.log(2.0), 9)
    best = math.inf
    for x in itertools.product(grid, repeat=3):
        trial = po.with_variables(pt, goals, x)
        if min(po.goal_margins(trial, goals).values()) < 0:
            continue
        best = min(
            best, po.rms_mount_force(pm.forced_response(trial, loads, orders, speed, speeds))
        )
    assert math.isfinite(best)
    assert found.feasible
    assert found.objective_after <= best * (1 + 1e-6)
    assert found.objective_after < found.objective_before
    f = pm.modes(found.powertrain).frequencies
    assert f[0] >= 5.0 - 1e-6 and f[-1] <= 14.0 + 1e-6
    factors = np.exp(found.variables)
    assert np.all(factors >= 0.5 - 1e-9) and np.all(factors <= 2.0 + 1e-9)


def test_the_optimiser_keeps_positions_in_bounds_and_meets_the_roll_goals() -> None:
    pt, loads, orders, speed, speeds = _car_case(8)
    goals = po.MountGoals(
        ("position",),
        position_range=0.03,
        roll_energy=75.0,
        roll_axis_angle=math.radians(15.0),
        objective="change",
        iterations=15,
    )
    assert min(po.goal_margins(pt, goals).values()) < 0  # not met as given
    found = po.optimize_mounts(pt, goals, loads, orders, speed, speeds)
    assert found.feasible
    moved = np.array(
        [m.position - g.position for m, g in zip(found.powertrain.mounts, pt.mounts, strict=True)]
    )
    assert np.all(np.abs(moved) <= 0.03 + 1e-12)
    md = pm.modes(found.powertrain)
    assert md.energy[md.roll_mode, 3] >= 75.0 - 1e-4
    assert md.roll_axis_angle <= math.radians(15.0) + 1e-6


def test_goals_already_met_need_no_change() -> None:
    pt, loads, orders, speed, speeds = _car_case(8)
    goals = po.MountGoals(("stiffness",), band=(1.0, 30.0), objective="change", iterations=5)
    found = po.optimize_mounts(pt, goals, loads, orders, speed, speeds)
    assert found.objective_after == pytest.approx(0.0, abs=1e-12)
    assert np.allclose(found.variables, 0.0)


def test_the_optimiser_from_the_command_line_shows_progress_and_its_answer(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code, out, err = _run(
        [
            "mounts",
            str(CAR),
            "--speed-samples",
            "20",
            "--optimize",
            "stiffness",
            "--frequency-band",
            "5 Hz, 14 Hz",
            "--optimize-iterations",
            "3",
            "--format",
            "json",
        ],
        capsys,
    )
    assert code == 0, err
    assert "mount optimiser: generation 3/3" in err
    opt = json.loads(out)["optimum"]
    assert opt["variables"] == ["stiffness"]
    assert opt["generations"] == 3
    assert len(opt["mounts"]) == 3 and len(opt["frequencies_Hz"]) == 6
    assert opt["objective_after"] <= opt["objective_before"] or not opt["feasible"]


def test_the_optimisers_work_is_bounded_before_it_starts(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code, _, err = _run(
        ["mounts", str(CAR), "--optimize", "position", "--optimize-iterations", "500"], capsys
    )
    assert code == 2
    assert "error: --optimize-iterations = '500'" in err
    assert f"at most {po.MAX_OPTIMIZER_EVALUATIONS}" in err
    with pytest.raises(InputError, match="optimize"):
        pt, loads, orders, speed, speeds = _car_case(4)
        po.optimize_mounts(pt, po.MountGoals(()), loads, orders, speed, speeds)


def test_each_variable_and_choice_is_given_once(capsys: pytest.CaptureFixture[str]) -> None:
    for args in (
        ["--optimize", "stiffness, stiffness"],
        ["--compare-balance-factors", "0.5,0.5"],
        ["--compare-pattern", "all", "--compare-pattern", "all"],
    ):
        code, _, err = _run(["mounts", str(CAR), *args], capsys)
        assert code == 2 and "must give each value once" in err, args
