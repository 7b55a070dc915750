"""Figure builders: every figure's data equals the API's numbers; static export works."""

from __future__ import annotations

import re
import shutil

import numpy as np
import pytest

pytest.importorskip("plotly", reason="plotly is in the web/test extras")

from crankbalance import plots  # noqa: E402
from crankbalance.analysis import analyze, balance_engine  # noqa: E402
from crankbalance.errors import InputError  # noqa: E402


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
    fig = plots.orders_bar(a)
    data = a.to_dict()
    fwd_f, fwd_m = traces(fig, "forward (co-rotating)")
    bwd_f, bwd_m = traces(fig, "backward (counter-rotating)")
    height_f = np.asarray(fwd_f.y) + np.asarray(bwd_f.y)
    height_m = np.asarray(fwd_m.y) + np.asarray(bwd_m.y)
    assert height_f[:-1] == pytest.approx([r["amplitude_N"] for r in data["free_forces"]])
    assert height_m[:-1] == pytest.approx([r["amplitude_Nm"] for r in data["free_moments"]])
    assert np.asarray(fwd_f.y)[:-1] == pytest.approx([r["forward_N"] for r in data["free_forces"]])
    assert np.asarray(bwd_f.y)[:-1] == pytest.approx(
        [r["backward_N"] for r in data["free_forces"]])
    assert height_f[-1] == pytest.approx(data["rotating"]["force_N"])
    assert height_m[-1] == pytest.approx(data["rotating"]["moment_Nm"])
    # inline-4: second order force is the largest free force (textbook: 4 m r w^2 lambda)
    assert np.argmax(height_f[:-1]) == 1


def test_orders_bar_drops_roundoff(paper: tuple) -> None:
    """Inline-3: the free forces cancel; round-off (~1e-12 N) is drawn as exactly zero."""
    a, _ = paper
    fig = plots.orders_bar(a)
    fwd_f = traces(fig, "forward (co-rotating)")[0]
    assert np.all(np.asarray(fwd_f.y)[:-1] == 0.0)


# --------------------------------------------------------------------------- curves
def test_curves_match_api_and_phasors(inline4: tuple) -> None:
    a, _ = inline4
    fig = plots.curves_figure(a, quantity="force")
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
    after = plots.balanced_curves(a, b)
    m_scale = np.abs(after.before_mx).max()
    assert m_scale > 100.0
    for name in ("after_fx", "after_fz"):
        assert np.abs(getattr(after, name)).max() < 1e-8
    for name in ("after_mx", "after_mz"):
        assert np.abs(getattr(after, name)).max() < 1e-10 * m_scale
    fig = plots.curves_figure(a, b, quantity="moment")
    assert np.all(np.asarray(traces(fig, "engine after balancing")[0].y) == 0.0)
    before = np.asarray(traces(fig, "engine before balancing")[0].y)
    assert before == pytest.approx(after.before_mx)


def test_curves_after_partial_balance_match_residuals(inline4: tuple) -> None:
    """Inline-4 with counterweights only: what is left after balancing is the second-order
    force; the curve's peak equals the solver's residual of order 2 plus higher orders."""
    a, b = inline4
    after = plots.balanced_curves(a, b)
    f = after.after_fx + 1j * after.after_fz
    spectrum = np.fft.fft(f) / f.size
    amp2 = abs(spectrum[2]) + abs(spectrum[-2])
    assert amp2 == pytest.approx(b.result.residual("order2").force_after, rel=1e-6)
    amp1 = abs(spectrum[1]) + abs(spectrum[-1])
    assert amp1 == pytest.approx(b.result.residual("order1").force_after, abs=1e-6)


def test_curves_reject_other_engine(paper: tuple, inline4: tuple) -> None:
    with pytest.raises(InputError, match="balance_study"):
        plots.curves_figure(paper[0], inline4[1])
    with pytest.raises(InputError, match="quantity"):
        plots.curves_figure(paper[0], quantity="torque")  # type: ignore[arg-type]


# --------------------------------------------------------------------------- polar
def test_polar_phasors_and_locus(paper: tuple) -> None:
    a, _ = paper
    fig = plots.polar_figure(a, 1, "moment")
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
    # the direction at crank angle 0 agrees with the phase the JSON reports
    data = a.to_dict()["free_moments"][0]
    assert np.degrees(np.arctan2(arrow_f.x[1], arrow_f.y[1])) == pytest.approx(
        data["forward_phase_deg"])


def test_polar_rotating_and_bad_order(inline4: tuple) -> None:
    a, _ = inline4
    fig = plots.polar_figure(a, "rotating", "force")
    assert np.hypot(fig.data[0].x, fig.data[0].y).max() == pytest.approx(
        abs(a.forces.rotating_force), rel=1e-6, abs=1e-9)
    for bad in (0.5, 99, "two"):
        with pytest.raises(InputError, match="order"):
            plots.polar_figure(a, bad)  # type: ignore[arg-type]


# --------------------------------------------------------------------------- 3-D
def test_crank_3d_has_every_mass(paper: tuple) -> None:
    a, b = paper
    fig = plots.crank_3d(b.model, b)
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
        assert t.z[0] == pytest.approx(r * np.cos(phi)) and t.y[0] == pytest.approx(
            r * np.sin(phi))
    # bare crank from a model alone
    assert not [t for t in plots.crank_3d(a.model).data if t.legendgroup == "counterweights"]


# --------------------------------------------------------------------------- residuals
def test_residuals_bar_equals_solver(inline4: tuple) -> None:
    _, b = inline4
    fig = plots.residuals_bar(b)
    comps = b.to_dict()["components"]
    before_f, before_m = traces(fig, "before balancing")
    after_f, after_m = traces(fig, "after balancing")
    assert list(before_f.y) == pytest.approx([c["force_before_N"] for c in comps])
    assert list(after_f.y) == pytest.approx([c["force_after_N"] for c in comps])
    assert list(before_m.y) == pytest.approx([c["moment_before_Nm"] for c in comps])
    assert list(after_m.y) == pytest.approx([c["moment_after_Nm"] for c in comps])


# --------------------------------------------------------------------------- export
chromium = pytest.mark.skipif(
    not (shutil.which("chromium") or shutil.which("google-chrome")),
    reason="static export needs a Chromium for kaleido (apt package chromium)")


@chromium
def test_to_image_png_and_svg(inline4: tuple) -> None:
    fig = plots.orders_bar(inline4[0])
    png = plots.to_image(fig, "png", width=500, height=300)
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    # IHDR: width and height as asked
    assert int.from_bytes(png[16:20], "big") == 500 and int.from_bytes(png[20:24], "big") == 300
    svg = plots.to_image(fig, "svg")
    assert svg.lstrip().startswith(b"<svg") and b"</svg>" in svg
    with pytest.raises(InputError, match="format"):
        plots.to_image(fig, "gif")  # type: ignore[arg-type]


def test_to_html_is_self_contained(inline4: tuple) -> None:
    html = plots.to_html(plots.orders_bar(inline4[0]))
    assert html.lstrip().lower().startswith("<!doctype html>")
    assert not re.search(r"<script[^>]*\ssrc=", html), "plotly.js must be inlined"
    assert "Plotly.newPlot" in html
