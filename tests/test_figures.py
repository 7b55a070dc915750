"""Figure builders: every figure's data equals the API's numbers."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("plotly", reason="plotly is in the web/test extras")

from crankbalance.errors import InputError  # noqa: E402
from crankbalance.output.figures.balancing import balanced_curves, residuals_bar  # noqa: E402
from crankbalance.output.figures.common import TITLE_NAME_CHARS, figure_title, roundoff_levels  # noqa: E402
from crankbalance.output.figures.counterweight import counterweight_profile, pareto_front  # noqa: E402
from crankbalance.output.figures.crank3d import crank_3d  # noqa: E402
from crankbalance.output.figures.engine import (  # noqa: E402
    curves_figure,
    leading_quantity,
    orders_bar,
    polar_figure,
)
from crankbalance.output.figures.performance import bench_figure, cycle_figure, sensitivity_figure  # noqa: E402
from crankbalance.output.figures.shaft import shaft_response_figure, shaft_study  # noqa: E402
from crankbalance.output.figures.single import (  # noqa: E402
    balance_factor_sweep,
    single_cylinder_forces,
    single_cylinder_polar,
)
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
    fig = orders_bar(a)
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


def test_orders_bar_panels_say_their_unit_in_their_title(inline4: tuple) -> None:
    """Three panels side by side: no value-axis title between them (the roll panel's was
    drawn over the moment panel's last bar in a half-width card at 1280 px); each panel's
    title gives its unit instead."""
    fig = orders_bar(inline4[0])
    titles = [a.text for a in fig.layout.annotations if a.yref == "paper"][:3]
    assert titles == [
        "Free forces<br>(x, z) [N]",
        "Free moments<br>(x, z) [N·m]",
        "Roll moment<br>(y) [N·m]",
    ]
    for key in ("yaxis", "yaxis2", "yaxis3"):
        assert fig.layout[key].title.text is None, key


def test_orders_bar_drops_roundoff(paper: tuple) -> None:
    """Inline-3: the free forces cancel; round-off (~1e-12 N) is drawn as exactly zero."""
    a, _ = paper
    fig = orders_bar(a)
    fwd_f = traces(fig, "forward (co-rotating)")[0]
    assert np.all(np.asarray(fwd_f.y)[:-1] == 0.0)


# --------------------------------------------------------------------------- curves
def test_curves_match_api_and_phasors(inline4: tuple) -> None:
    a, _ = inline4
    fig = curves_figure(a, quantity="force")
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
    after = balanced_curves(a, b)
    m_scale = np.abs(after.before_mx).max()
    assert m_scale > 100.0
    for name in ("after_fx", "after_fz"):
        assert np.abs(getattr(after, name)).max() < 1e-8
    for name in ("after_mx", "after_mz"):
        assert np.abs(getattr(after, name)).max() < 1e-10 * m_scale
    fig = curves_figure(a, b, quantity="moment")
    assert np.all(np.asarray(traces(fig, "engine after balancing")[0].y) == 0.0)
    before = np.asarray(traces(fig, "engine before balancing")[0].y)
    assert before == pytest.approx(after.before_mx)


def test_curves_after_partial_balance_match_residuals(inline4: tuple) -> None:
    """Inline-4 with counterweights only: what is left after balancing is the second-order
    force; the curve's peak equals the solver's residual of order 2 plus higher orders."""
    a, b = inline4
    after = balanced_curves(a, b)
    f = after.after_fx + 1j * after.after_fz
    spectrum = np.fft.fft(f) / f.size
    amp2 = abs(spectrum[2]) + abs(spectrum[-2])
    assert amp2 == pytest.approx(b.result.residual("order2").force_after, rel=1e-6)
    amp1 = abs(spectrum[1]) + abs(spectrum[-1])
    assert amp1 == pytest.approx(b.result.residual("order1").force_after, abs=1e-6)


def test_curves_reject_other_engine(paper: tuple, inline4: tuple) -> None:
    with pytest.raises(InputError, match="balance_study"):
        curves_figure(paper[0], inline4[1])
    with pytest.raises(InputError, match="quantity"):
        curves_figure(paper[0], quantity="torque")  # type: ignore[arg-type]


# --------------------------------------------------------------------------- polar
def test_polar_phasors_and_locus(paper: tuple) -> None:
    a, _ = paper
    fig = polar_figure(a, 1, "moment")
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
    fig = polar_figure(a, "rotating", "force")
    assert np.hypot(fig.data[0].x, fig.data[0].y).max() == pytest.approx(
        abs(a.forces.rotating_force), rel=1e-6, abs=1e-9
    )
    for bad in (0.5, 99, "two"):
        with pytest.raises(InputError, match="order"):
            polar_figure(a, bad)  # type: ignore[arg-type]


def test_polar_of_a_balanced_order_is_exactly_zero(paper: tuple, inline4: tuple) -> None:
    """Inline-3: the order-1 force cancels (2021 paper, Table 2: no primary force to balance);
    the diagram draws exact zeros on axes in the engine's own scale, not pico-newtons of
    round-off, and says so in the title."""
    a, _ = paper
    fig = polar_figure(a, 1, "force")
    for trace in fig.data:
        assert np.all(np.asarray(trace.x) == 0.0) and np.all(np.asarray(trace.y) == 0.0)
    assert "0 N (balanced)" in fig.layout.title.text
    # every force of the inline-3 is zero: the axes span +-1 N
    assert tuple(fig.layout.yaxis.range) == (-1.0, 1.0)
    # a balanced order among unbalanced ones reads against the largest amplitude
    b, _ = inline4
    k = b.forces.order(1)
    assert b.forces.force_amplitude[k] < roundoff_levels(b.model, 1e-12)[0]
    fig = polar_figure(b, 1, "force")
    largest = max(b.forces.force_amplitude.max(), abs(b.forces.rotating_force))
    assert fig.layout.yaxis.range[1] == pytest.approx(1.15 * largest)
    assert "0 N (balanced)" in fig.layout.title.text


def test_leading_quantity(paper: tuple, inline4: tuple) -> None:
    """Inline-3: forces cancel, moments do not (2021 paper, Table 2); inline-4 has a free
    second-order force."""
    assert leading_quantity(paper[0]) == "moment"
    assert leading_quantity(inline4[0]) == "force"


def test_titles_fit_a_panel(paper: tuple) -> None:
    """The engine name goes to a second, smaller line, shortened when very long."""
    a, s = paper
    for fig in (
        orders_bar(a),
        curves_figure(a, s),
        polar_figure(a, 1),
        residuals_bar(s),
        crank_3d(a.model),
    ):
        first, second = fig.layout.title.text.split("<br>")
        assert len(first) <= 60, first
        assert second.startswith("<sup>Inline-3, Table 1") and second.endswith("</sup>")
    title = figure_title("Free forces", "x" * 200, "note")
    assert f"{'x' * (TITLE_NAME_CHARS - 1)}… · note</sup>" in title, title


def test_zero_bars_say_balanced(paper: tuple, inline4: tuple) -> None:
    texts = [n.text for n in orders_bar(paper[0]).layout.annotations]
    assert any("0 N everywhere" in t for t in texts), texts
    # inline-4 (flat crank): free 2nd-order force, no free moment (mirror-symmetric crank)
    texts = [n.text for n in orders_bar(inline4[0]).layout.annotations]
    assert not any("0 N everywhere" in t for t in texts), texts
    assert any("0 N·m everywhere" in t for t in texts), texts


# --------------------------------------------------------------------------- 3-D
def drawn_3d(fig) -> tuple[list, list, list]:
    """What a 3-D figure draws, whatever the traces it is split into: line segments
    (name, legend group, line style, end points [mm], hover text), markers (name, legend
    group, colour, size, point [mm], hover text) and the legend's names in order."""
    segments, markers, legend = [], [], []
    for t in fig.data:
        if t.showlegend:
            legend.append(t.name)
        n = len(t.x)
        text = list(t.text) if isinstance(t.text, list | tuple) else [t.text] * n
        points = [None if t.x[k] is None else (t.x[k], t.y[k], t.z[k]) for k in range(n)]
        if t.mode == "markers":
            size = t.marker.size
            sizes = list(size) if isinstance(size, list | tuple) else [size] * n
            for k in range(n):
                markers.append(
                    (t.name, t.legendgroup, t.marker.color, sizes[k], points[k], text[k])
                )
            continue
        assert t.mode == "lines"
        style = (t.line.color, t.line.width, t.line.dash, t.hoverinfo)
        for k in range(0, n, 3):  # two points per segment, then a None break
            assert points[k] is not None and points[k + 1] is not None
            assert k + 2 == n or points[k + 2] is None
            assert text[k] == text[k + 1]
            segments.append((t.name, t.legendgroup, style, points[k], points[k + 1], text[k]))
    return segments, markers, legend


def test_crank_3d_has_every_mass(paper: tuple) -> None:
    a, b = paper
    segments, markers, legend = drawn_3d(crank_3d(b.model, b))
    cw = b.result.counterweights
    cws = [m for m in markers if m[1] == "counterweights"]
    assert len(cws) == cw.count
    for m, y, d in zip(cws, cw.position, cw.direction, strict=True):
        assert m[4] == pytest.approx(
            (y * 1e3, cw.cg_radius * np.sin(d) * 1e3, cw.cg_radius * np.cos(d) * 1e3)
        )
    shaft_masses = [m for m in markers if "shaft" in m[1]]
    assert len(shaft_masses) == 8  # two shafts per order, two masses each
    # one arm per mass, from its shaft's axis to the mass
    arms = [s for s in segments if "shaft" in s[1] and s[3][0] == s[4][0]]
    assert sorted(s[4] for s in arms) == sorted(m[4] for m in shaft_masses)
    pins = [s for s in segments if s[1] == "pin"]
    assert len(pins) == 3
    r = a.model.crank_radius * 1e3
    for s, phi in zip(pins, a.model.throw_angle, strict=True):
        assert s[3][2] == pytest.approx(r * np.cos(phi)) and s[3][1] == pytest.approx(
            r * np.sin(phi)
        )
        assert s[5].startswith(f"throw {pins.index(s) + 1}: angle")
    assert legend.count("counterweights") == 1 and legend.count("webs") == 1
    # bare crank from a model alone
    assert not [m for m in drawn_3d(crank_3d(a.model))[1] if m[1] == "counterweights"]


# Drawn by crank_3d before its segments were merged into one trace per legend entry
# (one trace per segment then): segments, markers, bounding box of every point [mm], sums
# of |coordinates| [mm] and of their squares [mm²] and of marker sizes, legend names in
# order.
LEGEND = ["crank axis / main journals", "crankpins", "webs", "cylinder axes (stroke)"]
SHAFTS = [f"order-{k} shaft, {s}-rotating" for k in (1, 2) for s in ("co", "counter")]
BEFORE_MERGE = {
    ("paper-inline3", True): (
        29,
        12,
        (-135.0, -135.0, -133.480762),
        (135.0, 135.0, 255.0),
        14107.8203,
        1571887.5,
        148.688688,
        [*LEGEND, "counterweights", *SHAFTS],
    ),
    ("paper-inline3", False): (
        13,
        0,
        (-135.0, -34.641016, -20.0),
        (135.0, 34.641016, 255.0),
        3732.1281,
        481312.5,
        0.0,
        LEGEND,
    ),
    ("v12-60", True): (
        43,
        12,
        (-336.0, -148.0, -40.703194),
        (336.0, 148.0, 256.34352),
        27769.87,
        5441632.0,
        216.0,
        [*LEGEND, "counterweights"],
    ),
    ("radial5", True): (
        11,
        2,
        (-75.0, -461.26241, -392.373242),
        (75.0, 461.26241, 485.0),
        6377.2762,
        1810375.0,
        36.0,
        [*LEGEND, "counterweights"],
    ),
    ("single", False): (5, 0, (-31.0, 0.0, 0.0), (31.0, 0.0, 203.0), 623.0, 68297.5, 0.0, LEGEND),
    ("w12", True): (
        33,
        8,
        (-224.0, -256.34352, -23.5),
        (224.0, 256.34352, 296.0),
        18000.7474,
        2878672.0,
        144.0,
        [*LEGEND, "counterweights"],
    ),
    ("boxer4", True): (
        25,
        8,
        (-184.0, -274.0, 0.0),
        (184.0, 274.0, 0.0),
        8744.0,
        1186432.0,
        144.0,
        [*LEGEND, "counterweights"],
    ),
}


@pytest.mark.parametrize(("engine", "balanced"), list(BEFORE_MERGE))
def test_crank_3d_draws_the_same_geometry_in_few_traces(engine: str, balanced: bool) -> None:
    """Same points, sizes and legend as the one-trace-per-segment figure, in at most one
    lines trace per line style and one markers trace per legend entry."""
    # the cranks balanced as a whole with each half's counterweights, as drawn before
    b = balance_engine(engine, halves_if_balanced=True)
    fig = crank_3d(b.model, b if balanced else None)
    segments, markers, legend = drawn_3d(fig)
    points = np.array([p for s in segments for p in s[3:5]] + [m[4] for m in markers])
    n_seg, n_mark, lo, hi, coords, squares, sizes, names = BEFORE_MERGE[engine, balanced]
    assert (len(segments), len(markers)) == (n_seg, n_mark)
    assert points.min(axis=0) == pytest.approx(lo, abs=1e-6)
    assert points.max(axis=0) == pytest.approx(hi, abs=1e-6)
    assert np.abs(points).sum() == pytest.approx(coords, abs=1e-3)
    assert np.square(points).sum() == pytest.approx(squares, rel=1e-9)
    assert sum(m[3] for m in markers) == pytest.approx(sizes, abs=1e-5)
    assert legend == names
    styles = {(s[0], s[2]) for s in segments} | {(m[0], "markers") for m in markers}
    assert len(fig.data) == len(styles)


# --------------------------------------------------------------------------- residuals
def test_residuals_bar_equals_solver(inline4: tuple) -> None:
    _, b = inline4
    fig = residuals_bar(b)
    comps = b.to_dict()["components"]
    tiny_f, tiny_m = roundoff_levels(b.model)
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
    from crankbalance.physics.single_cylinder import balance_factor_study

    s = balance_factor_study(0.3, 0.03, 900.0, 0.5, rod_length=0.12)
    fig = single_cylinder_forces(s)
    assert np.asarray(traces(fig, "in-line (cylinder axis)")[0].y) == pytest.approx(s.in_line)
    assert np.asarray(traces(fig, "transverse")[0].y) == pytest.approx(s.transverse)
    polar = single_cylinder_polar(s)
    locus = traces(polar, "residual force")[0]
    # the locus is the force vector: its largest length is the study's peak resultant
    assert np.hypot(locus.x, locus.y).max() == pytest.approx(s.peak_resultant, rel=1e-3)
    sweep = balance_factor_sweep(s)
    assert np.asarray(sweep.data[0].y) == pytest.approx(s.sweep_peak_resultant)
    best = [t for t in sweep.data if t.name.startswith("optimum")][0]
    assert best.y[0] == pytest.approx(np.min(s.sweep_peak_resultant), rel=1e-2)


def test_counterweight_figures_match_optimum() -> None:
    pytest.importorskip("shapely")
    from shapely.geometry import Polygon

    from crankbalance.physics.counterweight_optimize import optimize_counterweight

    o = optimize_counterweight(0.036, rng=1, population=256, iterations=4, children=256)
    fig = pareto_front(o)
    front = [t for t in fig.data if t.name.startswith("Pareto")][0]
    assert np.asarray(front.y) == pytest.approx(o.mass[o.pareto] * 1e3)
    least = [t for t in fig.data if t.name.startswith("least mass")][0]
    assert least.y[0] == pytest.approx(o.mass.min() * 1e3)
    least_r = [t for t in fig.data if t.name.startswith("least radius")][0]
    assert least_r.x[0] == pytest.approx(o.radius.min() * 1e3)
    design = o.least_mass_design
    prof = counterweight_profile(design)
    outline = [t for t in prof.data if t.name == "profile"]
    area = sum(Polygon(np.column_stack([t.x, t.y])).area for t in outline)  # mm^2
    props = design.properties()
    assert area == pytest.approx(float(props.area) * 1e6, rel=1e-3), "drawn to scale"
    cg = [t for t in prof.data if t.name.startswith("CG")][0]
    assert cg.y[0] == pytest.approx(float(props.cg_radius) * 1e3)
    # a front larger than the points drawn: evenly along it, both ends, the whole count named
    small = pareto_front(o, max_points=5)
    assert o.pareto.size > 5
    drawn = [t for t in small.data if t.name.startswith("Pareto")][0]
    assert drawn.name == f"Pareto front ({o.pareto.size}, 5 drawn)"
    assert np.asarray(drawn.x).size == 5
    ends = o.pareto[[0, -1]]
    assert np.asarray(drawn.y)[[0, -1]] == pytest.approx(o.mass[ends] * 1e3)


def test_counterweight_drawing_has_the_crank_parts_at_their_radii() -> None:
    """A design for an engine is drawn with its journal about the axis, its crankpin
    opposite the counterweight at the crank radius and the radial limit (issue 28, item 4):
    in the figure every edge shows (``plot`` of the study's result)."""
    from crankbalance import plot
    from crankbalance.schema.settings import CounterweightDesignOptions, parse_options
    from crankbalance.studies.counterweight import crank_outline, design
    from crankbalance.studies.engine import as_model

    settings = parse_options(
        CounterweightDesignOptions,
        {
            "web_radius": "20 mm",
            "rectangle_height": "20 mm",
            "trapezoid_angle": "0 deg",
            "segment_radius": "60 mm",
            "segment_angle": "120 deg",
        },
    )
    result = design("inline4", settings)
    model = as_model("inline4")
    r = model.crank_radius * 1e3
    assert result.crank == crank_outline("inline4")
    (fig,) = plot(result)

    def trace(prefix: str):
        (found,) = [t for t in fig.data if t.name.startswith(prefix)]
        return np.asarray(found.x, dtype=float), np.asarray(found.y, dtype=float)

    x, y = trace("main journal")
    assert np.hypot(x, y) == pytest.approx(result.crank.journal_diameter / 2 * 1e3)
    x, y = trace("crankpin")
    assert np.hypot(x, y + r) == pytest.approx(result.crank.pin_diameter / 2 * 1e3)
    assert result.crank.pin_diameter == pytest.approx(1.1 * model.crank_radius)
    x, y = trace("radial limit")
    space = (model.rod_length - model.crank_radius) * 1e3
    assert np.hypot(x, y) == pytest.approx(space)
    assert (
        "rod length - crank radius" in [t.name for t in fig.data if t.name.startswith("radial")][0]
    )
    cg = [t for t in fig.data if t.name.startswith("CG")][0]
    assert cg.y[0] > 0 > -r, "the crankpin is drawn opposite the counterweight"
    # the drawing reaches the crankpin's far edge and the limit
    reach = max(space, r + result.crank.pin_diameter / 2 * 1e3)
    assert fig.layout.xaxis.range[1] >= reach
    typed = crank_outline("inline4", 0.07)
    assert (typed.radial_limit, typed.limit_source) == (0.07, "typed")


def test_shaft_figures_match_study() -> None:
    from crankbalance.physics.balance_shaft import BalanceShaft, inline4_study, shaft_response
    from crankbalance.physics.beam import ShaftSection

    section = ShaftSection(outer_diameter=0.028)
    st = inline4_study(2e-4, 1300.0, 0.3, section)
    fig = shaft_study(st)
    assert "inline4" not in fig.layout.title.text  # the study's case is not the engine
    named = shaft_study(st, "Single cylinder", "free second-order force of 3081 N")
    assert "Single cylinder · free second-order force of 3081 N" in named.layout.title.text
    # legend at the bottom of the figure, below every axis title; x titles on the lower row
    assert fig.layout.legend.yref == "container" and fig.layout.legend.yanchor == "bottom"
    assert fig.layout.xaxis.title.text is None and fig.layout.xaxis3.title.text
    j = [t for t in fig.data if t.name.startswith("J (")][0]
    assert np.asarray(j.y) == pytest.approx(st.objective)
    opt = [t for t in fig.data if t.name.startswith("optimum")][0]
    assert opt.x[0] == pytest.approx(100 * st.optimum_position)
    shaft = BalanceShaft(0.3, section, (0.0, 0.3), (0.2,), (2e-4,), 1300.0)
    resp = shaft_response(shaft)
    f2 = shaft_response_figure(resp, shaft)
    assert np.max(f2.data[0].y) == pytest.approx(resp.max_deflection * 1e6, rel=1e-6)


def test_performance_figures_match_results() -> None:
    from crankbalance.physics.engine_cycle import CylinderSpec, balance_sensitivity, engine_cycle
    from crankbalance.physics.rotor_bench import BenchSettings, disc_rotor, run_bench

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
    fig = sensitivity_figure(sens, ("peak_bearing_load", "friction_power"))
    lines = [t for t in fig.data if t.xaxis == "x"]
    assert len(lines) == 2
    assert np.asarray(lines[1].y) == pytest.approx(sens.peak_bearing_load[1])
    with pytest.raises(InputError, match="indicators"):
        sensitivity_figure(sens, ("colour",))
    cyc = engine_cycle(cyl, 900.0, pressure, samples_per_revolution=72)
    cf = cycle_figure(cyc)
    assert np.asarray(traces(cf, "net torque")[0].y) == pytest.approx(cyc.net_torque)
    bench = run_bench(
        disc_rotor(0.098, 0.036704, 0.020, 0.188, 0.4, hole_mass=0.0146, hole_radius=0.0293),
        BenchSettings(speed=300.0, ramp_time=0.2, hold_time=0.2, samples=100),
    )
    bf = bench_figure(bench)
    assert np.asarray(traces(bf, "bearing A")[0].y) == pytest.approx(bench.bearing_load_a)


def test_drilling_plan_refuses_a_face_correction() -> None:
    """The drilling plan draws drilled holes only: a rebalancing by face removal is refused
    by its kind (the plan tells the two corrections apart by their type)."""
    from crankbalance.output.figures.single import drilling_plan
    from crankbalance.physics.rebalancing import FaceRemoval, rebalance

    face = FaceRemoval(area=4e-4, radius=0.05)
    reb = rebalance(0.8, 0.4, 0.8, 0.39, 1.2, 0.031, 0.031, face, 1e-9)
    with pytest.raises(InputError) as caught:
        drilling_plan(reb, 0.031)
    assert (caught.value.field, caught.value.value) == ("correction", "face")
    assert "the plan draws holes" in str(caught.value)


def test_engine_torque_figure_of_one_cylinder_is_the_cycle_figure() -> None:
    """A single cylinder's cycle (CycleResult) gets the cycle figure, the whole engine's
    (EngineCycleResult) its torque figure."""
    from crankbalance.output.figures.performance import engine_torque_figure
    from crankbalance.schema.settings import CycleOptions, parse_options
    from crankbalance.studies.cycle import cycle

    one = cycle(None, parse_options(CycleOptions, {}))
    whole = cycle("inline4", parse_options(CycleOptions, {}))
    assert engine_torque_figure(one.result).to_dict() == cycle_figure(one.result).to_dict()
    names = [t.name for t in engine_torque_figure(whole.result).data]
    assert [n for n in names if n.startswith("cylinder")] == [f"cylinder {k}" for k in range(1, 5)]


def test_crank_3d_takes_an_analysis_or_a_balancing_study() -> None:
    """crank_3d(analysis) draws the analysis' engine, crank_3d(study) the study's engine
    with its balancing, as crank_3d(model) and crank_3d(model, study) do."""
    b = balance_engine("inline4")
    a = analyze(b.model)
    assert crank_3d(b).to_dict() == crank_3d(b.model, b).to_dict()
    assert crank_3d(a).to_dict() == crank_3d(a.model).to_dict()
    assert crank_3d(b).to_dict() != crank_3d(b.model).to_dict()


def test_polar_titles_and_legends_in_the_output_vocabulary(inline4: tuple) -> None:
    """Numbers in the polar figures' titles and legends as the results print them (5
    significant digits, whole from 10^5): the inline-4's second-order force is 12804 N, not
    1.28e+04 N; the single cylinder's primary force 32490 N, not 3.249e+04 N."""
    from crankbalance.physics.single_cylinder import balance_factor_study

    a, _ = inline4
    fig = polar_figure(a, 2, "force")
    assert fig.layout.title.text.startswith("Order 2 force: amplitude 12804 N")
    assert "at crank angle 0: 12804 N" in [t.name for t in fig.data]
    s = balance_factor_study(0.3, 0.03, 1900.0, 0.5, rod_length=0.12)
    figures = (single_cylinder_polar(s), single_cylinder_forces(s), balance_factor_sweep(s))
    assert "primary force P = 32490 N (no balance)" in [t.name for t in figures[0].data]
    for g in (fig, *figures):
        words = [g.layout.title.text, *(t.name for t in g.data)]
        assert not any("e+" in w for w in words), words
