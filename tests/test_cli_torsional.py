"""``crankbalance torsional`` (in-process): JSON against the physics functions, the table,
CSV, the figure, and bad input (one line naming the option, exit 2)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from crankbalance.physics import torsional as tv
from crankbalance.studies.engine import as_model

from .conftest import run_cli

DAMPER = ["--damper-inertia", "0.004 kg*m^2", "--damper-frequency", "330 Hz"]
BASE = ["torsional", "--engine", "inline6", "--speed-points", "40"]
#: the crank dimensions of the worked example of docs/torsional.md, typed (the defaults are
#: the engine's, from its crank radius and web offset: test_untyped_dimensions_...)
TYPED = [
    "--journal-diameter",
    "60 mm",
    "--pin-diameter",
    "50 mm",
    "--journal-length",
    "25 mm",
    "--pin-length",
    "25 mm",
    "--web-thickness",
    "20 mm",
    "--web-width",
    "90 mm",
]


@pytest.fixture(scope="module")
def payload() -> dict:
    from click.testing import CliRunner

    from crankbalance.cli import cli

    result = CliRunner().invoke(
        cli,
        [*BASE, *TYPED, *DAMPER, "--damper-allowed-power", "200 W", "--format", "json"],
    )
    assert result.exit_code == 0, result.output
    return json.loads(result.output)


def test_json_matches_the_physics(payload: dict) -> None:
    assert payload["schema"] == "crankbalance.torsional/1"
    model = as_model("inline6")
    k = tv.carter_stiffness(0.060, 0.050, 0.025, 0.025, 0.020, 0.090, model.crank_radius)
    inertia = [m["inertia_kg_m2"] for m in payload["masses"]]
    stiffness = [s["stiffness_Nm_rad"] for s in payload["sections"]]
    assert [m["name"] for m in payload["masses"]][:2] == ["damper ring", "front"]
    assert stiffness[0] == pytest.approx(0.004 * (2 * math.pi * 330.0) ** 2, rel=1e-9)
    np.testing.assert_allclose(stiffness[1:], k, rtol=1e-9)
    assert len(payload["crank"]["dimensions"]["typed"]) == 6  # typed: they win
    np.testing.assert_allclose(inertia[2:8], tv.throw_inertias(model), rtol=1e-9)
    modes = tv.natural_modes(inertia, stiffness)
    got = [m["frequency_rad_s"] for m in payload["modes"]]
    np.testing.assert_allclose(got, modes.frequency[1:], rtol=1e-9)
    assert payload["modes_free"] == payload["modes"]  # no load
    low, high = payload["sweep"]["speed_rad_s"][0], payload["sweep"]["speed_rad_s"][-1]
    assert low == pytest.approx(600 * math.pi / 30)
    assert high == pytest.approx(model.speed)
    for r in payload["resonances"]:
        w = payload["modes"][r["mode"] - 1]["frequency_rad_s"]
        assert r["speed_rad_s"] == pytest.approx(w / r["order"], rel=1e-9)
        assert low <= r["speed_rad_s"] <= high
    damper = payload["damper"]
    assert damper["allowed_power_W"] == 200.0
    assert damper["within_allowed"] is (damper["max_power_W"] <= 200.0)
    assert len(payload["sweep"]["damper_power_W"]) == 40


def test_load_adds_a_mode_and_keeps_the_free_free_modes(capsys) -> None:
    load = ["--load-inertia", "0.5 kg*m^2", "--load-stiffness", "2e4 N*m/rad"]
    code, out, err = run_cli([*BASE, "--format", "json", *load], capsys)
    assert code == 0, err
    with_load = json.loads(out)
    code, out, err = run_cli([*BASE, "--format", "json"], capsys)
    bare = json.loads(out)
    assert len(with_load["modes"]) == len(bare["modes"]) + 1
    assert [m["frequency_rad_s"] for m in with_load["modes_free"]] == pytest.approx(
        [m["frequency_rad_s"] for m in bare["modes"]], rel=1e-9
    )
    assert with_load["damper"] is None


def test_table_and_csv(capsys) -> None:
    code, out, err = run_cli([*BASE, *DAMPER], capsys)
    assert code == 0, err
    assert "Natural frequencies (free-free engine)" in out
    assert "Resonances in the speed range" in out
    assert "Damper: largest power" in out and "no allowed power given" in out
    code, out, err = run_cli([*BASE, "--format", "csv"], capsys)
    assert code == 0, err
    lines = out.strip().splitlines()
    assert lines[0].split(",")[:2] == ["speed_rad_s", "front_amplitude_rad"]
    assert len(lines) == 41


def test_plot_html(capsys, tmp_path: Path) -> None:
    pytest.importorskip("plotly")
    target = tmp_path / "torsional.html"
    code, _out, err = run_cli([*BASE, *DAMPER, "--plot", str(target)], capsys)
    assert code == 0, err
    text = target.read_text()
    assert "Campbell diagram" in text and "damper power" in text


@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["--throw-stiffness", "5e5 N*m"], "--throw-stiffness"),
        (["--throw-stiffness", "nan N*m/rad"], "--throw-stiffness"),
        (["--damper-inertia", "0.004 kg*m^2"], "--damper-frequency"),
        (["--speed-max", "100 rpm"], "--speed-max"),
        (["--speed-min", "9000 rpm"], "--speed-min"),
        (["--load-inertia", "1 kg*m^2"], "--load-stiffness"),
        (["--shaft-damping-ratio", "0.9"], "--shaft-damping-ratio"),
        (["--damper-allowed-power", "100 W"], "--damper-allowed-power"),
        (["--highest-order", "100"], "--highest-order"),
    ],
)
def test_bad_input_names_the_option(capsys, args: list[str], option: str) -> None:
    code, out, err = run_cli([*BASE, *args], capsys)
    assert code == 2
    assert out == ""
    assert len(err.strip().splitlines()) == 1 and option in err, err


def test_damper_power_without_a_damper_names_the_damper_options(capsys) -> None:
    code, _out, err = run_cli([*BASE, "--damper-allowed-power", "1kW"], capsys)
    assert code == 2
    assert "--damper-allowed-power" in err and "--damper-inertia" in err, err
    assert "(damper inertia)" not in err


@pytest.mark.parametrize(
    ("option", "value"),
    [
        ("--journal-diameter", "60 mm"),
        ("--pin-diameter", "50 mm"),
        ("--journal-length", "25 mm"),
        ("--pin-length", "25 mm"),
        ("--web-thickness", "20 mm"),
        ("--web-width", "90 mm"),
        ("--shear-modulus", "80 GPa"),
    ],
)
@pytest.mark.parametrize(
    "stiffnesses",
    [
        ["--throw-stiffness", "5e5 N*m/rad"],
        [
            "--throw-stiffness",
            "5e5 N*m/rad",
            "--front-stiffness",
            "5e5 N*m/rad",
            "--flywheel-stiffness",
            "5e5 N*m/rad",
        ],
    ],
)
def test_carter_dimensions_with_a_given_throw_stiffness_are_refused(
    capsys, option: str, value: str, stiffnesses: list[str]
) -> None:
    code, out, err = run_cli([*BASE, *stiffnesses, option, value], capsys)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1, err
    assert option in err and "--throw-stiffness" in err, err


def test_engine_is_required(capsys) -> None:
    code, _out, err = run_cli(["torsional"], capsys)
    assert code == 2 and "--engine" in err


def test_worked_example_of_the_docs(payload: dict, capsys) -> None:
    """docs/torsional.md, worked example: the numbers that do not depend on the sweep's grid
    (modes, the resonance mode 2 x order 6 computed at its crossing speed)."""
    hz = [m["frequency_Hz"] for m in payload["modes"]][:4]
    np.testing.assert_allclose(hz, [300.1, 490.6, 1368.0, 2367.5], atol=0.05)
    (r,) = [r for r in payload["resonances"] if r["mode"] == 2 and r["order"] == 6]
    assert r["speed_rad_s"] * 30 / math.pi == pytest.approx(4906, abs=0.5)
    assert r["relative_excitation"] == pytest.approx(3.229, abs=5e-4)
    assert math.degrees(r["crank_twist_rad"]) == pytest.approx(0.4906, abs=5e-5)
    assert r["max_section_torque_Nm"] == pytest.approx(1135.8, abs=0.05)
    assert r["damper_power_W"] == pytest.approx(359.5, abs=0.05)
    code, out, err = run_cli([*BASE, *TYPED, "--format", "json"], capsys)
    assert code == 0, err
    bare = json.loads(out)
    assert bare["modes"][0]["frequency_Hz"] == pytest.approx(442.8, abs=0.05)
    (r,) = [r for r in bare["resonances"] if r["mode"] == 1 and r["order"] == 6]
    assert r["speed_rad_s"] * 30 / math.pi == pytest.approx(4428, abs=0.5)
    assert math.degrees(r["crank_twist_rad"]) == pytest.approx(1.2817, abs=5e-4)


def test_pressure_table_gives_the_gas_torque_of_the_table(capsys, tmp_path: Path) -> None:
    """--pressure-csv (the tables of ``cycle``): a table of the default Wiebe model sampled
    every degree gives the same resonances as the model (to the table's interpolation);
    the Wiebe options are refused with a table."""
    from crankbalance.physics.engine_cycle import CylinderSpec, WiebeCombustion, wiebe_pressure

    model = as_model("inline6")
    wiebe = WiebeCombustion(13.5, math.radians(-25.0), math.radians(50.0))
    spec = CylinderSpec(
        bore=2 * model.crank_radius,
        crank_radius=model.crank_radius,
        rod_length=model.rod_length,
        reciprocating_mass=float(model.reciprocating_mass[0]),
        crank_inertia=0.1,
    )
    angle = np.arange(-360.0, 360.0, 0.25)
    table = tmp_path / "wiebe.csv"
    pressure = wiebe_pressure(np.radians(angle), spec, wiebe, 4)
    table.write_text(
        "angle_deg,pressure_bar\n"
        + "\n".join(f"{a:.6f},{p / 1e5:.9f}" for a, p in zip(angle, pressure, strict=True))
    )
    code, out, err = run_cli([*BASE, "--format", "json"], capsys)
    model_run = json.loads(out)
    code, out, err = run_cli([*BASE, "--format", "json", "--pressure-csv", str(table)], capsys)
    assert code == 0, err
    table_run = json.loads(out)
    a = [r["crank_twist_rad"] for r in model_run["resonances"]]
    b = [r["crank_twist_rad"] for r in table_run["resonances"]]
    np.testing.assert_allclose(b, a, rtol=0.02)
    code, _out, err = run_cli(
        [*BASE, "--pressure-csv", str(table), "--compression-ratio", "10"], capsys
    )
    assert code == 2 and "--compression-ratio" in err
