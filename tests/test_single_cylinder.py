"""Unit tests of crankbalance.physics.single_cylinder and the rotor helpers of
crankbalance.physics.rotor_bench."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.physics import rebalancing as rb
from crankbalance.physics import single_cylinder as sc
from crankbalance.physics.rotor_bench import (
    crankpin_overlap,
    cylinder_inertia,
    disc_inertia,
    equal_inertia_test_rotor,
    stepped_rotor_inertia,
    stroking_effect,
)

M_REC, R, L, W = 0.28212, 0.0269, 0.105, 15200 * math.pi / 30


# --- forces and the balance-factor study ------------------------------------------------


@pytest.mark.parametrize("fb", [0.0, 0.28, 0.5, 0.6375, 1.0, 1.4, 2.0])
def test_first_order_closed_forms(fb: float) -> None:
    study = sc.balance_factor_study(M_REC, R, W, fb, model="first-order")
    p = M_REC * R * W**2
    assert study.primary_force == pytest.approx(p, rel=1e-12)
    assert study.peak_resultant == pytest.approx(max(fb, abs(1 - fb)) * p, rel=1e-9), (
        "Hoem and Røsholm (2016), Fig. 4.8: peak resultant max(f_b, 1 - f_b) P"
    )
    assert study.in_line_amplitude == pytest.approx(abs(1 - fb) * p, rel=1e-9, abs=1e-9), (
        "Hoem and Røsholm (2016), Eq. 4.7: in-line amplitude (1 - f_b) P"
    )
    assert study.transverse_amplitude == pytest.approx(fb * p, rel=1e-9, abs=1e-9), (
        "Hoem and Røsholm (2016), Eq. 4.8: transverse amplitude f_b P"
    )


def test_first_order_optimum_is_half() -> None:
    study = sc.balance_factor_study(M_REC, R, W, 0.3, model="first-order")
    assert study.optimum_balance_factor == pytest.approx(0.5, abs=1e-6), (
        "Hoem and Røsholm (2016), Sec. 4.1.2: least resultant at f_b = 0.5"
    )
    assert study.optimum_peak_resultant == pytest.approx(0.5 * study.primary_force, rel=1e-8)
    np.testing.assert_allclose(
        study.sweep_peak_resultant / study.primary_force,
        sc.first_order_peak_resultant(study.sweep_balance_factor),
        rtol=1e-9,
    )


def _time_domain_forces(fb: float, t: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
    """Shaking force from positions only: second differences of the piston and the extra
    counterweight positions (independent of the kinematics module)."""

    def piston(time: np.ndarray) -> np.ndarray:
        th = W * time
        return R * np.cos(th) + np.sqrt(L**2 - (R * np.sin(th)) ** 2)

    def counterweight(time: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        th = W * time
        return -R * np.cos(th), -R * np.sin(th)  # (in-line, transverse), opposite the pin

    def d2(fun, time):
        return (
            -fun(time + 2 * h)
            + 16 * fun(time + h)
            - 30 * fun(time)
            + 16 * fun(time - h)
            - fun(time - 2 * h)
        ) / (12 * h * h)

    a_piston = d2(piston, t)
    a_cw_i = d2(lambda s: counterweight(s)[0], t)
    a_cw_t = d2(lambda s: counterweight(s)[1], t)
    # force on the frame = minus the rate of change of momentum of the moving masses
    return -M_REC * a_piston - fb * M_REC * a_cw_i, -fb * M_REC * a_cw_t


@pytest.mark.parametrize("fb", [0.0, 0.28, 0.6375])
def test_exact_forces_match_time_domain(fb: float) -> None:
    period = 2 * math.pi / W
    t = np.linspace(0, period, 97)
    h = period / 4000
    fi_ref, ft_ref = _time_domain_forces(fb, t, h)
    fi, ft = sc.single_cylinder_forces(W * t, fb, M_REC, R, W, rod_length=L, model="exact")
    p = M_REC * R * W**2
    np.testing.assert_allclose(fi / p, fi_ref / p, atol=1e-6)
    np.testing.assert_allclose(ft / p, ft_ref / p, atol=1e-6)


def test_exact_study_peak_and_optimum_against_brute_force() -> None:
    study = sc.balance_factor_study(M_REC, R, W, 0.5, rod_length=L, model="exact")
    theta = np.linspace(0, 2 * np.pi, 4001)
    fbs = np.linspace(0, 1, 1001)
    period = 2 * math.pi / W
    peaks = []
    for fb in study.sweep_balance_factor[::5]:
        fi, ft = _time_domain_forces(fb, theta / W, period / 4000)
        peaks.append(np.hypot(fi, ft).max())
    np.testing.assert_allclose(study.sweep_peak_resultant[::5], peaks, rtol=1e-5)
    # the exact optimum lies above 0.5 (second order adds to the in-line force at TDC)
    fi, ft = sc.single_cylinder_forces(theta[None, :], fbs[:, None], M_REC, R, W, L)
    brute = np.hypot(fi, ft).max(axis=1)
    k = int(np.argmin(brute))
    assert study.optimum_balance_factor == pytest.approx(fbs[k], abs=1e-3)
    # a kinked minimum: the grid minimum is above the true one by at most slope * step / 2
    assert 0 <= brute[k] - study.optimum_peak_resultant < 1e-3 * study.primary_force
    assert study.optimum_balance_factor > 0.5
    # at f_b = 0.5 the peak is the in-line force at TDC: (0.5 + lambda) P exactly
    assert study.peak_resultant == pytest.approx((0.5 + R / L) * study.primary_force, rel=1e-9)


def test_series_close_to_exact() -> None:
    a = sc.peak_resultant(0.4, M_REC, R, W, L, model="exact")
    b = sc.peak_resultant(0.4, M_REC, R, W, L, model="series")
    assert a == pytest.approx(b, rel=1e-4)


def test_polar_curve_is_consistent() -> None:
    study = sc.balance_factor_study(M_REC, R, W, 0.28, rod_length=L, samples=72)
    np.testing.assert_allclose(
        study.resultant * np.cos(study.direction), study.in_line, atol=1e-9 * study.primary_force
    )
    np.testing.assert_allclose(
        study.resultant * np.sin(study.direction), study.transverse, atol=1e-9 * study.primary_force
    )
    assert study.to_dict()["model"] == "exact"


# --- mass properties ---------------------------------------------------------------------


def test_balance_factor_and_bob_weight_round_trip() -> None:
    m_rot, fb = 0.25, 0.42
    moment = sc.counterweight_moment(m_rot, M_REC, fb, R)
    m_cw = 1.9
    got = sc.balance_factor_from_mass_properties(m_cw, moment / m_cw, R, m_rot, M_REC)
    assert got == pytest.approx(fb, rel=1e-12)
    # the bob-weight at the crank radius balances exactly that counterweight
    assert sc.bob_weight(m_rot, M_REC, fb) * R == pytest.approx(moment, rel=1e-12)


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: sc.balance_factor_study(M_REC, R, W, 2.5, model="first-order"), "balance_factor"),
        (lambda: sc.balance_factor_study(M_REC, R, W, -0.1, model="first-order"), "balance_factor"),
        (
            lambda: sc.balance_factor_study(-1.0, R, W, 0.5, model="first-order"),
            "reciprocating_mass",
        ),
        (lambda: sc.balance_factor_study(M_REC, 0.0, W, 0.5, model="first-order"), "crank_radius"),
        (lambda: sc.balance_factor_study(M_REC, R, W, 0.5, model="exact"), "rod_length"),
        (lambda: sc.balance_factor_study(M_REC, R, W, 0.5, model="magic"), "model"),
        (
            lambda: sc.balance_factor_study(M_REC, R, W, 0.5, offset=0.005, model="first-order"),
            "offset",
        ),
        (
            lambda: sc.single_cylinder_forces(0.0, 0.5, M_REC, R, W, L, offset=float("nan")),
            "offset",
        ),
        (
            lambda: sc.balance_factor_from_mass_properties(2.0, 0.006, 0.0, 0.28, 0.28),
            "crank_radius",
        ),
        (
            lambda: sc.balance_factor_from_mass_properties(-2.0, 0.006, 0.0269, 0.28, 0.28),
            "counterweight_mass",
        ),
        (lambda: sc.bob_weight(-0.1, 0.28, 0.5), "rotating_mass"),
        (lambda: sc.bob_weight(0.1, 0.28, 3.0), "balance_factor"),
        (lambda: sc.sum_parts({"piston": 0.1, "pin": -0.01}), "parts.pin"),
        (lambda: rb.FaceRemoval(area=0.0, radius=0.04), "face_area"),
        (lambda: rb.DrilledHoles(diameter=0.008, radius=0.04, number=0), "holes"),
    ],
)
def test_bad_input_names_the_field(call, field: str) -> None:
    with pytest.raises(InputError) as info:
        call()
    assert info.value.field == field
    assert field in str(info.value)


# --- rebalancing -------------------------------------------------------------------------

OLD = dict(old_rotating_mass=0.28269, old_reciprocating_mass=0.28212)
NEW = dict(new_rotating_mass=0.24869, new_reciprocating_mass=0.26150)
CW = dict(counterweight_mass=2.0204, counterweight_radius=0.00616, crank_radius=0.0269)


def test_axial_face_is_exact_in_one_pass() -> None:
    corr = rb.FaceRemoval(area=1.5e-3, radius=0.035, orientation="axial", depth_resolution=0)
    res = rb.rebalance(
        **OLD, **NEW, **CW, correction=corr, tolerance=1e-9, target_balance_factor=0.28
    )
    assert len(res.iterations) == 1
    it = res.iterations[0]
    # independent: mass = unbalance / radius, depth = mass / (rho A webs)
    expected_mass = res.unbalance / 0.035
    assert it.correction_mass == pytest.approx(expected_mass, rel=1e-12)
    assert it.depth == pytest.approx(expected_mass / (7850 * 1.5e-3 * 2), rel=1e-12)
    assert res.achieved_balance_factor == pytest.approx(0.28, abs=1e-9)


def test_radial_holes_iterate_and_converge() -> None:
    corr = rb.DrilledHoles(
        diameter=0.012, radius=0.045, number=3, direction="radial", depth_resolution=1e-6
    )
    res = rb.rebalance(
        **OLD, **NEW, **CW, correction=corr, tolerance=1e-6, target_balance_factor=0.28
    )
    assert res.status == "converged" and res.passed
    assert len(res.iterations) >= 2
    residuals = [abs(it.residual) for it in res.iterations]
    assert residuals == sorted(residuals, reverse=True)
    last = res.iterations[-1]
    # removed first moment recomputed from the hole geometry: volume times centroid radius
    volume = math.pi * 0.012**2 / 4 * last.depth * 3 * 2
    assert last.removed_unbalance == pytest.approx(
        7850 * volume * (0.045 - last.depth / 2), rel=1e-12
    )
    assert res.unbalance - last.removed_unbalance == pytest.approx(res.residual, abs=1e-15)
    # the achieved balance factor, recomputed with Eq. 6.2 from the corrected moment
    moment = 2.0204 * 0.00616 - last.removed_unbalance
    assert res.achieved_balance_factor == pytest.approx(
        (moment / 0.0269 - 0.24869) / 0.26150, rel=1e-12
    )


def test_rebalance_needing_added_mass_is_refused() -> None:
    corr = rb.FaceRemoval(area=1.5e-3, radius=0.04)
    with pytest.raises(InputError, match="target_balance_factor"):
        rb.rebalance(**OLD, **NEW, **CW, correction=corr, tolerance=1e-5, target_balance_factor=1.5)


def test_rebalance_bad_masses() -> None:
    corr = rb.FaceRemoval(area=1.5e-3, radius=0.04)
    with pytest.raises(InputError, match="new_rotating_mass"):
        rb.rebalance(0.28, 0.28, -0.1, 0.26, 2.0, 0.006, 0.0269, corr, 1e-5)
    with pytest.raises(InputError, match="target_balance_factor"):
        rb.rebalance(
            **OLD, **NEW, **CW, correction=corr, tolerance=1e-5, target_balance_factor=-0.2
        )


# --- rotor helpers -----------------------------------------------------------------------


def test_cylinder_inertia_matches_numerical_integration() -> None:
    d, di, length, rho = 0.1, 0.03, 0.04, 7850.0
    rr = np.linspace(di / 2, d / 2, 20001)
    integrand = rho * 2 * np.pi * rr * length * rr**2
    numeric = float(np.sum((integrand[1:] + integrand[:-1]) / 2 * np.diff(rr)))
    assert cylinder_inertia(d, length, rho, bore=di) == pytest.approx(numeric, rel=1e-7)
    mass = rho * np.pi * d**2 / 4 * length
    assert disc_inertia(mass, d) == pytest.approx(cylinder_inertia(d, length, rho), rel=1e-12)


def test_equal_inertia_rotor_round_trip() -> None:
    rotor = equal_inertia_test_rotor(2.5e-3, 0.1, 0.02, 0.188)
    assert rotor.inertia == pytest.approx(2.5e-3, rel=1e-12)
    assert stepped_rotor_inertia(0.1, rotor.disc_thickness, 0.02, 0.188) == pytest.approx(
        2.5e-3, rel=1e-12
    )
    assert 2 * rotor.shaft_end_length + rotor.disc_thickness == pytest.approx(0.188)
    with pytest.raises(InputError, match="inertia"):
        equal_inertia_test_rotor(1.0, 0.1, 0.02, 0.188)


def test_crankpin_overlap() -> None:
    assert crankpin_overlap(0.040, 0.032, 0.0538) == pytest.approx(0.0091)
    with pytest.raises(InputError, match="stroke"):
        crankpin_overlap(0.04, 0.03, 0.0)


def test_stroking_effect() -> None:
    eff = stroking_effect(
        crank_radius=0.0269,
        crankpin_diameter=0.032,
        new_crankpin_diameter=0.030,
        crankpin_mass=0.11465,
        rotating_mass=0.28269,
        reciprocating_mass=0.28212,
        counterweight_mass=2.0204,
        counterweight_radius=0.00616,
        bore=0.0768,
        main_journal_diameter=0.040,
    )
    assert eff.new_stroke == pytest.approx(0.0538 + 0.002)
    assert eff.new_crankpin_mass == pytest.approx(0.11465 * (30 / 32) ** 2)
    assert eff.new_crankpin_overlap == pytest.approx(eff.crankpin_overlap - 0.002)
    assert eff.displacement_change == pytest.approx(math.pi * 0.0768**2 / 4 * 0.002)
    # restoring the old factor: m_cw r' - (m_rot' + f_b m_rec) r'
    keep = (eff.new_rotating_mass + eff.balance_factor * 0.28212) * eff.new_crank_radius
    assert eff.counterweight_correction == pytest.approx(2.0204 * 0.00616 - keep)
    # a larger radius with the same counterweight lowers the factor
    assert eff.new_balance_factor < eff.balance_factor
    with pytest.raises(InputError, match="new_crankpin_diameter"):
        stroking_effect(0.0269, 0.032, 0.034, 0.11, 0.28, 0.28, 2.0, 0.006)


def test_engine_cylinder_study_matches_plain_call() -> None:
    from crankbalance.io.engine_file import load_engine
    from crankbalance.studies.build import build_model
    from crankbalance.studies.cylinder import cylinder_study

    model = build_model(load_engine("single"))
    study = cylinder_study(model, 1, 0.4, kinematics="exact")
    plain = sc.balance_factor_study(
        float(model.reciprocating_mass[0]),
        model.crank_radius,
        model.speed,
        0.4,
        rod_length=model.rod_length,
        offset=float(model.cylinder_offset[0]),
    )
    assert study.peak_resultant == pytest.approx(plain.peak_resultant, rel=1e-12)
    with pytest.raises(InputError, match="cylinder"):
        cylinder_study(model, 3, 0.4)
