"""Articulated (master-and-link) rods of radial engines: the physics module against
independent references.

- The master piston is an ordinary slider-crank (:mod:`crankbalance.physics.kinematics`).
- With a zero link pin radius every link piston is an ordinary slider-crank on the pin,
  and its harmonics equal the exact slider-crank coefficients of the simple model.
- The analytic rates against central differences of the positions.
- The positions, strokes and dead centres against a second, independent construction in
  this file: angles instead of complex factors, every wrist pin found by bracketing root
  search (scipy ``brentq``) on the rod-length condition, dead centres by ``brentq`` on a
  central difference of the travel.
- The Fourier phasors against the exact time-domain force (sum of the orders), and the
  sampling against twice as many samples (aliasing).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from crankbalance.errors import InputError
from crankbalance.physics import kinematics
from crankbalance.physics.articulated import (
    ArticulatedRods,
    cylinder_coefficients,
    dead_centres,
    default_link_pin_angles,
    even_stroke_angles,
    harmonics,
    inertia_force,
    motion,
    piston_position,
)
from crankbalance.physics.model import EngineModel


def _radial(
    n: int = 5,
    master: int = 0,
    rho: float = 0.055,
    r: float = 0.0667,
    l_master: float = 0.25,
    offset: float | list[float] = 0.0,
    gamma_shift: float = 0.0,
) -> ArticulatedRods:
    beta = 2 * np.pi * np.arange(n) / n
    links = np.arange(n) != master
    gamma = default_link_pin_angles(beta, master) + np.where(links, gamma_shift, 0.0)
    return ArticulatedRods(
        master=master,
        crank_radius=r,
        bank_angle=beta,
        rod_length=np.where(links, l_master - rho, l_master),
        link_pin_radius=np.where(links, rho, 0.0),
        link_pin_angle=gamma,
        offset=np.broadcast_to(np.asarray(offset, dtype=float), (n,)).copy(),
    )


def _big_ends(rods: ArticulatedRods, mass: float = 0.4) -> np.ndarray:
    """Big-end masses of the rods: ``mass`` for the links, a heavier master's."""
    return np.where(np.arange(rods.cylinders) == rods.master, 2.0, mass)


# ----------------------------------------------------------------- independent geometry
def _along(point: np.ndarray, beta: float, rod: float, offset: float) -> float:
    """Wrist-pin travel on the path of a cylinder at angle beta, by root search."""
    axis = np.array([math.cos(beta), math.sin(beta)])  # (z, x)
    normal = np.array([-math.sin(beta), math.cos(beta)])

    def gap(t: float) -> float:
        return float(np.hypot(*(t * axis + offset * normal - point)) - rod)

    low = float(point @ axis)  # the rod points away from the crank axis
    return float(brentq(gap, low, low + rod + 1.0, xtol=1e-15, rtol=1e-15))


def _reference(rods: ArticulatedRods, theta: float) -> tuple[np.ndarray, np.ndarray]:
    """Link pins (C, 2) and travels (C,) at crank angle theta, built with angles."""
    m, r, e = rods.master, rods.crank_radius, np.asarray(rods.offset)
    pin = r * np.array([math.cos(theta), math.sin(theta)])
    beta = np.asarray(rods.bank_angle)
    sm = _along(pin, beta[m], rods.rod_length[m], e[m])
    small = sm * np.array([math.cos(beta[m]), math.sin(beta[m])]) + e[m] * np.array(
        [-math.sin(beta[m]), math.cos(beta[m])]
    )
    rod_angle = math.atan2(small[1] - pin[1], small[0] - pin[0])
    links = np.empty((beta.size, 2))
    travel = np.empty(beta.size)
    for c in range(beta.size):
        a = rod_angle + rods.link_pin_angle[c]
        links[c] = pin + rods.link_pin_radius[c] * np.array([math.cos(a), math.sin(a)])
        travel[c] = sm if c == m else _along(links[c], beta[c], rods.rod_length[c], e[c])
    return links, travel


def _reference_dead_centre(rods: ArticulatedRods, c: int, guess: float) -> tuple[float, float]:
    """Crank angle and travel of an extreme of cylinder c near ``guess``, by root search on
    a central difference of the independently built travel."""
    h = 1e-5

    def rate(theta: float) -> float:
        return (_reference(rods, theta + h)[1][c] - _reference(rods, theta - h)[1][c]) / (2 * h)

    step = 2 * np.pi / 720
    angle = brentq(rate, guess - step, guess + step, xtol=1e-13)
    return angle, float(_reference(rods, angle)[1][c])


# ----------------------------------------------------------------- closed forms
@pytest.mark.parametrize("offset", [0.0, 0.004])
def test_master_piston_is_exactly_a_slider_crank(offset: float) -> None:
    rods = _radial(n=7, master=2, offset=offset)
    theta = np.linspace(0, 2 * np.pi, 97)
    got = motion(rods, theta, speed=230.0)
    psi = theta - rods.bank_angle[2]
    args = (rods.crank_radius, rods.rod_length[2], offset)
    s = kinematics.piston_position(psi, *args)
    v = kinematics.piston_velocity(psi, *args, speed=230.0)
    a = kinematics.piston_acceleration(psi, *args, speed=230.0)
    assert np.allclose(got.travel[:, 2], s, rtol=0, atol=1e-15)
    assert np.allclose(got.travel_velocity[:, 2], v, rtol=1e-13, atol=1e-12)
    assert np.allclose(got.travel_acceleration[:, 2], a, rtol=1e-13, atol=1e-9)


def test_zero_link_pin_radius_gives_plain_slider_cranks_on_the_pin() -> None:
    rods = _radial(n=9, rho=0.0)
    theta = np.linspace(0, 2 * np.pi, 61)
    got = motion(rods, theta)
    psi = theta[:, None] - rods.bank_angle[None, :]
    s = kinematics.piston_position(psi, rods.crank_radius, rods.rod_length[None, :])
    a = kinematics.piston_acceleration(psi, rods.crank_radius, rods.rod_length[None, :])
    assert np.abs(got.travel - s).max() < 1e-15
    assert np.abs(got.travel_acceleration - a).max() < 1e-14
    assert np.abs(got.big_end - got.crankpin[:, None]).max() == 0.0


def test_zero_link_pin_radius_harmonics_equal_the_simple_models() -> None:
    """Per kilogram at 1 rad/s the simple model has F_n^+ = (r/2) c_n e^{i(1-n) beta} and
    F_n^- = (r/2) conj(c_n) e^{i(1+n) beta} (crankbalance.physics.shaking docstring, throw angle
    0)."""
    rods = _radial(n=5, rho=0.0)
    h = harmonics(rods, orders=8)
    r, l = rods.crank_radius, rods.rod_length[0]
    c = kinematics.exact_coefficients(r / l, 8)
    n = np.arange(1, 9)
    beta = rods.bank_angle[:, None]
    forward = 0.5 * r * c[None, :] * np.exp(1j * (1 - n) * beta)
    backward = 0.5 * r * np.conj(c)[None, :] * np.exp(1j * (1 + n) * beta)
    assert np.abs(h.piston_forward - forward).max() < 1e-9 * r
    assert np.abs(h.piston_backward - backward).max() < 1e-9 * r
    assert np.abs(h.link_forward).max() == 0.0


def test_the_articulated_result_tends_to_the_simple_one_as_the_link_pin_radius_vanishes() -> None:
    simple = harmonics(_radial(rho=0.0))
    gaps = []
    for rho in (1e-3, 1e-4, 1e-5):
        h = harmonics(_radial(rho=rho))
        gaps.append(np.abs(h.piston_forward - simple.piston_forward).max())
    assert gaps[0] > 0
    # first order in rho: each tenth of the radius gives a tenth of the gap
    assert gaps[1] / gaps[0] == pytest.approx(0.1, rel=0.02)
    assert gaps[2] / gaps[1] == pytest.approx(0.1, rel=0.02)


# ----------------------------------------------------------------- analytic rates
@pytest.mark.parametrize("offset", [0.0, -0.003])
def test_analytic_rates_match_central_differences(offset: float) -> None:
    rods = _radial(n=7, master=0, offset=offset, gamma_shift=math.radians(1.5))
    theta = np.linspace(0.1, 2 * np.pi, 41)
    h = 1e-4
    at = [motion(rods, theta + k * h) for k in (-2, -1, 0, 1, 2)]
    # five-point differences: error O(h^4)
    d1 = lambda f: (f[0] - 8 * f[1] + 8 * f[3] - f[4]) / (12 * h)  # noqa: E731
    d2 = lambda f: (-f[0] + 16 * f[1] - 30 * f[2] + 16 * f[3] - f[4]) / (12 * h * h)  # noqa: E731
    travel = [m.travel for m in at]
    big = [m.big_end for m in at]
    big1 = [m.big_end_velocity for m in at]
    scale = rods.crank_radius
    assert np.abs(d1(travel) - at[2].travel_velocity).max() < 1e-9 * scale
    assert np.abs(d2(travel) - at[2].travel_acceleration).max() < 1e-6 * scale
    assert np.abs(d1(big) - at[2].big_end_velocity).max() < 1e-9 * scale
    assert np.abs(d1(big1) - at[2].big_end_acceleration).max() < 1e-9 * scale


def test_rates_scale_with_the_speed() -> None:
    rods = _radial()
    theta = np.linspace(0, 6, 13)
    one, fast = motion(rods, theta), motion(rods, theta, speed=200.0)
    assert np.allclose(fast.travel_velocity, 200.0 * one.travel_velocity, rtol=1e-14)
    assert np.allclose(fast.travel_acceleration, 4e4 * one.travel_acceleration, rtol=1e-14)


# ----------------------------------------------------------------- independent geometry
@pytest.mark.parametrize("offset", [0.0, 0.003])
def test_positions_match_an_independent_construction(offset: float) -> None:
    rods = _radial(n=9, master=4, offset=offset, gamma_shift=math.radians(-2.0))
    for theta in np.linspace(0, 2 * np.pi, 23):
        links, travel = _reference(rods, float(theta))
        got = motion(rods, [theta])
        assert np.abs(got.travel[0] - travel).max() < 1e-12
        ours = got.big_end[0]
        assert np.abs(ours.real - links[:, 0]).max() < 1e-14
        assert np.abs(ours.imag - links[:, 1]).max() < 1e-14
        pistons = piston_position(rods, got)[0]
        axis = np.exp(1j * rods.bank_angle)
        assert np.abs(pistons - (travel + 1j * offset) * axis).max() < 1e-12


@pytest.mark.parametrize("n", [5, 7, 9])
def test_strokes_and_dead_centres_match_root_finding(n: int) -> None:
    rods = _radial(n=n, master=0, gamma_shift=math.radians(1.0))
    got = dead_centres(rods)
    for c in range(n):
        top, s_top = _reference_dead_centre(rods, c, got.tdc_angle[c])
        bottom, s_bottom = _reference_dead_centre(rods, c, got.bdc_angle[c])
        assert got.tdc_angle[c] == pytest.approx(top, abs=1e-8)
        assert got.bdc_angle[c] == pytest.approx(bottom, abs=1e-8)
        assert got.tdc_travel[c] == pytest.approx(s_top, abs=1e-12)
        assert got.stroke[c] == pytest.approx(s_top - s_bottom, abs=1e-12)
    # the master: stroke 2r and dead centres at its bank angle and opposite
    assert got.stroke[0] == pytest.approx(2 * rods.crank_radius, abs=1e-14)
    assert got.tdc_lag[0] == pytest.approx(0.0, abs=1e-12)


def test_link_strokes_differ_and_mirror_about_the_master() -> None:
    """Default link pin angles, master at cylinder 1: the assembly is symmetric about the
    master cylinder's axis, so cylinders k and n+2-k have equal strokes and opposite TDC
    lags, and every link stroke differs from 2r."""
    rods = _radial(n=9)
    got = dead_centres(rods)
    r = rods.crank_radius
    for k in range(1, 9):
        mirror = 9 - k
        assert got.stroke[k] == pytest.approx(got.stroke[mirror], abs=1e-13)
        assert got.tdc_lag[k] == pytest.approx(-got.tdc_lag[mirror], abs=1e-11)
        assert abs(got.stroke[k] - 2 * r) > 1e-6


def test_even_stroke_angles_give_the_master_stroke_by_root_finding() -> None:
    """The shifted link pin angles give every link piston a stroke of 2r, checked with the
    independent construction; the shifts mirror about the master and stay small."""
    rods = _radial(n=7)
    angles = even_stroke_angles(rods)
    shifted = replace(rods, link_pin_angle=angles)
    got = dead_centres(shifted)
    shift = angles - rods.link_pin_angle
    assert shift[0] == 0.0
    for k in range(1, 7):
        _t, top = _reference_dead_centre(shifted, k, got.tdc_angle[k])
        _b, bottom = _reference_dead_centre(shifted, k, got.bdc_angle[k])
        assert top - bottom == pytest.approx(2 * rods.crank_radius, abs=1e-11)
        assert shift[k] == pytest.approx(-shift[7 - k], abs=1e-12)
        assert 0 < abs(shift[k]) < math.radians(3.0)


# ----------------------------------------------------------------- harmonics
def test_phasors_rebuild_the_exact_time_domain_force() -> None:
    offsets = [0.002, 0.0, -0.001, 0.002, 0.003, 0.0, 0.001]
    rods = _radial(n=7, master=3, gamma_shift=math.radians(0.7), offset=offsets)
    mass = np.linspace(1.1, 1.7, 7)
    ends = _big_ends(rods)
    speed = 190.0
    h = harmonics(rods, orders=40)
    forward = speed**2 * (mass @ h.piston_forward + ends @ h.link_forward)
    backward = speed**2 * (mass @ h.piston_backward + ends @ h.link_backward)
    theta = np.linspace(0, 2 * np.pi, 53)
    n = h.orders[:, None]
    rebuilt = (
        forward[:, None] * np.exp(1j * n * theta) + backward[:, None] * np.exp(-1j * n * theta)
    ).sum(0)
    exact = inertia_force(rods, mass, ends, theta, speed).sum(axis=1)
    assert np.abs(rebuilt - exact).max() < 1e-10 * np.abs(exact).max()


def test_default_link_pin_angles_keep_the_first_order_and_no_odd_orders() -> None:
    """Closed form (docs/theory.md): with gamma_k = beta_k - beta_m the link pin's lateral
    coordinate in its cylinder's frame is a pure first harmonic, so every link piston has
    exactly a slider-crank's first harmonic (c_1 = 1) and no odd harmonic above it; a
    shifted link pin angle breaks both."""
    plain = cylinder_coefficients(_radial(n=9), 7)
    assert np.abs(plain[:, 0] - 1.0).max() < 1e-14
    assert np.abs(plain[:, 2::2]).max() < 1e-14
    assert np.abs(plain[1:, 1] - plain[0, 1]).max() > 1e-3  # the even orders do change
    shifted = cylinder_coefficients(_radial(n=9, gamma_shift=math.radians(1.0)), 7)
    assert np.abs(shifted[1:, 0] - 1.0).min() > 1e-5
    assert np.abs(shifted[1:, 2]).min() > 1e-6


def test_sampling_is_free_of_aliasing() -> None:
    rods = _radial(n=5, rho=0.06, l_master=0.2)
    h = harmonics(rods, orders=8)
    assert h.alias_bound < 1e-14
    # the same harmonics from four times the samples, by direct quadrature of the exact force
    n = 4 * h.samples
    theta = 2 * np.pi * np.arange(n) / n
    force = inertia_force(rods, np.ones(5), np.zeros(5), theta, 1.0).sum(axis=1)
    orders = np.arange(1, 9)
    forward = (force[None, :] * np.exp(-1j * orders[:, None] * theta)).mean(axis=1)
    assert np.abs(forward - h.piston_forward.sum(axis=0)).max() < 1e-15


def test_link_pin_masses_add_their_own_forces() -> None:
    """1 kg at a link pin beyond 1 kg at the crankpin: from the independent construction by
    second central differences of the link pin position."""
    rods = _radial(n=5, rho=0.06)
    theta = np.linspace(0, 2 * np.pi, 11)
    d = 1e-4
    ends = _big_ends(rods)
    got = inertia_force(rods, np.zeros(5), ends, theta, 1.0).sum(axis=1)
    expected = np.zeros(theta.size, dtype=complex)
    for j, t in enumerate(theta):
        pins = [_reference(rods, t + k * d)[0] for k in (-1, 0, 1)]
        accel = (pins[0] - 2 * pins[1] + pins[2]) / d**2  # (C, 2)
        crankpin = -rods.crank_radius * np.array([math.cos(t), math.sin(t)])
        extra = -(ends[:, None] * (accel - crankpin)).sum(axis=0)
        expected[j] = extra[0] + 1j * extra[1]
    assert np.abs(got - expected).max() < 1e-5 * np.abs(expected).max()


# ----------------------------------------------------------------- bad input
def test_bad_geometry_is_refused_with_the_field_named() -> None:
    good = _radial()
    for change, words in (
        ({"rod_length": np.full(5, 0.1)}, "rod_length"),
        ({"master": 5}, "master"),
        ({"master": 1}, "link_pin_radius"),
        ({"offset": np.zeros(4)}, "offset"),
        ({"link_pin_radius": -good.link_pin_radius}, "link_pin_radius"),
    ):
        with pytest.raises(InputError, match=words):
            replace(good, **change)


# ----------------------------------------------------------------- engine file and model
ARTICULATED_PRESETS = ["radial5-kinner", "radial7-scarab", "radial9-r985"]
#: masses as totals only: the link rods' big ends cannot be placed
TOTALS_ONLY = {"reciprocating": "1.5 kg", "rotating": "5 kg"}


def _preset_dict(name: str) -> dict:
    import tomllib

    from crankbalance.io.engine_file import preset_text

    return tomllib.loads(preset_text(name))


def _model(data: dict) -> EngineModel:
    from crankbalance.schema.engine import spec_from_dict
    from crankbalance.studies.build import build_model

    return build_model(spec_from_dict(data))


@pytest.mark.parametrize("name", ARTICULATED_PRESETS)
def test_zero_link_pin_radius_engine_equals_the_simple_radial(name: str) -> None:
    """An articulated engine file with link pin radius 0 and link rods as long as the master
    rod is the simple radial (every rod on the pin): the same FreeForces to 1e-9."""
    from crankbalance.physics.shaking import exact_time_domain, free_forces

    data = _preset_dict(name)
    art = data["crank_train"]["articulated"]
    art["link_pin_radius"] = "0 mm"
    art["link_rod_length"] = data["crank_train"]["rod_length"]
    zero = _model(data)
    del data["crank_train"]["articulated"]
    simple = _model(data)
    assert zero.articulation is not None and simple.articulation is None
    a, b = free_forces(zero, 12), free_forces(simple, 12)
    scale = np.abs(b.force_forward).max()
    for key in ("force_forward", "force_backward", "couple_forward", "couple_backward"):
        assert np.abs(getattr(a, key) - getattr(b, key)).max() < 1e-9 * scale, key
    assert a.rotating_force == pytest.approx(b.rotating_force, rel=1e-15)
    theta = np.linspace(0, 2 * np.pi, 37)
    fa, _ = exact_time_domain(zero, theta)
    fb, _ = exact_time_domain(simple, theta)
    assert np.abs(fa - fb).max() < 1e-9 * np.abs(fb).max()


@pytest.mark.parametrize("name", ARTICULATED_PRESETS)
def test_preset_builds_its_rods_from_the_engine_file(name: str) -> None:
    data = _preset_dict(name)
    model = _model(data)
    art = model.articulated_rods
    assert art is not None
    ct = data["crank_train"]
    n = ct["cylinders"]
    master = ct["articulated"]["master_cylinder"] - 1
    links = np.arange(n) != master
    assert art.master == master
    assert art.rod_length[master] == pytest.approx(model.rod_length)
    assert np.all(art.rod_length[links] < model.rod_length)
    # default link pin angles: the angles between each cylinder and the master
    gap = np.exp(1j * (art.link_pin_angle - art.bank_angle + art.bank_angle[master]))
    assert np.allclose(gap[links], 1.0, rtol=0, atol=1e-14)
    # the link rods' big ends: the conrod split over the link rod length
    for split in model.conrods:
        c = split.cylinder - 1
        assert model.cylinder_rotating_mass[c] == pytest.approx(split.rotating)
    # every big end is counted with the crank's rotating mass, as for plain rods
    total = sum(s.rotating for s in model.conrods)
    mass = data["masses"]
    web = 2 * float(mass["crank_web"].split()[0]) * float(mass["crank_web_cg_radius"].split()[0])
    r_mm = model.crank_radius * 1e3
    parts = (float(mass["crankpin"].split()[0]) + web / r_mm) / 1e3
    assert model.throw_rotating_mass[0] == pytest.approx(parts + total)


def test_link_rod_split_uses_the_link_rod_length() -> None:
    data = _preset_dict("radial5-kinner")
    masses = data["masses"]
    del masses["conrod_rotating_fraction"]
    masses["conrod_cg_from_big_end"] = "100 mm"
    masses["override"][0].pop("conrod_rotating_fraction")
    masses["override"][0]["conrod_cg_from_big_end"] = "60 mm"
    model = _model(data)
    link = data["crank_train"]["articulated"]["link_rod_length"]
    l_link = float(link.split()[0]) * 1e-3
    split = model.conrods[1]
    assert split.rotating == pytest.approx(0.55 * (l_link - 0.1) / l_link)
    assert model.articulation is not None
    assert model.cylinder_rotating_mass[1] == pytest.approx(split.rotating)
    assert model.articulation.link_rod_length[1] == pytest.approx(l_link)
    master = model.conrods[0]
    assert master.rotating == pytest.approx(2.2 * (0.254 - 0.06) / 0.254)


@pytest.mark.parametrize(
    "change, field, words",
    [
        (
            lambda d: d["crank_train"]["articulated"].update(link_rod_length="100 mm"),
            "crank_train.articulated.link_rod_length",
            "must exceed",
        ),
        (
            lambda d: d["crank_train"]["articulated"].update(master_cylinder=6),
            "crank_train.articulated.master_cylinder",
            "1..5",
        ),
        (
            lambda d: d["crank_train"]["articulated"].update(link_pin_angles=["0 deg"] * 3),
            "crank_train.articulated.link_pin_angles",
            "one angle per cylinder",
        ),
        (
            lambda d: d["crank_train"]["articulated"].update(link_pin_angles=["1 deg"] * 5),
            "crank_train.articulated.link_pin_angles",
            "master cylinder",
        ),
        (
            lambda d: d["crank_train"]["articulated"].update(link_pin_radius="-2 mm"),
            "crank_train.articulated.link_pin_radius",
            "negative",
        ),
        (
            lambda d: d["crank_train"]["articulated"].update(knuckle="1 mm"),
            "crank_train.articulated.knuckle",
            "unknown key",
        ),
        (lambda d: d.update(kinematics="series"), "kinematics", "exact"),
        (lambda d: d.update(masses=TOTALS_ONLY), "masses.conrod", "articulated"),
    ],
)
def test_bad_articulated_tables_name_the_field(
    change: Callable[[dict], object], field: str, words: str
) -> None:
    from crankbalance.schema.engine import spec_from_dict

    data = _preset_dict("radial5-kinner")
    change(data)
    with pytest.raises(InputError) as caught:
        spec_from_dict(data)
    assert caught.value.field == field
    assert words in str(caught.value)


def test_articulated_table_needs_a_radial() -> None:
    from crankbalance.schema.engine import spec_from_dict

    data = _preset_dict("radial5-kinner")
    data["crank_train"].update(layout="inline", crank_pitch="120 mm")
    with pytest.raises(InputError) as caught:
        spec_from_dict(data)
    assert caught.value.field == "crank_train.articulated.master_cylinder"
    assert "radial" in str(caught.value)


# ----------------------------------------------------------------- end to end
@pytest.mark.parametrize("name", ARTICULATED_PRESETS)
def test_analyze_and_balance_see_the_articulated_forces(
    name: str, capsys: pytest.CaptureFixture[str]
) -> None:
    """The command line prints the articulated phasors (not the simple model's), and the
    balance's time-domain check, computed from the exact articulated motion, finds the
    same amplitudes before balancing."""
    import json

    from crankbalance.physics.articulated import harmonics as articulated_harmonics

    from .conftest import run_cli

    model = _model(_preset_dict(name))
    rods = model.articulated_rods
    assert rods is not None
    h = articulated_harmonics(rods, 8)
    w2 = model.speed**2
    rec, big = model.reciprocating_mass, model.cylinder_rotating_mass
    amplitude = w2 * (
        np.abs(rec @ h.piston_forward + big @ h.link_forward)
        + np.abs(rec @ h.piston_backward + big @ h.link_backward)
    )
    code, out, err = run_cli(["analyze", name, "--format", "json"], capsys)
    assert code == 0, err
    data = json.loads(out)
    printed = np.array([row["amplitude_N"] for row in data["free_forces"]])
    assert np.allclose(printed, amplitude, rtol=1e-9, atol=1e-6)
    # the simple model has no second order in a radial; the articulated one has
    assert printed[1] > 0.05 * printed[0]
    code, out, err = run_cli(["balance", name, "--format", "json"], capsys)
    assert code == 0, err
    balance = json.loads(out)
    checks = {row["component"]: row for row in balance["components"]}
    for order in (1, 2, 4):
        before = checks[f"order{order}"]["force_before_N"]
        assert before == pytest.approx(amplitude[order - 1], rel=1e-6)


@pytest.mark.parametrize("name", ARTICULATED_PRESETS)
def test_engine_phasors_equal_the_exact_time_domain(name: str) -> None:
    """The free forces of an articulated preset (cylinder_coefficients rows plus the link
    pins' phasors) rebuild the exact time-domain force of every cylinder's masses."""
    from crankbalance.physics.shaking import exact_time_domain, free_forces, phasor_curve

    model = _model(_preset_dict(name))
    f = free_forces(model, 24)
    theta = np.linspace(0, 2 * np.pi, 91)
    force, couple = exact_time_domain(model, theta)
    rebuilt = phasor_curve(f.force_forward, f.force_backward, f.orders, theta).sum(axis=0)
    assert np.abs(force - rebuilt).max() < 1e-9 * np.abs(force).max()
    assert np.abs(couple).max() == 0.0  # one throw at the mid-point: no couple


def test_the_documented_tables_are_the_examples_output(capsys: pytest.CaptureFixture[str]) -> None:
    """docs/theory.md, "Articulated rods", shows what examples/articulated_radials.py prints."""
    import importlib.util
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    spec = importlib.util.spec_from_file_location(
        "articulated_radials", root / "examples" / "articulated_radials.py"
    )
    assert spec is not None and spec.loader is not None
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    example.main()
    printed = [line for line in capsys.readouterr().out.splitlines() if line.startswith("|")]
    doc = (root / "docs" / "theory.md").read_text(encoding="utf-8").splitlines()
    missing = [line for line in printed if line not in doc]
    assert len(printed) > 40
    assert not missing, "docs/theory.md lacks the example's lines:\n" + "\n".join(missing[:5])


def test_free_forces_are_linear_in_the_masses_as_the_balance_shop_assumes() -> None:
    """The balance shop builds its basis from one kilogram per cylinder (reciprocating, and
    big end with its pin). For an articulated radial the sum of those unit engines, weighted
    by the real masses, must give the engine's free forces: the link pins' phasors follow
    each cylinder's big-end mass, not a fixed table."""
    from crankbalance.physics.shaking import free_forces

    model = _model(_preset_dict("radial7-scarab"))
    c, t = model.cylinders, model.throws
    none = replace(
        model,
        reciprocating_mass=np.zeros(c),
        throw_rotating_mass=np.zeros(t),
        cylinder_rotating_mass=np.zeros(c),
    )
    whole = free_forces(model, 6)
    total = np.zeros(6, dtype=complex)
    rotating = 0j
    for k in range(c):
        unit = np.eye(c)[k]
        rec = free_forces(replace(none, reciprocating_mass=unit), 6)
        end = free_forces(
            replace(none, throw_rotating_mass=np.ones(t), cylinder_rotating_mass=unit), 6
        )
        total += model.reciprocating_mass[k] * rec.force_forward
        total += model.cylinder_rotating_mass[k] * end.force_forward
        rotating += model.cylinder_rotating_mass[k] * end.rotating_force
    rest = model.throw_rotating_mass - model.cylinder_rotating_mass.sum()
    rotating += free_forces(replace(none, throw_rotating_mass=rest), 6).rotating_force
    assert np.abs(total - whole.force_forward).max() < 1e-9 * np.abs(whole.force_forward).max()
    assert rotating == pytest.approx(whole.rotating_force, rel=1e-12)
    # and the link pins do matter: without them the second order differs
    bare = free_forces(replace(model, cylinder_rotating_mass=np.zeros(c)), 6)
    assert abs(bare.force_forward[1] - whole.force_forward[1]) > 1e-3 * abs(whole.force_forward[1])


def test_single_cylinder_studies_take_the_master_and_refuse_a_link(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """A link piston is no slider-crank: the single-cylinder view refuses it by name, and
    takes the master cylinder, which is one."""
    from crankbalance.studies.cylinder import cylinder_of

    from .conftest import run_cli

    model = _model(_preset_dict("radial7-scarab"))
    master = cylinder_of(model, 1)
    assert master.rod_length == model.rod_length
    with pytest.raises(InputError) as caught:
        cylinder_of(model, 3)
    assert caught.value.field == "cylinder" and "master cylinder (1)" in str(caught.value)
    out = run_cli(["plot", "single", "radial7-scarab", "--cylinder", "2", "-o", "x.html"], capsys)
    assert out[0] == 2 and "link rod" in out[2]


def test_offsets_per_cylinder_enter_the_articulated_motion() -> None:
    """cylinder_offsets of an articulated radial reach the articulated geometry; its free
    forces still rebuild the exact time-domain force, and the master piston stays the
    offset slider-crank of the kinematics module."""
    from crankbalance.physics.shaking import exact_time_domain, free_forces, phasor_curve

    data = _preset_dict("radial5-kinner")
    offsets = ["2 mm", "-1 mm", "0 mm", "3 mm", "1.5 mm"]
    data["crank_train"]["cylinder_offsets"] = offsets
    model = _model(data)
    rods = model.articulated_rods
    assert rods is not None
    expected = [float(s.split()[0]) * 1e-3 for s in offsets]
    assert np.allclose(rods.offset, expected)
    f = free_forces(model, 24)
    theta = np.linspace(0, 2 * np.pi, 61)
    force, _ = exact_time_domain(model, theta)
    rebuilt = phasor_curve(f.force_forward, f.force_backward, f.orders, theta).sum(axis=0)
    assert np.abs(force - rebuilt).max() < 1e-9 * np.abs(force).max()
    got = motion(rods, theta, model.speed)
    a = kinematics.piston_acceleration(
        theta, model.crank_radius, model.rod_length, rods.offset[0], model.speed
    )
    assert np.allclose(got.travel_acceleration[:, 0], a, rtol=1e-12, atol=1e-6)
    # the offsets change the result against the same engine without them
    plain = free_forces(_model(_preset_dict("radial5-kinner")), 24)
    assert np.abs(plain.force_forward - f.force_forward).max() > 1.0


def test_analysis_json_states_the_rods_and_strokes() -> None:
    from crankbalance.physics.articulated import dead_centres
    from crankbalance.studies.engine import analyze

    data = analyze("radial7-scarab").to_dict()["engine"]["articulated"]
    model = _model(_preset_dict("radial7-scarab"))
    rods = model.articulated_rods
    assert rods is not None
    centres = dead_centres(rods)
    assert data["master_cylinder"] == 1
    assert data["stroke_m"] == pytest.approx(centres.stroke, rel=1e-11)
    assert data["stroke_m"][0] == pytest.approx(2 * model.crank_radius, rel=1e-12)
    assert data["tdc_angle_deg"] == pytest.approx(np.degrees(centres.tdc_angle), abs=1e-9)
    assert "articulated" not in analyze("radial5").to_dict()["engine"]


def test_balancing_cancels_the_articulated_orders_in_the_time_domain() -> None:
    """Balancing sees the articulated phasors: counterweights with balance factor 0.5 leave
    only the backward first order (from the heavier master cylinder and the link pins), and
    a secondary shaft pair cancels the articulated second order, as the time-domain check
    (built from the exact articulated motion) confirms."""
    from crankbalance.physics.shaking import free_forces
    from crankbalance.schema.engine import spec_from_dict
    from crankbalance.studies.engine import balance_engine

    data = _preset_dict("radial7-scarab")
    data["counterweights"] = {"cg_radius": "50 mm", "balance_factor": 0.5}
    data["balance_shafts"] = {"secondary": {"cg_radius": "30 mm", "length": "100 mm"}}
    model = _model(data)
    forces = free_forces(model, 2)
    out = balance_engine(spec_from_dict(data)).to_dict()
    rows = {row["component"]: row for row in out["components"]}
    assert rows["order2"]["force_before_N"] > 1000.0
    assert rows["order2"]["force_after_N"] < 1e-9 * rows["order2"]["force_before_N"]
    # order 1 after: the backward phasor, and what the forward one differs from n/2 m r w^2
    w2r = model.speed**2 * model.crank_radius
    forward_left = abs(forces.force_forward[0] - 0.5 * w2r * model.reciprocating_mass.sum())
    expected = abs(forces.force_backward[0]) + forward_left
    assert rows["order1"]["force_after_N"] == pytest.approx(expected, rel=1e-6)
