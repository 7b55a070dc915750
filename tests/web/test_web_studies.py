"""Web app, study tabs (Counterweight design, Single cylinder, Balance shaft, Performance)
through NiceGUI's simulated User: enter values, compute, read results against the API."""

from __future__ import annotations

import pytest
from nicegui.testing.user import User

from crankbalance.physics.tolerance import permissible_unbalance
from crankbalance.studies.cylinder import cylinder_study
from crankbalance.studies.engine import analyze, balance_engine

pytestmark = pytest.mark.anyio


async def test_counterweight_design_tab(user: User, form) -> None:
    await user.open("/")
    form.open("counterweight")
    required = form.text("cw-requirement")
    cw = balance_engine("paper-inline3").result.counterweights
    # first moment m_c r_c of Table 2's counterweight: 1.2413 kg x 30 mm = 37239 g*mm
    assert f"{cw.mass.max() * cw.cg_radius * 1e6:.0f} g·mm" in required, required
    assert "from the balancing" in required, required
    form.set("setting-cw_iterations", "3")
    form.set("setting-cw_population", "256")
    form.set("setting-cw_max_radius", "120 mm")
    user.find(marker="optimise").click()
    await form.until(
        lambda: "feasible designs" in form.text("cw-summary") or "Error" in form.text("cw-summary")
    )
    summary = form.text("cw-summary")
    assert "Least mass" in summary and "Pareto front" in summary, summary
    assert form.element("figure-pareto").visible
    assert form.element("figure-profile").visible
    svg = (await form.download("export-svg")).decode()
    assert svg.lstrip().startswith("<") and "svg" in svg[:200]
    dxf = (await form.download("export-dxf")).decode()
    assert "SECTION" in dxf
    stl = await form.download("export-stl")
    assert len(stl) > 84


async def test_counterweight_requirement_of_the_halves(user: User, form) -> None:
    """A crank balanced as a whole (the flat inline-4: no counterweights from the
    balancing) takes each half balanced on its own, and the tab says so."""
    await user.open("/?preset=inline4")
    form.open("counterweight")
    required = form.text("cw-requirement")
    assert "each half of the crank balanced on its own" in required, required
    assert "from the balancing" not in required, required


async def test_counterweight_bad_constraint(user: User, form) -> None:
    await user.open("/")
    form.open("counterweight")
    form.set("setting-cw_density", "8000 kg")
    assert "density" in (form.error("setting-cw_density") or "")
    form.set("setting-cw_iterations", "many")
    assert form.error("setting-cw_iterations")
    user.find(marker="optimise").click()
    await form.until(lambda: form.text("cw-summary") not in ("", "optimising …"))
    summary = form.text("cw-summary")
    assert "Density" in summary or "Iterations" in summary, summary  # the form's labels
    assert "cw_" not in summary, summary


async def test_single_cylinder_tab(user: User, form) -> None:
    await user.open("/?preset=single")
    form.open("single")
    form.set("setting-sc_balance_factor", "0.6")
    form.set("setting-sc_residual", "5 g*mm")
    user.find(marker="run-single").click()
    await form.until(lambda: "Primary force" in form.text("single-summary"))
    spec_study = balance_engine("single")
    ref = cylinder_study(spec_study.model, 1, 0.6)
    summary = form.text("single-summary")
    assert f"{ref.peak_resultant:.1f} N" in summary, (summary, ref.peak_resultant)
    assert f"{ref.optimum_balance_factor:.3f}" in summary
    # review finding 29: the engine itself is balanced at its own factor (0 for the
    # single), which the Results tab shows; the card says both
    assert "This study is at f\\_b = 0.6" in summary, summary
    assert "the engine is balanced at f\\_b = 0 (the Engine form's" in summary, summary
    iso = form.text("iso-summary")
    mass = float(spec_study.model.throw_rotating_mass.sum())
    u_per = permissible_unbalance("G6.3", mass, spec_study.model.speed)
    assert f"{u_per * 1e6:.2f} g·mm" in iso, (iso, u_per)
    assert ("PASS" in iso) == (5e-6 <= u_per)
    assert "Unbalance to remove" in form.text("rebalance-summary")
    assert form.element("figure-single-forces").visible


async def test_single_cylinder_bad_inputs(user: User, form) -> None:
    await user.open("/?preset=single")
    form.open("single")
    form.set("setting-sc_cylinder", "2")
    user.find(marker="run-single").click()
    await form.until(lambda: form.error("setting-sc_cylinder"))
    assert "1 to 1" in (form.error("setting-sc_cylinder") or "")
    form.set("setting-sc_cylinder", "1")
    form.set("setting-sc_grade", "G7")
    user.find(marker="run-single").click()
    await form.until(lambda: form.error("setting-sc_grade"))
    assert "G6.3" in (form.error("setting-sc_grade") or "")


async def test_balance_shaft_tab(user: User, form) -> None:
    await user.open("/?preset=inline4")
    form.open("shaft")
    user.find(marker="run-shaft").click()
    await form.until(lambda: "optimum" in form.text("shaft-summary"))
    assert "of the shaft length" in form.text("shaft-summary")
    assert form.element("figure-shaft").visible
    form.set("setting-bs_diameter", "-3 mm")
    user.find(marker="run-shaft").click()
    await form.until(lambda: form.error("setting-bs_diameter"))


async def test_balance_shaft_words_and_figure_title(user: User, form) -> None:
    """The free force in the output vocabulary (no e-notation); the figure's title names
    the engine and the force the shaft balances, not the study's internal case."""
    await user.open("/?preset=inline4")
    form.open("shaft")
    force = analyze("inline4").to_dict()["free_forces"][1]["amplitude_N"]
    assert f"free second-order force of {force:.0f} N" in form.text("shaft-applies")
    user.find(marker="run-shaft").click()
    await form.until(lambda: "optimum" in form.text("shaft-summary"))
    title = form.element("figure-shaft").figure["layout"]["title"]["text"]
    assert "(inline4)" not in title and f"second-order force of {force:.0f} N" in title, title
    assert balance_engine("inline4").model.name.split()[0] in title, title
    assert form.text("shaft-not-applicable") == ""


async def test_balance_shaft_refusal_said_once(user: User, form) -> None:
    """An engine the study does not apply to: the red line says why, no toast repeats it,
    and the figure card says "not applicable" with the reason instead of an empty box."""
    await user.open("/?preset=v8-crossplane")
    form.open("shaft")
    user.find(marker="run-shaft").click()
    await form.until(lambda: form.text("shaft-not-applicable"))
    assert "does not apply" in form.text("shaft-applies")
    note = form.text("shaft-not-applicable")
    assert note.startswith("not applicable: Its free first-order effect is a moment of"), note
    assert "e+" not in form.text("shaft-applies")
    assert not [m for m in user.notify.messages if "does not apply" in m]
    assert not form.find_hidden("figure-shaft").visible


async def test_performance_tab(user: User, form) -> None:
    await user.open("/?preset=single")
    form.open("performance")
    form.set("setting-pf_balance_factors", "0, 0.5, 1")
    user.find(marker="run-performance").click()
    await form.until(lambda: len(form.rows("performance-table")) == 3)
    rows = form.rows("performance-table")
    assert [r["balance_factor"] for r in rows] == ["0", "0.5", "1"]
    assert all(float(r["friction_torque"]) > 0 for r in rows)
    assert form.element("figure-sensitivity").visible
    # the bore, peak pressure and journal it assumed: the single's estimate, as Crank loads
    # takes them (bore = stroke 62 mm, journal 1.3 x 31 mm), and why its peak bearing load
    # is another quantity than Crank loads' max N
    assumed = form.text("performance-assumed").replace("\\*", "*")  # Markdown-escaped
    assert "bore 62 mm*" in assumed and "main journal 40.3 mm*" in assumed, assumed
    assert "peak pressure" in assumed and "another quantity" in assumed, assumed
    form.set("setting-pf_balance_factors", "0, x")
    assert form.error("setting-pf_balance_factors")
