"""The whole engine over one working cycle (crankbalance.physics.engine_cycle_all, issue 18 item 2):
against the single-cylinder engine cycle, closed forms of the inertia torque, the free
forces of crankbalance.physics.shaking, the energy balance and a re-integration of the speed."""

from __future__ import annotations

import dataclasses
import json
import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crankbalance.errors import InputError
from crankbalance.physics.engine_cycle import (
    CylinderSpec,
    WiebeCombustion,
    cylinder_volume,
    engine_cycle,
    wiebe_pressure,
)
from crankbalance.physics.engine_cycle_all import (
    energy_excursion,
    engine_cycle_all,
    flywheel_inertia,
)
from crankbalance.physics.firing import firing_angles
from crankbalance.physics.shaking import exact_time_domain
from crankbalance.studies.engine import as_model
from crankbalance.studies.performance import cycle_cylinder

from .conftest import run_cli

WIEBE = WiebeCombustion(
    compression_ratio=12.0, ignition_angle=math.radians(-20), burn_duration=math.radians(50)
)


def _no_gas(strokes: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """A pressure table at the crankcase pressure: no gas force."""
    angle = np.radians(np.arange(0.0, 180.0 * strokes, 5.0)) - np.pi * strokes / 2
    return angle, np.full_like(angle, 1.0e5)


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))) / np.max(np.abs(b)))


# ---------------------------------------------------------------- one cylinder, two codes
@pytest.mark.parametrize(
    ("offset", "strokes", "pressure"),
    [(0.0, 4, WIEBE), (0.004, 4, WIEBE), (0.0, 2, WIEBE), (-0.003, 2, "table")],
)
def test_one_cylinder_engine_equals_engine_cycle(offset, strokes, pressure):
    model = dataclasses.replace(
        as_model("single"), cylinder_offset=np.array([offset]), strokes=strokes
    )
    if pressure == "table":
        angle = np.radians(np.arange(-180.0, 180.0, 2.0))
        pressure = (angle, 1e5 + 40e5 * np.exp(-((angle - 0.2) ** 2) / 0.1))
    spec = cycle_cylinder(
        model, 1, crank_inertia=0.03, journal_diameter=0.03, friction_coefficient=0.0
    )
    single = engine_cycle(spec, model.speed, pressure, strokes)
    whole = engine_cycle_all(model, pressure, bore=spec.bore, crank_inertia=0.03)
    for name in ("gas_torque", "inertia_torque", "speed", "crank_acceleration"):
        assert _relative(getattr(whole, name), getattr(single, name)) < 1e-9, name
    assert _relative(whole.torque, single.net_torque) < 1e-9, "no friction: net = gas + inertia"
    assert _relative(whole.pressure, single.pressure) < 1e-9
    assert whole.speed_fluctuation == pytest.approx(single.speed_fluctuation, rel=1e-9)
    assert whole.indicated_work == pytest.approx(single.indicated_work, rel=1e-12)


def test_one_cylinder_pin_force_is_the_bearing_load_of_engine_cycle():
    """With balance factor 0 and no crank weight, engine_cycle's main-bearing load of a
    single cylinder (the force its crank puts on the bearings) is the rod's force on the
    pin: the same force, two codes."""
    model = dataclasses.replace(as_model("single"), cylinder_offset=np.array([0.002]))
    spec = cycle_cylinder(
        model, 1, crank_inertia=0.03, journal_diameter=0.03, friction_coefficient=0.0
    )
    single = engine_cycle(spec, model.speed, WIEBE, 4)
    whole = engine_cycle_all(model, WIEBE, bore=spec.bore, crank_inertia=0.03)
    bearing = single.inline_load[0] + 1j * single.transverse_load[0]
    assert _relative(whole.throw_force[0], bearing) < 1e-9


# ---------------------------------------------------------------- inertia torque, closed form
def test_inline4_inertia_torque_has_even_orders_only_den_hartog():
    """Inline-4 (pins 0, 180, 180, 0), no gas: the inertia torque is 4 x the even orders of
    one cylinder's, Den Hartog (1956) Sec. 5.3: T = m r^2 w^2 [(l/4) sin t - 1/2 sin 2t -
    (3l/4) sin 3t - (l^2/4) sin 4t ...]; harmonics at l = 0.25 from the exact kinematics
    0.0635, -0.5001, -0.1921, -0.0161 (the values of tests/test_dynamics.py)."""
    base = as_model("inline4")
    model = dataclasses.replace(base, rod_length=base.crank_radius / 0.25)
    result = engine_cycle_all(
        model, _no_gas(), bore=0.08, crank_inertia=0.2, samples_per_revolution=256
    )
    m = float(model.reciprocating_mass[0])
    scale = m * model.crank_radius**2 * model.speed**2
    torque, th = result.inertia_torque / scale, result.angle
    b = np.array([2 * np.mean(torque * np.sin(n * th)) for n in range(9)])
    a = np.array([2 * np.mean(torque * np.cos(n * th)) for n in range(9)])
    assert np.max(np.abs(b[1::2])) < 1e-9 and np.max(np.abs(a[1:])) < 1e-9, "odd orders cancel"
    assert b[2] == pytest.approx(4 * -0.5001, abs=4 * 6e-5), "order 2: 4 x Den Hartog"
    assert b[4] == pytest.approx(4 * -0.0161, abs=4 * 6e-5), "order 4: 4 x Den Hartog"
    assert b[2] == pytest.approx(-2.0, abs=4 * 5e-3), "series to l^2: -1/2 per cylinder"
    assert b[4] == pytest.approx(-(0.25**2), abs=4 * 5e-3), "series to l^2: -l^2/4 per cyl."
    assert np.allclose(result.gas_torque, 0.0, atol=1e-12), "no gas force"


def test_vee_twin_90_torque_is_the_sum_of_two_phased_single_cylinders():
    model = as_model("v2-90")
    whole = engine_cycle_all(model, WIEBE, bore=0.07, crank_inertia=0.05)
    fire = np.degrees(whole.fire_angle)
    assert np.mod(fire[1] - fire[0], 720) == pytest.approx(450.0), "90 deg V-twin: 450/270"
    spec = cycle_cylinder(
        model, 1, bore=0.07, crank_inertia=0.05, journal_diameter=0.03, friction_coefficient=0
    )
    parts = [
        engine_cycle(spec, model.speed, WIEBE, 4, phases=[ph])
        for ph in whole.fire_angle - whole.fire_angle[0]
    ]
    for name in ("gas_torque", "inertia_torque"):
        total = sum(getattr(p, name) for p in parts)
        assert _relative(getattr(whole, name), total) < 1e-9, name
    assert _relative(whole.cylinder_gas_torque[1], parts[1].gas_torque) < 1e-9


# ---------------------------------------------------------------- forces: two codes
@pytest.mark.parametrize("preset", ["inline4", "v8-crossplane", "w12", "radial5", "v2-90"])
def test_pin_and_side_forces_of_inertia_sum_to_the_free_force(preset):
    """Sum over throws of the rods' inertia force on the pins, plus the pistons' inertia
    side forces on the walls, is the free force of crankbalance.physics.shaking (exact time
    domain): the same physics by two codes. The side forces carry the rods' obliquity, so
    the pin forces alone do not make the free force (checked too)."""
    base = as_model(preset)
    model = dataclasses.replace(base, cylinder_offset=np.full(base.cylinders, 0.002))
    result = engine_cycle_all(
        model, WIEBE, bore=0.08, crank_inertia=0.5, samples_per_revolution=180
    )
    free, _ = exact_time_domain(model, result.crank_angle)
    pins = result.throw_force_inertia.sum(axis=0)
    sides = result.side_force_inertia.sum(axis=0)
    assert _relative(pins + sides, free) < 1e-9
    assert np.max(np.abs(sides)) > 1e-3 * np.max(np.abs(free)), "obliquity is not negligible"


@pytest.mark.parametrize("preset", ["inline4", "v8-crossplane", "v6-90", "boxer2"])
def test_torque_is_the_moment_of_the_pin_forces(preset):
    """The crank torque computed per cylinder in its own frame equals the moment about the
    crank axis of ``throw_force`` at the crankpins, Im(conj(pin) F)."""
    model = as_model(preset)
    result = engine_cycle_all(model, WIEBE, bore=0.08, crank_inertia=0.5)
    pin = model.crank_radius * np.exp(
        1j * (result.crank_angle[None, :] + model.throw_angle[:, None])
    )
    moment = np.imag(np.conj(pin) * result.throw_force).sum(axis=0)
    assert _relative(moment, result.torque) < 1e-9
    # the gas forces are internal: pins + walls + heads (F_g along each axis) sum to zero
    gas_pins = (result.throw_force - result.throw_force_inertia).sum(axis=0)
    gas_sides = (result.side_force - result.side_force_inertia).sum(axis=0)
    area = math.pi * 0.08**2 / 4
    heads = ((result.pressure - 1e5) * area * np.exp(1j * model.cylinder_bank)[:, None]).sum(0)
    assert np.max(np.abs(gas_pins + gas_sides + heads)) < 1e-9 * np.max(np.abs(heads))


# ---------------------------------------------------------------- energy and flywheel
@pytest.mark.parametrize("preset", ["inline4", "v8-crossplane", "inline2-2stroke"])
def test_mean_torque_times_cycle_is_the_indicated_work(preset):
    model = as_model(preset)
    result = engine_cycle_all(model, WIEBE, bore=0.08, crank_inertia=0.5)
    cycle = math.pi * model.strokes
    assert result.mean_torque * cycle == pytest.approx(result.indicated_work, rel=5e-3)
    # against an independent, finer p-V integration of one cylinder times the count
    spec = CylinderSpec(
        bore=0.08,
        crank_radius=model.crank_radius,
        rod_length=model.rod_length,
        reciprocating_mass=0.3,
        crank_inertia=1.0,
    )
    theta = np.linspace(-np.pi, np.pi, 20001)
    p = wiebe_pressure(theta, spec, WIEBE, model.strokes)
    v = cylinder_volume(theta, 0.08, model.crank_radius, model.rod_length, 12.0)
    work = model.cylinders * np.trapezoid(p, v)
    assert result.mean_torque * cycle == pytest.approx(work, rel=5e-3), "0.5 % (issue 7)"
    assert abs(np.mean(result.inertia_torque)) < 1e-9 * np.max(np.abs(result.inertia_torque))
    assert result.indicated_power == pytest.approx(result.mean_torque * model.speed)


@pytest.mark.parametrize("preset", ["single", "inline4", "v8-crossplane", "v6-90", "radial5"])
@pytest.mark.parametrize("target", [0.005, 0.02])
def test_flywheel_sizing_checked_by_reintegration(preset, target):
    model = as_model(preset)
    result = engine_cycle_all(
        model, WIEBE, bore=0.08, crank_inertia=0.5, speed_fluctuation_target=target
    )
    assert result.required_inertia > 0
    assert result.required_inertia_fluctuation == pytest.approx(target, rel=0.02)
    again = engine_cycle_all(model, WIEBE, bore=0.08, crank_inertia=result.required_inertia)
    assert again.speed_fluctuation == pytest.approx(result.required_inertia_fluctuation, rel=1e-9)
    # the speed satisfies the equation of motion: acceleration = w dw/dtheta
    step = again.angle[1] - again.angle[0]
    fd = again.speed * np.gradient(again.speed, step)
    inner = slice(10, -10)
    assert np.allclose(
        fd[inner],
        again.crank_acceleration[inner],
        atol=2e-3 * np.max(np.abs(again.crank_acceleration)),
    )


def test_flywheel_closed_form_on_a_sine_torque():
    """T = T0 sin(k theta): E swings by 2 T0 / k, so I = 2 T0 / (k delta w^2)."""
    theta = np.linspace(0, 4 * np.pi, 1440, endpoint=False)
    inertia, swing = flywheel_inertia(theta, 50.0 + 120.0 * np.sin(3 * theta), 300.0, 0.01)
    assert swing == pytest.approx(2 * 120.0 / 3, rel=1e-4)
    assert inertia == pytest.approx(2 * 120.0 / 3 / (0.01 * 300.0**2), rel=1e-4)
    assert energy_excursion(theta, np.full_like(theta, 7.0)) == 0.0


# ---------------------------------------------------------------- firing
def test_firing_angles_even_and_uneven():
    four = as_model("inline4")  # 1-3-4-2 on pins 0, 180, 180, 0
    fire = firing_angles(four.cylinder_angle, four.cylinder_bank, four.firing_order, 4)
    assert np.degrees(fire) == pytest.approx([0, 540, 180, 360])
    twin = as_model("inline2-270")
    fire = firing_angles(twin.cylinder_angle, twin.cylinder_bank, twin.firing_order, 4)
    assert np.degrees(fire) == pytest.approx([0, 270]), "270 deg twin fires 270/450"
    v6 = as_model("v6-90")  # no firing order: the most even choice on pins 120 deg apart
    fire = np.sort(np.degrees(engine_cycle_all(v6, WIEBE, bore=0.09, crank_inertia=1).fire_angle))
    gaps = np.diff(np.append(fire, fire[0] + 720))
    assert gaps.sum() == pytest.approx(720) and np.max(np.abs(gaps - 120)) == pytest.approx(30)
    v8 = as_model("v8-crossplane")
    fire = firing_angles(v8.cylinder_angle, v8.cylinder_bank, v8.firing_order, 4)
    assert np.degrees(np.sort(fire)) == pytest.approx(np.arange(0, 720, 90))
    # every firing angle is a top dead centre of its cylinder
    assert np.allclose(np.cos(fire + v8.cylinder_angle - v8.cylinder_bank), 1.0)


def test_pressure_per_cylinder():
    model = as_model("inline2-180")
    weak = dataclasses.replace(WIEBE, intake_pressure=0.5e5)
    both = engine_cycle_all(model, [WIEBE, weak], bore=0.07, crank_inertia=0.05)
    same = engine_cycle_all(model, WIEBE, bore=0.07, crank_inertia=0.05)
    assert _relative(both.cylinder_gas_torque[0], same.cylinder_gas_torque[0]) < 1e-12
    assert both.indicated_work < same.indicated_work


@pytest.mark.parametrize(
    ("call", "field"),
    [
        (lambda m: engine_cycle_all(m, [WIEBE], bore=0.08, crank_inertia=1), "pressure"),
        (
            lambda m: engine_cycle_all(
                m, WIEBE, bore=0.08, crank_inertia=1, fire_angle=[0, 1, 2, 3]
            ),
            "fire_angle (cylinder 2)",
        ),
        (
            lambda m: engine_cycle_all(
                m, WIEBE, bore=0.08, crank_inertia=1, speed_fluctuation_target=0.0
            ),
            "speed_fluctuation_target",
        ),
        (lambda m: engine_cycle_all(m, WIEBE, bore=0.0, crank_inertia=1), "bore"),
        (
            lambda m: engine_cycle_all(m, WIEBE, bore=0.08, crank_inertia=float("nan")),
            "crank_inertia",
        ),
        (
            lambda m: firing_angles(m.cylinder_angle, m.cylinder_bank, [1, 2, 2, 4], 4),
            "crank_train.firing_order",
        ),
        (
            lambda m: firing_angles(m.cylinder_angle, m.cylinder_bank, [1, 3, 2, 4], 2),
            "crank_train.firing_order",
        ),
    ],
)
def test_bad_input_names_the_field(call, field):
    with pytest.raises(InputError) as error:
        call(as_model("inline4"))
    assert error.value.field == field


# ---------------------------------------------------------------- command line
def _cli(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, Any, str]:
    code, out, err = run_cli(args, capsys)
    data = json.loads(out) if code == 0 and "json" in args else out
    return code, data, err


def test_cli_cycle_runs_every_cylinder_by_default(capsys):
    args = ["cycle", "--engine", "v8-crossplane", "--crank-inertia", "0.05 kg*m^2"]
    code, data, err = _cli([*args, "--format", "json"], capsys)
    assert code == 0, err
    assert data["schema"] == "crankbalance.cycle/3" and "cylinder" not in data
    engine = data["engine"]
    assert engine["cylinders"] == 8 and engine["firing_order"] == [1, 5, 4, 8, 6, 3, 7, 2]
    assert np.degrees(engine["firing_interval_rad"]) == pytest.approx([90.0] * 8)
    curves = data["curves"]
    assert np.shape(curves["cylinder_torque_Nm"]) == (8, 1440)
    assert np.shape(curves["throw_force_z_N"]) == (4, 1440)
    # the command gives what the study gives
    model = as_model("v8-crossplane")
    result = engine_cycle_all(model, _cli_wiebe(), bore=2 * model.crank_radius, crank_inertia=0.05)
    assert curves["torque_Nm"] == pytest.approx(result.torque.tolist(), rel=1e-9, abs=1e-6)
    assert data["summary"]["mean_torque_Nm"] == pytest.approx(result.mean_torque, rel=1e-9)
    assert "flywheel" not in data
    code, text, err = _cli(args, capsys)
    assert code == 0 and "all 8 cylinders" in text and "intervals 90-90" in text


def _cli_wiebe() -> WiebeCombustion:
    """The Wiebe model of the command's defaults."""
    return WiebeCombustion(
        compression_ratio=13.5,
        ignition_angle=math.radians(-25.0),
        burn_duration=math.radians(50.0),
        intake_pressure=1e5,
    )


def test_cli_cycle_flywheel_sizing(capsys):
    args = ["cycle", "--engine", "inline4", "--crank-inertia", "0.05 kg*m^2"]
    code, data, err = _cli([*args, "--speed-fluctuation-target", "1%", "--format", "json"], capsys)
    assert code == 0, err
    fly = data["flywheel"]
    assert fly["speed_fluctuation_target"] == pytest.approx(0.01)
    assert fly["check_speed_fluctuation"] == pytest.approx(0.01, rel=0.02)
    assert fly["required_flywheel_inertia_kg_m2"] == pytest.approx(
        fly["required_inertia_kg_m2"] - 0.05
    )
    flywheel = f"{fly['required_flywheel_inertia_kg_m2']} kg*m^2"
    code, again, err = _cli([*args, "--flywheel-inertia", flywheel, "--format", "json"], capsys)
    assert code == 0, err
    assert again["engine"]["flywheel_inertia_kg_m2"] == pytest.approx(
        fly["required_flywheel_inertia_kg_m2"]
    )
    assert again["summary"]["speed_fluctuation"] == pytest.approx(
        fly["check_speed_fluctuation"], rel=1e-9
    )
    # one cylinder: sized on its net torque (with friction), checked by engine_cycle
    one = ["cycle", "--engine", "inline4", "--cylinder", "2", "--speed-fluctuation-target", "0.02"]
    code, data, err = _cli([*one, "--format", "json"], capsys)
    assert code == 0, err
    assert data["flywheel"]["check_speed_fluctuation"] == pytest.approx(0.02, rel=0.02)


def test_cli_cycle_pressure_table_per_cylinder(capsys, tmp_path):
    angle = np.arange(-360, 360, 5.0)
    paths = []
    for k, peak in enumerate((40.0, 20.0)):
        path = tmp_path / f"p{k}.csv"
        pressure = 1.0 + peak * np.exp(-(((angle - 10) / 30) ** 2))
        path.write_text("\n".join(f"{a},{p}" for a, p in zip(angle, pressure, strict=True)))
        paths.append(str(path))
    base = ["cycle", "--engine", "inline2-180", "--crank-inertia", "0.05 kg*m^2"]
    code, data, err = _cli(
        [*base, "--pressure-csv", paths[0], "--pressure-csv", paths[1], "--format", "json"],
        capsys,
    )
    assert code == 0, err
    peaks = np.max(data["curves"]["cylinder_pressure_Pa"], axis=1)
    assert peaks == pytest.approx([41e5, 21e5], rel=0.01)
    code, _, err = _cli([*base, "--pressure-csv", paths[0]], capsys)
    assert code == 0, err
    three = [*base, *(["--pressure-csv", paths[0]] * 3)]
    code, _, err = _cli(three, capsys)
    assert code == 2 and "--pressure-csv" in err and "one per cylinder (2)" in err


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--balance-factor", "0.3"], "--balance-factor"),
        (["--journal-diameter", "40 mm"], "--journal-diameter"),
        (["--speed-fluctuation-target", "0"], "--speed-fluctuation-target"),
        (["--speed-fluctuation-target", "60%"], "--speed-fluctuation-target"),
        (["--flywheel-inertia", "-1 kg*m^2"], "--flywheel-inertia"),
        (["--plot", "x.txt"], "--plot"),
    ],
)
def test_cli_cycle_refuses(args, needle, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _, err = _cli(["cycle", "--engine", "inline4", *args], capsys)
    assert code == 2 and err.startswith(f"error: {needle}"), err


def test_cli_cycle_too_small_inertia_names_the_option_and_the_flywheel(capsys):
    code, _, err = _cli(
        [
            "cycle",
            "--engine",
            "paper-inline3",
            "--crank-inertia",
            "0.006 kg*m^2",  # below the cylinders' reciprocating share
            "--speed-fluctuation-target",
            "0.01",
        ],
        capsys,
    )
    assert code == 2 and err.startswith("error: --crank-inertia")
    assert "needs" in err and "--flywheel-inertia" in err


def test_cli_cycle_plot(capsys, tmp_path):
    pytest.importorskip("plotly")
    out = tmp_path / "torque.html"
    args = ["cycle", "--engine", "v2-90", "--crank-inertia", "0.05 kg*m^2", "--plot", str(out)]
    code, _, err = _cli(args, capsys)
    assert code == 0, err
    page = out.read_text()
    assert "cylinder 2" in page and "Torque of each cylinder" in page


@pytest.mark.parametrize(
    ("preset", "rpm", "excursion", "required"),
    [("inline4", 2000, 346.9, 0.7886), ("v8-crossplane", 5500, 232.0, 0.0632)],
)
def test_worked_example_of_the_docs(preset, rpm, excursion, required):
    """The table of docs/engine_cycle.md (the command's default Wiebe model, 1 %)."""
    model = dataclasses.replace(as_model(preset), speed=rpm * math.pi / 30)
    result = engine_cycle_all(
        model,
        _cli_wiebe(),
        bore=2 * model.crank_radius,
        crank_inertia=0.05,
        speed_fluctuation_target=0.01,
    )
    assert result.energy_excursion == pytest.approx(excursion, abs=0.05)
    assert result.required_inertia == pytest.approx(required, abs=5e-5)


def test_cli_cycle_options_typed_override_the_engine(capsys):
    args = ["cycle", "--engine", "inline4", "--crank-inertia", "0.1 kg*m^2", "--format", "json"]
    code, base, err = _cli(args, capsys)
    assert code == 0, err
    typed = ["--speed", "3000 rpm", "--reciprocating-mass", "500 g", "--bore", "80 mm"]
    code, data, err = _cli([*args, *typed], capsys)
    assert code == 0, err
    assert data["speed_rad_s"] == pytest.approx(100 * math.pi)
    assert data["engine"]["reciprocating_mass_kg"] == pytest.approx([0.5] * 4)
    assert data["engine"]["bore_m"] == pytest.approx(0.08)
    assert base["engine"]["bore_m"] == pytest.approx(2 * as_model("inline4").crank_radius)
    # the inertia torque scales with m w^2: order 2 of an inline-4
    ratio = 0.5 / float(as_model("inline4").reciprocating_mass[0]) * (3000 / 6000) ** 2
    peak = np.max(np.abs(data["curves"]["inertia_torque_Nm"]))
    assert peak == pytest.approx(ratio * np.max(np.abs(base["curves"]["inertia_torque_Nm"])))


def test_result_to_dict_is_json_ready():
    model = as_model("v2-90")
    data = engine_cycle_all(model, WIEBE, bore=0.07, crank_inertia=0.05).to_dict()
    assert data["throw_force"][0][0].keys() == {"re", "im"}
    json.dumps(data)


@settings(derandomize=True, database=None, deadline=None, max_examples=60)
@given(
    st.integers(1, 7).flatmap(
        lambda n: st.tuples(
            st.lists(st.integers(0, 23), min_size=n, max_size=n),
            st.lists(st.sampled_from([-45, 0, 45]), min_size=n, max_size=n),
            st.permutations(list(range(1, n + 1))) | st.none(),
            st.sampled_from([2, 4]),
        )
    )
)
def test_firing_angles_are_top_dead_centres_in_the_order(case):
    """Any crank (pins at multiples of 15 deg, banks -45/0/45 deg), any or no order: the
    angles are top dead centres within one cycle, reached in the order; or the order is
    refused naming crank_train.firing_order."""
    pins, banks, order, strokes = case
    phi, beta = np.radians(np.array(pins) * 15.0), np.radians(np.array(banks, dtype=float))
    try:
        fire = firing_angles(phi, beta, order, strokes)
    except InputError as error:
        assert order is not None and error.field == "crank_train.firing_order"
        return
    cycle = np.pi * strokes
    assert np.all((fire >= 0) & (fire < cycle))
    assert np.allclose(np.cos(fire + phi - beta), 1.0), "each a top dead centre"
    if order is not None:
        seq = fire[np.array(order) - 1]
        steps = np.mod(np.diff(seq), cycle)
        assert steps.sum() <= cycle + 1e-9, "reached in the order within one cycle"


@pytest.mark.parametrize("preset", ["inline4", "v8-crossplane"])
def test_pin_and_side_forces_with_offsets_per_cylinder(preset):
    """Each cylinder's own offset (alternating signs, as in a VR bank) reaches the cycle:
    pins plus walls still make the free force of the exact time domain, which has the
    offsets per cylinder too (two codes)."""
    base = as_model(preset)
    offsets = np.where(np.arange(base.cylinders) % 2, 0.004, -0.002)
    model = dataclasses.replace(base, cylinder_offset=offsets)
    result = engine_cycle_all(
        model, WIEBE, bore=0.08, crank_inertia=0.5, samples_per_revolution=180
    )
    free, _ = exact_time_domain(model, result.crank_angle)
    pins = result.throw_force_inertia.sum(axis=0)
    sides = result.side_force_inertia.sum(axis=0)
    assert _relative(pins + sides, free) < 1e-9


def test_articulated_radial_is_refused():
    """Link pistons are no slider-cranks: the whole-engine cycle says so, naming the table."""
    with pytest.raises(InputError, match="crank_train.articulated"):
        engine_cycle_all(as_model("radial5-kinner"), WIEBE, bore=0.08, crank_inertia=0.5)


@pytest.mark.parametrize("preset", ["vr6", "w12-vw", "w8"])
def test_offset_cylinders_fire_at_their_real_top_dead_centre(preset):
    """VR rows' bore offsets move each piston's top dead centre asin(e/(l+r)) past its
    axis: every cylinder fires where its piston is at the top (piston velocity zero, by
    the slider-crank of kinematics, a second code), so the VW W12's even crank fires every
    60 deg (its crank is built for even firing with the offsets; the reviewer found
    53.1/66.9 deg when the offsets were left out of the firing angles)."""
    from crankbalance.physics.kinematics import piston_position, piston_velocity

    model = as_model(preset)
    result = engine_cycle_all(
        model, WIEBE, bore=0.08, crank_inertia=0.5, samples_per_revolution=180
    )
    axis = result.fire_angle + model.cylinder_angle - model.cylinder_bank
    r, length = model.crank_radius, model.rod_length
    velocity = piston_velocity(axis, r, length, model.cylinder_offset)
    assert np.max(np.abs(velocity)) < 1e-12 * r
    near = piston_position(
        axis[:, None] + np.array([-1e-3, 1e-3]), r, length, model.cylinder_offset[:, None]
    )
    assert np.all(near < piston_position(axis, r, length, model.cylinder_offset)[:, None])
    if preset == "w12-vw":
        fire = np.sort(result.fire_angle)
        steps = np.diff(np.append(fire, fire[0] + 4 * np.pi))
        np.testing.assert_allclose(np.degrees(steps), 60.0, atol=1e-9)


def test_one_cylinder_fires_once_a_cycle_in_the_output(capsys):
    """`cycle --engine single`: the firing interval of a single is the whole cycle (720
    deg), not the 0 deg that folding it into [0, cycle) gave."""
    from .conftest import run_cli

    code, out, _ = run_cli(["cycle", "--engine", "single", "--format", "json"], capsys)
    assert code == 0
    engine = json.loads(out)["engine"]
    assert engine["firing_interval_rad"] == pytest.approx([4 * math.pi])
    code, out, _ = run_cli(["cycle", "--engine", "single"], capsys)
    assert "one cylinder" in out and "intervals 720°" in out
