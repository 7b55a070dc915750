"""Tolerance statistics (crankbalance.physics.shop.scatter): the Monte Carlo against the analytic
variance of the phasor sum, written out in the tests.

Statistical checks use a fixed seed and a bound of 5 standard errors of the estimate, so
they are deterministic and would fail for a wrong variance of more than about 2 %.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.physics.model import EngineModel
from crankbalance.physics.shaking import free_forces
from crankbalance.physics.shop import scatter as sc
from crankbalance.studies.build import build_model

N = 200_000
PLANES = (-0.25, 0.25)


def v8() -> EngineModel:
    return build_model(load_engine("v8-crossplane"))


def three_on_one_plane() -> EngineModel:
    """Three cylinders 120 deg apart at one axial position: every phasor sum is isotropic
    (sum of e^{2 i phi} = 0), so its magnitude is Rayleigh distributed."""
    return EngineModel(
        name="three",
        speed=600.0,
        kinematics="first-order",
        crank_radius=0.04,
        rod_length=0.14,
        strokes=4,
        throw_angle=np.radians([0.0, 120.0, 240.0]),
        throw_position=np.zeros(3),
        throw_rotating_mass=np.full(3, 0.5),
        cylinder_throw=np.arange(3),
        cylinder_bank=np.zeros(3),
        reciprocating_mass=np.full(3, 0.4),
        cylinder_offset=np.zeros(3),
        cylinder_axial=np.zeros(3),
        cylinder_rotating_mass=np.zeros(3),
        firing_order=(1, 2, 3),
    )


def hand_moments(model: EngineModel, var_rot: float, var_rec: float, f_b: float) -> np.ndarray:
    """E[Re^2], E[Im^2], E[Re Im] of the ten phasors, written from the formulas of the
    module docstring with first-order kinematics (c1 = 1, c2 = lambda)."""
    r, w, lam = model.crank_radius, model.speed, model.rod_ratio
    phi, beta, y = model.cylinder_angle, model.cylinder_bank, model.cylinder_position
    z1, z2 = PLANES
    t1, t2 = (z2 - y) / (z2 - z1), (y - z1) / (z2 - z1)
    half = r * w**2 / 2
    rows = []  # (sensitivity to rotating, to reciprocating) per phasor, arrays over c
    e = np.exp(1j * phi)
    rows.append((t1 * r * e, f_b * t1 * r * e))
    rows.append((t2 * r * e, f_b * t2 * r * e))
    force = [
        (r * w**2 * e, half * e),
        (0 * e, half * np.exp(1j * (-phi + 2 * beta))),
        (0 * e, half * lam * np.exp(1j * (2 * phi - beta))),
        (0 * e, half * lam * np.exp(1j * (-2 * phi + 3 * beta))),
    ]
    rows += force
    rows += [(y * a, y * b) for a, b in force]
    out = []
    for a, b in rows:
        out.append(
            [
                var_rot * np.sum(a.real**2) + var_rec * np.sum(b.real**2),
                var_rot * np.sum(a.imag**2) + var_rec * np.sum(b.imag**2),
                var_rot * np.sum(a.real * a.imag) + var_rec * np.sum(b.real * b.imag),
            ]
        )
    return np.array(out)


def assert_moments_match(study: sc.ScatterStudy, expected: np.ndarray) -> None:
    scale = expected[:, :2].max(axis=1, keepdims=True)  # round-off of a row's sums
    assert np.all(np.abs(study.moments_analytic - expected) <= 1e-9 * scale)
    sampled = study.moments
    re2, im2, cross = expected.T
    # standard error of a mean of products of jointly normal variables, upper bound
    # (uniform variables have lighter tails)
    err = np.sqrt(np.stack([2 * re2**2, 2 * im2**2, re2 * im2 + cross**2], axis=1) / N)
    assert np.all(np.abs(sampled - expected) <= 5 * err + 1e-30), (sampled, expected)


@pytest.mark.parametrize("preset", ["v8-crossplane", "inline4", "boxer4", "v6-60", "w12"])
def test_sensitivities_agree_with_free_forces(preset: str) -> None:
    # the linear map of the Monte Carlo against the library's free forces of an engine
    # whose masses are one draw of deviations (exact kinematics)
    model = build_model(load_engine(preset))
    s = sc.sensitivities(model, PLANES, 0.5)
    c = model.cylinders
    rng = np.random.default_rng(3)
    rec = rng.normal(0, 1e-3, c)
    rot = rng.normal(0, 1e-3, c)
    # rotating deviations of cylinders sharing a pin add up on the throw
    throw_rot = np.bincount(model.cylinder_throw, weights=rot, minlength=model.throws)
    deviated = replace(model, reciprocating_mass=rec, throw_rotating_mass=throw_rot)
    forces = free_forces(deviated, orders=2)
    x = np.concatenate([rot, rec]) @ s
    assert x[2] == pytest.approx(forces.force_forward[0] + forces.rotating_force, rel=1e-9)
    assert x[3] == pytest.approx(forces.force_backward[0], rel=1e-9)
    assert x[4:6] == pytest.approx([forces.force_forward[1], forces.force_backward[1]])
    assert x[6] == pytest.approx(forces.couple_forward[0] + forces.rotating_couple, rel=1e-9)
    assert x[7:10] == pytest.approx(
        [forces.couple_backward[0], forces.couple_forward[1], forces.couple_backward[1]]
    )


def test_monte_carlo_matches_the_analytic_phasor_variance() -> None:
    model = replace(v8(), kinematics="first-order")
    parts = [
        sc.PartScatter("piston", "reciprocating", 1.0e-3),
        sc.PartScatter("small end", "reciprocating", 0.5e-3),
        sc.PartScatter("big end", "rotating", 0.8e-3),
    ]
    study = sc.scatter_study(model, parts, PLANES, 0.5, N, seed=11)
    expected = hand_moments(model, 0.8e-3**2, 1.0e-3**2 + 0.5e-3**2, 0.5)
    assert_moments_match(study, expected)
    # the RMS of a plane's residual magnitude is the root of E|U|^2
    assert study.rms[0] ** 2 == pytest.approx(expected[0, :2].sum(), rel=0.02)


def test_uniform_scatter_and_scale_resolution() -> None:
    # uniform on +-sqrt(3) sigma has variance sigma^2; a scale of step q adds q^2/12 per
    # weighed part (two shells per rod), nothing for the oil allowance
    model = replace(v8(), kinematics="first-order")
    q = 0.5e-3
    parts = [
        sc.PartScatter("pin", "reciprocating", 0.4e-3, "uniform"),
        sc.PartScatter("shells", "rotating", 0.0, count=2),
        sc.PartScatter("oil", "rotating", 0.3e-3, weighed=False),
    ]
    study = sc.scatter_study(model, parts, PLANES, 0.5, N, seed=5, scale_step=q)
    var_rec = 0.4e-3**2 + q**2 / 12
    var_rot = 2 * q**2 / 12 + 0.3e-3**2
    assert_moments_match(study, hand_moments(model, var_rot, var_rec, 0.5))


def test_variance_shares() -> None:
    # two reciprocating part types, sigma 2:1, no scale: shares 0.8 and 0.2 of every
    # output; no rotating part and no scale: share 0
    model = v8()
    parts = [
        sc.PartScatter("piston", "reciprocating", 2e-3),
        sc.PartScatter("pin", "reciprocating", 1e-3),
    ]
    study = sc.scatter_study(model, parts, PLANES, 0.5, 1000, seed=0)
    assert study.sources == ("piston", "pin", "scale")
    varying = study.variance_share.sum(axis=0) > 0
    assert study.variance_share[0, varying] == pytest.approx(0.8)
    assert study.variance_share[1, varying] == pytest.approx(0.2)
    assert np.all(study.variance_share[2] == 0)
    assert all(d in ("piston", "none") for d in study.dominant)
    # a crossplane V8's first-order force from the pistons does not cancel, order 1 varies
    assert study.dominant[2] == "piston"


def test_probabilities_and_quantiles_of_a_rayleigh_residual() -> None:
    # three cylinders 120 deg apart on one plane, rotating scatter only: U is a circular
    # complex normal, |U| Rayleigh, P(|U| <= t) = 1 - exp(-t^2 / E|U|^2); both correction
    # planes, symmetric about it, carry U/2 each
    model = three_on_one_plane()
    sigma = 1e-3
    parts = [sc.PartScatter("big end", "rotating", sigma)]
    mean_square = 3 * (sigma * model.crank_radius / 2) ** 2  # E|U_1|^2 [kg^2 m^2]
    t = math.sqrt(mean_square)  # tolerance at the RMS: P = 1 - 1/e
    force_square = 3 * (sigma * model.crank_radius * model.speed**2) ** 2
    limit = math.sqrt(force_square * math.log(4))  # P = 3/4
    study = sc.scatter_study(
        model,
        parts,
        (-0.1, 0.1),
        0.5,
        N,
        seed=2,
        plane_tolerance=t,
        force_limit=(limit, math.inf),
    )
    p_grade = 1 - math.exp(-1)
    assert study.p_grade is not None and study.p_free is not None and study.p_all is not None
    assert abs(study.p_grade - p_grade) <= 5 * math.sqrt(p_grade * (1 - p_grade) / N)
    assert abs(study.p_free - 0.75) <= 5 * math.sqrt(0.75 * 0.25 / N)
    # residual and force come from the same deviations: P(both) lies between
    assert study.p_all <= min(study.p_grade, study.p_free)
    # median of the Rayleigh: sqrt(E|U|^2 ln 2), to the histogram's resolution
    median = study.quantiles[0, list(study.quantile_levels).index(0.5)]
    resolution = study.histogram_upper[0] / sc.BINS
    assert abs(median - math.sqrt(mean_square * math.log(2))) <= 0.01 * median + resolution
    assert study.histogram.sum(axis=1) + study.overflow == pytest.approx(np.full(6, N))
    assert study.mean[0] == pytest.approx(math.sqrt(math.pi * mean_square) / 2, rel=0.01)


def test_seed_reproduces_and_chunks_bound_memory() -> None:
    model = v8()
    parts = [sc.PartScatter("piston", "reciprocating", 1e-3, "uniform")]
    a = sc.scatter_study(model, parts, PLANES, 0.5, 10_001, seed=4, chunk=1000)
    b = sc.scatter_study(model, parts, PLANES, 0.5, 10_001, seed=4, chunk=1000)
    assert np.array_equal(a.histogram, b.histogram) and np.array_equal(a.moments, b.moments)
    assert a.histogram.sum() + a.overflow.sum() == 6 * 10_001
    assert a.p_grade is None and a.p_free is None and a.p_all is None
    out = a.to_dict()
    assert out["samples"] == 10_001 and len(out["quantiles"]) == 6


@pytest.mark.parametrize(
    ("change", "field"),
    [
        ({"parts": [sc.PartScatter("p", "rotary", 1e-3)]}, "parts[0].kind"),  # type: ignore[arg-type]
        ({"parts": [sc.PartScatter("p", "rotating", -1e-3)]}, "parts[0].sigma"),
        ({"parts": [sc.PartScatter("p", "rotating", 1e-3, "gauss")]}, "parts[0].distribution"),  # type: ignore[arg-type]
        ({"parts": [sc.PartScatter("p", "rotating", 1e-3, count=0)]}, "parts[0].count"),
        ({"parts": []}, "parts"),
        ({"samples": 0}, "samples"),
        ({"balance_factor": 3.0}, "balance_factor"),
        ({"correction_planes": (0.1, 0.1)}, "correction_planes"),
        ({"scale_step": -1e-4}, "scale_step"),
        ({"plane_tolerance": -1.0}, "plane_tolerance"),
    ],
)
def test_bad_input_names_the_field(change: dict, field: str) -> None:
    args = {
        "parts": [sc.PartScatter("piston", "reciprocating", 1e-3)],
        "correction_planes": PLANES,
        "balance_factor": 0.5,
        "samples": 10,
    } | change
    with pytest.raises(InputError) as info:
        sc.scatter_study(v8(), **args)
    assert info.value.field == field
