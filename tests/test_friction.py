"""Unit tests of crankbalance.physics.friction: each formula against a second method."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from crankbalance.errors import InputError
from crankbalance.physics import friction


def _mean_magnitude(w: float, u: float, power: float) -> float:
    value, _ = quad(
        lambda t: np.hypot(w + u * np.cos(t), u * np.sin(t)) ** power, 0, 2 * np.pi, limit=200
    )
    return (value / (2 * np.pi)) ** (1 / power)


@pytest.mark.parametrize(
    "w,u", [(25.0, 0.0), (0.0, 40.0), (25.0, 42.2), (25.0, 25.0), (25.0, 1519.9), (300.0, 12.0)]
)
def test_arithmetic_and_cubic_means_match_quadrature(w, u):
    arith = friction.mean_equivalent_load(w, u, "arithmetic")
    cubic = friction.mean_equivalent_load(w, u, "cubic")
    assert arith == pytest.approx(_mean_magnitude(w, u, 1), rel=1e-9), "elliptic closed form"
    assert cubic == pytest.approx(_mean_magnitude(w, u, 3), rel=1e-6), "cubic mean, quadrature"


def test_fm_limits_and_fit_of_cubic_mean():
    # f_m = 1 for one load alone, 0.75 for equal loads (Hoem and Røsholm (2016), Fig. 4.12)
    assert friction.mean_load_factor(10.0, 0.0) == pytest.approx(1.0)
    assert friction.mean_load_factor(0.0, 10.0) == pytest.approx(1.0)
    assert friction.mean_load_factor(10.0, 10.0) == pytest.approx(0.75)
    # the thesis' f_m is an approximation of the cubic mean: within 2 % over all ratios
    x = np.linspace(0.0, 1.0, 41)
    w, u = 100 * x, 100 * (1 - x)
    approx = friction.mean_equivalent_load(w, u)
    cubic = friction.mean_equivalent_load(w, u, "cubic")
    assert np.max(np.abs(approx / cubic - 1)) < 0.02, (
        "Hoem and Røsholm (2016), Eq. 4.14 fits the cubic mean"
    )
    # the arithmetic mean is never larger than the cubic one (power-mean inequality)
    assert np.all(friction.mean_equivalent_load(w, u, "arithmetic") <= cubic + 1e-9)


def test_friction_torque_and_back_computation_are_inverse():
    mu = friction.friction_coefficient_from_torque(0.2083, 24.98, 42.2, 0.020)
    torque = friction.unbalanced_friction_torque(mu, 24.98, 42.2, 0.020)
    assert torque == pytest.approx(0.2083, rel=1e-12)
    assert friction.friction_torque(0.5, 20.0, 0.02) == pytest.approx(0.1), (
        "Hoem and Røsholm (2016), Eq. 4.10"
    )


def test_transducer_conversion():
    # Hoem and Røsholm (2016), Fig. 5.10: 0.44 V corresponds to 0.25 N m
    assert friction.torque_from_transducer_voltage(0.44) == pytest.approx(0.25), (
        "Hoem and Røsholm (2016), Fig. 5.10"
    )


def test_petroff_against_textbook_forms():
    eta, d, length, c, w = 0.01, 0.04, 0.02, 20e-6, 600.0
    r, n = d / 2, w / (2 * np.pi)  # journal radius [m], speed [rev/s]
    # Petroff's equation as in Shigley (Eq. 12-6): f = 2 pi^2 (mu N / P)(r / c) with the
    # projected-area pressure P = W / (2 r L); torque T = f W r (any load W)
    load = 1234.0
    f = 2 * np.pi**2 * eta * n / (load / (2 * r * length)) * r / c
    assert friction.petroff_torque(eta, d, length, c, w) == pytest.approx(
        f * load * r, rel=1e-12
    ), "Petroff equation (Shigley 12-6)"
    # Heywood's form printed in Hoem and Røsholm (2016), Eq. 7.2 with N in rev/s:
    # F = pi^2 eta D^2 L N / h
    heywood = np.pi**2 * eta * d**2 * length * n / c
    assert friction.petroff_torque(eta, d, length, c, w) == pytest.approx(heywood * r, rel=1e-12), (
        "Hoem and Røsholm (2016), App. A Eq. 7.2 (Heywood) with eps = 0, N in rev/s"
    )
    # eccentricity raises the shear term by 1/sqrt(1 - eps^2) (Hoem and Røsholm (2016), Eq. 7.2)
    t0 = friction.journal_bearing_torque(eta, d, length, c, w)
    t6 = friction.journal_bearing_torque(eta, d, length, c, w, eccentricity_ratio=0.6)
    assert t6 / t0 == pytest.approx(1 / 0.8)
    # load term: c*eps*W/D*sin(phi) times r_j
    t_load = friction.journal_bearing_torque(eta, d, length, c, w, 0.6, 1000.0, np.pi / 2) - t6
    assert t_load == pytest.approx(c * 0.6 * 1000.0 / d * d / 2)


def _reynolds_squeeze_force(width, length, gap, eta, velocity, n=61):
    """Finite-difference solution of lap(p) = 12 eta v / h^3 with p = 0 on the edges."""
    from scipy.sparse import diags, identity, kron
    from scipy.sparse.linalg import spsolve

    hx, hy = width / (n + 1), length / (n + 1)
    d2 = diags([1.0, -2.0, 1.0], [-1, 0, 1], shape=(n, n))
    lap = kron(identity(n), d2) / hx**2 + kron(d2, identity(n)) / hy**2
    p = spsolve(lap.tocsc(), np.full(n * n, 12 * eta * velocity / gap**3))
    return -p.sum() * hx * hy


def test_rectangular_squeeze_film_against_finite_differences():
    eta, gap = 0.02, 50e-6
    for width, length in [(0.01, 0.01), (0.01, 0.03)]:
        fd = _reynolds_squeeze_force(width, length, gap, eta, 1.0)
        exact = friction.rectangular_squeeze_film_damping(eta, gap, length, width)
        # second-order FD with the singular corners: 1 % on this grid
        assert fd == pytest.approx(exact, rel=0.01)


def test_squeeze_film_thesis_formula_properties():
    eta, gap, z, length = 0.02, 50e-6, 0.01, 0.01
    thesis = friction.squeeze_film_damping(eta, z * length, gap, length, z)
    reynolds = friction.rectangular_squeeze_film_damping(eta, gap, length, z)
    assert thesis / reynolds == pytest.approx(3.555, rel=2e-3), (
        "Hoem and Røsholm (2016), Eq. 7.5 vs Reynolds, square"
    )
    # stiffness 3W/H equals -dW/dH of a film force W ~ H^-3 (Hoem and Røsholm (2016), Eq. 7.4)
    h = np.array([0.99, 1.01]) * gap
    force = friction.rectangular_squeeze_film_damping(eta, h, length, z) * 1e-3
    w0 = friction.rectangular_squeeze_film_damping(eta, gap, length, z) * 1e-3
    slope = -(force[1] - force[0]) / (h[1] - h[0])
    assert friction.squeeze_film_stiffness(w0, gap) == pytest.approx(slope, rel=1e-3)


@pytest.mark.parametrize(
    "call,field",
    [
        (lambda: friction.mean_equivalent_load(-1.0, 2.0), "constant_load"),
        (lambda: friction.mean_equivalent_load(1.0, 2.0, "median"), "method"),
        (lambda: friction.friction_torque(0.1, 10.0, 0.0), "journal_diameter"),
        (lambda: friction.mean_load_factor(0.0, 0.0), "constant_load + rotating_load"),
        (lambda: friction.journal_bearing_torque(0.01, 0.04, 0.02, 2e-5, 100, 1.0), "eccentricity"),
        (lambda: friction.friction_coefficient_from_torque(float("nan"), 1.0, 1.0, 0.02), "torque"),
    ],
)
def test_bad_input(call, field):
    with pytest.raises(InputError) as info:
        call()
    assert field in str(info.value)
