"""The sixth component: the roll moment about the crank axis, and moments about any point
(issue 27, item 2), each against a method of its own."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.physics.model import with_moment_point
from crankbalance.physics.shaking import curves, free_forces, roll_time_domain
from crankbalance.schema.engine import EngineSpec
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import analyze, as_model

from .conftest import run_cli


def test_single_cylinder_roll_is_the_textbook_inertia_torque_reaction() -> None:
    """The inertia torque of the slider-crank on the crank, by the textbook series
    (e.g. Taylor 1985 ch. 8, Norton's Design of Machinery ch. 13),
    T = m r^2 w^2 [(l/4 + l^3/16) sin th - 1/2 sin 2th - (3l/4 + 9l^3/32) sin 3th ...],
    the block taking -T: its first three orders, to the series' first omitted terms."""
    model = as_model("single")
    for rod_ratio in (0.1, 0.2818):
        m = replace(model, rod_length=model.crank_radius / rod_ratio)
        lam = m.rod_ratio
        scale = m.reciprocating_mass[0] * (m.crank_radius * m.speed) ** 2
        torque = [lam / 4 + lam**3 / 16, -0.5, -(3 * lam / 4 + 9 * lam**3 / 32)]
        # M_y = -T = Re(R e^{in th}) with R = -i * (-T_n) for T_n sin(n th)
        expected = np.array([1j * t for t in torque]) * scale
        got = free_forces(m, 3).roll
        series_error = lam**4  # the omitted terms are O(lambda^4) of m r^2 w^2 or smaller
        assert np.abs(got - expected).max() <= series_error * scale, (lam, got / scale)


def test_a_shifted_point_adds_r_cross_f_at_every_order() -> None:
    """Moments about P = moments about the old point minus P x F, every component and every
    order (forces on the block act in the x-z plane: F_y = 0)."""
    for name in ("vr6", "v2-45", "radial9-r985", "single"):
        base = as_model(name)
        f0 = free_forces(base, 8)
        point = np.array([0.031, -0.047, 0.112])  # x, y, z from the crank's mid-point
        f1 = free_forces(with_moment_point(base, point), 8)
        theta = np.linspace(0, 2 * np.pi, 97, endpoint=False)
        for k, n in enumerate(f0.orders):
            turn = np.exp(1j * n * theta)
            force = f0.force_forward[k] * turn + f0.force_backward[k] * np.conj(turn)
            fvec = np.stack([force.imag, np.zeros_like(theta), force.real], axis=1)  # x, y, z

            def moments(f, k=k, turn=turn):
                c = f.couple_forward[k] * turn + f.couple_backward[k] * np.conj(turn)
                m = 1j * c  # M = iC: z + ix
                roll = (f.roll[k] * turn).real
                return np.stack([m.imag, roll, m.real], axis=1)

            expected = moments(f0) - np.cross(point, fvec)
            scale = 1.0 + np.abs(moments(f0)).max() + np.abs(fvec).max()
            assert np.abs(moments(f1) - expected).max() <= 1e-11 * scale, (name, n)
        # the rotating masses likewise: the roll of their force about a point off the axis
        rot = f0.rotating_force * np.exp(1j * theta)
        roll = (f1.rotating_roll * np.exp(1j * theta)).real
        assert roll == pytest.approx(point[0] * rot.real - point[2] * rot.imag, abs=1e-9)


def _roll_by_statics(model, theta: np.ndarray) -> np.ndarray:
    """Independent of the module's energy formula: each piston in equilibrium of its inertia
    force, the rod's force along the rod and the wall's normal force; the block takes the
    piston's push on the wall at the piston (the main bearings' forces pass through the
    axis). Exact slider-crank geometry, numerical differentiation of the travel."""
    total = np.zeros_like(theta)
    r, l, w = model.crank_radius, model.rod_length, model.speed
    h = 1e-4
    for c in range(model.cylinders):
        beta, e = model.cylinder_bank[c], model.cylinder_offset[c]
        axis = np.exp(1j * beta)

        def travel(psi: np.ndarray, e: float = e) -> np.ndarray:
            return r * np.cos(psi) + np.sqrt(l**2 - (e - r * np.sin(psi)) ** 2)

        psi = theta + model.cylinder_angle[c] - beta
        s = travel(psi)
        s2 = (
            (
                -travel(psi + 2 * h)
                + 16 * travel(psi + h)
                - 30 * s
                + 16 * travel(psi - h)
                - travel(psi - 2 * h)
            )
            / (12 * h * h)
            * w**2
        )
        piston = (s + 1j * e) * axis
        pin = r * np.exp(1j * (psi + beta))
        rod = (piston - pin) / l
        inertia = -model.reciprocating_mass[c] * s2 * axis
        # along the bore: inertia + rho * rod has no component along the axis
        rho = -(np.conj(axis) * inertia).real / (np.conj(axis) * rod).real
        push = inertia + rho * rod  # the piston's push on the wall (normal to the bore)
        total += (np.conj(piston) * push).imag
    return total


def test_offset_cylinders_roll_agrees_with_a_statics_time_domain() -> None:
    """VR6 (its rows offset 12.5 mm) and an offset single: the roll moment's orders and
    the exact total against the piston-on-the-wall statics, Fourier-analysed."""
    for name, offset in (("vr6", None), ("single", 0.011)):
        model = as_model(name)
        if offset is not None:
            model = replace(model, cylinder_offset=np.array([offset]))
        n = 256
        theta = 2 * np.pi * np.arange(n) / n
        statics = _roll_by_statics(model, theta)
        forces = free_forces(model, 8)
        spectrum = np.fft.fft(statics)[1:9] * 2 / n
        scale = np.abs(statics).max()
        differentiation = 1e-6  # the statics' five-point second difference, h = 1e-4 rad
        assert np.abs(forces.roll - spectrum).max() <= differentiation * scale, name
        assert roll_time_domain(model, theta) == pytest.approx(statics, abs=differentiation * scale)


def test_the_roll_curves_sum_to_the_exact_total_also_with_link_rods() -> None:
    """The orders of the roll (from the Fourier analysis) add up to its exact time domain,
    articulated radials included, about a point off the axis."""
    for name in ("radial9-r985", "radial5-kinner", "vr6"):
        model = with_moment_point(as_model(name), (0.02, 0.01, -0.05))
        c = curves(model, free_forces(model, 40))
        scale = np.abs(c.total_my).max()
        assert scale > 0
        assert c.my.sum(axis=0) == pytest.approx(c.total_my, abs=1e-10 * scale), name


def test_series_kinematics_roll_is_the_product_of_its_series() -> None:
    """First-order kinematics: f = cos + l cos 2, s' = -(sin + l/2 sin 2), so
    M_y = f s' reversed = (1/2 sin 2 - l/4 sin + 3l/4 sin 3 + l^2/4 sin 4) m r^2 w^2,
    exactly (no higher orders)."""
    m = replace(as_model("single"), kinematics="first-order")
    lam = m.rod_ratio
    scale = m.reciprocating_mass[0] * (m.crank_radius * m.speed) ** 2
    block = np.array([-lam / 4, 0.5, 3 * lam / 4, lam**2 / 4, 0, 0])  # sin n th coefficients
    assert free_forces(m, 6).roll / scale == pytest.approx(-1j * block, abs=1e-14)


def _spec(extra: dict) -> EngineSpec:
    data = load_engine("inline4").to_data()
    data["crank_train"].update(extra)
    return EngineSpec.parse(data)


def test_engine_file_moment_point_and_the_old_key() -> None:
    """crank_train.moment_point = [x, y, z]; moment_reference = y is the point (0, y, 0);
    both at once are refused by name."""
    old = build_model(_spec({"moment_reference": "40 mm"}))
    new = build_model(_spec({"moment_point": ["0 mm", "40 mm", "0 mm"]}))
    assert old.moment_point == pytest.approx((0, 0.04, 0))
    assert new.moment_point == pytest.approx((0, 0.04, 0))
    assert np.array_equal(free_forces(old).roll, free_forces(new).roll)
    off = build_model(_spec({"moment_point": ["50 mm", "40 mm", "200 mm"]}))
    assert off.moment_point == pytest.approx((0.05, 0.04, 0.2))
    f = free_forces(off)
    k = f.order(2)
    q = complex(0.05, 0.2)
    shift = q * f.force_forward[k] + np.conj(q * f.force_backward[k])
    assert f.roll[k] == pytest.approx(free_forces(old).roll[k] + shift)
    with pytest.raises(InputError) as error:
        _spec({"moment_point": ["0 mm", "40 mm", "0 mm"], "moment_reference": "10 mm"})
    assert "crank_train.moment_point" in str(error.value)
    with pytest.raises(InputError) as error:
        _spec({"moment_point": ["0 mm", "40 mm"]})
    assert "crank_train.moment_point" in str(error.value)


def test_analyze_moment_point_in_table_csv_and_json(capsys: pytest.CaptureFixture[str]) -> None:
    args = ["analyze", "inline4", "--moment-point", "100 mm, 0 mm, 0 mm"]
    code, out, err = run_cli(args, capsys)
    assert code == 0, err
    assert "roll N·m" in out and "(100 mm, 0 mm, 0 mm)" in out
    code, out, err = run_cli([*args, "--format", "json"], capsys)
    data = json.loads(out)
    assert data["schema"] == "crankbalance.analysis/4"
    assert data["engine"]["moment_point_m"] == [0.1, 0.0, 0.0]
    f = analyze("inline4").forces  # about the crank's mid-point
    rows = data["roll_moments"]
    # the vertical second-order force 0.1 m beside the point: roll + 0.1 F_z
    k = f.order(2)
    shifted = f.roll[k] + 0.1 * (f.force_forward[k] + np.conj(f.force_backward[k]))
    assert rows[k]["amplitude_Nm"] == pytest.approx(abs(shifted), rel=1e-9)
    # M_y = amplitude cos(n theta + phase): the phasor's own angle
    assert rows[k]["phase_deg"] % 360 == pytest.approx(np.degrees(np.angle(shifted)) % 360)
    with pytest.raises(InputError, match="moment_point"):
        analyze("inline4", moment_point=(0.0, float("nan"), 0.0))
    assert abs(shifted) != pytest.approx(abs(f.roll[k]), rel=1e-3)
    code, out, err = run_cli([*args, "--format", "csv"], capsys)
    header = out.splitlines()[0].split(",")
    assert {"my_1_Nm", "my_total_Nm", "my_rotating_Nm"} <= set(header)
    code, out, err = run_cli(["analyze", "inline4", "--moment-point", "1 mm, 2 mm"], capsys)
    assert code == 2 and "--moment-point" in err
