"""Main-bearing loads and crank bending (crankbalance.physics.main_bearings) against closed forms
(lever rule, the three-moment equation of a two-span beam, a rigid beam on equal springs,
the friction means of crankbalance.physics.friction) and a second method (beam finite elements of
the same stepped crank, crankbalance.physics.beam.element_matrices)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.physics import friction
from crankbalance.physics.beam import ShaftSection, beam_statics, element_matrices
from crankbalance.physics.main_bearings import (
    CrankLoads,
    CrankSection,
    CrankStiffness,
    bearing_friction,
    continuous_beam_reactions,
    crank_loads,
    crank_planes,
    crank_stiffness,
    default_bearing_positions,
    main_bearing_loads,
    uniform_stiffness,
)

RNG = np.random.default_rng(18)
ANGLE = np.linspace(0.0, 4 * np.pi, 72, endpoint=False)


def _random_forces(shape: tuple[int, ...], scale: float = 1e4) -> np.ndarray:
    return scale * (RNG.standard_normal(shape) + 1j * RNG.standard_normal(shape))


def _inline4_loads(
    with_counterweights: bool = True,
) -> tuple[object, np.ndarray, np.ndarray, CrankStiffness]:
    """An inline-4-like crank: pitch 92 mm, webs at +-23 mm, random pin forces."""
    y = (np.arange(4) - 1.5) * 0.092
    phi = np.radians([0.0, 180.0, 180.0, 0.0])
    cw = {}
    if with_counterweights:
        throw = np.repeat(np.arange(4), 2)
        side = np.tile([-1.0, 1.0], 4)
        cw = dict(
            counterweight_mass=np.full(8, 0.4),
            counterweight_radius=0.04,
            counterweight_direction=phi[throw] + np.pi,
            counterweight_position=y[throw] + side * 0.023,
            counterweight_throw=throw,
        )
    speed = 600.0 + 20 * np.sin(2 * ANGLE)
    loads = crank_loads(
        ANGLE,
        _random_forces((4, ANGLE.size)),
        phi,
        y,
        np.full(4, 0.9),
        0.043,
        speed,
        acceleration=4000 * np.cos(2 * ANGLE),
        **cw,
    )
    bearings = default_bearing_positions(y, 0.04)
    section = CrankSection(0.055, 0.045, 0.017, 0.09)
    stiffness = crank_stiffness(y, 0.023, 0.043, section, bearings[0], bearings[-1])
    return loads, bearings, y, stiffness


# ------------------------------------------------------------------ closed forms


@pytest.mark.parametrize("model", ["determinate", "indeterminate"])
def test_single_throw_lever_rule(model: str) -> None:
    """One throw between two bearings: the reactions by the lever rule, exactly, and the
    bending moment at the pin R_left * a."""
    span, a = 0.12, 0.05
    force = _random_forces((1, 5))
    loads = crank_loads(ANGLE[:5], force, [0.0], [a], [0.0], 0.04, 0.0)
    stiffness = uniform_stiffness(0.0, span, 2e4)
    result = main_bearing_loads(loads, [0.0, span], [a], model, stiffness)
    np.testing.assert_allclose(result.load[0], force[0] * (span - a) / span, rtol=1e-12)
    np.testing.assert_allclose(result.load[1], force[0] * a / span, rtol=1e-12)
    np.testing.assert_allclose(
        result.pin_moment[0], -force[0] * (span - a) / span * a, rtol=1e-12, atol=1e-9
    )
    np.testing.assert_allclose(result.journal_moment, 0.0, atol=1e-9)


def test_two_bearings_indeterminate_equals_determinate() -> None:
    """With two bearings the continuous beam is statically determinate: both models agree
    whatever the stiffness (elastic bearings included)."""
    y = np.array([-0.02, 0.03])
    loads = crank_loads(
        ANGLE, _random_forces((2, ANGLE.size)), [0.0, 2.0], y, [0.5, 0.7], 0.04, 500.0
    )
    bearings = [-0.06, 0.07]
    det = main_bearing_loads(loads, bearings, y, "determinate")
    for k in (None, 1e6, 1e9):
        ind = main_bearing_loads(
            loads,
            bearings,
            y,
            "indeterminate",
            uniform_stiffness(-0.06, 0.07, 5e3),
            bearing_stiffness=k,
        )
        np.testing.assert_allclose(ind.load, det.load, rtol=1e-9, atol=1e-9 * 1e4)


@pytest.mark.parametrize("a_over_l", [0.25, 0.5, 0.8])
def test_two_span_beam_three_moment_equation(a_over_l: float) -> None:
    """Continuous beam on three equal-spaced rigid supports, point load P at a in span 1:
    Clapeyron's three-moment equation gives M_B = -P a (L^2 - a^2) / (4 L^2) (Gere and
    Timoshenko, Mechanics of Materials), and the reactions from the spans' statics."""
    length = 0.1
    a = a_over_l * length
    force = np.array([[-1000.0 + 250.0j]])
    stiffness = uniform_stiffness(0.0, 2 * length, 3e4)
    reactions = continuous_beam_reactions([0.0, length, 2 * length], [a], force, stiffness)
    m = a * (length**2 - a**2) / (4 * length**2)  # |M_B| per unit load
    share_a = (length - a) / length - m / length
    share_c = -m / length
    expected = -force[0, 0] * np.array([share_a, 1 - share_a - share_c, share_c])
    np.testing.assert_allclose(
        reactions[:, 0], expected, rtol=1e-12, err_msg="three-moment equation reactions"
    )
    loads = crank_loads([0.0], force, [0.0], [a], [0.0], 0.04, 0.0)
    result = main_bearing_loads(loads, [0.0, length, 2 * length], [a], "indeterminate", stiffness)
    np.testing.assert_allclose(result.journal_moment[1, 0], force[0, 0] * m, rtol=1e-12)


def test_uniform_beam_matches_beam_statics() -> None:
    """With one EI the force method equals beam.beam_statics (Euler-Bernoulli), rigid and
    elastic bearings, four bearings and scattered loads: two codes, one answer."""
    xb = np.array([0.01, 0.1, 0.22, 0.3])
    xf = RNG.uniform(0.0, 0.32, 6)
    f = _random_forces((6,))
    stiffness = uniform_stiffness(0.0, 0.32, 8e3)
    for k in (None, 3e7):
        mine = continuous_beam_reactions(xb, xf, f[:, None], stiffness, k)[:, 0]
        theirs, _, _ = beam_statics(0.32, 8e3, xb, xf, f, [0.0], bearing_stiffness=k)
        np.testing.assert_allclose(mine, theirs, rtol=1e-9, atol=1e-9 * abs(f).max())


def test_soft_bearings_tend_to_rigid_beam_on_springs() -> None:
    """Bearings far softer than the crank: the crank moves as a rigid body on equal springs,
    R_k = -(F/B + M (y_k - ybar) / sum (y - ybar)^2) (closed form)."""
    loads, bearings, y, stiffness = _inline4_loads()
    soft = continuous_beam_reactions(bearings, loads.position, loads.load, stiffness, 1.0)
    total = loads.load.sum(axis=0)
    ybar = bearings.mean()
    moment = ((loads.position - ybar)[:, None] * loads.load).sum(axis=0)
    lever = bearings - ybar
    rigid = -(total / bearings.size + np.outer(lever, moment) / np.sum(lever**2))
    np.testing.assert_allclose(soft, rigid, rtol=1e-6, atol=1e-6 * np.abs(total).max())


def test_stiff_bearings_tend_to_rigid_bearings() -> None:
    loads, bearings, y, stiffness = _inline4_loads()
    rigid = continuous_beam_reactions(bearings, loads.position, loads.load, stiffness)
    stiff = continuous_beam_reactions(bearings, loads.position, loads.load, stiffness, 1e16)
    np.testing.assert_allclose(stiff, rigid, rtol=1e-6, atol=1e-6 * np.abs(rigid).max())


@pytest.mark.parametrize(
    ("model", "bearing_k"),
    [("determinate", None), ("indeterminate", None), ("indeterminate", 5e8)],
)
def test_force_and_moment_balance(model: str, bearing_k: float | None) -> None:
    """The bearing loads add up to the loads on the crank at every angle, and their moment
    about any point equals the loads' moment (equilibrium of the whole crank)."""
    loads, bearings, y, stiffness = _inline4_loads()
    result = main_bearing_loads(loads, bearings, y, model, stiffness, bearing_k)
    scale = np.abs(loads.load).max()
    np.testing.assert_allclose(result.load.sum(axis=0), loads.total, atol=1e-9 * scale)
    for y0 in (-0.3, 0.0, 0.117):
        bearing_moment = ((bearings - y0)[:, None] * result.load).sum(axis=0)
        load_moment = ((loads.position - y0)[:, None] * loads.load).sum(axis=0)
        np.testing.assert_allclose(bearing_moment, load_moment, atol=1e-9 * scale)


def test_determinate_crank_is_hinged_at_the_journals() -> None:
    loads, bearings, y, _ = _inline4_loads()
    result = main_bearing_loads(loads, bearings, y, "determinate")
    assert np.abs(result.journal_moment).max() < 1e-9 * np.abs(loads.load).max()
    assert np.all(result.max_pin_moment > 0)


def test_rotating_mass_load_and_tangential_inertia() -> None:
    """A rotating mass loads the crank with m r (w^2 - i alpha) e^{i(theta + phi)}: outward,
    and backward (against the rotation) when the crank speeds up."""
    theta = np.array([0.0, 0.7])
    loads = crank_loads(
        theta, np.zeros((1, 2)), [0.3], [0.0], [2.0], 0.05, [100.0, 200.0], [0.0, 500.0]
    )
    expected = 2.0 * 0.05 * np.array([1e4, 4e4 - 500j]) * np.exp(1j * (theta + 0.3))
    np.testing.assert_allclose(loads.load[0], expected, rtol=1e-14)


def test_counterweights_that_balance_their_throw_unload_its_bearings() -> None:
    """A throw whose two counterweights carry its rotating mass (m_cw r_cw = m r / 2 each,
    opposite the pin, symmetric webs) puts nothing on its bearings in either model."""
    m, r, rc = 1.2, 0.04, 0.03
    loads = crank_loads(
        ANGLE,
        np.zeros((1, ANGLE.size)),
        [0.4],
        [0.0],
        [m],
        r,
        700.0,
        counterweight_mass=[m * r / (2 * rc)] * 2,
        counterweight_radius=rc,
        counterweight_direction=[0.4 + np.pi] * 2,
        counterweight_position=[-0.02, 0.02],
        counterweight_throw=[0, 0],
    )
    scale = m * r * 700.0**2
    for model in ("determinate", "indeterminate"):
        result = main_bearing_loads(
            loads, [-0.05, 0.05], [0.0], model, uniform_stiffness(-0.05, 0.05, 1e4)
        )
        assert np.abs(result.load).max() < 1e-12 * scale
        assert np.abs(result.pin_moment).max() > 1e-3 * scale * 0.02  # the crank still bends


def test_default_bearings() -> None:
    y = (np.arange(4) - 1.5) * 0.092
    np.testing.assert_allclose(
        default_bearing_positions(y, 1.0), [-0.184, -0.092, 0.0, 0.092, 0.184], atol=1e-15
    )
    np.testing.assert_allclose(default_bearing_positions([0.01], 0.03), [-0.02, 0.04])


@pytest.mark.parametrize("model", ["determinate", "indeterminate"])
def test_coplanar_throws_load_their_plane_together(model: str) -> None:
    """A W-like crank, two throws in each of three planes (listed bank by bank, so not in
    axial order): the default bearings, the stepped beam and the bearing loads are those
    of the three-throw crank whose throws carry the two coplanar throws' forces summed by
    hand; and the loads balance the crank (force and moment)."""
    y3 = np.array([-0.046, 0.0, 0.046])
    y6 = np.concatenate([y3, y3])
    phi = np.radians([0.0, 120.0, 240.0, 72.0, 192.0, 312.0])
    loads = crank_loads(
        ANGLE, _random_forces((6, ANGLE.size)), phi, y6, np.full(6, 0.5), 0.04, 600.0
    )
    planes, plane_of_throw = crank_planes(y6)
    np.testing.assert_allclose(planes, y3, atol=1e-15)
    assert plane_of_throw.tolist() == [0, 1, 2, 0, 1, 2]
    bearings = default_bearing_positions(y6, 0.04)
    np.testing.assert_allclose(bearings, [-0.069, -0.023, 0.023, 0.069], atol=1e-15)
    section = CrankSection(0.055, 0.045, 0.010, 0.09)
    stiffness = crank_stiffness(y6, 0.015, 0.04, section, bearings[0], bearings[-1])
    stiffness3 = crank_stiffness(y3, 0.015, 0.04, section, bearings[0], bearings[-1])
    np.testing.assert_allclose(stiffness.edges, stiffness3.edges)
    np.testing.assert_allclose(stiffness.stiffness, stiffness3.stiffness)
    summed = CrankLoads(
        angle=loads.angle,
        position=y3,
        throw=np.arange(3),
        kind=("throw",) * 3,
        load=loads.load[:3] + loads.load[3:],
    )
    result = main_bearing_loads(loads, bearings, y6, model, stiffness)
    by_hand = main_bearing_loads(summed, bearings, y3, model, stiffness3)
    scale = np.abs(loads.load).max()
    np.testing.assert_allclose(result.load, by_hand.load, atol=1e-9 * scale)
    np.testing.assert_allclose(result.load.sum(axis=0), loads.total, atol=1e-9 * scale)
    for y0 in (-0.3, 0.0, 0.117):
        bearing_moment = ((bearings - y0)[:, None] * result.load).sum(axis=0)
        load_moment = ((loads.position - y0)[:, None] * loads.load).sum(axis=0)
        np.testing.assert_allclose(bearing_moment, load_moment, atol=1e-9 * scale)


# ------------------------------------------------------------------ second method: FE


def _fe_reactions(
    bearings: np.ndarray,
    positions: np.ndarray,
    loads: np.ndarray,
    stiffness: CrankStiffness,
    bearing_k: float | None,
    per_interval: int = 4,
) -> np.ndarray:
    """Reactions from Euler-Bernoulli beam elements (beam.element_matrices), nodes at every
    stiffness step, bearing and load, each interval cut in ``per_interval`` elements."""
    keys = np.unique(np.concatenate([stiffness.edges, bearings, positions]))
    pieces = [
        np.linspace(a, b, per_interval, endpoint=False)
        for a, b in zip(keys[:-1], keys[1:], strict=True)
    ]
    nodes = np.concatenate([*pieces, keys[-1:]])
    n = nodes.size
    k_global = np.zeros((2 * n, 2 * n))
    for e in range(n - 1):
        h = nodes[e + 1] - nodes[e]
        ei = float(stiffness.at(0.5 * (nodes[e] + nodes[e + 1])))
        diameter = (64 * ei / (math.pi * 210e9)) ** 0.25  # the section with this EI
        ke, _ = element_matrices(h, ShaftSection(diameter), "euler-bernoulli")
        k_global[2 * e : 2 * e + 4, 2 * e : 2 * e + 4] += ke
    at = {float(x): i for i, x in enumerate(nodes)}
    f = np.zeros((2 * n, loads.shape[1]), dtype=complex)
    for x, p in zip(positions, loads, strict=True):
        f[2 * at[float(x)]] += p
    rows = [2 * at[float(x)] for x in bearings]
    if bearing_k is None:
        free = np.setdiff1d(np.arange(2 * n), rows)
        u = np.zeros_like(f)
        kff = k_global[np.ix_(free, free)]
        u[free] = np.linalg.solve(kff, f[free].real) + 1j * np.linalg.solve(kff, f[free].imag)
        return (k_global @ u - f)[rows]
    k_global[rows, rows] += bearing_k
    u = np.linalg.solve(k_global, f.real) + 1j * np.linalg.solve(k_global, f.imag)
    return -bearing_k * u[rows]


@pytest.mark.parametrize("bearing_k", [None, 2e8])
def test_stepped_crank_against_finite_elements(bearing_k: float | None) -> None:
    """The force method on the stepped crank (journals, webs, pins) against a beam
    finite-element model of the same beam: Hermite elements are exact for point loads at
    nodes, so the two agree to round-off."""
    loads, bearings, y, stiffness = _inline4_loads()
    assert np.unique(stiffness.stiffness).size == 3  # journal, web, pin
    mine = continuous_beam_reactions(bearings, loads.position, loads.load, stiffness, bearing_k)
    fe = _fe_reactions(bearings, loads.position, loads.load, stiffness, bearing_k)
    np.testing.assert_allclose(mine, fe, rtol=1e-7, atol=1e-7 * np.abs(fe).max())


def test_stiffness_profile_of_a_throw() -> None:
    section = CrankSection(0.055, 0.045, 0.017, 0.09)
    profile = crank_stiffness([0.0], 0.023, 0.043, section, -0.05, 0.05)
    journal = section.youngs_modulus * math.pi * 0.055**4 / 64
    pin = section.youngs_modulus * math.pi * 0.045**4 / 64
    web = section.web_stiffness(0.043)
    np.testing.assert_allclose(
        profile.at([-0.045, -0.023, 0.0, 0.023, 0.045]), [journal, web, pin, web, journal]
    )
    np.testing.assert_allclose(
        profile.edges, [-0.05, -0.0315, -0.0145, 0.0145, 0.0315, 0.05], atol=1e-15
    )
    assert 0 < web < journal


# ------------------------------------------------------------------ friction


def test_coulomb_friction_is_the_arithmetic_mean_load() -> None:
    """A constant plus a rotating load: the cycle mean of mu |F| d/2 equals
    friction.unbalanced_friction_torque with the arithmetic mean (elliptic integral)."""
    theta = np.linspace(0, 2 * np.pi, 720, endpoint=False)
    load = (300.0 + 100.0 * np.exp(1j * theta))[None, :]
    result = bearing_friction(load, 500.0, 0.05, 0.01)
    expected = friction.unbalanced_friction_torque(0.01, 300.0, 100.0, 0.05, "arithmetic")
    np.testing.assert_allclose(result.coulomb_torque[0], expected, rtol=1e-10)
    np.testing.assert_allclose(result.coulomb_power[0], expected * 500.0, rtol=1e-10)
    assert result.petroff_torque is None


def test_equivalent_load_is_the_cubic_mean() -> None:
    theta = np.linspace(0, 2 * np.pi, 720, endpoint=False)
    force = (300.0 + 100.0 * np.exp(1j * theta))[None, :]
    loads = crank_loads(theta, force, [0.0], [0.0], [0.0], 0.04, 0.0)
    result = main_bearing_loads(loads, [-0.05, 0.05], [0.0], "determinate")
    expected = friction.mean_equivalent_load(150.0, 50.0, "cubic")
    np.testing.assert_allclose(result.equivalent_load, expected, rtol=1e-10)
    np.testing.assert_allclose(result.max_load, 200.0)


def test_petroff_friction_per_bearing() -> None:
    result = bearing_friction(np.ones((3, 4)), 600.0, 0.05, 0.005, 0.01, 0.02, 3e-5)
    expected = friction.petroff_torque(0.01, 0.05, 0.02, 3e-5, 600.0)
    np.testing.assert_allclose(result.petroff_torque, [expected] * 3)
    with pytest.raises(InputError, match="clearance"):
        bearing_friction(np.ones((3, 4)), 600.0, 0.05, 0.005, 0.01, 0.02)


# ------------------------------------------------------------------ bad input


def test_bad_input_names_the_field() -> None:
    loads, bearings, y, stiffness = _inline4_loads()
    with pytest.raises(InputError, match="bearing_positions.*each side"):
        main_bearing_loads(loads, bearings[1:], y, "determinate")
    with pytest.raises(InputError, match="bearing_stiffness"):
        main_bearing_loads(loads, bearings, y, "determinate", bearing_stiffness=1e8)
    with pytest.raises(InputError, match="stiffness"):
        main_bearing_loads(loads, bearings, y, "indeterminate")
    with pytest.raises(InputError, match="model"):
        main_bearing_loads(loads, bearings, y, "rigid")  # type: ignore[arg-type]
    with pytest.raises(InputError, match="throw_force"):
        crank_loads(ANGLE, np.zeros((3, 4)), [0.0], [0.0], [1.0], 0.04, 100.0)
    with pytest.raises(InputError, match="web_thickness"):
        crank_stiffness(y, 0.023, 0.043, CrankSection(0.05, 0.04, 0.05, 0.09), -0.2, 0.2)
    with pytest.raises(InputError, match="web_thickness"):
        crank_stiffness(y, 0.04, 0.043, CrankSection(0.05, 0.04, 0.03, 0.09), -0.2, 0.2)
    with pytest.raises(InputError, match="bearing_positions"):
        main_bearing_loads(loads, [0.0, 0.0, 0.1], y, "indeterminate", stiffness)
    with pytest.raises(InputError, match="bearing_positions"):
        main_bearing_loads(loads, [-0.5, 0.0, 0.1], y, "indeterminate", stiffness)
    with pytest.raises(InputError, match="journal_diameter"):
        CrankSection(0.0, 0.04, 0.02, 0.09)


# ------------------------------------------------------------------ whole engine


@pytest.mark.parametrize("engine", ["inline4", "v8-crossplane", "boxer2"])
@pytest.mark.parametrize("model", ["determinate", "indeterminate"])
def test_bearing_and_liner_forces_add_up_to_the_shaking_force(engine: str, model: str) -> None:
    """Without gas, at constant speed, the forces the crank train puts on the block are the
    main-bearing loads plus the pistons' side forces on the liners; they must add up to the
    free inertia force of shaking.exact_time_domain plus the rotating masses and the
    counterweights (balancing.point_mass_history), and the same for the couple: the
    rod-force route (engine_cycle_all, crank loads, beam reactions) against the direct sum
    of the masses' accelerations."""
    from crankbalance.physics.balancing import point_mass_history
    from crankbalance.physics.engine_cycle_all import engine_cycle_all
    from crankbalance.physics.shaking import exact_time_domain
    from crankbalance.studies.engine import balance_engine
    from crankbalance.studies.loads import _counterweight_arrays

    study = balance_engine(engine)
    m, balance = study.model, study.result
    table = (np.radians([-300.0, -100.0, 100.0, 300.0]), np.full(4, 1e5))
    cycle = engine_cycle_all(m, table, bore=0.08, crank_inertia=1.0, samples_per_revolution=90)
    theta = cycle.crank_angle
    loads = crank_loads(
        theta,
        cycle.throw_force,
        m.throw_angle,
        m.throw_position,
        m.throw_rotating_mass,
        m.crank_radius,
        m.speed,
        **_counterweight_arrays(balance),
    )
    bearings = default_bearing_positions(m.throw_position, m.crank_radius)
    stiffness = uniform_stiffness(bearings.min() - 0.1, bearings.max() + 0.1, 5e4)
    result = main_bearing_loads(loads, bearings, m.throw_position, model, stiffness)
    side = cycle.side_force_inertia  # (C, S)
    on_block = result.load.sum(axis=0) + side.sum(axis=0)
    couple_on_block = (bearings[:, None] * result.load).sum(axis=0) + (
        m.cylinder_position[:, None] * side
    ).sum(axis=0)
    recip, recip_couple = exact_time_domain(m, theta)
    rot = m.throw_rotating_mass * m.crank_radius * np.exp(1j * m.throw_angle)
    cw = balance.counterweights
    masses, mass_couple = point_mass_history(
        m.speed, theta, [(rot, m.throw_position), (cw.moments, cw.position)]
    )
    scale = np.abs(result.load).max() + np.abs(side).max()  # the size of the parts
    np.testing.assert_allclose(on_block, recip + masses, atol=1e-9 * scale)
    np.testing.assert_allclose(
        couple_on_block, recip_couple + mass_couple, atol=1e-9 * scale * np.ptp(bearings)
    )


# ------------------------------------------------------------------ bearing clearance


def test_clearance_zero_is_the_elastic_model() -> None:
    """No clearance: the ring contact is the linear elastic bearing, so the Newton
    solution on the condensed FE beam equals the force method's reactions."""
    from crankbalance.physics.main_bearings import clearance_reactions

    loads, bearings, y, stiffness = _inline4_loads()
    elastic = continuous_beam_reactions(bearings, loads.position, loads.load, stiffness, 3e8)
    ring = clearance_reactions(bearings, loads.position, loads.load, stiffness, 3e8, 0.0)
    np.testing.assert_allclose(ring, elastic, rtol=1e-7, atol=1e-7 * np.abs(elastic).max())


@pytest.mark.parametrize("lift_ratio", [0.0, 0.3, 0.8, 1.5])
def test_clearance_two_span_beam_closed_form(lift_ratio: float) -> None:
    """Two equal spans on three stiff rings of clearance c, a downward load P at mid-span
    of span 1. A and B touch at the bottom of their rings, C (which must hold the beam
    down) at the top: C is lifted 2c against the line A-B. Without C the free end would
    rise delta_C = P L^3 / (16 EI) (slope at B of the loaded span times L); the hold-down
    force falls linearly with the lift, R_C = R_C0 (1 - 2c/delta_C), and C lets go for
    2c >= delta_C, leaving the lever rule on A and B (superposition of a support
    settlement, Gere and Timoshenko)."""
    from crankbalance.physics.main_bearings import clearance_reactions

    length, ei, p = 0.1, 3e4, -1000.0
    delta_c = abs(p) * length**3 / (16 * ei)
    clearance = lift_ratio * delta_c / 2
    stiffness = uniform_stiffness(0.0, 2 * length, ei)
    support = [0.0, length, 2 * length]
    force = np.array([[p + 0j]])
    k = 1e13  # rings stiffer than the beam by far: the rigid-contact limit
    ring = clearance_reactions(support, [length / 2], force, stiffness, k, clearance)[:, 0]
    rigid = continuous_beam_reactions(support, [length / 2], force, stiffness)[:, 0]
    lever = np.array([-p / 2, -p / 2, 0.0])
    share = max(1.0 - lift_ratio, 0.0)
    expected = lever + share * (rigid - lever)
    np.testing.assert_allclose(ring, expected, atol=1e-5 * abs(p))
    assert abs(ring.imag).max() < 1e-9 * abs(p)  # a load in z stays in z


def test_clearance_equilibrium_and_unloaded_rings() -> None:
    from crankbalance.physics.main_bearings import clearance_reactions

    loads, bearings, y, stiffness = _inline4_loads()
    ring = clearance_reactions(bearings, loads.position, loads.load, stiffness, 5e8, 30e-6)
    scale = np.abs(loads.load).max()
    np.testing.assert_allclose(-ring.sum(axis=0), loads.total, atol=1e-8 * scale)
    moment = ((loads.position)[:, None] * loads.load).sum(axis=0)
    np.testing.assert_allclose(-(bearings[:, None] * ring).sum(axis=0), moment, atol=1e-8 * scale)
    # self-equilibrated loads (no net force or moment) inside the clearance: the crank
    # floats, no ring is touched, nothing is carried
    balanced = [[1.0], [-2.0], [1.0]]
    still = clearance_reactions([-0.1, 0.1], [0.0, 0.05, 0.1], balanced, stiffness, 1e8, 1e-3)
    assert np.abs(still).max() < 1e-9
    # a couple on two rings: the lever rule, R = M / span, whatever the clearance
    couple = clearance_reactions([-0.1, 0.1], [0.0, 0.05], [[1.0], [-1.0]], stiffness, 1e8, 1e-3)
    np.testing.assert_allclose(couple[:, 0], [-0.25, 0.25], rtol=1e-6)
