"""Exact slider-crank kinematics: finite differences, harmonics against the series."""

from __future__ import annotations

import numpy as np
import pytest

from crankbalance.physics.kinematics import (
    harmonic_coefficients,
    piston_acceleration,
    piston_position,
    piston_velocity,
    series_coefficients,
)


@pytest.mark.parametrize("offset", [0.0, 0.004, -0.007])
def test_velocity_and_acceleration_are_derivatives_of_position(offset: float) -> None:
    r, l, w = 0.04, 0.135, 300.0
    psi = np.linspace(0, 2 * np.pi, 73)
    h = 1e-4
    pos = lambda a: piston_position(a, r, l, offset)  # noqa: E731
    fd_v = w * (pos(psi + h) - pos(psi - h)) / (2 * h)
    fd_a = w**2 * (pos(psi + h) - 2 * pos(psi) + pos(psi - h)) / h**2
    v = piston_velocity(psi, r, l, offset, w)
    a = piston_acceleration(psi, r, l, offset, w)
    assert np.allclose(v, fd_v, rtol=0, atol=1e-6 * r * w), "central difference of the position"
    assert np.allclose(a, fd_a, rtol=0, atol=1e-4 * r * w**2), "second difference of the position"


def test_position_at_dead_centres() -> None:
    r, l = 0.04, 0.135
    assert piston_position(0.0, r, l) == pytest.approx(l + r)
    assert piston_position(np.pi, r, l) == pytest.approx(l - r)


def test_exact_harmonics_at_lambda_03() -> None:
    c = harmonic_coefficients(0.3, 8)
    assert c[1].real == pytest.approx(0.307051, abs=5e-7), "issue 2 / docs/references.md: A2(0.3)"
    assert c[3].real == pytest.approx(-0.007238, abs=5e-7), "issue 2 / docs/references.md: A4(0.3)"
    assert c[0].real == pytest.approx(1.0, abs=1e-14), "A1 = 1"
    assert np.all(np.abs(c[2::2]) < 1e-14), "no odd orders above 1 without offset"
    assert np.all(np.abs(c.imag) < 1e-14), "no sine terms without offset"


@pytest.mark.parametrize("lam", [0.15, 0.25, 0.3, 0.35])
def test_exact_harmonics_within_series_truncation(lam: float) -> None:
    c = harmonic_coefficients(lam, 6).real
    a2, a4, a6 = series_coefficients(lam)
    # the series is truncated after lambda**5: the next terms are O(lambda**7)
    tol = lam**7
    assert abs(c[1] - a2) < tol, (
        "A2 = lam + lam^3/4 + 15 lam^5/128 (Hoem and Røsholm (2016), Eq. 2.6)"
    )
    assert abs(c[3] - a4) < tol, "A4 = -(lam^3/4 + 3 lam^5/16) (Hoem and Røsholm (2016), Eq. 2.6)"
    assert abs(c[5] - a6) < tol, (
        "A6 = 9 lam^5/128 (docs/references.md erratum of Hoem and Røsholm 2016)"
    )


def test_fourier_reconstructs_the_exact_acceleration_with_offset() -> None:
    lam, eps = 0.3, 0.12
    c = harmonic_coefficients(lam, 16, eps)
    psi = np.linspace(0, 2 * np.pi, 97)
    n = np.arange(1, 17)[:, None]
    rebuilt = np.real(c[:, None] * np.exp(1j * n * psi)).sum(axis=0)
    exact = -piston_acceleration(psi, 1.0, 1 / lam, eps)
    assert np.allclose(rebuilt, exact, atol=1e-10), "Fourier series of the exact motion"


def test_batched_coefficients_match_single() -> None:
    lams = np.array([0.2, 0.25, 0.3])
    batch = harmonic_coefficients(lams, 8, np.array([0.0, 0.05, 0.1]))
    for k, lam in enumerate(lams):
        single = harmonic_coefficients(lam, 8, [0.0, 0.05, 0.1][k])
        assert np.allclose(batch[k], single, atol=1e-15)
