"""Torsional vibration of the crank train (crankbalance.physics.torsional) against closed forms.

References: the two- and three-inertia closed forms (Den Hartog 1956, Secs. 5.1-5.2;
Thomson 1993, ch. 6), the two-inertia frequency response solved by hand (Cramer's rule),
the phase diagram of the inline-6 firing 1-5-3-6-2-4 (Den Hartog 1956, Sec. 5.5; Ker
Wilson 1956), the energy balance (mean input power = mean dissipated power), and
openTorsion (Aalto ARotor, PyPI ``opentorsion``) as a second solver.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.physics import torsional as tv
from crankbalance.physics.engine_cycle import WiebeCombustion
from crankbalance.physics.engine_cycle_all import engine_cycle_all
from crankbalance.studies.engine import as_model

WIEBE = WiebeCombustion(13.5, math.radians(-25.0), math.radians(50.0))


@pytest.fixture(scope="module")
def inline6() -> tuple:
    model = as_model("inline6")
    cycle = engine_cycle_all(model, WIEBE, bore=0.086, crank_inertia=0.15)
    k = tv.carter_stiffness(0.060, 0.050, 0.025, 0.025, 0.020, 0.090, model.crank_radius)
    omega_d = 2 * math.pi * 330.0
    train = tv.crank_train(
        tv.throw_inertias(model),
        k,
        0.010,
        k,
        0.15,
        k,
        damper_inertia=0.004,
        damper_stiffness=0.004 * omega_d**2,
        damper_damping=2 * 0.15 * 0.004 * omega_d,
        shaft_damping_ratio=0.02,
    )
    return model, cycle, train


def test_two_inertia_closed_form() -> None:
    j1, j2, k = 0.25, 0.04, 3.0e5
    modes = tv.natural_modes([j1, j2], [k])
    expected = math.sqrt(k * (j1 + j2) / (j1 * j2))
    assert modes.frequency[0] == pytest.approx(0.0, abs=1e-6)
    assert modes.frequency[1] == pytest.approx(expected, rel=1e-12), "omega^2 = k(J1+J2)/(J1 J2)"
    shape = modes.mode_shape[:, 1]
    assert shape[1] / shape[0] == pytest.approx(-j1 / j2, rel=1e-10), "node: J1 th1 = -J2 th2"
    np.testing.assert_allclose(modes.mode_shape[:, 0], [1.0, 1.0], rtol=1e-10)
    assert list(modes.nodes) == [0, 1]


def test_three_inertia_closed_form() -> None:
    j1, j2, j3, k1, k2 = 0.3, 0.1, 0.2, 2.0e5, 1.0e5
    # det(K - w^2 M) = -w^2 [J1 J2 J3 w^4 - (k1 J3 (J1+J2) + k2 J1 (J2+J3)) w^2
    #                        + k1 k2 (J1+J2+J3)]
    a, b, c = j1 * j2 * j3, -(k1 * j3 * (j1 + j2) + k2 * j1 * (j2 + j3)), k1 * k2 * (j1 + j2 + j3)
    roots = np.sort(np.roots([a, b, c]).real)
    modes = tv.natural_modes([j1, j2, j3], [k1, k2])
    np.testing.assert_allclose(modes.frequency[1:], np.sqrt(roots), rtol=1e-12)
    for m, lam in zip((1, 2), roots, strict=True):
        shape = modes.mode_shape[:, m]
        ratio2 = 1 - lam * j1 / k1  # row 1: (k1 - lam J1) th1 = k1 th2
        ratio3 = k2 * ratio2 / (k2 - lam * j3)  # row 3: (k2 - lam J3) th3 = k2 th2
        np.testing.assert_allclose(shape / shape[0], [1.0, ratio2, ratio3], rtol=1e-9)
    assert list(modes.nodes) == [0, 1, 2]


def _one_order(force: complex, speed: float) -> tv.EngineExcitation:
    return tv.EngineExcitation(
        orders=np.array([1.0]),
        reference_speed=speed,
        gas=np.array([[force]]),
        inertia=np.zeros((1, 1), dtype=complex),
        cylinder_throw=np.array([0]),
        fire_angle=np.array([0.0]),
        mean_torque=0.0,
    )


def test_two_inertia_forced_response_closed_form() -> None:
    j1, j2, k, c, force = 0.25, 0.04, 3.0e5, 25.0, 40.0 - 15.0j
    train = tv.CrankTrain(
        names=("a", "b"),
        inertia=np.array([j1, j2]),
        stiffness=np.array([k]),
        damping=np.array([c]),
        throw_index=np.array([0]),
        front_index=0,
        damper_section=0,
    )
    speed = np.linspace(100.0, 6000.0, 400)
    result = tv.forced_response(train, _one_order(force, 1000.0), speed)
    z = k + 1j * speed * c
    det = (z - speed**2 * j1) * (z - speed**2 * j2) - z**2
    x1 = (z - speed**2 * j2) * force / det  # Cramer's rule, torque on mass 1
    x2 = z * force / det
    np.testing.assert_allclose(result.amplitude[:, 0, 0], x1, rtol=1e-9)
    np.testing.assert_allclose(result.amplitude[:, 0, 1], x2, rtol=1e-9)
    np.testing.assert_allclose(result.section_torque[:, 0, 0], z * (x1 - x2), rtol=1e-9)
    # the resonance of the closed form is where the response peaks
    peak = speed[np.argmax(np.abs(x1 - x2))]
    assert peak == pytest.approx(math.sqrt(k * (j1 + j2) / (j1 * j2)), rel=0.02)


def test_energy_balance_at_resonance(inline6: tuple) -> None:
    """Second method: the excitation's mean power F^H(iW X)/2 equals what the dampers take,
    sum of c W^2 |twist|^2 / 2, at the first elastic mode's critical speeds."""
    model, cycle, train = inline6
    excitation = tv.engine_excitation(cycle, model)
    modes = tv.natural_modes(train.inertia, train.stiffness)
    crossings = tv.critical_speeds(modes.frequency[1:2], excitation.orders, 50.0, 800.0)
    speeds = np.array([s for _m, _n, s in crossings])
    assert speeds.size >= 5
    result = tv.forced_response(train, excitation, speeds)
    np.testing.assert_allclose(result.input_power, result.total_dissipated_power, rtol=1e-8)
    assert np.all(result.damper_power <= result.total_dissipated_power * (1 + 1e-12))
    assert np.all(result.damper_power > 0)


def test_firing_phase_of_each_cylinder(inline6: tuple) -> None:
    """The harmonic of order n of cylinder c is the first cylinder's times e^{-i n (t_c-t_1)}
    (equal cylinders): the whole-engine cycle phases each cylinder by its firing angle."""
    model, cycle, _ = inline6
    ex = tv.engine_excitation(cycle, model)
    first = model.firing_order[0] - 1
    for c in range(model.cylinders):
        shift = np.exp(-1j * ex.orders * (ex.fire_angle[c] - ex.fire_angle[first]))
        np.testing.assert_allclose(ex.gas[c], ex.gas[first] * shift, atol=1e-9 * 100)
        np.testing.assert_allclose(ex.inertia[c], ex.inertia[first] * shift, atol=1e-9 * 100)
    # firing 1-5-3-6-2-4 every 120 deg
    order_angles = np.degrees(ex.fire_angle[np.array(model.firing_order) - 1])
    np.testing.assert_allclose(np.diff(order_angles), 120.0, atol=1e-9)


def test_inline6_phase_diagram(inline6: tuple) -> None:
    """Inline-6, 4-stroke, 1-5-3-6-2-4: cylinder c fires at t_c = 0, 480, 240, 600, 120, 360
    deg (cylinders 1..6). At order n its phase is n t_c. For n a multiple of 3, n * 120 deg
    is a multiple of 360 deg: all six in phase (the major orders 3, 6, 9, 12: vector sum 6);
    for other orders the six phases are spread evenly in groups and cancel (sum 0) when
    every throw swings alike. With the 2-node-like antisymmetric shape
    beta = (1, 0.6, 0.2, -0.2, -0.6, -1), order 1.5 puts cylinders 1, 2, 3 at 0 deg and 4, 5,
    6 at 180 deg: |sum| = (1 + 0.6 + 0.2) * 2 = 3.6 (the same at 4.5 and 7.5); the major
    orders give sum(beta) = 0."""
    model, cycle, _ = inline6
    ex = tv.engine_excitation(cycle, model)
    orders = ex.orders
    uniform = tv.order_vector_sum(ex.fire_angle, orders)
    major = np.isclose(np.mod(orders, 3.0), 0.0)
    np.testing.assert_allclose(uniform[major], 6.0, rtol=1e-12)
    np.testing.assert_allclose(uniform[~major], 0.0, atol=1e-12)
    beta = np.array([1.0, 0.6, 0.2, -0.2, -0.6, -1.0])
    weighted = tv.order_vector_sum(ex.fire_angle, orders, beta)
    for n in (1.5, 4.5, 7.5):
        assert weighted[np.isclose(orders, n)][0] == pytest.approx(3.6, rel=1e-12)
    np.testing.assert_allclose(weighted[major], 0.0, atol=1e-12)
    # the engine's total torque carries only the major orders (equal cylinders)
    total = np.abs(ex.gas.sum(axis=0) + ex.inertia.sum(axis=0))
    single = np.abs(ex.gas[0] + ex.inertia[0])
    np.testing.assert_allclose(total[major], 6 * single[major], rtol=1e-9)
    assert np.all(total[~major] < 1e-9 * single.max())


def test_order_harmonics_of_a_known_signal() -> None:
    theta = np.linspace(-2 * math.pi, 2 * math.pi, 1440, endpoint=False)
    signal = 3.0 + 2.0 * np.cos(1.5 * theta - 0.3) + 0.5 * np.sin(4 * theta)
    got = tv.order_harmonics(theta, signal, [0.5, 1.5, 4.0])
    np.testing.assert_allclose(got, [0.0, 2.0 * np.exp(-0.3j), -0.5j], atol=1e-12)


def test_reciprocating_share_series() -> None:
    """mean(s'^2) = r^2/2 (1 + lambda^2/4) + O(lambda^4) (s' = r(sin a + lambda/2 sin 2a))."""
    model = as_model("inline6")
    lam = model.crank_radius / model.rod_length
    base = np.asarray(model.throw_rotating_mass) * model.crank_radius**2
    share = tv.throw_inertias(model) - base
    expected = model.reciprocating_mass[0] * model.crank_radius**2 / 2 * (1 + lam**2 / 4)
    np.testing.assert_allclose(share, expected, rtol=lam**4)
    given = tv.throw_inertias(model, 0.01)
    np.testing.assert_allclose(given - 0.01, share, rtol=1e-12)


def test_carter_limits() -> None:
    """Carter's equivalent length by hand: D_j = D_p = 60 mm, l_j = l_p = 30 mm, h = 20 mm,
    w = 90 mm, r = 45 mm: L_e = 0.030 + 0.016 + 0.0225 + 1.5 * 0.045 * 0.06^4 / (0.02 * 0.09^3)
    (an empirical approximation, checked here only as written)."""
    d, r = 0.060, 0.045
    length = 0.030 + 0.8 * 0.020 + 0.75 * 0.030 + 1.5 * r * d**4 / (0.020 * 0.090**3)
    k = tv.carter_stiffness(d, d, 0.030, 0.030, 0.020, 0.090, r, 80e9)
    assert k == pytest.approx(80e9 * math.pi * d**4 / (32 * length), rel=1e-12)
    hollow = tv.carter_stiffness(d, d, 0.030, 0.030, 0.020, 0.090, r, 80e9, 0.02, 0.02)
    assert hollow < k
    with pytest.raises(InputError, match="journal_bore"):
        tv.carter_stiffness(d, d, 0.030, 0.030, 0.020, 0.090, r, 80e9, journal_bore=0.07)


def test_critical_speeds_and_bad_input() -> None:
    found = tv.critical_speeds([0.0, 1000.0, 3000.0], [1.0, 2.0, 3.0], 300.0, 1500.0)
    assert found == [
        (1, 3.0, 1000.0 / 3),
        (1, 2.0, 500.0),
        (1, 1.0, 1000.0),
        (2, 3.0, 1000.0),
        (2, 2.0, 1500.0),
    ]
    with pytest.raises(InputError, match="load_stiffness"):
        tv.crank_train([0.01, 0.01], 1e5, 0.01, 1e5, 0.1, 1e5, load_inertia=0.5)
    with pytest.raises(InputError, match="stiffness"):
        tv.chain_matrices([1.0, 2.0, 3.0], [1.0])
    with pytest.raises(InputError, match="inertia"):
        tv.natural_modes([1.0, float("nan")], [1.0])
    with pytest.raises(InputError, match="damper_stiffness"):
        tv.crank_train([0.01], 1e5, 0.01, 1e5, 0.1, 1e5, damper_inertia=0.01)


def test_the_damper_lowers_the_front_end_at_the_first_mode(inline6: tuple) -> None:
    model, cycle, train = inline6
    excitation = tv.engine_excitation(cycle, model)
    bare = tv.crank_train(
        tv.throw_inertias(model), train.stiffness[2], 0.014, train.stiffness[1], 0.15,
        train.stiffness[-1], shaft_damping_ratio=0.02,
    )  # fmt: skip
    speeds = np.linspace(1500, 7000, 300) * math.pi / 30
    with_damper = tv.forced_response(train, excitation, speeds)
    without = tv.forced_response(bare, excitation, speeds)
    twist_d = np.abs(with_damper.amplitude[..., train.front_index] - with_damper.amplitude[..., -1])
    twist_b = np.abs(without.amplitude[..., bare.front_index] - without.amplitude[..., -1])
    assert twist_d.sum(axis=1).max() < 0.7 * twist_b.sum(axis=1).max()


def test_opentorsion_gives_the_same_frequencies(inline6: tuple) -> None:
    """openTorsion (optional; evaluated in docs/torsional.md) on the same chain."""
    ot = pytest.importorskip("opentorsion")
    _, _, train = inline6
    shafts = [ot.Shaft(i, i + 1, k=float(k), I=0.0) for i, k in enumerate(train.stiffness)]
    disks = [ot.Disk(i, float(j)) for i, j in enumerate(train.inertia)]
    lam, _vectors = ot.Assembly(shafts, disk_elements=disks).undamped_modal_analysis()
    theirs = np.sort(np.sqrt(np.abs(lam.real)))
    ours = tv.natural_modes(train.inertia, train.stiffness).frequency
    np.testing.assert_allclose(theirs[1:], ours[1:], rtol=1e-8)
    assert theirs[0] < 1e-3 * ours[1]


def test_forced_response_against_time_integration(inline6: tuple) -> None:
    """Second method: integrate M th'' + C th' + K th = Re sum_n F_n e^{i n w t} in time
    (scipy solve_ivp, from rest, eight cycles until the transient has died out) and compare
    the twist front end to flywheel over the last cycle with the harmonic solution (the
    rigid-body drift a free chain keeps from its start cancels in a twist)."""
    from scipy.integrate import solve_ivp

    model, cycle, _ = inline6
    k = tv.carter_stiffness(0.060, 0.050, 0.025, 0.025, 0.020, 0.090, model.crank_radius)
    train = tv.crank_train(tv.throw_inertias(model), k, 0.010, k, 0.15, k, shaft_damping_ratio=0.05)
    excitation = tv.engine_excitation(cycle, model, highest_order=9.0)
    speed = 3500 * math.pi / 30
    result = tv.forced_response(train, excitation, [speed])
    m, kk, c = tv.chain_matrices(train.inertia, train.stiffness, train.damping)
    force = np.zeros((train.inertia.size, excitation.orders.size), dtype=complex)
    force[train.throw_index] = excitation.throw_torque(speed)
    orders = excitation.orders
    m_inv = 1.0 / np.diag(m)
    n_dof = train.inertia.size

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        q, v = y[:n_dof], y[n_dof:]
        f = np.real(force @ np.exp(1j * orders * speed * t))
        return np.concatenate([v, m_inv * (f - kk @ q - c @ v)])

    period = 4 * math.pi / speed  # one four-stroke cycle
    t_last = np.linspace(7 * period, 8 * period, 801)
    solution = solve_ivp(
        rhs, (0.0, 8 * period), np.zeros(2 * n_dof), t_eval=t_last, rtol=1e-9, atol=1e-12,
        method="DOP853",
    )  # fmt: skip
    assert solution.success
    flywheel = train.throw_index[-1] + 1
    twist_time = solution.y[train.front_index] - solution.y[flywheel]
    x = result.amplitude[0]
    twist_harm = np.real(
        (x[:, train.front_index] - x[:, flywheel]) @ np.exp(1j * np.outer(orders, speed * t_last))
    )
    scale = np.abs(twist_harm).max()
    assert np.abs(twist_time - twist_harm).max() < 1e-3 * scale
    peak = tv.synthesised_peak((x[:, train.front_index] - x[:, flywheel])[None, :], orders)[0]
    assert peak == pytest.approx(np.abs(twist_time).max(), rel=2e-3)


def test_holzer_residual_vanishes_at_the_natural_frequencies(inline6: tuple) -> None:
    """Second method for a many-mass chain: Holzer's table (Den Hartog 1956, Sec. 5.2; Ker
    Wilson 1956). Start with a twist of 1 at the first mass; at w^2 each mass adds
    J_i w^2 th_i to the shaft torque and the next twist is th_i - torque/k_i; the torque
    left after the last mass is zero at a natural frequency only."""
    _, _, train = inline6
    j, k = train.inertia, train.stiffness

    def residual(omega: float) -> float:
        theta, torque = 1.0, 0.0
        for i in range(j.size):
            torque += j[i] * omega**2 * theta
            if i < k.size:
                theta -= torque / k[i]
        return torque

    modes = tv.natural_modes(j, k)
    scale = float(np.sum(j)) * modes.frequency[-1] ** 2
    for omega in modes.frequency[1:]:
        assert abs(residual(omega)) < 1e-8 * scale
        # and it changes sign across each natural frequency
        assert residual(omega * 0.999) * residual(omega * 1.001) < 0


def _permuted_throws(model, order):  # type: ignore[no-untyped-def]
    """The same engine with its throws listed in ``order`` (cylinders unchanged)."""
    import dataclasses

    order = np.asarray(order)
    new_index = np.argsort(order)  # old throw t is listed at new_index[t]
    return dataclasses.replace(
        model,
        throw_angle=np.asarray(model.throw_angle)[order],
        throw_position=np.asarray(model.throw_position)[order],
        throw_rotating_mass=np.asarray(model.throw_rotating_mass)[order],
        cylinder_throw=new_index[np.asarray(model.cylinder_throw)],
    )


def test_w12_from_vr_banks_has_one_throw_mass_per_plane() -> None:
    """w12-vw lists its 12 throws bank by bank at six axial positions (two per plane): the
    chain has six throw masses, each the sum of its two throws' inertias, in axial order,
    and every cylinder drives its plane's mass."""
    model = as_model("w12-vw")
    station, names = tv.crank_stations(model)
    y = np.asarray(model.throw_position)
    assert np.unique(station).size == 6
    for s in range(6):
        assert np.ptp(y[station == s]) < 1e-9
    assert np.all(np.diff([y[station == s][0] for s in range(6)]) > 0), "front to rear"
    assert names[0] == "throws 1+7"
    inertia = tv.throw_inertias(model)
    assert inertia.size == 6
    lam = model.crank_radius / model.rod_length
    share = model.reciprocating_mass[0] * model.crank_radius**2 / 2 * (1 + lam**2 / 4)
    rotating = np.asarray(model.throw_rotating_mass) * model.crank_radius**2
    pistons = np.bincount(np.asarray(model.cylinder_throw), minlength=12)
    by_hand = np.bincount(station, weights=rotating + pistons * share)
    np.testing.assert_allclose(inertia, by_hand, rtol=lam**4)
    train = tv.crank_train(inertia, 5e5, 0.01, 5e5, 0.2, 5e5, throw_names=names)
    assert train.throw_index.size == 6
    assert [train.names[i] for i in train.throw_index] == list(names)
    assert train.stiffness.size == 7  # front, 5 throw-to-throw gaps, flywheel


def test_throws_listed_out_of_order_give_the_same_chain(inline6: tuple) -> None:
    """The inline-6 with its throws listed 4, 1, 6, 2, 5, 3: the same inertias, natural
    frequencies and throw torques as in axial order."""
    model, cycle, _ = inline6
    shuffled = _permuted_throws(model, [3, 0, 5, 1, 4, 2])
    assert tv.crank_stations(shuffled)[1] == (
        "throw 2",
        "throw 4",
        "throw 6",
        "throw 1",
        "throw 5",
        "throw 3",
    )
    np.testing.assert_allclose(tv.throw_inertias(shuffled), tv.throw_inertias(model), rtol=1e-12)
    k = 4e5
    trains = [tv.crank_train(tv.throw_inertias(m), k, 0.01, k, 0.15, k) for m in (model, shuffled)]
    modes = [tv.natural_modes(t.inertia, t.stiffness).frequency for t in trains]
    np.testing.assert_allclose(modes[1], modes[0], rtol=1e-10)
    ex = tv.engine_excitation(cycle, model)
    ex_shuffled = tv.engine_excitation(cycle, shuffled)
    speed = float(cycle.speed_mean)
    np.testing.assert_allclose(
        ex_shuffled.throw_torque(speed), ex.throw_torque(speed), atol=1e-9 * np.abs(ex.gas).max()
    )


def test_v8_one_throw_per_plane_is_unchanged() -> None:
    """A V8 (two cylinders on each of four pins, one throw per plane): one mass per throw,
    the throw with its two pistons' shares (the series of test_reciprocating_share_series)."""
    model = as_model("v8-crossplane")
    station, names = tv.crank_stations(model)
    assert station.tolist() == [0, 1, 2, 3]
    assert names == ("throw 1", "throw 2", "throw 3", "throw 4")
    lam = model.crank_radius / model.rod_length
    share = model.reciprocating_mass[0] * model.crank_radius**2 / 2 * (1 + lam**2 / 4)
    expected = np.asarray(model.throw_rotating_mass) * model.crank_radius**2 + 2 * share
    np.testing.assert_allclose(tv.throw_inertias(model), expected, rtol=lam**4)
