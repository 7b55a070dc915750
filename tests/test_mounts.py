"""Issue 31: the powertrain on its mounts (physics/mounts.py), against closed forms, the
definition of the torque-roll axis, the shaking module's own curves and a time integration
of the six-degree-of-freedom system to steady state."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from crankbalance.errors import InputError
from crankbalance.physics import mounts as pm
from crankbalance.physics.shaking import phasor_curve

M, KC, KS = 120.0, 2.0e5, 0.8e5
A, B, H = 0.25, 0.30, 0.15
IXX, IYY, IZZ = 6.0, 4.0, 7.0


def _four_mounts(height: float, damping: float = 0.0, eta: float = 0.0) -> pm.Powertrain:
    """Four equal mounts at (±A, ±B, -height) below a centre of gravity at the origin."""
    mounts = tuple(
        pm.Mount(
            f"m{k}",
            np.array([sx * A, sy * B, -height]),
            np.array([KC, KS, KS]),
            loss_factor=eta,
            damping=np.full(3, damping),
        )
        for k, (sx, sy) in enumerate([(1, 1), (1, -1), (-1, 1), (-1, -1)])
    )
    return pm.Powertrain(M, np.zeros(3), np.diag([IXX, IYY, IZZ]), mounts)


def _pair(k11: float, k12: float, k22: float, m1: float, m2: float) -> list[float]:
    """Closed-form frequencies [Hz] of two coupled coordinates (mass matrix diagonal)."""
    a = m1 * m2
    b = -(k11 * m2 + k22 * m1)
    c = k11 * k22 - k12**2
    root = math.sqrt(b * b - 4 * a * c)
    return [math.sqrt((-b + s * root) / (2 * a)) / (2 * math.pi) for s in (-1, 1)]


def test_symmetric_mounts_in_the_cg_plane_decouple_into_six_single_modes() -> None:
    modes = pm.modes(_four_mounts(0.0))
    expected = sorted(
        math.sqrt(k / m) / (2 * math.pi)
        for k, m in [
            (4 * KS, M),  # x
            (4 * KS, M),  # y
            (4 * KC, M),  # z
            (4 * KC * B**2, IXX),  # about x: z at y = ±B
            (4 * KC * A**2, IYY),  # about y: z at x = ±A
            (4 * KS * (A**2 + B**2), IZZ),  # about z: shear
        ]
    )
    np.testing.assert_allclose(modes.frequencies, expected, rtol=1e-10)
    # each mode's kinetic energy lies in one coordinate
    assert np.allclose(np.sort(modes.energy, axis=1)[:, -1], 100.0)


def test_symmetric_mounts_below_the_cg_give_two_coupled_pairs_and_two_single_modes() -> None:
    modes = pm.modes(_four_mounts(H))
    # x with the rotation about y, y with the rotation about x: u - h*theta at each mount
    x_pair = _pair(4 * KS, -4 * KS * H, 4 * KS * H**2 + 4 * KC * A**2, M, IYY)
    y_pair = _pair(4 * KS, 4 * KS * H, 4 * KS * H**2 + 4 * KC * B**2, M, IXX)
    singles = [
        math.sqrt(4 * KC / M) / (2 * math.pi),
        math.sqrt(4 * KS * (A**2 + B**2) / IZZ) / (2 * math.pi),
    ]
    np.testing.assert_allclose(modes.frequencies, sorted(x_pair + y_pair + singles), rtol=1e-10)
    # the coupled modes share their energy between x and pitch... only; z and yaw are pure
    names = pm.ENERGY_NAMES
    for row in modes.energy:
        big = {names[j] for j in range(6) if row[j] > 1e-6}
        assert big in ({"x", "roll"}, {"y", "pitch"}, {"z"}, {"yaw"})
        assert row.sum() == pytest.approx(100.0)


def test_the_torque_roll_axis_is_where_a_torque_about_the_crank_turns_a_free_body() -> None:
    rng = np.random.default_rng(3)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    inertia = q @ np.diag([3.0, 5.0, 6.5]) @ q.T
    tra = pm.torque_roll_axis(inertia)
    # definition: the angular acceleration of a free body under a torque T e_y is I^-1 T e_y
    alpha = np.linalg.solve(inertia, np.array([0.0, 10.0, 0.0]))
    assert np.linalg.norm(np.cross(tra, alpha)) < 1e-12 * np.linalg.norm(alpha)
    assert tra @ alpha > 0 and np.linalg.norm(tra) == pytest.approx(1.0)
    # a body whose principal axis is the crank axis rolls about the crank axis
    np.testing.assert_allclose(pm.torque_roll_axis(np.diag([2.0, 3.0, 4.0])), [0, 1, 0])
    # products of inertia tilt it: I_xy = -∫xy dm enters as the tensor's entry
    tilted = pm.torque_roll_axis(pm.inertia_tensor([2.0, 3.0, 4.0], [0.5, 0.0, 0.0]))
    assert tilted[0] < 0 < tilted[1]


def test_a_roll_mode_about_the_torque_roll_axis_is_reported_as_such() -> None:
    """Mounts in the CG plane, diagonal tensor: the roll mode turns about y, the TRA."""
    modes = pm.modes(_four_mounts(0.0))
    assert modes.roll_axis_angle == pytest.approx(0.0, abs=1e-9)
    assert modes.energy[modes.roll_mode, 3] == pytest.approx(100.0)


def test_statics_mounts_carry_the_weight_and_the_torque_reaction() -> None:
    pt = _four_mounts(H)
    torque = 150.0
    st = pm.statics(pt, torque)
    np.testing.assert_allclose(st.mount_loads.sum(axis=0), [0, 0, -M * pm.GRAVITY], atol=1e-9)
    moment = sum(
        np.cross(m.position - pt.cg, f) for m, f in zip(pt.mounts, st.mount_loads, strict=True)
    )
    np.testing.assert_allclose(moment, [0, -torque, 0], atol=1e-9)
    # weight alone: the body sinks by W / (4 kc), each mount takes a quarter
    plain = pm.statics(pt)
    assert plain.displacement[2] == pytest.approx(-M * pm.GRAVITY / (4 * KC))
    np.testing.assert_allclose(plain.mount_loads_local[:, 0], -M * pm.GRAVITY / 4)


def test_mount_orientation_turns_the_compression_axis() -> None:
    mount = pm.Mount("rod", np.zeros(3), np.array([3.0, 1.0, 2.0]), np.radians([0, 90, 0]))
    # 90 deg about y takes the compression axis (z) to x and the first shear axis (x) to -z
    np.testing.assert_allclose(mount.body_stiffness(), np.diag([3.0, 2.0, 1.0]), atol=1e-12)


def test_mounts_that_do_not_hold_every_direction_are_one_error_naming_them() -> None:
    free = tuple(
        pm.Mount(name, np.array(p, float), np.array([KC, 0.0, 0.0]))
        for name, p in [("left", (0.2, 0.3, 0)), ("right", (0.2, -0.3, 0)), ("rear", (-0.3, 0, 0))]
    )
    pt = pm.Powertrain(M, np.zeros(3), np.diag([IXX, IYY, IZZ]), free)
    with pytest.raises(InputError) as caught:
        pm.modes(pt)
    message = str(caught.value)
    assert "left, right, rear" in message and "six directions" in message


def test_order_loads_are_the_shaking_modules_curves() -> None:
    """The order phasors (forward, backward, z + ix) as real signals Re(X e^{inθ})."""
    rng = np.random.default_rng(7)
    ff, fb, cf, cb, roll = (rng.normal(size=3) + 1j * rng.normal(size=3) for _ in range(5))
    orders = np.array([1, 2, 3])
    theta = np.linspace(0, 2 * np.pi, 37)
    loads = pm.order_loads(ff, fb, cf, cb, roll)
    signal = (loads[:, :, None] * np.exp(1j * orders[:, None, None] * theta)).real
    force = phasor_curve(ff, fb, orders, theta)
    moment = 1j * phasor_curve(cf, cb, orders, theta)  # M = iC
    np.testing.assert_allclose(signal[:, 0], force.imag, atol=1e-12)
    np.testing.assert_allclose(signal[:, 1], 0.0)
    np.testing.assert_allclose(signal[:, 2], force.real, atol=1e-12)
    np.testing.assert_allclose(signal[:, 3], moment.imag, atol=1e-12)
    np.testing.assert_allclose(signal[:, 5], moment.real, atol=1e-12)
    roll_curve = (roll[:, None] * np.exp(1j * orders[:, None] * theta)).real
    np.testing.assert_allclose(signal[:, 4], roll_curve, atol=1e-12)


def test_peak_magnitude_is_the_largest_length_over_a_cycle() -> None:
    a = np.array([1.0 + 2j, -0.5 + 0.3j, 0.7 - 1.1j])
    t = np.linspace(0, 2 * np.pi, 20001)
    lengths = np.linalg.norm((a[:, None] * np.exp(1j * t)).real, axis=0)
    assert pm.peak_magnitude(a) == pytest.approx(lengths.max(), rel=1e-7)


def _viscous_powertrain() -> pm.Powertrain:
    """An unsymmetric body (CG off the origin, products of inertia, turned mounts) with
    viscous damping, for the time integration."""
    inertia = pm.inertia_tensor([5.0, 3.5, 6.0], [0.3, -0.2, 0.4])
    mounts = tuple(
        pm.Mount(
            f"m{k}",
            np.array(p),
            np.array(k3),
            np.radians(turn),
            damping=np.array(k3) * 2e-3,
        )
        for k, (p, k3, turn) in enumerate(
            [
                ((0.05, 0.3, 0.2), (2e5, 1e5, 1e5), (0, 0, 0)),
                ((0.0, -0.4, 0.15), (1.5e5, 0.8e5, 0.9e5), (10, 0, 20)),
                ((-0.25, 0.0, -0.2), (3e5, 0.3e5, 0.3e5), (0, 90, 0)),
            ]
        )
    )
    return pm.Powertrain(140.0, np.array([0.03, -0.08, 0.07]), inertia, mounts)


def test_forced_response_is_the_steady_state_of_the_time_integration() -> None:
    """Second method: integrate M q'' + C q' + K q = f(t) with scipy from rest until the
    transient has died, and compare the last revolutions with Re(Q e^{inωt}) of every
    coordinate and the transmitted force of every mount. The forcing is built from
    shaking.phasor_curve (x = imaginary, z = real part; M = iC), not from order_loads."""
    pt = _viscous_powertrain()
    rng = np.random.default_rng(11)
    ff, fb, cf, cb, roll = (
        s * (rng.normal(size=2) + 1j * rng.normal(size=2)) for s in (900.0, 900.0, 90.0, 90.0, 60.0)
    )
    orders = np.array([1, 2])
    speed = 2 * math.pi * 1500 / 60  # crank [rad/s]
    loads = pm.order_loads(ff, fb, cf, cb, roll)
    response = pm.forced_response(pt, loads, orders, speed, [speed])
    m, k = pm.mass_matrix(pt), pm.stiffness_matrix(pt)
    _, c = pm.damping_matrices(pt)
    minv = np.linalg.inv(m)

    def forcing(t: float) -> np.ndarray:
        theta = np.array([speed * t])
        f = phasor_curve(ff, fb, orders, theta).sum(axis=0)[0]
        mom = (1j * phasor_curve(cf, cb, orders, theta)).sum(axis=0)[0]
        my = (roll * np.exp(1j * orders * theta[0])).real.sum()
        load = np.array([f.imag, 0.0, f.real, mom.imag, my, mom.real])
        return pm.at_cg(load, pt.cg).real

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        q, v = y[:6], y[6:]
        return np.concatenate([v, minv @ (forcing(t) - c @ v - k @ q)])

    period = 2 * math.pi / speed
    end = 300 * period  # the slowest mode decays by e^-ζωt: more than e^-10 by then
    t_eval = np.linspace(end - 2 * period, end, 201)
    run = solve_ivp(
        rhs, (0.0, end), np.zeros(12), method="DOP853", rtol=1e-9, atol=1e-13, t_eval=t_eval
    )
    assert run.success
    turn = np.exp(1j * orders[:, None] * speed * t_eval[None, :])  # (K, T)
    q_freq = np.einsum("kj,kt->jt", response.displacement[0], turn).real
    scale = np.abs(q_freq).max(axis=1, keepdims=True)
    np.testing.assert_allclose(run.y[:6] / scale, q_freq / scale, atol=2e-4)
    for i, mount in enumerate(pt.mounts):
        t_map = pm.point_map(pt.cg, mount.position)
        d, v = t_map @ run.y[:6], t_map @ run.y[6:]
        f_time = mount.body_stiffness() @ d + mount.body_damping() @ v
        f_freq = np.einsum("ka,kt->at", response.mount_forces[0, :, i], turn).real
        np.testing.assert_allclose(f_time, f_freq, atol=2e-4 * np.abs(f_freq).max())


def test_forced_response_work_is_bounded_before_it_starts() -> None:
    pt = _four_mounts(H)
    too_many = np.linspace(10, 600, pm.MAX_RESPONSE_POINTS // 2 + 1)
    with pytest.raises(InputError) as caught:
        pm.forced_response(pt, np.zeros((2, 6), complex), [1, 2], 100.0, too_many)
    assert str(pm.MAX_RESPONSE_POINTS) in str(caught.value)


def test_hysteretic_response_at_resonance_is_the_loss_factor_peak() -> None:
    """A vertical force at the CG of the in-plane layout drives the bounce mode alone: at
    resonance |q_z| = F / (4 kc η)."""
    eta = 0.1
    pt = _four_mounts(0.0, eta=eta)
    bounce = math.sqrt(4 * KC / M)
    loads = np.array([[0, 0, 100.0, 0, 0, 0]], complex)
    response = pm.forced_response(pt, loads, [1], bounce, [bounce])
    assert abs(response.displacement[0, 0, 2]) == pytest.approx(100.0 / (4 * KC * eta))
    # each mount transmits a quarter of k(1+iη) q
    expected = KC * math.hypot(1, eta) * 100.0 / (4 * KC * eta)
    np.testing.assert_allclose(response.mount_peak[0, 0], expected, rtol=1e-9)


def test_mode_shapes_have_their_largest_entry_positive() -> None:
    shapes = pm.modes(_viscous_powertrain()).shapes
    largest = shapes[np.argmax(np.abs(shapes), axis=0), np.arange(6)]
    assert np.all(largest > 0)
