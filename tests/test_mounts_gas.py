"""Issue 31 item 4, the gas torque's reaction (``--gas-torque``): the roll about the crank
axis at every order of the engine cycle, the same at every speed; checked against the
cycle's own time curve (the order sum) and against an FFT of it."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from crankbalance.cli import main
from crankbalance.physics import mounts as pm
from crankbalance.physics.engine_cycle_all import engine_cycle_all
from crankbalance.schema.settings import MountsOptions
from crankbalance.studies.crank import rotating_inertia
from crankbalance.studies.mounts import mounts
from crankbalance.studies.performance import pressure_source

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "examples" / "mounts_inline4_car.toml"
BIKE = ROOT / "examples" / "mounts_vtwin_motorcycle.toml"


@pytest.mark.parametrize("engine", [CAR, BIKE])
def test_the_order_sum_of_the_applied_roll_is_the_cycles_gas_torque(engine: Path) -> None:
    settings = MountsOptions.parse({"gas_torque": True, "orders": 32, "speed_samples": 4})
    result = mounts(engine, settings)
    orders, roll = result.response.orders, result.gas_loads[:, 4]
    assert np.allclose(np.diff(orders), 0.5)  # a four-stroke: every half order
    assert np.all(result.gas_loads[:, [0, 1, 2, 3, 5]] == 0)  # a moment about y alone
    # the cycle again, as the study's settings give it
    model = result.model
    cycle = engine_cycle_all(
        model,
        pressure_source(settings, model.cylinders, model.strokes),
        bore=2 * model.crank_radius,
        crank_inertia=rotating_inertia(model),
    )
    theta = cycle.crank_angle
    applied = np.real(np.exp(1j * np.outer(theta, orders)) @ roll)
    reaction = -(cycle.gas_torque - cycle.gas_torque.mean())
    # the order sum up to order 32 is the curve within 1 % of its swing
    swing = np.ptp(reaction)
    assert np.max(np.abs(applied - reaction)) < 0.01 * swing
    # and each order is the FFT's (a cycle is two revolutions: order n is bin 2n)
    spectrum = np.fft.rfft(reaction) * 2 / theta.size
    start = np.exp(1j * np.outer(orders, [theta[0]]))[:, 0]  # the FFT's phase origin
    fft = spectrum[np.rint(2 * orders).astype(int)] / start
    keep = np.abs(roll) > 0
    assert np.allclose(roll[keep], fft[keep], rtol=1e-9, atol=1e-9 * np.abs(fft).max())
    assert np.all(np.abs(fft[~keep]) < 1e-8 * np.abs(fft).max())


def test_the_gas_reaction_does_not_scale_with_speed() -> None:
    result = mounts(CAR, MountsOptions.parse({"gas_torque": True, "speed_samples": 3}))
    plain = mounts(CAR, MountsOptions.parse({"speed_samples": 3}))
    # the response is the inertia loads' (x speed squared) plus the gas loads' as they are
    pt, rs = result.powertrain, result.response
    gas_only = pm.forced_response(
        pt, np.zeros_like(result.loads), rs.orders, result.model.speed, rs.speeds, result.gas_loads
    )
    k2 = int(np.argmin(np.abs(rs.orders - 2)))
    assert np.allclose(
        rs.displacement[:, k2], plain.response.displacement[:, 1] + gas_only.displacement[:, k2]
    )
    # at order 2 the gas roll amplitude is the same at every speed: the moment the mounts
    # take from it at a speed far above the modes tends to it
    assert abs(result.gas_loads[k2, 4]) > 0


def test_the_json_states_the_gas_torque_and_settings_that_would_not_act_are_refused(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code = main(
        [
            "mounts",
            str(BIKE),
            "--gas-torque",
            "--orders",
            "2",
            "--speed-samples",
            "10",
            "--format",
            "json",
        ]
    )
    out, err = capsys.readouterr()
    assert not code, err
    data = json.loads(out)
    assert [o["order"] for o in data["orders"]] == [0.5, 1, 1.5, 2]
    assert data["gas_torque"]["speed_dependence"].startswith("none")
    by_order = {e["order"]: e["amplitude_Nm"] for e in data["gas_torque"]["roll_Nm"]}
    # a 90 degree V-twin firing 270/450: the two cylinders' second orders cancel
    assert by_order[2] == 0 and by_order[0.5] > 0
    for args in (["--ignition", "-20 deg"], ["--bore", "90 mm"]):
        try:
            code = main(["mounts", str(BIKE), *args])
        except SystemExit as stop:
            code = stop.code
        _, err = capsys.readouterr()
        assert code == 2 and "only acts with --gas-torque" in err
