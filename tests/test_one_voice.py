"""Output in one voice (issue 29): round-off shown as 0 in text, CSV and JSON alike, no
all-zero column without a reason, ``cycle``'s table in words with units, the firing
intervals printed by ``analyze``."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from crankbalance.io.engine_file import preset_text
from crankbalance.results import angle

from .conftest import run_cli

#: a number that is float noise: 6.9e-14, 2.98e-15
NOISE = re.compile(r"\de-1\d")


def test_an_angle_of_round_off_is_zero() -> None:
    assert angle(2.98e-15) == 0.0
    assert angle(360.0 - 1e-12) == 0.0
    assert angle(1e-6) == 1e-6


@pytest.mark.parametrize("preset", ["boxer6", "w8"])
def test_a_balance_prints_no_round_off_angle(
    capsys: pytest.CaptureFixture[str], preset: str
) -> None:
    """boxer6 and w8 printed ``alpha = 2.98e-15°`` and its JSON held it."""
    for fmt in ("table", "json"):
        code, out, err = run_cli(["balance", preset, "--format", fmt], capsys)
        assert code == 0, err
        assert not NOISE.search(out), out


def test_the_curves_csv_has_no_round_off(capsys: pytest.CaptureFixture[str]) -> None:
    """The inline four's CSV curves held ``-0`` and ``6.9e-14`` where the text prints 0."""
    code, out, err = run_cli(["analyze", "inline4", "--format", "csv"], capsys)
    assert code == 0, err
    cells = [cell for line in out.splitlines()[1:] for cell in line.split(",")]
    assert "-0" not in cells
    assert not NOISE.search(out)
    header = out.splitlines()[0].split(",")
    first_order_force = [line.split(",")[header.index("fz_1_N")] for line in out.splitlines()[1:]]
    assert set(first_order_force) == {"0"}
    second = [float(line.split(",")[header.index("fz_2_N")]) for line in out.splitlines()[1:]]
    assert max(second) > 1e4


def test_analyze_prints_the_firing_intervals(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _err = run_cli(["analyze", "inline4"], capsys)
    assert code == 0
    assert "Firing intervals 180-180-180-180° (crank angle from each cylinder" in out
    code, out, _err = run_cli(["analyze", "v2-90"], capsys)
    assert "Firing intervals 450-270°" in out
    assert "no firing order given: the most even this crank allows, order 1-2" in out


def test_a_crossplane_four_with_published_pin_angles_shows_its_intervals(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A crossplane four entered with its pin angles and the flat four's firing order
    fires unevenly: analyze says so instead of staying silent."""
    text = preset_text("inline4").replace(
        "[crank_train]",
        '[crank_train]\nthrow_angles = ["0 deg", "90 deg", "270 deg", "180 deg"]',
        1,
    )
    path = tmp_path / "crossplane4.toml"
    path.write_text(text)
    code, out, err = run_cli(["analyze", str(path)], capsys)
    assert code == 0, err
    intervals = re.search(r"Firing intervals ([\d-]+)°", out)
    assert intervals is not None, out
    steps = [int(s) for s in intervals.group(1).split("-")]
    assert sum(steps) == 720 and len(set(steps)) > 1, steps


def test_cycle_speaks_in_words_with_units(capsys: pytest.CaptureFixture[str]) -> None:
    args = ["cycle", "--engine", "inline4", "--speed", "3000 rpm"]
    code, out, err = run_cli([*args, "--speed-fluctuation-target", "1%"], capsys)
    assert code == 0, err
    assert "(intervals 180-180-180-180°)" in out
    assert "_Nm" not in out and "_rad_s" not in out and "speed_fluctuation" not in out
    rows = dict(re.findall(r"^(\w[\w ]*?)  +(\S.*)$", out, re.M))
    assert re.fullmatch(r"[\d.]+ N·m", rows["mean torque"]), rows
    assert re.fullmatch(r"[\d.]+ %", rows["speed fluctuation"]), rows
    assert rows["speed fluctuation target"] == "1 %"
    assert re.fullmatch(r"[\d.]+ kg·m²", rows["required flywheel inertia"]), rows
    assert "kg·m²" in out and "ignition -25°" in out


def test_torsional_has_no_damper_column_without_a_damper(
    capsys: pytest.CaptureFixture[str],
) -> None:
    base = ["torsional", "--engine", "inline4", "--speed-points", "20"]
    code, out, err = run_cli(base, capsys)
    assert code == 0, err
    assert "damper [W]" not in out and "No damper" in out
    assert "torque [N·m]" in out and "twist [°]" in out
    damped = [*base, "--damper-inertia", "0.01 kg·m²", "--damper-frequency", "300 Hz"]
    code, out, err = run_cli(damped, capsys)
    assert code == 0, err
    assert "damper [W]" in out


def test_json_of_an_analysis_holds_no_float_noise(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _err = run_cli(["analyze", "inline4", "--format", "json"], capsys)
    assert code == 0
    assert not NOISE.search(out)
    assert json.loads(out)["free_forces"][0]["amplitude_N"] == 0


def test_tolerance_and_balance_factor_print_the_output_units(
    capsys: pytest.CaptureFixture[str],
) -> None:
    args = ["tolerance", "--grade", "G6.3", "--rotor-mass", "12 kg", "--speed", "6000 RPM"]
    code, out, err = run_cli(args, capsys)
    assert code == 0, err
    assert "120.3 g·mm" in out and "10.03 µm" in out
    assert "g*mm" not in out and " um" not in out
