"""Numerical warnings and bounded work of the engine-cycle and torsional studies (issue 25).

Every example of the issue is a test: a pressure table with 1e300 bar (``bearings``,
``torsional``, ``cycle --engine``: numpy warnings, then ``--speed`` or the crank inertia
blamed), a 1e-12 kg m^2 flywheel (inside the range of an inertia: ``damping = inf``) and a
torsional sweep that ran for tens of seconds or ended in ``MemoryError``. Then every
numeric option of ``cycle`` (one cylinder and the whole engine), ``sensitivity``,
``bearings``, ``bearings-sweep`` and ``torsional`` at both ends of its range, and extreme
pressure tables, with every warning an error (``python -W error``): each run ends in exit
0 with finite output, or in exit 2 with one line naming the option tried. The one refusal
that may name another option is the physics' own answer for a crank that would nearly
stop: it names the inertia that carries the cycle (``--crank-inertia``,
``--flywheel-inertia``) and says the energy the cycle's torque gives and takes.
"""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.pressure_csv import read_pressure_csv
from crankbalance.physics import main_bearings, torsional
from crankbalance.schema import settings as opt
from crankbalance.studies.performance import arithmetic_checked
from crankbalance.units import format_quantity

from .conftest import ROOT, hang_guard, run_cli

#: NaN or an infinity as a table or JSON prints it
NON_FINITE = re.compile(r"(?<![A-Za-z])(nan|inf|infinity)(?![A-Za-z])", re.IGNORECASE)
#: the physics' refusal of a crank that would nearly stop (engine_cycle._speed_from_energy)
STOPS = "is too small for this cycle"
INERTIAS = ("--crank-inertia", "--flywheel-inertia")


def run(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    """The CLI in-process with every warning an error (a numpy RuntimeWarning raises)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return run_cli(args, capsys)


def refused(args: list[str], needle: str, capsys: pytest.CaptureFixture[str]) -> str:
    """Exit 2, one line on stderr that names ``needle``, nothing on stdout."""
    code, out, err = run(args, capsys)
    lines = err.splitlines()
    assert code == 2, (code, out, err)
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    assert needle in lines[0], lines[0]
    assert out == ""
    return lines[0]


def table(tmp_path: Path, rows: list[tuple[float, float]], name: str = "p.csv") -> str:
    """A pressure table (angle [deg], pressure [bar]) written to ``tmp_path``."""
    path = tmp_path / name
    path.write_text("angle_deg,pressure_bar\n" + "".join(f"{a!r},{p!r}\n" for a, p in rows))
    return str(path)


def engine_file(tmp_path: Path, cylinders: int) -> str:
    """An inline engine of ``cylinders`` (the inline-8 preset's parts, no firing order)."""
    text = (ROOT / "src" / "crankbalance" / "presets" / "inline8.toml").read_text()
    text = text.replace("cylinders = 8", f"cylinders = {cylinders}")
    text = "\n".join(line for line in text.splitlines() if "firing_order" not in line)
    path = tmp_path / f"inline{cylinders}.toml"
    path.write_text(text)
    return str(path)


# ------------------------------------------------------------------------------------------
# the pressure table of 1e300 bar, and the table's other values
# ------------------------------------------------------------------------------------------

HUGE = [(0.0, 1e300), (90.0, 10.0), (180.0, 1.0), (360.0, 1.0), (540.0, 1.0)]
PRESSURE_COMMANDS = {
    "bearings": ["bearings", "inline4"],
    "torsional": ["torsional", "--engine", "inline4", "--speed-points", "10"],
    "cycle --engine": ["cycle", "--engine", "inline4"],
    "cycle": ["cycle"],
    "sensitivity": ["sensitivity", "--balance-factors", "0,1"],
    "bearings-sweep": ["bearings-sweep", "inline4", "--balance-factors", "0.5"],
}


@pytest.mark.parametrize("command", list(PRESSURE_COMMANDS))
def test_a_table_of_1e300_bar_names_its_row_and_column(
    command: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = table(tmp_path, HUGE)
    line = refused([*PRESSURE_COMMANDS[command], "--pressure-csv", path], path, capsys)
    assert "line 2, pressure_bar = '1e+300'" in line and "0 to 1000 bar" in line
    assert "--speed" not in line and "inertia" not in line


def test_no_warning_reaches_stderr_of_a_fresh_interpreter(tmp_path: Path) -> None:
    """The issue's command as a user runs it, under ``python -W error``."""
    path = table(tmp_path, HUGE)
    done = subprocess.run(
        [sys.executable, "-W", "error", "-m", "crankbalance", "cycle", "--engine", "inline4"]
        + ["--pressure-csv", path],
        capture_output=True,
        text=True,
        timeout=300,  # a hang guard only
    )
    assert done.returncode == 2, done.stderr
    assert done.stderr.count("\n") == 1 and "Warning" not in done.stderr
    assert f"pressure_csv {path}, line 2, pressure_bar" in done.stderr


@pytest.mark.parametrize(
    "rows, needle",
    [
        ([(0.0, 1.0), (90.0, -0.2), (180.0, 1.0), (360.0, 1.0)], "line 3, pressure_bar"),
        ([(0.0, 1.0), (90.0, 1000.5), (180.0, 1.0), (360.0, 1.0)], "line 3, pressure_bar"),
        ([(-721.0, 1.0), (90.0, 1.0), (180.0, 1.0), (360.0, 1.0)], "line 2, angle_deg"),
        ([(0.0, 1.0), (90.0, 1.0), (80.0, 1.0), (360.0, 1.0)], "line 4, angle_deg"),
        ([(0.0, 1.0), (90.0, 1.0), (90.0, 1.0), (360.0, 1.0)], "line 4, angle_deg"),
    ],
)
def test_table_values_out_of_range_name_the_line_and_column(
    rows: list[tuple[float, float]], needle: str, tmp_path: Path
) -> None:
    path = table(tmp_path, rows)
    with pytest.raises(InputError) as error:
        read_pressure_csv(path)
    assert error.value.field.endswith(needle) and path in error.value.field


def test_a_vacuum_and_the_range_ends_are_read(tmp_path: Path) -> None:
    rows = [(-720.0, 0.0), (-300.0, 0.005), (0.0, 1000.0), (719.0, 1.0)]
    angle, pressure = read_pressure_csv(table(tmp_path, rows))
    assert np.degrees(angle).tolist() == pytest.approx([-720.0, -300.0, 0.0, 719.0])
    assert pressure.tolist() == [0.0, 500.0, 1e8, 1e5]


def test_a_table_longer_than_the_cycle_names_its_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Less than one cycle is the model's check (it depends on the strokes): it names the
    file too, for every command that reads tables."""
    path = table(tmp_path, [(0.0, 1.0), (90.0, 10.0), (180.0, 1.0), (400.0, 1.0)])
    for args in (
        ["cycle", "--strokes", "2"],
        ["cycle", "--engine", "inline2-2stroke"],
        ["torsional", "--engine", "inline2-2stroke", "--speed-points", "10"],
        ["bearings", "inline2-2stroke"],
    ):
        line = refused([*args, "--pressure-csv", path], f"pressure_csv {path}, angle_deg", capsys)
        assert "less than one cycle (360 deg)" in line


# ------------------------------------------------------------------------------------------
# the flywheel of 1e-12 kg m^2
# ------------------------------------------------------------------------------------------


def test_a_flywheel_of_1e_12_kg_m2_computes(capsys: pytest.CaptureFixture[str]) -> None:
    """Inside the range of an inertia: finite, and the chain without a flywheel, plus the
    flywheel's own mode on its shaft."""
    code, out, err = run(
        ["torsional", "--engine", "inline4", "--flywheel-inertia", "1e-12 kg*m^2"]
        + ["--speed-points", "20", "--format", "json"],
        capsys,
    )
    assert code == 0 and err == "", err
    assert not NON_FINITE.search(out)
    data = json.loads(out)
    inertia = [m["inertia_kg_m2"] for m in data["masses"]]
    stiffness = [s["stiffness_Nm_rad"] for s in data["sections"]]
    assert inertia[-1] == 1e-12
    assert all(math.isfinite(s["damping_Nms_rad"]) for s in data["sections"])
    without = torsional.natural_modes(inertia[:-1], stiffness[:-1]).frequency[1:]
    got = [m["frequency_rad_s"] for m in data["modes"]]
    np.testing.assert_allclose(got[:-1], without, rtol=1e-9)
    assert got[-1] == pytest.approx(math.sqrt(stiffness[-1] / 1e-12), rel=1e-3)


@pytest.mark.parametrize("end", [1e-12, 1e-9, 1e-6])
def test_light_end_masses_keep_the_elastic_modes(end: float) -> None:
    """The rigid mode is set by count: a light mass on a stiff shaft (largest eigenvalue
    1e18) left the rounding of the rigid mode near 1e3 and the old threshold, 1e-10 of
    that scale, zeroed the first elastic mode."""
    inertia = [0.01, 0.0028, 0.0028, 0.0028, 0.0028, end]
    stiffness = [7.4e5] * 5
    modes = torsional.natural_modes(inertia, stiffness)
    without = torsional.natural_modes(inertia[:-1], stiffness[:-1])
    assert modes.frequency[0] == 0.0
    # the light mass shifts them by about its share of the inertia, nothing more
    shift = max(1e-9, end / 0.0028)
    np.testing.assert_allclose(modes.frequency[1:-1], without.frequency[1:], rtol=shift)
    train = torsional.crank_train(
        inertia[1:-1], 7.4e5, 0.01, 7.4e5, end, 7.4e5, shaft_damping_ratio=0.02
    )
    assert np.all(np.isfinite(train.damping)) and train.damping.max() > 0


def test_a_loose_section_leaves_two_rigid_modes() -> None:
    modes = torsional.natural_modes([1.0, 2.0, 3.0], [0.0, 1e5])
    assert modes.frequency[:2].tolist() == [0.0, 0.0]
    assert modes.frequency[2] == pytest.approx(math.sqrt(1e5 * (1 / 2 + 1 / 3)), rel=1e-12)


# ------------------------------------------------------------------------------------------
# the bounded torsional sweep
# ------------------------------------------------------------------------------------------


def test_a_huge_sweep_is_refused_before_any_work(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """64 cylinders up to order 64: 4143 resonances in the speed range besides the 400
    speeds, 38 million amplitudes (3.6 GB and a minute before); refused before the cycle."""
    engine = engine_file(tmp_path, 64)

    def no_cycle(*args: Any, **kwargs: Any) -> None:
        raise AssertionError("the cycle ran before the size was checked")

    monkeypatch.setattr("crankbalance.physics.engine_cycle_all.engine_cycle_all", no_cycle)
    with hang_guard(300):
        line = refused(
            ["torsional", "--engine", engine, "--highest-order", "64"], "--highest-order", capsys
        )
    assert "= 38379264 amplitudes, more than the 4000000 allowed" in line
    assert "--speed-points" in line and "--speed-min" in line
    with hang_guard(300):
        line = refused(
            ["torsional", "--engine", engine, "--speed-points", "2001", "--highest-order", "24"],
            "--speed-points = '2001'",
            capsys,
        )


def test_the_cap_counts_what_the_study_computes(monkeypatch: pytest.MonkeyPatch) -> None:
    """response_size is the size of the arrays the study fills: at the cap it computes, one
    amplitude over it the physics refuses before the forced response."""
    from crankbalance.schema.settings import TorsionalOptions
    from crankbalance.studies.torsional import torsional as run_study

    result = run_study("inline6", TorsionalOptions.parse({"speed_points": 30}))
    study, speeds = result.study, result.speeds
    crossings = len(study.resonances)
    amplitudes = study.response.amplitude.size + crossings * study.response.amplitude[0].size
    assert torsional.response_size(study.train, study.excitation.orders, speeds) == (
        crossings,
        amplitudes,
    )
    monkeypatch.setattr(torsional, "MAX_RESPONSE_SIZE", amplitudes)
    torsional.torsional_study(study.train, study.excitation, speeds)  # at the cap
    monkeypatch.setattr(torsional, "MAX_RESPONSE_SIZE", amplitudes - 1)

    def no_response(*args: Any) -> None:
        raise AssertionError("the forced response ran before the size was checked")

    monkeypatch.setattr(torsional, "forced_response", no_response)
    with pytest.raises(InputError, match="must make at most") as error:
        torsional.torsional_study(study.train, study.excitation, speeds)
    assert error.value.field == "speed"


def test_the_peak_by_fft_is_the_sampled_peak() -> None:
    """synthesised_peak (inverse real FFT) against the sum of the harmonics evaluated at
    the same samples, for the orders of a four-stroke and a two-stroke."""
    rng = np.random.default_rng(1)
    for orders in (0.5 * np.arange(1, 25), np.arange(1.0, 9.0)):
        x = rng.normal(size=(3, orders.size, 4)) + 1j * rng.normal(size=(3, orders.size, 4))
        samples = int(math.ceil(16 * orders.max() / orders.min()))
        theta = np.linspace(0.0, 2 * math.pi / orders.min(), samples, endpoint=False)
        signal = np.real(np.einsum("pnk,ns->pks", x, np.exp(1j * np.outer(orders, theta))))
        np.testing.assert_allclose(
            torsional.synthesised_peak(x, orders), np.abs(signal).max(axis=-1), rtol=1e-12
        )
    with pytest.raises(InputError, match="whole multiples"):
        torsional.synthesised_peak(np.ones((1, 2)), [1.0, 1.5])


# ------------------------------------------------------------------------------------------
# bounded bearing loads
# ------------------------------------------------------------------------------------------


def test_the_contact_model_is_refused_over_its_size(capsys: pytest.CaptureFixture[str]) -> None:
    """Nine bearings at 3600 samples per revolution: 2.3 million Hessian entries (more than
    a minute before); the line says the samples allowed."""
    line = refused(
        ["bearings", "inline8", "--samples", "3600"]
        + ["--bearing-stiffness", "5e8 N/m", "--clearance", "30 um"],
        "--samples = '3600'",
        capsys,
    )
    assert "at most 3086 with the clearance contact model of 9 bearings" in line


def test_the_contact_cap_at_its_edge(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """inline-4: five bearings, 72 samples of a cycle at 36 per revolution, 7200 entries."""
    monkeypatch.setattr(main_bearings, "MAX_CONTACT_SIZE", 7200)
    monkeypatch.setattr("crankbalance.studies.loads.MAX_CONTACT_SIZE", 7200)
    contact = ["--bearing-stiffness", "5e8 N/m", "--clearance", "30 um", "--format", "json"]
    code, out, err = run(["bearings", "inline4", "--samples", "36", *contact], capsys)
    assert code == 0, err
    refused(["bearings", "inline4", "--samples", "37", *contact], "--samples = '37'", capsys)
    monkeypatch.setattr("crankbalance.studies.loads.MAX_CONTACT_SIZE", 10**9)
    with pytest.raises(InputError, match="entries of the contact model"):
        main_bearings.clearance_reactions(
            [0.0, 1.0],
            [0.5],
            np.ones((1, 2000)),
            main_bearings.uniform_stiffness(0, 1, 1e5),
            1e8,
            1e-5,
        )


def test_bending_moments_in_blocks_are_the_moments(monkeypatch: pytest.MonkeyPatch) -> None:
    from crankbalance.physics.beam import bending_moment_at

    rng = np.random.default_rng(2)
    x, positions = np.sort(rng.random(7)), rng.random(11)
    loads = rng.normal(size=(50, 11)) + 1j * rng.normal(size=(50, 11))
    whole = bending_moment_at(x, positions, loads).T
    monkeypatch.setattr(main_bearings, "MOMENT_BLOCK", 7 * 11 * 3)  # blocks of 3 samples
    assert np.array_equal(main_bearings._moments(x, positions, loads), whole)


# ------------------------------------------------------------------------------------------
# the names of what the physics refuses
# ------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "args, needle",
    [
        (["cycle", "--stroke", "100000 mm"], "--stroke = '100000 mm': is too long for the rod"),
        (["cycle", "--engine", "inline4", "--stroke", "100000 mm"], "--stroke = '100000 mm'"),
        (["sensitivity", "--rod-length", "0.001 mm"], "--rod-length = '0.001 mm'"),
        (["cycle", "--engine", "inline4", "--strokes", "2"], "--strokes = '2': does not suit"),
        (["cycle", "--ignition", "720 deg"], "--ignition = '720 deg'"),
        (["torsional", "--engine", "inline4", "--burn-duration", "720 deg"], "--burn-duration"),
        (["cycle", "--speed-fluctuation-target", "0.5"], "from 1e-06 to 0.2"),
        (["cycle", "--speed", "1 rpm"], '--crank-inertia = "0.006 kg*m^2 of crank and flyw'),
        (["bearings", "inline4", "--speed", "1 rpm"], "(the engine's)\": is too small for"),
        (
            ["torsional", "--engine", "inline4", "--intake-pressure", "1000 bar"],
            "--flywheel-inertia = '0.15 kg*m^2': makes front end + throws + flywheel",
        ),
    ],
)
def test_physics_refusals_name_the_option_typed(
    args: list[str], needle: str, capsys: pytest.CaptureFixture[str]
) -> None:
    refused(args, needle, capsys)


def test_the_top_fluctuation_target_computes(capsys: pytest.CaptureFixture[str]) -> None:
    for args in (["cycle"], ["cycle", "--engine", "inline4"]):
        code, out, err = run(
            [*args, "--speed-fluctuation-target", "0.2", "--format", "json"], capsys
        )
        assert code == 0, err
        assert json.loads(out)["flywheel"]["check_speed_fluctuation"] < 0.25


# ------------------------------------------------------------------------------------------
# the last net: floating-point errors of a study are one line naming the study
# ------------------------------------------------------------------------------------------


def test_arithmetic_checked_names_the_study() -> None:
    with pytest.raises(InputError) as error, arithmetic_checked("the study", "--engine x"):
        np.array([1e308]) * 10.0
    assert error.value.field == "the study" and error.value.value == "--engine x"
    assert "overflow" in error.value.allowed
    with arithmetic_checked("the study", "--engine x"):
        assert np.array([1e-300]) * 1e-300 == 0.0  # underflow is rounding, not an error


def _overflow(*args: Any, **kwargs: Any) -> None:
    np.exp(np.array([1000.0]))


@pytest.mark.parametrize(
    "target, args, needle",
    [
        ("crankbalance.studies.loads.crank_loads", ["bearings", "inline4"], "the bearing-load"),
        (
            "crankbalance.studies.loads.crank_loads",
            ["bearings-sweep", "inline4", "--balance-factors", "0.5"],
            "the bearing-load study = \"engine 'Inline-4, flat crank'\"",
        ),
        (
            "crankbalance.physics.torsional.engine_excitation",
            ["torsional", "--engine", "inline4", "--speed-points", "10"],
            "torsional = '--engine inline4'",
        ),
        (
            "crankbalance.physics.engine_cycle_all.energy_excursion",
            ["cycle", "--engine", "inline4"],
            "the engine cycle",
        ),
        (
            "crankbalance.physics.engine_cycle.cylinder_forces",
            ["cycle"],
            "cycle = 'the cylinder of the options'",
        ),
        ("crankbalance.physics.engine_cycle.cylinder_forces", ["sensitivity"], "sensitivity = "),
    ],
)
def test_every_study_runs_inside_the_net(
    target: str,
    args: list[str],
    needle: str,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """An overflow anywhere in a study's computation (here planted) ends in one line naming
    the study, not in a warning, a traceback or a NaN blamed on an option."""
    monkeypatch.setattr(target, _overflow)
    line = refused(args, needle, capsys)
    assert "cannot be computed for these inputs (overflow encountered in exp)" in line


# ------------------------------------------------------------------------------------------
# every numeric option at both ends of its range, every warning an error
# ------------------------------------------------------------------------------------------

#: command -> (the words of a cheap valid call, its options' schema, fields not tried)
COMMANDS: dict[str, tuple[list[str], type[opt.StudyOptions], set[str]]] = {
    "cycle --engine": (
        ["cycle", "--engine", "inline4"],
        opt.CycleOptions,
        # one cylinder's bearing only: refused for the whole engine
        {"engine", "cylinder", "balance_factor", "journal_diameter", "friction_coefficient"},
    ),
    "cycle": (["cycle"], opt.CycleOptions, {"engine", "cylinder"}),
    "sensitivity": (
        ["sensitivity", "--balance-factors", "0,1"],
        opt.SensitivityOptions,
        {"engine", "cylinder", "balance_factor"},
    ),
    "bearings": (["bearings", "inline4"], opt.BearingOptions, set()),
    "bearings-sweep": (
        ["bearings-sweep", "inline4", "--balance-factors", "0.5"],
        opt.BearingOptions,
        set(),
    ),
    "torsional": (
        ["torsional", "--engine", "inline4", "--speed-points", "10"],
        opt.TorsionalOptions,
        {"engine"},
    ),
}
#: the options an option needs beside it
COMPANIONS = {
    "damper_inertia": ["--damper-frequency", "330 Hz"],
    "damper_frequency": ["--damper-inertia", "0.004 kg*m^2"],
    "damper_damping_ratio": ["--damper-inertia", "0.004 kg*m^2", "--damper-frequency", "330 Hz"],
    "damper_allowed_power": ["--damper-inertia", "0.004 kg*m^2", "--damper-frequency", "330 Hz"],
    "load_inertia": ["--load-stiffness", "5e5 N*m/rad"],
    "load_stiffness": ["--load-inertia", "1 kg*m^2"],
    "viscosity": ["--bearing-length", "20 mm", "--clearance", "30 um"],
    "bearing_length": ["--viscosity", "0.01 Pa*s", "--clearance", "30 um"],
    "clearance": ["--viscosity", "0.01 Pa*s", "--bearing-length", "20 mm"],
}


def _edges(model: type[opt.StudyOptions], name: str) -> list[str]:
    """The two ends of a numeric setting's range as a user types them (an open end: just
    inside it); nothing for a text, a list or a choice."""
    kind, quantity = opt.field_kind(model, name)
    spec = model.FIELDS[name]
    if spec.parse is opt.parse_torsional_stiffness:  # its own unit, per radian
        return [f"{value:g} N*m/rad" for value in opt.TORSIONAL_STIFFNESS_RANGE]
    if kind not in ("quantity", "number", "whole"):
        return []
    low, low_open, high, high_open = spec.low, spec.low_open, spec.high, spec.high_open
    if quantity is not None:
        low = opt.RANGES[quantity][0] if low is None else low
        high = opt.RANGES[quantity][1] if high is None else high
    ends = []
    for value, is_open, inward in ((low, low_open, 1), (high, high_open, -1)):
        if value is None:
            continue
        if is_open:
            value = 1e-300 if value == 0 else value + inward * abs(value) * 1e-9
        if quantity is not None:
            ends.append(format_quantity(value, quantity, 15))
        else:
            ends.append(str(int(value)) if kind == "whole" else repr(float(value)))
    return ends


def _edge_cases() -> list[Any]:
    from crankbalance.cli import cli

    cases = []
    for label, (words, model, skip) in COMMANDS.items():
        command = cli.get_command(None, words[0])  # type: ignore[arg-type]
        assert command is not None
        params = {p.name for p in command.params}
        for name in model.FIELDS:
            if name in skip or name not in params:
                continue
            for value in _edges(model, name):
                option = "--" + name.replace("_", "-")
                args = [*words, option, value, *COMPANIONS.get(name, []), "--format", "json"]
                cases.append(pytest.param(args, option, id=f"{label} {option} {value}"))
    return cases


def _clean(args: list[str], option: str, capsys: pytest.CaptureFixture[str]) -> None:
    """Exit 0 with finite output, or exit 2 with one line naming ``option`` (or the crank
    that would nearly stop, naming its inertia); never a warning."""
    code, out, err = run(args, capsys)
    progress = re.sub(r"sensitivity: \d+/\d+", "", err)  # sensitivity's progress
    if code == 0:
        assert not NON_FINITE.search(out), out[:300]
        assert progress.strip() == "", err
        return
    lines = err.splitlines()
    assert code == 2 and len(lines) == 1 and lines[0].startswith("error: "), (code, err)
    line = lines[0]
    named = option in line or (STOPS in line and any(name in line for name in INERTIAS))
    assert named, line


EDGE_CASES = _edge_cases()


def test_the_edges_cover_every_command() -> None:
    ids = " ".join(str(case.id) for case in EDGE_CASES)
    for label in COMMANDS:
        assert ids.count(f"{label} --") >= 10, label
    assert len(EDGE_CASES) > 150


@pytest.mark.parametrize("args, option", EDGE_CASES)
def test_every_option_at_the_ends_of_its_range(
    args: list[str], option: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with hang_guard(300):
        _clean(args, option, capsys)


#: extreme tables inside the ranges: the largest pressure everywhere, a vacuum, a table at
#: the ends of the angles, a spike from a vacuum to the largest pressure
EXTREME_TABLES = {
    "1000 bar": [(0.0, 1000.0), (90.0, 1000.0), (180.0, 1000.0), (700.0, 1000.0)],
    "vacuum": [(0.0, 0.0), (90.0, 0.0), (180.0, 0.0), (700.0, 0.0)],
    "angle ends": [(-720.0, 1.0), (-400.0, 60.0), (-300.0, 1.0), (-1.0, 1.0)],
    "spike": [(0.0, 0.0), (1e-9, 1000.0), (2e-9, 0.0), (359.0, 0.0)],
}


@pytest.mark.parametrize("rows", list(EXTREME_TABLES), ids=list(EXTREME_TABLES))
@pytest.mark.parametrize("command", list(PRESSURE_COMMANDS))
def test_extreme_pressure_tables(
    command: str, rows: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = table(tmp_path, EXTREME_TABLES[rows])
    with hang_guard(300):
        _clean(
            [*PRESSURE_COMMANDS[command], "--pressure-csv", path, "--format", "json"], path, capsys
        )
