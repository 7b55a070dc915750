"""Unit tests of crankbalance.physics.balance_shaft against textbook closed forms and second
methods."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import scipy.linalg

from crankbalance.errors import InputError
from crankbalance.physics.balance_shaft import (
    BalanceShaft,
    compare_inline3_types,
    design_checks,
    inline3_couple_unbalance,
    inline3_layout,
    inline3_study,
    inline4_closed_form,
    inline4_secondary_unbalance,
    inline4_study,
    minimise_on_grid,
    shaft_response,
)
from crankbalance.physics.beam import (
    ShaftSection,
    assemble,
    beam_statics,
    natural_frequencies,
    shape_vectors,
)

from .conftest import run_cli

SECTION = ShaftSection(outer_diameter=0.025)  # steel, solid 25 mm
EI = SECTION.bending_stiffness
RHO_A = SECTION.mass_per_length


def simply_supported(
    length: float, load_at: float, unbalance: float = 1e-3, speed: float = 500.0, **kw: object
) -> BalanceShaft:
    return BalanceShaft(
        length=length,
        section=SECTION,
        bearing_positions=(0.0, length),
        mass_positions=(load_at,),
        unbalances=(unbalance,),
        speed=speed,
        **kw,
    )


# --------------------------------------------------------------------------- statics


@pytest.mark.parametrize("a_frac", [0.2, 0.5, 0.67, 0.9])
def test_point_load_reactions_deflection_and_integral(a_frac: float) -> None:
    length = 0.4
    a = a_frac * length
    b = length - a
    shaft = simply_supported(length, a)
    p = 1e-3 * 500.0**2
    r = shaft_response(shaft, n_points=401)
    # reactions of a simply supported beam: P b / L and P a / L (Gere & Timoshenko)
    assert np.allclose(r.reactions, [p * b / length, p * a / length], rtol=1e-12), (
        "Gere: R = Pb/L, Pa/L"
    )
    # deflection under the load P a^2 b^2 / (3 E I L)
    under = np.interp(a, r.x, r.deflection)
    exact_under = p * a**2 * b**2 / (3 * EI * length)
    assert abs(under - exact_under) < 1e-3 * exact_under, (
        "Gere: deflection under load Pa^2b^2/(3EIL)"
    )
    # the whole curve on the loaded side: P b x (L^2 - b^2 - x^2) / (6 E I L)
    left = r.x <= a
    curve = p * b * r.x[left] * (length**2 - b**2 - r.x[left] ** 2) / (6 * EI * length)
    assert np.allclose(r.deflection[left], curve, rtol=1e-10, atol=1e-15), (
        "Gere: y1 (Kim (2018), Eq. 7)"
    )
    # maximum deflection (in the longer segment)
    d = min(a, b)
    exact_max = p * d * (length**2 - d**2) ** 1.5 / (9 * math.sqrt(3) * EI * length)
    assert abs(r.max_deflection - exact_max) < 1e-4 * exact_max, "Gere: max deflection"
    # integral of the deflection: P a b (L^2 + a b) / (24 E I)  (Kim (2018), Eq. 9; by Maxwell's
    # reciprocity it is P times the deflection at a under a unit uniform load)
    exact_int = p * a * b * (length**2 + a * b) / (24 * EI)
    assert abs(r.bending_measure - exact_int) < 1e-5 * exact_int, (
        "Kim (2018), Eq. 9: integral of deflection"
    )
    # maximum moment and stress P a b / L
    assert abs(r.max_moment - p * a * b / length) < 1e-9 * p * length, "M_max = P a b / L"
    assert abs(r.max_stress - r.max_moment / (math.pi * 0.025**3 / 32)) < 1e-6 * r.max_stress


def test_inline4_shapes_match_closed_form() -> None:
    xi = np.linspace(0.0, 1.0, 41)
    study = inline4_study(1e-3, 600.0, 0.35, SECTION, positions=xi)
    a, b = inline4_closed_form(xi)
    assert np.allclose(study.normalised_bending, a / a.max(), atol=1e-8), (
        "docs/references.md Kim (2018): A shape"
    )
    assert np.allclose(study.normalised_secondary, b, atol=1e-12), (
        "Kim (2018), Eq. 19: B = |1 - 2 xi|"
    )
    w = 1e-3 * 600.0**2
    assert np.allclose(study.reaction_difference, w * b, rtol=1e-10, atol=1e-9), (
        "Kim (2018), Eq. 19"
    )
    scale = w * 0.35**4 / (24 * EI)
    assert np.allclose(study.bending_measure, scale * a, rtol=1e-5, atol=1e-15), "Kim (2018), Eq. 9"


def test_two_span_continuous_beam_against_textbook_and_fe() -> None:
    # Three bearings at 0, L, 2L, load P at the middle of the first span:
    # R_A = 13P/32, R_B = 11P/16, R_C = -3P/32 (statically indeterminate, textbook)
    span = 0.2
    p = 1000.0
    reactions, _w, _ = beam_statics(
        2 * span, EI, [0.0, span, 2 * span], [span / 2], [-p], np.linspace(0, 2 * span, 5)
    )
    assert np.allclose(reactions.real, [13 * p / 32, 11 * p / 16, -3 * p / 32], rtol=1e-10), (
        "continuous beam on three supports: 13P/32, 11P/16, -3P/32"
    )
    # Second method: finite elements (nodes at the supports), K u = f with constraints
    n = 40
    k, _m = assemble(2 * span, SECTION, n)
    f = np.zeros(k.shape[0])
    f[2 * (n // 4)] = -p
    fixed = [0, 2 * (n // 2), 2 * n]
    free = np.setdiff1d(np.arange(k.shape[0]), fixed)
    u = np.zeros_like(f)
    u[free] = np.linalg.solve(k[np.ix_(free, free)], f[free])
    x_nodes = np.linspace(0, 2 * span, n + 1)
    _, w_exact, _ = beam_statics(2 * span, EI, [0.0, span, 2 * span], [span / 2], [-p], x_nodes)
    assert np.allclose(u[0::2], w_exact.real, atol=1e-12 * p), "FE nodal deflections = exact"


def test_elastic_bearings_move_by_reaction_over_stiffness() -> None:
    k = 2e7
    length, a = 0.3, 0.1
    r_rigid, w_rigid, _ = beam_statics(length, EI, [0.0, length], [a], [100.0], [0.0, a, length])
    r, w, _ = beam_statics(
        length, EI, [0.0, length], [a], [100.0], [0.0, a, length], bearing_stiffness=k
    )
    assert np.allclose(r, r_rigid), "statically determinate: reactions do not depend on stiffness"
    assert np.allclose(w[[0, 2]], -r / k, rtol=1e-12), "bearing moves by -R/k"
    rigid_body = (-r[0] / k) * (1 - a / length) + (-r[1] / k) * a / length
    assert np.isclose(w[1], w_rigid[1] + rigid_body, rtol=1e-12), "superposition of bearing motion"


def test_timoshenko_static_shear_deflection() -> None:
    length = 0.1  # stocky: L / D = 4
    p = 1000.0
    _, w, _ = beam_statics(
        length,
        EI,
        [0.0, length],
        [length / 2],
        [p],
        [length / 2],
        shear_stiffness=SECTION.shear_stiffness,
    )
    exact = p * length**3 / (48 * EI) + p * length / (4 * SECTION.shear_stiffness)
    assert abs(w[0].real - exact) < 1e-12 * exact, "Timoshenko: PL^3/48EI + PL/4kGA"


def test_bearing_forces_over_a_revolution() -> None:
    shaft = simply_supported(0.3, 0.2)
    r = shaft_response(shaft)
    angle, force = r.bearing_forces(361)
    assert np.allclose(np.abs(force).max(0), r.reactions, rtol=1e-4), "amplitude over a revolution"
    diff = np.abs(force[:, 0] - force[:, 1]).max()
    assert abs(diff - r.reaction_difference) < 1e-4 * r.reactions.max(), (
        "Kim (2018), Eq. 19 at theta = n pi"
    )
    assert angle[0] == 0 and abs(angle[-1] - 2 * math.pi) < 1e-12


def test_phase_rotation_and_mirror_invariance() -> None:
    base = BalanceShaft(
        0.3, SECTION, (0.03, 0.3), (0.0, 0.2), (2e-3, 1.5e-3), 600.0, phases=(0.0, 2.0)
    )
    turned = BalanceShaft(
        0.3, SECTION, (0.03, 0.3), (0.0, 0.2), (2e-3, 1.5e-3), 600.0, phases=(1.0, 3.0)
    )
    mirrored = BalanceShaft(
        0.3, SECTION, (0.0, 0.27), (0.3, 0.1), (2e-3, 1.5e-3), 600.0, phases=(0.0, 2.0)
    )
    a, b, c = (shaft_response(s, n_points=301) for s in (base, turned, mirrored))
    for name in ("bending_measure", "max_deflection", "max_stress", "first_frequency"):
        assert np.isclose(getattr(a, name), getattr(b, name), rtol=1e-10), f"rotation: {name}"
        assert np.isclose(getattr(a, name), getattr(c, name), rtol=2e-3), f"mirror: {name}"
    assert np.allclose(a.reactions, b.reactions) and np.allclose(a.reactions, c.reactions[::-1])
    assert np.allclose(a.deflection, c.deflection[::-1], rtol=1e-8, atol=1e-15)


# --------------------------------------------------------------------------- dynamics


def test_simply_supported_first_frequency_closed_form() -> None:
    length = 0.5
    exact = math.pi**2 * math.sqrt(EI / (RHO_A * length**4)) / (2 * math.pi)
    errors = []
    for n in (4, 8, 16):
        f = natural_frequencies(length, SECTION, [0.0, length], [0.0], [0.0], n_elements=n)[0]
        errors.append(abs(f / exact - 1))
    assert errors[-1] < 1e-3, "f1 = pi^2 sqrt(EI/(rho A L^4)) / 2pi within 0.1 %"
    assert errors[0] > errors[1] > errors[2], "FE frequency converges with refinement"
    # bearings inside elements (not on nodes) converge too
    f = natural_frequencies(length, SECTION, [0.0, length], [0.0], [0.0], n_elements=24)[0]
    assert abs(f / exact - 1) < 1e-4
    f = natural_frequencies(length + 0.1, SECTION, [0.033, 0.533], [0.0], [0.0], n_elements=60)
    # overhangs of 33 and 67 mm stiffen nothing but add mass at the ends: below the SS value
    assert f[0] < exact


def test_point_mass_against_rayleigh_and_dunkerley() -> None:
    length, mass = 0.4, 0.5
    f = natural_frequencies(length, SECTION, [0.0, length], [length / 2], [mass], n_elements=40)[0]
    omega = 2 * math.pi * f
    # Rayleigh with the static deflection of the mass load plus the beam's own sine mode:
    rayleigh = math.sqrt((math.pi**4 * EI / (2 * length**3)) / (RHO_A * length / 2 + mass))
    beam = math.pi**2 * math.sqrt(EI / (RHO_A * length**4))
    dunkerley = 1 / math.sqrt(1 / beam**2 + mass * length**3 / (48 * EI))
    assert omega <= rayleigh * (1 + 1e-9), "Rayleigh quotient is an upper bound"
    assert omega >= dunkerley, "Dunkerley is a lower bound"
    assert abs(omega / rayleigh - 1) < 0.01, "within 1 % of Rayleigh's estimate (sine shape)"
    # off-centre mass: Rayleigh with the sine mode still bounds it from above
    f2 = natural_frequencies(length, SECTION, [0.0, length], [0.1], [mass], n_elements=40)[0]
    rayleigh2 = math.sqrt(
        (math.pi**4 * EI / (2 * length**3))
        / (RHO_A * length / 2 + mass * math.sin(math.pi * 0.25) ** 2)
    )
    assert 2 * math.pi * f2 <= rayleigh2 * (1 + 1e-9) and 2 * math.pi * f2 > 0.97 * rayleigh2


def test_batched_frequencies_match_scipy_eigh() -> None:
    length, n = 0.3, 12
    xm = np.array([[0.0, 0.1], [0.0, 0.2], [0.05, 0.3]])
    xb = np.array([[0.03, 0.3], [0.03, 0.3], [0.0, 0.25]])
    mm = np.array([[0.2, 0.3], [0.1, 0.1], [0.4, 0.0]])
    batched = natural_frequencies(length, SECTION, xb, xm, mm, n_elements=n, n_modes=3)
    k, m = assemble(length, SECTION, n)
    for p in range(3):
        nm = shape_vectors(xm[p], length, n, SECTION)
        mp = m + (mm[p][:, None, None] * nm[:, :, None] * nm[:, None, :]).sum(0)
        c = shape_vectors(xb[p], length, n, SECTION)
        z = scipy.linalg.null_space(c)
        lam = scipy.linalg.eigh(z.T @ k @ z, z.T @ mp @ z, eigvals_only=True)[:3]
        assert np.allclose(batched[p], np.sqrt(lam) / (2 * math.pi), rtol=1e-9), "scipy.linalg.eigh"


def test_elastic_bearings_lower_the_frequency_and_tend_to_rigid() -> None:
    length = 0.4
    rigid = natural_frequencies(length, SECTION, [0.0, length], [0.2], [0.3])[0]
    soft = natural_frequencies(length, SECTION, [0.0, length], [0.2], [0.3], bearing_stiffness=1e6)[
        0
    ]
    stiff = natural_frequencies(
        length, SECTION, [0.0, length], [0.2], [0.3], bearing_stiffness=1e12
    )[0]
    assert soft < rigid and abs(stiff / rigid - 1) < 1e-4


def test_timoshenko_tends_to_euler_bernoulli_for_slender_shafts() -> None:
    section = ShaftSection(0.01)
    length = 0.5  # L / D = 50
    eb = natural_frequencies(length, section, [0, length], [0.2], [0.05], n_elements=30)[0]
    ti = natural_frequencies(
        length, section, [0, length], [0.2], [0.05], n_elements=30, theory="timoshenko"
    )[0]
    assert ti < eb and abs(ti / eb - 1) < 2e-3, "slender: Timoshenko -> Euler-Bernoulli"
    s_eb = shaft_response(BalanceShaft(length, section, (0, length), (0.2,), (1e-4,), 300.0))
    s_ti = shaft_response(
        BalanceShaft(length, section, (0, length), (0.2,), (1e-4,), 300.0), theory="timoshenko"
    )
    assert abs(s_ti.bending_measure / s_eb.bending_measure - 1) < 1e-3


def test_timoshenko_stocky_shaft_against_analytic_frequency() -> None:
    # Simply supported Timoshenko beam, mode 1 (k = pi / L), shear and rotary inertia:
    # rho^2 I / (kappa G) w^4 - (rho A + rho I k^2 + E I rho k^2 / (kappa G)) w^2 + E I k^4 = 0
    section = ShaftSection(0.04)
    length = 0.16  # L / D = 4
    kk = math.pi / length
    rho, i_, a_ = section.density, section.second_moment, section.area
    kg = section.shear_coefficient * section.shear_modulus
    c2 = rho**2 * i_ / kg
    c1 = rho * a_ + rho * i_ * kk**2 + section.youngs_modulus * i_ * rho * kk**2 / kg
    c0 = section.bending_stiffness * kk**4
    w2 = (c1 - math.sqrt(c1**2 - 4 * c2 * c0)) / (2 * c2)
    exact = math.sqrt(w2) / (2 * math.pi)
    f = natural_frequencies(
        length, section, [0, length], [0.0], [0.0], n_elements=40, theory="timoshenko"
    )[0]
    assert abs(f / exact - 1) < 1e-3, "Timoshenko SS frequency equation"
    eb = natural_frequencies(length, section, [0, length], [0.0], [0.0], n_elements=40)[0]
    assert eb > 1.05 * f, "stocky: Euler-Bernoulli overestimates by > 5 %"


# --------------------------------------------------------------------------- optimum, checks


def test_minimise_on_grid_refines_a_parabola() -> None:
    x = np.linspace(0, 1, 11)
    y = np.stack([(x - 0.537) ** 2 + 1, (x - 0.2) ** 2])
    xv, yv = minimise_on_grid(x, y)
    assert np.allclose(xv, [0.537, 0.2]) and np.allclose(yv, [1, 0])
    sym = (x - 0.5) ** 2 * (x - 0.5) ** 2 - (x - 0.5) ** 2  # two equal minima
    xs, _ = minimise_on_grid(x, sym)
    assert xs > 0.5, "ties go to the far end (paper: 67 % rather than 33 %)"


def test_weight_sweep_moves_the_optimum_toward_the_middle() -> None:
    study = inline4_study(1e-3, 600.0, 0.3, SECTION, weights=np.linspace(0.5, 2.2, 8))
    assert np.all(np.diff(study.optimum_positions) < 0), "more weight on B -> closer to mid-length"
    assert np.isclose(study.objective.min(), study.optimum_objective, atol=1e-3)


def test_design_checks() -> None:
    shaft = simply_supported(0.3, 0.2, unbalance=2e-3, speed=800.0, unbalance_radius=0.02)
    r = shaft_response(shaft)
    ok = design_checks(r, bearing_capacity=2 * r.reactions.max(), deflection_limit=1.0)
    assert ok.ok and ok.critical_speed_ratio == pytest.approx(r.first_critical_speed / 800.0)
    fast = design_checks(r, max_speed=2 * 800.0, bearing_capacity=2 * r.reactions.max())
    assert fast.max_bearing_load == pytest.approx(4 * r.reactions.max()), "loads grow with speed^2"
    assert not fast.bearing_ok and not fast.ok
    slow_critical = design_checks(r, max_speed=r.first_critical_speed)
    assert not slow_critical.critical_speed_ok
    assert slow_critical.dynamic_amplification >= 1e11
    tight = design_checks(r, deflection_limit=0.5 * r.max_deflection)
    assert not tight.deflection_ok
    expected = 1 / abs(1 - (800.0 / r.first_critical_speed) ** 2)
    assert ok.dynamic_amplification == pytest.approx(expected)
    json.dumps(ok.to_dict())


def test_required_unbalance_helpers() -> None:
    # Kim (2018), Eq. 4: m_b r_b = m_p r^2 / (2 l); with Eq. 3 the pair cancels 4 m_p r^2 w^2 / l
    u = inline4_secondary_unbalance(0.5, 0.04, 0.14)
    omega = 300.0
    assert math.isclose(2 * u * (2 * omega) ** 2, 4 * 0.5 * 0.04**2 * omega**2 / 0.14), (
        "Kim (2018), Eqs. 2-3"
    )
    # half the inline-3 primary couple sqrt(3) m r w^2 a, made by two masses L apart
    u3 = inline3_couple_unbalance(0.94, 0.04, 0.09, 0.25)
    assert math.isclose(u3 * 0.25, math.sqrt(3) / 2 * 0.94 * 0.04 * 0.09), "Kim (2018), Eq. 12"


def test_inline3_couple_is_held_and_reactions_cancel() -> None:
    study = inline3_study("III", 2e-3, 600.0, 0.3, SECTION)
    couple = study.unbalances[:, 0] * (study.mass_positions[:, 1] - study.mass_positions[:, 0])
    assert np.allclose(couple, 2e-3 * 0.3), "hold='couple' keeps U * spacing"
    # a pure couple on two bearings: equal and opposite reactions M / bearing distance
    gap = study.bearing_positions[:, 1] - study.bearing_positions[:, 0]
    assert np.allclose(study.reactions, (2e-3 * 0.3 * 600.0**2 / gap)[:, None], rtol=1e-10), (
        "Kim (2018), Eq. 13"
    )
    same = inline3_study("III", 2e-3, 600.0, 0.3, SECTION, hold="unbalance")
    assert np.allclose(same.unbalances, 2e-3)


def test_inline3_layouts_keep_their_order() -> None:
    z = np.linspace(0.3, 1.0, 9)
    for kind, order in {"I": "BMMB", "II": "MBBM", "III": "MBMB"}.items():
        bearings, masses = inline3_layout(kind, z, 1.0, 0.1)  # type: ignore[arg-type]
        for p in range(z.size - 1):
            items = sorted([(x, "B") for x in bearings[p]] + [(x, "M") for x in masses[p]])
            assert "".join(s for _, s in items) == order, f"type {kind}"


def test_compare_types_passes_the_options_to_each_type() -> None:
    z = np.linspace(0.4, 1.0, 31)
    result = compare_inline3_types(2e-3, 600.0, 0.3, SECTION, weight=1.5, positions=z)
    assert set(result) == {"I", "II", "III"}
    for kind, study in result.items():
        alone = inline3_study(kind, 2e-3, 600.0, 0.3, SECTION, weight=1.5, positions=z)  # type: ignore[arg-type]
        assert study.case == f"inline3-{kind}" and study.weight == 1.5
        assert np.array_equal(study.objective, alone.objective), f"type {kind}: same study"
        assert study.optimum_position == alone.optimum_position
        json.dumps(study.to_dict())


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(length=-0.3), "length"),
        (dict(bearing_positions=(0.0, 0.5)), "bearing_positions[1]"),
        (dict(bearing_positions=(0.1, 0.1)), "bearing_positions"),
        (dict(bearing_positions=(0.0, 0.1, 0.1)), "bearing_positions"),
        (dict(bearing_positions=(0.1,)), "bearing_positions"),
        (dict(mass_positions=(-0.01,)), "mass_positions[0]"),
        (dict(unbalances=(-1e-3,)), "unbalances[0]"),
        (dict(unbalances=(1e-3, 1e-3)), "unbalances"),
        (dict(speed=0.0), "speed"),
        (dict(unbalance_radius=0.0), "unbalance_radius"),
        (dict(bearing_stiffness=-1.0), "bearing_stiffness"),
        (dict(phases=(float("nan"),)), "phases[0]"),
    ],
)
def test_bad_shaft_input(kwargs: dict[str, object], name: str) -> None:
    base: dict[str, object] = dict(
        length=0.3,
        section=SECTION,
        bearing_positions=(0.0, 0.3),
        mass_positions=(0.2,),
        unbalances=(1e-3,),
        speed=500.0,
    )
    base.update(kwargs)
    with pytest.raises(InputError) as err:
        BalanceShaft(**base)  # type: ignore[arg-type]
    assert err.value.field == name


def test_bad_section_and_study_input() -> None:
    with pytest.raises(InputError, match="inner_diameter"):
        ShaftSection(0.02, inner_diameter=0.03)
    with pytest.raises(InputError, match="outer_diameter"):
        ShaftSection(-0.02)
    with pytest.raises(InputError, match="positions"):
        inline4_study(1e-3, 500.0, 0.3, SECTION, positions=[0.0, 0.5, 1.5])
    with pytest.raises(InputError, match="weight"):
        inline4_study(1e-3, 500.0, 0.3, SECTION, weight=-1.0)
    with pytest.raises(InputError, match="theory"):
        inline4_study(1e-3, 500.0, 0.3, SECTION, theory="bernoulli")  # type: ignore[arg-type]
    with pytest.raises(InputError, match="rotor_type"):
        inline3_study("IV", 1e-3, 500.0, 0.3, SECTION)  # type: ignore[arg-type]
    with pytest.raises(InputError, match="positions"):
        inline3_study("II", 1e-3, 500.0, 0.3, SECTION, positions=[0.1, 0.5, 1.0])
    with pytest.raises(InputError, match="bearing_offset"):
        inline3_study("I", 1e-3, 500.0, 0.3, SECTION, bearing_offset=0.2)
    with pytest.raises(InputError, match="n_points"):
        shaft_response(simply_supported(0.3, 0.1), n_points=200)


# --------------------------------------------------------------------------- CLI


SHAFT = ["--length", "300 mm", "--diameter", "25 mm"]
INLINE4 = ["shaft", "inline4", "--unbalance", "3.3 g*m", "--speed", "12000 rpm", *SHAFT]
CHECK = ["shaft", "check", *SHAFT, "--bearing", "0 mm", "--unbalance", "3.3 g*m"]
CHECK += ["--speed", "12000 rpm", "--mass", "200 mm"]


def test_cli_shaft_json(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli([*INLINE4, "--format", "json"], capsys)
    assert code == 0, err
    data = json.loads(out)
    assert data["schema"] == "crankbalance.shaft/2"
    assert abs(data["optimum"]["position"] - 0.67) < 0.01, "Kim (2018), Fig. 7: 67 % with w = 2"
    assert len(data["weight_sweep"]) == 20


def test_cli_shaft_tables(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(INLINE4, capsys)
    assert code == 0, err
    assert "optimum at 66.9 % of the length" in out, (
        "docs/references.md Kim (2018): 66.9 % with w = 2"
    )
    inline3 = ["shaft", "inline3", "--unbalance", "10 g*m", "--speed", "6000 rpm", *SHAFT]
    code, out, err = run_cli([*inline3, "--points", "41"], capsys)
    assert code == 0, err
    assert "III" in out and "B = inverse-frequency" in out
    code, out, err = run_cli([*inline3, "--points", "41", "--type", "I", "--secondary",
                              "reaction-difference"], capsys)  # fmt: skip
    assert code == 0 and "B = reaction-difference" in out, "--secondary reaches inline3"
    code, out, err = run_cli(
        [*CHECK, "--bearing", "300 mm", "--bearing-capacity", "5 kN", "--format", "json"], capsys
    )
    assert code == 0, err
    data = json.loads(out)
    assert data["schema"] == "crankbalance.shaft/2" and "checks" in data
    # Gere: R = P a / L on the bearing near the load, P = U Omega^2 (x = 200 of 300 mm)
    p = 3.3e-3 * (12000 * math.pi / 30) ** 2
    assert np.allclose(data["response"]["reactions_N"], [p / 3, 2 * p / 3], rtol=1e-9)


@pytest.mark.parametrize(
    "args, word",
    [
        ([*INLINE4[:-4], "--length", "-300 mm", "--diameter", "25 mm"], "length"),
        ([*INLINE4[:-4], "--length", "300..200 mm", "--diameter", "25 mm"], "not a range"),
        ([*INLINE4, "--points", "100000"], "points"),
        ([*INLINE4, "--weights", "1,nan"], "weights"),
        ([*INLINE4, "--bore", "25 mm"], "inner_diameter"),
        ([*INLINE4[:-6], "--speed", "0 rpm", *SHAFT], "speed"),
        (["shaft", "inline4", *SHAFT, "--unbalance", "3 kg", "--speed", "1 rpm"], "unbalance"),
        (["shaft", "inline4", *SHAFT, "--unbalance", "3 g*m"], "--speed"),
        ([*CHECK, "--bearing", "400 mm"], "bearing_positions"),
        ([*CHECK, "--bearing", "0 mm"], "bearing_positions"),
        ([*CHECK, "--bearing", "300 mm", "--phase", "1 deg", "--mass", "100 mm"], "phases"),
        ([*CHECK, "--bearing", "300 mm", "--margin", "nan"], "--margin"),
    ],
)
def test_cli_bad_input_exits_2(
    args: list[str], word: str, capsys: pytest.CaptureFixture[str]
) -> None:
    code, _out, err = run_cli(args, capsys)
    assert code == 2 and word in err and "Traceback" not in err, err


def test_inline4_critical_weight_closed_form() -> None:
    # Near mid-length (t = xi - 1/2): A/max A = 1 - 24/5 t^2 + O(t^4), B = 2|t|, so
    # J = 1 + (4 w - 48/5) t^2: the off-centre optimum exists only for w < 12/5 = 2.4
    xi = np.linspace(0.0, 1.0, 2001)
    study = inline4_study(
        1e-3, 600.0, 0.3, SECTION, positions=xi, weights=[2.3, 2.45, 3.0], n_elements=2
    )
    assert study.optimum_positions[0] > 0.55, "w = 2.3 < 12/5: optimum off centre"
    assert np.allclose(study.optimum_positions[1:], 0.5, atol=1e-3), "w > 12/5: mid-length"


def test_low_level_functions_refuse_points_off_the_shaft() -> None:
    with pytest.raises(InputError, match="bearing_positions"):
        natural_frequencies(0.3, SECTION, [0.0, 0.35], [0.1], [0.1])
    with pytest.raises(InputError, match="mass_positions"):
        natural_frequencies(0.3, SECTION, [0.0, 0.3], [-0.1], [0.1])
    with pytest.raises(InputError, match="masses"):
        natural_frequencies(0.3, SECTION, [0.0, 0.3], [0.1], [-0.1])
    with pytest.raises(InputError, match="n_elements"):
        natural_frequencies(0.3, SECTION, [0.0, 0.3], [0.1], [0.1], n_elements=1)
    with pytest.raises(InputError, match="force_positions"):
        beam_statics(0.3, EI, [0.0, 0.3], [0.4], [1.0], [0.1])
    with pytest.raises(InputError, match="bearing_positions"):
        beam_statics(0.3, EI, [0.1], [0.2], [1.0], [0.1])


@pytest.mark.parametrize("bearings", [[0.1, 0.1], [0.0, 0.2, 0.2], [[0.0, 0.3], [0.15, 0.15]]])
def test_low_level_functions_refuse_coincident_bearings(bearings: list[float]) -> None:
    # two bearings at one point carry no moment: the statics are singular (a LinAlgError
    # before) and the rigid constraints rank-deficient (a silently wrong frequency before)
    with pytest.raises(InputError, match="its own position"):
        beam_statics(0.3, EI, bearings, [0.25], [1.0], [0.1])
    with pytest.raises(InputError, match="its own position"):
        natural_frequencies(0.3, SECTION, bearings, [0.25], [0.1])
