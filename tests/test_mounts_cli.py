"""Issue 31: ``crankbalance mounts`` (table, JSON, figure) and its bad input: the engine
file's ``[powertrain]`` table validated key by key, mounts that do not hold the body, the
bounded work."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from crankbalance.cli import main
from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.physics import mounts as pm
from crankbalance.schema.settings import MountsOptions
from crankbalance.studies.engine import analyze
from crankbalance.studies.mounts import mounts, powertrain_of

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


def test_the_table_shows_statics_modes_crossings_and_mount_forces(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code, out, err = _run(["mounts", str(CAR), "--speed-samples", "50"], capsys)
    assert code == 0, err
    for words in (
        "powertrain 165 kg on 3 mounts",
        "Rigid-body modes",
        "Torque-roll axis",
        "torque rod",
        "Largest mount force per order",
    ):
        assert words in out


def test_json_gives_six_modes_every_mount_and_order(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = _run(
        ["mounts", str(BIKE), "--orders", "2", "--speed-samples", "30", "--format", "json"],
        capsys,
    )
    assert code == 0, err
    data = json.loads(out)
    assert data["schema"] == "crankbalance.mounts/1"
    assert len(data["modes"]) == 6
    assert [o["order"] for o in data["orders"]] == [1, 2]
    assert len(data["sweep"]["speed_rpm"]) == 30
    assert set(data["sweep"]["mount_force_N"]) == {
        "front left",
        "front right",
        "rear left",
        "rear right",
    }
    for mode in data["modes"]:
        assert sum(mode["energy_percent"].values()) == pytest.approx(100.0)
    # the static loads carry the weight, along the tilted vertical
    weight = np.sum([m["force_N"] for m in data["statics"]["mount_loads"]], axis=0)
    up = np.array(data["powertrain"]["up"])
    np.testing.assert_allclose(weight, -62.0 * pm.GRAVITY * up, atol=1e-6)


def test_the_figure_is_written(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "mounts.html"
    code, _, err = _run(["mounts", str(CAR), "--speed-samples", "20", "--plot", str(out)], capsys)
    assert code == 0, err
    assert "Campbell diagram" in out.read_text()


def test_forces_of_another_balancing_replace_the_engines(tmp_path: Path) -> None:
    """The study takes the free forces of a given balancing: halving every phasor halves
    every mount force (the system is linear), so comparing balancings is a loop."""
    settings = MountsOptions.parse({"speed_samples": 20, "orders": 2})
    plain = mounts(str(BIKE), settings)
    f = analyze(str(BIKE), orders=2).forces
    half = type(f)(
        **{
            name: getattr(f, name) * (0.5 if name != "orders" else 1)
            for name in f.__dataclass_fields__
        }
    )
    halved = mounts(str(BIKE), settings, forces=half)
    np.testing.assert_allclose(halved.response.mount_peak, 0.5 * plain.response.mount_peak)
    # a powertrain given in Python replaces the file's
    table = load_engine(str(BIKE)).powertrain
    assert table is not None
    heavier = powertrain_of(table)
    heavier = pm.Powertrain(2 * heavier.mass, heavier.cg, heavier.inertia, heavier.mounts)
    other = mounts(str(BIKE), settings, powertrain=heavier)
    assert other.modes.frequencies[0] < plain.modes.frequencies[0]


def _engine_with(tmp_path: Path, old: str, new: str, source: Path = CAR) -> str:
    text = source.read_text()
    assert old in text
    path = tmp_path / "engine.toml"
    path.write_text(text.replace(old, new, 1))
    return str(path)


@pytest.mark.parametrize(
    ("old", "new", "words"),
    [
        ("loss_factor = 0.2", "loss_factr = 0.2", "powertrain.mount[2].loss_factr"),
        ("loss_factor = 0.2", "loss_factor = 3", "powertrain.mount[2].loss_factor"),
        ('mass = "165 kg"', 'mass = "165 N"', "powertrain.mass"),
        (
            'inertia = ["8.5 kg*m^2"',
            'inertia = ["18.5 kg*m^2"',
            "each moment must be at most the sum of the other two",
        ),
        (
            'products = ["0.35 kg*m^2"',
            'products = ["7 kg*m^2"',
            "powertrain.products",
        ),
        (
            'position = ["30 mm", "330 mm", "260 mm"]',
            'position = ["30 mm", "330 mm"]',
            "powertrain.mount[0].position",
        ),
    ],
)
def test_bad_powertrain_keys_are_named_as_written(
    old: str, new: str, words: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code, out, err = _run(["mounts", _engine_with(tmp_path, old, new)], capsys)
    assert code == 2 and not out
    assert err.startswith("error: ") and words in err and err.count("\n") == 1
    if "factr" in words:
        assert "did you mean 'loss_factor'" in err


def test_mounts_that_do_not_hold_the_body_are_one_line_naming_them(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = CAR.read_text()
    for shear in ('"110 N/mm", "110 N/mm"', '"90 N/mm", "90 N/mm"', '"25 N/mm", "25 N/mm"'):
        text = text.replace(shear, '"0 N/mm", "0 N/mm"')
    text = text.replace('orientation = ["0 deg", "90 deg", "0 deg"]', "")
    path = tmp_path / "engine.toml"
    path.write_text(text)
    code, out, err = _run(["mounts", str(path)], capsys)
    assert code == 2 and not out
    assert "engine side, gearbox side, torque rod" in err and "six directions" in err
    assert err.count("\n") == 1


def test_an_engine_without_a_powertrain_says_what_it_needs(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code, _, err = _run(["mounts", "inline4"], capsys)
    assert code == 2 and "[powertrain]" in err and "docs/mounts.md" in err


def test_the_work_is_bounded_before_it_starts(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = _run(["mounts", str(CAR), "--speed-samples", "10001", "--orders", "5"], capsys)
    assert code == 2 and "--speed-samples" in err and str(pm.MAX_RESPONSE_POINTS) in err
    with pytest.raises(InputError):
        mounts(str(CAR), MountsOptions.parse({"speed_samples": 10001, "orders": 5}))


def test_a_speed_range_below_the_lowest_speed_is_refused(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code, _, err = _run(
        ["mounts", str(CAR), "--speed-min", "3000 rpm", "--speed-max", "2000 rpm"], capsys
    )
    assert code == 2 and "--speed-max" in err


def test_balanced_forces_are_the_balance_studys_residuals() -> None:
    """The phasors a balancing leaves, as the mount study takes them, have the amplitudes
    of the balance study's residuals (one solver, one answer)."""
    from crankbalance.physics.balance_types import CounterweightOptions
    from crankbalance.studies.engine import balance_engine
    from crankbalance.studies.mounts import balanced_forces

    spec = load_engine(str(BIKE))
    model = analyze(spec, orders=2).model
    options = CounterweightOptions(cg_radius=0.033, angle="optimal", balance_factor=0.5)
    left = balanced_forces(model, options, orders=2)
    study = balance_engine(spec, orders=2, angle="optimal", balance_factor=0.5)
    order1 = study.result.residual("order1")
    assert abs(left.force_forward[0]) == pytest.approx(order1.force_forward_after, abs=1e-6)
    assert abs(left.force_backward[0]) == pytest.approx(order1.force_backward_after, abs=1e-6)
    assert abs(left.couple_forward[0]) == pytest.approx(order1.moment_forward_after, abs=1e-6)
    assert abs(left.rotating_force) < 1e-6 * abs(analyze(spec, orders=2).forces.rotating_force)
    # a 90 deg V-twin's forward primary is its whole primary: half the reciprocating mass
    # on the counterweights cancels it
    assert abs(left.force_forward[0]) < 1e-9 * abs(analyze(spec).forces.force_forward[0])
    np.testing.assert_allclose(left.roll, analyze(spec, orders=2).forces.roll)


def test_comparing_balance_factors_at_the_mounts_is_a_loop() -> None:
    from crankbalance.physics.balance_types import CounterweightOptions
    from crankbalance.studies.mounts import MAX_CHOICES, Choice, compare, comparison_table

    settings = MountsOptions.parse({"orders": 2, "speed_samples": 60})
    choices = [Choice("bare crank", None)] + [
        Choice(f"bf {bf}", CounterweightOptions(0.033, angle="optimal", balance_factor=bf))
        for bf in (0.0, 0.5)
    ]
    rows = comparison_table(compare(str(BIKE), settings, choices))
    assert [r["choice"] for r in rows] == ["bare crank", "bf 0.0", "bf 0.5"]
    # the rotating masses left free add to the first order; half the reciprocating mass on
    # the counterweights removes the V-twin's primary force and leaves its rocking couple
    assert rows[0]["order_1_N"] > rows[1]["order_1_N"] > 10 * rows[2]["order_1_N"]
    # counterweights act at crank speed only: the second order is the same for all
    assert rows[0]["order_2_N"] == pytest.approx(rows[2]["order_2_N"])
    # balance factor 0 is the study's default (rotating masses carried by counterweights)
    plain = mounts(str(BIKE), settings)
    assert rows[1]["largest_N"] == pytest.approx(float(plain.response.mount_peak.max()))
    with pytest.raises(InputError):
        compare(str(BIKE), settings, [Choice("x", None)] * (MAX_CHOICES + 1))


def test_the_energy_table_shows_no_negative_zero(capsys: pytest.CaptureFixture[str]) -> None:
    """The V-twin's products of inertia give two rotations a share of about -0.01 %."""
    code, out, err = _run(["mounts", str(BIKE), "--orders", "2", "--speed-samples", "20"], capsys)
    assert code == 0, err
    assert "-0.0 " not in out and " 0.0 " in out
