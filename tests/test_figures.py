"""Figure builders: every figure's data equals the API's numbers."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("plotly", reason="plotly is in the web/test extras")

from crankbalance import figures  # noqa: E402
from crankbalance.errors import InputError  # noqa: E402
from crankbalance.studies.engine import analyze, balance_engine  # noqa: E402


@pytest.fixture(scope="module")
def paper() -> tuple:
    return analyze("paper-inline3"), balance_engine("paper-inline3")


@pytest.fixture(scope="module")
def inline4() -> tuple:
    return analyze("inline4"), balance_engine("inline4")


def traces(fig, name: str) -> list:
    return [t for t in fig.data if t.name == name]


# --------------------------------------------------------------------------- orders
def test_orders_bar_heights_equal_api(inline4: tuple) -> None:
    a, _ = inline4
    fig = figures.orders_bar(a)
    data = a.to_dict()
    fwd_f, fwd_m = traces(fig, "forward (co-rotating)")
    bwd_f, bwd_m = traces(fig, "backward (counter-rotating)")
    height_f = np.asarray(fwd_f.y) + np.asarray(bwd_f.y)
    height_m = np.asarray(fwd_m.y) + np.asarray(bwd_m.y)
    assert height_f[:-1] == pytest.approx([r["amplitude_N"] for r in data["free_forces"]])
    assert height_m[:-1] == pytest.approx([r["amplitude_Nm"] for r in data["free_moments"]])
    assert np.asarray(fwd_f.y)[:-1] == pytest.approx([r["forward_N"] for r in data["free_forces"]])
    assert np.asarray(bwd_f.y)[:-1] == pytest.approx([r["backward_N"] for r in data["free_forces"]])
    assert height_f[-1] == pytest.approx(data["rotating"]["force_N"])
    assert height_m[-1] == pytest.approx(data["rotating"]["moment_Nm"])
    # inline-4: second order force is the largest free force (textbook: 4 m r w^2 lambda)
    assert np.argmax(height_f[:-1]) == 1


def test_orders_bar_drops_roundoff(paper: tuple) -> None:
    """Inline-3: the free forces cancel; round-off (~1e-12 N) is drawn as exactly zero."""
    a, _ = paper
    fig = figures.orders_bar(a)
    fwd_f = traces(fig, "forward (co-rotating)")[0]
    assert np.all(np.asarray(fwd_f.y)[:-1] == 0.0)


# --------------------------------------------------------------------------- curves
def test_curves_match_api_and_phasors(inline4: tuple) -> None:
    a, _ = inline4
    fig = figures.curves_figure(a, quantity="force")
    c = a.curves()
    total = traces(fig, "reciprocating total")
    assert len(total) == 2
    assert np.asarray(total[0].y) == pytest.approx(c.total_fx, abs=1e-6)
    assert np.asarray(total[1].y) == pytest.approx(c.total_fz, abs=1e-6)
    # order 2 trace peaks at the order-2 amplitude of the API (independent: max of curve)
    k = a.forces.order(2)
    z2 = np.asarray(traces(fig, "order 2")[1].y)
    assert np.abs(z2).max() == pytest.approx(a.forces.force_amplitude[k], rel=1e-4)
    assert np.asarray(fig.data[0].x)[[0, -1]] == pytest.approx([0.0, 359.5])


def test_curves_after_balancing_vanish_for_full_balance(paper: tuple) -> None:
    """Paper inline-3, first-order kinematics, counterweights plus primary and secondary
    shafts: the whole engine is balanced, so the rebuilt after-curves are zero everywhere
    (a time-domain check independent of the solver's own residual report)."""
    a, b = paper
    after = figures.balanced_curves(a, b)
    m_scale = np.abs(after.before_mx).max()
    assert m_scale > 100.0
    for name in ("after_fx", "after_fz"):
        assert np.abs(getattr(after, name)).max() < 1e-8
    for name in ("after_mx", "after_mz"):
        assert np.abs(getattr(after, name)).max() < 1e-10 * m_scale
    fig = figures.curves_figure(a, b, quantity="moment")
    assert np.all(np.asarray(traces(fig, "engine after balancing")[0].y) == 0.0)
    before = np.asarray(traces(fig, "engine before balancing")[0].y)
    assert before == pytest.approx(after.before_mx)


def test_curves_after_partial_balance_match_residuals(inline4: tuple) -> None:
    """Inline-4 with counterweights only: what is left after balancing is the second-order
    force; the curve's peak equals the solver's residual of order 2 plus higher orders."""
    a, b = inline4
    after = figures.balanced_curves(a, b)
    f = after.after_fx + 1j * after.after_fz
    spectrum = np.fft.fft(f) / f.size
    amp2 = abs(spectrum[2]) + abs(spectrum[-2])
    assert amp2 == pytest.approx(b.result.residual("order2").force_after, rel=1e-6)
    amp1 = abs(spectrum[1]) + abs(spectrum[-1])
    assert amp1 == pytest.approx(b.result.residual("order1").force_after, abs=1e-6)


def test_curves_reject_other_engine(paper: tuple, inline4: tuple) -> None:
    with pytest.raises(InputError, match="balance_study"):
        figures.curves_figure(paper[0], inline4[1])
    with pytest.raises(InputError, match="quantity"):
        figures.curves_figure(paper[0], quantity="torque")  # type: ignore[arg-type]


# --------------------------------------------------------------------------- polar
def test_polar_phasors_and_locus(paper: tuple) -> None:
    a, _ = paper
    fig = figures.polar_figure(a, 1, "moment")
    k = a.forces.order(1)
    fwd = 1j * a.forces.couple_forward[k]
    bwd = 1j * a.forces.couple_backward[k]
    locus = traces(fig, "locus")[0]
    radius = np.hypot(locus.x, locus.y)
    assert radius.max() == pytest.approx(a.forces.moment_amplitude[k], rel=1e-4)
    arrow_f = [t for t in fig.data if t.name.startswith("forward")][0]
    assert arrow_f.x[1] == pytest.approx(fwd.imag) and arrow_f.y[1] == pytest.approx(fwd.real)
    arrow_b = [t for t in fig.data if t.name.startswith("backward")][0]
    assert arrow_b.x[1] == pytest.approx((fwd + bwd).imag)
    assert arrow_b.y[1] == pytest.approx((fwd + bwd).real)
    # the direction at crank angle 0 agrees with the phase the JSON reports (in [0, 360))
    data = a.to_dict()["free_moments"][0]
    assert np.degrees(np.arctan2(arrow_f.x[1], arrow_f.y[1])) % 360.0 == pytest.approx(
        data["forward_phase_deg"]
    )


def test_polar_rotating_and_bad_order(inline4: tuple) -> None:
    a, _ = inline4
    fig = figures.polar_figure(a, "rotating", "force")
    assert np.hypot(fig.data[0].x, fig.data[0].y).max() == pytest.approx(
        abs(a.forces.rotating_force), rel=1e-6, abs=1e-9
    )
    for bad in (0.5, 99, "two"):
        with pytest.raises(InputError, match="order"):
            figures.polar_figure(a, bad)  # type: ignore[arg-type]


def test_polar_of_a_balanced_order_is_exactly_zero(paper: tuple, inline4: tuple) -> None:
    """Inline-3: the order-1 force cancels (2021 paper, Table 2: no primary force to balance);
    the diagram draws exact zeros on axes in the engine's own scale, not pico-newtons of
    round-off, and says so in the title."""
    a, _ = paper
    fig = figures.polar_figure(a, 1, "force")
    for trace in fig.data:
        assert np.all(np.asarray(trace.x) == 0.0) and np.all(np.asarray(trace.y) == 0.0)
    assert "0 N (balanced)" in fig.layout.title.text
    # every force of the inline-3 is zero: the axes span +-1 N
    assert tuple(fig.layout.yaxis.range) == (-1.0, 1.0)
    # a balanced order among unbalanced ones reads against the largest amplitude
    b, _ = inline4
    k = b.forces.order(1)
    assert b.forces.force_amplitude[k] < figures.roundoff_levels(b.model, 1e-12)[0]
    fig = figures.polar_figure(b, 1, "force")
    largest = max(b.forces.force_amplitude.max(), abs(b.forces.rotating_force))
    assert fig.layout.yaxis.range[1] == pytest.approx(1.15 * largest)
    assert "0 N (balanced)" in fig.layout.title.text


def test_leading_quantity(paper: tuple, inline4: tuple) -> None:
    """Inline-3: forces cancel, moments do not (2021 paper, Table 2); inline-4 has a free
    second-order force."""
    assert figures.leading_quantity(paper[0]) == "moment"
    assert figures.leading_quantity(inline4[0]) == "force"


def test_titles_fit_a_panel(paper: tuple) -> None:
    """The engine name goes to a second, smaller line, shortened when very long."""
    a, s = paper
    for fig in (
        figures.orders_bar(a),
        figures.curves_figure(a, s),
        figures.polar_figure(a, 1),
        figures.residuals_bar(s),
        figures.crank_3d(a.model),
    ):
        first, second = fig.layout.title.text.split("<br>")
        assert len(first) <= 60, first
        assert second.startswith("<sup>Inline-3, Table 1") and second.endswith("</sup>")
    title = figures.figure_title("Free forces", "x" * 200, "note")
    assert f"{'x' * (figures.TITLE_NAME_CHARS - 1)}… · note</sup>" in title, title


def test_zero_bars_say_balanced(paper: tuple, inline4: tuple) -> None:
    texts = [n.text for n in figures.orders_bar(paper[0]).layout.annotations]
    assert any("0 N everywhere" in t for t in texts), texts
    # inline-4 (flat crank): free 2nd-order force, no free moment (mirror-symmetric crank)
    texts = [n.text for n in figures.orders_bar(inline4[0]).layout.annotations]
    assert not any("0 N everywhere" in t for t in texts), texts
    assert any("0 N·m everywhere" in t for t in texts), texts


# --------------------------------------------------------------------------- 3-D
def test_crank_3d_has_every_mass(paper: tuple) -> None:
    a, b = paper
    fig = figures.crank_3d(b.model, b)
    cw = b.result.counterweights
    markers = [t for t in fig.data if t.mode == "markers" and t.legendgroup == "counterweights"]
    assert len(markers) == cw.count
    for t, y, d in zip(markers, cw.position, cw.direction, strict=True):
        assert t.x[0] == pytest.approx(y * 1e3)
        assert t.y[0] == pytest.approx(cw.cg_radius * np.sin(d) * 1e3)
        assert t.z[0] == pytest.approx(cw.cg_radius * np.cos(d) * 1e3)
    shaft_masses = [t for t in fig.data if t.mode == "markers" and "shaft" in t.legendgroup]
    assert len(shaft_masses) == 8  # two shafts per order, two masses each
    pins = [t for t in fig.data if t.legendgroup == "pin"]
    assert len(pins) == 3
    r = a.model.crank_radius * 1e3
    for t, phi in zip(pins, a.model.throw_angle, strict=True):
        assert t.z[0] == pytest.approx(r * np.cos(phi)) and t.y[0] == pytest.approx(r * np.sin(phi))
    # bare crank from a model alone
    assert not [t for t in figures.crank_3d(a.model).data if t.legendgroup == "counterweights"]


# --------------------------------------------------------------------------- residuals
def test_residuals_bar_equals_solver(inline4: tuple) -> None:
    _, b = inline4
    fig = figures.residuals_bar(b)
    comps = b.to_dict()["components"]
    tiny_f, tiny_m = figures.roundoff_levels(b.model)
    before_f, before_m = traces(fig, "before balancing")
    after_f, after_m = traces(fig, "after balancing")
    assert list(before_f.y) == pytest.approx([c["force_before_N"] for c in comps], abs=tiny_f)
    assert list(after_f.y) == pytest.approx([c["force_after_N"] for c in comps], abs=tiny_f)
    assert list(before_m.y) == pytest.approx([c["moment_before_Nm"] for c in comps], abs=tiny_m)
    assert list(after_m.y) == pytest.approx([c["moment_after_Nm"] for c in comps], abs=tiny_m)
    # inline-4 with counterweights: the second-order force is left, large and unchanged
    k = [c["component"] for c in comps].index("order2")
    assert before_f.y[k] == after_f.y[k] > 1000.0


# --------------------------------------------------------------------------- other studies
def test_single_cylinder_figures_match_study() -> None:
    from crankbalance.single_cylinder import balance_factor_study

    s = balance_factor_study(0.3, 0.03, 900.0, 0.5, rod_length=0.12)
    fig = figures.single_cylinder_forces(s)
    assert np.asarray(traces(fig, "in-line (cylinder axis)")[0].y) == pytest.approx(s.in_line)
    assert np.asarray(traces(fig, "transverse")[0].y) == pytest.approx(s.transverse)
    polar = figures.single_cylinder_polar(s)
    locus = traces(polar, "residual force")[0]
    # the locus is the force vector: its largest length is the study's peak resultant
    assert np.hypot(locus.x, locus.y).max() == pytest.approx(s.peak_resultant, rel=1e-3)
    sweep = figures.balance_factor_sweep(s)
    assert np.asarray(sweep.data[0].y) == pytest.approx(s.sweep_peak_resultant)
    best = [t for t in sweep.data if t.name.startswith("optimum")][0]
    assert best.y[0] == pytest.approx(np.min(s.sweep_peak_resultant), rel=1e-2)


def test_counterweight_figures_match_optimum() -> None:
    pytest.importorskip("shapely")
    from shapely.geometry import Polygon

    from crankbalance.counterweight_optimize import optimize_counterweight

    o = optimize_counterweight(0.036, rng=1, population=256, iterations=4, children=256)
    fig = figures.pareto_front(o)
    front = [t for t in fig.data if t.name.startswith("Pareto")][0]
    assert np.asarray(front.y) == pytest.approx(o.mass[o.pareto] * 1e3)
    least = [t for t in fig.data if t.name.startswith("least mass")][0]
    assert least.y[0] == pytest.approx(o.mass.min() * 1e3)
    least_r = [t for t in fig.data if t.name.startswith("least radius")][0]
    assert least_r.x[0] == pytest.approx(o.radius.min() * 1e3)
    design = o.least_mass_design
    prof = figures.counterweight_profile(design)
    outline = [t for t in prof.data if t.name == "profile"]
    area = sum(Polygon(np.column_stack([t.x, t.y])).area for t in outline)  # mm^2
    props = design.properties()
    assert area == pytest.approx(float(props.area) * 1e6, rel=1e-3), "drawn to scale"
    cg = [t for t in prof.data if t.name.startswith("CG")][0]
    assert cg.y[0] == pytest.approx(float(props.cg_radius) * 1e3)


def test_shaft_figures_match_study() -> None:
    from crankbalance.balance_shaft import BalanceShaft, inline4_study, shaft_response
    from crankbalance.beam import ShaftSection

    section = ShaftSection(outer_diameter=0.028)
    st = inline4_study(2e-4, 1300.0, 0.3, section)
    fig = figures.shaft_study(st)
    # legend at the bottom of the figure, below every axis title; x titles on the lower row
    assert fig.layout.legend.yref == "container" and fig.layout.legend.yanchor == "bottom"
    assert fig.layout.xaxis.title.text is None and fig.layout.xaxis3.title.text
    j = [t for t in fig.data if t.name.startswith("J (")][0]
    assert np.asarray(j.y) == pytest.approx(st.objective)
    opt = [t for t in fig.data if t.name.startswith("optimum")][0]
    assert opt.x[0] == pytest.approx(100 * st.optimum_position)
    shaft = BalanceShaft(0.3, section, (0.0, 0.3), (0.2,), (2e-4,), 1300.0)
    resp = shaft_response(shaft)
    f2 = figures.shaft_response_figure(resp, shaft)
    assert np.max(f2.data[0].y) == pytest.approx(resp.max_deflection * 1e6, rel=1e-6)


def test_performance_figures_match_results() -> None:
    from crankbalance.engine_cycle import CylinderSpec, balance_sensitivity, engine_cycle
    from crankbalance.rotor_bench import BenchSettings, disc_rotor, run_bench

    cyl = CylinderSpec(
        bore=0.0768,
        crank_radius=0.0269,
        rod_length=0.1076,
        reciprocating_mass=0.282,
        crank_inertia=6e-3,
        balance_factor=0.5,
    )
    angle = np.radians(np.arange(0.0, 720.0, 10.0)) - 2 * np.pi
    pressure = (angle, np.full_like(angle, 1e5))
    sens = balance_sensitivity(
        cyl, 900.0, pressure, [0.0, 0.5, 1.0], mass_scales=[1.0, 0.8], samples_per_revolution=72
    )
    fig = figures.sensitivity_figure(sens, ("peak_bearing_load", "friction_power"))
    lines = [t for t in fig.data if t.xaxis == "x"]
    assert len(lines) == 2
    assert np.asarray(lines[1].y) == pytest.approx(sens.peak_bearing_load[1])
    with pytest.raises(InputError, match="indicators"):
        figures.sensitivity_figure(sens, ("colour",))
    cyc = engine_cycle(cyl, 900.0, pressure, samples_per_revolution=72)
    cf = figures.cycle_figure(cyc)
    assert np.asarray(traces(cf, "net torque")[0].y) == pytest.approx(cyc.net_torque)
    bench = run_bench(
        disc_rotor(0.098, 0.036704, 0.020, 0.188, 0.4, hole_mass=0.0146, hole_radius=0.0293),
        BenchSettings(speed=300.0, ramp_time=0.2, hold_time=0.2, samples=100),
    )
    bf = figures.bench_figure(bench)
    assert np.asarray(traces(bf, "bearing A")[0].y) == pytest.approx(bench.bearing_load_a)
